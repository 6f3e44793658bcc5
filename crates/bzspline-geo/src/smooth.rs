//! Smoothing a topology: the options, every arc once, the rounds of the
//! conflict search (the crate docs say how).

use bzspline::Flatten;
use rustc_hash::{FxHashMap, FxHashSet};

use bzspline::{CurveBuilder, Param};
use geo_types::{Coord, Rect};

use crate::crossings::{Lines, SegId};
use crate::error::Error;
use crate::graph::key;
use crate::levels::{arc_key, Levels};
use crate::topology::{ChainKind, Topology};

/// The default flattening tolerance as a fraction of the diagonal of the
/// data's bounding box.
pub const DEFAULT_TOLERANCE_FRACTION: f64 = 1e-4;

/// The most times a leg is halved to resolve a conflict (into `2^MAX_LEVEL`
/// parts); one more conflict keeps the leg as the original edge.
pub const MAX_LEVEL: u8 = 5;

/// A leg kept as the original edge.
const STRAIGHT: u8 = MAX_LEVEL + 1;

/// Rounds of refinement after which every leg still in conflict is kept as
/// its original edge at once.
const MAX_ROUNDS: usize = 3 * MAX_LEVEL as usize;

/// How to smooth.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SmoothOptions {
    /// Largest distance between the smooth curve and the output polyline;
    /// `None`: [`DEFAULT_TOLERANCE_FRACTION`] of the data's bounding-box
    /// diagonal.
    pub tolerance: Option<f64>,
    /// The shape parameter of every interval, in `[1/3, 2/3]`.
    pub alpha: f64,
    /// How the curve's parameters follow the positions.
    pub param: Param,
    /// Positions where the polyline turns by more than this many degrees stay
    /// where they are, as corners.
    pub keep_angle: Option<f64>,
    /// Pass through every position (the interpolating variant,
    /// `docs/method.md` §11) instead of cutting the corners: the output keeps
    /// every position of the input.
    pub through: bool,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            tolerance: None,
            alpha: bzspline::DEFAULT_ALPHA,
            param: Param::Centripetal,
            keep_angle: None,
            through: false,
        }
    }
}

impl SmoothOptions {
    /// Sets the flattening tolerance.
    #[must_use]
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    /// Sets the shape parameter.
    #[must_use]
    pub fn alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self
    }

    /// Sets the parametrisation.
    #[must_use]
    pub fn param(mut self, param: Param) -> Self {
        self.param = param;
        self
    }

    /// Passes through every position (`true`) or cuts the corners (`false`, the
    /// default).
    #[must_use]
    pub fn through(mut self, through: bool) -> Self {
        self.through = through;
        self
    }

    /// Keeps corners sharper than `degrees`.
    #[must_use]
    pub fn keep_angle(mut self, degrees: f64) -> Self {
        self.keep_angle = Some(degrees);
        self
    }

    fn check(&self) -> Result<(), Error> {
        if !(bzspline::ALPHA_MIN..=bzspline::ALPHA_MAX).contains(&self.alpha) {
            return Err(Error::InvalidOption {
                what: "alpha (must be in [1/3, 2/3])",
                value: self.alpha,
            });
        }
        if let Some(t) = self.tolerance {
            if !(t.is_finite() && t > 0.0) {
                return Err(Error::InvalidOption {
                    what: "tolerance (must be a positive number)",
                    value: t,
                });
            }
        }
        if let Some(a) = self.keep_angle {
            if !(0.0..=180.0).contains(&a) {
                return Err(Error::InvalidOption {
                    what: "keep-angle (must be in [0, 180] degrees)",
                    value: a,
                });
            }
        }
        Ok(())
    }
}

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

/// Smoothed arcs, with the same indices as the topology's.
#[derive(Clone, Debug, PartialEq)]
pub struct Smoothed {
    /// Each arc's smoothed positions.
    pub arcs: Vec<Vec<Coord>>,
    /// What was done.
    pub stats: Stats,
    /// The levels each refined arc ended at ([`Topology::smooth_from`]).
    pub levels: Levels,
}

