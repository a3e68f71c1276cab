#!/usr/bin/env bash
# The derivatives of the dynamics in one run: Pinocchio's C++ analytical
# derivatives (pinocchio_derivatives_bench.cpp: computeRNEADerivatives,
# computeABADerivatives, computeMinverse, rnea) and dynagen's generated ones
# (benches/examples/derivatives.rs), on ur5.urdf and panda.urdf, in
# alternation for ROUNDS rounds (default 3), the same states' distribution and
# statistic (median of 300 batches of 1000 calls).
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++ ; cargo.
# CXXFLAGS default "-O3 -DNDEBUG": with -march=native the program segfaults
# (Eigen's alignment changes the layout of Model/Data, which must match the
# prebuilt libpinocchio_parsers that builds the model; see
# pinocchio_bench.sh), so both sides run the baseline x86-64 ISA (dynagen's
# modules with their run-time AVX2 + FMA dispatch where they have it).
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
rounds="${1:-3}"
out="${TMPDIR:-/tmp}/pinocchio_derivatives_bench"
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
pinocchio_build "$here/pinocchio_derivatives_bench.cpp" "$out"
(cd "$repo" && cargo build --release -q -p dynagen-bench --example derivatives)
target="${CARGO_TARGET_DIR:-$repo/target}"
for r in $(seq "$rounds"); do
  echo "== round $r"
  "$out" "$repo/dynagen/robots/ur5.urdf" "$repo/dynagen/robots/panda.urdf"
  "$target/release/examples/derivatives"
done
