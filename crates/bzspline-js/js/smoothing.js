// bzspline/smoothing: smoothing splines and curves of noisy data, a module of
// its own so that a page drawing curves does not load the fit. The fit (a
// WebAssembly module of its own) gives the control values (points) and the
// knots; the result is the core's `Spline` (`Curve`) built on them, which is
// the fit bit for bit (a smoothing spline is the method's spline of its
// control values), with the fit's `lam`, `gcv`, `dof` and `robustness` as
// properties, and
// a spline's standard error `se(x)` and confidence band `band(x, level)`.
import { Spline, Curve } from "./index.js";
import init, { initSync, splineFit, curveFit } from "../wasm/smoothing.js";
import { load } from "./load.js";

await load(init, initSync, new URL("../wasm/smoothing_bg.wasm", import.meta.url));

function report(object, fit) {
  return Object.defineProperties(object, {
    lam: { value: fit.lam, enumerable: true },
    gcv: { value: fit.gcv, enumerable: true },
    dof: { value: fit.dof, enumerable: true },
    robustness: { value: fit.robustness, enumerable: true },
  });
}

/**
 * The smoothing spline of noisy data in the method's basis (knots at x), as
 * scipy's make_smoothing_spline: options w, lam (omitted or null: chosen by
 * generalized cross-validation), alpha, alphas, extrapolate, robust.
 */
export function smoothingSpline(x, y, options) {
  const fit = splineFit(x, y, options);
  const o = options ?? {};
  const s = report(
    new Spline(fit.x, fit.controls, { alpha: o.alpha, alphas: o.alphas, extrapolate: o.extrapolate }),
    fit,
  );
  const posterior = fit.posterior;
  return Object.defineProperties(s, {
    // The fit's standard error at x (a number, or a Float64Array for an array).
    se: {
      value(at) {
        const one = typeof at === "number";
        const out = posterior.se(one ? [at] : at);
        return one ? out[0] : out;
      },
    },
    // The confidence band at x: { lo, hi }, numbers or Float64Arrays.
    band: {
      value(at, level = 0.95) {
        const one = typeof at === "number";
        const xs = Float64Array.from(one ? [at] : at);
        const both = posterior.band(s.at(xs), xs, level);
        const n = xs.length;
        return one ? { lo: both[0], hi: both[1] } : { lo: both.subarray(0, n), hi: both.subarray(n) };
      },
    },
  });
}

/**
 * The smoothing curve of noisy points (open, or closed round its loop; one lam
 * for every coordinate) on the parameters of the points: options w, lam,
 * param, alpha, alphas, robust, closed.
 */
export function smoothingCurve(points, options) {
  const fit = curveFit(points, options);
  const rows = [];
  for (let i = 0; i < fit.points.length; i += fit.dim) rows.push(fit.points.subarray(i, i + fit.dim));
  return report(new Curve(rows, { param: fit.knots, alphas: fit.alphas, closed: fit.closed }), fit);
}
