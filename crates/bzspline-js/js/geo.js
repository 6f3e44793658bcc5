// bzspline/geo: map smoothing, a module of its own so that a page drawing
// curves does not load it. `smooth(doc, options)` takes a GeoJSON object or a
// TopoJSON Topology (or their JSON text) and returns the same kind, computed
// by the code of `bzspline smooth`: shared borders smoothed once, valid
// polygons kept valid.
import init, { initSync, smoothText } from "../wasm/geo.js";
import { load } from "./load.js";

await load(init, initSync, new URL("../wasm/geo_bg.wasm", import.meta.url));

/**
 * Smooths a GeoJSON object or TopoJSON Topology; a string in, a string out.
 * Options: tolerance, keepAngle, snap, independent, through, alpha, param,
 * object (the TopoJSON object to return as GeoJSON), output ("geojson" or
 * "topojson"; by default the kind that went in), name (the object a GeoJSON
 * input becomes in TopoJSON output; "collection" by default).
 */
export function smooth(doc, options = {}) {
  if (doc === null || (typeof doc !== "object" && typeof doc !== "string")) {
    throw new TypeError("smooth takes a GeoJSON object, a TopoJSON Topology or their JSON text");
  }
  const text = typeof doc === "string" ? doc : JSON.stringify(doc);
  const out = smoothText(text, options);
  return typeof doc === "string" ? out : JSON.parse(out);
}
