//! The interpolating variant's system `(T + K) d = K P` (`docs/method.md`
//! §11), solved for the control values `G = P - d`: one Thomas sweep forward
//! and one back over its rows, each row formed as the forward sweep reaches
//! it and eliminated for every coordinate of a curve at once; from
//! [`chunks::CHUNKED_MIN`] legs the same sweeps over overlapping chunks
//! (§16), side by side with the `rayon` feature, the same bits on any number
//! of threads. The chunks the plan pads to one shape go through the forward
//! sweep two at a time, one in each lane of an SSE2 register, so that their
//! two chains of divisions overlap (each chunk gets the bits it gets alone).

use super::chunks::{self, Chunk};
use crate::lanes::{Lane, F2};
use crate::method::{alpha_terms, neighbour_weights, power_of_two_scale, through_row};

/// The rows of the system: `knots` and `values` (`n` each, validated, `D`
/// coordinates a value), each coordinate scaled by its `inv` as it is read,
/// and the alphas' terms, from `alphas` (`n - 1`) unless `uniform` holds the
/// one alpha's.
struct Rows<'a, const D: usize> {
    knots: &'a [f64],
    values: &'a [[f64; D]],
    inv: [f64; D],
    alphas: &'a [f64],
    uniform: Option<[f64; 4]>,
}

/// A row after the forward sweep: `c'_k`, and `r'_k` of each coordinate.
type Swept<const D: usize> = (f64, [f64; D]);

