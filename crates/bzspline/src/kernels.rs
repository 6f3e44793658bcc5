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
//! The forward sweep keeps its two numbers per row (`u_k / piv_k` and the
//! swept right-hand side, `D + 1` numbers for `D` coordinates) in the slots of
//! two outputs of length `n` that the backward sweep writes anyway after it
//! has read them: a spline's copies of knot `k` and value `k`, a curve's copy of
//! point `k` and its deviation (the copies from the input, which the backward
//! sweep reads). The pieces are then written once, by the backward sweep, and
//! nothing else holds the rows: no scratch vector. The alpha inverses of
//! per-interval alphas are formed again in the backward sweep.

use crate::method::alpha_terms;
use crate::poly::deriv;

/// Rows between two renormalisations of the continuants: each row multiplies
/// them by a pivot between `3 * 2^-52` and `32` (widths relative to a span
/// near 1), so in 8 rows they stay within `2^-400 .. 2^40` of `[1, 2)`, and a
/// product of two of them far inside a double.
const RENORM: usize = 8;

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
#[cfg(test)]
fn alpha_terms_one_division(a: f64) -> [f64; 4] {
    let u = 1.0 - a;
    let iau = 1.0 / (a * u);
    terms_from_inverses(a, u * iau, a * iau)
}

/// The alpha terms a piece needs: `B2'` and `C'` for its first slope, and the
/// weights of `d0`, `d1` in its `t^2` and `t^3` coefficients.
#[inline(always)]
fn piece_terms(terms: [f64; 4]) -> [f64; 6] {
    let [al, b1, b2, cr] = terms;
    [
        b2,
        cr,
        2.0 * b2 + al - 3.0,
        3.0 - 2.0 * cr - b1,
        2.0 - b2 - al,
        cr + b1 - 2.0,
    ]
}

/// Coefficients of a piece from its scaled values, deviations and
/// [`piece_terms`]: the coefficients of `spline::piece_coefs`,
/// `c2 = 3 rise - 2 s0 - s1` and `c3 = s0 + s1 - 2 rise` with the value step
/// cancelled out beforehand (it drops out of both exactly).
#[inline(always)]
fn piece(f0: f64, f1: f64, d0: f64, d1: f64, pt: [f64; 6]) -> [f64; 4] {
    let [b2, cr, c2d0, c2d1, c3d0, c3d1] = pt;
    [
        f0 + d0,
        (f1 - f0) + (d1 * cr - d0 * b2),
        d0 * c2d0 + d1 * c2d1,
        d0 * c3d0 + d1 * c3d1,
    ]
}

/// Leg `k` of a sweep's output: the `D` pieces (one per coordinate).
pub(crate) trait Leg<const D: usize>: Copy {
    /// Stores the pieces.
    fn put_pieces(&mut self, pieces: [[f64; 4]; D]);
}

impl Leg<1> for Piece {
    #[inline(always)]
    fn put_pieces(&mut self, pieces: [[f64; 4]; 1]) {
        self.0 = pieces[0];
    }
}

/// The `D` pieces of a curve's segment, one per coordinate.
impl<const D: usize> Leg<D> for [[f64; 4]; D] {
    #[inline(always)]
    fn put_pieces(&mut self, pieces: [[f64; 4]; D]) {
        *self = pieces;
    }
}

/// Builds the pieces of a validated spline into `coefs` (resized to one piece
/// per interval; its allocation is reused).
///
/// `knots` are strictly increasing with a finite span, `values` finite and of
/// the same length (at least 2), `alphas` one per interval and in range;
/// `uniform` is `Some(a)` when every alpha is `a` (the exact [`alpha_terms`] are
/// then used throughout). `inv_scale` is the exact power of two that scales the
/// values, `wscale` the power of two that brings the span near 1.
pub(crate) fn build(
    knots: &[f64],
    values: &[f64],
    alphas: &[f64],
    uniform: Option<f64>,
    inv_scale: f64,
    wscale: f64,
    (coefs, knots_out, values_out): (&mut Vec<Piece>, &mut Vec<f64>, &mut Vec<f64>),
) {
    let n = knots.len();
    if n < 2 || values.len() != n || alphas.len() != n - 1 {
        // Not reached: the caller has validated the lengths.
        coefs.clear();
        for (out, v) in [(&mut *knots_out, knots), (&mut *values_out, values)] {
            out.clear();
            out.extend_from_slice(v);
        }
        return;
    }
    // Every piece and copy is overwritten below (the copies of the knots and
    // values by the backward sweep, after the forward one kept its rows in
    // them): keep the old contents rather than clearing them first (no pass
    // over the memory when the size is unchanged).
    coefs.truncate(n - 1);
    coefs.resize(n - 1, Piece::default());
    for out in [&mut *knots_out, &mut *values_out] {
        out.truncate(n);
        out.resize(n, 0.0);
    }
    let input = Sweep::new(
        knots,
        values.as_chunks().0,
        [inv_scale],
        alphas,
        uniform,
        wscale,
    );
    let (kn, vs) = (
        knots_out.as_chunks_mut::<1>().0,
        values_out.as_chunks_mut::<1>().0,
    );
    let Some((head, rows)) = coefs.split_first_mut() else {
        return;
    };
    let head = core::slice::from_mut(head);
    if uniform.is_some() {
        input.run::<false, true, _>(head, rows, kn, vs);
    } else {
        input.run::<true, true, _>(head, rows, kn, vs);
    }
}

