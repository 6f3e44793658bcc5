//! The fast paths of [`Spline`](crate::Spline): one fused sweep that validates
//! nothing and allocates nothing (the caller has validated the input and owns
//! every buffer), and the batch evaluators.
//!
//! Everything here computes the same quantities as the straightforward path of
//! `spline.rs` (`OpenSystem`, `piece_coefs`) in another order of operations, so
//! results agree to rounding (a few units in the last place), not bit for bit.
//!
//! # Construction
//!
//! Row `k` of the system (16), multiplied by `h_{k-1} + h_k` instead of the
//! `h_{k-1} h_k / (h_{k-1} + h_k)` of `spline.rs`, reads (widths `h` already
//! multiplied by a power of two that brings the span near 1, values scaled):
//!
//! ```text
//! l_k = -h_k A'    D_k = h_k B1' + h_{k-1} B2'    u_k = -h_{k-1} C'
//! r_k = h_{k-1} dF_k - h_k dF_{k-1}
//! ```
//!
//! so assembling a row needs no division. The Thomas pivots
//! `piv_k = D_k - l_k u_{k-1} / piv_{k-1}` are ratios `P_k / P_{k-1}` of the
//! continuants `P_k = D_k P_{k-1} - l_k u_{k-1} P_{k-2}`, a recurrence of
//! multiplications and subtractions only: the one division per row,
//! `1 / piv_k = P_{k-1} / P_k`, is off the chain of dependent operations. The
//! continuants are renormalised by an exact power of two every
//! [`RENORM`] rows. Diagonal dominance bounds every pivot ratio (for alphas in
//! `[1/3, 2/3]`, `piv_k >= 3 min(h_{k-1} + h_k)` and `<= 8 max(...)`), so the
//! continuants stay far from overflow and underflow between renormalisations.
//!
//! The forward sweep keeps its two numbers per row (`u_k / piv_k` and the swept
//! right-hand side) in the storage of piece `k`, which the backward sweep then
//! overwrites with the piece's coefficients: no scratch vector.

use crate::spline::alpha_terms;

/// Rows between two renormalisations of the continuants: at most `8^16 = 2^48`
/// growth and `(3 * 2^-52)^16` shrinkage in between, both far inside a double.
const RENORM: usize = 16;

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

/// Multiplies `p` and `q` by the power of two that brings `p` into `[1, 2)`.
/// `p` is positive and normal.
#[inline]
fn renormalise(p: &mut f64, q: &mut f64) {
    let e = (p.to_bits() >> 52) & 0x7ff;
    // 2^(1023 - e): the exponent field 2046 - e lies in [1, 2045] for normal p.
    let m = f64::from_bits((2046u64.saturating_sub(e)).max(1) << 52);
    *p *= m;
    *q *= m;
}

/// `A', B1', B2', C'` of one alpha with one division: `1/a = (1-a) / (a (1-a))`,
/// `1/(1-a) = a / (a (1-a))`. Agrees with [`alpha_terms`] to a few units in the
/// last place.
#[inline]
fn alpha_terms_one_division(a: f64) -> [f64; 4] {
    let u = 1.0 - a;
    let iau = 1.0 / (a * u);
    let ia = u * iau;
    let iu = a * iau;
    let r = a * iu;
    let ir = u * ia;
    [r * r, 2.0 * ia + 1.0, 2.0 * iu + 1.0, ir * ir]
}

/// Coefficients of a piece from its scaled values, deviations and alpha terms
/// (the arithmetic of `spline::piece_coefs`).
#[inline(always)]
fn piece(f0: f64, f1: f64, d0: f64, d1: f64, terms: [f64; 4]) -> Piece {
    let [al, b1, b2, cr] = terms;
    let df = f1 - f0;
    let s0 = df - d0 * b2 + d1 * cr;
    let s1 = df + d1 * b1 - d0 * al;
    let rise = df + (d1 - d0);
    Piece([
        f0 + d0,
        s0,
        3.0 * rise - 2.0 * s0 - s1,
        s0 + s1 - 2.0 * rise,
    ])
}

/// Where the alphas come from in the sweep.
#[derive(Clone, Copy)]
pub(crate) enum AlphaSource<'a> {
    /// One alpha for every interval.
    Uniform(f64),
    /// One per interval, already validated.
    PerInterval(&'a [f64]),
}

impl AlphaSource<'_> {
    #[inline(always)]
    fn terms(&self, k: usize, uniform: [f64; 4]) -> [f64; 4] {
        match *self {
            AlphaSource::Uniform(_) => uniform,
            AlphaSource::PerInterval(a) => alpha_terms_one_division(a[k]),
        }
    }
}

