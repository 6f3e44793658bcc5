// The Chart.js plugin in a real Chart.js 4 on a recording canvas (Node has
// no DOM, so Chart.js takes its basic platform): the path Chart.js strokes
// is the method's spline through the points' pixels, piece by piece, with
// gaps, stacking, fill, time scales and decimation; the tooltip helper
// agrees with Spline.at; datasets the method cannot take are drawn as
// Chart.js draws them.
import { test } from "node:test";
import assert from "node:assert/strict";
import { Chart, registerables, _adapters } from "chart.js";
import { Spline } from "../js/index.js";
import { smoothingSpline } from "../js/smoothing.js";
import { bzsplinePlugin, curveValue } from "../js/chartjs.js";
import { series, close } from "./record.mjs";

Chart.register(...registerables, bzsplinePlugin);

/** A 2D context that records the paths stroked and filled, exactly. */
function recordingCanvas(width = 640, height = 400) {
  const paths = [];
  let path = [];
  const ctx = {
    paths,
    beginPath: () => {
      path = [];
    },
    moveTo: (x, y) => path.push(["M", x, y]),
    lineTo: (x, y) => path.push(["L", x, y]),
    bezierCurveTo: (...a) => path.push(["C", ...a]),
    closePath: () => path.push(["Z"]),
    stroke: () => paths.push({ op: "stroke", style: ctx.strokeStyle, path }),
    fill: () => paths.push({ op: "fill", style: ctx.fillStyle, path }),
    measureText: (t) => ({ width: String(t).length * 6, actualBoundingBoxAscent: 8, actualBoundingBoxDescent: 2 }),
    getLineDash: () => [],
  };
  const noop = () => {};
  const proxy = new Proxy(ctx, {
    get: (t, k) => (k in t ? t[k] : typeof k === "string" && /^[a-z]/.test(k) && !k.endsWith("Style") ? noop : undefined),
    set: (t, k, v) => {
      t[k] = v;
      return true;
    },
  });
  const canvas = { width, height, style: {}, getContext: () => proxy };
  ctx.canvas = canvas;
  return { canvas, ctx };
}

function chart(config, size) {
  const { canvas, ctx } = recordingCanvas(...(size || []));
  const options = { animation: false, responsive: false, ...config.options };
  const c = new Chart(canvas, { ...config, options });
  return { chart: c, ctx };
}

/**
 * The stroked lines of one colour (each dataset gets its own; its points and
 * legend box, stroked in the same colour, draw no moveTo).
 */
function strokes(ctx, color) {
  return ctx.paths
    .filter((p) => p.op === "stroke" && p.style === color && p.path.length && p.path[0][0] === "M")
    .map((p) => p.path);
}

/** The Spline through a dataset's drawn points in pixels. */
function pixelSpline(c, i, options) {
  const pts = c.getDatasetMeta(i).data.filter((p) => !p.skip);
  return new Spline(pts.map((p) => p.x), pts.map((p) => p.y), options);
}

/** Checks a recorded path against the spline's pieces. */
function samePieces(path, s, tol, what) {
  const segs = s.segments;
  assert.equal(path[0][0], "M", what);
  assert.equal(path.length, segs.length + 1, `${what}: one C a piece`);
  segs.forEach((seg, k) => {
    const call = path[k + 1];
    assert.equal(call[0], "C", what);
    const want = [...seg[1], ...seg[2], ...seg[3]];
    want.forEach((v, j) => close(call[j + 1], v, tol, `${what}: piece ${k}, value ${j}`));
  });
}

test("a line dataset is the method's spline through its pixels, one bezierCurveTo a piece", () => {
  for (let seed = 1; seed <= 12; seed++) {
    const data = series(4 + seed * 3, seed).map(([x, y]) => ({ x, y }));
    const alpha = [1 / 3, 0.5, 2 / 3][seed % 3];
    const { chart: c, ctx } = chart({
      type: "line",
      data: { datasets: [{ data, borderColor: "#123456", bzspline: { alpha, through: seed % 2 === 0 } }] },
      options: { scales: { x: { type: "linear" } } },
    });
    const [path] = strokes(ctx, "#123456");
    const s = pixelSpline(c, 0, { alpha, through: seed % 2 === 0 });
    samePieces(path, s, 1e-9, `seed ${seed}`);
    s.free();
    c.destroy();
  }
});

test("without the plugin's option Chart.js draws its own line", () => {
  const data = series(12, 3).map(([x, y]) => ({ x, y }));
  const { ctx } = chart({
    type: "line",
    data: { datasets: [{ data, borderColor: "#111111" }] },
    options: { scales: { x: { type: "linear" } } },
  });
  const [path] = strokes(ctx, "#111111");
  assert.ok(path.slice(1).every((c) => c[0] === "L"), "straight segments");
});

