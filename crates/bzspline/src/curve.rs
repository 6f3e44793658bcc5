//! Parametric curves in `R^d`, open or closed, built coordinate by coordinate on
//! one shared parameter grid.
//!
//! # Open curves
//!
//! Control points `P_0 .. P_{n-1}` (n >= 2) get parameters `tau_0 < .. < tau_{n-1}`
//! ([`Param`]) and one shape parameter per leg `P_k -> P_{k+1}`. Each coordinate
//! is the spline of `spline.rs` on that grid; the continuity matrix depends
//! only on the parameter steps and the alphas, so it is factored once and solved
//! for one right-hand side per coordinate. Because every coordinate uses the same
//! linear map, the curve touches leg `k` at the parameter
//! `x_k = tau_{k+1} - alpha_k h_k`, at the point `alpha_k P_k + (1 - alpha_k) P_{k+1}`,
//! and starts at `P_0` and ends at `P_{n-1}`.
//!
//! # Closed curves
//!
//! Control points `P_0 .. P_{n-1}` (n >= 3) with the closing leg `P_{n-1} -> P_0`
//! get `n + 1` parameters; `tau_n` closes the loop. Every knot is interior: the
//! row-scaled continuity equation of the open spline holds at every knot with
//! indices taken cyclically, `d` is fixed nowhere, and the system is cyclic
//! tridiagonal and diagonally dominant in the theorem's range. It is solved in
//! O(n): from 48 points in one to three dimensions by the open curve's sweeps
//! over the ring's points with every leg but the closing one, the deviations
//! at the two ends found from each end's response and the ring's two
//! remaining rows (`docs/method.md` §16), else by the cyclic Thomas algorithm
//! (`tridiag.rs`). The curve is C1 across the
//! closing knot too. A closed curve answers at every finite parameter: it is
//! periodic with period `tau_n - tau_0`.
//!
//! # Numbers
//!
//! Each coordinate is divided by its own power of two (exact) before solving, as
//! the y(x) spline does, so coordinates near `1e308` do not overflow. Geometric
//! quantities that mix coordinates (lengths, distances, curvature) are computed
//! in units of the largest of these powers of two and converted back at the end.
//!
//! # Files
//!
//! This file holds the types and the accessors; the jobs are apart: building
//! (`builder.rs`), solving (`solve.rs`), evaluating (`eval.rs`), the Bezier
//! segments and their export (`segments.rs`), arc length (`arclen.rs`),
//! flattening (`flatten.rs`), the nearest point (`nearest.rs`) and the local
//! re-solve after an edit (`edit.rs`).

mod arclen;
mod builder;
mod edit;
mod eval;
mod flatten;
mod nearest;
mod segments;
mod solve;
#[cfg(test)]
mod tests;

use crate::error::{Error, Field};
use crate::pieces::Pieces;
pub use crate::traits::BBox;
use crate::traits::ParamCurve;
use crate::validate::check_finite;
pub use builder::CurveBuilder;

/// Default absolute accuracy of arc lengths and their inverse, in the curve's
/// units.
pub const DEFAULT_ACCURACY: f64 = 1e-9;

/// How the parameters `tau` of the control points are chosen
/// (`docs/method.md` §6).
///
/// The default is [`Param::Centripetal`], for the command, its server, the
/// bindings and the coverage smoothing alike: it follows the points' spacing
/// as chord lengths do but damps long legs, so that uneven spacing neither
/// makes cusps and loops (as uniform parameters do where a short leg follows
/// a long one) nor overshoots on long legs (as chordal ones can), the choice
/// of Catmull-Rom curves (`d3.curveCatmullRom`'s default) and of most curve
/// editors. The parameters of a shape do not change under rotation,
/// translation or scaling of its points.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Param {
    /// `tau_i = i`.
    Uniform,
    /// `tau_{i+1} - tau_i = |P_{i+1} - P_i|` (chord lengths), `tau_0 = 0`.
    Chordal,
    /// `tau_{i+1} - tau_i = |P_{i+1} - P_i|^(1/2)`, `tau_0 = 0`. The default.
    #[default]
    Centripetal,
    /// The given parameters: one per point for an open curve, one more for a
    /// closed curve (the last closes the loop). Strictly increasing.
    Given(Vec<f64>),
}

impl Param {
    /// The names [`Param::from_str`](std::str::FromStr) reads, in the order of
    /// the variants: the command's `--param`, the server's and the bindings'
    /// `param`.
    pub const NAMES: [&'static str; 3] = ["uniform", "chordal", "centripetal"];

    /// The name of a parametrisation chosen by name; `None` for given
    /// parameters.
    #[must_use]
    pub fn name(&self) -> Option<&'static str> {
        match self {
            Param::Uniform => Some(Self::NAMES[0]),
            Param::Chordal => Some(Self::NAMES[1]),
            Param::Centripetal => Some(Self::NAMES[2]),
            Param::Given(_) => None,
        }
    }
}

