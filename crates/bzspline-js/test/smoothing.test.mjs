// bzspline/smoothing: the smoothing spline of noisy data, the command's own
// (`bzspline fit --smooth`) bit for bit, with its exact limits and refusals;
// the results are the curves entry's Spline and Curve.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { Spline, Curve } from "../js/index.js";
import { smoothingSpline, smoothingCurve } from "../js/smoothing.js";
import { random, close } from "./record.mjs";

const root = join(dirname(fileURLToPath(import.meta.url)), "../../..");
const bin = process.env.BZSPLINE_BIN || join(root, "target/debug/bzspline");

/** A noisy sine: x increasing, y = sin x + noise. */
function noisy(n, seed) {
  const r = random(seed);
  const x = [];
  const y = [];
  let t = 0;
  for (let i = 0; i < n; i++) {
    t += 0.02 + 0.08 * r();
    x.push(t);
    y.push(Math.sin(t) + 0.6 * (r() - 0.5));
  }
  return { x, y };
}

test("the fit is the command's, bit for bit, with lam, gcv and dof", () => {
  assert.ok(existsSync(bin), `${bin} is missing: cargo build -p bzspline-cli`);
  for (const [seed, smooth] of [[1, "auto"], [2, "auto"], [3, "0.5"]]) {
    const { x, y } = noisy(150, seed);
    const table = "x,y\n" + x.map((v, i) => `${v},${y[i]}`).join("\n") + "\n";
    const got = JSON.parse(
      execFileSync(bin, ["fit", "--input-format", "csv", "--smooth", smooth], { input: table }),
    );
    const lam = smooth === "auto" ? undefined : Number(smooth);
    const s = smoothingSpline(x, y, { lam });
    assert.deepEqual(Array.from(s.controlValues), got.values, `seed ${seed}`);
    assert.equal(s.lam, got.lambda);
    assert.equal(s.gcv, got.gcv);
    assert.equal(s.dof, got.dof);
    s.free();
  }
});

test("lam 0 passes through; weights of zero are ignored; a plain spline has no lam", () => {
  const { x, y } = noisy(60, 4);
  const s = smoothingSpline(x, y, { lam: 0 });
  x.forEach((v, i) => close(s.at(v), y[i], 1e-12, `point ${i}`));
  const w = x.map((_, i) => (i % 7 === 0 ? 0 : 1));
  const a = smoothingSpline(x, y, { w });
  const moved = y.map((v, i) => (w[i] === 0 ? v + 100 : v));
  const b = smoothingSpline(x, moved, { w: Float64Array.from(w) });
  assert.deepEqual(Array.from(a.controlValues), Array.from(b.controlValues));
  assert.ok(a instanceof Spline);
  assert.equal(new Spline(x, y).lam, undefined);
});

test("bad input throws naming the index", () => {
  const { x, y } = noisy(10, 5);
  const cases = [
    [() => smoothingSpline(x.slice(0, 2), y.slice(0, 2)), RangeError, /at least 3/],
    [() => smoothingSpline(x, y, { w: x.map((_, i) => (i === 3 ? -1 : 1)) }), RangeError, /weights\[3\]/],
    [() => smoothingSpline(x, y, { lam: -1 }), RangeError, /lambda/],
    [() => smoothingSpline(x, y, { lam: "lots" }), TypeError, /lam/],
    [() => smoothingSpline(x, y, { w: [1, 2] }), RangeError, /weights/],
    [() => smoothingSpline([...x].reverse(), y), RangeError, /increasing/],
  ];
  for (const [f, kind, message] of cases) {
    assert.throws(f, (e) => e instanceof kind && message.test(e.message), String(f));
  }
});

test("a noisy track is smoothed on its times, each coordinate the function fit", () => {
  const r = random(7);
  const n = 300;
  const t = Array.from({ length: n }, (_, i) => (6 * i) / (n - 1));
  const track = t.map((s) => [10 * Math.cos(s) + 0.6 * (r() - 0.5), 10 * Math.sin(s) + 0.6 * (r() - 0.5)]);
  const c = smoothingCurve(track, { param: t });
  assert.ok(c.lam > 0 && c.dof > 3 && c.dof < n);
  assert.deepEqual(Array.from(c.knots), t);
  const off = (p) => Math.abs(Math.hypot(p[0], p[1]) - 10);
  const data = track.reduce((a, p) => a + off(p), 0) / n;
  const fit = c.at(t).reduce((a, p) => a + off(p), 0) / n;
  assert.ok(fit < 0.6 * data, `fit ${fit} against the data's ${data}`);
  for (const d of [0, 1]) {
    const s = smoothingSpline(t, track.map((p) => p[d]), { lam: c.lam });
    c.segments.forEach((seg, k) => {
      seg.forEach((p, j) => close(p[d], s.segments[k][j][1], 1e-11, `segment ${k} point ${j}`));
    });
  }
  assert.throws(() => smoothingCurve(track.slice(0, 2)), RangeError);
  assert.ok(c instanceof Curve);
  assert.equal(new Curve(track).lam, undefined);
});

