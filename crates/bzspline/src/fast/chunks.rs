//! The method's system cut into chunks solved independently, one after the
//! other or side by side on several cores (with the `rayon` feature).
//!
//! Each chunk keeps the pieces of its own legs and runs the fused sweeps of
//! [`super::sweep`] over its legs plus overlapping rows on both sides, with
//! the deviations at the two ends of that stretch set to zero. The rows' own
//! diagonal dominance bounds how much of that truncation reaches the kept
//! rows: every row damps it by a factor `rho <= 1` formed from its
//! coefficients (`docs/method.md` §16), and the overlap runs until the product
//! of those factors is below `2^-64`, so a chunk's deviations differ from the
//! whole system's by less than `2^-64` of the largest deviation, far below
//! the rounding of either solve. A cut whose rows would need more than
//! [`MAX_OVERLAP`] rows of overlap is not made: its chunks stay one.
//!
//! The cuts are a function of the number of points and the data only, never
//! of the number of threads: every thread count gives the same bits.
//!
//! The chunks between the first and the last are taken two by two, their
//! overlaps padded to the longer of the two, and each two eliminated side by
//! side in the two lanes of an SSE2 register ([`super::pair`]), with the bits
//! each would get alone: on one core, about two thirds of the elimination's
//! instructions.

use super::pair::Pair;
use super::sweep::{Elim, Fill, Sweep};
use super::Piece;
use crate::method::alpha_terms;

/// Legs between two cuts (when every cut can be made).
pub(crate) const CHUNK: usize = 16384;

/// The fewest legs for which the system is cut; fewer are solved by one pair
/// of sweeps over the whole system.
pub(crate) const CHUNKED_MIN: usize = 4 * CHUNK;

/// The fewest legs whose chunks are spread over threads: below, waking a
/// second thread cost about what it saved (measured at 10^5 and 2 * 10^5
/// points on two cores, BENCHMARKS.md). The result is the same bits either
/// way.
#[cfg(feature = "rayon")]
const PARALLEL_MIN: usize = 131_072;

/// The most rows of overlap on either side of a cut.
pub(super) const MAX_OVERLAP: usize = 512;

/// The product of the rows' damping factors an overlap must reach: `2^-64`.
pub(super) const TRUNCATION: f64 = 1.0 / 18_446_744_073_709_551_616.0;

/// One chunk: it keeps legs `start..end` and solves the system of knots
/// `lo..=hi`, whose end deviations are taken as zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Chunk {
    pub(crate) lo: usize,
    pub(crate) start: usize,
    pub(crate) end: usize,
    pub(crate) hi: usize,
}

impl Chunk {
    /// The knots whose slots in the outputs this chunk writes: `start + 1
    /// ..= end`, and knot 0 too for the first chunk.
    pub(crate) fn kept(&self) -> std::ops::RangeInclusive<usize> {
        let first = if self.start == 0 { 0 } else { self.start + 1 };
        first..=self.end
    }
}

/// The whole system's input, as the sweeps take it: `knots` (`n`), `values`
/// (`n`, scaled by `inv_scale` as they are read), `alphas` (`n - 1`, not read
/// when `uniform` gives the one alpha) and the power of two `ws` that brings
/// the span near 1.
#[derive(Clone, Copy)]
pub(crate) struct Whole<'a, const D: usize> {
    pub(crate) knots: &'a [f64],
    pub(crate) values: &'a [[f64; D]],
    pub(crate) inv_scale: [f64; D],
    pub(crate) alphas: &'a [f64],
    pub(crate) uniform: Option<f64>,
    pub(crate) ws: f64,
}

/// The damping factors of row `k` (`1 <= k <= n - 2`) of the sweeps' rows
/// `l = -h_k A'`, `D = h_k B1' + h_{k-1} B2'`, `u = -h_{k-1} C'`:
/// `|l| / (D - |u|)`, which bounds how much of an error in `d_{k-1}` reaches
/// `d_k`, and `|u| / (D - |l|)`, from `d_{k+1}` to `d_k` (§16). Both lie in
/// `[0, 1]` for alphas in range; anything else (a width that underflowed to
/// zero on both sides) counts as 1, no damping.
fn damping(knots: &[f64], ws: f64, left: [f64; 4], right: [f64; 4], k: usize) -> (f64, f64) {
    let hl = (knots[k] - knots[k - 1]) * ws;
    let hr = (knots[k + 1] - knots[k]) * ws;
    let [al, b1, _, _] = left;
    let [_, _, b2, cr] = right;
    let down = hr * al / (hr * b1 + hl * (b2 - cr));
    let up = hl * cr / (hr * (b1 - al) + hl * b2);
    let sane = |r: f64| if (0.0..=1.0).contains(&r) { r } else { 1.0 };
    (sane(down), sane(up))
}

