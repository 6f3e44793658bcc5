//! GeoJSON geometries (as JSON values) to and from geozero's geometry
//! processors: the geometry half of the GeoPackage, FlatGeobuf and GeoParquet readers
//! and writers. [`ToJson`] builds a geometry from what a reader emits;
//! [`emit`] feeds a geometry to a writer. Positions keep z; M is dropped.

use geozero::error::{GeozeroError, Result};
use geozero::GeomProcessor;
use serde_json::{json, Value};

use crate::features::{has_z, Source};

/// Geometries nested deeper than this (collections in collections) are
/// refused, so that no input can exhaust the stack.
const MAX_DEPTH: usize = 32;

/// Positions reserved up front at most, whatever count a file declares.
const MAX_RESERVE: usize = 1 << 12;

/// One geometry (or part of one) being built.
struct Frame {
    kind: &'static str,
    /// A geometry of its own (`true`), or the coordinates of a member of a
    /// multi-geometry.
    tagged: bool,
    items: Vec<Value>,
}

/// A geometry processor that builds the GeoJSON geometry it is given.
#[derive(Default)]
pub struct ToJson {
    /// Whether to keep z.
    z: bool,
    /// Whether a position without z gets z = 0 (a format whose positions
    /// have z for all or none).
    fill_z: bool,
    stack: Vec<Frame>,
    done: Option<Value>,
}

impl ToJson {
    /// A builder keeping z (`z`) or only x and y.
    #[must_use]
    pub fn new(z: bool) -> Self {
        ToJson {
            z,
            ..ToJson::default()
        }
    }

    /// A builder giving every position z: its own, else 0.
    #[must_use]
    pub fn with_z_everywhere() -> Self {
        ToJson {
            z: true,
            fill_z: true,
            ..ToJson::default()
        }
    }

    /// The geometry built (`null` for an empty point or nothing).
    #[must_use]
    pub fn finish(self) -> Value {
        self.done.unwrap_or(Value::Null)
    }

    fn begin(&mut self, kind: &'static str, tagged: bool, size: usize) -> Result<()> {
        if self.stack.len() >= MAX_DEPTH {
            return Err(GeozeroError::Geometry(format!(
                "geometries nested more than {MAX_DEPTH} deep"
            )));
        }
        self.stack.push(Frame {
            kind,
            tagged,
            items: Vec::with_capacity(size.min(MAX_RESERVE)),
        });
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        let Some(frame) = self.stack.pop() else {
            return Err(GeozeroError::GeometryFormat);
        };
        let value = if frame.kind == "GeometryCollection" {
            json!({"type": frame.kind, "geometries": frame.items})
        } else if frame.kind == "Point" {
            match frame.items.into_iter().next() {
                Some(p) => json!({"type": "Point", "coordinates": p}),
                None => Value::Null,
            }
        } else if frame.tagged {
            json!({"type": frame.kind, "coordinates": frame.items})
        } else {
            Value::Array(frame.items)
        };
        self.put(value);
        Ok(())
    }

    fn put(&mut self, value: Value) {
        match self.stack.last_mut() {
            Some(parent) => {
                if !value.is_null() {
                    parent.items.push(value);
                }
            }
            None => self.done = Some(value),
        }
    }

    fn position(&mut self, x: f64, y: f64, z: Option<f64>) -> Result<()> {
        for c in [Some(x), Some(y), z].into_iter().flatten() {
            if !c.is_finite() {
                return Err(GeozeroError::Geometry(format!(
                    "a coordinate is {c}, not a finite number"
                )));
            }
        }
        let p = match z {
            Some(z) if self.z => json!([x, y, z]),
            None if self.fill_z => json!([x, y, 0.0]),
            _ => json!([x, y]),
        };
        match self.stack.last_mut() {
            Some(frame) => {
                frame.items.push(p);
                Ok(())
            }
            None => Err(GeozeroError::GeometryFormat),
        }
    }

    fn curved<T>() -> Result<T> {
        Err(GeozeroError::Geometry(
            "curved and surface geometries (arcs, TINs, polyhedral surfaces) are not supported"
                .into(),
        ))
    }
}

