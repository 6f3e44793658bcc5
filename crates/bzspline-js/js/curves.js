// The d3 curves of bzspline, following d3-shape's curve protocol
// (https://d3js.org/d3-shape/curve#custom-curves): lineStart, point,
// lineEnd, areaStart, areaEnd; moveTo, lineTo, bezierCurveTo and closePath
// on the context. Every piece is one exact cubic Bezier segment of the
// method's spline or curve, computed by the WebAssembly core. A curve never
// throws inside a d3 call: coincident consecutive points are dropped, as
// d3.curveMonotoneX does, a line whose x does not run one way is drawn by the
// planar curve, and what the method cannot draw (NaN) is drawn straight.

/** 1 when x rises strictly, -1 when it falls strictly, 0 otherwise. */
function direction(x) {
  const n = x.length;
  if (x[1] > x[0]) {
    for (let i = 2; i < n; i++) if (!(x[i] > x[i - 1])) return 0;
    return 1;
  }
  if (x[1] < x[0]) {
    for (let i = 2; i < n; i++) if (!(x[i] < x[i - 1])) return 0;
    return -1;
  }
  return 0;
}

/** Draws pieces `[x0, y0, (x1, y1, x2, y2, x3, y3)...]` after the start. */
function drawForward(c, p, swap) {
  for (let i = 2; i + 5 < p.length; i += 6) {
    if (swap) c.bezierCurveTo(p[i + 1], p[i], p[i + 3], p[i + 2], p[i + 5], p[i + 4]);
    else c.bezierCurveTo(p[i], p[i + 1], p[i + 2], p[i + 3], p[i + 4], p[i + 5]);
  }
}

/** Draws the same pieces from the last point back to the first. */
function drawBackward(c, p, swap) {
  for (let i = p.length - 6; i >= 2; i -= 6) {
    // Piece k runs P0 = (i - 2, i - 1), P1 = (i, i + 1), P2 = (i + 2, i + 3).
    if (swap) c.bezierCurveTo(p[i + 3], p[i + 2], p[i + 1], p[i], p[i - 1], p[i - 2]);
    else c.bezierCurveTo(p[i + 2], p[i + 3], p[i], p[i + 1], p[i - 2], p[i - 1]);
  }
}

function drawStraight(c, x, y, swap) {
  for (let i = 1; i < x.length; i++) swap ? c.lineTo(y[i], x[i]) : c.lineTo(x[i], y[i]);
}

function interleave(x, y) {
  const pts = new Float64Array(2 * x.length);
  for (let i = 0; i < x.length; i++) {
    pts[2 * i] = x[i];
    pts[2 * i + 1] = y[i];
  }
  return pts;
}

/** The open curves: y(x) (`kind` "x"), x(y) ("y") and planar ("curve"). */
class Open {
  constructor(context, core, o) {
    this._context = context;
    this._core = core;
    this._o = o;
  }
  areaStart() {
    this._line = 0;
  }
  areaEnd() {
    this._line = NaN;
  }
  lineStart() {
    this._x = [];
    this._y = [];
  }
  point(x, y) {
    const swap = this._o.kind === "y";
    const u = swap ? +y : +x;
    const v = swap ? +x : +y;
    const n = this._x.length;
    if (n && u === this._x[n - 1] && v === this._y[n - 1]) return;
    this._x.push(u);
    this._y.push(v);
  }
  lineEnd() {
    const x = this._x;
    const y = this._y;
    const n = x.length;
    const c = this._context;
    const swap = this._o.kind === "y";
    if (n) {
      const [s, t] = swap ? [y[0], x[0]] : [x[0], y[0]];
      this._line ? c.lineTo(s, t) : c.moveTo(s, t);
      if (n === 2) drawStraight(c, x, y, swap);
      else if (n > 2) this._draw(c, x, y, swap);
    }
    if (this._line || (this._line !== 0 && n === 1)) c.closePath();
    this._line = 1 - this._line;
    this._x = this._y = null;
  }
  _draw(c, x, y, swap) {
    const { alpha, through, param, kind } = this._o;
    const dir = kind === "curve" ? 0 : direction(x);
    let p;
    if (dir === 1) {
      p = this._core.splinePieces(x, y, alpha, through);
      if (p.length) return drawForward(c, p, swap);
    } else if (dir === -1) {
      p = this._core.splinePieces(x.slice().reverse(), y.slice().reverse(), alpha, through);
      if (p.length) return drawBackward(c, p, swap);
    }
    p = this._core.curvePieces(interleave(x, y), false, param, alpha, through);
    if (p.length) return drawForward(c, p, swap);
    drawStraight(c, x, y, swap);
  }
}

/** The closed planar curve (areaStart and areaEnd do nothing, as in d3's closed curves). */
class Closed {
  constructor(context, core, o) {
    this._context = context;
    this._core = core;
    this._o = o;
  }
  areaStart() {}
  areaEnd() {}
  lineStart() {
    this._x = [];
    this._y = [];
  }
  point(x, y) {
    Open.prototype.point.call(this, x, y);
  }
  lineEnd() {
    const x = this._x;
    const y = this._y;
    const c = this._context;
    // A ring given with its first point repeated at the end.
    if (x.length > 1 && x[0] === x[x.length - 1] && y[0] === y[y.length - 1]) {
      x.pop();
      y.pop();
    }
    const n = x.length;
    if (n) {
      let p = [];
      if (n > 2) {
        const { alpha, through, param } = this._o;
        p = this._core.curvePieces(interleave(x, y), true, param, alpha, through);
      }
      if (p.length) {
        c.moveTo(p[0], p[1]);
        drawForward(c, p, false);
      } else {
        c.moveTo(x[0], y[0]);
        drawStraight(c, x, y, false);
      }
      c.closePath();
    }
    this._x = this._y = null;
  }
}

/** A d3 curve factory with d3-style parameter methods. */
function factory(Kind, core, o) {
  const curve = (context) => new Kind(context, core, o);
  // Coerced to a number as d3's own factories do (`+a`), and checked at once
  // by the core (the range; a parametrisation by the library's parser).
  curve.alpha = (a) => factory(Kind, core, { ...o, alpha: core.checkAlpha(+a) });
  curve.through = (t = true) => factory(Kind, core, { ...o, through: !!t });
  if (o.kind === "curve") {
    curve.param = (p) => factory(Kind, core, { ...o, param: core.checkParam(String(p)) });
  }
  return curve;
}

/** The four curves, on a loaded core. */
export function curves(core) {
  const o = { alpha: 0.5, through: false, param: "centripetal" };
  return {
    curveBzsplineX: factory(Open, core, { ...o, kind: "x" }),
    curveBzsplineY: factory(Open, core, { ...o, kind: "y" }),
    curveBzspline: factory(Open, core, { ...o, kind: "curve" }),
    curveBzsplineClosed: factory(Closed, core, { ...o, kind: "curve" }),
  };
}
