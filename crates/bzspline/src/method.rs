//! The method of Stelia, Potapenko and Sirenko in one place: the rows of the
//! paper's system (16) for open and closed polygons, the pieces they give, and
//! the straightforward assembly that the fast sweeps of [`crate::fast::sweep`] are
//! tested against. `docs/method.md` derives every formula here (sections cited
//! as §N) and lists the paper's misprints that this crate does not copy.
//!
//! Knots `tau_0 < ... < tau_{N-1}`, values `F_0 .. F_{N-1}`, and one shape
//! parameter `alpha_k` in `[1/3, 2/3]` per interval `[tau_k, tau_{k+1}]` (the paper
//! numbers knots from 1 and intervals from 2; this crate counts from 0). With
//! `h_k = tau_{k+1} - tau_k` and `dF_k = F_{k+1} - F_k`, the tangent abscissa of
//! interval `k` is `x_k = tau_{k+1} - alpha_k h_k` and the point of leg `k` there is
//! `f_k = alpha_k F_k + (1 - alpha_k) F_{k+1}` (the paper prints this with the
//! weights swapped: misprint 1, `docs/method.md` §9).
//!
//! On each interval `S` is one cubic with `S(x_k) = f_k`, `S'(x_k) = dF_k / h_k`
//! (conditions (1)-(2) of the paper), `S` and `S'` continuous at every interior
//! knot, `S(tau_0) = F_0` and `S(tau_{N-1}) = F_{N-1}`. Writing the knot values as
//! `phi_k = F_k + d_k` (so `d_0 = d_{N-1} = 0`), continuity of `S'` at knot `k`
//! is the paper's system (16) (§4):
//!
//! ```text
//! -A_k d_{k-1} + (B1_k + B2_k) d_k - C_k d_{k+1} = s_k - s_{k-1},   s_k = dF_k / h_k
//! A_k  = a^2 / ((1-a)^2 h_{k-1})     B1_k = (2/a + 1) / h_{k-1}       (a = alpha_{k-1})
//! C_k  = (1-b)^2 / (b^2 h_k)         B2_k = (2/(1-b) + 1) / h_k       (b = alpha_k)
//! ```
//!
//! This module multiplies row `k` by `h_{k-1} h_k / (h_{k-1} + h_k)`, which turns
//! every coefficient and the right-hand side into bounded numbers
//! (`p = h_k / (h_{k-1} + h_k)`, `q = 1 - p`; §4):
//!
//! ```text
//! -p A' d_{k-1} + (p B1' + q B2') d_k - q C' d_{k+1} = q dF_k - p dF_{k-1}
//! A' = a^2/(1-a)^2   B1' = 2/a + 1   B2' = 2/(1-b) + 1   C' = (1-b)^2/b^2
//! ```
//!
//! `B1' >= A'` iff `a <= 2/3` and `B2' >= C'` iff `b >= 1/3`: the system is
//! diagonally dominant in the theorem's range and the Thomas algorithm needs no
//! pivoting (§5). Values are scaled by a power of two so that `max |F|` is about 1, so
//! values near `1e308` do not overflow intermediate products.
//!
//! In the local variable `t = (x - tau_k) / h_k` each piece depends only on
//! `F_k, F_{k+1}, d_k, d_{k+1}` and `alpha_k`: its end slopes (times `h_k`) are (§3)
//!
//! ```text
//! h S'(tau_k + 0)     = dF_k - d_k (2/(1-a) + 1) + d_{k+1} (1-a)^2 / a^2
//! h S'(tau_{k+1} - 0) = dF_k + d_{k+1} (2/a + 1) - d_k a^2 / (1-a)^2
//! ```
//!
//! and its Bezier ordinates are `phi_k`, `phi_k + h S'(tau_k+0)/3`,
//! `phi_{k+1} - h S'(tau_{k+1}-0)/3`, `phi_{k+1}`.
//!
//! A closed polygon (§7) has the same row at every knot, indices taken
//! cyclically, and no deviation fixed: [`ClosedSystem`]. The interpolating
//! variant (§11) solves `(T + K) d = K P` with the same right-hand side and
//! takes `G = P - d` as control values: [`OpenSystem::through`],
//! [`ClosedSystem::through`], [`through_controls`].

use crate::lanes::Lane;
use crate::tridiag::{CyclicThomas, Thomas};

