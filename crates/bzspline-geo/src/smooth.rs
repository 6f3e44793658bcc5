//! Smoothing a topology: the options, every arc once, the rounds of the
//! conflict search (the crate docs say how); one arc's smoothing in
//! [`arc`], the checks of rings in [`rings`].

use geo_types::{Coord, Rect};
use std::hash::BuildHasher;

use std::collections::hash_map::Entry;

use rustc_hash::{FxBuildHasher, FxHashMap, FxHashSet};

use crate::arcs::Arcs;
use crate::crossings::{Lines, SegId};
use crate::error::Error;
use crate::graph::key;
use crate::levels::{arc_key, Levels};
use crate::options::{default_tolerance_of, Frame, SmoothOptions};
use crate::topology::{ChainKind, Topology};

mod arc;
mod legs;
mod rings;

pub(crate) use arc::turning_degrees;
use arc::{distinct, is_closed, smooth_arc, Along, Plans, Seg, Smoothing};
use legs::Legs;
use rings::{holes_inside, RingFacts, Shoelace, NO_POLYGON};

/// The most times a leg is halved to resolve a conflict (into `2^MAX_LEVEL`
/// parts); one more conflict keeps the leg as the original edge.
pub const MAX_LEVEL: u8 = 5;

/// A leg kept as the original edge.
const STRAIGHT: u8 = MAX_LEVEL + 1;

/// Rounds of refinement after which every leg still in conflict is kept as
/// its original edge at once.
const MAX_ROUNDS: usize = 3 * MAX_LEVEL as usize;

/// What smoothing did.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Stats {
    /// Lines in the topology.
    pub lines: usize,
    /// Rings in the topology.
    pub rings: usize,
    /// Arcs.
    pub arcs: usize,
    /// Arcs used by two or more lines and rings (shared borders).
    pub shared_arcs: usize,
    /// Arcs smoothed as closed curves.
    pub closed_arcs: usize,
    /// Positions of all lines and rings before.
    pub positions_in: usize,
    /// Positions of all lines and rings after.
    pub positions_out: usize,
    /// Legs cut into parts to resolve a conflict.
    pub refined_legs: usize,
    /// Legs kept as their original edge, the last resort.
    pub straight_legs: usize,
    /// Rounds of conflict search (1 when nothing needed refining).
    pub rounds: usize,
    /// Pairs of original edges that already crossed or touched in the input,
    /// left as they were.
    pub input_conflicts: usize,
    /// Pieces whose curve could not be built (kept as they were).
    pub kept_pieces: usize,
    /// Area of the polygons before (shells less holes).
    pub area_in: f64,
    /// Area of the polygons after.
    pub area_out: f64,
    /// The tolerance used.
    pub tolerance: f64,
}

/// Totals over several smoothings (the documents of a file, the lines of
/// newline-delimited input): counts and areas add up, `rounds` is the most
/// any took, `tolerance` the last one's.
impl core::ops::AddAssign<&Stats> for Stats {
    fn add_assign(&mut self, s: &Stats) {
        self.lines += s.lines;
        self.rings += s.rings;
        self.arcs += s.arcs;
        self.shared_arcs += s.shared_arcs;
        self.closed_arcs += s.closed_arcs;
        self.positions_in += s.positions_in;
        self.positions_out += s.positions_out;
        self.refined_legs += s.refined_legs;
        self.straight_legs += s.straight_legs;
        self.rounds = self.rounds.max(s.rounds);
        self.input_conflicts += s.input_conflicts;
        self.kept_pieces += s.kept_pieces;
        self.area_in += s.area_in;
        self.area_out += s.area_out;
        self.tolerance = s.tolerance;
    }
}

/// Smoothed arcs, with the same indices as the topology's.
#[derive(Clone, Debug, PartialEq)]
pub struct Smoothed {
    /// Each arc's smoothed positions.
    pub arcs: Arcs,
    /// What was done.
    pub stats: Stats,
    /// The levels each refined arc ended at ([`Topology::smooth_from`]).
    pub levels: Levels,
}

