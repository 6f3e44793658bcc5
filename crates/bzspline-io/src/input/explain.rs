//! The library's errors explained in terms of the input: which file and line
//! (or feature) the index at fault came from.

use anyhow::anyhow;

use super::{locate, Points};

/// Turns a library error (0-based row indices) into a message naming the source
/// and line at fault.
#[must_use]
pub fn explain(points: &Points, e: &bzspline::Error) -> anyhow::Error {
    use bzspline::{Error as E, Field};
    let n = points.len();
    match *e {
        E::TooFewPoints { found: 0, .. } => anyhow!(
            "{}: no data points (need at least 2)",
            locate(&points.source, points.end)
        ),
        E::TooFewPoints { found, min } => anyhow!(
            "{}: only {found} point{}, need at least {min}",
            points.at(found.saturating_sub(1)),
            if found == 1 { "" } else { "s" }
        ),
        E::NonFinite {
            field: Field::Alpha,
            index,
            value,
        } => anyhow!(
            "--alphas value {} = {value} is not a finite number",
            index + 1
        ),
        E::NonFinite { index, value, .. } => {
            anyhow!("{}: {value} is not a finite number", points.at(index))
        }
        E::NotIncreasing {
            index,
            previous,
            value,
        } => anyhow!(
            "{}: x = {value} does not exceed x = {previous} on {}: x must be strictly increasing{}",
            points.at(index),
            points.pos_words(index.saturating_sub(1)),
            curve_hint(points)
        ),
        E::IntervalTooSmall {
            interval,
            width,
            span,
        } => anyhow!(
            "{}: too close to {} (gap {width:e} in a span of {span:e})",
            points.at(interval + 1),
            points.pos_words(interval)
        ),
        E::SpanOverflow { first, last } => anyhow!(
            "{}: the span from {first:e} to {last:e} overflows a double",
            points.at(n.saturating_sub(1))
        ),
        E::AlphaOutOfRange { interval, value } => anyhow!(
            "alpha {} = {value} (the interval from {} to {}) is outside [1/3, 2/3]",
            interval + 1,
            points.pos_words(interval),
            points.pos_words(interval + 1)
        ),
        E::LengthMismatch {
            field: Field::Alpha,
            expected,
            found,
        } => anyhow!(
            "--alphas has {found} value{}, but {n} points ({}) need {expected}, one per interval",
            if found == 1 { "" } else { "s" },
            points.source
        ),
        E::RepeatedPoint { index } => anyhow!(
            "{}: repeats the point on {}: consecutive control points must differ",
            points.at(index),
            points.pos_words(index.saturating_sub(1))
        ),
        E::RepeatedClosingPoint { last } => anyhow!(
            "{}: repeats the first point ({}): a closed curve closes by itself, leave the repeat out",
            points.at(last),
            points.pos_words(0)
        ),
        ref other => anyhow!("{}: {other}", points.source),
    }
}

/// For two columns whose x runs back and forth (the corners of a polygon or
/// the points of a path rather than samples of a function), the options that
/// read them as a curve; nothing otherwise.
fn curve_hint(points: &Points) -> &'static str {
    if points.width != 2 || points.len < 3 {
        return "";
    }
    let x = |i: usize| points.coords[2 * i];
    let (mut up, mut down) = (false, false);
    for i in 1..points.len {
        up |= x(i) > x(i - 1);
        down |= x(i) < x(i - 1);
    }
    if !(up && down) {
        return "";
    }
    let last = 2 * (points.len - 1);
    if points.coords[..2] == points.coords[last..last + 2] {
        " (the rows look like a closed polygon: add --closed and leave out the last row, which repeats the first)"
    } else {
        " (the rows look like points along a path: --curve reads them as one)"
    }
}
