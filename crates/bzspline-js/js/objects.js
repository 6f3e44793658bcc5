// The arrays of points that Spline and Curve return, shaped here from the
// flat numbers the WebAssembly core gives (one copy out of the module):
// JavaScript makes many small arrays far faster than the module can by
// calling into JavaScript for each. A curve's points are Float64Array views
// of one buffer, d numbers each; a spline's are [x, y] pairs.

/** Views of `flat`, `d` numbers each. */
function rows(flat, d) {
  const out = new Array(flat.length / d);
  for (let i = 0, j = 0; i < out.length; i++, j += d) out[i] = flat.subarray(j, j + d);
  return out;
}

/** `[x, y]` pairs of `flat`, from `start` to `end`. */
function pairs(flat, start = 0, end = flat.length) {
  const out = new Array((end - start) >> 1);
  for (let i = 0, j = start; i < out.length; i++, j += 2) out[i] = [flat[j], flat[j + 1]];
  return out;
}

/** Adds the shaped methods and getters to the core's classes. */
export function shape(Spline, Curve) {
  Object.defineProperties(Spline.prototype, {
    tangentPoints: {
      get() {
        return pairs(this._tangentPoints());
      },
    },
    segments: {
      get() {
        const flat = this._segments();
        const out = new Array(flat.length >> 3);
        for (let k = 0; k < out.length; k++) out[k] = pairs(flat, 8 * k, 8 * k + 8);
        return out;
      },
    },
  });
  Object.defineProperties(Curve.prototype, {
    at: {
      value(t, nu) {
        const flat = this._at(t, nu);
        return typeof t === "number" ? flat : rows(flat, this.dim);
      },
    },
    resample: {
      value(n, accuracy) {
        return rows(this._resample(n, accuracy), this.dim);
      },
    },
    flatten: {
      value(tolerance) {
        return rows(this._flatten(tolerance), this.dim);
      },
    },
    segments: {
      get() {
        const d = this.dim;
        const flat = this._segments();
        const out = new Array(flat.length / (4 * d));
        for (let k = 0; k < out.length; k++) out[k] = rows(flat.subarray(4 * d * k, 4 * d * (k + 1)), d);
        return out;
      },
    },
  });
}
