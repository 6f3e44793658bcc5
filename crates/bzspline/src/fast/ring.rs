//! Closed curves' cyclic systems solved by the open curve's fused sweeps:
//! the method's system (§7) and the interpolating variant's (§11).
//!
//! Row `i` of a cyclic system couples knot `i` to knots `i - 1` and `i + 1`
//! around the ring. The ring's knots `0 ..= n - 1` with its legs but the
//! closing one are an open system, whose rows are the ring's rows `1 ..= n - 2`
//! and whose end deviations, at knots 0 and `n - 1`, the open sweeps take as
//! zero. The system is linear, so the ring's deviations are the open ones `y`
//! plus `a` at knot 0 and `a` times the response `w'` of the rows to a unit
//! deviation there, and `b` at knot `n - 1` and `b` times the response `w''`
//! to one there; each response decays from its end by the rows' damping
//! factors (`docs/method.md` §16), and is taken over the knots that bring it
//! below `2^-64`, as between two chunks. With the two responses apart (the
//! ring longer than both), the ring's rows 0 and `n - 1`, the two the open
//! system lacks, give `a` and `b` from a two-by-two system; the deviations
//! near the ends are corrected, the pieces of their legs formed again and the
//! closing leg's appended. The open system reads the ring's own knots, points
//! and alphas in place, and its outputs are the ring's: nothing is copied or
//! moved. Everything else is the open curve's sweeps, in chunks and on several
//! threads when long. The results agree with the cyclic systems' own solve
//! ([`crate::tridiag::CyclicThomas`]) to rounding.

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
/// together, or its end rows damp too little for the two-by-two system.
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
    // The open system: the ring's knots and legs but the closing one. With
    // one alpha no alpha is read: the knots pace the sweeps.
    let open = &knots[..n];
    let paced = match uniform {
        Some(_) => &knots[..n - 1],
        None => &alphas[..n - 1],
    };
    // Room for the closing leg, so that appending it moves nothing.
    coefs.reserve_exact((n * D).saturating_sub(coefs.len()));
    build_open_curve::<D>(
        open,
        points,
        inv_scale,
        paced,
        uniform,
        inverse_power_of_two(open[n - 1] - open[0]),
        coefs,
        dev,
        points_out,
    );
    coefs.resize(n * D, Piece::default());
    let scaled = |i: usize| -> [f64; D] { core::array::from_fn(|c| pts[i][c] * inv_scale[c]) };
    // The end deviations, and the deviations they move.
    for c in 0..D {
        ends.correct(n, &mut dev[c..], D, |i| pts[i][c] * inv_scale[c]);
    }
    // The legs whose deviations moved, the closing leg among them.
    let one = uniform.map(|a| sweep::leg_terms(a, true));
    for k in ends.legs(n) {
        let j = if k + 1 == n { 0 } else { k + 1 };
        let terms = one.unwrap_or_else(|| sweep::leg_terms(alphas[k], false));
        let (f0, f1) = (scaled(k), scaled(j));
        for c in 0..D {
            let (d0, d1) = (dev[k * D + c], dev[j * D + c]);
            coefs[k * D + c] = Piece(sweep::leg_piece(f0[c], f1[c], d0, d1, terms));
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
    let paced = match uniform {
        Some(_) => &[][..],
        None => &alphas[..n - 1],
    };
    let mut out = vec![[0.0; D]; n];
    if through::solve_all(&knots[..n], points, paced, uniform, scale, &mut out).is_none() {
        return Some(None);
    }
    let mut d = vec![0.0; n];
    for c in 0..D {
        // The open system's deviations from its control values (`G = (P /
        // scale - d) scale`, the power of two exact) at the knots the ends
        // move, which include the four the correction reads, put right.
        let inv = 1.0 / scale[c];
        for i in ends.moved(n) {
            d[i] = points[i][c] * inv - out[i][c] * inv;
        }
        ends.correct(n, &mut d, 1, |i| points[i][c] * inv);
        for i in ends.moved(n) {
            let g = (points[i][c] * inv - d[i]) * scale[c];
            if !g.is_finite() {
                return Some(None);
            }
            out[i][c] = g;
        }
    }
    Some(Some(out))
}

/// Which cyclic system.
#[derive(Clone, Copy, PartialEq, Eq)]
enum System {
    /// The method's, (16) around the ring (§7).
    Method,
    /// The interpolating variant's, `T + K` (§11).
    Through,
}

/// The two ends of a ring's open system, knots 0 and `n - 1`: the responses
/// of the deviations of knots `1, 2, ..` to a unit deviation at knot 0 and
/// of knots `n - 2, n - 3, ..` to one at knot `n - 1`, and the ring's rows 0
/// and `n - 1` with the two-by-two system they give for the deviations at
/// the two knots.
struct Ends {
    first: Vec<f64>,
    last: Vec<f64>,
    /// Rows 0 and `n - 1`: `(lower, diag, upper)`.
    rows: [(f64, f64, f64); 2],
    /// Their neighbour weights `(p, q)`, which weigh their right-hand sides.
    weights: [(f64, f64); 2],
    /// The diagonal of the two-by-two system, whose off-diagonal is the lower
    /// of row 0 and the upper of row `n - 1`, and its determinant's inverse.
    diag: [f64; 2],
    inv_det: f64,
}

impl Ends {
    /// The ends of the ring of `knots` (`tau_0 ..= tau_n`) for `system`;
    /// `None` when the ring is shorter than [`RING_MIN`] or than its two
    /// responses together, or the two-by-two system's determinant is below a
    /// quarter of its diagonal's product (its rows damp too little).
    fn of(knots: &[f64], alphas: &[f64], uniform: Option<f64>, system: System) -> Option<Ends> {
        let n = knots.len().checked_sub(1)?;
        if n < RING_MIN || (uniform.is_none() && alphas.len() != n) {
            return None;
        }
        let ring = Ring {
            knots,
            alphas,
            terms: uniform.map(alpha_terms),
            system,
        };
        let down = ring.reach(true, n - 2)?;
        let up = ring.reach(false, n - 2 - down.len())?;
        let (first, last) = (response(&down)?, response(&up)?);
        let ((r0, w0), (r1, w1)) = (ring.weighted_row(0), ring.weighted_row(n - 1));
        let rows = [r0, r1];
        let [(lo0, di0, up0), (lo1, di1, up1)] = rows;
        // Row 0 meets `w'` at knot 1, row `n - 1` meets `w''` at knot
        // `n - 2`; `w'` is zero at knot `n - 2` and `w''` at knot 1.
        let diag = [di0 + up0 * first[0], di1 + lo1 * last[0]];
        let det = diag[0] * diag[1] - lo0 * up1;
        // The responses are at most 1 in magnitude (§16), so the diagonal
        // dominates; for
        // the method's rows `det` is at least 24/25 of the diagonal's product
        // (the two rows meet at the closing leg, whose one alpha cannot make
        // both weak), and a quarter is checked for either system.
        if !(diag[0] > 0.0 && diag[1] > 0.0 && det.is_finite() && det >= 0.25 * (diag[0] * diag[1]))
        {
            return None;
        }
        Some(Ends {
            first,
            last,
            rows,
            weights: [w0, w1],
            diag,
            inv_det: 1.0 / det,
        })
    }

    /// Corrects the open system's deviations, `y[i * stride]` the one of
    /// knot `i` of `n`, to the ring's, `f(i)` the scaled coordinate of point
    /// `i`: the residuals of rows 0 and `n - 1` give the deviations to add
    /// at knots 0 (`a`) and `n - 1` (`b`), and every knot moves by `a w' +
    /// b w''`. Reads and writes only the knots of [`Ends::moved`].
    fn correct(&self, n: usize, y: &mut [f64], stride: usize, f: impl Fn(usize) -> f64) {
        let at = |i: usize| y[i * stride];
        let residual =
            |(lo, di, up): (f64, f64, f64), (p, q): (f64, f64), [l, i, r]: [usize; 3]| {
                let rhs = q * (f(r) - f(i)) - p * (f(i) - f(l));
                rhs - (lo * at(l) + di * at(i) + up * at(r))
            };
        let g0 = residual(self.rows[0], self.weights[0], [n - 1, 0, 1]);
        let g1 = residual(self.rows[1], self.weights[1], [n - 2, n - 1, 0]);
        let (lo0, up1) = (self.rows[0].0, self.rows[1].2);
        let a = (g0 * self.diag[1] - lo0 * g1) * self.inv_det;
        let b = (self.diag[0] * g1 - up1 * g0) * self.inv_det;
        y[0] += a;
        y[(n - 1) * stride] += b;
        for (i, w) in self.first.iter().enumerate() {
            y[(1 + i) * stride] += a * w;
        }
        for (j, w) in self.last.iter().enumerate() {
            y[(n - 2 - j) * stride] += b * w;
        }
    }

    /// The knots whose deviations [`Ends::correct`] moves: `0 ..` and
    /// `.. n - 1`.
    fn moved(&self, n: usize) -> impl Iterator<Item = usize> {
        (0..=self.first.len()).chain(n - 1 - self.last.len()..n)
    }

    /// The legs with a knot of [`Ends::moved`] at either end, the closing
    /// leg `n - 1` last.
    fn legs(&self, n: usize) -> impl Iterator<Item = usize> {
        (0..=self.first.len()).chain(n - 2 - self.last.len()..n)
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

    /// The leg before knot `i`, around the ring.
    fn before(&self, i: usize) -> usize {
        if i == 0 {
            self.n() - 1
        } else {
            i - 1
        }
    }

    /// Row `i` of the ring (legs `i - 1`, around the ring, and `i`), row-
    /// scaled: `(lower, diag, upper)`.
    fn row(&self, i: usize) -> (f64, f64, f64) {
        self.weighted_row(i).0
    }

    /// [`Ring::row`] and the neighbour weights `(p, q)` that scale it (of
    /// the widths of legs `i - 1` and `i`), which weigh its right-hand side.
    fn weighted_row(&self, i: usize) -> ((f64, f64, f64), (f64, f64)) {
        let l = self.before(i);
        let (p, q) = neighbour_weights(self.width(l), self.width(i));
        let (left, right) = (self.terms(l), self.terms(i));
        let row = match self.system {
            System::Method => row_of_terms(p, q, left, right),
            System::Through => through_row(p, q, left[0], left[1], right[2], right[3]),
        };
        (row, (p, q))
    }

    /// Row `s` in from one end of the open system: row `1 + s` from knot 0
    /// (`first`), else row `n - 2 - s` from knot `n - 1` with its lower and
    /// upper traded, so that `lower` always reaches towards that end.
    fn inward(&self, first: bool, s: usize) -> (f64, f64, f64) {
        if first {
            self.row(1 + s)
        } else {
            let (lower, diag, upper) = self.row(self.n() - 2 - s);
            (upper, diag, lower)
        }
    }

    /// The rows in from knot 0 (`first`: rows `1, 2, ..`) or from knot
    /// `n - 1` (rows `n - 2, n - 3, ..`, as [`Ring::inward`] gives them) of
    /// the knots that a unit deviation at that knot moves by more than
    /// `2^-64`, by the rows' damping factors (§16: `|lower| / (diag -
    /// |upper|)` towards that end; 1 when out of `[0, 1]`). `None` past
    /// [`MAX_OVERLAP`] or `most` rows.
    fn reach(&self, first: bool, most: usize) -> Option<Vec<(f64, f64, f64)>> {
        // Tens of rows at most alphas (21 at alpha 1/2 on even knots).
        let mut rows = Vec::with_capacity(64);
        let mut product = 1.0;
        for s in 0..MAX_OVERLAP.min(most) {
            let row = self.inward(first, s);
            rows.push(row);
            let (lo, di, up) = row;
            let r = lo.abs() / (di - up.abs());
            product *= if (0.0..=1.0).contains(&r) { r } else { 1.0 };
            if product <= TRUNCATION {
                return Some(rows);
            }
        }
        None
    }
}

/// The response of the open system's deviations to a unit deviation at one
/// end, at the knots of `rows` (from [`Ring::reach`]), the response beyond
/// them taken as zero. `None` when a pivot fails.
fn response(rows: &[(f64, f64, f64)]) -> Option<Vec<f64>> {
    let thomas = Thomas::factor_rows(rows.len(), |s| rows[s])?;
    let mut w = vec![0.0; rows.len()];
    w[0] = -rows.first()?.0;
    thomas.solve_in_place(&mut w).then_some(w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::tests::Rng;
    use crate::spline::{ALPHA_MAX, ALPHA_MIN};

    /// The two-by-two system of the method's ring has a determinant of at
    /// least 24/25 of its diagonal's product (§16), on widths over twelve
    /// decades and alphas across the range, its ends included, one alpha
    /// and one a leg.
    #[test]
    fn the_end_system_of_the_methods_ring_is_dominant() {
        let mut rng = Rng(0xd1a6_0a11);
        let mut solved = 0;
        for case in 0..400 {
            let n = 48 + (rng.next() * 3000.0) as usize;
            let mut knots = vec![0.0];
            for _ in 0..n {
                let w = 10f64.powf(12.0 * rng.next() - 6.0);
                knots.push(knots.last().unwrap() + w);
            }
            let pick = |r: f64| match case % 3 {
                0 => ALPHA_MIN,
                1 => ALPHA_MAX,
                _ => ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * r,
            };
            let alphas: Vec<f64> = (0..n).map(|_| pick(rng.next())).collect();
            let uniform = (case % 2 == 0).then(|| pick(rng.next()));
            let Some(e) = Ends::of(&knots, &alphas, uniform, System::Method) else {
                continue;
            };
            solved += 1;
            let product = e.diag[0] * e.diag[1];
            let det = product - e.rows[0].0 * e.rows[1].2;
            // The bound is approached (0.9600002 seen) with widths of very
            // different sizes at alpha 1/2; rounding may take it a hair lower.
            assert!(
                det >= 0.96 * (1.0 - 1e-12) * product,
                "case {case}: det {det}, diagonal {product}"
            );
        }
        // Most rings are long enough for the two responses to lie apart.
        assert!(solved > 300, "{solved}");
    }
}
