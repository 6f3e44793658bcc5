// Spline and Curve for numbers: their defining conditions checked on many
// generated inputs, errors that name the index, and memory released.
import { test } from "node:test";
import { setFlagsFromString } from "node:v8";
import { runInNewContext } from "node:vm";
import assert from "node:assert/strict";
import { Spline, Curve, memoryBytes } from "../js/index.js";
import { series, close, random } from "./record.mjs";

test("a spline starts and ends at the end points and touches every leg at its alpha", () => {
  for (let seed = 1; seed <= 50; seed++) {
    const data = series(2 + (seed % 23), seed);
    const x = data.map((p) => p[0]);
    const y = data.map((p) => p[1]);
    const alpha = 1 / 3 + (seed % 7) / 18;
    const s = new Spline(x, y, { alpha });
    close(s.at(x[0]), y[0], 1e-14, "start");
    close(s.at(x.at(-1)), y.at(-1), 1e-14, "end");
    const d = s.derivative();
    s.tangentPoints.forEach(([tx, ty], k) => {
      // On leg k, at alpha from its end, with the leg's slope.
      close(tx, x[k + 1] - alpha * (x[k + 1] - x[k]), 1e-14, `tangent x ${k}`);
      close(ty, alpha * y[k] + (1 - alpha) * y[k + 1], 1e-13, `tangent y ${k}`);
      close(s.at(tx), ty, 1e-13, `S at tangent ${k}`);
      close(d.at(tx), (y[k + 1] - y[k]) / (x[k + 1] - x[k]), 1e-9, `slope at tangent ${k}`);
    });
    // C1: at every knot the pieces' end tangents (Bezier legs) agree.
    const seg = s.segments;
    for (let k = 1; k < seg.length; k++) {
      const [p2, p3] = [seg[k - 1][2], seg[k - 1][3]];
      const [q0, q1] = [seg[k][0], seg[k][1]];
      assert.deepEqual(p3, q0);
      const left = (p3[1] - p2[1]) / (p3[0] - p2[0]);
      const right = (q1[1] - q0[1]) / (q1[0] - q0[0]);
      close(left, right, 1e-9, `C1 at knot ${k}`);
    }
    // Within the range of the control values.
    const lo = Math.min(...y);
    const hi = Math.max(...y);
    const xs = Float64Array.from({ length: 200 }, (_, i) => x[0] + ((x.at(-1) - x[0]) * i) / 199);
    for (const v of s.at(xs)) assert.ok(v >= lo - 1e-12 && v <= hi + 1e-12);
    s.free();
    d.free();
  }
});

test("integrate agrees with a dense Simpson sum; at of an array is at of each", () => {
  const data = series(30, 21);
  const s = new Spline(data.map((p) => p[0]), data.map((p) => p[1]));
  const [a, b] = [data[2][0] + 0.1, data[25][0] - 0.3];
  const n = 20000;
  const xs = Float64Array.from({ length: n + 1 }, (_, i) => a + ((b - a) * i) / n);
  const v = s.at(xs);
  let sum = v[0] + v[n];
  for (let i = 1; i < n; i++) sum += (i % 2 ? 4 : 2) * v[i];
  close(s.integrate(a, b), (sum * (b - a)) / (3 * n), 1e-10, "integral");
  close(s.integrate(b, a), -s.integrate(a, b), 1e-15, "reversed");
  for (let i = 0; i <= n; i += 997) assert.equal(v[i], s.at(xs[i]));
});

test("extrema are where the derivative vanishes", () => {
  const s = new Spline([0, 1, 2, 3, 4], [0, 2, -1, 3, 0]);
  const e = s.extrema();
  assert.deepEqual(e.map((p) => p.kind), ["maximum", "minimum", "maximum"]);
  const d = s.derivative();
  for (const p of e) {
    assert.ok(Math.abs(d.at(p.x)) < 1e-12);
    close(s.at(p.x), p.y, 1e-14, "y of the extremum");
  }
});