/// Builds the segments of a validated open curve in `D` dimensions: `coefs`
/// gets the curve's layout (`D` pieces per leg, coordinate fastest), `dev`
/// the scaled deviations of every point (zero at both ends) and `points_out`
/// a copy of `points`. Lengths: `points` `n D` (scaled by `inv_scale`,
/// coordinate by coordinate, as they are read), `knots` `n >= 2`, `alphas`
/// `n - 1`; `coefs`, `dev` and `points_out` are resized.
///
/// The forward sweep keeps row `k` in `points_out[k]` and `dev[k]` (`2 D` slots
/// for `D + 1` numbers), which the backward sweep then overwrites with the copy
/// of point `k` and its deviation: the legs' memory is written once, by the
/// backward sweep, rather than once with the rows and again with the pieces.
#[allow(clippy::too_many_arguments)] // the parts of a curve, validated
pub(crate) fn build_open_curve<const D: usize>(
    knots: &[f64],
    points: &[f64],
    inv_scale: [f64; D],
    alphas: &[f64],
    uniform: Option<f64>,
    wscale: f64,
    coefs: &mut Vec<[f64; 4]>,
    dev: &mut Vec<f64>,
    points_out: &mut Vec<f64>,
) {
    let n = knots.len();
    coefs.truncate((n.max(1) - 1) * D);
    coefs.resize((n.max(1) - 1) * D, [0.0; 4]);
    // Every slot is overwritten below: no pass to clear them first.
    for v in [&mut *dev, &mut *points_out] {
        v.truncate(n * D);
        v.resize(n * D, 0.0);
    }
    let (values, _) = points.as_chunks::<D>();
    if n < 2 || values.len() != n || alphas.len() != n - 1 {
        // Not reached: the caller has validated the lengths.
        points_out.clear();
        points_out.extend_from_slice(points);
        return;
    }
    let (legs, _) = coefs.as_chunks_mut::<D>();
    let Some((head, rows)) = legs.split_first_mut() else {
        return;
    };
    let head = core::slice::from_mut(head);
    let (dev, pts) = (
        dev.as_chunks_mut::<D>().0,
        points_out.as_chunks_mut::<D>().0,
    );
    let input = Sweep::new(knots, values, inv_scale, alphas, uniform, wscale);
    if uniform.is_some() {
        input.run::<false, false, _>(head, rows, dev, pts);
    } else {
        input.run::<true, false, _>(head, rows, dev, pts);
    }
}

/// `(1/a, 1/(1-a))` with one division.
#[inline(always)]
fn inverses(a: f64) -> (f64, f64) {
    let u = 1.0 - a;
    let iau = 1.0 / (a * u);
    (u * iau, a * iau)
}

/// [`inverses`] of `a` when the alphas differ (`PER`), for the sweeps; not
/// formed (and not read) otherwise.
#[inline(always)]
fn inv_of<const PER: bool>(a: f64) -> (f64, f64) {
    if PER {
        inverses(a)
    } else {
        (0.0, 0.0)
    }
}

/// `a - b` coordinate by coordinate.
#[inline(always)]
fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    core::array::from_fn(|c| a[c] - b[c])
}

/// The input of the fused sweeps: `D` right-hand sides (the coordinates of
/// the points, `values[k][c] * inv_scale[c]`) on one matrix.
struct Sweep<'a, const D: usize> {
    knots: &'a [f64],
    values: &'a [[f64; D]],
    inv_scale: [f64; D],
    alphas: &'a [f64],
    /// The terms of every alpha when they are all one (`PER` false).
    uniform: [f64; 4],
    /// Their [`piece_terms`].
    uniform_piece: [f64; 6],
    /// The power of two the widths are multiplied by.
    ws: f64,
}

impl<'a, const D: usize> Sweep<'a, D> {
    /// The input, with the alpha terms of `uniform` (the one alpha of every
    /// interval, when there is one) formed once.
    fn new(
        knots: &'a [f64],
        values: &'a [[f64; D]],
        inv_scale: [f64; D],
        alphas: &'a [f64],
        uniform: Option<f64>,
        ws: f64,
    ) -> Self {
        let terms = uniform.map_or([0.0; 4], alpha_terms);
        Sweep {
            knots,
            values,
            inv_scale,
            alphas,
            uniform: terms,
            uniform_piece: piece_terms(terms),
            ws,
        }
    }

    #[inline(always)]
    fn scaled(&self, v: [f64; D]) -> [f64; D] {
        core::array::from_fn(|c| v[c] * self.inv_scale[c])
    }

    /// The sweeps of [`build`] and [`build_open_curve`]; `PER` says whether the
    /// alphas differ (their terms are then formed per interval, else
    /// `uniform` serves every interval). `head` and `rows` are leg 0 and the
    /// rest (`n - 1` legs in all). The forward sweep keeps row `k` in
    /// `second[k]` and `first[k]` (`2 D` slots for `D + 1` numbers; `n` of
    /// each), which the backward sweep then overwrites with `values[k]` (in
    /// `first`) and the deviation (in `second`), or with `KNOT` the knot (in
    /// `second[k][0]`, for `D = 1`): a spline's copies of its knots and
    /// values, a curve's deviations and copy of its points. The pieces are
    /// written once, by the backward sweep.
    #[inline(always)]
    fn run<const PER: bool, const KNOT: bool, L: Leg<D>>(
        &self,
        head: &mut [L],
        rows: &mut [L],
        second: &mut [[f64; D]],
        first: &mut [[f64; D]],
    ) {
        let m = rows.len() + 1;
        let (Some(dev), Some(pts)) = (second.get_mut(..=m), first.get_mut(..=m)) else {
            return;
        };
        let (values, rows_d, rows_p) = (self.values, &mut dev[1..m], &mut pts[1..m]);
        {
            let (pd, ld) = rows_d.as_chunks_mut::<2>();
            let (pp, lp) = rows_p.as_chunks_mut::<2>();
            let pairs = pd
                .iter_mut()
                .zip(pp)
                .map(|([d0, d1], [p0, p1])| [Aside { p: p0, d: d0 }, Aside { p: p1, d: d1 }]);
            let last = ld
                .first_mut()
                .zip(lp.first_mut())
                .map(|(d, p)| Aside { p, d });
            self.forward::<PER>(pairs, last);
        }
        let (fd, pd) = rows_d.as_rchunks_mut::<2>();
        let (fp, pp) = rows_p.as_rchunks_mut::<2>();
        let (fl, pl) = rows.as_rchunks_mut::<2>();
        let pairs = pl
            .iter_mut()
            .zip(pd)
            .zip(pp)
            .rev()
            .map(|(([l0, l1], [d0, d1]), [p0, p1])| {
                [
                    AsideBack::<L, D, KNOT> {
                        leg: l0,
                        at: Aside { p: p0, d: d0 },
                    },
                    AsideBack {
                        leg: l1,
                        at: Aside { p: p1, d: d1 },
                    },
                ]
            });
        let first = match (fl.first_mut(), fd.first_mut(), fp.first_mut()) {
            (Some(leg), Some(d), Some(p)) => Some(AsideBack {
                leg,
                at: Aside { p, d },
            }),
            _ => None,
        };
        self.backward::<PER, L, KNOT>(pairs, first, head);
        // The end points: their copies, and deviation zero (or the knot).
        for i in [0, m] {
            if let (Some(d), Some(p), Some(v), Some(&k)) = (
                dev.get_mut(i),
                pts.get_mut(i),
                values.get(i),
                self.knots.get(i),
            ) {
                *p = *v;
                if KNOT {
                    d[0] = k;
                } else {
                    *d = [0.0; D];
                }
            }
        }
    }

