//! JSON: an array of points, or the object that `fit` prints.

use anyhow::{anyhow, Result};
use serde_json::Value;

use super::{too_many, utf8, Points, Pos, Positions};

fn json_number(source: &str, at: &str, v: &Value) -> Result<f64> {
    let x = v
        .as_f64()
        .ok_or_else(|| anyhow!("{source}: {at}: expected a number, found {v}"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(anyhow!("{source}: {at}: {x} is not a finite number"))
    }
}

/// The points of a JSON array (arrays of numbers, or numbers), flat, and their
/// width; at most `max` of them.
pub(super) fn json_rows(
    source: &str,
    items: &[Value],
    what: &str,
    max: usize,
) -> Result<(Vec<f64>, usize)> {
    if items.len() > max {
        return Err(too_many(&format!("{source}: {what}[{max}]"), max));
    }
    let mut coords = Vec::new();
    let mut width = None;
    for (i, item) in items.iter().enumerate() {
        let start = coords.len();
        match item {
            Value::Array(a) => {
                for (j, v) in a.iter().enumerate() {
                    coords.push(json_number(source, &format!("{what}[{i}][{j}]"), v)?);
                }
            }
            Value::Number(_) => coords.push(json_number(source, &format!("{what}[{i}]"), item)?),
            other => {
                return Err(anyhow!(
                    "{source}: {what}[{i}]: expected a point (an array of numbers), found {other}"
                ))
            }
        }
        let w = coords.len() - start;
        match width {
            None => {
                width = Some(w);
                coords.reserve(w * items.len());
            }
            Some(first) if first != w => {
                return Err(anyhow!(
                    "{source}: {what}[{i}]: {w} coordinates, but {what}[0] has {first}"
                ));
            }
            Some(_) => {}
        }
    }
    Ok((coords, width.unwrap_or(0)))
}

pub(super) fn parse_json_value(name: &str, bytes: &[u8]) -> Result<Value> {
    let text = utf8(name, bytes)?;
    serde_json::from_str(text).map_err(|e| anyhow!("{name}:{}: invalid JSON: {e}", e.line()))
}

/// Parses JSON: an array of points (`[[x, y], ...]` or coordinates for curves),
/// an object with `points`, or an object with `knots` and `values` (the form
/// `fit` prints).
///
/// # Errors
///
/// `FILE:LINE: invalid JSON`, or `FILE: points[i]: ...` for a bad element.
pub fn parse_json(name: &str, bytes: &[u8], max_points: usize) -> Result<Points> {
    let v = parse_json_value(name, bytes)?;
    let rows = |items: &[Value], what: &str| json_rows(name, items, what, max_points);
    let ((coords, width), len) = match &v {
        Value::Array(items) => (rows(items, "points")?, items.len()),
        Value::Object(o) => {
            if let Some(Value::Array(items)) = o.get("points") {
                (rows(items, "points")?, items.len())
            } else if let (Some(Value::Array(k)), Some(Value::Array(vals))) =
                (o.get("knots"), o.get("values"))
            {
                let (values, vw) = rows(vals, "values")?;
                if vals.first().is_some_and(Value::is_array) {
                    // A curve's control points: its knots are parameters.
                    ((values, vw), vals.len())
                } else {
                    if k.len() != vals.len() {
                        return Err(anyhow!(
                            "{name}: {} knots but {} values",
                            k.len(),
                            vals.len()
                        ));
                    }
                    let (knots, kw) = rows(k, "knots")?;
                    let mut coords = Vec::with_capacity(knots.len() + values.len());
                    for i in 0..k.len() {
                        coords.extend_from_slice(&knots[i * kw..(i + 1) * kw]);
                        coords.extend_from_slice(&values[i * vw..(i + 1) * vw]);
                    }
                    ((coords, kw + vw), k.len())
                }
            } else {
                return Err(anyhow!(
                    "{name}: expected an array of points, or an object with \"points\" or with \"knots\" and \"values\""
                ));
            }
        }
        _ => return Err(anyhow!("{name}: expected an array of points")),
    };
    Ok(Points::new(
        name,
        (width, len),
        coords,
        Positions::Items,
        Pos::Item(len),
    ))
}
