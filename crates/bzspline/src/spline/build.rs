//! Building a spline: checking the input, solving the paper's system (16)
//! for the knot values and forming the pieces (fused in one sweep where it
//! can, step by step where it must name a fault), and rebuilding in place.

use super::{Extrapolate, Shape, Spline, TINY_SPAN};
use crate::error::{Error, Field};
use crate::fast::search::{Summary, STRIDE};
use crate::fast::{chunks, sweep, Piece};
use crate::method::{self, piece_coefs, OpenSystem};
use crate::method::{power_of_two_scale, scale_for_max};
use crate::pieces::Pieces;
use crate::validate::{check_finite, resolve_alphas, validate_knots};
use crate::validate::{Alphas, ALPHA_MAX, ALPHA_MIN, MIN_RELATIVE_INTERVAL};

/// Every check of a spline's input, one at a time so that the first fault is
/// named: the knots (giving the widths), the values' length and finiteness, the
/// alphas (giving one per interval).
pub(super) fn validate_step_by_step(
    knots: &[f64],
    values: &[f64],
    alphas: Alphas<'_>,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let widths = validate_knots(knots)?;
    if values.len() != knots.len() {
        return Err(Error::LengthMismatch {
            field: Field::Value,
            expected: knots.len(),
            found: values.len(),
        });
    }
    check_finite(Field::Value, values)?;
    let resolved = resolve_alphas(alphas, widths.len())?;
    Ok((widths, resolved))
}

/// Every check of [`Spline::build`] in one branch-free pass (two halves side
/// by side on large inputs, [`chunks::both`]): `Some(max |F|)` when the
/// input is valid, `None` when something is wrong (the step-by-step
/// validation then finds what). A finite positive span and widths that are
/// positive and at least `span * MIN_RELATIVE_INTERVAL` imply finite,
/// strictly increasing knots.
///
/// As it reads the knots it puts every [`STRIDE`]-th into `summary`
/// (see [`Summary`]), which then needs no pass over them of its
/// own; when it returns `None` the summary may be partly written.
pub(super) fn quick_check(
    knots: &[f64],
    values: &[f64],
    alphas: Alphas<'_>,
    summary: &mut Summary,
) -> Option<f64> {
    let n = knots.len();
    if n < 2 || values.len() != n {
        return None;
    }
    let span = knots[n - 1] - knots[0];
    if !(span.is_finite() && span > 0.0) {
        return None;
    }
    // `w >= thr` and `w > 0` in one test: `thr` at least the least positive
    // double (the product underflows to 0 only for a subnormal span).
    let thr = (span * MIN_RELATIVE_INTERVAL).max(f64::from_bits(1));
    let (list, one) = alphas.parts();
    let alphas_ok = match one {
        Some(a) => (ALPHA_MIN..=ALPHA_MAX).contains(&a),
        None => list.len() == n - 1,
    };
    if !alphas_ok {
        return None;
    }
    // Two stretches of widths, the first a whole number of `STRIDE`s, side
    // by side on large inputs; each writes its share of the summary.
    let every = &mut summary.every;
    every.clear();
    every.resize((n - 1) / STRIDE + 1, 0.0);
    let half = (n - 1) / 2 / STRIDE * STRIDE;
    let (e0, e1) = every.split_at_mut(half / STRIDE);
    let check = Stretches {
        knots,
        values,
        alphas: list,
        thr,
    };
    let (a, b) = chunks::both(
        n,
        || check.widths(0..half, e0),
        || check.widths(half..n - 1, e1),
    );
    let m = a?.max(b?);
    summary.formed();
    Some(m)
}

/// The input of [`quick_check`], checked a stretch of widths at a time.
struct Stretches<'a> {
    knots: &'a [f64],
    values: &'a [f64],
    /// One per interval, or none for one alpha (checked apart).
    alphas: &'a [f64],
    /// The least width accepted, positive.
    thr: f64,
}