impl Topology {
    /// Smooths every arc once (see the [crate docs](crate#smoothing)); shared
    /// borders come out identical for every line and ring that uses them.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] for options out of range; [`Error::Overflow`]
    /// when a smoothed arc leaves the range of a double; [`Error::Spline`]
    /// when the tolerance asks for more vertices than a flattening may have.
    pub fn smooth(&self, opts: &SmoothOptions) -> Result<Smoothed, Error> {
        self.smooth_from(opts, &Levels::default())
    }

    /// As [`Topology::smooth`], with every arc that `start` lists refined at
    /// least to its levels there from the first round on (by [`arc_key`]);
    /// [`Smoothed::levels`] gives the levels the arcs end at (parts of a
    /// coverage smoothed apart go round by round instead:
    /// [`Topology::smooth_round`]).
    ///
    /// # Errors
    ///
    /// As [`Topology::smooth`].
    pub fn smooth_from(&self, opts: &SmoothOptions, start: &Levels) -> Result<Smoothed, Error> {
        self.smooth_rounds(opts, start, 1, false, &[])
    }

    /// One round of the conflict search of [`Topology::smooth_from`], as its
    /// `round`-th (counting from 1: from round `3 * MAX_LEVEL` on, a leg a
    /// conflict names is kept straight): every arc smoothed at its levels in
    /// `start`, the conflicts found, the legs they name raised.
    /// [`Smoothed::arcs`] are the arcs at `start`'s levels and
    /// [`Smoothed::levels`] the levels after the round; when these are
    /// `start`'s for every arc here, the round found nothing and the arcs are
    /// final.
    ///
    /// `exact` says, chain by chain, which chains this topology holds
    /// exactly, with every line and ring they share a position with (empty:
    /// all of them): conflicts are judged only between arcs of such chains,
    /// and rings turning over only for them.
    ///
    /// Parts of a coverage go through the rounds of the whole when each runs
    /// a round from the same levels and the levels they end at, merged
    /// ([`Levels::merge`]), start the next round for all, provided each
    /// part holds, with the whole's nodes, its own features and every
    /// feature of the other parts whose bounding box meets its extent
    /// (exactly), and the features whose bounding box meets the extent of
    /// all those (not exactly): every arc of its own features then comes out
    /// as one process smoothing the whole gives it, bit for bit.
    ///
    /// # Errors
    ///
    /// As [`Topology::smooth`].
    pub fn smooth_round(
        &self,
        opts: &SmoothOptions,
        start: &Levels,
        round: usize,
        exact: &[bool],
    ) -> Result<Smoothed, Error> {
        self.smooth_rounds(opts, start, round.max(1), true, exact)
    }

