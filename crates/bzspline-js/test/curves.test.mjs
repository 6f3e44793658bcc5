// The d3 curves against d3-shape's own protocol and against the Spline and
// Curve objects: what they draw is the method's pieces, exactly.
import { test } from "node:test";
import assert from "node:assert/strict";
import * as d3 from "d3-shape";
import { scaleLinear, scaleUtc } from "d3-scale";
import {
  Spline,
  Curve,
  curveBzsplineX,
  curveBzsplineY,
  curveBzspline,
  curveBzsplineClosed,
} from "../js/index.js";
import { record, series, close, random } from "./record.mjs";

const kinds = { curveBzsplineX, curveBzsplineY, curveBzspline, curveBzsplineClosed };

test("curveBzsplineX draws the spline's pieces: one C per interval, exactly", () => {
  for (let seed = 1; seed <= 40; seed++) {
    const data = series(3 + (seed % 17), seed);
    const calls = record(d3.line().curve(curveBzsplineX), data);
    const s = new Spline(data.map((p) => p[0]), data.map((p) => p[1]));
    assert.deepEqual(calls[0], ["M", data[0][0], data[0][1]]);
    assert.equal(calls.length, data.length);
    s.segments.forEach((seg, k) => {
      assert.deepEqual(calls[k + 1], ["C", ...seg[1], ...seg[2], ...seg[3]]);
    });
    s.free();
  }
});

test("through every point: the curve's knots are the data", () => {
  const data = series(25, 7);
  const calls = record(d3.line().curve(curveBzsplineX.through(true)), data);
  for (let k = 1; k < data.length; k++) {
    assert.equal(calls[k][0], "C");
    close(calls[k][5], data[k][0], 1e-15, `x at knot ${k}`);
    close(calls[k][6], data[k][1], 1e-12, `y at knot ${k}`);
  }
});

test("the drawn curve is new Spline(data) mapped through linear and time scales", () => {
  const r = random(3);
  const t0 = Date.UTC(2024, 0, 1);
  const data = Array.from({ length: 60 }, (_, i) => ({ date: new Date(t0 + i * 86400e3 * (1 + r())), v: 10 + 5 * r() }));
  data.sort((a, b) => a.date - b.date);
  const x = scaleUtc().domain([data[0].date, data.at(-1).date]).range([40, 900]);
  const y = scaleLinear().domain([0, 20]).range([500, 20]);
  const line = d3.line((d) => x(d.date), (d) => y(d.v)).curve(curveBzsplineX.alpha(0.4));
  const calls = record(line, data);
  const s = new Spline(data.map((d) => +d.date), data.map((d) => d.v), { alpha: 0.4 });
  // The method commutes with x -> a x + b and y -> c y + d: the pieces of
  // the data's spline, mapped, are the pieces of the screen's.
  s.segments.forEach((seg, k) => {
    const c = calls[k + 1];
    for (let j = 1; j <= 3; j++) {
      // A Date would cut the time to whole milliseconds: the number goes in.
      close(c[2 * j - 1], x(seg[j][0]), 1e-12, `x of piece ${k} point ${j}`);
      close(c[2 * j], y(seg[j][1]), 1e-12, `y of piece ${k} point ${j}`);
    }
  });
  // And the tooltip reads y at the pointer's x on the drawn curve.
  const px = 333.5;
  const dataY = s.at(+x.invert(px));
  assert.ok(dataY >= 10 && dataY <= 15);
});

test("an area draws its top forward and its baseline back, both the spline of their points", () => {
  const data = series(12, 5).map(([x, y]) => ({ x, y0: y - 1 - Math.cos(x), y1: y }));
  const area = d3.area((d) => d.x, (d) => d.y0, (d) => d.y1).curve(curveBzsplineX);
  const calls = record(area, data);
  const n = data.length;
  assert.deepEqual(calls[0], ["M", data[0].x, data[0].y1]);
  assert.deepEqual(calls[n], ["L", data[n - 1].x, data[n - 1].y0]);
  assert.deepEqual(calls.at(-1), ["Z"]);
  const base = new Spline(data.map((d) => d.x), data.map((d) => d.y0)).segments;
  for (let k = 0; k < n - 1; k++) {
    // The baseline's pieces run from the last point to the first.
    const seg = base[n - 2 - k];
    const c = calls[n + 1 + k];
    assert.equal(c[0], "C");
    for (const [i, p] of [[1, seg[2]], [3, seg[1]], [5, seg[0]]]) {
      close(c[i], p[0], 1e-15, "baseline x");
      close(c[i + 1], p[1], 1e-13, "baseline y");
    }
  }
  // d3.area's own reference: the same commands as curveLinear's outline.
  const linear = record(d3.area((d) => d.x, (d) => d.y0, (d) => d.y1), data);
  assert.deepEqual(calls.map((c) => c[0]).filter((c) => c !== "C"), linear.map((c) => c[0]).filter((c, i) => c !== "L" || i === n));
});

test("one and two points are drawn as d3's curves draw them", () => {
  for (const data of [[[1, 2]], [[1, 2], [3, 4]]]) {
    for (const curve of [curveBzsplineX, curveBzspline]) {
      assert.equal(d3.line().curve(curve)(data), d3.line().curve(d3.curveMonotoneX)(data));
      assert.equal(d3.area().curve(curve)(data), d3.area().curve(d3.curveMonotoneX)(data));
    }
    assert.equal(d3.line().curve(curveBzsplineY)(data), d3.line().curve(d3.curveMonotoneY)(data));
    assert.equal(d3.line().curve(curveBzsplineClosed)(data), d3.line().curve(d3.curveLinearClosed)(data));
  }
  assert.equal(d3.line().curve(curveBzsplineX)([]), null);
});

