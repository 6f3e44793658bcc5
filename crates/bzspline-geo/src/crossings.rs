//! Where polylines meet where they should not: pairs of segments that cross,
//! touch or overlap, found through a packed R-tree of the boxes of runs of
//! segments and decided with exact orientation predicates.
//!
//! Two segments may share an end position only where the polylines are meant
//! to meet: consecutive segments of one polyline, and *nodes* (the ends of
//! arcs, and positions fixed because several arcs or several places of one
//! arc hold them). Even there they conflict when they run on from the shared
//! position in the same direction (an overlap).

use rustc_hash::FxHashSet;

use geo_types::Coord;
use robust::{orient2d, Coord as RCoord};

use crate::arcs::Arcs;
use crate::graph::key;
use geo_index::rtree::sort::HilbertSort;
use geo_index::rtree::util::f64_box_to_f32;
use geo_index::rtree::{RTree, RTreeBuilder, RTreeIndex};
use rstar::{Envelope, AABB};

/// A segment of polyline `line`, from its position `seg` to `seg + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) struct SegId {
    pub line: u32,
    pub seg: u32,
}

/// Segments in one tree entry: a run of consecutive segments of one line
/// under one box, so that the tree holds a fraction of the segments.
const RUN: usize = 8;

/// A run of up to [`RUN`] segments of line `line`, from segment `first`.
struct Item {
    line: u32,
    first: u32,
    count: u32,
    env: AABB<[f64; 2]>,
}

impl Item {
    /// The run of `line` (its positions `l`) from segment `first`.
    fn of(line: usize, l: &[Coord], first: usize) -> Item {
        let count = RUN.min(l.len() - 1 - first);
        let mut env = seg_env(l[first], l[first + 1]);
        for c in &l[first + 2..=first + count] {
            env.merge(&AABB::from_point([c.x, c.y]));
        }
        Item {
            line: line as u32,
            first: first as u32,
            count: count as u32,
            env,
        }
    }

    /// The run's box in single precision, rounded outward so that it holds
    /// the exact box: the tree may offer a few runs more than meet, never
    /// fewer.
    fn env32(&self) -> (f32, f32, f32, f32) {
        let (l, u) = (self.env.lower(), self.env.upper());
        f64_box_to_f32(l[0], l[1], u[0], u[1])
    }
}

/// Runs of segments in a packed (Hilbert-sorted, immutable) R-tree of their
/// boxes in single precision: 20 bytes a run where a dynamic tree of double
/// boxes takes over 100, and the first round of a large coverage indexes
/// every run of its output.
struct Runs {
    tree: RTree<f32>,
    /// The line and first segment of each run, in the order they were added
    /// (the tree's item numbers).
    ids: Vec<(u32, u32)>,
}

impl Runs {
    fn new(runs: impl Iterator<Item = Item>, count: usize) -> Runs {
        // Lines are numbered in u32 and a run holds several positions, so
        // the count of runs fits.
        let mut builder = RTreeBuilder::<f32>::new(count as u32);
        let mut ids = Vec::with_capacity(count);
        for r in runs {
            let (x0, y0, x1, y1) = r.env32();
            builder.add(x0, y0, x1, y1);
            ids.push((r.line, r.first));
        }
        Runs {
            tree: builder.finish::<HilbertSort>(),
            ids,
        }
    }
}

fn seg_env(a: Coord, b: Coord) -> AABB<[f64; 2]> {
    AABB::from_corners([a.x, a.y], [b.x, b.y])
}

fn boxes_meet(p: &AABB<[f64; 2]>, q: &AABB<[f64; 2]>) -> bool {
    let (pl, pu, ql, qu) = (p.lower(), p.upper(), q.lower(), q.upper());
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
    pub nodes: &'a FxHashSet<(u64, u64)>,
}