test("category scales, gaps split or spanned, stacked datasets and fill", () => {
  const labels = Array.from({ length: 14 }, (_, i) => `d${i}`);
  const a = [3, 5, 4, 8, null, 7, 6, 9, 12, 11, 10, 14, 13, 15];
  const b = [1, 2, 2, 3, 2, 4, 3, 2, 5, 4, 6, 5, 4, 3];
  for (const spanGaps of [false, true]) {
    const { chart: c, ctx } = chart({
      type: "line",
      data: {
        labels,
        datasets: [
          { data: a, borderColor: "#aa0000", backgroundColor: "#aa000033", fill: "origin", spanGaps, bzspline: true },
          { data: b, borderColor: "#0000aa", bzspline: true },
        ],
      },
      options: { scales: { y: { stacked: true } } },
    });
    const red = strokes(ctx, "#aa0000");
    const runs = spanGaps ? [[0, 14]] : [[0, 4], [5, 14]];
    assert.equal(red.length, runs.length, `spanGaps ${spanGaps}: one stroke a run`);
    const pts = c.getDatasetMeta(0).data;
    runs.forEach(([from, to], r) => {
      const run = pts.slice(from, to).filter((p) => !p.skip);
      const s = new Spline(run.map((p) => p.x), run.map((p) => p.y));
      samePieces(red[r], s, 1e-9, `spanGaps ${spanGaps}, run ${r}`);
      s.free();
    });
    // The fill's outline follows the same pieces.
    const fills = ctx.paths.filter((p) => p.op === "fill" && p.style === "#aa000033");
    assert.ok(fills.length >= 1, "filled");
    const curves = fills.flatMap((f) => f.path.filter((x) => x[0] === "C"));
    const strokesC = red.flatMap((p) => p.filter((x) => x[0] === "C"));
    for (const sc of strokesC) {
      assert.ok(
        curves.some((fc) => fc.every((v, j) => j === 0 || Math.abs(v - sc[j]) < 1e-9)),
        "every stroked piece is in the fill's outline",
      );
    }
    // The stacked dataset is the spline through its stacked pixels.
    const blue = strokes(ctx, "#0000aa");
    const s = pixelSpline(c, 1);
    samePieces(blue[0], s, 1e-9, "stacked");
    s.free();
    c.destroy();
  }
});

test("the value on the drawn curve at a pixel is Spline.at there, in the data's units", () => {
  const data = series(40, 11).map(([x, y]) => ({ x, y }));
  const { chart: c } = chart({
    type: "line",
    data: { datasets: [{ data, bzspline: { alpha: 0.4 } }] },
    options: { scales: { x: { type: "linear" } } },
  });
  const s = pixelSpline(c, 0, { alpha: 0.4 });
  const meta = c.getDatasetMeta(0);
  const [lo, hi] = [meta.data[0].x, meta.data[meta.data.length - 1].x];
  for (let k = 0; k <= 200; k++) {
    const px = lo + ((hi - lo) * k) / 200;
    const want = meta.vScale.getValueForPixel(s.at(px));
    close(curveValue(c, 0, px), want, 1e-9 * (1 + Math.abs(want)), `pixel ${px}`);
  }
  // At a point's pixel the value is the point's own (the curve ends there
  // only at the ends; inside, the curve passes near, within the data's range).
  close(curveValue(c, 0, lo), data[0].y, 1e-9, "first point");
  assert.equal(curveValue(c, 0, lo - 5), null, "outside the points");
  assert.equal(curveValue(c, 0, Number.NaN), null);
  s.free();
  c.destroy();
});

test("timestamps and LTTB decimation draw the spline through what Chart.js keeps", () => {
  const day = 86400000;
  const data = series(3000, 5).map(([x, y], i) => ({ x: Date.UTC(2020, 0, 1) + i * day, y }));
  const { chart: c, ctx } = chart({
    type: "line",
    data: { datasets: [{ data, borderColor: "#00aa00", bzspline: true, pointRadius: 0 }] },
    options: {
      parsing: false,
      scales: { x: { type: "linear" } },
      plugins: { decimation: { enabled: true, algorithm: "lttb", samples: 200 } },
    },
  });
  const [path] = strokes(ctx, "#00aa00");
  const kept = c.getDatasetMeta(0).data;
  assert.ok(kept.length <= 200, `decimated to ${kept.length}`);
  const s = pixelSpline(c, 0);
  samePieces(path, s, 1e-9, "decimated");
  s.free();
  c.destroy();
});

