//! The fused construction sweeps: an elimination from the last row up and a
//! substitution from the first row down over a validated spline or open
//! curve, writing every piece once, in order.
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
//! so assembling a row needs no division. Eliminating from the last row, the
//! pivots `piv_k = D_k - u_k l_{k+1} / piv_{k+1}` are ratios `P_k / P_{k+1}`
//! of the continuants `P_k = D_k P_{k+1} - u_k l_{k+1} P_{k+2}`, a recurrence
//! of multiplications and subtractions only: the one division per row,
//! `1 / piv_k = P_{k+1} / P_k`, is off the chain of dependent operations. The
//! continuants are renormalised by an exact power of two every
//! [`RENORM`] rows. Diagonal dominance bounds every pivot ratio (for alphas in
//! `[1/3, 2/3]`, `piv_k >= 3 min(h_{k-1} + h_k)` and `<= 8 max(...)`), so the
//! continuants stay far from overflow and underflow between renormalisations.
//!
//! The elimination keeps its two numbers per row (`l_k / piv_k` and the swept
//! right-hand side, `D + 1` numbers for `D` coordinates) in the slots of two
//! outputs of length `n` that the substitution writes anyway after it has
//! read them: a spline's copies of knot `k` and value `k`, a curve's copy of
//! point `k` and its deviation. The substitution finds `d_k` from `d_{k-1}`,
//! so it has piece `k - 1` as soon as it has `d_k`, and appends the pieces
//! in order, a block at a time (each block cleared while it is in the cache,
//! then written): no pass over their memory before the sweeps, and nothing
//! else holds the rows (no scratch vector). The alpha inverses of
//! per-interval alphas are formed again in the substitution.

use super::chunks::{self, Whole};
use super::Piece;
use crate::lanes::{Lane, F2};
use crate::method::alpha_terms;

/// Rows between two renormalisations of the continuants: each row multiplies
/// them by a pivot between `3 * 2^-52` and `32` (widths relative to a span
/// near 1), so in 8 rows they stay within `2^-400 .. 2^40` of `[1, 2)`, far
/// inside a double.
pub(super) const RENORM: usize = 8;

/// Multiplies `p` and `q` by the power of two that brings `p` into `[1, 2)`,
/// lane by lane. `p` is positive and normal.
#[inline]
fn renormalise<L: Lane>(p: &mut L, q: &mut L) {
    let m = L::from_lanes(|i| {
        let e = (p.lane(i).to_bits() >> 52) & 0x7ff;
        // 2^(1023 - e): the exponent field 2046 - e lies in [1, 2045] for normal p.
        f64::from_bits((2046u64.saturating_sub(e)).max(1) << 52)
    });
    *p = *p * m;
    *q = *q * m;
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

/// Leg `k` of a sweep's output: its `D` pieces, one per coordinate.
type Leg<const D: usize> = [Piece; D];

/// Pairs of legs the substitution appends at a time.
const BLOCK: usize = 32;

/// Builds the pieces of a validated spline into `coefs` (one piece per
/// interval, appended in order after clearing it; its allocation is reused)
/// and copies `knots` and `values` into `knots_out` and `values_out`.
///
/// `knots` are strictly increasing with a finite span, `values` finite and of
/// the same length (at least 2), `alphas` one per interval and in range;
/// `uniform` is `Some(a)` when every alpha is `a` (the exact [`alpha_terms`] are
/// then used throughout, and `alphas` is not read: it may be empty).
/// `inv_scale` is the exact power of two that scales the values, `wscale` the
/// power of two that brings the span near 1.
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
    // With one alpha no alpha is read: the first `n - 1` knots pace the
    // loops in their place.
    let alphas = match uniform {
        Some(_) => knots.get(..n.saturating_sub(1)).unwrap_or_default(),
        None => alphas,
    };
    if n < 2 || values.len() != n || alphas.len() != n - 1 {
        // Not reached: the caller has validated the lengths.
        coefs.clear();
        for (out, v) in [(&mut *knots_out, knots), (&mut *values_out, values)] {
            out.clear();
            out.extend_from_slice(v);
        }
        return;
    }
    // The copies of the knots and values hold the rows until the
    // substitution writes the copies over them: keep the old contents rather
    // than clearing them first (no pass over the memory when the size is
    // unchanged).
    for out in [&mut *knots_out, &mut *values_out] {
        chunks::sized(out, n, 0.0);
    }
    let (kn, vs) = (
        knots_out.as_chunks_mut::<1>().0,
        values_out.as_chunks_mut::<1>().0,
    );
    let plan = chunks::plan(knots, alphas, uniform, wscale);
    if !plan.is_empty() {
        // Every piece is written by one chunk: no pass to clear them when
        // the size is unchanged.
        chunks::sized(coefs, n - 1, Piece::default());
        let whole = Whole {
            knots,
            values: values.as_chunks().0,
            inv_scale: [inv_scale],
            alphas,
            uniform,
            ws: wscale,
        };
        chunks::run::<1, true>(&plan, whole, coefs, kn, vs);
        return;
    }
    let input = Sweep::new(
        knots,
        values.as_chunks().0,
        [inv_scale],
        alphas,
        uniform,
        wscale,
    );
    if uniform.is_some() {
        input.run::<false, true>(coefs, kn, vs);
    } else {
        input.run::<true, true>(coefs, kn, vs);
    }
}

