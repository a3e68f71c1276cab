#!/usr/bin/env bash
# The Panda with its mimic finger (dynagen/tests/data/panda_mimic.urdf) in
# one run: Pinocchio's C++ rnea, crba and its forward dynamics (crba,
# nonLinearEffects and Eigen's LDLT: its aba refuses mimic joints) on the
# model its URDF parser builds with the mimic option (pinocchio_bench.cpp
# --mimic, the model made by make_pinocchio_models.py from
# "panda_mimic.urdf:mimic"; the bundled 9-joint Panda beside it), and
# dynagen's generated functions and generic solver
# (benches/examples/mimic.rs), in alternation for ROUNDS rounds (default 3),
# the same states' distribution and statistic (median of 300 batches of 1000
# calls).
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++ ; cargo.
# Pinocchio is compiled with CXXFLAGS (default "-O3 -DNDEBUG -march=native",
# pinocchio_build.sh); the dynagen side with the caller's RUSTFLAGS (a
# default build: baseline x86-64 with the module's run-time AVX2 + FMA
# dispatch; or RUSTFLAGS="-C target-cpu=native").
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
rounds="${1:-3}"
out="${TMPDIR:-/tmp}/pinocchio_mimic_bench"
panda="$repo/dynagen/robots/panda.urdf"
mimic="$repo/dynagen/tests/data/panda_mimic.urdf"
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
pinocchio_build "$here/pinocchio_bench.cpp" "$out" "$panda" "$mimic:mimic"
alternate "$rounds" mimic "" "$out" "$panda" --mimic "$mimic"