impl Lines<'_> {
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
        let shared: Vec<(Coord, Coord, Coord)> = [(a0, a1), (a1, a0)]
            .into_iter()
            .flat_map(|(ea, oa)| {
                [(b0, b1), (b1, b0)]
                    .into_iter()
                    .filter(move |&(eb, _)| key(ea) == key(eb))
                    .map(move |(_, ob)| (ea, oa, ob))
            })
            .collect();
        // The predicates run on the four positions scaled alike by one power
        // of two ([`unit_scale`]: exact, equal positions stay equal).
        let s = unit_scale(largest(&[a0, a1, b0, b1]));
        let at = |c: Coord| if s == 1.0 { c } else { times(c, s) };
        match shared.as_slice() {
            [] => intersect(at(a0), at(a1), at(b0), at(b1)),
            [(e, oa, ob)] => {
                let may_meet = consecutive || self.nodes.contains(&key(*e));
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

    /// The runs of segments of the lines `keep` selects, one at a time.
    fn runs<'s>(&'s self, keep: impl Fn(usize) -> bool + 's) -> impl Iterator<Item = Item> + 's {
        self.lines
            .iter()
            .enumerate()
            .filter(move |(li, l)| keep(*li) && l.len() >= 2)
            .flat_map(|(li, l)| {
                (0..l.len() - 1)
                    .step_by(RUN)
                    .map(move |f| Item::of(li, l, f))
            })
    }

    /// The runs of the lines `keep` selects, in a packed tree.
    fn index(&self, keep: impl Fn(usize) -> bool + Copy) -> Runs {
        let count = (self.lines.iter().enumerate())
            .filter(|(li, l)| keep(*li) && l.len() >= 2)
            .map(|(_, l)| (l.len() - 1).div_ceil(RUN))
            .sum();
        Runs::new(self.runs(keep), count)
    }

    /// Every conflicting pair with at least one segment on a line in `dirty`,
    /// each pair once, in order.
    ///
    /// When most lines are dirty, every run of segments is put in one tree and
    /// the dirty runs are looked up in it; when few are (a refinement round),
    /// the tree holds only the dirty runs and every run is looked up in that,
    /// which is much cheaper than building the whole tree again.
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
        let runs = self.index(|li| !few || dirty[li]);
        let mut out = Vec::new();
        for p in self.runs(|li| few || dirty[li]) {
            let (x0, y0, x1, y1) = p.env32();
            for i in runs.tree.search(x0, y0, x1, y1) {
                let (line, first) = runs.ids[i as usize];
                // Both on dirty lines: the pair of runs is met from both sides.
                if dirty[p.line as usize]
                    && dirty[line as usize]
                    && (line, first) < (p.line, p.first)
                {
                    continue;
                }
                let q = Item::of(line as usize, &self.lines[line as usize], first as usize);
                self.run_conflicts(&p, &q, &mut out);
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The conflicting pairs of segments of two runs.
    fn run_conflicts(&self, p: &Item, q: &Item, out: &mut Vec<(SegId, SegId)>) {
        let (lp, lq) = (&self.lines[p.line as usize], &self.lines[q.line as usize]);
        for i in p.first..p.first + p.count {
            let ep = seg_env(lp[i as usize], lp[i as usize + 1]);
            if !boxes_meet(&ep, &q.env) {
                continue;
            }
            for j in q.first..q.first + q.count {
                let eq = seg_env(lq[j as usize], lq[j as usize + 1]);
                if !boxes_meet(&ep, &eq) {
                    continue;
                }
                let a = SegId {
                    line: p.line,
                    seg: i,
                };
                let b = SegId {
                    line: q.line,
                    seg: j,
                };
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
        let mut nodes = FxHashSet::default();
        for l in lines.iter().take(2) {
            nodes.insert(key(l[0]));
            nodes.insert(key(l[l.len() - 1]));
        }
        let closed = vec![false; 3];
        let set = Lines {
            lines: &lines,
            closed: &closed,
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
        nodes.insert(key(c(1.0, 0.0)));
        let set = Lines {
            lines: &lines,
            closed: &closed,
            nodes: &nodes,
        };
        assert!(set.conflicts(&[true, true, true]).is_empty());
    }

    #[test]
    fn an_overlap_at_a_node_conflicts() {
        let lines = Arcs::from(vec![
            vec![c(0.0, 0.0), c(2.0, 0.0)],
            vec![c(0.0, 0.0), c(1.0, 0.0), c(1.0, 1.0)],
        ]);
        let nodes: FxHashSet<_> = [key(c(0.0, 0.0))].into_iter().collect();
        let set = Lines {
            lines: &lines,
            closed: &[false, false],
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

    #[test]
    fn the_index_finds_what_brute_force_finds_below_single_precision() {
        // Polylines far from the origin (where a single-precision box is
        // about 1 unit coarse) with steps of a thousandth of that: the
        // index's rounded boxes must still offer every pair that meets.
        let mut rng = bzspline_testing::Rng(7);
        let mut next = move || rng.next();
        for case in 0..40 {
            let (ox, oy) = (1.0e7 + next(), -3.0e6 - next());
            let step = if case % 2 == 0 { 1e-3 } else { 0.3 };
            let lines: Arcs = (0..12)
                .map(|_| {
                    let mut p = c(ox + next() * 40.0 * step, oy + next() * 40.0 * step);
                    (0..1 + (next() * 30.0) as usize)
                        .map(|_| {
                            p = c(
                                p.x + (next() - 0.5) * step * 8.0,
                                p.y + (next() - 0.5) * step * 8.0,
                            );
                            p
                        })
                        .collect::<Vec<_>>()
                })
                .collect();
            let closed = vec![false; lines.len()];
            let nodes = FxHashSet::default();
            let set = Lines {
                lines: &lines,
                closed: &closed,
                nodes: &nodes,
            };
            for dirty in [vec![true; 12], (0..12).map(|i| i == case % 12).collect()] {
                let found = set.conflicts(&dirty);
                assert!(case > 0 || !found.is_empty(), "the cases meet somewhere");
                assert_eq!(found, brute_force(&set, &dirty), "case {case}");
            }
        }
    }
}
