// Types of the `bzspline/smoothing` entry.
import type { Alpha, Curve, Numbers, Spline } from "./index.js";

/** What a smoothing fit reports. */
export interface Fit {
  /** The roughness penalty's weight used (the one chosen when none was given). */
  readonly lam: number;
  /** The fit's generalized cross-validation score. */
  readonly gcv: number;
  /** The fit's effective degrees of freedom (2 for a line, n through every point). */
  readonly dof: number;
  /**
   * A robust fit's weight of each point, in [0, 1] (0 for a point judged an
   * outlier); null for a plain fit.
   */
  readonly robustness: Float64Array | null;
}

export interface SmoothingOptions {
  /** One weight per point, finite and >= 0 (default 1); a point of weight 0 does not move the fit. */
  w?: Numbers | null;
  /** The roughness penalty's weight, >= 0; omitted or null: chosen by generalized cross-validation. */
  lam?: number | null;
  /** One shape parameter for every interval (default 0.5). */
  alpha?: Alpha;
  /** One shape parameter per interval (n - 1 of them); not with `alpha`. */
  alphas?: Numbers;
  /** Outside the knots, as for `new Spline`. */
  extrapolate?: boolean | "clamp" | "extend" | "nan";
  /**
   * Robust against outliers: the fit weighted again by its residuals (Tukey's
   * biweight on six median absolute residuals, as lowess does), lam chosen
   * again each time; needs 5 points of positive weight.
   */
  robust?: boolean;
}

export interface CurveSmoothingOptions {
  /** One weight per point, finite and >= 0 (default 1). */
  w?: Numbers | null;
  /** The roughness penalty's weight, >= 0; omitted or null: chosen by generalized cross-validation. */
  lam?: number | null;
  /** How the parameters follow the points (default "centripetal"), or the parameters (a track's times). */
  param?: "centripetal" | "chordal" | "uniform" | Numbers;
  /** One shape parameter for every leg (default 0.5). */
  alpha?: Alpha;
  /** One shape parameter per leg. */
  alphas?: Numbers;
  /**
   * Robust against outliers: the fit weighted again by its residuals (Tukey's
   * biweight on six median absolute residuals, as lowess does), the residual a
   * point's distance from the fit, lam chosen again each time; needs 5 points of positive weight.
   */
  robust?: boolean;
  /** A closed curve (a contour, a lap), smoothed round its loop; a given `param` then has n + 1 values. */
  closed?: boolean;
}

/**
 * The smoothing spline of noisy data in the method's basis (knots at x), as
 * scipy's make_smoothing_spline: control values minimising
 * sum w (S(x) - y)^2 + lam * integral S''^2, lam chosen by generalized
 * cross-validation when omitted. O(n). A `Spline` of the `bzspline` entry.
 */
export function smoothingSpline(x: Numbers, y: Numbers, options?: SmoothingOptions): Spline & Fit & Bands;

/** A smoothing spline's standard errors and confidence bands. */
export interface Bands {
  /**
   * The standard error of the fit at x (within the knots): the Bayesian
   * posterior of the penalised fit, noise variance RSS / (n - dof). Throws a
   * RangeError for a fit through every point (lam 0) or x outside the knots.
   */
  se(x: number): number;
  se(x: Numbers): Float64Array;
  /** The pointwise confidence band at `level` (default 0.95): S(x) -+ z se(x). */
  band(x: number, level?: number): { lo: number; hi: number };
  band(x: Numbers, level?: number): { lo: Float64Array; hi: Float64Array };
}

/**
 * The smoothing curve of noisy points (open, one lam for every coordinate),
 * on the parameters of the points. A `Curve` of the `bzspline` entry.
 */
export function smoothingCurve(points: ArrayLike<Numbers>, options?: CurveSmoothingOptions): Curve & Fit;
