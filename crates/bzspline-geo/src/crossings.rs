//! Where polylines meet where they should not: pairs of segments that cross,
//! touch or overlap, found through a packed R-tree of the boxes of runs of
//! segments and decided with exact orientation predicates.
//!
//! Two segments may share an end position only where the polylines are meant
//! to meet: consecutive segments of one polyline, and *nodes* (the ends of
//! arcs, and positions fixed because several arcs or several places of one
//! arc hold them). Even there they conflict when they run on from the shared
//! position in the same direction (an overlap).

use geo_types::Coord;
use robust::{orient2d, Coord as RCoord};

use crate::arcs::Arcs;
use crate::graph::key;
use geo_index::rtree::sort::HilbertSort;
use geo_index::rtree::util::f64_box_to_f32;
use geo_index::rtree::{RTree, RTreeBuilder, RTreeIndex};

/// A segment of polyline `line`, from its position `seg` to `seg + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) struct SegId {
    pub line: u32,
    pub seg: u32,
}

/// Segments in one tree entry: a run of consecutive segments, under one box,
/// so that the tree holds a fraction of the segments.
const RUN: usize = 8;

/// A run of up to [`RUN`] consecutive segments, in the order of the lines and
/// of their segments: a run goes on into the next line when its own ends and
/// the two lines meet (share an end position), so that short lines (a
/// mosaic's arcs have a few positions each, numbered as the rings that hold
/// them are walked) share entries of the tree, and a run's box stays about
/// its segments' size.
///
/// The run's segments are gathered once, with their boxes and whether their
/// lines are dirty: the pairs of two runs then compare boxes without going
/// back to the lines (reading a segment through [`Arcs`] costs more than
/// comparing its box, in the hottest loop of a coverage's first round).
struct Run {
    len: usize,
    ids: [SegId; RUN],
    boxes: [Bbox; RUN],
    dirty: [bool; RUN],
    /// The box of the whole run.
    env: Bbox,
}

/// A box with its lower and upper corners: the few comparisons a segment's
/// and a run's boxes take, in the hottest loops of a coverage's first round.
#[derive(Clone, Copy, Debug)]
struct Bbox {
    lo: [f64; 2],
    hi: [f64; 2],
}

impl Bbox {
    /// The box of the two corners.
    #[inline]
    fn of(a: Coord, b: Coord) -> Bbox {
        let min = |p: f64, q: f64| if p < q { p } else { q };
        let max = |p: f64, q: f64| if p > q { p } else { q };
        Bbox {
            lo: [min(a.x, b.x), min(a.y, b.y)],
            hi: [max(a.x, b.x), max(a.y, b.y)],
        }
    }

    /// Grows to hold `o` too.
    #[inline]
    fn merge(&mut self, o: &Bbox) {
        for k in 0..2 {
            if o.lo[k] < self.lo[k] {
                self.lo[k] = o.lo[k];
            }
            if o.hi[k] > self.hi[k] {
                self.hi[k] = o.hi[k];
            }
        }
    }
}

impl Run {
    /// The run of `lines` from segment `start` (a segment past the end of
    /// its line starts the run at the next line's first): its first [`RUN`]
    /// segments across the lines, in order, going on into a line only where
    /// it shares an end with the line before (an arc of the same ring, say):
    /// a run that jumped to a line elsewhere would take a box over both
    /// places and meet most of the tree. Empty past the last segment.
    fn gather(lines: &Arcs, dirty: &[bool], start: SegId) -> Run {
        let empty = Bbox {
            lo: [0.0; 2],
            hi: [0.0; 2],
        };
        let mut run = Run {
            len: 0,
            ids: [start; RUN],
            boxes: [empty; RUN],
            dirty: [false; RUN],
            env: empty,
        };
        // The end positions of the last line the run took segments from.
        let mut ends: Option<((u64, u64), (u64, u64))> = None;
        let mut first = start.seg as usize;
        for li in start.line as usize..lines.len() {
            let l = &lines[li];
            let n = l.len().saturating_sub(1);
            if first >= n {
                first = 0;
                continue;
            }
            let (a, b) = (key(l[0]), key(l[n]));
            if let Some((p, q)) = ends {
                if !(a == p || a == q || b == p || b == q) {
                    break;
                }
            }
            ends = Some((a, b));
            let take = (n - first).min(RUN - run.len);
            for (k, w) in l[first..=first + take].windows(2).enumerate() {
                let e = seg_env(w[0], w[1]);
                if run.len == 0 {
                    run.env = e;
                } else {
                    run.env.merge(&e);
                }
                run.ids[run.len] = SegId {
                    line: li as u32,
                    seg: (first + k) as u32,
                };
                run.boxes[run.len] = e;
                run.dirty[run.len] = dirty[li];
                run.len += 1;
            }
            if run.len == RUN {
                break;
            }
            first = 0;
        }
        run
    }

