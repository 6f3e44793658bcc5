//! # bzspline
//!
//! The third-degree Bezier-type spline of O. Stelia, L. Potapenko and I. Sirenko
//! ("On the one method of a third-degree Bezier type spline curve construction").
//!
//! Given knots `tau_0 < ... < tau_{N-1}`, control values `F_k` and one shape
//! parameter `alpha_k` in `[1/3, 2/3]` per interval, the spline `S` is the C1
//! piecewise cubic that
//!
//! 1. touches leg `k` of the control polygon at `x_k = tau_{k+1} - alpha_k h_k`:
//!    `S(x_k) = alpha_k F_k + (1 - alpha_k) F_{k+1}` and
//!    `S'(x_k) = (F_{k+1} - F_k) / h_k` (the paper's conditions (1)-(2));
//! 2. has continuous value and first derivative at every interior knot;
//! 3. starts at `F_0` and ends at `F_{N-1}`.
//!
//! Its knot values `phi_k = F_k + d_k` come from one diagonally dominant
//! tridiagonal system (the paper's (16)), solved in O(N) by the Thomas
//! algorithm; each piece is then exactly one cubic Bezier segment. The spline is
//! linear in `F` with a non-negative basis for alphas in the theorem's range, so it
//! stays inside the convex hull of the control points. `docs/method.md` in the
//! repository derives the equations as implemented, with the proof that the
//! system is diagonally dominant and the three misprints of the paper that this
//! crate does not copy.
//!
//! # Curves
//!
//! [`Curve`] applies the construction to every coordinate of control points in
//! `R^d` on one shared parameter grid ([`Param`]: uniform, chordal, centripetal
//! or given), open or closed; a closed curve solves one cyclic tridiagonal
//! system and is C1 across its closing knot too. A curve has tangents,
//! normals, curvature, equal-length resampling, the nearest point, a local
//! re-solve after moving one control point, and Bezier and SVG export.
//!
//! What curves and splines share is in capability traits, as in kurbo:
//! [`ParamCurve`] (domain and evaluation), [`Arclen`] (arc length and its
//! inverse), [`Bounds`] (the exact bounding box), [`Flatten`] (a polyline within
//! a tolerance) and [`BezierPieces`]; import the trait to call its methods.
//! [`Spline::smoothing`] fits noisy data; the module [`text`] holds the number
//! writer and readers that every output and option parser uses. Optional
//! features: `serde` (Serialize/Deserialize on the data types), `kurbo`
//! (conversion into `kurbo::BezPath`) and `rayon` (parallel batches, large
//! constructions and the smoothing fit's search on several threads, the same
//! bits as on one).
//!
//! ```
//! use bzspline::{Arclen, Curve, DEFAULT_ACCURACY};
//!
//! let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
//! let c = Curve::closed(&square)?; // uniform parameters, alpha = 1/2
//! // Knot points are pulled a tenth inside each corner.
//! let k = c.knot_points();
//! assert!((k[0][0] - 0.1).abs() < 1e-15 && (k[2][1] - 0.9).abs() < 1e-15);
//! assert!(c.arclen(DEFAULT_ACCURACY)? < 4.0);
//! assert!(c.to_svg_path()?.ends_with('Z'));
//! # Ok::<(), bzspline::Error>(())
//! ```
//!
//! Knots and intervals are numbered from 0 here (the paper numbers from 1):
//! interval `k` runs from `knots[k]` to `knots[k + 1]` and has `alphas[k]`.
//!
//! # Example: the paper's Example 1
//!
//! ```
//! use bzspline::Spline;
//!
//! let tau: Vec<f64> = (1..=11).map(f64::from).collect();
//! let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
//! let s = Spline::new(&tau, &f)?; // alpha = 1/2 on every interval
//!
//! // Ends at the end points, touches every leg at its middle.
//! assert_eq!(s.eval(1.0)?, 1.0);
//! assert_eq!(s.eval(11.0)?, 1.5);
//! for (k, (x, fk)) in s.tangent_points().into_iter().enumerate() {
//!     assert!((s.eval(x)? - fk).abs() < 1e-12);
//!     assert!((s.deriv(x, 1)? - (f[k + 1] - f[k])).abs() < 1e-12);
//! }
//! // Stays within the range of the control values (convex hull property).
//! let ((_, lo), (_, hi)) = s.range();
//! assert!(lo >= 1.0 && hi <= 10.0);
//! // Every piece is one cubic Bezier segment.
//! let seg = s.segment(0).unwrap();
//! assert_eq!(seg.p[0], [1.0, 1.0]);
//! # Ok::<(), bzspline::Error>(())
//! ```

mod bezier;
mod curve;
mod error;
mod fast;
mod flatten;
mod fraction;
#[cfg(feature = "kurbo")]
mod kurbo_path;
mod lanes;
pub(crate) mod method;
mod num;
mod pieces;
mod poly;
mod polyline;
mod smoothing;
mod spline;
#[cfg(test)]
mod testing;
mod traits;
mod tridiag;
mod validate;

/// Numbers as text: the shortest round-trip writer every output uses, and
/// the readers of numbers and fractions (`1/3`) that every entry point's
/// options use.
pub mod text {
    pub use crate::fraction::{parse_alpha, parse_fraction};
    pub use crate::num::Shortest;
}

pub use bezier::CubicBez;
pub use curve::{
    BBox, Curve, CurveBuilder, Nearest, Param, Repeats, UnknownParam, DEFAULT_ACCURACY,
};
pub use error::{Error, Field};
pub use flatten::{Polyline, MAX_FLATTEN_VERTICES};
pub use smoothing::{
    band_z, normal_quantile, Posterior, PosteriorParts, Smoothed, Smoothing, ROBUST_MIN_POINTS,
};
pub use spline::{
    check_alpha, AlphaChoice, Alphas, Antiderivative, Extrapolate, Extremum, ExtremumKind, Spline,
    UnknownExtrapolation, ALPHA_MAX, ALPHA_MIN, DEFAULT_ALPHA, MIN_RELATIVE_INTERVAL,
};
pub use traits::{write_svg_path, Arclen, BezierPieces, Bounds, Flatten, ParamCurve};
