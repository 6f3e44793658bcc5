// Types of the `bzspline` package (the curves entry).

/** Numbers as an Array or a typed array. */
export type Numbers = ArrayLike<number>;

/** A shape parameter in [1/3, 2/3] (a third is `1/3`). */
export type Alpha = number;

export interface SplineOptions {
  /** One shape parameter for every interval (default 0.5). */
  alpha?: Alpha;
  /** One shape parameter per interval (n - 1 of them); not with `alpha`. */
  alphas?: Numbers;
  /** Pass through every (x, y): the interpolating variant. */
  through?: boolean;
  /** Outside the knots: extend the end cubics (true, the default), NaN (false) or hold the end values. */
  extrapolate?: boolean | "clamp" | "extend" | "nan";
}

export interface Extremum {
  x: number;
  y: number;
  kind: "minimum" | "maximum" | "stationary";
}

/** A point as its coordinates. */
export type Point = [number, number];

/**
 * The third-degree Bezier-type spline y = S(x) of Stelia, Potapenko and
 * Sirenko: C1, through the first and last points, touching every leg of the
 * control polygon, within the range of y. Throws RangeError or TypeError
 * naming the index at fault.
 */
export class Spline {
  constructor(x: Numbers, y: Numbers, options?: SplineOptions);
  /** S(x) (or this derivative): a number for a number, a Float64Array for an array. */
  at(x: number): number;
  at(x: Numbers): Float64Array;
  /** The derivative of order nu (default 1) as a Spline-like object. */
  derivative(nu?: number): Spline;
  /** The integral of S from a to b. */
  integrate(a: number, b: number): number;
  /** The points where S' = 0 inside the domain, in increasing x. */
  extrema(): Extremum[];
  /** The graph as exact SVG path data, one C per piece. */
  svgPath(): string;
  /** Releases the WebAssembly memory now (otherwise when collected). */
  free(): void;
  readonly x: Float64Array;
  readonly knotValues: Float64Array;
  readonly controlValues: Float64Array;
  readonly alphas: Float64Array;
  readonly tangentPoints: Point[];
  /** Every piece's four Bezier control points. */
  readonly segments: [Point, Point, Point, Point][];
  /** The derivative order this object evaluates. */
  readonly nu: number;
}

export interface CurveOptions {
  /** A closed curve (the points as a ring, first not repeated). */
  closed?: boolean;
  /** How the parameters follow the points (default "centripetal"), or the parameters. */
  param?: "centripetal" | "chordal" | "uniform" | Numbers;
  alpha?: Alpha;
  alphas?: Numbers;
  /** Pass through every point. */
  through?: boolean;
}

/** A curve by the method in the plane or in space, open or closed. */
export class Curve {
  constructor(points: ArrayLike<Numbers>, options?: CurveOptions);
  /** The point (or derivative nu) at parameter t, or an array of them. */
  at(t: number, nu?: number): Float64Array;
  at(t: Numbers, nu?: number): Float64Array[];
  /** The arc length to an absolute accuracy (default 1e-9). */
  arclen(accuracy?: number): number;
  /** n points at equal arc-length steps from start to end. */
  resample(n: number, accuracy?: number): Float64Array[];
  /** The nearest point of the curve to p. */
  nearest(p: Numbers): { t: number; point: Float64Array; distance: number };
  /** The exact bounding box of the curve. */
  bbox(): { min: Float64Array; max: Float64Array };
  /** A polyline within tolerance of the curve. */
  flatten(tolerance: number): Float64Array[];
  /** Exact SVG path data of a planar curve. */
  svgPath(): string;
  free(): void;
  readonly knots: Float64Array;
  /** The shape parameters, one per leg. */
  readonly alphas: Float64Array;
  readonly dim: number;
  readonly closed: boolean;
  readonly segments: Float64Array[][];
}

/** The bytes of linear memory the WebAssembly module holds. */
export function memoryBytes(): number;

/** d3-shape's curve context (d3.path, a CanvasRenderingContext2D, ...). */
export interface CurveContext {
  moveTo(x: number, y: number): void;
  lineTo(x: number, y: number): void;
  bezierCurveTo(x1: number, y1: number, x2: number, y2: number, x: number, y: number): void;
  closePath(): void;
}

/** A d3 curve (d3-shape's CurveGenerator protocol). */
export interface CurveGenerator {
  lineStart(): void;
  lineEnd(): void;
  point(x: number, y: number): void;
  areaStart(): void;
  areaEnd(): void;
}

export interface BzsplineCurveFactory {
  (context: CurveContext): CurveGenerator;
  /** The same curve with another shape parameter, in [1/3, 2/3]. */
  alpha(alpha: Alpha): this;
  /** Through every point (the interpolating variant), or not. */
  through(through?: boolean): this;
}

export interface BzsplinePlanarCurveFactory extends BzsplineCurveFactory {
  /** The parametrisation of the planar curve. */
  param(param: "centripetal" | "chordal" | "uniform"): this;
}

/** y as a function of x: the chart curve (x strictly increasing; otherwise the planar curve). */
export const curveBzsplineX: BzsplineCurveFactory;
/** x as a function of y, for vertical charts. */
export const curveBzsplineY: BzsplineCurveFactory;
/** An open planar curve through any points. */
export const curveBzspline: BzsplinePlanarCurveFactory;
/** A closed planar curve. */
export const curveBzsplineClosed: BzsplinePlanarCurveFactory;
