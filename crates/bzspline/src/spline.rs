//! The spline `y = S(x)` of Stelia, Potapenko and Sirenko.
//!
//! The method itself (the rows of the paper's system (16), the pieces, the
//! reference assembly) is in `method.rs`, beside its equations;
//! `docs/method.md` derives them.
//!
//! # Conventions
//!
//! - Piece `k` answers on the half-open interval `[tau_k, tau_{k+1})`; the last
//!   piece also answers at `tau_{N-1}`. Values and first derivatives agree from
//!   both sides at a knot; second and third derivatives at an interior knot
//!   `tau_k` are those of piece `k` (the one to the right).
//! - Outside `[tau_0, tau_{N-1}]` the [`Extrapolate`] policy decides; the default
//!   is [`Extrapolate::Error`].

use crate::bezier::CubicBez;
use crate::curve::{Curve, CurveBuilder, Param};
use crate::error::{Error, Field};
use crate::fast::search::{Summary, STRIDE};
use crate::fast::{sweep, Piece};
use crate::flatten::{check_tol, steps, MAX_FLATTEN_VERTICES};
use crate::method::{self, piece_coefs, OpenSystem};
use crate::method::{power_of_two_scale, scale_for_max};
use crate::pieces::Pieces;
use crate::poly::{deriv_of, horner, quadratic_roots};
use crate::polyline::Polyline;
use crate::traits::{check_out, Arclen, BBox, BezierPieces, Bounds, Flatten, ParamCurve};
use crate::validate::{check_finite, resolve_alphas, validate_knots};
mod antiderivative;
mod shape;
pub use antiderivative::Antiderivative;
use shape::Shape;

pub use crate::validate::{Alphas, ALPHA_MAX, ALPHA_MIN, DEFAULT_ALPHA, MIN_RELATIVE_INTERVAL};

/// What evaluation does outside `[tau_0, tau_{N-1}]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Extrapolate {
    /// Return [`Error::OutOfDomain`]. The default.
    #[default]
    Error,
    /// Hold the end value: `S(x) = F_0` left of the span, `F_{N-1}` right of it,
    /// and every derivative is 0 there.
    Clamp,
    /// Continue the end pieces' cubics.
    Extend,
}

/// Kind of a critical point of `S`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExtremumKind {
    /// `S'' > 0`: a local minimum.
    Minimum,
    /// `S'' < 0`: a local maximum.
    Maximum,
    /// `S'' = 0`: a stationary point that may be neither.
    Stationary,
}

/// A point inside the span where `S'(x) = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extremum {
    /// Abscissa.
    pub x: f64,
    /// `S(x)`.
    pub y: f64,
    /// Minimum, maximum or neither.
    pub kind: ExtremumKind,
}

/// The paper's spline of a function `y(x)`: immutable once built (or rebuilt in
/// place by [`Spline::rebuild`], which reuses its allocations).
///
/// # Memory
///
/// A spline of `N` knots holds the knots and the control values (8 bytes a
/// point each, for [`Spline::knots`] and [`Spline::values`]), the four
/// coefficients of each piece (32 bytes) and every 16th knot for the search:
/// 48.5 bytes a point, see [`Spline::heap_bytes`]. Alphas given one per
/// interval add 8 bytes a point; one alpha for all adds them only when
/// [`Spline::alphas`] is first called. The first long batch of queries in
/// random order adds an index of those knots (a quarter of a byte a point),
/// kept until the next build.
///
/// # Examples
///
/// ```
/// use bzspline::Spline;
/// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
/// // The curve touches the leg (0,0)-(1,1) at its middle, x = 0.5, y = 0.5.
/// assert!((s.eval(0.5)? - 0.5).abs() < 1e-15);
/// assert!((s.deriv(0.5, 1)? - 1.0).abs() < 1e-15);
/// // It starts and ends at the end points and stays below the polygon's top.
/// assert_eq!(s.eval(0.0)?, 0.0);
/// assert!(s.eval(1.0)? < 1.0);
/// # Ok::<(), bzspline::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Spline {
    /// The knots, the pieces in `t = (x - tau_k) / h_k` and their one scale
    /// (a power of two near the largest value); piece `k`'s first
    /// coefficient is the scaled knot value `phi_k / scale`.
    pieces: Pieces,
    values: Vec<f64>,
    alphas: Shape,
    /// A power of two that keeps `1 / (h pre)` finite: 1 unless the whole span
    /// is below [`TINY_SPAN`], where `1 / h` could overflow.
    pre: f64,
    extrapolate: Extrapolate,
}

/// Spans below this get a `pre` factor other than 1: every width is then at
/// least `1e-270 * f64::EPSILON`, whose reciprocal is finite.
const TINY_SPAN: f64 = 1e-270;

