//! A closed curve's cyclic system solved by the open curve's fused sweeps.
//!
//! Row `i` of the cyclic system couples knot `i` to knots `i - 1` and
//! `i + 1` around the ring. Laid out as an open system over the ring's knots
//! `0 ..= n - 1` between two extra end knots, a copy of knot `n - 1` before
//! knot 0 (at `tau_0 - h_{n-1}`) and a copy of knot 0 after knot `n - 1` (at
//! `tau_n`), every row of the ring is a row of the open system with its own
//! widths and alphas; only the two end deviations, which the open sweeps take
//! as zero, should be `d_{n-1}` and `d_0`. The system is linear, so the true
//! deviations are the open ones `y` plus `a` times the response `w_a` to a
//! unit deviation at the first end and `b` times `w_b` at the last; each
//! response decays from its end by the rows' damping factors (`docs/method.md`
//! §16), and is taken over the rows that bring it below `2^-64`, as between
//! two chunks. With the two responses apart (the ring longer than both),
//! `a = y_{n-1} + b w_b(n-1)` and `b = y_0 + a w_a(0)`, a two-by-two system;
//! the deviations near the ends are corrected and the pieces of their legs
//! formed again. Everything else is the open curve's construction, in chunks
//! and on several threads when long. The result agrees with the cyclic
//! system's own solve ([`crate::tridiag::CyclicThomas`]) to rounding.

use super::chunks::{damping_of, MAX_OVERLAP, TRUNCATION};
use super::sweep::{self, build_open_curve};
use super::{inverse_power_of_two, Piece};
use crate::method::{alpha_terms, row};
use crate::tridiag::Thomas;

/// The fewest points of a ring solved this way. The response to each end
/// reaches 21 knots at alpha 1/2 on even knots (fewer where the rows damp
/// more), so shorter rings seldom have the two apart, and a failed attempt
/// costs its walks (a 30-point ring took a third longer); they go through
/// the cyclic system's own solve.
pub(crate) const RING_MIN: usize = 48;

/// The closed curve of `n = knots.len() - 1` points: `knots` (`tau_0 ..=
/// tau_n`, validated, `tau_n` closing the ring), `points` (`n D`, scaled by
/// `inv_scale` coordinate by coordinate as they are read), `alphas` (`n`, one
/// a leg, the closing leg last; not read when `uniform` gives the one alpha).
/// Writes what the open curve's build writes, for the ring: `coefs` (`n D`
/// pieces, leg by leg), `dev` (`n D` scaled deviations) and `points_out` (a
/// copy of `points`), and returns `true`; returns `false` and changes nothing
/// when the ring is shorter than [`RING_MIN`] or than its two end responses
/// together, neither end row damps, or the copy of knot `n - 1` before knot 0
/// cannot keep its width exactly.
#[allow(clippy::too_many_arguments)] // the parts of a curve, validated
pub(crate) fn build_closed_curve<const D: usize>(
    knots: &[f64],
    points: &[f64],
    inv_scale: [f64; D],
    alphas: &[f64],
    uniform: Option<f64>,
    coefs: &mut Vec<Piece>,
    dev: &mut Vec<f64>,
    points_out: &mut Vec<f64>,
) -> bool {
    let n = knots.len().saturating_sub(1);
    let (pts, _) = points.as_chunks::<D>();
    if n < RING_MIN || pts.len() != n || (uniform.is_none() && alphas.len() != n) {
        return false;
    }
    let (Some(&t0), Some(&t_last), Some(&t_end)) = (knots.first(), knots.get(n - 1), knots.last())
    else {
        return false;
    };
    let closing = t_end - t_last;
    let before = t0 - closing;
    if t0 - before != closing {
        return false;
    }
    let ring = Ring {
        knots,
        alphas,
        uniform,
        terms: uniform.map(alpha_terms),
    };
    let ws = inverse_power_of_two(t_end - before);
    let Some(ra) = ring.reach(ws, true, n) else {
        return false;
    };
    let Some(rb) = ring.reach(ws, false, n - ra) else {
        return false;
    };
    let (Some(wa), Some(wb)) = (ring.response(ra, true), ring.response(rb, false)) else {
        return false;
    };
    // The two-by-two system's determinant: each response at its end is at
    // most 1 in magnitude (§16), both near 1 only where neither end row damps.
    let (wa0, wb_last) = (wa[0], wb[0]);
    let det = 1.0 - wa0 * wb_last;
    if det.is_nan() || det < 0.25 {
        return false;
    }
    // The open system: the copies at both ends around the ring's knots.
    let mut ext_knots = Vec::with_capacity(n + 2);
    ext_knots.push(before);
    ext_knots.extend_from_slice(knots);
    let mut ext_points = Vec::with_capacity((n + 2) * D);
    ext_points.extend_from_slice(&points[(n - 1) * D..]);
    ext_points.extend_from_slice(points);
    ext_points.extend_from_slice(&points[..D]);
    // With one alpha no alpha is read: the knots pace the sweeps.
    let ext_alphas: Vec<f64> = match uniform {
        Some(_) => Vec::new(),
        None => core::iter::once(alphas[n - 1])
            .chain(alphas.iter().copied())
            .collect(),
    };
    let paced = match uniform {
        Some(_) => &ext_knots[..=n],
        None => &ext_alphas[..],
    };
    build_open_curve::<D>(
        &ext_knots,
        &ext_points,
        inv_scale,
        paced,
        uniform,
        ws,
        coefs,
        dev,
        points_out,
    );
    // The ring's knots and legs, moved to the front.
    for v in [&mut *dev, &mut *points_out] {
        v.copy_within(D..(n + 1) * D, 0);
        v.truncate(n * D);
    }
    coefs.copy_within(D..(n + 1) * D, 0);
    coefs.truncate(n * D);
    // The end deviations, and the deviations they move.
    for c in 0..D {
        let (y0, y_last) = (dev[c], dev[(n - 1) * D + c]);
        let a = (y_last + wb_last * y0) / det;
        let b = y0 + a * wa0;
        for (i, w) in wa.iter().enumerate() {
            dev[i * D + c] += a * w;
        }
        for (j, w) in wb.iter().enumerate() {
            dev[(n - 1 - j) * D + c] += b * w;
        }
    }
    // The legs whose deviations moved: the first ones, the last ones and
    // the closing leg.
    let scaled = |i: usize| -> [f64; D] { core::array::from_fn(|c| pts[i][c] * inv_scale[c]) };
    let legs = (0..wa.len()).chain(n - 1 - wb.len()..n);
    for k in legs {
        let j = if k + 1 == n { 0 } else { k + 1 };
        let a = uniform.unwrap_or_else(|| alphas[k]);
        let (f0, f1) = (scaled(k), scaled(j));
        for c in 0..D {
            let (d0, d1) = (dev[k * D + c], dev[j * D + c]);
            coefs[k * D + c] = Piece(sweep::leg_piece(f0[c], f1[c], d0, d1, a, uniform.is_some()));
        }
    }
    true
}