impl<const D: usize> Rows<'_, D> {
    #[inline(always)]
    fn terms(&self, leg: usize) -> [f64; 4] {
        match self.uniform {
            Some(t) => t,
            None => alpha_terms(self.alphas[leg]),
        }
    }

    /// Row `k` of the matrix (`1 <= k <= n - 2`): its lower, diagonal and
    /// upper entries.
    #[inline(always)]
    fn matrix(&self, k: usize) -> (f64, f64, f64) {
        let knots = self.knots;
        let (hl, hr) = (knots[k] - knots[k - 1], knots[k + 1] - knots[k]);
        let (p, q) = neighbour_weights(hl, hr);
        let [al, b1, _, _] = self.terms(k - 1);
        let [_, _, b2, cr] = self.terms(k);
        through_row(p, q, al, b1, b2, cr)
    }

    /// The forward Thomas sweep over rows `lo + 1 ..= hi - 1` with the
    /// deviation at `lo` taken as zero: `c'_k` and each coordinate's `r'_k`
    /// of each row, in order, into `out`. A row is [`Rows::matrix`]'s with
    /// the right-hand side `q (f_{k+1} - f_k) - p (f_k - f_{k-1})`, the jump
    /// of the scaled data's slope, formed from a window over the knots and
    /// values that moves a knot a row, each alpha's terms formed once; `PER`
    /// says whether the alphas differ (with one alpha the knots pace the loop
    /// in their place).
    #[inline(always)]
    fn forward<const PER: bool>(&self, lo: usize, hi: usize, out: &mut Vec<Swept<D>>) {
        let legs = if PER { self.alphas } else { self.knots };
        let (Some(kn), Some(vs), Some(al)) = (
            self.knots.get(lo..=hi),
            self.values.get(lo..=hi),
            legs.get(lo + 1..hi),
        ) else {
            return;
        };
        let (Some((&[k0, k1], kn)), Some((&[v0, v1], vs))) =
            (kn.split_first_chunk(), vs.split_first_chunk())
        else {
            return;
        };
        let scaled = |v: [f64; D]| -> [f64; D] { std::array::from_fn(|c| v[c] * self.inv[c]) };
        let one = self.uniform.unwrap_or_default();
        let mut st = Forward::start((k0, k1), (scaled(v0), scaled(v1)), self.terms(lo));
        for ((&kr, &vr), &a) in kn.iter().zip(vs).zip(al) {
            let right = if PER { alpha_terms(a) } else { one };
            out.push(st.row(kr, scaled(vr), right, neighbour_weights));
        }
    }

    /// [`Rows::forward`] of two chunks of one shape side by side, one in each
    /// lane of an [`F2`]: each lane takes the operations of its chunk's
    /// forward sweep in their order (the same bits), while the two chains of
    /// divisions overlap.
    #[inline(always)]
    fn forward_two<const PER: bool>(
        &self,
        [a, b]: [Chunk; 2],
        [out_a, out_b]: [&mut [Swept<D>]; 2],
    ) {
        let legs = if PER { self.alphas } else { self.knots };
        let (Some(kna), Some(vsa), Some(ala), Some(knb), Some(vsb), Some(alb)) = (
            self.knots.get(a.lo..=a.hi),
            self.values.get(a.lo..=a.hi),
            legs.get(a.lo + 1..a.hi),
            self.knots.get(b.lo..=b.hi),
            self.values.get(b.lo..=b.hi),
            legs.get(b.lo + 1..b.hi),
        ) else {
            return;
        };
        let (
            Some((&[ka0, ka1], kna)),
            Some((&[va0, va1], vsa)),
            Some((&[kb0, kb1], knb)),
            Some((&[vb0, vb1], vsb)),
        ) = (
            kna.split_first_chunk(),
            vsa.split_first_chunk(),
            knb.split_first_chunk(),
            vsb.split_first_chunk(),
        )
        else {
            return;
        };
        let two = |x: f64, y: f64| F2([x, y]);
        let inv: [F2; D] = std::array::from_fn(|c| F2::splat(self.inv[c]));
        let scaled = |x: [f64; D], y: [f64; D]| -> [F2; D] {
            std::array::from_fn(|c| two(x[c], y[c]) * inv[c])
        };
        let terms =
            |x: [f64; 4], y: [f64; 4]| -> [F2; 4] { std::array::from_fn(|i| two(x[i], y[i])) };
        let one = self.uniform.unwrap_or_default();
        let one = terms(one, one);
        let left = terms(self.terms(a.lo), self.terms(b.lo));
        let f = (scaled(va0, vb0), scaled(va1, vb1));
        let mut st = Forward::start((two(ka0, kb0), two(ka1, kb1)), f, left);
        let lane_a = kna.iter().zip(vsa).zip(ala).zip(out_a);
        let lane_b = knb.iter().zip(vsb).zip(alb).zip(out_b);
        for ((((&kra, &vra), &aa), oa), (((&krb, &vrb), &ab), ob)) in lane_a.zip(lane_b) {
            let right = if PER {
                terms(alpha_terms(aa), alpha_terms(ab))
            } else {
                one
            };
            let (cp, rp) = st.row(two(kra, krb), scaled(vra, vrb), right, weights_two);
            *oa = (cp.0[0], std::array::from_fn(|c| rp[c].0[0]));
            *ob = (cp.0[1], std::array::from_fn(|c| rp[c].0[1]));
        }
    }

    /// The damping factors of row `k` (§16): `|lower| / (diag - |upper|)`
    /// and `|upper| / (diag - |lower|)`, both in `[0, 1]` by the dominance
    /// of every term (§11); anything else counts as 1, no damping.
    fn damping(&self, k: usize) -> (f64, f64) {
        let (lo, di, up) = self.matrix(k);
        let sane = |r: f64| if (0.0..=1.0).contains(&r) { r } else { 1.0 };
        (
            sane(lo.abs() / (di - up.abs())),
            sane(up.abs() / (di - lo.abs())),
        )
    }
}

/// The forward sweep's state between rows, `L` a number of each chunk swept
/// side by side: the last knot, width, two scaled values and alpha terms, and
/// the last row's `c'` and `r'`.
struct Forward<L, const D: usize> {
    kc: L,
    hl: L,
    fl: [L; D],
    fc: [L; D],
    left: [L; 4],
    cp: L,
    rp: [L; D],
}