/// Every check of a spline's input, one at a time so that the first fault is
/// named: the knots (giving the widths), the values' length and finiteness, the
/// alphas (giving one per interval).
fn validate_step_by_step(
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

/// Every check of [`Spline::build`] in one branch-free pass: `Some(max |F|)`
/// when the input is valid, `None` when something is wrong (the step-by-step
/// validation then finds what). A finite positive span and widths that are
/// positive and at least `span * MIN_RELATIVE_INTERVAL` imply finite,
/// strictly increasing knots.
///
/// As it reads the knots it puts every [`STRIDE`]-th into `summary`
/// (see [`Summary`]), which then needs no pass over them of its
/// own; when it returns `None` the summary may be partly written.
fn quick_check(
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
    let thr = span * MIN_RELATIVE_INTERVAL;
    // Widths in four lanes, so that the loop vectorises; a stretch of
    // `STRIDE` knots at a time, whose first goes into the summary.
    let every = &mut summary.every;
    every.clear();
    every.reserve(n.div_ceil(STRIDE));
    let mut lanes = [true; 4];
    let (left, right) = (&knots[..n - 1], &knots[1..]);
    let (lc, rc) = (left.chunks_exact(STRIDE), right.chunks_exact(STRIDE));
    let (lr, rr) = (lc.remainder(), rc.remainder());
    for (l, r) in lc.zip(rc) {
        every.push(l[0]);
        for j in 0..STRIDE {
            let d = r[j] - l[j];
            lanes[j % 4] &= (d >= thr) & (d > 0.0);
        }
    }
    for (l, r) in lr.iter().zip(rr) {
        let d = r - l;
        lanes[0] &= (d >= thr) & (d > 0.0);
    }
    // The stretches the loop did not reach (the last knot's included).
    every.extend(knots[(n - 1) / STRIDE * STRIDE..].iter().step_by(STRIDE));
    let mut ok = lanes.iter().all(|&b| b);
    // Four running maxima and finiteness flags, so that the loop vectorises.
    let mut mx = [0.0f64; 4];
    let mut fin = [true; 4];
    let chunks = values.chunks_exact(4);
    let rest = chunks.remainder();
    for c in chunks {
        for j in 0..4 {
            let a = c[j].abs();
            mx[j] = if a > mx[j] { a } else { mx[j] };
            fin[j] &= c[j].is_finite();
        }
    }
    for &v in rest {
        let a = v.abs();
        mx[0] = if a > mx[0] { a } else { mx[0] };
        fin[0] &= v.is_finite();
    }
    ok &= fin.iter().all(|&f| f);
    match alphas {
        Alphas::Uniform(a) => ok &= (ALPHA_MIN..=ALPHA_MAX).contains(&a),
        Alphas::PerInterval(a) => {
            ok &= a.len() == n - 1;
            ok &= a
                .iter()
                .fold(true, |ok, a| ok & (ALPHA_MIN..=ALPHA_MAX).contains(a));
        }
    }
    let m = mx[0].max(mx[1]).max(mx[2].max(mx[3]));
    if ok {
        summary.formed();
    }
    ok.then_some(m)
}

/// Where a query falls.
enum Locus {
    /// Piece `k` at local parameter `t`, with `1 / (h_k pre)`.
    Piece(usize, f64, f64),
    /// The last knot, where the value is the last control value exactly.
    End,
    /// Clamped to the end value of knot `k`.
    Held(usize),
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
    fn empty() -> Self {
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

    /// [`Spline::through`] for valid input, in one forward and one backward
    /// sweep of `(T + K) d = K P` (§11) that forms each row as it goes, after
    /// the build's one-pass check; anything the check does not pass goes the
    /// step-by-step way, which names the fault.
    fn through_fast(knots: &[f64], values: &[f64], alphas: Alphas<'_>) -> Result<Self, Error> {
        let mut s = Self::empty();
        let Some(max_abs) = quick_check(knots, values, alphas, s.pieces.parts_mut().summary) else {
            return Self::through_checked(knots, values, alphas);
        };
        let n = knots.len();
        let scale = scale_for_max(max_abs);
        let inv = 1.0 / scale;
        let f = |k: usize| values[k] * inv;
        let uniform = match alphas {
            Alphas::Uniform(a) => Some(method::alpha_terms(a)),
            Alphas::PerInterval(_) => None,
        };
        let terms = |k: usize| match (uniform, alphas) {
            (Some(t), _) => t,
            (None, Alphas::PerInterval(a)) => method::alpha_terms(a[k]),
            (None, Alphas::Uniform(a)) => method::alpha_terms(a),
        };
        // Forward: c'_k and r'_k of the Thomas sweep, stored in `c` and `g`.
        let mut c = vec![0.0; n];
        let mut g = vec![0.0; n];
        let (mut cp, mut rp) = (0.0, 0.0);
        for k in 1..n.saturating_sub(1) {
            let (hl, hr) = (knots[k] - knots[k - 1], knots[k + 1] - knots[k]);
            let (p, q) = method::neighbour_weights(hl, hr);
            let [al, b1, _, _] = terms(k - 1);
            let [_, _, b2, cr] = terms(k);
            let (lo, di, up) = method::through_row(p, q, al, b1, b2, cr);
            let rhs = q * (f(k + 1) - f(k)) - p * (f(k) - f(k - 1));
            let m = di - lo * cp;
            cp = up / m;
            rp = (rhs - lo * rp) / m;
            c[k] = cp;
            g[k] = rp;
        }
        // Backward: d_k = r'_k - c'_k d_{k+1}, then G_k = P_k - d_k.
        let mut next = 0.0;
        g[n - 1] = values[n - 1];
        g[0] = values[0];
        let mut max_g = values[0].abs().max(values[n - 1].abs());
        for k in (1..n.saturating_sub(1)).rev() {
            let d = g[k] - c[k] * next;
            next = d;
            g[k] = (f(k) - d) * scale;
            if !g[k].is_finite() {
                return Err(Error::Overflow {
                    what: "a solved control value",
                });
            }
            max_g = max_g.max(g[k].abs());
        }
        // The knots and alphas passed the check above and every control value
        // is finite: the build needs no second check (and the summary of the
        // knots is formed).
        s.fill(knots, &g, alphas, max_g);
        Ok(s)
    }

    /// Rebuilds this spline in place from new data, reusing its allocations
    /// (no allocation at all when the new data is not longer than the old). The
    /// extrapolation policy is kept. The result is the spline that
    /// [`Spline::build`] returns for the same arguments.
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
    fn fill(&mut self, knots: &[f64], values: &[f64], alphas: Alphas<'_>, max_abs: f64) {
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

    /// Bytes of heap memory the spline holds (the capacities of its vectors):
    /// 48.5 bytes a point when built by [`Spline::build`] with one alpha (56.5
    /// with one per interval or once [`Spline::alphas`] has been called),
    /// 0.25 more once a batch of random-order queries has formed the search
    /// index.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.values.capacity() * core::mem::size_of::<f64>()
            + self.alphas.heap_bytes()
            + self.pieces.heap_bytes()
    }

    /// Returns the spline with another extrapolation policy.
    #[must_use]
    pub fn with_extrapolation(mut self, policy: Extrapolate) -> Self {
        self.extrapolate = policy;
        self
    }

    /// The extrapolation policy.
    #[must_use]
    pub fn extrapolation(&self) -> Extrapolate {
        self.extrapolate
    }

    /// The knots `tau`.
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        self.pieces.knots()
    }

    /// The control values `F`.
    #[must_use]
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The shape parameters, one per interval.
    #[must_use]
    pub fn alphas(&self) -> &[f64] {
        self.alphas.as_slice()
    }

    /// Number of pieces (intervals), one fewer than knots.
    #[must_use]
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// Always false: a spline has at least one piece.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.pieces.coefs().is_empty()
    }

    /// The domain `[tau_0, tau_{N-1}]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.pieces.domain()
    }

    /// The knot values `phi_k = S(tau_k)`; `phi_0 = F_0` and `phi_{N-1} = F_{N-1}`.
    #[must_use]
    pub fn knot_values(&self) -> Vec<f64> {
        // The end values are the end control values by construction (d = 0).
        let mut v = Vec::with_capacity(self.pieces.knots().len());
        v.push(self.values[0]);
        v.extend(
            self.pieces
                .coefs()
                .iter()
                .skip(1)
                .map(|c| c.0[0] * self.scale()),
        );
        v.push(self.values[self.len()]);
        v
    }

    /// The points `(x_k, f_k)` where the spline touches leg `k` of the control
    /// polygon: `x_k = tau_{k+1} - alpha_k h_k`,
    /// `f_k = alpha_k F_k + (1 - alpha_k) F_{k+1}` (docs/method.md §9, misprint 1).
    #[must_use]
    pub fn tangent_points(&self) -> Vec<(f64, f64)> {
        let inv = 1.0 / self.scale();
        (0..self.len())
            .map(|k| {
                let a = self.alphas.get(k);
                let h = self.pieces.width(k);
                let x = self.pieces.knots()[k + 1] - a * h;
                let f = (a * (self.values[k] * inv) + (1.0 - a) * (self.values[k + 1] * inv))
                    * self.scale();
                (x, f)
            })
            .collect()
    }

    /// The slope `s_k = (F_{k+1} - F_k) / h_k` of leg `k`.
    #[must_use]
    pub fn leg_slope(&self, k: usize) -> Option<f64> {
        let h = self.pieces.knots().get(k + 1)? - self.pieces.knots()[k];
        let inv = 1.0 / self.scale();
        Some((self.values[k + 1] * inv - self.values[k] * inv) * self.scale() / h)
    }

    /// Piece `k` as a cubic Bezier segment in the plane: control points at
    /// abscissas `tau_k + j h_k / 3` and the ordinates of `docs/method.md` §3. The two
    /// inner ordinates lie outside the range of the values and can be infinite
    /// when the values come near `f64::MAX`.
    #[must_use]
    pub fn segment(&self, k: usize) -> Option<CubicBez<2>> {
        let c = &self.pieces.coefs().get(k)?.0;
        let (x0, x1) = (self.pieces.knots()[k], self.pieces.knots()[k + 1]);
        let h = x1 - x0;
        let s = self.scale();
        let b0 = c[0];
        let b3 = self.phi(k + 1);
        let s0 = c[1];
        let s1 = c[1] + 2.0 * c[2] + 3.0 * c[3];
        let y0 = if k == 0 { self.values[0] } else { b0 * s };
        let y3 = if k + 1 == self.len() {
            self.values[k + 1]
        } else {
            b3 * s
        };
        Some(CubicBez::new([
            [x0, y0],
            [x0 + h / 3.0, (b0 + s0 / 3.0) * s],
            [x1 - h / 3.0, (b3 - s1 / 3.0) * s],
            [x1, y3],
        ]))
    }

    /// Every piece as a cubic Bezier segment, see [`Spline::segment`].
    #[must_use]
    pub fn segments(&self) -> Vec<CubicBez<2>> {
        (0..self.len()).filter_map(|k| self.segment(k)).collect()
    }

    /// Coefficients `[c0, c1, c2, c3]` of piece `k` in the local variable
    /// `x - tau_k`: `S(x) = c0 + c1 (x - tau_k) + c2 (x - tau_k)^2 + c3 (x - tau_k)^3`
    /// (scipy's `PPoly` convention, lowest order first).
    ///
    /// On very narrow intervals the higher coefficients can overflow; the spline
    /// itself does not use this form.
    #[must_use]
    pub fn power_coefficients(&self, k: usize) -> Option<[f64; 4]> {
        let c = &self.pieces.coefs().get(k)?.0;
        let h = self.pieces.width(k);
        let s = self.scale();
        Some([
            c[0] * s,
            c[1] * s / h,
            c[2] * s / h / h,
            c[3] * s / h / h / h,
        ])
    }

    /// Coefficients of piece `k` in `t = (x - tau_k) / h_k`, `t` in `[0, 1]`.
    #[must_use]
    pub fn unit_coefficients(&self, k: usize) -> Option<[f64; 4]> {
        let c = &self.pieces.coefs().get(k)?.0;
        Some(c.map(|v| v * self.scale()))
    }

    /// Index of the piece that answers at `x` inside the domain (see the module
    /// docs for the convention at knots); queries outside map to the end pieces.
    #[must_use]
    pub fn piece_index(&self, x: f64) -> usize {
        self.pieces.locate(x)
    }

    /// The one scale of the values (see [`Pieces`]).
    #[inline]
    pub(crate) fn scale(&self) -> f64 {
        self.pieces.unit()
    }

    /// The scaled knot value `phi_k / scale`.
    fn phi(&self, k: usize) -> f64 {
        match self.pieces.coefs().get(k) {
            Some(c) => c.0[0],
            None => self.values[self.len()] / self.scale(),
        }
    }

    fn locate_in(&self, x: f64, k: usize) -> Result<Locus, Error> {
        let (a, b) = self.domain();
        if !(a..=b).contains(&x) {
            if x.is_nan() {
                return Err(Error::NonFinite {
                    field: Field::Query,
                    index: 0,
                    value: x,
                });
            }
            match self.extrapolate {
                Extrapolate::Error => return Err(Error::OutOfDomain { x, min: a, max: b }),
                Extrapolate::Clamp => {
                    return Ok(Locus::Held(if x < a { 0 } else { self.len() }));
                }
                Extrapolate::Extend => {}
            }
        }
        if x == b {
            return Ok(Locus::End);
        }
        // The batch evaluators compute t and 1/h the same way (pre = 1 there).
        let inv = 1.0 / (self.pieces.width(k) * self.pre);
        let t = ((x - self.pieces.knots()[k]) * self.pre) * inv;
        Ok(Locus::Piece(k, t, inv))
    }

    fn eval_locus(&self, locus: Locus, order: u32) -> Result<f64, Error> {
        match locus {
            Locus::Held(k) => Ok(if order == 0 { self.values[k] } else { 0.0 }),
            Locus::End if order == 0 => Ok(self.values[self.len()]),
            Locus::End => {
                let k = self.len() - 1;
                let inv = 1.0 / (self.pieces.width(k) * self.pre);
                self.eval_locus(Locus::Piece(k, 1.0, inv), order)
            }
            Locus::Piece(0, t, _) if order == 0 && t == 0.0 => {
                // The first control value itself: scaled by the largest value
                // it may have underflowed to 0.
                Ok(self.values[0])
            }
            Locus::Piece(k, t, inv) => {
                let mut v = deriv_of(&self.pieces.coefs()[k].0, t, order) * self.scale();
                if order == 0 && v.is_infinite() && (0.0..=1.0).contains(&t) {
                    // Rounding above f64::MAX inside the hull: the true value is
                    // within the control values, which are finite.
                    v = f64::MAX.copysign(v);
                }
                for _ in 0..order.min(4) {
                    v = v * inv * self.pre;
                }
                if !v.is_finite() {
                    return Err(Error::Overflow {
                        what: if order == 0 {
                            "the extrapolated value"
                        } else {
                            "the derivative"
                        },
                    });
                }
                Ok(v)
            }
        }
    }

    /// `S(x)`.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a NaN `x`; [`Error::OutOfDomain`] outside the
    /// domain under [`Extrapolate::Error`]; [`Error::Overflow`] when an
    /// extrapolated value overflows.
    pub fn eval(&self, x: f64) -> Result<f64, Error> {
        self.deriv(x, 0)
    }

    /// The derivative of order `order` at `x` (0 is the value; above 3 it is 0).
    ///
    /// # Errors
    ///
    /// As [`Spline::eval`]; [`Error::Overflow`] also when the derivative exceeds
    /// the range of a double (on an extremely narrow interval).
    pub fn deriv(&self, x: f64, order: u32) -> Result<f64, Error> {
        let k = self.piece_index(x);
        let locus = self.locate_in(x, k)?;
        self.eval_locus(locus, order)
    }

    /// Value and derivatives of orders 1, 2 and 3 at `x`.
    ///
    /// # Errors
    ///
    /// As [`Spline::eval`].
    pub fn eval_all(&self, x: f64) -> Result<[f64; 4], Error> {
        let k = self.piece_index(x);
        let mut out = [0.0; 4];
        for (order, o) in out.iter_mut().enumerate() {
            let locus = self.locate_in(x, k)?;
            *o = self.eval_locus(locus, order as u32)?;
        }
        Ok(out)
    }

    /// Evaluates the derivative of order `order` (0 for values) at every `xs[i]`
    /// into `out[i]`, with the same result as [`Spline::deriv`] at each point.
    /// Queries in increasing order are the fastest (one pass over the pieces);
    /// any order is accepted.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] when `out.len() != xs.len()`; otherwise as
    /// [`Spline::eval`], with the index of the failing query in
    /// [`Error::NonFinite`]. On error the contents of `out` are unspecified.
    pub fn deriv_many(&self, xs: &[f64], order: u32, out: &mut [f64]) -> Result<(), Error> {
        if out.len() != xs.len() {
            return Err(Error::LengthMismatch {
                field: Field::Query,
                expected: xs.len(),
                found: out.len(),
            });
        }
        let slow = |i: usize, x: f64, o: &mut f64| -> Result<(), Error> {
            *o = self.deriv(x, order).map_err(|e| e.at_query(i))?;
            Ok(())
        };
        // The batch kernel sums the coefficients at tau_0 too; when the first
        // value underflowed in scaling (values spanning some 600 decades) only
        // the one-by-one path returns it exactly.
        let first_exact = self
            .pieces
            .coefs()
            .first()
            .is_none_or(|c| c.0[0] * self.scale() == self.values[0]);
        if self.pre != 1.0 || order > 3 || (order == 0 && !first_exact) {
            for (i, (&x, o)) in xs.iter().zip(out.iter_mut()).enumerate() {
                slow(i, x, o)?;
            }
            return Ok(());
        }
        let batch = self.pieces.batch();
        match order {
            0 => batch.run::<0, _>(xs, out, slow),
            1 => batch.run::<1, _>(xs, out, slow),
            2 => batch.run::<2, _>(xs, out, slow),
            _ => batch.run::<3, _>(xs, out, slow),
        }
    }

    /// [`Spline::deriv_many`] split over rayon's thread pool: the same results,
    /// each worker walking its own contiguous share of the queries.
    ///
    /// # Errors
    ///
    /// As [`Spline::deriv_many`] (the first failing query by index).
    #[cfg(feature = "rayon")]
    pub fn par_deriv_many(&self, xs: &[f64], order: u32, out: &mut [f64]) -> Result<(), Error> {
        use rayon::prelude::*;
        if out.len() != xs.len() {
            return Err(Error::LengthMismatch {
                field: Field::Query,
                expected: xs.len(),
                found: out.len(),
            });
        }
        // A few chunks per thread for balance, none so small that the start-up
        // search dominates.
        let chunk = (xs.len() / (4 * rayon::current_num_threads()).max(1)).max(1 << 14);
        let failed = xs
            .par_chunks(chunk)
            .zip(out.par_chunks_mut(chunk))
            .map(|(x, o)| self.deriv_many(x, order, o).is_err())
            .reduce(|| false, |a, b| a | b);
        if failed {
            // Rerun in order, so that the error is the one with the lowest index.
            return self.deriv_many(xs, order, out);
        }
        Ok(())
    }

    /// `S(xs[i])` into `out[i]` in parallel; see [`Spline::par_deriv_many`].
    ///
    /// # Errors
    ///
    /// As [`Spline::deriv_many`].
    #[cfg(feature = "rayon")]
    pub fn par_eval_many(&self, xs: &[f64], out: &mut [f64]) -> Result<(), Error> {
        self.par_deriv_many(xs, 0, out)
    }

    /// `S(xs[i])` into `out[i]`; see [`Spline::deriv_many`].
    ///
    /// # Errors
    ///
    /// As [`Spline::deriv_many`].
    pub fn eval_many(&self, xs: &[f64], out: &mut [f64]) -> Result<(), Error> {
        self.deriv_many(xs, 0, out)
    }

    /// Integral of `S` over `[a, b]` (negative when `b < a`), exact up to rounding.
    /// Parts outside the domain follow the extrapolation policy.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a non-finite bound; [`Error::OutOfDomain`] for a
    /// bound outside the domain under [`Extrapolate::Error`]; [`Error::Overflow`]
    /// when the result exceeds the range of a double.
    pub fn integral(&self, a: f64, b: f64) -> Result<f64, Error> {
        for (i, &v) in [a, b].iter().enumerate() {
            if !v.is_finite() {
                return Err(Error::NonFinite {
                    field: Field::Query,
                    index: i,
                    value: v,
                });
            }
        }
        if b < a {
            return self.integral(b, a).map(|v| -v);
        }
        let (lo, hi) = self.domain();
        if self.extrapolate == Extrapolate::Error && (a < lo || b > hi) {
            let x = if a < lo { a } else { b };
            return Err(Error::OutOfDomain {
                x,
                min: lo,
                max: hi,
            });
        }
        let mut total = 0.0;
        // Parts outside the domain.
        if a < lo {
            let end = b.min(lo);
            total += match self.extrapolate {
                Extrapolate::Clamp => (end - a) * (self.values[0] / self.scale()),
                _ => self.piece_integral(0, a, end),
            };
        }
        if b > hi {
            let start = a.max(hi);
            total += match self.extrapolate {
                Extrapolate::Clamp => (b - start) * (self.values[self.len()] / self.scale()),
                _ => self.piece_integral(self.len() - 1, start, b),
            };
        }
        let (ca, cb) = (a.max(lo), b.min(hi));
        if ca < cb {
            let (ka, kb) = (self.piece_index(ca), self.piece_index(cb));
            for k in ka..=kb {
                let x0 = ca.max(self.pieces.knots()[k]);
                let x1 = cb.min(self.pieces.knots()[k + 1]);
                if x0 < x1 {
                    total += self.piece_integral(k, x0, x1);
                }
            }
        }
        let v = total * self.scale();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Error::Overflow {
                what: "the integral",
            })
        }
    }

    /// Integral of piece `k`'s cubic (scaled) from `x0` to `x1`.
    pub(crate) fn piece_integral(&self, k: usize, x0: f64, x1: f64) -> f64 {
        let c = &self.pieces.coefs()[k].0;
        let h = self.pieces.width(k);
        let prim = |t: f64| t * (c[0] + t * (c[1] / 2.0 + t * (c[2] / 3.0 + t * c[3] / 4.0)));
        let t0 = (x0 - self.pieces.knots()[k]) / h;
        let t1 = (x1 - self.pieces.knots()[k]) / h;
        (prim(t1) - prim(t0)) * h
    }

    /// The points inside the domain where `S' = 0`, in increasing `x`: the real
    /// roots of each piece's derivative, classified by the sign of `S''`.
    #[must_use]
    pub fn extrema(&self) -> Vec<Extremum> {
        let mut out = Vec::new();
        for (k, Piece(c)) in self.pieces.coefs().iter().enumerate() {
            let h = self.pieces.width(k);
            let mut roots = quadratic_roots(3.0 * c[3], 2.0 * c[2], c[1]);
            roots.sort_by(f64::total_cmp);
            for t in roots {
                // Knots belong to the piece on their right; the domain's ends are
                // not interior points.
                let inside = if k == 0 {
                    t > 0.0 && t < 1.0
                } else {
                    (0.0..1.0).contains(&t)
                };
                if !inside {
                    continue;
                }
                let x = (self.pieces.knots()[k] + t * h).min(self.pieces.knots()[k + 1]);
                // Inside the hull the true value is finite; rounding above
                // f64::MAX is held at it, as in `eval`.
                let y = (horner(c, t) * self.scale()).clamp(-f64::MAX, f64::MAX);
                let curv = deriv_of(c, t, 2);
                let kind = if curv > 0.0 {
                    ExtremumKind::Minimum
                } else if curv < 0.0 {
                    ExtremumKind::Maximum
                } else {
                    ExtremumKind::Stationary
                };
                if out.last().is_some_and(|e: &Extremum| e.x >= x) {
                    continue;
                }
                out.push(Extremum { x, y, kind });
            }
        }
        out
    }

    /// The graph `x -> (x, S(x))` as a planar [`Curve`] with the knots as its
    /// parameters and the spline's alphas: each coordinate is the method's
    /// spline on the same knots, and the spline of the linear data `x` is `x`
    /// itself (to rounding), so the curve is this spline's graph. What a
    /// curve can do (arc length, resampling, the nearest point) then applies
    /// to the graph.
    ///
    /// # Errors
    ///
    /// None for a spline built by this crate; the curve builder's errors
    /// otherwise.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Spline, DEFAULT_ACCURACY};
    /// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// let g = s.graph()?;
    /// let p = g.eval(0.5)?;
    /// assert!((p[0] - 0.5).abs() < 1e-15 && (p[1] - s.eval(0.5)?).abs() < 1e-15);
    /// assert!(g.arclen(DEFAULT_ACCURACY)? > 2.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn graph(&self) -> Result<Curve, Error> {
        let flat: Vec<f64> = self
            .knots()
            .iter()
            .zip(self.values())
            .flat_map(|(&x, &y)| [x, y])
            .collect();
        CurveBuilder::new(&flat, 2)
            .param(Param::Given(self.knots().to_vec()))
            .alphas(self.alphas())
            .build()
    }

    /// The smallest and largest value of `S` on its domain, as `(x, y)` pairs.
    #[must_use]
    pub fn range(&self) -> ((f64, f64), (f64, f64)) {
        let (a, b) = self.domain();
        let ends = [(a, self.values[0]), (b, self.values[self.len()])];
        let mut lo = ends[0];
        let mut hi = ends[0];
        for (x, y) in ends
            .into_iter()
            .chain(self.extrema().into_iter().map(|e| (e.x, e.y)))
        {
            if y < lo.1 {
                lo = (x, y);
            }
            if y > hi.1 {
                hi = (x, y);
            }
        }
        (lo, hi)
    }
}