/// The rows of the ring.
struct Ring<'a> {
    knots: &'a [f64],
    alphas: &'a [f64],
    uniform: Option<f64>,
    /// The terms of the one alpha.
    terms: Option<[f64; 4]>,
}

impl Ring<'_> {
    fn n(&self) -> usize {
        self.knots.len() - 1
    }

    fn alpha(&self, leg: usize) -> f64 {
        self.uniform.unwrap_or_else(|| self.alphas[leg])
    }

    fn width(&self, leg: usize) -> f64 {
        self.knots[leg + 1] - self.knots[leg]
    }

    /// Row `i` of the ring: legs `i - 1` (around the ring) and `i`.
    fn legs(&self, i: usize) -> (usize, usize) {
        ((i + self.n() - 1) % self.n(), i)
    }

    /// The damping factors of row `i` (see [`damping_of`]).
    fn damping(&self, ws: f64, i: usize) -> (f64, f64) {
        let (l, r) = self.legs(i);
        let terms = |leg: usize| self.terms.unwrap_or_else(|| alpha_terms(self.alphas[leg]));
        damping_of(self.width(l) * ws, self.width(r) * ws, terms(l), terms(r))
    }

    /// The knots from the first end (`first`: knots `0, 1, ..`) or the last
    /// (`n - 1, n - 2, ..`) that a unit deviation at that end moves by more
    /// than `2^-64`, by the rows' damping: their count, `None` past
    /// [`MAX_OVERLAP`] or `most`.
    fn reach(&self, ws: f64, first: bool, most: usize) -> Option<usize> {
        let n = self.n();
        let mut product = 1.0;
        for s in 0..MAX_OVERLAP.min(most) {
            let (down, up) = self.damping(ws, if first { s } else { n - 1 - s });
            product *= if first { down } else { up };
            if product <= TRUNCATION {
                return Some(s + 1);
            }
        }
        None
    }

    /// The response of the ring's deviations to a unit deviation at the
    /// first end (before knot 0, `first`) or at the last (after knot
    /// `n - 1`): its values at the first `rows` knots from that end (`0, 1,
    /// ..` or `n - 1, n - 2, ..`), the response beyond them taken as zero.
    /// `None` when a pivot fails.
    fn response(&self, rows: usize, first: bool) -> Option<Vec<f64>> {
        let n = self.n();
        let at = |s: usize| if first { s } else { n - 1 - s };
        // Rows from the end inward.
        let row_of = |s: usize| {
            let (l, r) = self.legs(at(s));
            let (lower, diag, upper, _) =
                row(self.width(l), self.width(r), self.alpha(l), self.alpha(r));
            if first {
                (lower, diag, upper)
            } else {
                (upper, diag, lower)
            }
        };
        let thomas = Thomas::factor_rows(rows, row_of)?;
        let mut w = vec![0.0; rows];
        w[0] = -row_of(0).0;
        thomas.solve_in_place(&mut w).then_some(w)
    }
}