impl GeomProcessor for ToJson {
    fn dimensions(&self) -> geozero::CoordDimensions {
        if self.z {
            geozero::CoordDimensions::xyz()
        } else {
            geozero::CoordDimensions::xy()
        }
    }
    fn multi_dim(&self) -> bool {
        self.z
    }
    fn xy(&mut self, x: f64, y: f64, _idx: usize) -> Result<()> {
        self.position(x, y, None)
    }
    fn coordinate(
        &mut self,
        x: f64,
        y: f64,
        z: Option<f64>,
        _m: Option<f64>,
        _t: Option<f64>,
        _tm: Option<u64>,
        _idx: usize,
    ) -> Result<()> {
        self.position(x, y, z)
    }
    fn empty_point(&mut self, _idx: usize) -> Result<()> {
        self.put(Value::Null);
        Ok(())
    }
    fn point_begin(&mut self, _idx: usize) -> Result<()> {
        self.begin("Point", true, 1)
    }
    fn point_end(&mut self, _idx: usize) -> Result<()> {
        self.end()
    }
    fn multipoint_begin(&mut self, size: usize, _idx: usize) -> Result<()> {
        self.begin("MultiPoint", true, size)
    }
    fn multipoint_end(&mut self, _idx: usize) -> Result<()> {
        self.end()
    }
    fn linestring_begin(&mut self, tagged: bool, size: usize, _idx: usize) -> Result<()> {
        self.begin("LineString", tagged, size)
    }
    fn linestring_end(&mut self, _tagged: bool, _idx: usize) -> Result<()> {
        self.end()
    }
    fn multilinestring_begin(&mut self, size: usize, _idx: usize) -> Result<()> {
        self.begin("MultiLineString", true, size)
    }
    fn multilinestring_end(&mut self, _idx: usize) -> Result<()> {
        self.end()
    }
    fn polygon_begin(&mut self, tagged: bool, size: usize, _idx: usize) -> Result<()> {
        self.begin("Polygon", tagged, size)
    }
    fn polygon_end(&mut self, _tagged: bool, _idx: usize) -> Result<()> {
        self.end()
    }
    fn multipolygon_begin(&mut self, size: usize, _idx: usize) -> Result<()> {
        self.begin("MultiPolygon", true, size)
    }
    fn multipolygon_end(&mut self, _idx: usize) -> Result<()> {
        self.end()
    }
    fn geometrycollection_begin(&mut self, size: usize, _idx: usize) -> Result<()> {
        self.begin("GeometryCollection", true, size)
    }
    fn geometrycollection_end(&mut self, _idx: usize) -> Result<()> {
        self.end()
    }
    fn circularstring_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn compoundcurve_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn curvepolygon_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn multicurve_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn multisurface_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn triangle_begin(&mut self, _tagged: bool, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn polyhedralsurface_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
    fn tin_begin(&mut self, _size: usize, _idx: usize) -> Result<()> {
        Self::curved()
    }
}

/// The one geometry type of a layer's features (`"Polygon"`), `None` when
/// their types differ or there are none; features without geometry are
/// passed over unless `null_differs`.
#[must_use]
pub fn one_type(features: &dyn Source, null_differs: bool) -> Option<&'static str> {
    let mut kind: Option<&str> = None;
    for i in 0..features.count() {
        match (kind, features.geometry_type(i)) {
            (_, None) if null_differs => return None,
            (_, None) => {}
            (None, Some(t)) => kind = Some(t),
            (Some(k), Some(t)) if k == t => {}
            _ => return None,
        }
    }
    kind
}

/// Gives every position of a geometry with z somewhere z = 0 where it has
/// none (WKB lets the members of a collection differ; GeoPackage writers,
/// ours too, write one geometry with one set of dimensions).
pub fn fill_z(g: &mut Value) {
    fn walk(c: &mut Value) {
        if let Some(a) = c.as_array_mut() {
            if a.first().is_some_and(Value::is_number) {
                if a.len() == 2 {
                    a.push(json!(0.0));
                }
            } else {
                a.iter_mut().for_each(walk);
            }
        }
    }
    fn fill(g: &mut Value) {
        if let Some(members) = g.get_mut("geometries").and_then(Value::as_array_mut) {
            members.iter_mut().for_each(fill);
        } else if let Some(c) = g.get_mut("coordinates") {
            walk(c);
        }
    }
    if has_z(g) {
        fill(g);
    }
}

