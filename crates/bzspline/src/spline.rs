//! The spline `y = S(x)` of Stelia, Potapenko and Sirenko.
//!
//! The method itself (the rows of the paper's system (16), the pieces, the
//! reference assembly) is in `method.rs`, beside its equations;
//! `docs/method.md` derives them. This file holds the type and what it
//! stores; the jobs are apart: building (`build.rs`), evaluating (`eval.rs`),
//! integrals (`antiderivative.rs`), extrema and range (`extrema.rs`), the
//! graph as a curve (`graph.rs`), and the alphas (`shape.rs`).
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
use crate::pieces::Pieces;

mod antiderivative;
mod build;
mod eval;
mod extrema;
mod graph;
mod shape;
#[cfg(test)]
pub(crate) mod tests;

pub use antiderivative::Antiderivative;
use shape::Shape;

pub use crate::validate::{
    check_alpha, AlphaChoice, Alphas, ALPHA_MAX, ALPHA_MIN, DEFAULT_ALPHA, MIN_RELATIVE_INTERVAL,
};

/// What evaluation does outside `[tau_0, tau_{N-1}]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Extrapolate {
    /// Return [`Error::OutOfDomain`](crate::Error::OutOfDomain). The default.
    #[default]
    Error,
    /// Hold the end value: `S(x) = F_0` left of the span, `F_{N-1}` right of it,
    /// and every derivative is 0 there.
    Clamp,
    /// Continue the end pieces' cubics.
    Extend,
    /// Give NaN: for a value or derivative outside the span or at a NaN
    /// query, and for an integral with a bound outside the span or NaN.
    /// This is scipy's `extrapolate=False`.
    Nan,
}

impl Extrapolate {
    /// The policy's name, as [`str::parse`] takes it: `error`, `clamp`,
    /// `extend` or `nan`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Extrapolate::Error => "error",
            Extrapolate::Clamp => "clamp",
            Extrapolate::Extend => "extend",
            Extrapolate::Nan => "nan",
        }
    }
}

impl core::fmt::Display for Extrapolate {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// scipy's `extrapolate` flag: `true` continues the end pieces
/// ([`Extrapolate::Extend`]), `false` gives NaN outside the knots
/// ([`Extrapolate::Nan`]). The bindings take `True`/`False` (Python) and
/// `true`/`false` (JavaScript) through this, and the other policies by name.
impl From<bool> for Extrapolate {
    fn from(extend: bool) -> Self {
        if extend {
            Extrapolate::Extend
        } else {
            Extrapolate::Nan
        }
    }
}

/// A name that is not one of [`Extrapolate::name`]'s.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownExtrapolation(pub String);

impl core::fmt::Display for UnknownExtrapolation {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        // In quotes as given, as `UnknownParam`.
        write!(
            f,
            "\"{}\" is not \"error\", \"clamp\", \"extend\" or \"nan\"",
            self.0
        )
    }
}

impl std::error::Error for UnknownExtrapolation {}

impl core::str::FromStr for Extrapolate {
    type Err = UnknownExtrapolation;

    /// `error`, `clamp`, `extend` or `nan`, as [`Extrapolate::name`] gives them.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "error" => Ok(Extrapolate::Error),
            "clamp" => Ok(Extrapolate::Clamp),
            "extend" => Ok(Extrapolate::Extend),
            "nan" => Ok(Extrapolate::Nan),
            _ => Err(UnknownExtrapolation(s.to_owned())),
        }
    }
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

impl Spline {
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
}
