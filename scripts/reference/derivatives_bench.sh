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
prefix="$(python3 -c 'import cmeel, sys; print(cmeel.__path__[0] + ".prefix")' 2>/dev/null \
  || python3 -c 'import site; print(site.getsitepackages()[0] + "/cmeel.prefix")')"
out="${TMPDIR:-/tmp}/pinocchio_derivatives_bench"
CXXFLAGS=${CXXFLAGS:-"-O3 -DNDEBUG"}

if [ ! -x "$out" ] || [ "$here/pinocchio_derivatives_bench.cpp" -nt "$out" ]; then
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
    "$here/pinocchio_derivatives_bench.cpp" -o "$out" \
    -L"$prefix/lib" -Wl,-rpath,"$prefix/lib" \
    -lpinocchio_parsers -lpinocchio_default -lurdfdom_model
fi
(cd "$repo" && cargo build --release -q -p dynagen-bench --example derivatives)
target="${CARGO_TARGET_DIR:-$repo/target}"
for r in $(seq "$rounds"); do
  echo "== round $r"
  "$out" "$repo/dynagen/robots/ur5.urdf" "$repo/dynagen/robots/panda.urdf"
  "$target/release/examples/derivatives"
done
