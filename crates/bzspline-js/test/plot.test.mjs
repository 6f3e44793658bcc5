// Observable Plot takes the curves as its `curve` option (Plot needs a
// document: jsdom's).
import { test } from "node:test";
import assert from "node:assert/strict";
import { JSDOM } from "jsdom";
import * as Plot from "@observablehq/plot";
import * as d3 from "d3-shape";
import { scaleLinear } from "d3-scale";
import { curveBzsplineX, curveBzspline, Spline } from "../js/index.js";
import { series } from "./record.mjs";

const { document } = new JSDOM("").window;

test("Plot.line and Plot.areaY draw with curveBzsplineX, as d3.line does on Plot's scales", () => {
  const data = series(30, 3).map(([x, y]) => ({ x, y }));
  const chart = Plot.plot({
    document,
    x: { domain: [0, 20] },
    y: { domain: [-1, 2] },
    marks: [
      Plot.areaY(data, { x: "x", y: "y", curve: curveBzsplineX, fillOpacity: 0.2 }),
      Plot.line(data, { x: "x", y: "y", curve: curveBzsplineX }),
    ],
  });
  const paths = [...chart.querySelectorAll("path")].map((p) => p.getAttribute("d")).filter((d) => d && d.includes("C"));
  assert.equal(paths.length, 2);
  const line = paths[1];
  assert.equal((line.match(/C/g) || []).length, data.length - 1);
  // The same path as d3.line with the curve on Plot's own scales.
  const x = chart.scale("x");
  const y = chart.scale("y");
  const sx = scaleLinear().domain(x.domain).range(x.range);
  const sy = scaleLinear().domain(y.domain).range(y.range);
  const ours = d3.line((d) => sx(d.x), (d) => sy(d.y)).curve(curveBzsplineX)(data);
  const numbers = (d) => d.match(/-?[\d.]+(e-?\d+)?/g).map(Number);
  numbers(line).forEach((v, i) => assert.ok(Math.abs(v - numbers(ours)[i]) < 0.01, `coordinate ${i}`));
  // y at the pointer's x, on the drawn curve.
  const s = new Spline(data.map((d) => d.x), data.map((d) => d.y));
  assert.ok(Number.isFinite(s.at(sx.invert(300))));
});

test("Plot.line with the planar curve draws a path through any points", () => {
  const data = [[0, 0], [2, 1], [1, 2], [3, 3]];
  const chart = Plot.plot({ document, marks: [Plot.line(data, { curve: curveBzspline.param("chordal") })] });
  const d = [...chart.querySelectorAll("path")].map((p) => p.getAttribute("d")).filter((d) => d && d.includes("C"));
  assert.equal(d.length, 1);
  assert.equal((d[0].match(/C/g) || []).length, 3);
});

test("a smoothing spline's band draws with d3.area and Plot.areaY, as its README shows", async () => {
  const { smoothingSpline } = await import("../js/smoothing.js");
  const data = series(120, 7);
  const x = data.map((d) => d[0]);
  const y = data.map((d) => d[1]);
  const s = smoothingSpline(x, y);
  const xs = Array.from({ length: 200 }, (_, i) => x[0] + (i / 199) * (x.at(-1) - x[0]));
  const { lo, hi } = s.band(xs, 0.95);
  const X = scaleLinear().domain([x[0], x.at(-1)]).range([0, 600]);
  const Y = scaleLinear().domain([-3, 3]).range([400, 0]);
  const shade = d3.area().x((t) => X(t)).y0((_, i) => Y(lo[i])).y1((_, i) => Y(hi[i])).digits(null)(xs);
  // The area's outline: the upper edge forward, the lower edge back.
  const nums = shade.match(/-?[\d.]+(e-?\d+)?/g).map(Number);
  assert.equal(nums.length, 4 * xs.length);
  assert.deepEqual(nums.slice(0, 2), [X(xs[0]), Y(hi[0])]);
  assert.deepEqual(nums.slice(2 * xs.length, 2 * xs.length + 2), [X(xs.at(-1)), Y(lo.at(-1))]);
  const chart = Plot.plot({
    document,
    marks: [
      Plot.areaY(xs, { x: (t) => t, y1: (_, i) => lo[i], y2: (_, i) => hi[i], fillOpacity: 0.2 }),
      Plot.line(xs, { x: (t) => t, y: (t) => s.at(t) }),
      Plot.dot(x, { x: (t) => t, y: (_, i) => y[i], r: 1.5 }),
    ],
  });
  const area = [...chart.querySelectorAll("path")].find((p) => p.getAttribute("fill-opacity") === "0.2" || p.parentNode.getAttribute("fill-opacity") === "0.2");
  assert.ok(area, "Plot drew no area");
  const ys = chart.scale("y");
  const top = (area.getAttribute("d").match(/-?[\d.]+(e-?\d+)?/g) || []).map(Number);
  const sy = scaleLinear().domain(ys.domain).range(ys.range);
  assert.ok(Math.abs(top[1] - sy(hi[0])) < 0.01, `${top[1]} against ${sy(hi[0])}`);
});