    /// The run holds a segment of a line in `dirty`.
    fn any_dirty(&self) -> bool {
        self.dirty[..self.len].contains(&true)
    }

    /// The first segment.
    fn start(&self) -> SegId {
        self.ids[0]
    }

    /// The segment after the last, as [`Run::gather`] takes it.
    fn next(&self) -> SegId {
        let last = self.ids[self.len - 1];
        SegId {
            line: last.line,
            seg: last.seg + 1,
        }
    }

    /// The run's box in single precision, rounded outward so that it holds
    /// the exact box: the tree may offer a few runs more than meet, never
    /// fewer.
    fn env32(&self) -> (f32, f32, f32, f32) {
        let (l, u) = (self.env.lo, self.env.hi);
        f64_box_to_f32(l[0], l[1], u[0], u[1])
    }
}

/// Runs of segments in a packed (Hilbert-sorted, immutable) R-tree of their
/// boxes in single precision: 20 bytes a run where a dynamic tree of double
/// boxes takes over 100, and the first round of a large coverage indexes
/// every run of its output.
struct Runs {
    tree: RTree<f32>,
    /// The first segment of each run, in the order they were added (the
    /// tree's item numbers).
    ids: Vec<SegId>,
}

impl Runs {
    fn new(runs: impl Iterator<Item = Run>, count: usize) -> Runs {
        // Lines are numbered in u32 and a run holds several positions, so
        // the count of runs fits.
        let mut builder = RTreeBuilder::<f32>::new(count as u32);
        let mut ids = Vec::with_capacity(count);
        for r in runs {
            let (x0, y0, x1, y1) = r.env32();
            builder.add(x0, y0, x1, y1);
            ids.push(r.start());
        }
        Runs {
            tree: builder.finish::<HilbertSort>(),
            ids,
        }
    }
}

#[inline]
fn seg_env(a: Coord, b: Coord) -> Bbox {
    Bbox::of(a, b)
}

#[inline]
fn boxes_meet(p: &Bbox, q: &Bbox) -> bool {
    let (pl, pu, ql, qu) = (p.lo, p.hi, q.lo, q.hi);
    pl[0] <= qu[0] && ql[0] <= pu[0] && pl[1] <= qu[1] && ql[1] <= pu[1]
}

/// The power of two that brings a largest magnitude `m` near 1 when
/// products of numbers that large would overflow a double, or of numbers
/// that small underflow (outside `2^-400 ..= 2^400`); 1 otherwise.
/// Multiplying by it is exact and changes no sign, so predicates on scaled
/// positions decide as they would in exact arithmetic.
pub(crate) fn unit_scale(m: f64) -> f64 {
    let safe = 2f64.powi(-400)..=2f64.powi(400);
    if !m.is_finite() || m <= 0.0 || safe.contains(&m) {
        return 1.0;
    }
    let e = m.log2().floor() as i32;
    2f64.powi(-e.clamp(-1022, 1022))
}

/// The largest magnitude of the positions' coordinates.
fn largest(ps: &[Coord]) -> f64 {
    ps.iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()))
}

/// `p` times `s`.
fn times(p: Coord, s: f64) -> Coord {
    Coord {
        x: p.x * s,
        y: p.y * s,
    }
}

/// The positions scaled by [`unit_scale`] of their largest coordinate.
fn scaled<const N: usize>(ps: [Coord; N]) -> [Coord; N] {
    let s = unit_scale(largest(&ps));
    if s == 1.0 {
        return ps;
    }
    ps.map(|p| times(p, s))
}

