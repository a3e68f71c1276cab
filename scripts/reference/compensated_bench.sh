#!/usr/bin/env bash
# Compensated forward dynamics in one run with Pinocchio: Pinocchio's C++
# rnea, crba and aba (pinocchio_bench.cpp, median per call over batches of
# 1000 calls, qd in [-2, 2]) and dynagen's generic ABA, compensated forward
# dynamics (with and without a refinement step) and generated ABA
# (benches/examples/compensated.rs, cancelling states with |qd| up to 300
# rad/s, minimum and median per call over interleaved rounds), on the UR5,
# the Panda and the test robots of dynagen/tests/file_precision.rs, in
# alternation: Pinocchio, dynagen, Pinocchio, ... for ROUNDS rounds (default
# 2). ABA's time does not depend on the state's values.
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++ ; cargo.
# Pinocchio is compiled with CXXFLAGS (default "-O3 -DNDEBUG -march=native",
# pinocchio_build.sh); the dynagen side with the caller's RUSTFLAGS (e.g.
# RUSTFLAGS="-C target-cpu=native").
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
rounds="${1:-2}"
out="${TMPDIR:-/tmp}/pinocchio_compensated_bench"
data="$repo/dynagen/tests/data"
robots=("$repo/dynagen/robots/ur5.urdf" "$repo/dynagen/robots/panda.urdf")
for r in chain8 hand tiny huge near_dependent dependent; do
  robots+=("$data/precision_$r.urdf")
done
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
pinocchio_build "$here/pinocchio_bench.cpp" "$out" "${robots[@]}"
alternate "$rounds" compensated 100 "$out" "${robots[@]}"
echo "== last"
"$out" "${robots[@]}"
