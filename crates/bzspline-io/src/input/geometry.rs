//! The check every GeoJSON document passes before its geometries are
//! converted or smoothed: the shape RFC 7946 gives each geometry type, on the
//! JSON tree itself, so that a bad position is named by its feature and
//! coordinate path rather than met by a converter that indexes it unchecked.
//!
//! What it refuses: a position that is not an array of 2 or more numbers
//! (`null`, strings, `[1]`), coordinates nested to the wrong depth for their
//! type, a LineString of one position, a ring of fewer than 4 positions or
//! one that does not end where it starts, an unknown geometry type, features
//! that are not an array. What it changes: a position of more than 3 numbers
//! keeps x, y and z (the rest, such as a measure, is dropped), and the count
//! of such positions is returned so that the command can say so once.
//! Numbers are finite by construction (the JSON parser refuses overflow).

use std::fmt::{self, Write};

use serde_json::Value;

/// A geometry the check refused: where (the feature, unless the document is
/// a lone geometry, and the path inside it) and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fault {
    /// The feature of a FeatureCollection, or 0 for a lone Feature; `None`
    /// for a document that is a bare geometry.
    pub feature: Option<usize>,
    /// The member path inside the geometry, e.g. `coordinates[0][3]` or
    /// `geometries[1].coordinates[2]`; empty for the geometry itself.
    pub path: String,
    /// What is wrong.
    pub what: String,
}

impl fmt::Display for Fault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut sep = "";
        if let Some(i) = self.feature {
            write!(f, "feature {i}")?;
            sep = ", ";
        }
        if !self.path.is_empty() {
            write!(f, "{sep}{}", self.path)?;
            sep = ", ";
        }
        if sep.is_empty() {
            f.write_str(&self.what)
        } else {
            write!(f, ": {}", self.what)
        }
    }
}

impl std::error::Error for Fault {}

/// The most numbers a position keeps: x, y and z.
pub const MAX_POSITION_LEN: usize = 3;

/// Checks every geometry of a GeoJSON document (FeatureCollection, Feature
/// or geometry) in place, cutting positions of more than
/// [`MAX_POSITION_LEN`] numbers to x, y, z. Returns how many positions were
/// cut.
///
/// # Errors
///
/// The first [`Fault`] in document order.
pub fn check_document(doc: &mut Value) -> Result<usize, Fault> {
    let mut cut = 0;
    match doc.get("type").and_then(Value::as_str) {
        Some("FeatureCollection") => {
            let Some(features) = doc.get_mut("features").and_then(Value::as_array_mut) else {
                return Err(Fault {
                    feature: None,
                    path: String::new(),
                    what: "a FeatureCollection needs an array of \"features\"".to_owned(),
                });
            };
            for (i, f) in features.iter_mut().enumerate() {
                check_feature(f, i, &mut cut)?;
            }
        }
        Some("Feature") => check_feature(doc, 0, &mut cut)?,
        _ => check_geometry(doc, "", &mut cut).map_err(|(path, what)| Fault {
            feature: None,
            path,
            what,
        })?,
    }
    Ok(cut)
}

fn check_feature(f: &mut Value, i: usize, cut: &mut usize) -> Result<(), Fault> {
    let fault = |(path, what)| Fault {
        feature: Some(i),
        path,
        what,
    };
    if f.get("type").and_then(Value::as_str) != Some("Feature") {
        return Err(fault((String::new(), "not a Feature".to_owned())));
    }
    match f.get_mut("geometry") {
        None | Some(Value::Null) => Ok(()),
        Some(g) => check_geometry(g, "", cut).map_err(fault),
    }
}

/// Checks a GeoJSON document ([`check_document`]) and converts it. Errors
/// start with `where_` (the file, or `FILE:LINE` of a stream).
///
/// # Errors
///
/// `WHERE: feature i, coordinates[j][k]: ...`, or `WHERE: invalid GeoJSON:
/// ...` for what the check leaves to the GeoJSON parser (foreign members,
/// `bbox`, ids).
pub fn to_geojson(where_: &str, mut v: Value) -> anyhow::Result<(geojson::GeoJson, usize)> {
    let cut = check_document(&mut v).map_err(|e| anyhow::anyhow!("{where_}: {e}"))?;
    let doc = serde_json::from_value::<geojson::GeoJson>(v)
        .map_err(|e| anyhow::anyhow!("{where_}: invalid GeoJSON: {e}"))?;
    Ok((doc, cut))
}

/// A refusal inside a geometry: the path and what is wrong.
type Inner = (String, String);