    /// The rounds of conflict search from `start`, the first counted as
    /// round `first`; only that one with `one`; conflicts judged for the
    /// chains `exact` marks (all when it is empty).
    fn smooth_rounds(
        &self,
        opts: &SmoothOptions,
        start: &Levels,
        first: usize,
        one: bool,
        exact: &[bool],
    ) -> Result<Smoothed, Error> {
        opts.validate()?;
        let arcs = self.arcs();
        let extent = self.nodes().extent();
        let tolerance = opts
            .tolerance
            .unwrap_or_else(|| opts.default_tolerance_from(default_tolerance(arcs, extent)));
        let mut stats = self.input_stats(tolerance);
        let (plans, nodes) = self.plans(opts.keep_angle, opts.frame);
        stats.closed_arcs = plans.closed_curve.iter().filter(|&&c| c).count();
        let closed: Vec<bool> = arcs.iter().map(is_closed).collect();

        let shoelace = Shoelace::about(arcs, extent);
        let cross_in: Vec<f64> = arcs.iter().map(|a| shoelace.arc(a)).collect();
        let rings = RingFacts::of(self, &shoelace, &cross_in);
        stats.area_in = shoelace.polygons(self, &|a| cross_in[a]);
        // Not needed again: freed before the rounds' peak.
        drop(cross_in);

        let mut levels = start_levels(arcs, start);
        // Every arc starts empty, so the first round lays the arcs out in
        // order, in blocks added as they fill (no room kept for as many
        // positions as the input's: smoothing may make fewer or many more).
        let mut out = Arcs::with_capacity(arcs.len(), 0);
        (0..arcs.len()).for_each(|_| out.push([]));
        let mut along = Along::new(arcs, &plans, opts, tolerance);
        let mut work = Smoothing::default();
        let mut dirty = vec![true; arcs.len()];
        let judged = self.judged(exact);
        let mut input_conflicts: FxHashSet<(SegId, SegId)> = FxHashSet::default();
        loop {
            stats.rounds += 1;
            for a in (0..arcs.len()).filter(|&a| dirty[a]) {
                let plan = plans.get(arcs, a);
                stats.kept_pieces += smooth_arc(
                    a,
                    &arcs[a],
                    plan,
                    levels.get(arcs, a),
                    opts,
                    tolerance,
                    &mut work,
                )?;
                out.set(a, &work.out);
            }
            input_conflicts.retain(|(p, q)| !dirty[p.line as usize] && !dirty[q.line as usize]);
            let lines = Lines {
                lines: &out,
                closed: &closed,
                curve: &plans.closed_curve,
                nodes: &nodes,
            };
            let mut bump: Vec<(usize, Seg)> = Vec::new();
            for (p, q) in lines.conflicts(&dirty) {
                if !(judged[p.line as usize] && judged[q.line as usize]) {
                    continue;
                }
                let sp = along.segs(p.line as usize, &levels)?[p.seg as usize];
                let sq = along.segs(q.line as usize, &levels)?[q.seg as usize];
                if sp.original && sq.original {
                    input_conflicts.insert((p, q));
                    continue;
                }
                for (id, s) in [(p, sp), (q, sq)] {
                    if !s.original {
                        bump.push((id.line as usize, s));
                    }
                }
            }
            let facts = (&rings, &shoelace, &out);
            self.ring_conflicts(&dirty, exact, facts, &mut along, &levels, &mut bump)?;
            dirty.iter_mut().for_each(|d| *d = false);
            if bump.is_empty() {
                break;
            }
            let last_resort = first - 1 + stats.rounds >= MAX_ROUNDS;
            raise(bump, arcs, &mut levels, &mut dirty, &closed, last_resort);
            along.clear();
            if one {
                break;
            }
        }
        stats.input_conflicts = input_conflicts.len();
        let count = |f: fn(u8) -> bool| -> usize {
            (levels.listed())
                .map(|(_, l)| l.iter().filter(|&&v| f(v)).count())
                .sum()
        };
        stats.refined_legs = count(|l| l > 0);
        stats.straight_legs = count(|l| l == STRAIGHT);
        stats.positions_out = self.positions(&out);
        stats.area_out = shoelace.polygons(self, &|a| shoelace.arc(&out[a]));
        let mut ended = Levels::default();
        for (a, l) in levels.listed() {
            if l.iter().any(|&v| v > 0) {
                ended.insert(arc_key(&arcs[a]), l.to_vec());
            }
        }
        Ok(Smoothed {
            arcs: out,
            stats,
            levels: ended,
        })
    }

    /// The counts of the input a smoothing reports, at `tolerance`.
    fn input_stats(&self, tolerance: f64) -> Stats {
        let arcs = self.arcs();
        let count = |kind: ChainKind| self.chains().iter().filter(|c| c.kind == kind).count();
        Stats {
            lines: count(ChainKind::Line),
            rings: count(ChainKind::Ring),
            arcs: arcs.len(),
            shared_arcs: self.uses().iter().filter(|&&u| u >= 2).count(),
            tolerance,
            positions_in: self.positions(arcs),
            ..Stats::default()
        }
    }