    /// The forward sweep over rows `k = 1 .. n - 2`, two at a time (`pairs`,
    /// then `last` when their number is odd), kept in their slots.
    #[inline(always)]
    fn forward<'s, const PER: bool>(
        &self,
        pairs: impl Iterator<Item = [Aside<'s, D>; 2]>,
        last: Option<Aside<'s, D>>,
    ) {
        let (knots, values, alphas) = (self.knots, self.values, self.alphas);
        let ws = self.ws;
        let m = knots.len().saturating_sub(1);
        let terms = |a: f64, (ia, iu): (f64, f64)| {
            if PER {
                terms_from_inverses(a, ia, iu)
            } else {
                self.uniform
            }
        };
        let (Some(&k0), Some(&k1), Some(&v0), Some(&v1), Some(&a0)) = (
            knots.first(),
            knots.get(1),
            values.first(),
            values.get(1),
            alphas.first(),
        ) else {
            return;
        };
        let v0 = self.scaled(v0);

        let mut p_prev2 = 1.0; // P_{k-2}
        let mut p_prev = 1.0; // P_{k-1}
        let mut y_prev = [0.0; D];
        let mut u_prev = 0.0;
        let mut kc = k1; // knots[k]
        let mut hl = (k1 - k0) * ws;
        let mut fc = self.scaled(v1);
        let mut df_l = sub(fc, v0); // F_k - F_{k-1}, scaled
        let mut terms_l = terms(a0, inv_of::<PER>(a0));
        let mut since = 0;
        let kn = knots.get(2..).unwrap_or_default().chunks_exact(2);
        let vs = values.get(2..).unwrap_or_default().chunks_exact(2);
        let al = alphas.get(1..).unwrap_or_default().chunks_exact(2);
        for (((slots, kn), vs), al) in pairs.zip(kn).zip(vs).zip(al) {
            // Rows k and k + 1.
            let h1 = (kn[0] - kc) * ws;
            let h2 = (kn[1] - kn[0]) * ws;
            kc = kn[1];
            let (f1, f2) = (self.scaled(vs[0]), self.scaled(vs[1]));
            let (i1, i2) = (inv_of::<PER>(al[0]), inv_of::<PER>(al[1]));
            let (t1, t2) = (terms(al[0], i1), terms(al[1], i2));
            let l1 = -h1 * terms_l[0];
            let d1 = h1 * terms_l[1] + hl * t1[2];
            let u1 = -hl * t1[3];
            let (df1, df2) = (sub(f1, fc), sub(f2, f1));
            let l2 = -h2 * t1[0];
            let d2 = h2 * t1[1] + h1 * t2[2];
            let u2 = -h1 * t2[3];
            let e1 = l1 * u_prev;
            let e2 = l2 * u1;
            // P_k and P_{k+1} both from P_{k-1}, P_{k-2}: one multiply-subtract
            // on the chain for two rows.
            let p1 = d1 * p_prev - e1 * p_prev2;
            let p2 = (d2 * d1 - e2) * p_prev - (d2 * e1) * p_prev2;
            // One division for both pivots' reciprocals.
            let rr = 1.0 / (p1 * p2);
            let inv1 = p_prev * p2 * rr;
            let inv2 = p1 * p1 * rr;
            let (m1, m2) = (l1 * inv1, l2 * inv2);
            let mut y1 = [0.0; D];
            let mut y2 = [0.0; D];
            for c in 0..D {
                let g1 = (hl * df1[c] - h1 * df_l[c]) * inv1;
                let g2 = (h1 * df2[c] - h2 * df1[c]) * inv2;
                y1[c] = g1 - m1 * y_prev[c];
                y2[c] = (g2 - m2 * g1) + (m2 * m1) * y_prev[c];
            }
            let [mut s1, mut s2] = slots;
            s1.put(u1 * inv1, y1);
            s2.put(u2 * inv2, y2);
            p_prev2 = p1;
            p_prev = p2;
            since += 2;
            if since >= RENORM {
                renormalise(&mut p_prev, &mut p_prev2);
                since = 0;
            }
            y_prev = y2;
            u_prev = u2;
            hl = h2;
            df_l = df2;
            fc = f2;
            terms_l = t2;
        }
        let done = 1 + 2 * ((m - 1) / 2);
        if let (Some(mut slot), Some(&kr), Some(&vr), Some(&ar)) = (
            last,
            knots.get(done + 1),
            values.get(done + 1),
            alphas.get(done),
        ) {
            // The last row when their number is odd.
            let hr = (kr - kc) * ws;
            let fr = self.scaled(vr);
            let ir = inv_of::<PER>(ar);
            let terms_r = terms(ar, ir);
            let l = -hr * terms_l[0];
            let d = hr * terms_l[1] + hl * terms_r[2];
            let u = -hl * terms_r[3];
            let p = d * p_prev - (l * u_prev) * p_prev2;
            let inv = p_prev / p;
            let y = core::array::from_fn(|c| {
                (hl * (fr[c] - fc[c]) - hr * df_l[c]) * inv - (l * inv) * y_prev[c]
            });
            slot.put(u * inv, y);
        }
    }

