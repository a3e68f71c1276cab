# Sourced by the benchmark scripts of this folder: `pinocchio_build SRC OUT`
# compiles SRC (a C++ program of this folder) against the C++ headers and
# libraries that the `pin` wheel installs (cmeel prefix) into OUT, unless OUT
# is newer than SRC.
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++.
# CXXFLAGS default "-O3 -DNDEBUG". No -march=native: it changes Eigen's
# alignment and vectorisation (AVX-512 here) and so the layout of
# Model/Data, which must match the prebuilt libpinocchio_parsers that builds
# the model: the program then segfaults (also with
# -DEIGEN_MAX_ALIGN_BYTES=16). The algorithms are compiled with the same
# baseline ISA as the wheel's libraries.

pinocchio_build() {
  local src="$1" out="$2" prefix flags="${CXXFLAGS:-"-O3 -DNDEBUG"}"
  if [ -x "$out" ] && [ ! "$src" -nt "$out" ]; then
    return 0
  fi
  prefix="$(python3 -c 'import cmeel, sys; print(cmeel.__path__[0] + ".prefix")' 2>/dev/null \
    || python3 -c 'import site; print(site.getsitepackages()[0] + "/cmeel.prefix")')"
  # shellcheck disable=SC2086
  g++ -std=c++17 -w $flags \
    -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
    -DPINOCCHIO_WITH_URDFDOM \
    -DPINOCCHIO_URDFDOM_HEADERS_MAJOR_VERSION=3 \
    -DPINOCCHIO_URDFDOM_HEADERS_MINOR_VERSION=0 \
    -DPINOCCHIO_URDFDOM_HEADERS_PATCH_VERSION=0 \
    -I"$prefix/include" -I"$prefix/include/eigen3" \
    -I"$prefix/include/urdfdom_headers" \
    "$src" -o "$out" \
    -L"$prefix/lib" -Wl,-rpath,"$prefix/lib" \
    -lpinocchio_parsers -lpinocchio_default -lurdfdom_model
}