/// Its name (`uniform`, `chordal`, `centripetal`), or `given` for given
/// parameters.
impl std::fmt::Display for Param {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name().unwrap_or("given"))
    }
}

/// A name that is not one of [`Param::NAMES`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownParam(pub String);

impl std::fmt::Display for UnknownParam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The name in quotes as it was given: escaping it (`{:?}`) would
        // bring Debug's Unicode tables into the WebAssembly module (4 kB).
        write!(
            f,
            "\"{}\" is not \"uniform\", \"chordal\" or \"centripetal\"",
            self.0
        )
    }
}

impl std::error::Error for UnknownParam {}

impl std::str::FromStr for Param {
    type Err = UnknownParam;

    /// `uniform`, `chordal` or `centripetal`, as [`Param::NAMES`] lists them.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "uniform" => Ok(Param::Uniform),
            "chordal" => Ok(Param::Chordal),
            "centripetal" => Ok(Param::Centripetal),
            _ => Err(UnknownParam(s.to_owned())),
        }
    }
}

/// What to do with a control point equal to the one before it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Repeats {
    /// Refuse with [`Error::RepeatedPoint`] (or [`Error::RepeatedClosingPoint`]
    /// for a closed curve whose last point is its first). The default.
    #[default]
    Reject,
    /// Drop the repeat (with its parameter, when given, and the alpha of the
    /// empty leg); [`Curve::dropped`] lists the indices dropped.
    Drop,
}

/// How a curve was built, kept so that it can be rebuilt after a point moves.
#[derive(Clone, Debug, PartialEq)]
enum ParamKind {
    Uniform,
    Chordal,
    Centripetal,
    Given,
}

/// A curve in `R^d` made of one cubic segment per leg of its control polygon:
/// C1, touching every leg, inside the convex hull of its control points for
/// alphas in `[1/3, 2/3]`. Immutable except through [`Curve::move_point`].
///
/// Segment `k` runs over `[tau_k, tau_{k+1}]`, from knot point `k` to knot point
/// `k + 1` (point 0 for the closing segment of a closed curve), and answers on
/// the half-open interval `[tau_k, tau_{k+1})`; the last one also at its end.
///
/// With the feature `serde` a curve serializes as its inputs (dimension,
/// closedness, parameter choice, points after dropping repeats, alphas), and
/// deserializing builds and validates it again.
///
/// # Examples
///
/// ```
/// use bzspline::{Curve, ParamCurve};
/// let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
/// // Centripetal parameters (the default): steps of sqrt(|leg|).
/// let (lo, hi) = c.domain();
/// assert_eq!((lo, hi), (0.0, c.knots()[3]));
/// assert_eq!(c.eval(lo)?, vec![0.0, 0.0]);
/// assert_eq!(c.eval(hi)?, vec![4.0, 0.0]);
/// // Leg 1 is touched at its middle, where the curve runs parallel to it.
/// let (t, p) = &c.tangent_points()[1];
/// assert!((p[0] - 2.0).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12);
/// assert!(c.deriv(*t, 1)?[1].abs() < 1e-12);
/// # Ok::<(), bzspline::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "CurveData", into = "CurveData")
)]
pub struct Curve {
    closed: bool,
    kind: ParamKind,
    /// Control points, flat, `dim` per point.
    points: Vec<f64>,
    /// Indices (in the caller's array) of points dropped as repeats.
    dropped: Vec<usize>,
    /// The `n` parameters (open) or `n + 1` (closed) as knots, the segments'
    /// pieces (`dim` per segment, scaled) and one power-of-two scale per
    /// coordinate.
    pieces: Pieces,
    /// One per leg.
    alphas: Vec<f64>,
    /// The power of two chord lengths are measured in (chordal and
    /// centripetal parameters; 1 otherwise).
    chord_scale: f64,
    /// What the parameter steps in `chord_scale` units were multiplied by
    /// (1 when that would overflow the span).
    knot_unit: f64,
    /// `1 / scales[c]`: the scaled control points are `points[i dim + c] *
    /// inv_scales[c]` ([`Curve::fv`]), formed where they are used rather than
    /// held.
    inv_scales: Vec<f64>,
    /// Scaled deviations, flat: knot point `i` is `(fv + d)[i] * scale`.
    d: Vec<f64>,
}

/// The serialized form of a [`Curve`]: its inputs. Deserializing solves again
/// (and validates), so a stored curve cannot hold inconsistent numbers.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
struct CurveData {
    dim: usize,
    closed: bool,
    param: Param,
    points: Vec<f64>,
    alphas: Vec<f64>,
}

#[cfg(feature = "serde")]
impl From<Curve> for CurveData {
    fn from(c: Curve) -> Self {
        let param = match c.kind {
            ParamKind::Uniform => Param::Uniform,
            ParamKind::Chordal => Param::Chordal,
            ParamKind::Centripetal => Param::Centripetal,
            ParamKind::Given => Param::Given(c.pieces.knots().to_vec()),
        };
        CurveData {
            dim: c.dim(),
            closed: c.closed,
            param,
            points: c.points,
            alphas: c.alphas,
        }
    }
}