/// Builds the segments of a validated open curve in `D` dimensions: `coefs`
/// gets the curve's layout (`D` pieces per leg, coordinate fastest), `dev`
/// the scaled deviations of every point (zero at both ends) and `points_out`
/// a copy of `points`. Lengths: `points` `n D` (scaled by `inv_scale`,
/// coordinate by coordinate, as they are read), `knots` `n >= 2`, `alphas`
/// `n - 1`; `coefs`, `dev` and `points_out` are resized.
///
/// The elimination keeps row `k` in `points_out[k]` and `dev[k]` (`2 D` slots
/// for `D + 1` numbers), which the substitution then overwrites with the copy
/// of point `k` and its deviation.
#[allow(clippy::too_many_arguments)] // the parts of a curve, validated
pub(crate) fn build_open_curve<const D: usize>(
    knots: &[f64],
    points: &[f64],
    inv_scale: [f64; D],
    alphas: &[f64],
    uniform: Option<f64>,
    wscale: f64,
    coefs: &mut Vec<Piece>,
    dev: &mut Vec<f64>,
    points_out: &mut Vec<f64>,
) {
    let n = knots.len();
    // Every slot is overwritten below: no pass to clear them first.
    for v in [&mut *dev, &mut *points_out] {
        chunks::sized(v, n * D, 0.0);
    }
    let (values, _) = points.as_chunks::<D>();
    if n < 2 || values.len() != n || alphas.len() != n - 1 {
        // Not reached: the caller has validated the lengths.
        coefs.clear();
        points_out.clear();
        points_out.extend_from_slice(points);
        return;
    }
    let (dev, pts) = (
        dev.as_chunks_mut::<D>().0,
        points_out.as_chunks_mut::<D>().0,
    );
    let plan = chunks::plan(knots, alphas, uniform, wscale);
    if !plan.is_empty() {
        chunks::sized(coefs, (n - 1) * D, Piece::default());
        let whole = Whole {
            knots,
            values,
            inv_scale,
            alphas,
            uniform,
            ws: wscale,
        };
        chunks::run::<D, false>(&plan, whole, coefs, dev, pts);
        return;
    }
    let input = Sweep::new(knots, values, inv_scale, alphas, uniform, wscale);
    if uniform.is_some() {
        input.run::<false, false>(coefs, dev, pts);
    } else {
        input.run::<true, false>(coefs, dev, pts);
    }
}

/// The terms [`leg_piece`] forms the pieces of a leg of alpha `a` with, as
/// the sweeps form them: from the exact [`alpha_terms`] when `uniform` (every
/// leg has this alpha), else from [`inverses`].
pub(crate) fn leg_terms(a: f64, uniform: bool) -> [f64; 6] {
    let terms = if uniform {
        alpha_terms(a)
    } else {
        let (ia, iu) = inverses(a);
        terms_from_inverses(a, ia, iu)
    };
    piece_terms(terms)
}

