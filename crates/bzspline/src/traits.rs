//! Capabilities shared by the crate's curve types, in the spirit of kurbo's
//! `ParamCurve` family but for any dimension: evaluation and derivatives into a
//! caller's buffer ([`ParamCurve`]), the pieces as cubic Bezier segments
//! ([`BezierPieces`]), flattening ([`Flatten`]), the exact bounding box
//! ([`Bounds`]) and arc length ([`Arclen`], not for a lone [`CubicBez`]).
//!
//! [`Curve`] implements them in its own dimension; a [`Spline`] as its graph,
//! the planar curve `x -> (x, S(x))`; a [`CubicBez`] on `t` in `[0, 1]`. Generic
//! code (the command, the geo and Python crates) writes against these.
//!
//! ```
//! use bzspline::{Curve, ParamCurve, Spline};
//!
//! /// The midpoint of the domain, whatever the curve.
//! fn middle(c: &impl ParamCurve) -> Vec<f64> {
//!     let (a, b) = c.domain();
//!     let mut p = vec![0.0; c.dim()];
//!     c.eval_into(0.5 * (a + b), &mut p).unwrap();
//!     p
//! }
//! let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
//! assert_eq!(middle(&s), vec![1.0, s.eval(1.0)?]);
//! let c = Curve::open(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 0.0, 2.0]])?;
//! let (a, b) = c.domain();
//! assert_eq!(middle(&c), c.eval(0.5 * (a + b))?);
//! # Ok::<(), bzspline::Error>(())
//! ```

use crate::error::Error;
use crate::num::Shortest;
use crate::polyline::Polyline;

/// The axis-aligned box spanned by a curve.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BBox {
    /// Smallest value of each coordinate.
    pub min: Vec<f64>,
    /// Largest value of each coordinate.
    pub max: Vec<f64>,
}

/// Refuses an output buffer that does not hold `dim` numbers.
pub(crate) fn check_out(out: &[f64], dim: usize) -> Result<(), Error> {
    if out.len() == dim {
        Ok(())
    } else {
        Err(Error::InvalidArgument {
            what: "the output buffer must hold one number per coordinate; its length",
            value: out.len() as f64,
        })
    }
}

/// A curve `t -> C(t)` in `R^dim` over a parameter interval.
pub trait ParamCurve {
    /// How many coordinates a point has.
    fn dim(&self) -> usize;

    /// The parameter interval `(start, end)`.
    fn domain(&self) -> (f64, f64);

    /// The point at `t` into `out`, which holds [`ParamCurve::dim`] numbers.
    ///
    /// # Errors
    ///
    /// A typed error for a parameter the curve does not answer at (not finite,
    /// or outside the domain where the type refuses that), or an `out` of the
    /// wrong length.
    fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<(), Error>;

    /// The derivative of order `order` with respect to `t` into `out` (order 0
    /// is the point).
    ///
    /// # Errors
    ///
    /// As [`ParamCurve::eval_into`]; an overflow of the derivative.
    fn deriv_into(&self, t: f64, order: u32, out: &mut [f64]) -> Result<(), Error>;

    /// The point at `t` as an array of `D` coordinates (`Curve::point(i)` is
    /// control point `i`, not this).
    ///
    /// # Errors
    ///
    /// As [`ParamCurve::eval_into`] (`D` must be the dimension).
    fn point_at<const D: usize>(&self, t: f64) -> Result<[f64; D], Error>
    where
        Self: Sized,
    {
        let mut p = [0.0; D];
        self.eval_into(t, &mut p)?;
        Ok(p)
    }
}

/// Arc length and its inverse, in the spirit of kurbo's `ParamCurveArclen`.
pub trait Arclen {
    /// The length of the whole curve, to `accuracy` (absolute, in the
    /// curve's units).
    ///
    /// # Errors
    ///
    /// A typed error for an accuracy that is not finite and positive, or a
    /// length that overflows.
    fn arclen(&self, accuracy: f64) -> Result<f64, Error>;

