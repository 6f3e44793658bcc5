// Spline.at(Float64Array) alone in a process: 1,000,000 sorted evaluations
// on a spline of 100,000 points (the workload of bench/curves.mjs), timed 30
// times in a row after half a second of warm-up, to see the steady state and
// the machine's noise apart from the other benchmarks' heap:
//   node bench/evaluate.mjs
// With two numbers it evaluates WARM times, then REPS times, untimed: for
// instruction counts, which no other process disturbs (the difference of
// two runs, over 10^7 evaluations, is the count of one):
//   for r in 0 10; do valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//     --smc-check=all-non-file node bench/evaluate.mjs 20 $r; done
import { Spline } from "../js/index.js";

const n = 100000;
const x = Float64Array.from({ length: n }, (_, i) => i + 0.5 * Math.sin(i));
const y = x.map((v) => Math.sin(v / 100));
const s = new Spline(x, y);
const q = Float64Array.from({ length: 1e6 }, (_, i) => (i * (n - 1)) / 1e6);
if (process.argv.length > 3) {
  const [warm, reps] = process.argv.slice(2).map(Number);
  for (let i = 0; i < warm + reps; i++) s.at(q);
  process.exit(0);
}
for (const t0 = performance.now(); performance.now() - t0 < 500; ) s.at(q);
const t = [];
for (let i = 0; i < 30; i++) {
  const t0 = performance.now();
  s.at(q);
  t.push(performance.now() - t0);
}
const sorted = [...t].sort((a, b) => a - b);
console.log(`ms: ${t.map((v) => v.toFixed(1)).join(" ")}`);
console.log(`min ${sorted[0].toFixed(2)}, median ${sorted[15].toFixed(2)}`);
