// bzspline: the third-degree Bezier-type spline of Stelia, Potapenko and
// Sirenko for JavaScript. `Spline` (y = S(x)) and `Curve` (open or closed,
// in the plane or in space) from the WebAssembly core, and the d3 curves
// curveBzsplineX, curveBzsplineY, curveBzspline and curveBzsplineClosed.
// The module loads its WebAssembly itself (a top-level await): importing it
// is all a page or a Node program does.
import init, {
  initSync,
  Spline,
  Curve,
  splinePieces,
  curvePieces,
  checkAlpha,
  checkParam,
  memoryBytes,
} from "../wasm/core.js";
import { curves } from "./curves.js";
import { load } from "./load.js";
import { shape } from "./objects.js";

await load(init, initSync, new URL("../wasm/core_bg.wasm", import.meta.url));
shape(Spline, Curve);

export { Spline, Curve, memoryBytes };
export const { curveBzsplineX, curveBzsplineY, curveBzspline, curveBzsplineClosed } = curves({
  splinePieces,
  curvePieces,
  checkAlpha,
  checkParam,
});