/// The bounding box `[min x, max x, min y, max y]` of a geometry's
/// positions (GeoPackage's envelope order); `None` for no positions.
#[must_use]
pub fn envelope(g: &Value) -> Option<[f64; 4]> {
    fn walk(c: &Value, b: &mut Option<[f64; 4]>) {
        let Some(a) = c.as_array() else { return };
        if a.first().is_some_and(Value::is_number) {
            if let (Some(x), Some(y)) = (a[0].as_f64(), a.get(1).and_then(Value::as_f64)) {
                *b = Some(match *b {
                    None => [x, x, y, y],
                    Some([x0, x1, y0, y1]) => [x0.min(x), x1.max(x), y0.min(y), y1.max(y)],
                });
            }
        } else {
            a.iter().for_each(|m| walk(m, b));
        }
    }
    let mut b = None;
    match g.get("geometries").and_then(Value::as_array) {
        Some(members) => {
            for m in members {
                if let Some([x0, x1, y0, y1]) = envelope(m) {
                    walk(&json!([[x0, y0], [x1, y1]]), &mut b);
                }
            }
        }
        None => walk(&g["coordinates"], &mut b),
    }
    b
}

/// Feeds a GeoJSON geometry to a geozero processor (a WKB or FlatGeobuf
/// writer), z included when the processor takes it (missing z as 0).
///
/// # Errors
///
/// A geometry that is not GeoJSON, and the processor's errors.
pub fn emit<P: GeomProcessor>(g: &Value, p: &mut P) -> Result<()> {
    emit_n(g, p, 0, 0)
}

fn emit_n<P: GeomProcessor>(g: &Value, p: &mut P, idx: usize, depth: usize) -> Result<()> {
    let bad = || GeozeroError::Geometry(format!("not a GeoJSON geometry: {g}"));
    if depth > MAX_DEPTH {
        return Err(bad());
    }
    let kind = g["type"].as_str().ok_or_else(bad)?;
    if kind == "GeometryCollection" {
        let members = g["geometries"].as_array().ok_or_else(bad)?;
        p.geometrycollection_begin(members.len(), idx)?;
        for (i, m) in members.iter().enumerate() {
            emit_n(m, p, i, depth + 1)?;
        }
        return p.geometrycollection_end(idx);
    }
    let c = &g["coordinates"];
    let list = |v: &Value| v.as_array().cloned().ok_or_else(bad);
    match kind {
        "Point" => {
            p.point_begin(idx)?;
            position(c, p, 0)?;
            p.point_end(idx)
        }
        "MultiPoint" => {
            let pts = list(c)?;
            p.multipoint_begin(pts.len(), idx)?;
            for (i, q) in pts.iter().enumerate() {
                position(q, p, i)?;
            }
            p.multipoint_end(idx)
        }
        "LineString" => line(c, p, true, idx),
        "MultiLineString" => {
            let lines = list(c)?;
            p.multilinestring_begin(lines.len(), idx)?;
            for (i, l) in lines.iter().enumerate() {
                line(l, p, false, i)?;
            }
            p.multilinestring_end(idx)
        }
        "Polygon" => polygon(c, p, true, idx),
        "MultiPolygon" => {
            let polys = list(c)?;
            p.multipolygon_begin(polys.len(), idx)?;
            for (i, r) in polys.iter().enumerate() {
                polygon(r, p, false, i)?;
            }
            p.multipolygon_end(idx)
        }
        _ => Err(bad()),
    }
}

fn position<P: GeomProcessor>(c: &Value, p: &mut P, idx: usize) -> Result<()> {
    let n = |i: usize| c.get(i).and_then(Value::as_f64);
    let (Some(x), Some(y)) = (n(0), n(1)) else {
        return Err(GeozeroError::Geometry(format!("not a position: {c}")));
    };
    if p.multi_dim() {
        let z = p.dimensions().z.then(|| n(2).unwrap_or(0.0));
        p.coordinate(x, y, z, None, None, None, idx)
    } else {
        p.xy(x, y, idx)
    }
}

fn line<P: GeomProcessor>(c: &Value, p: &mut P, tagged: bool, idx: usize) -> Result<()> {
    let pts = c
        .as_array()
        .ok_or_else(|| GeozeroError::Geometry(format!("not a line: {c}")))?;
    p.linestring_begin(tagged, pts.len(), idx)?;
    for (i, q) in pts.iter().enumerate() {
        position(q, p, i)?;
    }
    p.linestring_end(tagged, idx)
}

fn polygon<P: GeomProcessor>(c: &Value, p: &mut P, tagged: bool, idx: usize) -> Result<()> {
    let rings = c
        .as_array()
        .ok_or_else(|| GeozeroError::Geometry(format!("not a polygon: {c}")))?;
    p.polygon_begin(tagged, rings.len(), idx)?;
    for (i, r) in rings.iter().enumerate() {
        line(r, p, false, i)?;
    }
    p.polygon_end(tagged, idx)
}

