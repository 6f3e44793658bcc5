//! Cubic Bezier segments in `R^D`: the exact export form of every piece.

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
