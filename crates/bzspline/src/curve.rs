//! Parametric curves in `R^d`, open or closed, built coordinate by coordinate on
//! one shared parameter grid.
//!
//! # Open curves
//!
//! Control points `P_0 .. P_{n-1}` (n >= 2) get parameters `tau_0 < .. < tau_{n-1}`
//! ([`Param`]) and one shape parameter per leg `P_k -> P_{k+1}`. Each coordinate
//! is the spline of [`crate::spline`] on that grid; the continuity matrix depends
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
//! row-scaled continuity equation of [`crate::spline`] holds at every knot with
//! indices taken cyclically, `d` is fixed nowhere, and the system is cyclic
//! tridiagonal and diagonally dominant in the theorem's range. It is solved in
//! O(n) by [`CyclicThomas`](crate::CyclicThomas). The curve is C1 across the
//! closing knot too. A closed curve answers at every finite parameter: it is
//! periodic with period `tau_n - tau_0`.
//!
//! # Numbers
//!
//! Each coordinate is divided by its own power of two (exact) before solving, as
//! the y(x) spline does, so coordinates near `1e308` do not overflow. Geometric
//! quantities that mix coordinates (lengths, distances, curvature) are computed
//! in units of the largest of these powers of two and converted back at the end.

mod arclen;
mod builder;
mod edit;
mod flatten;
mod nearest;