test("through passes through every point; extrapolate as scipy", () => {
  const data = series(12, 4);
  const x = data.map((p) => p[0]);
  const y = data.map((p) => p[1]);
  const s = new Spline(x, y, { through: true });
  x.forEach((xi, i) => close(s.at(xi), y[i], 1e-12, `point ${i}`));
  assert.ok(Number.isFinite(s.at(x[0] - 1)));
  assert.ok(Number.isNaN(new Spline(x, y, { extrapolate: false }).at(x[0] - 1)));
  assert.equal(new Spline(x, y, { extrapolate: "clamp" }).at(x.at(-1) + 5), y.at(-1));
  // The library's names: "nan" is false, "extend" is true.
  const q = Float64Array.of(x[0] - 1, x[1], x.at(-1) + 2);
  assert.deepEqual(new Spline(x, y, { extrapolate: "nan" }).at(q), new Spline(x, y, { extrapolate: false }).at(q));
  assert.deepEqual(new Spline(x, y, { extrapolate: "extend" }).at(q), new Spline(x, y).at(q));
  assert.ok(Number.isNaN(s.at(NaN)));
});

test("a curve starts and ends at its end points, touches every leg and stays in the hull", () => {
  const r = random(8);
  for (let trial = 0; trial < 30; trial++) {
    const pts = Array.from({ length: 3 + (trial % 9) }, () => [r() * 10, r() * 10]);
    const c = new Curve(pts);
    const [t0, t1] = [c.knots[0], c.knots.at(-1)];
    assert.deepEqual([...c.at(t0)].map((v, i) => Math.abs(v - pts[0][i]) < 1e-12), [true, true]);
    const end = c.at(t1);
    pts.at(-1).forEach((v, i) => close(end[i], v, 1e-12, "end"));
    const b = c.bbox();
    const lo = [0, 1].map((i) => Math.min(...pts.map((p) => p[i])));
    const hi = [0, 1].map((i) => Math.max(...pts.map((p) => p[i])));
    [0, 1].forEach((i) => assert.ok(b.min[i] >= lo[i] - 1e-12 && b.max[i] <= hi[i] + 1e-12));
    const flat = c.flatten(1e-3);
    assert.ok(flat.length >= 2);
    const len = c.arclen();
    let poly = 0;
    for (let i = 1; i < flat.length; i++) poly += Math.hypot(flat[i][0] - flat[i - 1][0], flat[i][1] - flat[i - 1][1]);
    assert.ok(poly <= len + 1e-9 && poly > len * 0.999);
    const q = [r() * 10, r() * 10];
    const near = c.nearest(q);
    for (const p of c.resample(200)) assert.ok(Math.hypot(p[0] - q[0], p[1] - q[1]) >= near.distance - 1e-9);
    c.free();
  }
});

test("closed curves and curves in space", () => {
  const c = new Curve([[0, 0, 0], [1, 0, 1], [1, 1, 0], [0, 1, 1]], { closed: true });
  assert.equal(c.dim, 3);
  assert.equal(c.closed, true);
  assert.equal(c.segments.length, 4);
  const a = c.at(c.knots[0]);
  const b = c.at(c.knots.at(-1));
  a.forEach((v, i) => close(v, b[i], 1e-14, "closed"));
  assert.throws(() => c.svgPath(), RangeError);
  assert.match(new Curve([[0, 0], [1, 0], [1, 1]], { closed: true }).svgPath(), /Z$/);
});

