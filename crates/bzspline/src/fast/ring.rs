//! Closed curves' cyclic systems solved by the open curve's fused sweeps:
//! the method's system (§7) and the interpolating variant's (§11).
//!
//! Row `i` of a cyclic system couples knot `i` to knots `i - 1` and `i + 1`
//! around the ring. Laid out as an open system over the ring's knots
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
//! the deviations near the ends are corrected (and the pieces of their legs
//! formed again). Everything else is the open curve's sweeps, in chunks and on
//! several threads when long. The results agree with the cyclic systems' own
//! solve ([`crate::tridiag::CyclicThomas`]) to rounding.

use super::chunks::{MAX_OVERLAP, TRUNCATION};
use super::sweep::{self, build_open_curve};
use super::{inverse_power_of_two, through, Piece};
use crate::method::{alpha_terms, neighbour_weights, row_of_terms, through_row};
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
    if pts.len() != n {
        return false;
    }
    let Some(ends) = Ends::of(knots, alphas, uniform, System::Method) else {
        return false;
    };
    // The open system: the copies at both ends around the ring's knots.
    let ext_knots = ends.knots(knots);
    let ext_points = around(pts);
    // With one alpha no alpha is read: the knots pace the sweeps.
    let ext_alphas = ends.alphas(alphas, uniform);
    let paced = match uniform {
        Some(_) => &ext_knots[..=n],
        None => &ext_alphas[..],
    };
    build_open_curve::<D>(
        &ext_knots,
        ext_points.as_flattened(),
        inv_scale,
        paced,
        uniform,
        ends.ws,
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
        ends.correct(n, &mut dev[c..], D);
    }
    // The legs whose deviations moved: the first ones, the last ones (and
    // the one before them) and the closing leg.
    let scaled = |i: usize| -> [f64; D] { core::array::from_fn(|c| pts[i][c] * inv_scale[c]) };
    let legs = ends
        .moved(n)
        .chain(core::iter::once(n - 1 - ends.last.len()));
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

/// The control points of the closed curve through `points` (`n` of them)
/// at `knots` (`tau_0 ..= tau_n`, validated) with `alphas` (`n`, the closing
/// leg last) unless `uniform` gives the one alpha: the interpolating
/// variant's cyclic system (§11) through the open one's sweeps
/// ([`through`]), each coordinate scaled by its `scale` while it is solved.
/// `None` where [`build_closed_curve`] would return `false` (the caller
/// solves the cyclic system itself); `Some(None)` when a control value leaves
/// the range of a double.
pub(crate) fn closed_controls<const D: usize>(
    knots: &[f64],
    points: &[[f64; D]],
    alphas: &[f64],
    uniform: Option<f64>,
    scale: [f64; D],
) -> Option<Option<Vec<[f64; D]>>> {
    let n = knots.len().saturating_sub(1);
    if points.len() != n {
        return None;
    }
    let ends = Ends::of(knots, alphas, uniform, System::Through)?;
    let ext_knots = ends.knots(knots);
    let ext_points = around(points);
    let ext_alphas = ends.alphas(alphas, uniform);
    let mut out = vec![[0.0; D]; n + 2];
    if through::solve_all(
        &ext_knots,
        &ext_points,
        &ext_alphas,
        uniform,
        scale,
        &mut out,
    )
    .is_none()
    {
        return Some(None);
    }
    let ring = &mut out[1..=n];
    let mut d = vec![0.0; n];
    for c in 0..D {
        // The open system's deviations from its control values (`G = (P /
        // scale - d) scale`, the power of two exact) at the knots the ends
        // move, which include the two the correction reads, put right.
        let inv = 1.0 / scale[c];
        for i in ends.moved(n) {
            d[i] = points[i][c] * inv - ring[i][c] * inv;
        }
        ends.correct(n, &mut d, 1);
        for i in ends.moved(n) {
            let g = (points[i][c] * inv - d[i]) * scale[c];
            if !g.is_finite() {
                return Some(None);
            }
            ring[i][c] = g;
        }
    }
    out.truncate(n + 1);
    out.remove(0);
    Some(Some(out))
}

/// The ring's points between copies of its last and its first: the open
/// system's points.
fn around<T: Copy>(points: &[T]) -> Vec<T> {
    let mut ext = Vec::with_capacity(points.len() + 2);
    ext.extend(points.last().copied());
    ext.extend_from_slice(points);
    ext.extend(points.first().copied());
    ext
}

/// Which cyclic system.
#[derive(Clone, Copy, PartialEq, Eq)]
enum System {
    /// The method's, (16) around the ring (§7).
    Method,
    /// The interpolating variant's, `T + K` (§11).
    Through,
}

/// The two ends of a ring laid out as an open system: the copy of knot
/// `n - 1` before knot 0 and the power of two for its widths, the responses
/// to a unit deviation at the first end (at knots `0, 1, ..`) and at the last
/// (at knots `n - 1, n - 2, ..`), and the determinant of the two-by-two
/// system for the end deviations.
struct Ends {
    before: f64,
    ws: f64,
    first: Vec<f64>,
    last: Vec<f64>,
    det: f64,
}