    /// The backward sweep: `d_k` from `d_{k+1}`, two rows at a time from the
    /// end (`pairs`: rows `k - 2, k - 1`; then `first`, row 1, when their
    /// number is odd), then the pieces; `head` is leg 0.
    #[inline(always)]
    fn backward<'s, const PER: bool, L: Leg<D> + 's, const KNOT: bool>(
        &self,
        pairs: impl Iterator<Item = [AsideBack<'s, L, D, KNOT>; 2]>,
        first: Option<AsideBack<'s, L, D, KNOT>>,
        head: &mut [L],
    ) {
        let (values, alphas) = (self.values, self.alphas);
        let m = self.knots.len().saturating_sub(1);
        let pieces = |f0: [f64; D], f1: [f64; D], d0: [f64; D], d1: [f64; D], a: f64, inv| {
            let pt = if PER {
                let (ia, iu) = inv;
                piece_terms(terms_from_inverses(a, ia, iu))
            } else {
                self.uniform_piece
            };
            core::array::from_fn(|c| piece(f0[c], f1[c], d0[c], d1[c], pt))
        };
        let (Some(&v0), Some(&a0)) = (values.first(), alphas.first()) else {
            return;
        };
        let mut d_next = [0.0; D];
        let mut f_next = self.scaled(values.get(m).copied().unwrap_or([0.0; D]));
        let vs = values.get(1..m).unwrap_or_default().rchunks_exact(2);
        let al = alphas.get(1..m).unwrap_or_default().rchunks_exact(2);
        let kn = self.knots.get(1..m).unwrap_or_default().rchunks_exact(2);
        for (((pair, vs), al), kn) in pairs.zip(vs).zip(al).zip(kn) {
            // Rows k - 2 and k - 1.
            let [mut a, mut b] = pair;
            let (ma, ya) = a.row();
            let (mb, yb) = b.row();
            let mut d_k = [0.0; D];
            let mut d_km1 = [0.0; D];
            for c in 0..D {
                d_k[c] = yb[c] - mb * d_next[c];
                // d_{k-1} from d_{k+1}: one multiply-add on the chain for two rows.
                d_km1[c] = (ya[c] - ma * yb[c]) + (ma * mb) * d_next[c];
            }
            let (fkm1, fk) = (self.scaled(vs[0]), self.scaled(vs[1]));
            // The alpha inverses, formed again.
            let (ia, ib) = (inv_of::<PER>(al[0]), inv_of::<PER>(al[1]));
            b.finish(
                pieces(fk, f_next, d_k, d_next, al[1], ib),
                vs[1],
                d_k,
                kn[1],
            );
            a.finish(pieces(fkm1, fk, d_km1, d_k, al[0], ia), vs[0], d_km1, kn[0]);
            d_next = d_km1;
            f_next = fkm1;
        }
        if let (Some(mut slot), Some(&v), Some(&a), Some(&kv)) =
            (first, values.get(1), alphas.get(1), self.knots.get(1))
        {
            // Row 1 when the number of rows is odd.
            let (mb, yb) = slot.row();
            let d = core::array::from_fn(|c| yb[c] - mb * d_next[c]);
            let f1 = self.scaled(v);
            slot.finish(pieces(f1, f_next, d, d_next, a, inv_of::<PER>(a)), v, d, kv);
            d_next = d;
            f_next = f1;
        }
        if let Some(slot) = head.first_mut() {
            let v0 = self.scaled(v0);
            slot.put_pieces(pieces(v0, f_next, [0.0; D], d_next, a0, inv_of::<PER>(a0)));
        }
    }
}

/// Row `k` of a sweep in the `2 D` slots `p` and `d` (a spline's copies of
/// value and knot `k`, a curve's copy of point `k` and its deviation):
/// `u_k / piv_k`, then the `D` swept right-hand sides.
struct Aside<'a, const D: usize> {
    p: &'a mut [f64; D],
    d: &'a mut [f64; D],
}

impl<const D: usize> Aside<'_, D> {
    #[inline(always)]
    fn get(&self, i: usize) -> f64 {
        if i < D {
            self.p[i]
        } else {
            self.d[i - D]
        }
    }

    /// Stores the row.
    #[inline(always)]
    fn put(&mut self, m: f64, y: [f64; D]) {
        self.p[0] = m;
        for (c, &v) in y.iter().enumerate() {
            if c + 1 < D {
                self.p[c + 1] = v;
            } else {
                self.d[c + 1 - D] = v;
            }
        }
    }
}

/// Leg `k` with the slots of row `k` ([`Aside`]); `KNOT`: the second slot
/// takes knot `k` (a spline's copy of its knots) rather than the deviation.
struct AsideBack<'a, L, const D: usize, const KNOT: bool> {
    leg: &'a mut L,
    at: Aside<'a, D>,
}

impl<const D: usize, L: Leg<D>, const KNOT: bool> AsideBack<'_, L, D, KNOT> {
    /// The row as [`Aside::put`] stored it.
    #[inline(always)]
    fn row(&self) -> (f64, [f64; D]) {
        (self.at.get(0), core::array::from_fn(|c| self.at.get(c + 1)))
    }

    /// Stores leg `k`'s pieces, the copy of value or point `k` (`value`,
    /// unscaled), and the deviation `d` or the `knot`.
    #[inline(always)]
    fn finish(&mut self, pieces: [[f64; 4]; D], value: [f64; D], d: [f64; D], knot: f64) {
        self.leg.put_pieces(pieces);
        *self.at.p = value;
        if KNOT {
            self.at.d[0] = knot;
        } else {
            *self.at.d = d;
        }
    }
}