/// The rows of the system, for their damping factors.
struct Rows<'a> {
    knots: &'a [f64],
    alphas: &'a [f64],
    uniform: Option<[f64; 4]>,
    ws: f64,
}

impl Rows<'_> {
    fn terms(&self, leg: usize) -> [f64; 4] {
        self.uniform
            .unwrap_or_else(|| alpha_terms(self.alphas[leg]))
    }

    fn damping(&self, k: usize) -> (f64, f64) {
        damping(self.knots, self.ws, self.terms(k - 1), self.terms(k), k)
    }
}

/// The first knot `lo` of the chunk that keeps knot `s` first: the product
/// of the downward damping of rows `lo + 1 ..= s` is at most [`TRUNCATION`]
/// (or `lo` is 0, the true end). `None` past [`MAX_OVERLAP`] rows.
fn reach_down(damping: &impl Fn(usize) -> (f64, f64), s: usize) -> Option<usize> {
    let mut product = 1.0;
    for (i, k) in (1..=s).rev().enumerate() {
        if i >= MAX_OVERLAP {
            return None;
        }
        product *= damping(k).0;
        if product <= TRUNCATION {
            return Some(k - 1);
        }
    }
    Some(0)
}

/// The last knot `hi` of the chunk that keeps knot `s` last (of `m + 1`):
/// the product of the upward damping of rows `s ..= hi - 1` is at most
/// [`TRUNCATION`] (or `hi` is `m`, the true end).
fn reach_up(damping: &impl Fn(usize) -> (f64, f64), m: usize, s: usize) -> Option<usize> {
    let mut product = 1.0;
    for (i, k) in (s..m).enumerate() {
        if i >= MAX_OVERLAP {
            return None;
        }
        product *= damping(k).1;
        if product <= TRUNCATION {
            return Some(k + 1);
        }
    }
    Some(m)
}

/// The chunks of the system of `knots` (validated: strictly increasing, `n`
/// of them) with `alphas` (or the one alpha `uniform`): cuts every [`CHUNK`]
/// legs where the overlap they need is at most [`MAX_OVERLAP`] rows, the last
/// chunk at least half a chunk long. Empty when the system is solved whole:
/// fewer than [`CHUNKED_MIN`] legs, or no cut made.
pub(crate) fn plan(knots: &[f64], alphas: &[f64], uniform: Option<f64>, ws: f64) -> Vec<Chunk> {
    let m = knots.len().saturating_sub(1);
    if uniform.is_none() && alphas.len() != m {
        return Vec::new();
    }
    let rows = Rows {
        knots,
        alphas,
        uniform: uniform.map(alpha_terms),
        ws,
    };
    let mut chunks = cut(m, |k| rows.damping(k));
    pad_pairs(&mut chunks, m);
    chunks
}

/// Whether chunks `a` and `b`, one after the other, are swept side by side
/// ([`super::pair`]): neither at an end of the system, and rows of the same
/// count below, in and above their own legs.
pub(crate) fn pairable(a: &Chunk, b: &Chunk, m: usize) -> bool {
    let shape = |c: &Chunk| (c.start - c.lo, c.end - c.start, c.hi - c.end);
    a.start > 0 && b.hi < m && shape(a) == shape(b)
}

/// Pads the overlaps of chunks taken two by two (the second and third, the
/// fourth and fifth, ...: the first and the last end at the system's ends) to
/// the larger of each pair's, so that [`pairable`] holds for every such pair
/// whose own legs are as many, and for no other two chunks; an overlap longer
/// than needed only takes the truncation further below rounding.
pub(crate) fn pad_pairs(chunks: &mut [Chunk], m: usize) {
    let mut i = 1;
    while i + 2 < chunks.len() {
        let (a, b) = (chunks[i], chunks[i + 1]);
        if a.end - a.start != b.end - b.start {
            i += 1;
            continue;
        }
        let below = (a.start - a.lo).max(b.start - b.lo);
        let above = (a.hi - a.end).max(b.hi - b.end);
        for c in &mut chunks[i..i + 2] {
            c.lo = c.start - below;
            c.hi = (c.end + above).min(m - 1);
        }
        debug_assert!(pairable(&chunks[i], &chunks[i + 1], m));
        i += 2;
    }
}

/// The chunks of any tridiagonal system of `m` legs (knots `0..=m`, rows
/// `1..m`, the end deviations zero) whose row `k` has the damping factors
/// `damping(k)` (§16: each in `[0, 1]`, what an error at the row below and at
/// the row above passes on to row `k`), cut as [`plan`] cuts. Empty below
/// [`CHUNKED_MIN`] legs or when no cut can be made.
pub(crate) fn cut(m: usize, damping: impl Fn(usize) -> (f64, f64)) -> Vec<Chunk> {
    if m < CHUNKED_MIN {
        return Vec::new();
    }
    let mut chunks = Vec::with_capacity(m / CHUNK + 1);
    let (mut lo, mut start) = (0, 0);
    let mut cut = CHUNK;
    while cut + CHUNK / 2 <= m {
        if let (Some(next_lo), Some(hi)) = (reach_down(&damping, cut), reach_up(&damping, m, cut)) {
            chunks.push(Chunk {
                lo,
                start,
                end: cut,
                hi,
            });
            (lo, start) = (next_lo, cut);
        }
        cut += CHUNK;
    }
    if !chunks.is_empty() {
        chunks.push(Chunk {
            lo,
            start,
            end: m,
            hi: m,
        });
    }
    chunks
}