    /// The parameters at which the length from the start is `lengths[i]`,
    /// each to `accuracy` in length.
    ///
    /// # Errors
    ///
    /// As [`Arclen::arclen`]; a length that is not finite or lies outside
    /// `[0, arclen]` by more than the accuracy, with its index.
    fn params_at_lengths(&self, lengths: &[f64], accuracy: f64) -> Result<Vec<f64>, Error>;
}

/// A curve made of cubic Bezier segments, exactly.
pub trait BezierPieces {
    /// How many segments.
    fn piece_count(&self) -> usize;

    /// The four control points of segment `k`, flat (`4 * dim` numbers), into
    /// `out`; false past the last segment or for an `out` of the wrong length.
    fn piece_into(&self, k: usize, out: &mut [f64]) -> bool;
}

/// A polyline within a distance of the curve.
///
/// On a segment with local parameter `t` in `[0, 1]`, the chord between the
/// points at `t0` and `t0 + delta` deviates from the curve by at most
/// `delta^2 / 8 * max |r''(t)|`, and `r''` of a cubic is linear in `t`, largest
/// at an end of the segment; `m = ceil(sqrt(max |r''| / (8 tol)))` equal steps
/// a segment keep every point of the curve within `tol` of the polyline, the
/// fewest equal steps the bound allows. Vertices are points of the curve, and
/// the first and last are its ends exactly. A spline takes equal steps a
/// piece; a planar curve also merges runs of segments that stay within `tol`
/// of one chord.
pub trait Flatten {
    /// Vertices on the curve, every point of the curve within `tol` of the
    /// polyline; the first and last vertices are the curve's ends.
    ///
    /// # Errors
    ///
    /// A tolerance that is not a finite positive number, or one that needs too
    /// many vertices.
    fn flatten(&self, tol: f64) -> Result<Polyline, Error>;
}

/// The exact axis-aligned bounding box.
pub trait Bounds {
    /// The smallest and largest value of each coordinate over the curve.
    fn bbox(&self) -> BBox;
}