impl Stretches<'_> {
    /// The checks of widths `w` (`w.start` a multiple of [`STRIDE`]), of the
    /// values at their left ends (and the last value with the last width),
    /// and of their alphas: `Some(max |F|)` of those values when they pass.
    /// `every` gets every `STRIDE`-th knot from `w.start`.
    ///
    /// Knots and values are read side by side in one loop (two streams from
    /// memory at once, where a loop over each in turn read one), into four
    /// [`Lanes`] so that the loop vectorises; every 1,024 knots the summary
    /// takes its share while they are in the cache.
    fn widths(&self, w: std::ops::Range<usize>, every: &mut [f64]) -> Option<f64> {
        /// Knots read between two visits to the summary.
        const BLOCK: usize = 64 * STRIDE;
        let (knots, n, thr) = (self.knots, self.knots.len(), self.thr);
        let mut lanes = Lanes {
            least: [f64::MAX; 4],
            most: [0.0; 4],
            zero: [0.0; 4],
        };
        let (left, right) = (&knots[w.start..w.end], &knots[w.start + 1..=w.end]);
        let values = &self.values[w.clone()];
        let mut slots = every.iter_mut();
        let blocks = left
            .chunks(BLOCK)
            .zip(right.chunks(BLOCK))
            .zip(values.chunks(BLOCK));
        for ((l, r), v) in blocks {
            let (lc, rc, vc) = (l.chunks_exact(4), r.chunks_exact(4), v.chunks_exact(4));
            let rest = lc
                .remainder()
                .iter()
                .zip(rc.remainder())
                .zip(vc.remainder());
            for ((l, r), v) in lc.zip(rc).zip(vc) {
                for j in 0..4 {
                    lanes.take(j, r[j] - l[j], v[j]);
                }
            }
            for ((l, r), &v) in rest {
                lanes.take(0, r - l, v);
            }
            // The knots first: `zip` would take a slot past the last one.
            for (k, e) in l.iter().step_by(STRIDE).zip(&mut slots) {
                *e = *k;
            }
        }
        if w.end == n - 1 {
            // The last value, beside a width that passes (the last width
            // was taken with the value before).
            lanes.take(0, thr, self.values[n - 1]);
        }
        // The summary's entries past the widths (the last knot's, when the
        // widths end on a stride).
        let past = w.start + (w.end - w.start).div_ceil(STRIDE) * STRIDE;
        for (e, k) in slots.zip(knots.get(past..).unwrap_or_default().iter().step_by(STRIDE)) {
            *e = *k;
        }
        let Lanes { least, most, zero } = lanes;
        let mut ok = least.iter().all(|&d| d >= thr) && zero.iter().sum::<f64>() == 0.0;
        if let Some(a) = self.alphas.get(w) {
            ok &= a
                .iter()
                .fold(true, |ok, a| ok & (ALPHA_MIN..=ALPHA_MAX).contains(a));
        }
        let m = most[0].max(most[1]).max(most[2].max(most[3]));
        ok.then_some(m)
    }
}

/// What [`Stretches::widths`] keeps of the widths and values it has read,
/// in four lanes.
struct Lanes {
    /// The least width.
    least: [f64; 4],
    /// The largest `|F|`.
    most: [f64; 4],
    /// The sum of `0 * w + 0 * F`: zero while every width and value is
    /// finite, NaN once one is not.
    zero: [f64; 4],
}

impl Lanes {
    /// Takes width `d` and value `v` into lane `j`.
    #[inline(always)]
    fn take(&mut self, j: usize, d: f64, v: f64) {
        self.least[j] = if d < self.least[j] { d } else { self.least[j] };
        let a = v.abs();
        self.most[j] = if a > self.most[j] { a } else { self.most[j] };
        self.zero[j] += d * 0.0 + v * 0.0;
    }
}

impl Spline {
    /// Builds the spline with `alpha = 1/2` on every interval.
    ///
    /// # Errors
    ///
    /// See [`Spline::with_alphas`].
    pub fn new(knots: &[f64], values: &[f64]) -> Result<Self, Error> {
        Self::build(knots, values, Alphas::default())
    }

    /// Builds the spline with the same `alpha` on every interval.
    ///
    /// # Errors
    ///
    /// See [`Spline::with_alphas`].
    pub fn with_alpha(knots: &[f64], values: &[f64], alpha: f64) -> Result<Self, Error> {
        Self::build(knots, values, Alphas::Uniform(alpha))
    }

