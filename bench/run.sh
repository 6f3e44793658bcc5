#!/usr/bin/env sh
# Compare bzspline with scipy at the sizes of BENCHMARKS.md.
# Usage: bench/run.sh [--n 1000000] [--m 10000000] [--repeats 5]
set -eu
cd "$(dirname "$0")/.."
exec python3 bench/compare.py "$@"
