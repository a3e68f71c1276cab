#!/usr/bin/env bash
# The headline of docs/performance.md and README.md in one run: per robot
# (ur5.urdf, panda.urdf, iiwa14.urdf of dynagen/robots, fixed base),
# Pinocchio's C++ rnea, crba, nonLinearEffects and aba (pinocchio_bench.cpp)
# and dynagen's generated inverse_dynamics, mass_matrix, bias_forces and
# forward_dynamics (the default modules, as `dynagen generate
# dynagen/robots/ROBOT.urdf` writes them) and generic solver
# (benches/examples/headline.rs), in alternation for ROUNDS rounds (default
# 3), the same states' distribution and statistic (median of 300 batches of
# 1000 calls, and the minimum); `uptime` before and after.
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++ ; cargo.
# Pinocchio is compiled with CXXFLAGS (default "-O3 -DNDEBUG -march=native",
# pinocchio_build.sh); the dynagen side with the caller's RUSTFLAGS (a
# default build: baseline x86-64 with the modules' run-time AVX2 + FMA
# dispatch; or RUSTFLAGS="-C target-cpu=native").
# Usage: headline_bench.sh [ROUNDS]
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
rounds="${1:-3}"
out="${TMPDIR:-/tmp}/pinocchio_headline_bench"
robots=(ur5 panda iiwa14)
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
urdfs=()
for r in "${robots[@]}"; do urdfs+=("$repo/dynagen/robots/$r.urdf"); done
pinocchio_build "$here/pinocchio_bench.cpp" "$out" "${urdfs[@]}"
uptime
for robot in "${robots[@]}"; do
  echo "=== $robot"
  alternate "$rounds" headline "$robot" "$out" "$repo/dynagen/robots/$robot.urdf"
done
uptime
