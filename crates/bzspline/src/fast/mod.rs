//! The speed machinery behind [`Spline`](crate::Spline) and
//! [`Curve`](crate::Curve), with the same results as the plain code of
//! [`crate::method`] (to a few units in the last place) and no other
//! contract:
//!
//! - [`sweep`]: the fused construction sweeps, which validate nothing and
//!   allocate nothing (the caller has validated the input and owns every
//!   buffer);
//! - [`chunks`]: the system cut into overlapping chunks, solved one after
//!   the other or side by side, for large inputs;
//! - `pair`: two chunks eliminated at once, one in each lane of an SSE2
//!   register;
//! - [`ring`]: a closed curve's cyclic system through the open sweeps;
//! - [`through`]: the interpolating variant's system, whole or in chunks;
//! - [`batch`]: the batch evaluator of a spline's derivatives at many queries;
//! - [`search`]: the summary of the knots and its index, and the searches of
//!   one query and of a block of them.
//!
//! Nothing here knows the types above it: they hand in slices.

pub(crate) mod batch;
pub(crate) mod chunks;
mod pair;
pub(crate) mod ring;
pub(crate) mod search;
pub(crate) mod sweep;
pub(crate) mod through;

/// The four power-basis coefficients of one piece in `t = (x - tau_k) / h_k`,
/// aligned so that one piece never straddles two cache lines.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(align(32))]
pub(crate) struct Piece(pub(crate) [f64; 4]);

/// A power of two `2^-e` with `x 2^-e` in `[1, 2)` for a positive normal `x`
/// (for a subnormal `x`, `2^1023`, which brings it above `2^-52`); 1 for
/// anything else.
#[must_use]
pub(crate) fn inverse_power_of_two(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let e = (-x.log2().floor()).clamp(-1023.0, 1023.0);
    if e >= -1022.0 {
        f64::from_bits(((e as i64 + 1023) as u64) << 52)
    } else {
        // 2^-1023, a subnormal power of two.
        f64::from_bits(1u64 << 51)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_power_of_two_brings_to_one_two() {
        for x in [1e-300, 0.3, 1.0, 7.0, 1e300, f64::MAX] {
            let s = inverse_power_of_two(x);
            assert!((1.0..2.0).contains(&(x * s)), "{x} * {s}");
        }
        let s = inverse_power_of_two(1e-310);
        assert!((2f64.powi(-52)..2.0).contains(&(1e-310 * s)), "{s}");
        assert_eq!(inverse_power_of_two(0.0), 1.0);
    }
}