/// Builds the pieces of a validated spline into `coefs` (cleared first; its
/// allocation is reused).
///
/// `knots` are strictly increasing with a finite span, `values` finite and of
/// the same length (at least 2), `inv_scale` the exact power of two that
/// scales the values, `wscale` the power of two that brings the span near 1.
pub(crate) fn build(
    knots: &[f64],
    values: &[f64],
    alphas: AlphaSource<'_>,
    inv_scale: f64,
    wscale: f64,
    coefs: &mut Vec<Piece>,
) {
    let n = knots.len().min(values.len());
    coefs.clear();
    if n < 2 {
        return;
    }
    let m = n - 1;
    coefs.resize(m, Piece::default());
    let uniform = match alphas {
        AlphaSource::Uniform(a) => alpha_terms(a),
        AlphaSource::PerInterval(_) => [0.0; 4],
    };
    let f = |k: usize| values[k] * inv_scale;

    // Forward sweep over rows k = 1 .. n-2, stored in coefs[k].
    if n > 2 {
        let mut p_prev2 = 1.0; // P_{k-2}
        let mut p_prev = 1.0; // P_{k-1}
        let mut y_prev = 0.0;
        let mut u_prev = 0.0;
        let mut hl = (knots[1] - knots[0]) * wscale;
        let mut fl = f(0);
        let mut fc = f(1);
        let mut terms_l = alphas.terms(0, uniform);
        let mut since = 0;
        for (k, slot) in coefs.iter_mut().enumerate().take(m).skip(1) {
            let hr = (knots[k + 1] - knots[k]) * wscale;
            let fr = f(k + 1);
            let terms_r = alphas.terms(k, uniform);
            let l = -hr * terms_l[0];
            let d = hr * terms_l[1] + hl * terms_r[2];
            let u = -hl * terms_r[3];
            let r = hl * (fr - fc) - hr * (fc - fl);
            let p = d * p_prev - (l * u_prev) * p_prev2;
            let inv = p_prev / p;
            let y = (r - l * y_prev) * inv;
            let up = u * inv;
            *slot = Piece([up, y, 0.0, 0.0]);
            p_prev2 = p_prev;
            p_prev = p;
            since += 1;
            if since == RENORM {
                renormalise(&mut p_prev, &mut p_prev2);
                since = 0;
            }
            y_prev = y;
            u_prev = u;
            hl = hr;
            fl = fc;
            fc = fr;
            terms_l = terms_r;
        }
    }

    // Backward sweep: d_k from d_{k+1}, then piece k.
    let mut d_next = 0.0;
    let mut f_next = f(m);
    for k in (0..m).rev() {
        let slot = &mut coefs[k];
        let d = if k > 0 {
            slot.0[1] - slot.0[0] * d_next
        } else {
            0.0
        };
        let fk = f(k);
        *slot = piece(fk, f_next, d, d_next, alphas.terms(k, uniform));
        d_next = d;
        f_next = fk;
    }
}

/// Derivative of order `O` (0..=3) in `t` of the cubic `c`, not divided by
/// `h^O`: the arithmetic of `spline::poly_deriv`.
#[inline(always)]
pub(crate) fn poly<const O: u32>(c: &[f64; 4], t: f64) -> f64 {
    match O {
        0 => c[0] + t * (c[1] + t * (c[2] + t * c[3])),
        1 => c[1] + t * (2.0 * c[2] + 3.0 * t * c[3]),
        2 => 2.0 * c[2] + 6.0 * t * c[3],
        3 => 6.0 * c[3],
        _ => 0.0,
    }
}

/// `v / h^O` as `v * (1/h)^O`, the way the pointwise evaluator does it.
#[inline(always)]
pub(crate) fn per_h<const O: u32>(v: f64, inv: f64) -> f64 {
    let mut v = v;
    for _ in 0..O {
        v *= inv;
    }
    v
}

/// Queries handed to the batch evaluators at once by the block search.
pub(crate) const BLOCK: usize = 16;

/// The batch evaluator's view of a spline.
pub(crate) struct Batch<'a> {
    pub(crate) knots: &'a [f64],
    pub(crate) coefs: &'a [Piece],
    pub(crate) scale: f64,
}