/// The piece of one leg from its scaled values `f0`, `f1`, deviations `d0`,
/// `d1` and the [`leg_terms`] of its alpha, as the sweeps form it.
pub(crate) fn leg_piece(f0: f64, f1: f64, d0: f64, d1: f64, terms: [f64; 6]) -> [f64; 4] {
    piece(f0, f1, d0, d1, terms)
}

/// `(1/a, 1/(1-a))` with one division.
#[inline(always)]
pub(super) fn inverses<L: Lane>(a: L) -> (L, L) {
    let u = L::splat(1.0) - a;
    let iau = L::splat(1.0) / (a * u);
    (u * iau, a * iau)
}

/// `a - b` coordinate by coordinate.
#[inline(always)]
fn sub<L: Lane, const D: usize>(a: [L; D], b: [L; D]) -> [L; D] {
    core::array::from_fn(|c| a[c] - b[c])
}

/// The input of the fused sweeps: `D` right-hand sides (the coordinates of
/// the points, `values[k][c] * inv_scale[c]`) on one matrix.
pub(super) struct Sweep<'a, const D: usize> {
    pub(super) knots: &'a [f64],
    pub(super) values: &'a [[f64; D]],
    pub(super) inv_scale: [f64; D],
    pub(super) alphas: &'a [f64],
    /// The terms of every alpha when they are all one (`PER` false).
    pub(super) uniform: [f64; 4],
    /// Their [`piece_terms`].
    uniform_piece: [f64; 6],
    /// The power of two the widths are multiplied by.
    pub(super) ws: f64,
}

