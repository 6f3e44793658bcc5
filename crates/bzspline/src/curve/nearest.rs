//! The point of a curve nearest to a given point.
//!
//! On a segment the squared distance `|r(t) - q|^2` has the derivative
//! `2 (r(t) - q) . r'(t)`, a quintic in `t`. Its real roots in `[0, 1]` are
//! isolated between the roots of its derivative (recursively, down to a
//! quadratic), where it is monotone, and found by bisection; with the
//! segment's ends they are the candidates for the minimum.

use super::{check_query, norm, Curve, Nearest};
use crate::error::Error;
use crate::method::power_of_two_scale;
use crate::poly::quadratic_roots;
use crate::traits::ParamCurve;

/// Real roots in `[lo, hi]` of the polynomial with power coefficients `c`
/// (lowest first), by isolating them between the roots of its derivative:
/// between two consecutive critical points the polynomial is monotone, so a
/// sign change brackets exactly one root, found by bisection.
pub(crate) fn real_roots_in(c: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let eval = |t: f64| c.iter().rev().fold(0.0, |acc, v| acc * t + v);
    if c.len() <= 3 {
        let (a, b, c0) = (
            c.get(2).copied().unwrap_or(0.0),
            c.get(1).copied().unwrap_or(0.0),
            c.first().copied().unwrap_or(0.0),
        );
        return quadratic_roots(a, b, c0)
            .into_iter()
            .filter(|t| (lo..=hi).contains(t))
            .collect();
    }
    let dc: Vec<f64> = c
        .iter()
        .enumerate()
        .skip(1)
        .map(|(i, v)| i as f64 * v)
        .collect();
    let mut crit = real_roots_in(&dc, lo, hi);
    crit.sort_unstable_by(f64::total_cmp);
    let mut pts = Vec::with_capacity(crit.len() + 2);
    pts.push(lo);
    pts.extend(crit);
    pts.push(hi);
    let mut out = Vec::new();
    for w in pts.windows(2) {
        let (mut a, mut b) = (w[0], w[1]);
        let (mut fa, fb) = (eval(a), eval(b));
        if fa == 0.0 {
            out.push(a);
            continue;
        }
        if fb == 0.0 || fa.signum() == fb.signum() {
            continue;
        }
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                break;
            }
            let fm = eval(m);
            if fm == 0.0 {
                a = m;
                b = m;
                break;
            }
            if fm.signum() == fa.signum() {
                a = m;
                fa = fm;
            } else {
                b = m;
            }
        }
        out.push(0.5 * (a + b));
    }
    if eval(hi) == 0.0 {
        out.push(hi);
    }
    out
}

impl Curve {
    /// The point of the curve nearest to `q`: per segment, the roots of the
    /// derivative of the squared distance (a quintic, isolated between the
    /// roots of its derivatives) and the segment's ends.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] when `q` does not have [`Curve::dim`]
    /// coordinates; [`Error::NonFinite`] for a non-finite coordinate;
    /// [`Error::Overflow`] when the distance exceeds the range of a double.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])?;
    /// let n = c.nearest(&[1.5, 3.0])?;
    /// assert!((n.point[0] - 1.5).abs() < 1e-12 && (n.distance - 3.0).abs() < 1e-12);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn nearest(&self, q: &[f64]) -> Result<Nearest, Error> {
        check_query(q, self.dim())?;
        let dim = self.dim();
        // One unit for the curve and the query, so that neither overflows.
        let unit = self.pieces.unit().max(power_of_two_scale(q));
        let to_unit = self.pieces.unit() / unit;
        let qs: Vec<f64> = q.iter().map(|v| v / unit).collect();
        let mut best = (f64::INFINITY, 0usize, 0.0f64);
        let mut diff = vec![0.0; dim];
        for k in 0..self.len() {
            // g(t) = (r(t) - q) . r'(t), degree 5, lowest coefficient first.
            let mut g = [0.0f64; 6];
            for (c, qc) in qs.iter().enumerate() {
                let rel = self.pieces.scale(c) / unit;
                let co = self.pieces.piece(k, c).map(|v| v * rel);
                let p = [co[0] - qc, co[1], co[2], co[3]];
                let dp = [co[1], 2.0 * co[2], 3.0 * co[3]];
                for (i, a) in p.iter().enumerate() {
                    for (j, b) in dp.iter().enumerate() {
                        g[i + j] += a * b;
                    }
                }
            }
            let mut cands = real_roots_in(&g, 0.0, 1.0);
            cands.push(0.0);
            cands.push(1.0);
            for t in cands {
                self.local(k, t, 0, &mut diff);
                for (x, qc) in diff.iter_mut().zip(&qs) {
                    *x = *x * to_unit - qc;
                }
                let dist = norm(&diff);
                if dist < best.0 {
                    best = (dist, k, t);
                }
            }
        }
        let (dist, k, t) = best;
        let h = self.pieces.width(k);
        let param = (self.pieces.knots()[k] + t * h).min(self.pieces.knots()[k + 1]);
        let point = self.eval(param)?;
        let distance = dist * unit;
        if !distance.is_finite() {
            return Err(Error::Overflow {
                what: "the distance",
            });
        }
        Ok(Nearest {
            param,
            point,
            distance,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_queries_do_not_overflow() {
        let c = Curve::open(&[[1e-3, 0.0], [2e-3, 1e-3], [3e-3, 0.0]]).unwrap();
        let n = c.nearest(&[1e10, 0.0]).unwrap();
        assert_eq!(n.point, vec![3e-3, 0.0]);
        // So far away the whole curve is at one distance, to rounding.
        let n = c.nearest(&[1e308, 0.0]).unwrap();
        assert!((n.distance - 1e308).abs() <= 1e293, "{}", n.distance);
        let n = c.nearest(&[-1e300, -1e300]).unwrap();
        assert_eq!(n.param, 0.0);
        assert!(c.nearest(&[f64::MAX, f64::MAX]).is_err());
        assert!(c.nearest(&[0.0, f64::NAN]).is_err());
        assert!(c.nearest(&[0.0]).is_err());
    }

    #[test]
    fn root_isolation_finds_close_roots() {
        // (t - 0.3)(t - 0.30001)(t - 0.7)(t + 2)(t - 0.9)
        let roots = [0.3, 0.30001, 0.7, -2.0, 0.9];
        let mut c = vec![1.0];
        for r in roots {
            let mut next = vec![0.0; c.len() + 1];
            for (i, v) in c.iter().enumerate() {
                next[i + 1] += v;
                next[i] -= r * v;
            }
            c = next;
        }
        let mut got = real_roots_in(&c, 0.0, 1.0);
        got.sort_unstable_by(f64::total_cmp);
        assert_eq!(got.len(), 4, "{got:?}");
        for (g, w) in got.iter().zip([0.3, 0.30001, 0.7, 0.9]) {
            // The close pair is ill-conditioned: rounding moves it by ~1e-11.
            assert!((g - w).abs() < 1e-9, "want {w}, got {g}");
        }
    }
}