impl<L: Lane, const D: usize> Forward<L, D> {
    /// Before the first row: knots `lo`, `lo + 1`, the scaled values there,
    /// the terms of alpha `lo`; the deviation at `lo` taken as zero.
    #[inline(always)]
    fn start((k0, k1): (L, L), (f0, f1): ([L; D], [L; D]), left: [L; 4]) -> Self {
        Forward {
            kc: k1,
            hl: k1 - k0,
            fl: f0,
            fc: f1,
            left,
            cp: L::splat(0.0),
            rp: [L::splat(0.0); D],
        }
    }

    /// The next row, from the knot and scaled value past it and the terms of
    /// the alpha between: [`Rows::matrix`]'s row with the right-hand side
    /// `q (f_{k+1} - f_k) - p (f_k - f_{k-1})`, eliminated; its `c'` and `r'`.
    /// `weights` is [`neighbour_weights`] in the lanes.
    #[inline(always)]
    fn row(
        &mut self,
        kr: L,
        fr: [L; D],
        right: [L; 4],
        weights: fn(L, L) -> (L, L),
    ) -> (L, [L; D]) {
        let hr = kr - self.kc;
        let (p, q) = weights(self.hl, hr);
        let left = self.left;
        let (l, di, up) = through_row(p, q, left[0], left[1], right[2], right[3]);
        let m = di - l * self.cp;
        self.cp = up / m;
        let each = self.rp.iter_mut().zip(&fr).zip(&self.fc).zip(&self.fl);
        for (((rp, &fr), &fc), &fl) in each {
            let rhs = q * (fr - fc) - p * (fc - fl);
            *rp = (rhs - l * *rp) / m;
        }
        (self.kc, self.hl, self.fl, self.fc, self.left) = (kr, hr, self.fc, fr, right);
        (self.cp, self.rp)
    }
}

/// [`neighbour_weights`] of both lanes.
#[inline(always)]
fn weights_two(hl: F2, hr: F2) -> (F2, F2) {
    let sum = hl + hr;
    if sum.0[0].is_finite() && sum.0[1].is_finite() {
        (hr / sum, hl / sum)
    } else {
        let (a, b) = (
            neighbour_weights(hl.0[0], hr.0[0]),
            neighbour_weights(hl.0[1], hr.0[1]),
        );
        (F2([a.0, b.0]), F2([a.1, b.1]))
    }
}

/// The control values of the spline through `values` at `knots` into
/// `out` (`n` long), with the largest of their magnitudes; `None` when one
/// of them is not finite. The input is validated: `knots` strictly
/// increasing with a finite span, `values` finite (their largest magnitude
/// scaled by `1 / scale` near 1), `alphas` one per interval in range unless
/// `uniform` gives the one alpha.
pub(crate) fn controls(
    knots: &[f64],
    values: &[f64],
    alphas: &[f64],
    uniform: Option<f64>,
    scale: f64,
    out: &mut [f64],
) -> Option<f64> {
    let (values, out) = (values.as_chunks::<1>().0, out.as_chunks_mut::<1>().0);
    let [max] = solve_all(knots, values, alphas, uniform, [scale], out)?;
    Some(max)
}

/// [`controls`] of `D` coordinates at once, each scaled by its own `scale`,
/// with the largest magnitude of each coordinate's control values.
pub(super) fn solve_all<const D: usize>(
    knots: &[f64],
    values: &[[f64; D]],
    alphas: &[f64],
    uniform: Option<f64>,
    scale: [f64; D],
    out: &mut [[f64; D]],
) -> Option<[f64; D]> {
    solve_paired(knots, values, (alphas, uniform), scale, out, true)
}