impl<'a, const D: usize> Sweep<'a, D> {
    /// The input, with the alpha terms of `uniform` (the one alpha of every
    /// interval, when there is one) formed once.
    pub(super) fn new(
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

    /// The sweeps of [`build`] and [`build_open_curve`] over the whole
    /// system; `PER` says whether the alphas differ (their terms are then
    /// formed per interval, else `uniform` serves every interval). The
    /// elimination, from the last row up, keeps row `k` in `second[k]` and
    /// `first[k]` (`2 D` slots for `D + 1` numbers; `n` of each); the
    /// substitution, from the first row down, overwrites them with
    /// `values[k]` (in `first`) and the deviation (in `second`), or with
    /// `KNOT` the knot (in `second[k][0]`, for `D = 1`): a spline's copies of
    /// its knots and values, a curve's deviations and copy of its points. It
    /// appends the legs to `coefs` (cleared first) in order, each once.
    #[inline(always)]
    pub(super) fn run<const PER: bool, const KNOT: bool>(
        &self,
        coefs: &mut Vec<Piece>,
        second: &mut [[f64; D]],
        first: &mut [[f64; D]],
    ) {
        let n = self.knots.len();
        let m = n.saturating_sub(1);
        let (Some(dev), Some(pts)) = (second.get_mut(..n), first.get_mut(..n)) else {
            return;
        };
        let (Some(rows_d), Some(rows_p)) = (dev.get_mut(1..m), pts.get_mut(1..m)) else {
            return;
        };
        let Some(mut elim) = self.top::<PER>() else {
            return;
        };
        self.eliminate::<PER>(&mut elim, 1, (&mut *rows_d, &mut *rows_p));
        coefs.clear();
        coefs.reserve_exact(m * D);
        let mut sub = self.bottom();
        self.substitute::<PER, KNOT>(&mut sub, 1, (rows_d, rows_p), coefs);
        self.tail::<PER>(&sub, coefs);
        for i in [0, m] {
            if let (Some(d), Some(p)) = (dev.get_mut(i), pts.get_mut(i)) {
                self.end_point::<KNOT>(i, d, p);
            }
        }
    }

    /// The copies at end point `i` (deviation zero, or the knot) in its slots.
    #[inline(always)]
    pub(super) fn end_point<const KNOT: bool>(
        &self,
        i: usize,
        second: &mut [f64; D],
        first: &mut [f64; D],
    ) {
        if let (Some(v), Some(&k)) = (self.values.get(i), self.knots.get(i)) {
            *first = *v;
            if KNOT {
                second[0] = k;
            } else {
                *second = [0.0; D];
            }
        }
    }

    /// The mirrored terms of alpha `a` for the elimination (see
    /// [`Sweep::eliminate`]).
    #[inline(always)]
    fn mirrored<const PER: bool>(&self, a: f64) -> [f64; 4] {
        let [al, b1, b2, cr] = if PER {
            let (ia, iu) = inverses(a);
            terms_from_inverses(a, ia, iu)
        } else {
            self.uniform
        };
        [cr, b2, b1, al]
    }

    /// The elimination's state before its first row, `n - 2`: the last
    /// deviation is zero. `None` for fewer than two knots.
    #[inline(always)]
    pub(super) fn top<const PER: bool>(&self) -> Option<Elim<f64, D>> {
        let (knots, values, alphas) = (self.knots, self.values, self.alphas);
        let m = knots.len().checked_sub(1)?;
        let (Some(&k0), Some(&k1), Some(&v0), Some(&v1), Some(&a0)) = (
            knots.get(m),
            knots.get(m.wrapping_sub(1)),
            values.get(m),
            values.get(m.wrapping_sub(1)),
            alphas.get(m.wrapping_sub(1)),
        ) else {
            return None;
        };
        let fc = self.scaled(v1);
        Some(Elim {
            p_prev2: 1.0,
            p_prev: 1.0,
            y_prev: [0.0; D],
            u_prev: 0.0,
            kc: k1,
            hl: (k0 - k1) * self.ws,
            fc,
            df_l: sub(fc, self.scaled(v0)),
            terms_l: self.mirrored::<PER>(a0),
            since: 0,
        })
    }

    /// The elimination over rows `r0 + c - 1` down to `r0` (`c` the slots'
    /// length, `r0 >= 1`), kept in their slots (`rows.0[i]`, `rows.1[i]` for
    /// row `r0 + i`): `l_k / piv_k` and the swept right-hand sides, two rows
    /// at a time, then row `r0` alone when `c` is odd. `st` carries the
    /// state from the rows below (higher `k`) to the rows above.
    ///
    /// The code reads as a left-to-right sweep of the mirrored system (knots
    /// in reverse, each width the same, every alpha's terms `A', B1', B2', C'`
    /// read as `C', B2', B1', A'`), where `l` and `u` trade places and `r_k`
    /// is unchanged: its `l`, `u`, `df` and `h1`/`hl` are the mirrored ones.
    #[inline(always)]
    pub(super) fn eliminate<const PER: bool>(
        &self,
        st: &mut Elim<f64, D>,
        r0: usize,
        rows: (&mut [[f64; D]], &mut [[f64; D]]),
    ) {
        let (knots, values, alphas) = (self.knots, self.values, self.alphas);
        let ws = self.ws;
        let c = rows.0.len().min(rows.1.len());
        // Row k reads knot, value and alpha k - 1 (and, in a pair, k - 2).
        let (Some(kn), Some(vs), Some(al), Some(rd), Some(rp)) = (
            knots.get(r0.wrapping_sub(1)..r0.wrapping_sub(1).wrapping_add(c)),
            values.get(r0.wrapping_sub(1)..r0.wrapping_sub(1).wrapping_add(c)),
            alphas.get(r0.wrapping_sub(1)..r0.wrapping_sub(1).wrapping_add(c)),
            rows.0.get_mut(..c),
            rows.1.get_mut(..c),
        ) else {
            return;
        };
        let mut e = *st;
        // Pairs from the end, each in the order of the sweep (`[1]` then
        // `[0]`); the lone row left over, `r0`, in front.
        let (lk, kn) = kn.as_rchunks::<2>();
        let (lv, vs) = vs.as_rchunks::<2>();
        let (la, al) = al.as_rchunks::<2>();
        let (ld, pd) = rd.as_rchunks_mut::<2>();
        let (lp, pp) = rp.as_rchunks_mut::<2>();
        // Slices of one length zipped and walked from the end: one index.
        let pairs = pd.iter_mut().zip(pp).zip(kn).zip(vs).zip(al).rev();
        for (((([d0, d1], [p0, p1]), kn), vs), al) in pairs {
            // Rows k and k - 1.
            let f = (self.scaled(vs[1]), self.scaled(vs[0]));
            let t = (self.mirrored::<PER>(al[1]), self.mirrored::<PER>(al[0]));
            let [(w1, y1), (w2, y2)] = e.two_rows((kn[1], kn[0]), f, t, ws);
            Aside { p: p1, d: d1 }.put(w1, y1);
            Aside { p: p0, d: d0 }.put(w2, y2);
        }
        if let (Some(mut slot), Some(&kr), Some(&vr), Some(&ar)) =
            (Aside::first(ld, lp), lk.first(), lv.first(), la.first())
        {
            // Row r0 when the count is odd.
            let (w, y) = e.one_row(kr, self.scaled(vr), self.mirrored::<PER>(ar), ws);
            slot.put(w, y);
        }
        *st = e;
    }

    /// The substitution's state before its first row: the first deviation
    /// is zero.
    #[inline(always)]
    pub(super) fn bottom(&self) -> Subst<D> {
        Subst {
            d_prev: [0.0; D],
            f_prev: self.values.first().map_or([0.0; D], |&v| self.scaled(v)),
        }
    }

    /// Leg `k` from its values, deviations and alpha.
    #[inline(always)]
    fn leg<const PER: bool>(
        &self,
        f0: [f64; D],
        f1: [f64; D],
        d0: [f64; D],
        d1: [f64; D],
        a: f64,
    ) -> Leg<D> {
        let pt = if PER {
            let (ia, iu) = inverses(a);
            piece_terms(terms_from_inverses(a, ia, iu))
        } else {
            self.uniform_piece
        };
        core::array::from_fn(|c| Piece(piece(f0[c], f1[c], d0[c], d1[c], pt)))
    }

    /// The substitution over rows `r0` to `r0 + c - 1` (`c` the slots'
    /// length, as [`Sweep::eliminate`] left them): `d_k` from `d_{k-1}`,
    /// two rows at a time, then the last alone when `c` is odd; each row's
    /// slots overwritten with its copies, and legs `r0 - 1 ..= r0 + c - 2`
    /// appended to `coefs` in order (leg `k - 1` once `d_k` is known).
    #[inline(always)]
    pub(super) fn substitute<const PER: bool, const KNOT: bool>(
        &self,
        st: &mut Subst<D>,
        r0: usize,
        rows: (&mut [[f64; D]], &mut [[f64; D]]),
        coefs: &mut impl Legs,
    ) {
        let (values, alphas, knots) = (self.values, self.alphas, self.knots);
        let c = rows.0.len().min(rows.1.len());
        // Row k reads value and knot k and alpha k - 1.
        let (Some(vs), Some(al), Some(kn), Some(rd), Some(rp)) = (
            values.get(r0..r0 + c),
            alphas.get(r0.wrapping_sub(1)..r0.wrapping_sub(1).wrapping_add(c)),
            knots.get(r0..r0 + c),
            rows.0.get_mut(..c),
            rows.1.get_mut(..c),
        ) else {
            return;
        };
        let Subst {
            mut d_prev,
            mut f_prev,
        } = *st;
        let (pd, ld) = rd.as_chunks_mut::<2>();
        let (pp, lp) = rp.as_chunks_mut::<2>();
        let (vs, lv) = vs.as_chunks::<2>();
        let (al, la) = al.as_chunks::<2>();
        let (kn, lk) = kn.as_chunks::<2>();
        let count = pd.len();
        // The legs are appended a block at a time: the output's length is
        // checked once a block, then every leg written; within a block every
        // input is a slice of the same length, walked by one index.
        for start in (0..count).step_by(BLOCK) {
            let at = start..(start + BLOCK).min(count);
            let (Some(pd), Some(pp), Some(vs), Some(al), Some(kn)) = (
                pd.get_mut(at.clone()),
                pp.get_mut(at.clone()),
                vs.get(at.clone()),
                al.get(at.clone()),
                kn.get(at.clone()),
            ) else {
                break;
            };
            let (legs, _) = coefs.next(2 * D * at.len()).as_chunks_mut::<D>();
            let (block, _) = legs.as_chunks_mut::<2>();
            let rows = pd.iter_mut().zip(pp).zip(vs).zip(al).zip(kn);
            for (out, (((([d0, d1], [p0, p1]), vs), al), kn)) in block.iter_mut().zip(rows) {
                // Rows k and k + 1.
                let mut a = Aside { p: p0, d: d0 };
                let mut b = Aside { p: p1, d: d1 };
                let (ma, ya) = a.row();
                let (mb, yb) = b.row();
                let mut d_k = [0.0; D];
                let mut d_k1 = [0.0; D];
                for c in 0..D {
                    d_k[c] = ya[c] - ma * d_prev[c];
                    // d_{k+1} from d_{k-1}: one multiply-add on the chain for
                    // two rows.
                    d_k1[c] = (yb[c] - mb * ya[c]) + (mb * ma) * d_prev[c];
                }
                let (fk, fk1) = (self.scaled(vs[0]), self.scaled(vs[1]));
                *out = [
                    self.leg::<PER>(f_prev, fk, d_prev, d_k, al[0]),
                    self.leg::<PER>(fk, fk1, d_k, d_k1, al[1]),
                ];
                a.finish::<KNOT>(vs[0], d_k, kn[0]);
                b.finish::<KNOT>(vs[1], d_k1, kn[1]);
                d_prev = d_k1;
                f_prev = fk1;
            }
        }
        if let (Some(mut slot), Some(&v), Some(&a), Some(&kv)) =
            (Aside::first(ld, lp), lv.first(), la.first(), lk.first())
        {
            // The last row when the count is odd.
            let (mb, yb) = slot.row();
            let d = core::array::from_fn(|c| yb[c] - mb * d_prev[c]);
            let fk = self.scaled(v);
            let leg = self.leg::<PER>(f_prev, fk, d_prev, d, a);
            for (o, p) in coefs.next(D).iter_mut().zip(leg) {
                *o = p;
            }
            slot.finish::<KNOT>(v, d, kv);
            d_prev = d;
            f_prev = fk;
        }
        *st = Subst { d_prev, f_prev };
    }

    /// The last leg, `n - 2`, whose second deviation is zero, appended to
    /// `coefs` after the substitution of every row.
    #[inline(always)]
    pub(super) fn tail<const PER: bool>(&self, st: &Subst<D>, coefs: &mut impl Legs) {
        let m = self.knots.len().saturating_sub(1);
        if let (Some(&v), Some(&a)) = (self.values.get(m), self.alphas.get(m.wrapping_sub(1))) {
            let leg = self.leg::<PER>(st.f_prev, self.scaled(v), st.d_prev, [0.0; D], a);
            for (o, p) in coefs.next(D).iter_mut().zip(leg) {
                *o = p;
            }
        }
    }
}

/// The elimination's state between two rows `k + 1` and `k`: the last two
/// continuants, the last swept right-hand side and upper coefficient, and
/// what row `k` shares with row `k + 1` (knot `k`, the width and value step
/// of leg `k`, the mirrored terms of its alpha).
/// `L` holds one number of each of the chunks eliminated side by side
/// (`f64` for one).
#[derive(Clone, Copy)]
pub(super) struct Elim<L, const D: usize> {
    p_prev2: L,
    p_prev: L,
    y_prev: [L; D],
    u_prev: L,
    kc: L,
    hl: L,
    fc: [L; D],
    df_l: [L; D],
    terms_l: [L; 4],
    since: usize,
}

impl<const D: usize> Elim<f64, D> {
    /// Two states side by side, `a` in the first lane; `None` unless both
    /// have gone through the same number of rows since their last
    /// renormalisation.
    pub(super) fn pair(a: &Self, b: &Self) -> Option<Elim<F2, D>> {
        let two = |x: f64, y: f64| F2([x, y]);
        let each = |x: [f64; D], y: [f64; D]| core::array::from_fn(|c| two(x[c], y[c]));
        (a.since == b.since).then(|| Elim {
            p_prev2: two(a.p_prev2, b.p_prev2),
            p_prev: two(a.p_prev, b.p_prev),
            y_prev: each(a.y_prev, b.y_prev),
            u_prev: two(a.u_prev, b.u_prev),
            kc: two(a.kc, b.kc),
            hl: two(a.hl, b.hl),
            fc: each(a.fc, b.fc),
            df_l: each(a.df_l, b.df_l),
            terms_l: core::array::from_fn(|i| two(a.terms_l[i], b.terms_l[i])),
            since: a.since,
        })
    }
}

impl<L: Lane, const D: usize> Elim<L, D> {
    /// Rows `k` and `k - 1` of the elimination (of the mirrored system, see
    /// [`Sweep::eliminate`]), from knots `k - 1` and `k - 2` (`k1`, `k0`),
    /// the scaled values there (`f1`, `f2`) and the mirrored terms of alphas
    /// `k - 1` and `k - 2` (`t1`, `t2`); the widths are multiplied by `ws`.
    /// The rows to keep, `(u_k / piv_k, y_k)` and the same of row `k - 1`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)] // a pair of rows' inputs
    pub(super) fn two_rows(
        &mut self,
        (k1, k0): (L, L),
        (f1, f2): ([L; D], [L; D]),
        (t1, t2): ([L; 4], [L; 4]),
        ws: L,
    ) -> [(L, [L; D]); 2] {
        let h1 = (self.kc - k1) * ws;
        let h2 = (k1 - k0) * ws;
        self.kc = k0;
        let (hl, terms_l) = (self.hl, self.terms_l);
        let l1 = -h1 * terms_l[0];
        let d1 = h1 * terms_l[1] + hl * t1[2];
        let u1 = -hl * t1[3];
        let (df1, df2) = (sub(f1, self.fc), sub(f2, f1));
        let l2 = -h2 * t1[0];
        let d2 = h2 * t1[1] + h1 * t2[2];
        let u2 = -h1 * t2[3];
        let e1 = l1 * self.u_prev;
        let e2 = l2 * u1;
        // P_k and P_{k-1} both from P_{k+1}, P_{k+2}: one multiply-subtract
        // on the chain for two rows.
        let (p_prev, p_prev2) = (self.p_prev, self.p_prev2);
        let p1 = d1 * p_prev - e1 * p_prev2;
        let p2 = (d2 * d1 - e2) * p_prev - (d2 * e1) * p_prev2;
        // Each pivot's reciprocal `P_{k+1} / P_k` by its own division, off
        // the chain: measured, two divisions cost less than the five
        // multiplications that would share one between the rows
        // (BENCHMARKS.md, "Construction in chunks").
        let inv1 = p_prev / p1;
        let inv2 = p1 / p2;
        let (m1, m2) = (l1 * inv1, l2 * inv2);
        let mut y1 = [L::splat(0.0); D];
        let mut y2 = [L::splat(0.0); D];
        for c in 0..D {
            let g1 = (hl * df1[c] - h1 * self.df_l[c]) * inv1;
            let g2 = (h1 * df2[c] - h2 * df1[c]) * inv2;
            y1[c] = g1 - m1 * self.y_prev[c];
            // y_{k-1} from y_k, as a row taken alone would: one more
            // multiply-subtract on the chain of swept right-hand sides, which
            // measured less than the two multiplications that would take it
            // from y_{k+1} (BENCHMARKS.md, "Construction in chunks").
            y2[c] = g2 - m2 * y1[c];
        }
        self.advance(2, p1, p2);
        self.y_prev = y2;
        self.u_prev = u2;
        self.hl = h2;
        self.df_l = df2;
        self.fc = f2;
        self.terms_l = t2;
        [(u1 * inv1, y1), (u2 * inv2, y2)]
    }

