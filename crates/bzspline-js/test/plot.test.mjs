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