/// [`solve_all`], with the forward sweeps of chunks of one shape two at a
/// time when `paired` (each chunk gets the same bits either way).
fn solve_paired<const D: usize>(
    knots: &[f64],
    values: &[[f64; D]],
    (alphas, uniform): (&[f64], Option<f64>),
    scale: [f64; D],
    out: &mut [[f64; D]],
    paired: bool,
) -> Option<[f64; D]> {
    let n = knots.len();
    if n < 2 || values.len() != n || out.len() != n || (uniform.is_none() && alphas.len() != n - 1)
    {
        // Not reached: the caller has validated the lengths.
        return None;
    }
    let rows = Rows {
        knots,
        values,
        inv: scale.map(|s| 1.0 / s),
        alphas,
        uniform: uniform.map(alpha_terms),
    };
    let m = n - 1;
    let mut plan = chunks::cut(m, |k| rows.damping(k));
    chunks::pad_pairs(&mut plan, m);
    if plan.is_empty() {
        plan.push(Chunk {
            lo: 0,
            start: 0,
            end: m,
            hi: m,
        });
    }
    // Each chunk writes the control values of the knots it keeps.
    let mut jobs = Vec::with_capacity(plan.len());
    let mut rest = out;
    for &c in &plan {
        let owned = c.kept().count();
        let (mine, later) = rest.split_at_mut(owned.min(rest.len()));
        jobs.push((c, mine, Some([0.0; D])));
        rest = later;
    }
    // Chunks the plan padded to one shape go through the forward sweep two
    // at a time.
    let mut units = Vec::with_capacity(plan.len());
    let mut jobs = jobs.iter_mut().peekable();
    while let Some(job) = jobs.next() {
        match jobs.next_if(|next| paired && chunks::pairable(&job.0, &next.0, m)) {
            Some(other) => units.push([Some(job), Some(other)]),
            None => units.push([Some(job), None]),
        }
    }
    let scratch = || [Vec::new(), Vec::new()];
    chunks::each(n, &mut units, scratch, |[sa, sb], unit| match unit {
        [Some((a, out_a, max_a)), Some((b, out_b, max_b))] => {
            // Rows `lo + 1 ..= hi - 1` of each.
            for (s, c) in [(&mut *sa, *a), (&mut *sb, *b)] {
                s.resize(c.hi - c.lo - 1, (0.0, [0.0; D]));
            }
            if rows.uniform.is_some() {
                rows.forward_two::<false>([*a, *b], [&mut *sa, &mut *sb]);
            } else {
                rows.forward_two::<true>([*a, *b], [&mut *sa, &mut *sb]);
            }
            *max_a = backward(&rows, *a, scale, out_a, sa);
            *max_b = backward(&rows, *b, scale, out_b, sb);
        }
        [Some((c, mine, max)), _] => *max = solve(&rows, *c, scale, mine, sa),
        _ => {}
    });
    units
        .iter()
        .flatten()
        .flatten()
        .try_fold([0.0f64; D], |m, (_, _, max)| {
            let max = (*max)?;
            Some(std::array::from_fn(|c| m[c].max(max[c])))
        })
}

/// The control points of the open curve through `points` (`dim`
/// coordinates a point, flat) at the parameters `knots` with `alphas` (one
/// per leg) unless `uniform` gives the one alpha: the sweeps of [`controls`]
/// with every coordinate eliminated at once (one at a time beyond three),
/// each scaled by its own power of two while it is solved. `None` when a
/// control value leaves the range of a double.
pub(crate) fn curve_controls(
    knots: &[f64],
    points: &[f64],
    dim: usize,
    alphas: &[f64],
    uniform: Option<f64>,
) -> Option<Vec<f64>> {
    fn fixed<const D: usize>(
        knots: &[f64],
        points: &[f64],
        alphas: &[f64],
        uniform: Option<f64>,
    ) -> Option<Vec<f64>> {
        let values = points.as_chunks::<D>().0;
        let scale = std::array::from_fn(|c| power_of_two_scale(values.iter().map(|p| &p[c])));
        let mut out = vec![0.0; points.len()];
        let dst = out.as_chunks_mut::<D>().0;
        solve_all(knots, values, alphas, uniform, scale, dst)?;
        Some(out)
    }
    let n = knots.len();
    if dim == 0 || points.len() != n * dim {
        return None;
    }
    match dim {
        1 => return fixed::<1>(knots, points, alphas, uniform),
        2 => return fixed::<2>(knots, points, alphas, uniform),
        3 => return fixed::<3>(knots, points, alphas, uniform),
        _ => {}
    }
    let mut out = vec![0.0; points.len()];
    let (mut coord, mut g) = (vec![0.0; n], vec![0.0; n]);
    for c in 0..dim {
        for (v, p) in coord.iter_mut().zip(points.chunks_exact(dim)) {
            *v = p[c];
        }
        let scale = power_of_two_scale(&coord);
        controls(knots, &coord, alphas, uniform, scale, &mut g)?;
        for (p, v) in out.chunks_exact_mut(dim).zip(&g) {
            p[c] = *v;
        }
    }
    Some(out)
}