    /// The arcs whose conflicts are judged: those of the chains `exact`
    /// marks (every arc when it is empty).
    fn judged(&self, exact: &[bool]) -> Vec<bool> {
        let n = self.arcs().len();
        if exact.is_empty() {
            return vec![true; n];
        }
        let mut j = vec![false; n];
        for (c, _) in self.chains().iter().zip(exact).filter(|(_, &e)| e) {
            for r in c.arcs {
                j[r.index()] = true;
            }
        }
        j
    }

    /// Adds to `bump` every leg of the rings that turned over and of the
    /// holes (and their shells) that left their shell, among the rings that
    /// use a `dirty` arc (and that `exact` marks, unless it is empty).
    fn ring_conflicts(
        &self,
        dirty: &[bool],
        exact: &[bool],
        (rings, shoelace, out): (&RingFacts, &Shoelace, &Arcs),
        along: &mut Along<'_>,
        levels: &Legs,
        bump: &mut Vec<(usize, Seg)>,
    ) -> Result<(), Error> {
        // Marks rather than lists of indices: in the first round every arc
        // is dirty, and a list would hold each chain once per arc it uses.
        // Found by a pass over the chains' references, which costs less
        // than a round's smoothing and needs no table from arcs to chains.
        let suspect: Vec<bool> = (self.chains().iter().enumerate())
            .map(|(ci, c)| {
                exact.get(ci).copied().unwrap_or(exact.is_empty())
                    && c.arcs.iter().any(|r| dirty[r.index()])
            })
            .collect();
        let mut in_play = vec![false; self.polygons().len()];
        // Each arc's cross products summed again for each ring that uses it
        // (twice for a border) rather than held, 8 bytes an arc.
        let cross_out = |a: usize| shoelace.arc(&out[a]);
        for ci in (0..suspect.len()).filter(|&ci| suspect[ci]) {
            let sign = rings.sign_in[ci];
            if sign != 0 && shoelace.ring(self, ci, &cross_out).signum() != f64::from(sign) {
                bump_chain(self, ci, along, levels, bump)?;
            }
            if rings.polygon_of[ci] != NO_POLYGON {
                in_play[rings.polygon_of[ci] as usize] = true;
            }
        }
        drop(suspect);
        for p in (0..in_play.len()).filter(|&p| in_play[p]) {
            let members = &self.polygons()[p];
            let now = holes_inside(self, members, out);
            for (h, (&was, &is)) in rings.inside_in[p].iter().zip(&now).enumerate() {
                if was && !is {
                    bump_chain(self, members[0], along, levels, bump)?;
                    bump_chain(self, members[h + 1], along, levels, bump)?;
                }
            }
        }
        Ok(())
    }

    /// Positions of all chains assembled from `arcs` (joints once, rings
    /// closed).
    fn positions(&self, arcs: &Arcs) -> usize {
        self.chains()
            .iter()
            .map(|c| {
                c.arcs
                    .iter()
                    .map(|r| arcs[r.index()].len() - 1)
                    .sum::<usize>()
                    + 1
            })
            .sum()
    }

