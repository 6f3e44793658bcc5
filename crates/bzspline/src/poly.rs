//! Cubic polynomials in the power basis, `c[0] + c[1] t + c[2] t^2 + c[3] t^3`:
//! the one evaluation of values and derivatives that every piece of a spline
//! or curve goes through (Horner's scheme for the value).

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
