// A Chart.js 4 plugin that draws line datasets with the method's spline:
// registered once (`Chart.register(bzsplinePlugin)`), chosen per dataset
// (`bzspline: true` or `{ alpha, through, smooth }`). The curve is the
// spline of the dataset's points in pixel space, or the fit `smooth` makes
// of them; each piece is one cubic Bezier segment, drawn by the line
// element's own path methods (`path`, `pathSegment`, `interpolate`, `draw`),
// which the filler, the animations and the decimation call, so fill, gaps,
// stacking, decimation, animation and resizing keep working. Pieces join at
// the spline's knots, which are the points themselves only for `through`
// and at the ends. `curveValue` gives the value on the drawn curve at a
// pixel (a tooltip at the pointer's x).
import "./index.js";
import { splinePieces, checkAlpha } from "../wasm/core.js";

/** The dataset's settings, or null where the plugin does not draw it. */
function settings(dataset, index) {
  const o = dataset.bzspline;
  if (!o) return null;
  if (o === true) return { alpha: 0.5, through: false };
  if (typeof o !== "object") {
    throw new TypeError(`dataset ${index}: bzspline is true or { alpha, through }, not ${String(o)}`);
  }
  let alpha = 0.5;
  if (o.alpha !== undefined) {
    try {
      alpha = checkAlpha(+o.alpha);
    } catch (e) {
      throw new RangeError(`dataset ${index}: bzspline ${e.message}`);
    }
  }
  if (o.smooth !== undefined && typeof o.smooth !== "function") {
    throw new TypeError(
      `dataset ${index}: bzspline smooth is a function (x, y) => Spline, such as smoothingSpline of bzspline/smoothing`,
    );
  }
  return { alpha, through: !!o.through, smooth: o.smooth };
}

/**
 * The pieces, flat as `splinePieces` gives them, of the spline `smooth`
 * fits to (u, v); null where it throws or its knots are not the points'.
 */
function fitted(smooth, u, v) {
  let s;
  try {
    s = smooth(u, v);
    const segs = s.segments;
    if (segs.length !== u.length - 1) return null;
    const p = new Float64Array(2 + 6 * segs.length);
    p.set(segs[0][0], 0);
    segs.forEach((seg, k) => p.set([...seg[1], ...seg[2], ...seg[3]], 2 + 6 * k));
    return p;
  } catch {
    return null;
  } finally {
    if (s && typeof s.free === "function") s.free();
  }
}

/** 1 when the values rise strictly, -1 when they fall strictly, 0 otherwise. */
function direction(u) {
  if (u.length < 2) return 0;
  const s = Math.sign(u[1] - u[0]);
  if (s === 0 || Number.isNaN(s)) return 0;
  for (let i = 1; i < u.length; i++) if (!(Math.sign(u[i] - u[i - 1]) === s)) return 0;
  return s;
}

/** The runs of point indices drawn as one piece of line: split at gaps unless spanned. */
function runs(points, spanGaps) {
  const out = [];
  let run = [];
  for (let i = 0; i < points.length; i++) {
    if (points[i].skip) {
      if (!spanGaps && run.length) {
        out.push(run);
        run = [];
      }
      continue;
    }
    run.push(i);
  }
  if (run.length) out.push(run);
  return out;
}

/**
 * The pieces of one run in pixels, as in `splinePieces`: `[u0, v0, (u1, v1,
 * u2, v2, u3, v3)...]` with u the index axis, in the order of the points;
 * null where the method cannot take the run or a value is not finite.
 */
function pieces(points, run, swap, o) {
  const n = run.length;
  const u = new Float64Array(n);
  const v = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    const p = points[run[k]];
    u[k] = swap ? p.y : p.x;
    v[k] = swap ? p.x : p.y;
  }
  const dir = direction(u);
  if (dir === 0) return null;
  // The method's spline, or the fit `smooth` gives, through rising u.
  const spline = (u, v) => (o.smooth ? fitted(o.smooth, u, v) : splinePieces(u, v, o.alpha, o.through));
  let p;
  if (n === 2) {
    const [du, dv] = [u[1] - u[0], v[1] - v[0]];
    p = Float64Array.of(u[0], v[0], u[0] + du / 3, v[0] + dv / 3, u[0] + (2 * du) / 3, v[0] + (2 * dv) / 3, u[1], v[1]);
  } else if (dir === 1) {
    p = spline(u, v);
  } else {
    const r = spline(u.reverse(), v.reverse());
    if (!r) return null;
    // The same pieces, each written from its other end.
    p = new Float64Array(r.length);
    if (r.length) {
      p[0] = r[r.length - 2];
      p[1] = r[r.length - 1];
    }
    for (let i = r.length - 6, j = 2; i >= 2; i -= 6, j += 6) {
      p.set([r[i + 2], r[i + 3], r[i], r[i + 1], r[i - 2], r[i - 1]], j);
    }
  }
  if (!p || p.length !== 2 + 6 * (n - 1)) return null;
  if (p.length !== 2 + 6 * (n - 1)) return null;
  for (let i = 0; i < p.length; i++) if (!Number.isFinite(p[i])) return null;
  return p;
}