    /// The last two pivots after `rows` more rows, `p_prev2` then `p_prev`,
    /// renormalised every [`RENORM`] rows.
    #[inline(always)]
    fn advance(&mut self, rows: usize, p_prev2: L, p_prev: L) {
        self.p_prev2 = p_prev2;
        self.p_prev = p_prev;
        self.since += rows;
        if self.since >= RENORM {
            renormalise(&mut self.p_prev, &mut self.p_prev2);
            self.since = 0;
        }
    }

    /// One row `k` of the elimination, from knot `k - 1` (`kr`), the scaled
    /// value there and the mirrored terms of alpha `k - 1`: the row to keep.
    #[inline(always)]
    pub(super) fn one_row(&mut self, kr: L, fr: [L; D], terms_r: [L; 4], ws: L) -> (L, [L; D]) {
        let (hl, terms_l) = (self.hl, self.terms_l);
        let hr = (self.kc - kr) * ws;
        let l = -hr * terms_l[0];
        let d = hr * terms_l[1] + hl * terms_r[2];
        let u = -hl * terms_r[3];
        let p = d * self.p_prev - (l * self.u_prev) * self.p_prev2;
        let inv = self.p_prev / p;
        let df_r = sub(fr, self.fc);
        let (df_l, y_prev) = (self.df_l, self.y_prev);
        let y =
            core::array::from_fn(|c| (hl * df_r[c] - hr * df_l[c]) * inv - (l * inv) * y_prev[c]);
        self.advance(1, self.p_prev, p);
        self.y_prev = y;
        self.u_prev = u;
        self.kc = kr;
        self.hl = hr;
        self.df_l = df_r;
        self.fc = fr;
        self.terms_l = terms_r;
        (u * inv, y)
    }
}

/// The substitution's state between two rows: the last deviation and the
/// scaled value at its knot.
#[derive(Clone, Copy)]
pub(super) struct Subst<const D: usize> {
    d_prev: [f64; D],
    f_prev: [f64; D],
}

/// Where the substitution writes its legs, in order: a vector it grows, or
/// a slice it fills from the front.
pub(super) trait Legs {
    /// The next `count` pieces' slots (fewer at the end of a slice).
    fn next(&mut self, count: usize) -> &mut [Piece];
}

impl Legs for Vec<Piece> {
    #[inline(always)]
    fn next(&mut self, count: usize) -> &mut [Piece] {
        let len = self.len();
        self.resize(len + count, Piece([0.0; 4]));
        self.get_mut(len..).unwrap_or_default()
    }
}

/// A slice filled from the front by [`Legs::next`]. Its slots are handed
/// out as they are (old pieces, on a rebuild): the substitution writes every
/// one it asks for.
pub(super) struct Fill<'a>(pub(super) &'a mut [Piece]);

