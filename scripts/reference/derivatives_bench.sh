#!/usr/bin/env bash
# The derivatives of the dynamics in one run: Pinocchio's C++ analytical
# derivatives (pinocchio_derivatives_bench.cpp: computeRNEADerivatives,
# computeABADerivatives, computeMinverse, rnea) and dynagen's generated ones
# (benches/examples/derivatives.rs), on ur5.urdf, panda.urdf, iiwa14.urdf and
# quadruped12.urdf (its trunk fixed, then floating: a free flyer), in
# alternation for ROUNDS rounds (default 3), the same states' distribution and
# statistic (median of 300 batches of 1000 calls).
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++ ; cargo.
# Pinocchio is compiled with CXXFLAGS (default "-O3 -DNDEBUG -march=native",
# pinocchio_build.sh); the dynagen side with the caller's RUSTFLAGS (a
# default build: baseline x86-64 with the modules' run-time AVX2 + FMA
# dispatch where they have it; or RUSTFLAGS="-C target-cpu=native").
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
rounds="${1:-3}"
out="${TMPDIR:-/tmp}/pinocchio_derivatives_bench"
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
robots=()
for r in ur5 panda iiwa14 quadruped12; do robots+=("$repo/dynagen/robots/$r.urdf"); done
robots+=("$repo/dynagen/robots/quadruped12.urdf:floating")
pinocchio_build "$here/pinocchio_derivatives_bench.cpp" "$out" "${robots[@]}"
alternate "$rounds" derivatives "" "$out" "${robots[@]}"
