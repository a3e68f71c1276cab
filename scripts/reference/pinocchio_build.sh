# Sourced by the benchmark scripts of this folder (pinocchio_build, and
# alternate below):
#   pinocchio_build SRC OUT ROBOT.urdf[:floating] ...
# compiles SRC (a C++ program of this folder) into OUT against the C++
# headers that the `pin` wheel installs (cmeel prefix), with the robots'
# models made by make_pinocchio_models.py (OUT.models/pinocchio_models.hpp)
# instead of Pinocchio's URDF parser, whose prebuilt library is baseline
# x86-64 and, with -march=native, does not match the program's layout of
# Model (it segfaulted). Everything Pinocchio computes is header-only
# templates, compiled here with CXXFLAGS (default "-O3 -DNDEBUG
# -march=native", as the issues ask of the comparison). OUT is rebuilt when
# SRC, bench_common.hpp, the models or the flags change.
# Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers ; g++.

pinocchio_build() {
  local src="$1" out="$2" here prefix flags="${CXXFLAGS:-"-O3 -DNDEBUG -march=native"}"
  shift 2
  here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
  mkdir -p "$out.models"
  python3 "$here/make_pinocchio_models.py" "$out.models/new.hpp" "$@"
  echo "$flags" >> "$out.models/new.hpp"   # the flags as a comment-free stamp: see below
  if [ -x "$out" ] && [ ! "$src" -nt "$out" ] && [ ! "$here/bench_common.hpp" -nt "$out" ] \
    && cmp -s "$out.models/new.hpp" "$out.models/stamp"; then
    return 0
  fi
  mv "$out.models/new.hpp" "$out.models/stamp"
  sed '$d' "$out.models/stamp" > "$out.models/pinocchio_models.hpp"
  prefix="$(python3 -c 'import cmeel; print(cmeel.__path__[0] + ".prefix")' 2>/dev/null \
    || python3 -c 'import site; print(site.getsitepackages()[0] + "/cmeel.prefix")')"
  echo "compiling $(basename "$src") with $flags" >&2
  # shellcheck disable=SC2086
  g++ -std=c++17 -w $flags \
    -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
    -I"$out.models" -I"$here" -I"$prefix/include" -I"$prefix/include/eigen3" \
    "$src" -o "$out"
}

# Sourced likewise:
#   alternate ROUNDS EXAMPLE "EXAMPLE ARGS" PROGRAM [ARGS ...]
# builds dynagen-bench's EXAMPLE (cargo build --release, the caller's
# RUSTFLAGS and CARGO_TARGET_DIR) and runs PROGRAM ARGS (a Pinocchio program
# pinocchio_build compiled) and the example with EXAMPLE ARGS (split on
# spaces) in alternation, ROUNDS times, each round headed "== round R".
# With NO_ASLR set, both run without address-space randomisation
# (`fixed`, below).
alternate() {
  local rounds="$1" example="$2" example_args="$3" repo target r
  shift 3
  repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  (cd "$repo" && cargo build --release -q -p dynagen-bench --example "$example")
  target="${CARGO_TARGET_DIR:-$repo/target}"
  for r in $(seq "$rounds"); do
    echo "== round $r"
    fixed "$@"
    # shellcheck disable=SC2086
    fixed "$target/release/examples/$example" $example_args
  done
}

# fixed PROGRAM [ARGS ...]: runs PROGRAM, and with NO_ASLR set runs it
# without address-space randomisation (`setarch -R`): Linux otherwise puts
# each process's stack at a random place within a page, and the generated
# floating-base functions' times depend on that place (docs/performance.md,
# "Where the frame lies").
fixed() {
  if [ -n "${NO_ASLR:-}" ]; then
    setarch "$(uname -m)" -R "$@"
  else
    "$@"
  fi
}