test("bad input throws RangeError or TypeError naming the index", () => {
  const cases = [
    [() => new Spline([0, 2, 1], [0, 1, 2]), RangeError, /knots\[2\]/],
    [() => new Spline([0, 1, 2], [0, NaN, 2]), RangeError, /1/],
    [() => new Spline([0, 1, 2], [0, 1]), RangeError, /length|values/],
    [() => new Spline([0, 1, 2], [0, "1", 2]), TypeError, /y\[1\]/],
    [() => new Spline("012", [0, 1, 2]), TypeError, /x must be an array/],
    [() => new Spline([0, 1, 2], [0, 1, 2], { alpha: 0.9 }), RangeError, /alpha/],
    [() => new Spline([0, 1, 2], [0, 1, 2], { alpha: "1/3" }), TypeError, /alpha must be a number, such as 1\/3 \(found the string "1\/3"\)/],
    [() => new Spline([0, 1, 2], [0, 1, 2], { alphas: [0.5] }), RangeError, /alpha/],
    [() => new Spline([0, 1, 2], [0, 1, 2], { extrapolate: "yes" }), TypeError, /extrapolate/],
    [() => new Spline([0, 1, 2], [0, 1, 2], { extrapolate: "error" }), TypeError, /extrapolate must be true, false, "clamp"/],
    [() => new Spline([0, 1, 2], [0, 1, 2], 5), TypeError, /options/],
    [() => new Curve([[0, 0], [1, 1], [1, 1]]), RangeError, /2/],
    [() => new Curve([[0, 0], [1]]), RangeError, /points\[1\]/],
    [() => new Curve([[0, 0], [1, 2]], { param: "spiral" }), RangeError, /spiral/],
    [() => new Curve([[0, 0], [1, 2]], { closed: true }), RangeError, /3|closed/],
    [() => new Curve([[0, 0], [1, 2]]).flatten(0), RangeError, /tolerance/],
  ];
  for (const [f, kind, message] of cases) assert.throws(f, (e) => e instanceof kind && message.test(e.message), f.toString());
  assert.equal(new Spline([0, 1, 2], [0, 1, 2], { alpha: 1 / 3 }).alphas[0], 1 / 3);
});

test("memory is released: 100,000 constructions do not grow the module's heap", () => {
  const x = Float64Array.from({ length: 50 }, (_, i) => i);
  const y = x.map(Math.sin);
  for (let i = 0; i < 1000; i++) new Spline(x, y).free();
  const before = memoryBytes();
  for (let i = 0; i < 100000; i++) {
    const s = new Spline(x, y);
    s.at(3.5);
    s.free();
    const c = new Curve([[0, 0], [1, 2], [3, 1]]);
    c.free();
  }
  assert.equal(memoryBytes(), before);
});

test("memory is released without free(): the garbage collector's finalizers return it", async () => {
  // gc() as --expose-gc gives it, for this test alone.
  setFlagsFromString("--expose-gc");
  const gc = runInNewContext("gc");
  const settle = async () => {
    gc();
    // Finalization callbacks run in a task of their own after the collection.
    await new Promise((resolve) => setTimeout(resolve, 0));
  };
  const x = Float64Array.from({ length: 200 }, (_, i) => i);
  const y = x.map(Math.sin);
  const round = () => {
    for (let i = 0; i < 1000; i++) {
      new Spline(x, y).at(3.5);
      new Curve([[0, 0], [1, 2], [3, 1], [4, 4]]).arclen();
    }
  };
  round();
  await settle();
  const before = memoryBytes();
  // 100,000 of each, never freed: some 2 GB of the module's heap if nothing
  // were returned (a spline of 200 points holds about 20 kB).
  for (let r = 0; r < 100; r++) {
    round();
    await settle();
  }
  assert.ok(memoryBytes() <= before + 16 * 2 ** 20, `${memoryBytes()} bytes after, ${before} before`);
});

test("evaluating a large typed array does not grow the module's memory by its size", () => {
  const x = Float64Array.from({ length: 1000 }, (_, i) => i);
  const s = new Spline(x, x.map(Math.sin));
  const q = Float64Array.from({ length: 4e6 }, (_, i) => (i * 999) / 4e6);
  const before = memoryBytes();
  const v = s.at(q);
  // 32 MB in and 32 MB out; WebAssembly memory never shrinks once grown.
  assert.ok(memoryBytes() - before <= 4 * 2 ** 20, `grew by ${memoryBytes() - before} bytes`);
  for (const i of [0, 1, 65535, 65536, 65537, 2e6, 4e6 - 1]) assert.equal(v[i], s.at(q[i]), `at(q)[${i}]`);
  s.free();
});