/// `a()` and `b()`, side by side on the current rayon pool (with the `rayon`
/// feature) for inputs of more than `PARALLEL_MIN` knots, else one after
/// the other.
pub(crate) fn both<A: Send, B: Send>(
    knots: usize,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(feature = "rayon")]
    {
        if rayon::current_num_threads() > 1 && knots > PARALLEL_MIN {
            return rayon::join(a, b);
        }
    }
    let _ = knots;
    (a(), b())
}

/// Makes `v` `n` items long, keeping what it holds and filling new slots
/// with `value`; on several threads from [`PARALLEL_MIN`] items, so that a
/// fresh output's first touch (page faults and clearing) is shared as its
/// chunks will share it.
pub(crate) fn sized<T: Copy + Send + Sync>(v: &mut Vec<T>, n: usize, value: T) {
    v.truncate(n);
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        let more = n - v.len();
        if rayon::current_num_threads() > 1 && more > PARALLEL_MIN {
            v.par_extend(rayon::iter::repeat_n(value, more));
            return;
        }
    }
    v.resize(n, value);
}

/// Runs `f` on every item with a scratch made by `init`: side by side on the
/// current rayon pool (with the `rayon` feature) for systems of more than
/// `PARALLEL_MIN` knots, else one after the other. The items are a plan's
/// chunks, each computed the same way wherever it runs.
pub(crate) fn each<T: Send, S>(
    knots: usize,
    items: &mut [T],
    init: impl Fn() -> S + Sync + Send,
    f: impl Fn(&mut S, &mut T) + Sync + Send,
) {
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        if rayon::current_num_threads() > 1 && knots > PARALLEL_MIN {
            items.par_iter_mut().for_each_init(init, f);
            return;
        }
    }
    let _ = knots;
    let mut scratch = init();
    for item in items {
        f(&mut scratch, item);
    }
}

/// Where one chunk writes: the pieces of its legs (`D` a leg), and the slots
/// of the knots it owns (`start + 1 ..= end`, and knot 0 for the first
/// chunk) in the sweeps' two outputs, as [`Sweep::run`] fills them: the
/// elimination keeps the chunk's own rows there, the substitution then
/// writes the copies over them. `below` keeps the rows of knots
/// `lo + 1 ..= start` from the elimination to the substitution.
struct Out<'a, const D: usize> {
    coefs: &'a mut [Piece],
    second: &'a mut [[f64; D]],
    first: &'a mut [[f64; D]],
    below: (&'a mut [[f64; D]], &'a mut [[f64; D]]),
}

/// The rows a chunk eliminates past its own, and the legs it substitutes
/// before its own: reused from chunk to chunk.
struct Scratch<const D: usize> {
    coefs: Vec<Piece>,
    second: Vec<[f64; D]>,
    first: Vec<[f64; D]>,
}

impl<const D: usize> Scratch<D> {
    /// Empty: each grows to the overlaps of the chunks it serves (tens of
    /// rows, at most [`MAX_OVERLAP`]), since rayon may make one for every
    /// piece of work it splits off.
    fn new() -> Self {
        Scratch {
            coefs: Vec::new(),
            second: Vec::new(),
            first: Vec::new(),
        }
    }
}

/// The two sweeps of one chunk. A chunk's substitution runs right after its
/// own elimination, while the rows it left in the outputs' slots and the
/// input it read are still in the caches (the chunk's elimination touches 16
/// bytes of input and 16 of rows a leg, 512 KiB for a chunk of one
/// coordinate): on a machine streaming 10 GB/s that saved the second pass's
/// 32 bytes a leg from memory, 7-15 % of a build of 10^6-10^7 points on one
/// thread and on two (BENCHMARKS.md).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Phase {
    Eliminate,
    Substitute,
}

/// Solves the chunks of `plan` (from [`plan`], not empty) and writes what
/// [`Sweep::run`] writes for the whole system: `coefs` (`D` pieces a leg,
/// already `n - 1` legs long), `second` and `first` (`n` each), with `KNOT`
/// the knots in `second`, else the deviations.
pub(crate) fn run<const D: usize, const KNOT: bool>(
    plan: &[Chunk],
    whole: Whole<'_, D>,
    coefs: &mut [Piece],
    second: &mut [[f64; D]],
    first: &mut [[f64; D]],
) {
    run_paired::<D, KNOT>(plan, whole, (coefs, second, first), true);
}