/// The graph `x -> (x, S(x))`, under the spline's extrapolation policy.
impl ParamCurve for Spline {
    fn dim(&self) -> usize {
        2
    }
    fn domain(&self) -> (f64, f64) {
        Spline::domain(self)
    }
    fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, 2)?;
        out[1] = self.eval(t)?;
        out[0] = t;
        Ok(())
    }
    fn deriv_into(&self, t: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, 2)?;
        out[1] = self.deriv(t, order)?;
        out[0] = match order {
            0 => t,
            1 => 1.0,
            _ => 0.0,
        };
        Ok(())
    }
}

impl Spline {
    /// The graph `(x, S(x))` flattened to a polyline within `tol` of it; see
    /// [`Curve::flatten`]. Vertices' parameters are their abscissas.
    ///
    /// # Errors
    ///
    /// As [`Curve::flatten`].
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Spline;
    /// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// let p = s.flatten(1e-4)?;
    /// assert_eq!(p.point(0), Some(&[0.0, 0.0][..]));
    /// assert_eq!(p.point(p.len() - 1), Some(&[2.0, 0.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        check_tol(tol)?;
        let knots = self.knots();
        let mut coords = Vec::new();
        let mut params = Vec::new();
        for k in 0..self.len() {
            let c = self.unit_coefficients(k).unwrap_or([0.0; 4]);
            let accel = (2.0 * c[2]).abs().max((2.0 * c[2] + 6.0 * c[3]).abs());
            let m = steps(accel, tol)?;
            if params.len().saturating_add(m) > MAX_FLATTEN_VERTICES {
                return Err(Error::TooManyVertices { tolerance: tol });
            }
            let h = knots[k + 1] - knots[k];
            for j in usize::from(k > 0)..=m {
                let x = if j == m {
                    knots[k + 1]
                } else {
                    knots[k] + (j as f64 / m as f64) * h
                };
                let y = self.eval(x)?;
                coords.push(x);
                coords.push(y);
                params.push(x);
            }
        }
        Ok(Polyline::new(2, coords, params))
    }
}