/// `A', B1', B2', C'` from `a`, `1/a` and `1/(1-a)`.
#[inline(always)]
fn terms_from_inverses(a: f64, ia: f64, iu: f64) -> [f64; 4] {
    let r = a * iu;
    let ir = (1.0 - a) * ia;
    [r * r, 2.0 * ia + 1.0, 2.0 * iu + 1.0, ir * ir]
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

/// Whether `per_h::<O>(deriv::<O>(c, t) * scale, inv)` is finite for every
/// `t` in `[0, 1]` (and a little past it, where rounding puts the end of a
/// piece): the sum of the magnitudes of the terms bounds every partial sum
/// of the Horner scheme, and the margin of a factor 4 covers its rounding.
#[inline(always)]
fn bounded<const O: u32>(c: &[f64; 4], scale: f64, inv: f64) -> bool {
    let b = match O {
        0 => c[0].abs() + c[1].abs() + c[2].abs() + c[3].abs(),
        1 => c[1].abs() + 2.0 * c[2].abs() + 3.0 * c[3].abs(),
        2 => 2.0 * c[2].abs() + 6.0 * c[3].abs(),
        _ => 6.0 * c[3].abs(),
    };
    // NaN and infinities fail the comparison.
    per_h::<O>(b * scale, inv) <= 0.25 * f64::MAX
}

/// Evaluates the queries from `xb[j]` on while they lie in the piece
/// `[k0, k1)` with coefficients `c`; returns the index of the first that does
/// not (or the block's length).
#[inline(always)]
fn walk_piece<const O: u32>(
    xb: &[f64],
    ob: &mut [f64],
    mut j: usize,
    c: &[f64; 4],
    (k0, k1, inv): (f64, f64, f64),
    scale: f64,
) -> usize {
    let c = *c;
    while let (Some(&x), Some(o)) = (xb.get(j), ob.get_mut(j)) {
        if !(x >= k0 && x < k1) {
            break;
        }
        let t = (x - k0) * inv;
        *o = per_h::<O>(deriv::<O>(&c, t) * scale, inv);
        j += 1;
    }
    j
}

/// The batch evaluators' way to the one-by-one path: kept out of line, so
/// that the rare call does not crowd the registers of the hot loops.
#[cold]
#[inline(never)]
fn call_slow<E>(
    slow: &mut impl FnMut(usize, f64, &mut f64) -> Result<(), E>,
    i: usize,
    x: f64,
    o: &mut f64,
) -> Result<(), E> {
    slow(i, x, o)
}

/// Queries handed to the batch evaluators at once by the block search.
pub(crate) const BLOCK: usize = 32;

/// Knots between two entries of the search summary.
pub(crate) const STRIDE: usize = 16;

/// The random-order search's summary of the knots: every [`STRIDE`]-th knot
/// (`N / 16` doubles, small enough to stay in cache), where the search looks
/// first before it halves the [`STRIDE`] knots of one stretch (two cache
/// lines), instead of touching a new cache line at each of the last ten or
/// so halvings of a search over all knots; and, once a batch large enough to
/// pay for it has searched, an [`Index`] of those entries by position.
#[derive(Clone, Debug, Default)]
pub(crate) struct Summary {
    /// `knots[0], knots[STRIDE], knots[2 STRIDE], ...`
    pub(crate) every: Vec<f64>,
    /// Formed by the first search of a batch large enough to pay for it
    /// (see [`Summary::index`]), so that building a spline costs nothing more.
    index: std::sync::OnceLock<Index>,
}

/// The index is formed from the rest when asked for: not part of the value.
impl PartialEq for Summary {
    fn eq(&self, other: &Self) -> bool {
        self.every == other.every
    }
}

impl Summary {
    /// Fills the summary of `knots` (at least one).
    pub(crate) fn of(&mut self, knots: &[f64]) {
        self.every.clear();
        self.every.extend(knots.iter().step_by(STRIDE).copied());
        self.formed();
    }

    /// Records that `every` now holds the summary of other knots (and
    /// forgets the index of the knots before).
    pub(crate) fn formed(&mut self) {
        self.index = std::sync::OnceLock::new();
    }

    /// The index of the summary of knots ending at `hi`, when it is formed
    /// and of use (see [`Index::of`]); formed now if a batch of `queries`
    /// more pays for it: forming it costs about what it saves the searches
    /// of a quarter as many queries as the summary has entries, so half as
    /// many suffice.
    #[inline]
    fn index(&self, hi: f64, queries: usize) -> Option<&Index> {
        let index = match self.index.get() {
            Some(index) => index,
            None if 2 * queries >= self.every.len() => {
                self.index.get_or_init(|| Index::of(&self.every, hi))
            }
            None => return None,
        };
        (!index.start.is_empty()).then_some(index)
    }

    /// The last knot index `i` with `knots[i] <= x` (0 when there is none,
    /// and any from the last stretch on past the last knot), for one query;
    /// `knots` are those summarised. With an index that a batch has formed,
    /// its search; without one, the summary's when the knots outgrow the
    /// caches (its last halvings stay within two cache lines, where a search
    /// over all knots touches a new line at each), else that plain search
    /// (fewer instructions).
    #[inline]
    pub(crate) fn locate(&self, knots: &[f64], x: f64) -> usize {
        let index = self.index(knots.last().copied().unwrap_or(0.0), 0);
        if index.is_none() && knots.len() <= 1 << 18 {
            knots.partition_point(|&k| k <= x).saturating_sub(1)
        } else {
            search_one(knots, (&self.every, index), x)
        }
    }

    /// Whether a usable index is formed.
    #[cfg(test)]
    pub(crate) fn indexed(&self) -> bool {
        self.index.get().is_some_and(|i| !i.start.is_empty())
    }

    /// Bytes of heap memory held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.every.capacity() * core::mem::size_of::<f64>()
            + self
                .index
                .get()
                .map_or(0, |i| i.start.capacity() * core::mem::size_of::<u32>())
    }
}

/// An index of a summary's entries by position: the span cut into as many
/// equal buckets as there are entries, and for each bucket the first entry
/// that falls in it or after. A query's bucket, one subtraction and one
/// multiplication away, then leaves one or two entries to halve among when
/// the knots are spread evenly, instead of the some sixteen halvings of a
/// search over the whole summary (at `N = 10^6`).
///
/// The bucket of a value is a nondecreasing function of it (a subtraction, a
/// multiplication by a positive number, clamping and rounding, all monotone in
/// floating point), which is all the search relies on: whatever the rounding,
/// the last entry not above `x` lies between `start[b] - 1` and
/// `start[b + 1] - 1`, `b` being the bucket of `x`.
#[derive(Clone, Debug, Default)]
struct Index {
    /// `start[b]`: the first entry whose bucket is `b` or more, for `b` in
    /// `0 ..= entries`; empty when the index would not help (see
    /// [`Index::of`]) or there are too many entries for a `u32`.
    start: Vec<u32>,
    /// The first knot, buckets per unit of `x`, and the last bucket.
    lo: f64,
    per: f64,
    last: f64,
}

/// An [`Index`] as a search reads it.
#[derive(Clone, Copy)]
struct Buckets<'a> {
    start: &'a [u32],
    lo: f64,
    per: f64,
    last: f64,
}

