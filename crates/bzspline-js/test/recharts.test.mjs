// Recharts draws its lines and areas with d3-shape and takes a d3 curve
// factory as `type`: a LineChart and an AreaChart rendered by React in jsdom
// draw exactly what d3's line().curve(curveBzsplineX) draws on the same pixels.
import { test } from "node:test";
import assert from "node:assert/strict";
import { JSDOM } from "jsdom";
import { line } from "d3-shape";
import { curveBzsplineX } from "../js/index.js";
import { series } from "./record.mjs";

const dom = new JSDOM("<!doctype html><div id=root></div>", { pretendToBeVisual: true });
for (const k of ["window", "document", "HTMLElement", "Element", "Node", "SVGElement", "getComputedStyle"]) {
  globalThis[k] = k === "window" ? dom.window : dom.window[k];
}
// Node 20 has no navigator, which react-dom reads when it loads.
if (!globalThis.navigator) globalThis.navigator = dom.window.navigator;
globalThis.IS_REACT_ACT_ENVIRONMENT = true;
const React = (await import("react")).default;
const { createRoot } = await import("react-dom/client");
const { LineChart, Line, AreaChart, Area, XAxis, YAxis } = await import("recharts");
const h = React.createElement;

/** Renders `element` and returns the container once React has settled. */
async function render(element) {
  const host = document.createElement("div");
  document.body.append(host);
  const root = createRoot(host);
  await React.act(async () => root.render(element));
  await React.act(() => new Promise((r) => setTimeout(r, 20)));
  return { host, done: () => React.act(() => root.unmount()) };
}

/** The numbers of an SVG path, in order. */
const numbers = (d) => (d.match(/-?\d+(\.\d+)?(e[-+]?\d+)?/g) || []).map(Number);

/** The pixels of the dots Recharts draws at the data. */
function dots(host, cls) {
  return [...host.querySelectorAll(`${cls} circle`)].map((c) => [+c.getAttribute("cx"), +c.getAttribute("cy")]);
}

function samePath(got, want, what) {
  assert.equal(got.replace(/[-\d.e+,\s]/g, ""), want.replace(/[-\d.e+,\s]/g, ""), `${what}: the same commands`);
  const [a, b] = [numbers(got), numbers(want)];
  assert.equal(a.length, b.length, what);
  a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-9, `${what}: value ${i}: ${v} against ${b[i]}`));
}

test("<Line type={curveBzsplineX}> draws d3's line().curve(curveBzsplineX) on its points", async () => {
  for (const seed of [2, 5, 8]) {
    const data = series(6 + seed, seed).map(([x, y]) => ({ x, y }));
    const { host, done } = await render(
      h(
        LineChart,
        { width: 480, height: 300, data },
        h(XAxis, { dataKey: "x", type: "number", domain: ["dataMin", "dataMax"] }),
        h(YAxis, {}),
        h(Line, { type: curveBzsplineX, dataKey: "y", isAnimationActive: false }),
      ),
    );
    const d = host.querySelector("path.recharts-line-curve").getAttribute("d");
    const pts = dots(host, ".recharts-line-dots");
    assert.equal(pts.length, data.length);
    samePath(d, line().digits(null).curve(curveBzsplineX)(pts), `seed ${seed}`);
    assert.equal((d.match(/C/g) || []).length, data.length - 1, "one cubic a piece");
    await done();
  }
});

test("<Area type={curveBzsplineX}> outlines its area with the same curve", async () => {
  const data = series(12, 4).map(([x, y]) => ({ x, y: y + 20 }));
  const { host, done } = await render(
    h(
      AreaChart,
      { width: 480, height: 300, data },
      h(XAxis, { dataKey: "x", type: "number", domain: ["dataMin", "dataMax"] }),
      h(YAxis, {}),
      h(Area, { type: curveBzsplineX, dataKey: "y", isAnimationActive: false, dot: true }),
    ),
  );
  const d = host.querySelector("path.recharts-area-curve").getAttribute("d");
  const pts = dots(host, ".recharts-area-dots");
  assert.equal(pts.length, data.length);
  samePath(d, line().digits(null).curve(curveBzsplineX)(pts), "area");
  // The filled shape starts with the same curve.
  const fill = host.querySelector("path.recharts-area-area").getAttribute("d");
  assert.ok(fill.startsWith(d.slice(0, 40)), "the fill follows the curve");
  await done();
});
