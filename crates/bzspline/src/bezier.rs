//! Cubic Bezier segments in `R^D`: the exact export form of every piece.

use crate::error::{Error, Field};
use crate::poly::quadratic_roots;
use crate::polyline::Polyline;
use crate::traits::{check_out, BBox, BezierPieces, Bounds, Flatten, ParamCurve};

/// A cubic Bezier segment with control points `p[0] .. p[3]` in `R^D`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicBez<const D: usize> {
    /// The four control points; the segment starts at `p[0]` and ends at `p[3]`.
    pub p: [[f64; D]; 4],
}

impl<const D: usize> CubicBez<D> {
    /// A segment from its control points.
    #[must_use]
    pub const fn new(p: [[f64; D]; 4]) -> Self {
        CubicBez { p }
    }

    /// The point at `t` in `[0, 1]` (de Casteljau's algorithm, which stays inside
    /// the control points' hull for `t` in `[0, 1]`).
    #[must_use]
    pub fn eval(&self, t: f64) -> [f64; D] {
        let lerp = |a: [f64; D], b: [f64; D]| -> [f64; D] {
            let mut r = a;
            for i in 0..D {
                r[i] = a[i] + t * (b[i] - a[i]);
            }
            r
        };
        let [p0, p1, p2, p3] = self.p;
        let (a, b, c) = (lerp(p0, p1), lerp(p1, p2), lerp(p2, p3));
        let (d, e) = (lerp(a, b), lerp(b, c));
        lerp(d, e)
    }

    /// The derivative with respect to `t` at `t`.
    #[must_use]
    pub fn deriv(&self, t: f64) -> [f64; D] {
        let [p0, p1, p2, p3] = self.p;
        let mt = 1.0 - t;
        let mut r = [0.0; D];
        for i in 0..D {
            r[i] = 3.0
                * (mt * mt * (p1[i] - p0[i])
                    + 2.0 * mt * t * (p2[i] - p1[i])
                    + t * t * (p3[i] - p2[i]));
        }
        r
    }

    /// The second derivative with respect to `t` at `t`.
    #[must_use]
    pub fn deriv2(&self, t: f64) -> [f64; D] {
        let [p0, p1, p2, p3] = self.p;
        let mut r = [0.0; D];
        for i in 0..D {
            r[i] = 6.0
                * ((1.0 - t) * (p2[i] - 2.0 * p1[i] + p0[i]) + t * (p3[i] - 2.0 * p2[i] + p1[i]));
        }
        r
    }

    /// Splits at `t` into the segments on `[0, t]` and `[t, 1]`.
    #[must_use]
    pub fn subdivide(&self, t: f64) -> (Self, Self) {
        let lerp = |a: [f64; D], b: [f64; D]| -> [f64; D] {
            let mut r = a;
            for i in 0..D {
                r[i] = a[i] + t * (b[i] - a[i]);
            }
            r
        };
        let [p0, p1, p2, p3] = self.p;
        let (a, b, c) = (lerp(p0, p1), lerp(p1, p2), lerp(p2, p3));
        let (d, e) = (lerp(a, b), lerp(b, c));
        let m = lerp(d, e);
        (Self::new([p0, a, d, m]), Self::new([m, e, c, p3]))
    }

    /// Power-basis coefficients per coordinate: the point at `t` is
    /// `c[0] + c[1] t + c[2] t^2 + c[3] t^3`.
    #[must_use]
    pub fn power_coefficients(&self) -> [[f64; D]; 4] {
        let [p0, p1, p2, p3] = self.p;
        let mut c = [[0.0; D]; 4];
        for i in 0..D {
            c[0][i] = p0[i];
            c[1][i] = 3.0 * (p1[i] - p0[i]);
            c[2][i] = 3.0 * (p2[i] - 2.0 * p1[i] + p0[i]);
            c[3][i] = p3[i] - 3.0 * (p2[i] - p1[i]) - p0[i];
        }
        c
    }
}

/// On `t` in `[0, 1]`; the polynomial is evaluated at any finite `t`.
impl<const D: usize> ParamCurve for CubicBez<D> {
    fn dim(&self) -> usize {
        D
    }
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<(), Error> {
        self.deriv_into(t, 0, out)
    }
    fn deriv_into(&self, t: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, D)?;
        if !t.is_finite() {
            return Err(Error::NonFinite {
                field: Field::Query,
                index: 0,
                value: t,
            });
        }
        let [p0, p1, p2, p3] = self.p;
        let v = match order {
            0 => self.eval(t),
            1 => self.deriv(t),
            2 => self.deriv2(t),
            3 => std::array::from_fn(|i| 6.0 * (p3[i] - 3.0 * p2[i] + 3.0 * p1[i] - p0[i])),
            _ => [0.0; D],
        };
        if v.iter().any(|x| !x.is_finite()) {
            return Err(Error::Overflow {
                what: "the derivative",
            });
        }
        out.copy_from_slice(&v);
        Ok(())
    }
}

