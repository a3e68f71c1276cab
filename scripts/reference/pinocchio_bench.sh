#!/usr/bin/env bash
# Build and run pinocchio_bench.cpp against the C++ headers and libraries that
# the `pin` wheel installs (cmeel prefix), on ur5.urdf and panda.urdf.
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++.
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
prefix="$(python3 -c 'import cmeel, sys; print(cmeel.__path__[0] + ".prefix")' 2>/dev/null \
  || python3 -c 'import site; print(site.getsitepackages()[0] + "/cmeel.prefix")')"
out="${TMPDIR:-/tmp}/pinocchio_bench"

# No -march=native: it changes Eigen's alignment and vectorisation (AVX-512
# here) and so the layout of Model/Data, which must match the prebuilt
# libpinocchio_parsers that builds the model: the program then segfaults
# (also with -DEIGEN_MAX_ALIGN_BYTES=16).  The algorithms are compiled here
# with the same baseline ISA as the wheel's libraries.
CXXFLAGS=${CXXFLAGS:-"-O3 -DNDEBUG"}

# shellcheck disable=SC2086
g++ -std=c++17 -w $CXXFLAGS \
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
  -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
  -DPINOCCHIO_WITH_URDFDOM \
  -DPINOCCHIO_URDFDOM_HEADERS_MAJOR_VERSION=3 \
  -DPINOCCHIO_URDFDOM_HEADERS_MINOR_VERSION=0 \
  -DPINOCCHIO_URDFDOM_HEADERS_PATCH_VERSION=0 \
  -I"$prefix/include" -I"$prefix/include/eigen3" \
  -I"$prefix/include/urdfdom_headers" \
  "$here/pinocchio_bench.cpp" -o "$out" \
  -L"$prefix/lib" -Wl,-rpath,"$prefix/lib" \
  -lpinocchio_parsers -lpinocchio_default -lurdfdom_model

"$out" "$repo/dynagen/robots/ur5.urdf" "$repo/dynagen/robots/panda.urdf"