impl Ends {
    /// The ends of the ring of `knots` (`tau_0 ..= tau_n`) for `system`;
    /// `None` when the ring is shorter than [`RING_MIN`] or than its two
    /// responses together, neither end row damps, or the copy of knot
    /// `n - 1` cannot keep its width exactly.
    fn of(knots: &[f64], alphas: &[f64], uniform: Option<f64>, system: System) -> Option<Ends> {
        let n = knots.len().checked_sub(1)?;
        if n < RING_MIN || (uniform.is_none() && alphas.len() != n) {
            return None;
        }
        let (&t0, &t_last, &t_end) = (knots.first()?, knots.get(n - 1)?, knots.last()?);
        let closing = t_end - t_last;
        let before = t0 - closing;
        if t0 - before != closing {
            return None;
        }
        let ring = Ring {
            knots,
            alphas,
            terms: uniform.map(alpha_terms),
            system,
        };
        let ra = ring.reach(true, n)?;
        let rb = ring.reach(false, n - ra)?;
        let (first, last) = (ring.response(ra, true)?, ring.response(rb, false)?);
        // Each response at its end is at most 1 in magnitude (§16), both near
        // 1 only where neither end row damps.
        let det = 1.0 - first[0] * last[0];
        if det.is_nan() || det < 0.25 {
            return None;
        }
        Some(Ends {
            before,
            ws: inverse_power_of_two(t_end - before),
            first,
            last,
            det,
        })
    }

    /// The open system's knots: the copy of knot `n - 1`, then the ring's
    /// `tau_0 ..= tau_n` (`tau_n` the copy of knot 0).
    fn knots(&self, knots: &[f64]) -> Vec<f64> {
        let mut ext = Vec::with_capacity(knots.len() + 1);
        ext.push(self.before);
        ext.extend_from_slice(knots);
        ext
    }

    /// The open system's alphas, the closing leg's first (none with one
    /// alpha).
    fn alphas(&self, alphas: &[f64], uniform: Option<f64>) -> Vec<f64> {
        match (uniform, alphas.last()) {
            (None, Some(&last)) => core::iter::once(last)
                .chain(alphas.iter().copied())
                .collect(),
            _ => Vec::new(),
        }
    }

    /// Corrects the deviations of the open system, `y[i * stride]` the one
    /// of knot `i` of `n`, to the ring's: `y_i + a w_a(i) + b w_b(i)`. Reads
    /// and writes only the knots of [`Ends::moved`].
    fn correct(&self, n: usize, y: &mut [f64], stride: usize) {
        let (wa0, wb0) = (self.first[0], self.last[0]);
        let (y0, y_last) = (y[0], y[(n - 1) * stride]);
        let a = (y_last + wb0 * y0) / self.det;
        let b = y0 + a * wa0;
        for (i, w) in self.first.iter().enumerate() {
            y[i * stride] += a * w;
        }
        for (j, w) in self.last.iter().enumerate() {
            y[(n - 1 - j) * stride] += b * w;
        }
    }

    /// The knots whose deviations [`Ends::correct`] moves: `0 ..` and
    /// `.. n - 1`.
    fn moved(&self, n: usize) -> impl Iterator<Item = usize> {
        (0..self.first.len()).chain(n - self.last.len()..n)
    }
}

/// The rows of a ring.
struct Ring<'a> {
    knots: &'a [f64],
    alphas: &'a [f64],
    /// The terms of the one alpha.
    terms: Option<[f64; 4]>,
    system: System,
}

impl Ring<'_> {
    fn n(&self) -> usize {
        self.knots.len() - 1
    }

    fn terms(&self, leg: usize) -> [f64; 4] {
        self.terms.unwrap_or_else(|| alpha_terms(self.alphas[leg]))
    }

    fn width(&self, leg: usize) -> f64 {
        self.knots[leg + 1] - self.knots[leg]
    }

    /// Row `i` of the ring (legs `i - 1`, around the ring, and `i`), row-
    /// scaled: `(lower, diag, upper)`.
    fn row(&self, i: usize) -> (f64, f64, f64) {
        let (l, r) = ((i + self.n() - 1) % self.n(), i);
        let (p, q) = neighbour_weights(self.width(l), self.width(r));
        let (left, right) = (self.terms(l), self.terms(r));
        match self.system {
            System::Method => row_of_terms(p, q, left, right),
            System::Through => through_row(p, q, left[0], left[1], right[2], right[3]),
        }
    }

    /// The knots from the first end (`first`: knots `0, 1, ..`) or the last
    /// (`n - 1, n - 2, ..`) that a unit deviation at that end moves by more
    /// than `2^-64`, by the rows' damping factors (§16: `|lower| / (diag -
    /// |upper|)` from below, `|upper| / (diag - |lower|)` from above; 1 when
    /// out of `[0, 1]`): their count, `None` past [`MAX_OVERLAP`] or `most`.
    fn reach(&self, first: bool, most: usize) -> Option<usize> {
        let n = self.n();
        let mut product = 1.0;
        for s in 0..MAX_OVERLAP.min(most) {
            let (lo, di, up) = self.row(if first { s } else { n - 1 - s });
            let r = if first {
                lo.abs() / (di - up.abs())
            } else {
                up.abs() / (di - lo.abs())
            };
            product *= if (0.0..=1.0).contains(&r) { r } else { 1.0 };
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
        // Rows from the end inward.
        let row_of = |s: usize| {
            if first {
                self.row(s)
            } else {
                let (lower, diag, upper) = self.row(n - 1 - s);
                (upper, diag, lower)
            }
        };
        let thomas = Thomas::factor_rows(rows, row_of)?;
        let mut w = vec![0.0; rows];
        w[0] = -row_of(0).0;
        thomas.solve_in_place(&mut w).then_some(w)
    }
}