/// Writes the SVG path data of a planar curve's pieces into `out`, formed while
/// it is written: `M x0 y0` and one `C x1 y1 x2 y2 x3 y3` a piece, each number
/// as [`Shortest`] writes it, and ` Z` when `closed`. Returns
/// `Ok(false)`, having written the pieces before it, at the first piece with a
/// control point that is not finite (near `f64::MAX` the inner control points
/// can overflow; [`Curve::to_svg_path`](crate::Curve::to_svg_path) reports that as an error), and for a
/// curve that is not planar.
///
/// # Errors
///
/// `out`'s write errors.
///
/// # Examples
///
/// ```
/// use bzspline::{write_svg_path, Spline};
/// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
/// let mut d = String::new();
/// assert!(write_svg_path(&s, false, &mut d).unwrap());
/// assert!(d.starts_with("M 0 0 C ") && d.matches(" C ").count() == 2);
/// # Ok::<(), bzspline::Error>(())
/// ```
pub fn write_svg_path<W: std::fmt::Write>(
    c: &(impl BezierPieces + ?Sized),
    closed: bool,
    out: &mut W,
) -> Result<bool, std::fmt::Error> {
    let mut p = [0.0; 8];
    for k in 0..c.piece_count() {
        if !c.piece_into(k, &mut p) || p.iter().any(|v| !v.is_finite()) {
            return Ok(false);
        }
        if k == 0 {
            write!(out, "M {} {}", Shortest(p[0]), Shortest(p[1]))?;
        }
        out.write_str(" C")?;
        for v in &p[2..] {
            write!(out, " {}", Shortest(*v))?;
        }
    }
    if closed {
        out.write_str(" Z")?;
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Curve, Spline};

    /// Central differences of `eval_into` against `deriv_into` at a few
    /// parameters inside every piece, for any of the types.
    fn check_derivatives(c: &impl ParamCurve, params: &[f64]) {
        let d = c.dim();
        let (mut lo, mut hi, mut p1) = (vec![0.0; d], vec![0.0; d], vec![0.0; d]);
        for &t in params {
            let h = 1e-6;
            c.eval_into(t - h, &mut lo).unwrap();
            c.eval_into(t + h, &mut hi).unwrap();
            c.deriv_into(t, 1, &mut p1).unwrap();
            for i in 0..d {
                let fd = (hi[i] - lo[i]) / (2.0 * h);
                assert!(
                    (fd - p1[i]).abs() < 1e-6 * (1.0 + p1[i].abs()),
                    "t = {t}, coordinate {i}: difference {fd}, derivative {}",
                    p1[i]
                );
            }
        }
    }

    #[test]
    fn the_three_types_answer_alike() {
        let s = Spline::new(&[0.0, 1.0, 2.5, 3.0], &[1.0, -1.0, 2.0, 0.5]).unwrap();
        check_derivatives(&s, &[0.3, 1.7, 2.9]);
        let pts = [0.0, 0.0, 1.0, 2.0, 0.0, 0.0, 2.0, 1.0, 2.0, 0.0, 1.0, 0.0];
        let c = Curve::builder(&pts, 3)
            .closed(true)
            .param(crate::Param::Uniform)
            .build()
            .unwrap();
        check_derivatives(&c, &[0.2, 1.5, 3.8]);
        let b = c.segment::<3>(1).unwrap();
        check_derivatives(&b, &[0.1, 0.5, 0.9]);
        // The segment and the curve agree on the segment's span.
        let (mut pb, mut pc) = ([0.0; 3], [0.0; 3]);
        b.eval_into(0.25, &mut pb).unwrap();
        c.eval_into(1.25, &mut pc).unwrap();
        for i in 0..3 {
            assert!((pb[i] - pc[i]).abs() < 1e-14, "{pb:?} {pc:?}");
        }
        // A buffer of the wrong length is refused, not a panic.
        assert!(c.eval_into(0.5, &mut [0.0; 2]).is_err());
        assert!(s.deriv_into(0.5, 1, &mut [0.0; 3]).is_err());
        assert!(b.eval_into(f64::NAN, &mut pb).is_err());
    }

    #[test]
    fn pieces_boxes_and_flattening_agree_with_the_types_own() {
        let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
        let mut buf = [0.0; 8];
        assert_eq!(c.piece_count(), 3);
        assert!(c.piece_into(1, &mut buf));
        assert_eq!(buf.to_vec(), c.segment_points(1).unwrap());
        assert!(!c.piece_into(3, &mut buf));
        let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0]).unwrap();
        assert!(s.piece_into(0, &mut buf));
        assert_eq!(&buf[..2], &[0.0, 0.0]);
        // The Bezier segment's exact box against dense sampling.
        let b = c.segment::<2>(1).unwrap();
        let bb = Bounds::bbox(&b);
        for i in 0..=1000 {
            let p = b.eval(f64::from(i) / 1000.0);
            for (k, v) in p.iter().enumerate() {
                assert!(*v >= bb.min[k] - 1e-12 && *v <= bb.max[k] + 1e-12);
            }
        }
        let top = (0..=100_000)
            .map(|i| b.eval(f64::from(i) / 100_000.0)[1])
            .fold(f64::MIN, f64::max);
        assert!((top - bb.max[1]).abs() < 1e-9, "{top} {}", bb.max[1]);
        // Flattening the segment: vertices on it, chords within the tolerance
        // of points between them.
        let tol = 1e-4;
        let poly = Flatten::flatten(&b, tol).unwrap();
        let v = poly.to_arrays::<2>().unwrap();
        assert_eq!(v[0], b.p[0]);
        assert_eq!(v[v.len() - 1], b.p[3]);
        for (w, t) in v.windows(2).zip(poly.params().windows(2)) {
            let mid = b.eval(0.5 * (t[0] + t[1]));
            let (dx, dy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
            let dist = ((mid[0] - w[0][0]) * dy - (mid[1] - w[0][1]) * dx).abs() / dx.hypot(dy);
            assert!(dist <= tol, "{dist}");
        }
    }
}