/// A power of two close to `max |v|` (1 for an all-zero input), so that values
/// divided by it lie in `[-2, 2]` and the division is exact.
pub(crate) fn power_of_two_scale<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    let m = values.into_iter().fold(0.0f64, |m, v| m.max(v.abs()));
    scale_for_max(m)
}

/// [`power_of_two_scale`] of values whose largest magnitude is `m`.
pub(crate) fn scale_for_max(m: f64) -> f64 {
    if m == 0.0 || !m.is_finite() {
        return 1.0;
    }
    let e = m.log2().floor().clamp(-1022.0, 1023.0);
    // powi cannot reach 2^-1022 through 2.0f64.powi on all platforms exactly, so
    // build the double from its exponent bits.
    f64::from_bits(((e as i64 + 1023) as u64) << 52)
}

/// The factored continuity system of an open spline: depends on the widths and
/// alphas only, so one factorization serves every coordinate of a curve.
#[derive(Clone, Debug)]
pub(crate) struct OpenSystem {
    /// `p_k` of row `k` (knot `k`, 1 <= k <= N-2), stored at `k - 1`.
    p: Vec<f64>,
    thomas: Thomas,
}

/// The alpha of every leg when `alphas` are all one (`None` when they
/// differ or there are none).
#[inline]
pub(crate) fn one_alpha(alphas: &[f64]) -> Option<f64> {
    alphas
        .first()
        .copied()
        .filter(|&a| alphas.iter().all(|&b| b == a))
}

/// `a^2 / (1-a)^2`, `2/a + 1`, `2/(1-a) + 1`, `(1-a)^2 / a^2` for one alpha.
#[inline]
pub(crate) fn alpha_terms(a: f64) -> [f64; 4] {
    let r = a / (1.0 - a);
    [r * r, 2.0 / a + 1.0, 2.0 / (1.0 - a) + 1.0, 1.0 / (r * r)]
}

/// `(hr / (hl + hr), hl / (hl + hr))` for the widths left and right of a knot.
/// Each width is finite, but their sum can round above `f64::MAX` when the span
/// is within rounding of it; then both are halved first (exact at that size).
#[inline]
pub(crate) fn neighbour_weights(hl: f64, hr: f64) -> (f64, f64) {
    let sum = hl + hr;
    if sum.is_finite() {
        (hr / sum, hl / sum)
    } else {
        let (hl, hr) = (0.5 * hl, 0.5 * hr);
        let sum = hl + hr;
        (hr / sum, hl / sum)
    }
}

impl OpenSystem {
    /// Builds and factors the row-scaled system (16) for interior knots.
    pub(crate) fn new(widths: &[f64], alphas: &[f64]) -> Self {
        Self::assemble(widths, alphas, false)
    }

    /// The system of the interpolating variant (`docs/method.md` §11): the rows
    /// of (16) plus those of the slope jumps, `(T + K) d = K P`, whose solution
    /// gives control values `G = P - d` with knot values `P`.
    pub(crate) fn through(widths: &[f64], alphas: &[f64]) -> Self {
        Self::assemble(widths, alphas, true)
    }

    fn assemble(widths: &[f64], alphas: &[f64], through: bool) -> Self {
        let n = widths.len() + 1;
        let m = n.saturating_sub(2);
        let mut p_all = Vec::with_capacity(m);
        // Each leg's terms are formed once (once in all for one alpha) and
        // serve the rows on both sides of it.
        let uniform = one_alpha(alphas).map(alpha_terms);
        let terms = |k: usize| uniform.unwrap_or_else(|| alpha_terms(alphas[k]));
        let mut left = if m > 0 { terms(0) } else { [0.0; 4] };
        // Diagonal dominance with a strictly dominant first row (it has no lower
        // neighbour) keeps every pivot positive, so factoring cannot fail.
        let thomas = Thomas::factor_rows(m, |i| {
            let k = i + 1;
            let (p, q) = neighbour_weights(widths[k - 1], widths[k]);
            let [al, b1, _, _] = left;
            let right = terms(k);
            let [_, _, b2, cr] = right;
            left = right;
            p_all.push(p);
            if through {
                through_row(p, q, al, b1, b2, cr)
            } else {
                (-p * al, p * b1 + q * b2, -q * cr)
            }
        })
        .unwrap_or_default();
        OpenSystem { p: p_all, thomas }
    }