/// The orientation of `c` to the line `a b` (positive to the left), exact at
/// any scale (see [`unit_scale`]).
pub(crate) fn orient_at_any_scale(a: Coord, b: Coord, c: Coord) -> f64 {
    let [a, b, c] = scaled([a, b, c]);
    orient(a, b, c)
}

/// The orientation of `c` to the line `a b` (positive to the left), exact
/// where the products of coordinate differences neither underflow nor
/// overflow (callers scale first, [`scaled`]).
fn orient(a: Coord, b: Coord, c: Coord) -> f64 {
    orient2d(
        RCoord { x: a.x, y: a.y },
        RCoord { x: b.x, y: b.y },
        RCoord { x: c.x, y: c.y },
    )
}

/// `c`, known to be on the line through `a b`, lies within the segment.
fn within(a: Coord, b: Coord, c: Coord) -> bool {
    c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
}

/// The closed segments `a0 a1` and `b0 b1` have a point in common.
pub(crate) fn intersect(a0: Coord, a1: Coord, b0: Coord, b1: Coord) -> bool {
    let d1 = orient(a0, a1, b0);
    let d2 = orient(a0, a1, b1);
    let d3 = orient(b0, b1, a0);
    let d4 = orient(b0, b1, a1);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && within(a0, a1, b0))
        || (d2 == 0.0 && within(a0, a1, b1))
        || (d3 == 0.0 && within(b0, b1, a0))
        || (d4 == 0.0 && within(b0, b1, a1))
}

/// Segments `a0 a1` and `b0 b1` that share the end `e` (with `a`, `b` their
/// other ends) have more than `e` in common: they leave `e` in one direction.
fn overlap_from(e: Coord, a: Coord, b: Coord) -> bool {
    orient(e, a, b) == 0.0 && (a.x - e.x) * (b.x - e.x) + (a.y - e.y) * (b.y - e.y) > 0.0
}

/// The polylines and the positions where they may meet.
pub(crate) struct Lines<'a> {
    pub lines: &'a Arcs,
    /// A closed polyline's last segment is followed by its first.
    pub closed: &'a [bool],
    /// A polyline whose ends are no nodes (a closed curve); every other
    /// polyline's two ends are nodes.
    pub curve: &'a [bool],
    /// The keys of the nodes beyond the polylines' ends, sorted.
    pub nodes: &'a [(u64, u64)],
}