use crate::bezier::CubicBez;
use crate::error::{Error, Field};
use crate::fast::{self, Piece};
use crate::method::{alpha_terms, piece_coefs_with, ClosedSystem, OpenSystem};
use crate::method::{power_of_two_scale, scale_for_max};
use crate::pieces::Pieces;
use crate::poly::{deriv_of, horner, quadratic_roots};
use crate::polyline::Polyline;
pub use crate::traits::BBox;
use crate::traits::{check_out, Arclen, BezierPieces, Bounds, Flatten, ParamCurve};
use crate::validate::{check_finite, check_knots, Alphas};
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
        write!(
            f,
            "{:?} is not \"uniform\", \"chordal\" or \"centripetal\"",
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
/// use bzspline::Curve;
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
fn norm(v: &[f64]) -> f64 {
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    let s: f64 = v.iter().map(|x| (x / m) * (x / m)).sum();
    m * s.sqrt()
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

/// Checks that `q` holds `dim` numbers: a query point of the curve's
/// dimension, or the output of a batch of queries.
pub(crate) fn check_query(q: &[f64], dim: usize) -> Result<(), Error> {
    if q.len() != dim {
        return Err(Error::LengthMismatch {
            field: Field::Query,
            expected: dim,
            found: q.len(),
        });
    }
    check_finite(Field::Query, q)
}

/// One pass over points of `dim` coordinates: `None` if a coordinate is not
/// finite, else whether two consecutive points are equal; `maxes` gets the
/// largest magnitude of each coordinate.
fn survey(points: &[f64], dim: usize, maxes: &mut Vec<f64>) -> Option<bool> {
    fn fixed<const D: usize>(points: &[f64], maxes: &mut Vec<f64>) -> Option<bool> {
        let (pts, _) = points.as_chunks::<D>();
        let mut mx = [0.0f64; D];
        let mut finite = true;
        let mut repeat = false;
        let mut prev = [f64::NAN; D];
        for p in pts {
            for c in 0..D {
                let a = p[c].abs();
                // Branch-free: NaN fails `a <= MAX`, infinities too.
                finite &= a <= f64::MAX;
                mx[c] = if a > mx[c] { a } else { mx[c] };
            }
            repeat |= *p == prev;
            prev = *p;
        }
        maxes.clear();
        maxes.extend_from_slice(&mx);
        finite.then_some(repeat)
    }
    match dim {
        1 => fixed::<1>(points, maxes),
        2 => fixed::<2>(points, maxes),
        3 => fixed::<3>(points, maxes),
        _ => {
            maxes.clear();
            maxes.resize(dim, 0.0);
            if points.iter().any(|v| !v.is_finite()) {
                return None;
            }
            let mut repeat = false;
            let mut prev: Option<&[f64]> = None;
            for p in points.chunks_exact(dim.max(1)) {
                for (m, v) in maxes.iter_mut().zip(p) {
                    *m = m.max(v.abs());
                }
                repeat |= prev == Some(p);
                prev = Some(p);
            }
            Some(repeat)
        }
    }
}

/// The parameter step of the leg from `a` to `b` in units of `chord_scale`
/// (before multiplying by the curve's `knot_unit`): the chord length, or its
/// square root for centripetal parameters.
fn chord_step(kind: &ParamKind, a: &[f64], b: &[f64], chord_scale: f64, buf: &mut [f64]) -> f64 {
    let inv = 1.0 / chord_scale;
    for ((d, x), y) in buf.iter_mut().zip(a).zip(b) {
        *d = y * inv - x * inv;
    }
    let len = norm(buf);
    if *kind == ParamKind::Centripetal {
        len.sqrt()
    } else {
        len
    }
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

    /// A curve with no points, to be built into.
    fn empty() -> Self {
        Curve {
            closed: false,
            kind: ParamKind::Uniform,
            points: Vec::new(),
            dropped: Vec::new(),
            pieces: Pieces::default(),
            alphas: Vec::new(),
            chord_scale: 1.0,
            knot_unit: 1.0,
            inv_scales: Vec::new(),
            d: Vec::new(),
        }
    }

    /// Parameters for the kind, validates them, and solves into `c`, reusing
    /// its allocations; `c` changes only on success. `alphas` are checked;
    /// `points` come with the largest magnitude of each coordinate.
    #[allow(clippy::too_many_arguments)] // the parts of a builder, validated
    fn solve_into(
        c: &mut Curve,
        dim: usize,
        closed: bool,
        kind: ParamKind,
        (points, maxes): (&[f64], &[f64]),
        dropped: Vec<usize>,
        given: Option<&[f64]>,
        alphas: Alphas<'_>,
    ) -> Result<(), Error> {
        let n = points.len() / dim;
        let legs = if closed { n } else { n - 1 };
        let mut chord_scale = 1.0;
        let mut knot_unit = 1.0;
        // Parameters other than uniform ones are formed aside and validated
        // before anything in `c` changes.
        let aside: Option<Vec<f64>> = match (&kind, given) {
            (ParamKind::Given, Some(g)) => Some(g.to_vec()),
            (ParamKind::Uniform, _) | (ParamKind::Given, None) => None,
            (ParamKind::Chordal | ParamKind::Centripetal, _) => {
                chord_scale = power_of_two_scale(points);
                let mut chord = vec![0.0; dim];
                let mut knots = Vec::with_capacity(legs + 1);
                let mut acc = 0.0;
                knots.push(0.0);
                for k in 0..legs {
                    let j = (k + 1) % n;
                    acc += chord_step(
                        &kind,
                        &points[k * dim..(k + 1) * dim],
                        &points[j * dim..(j + 1) * dim],
                        chord_scale,
                        &mut chord,
                    );
                    knots.push(acc);
                }
                let unit = if kind == ParamKind::Chordal {
                    chord_scale
                } else {
                    chord_scale.sqrt()
                };
                // Back to the points' units unless the total would overflow.
                if (acc * unit).is_finite() {
                    knot_unit = unit;
                    for k in &mut knots {
                        *k *= unit;
                    }
                }
                Some(knots)
            }
        };
        if let Some(k) = &aside {
            check_knots(k)?;
        }
        // From here on nothing fails.
        let parts = c.pieces.parts_mut();
        match aside {
            Some(k) => *parts.knots = k,
            None => {
                parts.knots.clear();
                parts.knots.extend((0..=legs).map(|i| i as f64));
            }
        }
        c.pieces.knots_changed();
        c.pieces.set_scales(maxes.iter().map(|&m| scale_for_max(m)));
        c.alphas.clear();
        match alphas {
            Alphas::Uniform(a) => c.alphas.resize(legs, a),
            Alphas::PerInterval(a) => c.alphas.extend_from_slice(a),
        }
        c.inv_scales.clear();
        c.inv_scales
            .extend(c.pieces.scales().iter().map(|s| 1.0 / s));
        c.closed = closed;
        c.kind = kind;
        c.dropped = dropped;
        c.chord_scale = chord_scale;
        c.knot_unit = knot_unit;
        // One alpha for every leg: known here, no pass over them to find it.
        let uniform = match alphas {
            Alphas::Uniform(a) => Some(a),
            Alphas::PerInterval(_) => None,
        };
        c.solve_all(points, uniform);
        Ok(())
    }

    /// [`Self::solve_into`] for a new curve.
    #[allow(clippy::too_many_arguments)] // the parts of a curve, validated
    fn solve_new(
        dim: usize,
        closed: bool,
        kind: ParamKind,
        points: &[f64],
        dropped: Vec<usize>,
        given: Option<&[f64]>,
        alphas: &[f64],
    ) -> Result<Self, Error> {
        let mut c = Curve::empty();
        let alphas = Alphas::PerInterval(alphas);
        let mut maxes = Vec::new();
        survey(points, dim, &mut maxes);
        let pts = (points, &maxes[..]);
        Self::solve_into(&mut c, dim, closed, kind, pts, dropped, given, alphas)?;
        Ok(c)
    }

    /// Makes `points` the curve's points, solves every coordinate and
    /// rebuilds every segment; `uniform` is the one alpha of every leg when
    /// the caller knows it.
    fn solve_all(&mut self, points: &[f64], uniform: Option<f64>) {
        let dim = self.dim();
        if !self.closed && (1..=3).contains(&dim) {
            // One fused sweep for all coordinates (the arithmetic of
            // `Spline`'s construction).
            let uniform = uniform.or_else(|| {
                self.alphas
                    .first()
                    .copied()
                    .filter(|&a| self.alphas.iter().all(|&b| b == a))
            });
            match dim {
                1 => self.solve_fused::<1>(points, uniform),
                2 => self.solve_fused::<2>(points, uniform),
                _ => self.solve_fused::<3>(points, uniform),
            }
            return;
        }
        self.points.clear();
        self.points.extend_from_slice(points);
        let widths: Vec<f64> = self
            .pieces
            .knots()
            .windows(2)
            .map(|w| w[1] - w[0])
            .collect();
        self.solve_general(&widths);
    }

    /// [`Self::solve_all`] one coordinate at a time through the factored
    /// system: closed curves, more than three dimensions, and the reference
    /// the fused sweep is tested against.
    fn solve_general(&mut self, widths: &[f64]) {
        let (n, dim) = (self.points.len() / self.dim(), self.dim());
        self.d = vec![0.0; n * dim];
        let mut col = vec![0.0; n];
        let mut dev = Vec::with_capacity(n);
        if self.closed {
            let sys = ClosedSystem::new(widths, &self.alphas);
            dev.resize(n, 0.0);
            for c in 0..dim {
                for (i, v) in col.iter_mut().enumerate() {
                    *v = self.fv(i, c);
                }
                sys.solve(&col, &mut dev);
                for (i, v) in dev.iter().enumerate() {
                    self.d[i * dim + c] = *v;
                }
            }
        } else {
            let sys = OpenSystem::new(widths, &self.alphas);
            for c in 0..dim {
                for (i, v) in col.iter_mut().enumerate() {
                    *v = self.fv(i, c);
                }
                sys.solve(&col, &mut dev);
                for (i, v) in dev.iter().enumerate() {
                    self.d[i * dim + c] = *v;
                }
            }
        }
        // Every segment: the alpha terms formed once per leg (once in all for
        // one alpha), the closing leg of a closed curve last.
        let legs = self.len();
        let mut coefs = Vec::with_capacity(legs * dim);
        let uniform = self
            .alphas
            .first()
            .filter(|&&a| self.alphas.iter().all(|&b| b == a))
            .map(|&a| alpha_terms(a));
        for k in 0..legs {
            let j = if k + 1 == n { 0 } else { k + 1 };
            let terms = uniform.unwrap_or_else(|| alpha_terms(self.alphas[k]));
            let (d0, d1) = (&self.d[k * dim..][..dim], &self.d[j * dim..][..dim]);
            for c in 0..dim {
                let (f0, f1) = (self.fv(k, c), self.fv(j, c));
                coefs.push(Piece(piece_coefs_with(f0, f1, d0[c], d1[c], terms)));
            }
        }
        *self.pieces.parts_mut().coefs = coefs;
    }

    fn update_segment(&mut self, k: usize) {
        let (n, dim) = (self.n_points(), self.dim());
        let j = (k + 1) % n;
        let terms = alpha_terms(self.alphas[k]);
        for c in 0..dim {
            let piece = piece_coefs_with(
                self.fv(k, c),
                self.fv(j, c),
                self.d[k * dim + c],
                self.d[j * dim + c],
                terms,
            );
            self.pieces.parts_mut().coefs[k * dim + c] = Piece(piece);
        }
    }

    fn n_points(&self) -> usize {
        self.points.len() / self.dim()
    }

    /// [`fast::sweep::build_open_curve`] in `D` dimensions, which also writes the
    /// copy of the points as it goes.
    fn solve_fused<const D: usize>(&mut self, points: &[f64], uniform: Option<f64>) {
        let knots = self.pieces.knots();
        let span = knots.last().copied().unwrap_or(0.0) - knots.first().copied().unwrap_or(0.0);
        let ws = fast::inverse_power_of_two(span);
        let inv = core::array::from_fn(|c| self.inv_scales.get(c).copied().unwrap_or(1.0));
        let parts = self.pieces.parts_mut();
        fast::sweep::build_open_curve::<D>(
            parts.knots,
            points,
            inv,
            &self.alphas,
            uniform,
            ws,
            parts.coefs,
            &mut self.d,
            &mut self.points,
        );
    }

    /// Coordinate `c` of knot point `i` (the curve's point at knot `i`) in the
    /// curve's units, from `f`, the scaled control point's coordinate.
    #[inline]
    fn knot_coord_with(&self, f: f64, i: usize, c: usize) -> f64 {
        ((f + self.d[i * self.dim() + c]) * self.pieces.scale(c)).clamp(-f64::MAX, f64::MAX)
    }

    /// Coordinate `c` of knot point `i` in the curve's units.
    #[inline]
    fn knot_coord(&self, i: usize, c: usize) -> f64 {
        self.knot_coord_with(self.fv(i, c), i, c)
    }

    /// Coordinate `c` of control point `i`, scaled: `P / scale`.
    #[inline]
    fn fv(&self, i: usize, c: usize) -> f64 {
        self.points[i * self.dim() + c] * self.inv_scales[c]
    }

    /// The dimension `d` of the space.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.pieces.dim()
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

    /// The parameter domain `[tau_0, tau_last]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (
            self.pieces.knots()[0],
            self.pieces.knots()[self.pieces.knots().len() - 1],
        )
    }

    /// Segment and local parameter of `s`.
    fn locate(&self, s: f64) -> Result<(usize, f64), Error> {
        self.locate_near(s, usize::MAX)
    }

    /// [`Curve::locate`], trying segment `hint` and the next one before the
    /// search (queries in order mostly stay in one segment or move to the
    /// next); the segment found is the one the search finds.
    fn locate_near(&self, s: f64, hint: usize) -> Result<(usize, f64), Error> {
        if !s.is_finite() {
            return Err(Error::NonFinite {
                field: Field::Query,
                index: 0,
                value: s,
            });
        }
        let (lo, hi) = self.domain();
        let mut s = s;
        if !(lo..=hi).contains(&s) {
            if !self.closed {
                return Err(Error::OutOfDomain {
                    x: s,
                    min: lo,
                    max: hi,
                });
            }
            s = lo + (s - lo).rem_euclid(hi - lo);
            if !(lo..=hi).contains(&s) {
                s = lo;
            }
        }
        let knots = self.pieces.knots();
        // Segment k answers on [tau_k, tau_{k+1}); the search gives the same.
        let within = |k: usize| k < knots.len() - 1 && knots[k] <= s && s < knots[k + 1];
        let next = hint.wrapping_add(1);
        let k = if within(hint) {
            hint
        } else if within(next) {
            next
        } else {
            self.pieces.locate(s)
        };
        let t = ((s - knots[k]) / self.pieces.width(k)).clamp(0.0, 1.0);
        Ok((k, t))
    }

    /// Derivative of order `order` in the local `t` of segment `k`, in units of
    /// the largest scale, into `out`.
    fn local(&self, k: usize, t: f64, order: u32, out: &mut [f64]) {
        let dim = self.dim();
        let j = (k + 1) % self.n_points();
        for (c, o) in out.iter_mut().enumerate() {
            let rel = self.pieces.scale(c) / self.pieces.unit();
            let v = if order == 0 && t == 1.0 {
                self.fv(j, c) + self.d[j * dim + c]
            } else {
                deriv_of(self.pieces.piece(k, c), t, order)
            };
            *o = v * rel;
        }
    }

    /// The point at parameter `s`.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a NaN or infinite `s`; [`Error::OutOfDomain`]
    /// outside the domain of an open curve (a closed curve is periodic).
    pub fn eval(&self, s: f64) -> Result<Vec<f64>, Error> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(s, &mut out)?;
        Ok(out)
    }

    /// [`Curve::eval`] into `out` (`dim` numbers), without allocating.
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`]; [`Error::InvalidArgument`] when `out` does not hold
    /// [`Curve::dim`] numbers.
    pub fn eval_into(&self, s: f64, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, self.dim())?;
        let (k, t) = self.locate(s)?;
        self.point_at(k, t, out);
        Ok(())
    }

    /// The point at local `t` of segment `k` into `out` (`dim` numbers).
    fn point_at(&self, k: usize, t: f64, out: &mut [f64]) {
        let dim = self.dim();
        let n = self.n_points();
        let j = (k + 1) % n;
        if !self.closed && ((k == 0 && t == 0.0) || (t == 1.0 && j == n - 1)) {
            // An open curve's end points are its end control points, also when
            // one of them underflowed in scaling beside a much larger one.
            let i = if t == 0.0 { 0 } else { n - 1 };
            out.copy_from_slice(&self.points[i * dim..(i + 1) * dim]);
            return;
        }
        for (c, o) in out.iter_mut().enumerate() {
            let v = if t == 1.0 {
                self.fv(j, c) + self.d[j * dim + c]
            } else {
                horner(self.pieces.piece(k, c), t)
            };
            let v = v * self.pieces.scale(c);
            *o = if v.is_infinite() {
                // Rounding above the largest double inside the hull.
                f64::MAX.copysign(v)
            } else {
                v
            };
        }
    }

    /// The derivative of order `order` (0..=3; higher ones are 0) with respect
    /// to the parameter at `s`. At a knot, orders 2 and 3 are those of the
    /// segment to the right.
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`]; [`Error::Overflow`] when a derivative exceeds the
    /// range of a double.
    pub fn deriv(&self, s: f64, order: u32) -> Result<Vec<f64>, Error> {
        let mut out = vec![0.0; self.dim()];
        self.deriv_into(s, order, &mut out)?;
        Ok(out)
    }

    /// [`Curve::deriv`] into `out` (`dim` numbers), without allocating.
    ///
    /// # Errors
    ///
    /// As [`Curve::deriv`]; [`Error::InvalidArgument`] when `out` does not hold
    /// [`Curve::dim`] numbers.
    pub fn deriv_into(&self, s: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, self.dim())?;
        let (k, t) = self.locate(s)?;
        self.deriv_at(k, t, order, out)
    }

    /// The derivative of order `order` at local `t` of segment `k` into `out`.
    fn deriv_at(&self, k: usize, t: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        if order == 0 {
            self.point_at(k, t, out);
            return Ok(());
        }
        let h = self.pieces.width(k);
        for (c, o) in out.iter_mut().enumerate() {
            let mut v = self.pieces.value(k, c, t, order);
            for _ in 0..order.min(4) {
                v /= h;
            }
            if !v.is_finite() {
                return Err(Error::Overflow {
                    what: "the derivative",
                });
            }
            *o = v;
        }
        Ok(())
    }

    /// [`Curve::deriv`] at every parameter of `ss`, into `out` (`dim` numbers
    /// a parameter, parameter after parameter): the same numbers as one call
    /// a parameter, found faster when the parameters come in order (each
    /// search starts from the segment of the one before).
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] when `out` does not hold `dim` numbers for
    /// every parameter; otherwise as [`Curve::deriv`], naming the parameter's
    /// index. `out` is then written up to that parameter.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let ts = [0.0, 0.5, 1.5, 2.5];
    /// let mut out = [0.0; 8];
    /// c.deriv_many(&ts, 0, &mut out)?;
    /// assert_eq!(&out[2..4], c.eval(0.5)?.as_slice());
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn deriv_many(&self, ss: &[f64], order: u32, out: &mut [f64]) -> Result<(), Error> {
        let dim = self.dim();
        check_query(out, ss.len() * dim)?;
        let mut hint = usize::MAX;
        for (i, (&s, o)) in ss.iter().zip(out.chunks_exact_mut(dim)).enumerate() {
            let (k, t) = self.locate_near(s, hint).map_err(|e| e.at_query(i))?;
            self.deriv_at(k, t, order, o)?;
            hint = k;
        }
        Ok(())
    }

    /// The unit tangent at `s` (the zero vector where the derivative vanishes).
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`].
    pub fn tangent(&self, s: f64) -> Result<Vec<f64>, Error> {
        let (k, t) = self.locate(s)?;
        let mut v = vec![0.0; self.dim()];
        self.local(k, t, 1, &mut v);
        let m = norm(&v);
        if m > 0.0 {
            v.iter_mut().for_each(|x| *x /= m);
        }
        Ok(v)
    }

    /// The unit normal at `s`. In the plane it is the tangent turned by +90
    /// degrees, `(-t_y, t_x)`. In other dimensions it is the part of the second
    /// derivative orthogonal to the tangent, normalised (the principal normal);
    /// the zero vector where the curve is straight or the derivative vanishes.
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`].
    pub fn normal(&self, s: f64) -> Result<Vec<f64>, Error> {
        let tan = self.tangent(s)?;
        if self.dim() == 2 {
            return Ok(vec![-tan[1], tan[0]]);
        }
        let (k, t) = self.locate(s)?;
        let mut a = vec![0.0; self.dim()];
        self.local(k, t, 2, &mut a);
        let along = dot(&a, &tan);
        for (x, u) in a.iter_mut().zip(&tan) {
            *x -= along * u;
        }
        let m = norm(&a);
        if m > 0.0 && m.is_finite() && tan.iter().any(|x| *x != 0.0) {
            a.iter_mut().for_each(|x| *x /= m);
        } else {
            a.iter_mut().for_each(|x| *x = 0.0);
        }
        Ok(a)
    }

    /// The curvature `|r' x r''| / |r'|^3` at `s` (unsigned; 0 on a straight
    /// part).
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])?;
    /// assert_eq!(c.curvature(0.7)?, 0.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`]; [`Error::Overflow`] where the derivative vanishes or
    /// the curvature exceeds the range of a double.
    pub fn curvature(&self, s: f64) -> Result<f64, Error> {
        let (k, t) = self.locate(s)?;
        let mut v = vec![0.0; self.dim()];
        let mut a = vec![0.0; self.dim()];
        self.local(k, t, 1, &mut v);
        self.local(k, t, 2, &mut a);
        let speed = norm(&v);
        if speed == 0.0 {
            return Err(Error::Overflow {
                what: "the curvature where the derivative vanishes",
            });
        }
        let u: Vec<f64> = v.iter().map(|x| x / speed).collect();
        let along = dot(&a, &u);
        for (x, u) in a.iter_mut().zip(&u) {
            *x -= along * u;
        }
        let kappa = norm(&a) / speed / speed / self.pieces.unit();
        if kappa.is_finite() {
            Ok(kappa)
        } else {
            Err(Error::Overflow {
                what: "the curvature",
            })
        }
    }

    /// `v` in units of the largest scale back in the curve's units.
    fn to_units(&self, v: f64, what: &'static str) -> Result<f64, Error> {
        let r = v * self.pieces.unit();
        if r.is_finite() {
            Ok(r)
        } else {
            Err(Error::Overflow { what })
        }
    }

    /// `count >= 2` points at equal parameter steps from the start to the end
    /// (a closed curve's last point is its first), with their parameters. For
    /// equal arc-length steps see [`Curve::resample`].
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for `count < 2`.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Curve, Param};
    /// // Uniform parameters: the domain is [0, 2].
    /// let c = Curve::builder_from(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
    ///     .param(Param::Uniform)
    ///     .build()?;
    /// let p = c.sample(3)?;
    /// assert_eq!(p.params(), &[0.0, 1.0, 2.0]);
    /// assert_eq!(p.point(2), Some(&[2.0, 0.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn sample(&self, count: usize) -> Result<Polyline, Error> {
        if count < 2 {
            return Err(Error::InvalidArgument {
                what: "sampling needs at least 2 points",
                value: count as f64,
            });
        }
        let (lo, hi) = self.domain();
        let mut params = Vec::with_capacity(count);
        let mut coords = Vec::with_capacity(count * self.dim());
        for i in 0..count {
            let s = if i + 1 == count {
                hi
            } else {
                (lo + (hi - lo) * (i as f64 / (count - 1) as f64)).min(hi)
            };
            coords.extend(self.eval(s)?);
            params.push(s);
        }
        Ok(Polyline::new(self.dim(), coords, params))
    }

    /// The exact axis-aligned bounding box: per segment and coordinate, the
    /// segment's ends and the roots of its derivative (a quadratic) inside it.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?;
    /// let bb = c.bbox();
    /// assert_eq!((bb.min[0], bb.max[0]), (0.0, 2.0));
    /// // The top is below the middle control point: the curve does not reach it.
    /// assert!(bb.max[1] > 0.5 && bb.max[1] < 2.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    #[must_use]
    pub fn bbox(&self) -> BBox {
        let dim = self.dim();
        let mut min = vec![f64::INFINITY; dim];
        let mut max = vec![f64::NEG_INFINITY; dim];
        for k in 0..self.len() {
            let j = (k + 1) % self.n_points();
            for c in 0..dim {
                let co = self.pieces.piece(k, c);
                let mut vals = vec![
                    self.fv(k, c) + self.d[k * dim + c],
                    self.fv(j, c) + self.d[j * dim + c],
                ];
                for t in quadratic_roots(3.0 * co[3], 2.0 * co[2], co[1]) {
                    if t > 0.0 && t < 1.0 {
                        vals.push(horner(co, t));
                    }
                }
                for v in vals {
                    let v = (v * self.pieces.scale(c)).clamp(-f64::MAX, f64::MAX);
                    min[c] = min[c].min(v);
                    max[c] = max[c].max(v);
                }
            }
        }
        BBox { min, max }
    }

    /// Where the curve touches each leg: `(x_k, alpha_k P_k + (1 - alpha_k)
    /// P_{k+1})` with `x_k = tau_{k+1} - alpha_k h_k` (docs/method.md §9, misprint 1).
    #[must_use]
    pub fn tangent_points(&self) -> Vec<(f64, Vec<f64>)> {
        let (dim, n) = (self.dim(), self.n_points());
        (0..self.len())
            .map(|k| {
                let a = self.alphas[k];
                let h = self.pieces.width(k);
                let j = (k + 1) % n;
                let p = (0..dim)
                    .map(|c| (a * self.fv(k, c) + (1.0 - a) * self.fv(j, c)) * self.pieces.scale(c))
                    .collect();
                (self.pieces.knots()[k + 1] - a * h, p)
            })
            .collect()
    }

    /// The knot points `S(tau_i)`, one per control point; an open curve's first
    /// and last are its end control points exactly.
    #[must_use]
    pub fn knot_points(&self) -> Vec<Vec<f64>> {
        let dim = self.dim();
        (0..self.n_points())
            .map(|i| (0..dim).map(|c| self.knot_coord(i, c)).collect())
            .collect()
    }

    /// The four Bezier control points of segment `k`, each coordinate
    /// multiplied back, flat (`4 * dim` numbers), or `None` past the end.
    /// Consecutive segments share their end points bit for bit. The two inner
    /// control points lie outside the convex hull and can be infinite when the
    /// points come near `f64::MAX` ([`Curve::to_svg_path`] then reports
    /// [`Error::Overflow`]).
    #[must_use]
    pub fn segment_points(&self, k: usize) -> Option<Vec<f64>> {
        if k >= self.len() {
            return None;
        }
        let (dim, n) = (self.dim(), self.n_points());
        let j = (k + 1) % n;
        let a = self.alphas[k];
        let [al, b1, b2, cr] = alpha_terms(a);
        let mut ctrl = vec![0.0; 4 * dim];
        for c in 0..dim {
            let (f0, f1) = (self.fv(k, c), self.fv(j, c));
            let (d0, d1) = (self.d[k * dim + c], self.d[j * dim + c]);
            let df = f1 - f0;
            let s0 = df - d0 * b2 + d1 * cr;
            let s1 = df + d1 * b1 - d0 * al;
            let (p0, p3) = (f0 + d0, f1 + d1);
            let s = self.pieces.scale(c);
            ctrl[c] = p0 * s;
            ctrl[dim + c] = (p0 + s0 / 3.0) * s;
            ctrl[2 * dim + c] = (p3 - s1 / 3.0) * s;
            ctrl[3 * dim + c] = p3 * s;
        }
        if !self.closed {
            // The end control points exactly, as `eval` gives them.
            if k == 0 {
                ctrl[..dim].copy_from_slice(&self.points[..dim]);
            }
            if j == n - 1 {
                ctrl[3 * dim..].copy_from_slice(&self.points[(n - 1) * dim..]);
            }
        }
        Some(ctrl)
    }

    /// Segment `k` as a [`CubicBez<D>`]; `None` past the end or when `D` is not
    /// the curve's dimension.
    #[must_use]
    pub fn segment<const D: usize>(&self, k: usize) -> Option<CubicBez<D>> {
        if D != self.dim() {
            return None;
        }
        let v = self.segment_points(k)?;
        let mut p = [[0.0; D]; 4];
        for (j, pj) in p.iter_mut().enumerate() {
            pj.copy_from_slice(&v[j * D..(j + 1) * D]);
        }
        Some(CubicBez::new(p))
    }

    /// Every segment as a [`CubicBez<D>`]; `None` when `D` is not the curve's
    /// dimension.
    #[must_use]
    pub fn segments<const D: usize>(&self) -> Option<Vec<CubicBez<D>>> {
        (0..self.len()).map(|k| self.segment::<D>(k)).collect()
    }

    /// The SVG path data of a planar curve: `M x y C x1 y1 x2 y2 x y ...`,
    /// closed with `Z`. Numbers are printed in Rust's shortest round-trip form,
    /// so they parse back to the same doubles.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when the curve is not planar;
    /// [`Error::Overflow`] when a Bezier control point exceeds the range of a
    /// double.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])?;
    /// let d = c.to_svg_path()?;
    /// assert!(d.starts_with("M 0 0 C "), "{d}");
    /// assert_eq!(d.matches('C').count(), 2);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn to_svg_path(&self) -> Result<String, Error> {
        if self.dim() != 2 {
            return Err(Error::InvalidArgument {
                what: "an SVG path needs a planar curve; dimension",
                value: self.dim() as f64,
            });
        }
        let mut out = String::new();
        // Writing into a String cannot fail; `false` is a non-finite point.
        match crate::traits::write_svg_path(self, self.closed, &mut out) {
            Ok(true) => Ok(out),
            _ => Err(Error::Overflow {
                what: "a Bezier control point",
            }),
        }
    }
}