/// Which original legs one output segment lies along, and whether it is an
/// original edge.
#[derive(Clone, Copy, Debug)]
struct Seg {
    lo: u32,
    hi: u32,
    original: bool,
}

/// How one arc is smoothed, fixed for all rounds.
struct Plan {
    /// Smoothed as a closed curve when nothing cuts it.
    closed_curve: bool,
    /// Positions that stay (per distinct position).
    fixed: Vec<bool>,
    /// The fewest positions the output may have.
    min_out: usize,
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
        opts.check()?;
        let arcs = self.arcs();
        let extent = self.nodes().extent();
        let tolerance = opts
            .tolerance
            .unwrap_or_else(|| default_tolerance(arcs, extent));
        let mut stats = self.input_stats(tolerance);
        let (plans, nodes) = self.plans(opts.keep_angle);
        stats.closed_arcs = plans.iter().filter(|p| p.closed_curve).count();
        let closed: Vec<bool> = arcs.iter().map(|a| is_closed(a)).collect();

        let shoelace = Shoelace::about(arcs, extent);
        let cross_in: Vec<f64> = arcs.iter().map(|a| shoelace.arc(a)).collect();
        let mut cross_out: Vec<f64> = vec![0.0; arcs.len()];
        let rings = RingFacts::of(self, &shoelace, &cross_in);
        stats.area_in = shoelace.polygons(self, &cross_in);

