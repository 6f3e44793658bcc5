// Types of the `bzspline/chartjs` entry (Chart.js 4).
import type { Chart, ChartType, Plugin } from "chart.js";
import type { Alpha, Spline } from "./index.js";

/** How a dataset is drawn by the plugin. */
export interface BzsplineDatasetOptions {
  /** The shape parameter, in [1/3, 2/3] (default 0.5). */
  alpha?: Alpha;
  /** Pass through every point: the interpolating variant. */
  through?: boolean;
  /**
   * Draw a fit of the points instead: a function of the points' pixels
   * (index axis rising, value axis) returning a `Spline` with its knots at
   * them, such as `smoothingSpline` of `bzspline/smoothing` (the weight
   * chosen by cross-validation). Where it throws, Chart.js draws the line.
   */
  smooth?: (x: Float64Array, y: Float64Array) => Spline;
}

declare module "chart.js" {
  interface LineControllerDatasetOptions {
    /** Draw this dataset with bzspline's curve: `true` or its options. */
    bzspline?: boolean | BzsplineDatasetOptions;
  }
}

/**
 * The plugin: `Chart.register(bzsplinePlugin)`, then `bzspline: true` (or
 * `{ alpha, through }`) on a line dataset. A dataset the method cannot take
 * (index values not running one way, a stepped or looped line) is drawn as
 * Chart.js draws it. A bad option throws from `new Chart` or `update`, naming
 * the dataset.
 */
export declare const bzsplinePlugin: Plugin<ChartType>;
export default bzsplinePlugin;

/**
 * The value, in the value scale's units, on the drawn curve of dataset
 * `datasetIndex` at `pixel` on the index axis (the pointer's x); null where
 * the plugin does not draw the dataset or its curve has no point there.
 */
export declare function curveValue(chart: Chart, datasetIndex: number, pixel: number): number | null;
