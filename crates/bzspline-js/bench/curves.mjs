// d3.line().curve(c)(data) with d3's curves and ours (also into a context that
// draws nothing, the curves' own work), Spline construction and
// evaluation beside the native figures, results shaped as arrays of points,
// and the sizes a page loads. Ratios within one run are what to
// compare (BENCHMARKS.md):   node bench/curves.mjs
import { gzipSync } from "node:zlib";
import { execFileSync } from "node:child_process";
import { existsSync, readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import { setFlagsFromString } from "node:v8";
import { runInNewContext } from "node:vm";
import * as d3 from "d3-shape";
import { Spline, Curve, curveBzsplineX } from "../js/index.js";

function series(n) {
  let s = 1;
  const r = () => ((s = (s * 16807) % 2147483647) / 2147483647);
  let x = 0;
  return Array.from({ length: n }, () => [(x += 0.5 + r()), Math.sin(x / 50) * 100 + r() * 10]);
}

// A full collection before each timed function, so that the garbage one
// leaves (100,000-point path strings) is not collected in the next one's time.
setFlagsFromString("--expose-gc");
const gc = runInNewContext("gc");

/**
 * The medians of `reps` timings of each function of `fs` (an object), in
 * milliseconds, taken in turn (one of each per round), so that a spell of
 * the machine's noise falls on all of them alike. Each is first called for
 * half a second: V8 first runs WebAssembly from its baseline compiler and
 * swaps in optimised code as functions turn hot.
 */
function timeEach(fs, reps) {
  const t = Object.fromEntries(Object.keys(fs).map((k) => [k, []]));
  gc();
  for (const f of Object.values(fs)) {
    for (const t0 = performance.now(); performance.now() - t0 < 500; ) f();
  }
  for (let i = 0; i < reps; i++) {
    for (const [k, f] of Object.entries(fs)) {
      const t0 = performance.now();
      f();
      t[k].push(performance.now() - t0);
    }
  }
  return Object.fromEntries(Object.entries(t).map(([k, v]) => [k, v.sort((a, b) => a - b)[reps >> 1]]));
}

/** The median of `reps` timings of f alone, as `timeEach`. */
const time = (f, reps) => timeEach({ f }, reps).f;

const curves = {
  curveLinear: d3.curveLinear,
  curveNatural: d3.curveNatural,
  curveCatmullRom: d3.curveCatmullRom,
  curveMonotoneX: d3.curveMonotoneX,
  curveBzsplineX,
};
// A context that draws nothing: the curves' own work without d3-path's
// formatting of the path string.
const nothing = { moveTo() {}, lineTo() {}, bezierCurveTo() {}, closePath() {} };
for (const n of [1000, 100000]) {
  const data = series(n);
  const reps = n > 10000 ? 15 : 300;
  for (const [what, line] of [
    ["d3.line()(data)", () => d3.line()],
    ["into a context that draws nothing", () => d3.line().context(nothing)],
  ]) {
    const ms = timeEach(Object.fromEntries(Object.entries(curves).map(([name, c]) => [name, () => line().curve(c)(data)])), reps);
    console.log(`\n${what}, ${n} points: median ms, and the ratio to curveNatural`);
    for (const [name, t] of Object.entries(ms)) {
      console.log(`  ${name.padEnd(16)} ${t.toFixed(3).padStart(9)}  ${(t / ms.curveNatural).toFixed(2)}`);
    }
  }
}

// A Spline of 100,000 points: construction and 1,000,000 sorted evaluations
// into a new array, beside the native Rust figures of the same workload
// (`cargo build --release -p bzspline --example throughput`), each round
// timing both, so that the ratio does not straddle the machine's drift.
const n = 100000;
const x = Float64Array.from({ length: n }, (_, i) => i + 0.5 * Math.sin(i));
const y = x.map((v) => Math.sin(v / 100));
const s = new Spline(x, y);
const q = Float64Array.from({ length: 1e6 }, (_, i) => (i * (n - 1)) / 1e6);
const native = process.env.BZSPLINE_THROUGHPUT ?? fileURLToPath(new URL("../../../target/release/examples/throughput", import.meta.url));
console.log(`\nSpline of ${n} points: median ms of build and of 1,000,000 evaluations; native ms and the ratio`);
for (let round = 0; round < 3; round++) {
  const build = time(() => new Spline(x, y).free(), 21);
  const evalMs = time(() => s.at(q), 21);
  let line = `  round ${round + 1}: build ${build.toFixed(2)}, evaluate ${evalMs.toFixed(2)}`;
  if (existsSync(native)) {
    const r = JSON.parse(execFileSync(native, ["--n", String(n), "--m", "1000000"], { encoding: "utf8" }));
    // ns a point times the number of points, in ms.
    const nb = (r.construct_ns_per_point * n) / 1e6;
    const ne = (r.eval_sorted_new_ns_per_point * 1e6) / 1e6;
    line += `; native ${nb.toFixed(2)} and ${ne.toFixed(2)}: ${(build / nb).toFixed(2)}x and ${(evalMs / ne).toFixed(2)}x`;
  }
  console.log(line);
}

// Results as arrays of points (shaped in JavaScript from the core's flat
// numbers): a spline's and a curve's of 10,000 points.
{
  const m = 10000;
  const sx = Float64Array.from({ length: m }, (_, i) => i);
  const sp = new Spline(sx, sx.map((v) => Math.sin(v / 10)));
  const c = new Curve(Array.from({ length: m }, (_, i) => [Math.cos(i / 100) * i, Math.sin(i / 100) * i]));
  const ts = sx.map((v) => (v / m) * c.knots[m - 1]);
  console.log(`\nArrays of points, ${m}-point spline and curve: median ms`);
  console.log(`  Spline.segments ${time(() => sp.segments, 21).toFixed(2)}, tangentPoints ${time(() => sp.tangentPoints, 21).toFixed(2)}`);
  console.log(`  Curve.segments ${time(() => c.segments, 21).toFixed(2)}, at(${m} parameters) ${time(() => c.at(ts), 21).toFixed(2)}, flatten(1e-3) ${time(() => c.flatten(1e-3), 21).toFixed(2)} (${c.flatten(1e-3).length} vertices)`);
  sp.free();
  c.free();
}

const gz = (f) => gzipSync(readFileSync(new URL(f, import.meta.url)), { level: 9 }).length;
const core = gz("../wasm/core_bg.wasm") + gz("../wasm/core.js") + gz("../js/index.js") + gz("../js/curves.js") + gz("../js/load.js");
// The other entries: what they load beyond the curves entry (smoothing
// imports it), and all the map entry loads.
const smoothing = gz("../wasm/smoothing_bg.wasm") + gz("../wasm/smoothing.js") + gz("../js/smoothing.js");
const geo = gz("../wasm/geo_bg.wasm") + gz("../wasm/geo.js") + gz("../js/geo.js") + gz("../js/load.js");
const kb = (b) => `${(b / 1000).toFixed(1)} kB`;
console.log(`\ngzipped: curves entry ${kb(core)}; smoothing entry ${kb(smoothing)} more; geo entry ${kb(geo)}`);
