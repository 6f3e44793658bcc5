// A d3 path context that records its calls exactly (no rounding), for
// comparing what a curve draws with the spline's own pieces.
export class Recorder {
  constructor() {
    this.calls = [];
  }
  moveTo(x, y) {
    this.calls.push(["M", x, y]);
  }
  lineTo(x, y) {
    this.calls.push(["L", x, y]);
  }
  bezierCurveTo(x1, y1, x2, y2, x, y) {
    this.calls.push(["C", x1, y1, x2, y2, x, y]);
  }
  closePath() {
    this.calls.push(["Z"]);
  }
}

/** What `shape` (a d3 line or area with a context) draws on `data`. */
export function record(shape, data) {
  const r = new Recorder();
  shape.context(r)(data);
  return r.calls;
}

/** A deterministic generator of numbers in [0, 1). */
export function random(seed) {
  let s = seed >>> 0;
  return () => {
    s = (s + 0x6d2b79f5) >>> 0;
    let t = s;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** n points with increasing x and noisy y. */
export function series(n, seed) {
  const r = random(seed);
  let x = 0;
  return Array.from({ length: n }, () => {
    x += 0.1 + r();
    return [x, Math.sin(x) + r()];
  });
}

/** Asserts |a - b| <= tol * scale for numbers a and b. */
export function close(a, b, tol, what) {
  const scale = Math.max(1, Math.abs(a), Math.abs(b));
  if (!(Math.abs(a - b) <= tol * scale)) {
    throw new Error(`${what}: ${a} differs from ${b}`);
  }
}