/**
 * What the line element `line` draws, from the method: the pieces of each
 * run, and for each point index its run and place in it; null where Chart.js
 * must draw the line itself (a loop, a stepped line, index values that do
 * not run one way, a piece that is not finite).
 */
function build(line, indexAxis) {
  const o = line._bzspline;
  const opts = line.options || {};
  const points = line.points || [];
  if (!o || line._loop || opts.stepped) return null;
  const swap = indexAxis === "y";
  const all = [];
  // For each point index: its run in `all` and its place in the run.
  const runOf = new Int32Array(points.length).fill(-1);
  const place = new Int32Array(points.length);
  for (const run of runs(points, opts.spanGaps)) {
    if (run.length < 2) continue;
    const p = pieces(points, run, swap, o);
    if (!p) return null;
    for (let k = 0; k < run.length; k++) {
      runOf[run[k]] = all.length;
      place[run[k]] = k;
    }
    all.push(p);
  }
  return { swap, pieces: all, runOf, place };
}

/** The drawing of `line`, built for its current pixels when needed. */
function drawn(line, indexAxis) {
  if (!line._bzspline) return null;
  if (!line._pointsUpdated || !line._bzsplineDrawn || line._bzsplineAxis !== indexAxis) {
    // Where the method cannot take the line, Chart.js's own control points
    // are still to be computed: the line stays not updated.
    line._bzsplineDrawn = build(line, indexAxis);
    line._bzsplineAxis = indexAxis;
    if (line._bzsplineDrawn) line._pointsUpdated = true;
  }
  return line._bzsplineDrawn;
}

/** What `line` draws for its current pixels, or null where Chart.js draws it. */
function placed(line) {
  return line._bzspline && line._pointsUpdated ? line._bzsplineDrawn : null;
}

/** Sets the stroke style of a line segment as Chart.js does. */
function setStyle(ctx, options, style = options) {
  const or = (v, d) => (v === undefined ? d : v);
  ctx.lineCap = or(style.borderCapStyle, options.borderCapStyle);
  ctx.setLineDash(or(style.borderDash, options.borderDash));
  ctx.lineDashOffset = or(style.borderDashOffset, options.borderDashOffset);
  ctx.lineJoin = or(style.borderJoinStyle, options.borderJoinStyle);
  ctx.lineWidth = or(style.borderWidth, options.borderWidth);
  ctx.strokeStyle = or(style.borderColor, options.borderColor);
}

/**
 * The line element's methods that draw and interpolate it, for a line the
 * plugin draws; each defers to Chart.js's own where the method cannot take
 * the line. Their contracts are those of Chart.js's `LineElement`.
 */
const methods = {
  updateControlPoints(chartArea, indexAxis) {
    if (drawn(this, indexAxis)) return;
    this._bzsplineOwn.updateControlPoints.call(this, chartArea, indexAxis);
  },

  pathSegment(ctx, segment, params = {}) {
    const d = placed(this);
    if (!d || segment.loop) return this._bzsplineOwn.pathSegment.call(this, ctx, segment, params);
    const points = this.points;
    const { runOf, place, swap } = d;
    const start = Math.max(params.start ?? 0, segment.start);
    const end = Math.min(params.end ?? points.length - 1, segment.end);
    const reverse = !!params.reverse;
    let move = params.move ?? true;
    let prev = -1;
    for (let k = 0; k <= end - start; k++) {
      const i = reverse ? end - k : start + k;
      if (points[i].skip) continue;
      const r = runOf[i];
      const p = r < 0 ? null : d.pieces[r];
      // The point's knot on the curve (the point itself outside a run).
      const j = p ? 6 * place[i] : 0;
      const [x, y] = !p ? [points[i].x, points[i].y] : swap ? [p[j + 1], p[j]] : [p[j], p[j + 1]];
      if (move) {
        ctx.moveTo(x, y);
        move = false;
      } else if (p && prev >= 0 && runOf[prev] === r && Math.abs(place[prev] - place[i]) === 1) {
        // The piece between the two, from its first or its last end.
        const c = 6 * Math.min(place[prev], place[i]) + 2;
        const [a, b] = reverse ? [c + 2, c] : [c, c + 2];
        if (swap) ctx.bezierCurveTo(p[a + 1], p[a], p[b + 1], p[b], x, y);
        else ctx.bezierCurveTo(p[a], p[a + 1], p[b], p[b + 1], x, y);
      } else {
        ctx.lineTo(x, y);
      }
      prev = i;
    }
    return false;
  },

  path(ctx, start, count) {
    if (!placed(this)) {
      return this._bzsplineOwn.path.call(this, ctx, start, count);
    }
    start = start || 0;
    count = count || this.points.length - start;
    for (const segment of this.segments) this.pathSegment(ctx, segment, { start, end: start + count - 1 });
    return false;
  },

  interpolate(point, property) {
    const d = placed(this);
    const axis = d && (d.swap ? "y" : "x");
    if (!d || property !== axis) return this._bzsplineOwn.interpolate.call(this, point, property);
    const v = valueAt(d, point[property]);
    if (v === null) return undefined;
    return d.swap ? { x: v, y: point[property] } : { x: point[property], y: v };
  },

  draw(ctx, chartArea, start, count) {
    if (!placed(this)) {
      return this._bzsplineOwn.draw.call(this, ctx, chartArea, start, count);
    }
    const options = this.options || {};
    const points = this.points || [];
    if (points.length && options.borderWidth) {
      start = start || 0;
      count = count || points.length - start;
      ctx.save();
      for (const segment of this.segments) {
        setStyle(ctx, options, segment.style);
        ctx.beginPath();
        this.pathSegment(ctx, segment, { start, end: start + count - 1 });
        ctx.stroke();
      }
      ctx.restore();
    }
    if (this.animated) {
      // As Chart.js: an animated line is rebuilt for every frame's pixels.
      this._pointsUpdated = false;
      this._path = undefined;
    }
  },
};