impl Lines<'_> {
    /// `e` is an end of `id`'s polyline, and that end is a node.
    fn node_end(&self, id: SegId, e: Coord) -> bool {
        let l = id.line as usize;
        !self.curve[l] && {
            let line = &self.lines[l];
            key(e) == key(line[0]) || key(e) == key(line[line.len() - 1])
        }
    }

    fn seg(&self, id: SegId) -> (Coord, Coord) {
        let l = &self.lines[id.line as usize];
        (l[id.seg as usize], l[id.seg as usize + 1])
    }

    /// The segments meet where they should not.
    pub(crate) fn conflict(&self, p: SegId, q: SegId) -> bool {
        if p == q {
            return false;
        }
        let (a0, a1) = self.seg(p);
        let (b0, b1) = self.seg(q);
        let consecutive = p.line == q.line && {
            let n = self.lines[p.line as usize].len() as u32 - 1;
            let (i, j) = (p.seg.min(q.seg), p.seg.max(q.seg));
            j == i + 1 || (self.closed[p.line as usize] && i == 0 && j + 1 == n)
        };
        // Each end the segments share, with the other end of each (no
        // vector: this runs for every pair of segments whose boxes meet).
        let mut shared = [(a0, a1, b1); 4];
        let mut n = 0;
        for (ea, oa) in [(a0, a1), (a1, a0)] {
            for (eb, ob) in [(b0, b1), (b1, b0)] {
                if key(ea) == key(eb) {
                    shared[n] = (ea, oa, ob);
                    n += 1;
                }
            }
        }
        let shared = &shared[..n];
        // The predicates run on the four positions scaled alike by one power
        // of two ([`unit_scale`]: exact, equal positions stay equal).
        let s = unit_scale(largest(&[a0, a1, b0, b1]));
        let at = |c: Coord| if s == 1.0 { c } else { times(c, s) };
        match shared {
            [] => intersect(at(a0), at(a1), at(b0), at(b1)),
            [(e, oa, ob)] => {
                let may_meet = consecutive
                    || self.node_end(p, *e)
                    || self.node_end(q, *e)
                    || self.nodes.binary_search(&key(*e)).is_ok();
                if !may_meet {
                    return true;
                }
                let (a0, a1, b0, b1) = (at(a0), at(a1), at(b0), at(b1));
                let (e, oa, ob) = (at(*e), at(*oa), at(*ob));
                overlap_from(e, oa, ob)
                    || (orient(a0, a1, ob) == 0.0 && within(a0, a1, ob))
                    || (orient(b0, b1, oa) == 0.0 && within(b0, b1, oa))
            }
            // The same segment twice.
            _ => true,
        }
    }

    /// Every run of segments, one at a time, each with whether it holds a
    /// segment of a line in `dirty`.
    fn runs<'s>(&'s self, dirty: &'s [bool]) -> impl Iterator<Item = Run> + 's {
        let lines = self.lines;
        let mut at = SegId { line: 0, seg: 0 };
        std::iter::from_fn(move || {
            let run = Run::gather(lines, dirty, at);
            if run.len == 0 {
                return None;
            }
            at = run.next();
            Some(run)
        })
    }

    /// Every conflicting pair with at least one segment on a line in `dirty`,
    /// each pair once, in order.
    ///
    /// When most lines are dirty, every run of segments is put in one tree and
    /// the dirty runs are looked up in it; when few are (a refinement round),
    /// the tree holds only the dirty runs and every run is looked up in that,
    /// which is much cheaper than building the whole tree again. A run is
    /// dirty when it holds a segment of a dirty line.
    pub(crate) fn conflicts(&self, dirty: &[bool]) -> Vec<(SegId, SegId)> {
        let total: usize = self.lines.iter().map(|l| l.len().saturating_sub(1)).sum();
        let changed: usize = self
            .lines
            .iter()
            .zip(dirty)
            .filter(|(_, &d)| d)
            .map(|(l, _)| l.len().saturating_sub(1))
            .sum();
        let few = changed * 8 < total;
        // Runs end where lines part, so they are counted.
        let count = self.runs(dirty).filter(|r| !few || r.any_dirty()).count();
        let runs = Runs::new(self.runs(dirty).filter(|r| !few || r.any_dirty()), count);
        let mut out = Vec::new();
        for p in self.runs(dirty).filter(|r| few || r.any_dirty()) {
            let (x0, y0, x1, y1) = p.env32();
            for i in runs.tree.search(x0, y0, x1, y1) {
                let start = runs.ids[i as usize];
                let q = Run::gather(self.lines, dirty, start);
                // Both dirty: the pair of runs is met from both sides.
                if p.any_dirty() && q.any_dirty() && start < p.start() {
                    continue;
                }
                self.run_conflicts(&p, &q, &mut out);
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The conflicting pairs of segments of two runs with at least one
    /// segment on a dirty line.
    fn run_conflicts(&self, p: &Run, q: &Run, out: &mut Vec<(SegId, SegId)>) {
        for i in 0..p.len {
            let ep = &p.boxes[i];
            if !boxes_meet(ep, &q.env) {
                continue;
            }
            for j in 0..q.len {
                if !(p.dirty[i] || q.dirty[j]) || !boxes_meet(ep, &q.boxes[j]) {
                    continue;
                }
                let (a, b) = (p.ids[i], q.ids[j]);
                if self.conflict(a, b) {
                    out.push((a.min(b), a.max(b)));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(x: f64, y: f64) -> Coord {
        Coord { x, y }
    }

    #[test]
    fn segment_intersection_cases() {
        let o = c(0.0, 0.0);
        assert!(intersect(o, c(2.0, 2.0), c(0.0, 2.0), c(2.0, 0.0)));
        assert!(!intersect(o, c(1.0, 1.0), c(0.0, 2.0), c(0.9, 1.2)));
        // Touching at an end, collinear overlap, collinear apart.
        assert!(intersect(o, c(2.0, 0.0), c(1.0, 0.0), c(1.0, 5.0)));
        assert!(intersect(o, c(2.0, 0.0), c(1.0, 0.0), c(3.0, 0.0)));
        assert!(!intersect(o, c(1.0, 0.0), c(2.0, 0.0), c(3.0, 0.0)));
    }

    #[test]
    fn meeting_at_nodes_and_consecutive_segments_is_allowed() {
        let lines = Arcs::from(vec![
            vec![c(0.0, 0.0), c(1.0, 0.0), c(2.0, 1.0)],
            vec![c(0.0, 0.0), c(0.0, 1.0)],
            vec![c(1.0, 0.0), c(1.0, -1.0)],
        ]);
        let mut nodes = Vec::new();
        for l in lines.iter().take(2) {
            nodes.push(key(l[0]));
            nodes.push(key(l[l.len() - 1]));
        }
        nodes.sort_unstable();
        let closed = vec![false; 3];
        // Line 2's ends are no nodes (as a closed curve's are not).
        let curve = [false, false, true];
        let set = Lines {
            lines: &lines,
            closed: &closed,
            curve: &curve,
            nodes: &nodes,
        };
        // Line 2 starts at an interior position of line 0 that is no node.
        assert_eq!(
            set.conflicts(&[true, true, true]),
            vec![
                (SegId { line: 0, seg: 0 }, SegId { line: 2, seg: 0 }),
                (SegId { line: 0, seg: 1 }, SegId { line: 2, seg: 0 })
            ]
        );
        nodes.push(key(c(1.0, 0.0)));
        nodes.sort_unstable();
        let set = Lines {
            lines: &lines,
            closed: &closed,
            curve: &curve,
            nodes: &nodes,
        };
        assert!(set.conflicts(&[true, true, true]).is_empty());
        // So they may when line 2's ends are nodes, with none listed.
        let set = Lines {
            lines: &lines,
            closed: &closed,
            curve: &[false; 3],
            nodes: &[],
        };
        assert!(set.conflicts(&[true, true, true]).is_empty());
    }

    #[test]
    fn an_overlap_at_a_node_conflicts() {
        let lines = Arcs::from(vec![
            vec![c(0.0, 0.0), c(2.0, 0.0)],
            vec![c(0.0, 0.0), c(1.0, 0.0), c(1.0, 1.0)],
        ]);
        let nodes = [key(c(0.0, 0.0))];
        let set = Lines {
            lines: &lines,
            closed: &[false, false],
            curve: &[false, false],
            nodes: &nodes,
        };
        assert_eq!(set.conflicts(&[true, false]).len(), 2);
    }

    /// Every pair of segments judged one by one, with no index.
    fn brute_force(set: &Lines, dirty: &[bool]) -> Vec<(SegId, SegId)> {
        let segs: Vec<SegId> = (set.lines.iter().enumerate())
            .flat_map(|(li, l)| {
                (0..l.len().saturating_sub(1)).map(move |s| SegId {
                    line: li as u32,
                    seg: s as u32,
                })
            })
            .collect();
        let mut out = Vec::new();
        for (i, &p) in segs.iter().enumerate() {
            for &q in &segs[i + 1..] {
                let any_dirty = dirty[p.line as usize] || dirty[q.line as usize];
                if any_dirty && set.conflict(p, q) {
                    out.push((p.min(q), p.max(q)));
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// A run goes on into the next line only where that line shares an
    /// end with the line before; it holds [`RUN`] segments unless a line
    /// that does not meet it, or the last segment, comes first.
    #[test]
    fn runs_go_on_only_into_lines_that_meet() {
        let mut rng = bzspline_testing::Rng(11);
        let mut next = move || rng.next();
        for case in 0..40 {
            let mut lines: Vec<Vec<Coord>> = Vec::new();
            for _ in 0..5 + case % 17 {
                let joined = lines.last().and_then(|l| l.last().copied());
                let mut p = match joined {
                    Some(e) if next() < 0.5 => e,
                    _ => c(next() * 1e3, next() * 1e3),
                };
                let mut line = vec![p];
                for _ in 0..(next() * 6.0) as usize {
                    p = c(p.x + next(), p.y + next());
                    line.push(p);
                }
                lines.push(line);
            }
            let lines = Arcs::from(lines);
            let none = vec![false; lines.len()];
            let set = Lines {
                lines: &lines,
                closed: &none,
                curve: &none,
                nodes: &[],
            };
            let meet = |a: usize, b: usize| {
                let (p, q) = (&lines[a], &lines[b]);
                let ends = |l: &[Coord]| [key(l[0]), key(l[l.len() - 1])];
                ends(p).iter().any(|e| ends(q).contains(e))
            };
            let mut seen = 0;
            for run in set.runs(&none) {
                let ids = &run.ids[..run.len];
                seen += ids.len();
                for w in ids.windows(2) {
                    if w[0].line != w[1].line {
                        assert!(meet(w[0].line as usize, w[1].line as usize), "case {case}");
                    }
                }
                let after = segs_after(&lines, run.ids[run.len - 1]);
                if run.len < RUN {
                    // Stopped by a line that does not meet it, or the end.
                    if let Some(s) = after {
                        assert!(!meet(run.ids[run.len - 1].line as usize, s.line as usize));
                    }
                }
            }
            let total: usize = lines.iter().map(|l| l.len() - 1).sum();
            assert_eq!(seen, total, "case {case}: every segment in one run");
        }
    }

    /// The segment after `id` across the lines, if any.
    fn segs_after(lines: &Arcs, id: SegId) -> Option<SegId> {
        let (mut li, mut seg) = (id.line as usize, id.seg as usize + 1);
        while li < lines.len() {
            if seg + 1 < lines[li].len() {
                return Some(SegId {
                    line: li as u32,
                    seg: seg as u32,
                });
            }
            li += 1;
            seg = 0;
        }
        None
    }

    #[test]
    fn the_index_finds_what_brute_force_finds_below_single_precision() {
        // Polylines far from the origin (where a single-precision box is
        // about 1 unit coarse) with steps of a thousandth of that: the
        // index's rounded boxes must still offer every pair that meets.
        // Every other case has short lines (a run of the tree then spans
        // several, where they meet), and the dirty lines are all, one, or a
        // random third. Lines start or end where the line before ends (as
        // a ring's arcs do) or anywhere.
        let mut rng = bzspline_testing::Rng(7);
        let mut next = move || rng.next();
        for case in 0..60 {
            let (ox, oy) = (1.0e7 + next(), -3.0e6 - next());
            let step = if case % 3 == 0 { 1e-3 } else { 0.3 };
            let longest = if case % 2 == 0 { 30.0 } else { 4.0 };
            let count = 12 + case % 13;
            let mut lines: Vec<Vec<Coord>> = Vec::new();
            for _ in 0..count {
                let joined = lines.last().and_then(|l| l.last().copied());
                let how = next();
                let mut p = match joined {
                    Some(e) if how < 0.6 => e,
                    _ => c(ox + next() * 40.0 * step, oy + next() * 40.0 * step),
                };
                let mut line = vec![p];
                for _ in 0..(next() * longest) as usize {
                    p = c(
                        p.x + (next() - 0.5) * step * 8.0,
                        p.y + (next() - 0.5) * step * 8.0,
                    );
                    line.push(p);
                }
                if how < 0.25 {
                    line.reverse();
                }
                lines.push(line);
            }
            let lines = Arcs::from(lines);
            let closed = vec![false; lines.len()];
            let nodes = [];
            let set = Lines {
                lines: &lines,
                closed: &closed,
                curve: &closed,
                nodes: &nodes,
            };
            let some: Vec<bool> = (0..count).map(|_| next() < 0.33).collect();
            for dirty in [
                vec![true; count],
                (0..count).map(|i| i == case % count).collect(),
                some,
            ] {
                let found = set.conflicts(&dirty);
                assert!(case > 0 || !found.is_empty(), "the cases meet somewhere");
                assert_eq!(found, brute_force(&set, &dirty), "case {case}");
            }
        }
    }
}
