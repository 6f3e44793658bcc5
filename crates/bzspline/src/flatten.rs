//! Flattening: a polyline within a given distance of a curve.
//!
//! On a segment with local parameter `t` in `[0, 1]`, the chord between the
//! points at `t0` and `t0 + delta` deviates from the curve by at most
//! `delta^2 / 8 * max |r''(t)|` (the interpolation error of a straight line,
//! which holds for vectors as for scalars). `r''` of a cubic is linear in `t`,
//! so its largest norm is at an end of the segment. With
//! `m = ceil(sqrt(max |r''| / (8 tol)))` equal parameter steps per segment every
//! point of the curve is within `tol` of the polyline; this is the fewest equal
//! steps the bound allows. Vertices are points of the curve, and the first and
//! last are the curve's ends exactly.
//!
//!
//! [`Spline::flatten`](crate::Spline::flatten) takes equal steps per piece; [`Curve::flatten`](crate::Curve::flatten)
//! (module `curve::flatten`) adds the chord search over runs of segments of a
//! planar curve.

use crate::error::{Error, Field};

pub use crate::polyline::Polyline;

/// The most vertices one flattening may produce; a tolerance that would need
/// more is refused.
pub const MAX_FLATTEN_VERTICES: usize = 1 << 24;

/// Refuses a tolerance that is not finite and positive.
pub(crate) fn check_tol(tol: f64) -> Result<(), Error> {
    if !tol.is_finite() {
        return Err(Error::NonFinite {
            field: Field::Tolerance,
            index: 0,
            value: tol,
        });
    }
    if tol <= 0.0 {
        return Err(Error::InvalidArgument {
            what: "the flattening tolerance must be positive",
            value: tol,
        });
    }
    Ok(())
}

/// Steps for a segment whose `|r''|` is at most `accel`, for tolerance `tol`
/// (same units). A small margin covers the rounding of the vertices.
pub(crate) fn steps(accel: f64, tol: f64) -> Result<usize, Error> {
    let x = (accel / (8.0 * tol * 0.999)).sqrt();
    // The ceiling by hand (f64::ceil is a library call on baseline x86-64);
    // the comparison also catches NaN.
    let m = if x < MAX_FLATTEN_VERTICES as f64 {
        let m = x as usize;
        m + usize::from((m as f64) < x)
    } else {
        MAX_FLATTEN_VERTICES
    };
    if m >= MAX_FLATTEN_VERTICES {
        return Err(Error::TooManyVertices { tolerance: tol });
    }
    Ok(m.max(1))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::curve::Curve;
    use crate::spline::Spline;
    use crate::traits::Flatten;

    /// Distance from `p` to the segment `a`-`b`.
    pub(crate) fn seg_dist(p: &[f64], a: &[f64], b: &[f64]) -> f64 {
        let ab: Vec<f64> = a.iter().zip(b).map(|(a, b)| b - a).collect();
        let ap: Vec<f64> = a.iter().zip(p).map(|(a, p)| p - a).collect();
        let l2: f64 = ab.iter().map(|v| v * v).sum();
        let t = if l2 > 0.0 {
            (ab.iter().zip(&ap).map(|(u, v)| u * v).sum::<f64>() / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        ap.iter()
            .zip(&ab)
            .map(|(v, u)| (v - t * u) * (v - t * u))
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn bad_tolerances_are_refused() {
        let c = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]).unwrap();
        for tol in [0.0, -1.0] {
            assert!(matches!(c.flatten(tol), Err(Error::InvalidArgument { .. })));
        }
        assert!(matches!(
            c.flatten(f64::NAN),
            Err(Error::NonFinite {
                field: Field::Tolerance,
                ..
            })
        ));
        assert!(matches!(
            c.flatten(1e-300),
            Err(Error::TooManyVertices { tolerance }) if tolerance == 1e-300
        ));
        // A straight planar curve is one chord; in space, one step per segment.
        let line = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]).unwrap();
        assert_eq!(line.flatten(1e-9).unwrap().len(), 2);
        let line = Curve::open(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]).unwrap();
        assert_eq!(line.flatten(1e-9).unwrap().len(), 3);
    }

    #[test]
    fn spline_flattening_stays_within_tolerance() {
        let x = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0];
        let s = Spline::new(&x, &f).unwrap();
        let tol = 1e-3;
        let p = s.flatten(tol).unwrap();
        assert_eq!(p.point(0).unwrap(), &[1.0, 1.0]);
        assert_eq!(p.point(p.len() - 1).unwrap(), &[6.0, 7.0]);
        for i in 0..=5000 {
            let xq = 1.0 + 5.0 * i as f64 / 5000.0;
            let q = [xq, s.eval(xq).unwrap()];
            let j = p
                .params()
                .partition_point(|&v| v <= xq)
                .clamp(1, p.len() - 1);
            let d = seg_dist(&q, p.point(j - 1).unwrap(), p.point(j).unwrap());
            assert!(d <= tol, "at x = {xq}: {d}");
        }
    }
}