    /// Solves for the deviations `d` (length N, zero at both ends) of the scaled
    /// values `f`.
    pub(crate) fn solve(&self, f: &[f64], d: &mut Vec<f64>) {
        let n = f.len();
        d.clear();
        d.resize(n, 0.0);
        if n < 3 {
            return;
        }
        for k in 1..n - 1 {
            let p = self.p[k - 1];
            let q = 1.0 - p;
            d[k] = q * (f[k + 1] - f[k]) - p * (f[k] - f[k - 1]);
        }
        self.thomas.solve_in_place(&mut d[1..n - 1]);
    }
}

/// Power-basis coefficients in `t` of the piece between scaled values `f0, f1`
/// with deviations `d0, d1` and shape parameter `a`.
#[inline]
pub(crate) fn piece_coefs(f0: f64, f1: f64, d0: f64, d1: f64, a: f64) -> [f64; 4] {
    piece_coefs_with(f0, f1, d0, d1, alpha_terms(a))
}

/// [`piece_coefs`] with the [`alpha_terms`] of its shape parameter given.
#[inline]
pub(crate) fn piece_coefs_with(f0: f64, f1: f64, d0: f64, d1: f64, terms: [f64; 4]) -> [f64; 4] {
    let [al, b1, b2, cr] = terms;
    let df = f1 - f0;
    let s0 = df - d0 * b2 + d1 * cr; // h S'(tau_k + 0)
    let s1 = df + d1 * b1 - d0 * al; // h S'(tau_{k+1} - 0)
    let rise = df + (d1 - d0);
    [
        f0 + d0,
        s0,
        3.0 * rise - 2.0 * s0 - s1,
        s0 + s1 - 2.0 * rise,
    ]
}

/// The row-scaled row of `T + K` (§11) from the terms of (16): `p (1 - A')`,
/// `p B1' + q B2' - 1` (which is `2p/a + 2q/(1-b)`), `q (1 - C')`, with the signs
/// of [`row`]; diagonally dominant on `[1/3, 2/3]`, diagonal at alpha = 1/2.
#[inline]
pub(crate) fn through_row<L: Lane>(p: L, q: L, al: L, b1: L, b2: L, cr: L) -> (L, L, L) {
    let one = L::splat(1.0);
    (p * (one - al), p * b1 + q * b2 - one, q * (one - cr))
}

/// Row `i` of the row-scaled continuity system for the knot between legs of
/// widths `hl`, `hr` and alphas `al`, `ar`: `(lower, diag, upper, p)`.
#[inline]
pub(crate) fn row(hl: f64, hr: f64, al: f64, ar: f64) -> (f64, f64, f64, f64) {
    let (p, q) = neighbour_weights(hl, hr);
    let (lower, diag, upper) = row_of_terms(p, q, alpha_terms(al), alpha_terms(ar));
    (lower, diag, upper, p)
}

/// [`row`] from the neighbour weights `p`, `q` and the [`alpha_terms`] of the
/// alphas on the left and the right: `(lower, diag, upper)`.
#[inline]
pub(crate) fn row_of_terms(p: f64, q: f64, left: [f64; 4], right: [f64; 4]) -> (f64, f64, f64) {
    let [a, b1, _, _] = left;
    let [_, _, b2, c] = right;
    (-p * a, p * b1 + q * b2, -q * c)
}

/// The factored cyclic system of a closed curve.
pub(crate) struct ClosedSystem {
    p: Vec<f64>,
    solver: Option<CyclicThomas>,
}

impl ClosedSystem {
    pub(crate) fn new(widths: &[f64], alphas: &[f64]) -> Self {
        Self::assemble(widths, alphas, false)
    }

    /// The cyclic system of the interpolating variant (§11).
    pub(crate) fn through(widths: &[f64], alphas: &[f64]) -> Self {
        Self::assemble(widths, alphas, true)
    }

    fn assemble(widths: &[f64], alphas: &[f64], through: bool) -> Self {
        let n = widths.len();
        let (mut lower, mut diag, mut upper, mut ps) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        // Each leg's terms are formed once (once in all for one alpha) and
        // serve the rows on both sides of it, the closing leg's the first
        // row's left.
        let uniform = one_alpha(alphas).map(alpha_terms);
        let terms = |k: usize| uniform.unwrap_or_else(|| alpha_terms(alphas[k]));
        let mut left = if n > 0 { terms(n - 1) } else { [0.0; 4] };
        for i in 0..n {
            let l = if i == 0 { n - 1 } else { i - 1 };
            let (p, q) = neighbour_weights(widths[l], widths[i]);
            let right = terms(i);
            let (lo, di, up) = if through {
                through_row(p, q, left[0], left[1], right[2], right[3])
            } else {
                row_of_terms(p, q, left, right)
            };
            left = right;
            lower.push(lo);
            diag.push(di);
            upper.push(up);
            ps.push(p);
        }
        ClosedSystem {
            p: ps,
            solver: CyclicThomas::factor(&lower, &diag, &upper),
        }
    }

