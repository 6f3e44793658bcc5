// How far each d3 curve leaves the data: on the paper's Example 1 and on a
// step, the largest excursion beyond the range of the two points of an
// interval (local) and beyond the range of all the data (global), in units of
// y, from the drawn Bezier pieces sampled 200 times each:
//   node bench/overshoot.mjs
import * as d3 from "d3-shape";
import { curveBzsplineX } from "../js/index.js";
import { Recorder } from "../test/record.mjs";

const sets = {
  "Example 1": [1, 3, 3, 1, 2, 7, 1.5, 1, 10, 2, 1.5].map((y, i) => [i + 1, y]),
  step: [0, 0, 0, 0, 1, 1, 1, 1].map((y, i) => [i, y]),
};
const curves = {
  curveNatural: d3.curveNatural,
  curveCatmullRom: d3.curveCatmullRom,
  "curveCardinal": d3.curveCardinal,
  curveMonotoneX: d3.curveMonotoneX,
  curveBasis: d3.curveBasis,
  curveBzsplineX,
  "curveBzsplineX.through(true)": curveBzsplineX.through(true),
};

function excursion(data, curve) {
  const r = new Recorder();
  d3.line().curve(curve).context(r)(data);
  const ys = data.map((d) => d[1]);
  const [lo, hi] = [Math.min(...ys), Math.max(...ys)];
  let local = 0;
  let global = 0;
  let at = [0, 0];
  for (const c of r.calls) {
    if (c[0] === "M" || c[0] === "L") {
      at = [c[1], c[2]];
      continue;
    }
    if (c[0] !== "C") continue;
    const [x0, y0] = at;
    const [x1, y1, x2, y2, x3, y3] = c.slice(1);
    for (let i = 0; i <= 200; i++) {
      const t = i / 200;
      const u = 1 - t;
      const x = u * u * u * x0 + 3 * u * u * t * x1 + 3 * u * t * t * x2 + t * t * t * x3;
      const y = u * u * u * y0 + 3 * u * u * t * y1 + 3 * u * t * t * y2 + t * t * t * y3;
      // The data interval holding x.
      const next = data.findIndex((d) => d[0] > x);
      const k = next === -1 ? data.length - 2 : Math.min(Math.max(0, next - 1), data.length - 2);
      const a = Math.min(data[k][1], data[k + 1][1]);
      const b = Math.max(data[k][1], data[k + 1][1]);
      local = Math.max(local, a - y, y - b);
      global = Math.max(global, lo - y, y - hi);
    }
    at = [x3, y3];
  }
  return [local, global];
}

console.log("| curve | " + Object.keys(sets).map((s) => `${s}: local | global`).join(" | ") + " |");
console.log("|---|" + Object.keys(sets).map(() => "---:|---:").join("|") + "|");
for (const [name, curve] of Object.entries(curves)) {
  const cells = Object.values(sets).flatMap((data) => excursion(data, curve).map((v) => (v < 1e-12 ? "0" : v.toFixed(3))));
  console.log(`| \`${name}\` | ${cells.join(" | ")} |`);
}