impl ParamCurve for Curve {
    fn dim(&self) -> usize {
        Curve::dim(self)
    }
    fn domain(&self) -> (f64, f64) {
        Curve::domain(self)
    }
    fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<(), Error> {
        Curve::eval_into(self, t, out)
    }
    fn deriv_into(&self, t: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        Curve::deriv_into(self, t, order, out)
    }
}

impl Arclen for Curve {
    fn arclen(&self, accuracy: f64) -> Result<f64, Error> {
        Curve::arclen(self, accuracy)
    }
    fn params_at_lengths(&self, lengths: &[f64], accuracy: f64) -> Result<Vec<f64>, Error> {
        Curve::params_at_lengths(self, lengths, accuracy)
    }
}

impl BezierPieces for Curve {
    fn piece_count(&self) -> usize {
        self.len()
    }
    fn piece_into(&self, k: usize, out: &mut [f64]) -> bool {
        match self.segment_points(k) {
            Some(p) if p.len() == out.len() => {
                out.copy_from_slice(&p);
                true
            }
            _ => false,
        }
    }
}

impl Flatten for Curve {
    fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        Curve::flatten(self, tol)
    }
}

impl Bounds for Curve {
    fn bbox(&self) -> BBox {
        Curve::bbox(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::tests::Rng;
    use crate::spline::{Spline, ALPHA_MAX, ALPHA_MIN};

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
    }

    #[test]
    fn building_into_a_curve_gives_the_built_curve_and_keeps_it_on_error() {
        let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
        let helix: Vec<f64> = (0..9)
            .flat_map(|i| {
                let t = f64::from(i);
                [t.cos(), t.sin(), 0.3 * t]
            })
            .collect();
        let repeated = [0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0, 0.0];
        let wave = [0.0, 2.0, 1.0, 3.0, 2.5, 4.0, 0.5, 1.0];
        let builders = [
            Curve::builder(&square, 2),
            Curve::builder(&square, 2)
                .closed(true)
                .param(Param::Chordal),
            Curve::builder(&helix, 3)
                .param(Param::Centripetal)
                .alpha(0.4),
            Curve::builder(&helix, 3).closed(true).alpha(0.6),
            Curve::builder(&wave, 1).param(Param::Given((0..8).map(f64::from).collect())),
            Curve::builder(&repeated, 2).repeats(Repeats::Drop),
            Curve::builder(&helix, 9).closed(true),
        ];
        for b in &builders {
            let want = b.clone().build().unwrap();
            for seed in &builders {
                let mut c = seed.clone().build().unwrap();
                b.clone().build_into(&mut c).unwrap();
                assert_eq!(c, want, "{b:?} into {seed:?}");
            }
            // A refused build leaves the curve as it was.
            let mut c = want.clone();
            let bad = [
                Curve::builder(&repeated, 2),
                Curve::builder(&square, 2).alpha(0.9),
                Curve::builder(&square, 2).param(Param::Given(vec![0.0, 1.0, 1.0, 2.0])),
                Curve::builder(&[0.0, 0.0, 1e-300, 0.0, 1.0, 0.0], 2).param(Param::Chordal),
            ];
            for e in bad {
                assert!(e.clone().build_into(&mut c).is_err(), "{e:?}");
                assert_eq!(c, want);
            }
        }
    }

    #[test]
    fn fused_open_curves_match_the_coordinate_by_coordinate_solve() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        for dim in 1..=3 {
            for n in [2usize, 3, 4, 5, 6, 17, 64, 257] {
                for (param, uniform) in [
                    (Param::Uniform, true),
                    (Param::Chordal, false),
                    (Param::Centripetal, true),
                ] {
                    // Coordinates of different magnitudes in each dimension.
                    let pts: Vec<f64> = (0..n * dim)
                        .map(|i| (rng.next() - 0.5) * [1.0, 1e-200, 3e250][i % dim])
                        .collect();
                    let alphas: Vec<f64> = (0..n - 1)
                        .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
                        .collect();
                    let b = Curve::builder(&pts, dim).param(param.clone());
                    let fast = if uniform {
                        b.alpha(alphas[0])
                    } else {
                        b.alphas(&alphas)
                    }
                    .build()
                    .unwrap();
                    let widths: Vec<f64> = fast.knots().windows(2).map(|w| w[1] - w[0]).collect();
                    let mut slow = fast.clone();
                    slow.solve_general(&widths);
                    // Scaled numbers lie in [-2, 2]: compare them absolutely.
                    let tol = 1e-13;
                    for (i, (p, q)) in fast.d.iter().zip(&slow.d).enumerate() {
                        assert!(
                            (p - q).abs() <= tol,
                            "dim {dim} n {n} {param:?}: deviation {i}: want {q}, got {p}"
                        );
                    }
                    let (fc, sc) = (fast.pieces.coefs(), slow.pieces.coefs());
                    assert_eq!(fc.len(), sc.len());
                    for (i, (Piece(p), Piece(q))) in fc.iter().zip(sc).enumerate() {
                        for j in 0..4 {
                            assert!(
                                (p[j] - q[j]).abs() <= 4.0 * tol,
                                "dim {dim} n {n} {param:?}: piece {i} coef {j}: want {}, got {}",
                                q[j],
                                p[j]
                            );
                        }
                    }
                }
            }
        }
    }

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    #[test]
    fn unit_square_knots_are_pulled_a_tenth_inside() {
        let c = Curve::closed(&SQUARE).unwrap();
        let want = [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]];
        for (k, w) in c.knot_points().iter().zip(want) {
            for i in 0..2 {
                assert!(close(k[i], w[i], 1e-14), "want {w:?}, got {k:?}");
            }
        }
        // Periodic evaluation and C1 across the closing knot.
        let a = c.eval(4.0).unwrap();
        let b = c.eval(0.0).unwrap();
        assert_eq!(a, b);
        let l = c.deriv(4.0 - 1e-9, 1).unwrap();
        let r = c.deriv(1e-9, 1).unwrap();
        for i in 0..2 {
            assert!((l[i] - r[i]).abs() < 1e-7, "{l:?} vs {r:?}");
        }
        assert_eq!(c.eval(5.5).unwrap(), c.eval(1.5).unwrap());
    }

    #[test]
    fn open_curve_matches_per_coordinate_splines() {
        let pts = [[0.0, 1.0], [2.0, 3.0], [3.0, -1.0], [7.0, 0.5], [8.0, 4.0]];
        let alphas = [0.4, ALPHA_MIN, 0.6, ALPHA_MAX];
        for param in [Param::Uniform, Param::Chordal, Param::Centripetal] {
            let c = Curve::builder_from(&pts)
                .param(param.clone())
                .alphas(&alphas)
                .build()
                .unwrap();
            let kp = c.knot_points();
            for dim in 0..2 {
                let v: Vec<f64> = pts.iter().map(|p| p[dim]).collect();
                let s = Spline::with_alphas(c.knots(), &v, &alphas).unwrap();
                for (i, want) in s.knot_values().iter().enumerate() {
                    assert!(
                        close(kp[i][dim], *want, 1e-12),
                        "{param:?} knot {i}: want {want}, got {}",
                        kp[i][dim]
                    );
                }
            }
        }
    }

    #[test]
    fn one_dimensional_curve_is_the_y_of_x_spline() {
        // The paper's Example 1 without its repeated value (a curve refuses
        // repeated points).
        let f = [1.0, 3.0, 3.5, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
        let c = Curve::builder(&f, 1).param(Param::Uniform).build().unwrap();
        let tau: Vec<f64> = (0..f.len()).map(|i| i as f64).collect();
        let s = Spline::new(&tau, &f).unwrap();
        // Spline::build runs its own fused sweep (same equations, another
        // order of operations): equal to rounding, not bit for bit.
        for (k, v) in c.knot_points().iter().zip(s.knot_values()) {
            assert!(close(k[0], v, 1e-13), "want {v}, got {}", k[0]);
        }
        for i in 0..=100 {
            let x = 0.1 * f64::from(i);
            let (a, b) = (c.eval(x).unwrap()[0], s.eval(x).unwrap());
            assert!(close(a, b, 1e-14), "at {x}: want {b}, got {a}");
        }
        assert_eq!(c.normal(2.5).unwrap(), vec![0.0]);
        assert!(c.tangent(2.5).unwrap()[0].abs() == 1.0);
    }

    #[test]
    fn chordal_and_centripetal_parameters() {
        let pts = [[0.0, 0.0], [3.0, 4.0], [3.0, 13.0]];
        let c = Curve::builder_from(&pts)
            .param(Param::Chordal)
            .alpha_choice(Alphas::Uniform(0.4))
            .build()
            .unwrap();
        assert_eq!(c.knots(), &[0.0, 5.0, 14.0]);
        assert_eq!(c.alphas(), &[0.4, 0.4]);
        let c = Curve::builder_from(&pts)
            .param(Param::Centripetal)
            .build()
            .unwrap();
        assert!(close(c.knots()[1], 5f64.sqrt(), 1e-15));
        assert!(close(c.knots()[2], 5f64.sqrt() + 3.0, 1e-15));
    }

    #[test]
    fn errors_name_the_point() {
        let e = Curve::open(&[[0.0, 0.0], [1.0, f64::NAN], [2.0, 0.0]]).unwrap_err();
        assert!(
            matches!(
                e,
                Error::NonFinite {
                    field: Field::Coordinate,
                    index: 1,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [1.0, 1.0]]).unwrap_err();
        assert_eq!(e, Error::RepeatedPoint { index: 2 });
        let e = Curve::closed(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [0.0, 0.0]]).unwrap_err();
        assert_eq!(e, Error::RepeatedClosingPoint { last: 3 });
        assert!(e.to_string().contains("points[3]"));
        assert!(matches!(
            Curve::closed(&[[0.0, 0.0], [1.0, 1.0]]),
            Err(Error::TooFewPoints { found: 2, min: 3 })
        ));
        assert!(matches!(
            Curve::builder(&[1.0, 2.0, 3.0], 2).build(),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(Curve::builder(&[1.0, 2.0], 0).build().is_err());
        assert!(matches!(
            Curve::builder_from(&SQUARE).alpha(0.7).build(),
            Err(Error::AlphaOutOfRange { .. })
        ));
        assert!(matches!(
            Curve::builder_from(&SQUARE)
                .closed(true)
                .param(Param::Given(vec![0.0, 1.0, 2.0, 3.0]))
                .build(),
            Err(Error::LengthMismatch {
                field: Field::Knot,
                expected: 5,
                found: 4
            })
        ));
    }

    #[test]
    fn repeats_can_be_dropped() {
        let pts = [
            [0.0, 0.0],
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [1.0, 1.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.0, 0.0],
        ];
        let alphas = [0.5, 0.4, 0.6, 0.5, 0.5, 0.45, 0.55, 0.35];
        let c = Curve::builder_from(&pts)
            .closed(true)
            .param(Param::Chordal)
            .alphas(&alphas)
            .repeats(Repeats::Drop)
            .build()
            .unwrap();
        assert_eq!(c.dropped(), &[1, 4, 5, 7]);
        assert_eq!(c.point_count(), 4);
        assert_eq!(c.alphas(), &[0.4, 0.6, 0.45, 0.55]);
        let d = Curve::builder_from(&SQUARE)
            .closed(true)
            .param(Param::Chordal)
            .alphas(&[0.4, 0.6, 0.45, 0.55])
            .build()
            .unwrap();
        assert_eq!(c.knot_points(), d.knot_points());
    }

    #[test]
    fn geometry_of_a_circle_like_curve() {
        let n = 64;
        let pts: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [a.cos(), a.sin()]
            })
            .collect();
        let c = Curve::closed(&pts).unwrap();
        // Nearly a circle of radius a little below 1.
        let len = c.arclen(1e-12).unwrap();
        assert!((len - std::f64::consts::TAU).abs() < 1e-2, "{len}");
        let k = c.curvature(10.3).unwrap();
        assert!((k - 1.0).abs() < 2e-2, "{k}");
        // Normal points inwards (counter-clockwise curve).
        let p = c.eval(10.3).unwrap();
        let nrm = c.normal(10.3).unwrap();
        assert!(nrm[0] * p[0] + nrm[1] * p[1] < -0.99);
        let bb = c.bbox();
        assert!(bb.max[0] <= 1.0 && bb.max[0] > 0.99, "{bb:?}");
        // Arc length inverse.
        let s = c.param_at_length(len / 4.0, 1e-10).unwrap();
        let back = c.arclen_range(0.0, s, 1e-12).unwrap();
        assert!((back - len / 4.0).abs() < 1e-9, "{back}");
        let r = c.resample(9, 1e-10).unwrap();
        assert_eq!(r.len(), 9);
        let near = c.nearest(&[2.0, 0.0]).unwrap();
        assert!((near.distance - 1.0).abs() < 1e-2, "{near:?}");
        assert!(near.param.abs() < 1e-9 || (near.param - 64.0).abs() < 1e-9);
    }

    #[test]
    fn space_curve_normal_is_orthogonal_to_tangent() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 2.0],
            [0.0, 1.0, 3.0],
        ];
        let c = Curve::open(&pts).unwrap();
        for s in [0.2, 1.0, 1.7, 2.9] {
            let t = c.tangent(s).unwrap();
            let n = c.normal(s).unwrap();
            assert!((norm(&t) - 1.0).abs() < 1e-14);
            assert!((norm(&n) - 1.0).abs() < 1e-14);
            assert!(dot(&t, &n).abs() < 1e-14);
        }
    }

    #[test]
    fn exports_share_end_points() {
        let c = Curve::closed(&SQUARE).unwrap();
        let segs = c.segments::<2>().unwrap();
        assert_eq!(segs.len(), 4);
        for k in 0..4 {
            assert_eq!(segs[k].p[3], segs[(k + 1) % 4].p[0]);
        }
        assert!(c.segments::<3>().is_none());
        let svg = c.to_svg_path().unwrap();
        assert!(
            svg.starts_with("M 0.1 0.1 C") && svg.ends_with(" Z"),
            "{svg}"
        );
        let c3 = Curve::open(&[[0.0; 3], [1.0, 2.0, 3.0]]).unwrap();
        assert!(c3.to_svg_path().is_err());
        assert_eq!(c3.segment::<3>(0).unwrap().p[3], [1.0, 2.0, 3.0]);
    }

    #[test]
    fn parameters_spanning_the_whole_range_keep_the_system_regular() {
        // Neighbouring steps whose sum rounds above f64::MAX: the knot points
        // must match the same curve on parameters scaled down by 2^-1000.
        let tri = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]];
        let big = vec![2.2250738585072014e-308, 5.376052040422133e307, f64::MAX];
        assert!((big[1] - big[0]) + (big[2] - big[1]) == f64::INFINITY);
        let down = 2f64.powi(-1000);
        let small: Vec<f64> = big.iter().map(|x| x * down).collect();
        let a = Curve::builder_from(&tri)
            .param(Param::Given(big))
            .build()
            .unwrap();
        let b = Curve::builder_from(&tri)
            .param(Param::Given(small))
            .build()
            .unwrap();
        for (p, q) in a.knot_points().iter().zip(b.knot_points()) {
            for i in 0..2 {
                assert!(close(p[i], q[i], 1e-14), "want {q:?}, got {p:?}");
            }
        }
    }

    #[test]
    fn huge_coordinates_stay_finite() {
        let pts = [
            [1e308, -1e308],
            [-1e308, 1.5e308],
            [1.7e308, 0.0],
            [0.0, 1e308],
        ];
        for closed in [false, true] {
            for param in [Param::Uniform, Param::Chordal, Param::Centripetal] {
                let c = Curve::builder_from(&pts)
                    .closed(closed)
                    .param(param)
                    .build()
                    .unwrap();
                let (lo, hi) = c.domain();
                for i in 0..=50 {
                    let s = lo + (hi - lo) * i as f64 / 50.0;
                    assert!(c.eval(s).unwrap().iter().all(|v| v.is_finite()));
                    assert!(c.tangent(s).unwrap().iter().all(|v| v.is_finite()));
                }
                assert!(c.bbox().max.iter().all(|v| v.is_finite()));
                assert!(c.arclen(1e300).is_err() || c.arclen(1e300).unwrap().is_finite());
            }
        }
    }
}

#[cfg(all(test, feature = "serde"))]
mod serde_tests {
    use super::*;

    #[test]
    fn curve_round_trips_through_json() {
        let pts = [[0.0, 0.0], [2.0, 1.0], [3.0, -1.0], [5.0, 0.5]];
        for (closed, param) in [
            (false, Param::Chordal),
            (true, Param::Centripetal),
            (true, Param::Given(vec![0.0, 1.0, 3.0, 4.0, 6.5])),
        ] {
            let c = Curve::builder_from(&pts)
                .closed(closed)
                .param(param)
                .alphas(&[0.4, 0.5, 0.6, 0.45][..if closed { 4 } else { 3 }])
                .build()
                .unwrap();
            let json = serde_json::to_string(&c).unwrap();
            let back: Curve = serde_json::from_str(&json).unwrap();
            assert_eq!(back, c, "{json}");
        }
        // Invalid input is refused on the way in.
        let bad = r#"{"dim":2,"closed":false,"param":"Uniform","points":[0,0,0,0],"alphas":[0.5]}"#;
        let e = serde_json::from_str::<Curve>(bad).unwrap_err();
        assert!(e.to_string().contains("repeats"), "{e}");
    }
}