impl Index {
    /// The index of the summary `every` of knots ending at `hi`.
    fn of(every: &[f64], hi: f64) -> Self {
        let nb = every.len();
        let mut index = Index::default();
        let Some(&lo) = every.first() else {
            return index;
        };
        // Any positive factor keeps the buckets in order; this one spreads
        // them over the span (capped, so that a tiny span gives no infinity).
        let per = (nb as f64 / (hi - lo)).min(f64::MAX);
        if per.is_nan() || per <= 0.0 || u32::try_from(nb).is_err() {
            return index;
        }
        (index.lo, index.per, index.last) = (lo, per, (nb - 1) as f64);
        // Entries per bucket, counted into `start[b + 1]`, then summed up.
        index.start.resize(nb + 1, 0);
        let (_, counts) = index.start.split_at_mut(1);
        for &v in every {
            if let Some(c) = counts.get_mut(bucket_of(v, lo, per, index.last)) {
                *c += 1;
            }
        }
        let mut widest = 0;
        let mut total = 0;
        for c in counts.iter_mut() {
            widest = widest.max(*c);
            total += *c;
            *c = total;
        }
        // Knots so uneven that one bucket holds an eighth of the entries or
        // more: a block of random queries would mostly meet that bucket and
        // save at most three halvings for the work of finding it; search the
        // whole summary instead.
        if 8 * widest as usize >= nb.max(64) {
            index.start = Vec::new();
        }
        index
    }

    /// The index as a search reads it.
    #[inline(always)]
    fn buckets(&self) -> Buckets<'_> {
        Buckets {
            start: &self.start,
            lo: self.lo,
            per: self.per,
            last: self.last,
        }
    }
}

impl Buckets<'_> {
    /// The entries among which the last one not above `x` lies (the first
    /// entry when there is none), as `(first, last)`; `None` without an
    /// index.
    #[inline(always)]
    fn range(&self, x: f64) -> Option<(usize, usize)> {
        let b = bucket_of(x, self.lo, self.per, self.last);
        match (self.start.get(b), self.start.get(b + 1)) {
            (Some(&s0), Some(&s1)) => Some((
                (s0 as usize).saturating_sub(1),
                (s1 as usize).saturating_sub(1),
            )),
            _ => None,
        }
    }
}

/// The bucket `(x - lo) per`, clamped to `[0, last]` (`max` turns NaN into
/// 0) and rounded to the nearest integer by adding 2^52, which leaves no
/// fraction bits: monotone in `x`, and cheaper than the saturating `as`
/// conversion.
#[inline(always)]
fn bucket_of(x: f64, lo: f64, per: f64, last: f64) -> usize {
    const UNIT: f64 = (1u64 << 52) as f64;
    let f = ((x - lo) * per).max(0.0).min(last);
    ((f + UNIT).to_bits() - UNIT.to_bits()) as usize
}

/// The batch evaluator's view of a spline.
pub(crate) struct Batch<'a> {
    pub(crate) knots: &'a [f64],
    /// See [`Summary`].
    pub(crate) summary: &'a Summary,
    pub(crate) coefs: &'a [Piece],
    pub(crate) scale: f64,
}

impl Batch<'_> {
    /// Evaluates `out[i] = S^(O)(xs[i])` for every query inside `[tau_0, tau_{N-1})`
    /// whose result is finite; calls `slow(i, x, out_i)` for the others (outside
    /// the domain, NaN, the last knot, overflow), which writes `out[i]` itself or
    /// fails.
    ///
    /// Queries go in blocks of [`BLOCK`]. A block is either walked (the piece of
    /// the previous query is tried first, then a few steps forward, then the
    /// summary's search) or searched (a branchless binary search interleaved
    /// over the block). A walked block with more than two jumps backward or far
    /// forward hands the next block to the search; a searched block whose
    /// queries are all in order hands the next block back to the walk.
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
            for (i, (&x, o)) in xs.iter().zip(out.iter_mut()).enumerate() {
                slow(i, x, o)?;
            }
            return Ok(());
        }
        let (lo, hi) = (knots[0], knots[m]);
        let scale = self.scale;
        // The current piece of the walk, and whether every result on it is
        // sure to be finite.
        let mut k = 0;
        let mut k0 = knots[0];
        let mut k1 = knots[1];
        let mut inv = 1.0 / (k1 - k0);
        let mut c = coefs[0].0;
        let mut safe = bounded::<O>(&c, scale, inv);
        let mut base = 0;
        let mut search = false;
        for (xb, ob) in xs.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
            if !search {
                let mut jumps = 0;
                // Finiteness is known per piece (see [`bounded`]); a block that
                // met a piece without that assurance has its results checked
                // afterwards, which is dearer than a test per query only for
                // such rare blocks.
                let mut finite = safe;
                let n = xb.len();
                let ob = &mut ob[..n];
                let mut j = 0;
                loop {
                    j = walk_piece::<O>(xb, ob, j, &c, (k0, k1, inv), scale);
                    let Some(&x) = xb.get(j) else { break };
                    if !(x >= lo && x < hi) {
                        call_slow(&mut slow, base + j, x, &mut ob[j])?;
                        j += 1;
                        continue;
                    }
                    // Sorted queries mostly move on to the next piece.
                    match knots.get(k + 2) {
                        Some(&k2) if x >= k1 && x < k2 => {
                            k += 1;
                            k0 = k1;
                            k1 = k2;
                        }
                        _ => {
                            // An index only if one is formed: a far jump in a walk does
                            // not pay for one.
                            let find = (&self.summary.every[..], self.summary.index(hi, 0));
                            let (next, far) = locate_from(knots, find, k, x);
                            jumps += usize::from(far);
                            k = next;
                            k0 = knots[k];
                            k1 = knots[k + 1];
                        }
                    }
                    inv = 1.0 / (k1 - k0);
                    c = coefs[k].0;
                    safe = bounded::<O>(&c, scale, inv);
                    finite &= safe;
                }
                if !finite {
                    for (j, (&x, o)) in xb.iter().zip(ob.iter_mut()).enumerate() {
                        if !o.is_finite() {
                            slow(base + j, x, o)?;
                        }
                    }
                }
                search = jumps > 2;
            } else {
                let mut idx = [0usize; BLOCK];
                let find = (
                    &self.summary.every[..],
                    self.summary.index(hi, xs.len() - base),
                );
                search_block(knots, find, xb, &mut idx);
                for (j, ((&x, o), &q)) in xb.iter().zip(ob.iter_mut()).zip(&idx).enumerate() {
                    if !(x >= lo && x < hi) {
                        slow(base + j, x, o)?;
                        continue;
                    }
                    let q = q.min(m - 1);
                    let (a, b) = (knots[q], knots[q + 1]);
                    let iv = 1.0 / (b - a);
                    let t = (x - a) * iv;
                    let v = per_h::<O>(deriv::<O>(&coefs[q].0, t) * scale, iv);
                    if v.is_finite() {
                        *o = v;
                    } else {
                        slow(base + j, x, o)?;
                    }
                }
                search = !xb.is_sorted();
            }
            base += xb.len();
        }
        Ok(())
    }
}

