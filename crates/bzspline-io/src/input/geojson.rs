//! GeoJSON: the first line, ring or run of points of a document.

use anyhow::{anyhow, Result};
use serde_json::Value;

use super::json::{json_rows, parse_json_value};
use super::{check_document, too_many, Points, Pos, Positions};

/// Reads the control points of the first line in a GeoJSON document: a
/// LineString, a MultiPoint, the outer ring of a Polygon (without the position
/// that repeats the first), or the Point features of a collection in order.
///
/// # Errors
///
/// `FILE:LINE: invalid JSON`, `FILE: feature i, coordinates[j]: ...` for a
/// geometry the check refuses ([`super::check_document`]: every geometry of
/// the document, not only the first line), or `FILE: feature i, coordinate
/// j: ...`.
pub fn parse_geojson_points(name: &str, bytes: &[u8], max_points: usize) -> Result<Points> {
    let mut v = parse_json_value(name, bytes)?;
    let cut = check_document(&mut v).map_err(|e| anyhow!("{name}: {e}"))?;
    let mut points = first_points(name, &v, max_points)?;
    points.cut = cut;
    Ok(points)
}

/// The control points of the first line of a checked document.
fn first_points(name: &str, v: &Value, max_points: usize) -> Result<Points> {
    let features: Vec<&Value> = match v.get("type").and_then(Value::as_str) {
        Some("FeatureCollection") => v
            .get("features")
            .and_then(Value::as_array)
            .map(|f| f.iter().collect())
            .unwrap_or_default(),
        _ => vec![&v],
    };
    let geometry = |f: &'_ Value| -> Option<Value> {
        match f.get("type").and_then(Value::as_str) {
            Some("Feature") => f.get("geometry").cloned(),
            _ => Some(f.clone()),
        }
    };
    // Point features, one row each, in document order.
    let mut coords: Vec<f64> = Vec::new();
    let mut width: Option<usize> = None;
    let mut point_features: Vec<usize> = Vec::new();
    // The first feature passed over, for the message when none has points.
    let mut skipped: Option<(usize, String)> = None;
    for (fi, f) in features.iter().enumerate() {
        let Some(g) = geometry(f) else {
            skipped.get_or_insert((fi, "a feature without geometry".to_owned()));
            continue;
        };
        let at = format!("feature {fi}: coordinates");
        let kind = g.get("type").and_then(Value::as_str).unwrap_or("");
        skipped.get_or_insert((fi, format!("a {kind:?} geometry")));
        let list = match (kind, g.get("coordinates")) {
            ("Point", Some(c)) => {
                if point_features.len() >= max_points {
                    return Err(too_many(&format!("{name}: feature {fi}"), max_points));
                }
                let (row, w) = json_rows(name, std::slice::from_ref(c), &at, 1)?;
                if let Some(first) = width.filter(|&first| first != w) {
                    return Err(anyhow!(
                        "{name}: feature {fi}, coordinate 0: {w} coordinates, expected {first}"
                    ));
                }
                width = Some(w);
                coords.extend(row);
                point_features.push(fi);
                continue;
            }
            ("LineString" | "MultiPoint", Some(Value::Array(c))) => &c[..],
            ("Polygon", Some(Value::Array(rings))) => match rings.first() {
                Some(Value::Array(c)) => {
                    if !same_position(c.first(), c.last()) {
                        return Err(anyhow!(
                            "{name}: feature {fi}: the ring is not closed (GeoJSON repeats its first position at the end)"
                        ));
                    }
                    // The repeat only closes the ring: the control points are
                    // the distinct vertices (--closed closes the curve).
                    &c[..c.len().saturating_sub(1)]
                }
                _ => continue,
            },
            _ => continue,
        };
        if !point_features.is_empty() {
            break;
        }
        // The first line: its coordinates are the control points.
        let len = list.len();
        let (coords, w) = json_rows(name, list, &at, max_points)?;
        return Ok(Points::new(
            name,
            (w, len),
            coords,
            Positions::Coords { feature: fi },
            Pos::Coord {
                feature: fi,
                index: len,
            },
        ));
    }
    if point_features.is_empty() {
        if let Some((fi, what)) = skipped {
            return Err(anyhow!(
                "{name}: feature {fi}: {what} has no control points (expected a LineString, MultiPoint, Polygon or Point)"
            ));
        }
    }
    let len = point_features.len();
    Ok(Points::new(
        name,
        (width.unwrap_or(0), len),
        coords,
        Positions::Features(point_features),
        Pos::Item(len),
    ))
}

/// Whether two GeoJSON positions have the same numbers (`0` and `0.0` alike).
fn same_position(a: Option<&Value>, b: Option<&Value>) -> bool {
    let coords = |v: Option<&Value>| -> Option<Vec<Option<f64>>> {
        Some(v?.as_array()?.iter().map(Value::as_f64).collect())
    };
    coords(a) == coords(b)
}
