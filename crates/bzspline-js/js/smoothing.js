// bzspline/smoothing: smoothing splines and curves of noisy data, a module of
// its own so that a page drawing curves does not load the fit. The fit (a
// WebAssembly module of its own) gives the control values (points) and the
// knots; the result is the core's `Spline` (`Curve`) built on them, which is
// the fit bit for bit (a smoothing spline is the method's spline of its
// control values), with the fit's `lam`, `gcv` and `dof` as properties.
import { Spline, Curve } from "./index.js";
import init, { initSync, splineFit, curveFit } from "../wasm/smoothing.js";
import { load } from "./load.js";

await load(init, initSync, new URL("../wasm/smoothing_bg.wasm", import.meta.url));

function report(object, fit) {
  return Object.defineProperties(object, {
    lam: { value: fit.lam, enumerable: true },
    gcv: { value: fit.gcv, enumerable: true },
    dof: { value: fit.dof, enumerable: true },
  });
}

/**
 * The smoothing spline of noisy data in the method's basis (knots at x), as
 * scipy's make_smoothing_spline: options w, lam (omitted or null: chosen by
 * generalized cross-validation), alpha, alphas, extrapolate.
 */
export function smoothingSpline(x, y, options) {
  const fit = splineFit(x, y, options);
  const o = options ?? {};
  return report(
    new Spline(fit.x, fit.controls, { alpha: o.alpha, alphas: o.alphas, extrapolate: o.extrapolate }),
    fit,
  );
}

/**
 * The smoothing curve of noisy points (open, one lam for every coordinate)
 * on the parameters of the points: options w, lam, param, alpha, alphas.
 */
export function smoothingCurve(points, options) {
  const fit = curveFit(points, options);
  const rows = [];
  for (let i = 0; i < fit.points.length; i += fit.dim) rows.push(fit.points.subarray(i, i + fit.dim));
  return report(new Curve(rows, { param: fit.knots, alphas: fit.alphas }), fit);
}
