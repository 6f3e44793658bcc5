//! Fitting the points a command read with the shape its options give: the
//! library's refusals mapped to the input's lines, and results that overflow
//! a double refused before anything is written.

use anyhow::{bail, Result};

use crate::input::{self, Points};
use crate::model::{self, FitSpec, Fitted, Mode, Shape, SmoothingReport};

/// Builds the spline for `points` with the validated `shape`, naming the file
/// and line of any fault.
///
/// # Errors
///
/// Rows of the wrong width, the library's refusals mapped to lines, and results
/// that overflow a double.
pub fn fit_points(points: &Points, shape: &Shape) -> Result<Fitted> {
    fit_points_reported(points, shape).map(|(f, _)| f)
}

/// [`fit_points`], with the report of a smoothing fit.
///
/// # Errors
///
/// As [`fit_points`].
pub fn fit_points_reported(
    points: &Points,
    shape: &Shape,
) -> Result<(Fitted, Option<SmoothingReport>)> {
    check_columns(points, shape)?;
    let (built, report) = match model::build_reported(&spec_of(points, shape)) {
        Ok((f, r)) => (Ok(f), r),
        Err(e) => (Err(e), None),
    };
    Ok((checked(points, built)?, report))
}

fn check_columns(points: &Points, shape: &Shape) -> Result<()> {
    match shape.mode {
        Mode::Function => input::check_columns(points, &[2], "2 (x, y)"),
        Mode::Curve => input::check_columns(points, &[2, 3], "2 or 3 coordinates"),
    }
}

fn spec_of<'a>(points: &'a Points, shape: &Shape) -> FitSpec<'a> {
    FitSpec {
        points: std::borrow::Cow::Borrowed(&points.coords),
        dim: points.width,
        weights: points.weights.as_deref().map(std::borrow::Cow::Borrowed),
        shape: shape.clone(),
    }
}

/// Maps a library error to the input's lines and refuses non-finite results.
fn checked(points: &Points, built: Result<Fitted, bzspline::Error>) -> Result<Fitted> {
    let fitted = built.map_err(|e| input::explain(points, &e))?;
    let finite = match &fitted {
        // The segments' end points are the knot values (knot points).
        Fitted::Function(s) => {
            (0..s.len()).all(|k| {
                s.segment(k)
                    .is_some_and(|b| b.p.iter().flatten().all(|v| v.is_finite()))
            }) && s
                .tangent_points()
                .iter()
                .all(|(x, y)| x.is_finite() && y.is_finite())
        }
        Fitted::Curve(c) => {
            (0..c.len()).all(|k| {
                c.segment_points(k)
                    .is_some_and(|p| p.iter().all(|v| v.is_finite()))
            }) && c
                .tangent_points()
                .iter()
                .all(|(t, p)| t.is_finite() && p.iter().all(|v| v.is_finite()))
        }
    };
    if !finite {
        bail!(
            "{}: the spline's coefficients overflow a double (values too large)",
            points.source
        );
    }
    Ok(fitted)
}