test("the options reach the spline: alpha, alphas, extrapolate; repeats in a curve", () => {
  const { x, y } = noisy(40, 8);
  const lam = 0.05;
  const a = smoothingSpline(x, y, { lam, alpha: 0.4, extrapolate: "clamp" });
  assert.ok(Array.from(a.alphas).every((v) => v === 0.4));
  assert.equal(a.at(x[39] + 5), a.at(x[39]));
  assert.ok(Number.isNaN(smoothingSpline(x, y, { lam, extrapolate: false }).at(x[0] - 1)));
  const alphas = x.slice(1).map((_, i) => (i % 2 ? 1 / 3 : 2 / 3));
  assert.deepEqual(Array.from(smoothingSpline(x, y, { lam, alphas }).alphas), alphas);
  assert.throws(() => smoothingSpline(x, y, { alpha: 0.5, alphas }), TypeError);
  assert.throws(() => smoothingSpline(x, y, { extrapolate: "yes" }), TypeError);
  // A curve on given parameters and alphas keeps them.
  const pts = x.map((v, i) => [v, y[i]]);
  const legs = alphas.map((v) => 1 - v);
  const c = smoothingCurve(pts, { lam, param: x, alphas: legs });
  assert.deepEqual(Array.from(c.knots), x);
  assert.deepEqual(Array.from(c.alphas), legs);
  assert.deepEqual(c.knots, smoothingCurve(pts, { lam, param: Float64Array.from(x) }).knots);
});

test("bands are the command's, bit for bit, around the fit", () => {
  assert.ok(existsSync(bin), `${bin} is missing: cargo build -p bzspline-cli`);
  const { x, y } = noisy(200, 4);
  const table = "x,y\n" + x.map((v, i) => `${v},${y[i]}`).join("\n") + "\n";
  const at = [x[0], 1.5, 4.25, x[x.length - 1]];
  const rows = execFileSync(
    bin,
    ["eval", "--input-format", "csv", "--smooth", "auto", "--band", "0.9", "--at", at.join(",")],
    { input: table },
  )
    .toString()
    .trim()
    .split("\n")
    .slice(1)
    .map((l) => l.split(",").map(Number));
  const s = smoothingSpline(x, y);
  const { lo, hi } = s.band(at, 0.9);
  assert.ok(lo instanceof Float64Array && hi.length === at.length);
  at.forEach((t, i) => {
    assert.deepEqual([lo[i], hi[i]], [rows[i][2], rows[i][3]], `at ${t}`);
    assert.ok(lo[i] < s.at(t) && s.at(t) < hi[i]);
    const one = s.band(t, 0.9);
    assert.deepEqual([one.lo, one.hi], [lo[i], hi[i]]);
  });
  // A 95 % band is wider by the ratio of the normal quantiles.
  const se = s.se(at);
  const wide = s.band(at);
  at.forEach((_, i) => {
    close(wide.hi[i] - wide.lo[i], 2 * 1.959963984540054 * se[i], 1e-12, "95 % width");
  });
  assert.equal(typeof s.se(2), "number");
});

test("bands are refused where there are none", () => {
  const { x, y } = noisy(50, 5);
  const s = smoothingSpline(x, y);
  assert.throws(() => s.band([1], 1.5), (e) => e instanceof RangeError && /strictly between 0 and 1/.test(e.message));
  assert.throws(() => s.se([1, 1e6]), (e) => e instanceof RangeError && /x\[1\]/.test(e.message));
  const exact = smoothingSpline(x, y, { lam: 0 });
  assert.throws(() => exact.se(1), /no residual degrees of freedom/);
  assert.equal(new Spline([0, 1, 2], [0, 1, 0]).band, undefined);
});

test("robust fits and weights are the command's, bit for bit", () => {
  assert.ok(existsSync(bin), `${bin} is missing: cargo build -p bzspline-cli`);
  const { x, y } = noisy(200, 5);
  y[60] += 9;
  y[140] -= 7;
  const w = x.map((_, i) => [1, 0.5, 2][i % 3]);
  const table = "x,y,w\n" + x.map((v, i) => `${v},${y[i]},${w[i]}`).join("\n") + "\n";
  const got = JSON.parse(
    execFileSync(
      bin,
      ["fit", "--input-format", "csv", "--smooth", "auto", "--weights", "w", "--robust"],
      { input: table },
    ),
  );
  const s = smoothingSpline(x, y, { w, robust: true });
  assert.deepEqual(Array.from(s.controlValues), got.values);
  assert.deepEqual(Array.from(s.robustness), got.robustness);
  assert.equal(s.robustness[60], 0);
  assert.equal(s.robustness[140], 0);
  assert.equal(smoothingSpline(x, y).robustness, null);
  // A track with a jump, on its times.
  const t = x.slice(0, 100);
  const track = t.map((v) => [Math.cos(v), Math.sin(v)]);
  track[50] = [track[50][0] + 1, track[50][1]];
  const c = smoothingCurve(track, { param: t, robust: true });
  assert.equal(c.robustness.length, 100);
  assert.equal(c.robustness[50], 0);
  assert.throws(() => smoothingSpline(x.slice(0, 4), y.slice(0, 4), { robust: true }), /at least 5/);
  assert.throws(() => smoothingSpline(x, y, { robust: "yes" }), /robust must be true or false/);
});

test("closed curves smooth round their loop, as the command does", () => {
  assert.ok(existsSync(bin), `${bin} is missing: cargo build -p bzspline-cli`);
  const r = random(11);
  const ring = [];
  for (let i = 0; i < 90; i++) {
    const a = (2 * Math.PI * i) / 90;
    ring.push([5 * Math.cos(a) + 0.4 * (r() - 0.5), 3 * Math.sin(a) + 0.4 * (r() - 0.5)]);
  }
  const table = "x,y\n" + ring.map((p) => p.join(",")).join("\n") + "\n";
  const got = JSON.parse(
    execFileSync(bin, ["fit", "--input-format", "csv", "--closed", "--smooth", "auto"], { input: table }),
  );
  const c = smoothingCurve(ring, { closed: true });
  assert.equal(c.closed, true);
  assert.equal(c.dof, got.dof);
  assert.deepEqual(c.segments.map((s) => s.map((p) => Array.from(p))), got.segments);
});
