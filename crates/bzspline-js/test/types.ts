// Compiled by `tsc --noEmit` (scripts/ci.sh): the package's declarations
// accept what the README shows and refuse what they should.
import { line, area } from "d3-shape";
import { Spline, Curve, curveBzsplineX, curveBzspline, curveBzsplineClosed, type Extremum } from "../js/index.js";
import { smooth } from "../js/geo.js";
import { smoothingSpline, smoothingCurve } from "../js/smoothing.js";

const s = new Spline([0, 1, 2], Float64Array.of(0, 1, 0), { alpha: 1 / 3, extrapolate: "clamp" });
const v: number = s.at(0.5);
const vs: Float64Array = s.at([0.5, 1.5]);
const e: Extremum[] = s.extrema();
const d1: number = s.derivative().at(1);
const segs: [number, number][][] = s.segments;
const sm = smoothingSpline([0, 1, 2, 3], [0, 1, 0, 1], { w: [1, 1, 0, 1] });
const lam: number = sm.lam;
const sv: number = sm.at(1.5);
smoothingSpline([0, 1, 2], [0, 1, 0], { lam: 0.5, alpha: 1 / 3 });
// @ts-expect-error: lam is a number (or omitted for cross-validation)
smoothingSpline([0, 1, 2], [0, 1, 0], { lam: "auto" });
const seOne: number = sm.se(1);
const seMany: Float64Array = sm.se([0.5, 1]);
const bandMany: Float64Array = sm.band([0.5, 1], 0.9).lo;
const bandOne: number = sm.band(1).hi;
void [seOne, seMany, bandMany, bandOne];
const weights: Float64Array | null = smoothingSpline([0, 1, 2, 3, 4], [0, 1, 9, 1, 0], { robust: true }).robustness;
const cw: Float64Array | null = smoothingCurve([[0, 0], [1, 1], [2, 0], [3, 1], [4, 0]], { robust: true }).robustness;
const sc: number = smoothingCurve([[0, 0], [1, 1], [2, 0]], { param: [0, 1, 2], lam: 1 }).dof;
// @ts-expect-error: a plain spline reports no fit
new Spline([0, 1], [0, 1]).lam;
const c = new Curve([[0, 0], [1, 0], [1, 1]], { closed: true, param: "chordal" });
const p: Float64Array = c.at(0.25);
const near: number = c.nearest([2, 2]).distance;
const path: string | null = line().curve(curveBzsplineX.alpha(0.4).through(true))([[0, 0], [1, 1]]);
const outline: string | null = area().curve(curveBzspline.param("uniform"))([[0, 0], [1, 1]]);
line().curve(curveBzsplineClosed);
const out: string = smooth("{}", { tolerance: 1, keepAngle: 60, output: "topojson" });
const obj: object = smooth({ type: "FeatureCollection", features: [] }, { independent: true });
// @ts-expect-error: alpha is a number, not a boolean
new Spline([0, 1], [0, 1], { alpha: true });
// @ts-expect-error: alpha is a number, not text (a third is 1 / 3)
new Spline([0, 1], [0, 1], { alpha: "1/3" });
// @ts-expect-error: the chart curve has no parametrisation
curveBzsplineX.param("uniform");
// @ts-expect-error: an unknown parametrisation
curveBzspline.param("spiral");
s.free();
c.free();
export { lam, sv, sc, v, vs, e, d1, segs, p, near, path, outline, out, obj };
// The Chart.js plugin: registered once, chosen per dataset.
import { Chart, type ChartConfiguration } from "chart.js";
import { bzsplinePlugin, curveValue } from "../js/chartjs.js";
Chart.register(bzsplinePlugin);
const lineConfig: ChartConfiguration<"line"> = {
  type: "line",
  data: { labels: ["a", "b", "c"], datasets: [{ data: [1, 3, 2], bzspline: { alpha: 0.4, through: true } }] },
};
const scatterConfig: ChartConfiguration<"scatter"> = {
  type: "scatter",
  data: { datasets: [{ data: [{ x: 0, y: 1 }], showLine: true, bzspline: true }] },
};
const smoothConfig: ChartConfiguration<"line"> = {
  type: "line",
  data: { labels: ["a", "b", "c"], datasets: [{ data: [1, 3, 2], bzspline: { smooth: smoothingSpline } }] },
};
const badConfig: ChartConfiguration<"line"> = {
  type: "line",
  // @ts-expect-error: alpha is a number
  data: { datasets: [{ data: [1, 2], bzspline: { alpha: "half" } }] },
};
declare const someChart: Chart;
const atPointer: number | null = curveValue(someChart, 0, 120);
// Recharts takes the d3 curve factories as `type`.
import { createElement } from "react";
import { Line as RechartsLine, Area as RechartsArea } from "recharts";
createElement(RechartsLine, { type: curveBzsplineX, dataKey: "y" });
createElement(RechartsArea, { type: curveBzsplineX.alpha(0.4).through(true), dataKey: "y" });