test("repeated points are dropped; x that does not run one way is drawn by the planar curve", () => {
  const data = series(10, 9);
  const doubled = data.flatMap((p, i) => (i % 3 ? [p] : [p, p.slice()]));
  assert.equal(d3.line().curve(curveBzsplineX)(doubled), d3.line().curve(curveBzsplineX)(data));
  const loop = [[0, 0], [2, 1], [1, 2], [3, 3], [3, 4]];
  assert.equal(d3.line().curve(curveBzsplineX)(loop), d3.line().curve(curveBzspline)(loop));
  const calls = record(d3.line().curve(curveBzspline), loop);
  const c = new Curve(loop);
  c.segments.forEach((seg, k) => assert.deepEqual(calls[k + 1], ["C", ...seg[1], ...seg[2], ...seg[3]]));
});

test("curveBzsplineY is curveBzsplineX with x and y exchanged", () => {
  const data = series(15, 11);
  const swapped = record(d3.line().curve(curveBzsplineY), data.map(([x, y]) => [y, x]));
  const direct = record(d3.line().curve(curveBzsplineX), data);
  assert.deepEqual(swapped, direct.map((c) => [c[0], ...c.slice(1).map((_, i, a) => a[i ^ 1])]));
});

test("curveBzsplineClosed draws the closed curve, one C per leg, and closes", () => {
  const ring = [[0, 0], [4, 0], [4, 3], [0, 3]];
  const calls = record(d3.line().curve(curveBzsplineClosed), [...ring, ring[0]]);
  const c = new Curve(ring, { closed: true });
  assert.deepEqual(calls[0], ["M", ...c.segments[0][0]]);
  assert.equal(calls.length, ring.length + 2);
  c.segments.forEach((seg, k) => assert.deepEqual(calls[k + 1], ["C", ...seg[1], ...seg[2], ...seg[3]]));
  assert.deepEqual(calls.at(-1), ["Z"]);
});

test("never throws inside a d3 call, whatever the data", () => {
  const hostile = [
    [[0, NaN], [1, 2], [2, 3]],
    [[0, 0], [0, 1], [0, 2]],
    [[0, 0], [1e308, 1], [-1e308, 2], [0, Infinity]],
    [["a", 1], [null, 2], [undefined, 3]],
    [[1, 1], [1, 1], [1, 1]],
    [[0, 0], [1, 1], [0, 0], [1, 1]],
  ];
  for (const [name, curve] of Object.entries(kinds)) {
    for (const data of hostile) {
      for (const shape of [d3.line(), d3.area(), d3.lineRadial(), d3.areaRadial()]) {
        assert.doesNotThrow(() => shape.curve(curve)(data), `${name} on ${JSON.stringify(data)}`);
      }
    }
  }
});

test("d3.lineRadial and d3.areaRadial take the curves", () => {
  const data = series(20, 13).map(([x, y]) => [x / 3, 50 + 10 * y]);
  for (const curve of Object.values(kinds)) {
    const d = d3.lineRadial().curve(curve)(data);
    assert.match(d, /^M[-\d.e]+,[-\d.e]+C/);
    assert.match(d3.areaRadial().curve(curve)(data), /C/);
  }
});

test("factories take parameters in d3's style and check them at once", () => {
  const data = series(8, 17);
  assert.notEqual(d3.line().curve(curveBzsplineX.alpha(1 / 3))(data), d3.line().curve(curveBzsplineX)(data));
  // Coerced as d3 coerces its curves' parameters.
  assert.equal(d3.line().curve(curveBzsplineX.alpha("0.5"))(data), d3.line().curve(curveBzsplineX)(data));
  assert.throws(() => curveBzsplineX.alpha("1/3"), RangeError);
  const calls = record(d3.line().curve(curveBzspline.param("uniform")), data);
  const c = new Curve(data, { param: "uniform" });
  c.segments.forEach((seg, k) => assert.deepEqual(calls[k + 1], ["C", ...seg[1], ...seg[2], ...seg[3]]));
  assert.notDeepEqual(calls, record(d3.line().curve(curveBzspline), data));
  assert.throws(() => curveBzsplineX.alpha(0.7), RangeError);
  assert.throws(() => curveBzspline.param("spiral"), RangeError);
  assert.equal(typeof curveBzsplineX.param, "undefined");
});

test("never overshoots: a step stays within the data's range", () => {
  // A step: the curve stays in [0, 1], where d3.curveNatural overshoots.
  const step = [[0, 0], [1, 0], [2, 0], [3, 1], [4, 1], [5, 1]];
  const s = new Spline(step.map((p) => p[0]), step.map((p) => p[1]));
  const xs = Float64Array.from({ length: 501 }, (_, i) => i / 100);
  for (const v of s.at(xs)) assert.ok(v >= 0 && v <= 1, `${v} outside [0, 1]`);
  const natural = record(d3.line().curve(d3.curveNatural), step);
  assert.ok(natural.some((c) => c[0] === "C" && (c[2] < 0 || c[4] > 1)));
});