/** Gives a line element the plugin's methods (once). */
function adopt(line) {
  if (line._bzsplineOwn) return;
  const own = {};
  for (const name of Object.keys(methods)) {
    own[name] = line[name];
    line[name] = methods[name];
  }
  line._bzsplineOwn = own;
}

/** The plugin: `Chart.register(bzsplinePlugin)`. */
export const bzsplinePlugin = {
  id: "bzspline",
  beforeUpdate(chart) {
    // Options are checked before Chart.js builds anything, so a bad one
    // throws from `new Chart` or `update`, not while drawing.
    chart.data.datasets.forEach((dataset, i) => settings(dataset, i));
  },
  afterDatasetUpdate(chart, args) {
    const line = args.meta && args.meta.dataset;
    if (!line || typeof line.updateControlPoints !== "function") return;
    const o = settings(chart.data.datasets[args.index] || {}, args.index);
    line._bzspline = o;
    line._pointsUpdated = false;
    line._path = undefined;
    if (o) adopt(line);
  },
};

/** The value of a cubic Bezier piece's coordinate at t. */
function bezier(a, b, c, d, t) {
  const s = 1 - t;
  return s * s * s * a + 3 * s * s * t * b + 3 * s * t * t * c + t * t * t * d;
}

/** The value on the drawn curve at `u` on the index axis, in pixels; null where none. */
function valueAt(d, u) {
  if (!Number.isFinite(u)) return null;
  for (const p of d.pieces) {
    const m = (p.length - 2) / 6;
    const rising = p[6 * m] > p[0];
    const ahead = (k) => (rising ? p[6 * k] <= u : p[6 * k] >= u);
    if (!ahead(0) || !(rising ? u <= p[6 * m] : u >= p[6 * m])) continue;
    // The last knot at or before u, by bisection on the knots.
    let [lo, hi] = [0, m];
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (ahead(mid)) lo = mid;
      else hi = mid;
    }
    const i = 6 * lo + 2;
    const [u0, u3] = [p[i - 2], p[i + 4]];
    // u(t) is monotone on the piece: bisect to the last bit.
    let [a, b] = rising ? [0, 1] : [1, 0];
    for (let k = 0; k < 60; k++) {
      const mid = (a + b) / 2;
      if (bezier(u0, p[i], p[i + 2], u3, mid) < u) a = mid;
      else b = mid;
    }
    return bezier(p[i - 1], p[i + 1], p[i + 3], p[i + 5], (a + b) / 2);
  }
  return null;
}

/**
 * The value on the drawn curve of dataset `datasetIndex` at `pixel` on the
 * index axis (the pointer's x for a vertical line chart), in the value
 * scale's units; null where the dataset is not drawn by the plugin or has
 * no curve at that pixel (outside its points, in a gap).
 */
export function curveValue(chart, datasetIndex, pixel) {
  const meta = chart.getDatasetMeta(datasetIndex);
  const line = meta && meta.dataset;
  if (!line || !line._bzspline) return null;
  const d = drawn(line, meta.iScale && meta.iScale.axis);
  const v = d ? valueAt(d, pixel) : null;
  return v === null ? null : meta.vScale.getValueForPixel(v);
}

export default bzsplinePlugin;