    /// Deviations of the scaled closed polygon `f` (one coordinate).
    pub(crate) fn solve(&self, f: &[f64], d: &mut [f64]) {
        let n = f.len();
        for i in 0..n {
            let p = self.p[i];
            let q = 1.0 - p;
            let (prev, next) = (f[(i + n - 1) % n], f[(i + 1) % n]);
            d[i] = q * (next - f[i]) - p * (f[i] - prev);
        }
        // Diagonal dominance keeps the factorization valid for alphas in range;
        // the fallback (no correction) is unreachable but never panics.
        match &self.solver {
            Some(s) => {
                s.solve_in_place(d);
            }
            None => d.iter_mut().for_each(|v| *v = 0.0),
        }
    }
}

/// The control values of the interpolating variant (§11) for `points` (`dim`
/// coordinates a point, flat) on the grid of `widths`, open or `closed`: one
/// factorisation for every coordinate, each coordinate scaled by a power of
/// two while it is solved. `None` when a control value leaves the range of a
/// double.
pub(crate) fn through_controls(
    widths: &[f64],
    alphas: &[f64],
    points: &[f64],
    dim: usize,
    closed: bool,
) -> Option<Vec<f64>> {
    let n = points.len() / dim.max(1);
    let mut out = vec![0.0; points.len()];
    enum System {
        Open(OpenSystem),
        Closed(ClosedSystem),
    }
    let system = if closed {
        System::Closed(ClosedSystem::through(widths, alphas))
    } else {
        System::Open(OpenSystem::through(widths, alphas))
    };
    let mut f = vec![0.0; n];
    let mut d = vec![0.0; n];
    for c in 0..dim {
        let scale = power_of_two_scale((0..n).map(|i| &points[i * dim + c]));
        let inv = 1.0 / scale;
        for (i, v) in f.iter_mut().enumerate() {
            *v = points[i * dim + c] * inv;
        }
        match &system {
            System::Open(s) => s.solve(&f, &mut d),
            System::Closed(s) => s.solve(&f, &mut d),
        }
        for i in 0..n {
            let g = (f[i] - d[i]) * scale;
            if !g.is_finite() {
                return None;
            }
            out[i * dim + c] = g;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ALPHA_MAX, ALPHA_MIN};

    #[test]
    fn neighbour_weights_survive_a_sum_above_the_largest_double() {
        assert_eq!(neighbour_weights(f64::MAX, f64::MAX), (0.5, 0.5));
        assert_eq!(neighbour_weights(1.0, 3.0), (0.75, 0.25));
    }

    #[test]
    fn rows_are_dominant_exactly_on_the_theorems_range() {
        // §5: B1' >= A' iff alpha <= 2/3, B2' >= C' iff alpha >= 1/3, both 4 at
        // the bound.
        for i in 0..=1000 {
            let a = 0.05 + 0.9 * f64::from(i) / 1000.0;
            let [al, b1, b2, cr] = alpha_terms(a);
            if (a - 2.0 / 3.0).abs() > 1e-9 {
                assert_eq!(b1 > al, a < 2.0 / 3.0, "a = {a}: B1' {b1}, A' {al}");
            }
            if (a - 1.0 / 3.0).abs() > 1e-9 {
                assert_eq!(b2 > cr, a > 1.0 / 3.0, "a = {a}: B2' {b2}, C' {cr}");
            }
        }
        let [al, b1, _, _] = alpha_terms(ALPHA_MAX);
        assert!(
            (al - 4.0).abs() < 1e-14 && (b1 - 4.0).abs() < 1e-14,
            "{al} {b1}"
        );
        let [_, _, b2, cr] = alpha_terms(ALPHA_MIN);
        assert!(
            (b2 - 4.0).abs() < 1e-14 && (cr - 4.0).abs() < 1e-14,
            "{b2} {cr}"
        );
        // Just outside, dominance fails.
        let [al, b1, _, _] = alpha_terms(0.7);
        assert!(b1 < al);
        let [_, _, b2, cr] = alpha_terms(0.3);
        assert!(b2 < cr);
    }

    /// The paper's rows (16), unscaled: `-A d_{k-1} + (B1 + B2) d_k - C d_{k+1}
    /// = s_k - s_{k-1}` with the widths in the coefficients (§4), solved by
    /// dense Gaussian elimination.
    fn paper_deviations(widths: &[f64], alphas: &[f64], f: &[f64]) -> Vec<f64> {
        let n = f.len();
        let m = n - 2;
        let mut a = vec![0.0; m * m];
        let mut b = vec![0.0; m];
        for i in 0..m {
            let k = i + 1;
            let (hl, hr) = (widths[k - 1], widths[k]);
            let (x, y) = (alphas[k - 1], alphas[k]);
            let big_a = x * x / ((1.0 - x) * (1.0 - x) * hl);
            let b1 = (2.0 / x + 1.0) / hl;
            let b2 = (2.0 / (1.0 - y) + 1.0) / hr;
            let c = (1.0 - y) * (1.0 - y) / (y * y * hr);
            a[i * m + i] = b1 + b2;
            if i > 0 {
                a[i * m + i - 1] = -big_a;
            }
            if i + 1 < m {
                a[i * m + i + 1] = -c;
            }
            b[i] = (f[k + 1] - f[k]) / hr - (f[k] - f[k - 1]) / hl;
        }
        for col in 0..m {
            for r in col + 1..m {
                let factor = a[r * m + col] / a[col * m + col];
                for j in col..m {
                    a[r * m + j] -= factor * a[col * m + j];
                }
                b[r] -= factor * b[col];
            }
        }
        let mut x = vec![0.0; m];
        for r in (0..m).rev() {
            let tail: f64 = (r + 1..m).map(|j| a[r * m + j] * x[j]).sum();
            x[r] = (b[r] - tail) / a[r * m + r];
        }
        let mut d = vec![0.0];
        d.extend(x);
        d.push(0.0);
        d
    }

    #[test]
    fn the_scaled_rows_solve_the_papers_system() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [3usize, 4, 7, 30] {
            let widths: Vec<f64> = (0..n - 1).map(|_| 0.01 + 3.0 * next()).collect();
            let alphas: Vec<f64> = (0..n - 1)
                .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * next())
                .collect();
            let f: Vec<f64> = (0..n).map(|_| 4.0 * next() - 2.0).collect();
            let mut d = Vec::new();
            OpenSystem::new(&widths, &alphas).solve(&f, &mut d);
            let want = paper_deviations(&widths, &alphas, &f);
            for (k, (x, y)) in d.iter().zip(&want).enumerate() {
                assert!((x - y).abs() < 1e-12, "n = {n}, d_{k}: want {y}, got {x}");
            }
        }
    }

    #[test]
    fn a_straight_polygon_has_no_deviation() {
        // §4: the right-hand side is the jump of the slope, zero on a line.
        let widths = [1.0, 0.5, 2.0, 0.25];
        let alphas = [0.4, 0.5, 0.6, 0.45];
        let x = [0.0, 1.0, 1.5, 3.5, 3.75];
        let f: Vec<f64> = x.iter().map(|v| 2.0 * v - 1.0).collect();
        let mut d = Vec::new();
        OpenSystem::new(&widths, &alphas).solve(&f, &mut d);
        assert!(d.iter().all(|&v| v.abs() < 1e-15), "{d:?}");
    }

    #[test]
    fn the_closed_square_is_pulled_a_tenth_inside() {
        // §7: the unit square, uniform parameters, alpha = 1/2.
        let widths = [1.0; 4];
        let alphas = [0.5; 4];
        let sys = ClosedSystem::new(&widths, &alphas);
        let xs = [0.0, 1.0, 1.0, 0.0];
        let ys = [0.0, 0.0, 1.0, 1.0];
        let (mut dx, mut dy) = ([0.0; 4], [0.0; 4]);
        sys.solve(&xs, &mut dx);
        sys.solve(&ys, &mut dy);
        let want = [(0.1, 0.1), (0.9, 0.1), (0.9, 0.9), (0.1, 0.9)];
        for k in 0..4 {
            let got = (xs[k] + dx[k], ys[k] + dy[k]);
            assert!(
                (got.0 - want[k].0).abs() < 1e-15 && (got.1 - want[k].1).abs() < 1e-15,
                "knot {k}: {got:?}"
            );
        }
    }
}
