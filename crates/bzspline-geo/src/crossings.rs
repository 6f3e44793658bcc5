//! Where polylines meet where they should not: pairs of segments that cross,
//! touch or overlap, found through an R-tree of the segments' boxes and
//! decided with exact orientation predicates.
//!
//! Two segments may share an end position only where the polylines are meant
//! to meet: consecutive segments of one polyline, and *nodes* (the ends of
//! arcs, and positions fixed because several arcs or several places of one
//! arc hold them). Even there they conflict when they run on from the shared
//! position in the same direction (an overlap).

use std::collections::HashSet;

use geo_types::Coord;
use robust::{orient2d, Coord as RCoord};
use rstar::{RTree, RTreeObject, AABB};

/// A segment of polyline `line`, from its position `seg` to `seg + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) struct SegId {
    pub line: u32,
    pub seg: u32,
}

struct Item {
    id: SegId,
    a: Coord,
    b: Coord,
}

impl RTreeObject for Item {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        AABB::from_corners([self.a.x, self.a.y], [self.b.x, self.b.y])
    }
}

pub(crate) fn key(c: Coord) -> (u64, u64) {
    ((c.x + 0.0).to_bits(), (c.y + 0.0).to_bits())
}

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
    pub lines: &'a [Vec<Coord>],
    /// A closed polyline's last segment is followed by its first.
    pub closed: &'a [bool],
    pub nodes: &'a HashSet<(u64, u64)>,
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
        match shared.as_slice() {
            [] => intersect(a0, a1, b0, b1),
            [(e, oa, ob)] => {
                let may_meet = consecutive || self.nodes.contains(&key(*e));
                if !may_meet {
                    return true;
                }
                overlap_from(*e, *oa, *ob)
                    || (orient(a0, a1, *ob) == 0.0 && within(a0, a1, *ob))
                    || (orient(b0, b1, *oa) == 0.0 && within(b0, b1, *oa))
            }
            // The same segment twice.
            _ => true,
        }
    }

    /// Every conflicting pair with at least one segment on a line in `dirty`,
    /// each pair once, in order.
    pub(crate) fn conflicts(&self, dirty: &[bool]) -> Vec<(SegId, SegId)> {
        let items: Vec<Item> = self
            .lines
            .iter()
            .enumerate()
            .flat_map(|(li, l)| {
                l.windows(2).enumerate().map(move |(si, w)| Item {
                    id: SegId {
                        line: li as u32,
                        seg: si as u32,
                    },
                    a: w[0],
                    b: w[1],
                })
            })
            .collect();
        let tree = RTree::bulk_load(items);
        let mut out = Vec::new();
        for (li, l) in self.lines.iter().enumerate() {
            if !dirty[li] {
                continue;
            }
            for (si, w) in l.windows(2).enumerate() {
                let p = SegId {
                    line: li as u32,
                    seg: si as u32,
                };
                let env = AABB::from_corners([w[0].x, w[0].y], [w[1].x, w[1].y]);
                for it in tree.locate_in_envelope_intersecting(&env) {
                    let q = it.id;
                    // A pair of two dirty lines is seen from both: keep one.
                    if dirty[q.line as usize] && q < p {
                        continue;
                    }
                    if self.conflict(p, q) {
                        out.push((p, q));
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
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
        let lines = vec![
            vec![c(0.0, 0.0), c(1.0, 0.0), c(2.0, 1.0)],
            vec![c(0.0, 0.0), c(0.0, 1.0)],
            vec![c(1.0, 0.0), c(1.0, -1.0)],
        ];
        let mut nodes = HashSet::new();
        for l in &lines[..2] {
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
        let lines = vec![
            vec![c(0.0, 0.0), c(2.0, 0.0)],
            vec![c(0.0, 0.0), c(1.0, 0.0), c(1.0, 1.0)],
        ];
        let nodes: HashSet<_> = [key(c(0.0, 0.0))].into_iter().collect();
        let set = Lines {
            lines: &lines,
            closed: &[false, false],
            nodes: &nodes,
        };
        assert_eq!(set.conflicts(&[true, false]).len(), 2);
    }
}
