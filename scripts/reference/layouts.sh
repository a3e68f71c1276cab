#!/usr/bin/env bash
# One dynagen-bench example timed over several code layouts: the bench
# library rebuilt with DYNAGEN_BENCH_LAYOUT = 0, 1, ..., K-1 (benches/build.rs
# puts a function of that size ahead of the generated modules, moving their
# code), the example run once per build. Identical generated bodies have
# measured up to 2x apart between binaries (docs/performance.md, "The same
# body, different binaries"); a comparison of code variants, or a ratio to
# Pinocchio, is then read over the layouts rather than from one binary.
# Each build recompiles the bench library (about a minute on 2 cores).
# Usage: layouts.sh K EXAMPLE [ARGS ...]   e.g. layouts.sh 4 floating 100 quadruped12
# Not run in CI; see README.md in this folder.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
[ $# -ge 2 ] || { echo "usage: $0 K EXAMPLE [ARGS ...]" >&2; exit 2; }
k="$1"
example="$2"
shift 2
cd "$repo"
for ((layout = 0; layout < k; layout++)); do
  echo "== code layout $layout"
  DYNAGEN_BENCH_LAYOUT="$layout" cargo run --quiet --release -p dynagen-bench --example "$example" -- "$@"
done