/// [`run`], with the chunks of one shape swept two at a time when `paired`
/// (each gets the same bits either way).
fn run_paired<const D: usize, const KNOT: bool>(
    plan: &[Chunk],
    whole: Whole<'_, D>,
    (coefs, second, first): (&mut [Piece], &mut [[f64; D]], &mut [[f64; D]]),
    paired: bool,
) {
    let rows: usize = plan.iter().map(|c| c.start - c.lo).sum();
    let (mut below_d, mut below_p) = (vec![[0.0; D]; rows], vec![[0.0; D]; rows]);
    let mut outs = Vec::with_capacity(plan.len());
    let (mut coefs, mut second, mut first) = (coefs, second, first);
    let (mut bd, mut bp) = (&mut below_d[..], &mut below_p[..]);
    for c in plan {
        // The slots of the knots it keeps: the rows it keeps.
        let owned = c.kept().count();
        let below = c.start - c.lo;
        let (Some((pieces, rest_c)), Some((s, rest_s)), Some((f, rest_f))) = (
            coefs.split_at_mut_checked((c.end - c.start) * D),
            second.split_at_mut_checked(owned),
            first.split_at_mut_checked(owned),
        ) else {
            // Not reached: the plan covers the outputs' lengths.
            return;
        };
        let (Some((d, rest_d)), Some((p, rest_p))) = (
            bd.split_at_mut_checked(below),
            bp.split_at_mut_checked(below),
        ) else {
            return;
        };
        outs.push(Out {
            coefs: pieces,
            second: s,
            first: f,
            below: (d, p),
        });
        (coefs, second, first, bd, bp) = (rest_c, rest_s, rest_f, rest_d, rest_p);
    }
    // Chunks the plan padded to one shape are swept two at a time.
    let m = whole.knots.len().saturating_sub(1);
    let mut jobs = Vec::with_capacity(plan.len());
    let mut chunks = outs.iter_mut().zip(plan.iter().copied()).peekable();
    while let Some((out, c)) = chunks.next() {
        match chunks.next_if(|(_, next)| paired && pairable(&c, next, m)) {
            Some(other) => jobs.push(Job::Two([(out, c), other])),
            None => jobs.push(Job::One(out, c)),
        }
    }
    each(
        whole.knots.len(),
        &mut jobs,
        || [Scratch::new(), Scratch::new()],
        |[scratch, scratch_b], job| match job {
            Job::One(out, c) => {
                for phase in [Phase::Eliminate, Phase::Substitute] {
                    solve::<D, KNOT>(whole, *c, out, scratch, phase);
                }
            }
            Job::Two([(out_a, a), (out_b, b)]) => {
                let (Some(sa), Some(sb)) = (sweep_of(whole, *a), sweep_of(whole, *b)) else {
                    return;
                };
                let pair = Pair { a: &sa, b: &sb };
                let (outs, scratch) = ([&mut **out_a, &mut **out_b], [scratch, scratch_b]);
                if whole.uniform.is_some() {
                    solve_pair::<D, false, KNOT>(&pair, *a, outs, scratch);
                } else {
                    solve_pair::<D, true, KNOT>(&pair, *a, outs, scratch);
                }
            }
        },
    );
}

/// One chunk, or two swept side by side.
enum Job<'j, 'o, const D: usize> {
    One(&'j mut Out<'o, D>, Chunk),
    Two([(&'j mut Out<'o, D>, Chunk); 2]),
}

/// The sweeps' input of chunk `c`: the system of its knots.
fn sweep_of<'a, const D: usize>(whole: Whole<'a, D>, c: Chunk) -> Option<Sweep<'a, D>> {
    let knots = whole.knots.get(c.lo..=c.hi)?;
    let values = whole.values.get(c.lo..=c.hi)?;
    // With one alpha the knots pace the sweeps in the alphas' place.
    let alphas = match whole.uniform {
        Some(_) => whole.knots.get(c.lo..c.hi),
        None => whole.alphas.get(c.lo..c.hi),
    }
    .unwrap_or_default();
    Some(Sweep::new(
        knots,
        values,
        whole.inv_scale,
        alphas,
        whole.uniform,
        whole.ws,
    ))
}