/// The arc length of the graph, measured on [`Spline::graph`]; parameters
/// are abscissas.
impl Arclen for Spline {
    fn arclen(&self, accuracy: f64) -> Result<f64, Error> {
        self.graph()?.arclen(accuracy)
    }
    fn params_at_lengths(&self, lengths: &[f64], accuracy: f64) -> Result<Vec<f64>, Error> {
        self.graph()?.params_at_lengths(lengths, accuracy)
    }
}

impl BezierPieces for Spline {
    fn piece_count(&self) -> usize {
        self.len()
    }
    fn piece_into(&self, k: usize, out: &mut [f64]) -> bool {
        match self.segment(k) {
            Some(s) if out.len() == 8 => {
                out.copy_from_slice(s.p.as_flattened());
                true
            }
            _ => false,
        }
    }
}

impl Flatten for Spline {
    fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        Spline::flatten(self, tol)
    }
}

impl Bounds for Spline {
    fn bbox(&self) -> BBox {
        let (a, b) = self.domain();
        let ((_, lo), (_, hi)) = self.range();
        BBox {
            min: vec![a, lo],
            max: vec![b, hi],
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn the_fused_through_sweep_matches_the_reference() {
        let mut rng = Rng(0x7e120);
        for case in 0..300 {
            let n = 2 + (rng.next() * 40.0) as usize;
            let mut x = vec![rng.next() * 10.0 - 5.0];
            for _ in 1..n {
                let w = 10f64.powf(rng.next() * 4.0 - 2.0);
                x.push(x[x.len() - 1] + w);
            }
            let big = 10f64.powi((rng.next() * 600.0) as i32 - 300);
            let y: Vec<f64> = (0..n).map(|_| (rng.next() * 2.0 - 1.0) * big).collect();
            let a: Vec<f64> = (0..n - 1)
                .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
                .collect();
            for alphas in [Alphas::Uniform(a[0]), Alphas::PerInterval(&a)] {
                let fast = Spline::through(&x, &y, alphas).unwrap();
                let slow = Spline::through_checked(&x, &y, alphas).unwrap();
                let scale = fast
                    .values()
                    .iter()
                    .fold(0.0f64, |m, v| m.max(v.abs()))
                    .max(f64::MIN_POSITIVE);
                for (k, (u, v)) in fast.values().iter().zip(slow.values()).enumerate() {
                    assert!(
                        (u - v).abs() <= 1e-13 * scale,
                        "case {case}, G_{k}: fused {u}, reference {v}"
                    );
                }
            }
        }
        // Bad input goes the step-by-step way and is named alike.
        let bad = ([0.0, 1.0, 1.0], [0.0, 1.0, 2.0]);
        assert_eq!(
            Spline::through(&bad.0, &bad.1, Alphas::default()).unwrap_err(),
            Spline::through_checked(&bad.0, &bad.1, Alphas::default()).unwrap_err()
        );
    }

    const EX1_X: [f64; 11] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0];
    const EX1_F: [f64; 11] = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
    }

