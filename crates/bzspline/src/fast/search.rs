//! Finding the piece of a query: the summary of the knots (every
//! [`STRIDE`]-th), its index by position, and the searches of one query and of
//! a block of [`BLOCK`] queries over them.

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
    pub(super) fn index(&self, hi: f64, queries: usize) -> Option<&Index> {
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
pub(super) struct Index {
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

/// The piece of `x` (inside the domain) starting the search at piece `k`: a few
/// linear steps forward, then the summary's search (see [`search_one`]). The
/// flag says whether it took the search.
#[inline(never)]
pub(super) fn locate_from(knots: &[f64], find: Find<'_>, k: usize, x: f64) -> (usize, bool) {
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
pub(super) type Find<'a> = (&'a [f64], Option<&'a Index>);

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
pub(super) fn search_block(
    knots: &[f64],
    (every, index): Find<'_>,
    xb: &[f64],
    idx: &mut [usize; BLOCK],
) {
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
