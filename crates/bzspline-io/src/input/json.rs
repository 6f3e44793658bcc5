//! JSON: an array of points, or the object that `fit` prints.

use anyhow::{anyhow, Result};
use serde_json::Value;

use super::{too_many, utf8, Points, Pos, Positions};
use crate::time::{self, TimeKind};

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
    json_rows_dated(source, items, what, max, None)
}

/// [`json_rows`]; with `kind`, a row may start with (or an item be) a date or
/// date-time string, of one kind for all rows: `kind` is unset until the first
/// row, then `Some(None)` for numbers or the kind of the dates (see
/// [`crate::time`]).
pub(super) fn json_rows_dated(
    source: &str,
    items: &[Value],
    what: &str,
    max: usize,
    mut kind: Option<&mut Option<Option<TimeKind>>>,
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
                    let at = format!("{what}[{i}][{j}]");
                    coords.push(match (j, kind.as_deref_mut()) {
                        (0, Some(k)) => first_value(source, &at, v, k)?,
                        _ => json_number(source, &at, v)?,
                    });
                }
            }
            Value::Number(_) | Value::String(_) => {
                let at = format!("{what}[{i}]");
                coords.push(match kind.as_deref_mut() {
                    Some(k) => first_value(source, &at, item, k)?,
                    None => json_number(source, &at, item)?,
                });
            }
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

/// A row's first value: a number, or a date string of the rows' one kind.
fn first_value(
    source: &str,
    at: &str,
    v: &Value,
    kind: &mut Option<Option<TimeKind>>,
) -> Result<f64> {
    let Value::String(text) = v else {
        if matches!(kind, Some(Some(_))) {
            return Err(anyhow!(
                "{source}: {at}: a number, but the first values are dates"
            ));
        }
        *kind = Some(None);
        return json_number(source, at, v);
    };
    match (time::parse(text), *kind) {
        (Some((x, k)), None) => {
            *kind = Some(Some(k));
            Ok(x)
        }
        (Some((x, k)), Some(Some(want))) => Ok(time::convert(x, k, want)),
        (Some(_), Some(None)) => Err(anyhow!(
            "{source}: {at}: a date, but the first values are numbers"
        )),
        (None, _) => json_number(source, at, v),
    }
}

pub(super) fn parse_json_value(name: &str, bytes: &[u8]) -> Result<Value> {
    let text = utf8(name, bytes)?;
    serde_json::from_str(text).map_err(|e| anyhow!("{name}:{}: invalid JSON: {e}", e.line()))
}

/// Parses JSON: an array of points (`[[x, y], ...]` or coordinates for curves),
/// an object with `points`, or an object with `knots` (or `knot_times`) and
/// `values` (the form `fit` prints). The first value of each point (or each
/// knot) may be an ISO 8601 date or date-time string, as in tables.
///
/// # Errors
///
/// `FILE:LINE: invalid JSON`, or `FILE: points[i]: ...` for a bad element.
pub fn parse_json(name: &str, bytes: &[u8], max_points: usize) -> Result<Points> {
    let v = parse_json_value(name, bytes)?;
    let mut kind = None;
    let mut rows = |items: &[Value], what: &str, dated: bool| {
        json_rows_dated(name, items, what, max_points, dated.then_some(&mut kind))
    };
    let ((coords, width), len) = match &v {
        Value::Array(items) => (rows(items, "points", true)?, items.len()),
        Value::Object(o) => {
            if let Some(Value::Array(items)) = o.get("points") {
                (rows(items, "points", true)?, items.len())
            } else if let (Some(Value::Array(k)), Some(Value::Array(vals))) =
                (o.get("knots"), o.get("values"))
            {
                let (values, vw) = rows(vals, "values", false)?;
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
                    // The dates `fit` writes beside the knots, when it wrote them.
                    let (knots, kw) = match o.get("knot_times") {
                        Some(Value::Array(t)) if t.len() == k.len() => rows(t, "knot_times", true)?,
                        _ => rows(k, "knots", true)?,
                    };
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
    let mut points = Points::new(name, (width, len), coords, Positions::Items, Pos::Item(len));
    points.time = kind.flatten();
    Ok(points)
}