    /// Builds the spline with `alphas[k]` on interval `k` (one fewer alphas than
    /// knots).
    ///
    /// # Errors
    ///
    /// - [`Error::TooFewPoints`] for fewer than 2 knots;
    /// - [`Error::LengthMismatch`] when `values` or `alphas` has the wrong length;
    /// - [`Error::NonFinite`] for a NaN or infinite knot, value or alpha;
    /// - [`Error::NotIncreasing`] when a knot does not exceed the one before;
    /// - [`Error::SpanOverflow`] when `knots[N-1] - knots[0]` overflows;
    /// - [`Error::IntervalTooSmall`] for an interval narrower than
    ///   [`MIN_RELATIVE_INTERVAL`] times the span;
    /// - [`Error::AlphaOutOfRange`] for an alpha outside `[ALPHA_MIN, ALPHA_MAX]`.
    pub fn with_alphas(knots: &[f64], values: &[f64], alphas: &[f64]) -> Result<Self, Error> {
        Self::build(knots, values, Alphas::PerInterval(alphas))
    }

    /// Builds the spline from any [`Alphas`] choice.
    ///
    /// # Errors
    ///
    /// See [`Spline::with_alphas`].
    pub fn build(knots: &[f64], values: &[f64], alphas: Alphas<'_>) -> Result<Self, Error> {
        let mut s = Self::empty();
        s.rebuild(knots, values, alphas)?;
        Ok(s)
    }

    /// A spline with nothing in it, to build into.
    pub(super) fn empty() -> Self {
        Spline {
            pieces: Pieces::default(),
            values: Vec::new(),
            alphas: Shape::default(),
            pre: 1.0,
            extrapolate: Extrapolate::default(),
        }
    }