/// One chunk `c` of the system: the forward sweep over its rows
/// `lo + 1 ..= hi - 1` (the deviations at `lo` and `hi` taken as zero) into
/// `scratch`, then the backward sweep, writing the control values of the
/// knots it keeps into `out`. The largest magnitude of each coordinate's,
/// or `None` when one is not finite.
fn solve<const D: usize>(
    rows: &Rows<'_, D>,
    c: Chunk,
    scale: [f64; D],
    out: &mut [[f64; D]],
    scratch: &mut Vec<Swept<D>>,
) -> Option<[f64; D]> {
    scratch.clear();
    scratch.reserve(c.hi - c.lo);
    if rows.uniform.is_some() {
        rows.forward::<false>(c.lo, c.hi, scratch);
    } else {
        rows.forward::<true>(c.lo, c.hi, scratch);
    }
    backward(rows, c, scale, out, scratch)
}

/// The backward sweep of chunk `c` over the rows its forward sweep left in
/// `swept`, writing the control values of the knots it keeps into `out`: the
/// largest magnitude of each coordinate's, or `None` when one is not finite.
fn backward<const D: usize>(
    rows: &Rows<'_, D>,
    c: Chunk,
    scale: [f64; D],
    out: &mut [[f64; D]],
    swept: &[Swept<D>],
) -> Option<[f64; D]> {
    let n = rows.knots.len();
    let first = *c.kept().start();
    if out.len() != c.kept().count() {
        // Not reached: the plan covers the knots once.
        return None;
    }
    let scratch = swept;
    // Backward: d_k = r'_k - c'_k d_{k+1}, then G_k = P_k - d_k; the rows
    // past the kept knots (`end + 1 ..= hi - 1`) only carry d down. The kept
    // rows are knots `kmin..=kmax`, `scratch[k - lo - 1]` each.
    let (kmin, kmax) = (first.max(1), c.end.min(c.hi - 1));
    let (Some(own), Some(past), Some(dst), Some(src)) = (
        scratch.get(kmin - c.lo - 1..kmax - c.lo),
        scratch.get(kmax - c.lo..),
        out.get_mut(kmin - first..=kmax - first),
        rows.values.get(kmin..=kmax),
    ) else {
        // Not reached: the chunk's rows hold its knots.
        return None;
    };
    let mut next = [0.0; D];
    for &(cp, rp) in past.iter().rev() {
        for c in 0..D {
            next[c] = rp[c] - cp * next[c];
        }
    }
    let mut max = [0.0f64; D];
    let mut finite = true;
    for ((&(cp, rp), g), v) in own.iter().zip(dst).zip(src).rev() {
        for c in 0..D {
            let d = rp[c] - cp * next[c];
            next[c] = d;
            g[c] = (v[c] * rows.inv[c] - d) * scale[c];
            let a = g[c].abs();
            finite &= a <= f64::MAX;
            max[c] = if a > max[c] { a } else { max[c] };
        }
    }
    // The end points are their own control values.
    for k in [0, n - 1] {
        if (first..=c.end).contains(&k) {
            out[k - first] = rows.values[k];
            for (m, v) in max.iter_mut().zip(rows.values[k]) {
                *m = m.max(v.abs());
            }
        }
    }
    finite.then_some(max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::case;

    /// The whole system in one Thomas sweep over all its rows, written
    /// plainly: the reference the chunks must reproduce.
    fn whole(knots: &[f64], values: &[f64], alphas: &[f64], uniform: Option<f64>) -> Vec<f64> {
        let n = knots.len();
        let rows = Rows {
            knots,
            values: values.as_chunks::<1>().0,
            inv: [1.0],
            alphas,
            uniform: uniform.map(alpha_terms),
        };
        let (mut c, mut r) = (vec![0.0; n], vec![0.0; n]);
        for k in 1..n - 1 {
            let (lo, di, up) = rows.matrix(k);
            let (p, q) = neighbour_weights(knots[k] - knots[k - 1], knots[k + 1] - knots[k]);
            let rhs = q * (values[k + 1] - values[k]) - p * (values[k] - values[k - 1]);
            let m = di - lo * c[k - 1];
            c[k] = up / m;
            r[k] = (rhs - lo * r[k - 1]) / m;
        }
        let mut d = vec![0.0; n];
        for k in (1..n - 1).rev() {
            d[k] = r[k] - c[k] * d[k + 1];
        }
        (0..n).map(|k| values[k] - d[k]).collect()
    }

    #[test]
    fn chunks_agree_with_the_whole_system_to_rounding() {
        let n = 5 * chunks::CHUNK + 1234;
        let mut worst: f64 = 0.0;
        for grid in 0..2u8 {
            for kind in 0..6u8 {
                let seed = 10 * u64::from(grid) + u64::from(kind);
                let (knots, values, a, uniform) = case(n, grid, kind, seed);
                let rows = Rows {
                    knots: &knots,
                    values: values.as_chunks::<1>().0,
                    inv: [1.0],
                    alphas: &a,
                    uniform: uniform.map(alpha_terms),
                };
                let plan = chunks::cut(n - 1, |k| rows.damping(k));
                assert!(plan.len() >= 4, "grid {grid}, alphas {kind}: {plan:?}");
                let mut g = vec![0.0; n];
                let max = controls(&knots, &values, &a, uniform, 1.0, &mut g);
                let want = whole(&knots, &values, &a, uniform);
                let big = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let max = max.unwrap_or(f64::NAN);
                assert!(
                    (max - big).abs() <= 16.0 * big * f64::EPSILON,
                    "grid {grid}, alphas {kind}: {max} against {big}"
                );
                for (k, (x, y)) in g.iter().zip(&want).enumerate() {
                    let e = (x - y).abs() / (big * f64::EPSILON);
                    worst = worst.max(e);
                    assert!(
                        e <= 16.0,
                        "grid {grid}, alphas {kind}: G_{k} {x} against {y}"
                    );
                }
            }
        }
        eprintln!("largest difference: {worst} ulps of the largest control value");
    }

    #[test]
    fn alpha_one_half_needs_one_row_of_overlap() {
        // The system is diagonal: no row passes anything on.
        let n = 5 * chunks::CHUNK;
        let (knots, values, _, _) = case(n, 1, 5, 3);
        let rows = Rows {
            knots: &knots,
            values: values.as_chunks::<1>().0,
            inv: [1.0],
            alphas: &[],
            uniform: Some(alpha_terms(0.5)),
        };
        let plan = chunks::cut(n - 1, |k| rows.damping(k));
        assert!(plan.len() >= 4);
        for (i, c) in plan.iter().enumerate() {
            if i > 0 {
                assert_eq!(c.start - c.lo, 1, "{c:?}");
            }
            if i + 1 < plan.len() {
                assert_eq!(c.hi - c.end, 1, "{c:?}");
            }
        }
    }

    #[test]
    fn a_control_value_that_overflows_is_refused() {
        let n = 5 * chunks::CHUNK;
        let (knots, ..) = case(n, 0, 5, 4);
        // Values of 0.9 times the largest double, alternating in sign: at
        // alpha 1/2 each control value is 1.5 times its value, past the
        // largest double, in every chunk.
        let values: Vec<f64> = (0..n)
            .map(|i| if i % 2 == 0 { 0.9 } else { -0.9 } * f64::MAX)
            .collect();
        let scale = 2f64.powi(1023);
        let mut g = vec![0.0; n];
        assert_eq!(
            controls(&knots, &values, &[], Some(0.5), scale, &mut g),
            None
        );
        // A tenth of them stays finite.
        let tenth: Vec<f64> = values.iter().map(|v| v / 10.0).collect();
        assert!(controls(&knots, &tenth, &[], Some(0.5), scale, &mut g).is_some());
    }

    #[cfg(feature = "rayon")]
    #[test]
    fn every_thread_count_gives_the_same_bits() {
        let n = 10 * chunks::CHUNK + 3;
        let (knots, values, a, _) = case(n, 1, 0, 9);
        let runs: Vec<Vec<u64>> = [1, 2, 16]
            .into_iter()
            .map(|threads| {
                crate::testing::on_threads(threads, || {
                    let mut g = vec![0.0; n];
                    let max = controls(&knots, &values, &a, None, 1.0, &mut g);
                    assert!(max.is_some());
                    g.iter().map(|v| v.to_bits()).collect()
                })
            })
            .collect();
        assert!(runs.iter().all(|r| *r == runs[0]));
    }

    #[test]
    fn paired_forward_sweeps_give_each_chunk_s_bits() {
        let n = 9 * chunks::CHUNK + 321;
        for grid in 0..2u8 {
            for kind in 0..5u8 {
                let (knots, v, a, uniform) = case(n, grid, kind, 40 + u64::from(kind));
                let m = n - 1;
                let rows = Rows {
                    knots: &knots,
                    values: v.as_chunks::<1>().0,
                    inv: [1.0],
                    alphas: &a,
                    uniform: uniform.map(alpha_terms),
                };
                let mut plan = chunks::cut(m, |k| rows.damping(k));
                chunks::pad_pairs(&mut plan, m);
                let pairs = plan
                    .windows(2)
                    .filter(|w| chunks::pairable(&w[0], &w[1], m));
                assert!(pairs.count() >= 3, "grid {grid}, alphas {kind}: {plan:?}");
                let points: Vec<[f64; 2]> = v.iter().map(|&y| [y, y * y * 1e3]).collect();
                let solved = |paired: bool| {
                    let mut one = vec![[0.0]; n];
                    let mut two = vec![[0.0; 2]; n];
                    let values = v.as_chunks::<1>().0;
                    solve_paired(&knots, values, (&a, uniform), [2.0], &mut one, paired);
                    solve_paired(
                        &knots,
                        &points,
                        (&a, uniform),
                        [1.0, 4096.0],
                        &mut two,
                        paired,
                    );
                    let bits = one.iter().flatten().chain(two.iter().flatten());
                    bits.map(|x| x.to_bits()).collect::<Vec<u64>>()
                };
                assert!(solved(true) == solved(false), "grid {grid}, alphas {kind}");
            }
        }
    }

    #[test]
    fn every_coordinate_at_once_gives_each_coordinate_s_bits() {
        // A curve's coordinates are eliminated together; each must come out
        // as the one-coordinate solve gives it, in chunks and without.
        for (n, seed) in [(1000, 1u64), (5 * chunks::CHUNK + 17, 2)] {
            for dim in 1..=3 {
                for kind in [0u8, 5] {
                    let (knots, _, a, uniform) = case(n, 1, kind, seed);
                    // Coordinates of their own data and magnitudes.
                    let coords: Vec<Vec<f64>> = (0..dim)
                        .map(|c| {
                            let v = case(n, 0, 0, seed + 100 + c as u64).1;
                            v.iter().map(|x| x * 1e3f64.powi(c as i32)).collect()
                        })
                        .collect();
                    let pts: Vec<f64> = (0..n * dim).map(|i| coords[i % dim][i / dim]).collect();
                    let got = curve_controls(&knots, &pts, dim, &a, uniform).unwrap();
                    for c in 0..dim {
                        let coord = &coords[c];
                        let mut want = vec![0.0; n];
                        let scale = power_of_two_scale(coord);
                        controls(&knots, coord, &a, uniform, scale, &mut want).unwrap();
                        for k in 0..n {
                            assert_eq!(
                                got[k * dim + c].to_bits(),
                                want[k].to_bits(),
                                "n {n}, dim {dim}, alphas {kind}, coordinate {c}, knot {k}"
                            );
                        }
                    }
                }
            }
        }
    }
}