    /// Each arc's plan, and the nodes beyond the arcs' ends: positions
    /// where arcs may meet (keys, sorted, each once). Every arc's two ends
    /// are nodes, but a closed curve's.
    fn plans(&self, keep_angle: Option<f64>, frame: Frame) -> (Plans, Vec<(u64, u64)>) {
        let arcs = self.arcs();
        // The positions that occur twice or more over all arcs (a closed
        // arc's end once), marked where they are.
        let mut fixed = shared_positions(arcs);
        let mut in_line = vec![false; arcs.len()];
        let mut min_out = vec![2u8; arcs.len()];
        for c in self.chains() {
            for r in c.arcs {
                if c.kind == ChainKind::Line {
                    in_line[r.index()] = true;
                }
                let want: u8 = match (c.kind, c.arcs.len()) {
                    (ChainKind::Ring, 1) => 4,
                    (ChainKind::Ring, 2) => 3,
                    _ => 2,
                };
                let len = u8::try_from(arcs[r.index()].len()).unwrap_or(u8::MAX);
                min_out[r.index()] = min_out[r.index()].max(want.min(len));
            }
        }
        // The nodes within arcs: held as keys, where the ends are not (an
        // arc's positions are met there only in a degenerate coverage, or
        // when `keep_angle` fixes them).
        let mut nodes: Vec<(u64, u64)> = Vec::new();
        // A node: met by two arcs here, or by the whole coverage's (given).
        let given = self.nodes();
        let is_given = |c: Coord| !given.is_empty() && given.contains(c);
        let mut closed_curve = Vec::with_capacity(arcs.len());
        for (ai, a) in arcs.iter().enumerate() {
            let at = arcs.address(ai);
            let closed = is_closed(a);
            let n = distinct(a);
            // Arc `ai`'s marks so far are the shared positions only: no other
            // arc's positions have its addresses.
            let fixed = &mut fixed[at..at + n];
            let first_node = fixed[0] || is_given(a[0]) || in_line[ai];
            let curve = closed && !first_node && a.len() >= 4;
            let within = if closed { 1..n } else { 1..n.saturating_sub(1) };
            for i in within.filter(|&i| fixed[i]) {
                nodes.push(key(a[i]));
            }
            if !given.is_empty() {
                for (f, &c) in fixed.iter_mut().zip(a) {
                    *f |= given.contains(c);
                }
            }
            closed_curve.push(curve);
            if let Some(deg) = keep_angle {
                for i in 0..n {
                    let (prev, next) = match (closed, i) {
                        (true, _) => (a[(i + n - 1) % n], a[(i + 1) % n]),
                        (false, 0) => continue,
                        (false, _) if i + 1 == n => continue,
                        (false, _) => (a[i - 1], a[i + 1]),
                    };
                    if turning_degrees(prev, a[i], next, frame) > deg {
                        fixed[i] = true;
                        nodes.push(key(a[i]));
                    }
                }
            }
        }
        let plans = Plans {
            closed_curve,
            fixed,
            min_out,
        };
        nodes.sort_unstable();
        nodes.dedup();
        nodes.shrink_to_fit();
        (plans, nodes)
    }
}

/// Positions per pass of [`shared_positions`]: its table of counts holds
/// about this many keys at a time (half as many distinct ones in a
/// coverage, whose positions are mostly held by two arcs).
const COUNTED_PER_PASS: usize = 1 << 19;

/// The most passes of [`shared_positions`]: a pass is a byte's value.
const MAX_PASSES: usize = 254;

/// Whether each position occurs twice or more over all arcs (a closed arc's
/// end once), by address ([`Arcs::address`]; a closed arc's last position is
/// left unmarked). Counted in as many passes as it takes for each pass's
/// table to hold about [`COUNTED_PER_PASS`] positions (up to [`MAX_PASSES`]),
/// each pass the positions whose hash falls in its share: a table of every
/// position of a large coverage at once would take more than the arcs.
fn shared_positions(arcs: &Arcs) -> Vec<bool> {
    // Each position's byte holds its pass, then whether it is shared.
    const SHARED: u8 = MAX_PASSES as u8;
    const UNHELD: u8 = SHARED + 1;
    let total: usize = arcs.iter().map(distinct).sum();
    let passes = total.div_ceil(COUNTED_PER_PASS).clamp(1, MAX_PASSES) as u64;
    // Positions no arc holds (a closed arc's last, those left behind) have
    // no pass and are never met.
    let mut marks = vec![UNHELD; arcs.span()];
    // The pass a key is counted in, from its hash's upper bits: the table
    // places keys by the lower bits, which must stay spread.
    for (ai, a) in arcs.iter().enumerate() {
        let at = arcs.address(ai);
        for (m, &c) in marks[at..at + distinct(a)].iter_mut().zip(a) {
            *m = ((FxBuildHasher.hash_one(key(c)) >> 32) % passes) as u8;
        }
    }
    // The pass's keys met so far, each with the address it was first met at.
    let mut first: FxHashMap<(u64, u64), usize> = FxHashMap::default();
    for pass in 0..passes as u8 {
        first.clear();
        for (at, run) in arcs.runs() {
            for (i, &c) in run.iter().enumerate() {
                if marks[at + i] != pass {
                    continue;
                }
                match first.entry(key(c)) {
                    Entry::Vacant(v) => {
                        v.insert(at + i);
                    }
                    Entry::Occupied(o) => {
                        marks[*o.get()] = SHARED;
                        marks[at + i] = SHARED;
                    }
                }
            }
        }
    }
    marks.into_iter().map(|m| m == SHARED).collect()
}