// Chart.js's time scale needs a date adapter (a page takes one such as
// chartjs-adapter-date-fns); this one knows UTC, which is all a test needs.
const MS = { millisecond: 1, second: 1e3, minute: 6e4, hour: 36e5, day: 864e5, week: 6048e5 };
const fields = (t) => {
  const d = new Date(t);
  return [d.getUTCFullYear(), d.getUTCMonth(), d.getUTCDate()];
};
_adapters._date.override({
  formats: () => Object.fromEntries(Object.keys({ ...MS, month: 0, quarter: 0, year: 0, datetime: 0 }).map((k) => [k, k])),
  parse: (v) => (typeof v === "number" ? v : v instanceof Date ? +v : Date.parse(v)),
  format: (t) => new Date(t).toISOString().slice(0, 10),
  add(t, n, unit) {
    if (unit in MS) return t + n * MS[unit];
    const [y, m, d] = fields(t);
    const months = unit === "year" ? 12 * n : unit === "quarter" ? 3 * n : n;
    return Date.UTC(y, m + months, d) + (t % MS.day);
  },
  diff(a, b, unit) {
    if (unit in MS) return (a - b) / MS[unit];
    const [[ya, ma], [yb, mb]] = [fields(a), fields(b)];
    const months = 12 * (ya - yb) + ma - mb;
    return unit === "year" ? months / 12 : unit === "quarter" ? months / 3 : months;
  },
  startOf(t, unit) {
    if (unit === "week" || unit === "isoWeek") unit = "day";
    if (unit in MS) return t - (t % MS[unit]);
    const [y, m] = fields(t);
    return unit === "year" ? Date.UTC(y, 0) : unit === "quarter" ? Date.UTC(y, m - (m % 3)) : Date.UTC(y, m);
  },
  endOf(t, unit) {
    return this.add(this.startOf(t, unit), 1, unit) - 1;
  },
});

test("a time scale draws the spline through its points' pixels", () => {
  const data = series(60, 21).map(([, y], i) => ({ x: Date.UTC(2024, 0, 1) + i * 7 * MS.day, y }));
  const { chart: c, ctx } = chart({
    type: "line",
    data: { datasets: [{ data, borderColor: "#0a0b0c", bzspline: true }] },
    options: { scales: { x: { type: "time" } } },
  });
  assert.equal(c.scales.x.type, "time");
  const [path] = strokes(ctx, "#0a0b0c");
  const s = pixelSpline(c, 0);
  samePieces(path, s, 1e-9, "time scale");
  s.free();
  c.destroy();
});

test("smooth draws the fit it is given: the smoothing spline of noisy points", () => {
  let state = 7;
  const noise = () => ((state = (state * 16807) % 2147483647) / 2147483647 - 0.5) * 30;
  const data = Array.from({ length: 120 }, (_, i) => ({ x: i, y: 100 * Math.sin(i / 15) + noise() }));
  const { chart: c, ctx } = chart({
    type: "line",
    data: { datasets: [{ data, borderColor: "#aabbcc", bzspline: { smooth: smoothingSpline } }] },
    options: { scales: { x: { type: "linear" } } },
  });
  const [path] = strokes(ctx, "#aabbcc");
  const pts = c.getDatasetMeta(0).data;
  const fit = smoothingSpline(pts.map((p) => p.x), pts.map((p) => p.y));
  assert.ok(fit.lam > 0 && fit.dof < pts.length / 2, `lam ${fit.lam}, dof ${fit.dof}`);
  samePieces(path, fit, 1e-9, "smoothed");
  // The tooltip helper reads the smoothed curve.
  const px = pts[50].x;
  close(curveValue(c, 0, px), c.getDatasetMeta(0).vScale.getValueForPixel(fit.at(px)), 1e-9, "curveValue");
  fit.free();
  c.destroy();
  // A fit that throws leaves the line to Chart.js, without an exception.
  const { ctx: ctx2 } = chart({
    type: "line",
    data: { datasets: [{ data, borderColor: "#aabbcc", bzspline: { smooth: () => { throw new Error("no"); } } }] },
    options: { scales: { x: { type: "linear" } } },
  });
  const [own] = strokes(ctx2, "#aabbcc");
  assert.ok(own.slice(1).every((call) => call[0] === "L"));
});

test("after a resize the curve is rebuilt for the new pixels", () => {
  const data = series(20, 9).map(([x, y]) => ({ x, y }));
  const { chart: c, ctx } = chart({
    type: "line",
    data: { datasets: [{ data, borderColor: "#345678", bzspline: true }] },
    options: { scales: { x: { type: "linear" } } },
  });
  c.resize(300, 200);
  const last = strokes(ctx, "#345678").at(-1);
  const s = pixelSpline(c, 0);
  samePieces(last, s, 1e-9, "resized");
  s.free();
  c.destroy();
});