/// The piece of `x` (inside the domain) starting the search at piece `k`: a few
/// linear steps forward, then the summary's search (see [`search_one`]). The
/// flag says whether it took the search.
#[inline(never)]
fn locate_from(knots: &[f64], find: Find<'_>, k: usize, x: f64) -> (usize, bool) {
    let last = knots.len() - 2;
    let mut k = k;
    if x >= knots[k] {
        for _ in 0..4 {
            if k == last || x < knots[k + 1] {
                return (k, false);
            }
            k += 1;
        }
    }
    let k = search_one(knots, find, x).min(last);
    // The walk loops on the piece it is given until the query lies in it: a
    // piece that does not hold `x` (which the search's invariants rule out)
    // must not hang it.
    if x >= knots[k] && x < knots[k + 1] {
        (k, true)
    } else {
        (
            knots.partition_point(|&t| t <= x).clamp(1, last + 1) - 1,
            true,
        )
    }
}

/// What a search reads besides the knots: the summary's entries and, when
/// formed, their [`Index`].
type Find<'a> = (&'a [f64], Option<&'a Index>);

/// The last knot index `i` with `knots[i] <= x` (0 when there is none): the
/// search of [`search_block`] for one query.
#[inline]
fn search_one(knots: &[f64], (every, index): Find<'_>, x: f64) -> usize {
    let (mut s, end) = index
        .and_then(|i| i.buckets().range(x))
        .unwrap_or((0, every.len().saturating_sub(1)));
    let mut len = end + 1 - s;
    while len > 1 {
        let half = len / 2;
        let v = every[s + half];
        s = core::hint::select_unpredictable(v <= x, s + half, s);
        len -= half;
    }
    let last = knots.len().saturating_sub(1);
    let mut i = s * STRIDE;
    let mut len = STRIDE.min(knots.len());
    while len > 1 {
        let half = len / 2;
        let probe = i + half;
        let v = knots[probe.min(last)];
        i = core::hint::select_unpredictable(v <= x, probe, i);
        len -= half;
    }
    i
}

/// For each query the last knot index `i` with `knots[i] <= x` (0 when there is
/// none), by a branchless binary search interleaved over the block: first over
/// the summary's entries (those the query's bucket leaves, with an
/// [`Index`]), then over the [`STRIDE`] knots of the stretch it names.
#[inline]
fn search_block(knots: &[f64], (every, index): Find<'_>, xb: &[f64], idx: &mut [usize; BLOCK]) {
    let mut q = [0.0; BLOCK];
    for (d, &s) in q.iter_mut().zip(xb) {
        *d = s;
    }
    let mut stretch = [0usize; BLOCK];
    let entries = every.len();
    let mut len = entries;
    if let Some(index) = index {
        // Each query's candidates as a window of the block's widest length
        // `len`, moved left where it would run past the last entry: it still
        // holds them, and the halving then never probes past the end (where
        // it would step beyond the last entry on reading it).
        len = 1;
        // A copy, so that the loop keeps it in registers.
        let index = index.buckets();
        for (s, &x) in stretch.iter_mut().zip(&q) {
            let (first, last) = index.range(x).unwrap_or((0, entries - 1));
            *s = first;
            len = len.max(last + 1 - first);
        }
        for s in &mut stretch {
            *s = (*s).min(entries - len);
        }
    }
    halve(every, len, &q, &mut stretch);
    for (i, s) in idx.iter_mut().zip(&stretch) {
        *i = s * STRIDE;
    }
    // The answer lies in [s STRIDE, (s + 1) STRIDE): past the last knot the
    // probes read the last knot, which no query inside the domain reaches.
    halve(knots, STRIDE.min(knots.len()), &q, idx);
}

