// Chart.js 4 with the plugin against Chart.js's own curves: the time of
// `chart.update()` (which lays out, builds the curves and draws), on 1,000
// and 100,000 points, into a 2D context that draws nothing (Node has no
// canvas; what is timed is Chart.js's work and the curves', the same for
// every mode), medians taken in turn, and the gzipped size the entry adds
// to a page that has Chart.js. Ratios within one run are what to compare
// (BENCHMARKS.md):   node bench/chartjs.mjs
import { gzipSync } from "node:zlib";
import { readFileSync } from "node:fs";
import { Chart, registerables } from "chart.js";
import { bzsplinePlugin } from "../js/chartjs.js";

Chart.register(...registerables, bzsplinePlugin);

function series(n) {
  let s = 1;
  const r = () => ((s = (s * 16807) % 2147483647) / 2147483647);
  let x = 0;
  return Array.from({ length: n }, () => ({ x: (x += 0.5 + r()), y: Math.sin(x / 50) * 100 + r() * 10 }));
}

/** A canvas whose context accepts every call and draws nothing. */
function canvas() {
  const noop = () => {};
  const ctx = new Proxy(
    { measureText: (t) => ({ width: String(t).length * 6 }), getLineDash: () => [] },
    {
      get: (t, k) => (k in t ? t[k] : typeof k === "string" && /^[a-z]/.test(k) && !k.endsWith("Style") ? noop : undefined),
      set: (t, k, v) => ((t[k] = v), true),
    },
  );
  const c = { width: 960, height: 480, style: {}, getContext: () => ctx };
  ctx.canvas = c;
  return c;
}

const modes = {
  "straight (tension 0)": {},
  "tension: 0.4": { tension: 0.4 },
  'cubicInterpolationMode "monotone"': { cubicInterpolationMode: "monotone" },
  "bzspline: true": { bzspline: true },
};

for (const n of [1000, 100000]) {
  const data = series(n);
  const charts = Object.fromEntries(
    Object.entries(modes).map(([name, o]) => [
      name,
      new Chart(canvas(), {
        type: "line",
        data: { datasets: [{ data, pointRadius: 0, ...o }] },
        options: { animation: false, responsive: false, parsing: false, normalized: true, scales: { x: { type: "linear" } } },
      }),
    ]),
  );
  const t = Object.fromEntries(Object.keys(charts).map((k) => [k, []]));
  for (const c of Object.values(charts)) {
    for (const t0 = performance.now(); performance.now() - t0 < 500; ) c.update("none");
  }
  const reps = n > 10000 ? 21 : 201;
  for (let i = 0; i < reps; i++) {
    for (const [k, c] of Object.entries(charts)) {
      const t0 = performance.now();
      c.update("none");
      t[k].push(performance.now() - t0);
    }
  }
  const ms = Object.fromEntries(Object.entries(t).map(([k, v]) => [k, v.sort((a, b) => a - b)[reps >> 1]]));
  const mono = ms['cubicInterpolationMode "monotone"'];
  console.log(`\nchart.update(), ${n} points: median ms, and the ratio to monotone`);
  for (const [k, v] of Object.entries(ms)) {
    console.log(`  ${k.padEnd(34)} ${v.toFixed(3).padStart(9)}  ${(v / mono).toFixed(2)}`);
  }
  for (const c of Object.values(charts)) c.destroy();
}

const gz = (f) => gzipSync(readFileSync(new URL(f, import.meta.url)), { level: 9 }).length;
const entry = gz("../js/chartjs.js");
const curves = gz("../wasm/core_bg.wasm") + gz("../wasm/core.js") + gz("../js/index.js") + gz("../js/curves.js") + gz("../js/load.js");
console.log(`\ngzipped: the Chart.js entry's own script ${(entry / 1000).toFixed(1)} kB, with the curves entry it loads ${((entry + curves) / 1000).toFixed(1)} kB`);