    #[test]
    fn alpha_bounds_accept_the_decimal_literals() {
        assert_eq!(ALPHA_MIN, 1.0 / 3.0);
        const { assert!(ALPHA_MAX > 2.0 / 3.0) };
        assert_eq!(ALPHA_MAX, "0.6666666666666667".parse::<f64>().unwrap());
        for a in [ALPHA_MIN, ALPHA_MAX, 1.0 / 3.0, 2.0 / 3.0] {
            assert!(Spline::with_alpha(&EX1_X, &EX1_F, a).is_ok(), "alpha {a}");
        }
        for a in [
            f64::from_bits(ALPHA_MIN.to_bits() - 1),
            f64::from_bits(ALPHA_MAX.to_bits() + 1),
        ] {
            assert!(
                matches!(
                    Spline::with_alpha(&EX1_X, &EX1_F, a),
                    Err(Error::AlphaOutOfRange { interval: 0, .. })
                ),
                "alpha {a} should be refused"
            );
        }
    }

    #[test]
    fn example_1_touches_every_leg_and_is_c1() {
        for alpha in [ALPHA_MIN, 0.4, 0.5, 0.6, ALPHA_MAX] {
            let s = Spline::with_alpha(&EX1_X, &EX1_F, alpha).unwrap();
            for (k, (x, f)) in s.tangent_points().into_iter().enumerate() {
                let c = &s.pieces.coefs()[k].0;
                let t = (x - EX1_X[k]) / (EX1_X[k + 1] - EX1_X[k]);
                let y = horner(c, t) * s.scale();
                let dy = deriv_of(c, t, 1) * s.scale();
                assert!(close(y, f, 1e-13), "S(x_{k}): want {f}, got {y}");
                let slope = s.leg_slope(k).unwrap();
                assert!(close(dy, slope, 1e-13), "S'(x_{k}): want {slope}, got {dy}");
            }
            for k in 1..s.len() {
                let l = &s.pieces.coefs()[k - 1].0;
                let r = &s.pieces.coefs()[k].0;
                assert!(close(horner(l, 1.0), horner(r, 0.0), 1e-13));
                assert!(close(deriv_of(l, 1.0, 1), deriv_of(r, 0.0, 1), 1e-13));
            }
            assert_eq!(s.eval(1.0).unwrap(), 1.0);
            assert_eq!(s.eval(11.0).unwrap(), 1.5);
        }
    }

