//! Two chunks of the method's system eliminated side by side, one in each
//! lane of an [`F2`]: the elimination of [`super::sweep`] with every number a
//! pair of numbers, one a chunk. Each lane goes through the operations of
//! [`Sweep::eliminate`] in their order, so each chunk of a pair gets the bits
//! it gets eliminated alone, while the arithmetic of both runs in the same
//! SSE2 instructions: 0.65 times the instructions of the two eliminations one
//! after the other. (The substitution, mostly loads and stores, gained
//! nothing from pairing: each chunk is substituted alone.)
//!
//! The two chunks must have rows of the same count in each stretch the
//! elimination goes through (the plan pads their overlaps to match,
//! `chunks.rs`).

use super::sweep::{inverses, renormalise, terms_from_inverses, Aside, Elim, Sweep, RENORM};
use crate::lanes::{Lane, F2};

/// Two sweeps' numbers side by side.
#[inline(always)]
fn two(a: f64, b: f64) -> F2 {
    F2([a, b])
}

/// `a - b` coordinate by coordinate.
#[inline(always)]
fn sub<const D: usize>(a: [F2; D], b: [F2; D]) -> [F2; D] {
    core::array::from_fn(|c| a[c] - b[c])
}

/// Lane `l` of each coordinate.
#[inline(always)]
fn lane<const D: usize>(v: [F2; D], l: usize) -> [f64; D] {
    core::array::from_fn(|c| v[c].0[l])
}

/// The elimination's state of two chunks ([`Elim`], a lane each).
#[derive(Clone, Copy)]
pub(super) struct Elim2<const D: usize> {
    p_prev2: F2,
    p_prev: F2,
    y_prev: [F2; D],
    u_prev: F2,
    kc: F2,
    hl: F2,
    fc: [F2; D],
    df_l: [F2; D],
    terms_l: [F2; 4],
    since: usize,
}