#[cfg(feature = "serde")]
impl TryFrom<CurveData> for Curve {
    type Error = Error;
    fn try_from(d: CurveData) -> Result<Self, Error> {
        Curve::builder(&d.points, d.dim)
            .closed(d.closed)
            .param(d.param)
            .alphas(&d.alphas)
            .build()
    }
}

/// The point of a curve nearest to a query point.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Nearest {
    /// Its parameter.
    pub param: f64,
    /// The point.
    pub point: Vec<f64>,
    /// Its distance from the query.
    pub distance: f64,
}

/// Euclidean norm without overflow or underflow in the squares.
#[inline]
fn norm(v: &[f64]) -> f64 {
    let (m, s) = norm_parts(v);
    norm_of(m, s.map_or(0.0, f64::sqrt))
}

/// The largest magnitude `m` of `v` and, unless `m` is zero or not finite,
/// the sum of the squares of `v / m`: what [`norm`] takes the square root
/// of.
#[inline]
fn norm_parts(v: &[f64]) -> (f64, Option<f64>) {
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return (m, None);
    }
    (m, Some(v.iter().map(|x| (x / m) * (x / m)).sum()))
}

/// [`norm`] from [`norm_parts`]'s `m` and the square root of its sum.
#[inline(always)]
fn norm_of(m: f64, root: f64) -> f64 {
    if m == 0.0 || !m.is_finite() {
        m
    } else {
        m * root
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn check_tolerance(what: &'static str, tol: f64) -> Result<(), Error> {
    if !tol.is_finite() {
        return Err(Error::NonFinite {
            field: Field::Tolerance,
            index: 0,
            value: tol,
        });
    }
    if tol < 0.0 {
        return Err(Error::InvalidArgument { what, value: tol });
    }
    Ok(())
}

/// Checks that a batch's output buffer holds `len` numbers. Only its length:
/// the buffer may hold anything before it is written (NaN from an earlier
/// batch included).
pub(crate) fn check_output(out: &[f64], len: usize) -> Result<(), Error> {
    if out.len() != len {
        return Err(Error::LengthMismatch {
            field: Field::Query,
            expected: len,
            found: out.len(),
        });
    }
    Ok(())
}

/// Checks that a query point holds `dim` finite numbers.
pub(crate) fn check_query(q: &[f64], dim: usize) -> Result<(), Error> {
    check_output(q, dim)?;
    check_finite(Field::Query, q)
}

impl Curve {
    /// A builder for points stored flat, `dim` coordinates per point.
    #[must_use]
    pub fn builder(points: &[f64], dim: usize) -> CurveBuilder<'_> {
        CurveBuilder::new(points, dim)
    }

    /// A builder for points given as arrays (`[[f64; 2]]`, `[[f64; 3]]`, ...).
    #[must_use]
    pub fn builder_from<const D: usize>(points: &[[f64; D]]) -> CurveBuilder<'_> {
        CurveBuilder::new(points.as_flattened(), D)
    }

    /// The open curve through `points` with uniform parameters and alpha 1/2.
    ///
    /// # Errors
    ///
    /// See [`CurveBuilder::build`].
    pub fn open<const D: usize>(points: &[[f64; D]]) -> Result<Self, Error> {
        Self::builder_from(points).build()
    }

    /// The closed curve around `points` with uniform parameters and alpha 1/2.
    ///
    /// # Errors
    ///
    /// See [`CurveBuilder::build`].
    pub fn closed<const D: usize>(points: &[[f64; D]]) -> Result<Self, Error> {
        Self::builder_from(points).closed(true).build()
    }

    /// True for a closed curve.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Number of segments (legs): `n - 1` open, `n` closed.
    #[must_use]
    pub fn len(&self) -> usize {
        self.pieces.knots().len() - 1
    }

    /// Always false: a curve has at least one segment.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.pieces.knots().len() < 2
    }

    /// The control points (after dropping repeats), flat, [`Curve::dim`] per
    /// point.
    #[must_use]
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// Control point `i`.
    #[must_use]
    pub fn point(&self, i: usize) -> Option<&[f64]> {
        self.points.get(i * self.dim()..(i + 1) * self.dim())
    }

    /// Number of control points (after dropping repeats).
    #[must_use]
    pub fn point_count(&self) -> usize {
        self.n_points()
    }

    /// Indices, in the array given to the builder, of the points dropped as
    /// repeats under [`Repeats::Drop`]; empty otherwise.
    #[must_use]
    pub fn dropped(&self) -> &[usize] {
        &self.dropped
    }

    /// The parameters `tau`: one per point, and one more for a closed curve.
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        self.pieces.knots()
    }

    /// The shape parameters, one per leg.
    #[must_use]
    pub fn alphas(&self) -> &[f64] {
        &self.alphas
    }
}
