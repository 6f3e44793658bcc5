// Run in a fresh folder where the packed package is installed: the four
// entries load, a d3 line draws, a spline answers, noisy data smooth, a map
// smooths.
import assert from "node:assert/strict";
import { line } from "d3-shape";
import { Spline, curveBzsplineX } from "bzspline";
import { smooth } from "bzspline/geo";
import { smoothingSpline } from "bzspline/smoothing";
import { bzsplinePlugin, curveValue } from "bzspline/chartjs";

const d = line().curve(curveBzsplineX)([[0, 0], [1, 2], [2, 1], [3, 3]]);
assert.match(d, /^M0,0C/);
assert.equal(new Spline([1, 2, 3, 4], [1, 3, 3, 1]).at(2.5), 3);
const fit = smoothingSpline([0, 1, 2, 3, 4], [0, 1, 0, 1, 0], { lam: 1e9 });
assert.ok(fit instanceof Spline && fit.dof < 2.01 && Math.abs(fit.at(2) - 0.4) < 1e-3);
const square = { type: "Polygon", coordinates: [[[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]] };
const out = smooth({ type: "Feature", properties: {}, geometry: square });
assert.equal(out.geometry.type, "Polygon");
assert.ok(out.geometry.coordinates[0].length > 5);
assert.equal(bzsplinePlugin.id, "bzspline");
assert.equal(typeof curveValue, "function");
console.log("smoke: ok");