impl<const D: usize> Elim2<D> {
    /// The two states side by side; `None` unless both have gone through
    /// the same number of rows since their last renormalisation.
    pub(super) fn new(a: &Elim<D>, b: &Elim<D>) -> Option<Self> {
        let pair = |x: [f64; D], y: [f64; D]| core::array::from_fn(|c| two(x[c], y[c]));
        (a.since == b.since).then(|| Elim2 {
            p_prev2: two(a.p_prev2, b.p_prev2),
            p_prev: two(a.p_prev, b.p_prev),
            y_prev: pair(a.y_prev, b.y_prev),
            u_prev: two(a.u_prev, b.u_prev),
            kc: two(a.kc, b.kc),
            hl: two(a.hl, b.hl),
            fc: pair(a.fc, b.fc),
            df_l: pair(a.df_l, b.df_l),
            terms_l: core::array::from_fn(|i| two(a.terms_l[i], b.terms_l[i])),
            since: a.since,
        })
    }
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
    /// `r0`, `c` the same for both.
    #[inline(always)]
    pub(super) fn eliminate<const PER: bool>(
        &self,
        st: &mut Elim2<D>,
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
        let Elim2 {
            mut p_prev2,
            mut p_prev,
            mut y_prev,
            mut u_prev,
            mut kc,
            mut hl,
            mut fc,
            mut df_l,
            mut terms_l,
            mut since,
        } = *st;
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
            let (k1, k0) = (two(kna[1], knb[1]), two(kna[0], knb[0]));
            let h1 = (kc - k1) * ws;
            let h2 = (k1 - k0) * ws;
            kc = k0;
            let (f1, f2) = (self.scaled(vsa[1], vsb[1]), self.scaled(vsa[0], vsb[0]));
            let t1 = self.mirrored::<PER>(ala[1], alb[1]);
            let t2 = self.mirrored::<PER>(ala[0], alb[0]);
            let l1 = -h1 * terms_l[0];
            let d1 = h1 * terms_l[1] + hl * t1[2];
            let u1 = -hl * t1[3];
            let (df1, df2) = (sub(f1, fc), sub(f2, f1));
            let l2 = -h2 * t1[0];
            let d2 = h2 * t1[1] + h1 * t2[2];
            let u2 = -h1 * t2[3];
            let e1 = l1 * u_prev;
            let e2 = l2 * u1;
            let p1 = d1 * p_prev - e1 * p_prev2;
            let p2 = (d2 * d1 - e2) * p_prev - (d2 * e1) * p_prev2;
            let rr = F2::splat(1.0) / (p1 * p2);
            let inv1 = p_prev * p2 * rr;
            let inv2 = p1 * p1 * rr;
            let (m1, m2) = (l1 * inv1, l2 * inv2);
            let mut y1 = [F2::splat(0.0); D];
            let mut y2 = [F2::splat(0.0); D];
            for c in 0..D {
                let g1 = (hl * df1[c] - h1 * df_l[c]) * inv1;
                let g2 = (h1 * df2[c] - h2 * df1[c]) * inv2;
                y1[c] = g1 - m1 * y_prev[c];
                y2[c] = (g2 - m2 * g1) + (m2 * m1) * y_prev[c];
            }
            let (w1, w2) = (u1 * inv1, u2 * inv2);
            Aside { p: pa1, d: da1 }.put(w1.0[0], lane(y1, 0));
            Aside { p: pa0, d: da0 }.put(w2.0[0], lane(y2, 0));
            Aside { p: pb1, d: db1 }.put(w1.0[1], lane(y1, 1));
            Aside { p: pb0, d: db0 }.put(w2.0[1], lane(y2, 1));
            p_prev2 = p1;
            p_prev = p2;
            since += 2;
            if since >= RENORM {
                renormalise_both(&mut p_prev, &mut p_prev2);
                since = 0;
            }
            y_prev = y2;
            u_prev = u2;
            hl = h2;
            df_l = df2;
            fc = f2;
            terms_l = t2;
        }
        if let (
            Some(sa),
            Some(sb),
            Some(&kra),
            Some(&krb),
            Some(&vra),
            Some(&vrb),
            Some(&ara),
            Some(&arb),
        ) = (
            Aside::first(lda, lpa),
            Aside::first(ldb, lpb),
            lka.first(),
            lkb.first(),
            lva.first(),
            lvb.first(),
            laa.first(),
            lab.first(),
        ) {
            // Row r0 when the count is odd.
            let hr = (kc - two(kra, krb)) * ws;
            let fr = self.scaled(vra, vrb);
            let terms_r = self.mirrored::<PER>(ara, arb);
            let l = -hr * terms_l[0];
            let d = hr * terms_l[1] + hl * terms_r[2];
            let u = -hl * terms_r[3];
            let p = d * p_prev - (l * u_prev) * p_prev2;
            let inv = p_prev / p;
            let df_r = sub(fr, fc);
            let y = core::array::from_fn(|c| {
                (hl * df_r[c] - hr * df_l[c]) * inv - (l * inv) * y_prev[c]
            });
            let w = u * inv;
            let (mut sa, mut sb) = (sa, sb);
            sa.put(w.0[0], lane(y, 0));
            sb.put(w.0[1], lane(y, 1));
            p_prev2 = p_prev;
            p_prev = p;
            since += 1;
            if since >= RENORM {
                renormalise_both(&mut p_prev, &mut p_prev2);
                since = 0;
            }
            y_prev = y;
            u_prev = u;
            kc = two(kra, krb);
            hl = hr;
            df_l = df_r;
            fc = fr;
            terms_l = terms_r;
        }
        *st = Elim2 {
            p_prev2,
            p_prev,
            y_prev,
            u_prev,
            kc,
            hl,
            fc,
            df_l,
            terms_l,
            since,
        };
    }
}

/// [`renormalise`] in each lane.
#[inline(always)]
fn renormalise_both(p: &mut F2, q: &mut F2) {
    for l in 0..2 {
        renormalise(&mut p.0[l], &mut q.0[l]);
    }
}