/// A GeoJSON geometry as WKB of `dialect` (ISO WKB; GeoPackage's with its
/// `srid` and `envelope`), with z when any position has z.
///
/// # Errors
///
/// As [`emit`].
pub fn to_wkb(
    g: &Value,
    dialect: geozero::wkb::WkbDialect,
    srid: Option<i32>,
    envelope: Vec<f64>,
) -> Result<Vec<u8>> {
    let dims = if has_z(g) {
        geozero::CoordDimensions::xyz()
    } else {
        geozero::CoordDimensions::xy()
    };
    let mut bytes = Vec::new();
    let mut w = geozero::wkb::WkbWriter::with_opts(&mut bytes, dialect, dims, srid, envelope);
    emit(g, &mut w)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of geometry through WKB and back, with and without z.
    #[test]
    fn geometries_round_trip_through_wkb() {
        let geoms = [
            json!({"type": "Point", "coordinates": [1.5, -2.0]}),
            json!({"type": "MultiPoint", "coordinates": [[1.0, 2.0], [3.0, 4.0]]}),
            json!({"type": "LineString", "coordinates": [[0.0, 0.0, 1.0], [1.0, 1.0, 2.0]]}),
            json!({"type": "MultiLineString", "coordinates": [[[0.0, 0.0], [1.0, 1.0]], [[2.0, 2.0], [3.0, 1.0]]]}),
            json!({"type": "Polygon", "coordinates": [[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 0.0]], [[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 1.0]]]}),
            json!({"type": "MultiPolygon", "coordinates": [[[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]]], [[[5.0, 5.0], [6.0, 5.0], [6.0, 6.0], [5.0, 5.0]]]]}),
            json!({"type": "GeometryCollection", "geometries": [
                {"type": "Point", "coordinates": [0.1, 0.2]},
                {"type": "LineString", "coordinates": [[0.0, 0.0], [1.0, 1.0]]}]}),
        ];
        for g in geoms {
            let bytes = to_wkb(&g, geozero::wkb::WkbDialect::Wkb, None, Vec::new()).unwrap();
            let mut back = ToJson::new(true);
            geozero::wkb::process_wkb_geom(&mut bytes.as_slice(), &mut back).unwrap();
            assert_eq!(back.finish(), g);
        }
    }

    #[test]
    fn deep_nesting_and_bad_coordinates_are_refused() {
        let mut g = json!({"type": "Point", "coordinates": [0.0, 0.0]});
        for _ in 0..40 {
            g = json!({"type": "GeometryCollection", "geometries": [g]});
        }
        let mut bytes = Vec::new();
        let mut w = geozero::wkb::WkbWriter::new(&mut bytes, geozero::wkb::WkbDialect::Wkb);
        assert!(emit(&g, &mut w).is_err());
        let mut t = ToJson::new(false);
        t.linestring_begin(true, usize::MAX, 0).unwrap();
        assert!(t.xy(f64::NAN, 0.0, 0).is_err());
        for _ in 0..MAX_DEPTH {
            let _ = t.geometrycollection_begin(1, 0);
        }
        assert!(t.geometrycollection_begin(1, 0).is_err());
    }

    #[test]
    fn z_is_filled_only_in_geometries_with_z() {
        let mut g = json!({"type": "GeometryCollection", "geometries": [
            {"type": "LineString", "coordinates": [[0.0, 0.0, 1.0], [1.0, 1.0, 2.0]]},
            {"type": "GeometryCollection", "geometries": [{"type": "Point", "coordinates": [5.0, 5.0]}]}]});
        fill_z(&mut g);
        assert_eq!(
            g["geometries"][1]["geometries"][0]["coordinates"],
            json!([5.0, 5.0, 0.0])
        );
        let mut flat = json!({"type": "Point", "coordinates": [1.0, 2.0]});
        fill_z(&mut flat);
        assert_eq!(flat["coordinates"], json!([1.0, 2.0]));
    }

    #[test]
    fn envelopes_span_every_position() {
        let g = json!({"type": "MultiLineString", "coordinates": [[[0.0, 5.0], [1.0, -1.0]], [[-2.0, 2.0], [3.0, 0.0]]]});
        assert_eq!(envelope(&g), Some([-2.0, 3.0, -1.0, 5.0]));
        assert_eq!(
            envelope(&json!({"type": "MultiPoint", "coordinates": []})),
            None
        );
    }
}