/// Both sweeps of two chunks of one shape (`c` either of them: neither is
/// at an end of the system), side by side, as [`eliminate`] and
/// [`substitute`] sweep one.
fn solve_pair<const D: usize, const PER: bool, const KNOT: bool>(
    pair: &Pair<'_, '_, D>,
    c: Chunk,
    [out_a, out_b]: [&mut Out<'_, D>; 2],
    [scratch_a, scratch_b]: [&mut Scratch<D>; 2],
) {
    let (m, s, top) = own_rows(c, false);
    let above = (m - 1).saturating_sub(top);
    for scratch in [&mut *scratch_a, &mut *scratch_b] {
        for v in [&mut scratch.second, &mut scratch.first] {
            v.truncate(above);
            v.resize(above, [0.0; D]);
        }
    }
    let (Some(ea), Some(eb)) = (pair.a.top::<PER>(), pair.b.top::<PER>()) else {
        return;
    };
    let Some(mut elim) = Elim::pair(&ea, &eb) else {
        return;
    };
    let (Some(own_a), Some(own_b)) = (
        own_slots((&mut *out_a.second, &mut *out_a.first), s, top),
        own_slots((&mut *out_b.second, &mut *out_b.first), s, top),
    ) else {
        return;
    };
    pair.eliminate::<PER>(
        &mut elim,
        top + 1,
        (&mut scratch_a.second, &mut scratch_a.first),
        (&mut scratch_b.second, &mut scratch_b.first),
    );
    pair.eliminate::<PER>(&mut elim, s + 1, own_a, own_b);
    let below_a = (&mut *out_a.below.0, &mut *out_a.below.1);
    let below_b = (&mut *out_b.below.0, &mut *out_b.below.1);
    pair.eliminate::<PER>(&mut elim, 1, below_a, below_b);
    // The substitution is mostly loads and stores: one chunk at a time.
    substitute::<D, PER, KNOT>(pair.a, c, false, out_a, scratch_a);
    substitute::<D, PER, KNOT>(pair.b, c, false, out_b, scratch_b);
}

/// One sweep of one chunk, over its share of the outputs.
fn solve<const D: usize, const KNOT: bool>(
    whole: Whole<'_, D>,
    c: Chunk,
    out: &mut Out<'_, D>,
    scratch: &mut Scratch<D>,
    phase: Phase,
) {
    let Some(sweep) = sweep_of(whole, c) else {
        return;
    };
    let last = c.hi + 1 == whole.knots.len();
    match (phase, whole.uniform.is_some()) {
        (Phase::Eliminate, true) => eliminate::<D, false>(&sweep, c, last, out, scratch),
        (Phase::Eliminate, false) => eliminate::<D, true>(&sweep, c, last, out, scratch),
        (Phase::Substitute, true) => substitute::<D, false, KNOT>(&sweep, c, last, out, scratch),
        (Phase::Substitute, false) => substitute::<D, true, KNOT>(&sweep, c, last, out, scratch),
    }
}

/// The rows of a chunk over `sweep`, the system of its knots `lo..=hi`
/// (counted from `lo` here): rows `s + 1 ..= top` are its own, `top` the
/// last row before its end deviation (zero only for the last chunk).
fn own_rows(c: Chunk, last: bool) -> (usize, usize, usize) {
    let m = c.hi - c.lo;
    let (s, e) = (c.start - c.lo, c.end - c.lo);
    let top = if last { m.saturating_sub(1) } else { e };
    (m, s, top)
}

/// Rows' slots in the sweeps' two outputs.
type Slots<'o, const D: usize> = (&'o mut [[f64; D]], &'o mut [[f64; D]]);

/// The slots of a chunk's own rows `s + 1 ..= top` in its share of the two
/// outputs, after those of knot 0 in the first chunk's.
fn own_slots<'o, const D: usize>(
    (second, first): Slots<'o, D>,
    s: usize,
    top: usize,
) -> Option<Slots<'o, D>> {
    let at = usize::from(s == 0);
    let own = at..at + (top - s);
    Some((second.get_mut(own.clone())?, first.get_mut(own)?))
}

/// The elimination of one chunk, in three stretches of rows from the top:
/// those past its own (kept in `scratch`), its own (kept in `out`'s slots)
/// and those before them (kept in `out.below`).
fn eliminate<const D: usize, const PER: bool>(
    sweep: &Sweep<'_, D>,
    c: Chunk,
    last: bool,
    out: &mut Out<'_, D>,
    scratch: &mut Scratch<D>,
) {
    let (m, s, top) = own_rows(c, last);
    let above = (m - 1).saturating_sub(top);
    for v in [&mut scratch.second, &mut scratch.first] {
        v.truncate(above);
        v.resize(above, [0.0; D]);
    }
    let Some(mut elim) = sweep.top::<PER>() else {
        return;
    };
    let (Some((od, op)), Some(ad), Some(ap)) = (
        own_slots((&mut *out.second, &mut *out.first), s, top),
        scratch.second.get_mut(..above),
        scratch.first.get_mut(..above),
    ) else {
        return;
    };
    sweep.eliminate::<PER>(&mut elim, top + 1, (ad, ap));
    sweep.eliminate::<PER>(&mut elim, s + 1, (od, op));
    sweep.eliminate::<PER>(&mut elim, 1, (&mut *out.below.0, &mut *out.below.1));
}