impl Batch<'_> {
    /// Evaluates `out[i] = S^(O)(xs[i])` for every query inside `[tau_0, tau_{N-1})`
    /// whose result is finite; calls `slow(i, x, out_i)` for the others (outside the
    /// domain, NaN, the last knot, overflow), which writes `out[i]` itself or
    /// fails. Sorted runs walk a pointer; unsorted blocks use a branchless
    /// binary search on [`BLOCK`] queries at a time.
    pub(crate) fn run<const O: u32, E>(
        &self,
        xs: &[f64],
        out: &mut [f64],
        mut slow: impl FnMut(usize, f64, &mut f64) -> Result<(), E>,
    ) -> Result<(), E> {
        let knots = self.knots;
        let coefs = self.coefs;
        let m = coefs.len();
        if m == 0 || knots.len() != m + 1 {
            for (i, o) in out.iter_mut().enumerate() {
                slow(i, xs.get(i).copied().unwrap_or(f64::NAN), o)?;
            }
            return Ok(());
        }
        let (lo, hi) = (knots[0], knots[m]);
        let scale = self.scale;
        // The current piece of the walk.
        let mut k = 0;
        let mut k0 = knots[0];
        let mut k1 = knots[1];
        let mut inv = 1.0 / (k1 - k0);
        let mut c = coefs[0].0;
        let mut base = 0;
        for (xb, ob) in xs.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
            let sorted = xb.windows(2).fold(true, |s, w| s & (w[0] <= w[1]));
            if sorted {
                for (j, (&x, o)) in xb.iter().zip(ob.iter_mut()).enumerate() {
                    if !(x >= lo && x < hi) {
                        slow(base + j, x, o)?;
                        continue;
                    }
                    if !(x >= k0 && x < k1) {
                        k = locate_from(knots, k, x);
                        k0 = knots[k];
                        k1 = knots[k + 1];
                        inv = 1.0 / (k1 - k0);
                        c = coefs[k].0;
                    }
                    let t = (x - k0) * inv;
                    let v = per_h::<O>(poly::<O>(&c, t) * scale, inv);
                    if v.is_finite() {
                        *o = v;
                    } else {
                        slow(base + j, x, o)?;
                    }
                }
            } else {
                let mut idx = [0usize; BLOCK];
                search_block(knots, xb, &mut idx);
                for (j, (&x, o)) in xb.iter().zip(ob.iter_mut()).enumerate() {
                    if !(x >= lo && x < hi) {
                        slow(base + j, x, o)?;
                        continue;
                    }
                    let q = idx[j].min(m - 1);
                    let (a, b) = (knots[q], knots[q + 1]);
                    let iv = 1.0 / (b - a);
                    let t = (x - a) * iv;
                    let v = per_h::<O>(poly::<O>(&coefs[q].0, t) * scale, iv);
                    if v.is_finite() {
                        *o = v;
                    } else {
                        slow(base + j, x, o)?;
                    }
                }
            }
            base += xb.len();
        }
        Ok(())
    }
}

/// The piece of `x` (inside the domain) starting the search at piece `k`: a few
/// linear steps forward, then a binary search.
#[inline]
fn locate_from(knots: &[f64], k: usize, x: f64) -> usize {
    let last = knots.len() - 2;
    let mut k = k;
    if x >= knots[k] {
        for _ in 0..4 {
            if k == last || x < knots[k + 1] {
                return k;
            }
            k += 1;
        }
        let rest = &knots[k + 1..];
        (k + rest.partition_point(|&v| v <= x)).min(last)
    } else {
        knots[..k]
            .partition_point(|&v| v <= x)
            .saturating_sub(1)
            .min(last)
    }
}

/// For each query the last knot index `i` with `knots[i] <= x` (0 when there is
/// none), by a branchless binary search interleaved over the block.
#[inline]
fn search_block(knots: &[f64], xb: &[f64], idx: &mut [usize; BLOCK]) {
    let mut len = knots.len();
    let mut q = [0.0; BLOCK];
    for (d, &s) in q.iter_mut().zip(xb) {
        *d = s;
    }
    while len > 1 {
        let half = len / 2;
        for (b, &x) in idx.iter_mut().zip(q.iter()) {
            let probe = *b + half;
            // The probe stays below knots.len(): base + len <= knots.len().
            let v = knots.get(probe).copied().unwrap_or(f64::INFINITY);
            *b = if v <= x { probe } else { *b };
        }
        len -= half;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_division_terms_match() {
        for i in 0..=100 {
            let a = 1.0 / 3.0 + f64::from(i) / 300.0;
            let want = alpha_terms(a);
            let got = alpha_terms_one_division(a);
            for j in 0..4 {
                assert!(
                    (want[j] - got[j]).abs() <= 4.0 * f64::EPSILON * want[j].abs(),
                    "alpha {a} term {j}: want {}, got {}",
                    want[j],
                    got[j]
                );
            }
        }
    }

    #[test]
    fn renormalise_lands_in_one_two() {
        for p in [1e-300, 3.5, 1e300, f64::MIN_POSITIVE] {
            let (mut a, mut b) = (p, p / 4.0);
            renormalise(&mut a, &mut b);
            assert!((1.0..2.0).contains(&a), "{p} -> {a}");
            assert_eq!(a / b, 4.0);
        }
    }

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

    #[test]
    fn block_search_finds_the_last_knot_not_above() {
        let knots: Vec<f64> = (0..37).map(|i| f64::from(i * i)).collect();
        let xs: Vec<f64> = (0..16).map(|i| f64::from(i * 83 % 1300) - 5.0).collect();
        let mut idx = [0; BLOCK];
        search_block(&knots, &xs, &mut idx);
        for (x, i) in xs.iter().zip(idx) {
            let want = knots.partition_point(|&k| k <= *x).saturating_sub(1);
            assert_eq!(i, want, "x = {x}");
        }
    }

    #[test]
    fn locate_from_matches_partition_point() {
        let knots: Vec<f64> = (0..50).map(|i| f64::from(i) * 0.5).collect();
        for start in [0, 3, 20, 48] {
            for i in 0..98 {
                let x = f64::from(i) * 0.25;
                let want = knots.partition_point(|&k| k <= x).saturating_sub(1).min(48);
                assert_eq!(locate_from(&knots, start, x), want, "from {start} x {x}");
            }
        }
    }
}