        let mut levels = start_levels(arcs, start);
        let mut out: Vec<Vec<Coord>> = vec![Vec::new(); arcs.len()];
        let mut segs: Vec<Vec<Seg>> = vec![Vec::new(); arcs.len()];
        let mut dirty = vec![true; arcs.len()];
        let judged = self.judged(exact);
        let mut input_conflicts: FxHashSet<(SegId, SegId)> = FxHashSet::default();
        loop {
            stats.rounds += 1;
            for a in (0..arcs.len()).filter(|&a| dirty[a]) {
                let (coords, s, kept) =
                    smooth_arc(a, &arcs[a], &plans[a], &levels[a], opts, tolerance)?;
                stats.kept_pieces += kept;
                cross_out[a] = shoelace.arc(&coords);
                out[a] = coords;
                segs[a] = s;
            }
            input_conflicts.retain(|(p, q)| !dirty[p.line as usize] && !dirty[q.line as usize]);
            let lines = Lines {
                lines: &out,
                closed: &closed,
                nodes: &nodes,
            };
            let mut bump: Vec<(usize, Seg)> = Vec::new();
            for (p, q) in lines.conflicts(&dirty) {
                if !(judged[p.line as usize] && judged[q.line as usize]) {
                    continue;
                }
                let sp = segs[p.line as usize][p.seg as usize];
                let sq = segs[q.line as usize][q.seg as usize];
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
            self.ring_conflicts(
                &dirty, exact, &rings, &shoelace, &cross_out, &out, &segs, &mut bump,
            );
            dirty.iter_mut().for_each(|d| *d = false);
            if bump.is_empty() {
                break;
            }
            let last_resort = first - 1 + stats.rounds >= MAX_ROUNDS;
            raise(bump, &mut levels, &mut dirty, &closed, last_resort);
            if one {
                break;
            }
        }
        stats.input_conflicts = input_conflicts.len();
        stats.refined_legs = levels.iter().flatten().filter(|&&l| l > 0).count();
        stats.straight_legs = levels
            .iter()
            .map(|l| l.iter().filter(|&&v| v == STRAIGHT).count())
            .sum();
        stats.positions_out = self.positions(&out);
        stats.area_out = shoelace.polygons(self, &cross_out);
        let mut ended = Levels::default();
        for (a, l) in arcs.iter().zip(levels) {
            if l.iter().any(|&v| v > 0) {
                ended.insert(arc_key(a), l);
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
            for r in &c.arcs {
                j[r.arc] = true;
            }
        }
        j
    }

    /// Adds to `bump` every leg of the rings that turned over and of the
    /// holes (and their shells) that left their shell, among the rings that
    /// use a `dirty` arc (and that `exact` marks, unless it is empty).
    #[allow(clippy::too_many_arguments)] // the round's state, read only
    fn ring_conflicts(
        &self,
        dirty: &[bool],
        exact: &[bool],
        rings: &RingFacts,
        shoelace: &Shoelace,
        cross_out: &[f64],
        out: &[Vec<Coord>],
        segs: &[Vec<Seg>],
        bump: &mut Vec<(usize, Seg)>,
    ) {
        let mut suspects: Vec<usize> = (0..dirty.len())
            .filter(|&a| dirty[a])
            .flat_map(|a| rings.chains_of[a].iter().map(|&c| c as usize))
            .filter(|&c| exact.get(c).copied().unwrap_or(exact.is_empty()))
            .collect();
        suspects.sort_unstable();
        suspects.dedup();
        let mut polys: Vec<usize> = Vec::new();
        for &ci in &suspects {
            let sign = rings.sign_in[ci];
            if sign != 0.0 && shoelace.ring(self, ci, cross_out).signum() != sign {
                bump_chain(self, ci, segs, bump);
            }
            if let Some(p) = rings.polygon_of[ci] {
                polys.push(p as usize);
            }
        }
        polys.sort_unstable();
        polys.dedup();
        for p in polys {
            let members = &self.polygons()[p];
            let now = holes_inside(self, members, out);
            for (h, (&was, &is)) in rings.inside_in[p].iter().zip(&now).enumerate() {
                if was && !is {
                    bump_chain(self, members[0], segs, bump);
                    bump_chain(self, members[h + 1], segs, bump);
                }
            }
        }
    }

    /// Positions of all chains assembled from `arcs` (joints once, rings
    /// closed).
    fn positions(&self, arcs: &[Vec<Coord>]) -> usize {
        self.chains()
            .iter()
            .map(|c| c.arcs.iter().map(|r| arcs[r.arc].len() - 1).sum::<usize>() + 1)
            .sum()
    }

    /// Each arc's plan, and the nodes: positions where arcs may meet.
    fn plans(&self, keep_angle: Option<f64>) -> (Vec<Plan>, FxHashSet<(u64, u64)>) {
        let arcs = self.arcs();
        // How often each position occurs over all arcs (a closed arc's end once).
        let mut count: FxHashMap<(u64, u64), u32> = FxHashMap::default();
        for a in arcs {
            let distinct = if is_closed(a) {
                &a[..a.len() - 1]
            } else {
                &a[..]
            };
            for &c in distinct {
                *count.entry(key(c)).or_insert(0) += 1;
            }
        }
        let mut in_line = vec![false; arcs.len()];
        let mut min_out = vec![2usize; arcs.len()];
        for c in self.chains() {
            for r in &c.arcs {
                if c.kind == ChainKind::Line {
                    in_line[r.arc] = true;
                }
                let want = match (c.kind, c.arcs.len()) {
                    (ChainKind::Ring, 1) => 4,
                    (ChainKind::Ring, 2) => 3,
                    _ => 2,
                };
                min_out[r.arc] = min_out[r.arc].max(want.min(arcs[r.arc].len()));
            }
        }
        let mut nodes: FxHashSet<(u64, u64)> = count
            .iter()
            .filter(|&(_, &n)| n >= 2)
            .map(|(&k, _)| k)
            .collect();
        // A node: met by two arcs here, or by the whole coverage's (given).
        let given = self.nodes();
        let is_node = |c: Coord| {
            count.get(&key(c)).is_some_and(|&n| n >= 2) || (!given.is_empty() && given.contains(c))
        };
        let mut plans = Vec::with_capacity(arcs.len());
        for (ai, a) in arcs.iter().enumerate() {
            let closed = is_closed(a);
            let first_node = is_node(a[0]) || in_line[ai];
            let closed_curve = closed && !first_node && a.len() >= 4;
            if !closed_curve {
                nodes.insert(key(a[0]));
                nodes.insert(key(a[a.len() - 1]));
            }
            let n = if closed { a.len() - 1 } else { a.len() };
            let mut fixed: Vec<bool> = (0..n).map(|i| is_node(a[i])).collect();
            if let Some(deg) = keep_angle {
                for i in 0..n {
                    let (prev, next) = match (closed, i) {
                        (true, _) => (a[(i + n - 1) % n], a[(i + 1) % n]),
                        (false, 0) => continue,
                        (false, _) if i + 1 == n => continue,
                        (false, _) => (a[i - 1], a[i + 1]),
                    };
                    if turning_degrees(prev, a[i], next) > deg {
                        fixed[i] = true;
                        nodes.insert(key(a[i]));
                    }
                }
            }
            plans.push(Plan {
                closed_curve,
                fixed,
                min_out: min_out[ai],
            });
        }
        (plans, nodes)
    }
}

/// What the input says about its rings, for the checks after smoothing.
struct RingFacts {
    /// The chains that use each arc.
    chains_of: Vec<Vec<u32>>,
    /// The polygon each ring belongs to.
    polygon_of: Vec<Option<u32>>,
    /// Each ring's winding in the input (0 for a line or a flat ring).
    sign_in: Vec<f64>,
    /// Per polygon, whether each hole lies inside the shell in the input.
    inside_in: Vec<Vec<bool>>,
}

impl RingFacts {
    fn of(t: &Topology, shoelace: &Shoelace, cross_in: &[f64]) -> RingFacts {
        let mut chains_of: Vec<Vec<u32>> = vec![Vec::new(); t.arcs().len()];
        for (ci, c) in t.chains().iter().enumerate() {
            for r in &c.arcs {
                chains_of[r.arc].push(ci as u32);
            }
        }
        let mut polygon_of: Vec<Option<u32>> = vec![None; t.chains().len()];
        for (pi, p) in t.polygons().iter().enumerate() {
            for &c in p {
                polygon_of[c] = Some(pi as u32);
            }
        }
        let sign_in = (0..t.chains().len())
            .map(|ci| match t.chains()[ci].kind {
                ChainKind::Ring => shoelace.ring(t, ci, cross_in).signum(),
                ChainKind::Line => 0.0,
            })
            .collect();
        let inside_in = t
            .polygons()
            .iter()
            .map(|p| holes_inside(t, p, t.arcs()))
            .collect();
        RingFacts {
            chains_of,
            polygon_of,
            sign_in,
            inside_in,
        }
    }
}

/// For each hole of `rings` (shell first), whether it lies inside the shell.
fn holes_inside(t: &Topology, rings: &[usize], arcs: &[Vec<Coord>]) -> Vec<bool> {
    if rings.len() < 2 {
        return Vec::new();
    }
    let shell = t.chain_coords(rings[0], arcs);
    rings[1..]
        .iter()
        .map(|&h| {
            let hole = t.chain_coords(h, arcs);
            hole.iter().find_map(|&p| locate(p, &shell)).unwrap_or(true)
        })
        .collect()
}

/// Adds every leg of every arc of chain `ci` to `bump`.
fn bump_chain(t: &Topology, ci: usize, segs: &[Vec<Seg>], bump: &mut Vec<(usize, Seg)>) {
    for r in &t.chains()[ci].arcs {
        for s in &segs[r.arc] {
            if !s.original {
                bump.push((r.arc, *s));
            }
        }
    }
}

/// The refinement levels the rounds start from: `start`'s for the arcs it
/// holds (of the right length), 0 for every leg of the others.
fn start_levels(arcs: &[Vec<Coord>], start: &Levels) -> Vec<Vec<u8>> {
    let mut levels: Vec<Vec<u8>> = arcs.iter().map(|a| vec![0; a.len() - 1]).collect();
    if !start.is_empty() {
        for (a, l) in arcs.iter().zip(levels.iter_mut()) {
            if let Some(given) = start.get(arc_key(a)).filter(|g| g.len() == l.len()) {
                l.copy_from_slice(given);
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
    levels: &mut [Vec<u8>],
    dirty: &mut [bool],
    closed: &[bool],
    last_resort: bool,
) {
    let mut legs: FxHashSet<(usize, u32)> = FxHashSet::default();
    for (a, s) in bump {
        legs.extend(
            leg_range(s, levels[a].len() as u32, closed[a])
                .into_iter()
                .map(|l| (a, l)),
        );
    }
    for (a, leg) in legs {
        let l = &mut levels[a][leg as usize];
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

fn is_closed(a: &[Coord]) -> bool {
    a.len() >= 2 && key(a[0]) == key(a[a.len() - 1])
}

/// The corners of `extent`, or of the arcs' bounding box.
fn bounds(arcs: &[Vec<Coord>], extent: Option<Rect<f64>>) -> ([f64; 2], [f64; 2]) {
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

fn default_tolerance(arcs: &[Vec<Coord>], extent: Option<Rect<f64>>) -> f64 {
    let (lo, hi) = bounds(arcs, extent);
    default_tolerance_of(lo, hi)
}

/// The flattening tolerance smoothing takes when none is given: the
/// fraction [`DEFAULT_TOLERANCE_FRACTION`] of the diagonal of the box from
/// `lo` to `hi` (the data's extent, `[x, y]`), or 1 when that diagonal is zero
/// or not finite (a single position, no positions). Every entry point (the
/// command, ring by ring too, and the bindings) takes its default from here.
#[must_use]
pub fn default_tolerance_of(lo: [f64; 2], hi: [f64; 2]) -> f64 {
    let diag = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    if diag.is_finite() && diag > 0.0 {
        diag * DEFAULT_TOLERANCE_FRACTION
    } else {
        1.0
    }
}

/// The angle in degrees between the legs into and out of `b`.
fn turning_degrees(a: Coord, b: Coord, c: Coord) -> f64 {
    let (ux, uy) = (b.x - a.x, b.y - a.y);
    let (vx, vy) = (c.x - b.x, c.y - b.y);
    (ux * vy - uy * vx)
        .abs()
        .atan2(ux * vx + uy * vy)
        .to_degrees()
}

/// Signed areas by the shoelace formula, summed over arcs: a ring's area is
/// half the sum of its arcs' cross products (negated for a reversed arc), so
/// no ring is assembled. Coordinates are taken about the centre of the data,
/// which keeps the products small far from the origin, and scaled by a power
/// of two where products of the data's size would underflow or overflow
/// ([`crate::crossings::unit_scale`]), so that a ring's sign is kept.
struct Shoelace {
    origin: Coord,
    scale: f64,
}

impl Shoelace {
    fn about(arcs: &[Vec<Coord>], extent: Option<Rect<f64>>) -> Shoelace {
        let (lo, hi) = bounds(arcs, extent);
        let mid = |a: f64, b: f64| {
            if a.is_finite() {
                a / 2.0 + b / 2.0
            } else {
                0.0
            }
        };
        let half = (hi[0] - lo[0]).max(hi[1] - lo[1]) / 2.0;
        Shoelace {
            origin: Coord {
                x: mid(lo[0], hi[0]),
                y: mid(lo[1], hi[1]),
            },
            scale: crate::crossings::unit_scale(half),
        }
    }

    /// The sum of `x_i y_{i+1} - x_{i+1} y_i` along an arc.
    fn arc(&self, a: &[Coord]) -> f64 {
        let (o, s) = (self.origin, self.scale);
        if s == 1.0 {
            return a
                .windows(2)
                .map(|w| (w[0].x - o.x) * (w[1].y - o.y) - (w[1].x - o.x) * (w[0].y - o.y))
                .sum();
        }
        a.windows(2)
            .map(|w| {
                let (x0, y0) = ((w[0].x - o.x) * s, (w[0].y - o.y) * s);
                let (x1, y1) = ((w[1].x - o.x) * s, (w[1].y - o.y) * s);
                x0 * y1 - x1 * y0
            })
            .sum()
    }

    /// The signed area of ring `ci` (positive counter-clockwise).
    fn ring(&self, t: &Topology, ci: usize, cross: &[f64]) -> f64 {
        t.chains()[ci]
            .arcs
            .iter()
            .map(|r| {
                if r.reversed {
                    -cross[r.arc]
                } else {
                    cross[r.arc]
                }
            })
            .sum::<f64>()
            / 2.0
    }

    /// Area of the polygons: shells less holes, in the data's units.
    fn polygons(&self, t: &Topology, cross: &[f64]) -> f64 {
        self.scaled_polygons(t, cross) / self.scale / self.scale
    }

    /// Area of the polygons in the scaled units of the cross products.
    fn scaled_polygons(&self, t: &Topology, cross: &[f64]) -> f64 {
        t.polygons()
            .iter()
            .map(|p| {
                p.iter()
                    .enumerate()
                    .map(|(k, &c)| {
                        let a = self.ring(t, c, cross).abs();
                        if k == 0 {
                            a
                        } else {
                            -a
                        }
                    })
                    .sum::<f64>()
            })
            .sum()
    }
}

/// Whether `p` is inside the closed `ring` (winding number with exact
/// orientation); `None` on its boundary.
fn locate(p: Coord, ring: &[Coord]) -> Option<bool> {
    let orient = |a: Coord, b: Coord| crate::crossings::orient_at_any_scale(a, b, p);
    let mut wn = 0i64;
    for w in ring.windows(2) {
        let (a, b) = (w[0], w[1]);
        let o = orient(a, b);
        if o == 0.0
            && p.x >= a.x.min(b.x)
            && p.x <= a.x.max(b.x)
            && p.y >= a.y.min(b.y)
            && p.y <= a.y.max(b.y)
        {
            return None;
        }
        if a.y <= p.y {
            if b.y > p.y && o > 0.0 {
                wn += 1;
            }
        } else if b.y <= p.y && o < 0.0 {
            wn -= 1;
        }
    }
    Some(wn != 0)
}

/// One arc smoothed at the given leg levels: its positions, what each output
/// segment lies along, and how many pieces were kept as they were because
/// their curve could not be built.
fn smooth_arc(
    ai: usize,
    arc: &[Coord],
    plan: &Plan,
    levels: &[u8],
    opts: &SmoothOptions,
    tol: f64,
) -> Result<(Vec<Coord>, Vec<Seg>, usize), Error> {
    let n_legs = arc.len() - 1;
    if n_legs == 0 {
        return Ok((arc.to_vec(), Vec::new(), 0));
    }
    let closed = is_closed(arc);
    if closed && n_legs < 3 {
        // Too few distinct positions for a ring's curve: kept as it is.
        let all: Vec<usize> = (0..=n_legs).map(|j| j % n_legs).collect();
        let (mut out, mut segs) = (Vec::new(), Vec::new());
        keep(arc, &all, &mut out, &mut segs);
        return finish(ai, out, segs, 0, closed);
    }
    // Leg l runs from position l to l + 1 (for a closed arc, modulo n_legs).
    let straight = |l: usize| levels[l] >= STRAIGHT;
    // A position cuts the arc when it is fixed or ends a straight leg.
    let cuts = |i: usize| -> bool {
        let before = if i > 0 {
            Some(i - 1)
        } else if closed {
            Some(n_legs - 1)
        } else {
            None
        };
        plan.fixed[i] || (i < n_legs && straight(i)) || before.is_some_and(straight)
    };
    let spline_err = |e| Error::Spline { arc: ai, source: e };
    let mut out: Vec<Coord> = Vec::new();
    let mut segs: Vec<Seg> = Vec::new();
    let mut kept = 0;
    // Positions in the order smoothed: a closed arc from its first cut round
    // to it again.
    let walk: Vec<usize> = if closed {
        if plan.closed_curve && !(0..n_legs).any(cuts) {
            let all: Vec<usize> = (0..=n_legs).collect();
            let (ctrl, leg_of) = refine(arc, &all, levels, true);
            match curve_polyline(&ctrl, true, opts, tol, plan.min_out).map_err(spline_err)? {
                Some(flat) => collect(&flat, &leg_of, &mut out, &mut segs),
                None => {
                    kept += 1;
                    keep(arc, &all, &mut out, &mut segs);
                }
            }
            return finish(ai, out, segs, kept, closed);
        }
        let start = (0..n_legs).find(|&i| cuts(i)).unwrap_or(0);
        (0..=n_legs).map(|j| (start + j) % n_legs).collect()
    } else {
        (0..arc.len()).collect()
    };
    let single_piece = !(1..n_legs).any(|j| cuts(walk[j]));
    let mut j0 = 0;
    for j in 1..walk.len() {
        if j + 1 != walk.len() && !cuts(walk[j]) {
            continue;
        }
        let piece = &walk[j0..=j];
        j0 = j;
        if piece.len() == 2 {
            keep(arc, piece, &mut out, &mut segs);
            continue;
        }
        let (ctrl, leg_of) = refine(arc, piece, levels, false);
        let min = if single_piece { plan.min_out } else { 2 };
        match curve_polyline(&ctrl, false, opts, tol, min).map_err(spline_err)? {
            Some(flat) => {
                let joint = out.len().checked_sub(1);
                collect(&flat, &leg_of, &mut out, &mut segs);
                // The piece ends exactly at its cut positions.
                out[joint.unwrap_or(0)] = arc[piece[0]];
                let last = out.len() - 1;
                out[last] = arc[piece[piece.len() - 1]];
            }
            None => {
                kept += 1;
                keep(arc, piece, &mut out, &mut segs);
            }
        }
    }
    finish(ai, out, segs, kept, closed)
}

/// Checks an arc's output and closes a closed one on its first position.
fn finish(
    ai: usize,
    mut out: Vec<Coord>,
    segs: Vec<Seg>,
    kept: usize,
    closed: bool,
) -> Result<(Vec<Coord>, Vec<Seg>, usize), Error> {
    if out.iter().any(|c| !(c.x.is_finite() && c.y.is_finite())) {
        return Err(Error::Overflow { arc: ai });
    }
    if closed {
        let first = out[0];
        let last = out.len() - 1;
        out[last] = first;
    }
    debug_assert_eq!(segs.len() + 1, out.len());
    Ok((out, segs, kept))
}

/// Appends the original edges along the positions `walk` of `arc`.
fn keep(arc: &[Coord], walk: &[usize], out: &mut Vec<Coord>, segs: &mut Vec<Seg>) {
    if out.is_empty() {
        out.push(arc[walk[0]]);
    }
    for w in walk.windows(2) {
        out.push(arc[w[1]]);
        segs.push(Seg {
            lo: w[0] as u32,
            hi: w[0] as u32,
            original: true,
        });
    }
}

/// The control polygon of the positions `walk` of `arc` (closed: the walk
/// returns to its start), each leg `l` cut into `2^levels[l]` equal parts,
/// flat `[x, y, ...]`; and the original leg of each of its intervals.
fn refine(arc: &[Coord], walk: &[usize], levels: &[u8], closed: bool) -> (Vec<f64>, Vec<u32>) {
    let mut ctrl = Vec::with_capacity(2 * walk.len());
    let mut leg_of = Vec::with_capacity(walk.len());
    for w in walk.windows(2) {
        let (a, b) = (arc[w[0]], arc[w[1]]);
        let leg = w[0];
        let parts = 1u32 << levels[leg].min(MAX_LEVEL);
        for k in 0..parts {
            let t = f64::from(k) / f64::from(parts);
            ctrl.push(a.x + (b.x - a.x) * t);
            ctrl.push(a.y + (b.y - a.y) * t);
            leg_of.push(leg as u32);
        }
    }
    if !closed {
        let last = arc[walk[walk.len() - 1]];
        ctrl.push(last.x);
        ctrl.push(last.y);
    }
    (ctrl, leg_of)
}

/// The flattened curve of the control points `ctrl` (at least `min`
/// positions, sampled evenly in the parameter when flattening gives fewer):
/// its vertices' parameters and coordinates, and the curve's knots; `None`
/// when no curve can be built on them (points too close for the
/// parametrisation, say). Through the points, every control point is a
/// vertex, with its coordinates exactly.
///
/// # Errors
///
/// The flattening's: a tolerance that asks for too many vertices.
fn curve_polyline(
    ctrl: &[f64],
    closed: bool,
    opts: &SmoothOptions,
    tol: f64,
    min: usize,
) -> Result<Option<Flat>, bzspline::Error> {
    let Ok(curve) = CurveBuilder::new(ctrl, 2)
        .closed(closed)
        .param(opts.param.clone())
        .alpha(opts.alpha)
        .through(opts.through)
        .build()
    else {
        return Ok(None);
    };
    let mut poly = if opts.through {
        curve.flatten_with_knots(tol)?
    } else {
        curve.flatten(tol)?
    };
    if poly.len() < min {
        poly = curve.sample(min)?;
    }
    let knots = curve.knots().to_vec();
    let params = poly.params().to_vec();
    let mut coords = poly.coords().to_vec();
    if opts.through {
        let n = ctrl.len() / 2;
        let mut k = 0;
        for (i, &t) in params.iter().enumerate() {
            while k < knots.len() && knots[k] < t {
                k += 1;
            }
            if k < knots.len() && knots[k] == t {
                let j = k % n;
                coords[2 * i] = ctrl[2 * j];
                coords[2 * i + 1] = ctrl[2 * j + 1];
            }
        }
    }
    Ok(Some(Flat {
        params,
        coords,
        knots,
    }))
}

/// A flattened piece: vertex parameters, coordinates (flat), the knots.
struct Flat {
    params: Vec<f64>,
    coords: Vec<f64>,
    knots: Vec<f64>,
}

/// Appends the polyline's vertices (after the first when `out` already
/// ends at it) and its segments' legs.
fn collect(flat: &Flat, leg_of: &[u32], out: &mut Vec<Coord>, segs: &mut Vec<Seg>) {
    let knots = &flat.knots;
    let nint = knots.len() - 1;
    // The interval a parameter starts (or, `right`, ends) a segment in.
    let interval = |p: f64, right: bool| -> usize {
        let k = if right {
            knots.partition_point(|&k| k < p)
        } else {
            knots.partition_point(|&k| k <= p)
        };
        k.saturating_sub(1).min(nint - 1)
    };
    let params = &flat.params;
    let coords = &flat.coords;
    out.reserve(params.len());
    segs.reserve(params.len());
    let mut prev = params[0];
    for (i, &p) in params.iter().enumerate() {
        let c = Coord {
            x: coords[2 * i],
            y: coords[2 * i + 1],
        };
        if out.is_empty() {
            out.push(c);
            continue;
        }
        if i == 0 || out.last().map(|&l| key(l)) == Some(key(c)) {
            continue;
        }
        let lo = interval(prev, false);
        let hi = interval(p, true).max(lo);
        out.push(c);
        segs.push(Seg {
            lo: leg_of[lo],
            hi: leg_of[hi],
            original: false,
        });
        prev = p;
    }
}