/// The substitution of one chunk after its elimination: the rows before its
/// own (their legs to `scratch`, for the deviation at `start`), then its
/// own, their legs to `out`; the end points' copies at the system's ends.
fn substitute<const D: usize, const PER: bool, const KNOT: bool>(
    sweep: &Sweep<'_, D>,
    c: Chunk,
    last: bool,
    out: &mut Out<'_, D>,
    scratch: &mut Scratch<D>,
) {
    let (m, s, top) = own_rows(c, last);
    let mut sub = sweep.bottom();
    scratch.coefs.clear();
    sweep.substitute::<PER, KNOT>(
        &mut sub,
        1,
        (&mut *out.below.0, &mut *out.below.1),
        &mut scratch.coefs,
    );
    let Some((od, op)) = own_slots((&mut *out.second, &mut *out.first), s, top) else {
        return;
    };
    let mut fill = Fill(&mut *out.coefs);
    sweep.substitute::<PER, KNOT>(&mut sub, s + 1, (od, op), &mut fill);
    if last {
        sweep.tail::<PER>(&sub, &mut fill);
        if let (Some(d), Some(p)) = (out.second.last_mut(), out.first.last_mut()) {
            sweep.end_point::<KNOT>(m, d, p);
        }
    }
    if s == 0 {
        if let (Some(d), Some(p)) = (out.second.first_mut(), out.first.first_mut()) {
            sweep.end_point::<KNOT>(0, d, p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::case;

    /// The pieces and deviations of one solve.
    type Solved = (Vec<Piece>, Vec<[f64; 1]>);

    /// The pieces and deviations of one sweep over the whole system and of
    /// the chunks, for `case`.
    fn both(
        knots: &[f64],
        values: &[f64],
        alphas: &[f64],
        uniform: Option<f64>,
    ) -> (Vec<Chunk>, [Solved; 2]) {
        let n = knots.len();
        let span = knots[n - 1] - knots[0];
        let ws = crate::fast::inverse_power_of_two(span);
        let alphas = if uniform.is_some() {
            &knots[..n - 1]
        } else {
            alphas
        };
        let values = values.as_chunks::<1>().0;
        let plan = plan(knots, alphas, uniform, ws);
        let mut whole = (Vec::new(), vec![[0.0]; n], vec![[0.0]; n]);
        let sweep = Sweep::new(knots, values, [1.0], alphas, uniform, ws);
        if uniform.is_some() {
            sweep.run::<false, false>(&mut whole.0, &mut whole.1, &mut whole.2);
        } else {
            sweep.run::<true, false>(&mut whole.0, &mut whole.1, &mut whole.2);
        }
        let mut cut = (
            vec![Piece::default(); n - 1],
            vec![[0.0]; n],
            vec![[0.0]; n],
        );
        let input = Whole {
            knots,
            values,
            inv_scale: [1.0],
            alphas,
            uniform,
            ws,
        };
        if !plan.is_empty() {
            run::<1, false>(&plan, input, &mut cut.0, &mut cut.1, &mut cut.2);
        }
        assert_eq!(whole.2, cut.2, "the copies of the values");
        (plan, [(whole.0, whole.1), (cut.0, cut.1)])
    }

    #[test]
    fn chunks_agree_with_one_sweep_to_rounding() {
        let mut worst: f64 = 0.0;
        for grid in 0..2u8 {
            for alphas in 0..5u8 {
                for (seed, n) in [(1, CHUNKED_MIN + 1), (2, 5 * CHUNK + 1234)] {
                    let (k, v, a, u) = case(n, grid, alphas, seed + 10 * u64::from(alphas));
                    let (plan, [(pw, dw), (pc, dc)]) = both(&k, &v, &a, u);
                    let what = format!("grid {grid}, alphas {alphas}, n {n}");
                    assert!(plan.len() >= 4, "{what}: {plan:?}");
                    let dmax = dw.iter().fold(0.0f64, |m, d| m.max(d[0].abs()));
                    let cmax = pw
                        .iter()
                        .fold(0.0f64, |m, p| p.0.iter().fold(m, |m, c| m.max(c.abs())));
                    for (i, (x, y)) in dw.iter().zip(&dc).enumerate() {
                        let e = (x[0] - y[0]).abs() / (dmax * f64::EPSILON);
                        worst = worst.max(e);
                        assert!(e <= 16.0, "{what}: d_{i} {} against {}", y[0], x[0]);
                    }
                    for (i, (x, y)) in pw.iter().zip(&pc).enumerate() {
                        for j in 0..4 {
                            let e = (x.0[j] - y.0[j]).abs() / (cmax * f64::EPSILON);
                            assert!(e <= 16.0, "{what}: piece {i}: {:?} against {:?}", y.0, x.0);
                        }
                    }
                }
            }
        }
        eprintln!("largest difference: {worst} ulps of the largest deviation");
    }

    #[test]
    fn curves_in_the_plane_agree_with_one_sweep_to_rounding() {
        // Two coordinates on one matrix, as the curve builder solves them.
        let n = 6 * CHUNK + 11;
        let (knots, v, alphas, _) = case(n, 1, 1, 5);
        let values: Vec<[f64; 2]> = v.iter().map(|&y| [y, y * y - 0.5]).collect();
        let ws = crate::fast::inverse_power_of_two(knots[n - 1] - knots[0]);
        let plan = plan(&knots, &alphas, None, ws);
        assert!(plan.len() >= 4, "{plan:?}");
        let mut whole = (Vec::new(), vec![[0.0; 2]; n], vec![[0.0; 2]; n]);
        let sweep = Sweep::new(&knots, &values, [1.0, 0.5], &alphas, None, ws);
        sweep.run::<true, false>(&mut whole.0, &mut whole.1, &mut whole.2);
        let mut cut = (
            vec![Piece::default(); 2 * (n - 1)],
            vec![[0.0; 2]; n],
            vec![[0.0; 2]; n],
        );
        let input = Whole {
            knots: &knots,
            values: &values,
            inv_scale: [1.0, 0.5],
            alphas: &alphas,
            uniform: None,
            ws,
        };
        run::<2, false>(&plan, input, &mut cut.0, &mut cut.1, &mut cut.2);
        assert_eq!(whole.2, cut.2, "the copies of the points");
        for c in 0..2 {
            let dmax = whole.1.iter().fold(0.0f64, |m, d| m.max(d[c].abs()));
            for (i, (x, y)) in whole.1.iter().zip(&cut.1).enumerate() {
                let e = (x[c] - y[c]).abs() / (dmax * f64::EPSILON);
                assert!(e <= 16.0, "coordinate {c}: d_{i} {} against {}", y[c], x[c]);
            }
        }
        let cmax = whole
            .0
            .iter()
            .fold(0.0f64, |m, p| p.0.iter().fold(m, |m, c| m.max(c.abs())));
        for (i, (x, y)) in whole.0.iter().zip(&cut.0).enumerate() {
            for j in 0..4 {
                let e = (x.0[j] - y.0[j]).abs() / (cmax * f64::EPSILON);
                assert!(e <= 16.0, "piece {i}: {:?} against {:?}", y.0, x.0);
            }
        }
    }

    /// The bits of every output of `run` on `plan`, chunks paired or not.
    fn bits_of<const D: usize, const KNOT: bool>(
        plan: &[Chunk],
        whole: Whole<'_, D>,
        paired: bool,
    ) -> Vec<u64> {
        let n = whole.knots.len();
        let mut out = (
            vec![Piece::default(); D * (n - 1)],
            vec![[0.0; D]; n],
            vec![[0.0; D]; n],
        );
        run_paired::<D, KNOT>(plan, whole, (&mut out.0, &mut out.1, &mut out.2), paired);
        let pieces = out.0.iter().flat_map(|p| p.0);
        let rows = out.1.iter().chain(&out.2).flatten().copied();
        pieces.chain(rows).map(f64::to_bits).collect()
    }

    #[test]
    fn paired_chunks_get_the_bits_of_each_chunk_alone() {
        for grid in 0..2u8 {
            for alphas in 0..5u8 {
                let n = 9 * CHUNK + 77 * u64::from(alphas) as usize;
                let (knots, v, a, uniform) = case(n, grid, alphas, 20 + u64::from(alphas));
                let ws = crate::fast::inverse_power_of_two(knots[n - 1] - knots[0]);
                let alphas_in = if uniform.is_some() {
                    &knots[..n - 1]
                } else {
                    &a[..]
                };
                let plan = plan(&knots, alphas_in, uniform, ws);
                let m = n - 1;
                let pairs = plan
                    .windows(2)
                    .filter(|w| pairable(&w[0], &w[1], m))
                    .count();
                let what = format!("grid {grid}, alphas {alphas}");
                assert!(pairs >= 3, "{what}: {plan:?}");
                // A spline (the knots copied), and a planar curve.
                let values = v.as_chunks::<1>().0;
                let whole = Whole {
                    knots: &knots,
                    values,
                    inv_scale: [0.5],
                    alphas: alphas_in,
                    uniform,
                    ws,
                };
                let (alone, side_by_side) = (
                    bits_of::<1, true>(&plan, whole, false),
                    bits_of::<1, true>(&plan, whole, true),
                );
                assert!(alone == side_by_side, "{what}: a spline's chunks");
                let points: Vec<[f64; 2]> = v.iter().map(|&y| [y, 1.0 - y * y]).collect();
                let whole = Whole {
                    knots: &knots,
                    values: &points,
                    inv_scale: [1.0, 0.25],
                    alphas: alphas_in,
                    uniform,
                    ws,
                };
                let (alone, side_by_side) = (
                    bits_of::<2, false>(&plan, whole, false),
                    bits_of::<2, false>(&plan, whole, true),
                );
                assert!(alone == side_by_side, "{what}: a curve's chunks");
            }
        }
    }

    #[test]
    fn padded_pairs_keep_their_shape_and_the_system() {
        let (knots, _, a, _) = case(11 * CHUNK + 5, 1, 0, 31);
        let ws = crate::fast::inverse_power_of_two(knots[knots.len() - 1] - knots[0]);
        let m = knots.len() - 1;
        let unpadded = {
            let rows = Rows {
                knots: &knots,
                alphas: &a,
                uniform: None,
                ws,
            };
            cut(m, |k| rows.damping(k))
        };
        let padded = plan(&knots, &a, None, ws);
        assert_eq!(padded.len(), unpadded.len());
        for (i, (p, u)) in padded.iter().zip(&unpadded).enumerate() {
            // The same own legs, overlaps at least as long, inside the system.
            assert_eq!((p.start, p.end), (u.start, u.end), "chunk {i}");
            assert!(
                p.lo <= u.lo && p.hi >= u.hi && p.hi <= m,
                "chunk {i}: {p:?} {u:?}"
            );
        }
        // The second and third, the fourth and fifth, ... pair; the ends not.
        for i in (1..padded.len() - 2).step_by(2) {
            assert!(
                pairable(&padded[i], &padded[i + 1], m),
                "chunks {i}, {}",
                i + 1
            );
        }
        assert!(!pairable(&padded[0], &padded[1], m));
        let last = padded.len() - 1;
        assert!(!pairable(&padded[last - 1], &padded[last], m));
    }

    #[test]
    fn rows_without_dominance_are_not_cut() {
        // Alphas outside the theorem's range (which validation refuses): no
        // row damps, so no overlap reaches 2^-64 and the system stays whole.
        let n = 6 * CHUNK;
        let knots: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let alphas = vec![0.9; n - 1];
        assert!(plan(&knots, &alphas, None, 1.0 / 32768.0).is_empty());
        assert!(!plan(&knots, &[], Some(0.5), 1.0 / 32768.0).is_empty());
    }

    #[cfg(feature = "rayon")]
    #[test]
    fn every_thread_count_gives_the_same_bits() {
        for (alphas, seed) in [(0, 7), (3, 8)] {
            let (k, v, a, u) = case(10 * CHUNK + 3, 1, alphas, seed);
            let runs: Vec<_> = [1, 2, 16]
                .into_iter()
                .map(|threads| {
                    let [_, (pieces, dev)] =
                        crate::testing::on_threads(threads, || both(&k, &v, &a, u)).1;
                    let bits: Vec<u64> = pieces
                        .iter()
                        .flat_map(|p| p.0)
                        .chain(dev.iter().map(|d| d[0]))
                        .map(f64::to_bits)
                        .collect();
                    bits
                })
                .collect();
            assert!(runs.iter().all(|r| *r == runs[0]), "alphas {alphas}");
        }
    }

    #[test]
    fn damping_is_at_most_one_and_one_only_at_the_weakest_rows() {
        for (al, ar) in [(1.0 / 3.0, 1.0 / 3.0), (0.5, 0.5), (2.0 / 3.0, 1.0 / 3.0)] {
            let knots = [0.0, 1.0, 2.0];
            let (down, up) = damping(&knots, 1.0, alpha_terms(al), alpha_terms(ar), 1);
            assert!((0.0..=1.0).contains(&down) && (0.0..=1.0).contains(&up));
            if al == 2.0 / 3.0 && ar == 1.0 / 3.0 {
                // The row -4p, 4, -4q: no strict dominance, no damping.
                assert!(down > 1.0 - 1e-12 && up > 1.0 - 1e-12, "{down} {up}");
            } else {
                assert!(down < 0.9 && up < 0.9, "{down} {up}");
            }
        }
    }

    #[test]
    fn plans_cover_every_leg_once() {
        for n in [CHUNKED_MIN, CHUNKED_MIN + 1, 5 * CHUNK + 7, 9 * CHUNK] {
            let knots: Vec<f64> = (0..n).map(|i| i as f64).collect();
            let plan = plan(&knots, &[], Some(0.5), 1.0 / 8192.0);
            if n <= CHUNKED_MIN {
                assert!(plan.is_empty(), "n = {n}");
                continue;
            }
            assert_eq!(plan.first().map(|c| (c.lo, c.start)), Some((0, 0)));
            assert_eq!(plan.last().map(|c| (c.end, c.hi)), Some((n - 1, n - 1)));
            for w in plan.windows(2) {
                assert_eq!(w[0].end, w[1].start);
                assert!(w[1].lo < w[1].start && w[0].hi > w[0].end);
            }
            for c in &plan {
                // Uniform rows at alpha 1/2 damp by 1/9 a row: 21 rows reach 2^-64.
                assert!(c.start - c.lo <= 21 && c.hi - c.end <= 21, "{c:?}");
            }
        }
    }
}
