//! The batch evaluator: the derivative of one order of a spline at many
//! queries, walking sorted ones piece by piece and searching blocks of
//! unsorted ones (see [`super::search`]), with the results of the one-by-one
//! path.

use super::search::{locate_from, search_block, Summary, BLOCK};
use super::Piece;
use crate::poly::deriv;

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
