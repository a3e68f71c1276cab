#!/usr/bin/env bash
# The Panda with its mimic finger (dynagen/tests/data/panda_mimic.urdf) in
# one run: Pinocchio's C++ rnea, crba and its forward dynamics (crba,
# nonLinearEffects and Eigen's LDLT: its aba refuses mimic joints) with the
# URDF parser's mimic option (pinocchio_bench.cpp --mimic; the bundled
# 9-joint Panda beside it), and dynagen's generated functions and generic
# solver (benches/examples/mimic.rs), in alternation for ROUNDS rounds
# (default 3), the same states' distribution and statistic (median of 300
# batches of 1000 calls). Baseline x86-64 ISA on both sides (see
# pinocchio_build.sh; dynagen's module with its run-time AVX2 + FMA dispatch).
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++ ; cargo.
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
rounds="${1:-3}"
out="${TMPDIR:-/tmp}/pinocchio_bench"
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
pinocchio_build "$here/pinocchio_bench.cpp" "$out"
(cd "$repo" && cargo build --release -q -p dynagen-bench --example mimic)
target="${CARGO_TARGET_DIR:-$repo/target}"
for r in $(seq "$rounds"); do
  echo "== round $r"
  "$out" "$repo/dynagen/robots/panda.urdf" --mimic "$repo/dynagen/tests/data/panda_mimic.urdf"
  "$target/release/examples/mimic"
done
