//! Cubic polynomials in the power basis, `c[0] + c[1] t + c[2] t^2 + c[3] t^3`:
//! the one evaluation of values and derivatives that every piece of a spline
//! or curve goes through (Horner's scheme for the value), and the real roots
//! of a quadratic (a cubic's derivative).

/// Derivative of order `O` (0..=3; higher orders are 0) in `t` of the cubic
/// `c`, not divided by the piece's width to the power `O`.
#[inline(always)]
pub(crate) fn deriv<const O: u32>(c: &[f64; 4], t: f64) -> f64 {
    match O {
        0 => c[0] + t * (c[1] + t * (c[2] + t * c[3])),
        1 => c[1] + t * (2.0 * c[2] + 3.0 * t * c[3]),
        2 => 2.0 * c[2] + 6.0 * t * c[3],
        3 => 6.0 * c[3],
        _ => 0.0,
    }
}

/// The value of the cubic `c` at `t`.
#[inline]
pub(crate) fn horner(c: &[f64; 4], t: f64) -> f64 {
    deriv::<0>(c, t)
}

/// [`deriv`] with the order known only at run time.
#[inline]
pub(crate) fn deriv_of(c: &[f64; 4], t: f64, order: u32) -> f64 {
    match order {
        0 => deriv::<0>(c, t),
        1 => deriv::<1>(c, t),
        2 => deriv::<2>(c, t),
        3 => deriv::<3>(c, t),
        _ => 0.0,
    }
}

/// Real roots of `a t^2 + b t + c` (numerically stable form); an empty vector for
/// the zero polynomial.
pub(crate) fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 || !scale.is_finite() {
        return Vec::new();
    }
    let (a, b, c) = (a / scale, b / scale, c / scale);
    if a.abs() < 1e-14 {
        if b == 0.0 {
            return Vec::new();
        }
        // A nearly linear derivative: the large root of the quadratic is far
        // outside any piece, the small one is the linear root.
        let r = -c / b;
        return if a == 0.0 {
            vec![r]
        } else {
            refine_pair(a, b, c)
        };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return Vec::new();
    }
    if disc == 0.0 {
        return vec![-b / (2.0 * a)];
    }
    refine_pair(a, b, c)
}

fn refine_pair(a: f64, b: f64, c: f64) -> Vec<f64> {
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return Vec::new();
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut r = Vec::with_capacity(2);
    if q != 0.0 {
        r.push(c / q);
    }
    if a != 0.0 {
        r.push(q / a);
    }
    if q == 0.0 && a != 0.0 && r.len() == 1 {
        // b = 0 and c = 0: a double root at 0.
        r.push(0.0);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
    }

    #[test]
    fn quadratic_roots_are_stable() {
        let mut r = quadratic_roots(1.0, -3.0, 2.0);
        r.sort_unstable_by(f64::total_cmp);
        assert_eq!(r.len(), 2);
        assert!(close(r[0], 1.0, 1e-15) && close(r[1], 2.0, 1e-15), "{r:?}");
        assert_eq!(quadratic_roots(0.0, 2.0, -1.0), vec![0.5]);
        assert!(quadratic_roots(1.0, 0.0, 1.0).is_empty());
        assert!(quadratic_roots(0.0, 0.0, 0.0).is_empty());
        let r = quadratic_roots(1e-20, 1.0, -0.25);
        assert!(r.iter().any(|t| (t - 0.25).abs() < 1e-15), "{r:?}");
    }
}
