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

impl<'a> Alphas<'a> {
    /// The form the sweeps take: the alphas given one per interval (none for
    /// one alpha), and the one alpha when there is one.
    pub(crate) fn parts(self) -> (&'a [f64], Option<f64>) {
        match self {
            Alphas::Uniform(a) => (&[], Some(a)),
            Alphas::PerInterval(a) => (a, None),
        }
    }
}

/// The owned form of [`Alphas`]: what an option or a binding's argument
/// holds (one alpha, or one per interval) before there are knots to count.
///
/// [`AlphaChoice::check`] checks every value at once (finite, in
/// `[1/3, 2/3]`); the count is checked by the construction that takes
/// [`AlphaChoice::as_alphas`].
///
/// # Examples
///
/// ```
/// use bzspline::{AlphaChoice, Spline};
///
/// let choice = AlphaChoice::Each(vec![0.4, 0.5]);
/// choice.check()?;
/// let s = Spline::build(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0], choice.as_alphas())?;
/// assert_eq!(s.alphas(), &[0.4, 0.5]);
/// assert!(AlphaChoice::One(0.7).check().is_err());
/// # Ok::<(), bzspline::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum AlphaChoice {
    /// The same alpha on every interval.
    One(f64),
    /// One alpha per interval.
    Each(Vec<f64>),
}

impl Default for AlphaChoice {
    fn default() -> Self {
        AlphaChoice::One(DEFAULT_ALPHA)
    }
}

impl AlphaChoice {
    /// As a construction takes it.
    #[must_use]
    pub fn as_alphas(&self) -> Alphas<'_> {
        match self {
            AlphaChoice::One(a) => Alphas::Uniform(*a),
            AlphaChoice::Each(v) => Alphas::PerInterval(v),
        }
    }

    /// Checks every value: finite and in `[1/3, 2/3]`
    /// ([`ALPHA_MIN`]..=[`ALPHA_MAX`]), whatever their count.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] or [`Error::AlphaOutOfRange`] naming the first
    /// value at fault (index 0 for one alpha).
    pub fn check(&self) -> Result<(), Error> {
        match self {
            AlphaChoice::One(a) => check_alpha(*a).map(drop),
            AlphaChoice::Each(v) => check_alphas(Alphas::PerInterval(v), v.len()),
        }
    }
}

/// Checks one shape parameter: finite and in `[1/3, 2/3]`
/// ([`ALPHA_MIN`]..=[`ALPHA_MAX`]). Every entry point that takes an alpha
/// before it has knots (an option, a d3 curve factory, a smoothing option)
/// checks it here.
///
/// # Errors
///
/// [`Error::NonFinite`] or [`Error::AlphaOutOfRange`], at index 0.
///
/// # Examples
///
/// ```
/// assert_eq!(bzspline::check_alpha(0.5), Ok(0.5));
/// assert!(bzspline::check_alpha(0.3).is_err());
/// assert!(bzspline::check_alpha(f64::NAN).is_err());
/// ```
pub fn check_alpha(alpha: f64) -> Result<f64, Error> {
    check_alphas(Alphas::Uniform(alpha), 1).map(|()| alpha)
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
    if knots_pass(knots) {
        return Ok(());
    }
    first_knot_failure(knots)
}

/// The first check of [`check_knots`] that `knots` (at least two) fail, in
/// its order: a non-finite knot, a knot not above the one before, a span
/// that overflows, an interval too narrow.
fn first_knot_failure(knots: &[f64]) -> Result<(), Error> {
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

/// Whether `knots` (at least two) pass every check of [`check_knots`], in one
/// pass with no early exit (so that it vectorises); [`check_knots`] finds the
/// first failure, in its order, only when they do not. A finite span and
/// every knot finite and every width positive and at least `span *`
/// [`MIN_RELATIVE_INTERVAL`] is exactly those checks: a width of finite knots
/// is positive when, and only when, the knots increase.
fn knots_pass(knots: &[f64]) -> bool {
    let (Some(&first), Some(&last)) = (knots.first(), knots.last()) else {
        return false;
    };
    let span = last - first;
    let min = span * MIN_RELATIVE_INTERVAL;
    // Four lanes of flags, so that the loop vectorises.
    let mut ok = [true; 4];
    let (left, right) = (&knots[..knots.len() - 1], &knots[1..]);
    let (lc, rc) = (left.chunks_exact(4), right.chunks_exact(4));
    let (lr, rr) = (lc.remainder(), rc.remainder());
    for (l, r) in lc.zip(rc) {
        for j in 0..4 {
            let w = r[j] - l[j];
            ok[j] &= l[j].is_finite() & (w > 0.0) & (w >= min);
        }
    }
    for (l, r) in lr.iter().zip(rr) {
        let w = r - l;
        ok[0] &= l.is_finite() & (w > 0.0) & (w >= min);
    }
    // A finite span has finite ends; the knots before the last are checked.
    span.is_finite() && ok.iter().all(|&o| o)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::tests::Rng;

    /// Knots of every kind the checks meet: increasing over many decades,
    /// with a repeat, a step back, a non-finite knot, a span past the range
    /// of a double, widths at and around the narrowest allowed, decreasing,
    /// all the same.
    fn knots(rng: &mut Rng, case: usize) -> Vec<f64> {
        let n = 2 + (rng.next() * 40.0) as usize;
        let scale = 10f64.powf(600.0 * rng.next() - 300.0);
        let mut k = vec![scale * (rng.next() - 0.5)];
        for _ in 1..n {
            let w = scale * 10f64.powf(6.0 * rng.next() - 3.0);
            k.push(k.last().unwrap() + w);
        }
        let at = 1 + (rng.next() * (n - 1) as f64) as usize;
        match case % 8 {
            0 => {}
            1 => k[at] = k[at - 1],
            2 => k[at] = k[at - 1] - scale * rng.next(),
            3 => k[at - (case / 8) % 2] = [f64::NAN, f64::INFINITY, -f64::INFINITY][case % 3],
            4 => {
                k[0] = -f64::MAX;
                k[n - 1] = f64::MAX;
            }
            5 => {
                let span = k[n - 1] - k[0];
                // At, just below and just above the narrowest width.
                let w = span * MIN_RELATIVE_INTERVAL * [1.0, 0.5, 2.0][case % 3];
                k[at] = k[at - 1] + w;
            }
            6 => k[at] = f64::from_bits(k[at - 1].to_bits() + 1),
            _ if case % 16 == 7 => k.reverse(),
            // Every knot the same: no width, no span.
            _ => k = vec![k[0]; n],
        }
        k
    }

    /// The one pass passes exactly the knots that pass every check, and the
    /// checks report the first failure either way.
    #[test]
    fn one_pass_over_the_knots_passes_what_the_checks_pass() {
        let mut rng = Rng(0x5eed_4b1d);
        let mut outcomes = [0usize; 2];
        for case in 0..40_000 {
            let k = knots(&mut rng, case);
            let want = first_knot_failure(&k);
            assert_eq!(knots_pass(&k), want.is_ok(), "case {case}: {k:?}");
            // Compared as text: a NaN knot in the error is not equal to itself.
            let got = check_knots(&k);
            assert_eq!(format!("{got:?}"), format!("{want:?}"), "case {case}");
            outcomes[usize::from(want.is_ok())] += 1;
        }
        // Both outcomes are met many times.
        assert!(outcomes.iter().all(|&c| c > 5_000), "{outcomes:?}");
    }
}