    /// The spline through the points `(knots[k], values[k])`: the
    /// interpolating variant (`docs/method.md` §11). Its knot values are
    /// `values` (to rounding) and it touches every leg of its solved control
    /// polygon, whose values [`Spline::values`] returns; it is C1 like every
    /// spline here and passes through the data, but it is not confined to the
    /// hull of `values` (it swings far less than the interpolating cubic spline).
    /// Every capability of a spline works on it.
    ///
    /// # Errors
    ///
    /// As [`Spline::build`]; [`Error::Overflow`] when a solved control value
    /// leaves the range of a double.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Alphas, Spline};
    /// let x = [0.0, 1.0, 2.0, 3.0];
    /// let y = [0.0, 2.0, 1.0, 3.0];
    /// let s = Spline::through(&x, &y, Alphas::default())?;
    /// for (k, v) in s.knot_values().iter().enumerate() {
    ///     assert!((v - y[k]).abs() < 1e-14);
    /// }
    /// // It touches the legs of its control polygon, not of the data.
    /// let g = s.values();
    /// assert!((s.eval(0.5)? - (g[0] + g[1]) / 2.0).abs() < 1e-14);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn through(knots: &[f64], values: &[f64], alphas: Alphas<'_>) -> Result<Self, Error> {
        Self::through_fast(knots, values, alphas)
    }

    /// [`Spline::through`] step by step: validation that names each fault,
    /// the system assembled and factored ([`method::through_controls`]); the
    /// reference the fused sweep is tested against.
    pub(crate) fn through_checked(
        knots: &[f64],
        values: &[f64],
        alphas: Alphas<'_>,
    ) -> Result<Self, Error> {
        let (widths, resolved) = validate_step_by_step(knots, values, alphas)?;
        let g = method::through_controls(&widths, &resolved, values, 1, false).ok_or(
            Error::Overflow {
                what: "a solved control value",
            },
        )?;
        Self::build(knots, &g, alphas)
    }

    /// [`Spline::through`] for valid input: the control values from one
    /// forward and one backward sweep of `(T + K) d = K P` (§11) that form
    /// each row as they go, over overlapping chunks for large inputs
    /// ([`crate::fast::through`]), after the build's one-pass check; anything
    /// the check does not pass goes the step-by-step way, which names the
    /// fault.
    pub(super) fn through_fast(
        knots: &[f64],
        values: &[f64],
        alphas: Alphas<'_>,
    ) -> Result<Self, Error> {
        let mut s = Self::empty();
        let Some(max_abs) = quick_check(knots, values, alphas, s.pieces.parts_mut().summary) else {
            return Self::through_checked(knots, values, alphas);
        };
        let scale = scale_for_max(max_abs);
        let (given, uniform) = alphas.parts();
        let mut g = vec![0.0; knots.len()];
        let max_g = crate::fast::through::controls(knots, values, given, uniform, scale, &mut g)
            .ok_or(Error::Overflow {
                what: "a solved control value",
            })?;
        // The knots and alphas passed the check above and every control value
        // is finite: the build needs no second check (and the summary of the
        // knots is formed).
        s.fill(knots, &g, alphas, max_g);
        Ok(s)
    }

    /// Rebuilds this spline in place from new data, reusing its allocations:
    /// when the new data is not longer than the old, its pieces, knots and
    /// values are written over the old ones with no allocation of their own,
    /// which saves the page faults of fresh memory. Up to 65,536 knots nothing
    /// is allocated at all; from there the system is solved in chunks, whose
    /// plan and overlapping rows take a few small allocations (under 100 kB for
    /// a million knots). The extrapolation policy is kept. The result is the
    /// spline that [`Spline::build`] returns for the same arguments.
    ///
    /// # Errors
    ///
    /// As [`Spline::with_alphas`]; on error the spline is left unchanged.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Alphas, Spline};
    /// let mut s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// s.rebuild(&[0.0, 1.0, 2.0], &[0.0, 2.0, 0.0], Alphas::Uniform(0.5))?;
    /// assert!((s.eval(0.5)? - 1.0).abs() < 1e-15);
    /// assert!(s.rebuild(&[0.0, 0.0], &[1.0, 2.0], Alphas::default()).is_err());
    /// assert!((s.eval(0.5)? - 1.0).abs() < 1e-15);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn rebuild(
        &mut self,
        knots: &[f64],
        values: &[f64],
        alphas: Alphas<'_>,
    ) -> Result<(), Error> {
        let Some(max_abs) = quick_check(knots, values, alphas, self.pieces.parts_mut().summary)
        else {
            // Something is wrong (or on an edge the quick check does not
            // decide): the step-by-step validation names it. The summary of
            // the knots held first, which the check may have overwritten.
            self.pieces.knots_changed();
            let reference = Self::build_reference(knots, values, alphas)?;
            let policy = self.extrapolate;
            *self = reference.with_extrapolation(policy);
            return Ok(());
        };
        self.fill(knots, values, alphas, max_abs);
        Ok(())
    }

    /// The build after the check: `knots`, `values` and `alphas` are valid,
    /// `max_abs` is the largest `|values[k]|`, and the summary is that of
    /// `knots`.
    pub(super) fn fill(&mut self, knots: &[f64], values: &[f64], alphas: Alphas<'_>, max_abs: f64) {
        let n = knots.len();
        let scale = scale_for_max(max_abs);
        let span = knots[n - 1] - knots[0];
        match alphas {
            Alphas::Uniform(a) => self.alphas.set_uniform(a, n - 1),
            Alphas::PerInterval(a) => self.alphas.set_each(a),
        }
        let parts = self.pieces.parts_mut();
        sweep::build(
            knots,
            values,
            self.alphas.given(),
            self.alphas.uniform(),
            1.0 / scale,
            crate::fast::inverse_power_of_two(span),
            (parts.coefs, parts.knots, &mut self.values),
        );
        self.pieces.set_scales([scale].into_iter());
        self.pre = if span < TINY_SPAN {
            crate::fast::inverse_power_of_two(span)
        } else {
            1.0
        };
    }

    /// The straightforward construction: validate step by step, assemble and
    /// factor the system with [`OpenSystem`], solve, and form each piece with
    /// [`piece_coefs`]. The reference that the fused sweep is tested against.
    pub(crate) fn build_reference(
        knots: &[f64],
        values: &[f64],
        alphas: Alphas<'_>,
    ) -> Result<Self, Error> {
        let given = alphas;
        let (widths, alphas) = validate_step_by_step(knots, values, given)?;
        let scale = power_of_two_scale(values);
        let inv = 1.0 / scale;
        let f: Vec<f64> = values.iter().map(|v| v * inv).collect();
        let system = OpenSystem::new(&widths, &alphas);
        let mut d = Vec::new();
        system.solve(&f, &mut d);
        let coefs = (0..widths.len())
            .map(|k| Piece(piece_coefs(f[k], f[k + 1], d[k], d[k + 1], alphas[k])))
            .collect();
        let span = knots[knots.len() - 1] - knots[0];
        let mut shape = Shape::default();
        match given {
            Alphas::Uniform(a) => shape.set_uniform(a, alphas.len()),
            Alphas::PerInterval(a) => shape.set_each(a),
        }
        Ok(Spline {
            pieces: Pieces::from_parts(knots.to_vec(), coefs, vec![scale]),
            values: values.to_vec(),
            alphas: shape,
            pre: if span < TINY_SPAN {
                crate::fast::inverse_power_of_two(span)
            } else {
                1.0
            },
            extrapolate: Extrapolate::default(),
        })
    }
}
