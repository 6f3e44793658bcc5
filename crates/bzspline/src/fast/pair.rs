//! Two chunks of the method's system eliminated side by side, one in each
//! lane of an [`F2`]: the row steps of [`super::sweep`]'s elimination
//! ([`Elim::two_rows`], [`Elim::one_row`], generic over the lanes) with every
//! number a pair of numbers, one a chunk, and this module's loads and
//! stores. Each lane goes through the operations of [`Sweep::eliminate`] in
//! their order, so each chunk of a pair gets the bits it gets eliminated
//! alone, while the arithmetic of both runs in the same SSE2 instructions:
//! 0.65 times the instructions of the two eliminations one after the other. (The substitution, mostly loads and stores, gained
//! nothing from pairing: each chunk is substituted alone.)
//!
//! The two chunks must have rows of the same count in each stretch the
//! elimination goes through (the plan pads their overlaps to match,
//! `chunks.rs`).

use super::sweep::{inverses, terms_from_inverses, Aside, Elim, Sweep};
use crate::lanes::{Lane, F2};

/// Two sweeps' numbers side by side.
#[inline(always)]
fn two(a: f64, b: f64) -> F2 {
    F2([a, b])
}

/// Lane `l` of each coordinate.
#[inline(always)]
fn lane<const D: usize>(v: [F2; D], l: usize) -> [f64; D] {
    core::array::from_fn(|c| v[c].0[l])
}

/// Rows' slots of one chunk: `(second, first)` as [`Sweep::eliminate`] takes
/// them.
pub(super) type Rows<'r, const D: usize> = (&'r mut [[f64; D]], &'r mut [[f64; D]]);

/// The sweeps of two chunks over the same whole input (the same scale, the
/// same alpha or none).
pub(super) struct Pair<'s, 'a, const D: usize> {
    pub(super) a: &'s Sweep<'a, D>,
    pub(super) b: &'s Sweep<'a, D>,
}

impl<const D: usize> Pair<'_, '_, D> {
    #[inline(always)]
    fn scaled(&self, a: [f64; D], b: [f64; D]) -> [F2; D] {
        let s = self.a.inv_scale;
        core::array::from_fn(|c| two(a[c], b[c]) * F2::splat(s[c]))
    }

    /// As [`Sweep::mirrored`], lane by lane.
    #[inline(always)]
    fn mirrored<const PER: bool>(&self, a: f64, b: f64) -> [F2; 4] {
        let [al, b1, b2, cr] = if PER {
            let x = two(a, b);
            let (ia, iu) = inverses(x);
            terms_from_inverses(x, ia, iu)
        } else {
            let u = self.a.uniform;
            [
                F2::splat(u[0]),
                F2::splat(u[1]),
                F2::splat(u[2]),
                F2::splat(u[3]),
            ]
        };
        [cr, b2, b1, al]
    }

    /// [`Sweep::eliminate`] of both chunks over rows `r0 + c - 1` down to
    /// `r0`, `c` the same for both: the same row steps ([`Elim::two_rows`],
    /// [`Elim::one_row`]) on numbers of two lanes.
    #[inline(always)]
    pub(super) fn eliminate<const PER: bool>(
        &self,
        st: &mut Elim<F2, D>,
        r0: usize,
        rows_a: Rows<'_, D>,
        rows_b: Rows<'_, D>,
    ) {
        let c = rows_a.0.len();
        let at = r0.wrapping_sub(1)..r0.wrapping_sub(1).wrapping_add(c);
        let (Some(kna), Some(vsa), Some(ala), Some(knb), Some(vsb), Some(alb)) = (
            self.a.knots.get(at.clone()),
            self.a.values.get(at.clone()),
            self.a.alphas.get(at.clone()),
            self.b.knots.get(at.clone()),
            self.b.values.get(at.clone()),
            self.b.alphas.get(at),
        ) else {
            return;
        };
        let (Some(rda), Some(rpa), Some(rdb), Some(rpb)) = (
            rows_a.0.get_mut(..c),
            rows_a.1.get_mut(..c),
            rows_b.0.get_mut(..c),
            rows_b.1.get_mut(..c),
        ) else {
            return;
        };
        let ws = F2::splat(self.a.ws);
        let mut e = *st;
        let (lka, kna) = kna.as_rchunks::<2>();
        let (lva, vsa) = vsa.as_rchunks::<2>();
        let (laa, ala) = ala.as_rchunks::<2>();
        let (lda, pda) = rda.as_rchunks_mut::<2>();
        let (lpa, ppa) = rpa.as_rchunks_mut::<2>();
        let (lkb, knb) = knb.as_rchunks::<2>();
        let (lvb, vsb) = vsb.as_rchunks::<2>();
        let (lab, alb) = alb.as_rchunks::<2>();
        let (ldb, pdb) = rdb.as_rchunks_mut::<2>();
        let (lpb, ppb) = rpb.as_rchunks_mut::<2>();
        let lane_a = pda.iter_mut().zip(ppa).zip(kna).zip(vsa).zip(ala);
        let lane_b = pdb.iter_mut().zip(ppb).zip(knb).zip(vsb).zip(alb);
        for (a, b) in lane_a.zip(lane_b).rev() {
            let (((([da0, da1], [pa0, pa1]), kna), vsa), ala) = a;
            let (((([db0, db1], [pb0, pb1]), knb), vsb), alb) = b;
            // Rows k and k - 1, as in the sweep of one chunk.
            let k = (two(kna[1], knb[1]), two(kna[0], knb[0]));
            let f = (self.scaled(vsa[1], vsb[1]), self.scaled(vsa[0], vsb[0]));
            let t = (
                self.mirrored::<PER>(ala[1], alb[1]),
                self.mirrored::<PER>(ala[0], alb[0]),
            );
            let [(w1, y1), (w2, y2)] = e.two_rows(k, f, t, ws);
            Aside { p: pa1, d: da1 }.put(w1.0[0], lane(y1, 0));
            Aside { p: pa0, d: da0 }.put(w2.0[0], lane(y2, 0));
            Aside { p: pb1, d: db1 }.put(w1.0[1], lane(y1, 1));
            Aside { p: pb0, d: db0 }.put(w2.0[1], lane(y2, 1));
        }
        let odd = (
            Aside::first(lda, lpa),
            Aside::first(ldb, lpb),
            lka.first().zip(lkb.first()),
            lva.first().zip(lvb.first()),
            laa.first().zip(lab.first()),
        );
        if let (Some(mut sa), Some(mut sb), Some((&ka, &kb)), Some((&va, &vb)), Some((&aa, &ab))) =
            odd
        {
            // Row r0 when the count is odd.
            let f = self.scaled(va, vb);
            let (w, y) = e.one_row(two(ka, kb), f, self.mirrored::<PER>(aa, ab), ws);
            sa.put(w.0[0], lane(y, 0));
            sb.put(w.0[1], lane(y, 1));
        }
        *st = e;
    }
}