    #[test]
    fn two_and_three_knots() {
        let s = Spline::new(&[0.0, 2.0], &[1.0, 5.0]).unwrap();
        assert_eq!(s.knot_values(), vec![1.0, 5.0]);
        assert!(close(s.eval(1.0).unwrap(), 3.0, 1e-15));
        assert!(close(s.deriv(0.3, 1).unwrap(), 2.0, 1e-15));
        assert!(s.deriv(0.3, 2).unwrap().abs() < 1e-14);
        let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0]).unwrap();
        // One unknown: -(p B1 + q B2) d = ... with p = q = 1/2, B1 = B2 = 5: d = -2/10.
        assert!(
            close(s.knot_values()[1], 0.8, 1e-15),
            "{:?}",
            s.knot_values()
        );
    }

    #[test]
    fn straight_polygon_is_reproduced() {
        let x = [0.0, 0.3, 1.7, 2.0, 5.5];
        let f: Vec<f64> = x.iter().map(|x| 2.0 * x - 1.0).collect();
        let s = Spline::new(&x, &f).unwrap();
        for (phi, f) in s.knot_values().iter().zip(&f) {
            assert!(close(*phi, *f, 1e-14), "want {f}, got {phi}");
        }
    }

    #[test]
    fn extrapolation_policies() {
        let s = Spline::new(&EX1_X, &EX1_F).unwrap();
        assert!(matches!(s.eval(0.5), Err(Error::OutOfDomain { .. })));
        assert!(matches!(s.eval(f64::NAN), Err(Error::NonFinite { .. })));
        let c = s.clone().with_extrapolation(Extrapolate::Clamp);
        assert_eq!(c.eval(-1e300).unwrap(), 1.0);
        assert_eq!(c.eval(f64::INFINITY).unwrap(), 1.5);
        assert_eq!(c.deriv(20.0, 1).unwrap(), 0.0);
        let e = s.with_extrapolation(Extrapolate::Extend);
        let c0 = e.power_coefficients(0).unwrap();
        let x = 0.25;
        let dx = x - 1.0;
        let want = c0[0] + dx * (c0[1] + dx * (c0[2] + dx * c0[3]));
        assert!(close(e.eval(x).unwrap(), want, 1e-13));
        assert!(matches!(e.eval(f64::INFINITY), Err(Error::Overflow { .. })));
    }

    #[test]
    fn integral_matches_power_form() {
        let s = Spline::with_alpha(&EX1_X, &EX1_F, 0.4).unwrap();
        let mut want = 0.0;
        for k in 0..s.len() {
            let c = s.power_coefficients(k).unwrap();
            want += c[0] + c[1] / 2.0 + c[2] / 3.0 + c[3] / 4.0;
        }
        let got = s.integral(1.0, 11.0).unwrap();
        assert!(close(got, want, 1e-13), "want {want}, got {got}");
        assert!(close(s.integral(11.0, 1.0).unwrap(), -want, 1e-13));
        let split = s.integral(1.0, 4.3).unwrap() + s.integral(4.3, 11.0).unwrap();
        assert!(close(split, want, 1e-13));
        assert!(s.integral(0.0, 2.0).is_err());
    }

    #[test]
    fn extrema_are_roots_of_the_derivative() {
        let s = Spline::new(&EX1_X, &EX1_F).unwrap();
        let ex = s.extrema();
        // 1 3 3 1 2 7 1.5 1 10 2 1.5: three maxima and two minima, alternating.
        assert_eq!(ex.len(), 5, "{ex:?}");
        for (i, e) in ex.iter().enumerate() {
            let want = if i % 2 == 0 {
                ExtremumKind::Maximum
            } else {
                ExtremumKind::Minimum
            };
            assert_eq!(e.kind, want, "{ex:?}");
        }
        for e in &ex {
            let d = s.deriv(e.x, 1).unwrap();
            assert!(d.abs() < 1e-10, "S'({}) = {d}", e.x);
        }
        let ((_, lo), (_, hi)) = s.range();
        let mut xs = vec![0.0; 10001];
        for (i, x) in xs.iter_mut().enumerate() {
            *x = 1.0 + 10.0 * i as f64 / 10000.0;
        }
        let mut ys = vec![0.0; xs.len()];
        s.eval_many(&xs, &mut ys).unwrap();
        for y in ys {
            assert!(
                y >= lo - 1e-12 && y <= hi + 1e-12,
                "{y} outside [{lo}, {hi}]"
            );
        }
    }

    #[test]
    fn batch_matches_pointwise_sorted_and_not() {
        let s = Spline::with_alpha(&EX1_X, &EX1_F, 0.6).unwrap();
        let xs: Vec<f64> = (0..200)
            .map(|i| 1.0 + ((i * 7919) % 1000) as f64 / 100.0)
            .collect();
        let mut sorted = xs.clone();
        sorted.sort_by(f64::total_cmp);
        for q in [&xs, &sorted] {
            for order in 0..4 {
                let mut out = vec![0.0; q.len()];
                s.deriv_many(q, order, &mut out).unwrap();
                for (x, y) in q.iter().zip(&out) {
                    assert_eq!(*y, s.deriv(*x, order).unwrap(), "order {order} at {x}");
                }
            }
        }
        let mut out = vec![0.0; 3];
        assert!(matches!(
            s.eval_many(&[2.0, f64::NAN, 3.0], &mut out),
            Err(Error::NonFinite { index: 1, .. })
        ));
        assert!(s.eval_many(&[2.0], &mut out).is_err());
    }

    #[test]
    fn huge_values_do_not_overflow() {
        // Values at the very top of the range: evaluation stays finite.
        let f = [1e308, -1.7e308, 1.7e308, f64::MAX, -f64::MAX];
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let s = Spline::new(&x, &f).unwrap();
        for v in s.knot_values() {
            assert!(v.is_finite());
        }
        for i in 0..=400 {
            let y = s.eval(i as f64 / 100.0).unwrap();
            assert!(y.is_finite(), "{y}");
        }
        // Values near 1e308 whose Bezier ordinates are representable: the
        // export is finite and agrees with a scaled-down copy.
        let f = [1e308, -1e308, 1e308, 5e307, -1e308];
        let s = Spline::new(&x, &f).unwrap();
        let small: Vec<f64> = f.iter().map(|v| v * 1e-300).collect();
        let t = Spline::new(&x, &small).unwrap();
        for (a, b) in s.segments().iter().zip(t.segments()) {
            for j in 0..4 {
                let (ya, yb) = (a.p[j][1], b.p[j][1] * 1e300);
                assert!(
                    ya.is_finite() && close(ya, yb, 1e-13),
                    "want {yb}, got {ya}"
                );
            }
        }
    }

    #[test]
    fn tiny_interval_is_computed_or_refused() {
        let ok = Spline::new(&[0.0, 1e-15, 1.0], &[0.0, 1.0, 0.0]).unwrap();
        assert!(ok.knot_values().iter().all(|v| v.is_finite()));
        assert!(matches!(
            Spline::new(&[0.0, 5e-324, 1.0], &[0.0, 1.0, 0.0]),
            Err(Error::IntervalTooSmall { interval: 0, .. })
        ));
        assert!(matches!(
            Spline::new(&[-1e308, 1e308], &[0.0, 1.0]),
            Err(Error::SpanOverflow { .. })
        ));
    }

    /// A small deterministic generator (xorshift64*), uniform in `[0, 1)`;
    /// the curve tests use it too.
    pub(crate) struct Rng(pub(crate) u64);

    impl Rng {
        pub(crate) fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Random data: widths over three decades, values over several, at a
    /// magnitude `mag`.
    fn random_data(rng: &mut Rng, n: usize, mag: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut x = Vec::with_capacity(n);
        let mut t = -3.0 + 6.0 * rng.next();
        for _ in 0..n {
            x.push(t);
            t += 10f64.powf(-1.5 + 3.0 * rng.next());
        }
        let f = (0..n)
            .map(|_| mag * (2.0 * rng.next() - 1.0) * 10f64.powf(2.0 * rng.next()))
            .collect();
        let a = (0..n.saturating_sub(1))
            .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
            .collect();
        (x, f, a)
    }

    /// The straightforward evaluator: binary search, `t = (x - tau_k) / h_k`,
    /// Horner, division by `h` per order.
    fn reference_deriv(s: &Spline, x: f64, order: u32) -> f64 {
        let k = s.piece_index(x);
        let h = s.pieces.knots()[k + 1] - s.pieces.knots()[k];
        let t = (x - s.pieces.knots()[k]) / h;
        let mut v = deriv_of(&s.pieces.coefs()[k].0, t, order) * s.scale();
        for _ in 0..order {
            v /= h;
        }
        v
    }

    #[test]
    fn rebuilds_of_other_sizes_keep_the_summary_right() {
        // A stale summary would send the batch search to the wrong stretch
        // of knots.
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (x, f, _) = random_data(&mut rng, 40, 1.0);
        let mut s = Spline::new(&x, &f).unwrap();
        for n in [17usize, 100, 16, 2, 33, 1000, 5, 64, 65, 3, 48, 49] {
            let (x, f, a) = random_data(&mut rng, n, 1.0);
            for alphas in [Alphas::Uniform(0.5), Alphas::PerInterval(&a)] {
                s.rebuild(&x, &f, alphas).unwrap();
                let mut want = Summary::default();
                want.of(&x);
                assert_eq!(s.pieces.summary(), &want, "n {n}");
                let q: Vec<f64> = (0..64)
                    .map(|_| x[0] + (x[n - 1] - x[0]) * rng.next())
                    .collect();
                let mut got = vec![0.0; q.len()];
                s.eval_many(&q, &mut got).unwrap();
                for (q, g) in q.iter().zip(&got) {
                    assert_eq!(*g, s.eval(*q).unwrap(), "n {n} x {q}");
                }
            }
        }
    }

    #[test]
    fn random_order_batches_match_pointwise_with_and_without_the_search_index() {
        let mut rng = Rng(0x51ed_270b_0a3f_1c25);
        let mut s = Spline::new(&[0.0, 1.0], &[0.0, 1.0]).unwrap();
        for n in [40usize, 300, 2_000, 5_000] {
            for shape in 0..3 {
                let (mut x, f, _) = random_data(&mut rng, n, 1.0);
                match shape {
                    // Widths over three decades, mixed: evenly spread at the
                    // scale of the buckets.
                    0 => {}
                    // Runs of close knots between wide gaps.
                    1 => {
                        let mut t = 0.0;
                        for (i, v) in x.iter_mut().enumerate() {
                            t += if i % 50 < 45 {
                                1e-3
                            } else {
                                10.0 * (1.0 + rng.next())
                            };
                            *v = t;
                        }
                    }
                    // Geometric: too uneven for an index.
                    _ => {
                        for (i, v) in x.iter_mut().enumerate() {
                            *v = (30.0 * i as f64 / n as f64).exp();
                        }
                    }
                }
                s.rebuild(&x, &f, Alphas::Uniform(0.5)).unwrap();
                assert!(
                    !s.pieces.summary().indexed(),
                    "n {n} shape {shape}: a rebuild forgets it"
                );
                let (lo, hi) = (x[0], x[n - 1]);
                let q: Vec<f64> = (0..n.max(100))
                    .map(|_| lo + (hi - lo) * rng.next() * rng.next().sqrt())
                    .collect();
                let mut got = vec![0.0; q.len()];
                for round in 0..2 {
                    s.deriv_many(&q, 1, &mut got).unwrap();
                    for (x, g) in q.iter().zip(&got) {
                        let want = s.deriv(*x, 1).unwrap();
                        assert_eq!(*g, want, "n {n} shape {shape} round {round} x {x}");
                    }
                }
                // With a handful of entries even uneven knots keep theirs:
                // it cannot cost much.
                if n >= 300 {
                    assert_eq!(
                        s.pieces.summary().indexed(),
                        shape < 2,
                        "n {n} shape {shape}"
                    );
                }
            }
        }
    }

    #[test]
    fn piece_index_is_the_last_knot_not_above_at_any_size() {
        // Past 2^18 knots, and once a batch has formed the index, the single
        // query takes the summary's search rather than one over all knots.
        let mut rng = Rng(0x6a09_e667_f3bc_c908);
        for n in [2usize, 17, 1_000, 300_000] {
            let (x, f, _) = random_data(&mut rng, n, 1.0);
            let s = Spline::new(&x, &f).unwrap();
            let (lo, hi) = (x[0], x[n - 1]);
            let mut q: Vec<f64> = (0..2_000).map(|_| lo + (hi - lo) * rng.next()).collect();
            for i in (0..n).step_by((n / 500).max(1)) {
                q.extend([x[i], x[i].next_down(), x[i].next_up()]);
            }
            q.extend([
                f64::NAN,
                f64::NEG_INFINITY,
                f64::INFINITY,
                hi.next_up(),
                lo.next_down(),
            ]);
            for indexed in [false, true] {
                if indexed {
                    // A batch of random order, long enough to form it.
                    let b: Vec<f64> = (0..n.div_ceil(32) + 64)
                        .map(|_| lo + (hi - lo) * rng.next())
                        .collect();
                    let mut out = vec![0.0; b.len()];
                    s.eval_many(&b, &mut out).unwrap();
                    // One piece: the batch only walks, and never searches.
                    assert_eq!(s.pieces.summary().indexed(), n > 2, "n {n}");
                }
                for &x0 in &q {
                    let want = x.partition_point(|&k| k <= x0).saturating_sub(1).min(n - 2);
                    assert_eq!(s.piece_index(x0), want, "n {n} x {x0} index {indexed}");
                }
            }
        }
    }

    #[test]
    fn fused_build_and_batches_match_the_reference() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for (case, &n) in [2usize, 3, 4, 5, 17, 18, 33, 100, 1000, 4097]
            .iter()
            .enumerate()
        {
            for mag in [1.0, 1e-300, 1e300, 3e-7] {
                let (x, f, a) = random_data(&mut rng, n, mag);
                let fmax = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let uniform = ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next();
                for alphas in [Alphas::PerInterval(&a), Alphas::Uniform(uniform)] {
                    let fast = Spline::build(&x, &f, alphas).unwrap();
                    let slow = Spline::build_reference(&x, &f, alphas).unwrap();
                    assert_eq!(fast.alphas(), slow.alphas());
                    assert_eq!(fast.knots(), slow.knots());
                    assert_eq!(fast.values(), slow.values());
                    assert_eq!(fast.scale(), slow.scale());
                    assert_eq!(
                        fast.pieces.summary(),
                        slow.pieces.summary(),
                        "case {case} n {n}: summary"
                    );
                    let tol = 1e-13 * fmax;
                    for (k, (p, q)) in fast
                        .knot_values()
                        .iter()
                        .zip(slow.knot_values())
                        .enumerate()
                    {
                        assert!(
                            (p - q).abs() <= tol,
                            "case {case} n {n} mag {mag}: knot value {k}: want {q}, got {p}"
                        );
                    }
                    for k in 0..fast.len() {
                        let (p, q) = (
                            fast.unit_coefficients(k).unwrap(),
                            slow.unit_coefficients(k).unwrap(),
                        );
                        for j in 0..4 {
                            assert!(
                                (p[j] - q[j]).abs() <= tol,
                                "case {case} n {n}: piece {k} coef {j}: want {}, got {}",
                                q[j],
                                p[j]
                            );
                        }
                    }
                    // Batches: sorted (several queries per piece) and random,
                    // against pointwise deriv exactly and the straightforward
                    // evaluator to rounding.
                    let (lo, hi) = fast.domain();
                    let m = 3 * n + 7;
                    let mut random: Vec<f64> =
                        (0..m).map(|_| lo + (hi - lo) * rng.next()).collect();
                    random.push(hi);
                    random.push(lo);
                    random.extend_from_slice(&x);
                    let mut sorted = random.clone();
                    sorted.sort_by(f64::total_cmp);
                    // Runs in order broken by jumps both ways, and descending:
                    // the walk's far jumps and the hand-overs between walk and search.
                    let mut jumpy: Vec<f64> = sorted
                        .chunks(37)
                        .rev()
                        .flat_map(|c| c.iter().copied())
                        .collect();
                    jumpy.rotate_left(m / 3);
                    let descending: Vec<f64> = sorted.iter().rev().copied().collect();
                    let mut out = vec![0.0; random.len()];
                    for q in [&sorted, &random, &jumpy, &descending] {
                        for order in 0..4 {
                            fast.deriv_many(q, order, &mut out).unwrap();
                            for (&xq, &y) in q.iter().zip(&out) {
                                assert_eq!(
                                    y,
                                    fast.deriv(xq, order).unwrap(),
                                    "order {order} at {xq}"
                                );
                                let want = reference_deriv(&slow, xq, order);
                                let k = fast.piece_index(xq);
                                let h = x[k + 1] - x[k];
                                let tol = 1e-13 * fmax / h.powi(order as i32);
                                assert!(
                                    (y - want).abs() <= tol,
                                    "case {case} n {n} order {order} at {xq}: want {want}, got {y}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn rebuilds_with_one_alpha_keep_the_alphas_right() {
        // The uniform hint lets a rebuild skip rewriting the alphas only when
        // they are already that one alpha.
        let mut rng = Rng(9);
        let (x, f, a) = random_data(&mut rng, 300, 1.0);
        let mut s = Spline::with_alphas(&x, &f, &a).unwrap();
        for (alpha, per) in [
            (0.4, false),
            (0.4, false),
            (0.6, false),
            (0.0, true),
            (0.6, false),
        ] {
            if per {
                s.rebuild(&x, &f, Alphas::PerInterval(&a)).unwrap();
                assert_eq!(s.alphas(), &a[..]);
            } else {
                s.rebuild(&x, &f, Alphas::Uniform(alpha)).unwrap();
                assert!(s.alphas().iter().all(|&b| b == alpha), "alpha {alpha}");
                assert_eq!(s, Spline::with_alpha(&x, &f, alpha).unwrap());
            }
        }
        // A shorter rebuild, then the full length again.
        s.rebuild(&x[..100], &f[..100], Alphas::Uniform(0.6))
            .unwrap();
        assert_eq!(s.alphas().len(), 99);
        s.rebuild(&x, &f, Alphas::Uniform(0.6)).unwrap();
        assert_eq!(s.alphas(), &[0.6; 299][..]);
    }

    #[test]
    fn rebuild_reuses_and_keeps_the_spline_on_error() {
        let mut rng = Rng(7);
        let (x, f, a) = random_data(&mut rng, 500, 1.0);
        let mut s = Spline::with_alphas(&x, &f, &a)
            .unwrap()
            .with_extrapolation(Extrapolate::Clamp);
        let bytes = s.heap_bytes();
        // Knots, values, alphas, pieces, the summary and the one scale.
        assert_eq!(bytes, 500 * 8 * 3 - 8 + 499 * 32 + 32 * 8 + 8, "heap bytes");
        let (x2, f2, _) = random_data(&mut rng, 400, 2.0);
        s.rebuild(&x2, &f2, Alphas::Uniform(0.4)).unwrap();
        assert_eq!(
            s,
            Spline::with_alpha(&x2, &f2, 0.4)
                .unwrap()
                .with_extrapolation(Extrapolate::Clamp)
        );
        assert_eq!(s.heap_bytes(), bytes, "no reallocation");
        let before = s.clone();
        let mut bad = x2.clone();
        bad[200] = f64::NAN;
        assert!(matches!(
            s.rebuild(&bad, &f2, Alphas::default()),
            Err(Error::NonFinite {
                field: Field::Knot,
                index: 200,
                ..
            })
        ));
        assert_eq!(s, before);
        // Other knots, good, with a bad value: the check has read them all
        // (and put them in its summary) before it fails.
        let mut bad_values = f.clone();
        bad_values[3] = f64::NAN;
        assert!(s.rebuild(&x, &bad_values, Alphas::default()).is_err());
        assert_eq!(s, before);
    }

    #[test]
    fn errors_are_those_of_the_step_by_step_validation() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let f = [0.0, 1.0, 0.0, 1.0];
        let cases: [(&[f64], &[f64], Alphas<'_>); 9] = [
            (&[0.0], &[0.0], Alphas::default()),
            (&x, &f[..3], Alphas::default()),
            (&[0.0, 1.0, 1.0, 3.0], &f, Alphas::default()),
            (&[0.0, f64::INFINITY, 2.0, 3.0], &f, Alphas::default()),
            (&[0.0, 1e-17, 2.0, 3.0], &f, Alphas::default()),
            (&x, &[0.0, f64::NAN, 0.0, 1.0], Alphas::default()),
            (&x, &f, Alphas::Uniform(0.7)),
            (&x, &f, Alphas::PerInterval(&[0.5, 0.5])),
            (&x, &f, Alphas::PerInterval(&[0.5, f64::NAN, 0.2])),
        ];
        for (k, v, a) in cases {
            let got = Spline::build(k, v, a);
            let want = Spline::build_reference(k, v, a);
            assert!(got.is_err(), "{k:?} {v:?} {a:?} should fail");
            // Debug text, because a NaN in the error is not equal to itself.
            assert_eq!(format!("{got:?}"), format!("{want:?}"));
        }
    }

    #[test]
    fn span_at_the_top_of_the_range_keeps_the_system_regular() {
        // Both widths are finite but their sum rounds to infinity; the knot
        // values must match the same data on knots scaled down by 2^-1000.
        let knots = [2.2250738585072014e-308, 5.376052040422133e307, f64::MAX];
        assert!((knots[1] - knots[0]) + (knots[2] - knots[1]) == f64::INFINITY);
        let f = [0.0, 0.0, 1.0];
        let a = [ALPHA_MIN, ALPHA_MAX];
        let s = Spline::with_alphas(&knots, &f, &a).unwrap();
        let down = 2f64.powi(-1000);
        let small: Vec<f64> = knots.iter().map(|x| x * down).collect();
        let t = Spline::with_alphas(&small, &f, &a).unwrap();
        for (got, want) in s.knot_values().iter().zip(t.knot_values()) {
            assert!(close(*got, want, 1e-14), "want {want}, got {got}");
        }
        assert!(s.knot_values()[1] < 0.1, "{:?}", s.knot_values());
    }

    #[test]
    fn walked_blocks_with_outside_queries_and_huge_pieces_match_pointwise() {
        // Sorted blocks that leave the domain and come back, meet NaN, cross
        // pieces whose values near f64::MAX leave no margin for the batch's
        // finiteness bound, and end on the last knot: each result as the
        // pointwise evaluator gives it, under every extrapolation policy.
        let x: Vec<f64> = (0..40).map(|i| f64::from(i) * 0.5).collect();
        let f: Vec<f64> = (0..40)
            .map(|i| match i % 7 {
                3 => f64::MAX,
                4 => -0.9 * f64::MAX,
                _ => f64::from(i).sin(),
            })
            .collect();
        let (lo, hi) = (x[0], x[39]);
        let mut qs: Vec<f64> = (0..400).map(|i| -1.0 + f64::from(i) * 0.0537).collect();
        qs[100] = f64::NAN;
        qs.extend([hi, hi, lo, hi + 1.0, lo - 1.0]);
        qs.extend((0..80).map(|i| lo + f64::from(i) * 0.2461));
        let clean: Vec<f64> = qs.iter().copied().filter(|q| !q.is_nan()).collect();
        let mut answered = 0;
        for policy in [Extrapolate::Clamp, Extrapolate::Extend, Extrapolate::Error] {
            let s = Spline::new(&x, &f).unwrap().with_extrapolation(policy);
            for order in 0..4 {
                for q in [&qs, &clean] {
                    answered += usize::from(batch_is_pointwise(&s, q, order));
                }
            }
        }
        // Clamped values answer every query but the NaN; derivatives and
        // extended values overflow beside the huge pieces.
        assert_eq!(answered, 1);
    }

    /// `deriv_many` against `deriv` query by query: the same values, or the
    /// error of the first query that fails. True when every query was answered.
    fn batch_is_pointwise(s: &Spline, qs: &[f64], order: u32) -> bool {
        let mut out = vec![0.0; qs.len()];
        let got = s.deriv_many(qs, order, &mut out);
        let first_err = qs
            .iter()
            .enumerate()
            .find_map(|(i, &q)| s.deriv(q, order).err().map(|e| e.at_query(i)));
        let label = format!("{:?} order {order}", s.extrapolate);
        match first_err {
            // (Compared as text: the error may hold a NaN.)
            Some(e) => {
                assert_eq!(
                    format!("{got:?}"),
                    format!("{:?}", Err::<(), _>(e)),
                    "{label}"
                );
                false
            }
            None => {
                assert_eq!(got, Ok(()), "{label}");
                for (&q, &y) in qs.iter().zip(&out) {
                    assert_eq!(Ok(y), s.deriv(q, order), "{label} at {q}");
                }
                true
            }
        }
    }

    #[test]
    fn batch_overflow_is_the_pointwise_error() {
        // The higher derivatives overflow on the narrow first piece only: the
        // batch must stop at the same query with the same error, and agree with
        // the pointwise values where they are finite.
        let s = Spline::new(&[0.0, 1e-12, 1.0], &[0.0, 1e300, 0.0]).unwrap();
        let xs: Vec<f64> = [0.5, 0.25]
            .into_iter()
            .chain((0..100).map(|i| f64::from(i) * 1e-14))
            .collect();
        let mut failed = Vec::new();
        for order in 0..=3 {
            let mut out = vec![0.0; xs.len()];
            let batch = s.deriv_many(&xs, order, &mut out);
            match xs.iter().find_map(|&x| s.deriv(x, order).err()) {
                Some(e) => {
                    assert_eq!(batch, Err(e), "order {order}");
                    failed.push(order);
                }
                None => {
                    assert_eq!(batch, Ok(()), "order {order}");
                    for (&x, &o) in xs.iter().zip(&out) {
                        assert_eq!(Ok(o), s.deriv(x, order), "order {order} at {x}");
                    }
                }
            }
        }
        assert!(
            failed.contains(&3),
            "the third derivative overflows: {failed:?}"
        );
        assert!(!failed.contains(&0), "values do not: {failed:?}");
    }

    #[test]
    fn extrema_near_f64_max_are_finite() {
        // A maximum between two knots valued f64::MAX: at the top of the range
        // (where rounding may carry it above, and it is clamped).
        let knots = [
            -859.3884755308262,
            0.0,
            365.72855093326575,
            436.5118599248209,
            767.2605905654594,
        ];
        let f = [0.0, 0.0, -f64::MAX, f64::MAX, f64::MAX];
        let s = Spline::with_alphas(&knots, &f, &[ALPHA_MAX, ALPHA_MIN, 0.5, 0.5]).unwrap();
        let ex = s.extrema();
        let top = f64::MAX * (1.0 - 1e-15);
        assert!(ex.iter().any(|e| e.y >= top), "{ex:?}");
        assert!(ex.iter().all(|e| e.y.is_finite()), "{ex:?}");
        let ((_, lo), (_, hi)) = s.range();
        assert!(
            lo.is_finite() && hi >= top && hi.is_finite(),
            "range [{lo}, {hi}]"
        );
        for e in ex {
            let y = s.eval(e.x).unwrap();
            assert!(close(y, e.y, 1e-12), "S({}) = {y}, extremum {}", e.x, e.y);
        }
    }

    #[test]
    fn first_value_is_exact_beside_a_value_near_the_top_of_the_range() {
        // Found by the spline_build fuzz target: F_0 divided by the scale of
        // f64::MAX underflowed to 0, so S(tau_0) was 0 instead of F_0.
        let f0 = 1.568_603_515_624_999_3e-203;
        let s = Spline::with_alpha(&[0.0, 3.906_25e-303], &[f0, f64::MAX], ALPHA_MIN).unwrap();
        assert_eq!(s.eval(0.0).unwrap(), f0, "S(tau_0) must be F_0");
        assert_eq!(
            s.eval(3.906_25e-303).unwrap(),
            f64::MAX,
            "S(tau_N) must be F_N"
        );
        assert_eq!(s.knot_values(), vec![f0, f64::MAX]);
        // The batch evaluator agrees (on knots of ordinary size, which it
        // handles without rescaling them).
        let s = Spline::new(&[0.0, 1.0, 2.0], &[f0, f64::MAX, 0.0]).unwrap();
        let xs = [0.0, 0.5, 0.0, 2.0];
        let mut out = [0.0; 4];
        s.eval_many(&xs, &mut out).unwrap();
        for (x, y) in xs.iter().zip(out) {
            assert_eq!(y, s.eval(*x).unwrap(), "batch at {x}");
        }
        assert_eq!(out[0], f0);
    }
}