/// Branchless binary search of `len` steps' worth from the bases in `idx`.
#[inline(always)]
fn halve(knots: &[f64], len: usize, q: &[f64; BLOCK], idx: &mut [usize; BLOCK]) {
    let Some(last) = knots.len().checked_sub(1) else {
        return;
    };
    let mut len = len;
    while len > 1 {
        let half = len / 2;
        for (b, &x) in idx.iter_mut().zip(q.iter()) {
            let probe = *b + half;
            // The min only spares a bounds check (and keeps the probes of a
            // stretch at the end inside the knots).
            let v = knots[probe.min(last)];
            // The outcome is random: a conditional move, not a branch that
            // would mispredict half the time.
            *b = core::hint::select_unpredictable(v <= x, probe, *b);
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
        let knots: Vec<f64> = (0..77).map(|i| f64::from(i * i)).collect();
        let xs: Vec<f64> = (0..16).map(|i| f64::from(i * 383 % 5800) - 5.0).collect();
        let mut summary = Summary::default();
        summary.of(&knots);
        let index = Index::of(&summary.every, knots[76]);
        for index in [None, Some(&index)] {
            let mut idx = [0; BLOCK];
            search_block(&knots, (&summary.every, index), &xs, &mut idx);
            for (x, i) in xs.iter().zip(idx) {
                let want = knots.partition_point(|&k| k <= *x).saturating_sub(1);
                assert_eq!(i, want, "x = {x}");
            }
        }
    }

    /// Knots spread evenly, jittered, in clusters, growing geometrically (too
    /// uneven for an index), over tiny and huge spans and far from zero.
    fn knot_sets() -> Vec<Vec<f64>> {
        let mut st = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            st ^= st >> 12;
            st ^= st << 25;
            st ^= st >> 27;
            (st.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut sets = Vec::new();
        for n in [2usize, 3, 16, 17, 33, 100, 257, 1000, 4099] {
            sets.push((0..n).map(|i| i as f64).collect());
            sets.push((0..n).map(|i| i as f64 + 0.9 * next()).collect());
            // Clusters: runs of close knots between wide gaps.
            let mut x = 0.0;
            sets.push(
                (0..n)
                    .map(|i| {
                        x += if i % 40 < 30 {
                            1e-3 * (1.0 + next())
                        } else {
                            5.0 * next() + 1e-3
                        };
                        x
                    })
                    .collect(),
            );
            sets.push((0..n).map(|i| (20.0 * i as f64 / n as f64).exp()).collect());
            sets.push((0..n).map(|i| 1e-300 * (i as f64 + 0.5 * next())).collect());
            sets.push(
                (0..n)
                    .map(|i| -1e300 + 1e300 / n as f64 * (2 * i) as f64)
                    .collect(),
            );
            sets.push((0..n).map(|i| 1e9 + 1e-3 * i as f64).collect());
        }
        sets
    }

    #[test]
    fn searches_with_and_without_the_index_find_the_last_knot_not_above() {
        let mut with_index = 0;
        for knots in knot_sets() {
            let n = knots.len();
            let mut summary = Summary::default();
            summary.of(&knots);
            let index = Index::of(&summary.every, knots[n - 1]);
            with_index += usize::from(!index.start.is_empty());
            // Every knot, its neighbours by one unit in the last place,
            // midpoints, and the outside.
            let mut xs = vec![
                f64::NAN,
                f64::NEG_INFINITY,
                f64::INFINITY,
                -f64::MAX,
                f64::MAX,
            ];
            for w in knots.windows(2) {
                xs.extend([
                    w[0],
                    w[0].next_down(),
                    w[0].next_up(),
                    0.5 * w[0] + 0.5 * w[1],
                ]);
            }
            xs.extend([
                knots[n - 1],
                knots[n - 1].next_down(),
                knots[n - 1].next_up(),
            ]);
            // Sorted, then every seventh in reverse: blocks in order and
            // out of it.
            xs.sort_by(f64::total_cmp);
            let sorted = xs.clone();
            xs.extend(sorted.iter().step_by(7).rev());
            let want: Vec<usize> = xs
                .iter()
                .map(|x| knots.partition_point(|k| k <= x).saturating_sub(1))
                .collect();
            for index in [None, Some(&index)] {
                let find = (&summary.every[..], index);
                for (xb, wb) in xs.chunks(BLOCK).zip(want.chunks(BLOCK)) {
                    let mut idx = [0; BLOCK];
                    search_block(&knots, find, xb, &mut idx);
                    for ((x, &i), &w) in xb.iter().zip(&idx).zip(wb) {
                        // Past the last knot the block search may give any
                        // index from the last stretch on; the batch
                        // evaluators send those queries to the one-by-one
                        // path.
                        if *x >= knots[n - 1] {
                            assert!(i >= (n - 1) / STRIDE * STRIDE, "n {n} x {x}: {i}");
                            continue;
                        }
                        assert_eq!(i, w, "n {n} x {x} index {}", index.is_some());
                    }
                }
                for (x, &w) in xs.iter().zip(&want) {
                    if *x < knots[n - 1] {
                        assert_eq!(search_one(&knots, find, *x), w, "n {n} x {x}");
                    }
                }
            }
        }
        assert!(with_index >= 30, "only {with_index} sets had an index");
    }

    #[test]
    fn the_index_is_formed_for_even_knots_and_dropped_for_uneven_ones() {
        let even: Vec<f64> = (0..10_000).map(|i| f64::from(i) * 0.1).collect();
        let mut summary = Summary::default();
        summary.of(&even);
        let index = Index::of(&summary.every, even[9_999]);
        assert_eq!(index.start.len(), summary.every.len() + 1);
        for x in [0.0, 1.55, 500.0, 999.85] {
            let (first, last) = index.buckets().range(x).unwrap();
            assert!(last - first <= 2, "x {x}: {first}..={last}");
        }
        let uneven: Vec<f64> = (0..10_000).map(|i| (f64::from(i) * 2e-3).exp()).collect();
        summary.of(&uneven);
        assert!(Index::of(&summary.every, uneven[9_999]).start.is_empty());
    }

    #[test]
    fn the_index_is_formed_for_batches_that_pay_for_it_and_forgotten_on_change() {
        let knots: Vec<f64> = (0..1_600).map(f64::from).collect();
        let mut summary = Summary::default();
        summary.of(&knots);
        assert_eq!(summary.every.len(), 100);
        assert!(summary.index(1_599.0, 49).is_none());
        assert!(summary.index(1_599.0, 0).is_none());
        assert!(summary.index(1_599.0, 50).is_some());
        assert!(summary.index(1_599.0, 0).is_some(), "kept once formed");
        let bytes = summary.heap_bytes();
        summary.of(&knots[..800]);
        assert!(
            summary.index(799.0, 0).is_none(),
            "forgotten with the knots"
        );
        assert!(summary.heap_bytes() < bytes);
        let other = {
            let mut s = Summary::default();
            s.of(&knots[..800]);
            s
        };
        assert!(summary.index(799.0, 25).is_some());
        assert_eq!(summary, other, "the index is not part of the value");
    }

    #[test]
    fn locate_from_matches_partition_point() {
        for n in [2, 3, 16, 17, 50, 257] {
            let knots: Vec<f64> = (0..n).map(|i| f64::from(i) * 0.5).collect();
            let mut summary = Summary::default();
            summary.of(&knots);
            let last = knots.len() - 2;
            for start in [0, 3, 20, 48, 255] {
                let start = start.min(last);
                for i in 0..(2 * n) {
                    let x = f64::from(i) * 0.25;
                    let want = knots
                        .partition_point(|&k| k <= x)
                        .saturating_sub(1)
                        .min(last);
                    let find = (&summary.every[..], None);
                    let got = locate_from(&knots, find, start, x).0;
                    assert_eq!(got, want, "n {n} from {start} x {x}");
                    assert_eq!(search_one(&knots, find, x).min(last), want);
                    // A summary of other knots sends the search astray, but
                    // the piece handed to the walk still holds the query.
                    let stale = [0.0, 1e9, 2e9];
                    let got = locate_from(&knots, (&stale, None), start, x).0;
                    assert_eq!(got, want, "n {n} from {start} x {x}, stale summary");
                }
            }
        }
    }
}
