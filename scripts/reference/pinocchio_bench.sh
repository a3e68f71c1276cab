#!/usr/bin/env bash
# Build and run pinocchio_bench.cpp against the C++ headers and libraries that
# the `pin` wheel installs (cmeel prefix), on ur5.urdf and panda.urdf.
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++.
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
out="${TMPDIR:-/tmp}/pinocchio_bench"
# shellcheck source=pinocchio_build.sh
. "$here/pinocchio_build.sh"
pinocchio_build "$here/pinocchio_bench.cpp" "$out" "$repo/dynagen/robots/ur5.urdf" "$repo/dynagen/robots/panda.urdf"

"$out" "$repo/dynagen/robots/ur5.urdf" "$repo/dynagen/robots/panda.urdf"
