// d3.line().curve(c)(data) with d3's curves and ours (also into a context that
// draws nothing, the curves' own work), Spline construction and
// evaluation, and the sizes a page loads. Ratios within one run are what to
// compare (BENCHMARKS.md):   node bench/curves.mjs
import { gzipSync } from "node:zlib";
import { readFileSync } from "node:fs";
import * as d3 from "d3-shape";
import { Spline, curveBzsplineX } from "../js/index.js";

function series(n) {
  let s = 1;
  const r = () => ((s = (s * 16807) % 2147483647) / 2147483647);
  let x = 0;
  return Array.from({ length: n }, () => [(x += 0.5 + r()), Math.sin(x / 50) * 100 + r() * 10]);
}

/** The median of `reps` timings of f, in milliseconds. */
function time(f, reps) {
  f();
  const t = [];
  for (let i = 0; i < reps; i++) {
    const t0 = performance.now();
    f();
    t.push(performance.now() - t0);
  }
  return t.sort((a, b) => a - b)[reps >> 1];
}

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
    const ms = Object.fromEntries(Object.entries(curves).map(([name, c]) => [name, time(() => line().curve(c)(data), reps)]));
    console.log(`\n${what}, ${n} points: median ms, and the ratio to curveNatural`);
    for (const [name, t] of Object.entries(ms)) {
      console.log(`  ${name.padEnd(16)} ${t.toFixed(3).padStart(9)}  ${(t / ms.curveNatural).toFixed(2)}`);
    }
  }
}

const n = 100000;
const x = Float64Array.from({ length: n }, (_, i) => i + 0.5 * Math.sin(i));
const y = x.map((v) => Math.sin(v / 100));
const build = time(() => new Spline(x, y).free(), 20);
const s = new Spline(x, y);
const q = Float64Array.from({ length: 1e6 }, (_, i) => (i * (n - 1)) / 1e6);
const evalMs = time(() => s.at(q), 10);
console.log(`\nSpline of ${n} points: build ${build.toFixed(2)} ms; 1,000,000 evaluations ${evalMs.toFixed(2)} ms`);

const gz = (f) => gzipSync(readFileSync(new URL(f, import.meta.url)), { level: 9 }).length;
const core = gz("../wasm/core_bg.wasm") + gz("../wasm/core.js") + gz("../js/index.js") + gz("../js/curves.js") + gz("../js/load.js");
// The other entries: what they load beyond the curves entry (smoothing
// imports it), and all the map entry loads.
const smoothing = gz("../wasm/smoothing_bg.wasm") + gz("../wasm/smoothing.js") + gz("../js/smoothing.js");
const geo = gz("../wasm/geo_bg.wasm") + gz("../wasm/geo.js") + gz("../js/geo.js") + gz("../js/load.js");
const kb = (b) => `${(b / 1000).toFixed(1)} kB`;
console.log(`\ngzipped: curves entry ${kb(core)}; smoothing entry ${kb(smoothing)} more; geo entry ${kb(geo)}`);