test("reversed axes and horizontal lines (indexAxis y) draw the same spline", () => {
  const data = series(15, 4).map(([x, y]) => ({ x, y }));
  for (const [what, options, axis] of [
    ["reversed x", { scales: { x: { type: "linear", reverse: true } } }, "x"],
    ["indexAxis y", { indexAxis: "y", scales: { y: { type: "linear" }, x: { type: "linear" } } }, "y"],
    ["indexAxis y, reversed", { indexAxis: "y", scales: { y: { type: "linear", reverse: true }, x: { type: "linear" } } }, "y"],
  ]) {
    const rows = axis === "y" ? data.map(({ x, y }) => ({ x: y, y: x })) : data;
    const { chart: c, ctx } = chart({
      type: "line",
      data: { datasets: [{ data: rows, borderColor: "#765432", bzspline: { alpha: 0.4 } }] },
      options,
    });
    const [path] = strokes(ctx, "#765432");
    // Each drawn piece as [start, c1, c2, end] in (u, v), u the index axis,
    // written from its lower u.
    const uv = (x, y) => (axis === "y" ? [y, x] : [x, y]);
    const drawn = path.slice(1).map((call, k) => {
      const q = [uv(...path[k].slice(-2)), uv(call[1], call[2]), uv(call[3], call[4]), uv(call[5], call[6])];
      return q[0][0] < q[3][0] ? q : q.reverse();
    });
    drawn.sort((a, b) => a[0][0] - b[0][0]);
    const pts = c.getDatasetMeta(0).data.map((p) => uv(p.x, p.y)).sort((a, b) => a[0] - b[0]);
    const s = new Spline(pts.map((p) => p[0]), pts.map((p) => p[1]), { alpha: 0.4 });
    assert.equal(drawn.length, s.segments.length, what);
    s.segments.forEach((seg, k) =>
      seg.forEach((pt, j) => pt.forEach((v, e) => close(drawn[k][j][e], v, 1e-9, `${what}: piece ${k}`))),
    );
    s.free();
    c.destroy();
  }
});

test("what the method cannot take is drawn as Chart.js draws it, without an exception", () => {
  // x going back and forth (a scatter drawn as a line), and one point.
  const zigzag = [0, 2, 1, 3, 2, 4].map((x, i) => ({ x, y: i % 3 }));
  const { chart: c, ctx } = chart({
    type: "scatter",
    data: {
      datasets: [
        { data: zigzag, showLine: true, borderColor: "#999999", bzspline: true },
        { data: [{ x: 1, y: 1 }], showLine: true, borderColor: "#888888", bzspline: true },
      ],
    },
  });
  // Chart.js's own line: straight, or its own Bezier pieces with a tension.
  const [path] = strokes(ctx, "#999999");
  assert.ok(path.slice(1).every((c) => c[0] === "L"), "straight segments");
  for (const p of c.getDatasetMeta(0).data) {
    assert.ok(path.some(([, x, y]) => Math.abs(x - p.x) < 1e-9 && Math.abs(y - p.y) < 1e-9), "through every point");
  }
  const { ctx: ctx2 } = chart({
    type: "scatter",
    data: { datasets: [{ data: zigzag, showLine: true, tension: 0.3, borderColor: "#999999", bzspline: true }] },
  });
  const [curved] = strokes(ctx2, "#999999");
  assert.equal(curved.length, zigzag.length);
  assert.ok(curved.slice(1).every((c) => c[0] === "C"), "Chart.js's tension pieces");
});

test("a bad option is refused naming the dataset", () => {
  const { canvas } = recordingCanvas();
  assert.throws(
    () => new Chart(canvas, { type: "line", data: { datasets: [{ data: [1, 2, 3], bzspline: { alpha: 0.9 } }] } }),
    /dataset 0: bzspline alpha = 0.9 is outside \[1\/3, 2\/3\]/,
  );
  assert.throws(
    () => new Chart(recordingCanvas().canvas, { type: "line", data: { datasets: [{ data: [1], bzspline: "yes" }] } }),
    /dataset 0: bzspline is true or/,
  );
  assert.throws(
    () =>
      new Chart(recordingCanvas().canvas, {
        type: "line",
        data: { datasets: [{ data: [1, 2, 3], bzspline: { smooth: "auto" } }] },
      }),
    /dataset 0: bzspline smooth is a function/,
  );
});