/// How deeply each type nests its positions (0: one position).
fn depth(kind: &str) -> Option<usize> {
    match kind {
        "Point" => Some(0),
        "MultiPoint" | "LineString" => Some(1),
        "MultiLineString" | "Polygon" => Some(2),
        "MultiPolygon" => Some(3),
        _ => None,
    }
}

fn check_geometry(g: &mut Value, here: &str, cut: &mut usize) -> Result<(), Inner> {
    let here = here.to_owned();
    let Some(kind) = g.get("type").and_then(Value::as_str).map(str::to_owned) else {
        return Err((here, "a geometry needs a \"type\"".to_owned()));
    };
    if kind == "GeometryCollection" {
        let Some(members) = g.get_mut("geometries").and_then(Value::as_array_mut) else {
            return Err((
                here,
                "a GeometryCollection needs an array of \"geometries\"".to_owned(),
            ));
        };
        for (k, m) in members.iter_mut().enumerate() {
            check_geometry(m, &join(&here, &format!("geometries[{k}]")), cut)?;
        }
        return Ok(());
    }
    let Some(d) = depth(&kind) else {
        return Err((here, format!("unknown geometry type {kind:?}")));
    };
    let mut p = join(&here, "coordinates");
    let Some(c) = g.get_mut("coordinates") else {
        return Err((here, format!("a {kind} needs \"coordinates\"")));
    };
    nested(c, d, &kind, &mut p, cut)
}

fn join(a: &str, b: &str) -> String {
    if a.is_empty() {
        b.to_owned()
    } else {
        format!("{a}.{b}")
    }
}

/// Checks coordinates nested `d` deep (0: a position) for a geometry `kind`.
fn nested(
    c: &mut Value,
    d: usize,
    kind: &str,
    path: &mut String,
    cut: &mut usize,
) -> Result<(), Inner> {
    if d == 0 {
        return position(c, path, cut);
    }
    let Some(items) = c.as_array_mut() else {
        return Err((
            path.clone(),
            format!("expected an array, found {}", brief(c)),
        ));
    };
    let n = items.len();
    // The positions of a line or ring: of one dimension (before any is cut).
    let line = d == 1 && kind != "MultiPoint";
    let dims: Vec<usize> = if line {
        items
            .iter()
            .map(|p| p.as_array().map_or(0, Vec::len))
            .collect()
    } else {
        Vec::new()
    };
    for (k, item) in items.iter_mut().enumerate() {
        let len = path.len();
        // Into the one path buffer: no string made per position.
        let _ = write!(path, "[{k}]");
        nested(item, d - 1, kind, path, cut)?;
        path.truncate(len);
    }
    if let Some(k) = dims.iter().position(|&m| m != dims[0]) {
        return Err((
            format!("{path}[{k}]"),
            format!(
                "{} numbers, but {path}[0] has {} (the positions of a line or ring have one dimension)",
                dims[k], dims[0]
            ),
        ));
    }
    if line && kind == "LineString" && n == 1 {
        return Err((
            path.clone(),
            "a LineString needs 2 or more positions".to_owned(),
        ));
    }
    let ring = matches!((kind, d), ("Polygon" | "MultiPolygon", 1));
    if ring {
        if n < 4 {
            return Err((
                path.clone(),
                format!(
                    "a ring needs 4 or more positions (the last repeating the first), found {n}"
                ),
            ));
        }
        if items[0] != items[n - 1] && numbers(&items[0]) != numbers(&items[n - 1]) {
            return Err((
                path.clone(),
                "the ring is not closed (GeoJSON repeats its first position at the end)".to_owned(),
            ));
        }
    }
    Ok(())
}

fn numbers(v: &Value) -> Vec<Option<f64>> {
    v.as_array()
        .map(|a| a.iter().map(Value::as_f64).collect())
        .unwrap_or_default()
}

/// One position: 2 or more finite numbers; more than 3 are cut to 3.
fn position(c: &mut Value, path: &str, cut: &mut usize) -> Result<(), Inner> {
    let Some(a) = c.as_array_mut() else {
        return Err((
            path.to_owned(),
            format!("expected a position [x, y], found {}", brief(c)),
        ));
    };
    for (k, v) in a.iter().enumerate() {
        match v.as_f64() {
            Some(x) if x.is_finite() => {}
            Some(x) => {
                return Err((
                    format!("{path}[{k}]"),
                    format!("{x} is not a finite number"),
                ))
            }
            None => {
                return Err((
                    format!("{path}[{k}]"),
                    format!("expected a number, found {}", brief(v)),
                ))
            }
        }
    }
    if a.len() < 2 {
        return Err((
            path.to_owned(),
            format!(
                "a position needs 2 or 3 numbers (x, y[, z]), found {}",
                a.len()
            ),
        ));
    }
    if a.len() > MAX_POSITION_LEN {
        a.truncate(MAX_POSITION_LEN);
        *cut += 1;
    }
    Ok(())
}

