// Types of the `bzspline/geo` entry.

export interface SmoothOptions {
  /** Largest distance between the curve and the output polyline (default 1e-4 of the extent's diagonal):
   * a number in the data's units, or a distance with a unit, "50m", "2km", "0.001deg". */
  tolerance?: number | string;
  /** Keep positions where the line turns by more than this many degrees. */
  keepAngle?: number;
  /** Join positions (and positions to edges) closer than this first. */
  snap?: number | string;
  /** Every feature's geometry on its own (each stays valid), not the document as one coverage. */
  independent?: boolean;
  /** Pass through every position. */
  through?: boolean;
  /** The shape parameter in [1/3, 2/3] (a third is `1/3`). */
  alpha?: number;
  param?: "centripetal" | "chordal" | "uniform";
  /** The one TopoJSON object to return as GeoJSON. */
  object?: string;
  /** The kind returned (default: the kind that went in). */
  output?: "geojson" | "topojson";
  /** The object a GeoJSON input becomes in TopoJSON output (default "collection"). */
  name?: string;
}

/** Smooths a GeoJSON object or TopoJSON Topology as `bzspline smooth` does. */
export function smooth<T extends object>(doc: T, options?: SmoothOptions): object;
export function smooth(doc: string, options?: SmoothOptions): string;
