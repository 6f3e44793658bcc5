//! What every construction checks first: the knots, finiteness, the shape
//! parameters and their range.

use crate::error::{Error, Field};

/// Smallest accepted shape parameter: the double nearest to 1/3 (the decimal
/// literal `0.3333333333333333` parses to it).
pub const ALPHA_MIN: f64 = 0.333_333_333_333_333_3;
/// Largest accepted shape parameter: the double that the decimal literal
/// `0.6666666666666667` parses to, one step above the double nearest to 2/3.
pub const ALPHA_MAX: f64 = 0.666_666_666_666_666_7;
/// The default shape parameter: each leg is touched at its middle.
pub const DEFAULT_ALPHA: f64 = 0.5;
/// An interval narrower than this fraction of the whole span is refused: it is
/// below one unit in the last place of the span, so the knots' own rounding
/// would decide the shape.
pub const MIN_RELATIVE_INTERVAL: f64 = f64::EPSILON;

/// One shape parameter for every interval, or one each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Alphas<'a> {
    /// The same alpha on every interval.
    Uniform(f64),
    /// `alphas[k]` for interval `k`; there must be one fewer than knots.
    PerInterval(&'a [f64]),
}

impl Default for Alphas<'_> {
    fn default() -> Self {
        Alphas::Uniform(DEFAULT_ALPHA)
    }
}

/// Checks knots: at least two, finite, strictly increasing, a finite span and no
/// interval narrower than [`MIN_RELATIVE_INTERVAL`] of it. Returns the widths.
pub(crate) fn validate_knots(knots: &[f64]) -> Result<Vec<f64>, Error> {
    check_knots(knots)?;
    Ok(knots.windows(2).map(|w| w[1] - w[0]).collect())
}

/// The checks of [`validate_knots`], without forming the widths.
pub(crate) fn check_knots(knots: &[f64]) -> Result<(), Error> {
    if knots.len() < 2 {
        return Err(Error::TooFewPoints {
            found: knots.len(),
            min: 2,
        });
    }
    check_finite(Field::Knot, knots)?;
    for i in 1..knots.len() {
        if knots[i] <= knots[i - 1] {
            return Err(Error::NotIncreasing {
                index: i,
                previous: knots[i - 1],
                value: knots[i],
            });
        }
    }
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    let span = last - first;
    if !span.is_finite() {
        return Err(Error::SpanOverflow { first, last });
    }
    for (k, w) in knots.windows(2).map(|w| w[1] - w[0]).enumerate() {
        if w < span * MIN_RELATIVE_INTERVAL {
            return Err(Error::IntervalTooSmall {
                interval: k,
                width: w,
                span,
            });
        }
    }
    Ok(())
}

/// Returns the first non-finite entry as an error.
pub(crate) fn check_finite(field: Field, xs: &[f64]) -> Result<(), Error> {
    match xs.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Error::NonFinite {
            field,
            index,
            value: xs[index],
        }),
        None => Ok(()),
    }
}

/// Expands and checks the shape parameters for `intervals` intervals.
pub(crate) fn resolve_alphas(alphas: Alphas<'_>, intervals: usize) -> Result<Vec<f64>, Error> {
    check_alphas(alphas, intervals)?;
    Ok(match alphas {
        Alphas::Uniform(a) => vec![a; intervals],
        Alphas::PerInterval(a) => a.to_vec(),
    })
}

/// The checks of [`resolve_alphas`], without expanding them.
pub(crate) fn check_alphas(alphas: Alphas<'_>, intervals: usize) -> Result<(), Error> {
    let (list, one): (&[f64], f64) = match alphas {
        Alphas::Uniform(a) => (&[], a),
        Alphas::PerInterval(a) => {
            if a.len() != intervals {
                return Err(Error::LengthMismatch {
                    field: Field::Alpha,
                    expected: intervals,
                    found: a.len(),
                });
            }
            (a, 0.5)
        }
    };
    // One alpha stands for every interval: the first names it.
    let uniform = (intervals > 0 && list.is_empty()).then_some((0, one));
    for (k, a) in list.iter().copied().enumerate().chain(uniform) {
        if !a.is_finite() {
            return Err(Error::NonFinite {
                field: Field::Alpha,
                index: k,
                value: a,
            });
        }
        if !(ALPHA_MIN..=ALPHA_MAX).contains(&a) {
            return Err(Error::AlphaOutOfRange {
                interval: k,
                value: a,
            });
        }
    }
    Ok(())
}