/// A short description of a JSON value for messages.
fn brief(v: &Value) -> String {
    match v {
        Value::Null => "null".to_owned(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => n.to_string(),
        Value::String(s) => {
            let short: String = s.chars().take(20).collect();
            format!(
                "{short:?}{}",
                if s.chars().count() > 20 { "..." } else { "" }
            )
        }
        Value::Array(_) => "an array".to_owned(),
        Value::Object(_) => "an object".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn fault(mut v: Value) -> String {
        check_document(&mut v).unwrap_err().to_string()
    }

    #[test]
    fn a_short_position_is_named_by_its_path() {
        let v = json!({"type": "LineString", "coordinates": [[0, 0], [1], [2, 0]]});
        assert_eq!(
            fault(v),
            "coordinates[1]: a position needs 2 or 3 numbers (x, y[, z]), found 1"
        );
    }

    #[test]
    fn features_and_collections_are_named() {
        let v = json!({"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [0, 0]}},
            {"type": "Feature", "properties": {}, "geometry": {"type": "GeometryCollection", "geometries": [
                {"type": "Point", "coordinates": [0, 0]},
                {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [null, 1], [0, 0]]]}
            ]}}
        ]});
        assert_eq!(
            fault(v),
            "feature 1, geometries[1].coordinates[0][2][0]: expected a number, found null"
        );
        let v = json!({"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0, "1"], [1, 1]]}});
        assert_eq!(
            fault(v),
            "feature 0, coordinates[0][1]: expected a number, found \"1\""
        );
    }

    #[test]
    fn rings_need_four_closed_positions() {
        let v = json!({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 0]]]});
        assert!(fault(v).starts_with("coordinates[0]: a ring needs 4 or more positions"));
        let v =
            json!({"type": "MultiPolygon", "coordinates": [[[[0, 0], [1, 0], [1, 1], [0, 1]]]]});
        assert!(fault(v).starts_with("coordinates[0][0]: the ring is not closed"));
        // 0 and 0.0 are the same number.
        let mut v =
            json!({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0.0, 0.0]]]});
        assert_eq!(check_document(&mut v), Ok(0));
    }

    #[test]
    fn wrong_depths_and_types_are_refused() {
        let v = json!({"type": "Polygon", "coordinates": [[0, 0], [1, 0], [1, 1], [0, 0]]});
        assert_eq!(
            fault(v),
            "coordinates[0][0]: expected a position [x, y], found 0"
        );
        let v = json!({"type": "LineString", "coordinates": [[[0, 0]], [[1, 1]]]});
        assert_eq!(
            fault(v),
            "coordinates[0][0]: expected a number, found an array"
        );
        let v = json!({"type": "Line", "coordinates": []});
        assert_eq!(fault(v), "unknown geometry type \"Line\"");
        let v = json!({"type": "LineString", "coordinates": [[0, 0]]});
        assert_eq!(
            fault(v),
            "coordinates: a LineString needs 2 or more positions"
        );
        let v = json!({"type": "FeatureCollection", "features": {}});
        assert!(fault(v).contains("array of \"features\""));
    }

    #[test]
    fn empty_and_null_geometries_pass() {
        for mut v in [
            json!({"type": "Feature", "properties": null, "geometry": null}),
            json!({"type": "LineString", "coordinates": []}),
            json!({"type": "Polygon", "coordinates": []}),
            json!({"type": "GeometryCollection", "geometries": []}),
        ] {
            assert_eq!(check_document(&mut v), Ok(0), "{v}");
        }
    }

    #[test]
    fn positions_keep_x_y_z() {
        let mut v =
            json!({"type": "MultiPoint", "coordinates": [[0, 0, 1, 7], [1, 1, 2, 8, 9], [2, 0]]});
        assert_eq!(check_document(&mut v), Ok(2));
        assert_eq!(v["coordinates"], json!([[0, 0, 1], [1, 1, 2], [2, 0]]));
        let v = json!({"type": "LineString", "coordinates": [[0, 0, 1, 7], [1, 1, 2, 8], [2, 0]]});
        assert!(fault(v).starts_with("coordinates[2]: 2 numbers, but coordinates[0] has 4"));
    }
}