/// Adds every leg of every arc of chain `ci` to `bump`.
fn bump_chain(
    t: &Topology,
    ci: usize,
    along: &mut Along<'_>,
    levels: &Legs,
    bump: &mut Vec<(usize, Seg)>,
) -> Result<(), Error> {
    for r in t.chain(ci).arcs {
        for s in along.segs(r.index(), levels)? {
            if !s.original {
                bump.push((r.index(), *s));
            }
        }
    }
    Ok(())
}

/// The refinement levels the rounds start from: `start`'s for the arcs it
/// holds (of the right length), 0 for every leg of the others.
fn start_levels(arcs: &Arcs, start: &Levels) -> Legs {
    let mut levels = Legs::new(arcs);
    if !start.is_empty() {
        for (i, a) in arcs.iter().enumerate() {
            if let Some(given) = start.get(arc_key(a)).filter(|g| g.len() == a.len() - 1) {
                levels.get_mut(arcs, i).copy_from_slice(given);
            }
        }
    }
    levels
}

/// Raises the level of every leg a conflict of this round named, once
/// however many name it (straight at the last resort), and marks its arc
/// for smoothing again.
fn raise(
    bump: Vec<(usize, Seg)>,
    arcs: &Arcs,
    levels: &mut Legs,
    dirty: &mut [bool],
    closed: &[bool],
    last_resort: bool,
) {
    let mut legs: FxHashSet<(usize, u32)> = FxHashSet::default();
    for (a, s) in bump {
        legs.extend(
            leg_range(s, (arcs[a].len() - 1) as u32, closed[a])
                .into_iter()
                .map(|l| (a, l)),
        );
    }
    for (a, leg) in legs {
        let l = &mut levels.get_mut(arcs, a)[leg as usize];
        *l = if last_resort {
            STRAIGHT
        } else {
            (*l + 1).min(STRAIGHT)
        };
        dirty[a] = true;
    }
}

/// The legs a segment lies along and one on each side.
fn leg_range(s: Seg, n: u32, wrap: bool) -> Vec<u32> {
    let mut v = Vec::new();
    if wrap {
        let span = (s.hi + n - s.lo) % n;
        for k in 0..=span + 2 {
            v.push((s.lo + n - 1 + k) % n);
        }
    } else {
        v.extend(s.lo.saturating_sub(1)..=(s.hi + 1).min(n - 1));
    }
    v
}

/// The corners of `extent`, or of the arcs' bounding box.
fn bounds(arcs: &Arcs, extent: Option<Rect<f64>>) -> ([f64; 2], [f64; 2]) {
    if let Some(r) = extent {
        return ([r.min().x, r.min().y], [r.max().x, r.max().y]);
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for c in arcs.iter().flatten() {
        lo = [lo[0].min(c.x), lo[1].min(c.y)];
        hi = [hi[0].max(c.x), hi[1].max(c.y)];
    }
    (lo, hi)
}

fn default_tolerance(arcs: &Arcs, extent: Option<Rect<f64>>) -> f64 {
    let (lo, hi) = bounds(arcs, extent);
    default_tolerance_of(lo, hi)
}