impl Legs for Fill<'_> {
    #[inline(always)]
    fn next(&mut self, count: usize) -> &mut [Piece] {
        let rest = core::mem::take(&mut self.0);
        let (now, later) = rest.split_at_mut(count.min(rest.len()));
        self.0 = later;
        now
    }
}

/// Row `k` of a sweep in the `2 D` slots `p` and `d` (a spline's copies of
/// value and knot `k`, a curve's copy of point `k` and its deviation):
/// `l_k / piv_k`, then the `D` swept right-hand sides.
pub(super) struct Aside<'a, const D: usize> {
    pub(super) p: &'a mut [f64; D],
    pub(super) d: &'a mut [f64; D],
}

impl<'a, const D: usize> Aside<'a, D> {
    /// The slots of the first row of `d` and `p` (a lone row left over by
    /// the pairs), if there is one.
    #[inline(always)]
    pub(super) fn first(d: &'a mut [[f64; D]], p: &'a mut [[f64; D]]) -> Option<Self> {
        d.first_mut()
            .zip(p.first_mut())
            .map(|(d, p)| Aside { p, d })
    }

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
    pub(super) fn put(&mut self, m: f64, y: [f64; D]) {
        self.p[0] = m;
        for (c, &v) in y.iter().enumerate() {
            if c + 1 < D {
                self.p[c + 1] = v;
            } else {
                self.d[c + 1 - D] = v;
            }
        }
    }

    /// The row as [`Aside::put`] stored it.
    #[inline(always)]
    fn row(&self) -> (f64, [f64; D]) {
        (self.get(0), core::array::from_fn(|c| self.get(c + 1)))
    }

    /// Overwrites the row with the copy of value or point `k` (`value`,
    /// unscaled) and the deviation `d`, or with `KNOT` the `knot`.
    #[inline(always)]
    fn finish<const KNOT: bool>(&mut self, value: [f64; D], d: [f64; D], knot: f64) {
        *self.p = value;
        if KNOT {
            self.d[0] = knot;
        } else {
            *self.d = d;
        }
    }
}

/// `A', B1', B2', C'` from `a`, `1/a` and `1/(1-a)`.
#[inline(always)]
pub(super) fn terms_from_inverses<L: Lane>(a: L, ia: L, iu: L) -> [L; 4] {
    let k = L::splat;
    let r = a * iu;
    let ir = (k(1.0) - a) * ia;
    [r * r, k(2.0) * ia + k(1.0), k(2.0) * iu + k(1.0), ir * ir]
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
}