impl<const D: usize> BezierPieces for CubicBez<D> {
    fn piece_count(&self) -> usize {
        1
    }
    fn piece_into(&self, k: usize, out: &mut [f64]) -> bool {
        if k != 0 || out.len() != 4 * D {
            return false;
        }
        out.copy_from_slice(self.p.as_flattened());
        true
    }
}

/// The fewest equal steps in `t` that keep every chord within `tol`: the
/// chord over a step `delta` is within `delta^2 / 8 max |C''|` of the curve,
/// and `C''` is linear in `t`, largest at an end (`docs/method.md` §3; the
/// bound of [`Flatten`](crate::Flatten)).
impl<const D: usize> Flatten for CubicBez<D> {
    fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        if !(tol.is_finite() && tol > 0.0) {
            return Err(Error::InvalidArgument {
                what: "the flattening tolerance must be a positive number",
                value: tol,
            });
        }
        let norm = |v: [f64; D]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let m2 = norm(self.deriv2(0.0)).max(norm(self.deriv2(1.0)));
        let steps = (m2 / (8.0 * tol)).sqrt().ceil().max(1.0);
        // m2 is finite for finite control points; NaN only for non-finite ones.
        if steps.is_nan() || steps > crate::MAX_FLATTEN_VERTICES as f64 {
            return Err(Error::TooManyVertices { tolerance: tol });
        }
        let n = steps as usize;
        let mut coords = Vec::with_capacity((n + 1) * D);
        let mut params = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let t = if i == n { 1.0 } else { i as f64 / n as f64 };
            let p = if i == n { self.p[3] } else { self.eval(t) };
            coords.extend_from_slice(&p);
            params.push(t);
        }
        Ok(Polyline::new(D, coords, params))
    }
}

/// Per coordinate, the ends and the roots of the derivative (a quadratic)
/// inside `(0, 1)`.
impl<const D: usize> Bounds for CubicBez<D> {
    fn bbox(&self) -> BBox {
        let [p0, p1, p2, p3] = self.p;
        let mut min = vec![0.0; D];
        let mut max = vec![0.0; D];
        for i in 0..D {
            // C'(t) / 3 = a t^2 + b t + c in the power basis.
            let a = p3[i] - 3.0 * p2[i] + 3.0 * p1[i] - p0[i];
            let b = 2.0 * (p2[i] - 2.0 * p1[i] + p0[i]);
            let c = p1[i] - p0[i];
            let (mut lo, mut hi) = (p0[i].min(p3[i]), p0[i].max(p3[i]));
            for t in quadratic_roots(a, b, c) {
                if t > 0.0 && t < 1.0 {
                    let v = self.eval(t)[i];
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
            min[i] = lo;
            max[i] = hi;
        }
        BBox { min, max }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eval_deriv_agree_with_power_form_and_differences() {
        let b = CubicBez::new([[0.0, 1.0], [1.0, 3.0], [2.5, -1.0], [3.0, 0.5]]);
        let c = b.power_coefficients();
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            let p = b.eval(t);
            for d in 0..2 {
                let want = c[0][d] + t * (c[1][d] + t * (c[2][d] + t * c[3][d]));
                assert!(
                    (p[d] - want).abs() < 1e-14,
                    "t={t}: want {want}, got {}",
                    p[d]
                );
            }
            let eps = 1e-6;
            let (a, z) = (b.eval(t - eps), b.eval(t + eps));
            let dv = b.deriv(t);
            let d2 = b.deriv2(t);
            let (da, dz) = (b.deriv(t - eps), b.deriv(t + eps));
            for d in 0..2 {
                let fd = (z[d] - a[d]) / (2.0 * eps);
                assert!((dv[d] - fd).abs() < 1e-7, "deriv: want {fd}, got {}", dv[d]);
                let fd2 = (dz[d] - da[d]) / (2.0 * eps);
                assert!(
                    (d2[d] - fd2).abs() < 1e-6,
                    "deriv2: want {fd2}, got {}",
                    d2[d]
                );
            }
        }
    }

    #[test]
    fn subdivide_reproduces_both_halves() {
        let b = CubicBez::new([
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [2.0, 2.0, 1.0],
            [3.0, 0.0, 2.0],
        ]);
        let (l, r) = b.subdivide(0.3);
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            let (pl, pr) = (l.eval(s), r.eval(s));
            let (wl, wr) = (b.eval(0.3 * s), b.eval(0.3 + 0.7 * s));
            for d in 0..3 {
                assert!((pl[d] - wl[d]).abs() < 1e-14);
                assert!((pr[d] - wr[d]).abs() < 1e-14);
            }
        }
    }
}
