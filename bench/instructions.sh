#!/usr/bin/env bash
# Instructions per point or query of each workload of the `instructions`
# example (callgrind: a run with 13 repetitions less one with 3, over 10).
#   bash bench/instructions.sh [WORKLOAD...]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p bzspline --example instructions
bin=target/release/examples/instructions
modes=("$@")
[ ${#modes[@]} -gt 0 ] || modes=(build build_alphas through sorted random curve closed flatten ceval seval)
count() {
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$1" "$2" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
for m in "${modes[@]}"; do
  per=$("$bin" "$m" 0)
  a=$(count "$m" 3)
  b=$(count "$m" 13)
  awk -v m="$m" -v a="$a" -v b="$b" -v p="$per" 'BEGIN { printf "%-13s %8.2f\n", m, (b - a) / 10 / p }'
done
