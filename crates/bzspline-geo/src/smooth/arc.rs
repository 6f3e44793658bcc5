//! One arc smoothed at given leg levels: cut where positions must stay,
//! each piece's control polygon refined along its legs, the method's curve
//! flattened, and each output segment traced back to the legs it lies along.

use std::collections::hash_map::Entry;

use geo_types::Coord;
use rustc_hash::FxHashMap;

use super::legs::Legs;
use super::{MAX_LEVEL, STRAIGHT};
use crate::arcs::Arcs;
use crate::error::Error;
use crate::geodesy::{self, Convention};
use crate::graph::key;
use crate::options::{Frame, SmoothOptions};
use crate::piece::{self, Flat};

/// Which original legs one output segment lies along, and whether it is an
/// original edge.
#[derive(Clone, Copy, Debug)]
pub(super) struct Seg {
    pub(super) lo: u32,
    pub(super) hi: u32,
    pub(super) original: bool,
}

/// How one arc is smoothed, fixed for all rounds.
#[derive(Clone, Copy)]
pub(super) struct Plan<'a> {
    /// Smoothed as a closed curve when nothing cuts it.
    pub(super) closed_curve: bool,
    /// Positions that stay (per distinct position).
    pub(super) fixed: &'a [bool],
    /// The fewest positions the output may have.
    pub(super) min_out: usize,
}

/// Every arc's [`Plan`], in three vectors.
#[derive(Default)]
pub(super) struct Plans {
    pub(super) closed_curve: Vec<bool>,
    /// Whether each position stays, by its address in the arcs
    /// ([`Arcs::address`]): a byte a position, with no row per arc.
    pub(super) fixed: Vec<bool>,
    /// 2, 3 or 4 ([`Plan::min_out`]): a byte an arc.
    pub(super) min_out: Vec<u8>,
}

impl Plans {
    /// The plan of arc `a` of `arcs` (the arcs the plans were made for).
    pub(super) fn get(&self, arcs: &Arcs, a: usize) -> Plan<'_> {
        let n = distinct(&arcs[a]);
        let at = arcs.address(a);
        Plan {
            closed_curve: self.closed_curve[a],
            fixed: &self.fixed[at..at + n],
            min_out: usize::from(self.min_out[a]),
        }
    }
}

/// What each output segment of an arc lies along ([`Seg`]), for the arcs a
/// conflict names: found again by smoothing the arc once more at the levels
/// it was smoothed at (the same bits), rather than held for every arc.
pub(super) struct Along<'a> {
    arcs: &'a Arcs,
    plans: &'a Plans,
    opts: &'a SmoothOptions,
    tol: f64,
    found: FxHashMap<usize, Vec<Seg>>,
}

impl<'a> Along<'a> {
    pub(super) fn new(arcs: &'a Arcs, plans: &'a Plans, opts: &'a SmoothOptions, tol: f64) -> Self {
        Along {
            arcs,
            plans,
            opts,
            tol,
            found: FxHashMap::default(),
        }
    }

    /// The segments of arc `a` smoothed at `levels[a]`.
    pub(super) fn segs(&mut self, a: usize, levels: &Legs) -> Result<&[Seg], Error> {
        match self.found.entry(a) {
            Entry::Occupied(e) => Ok(e.into_mut()),
            Entry::Vacant(v) => {
                let plan = self.plans.get(self.arcs, a);
                let mut work = Smoothing::default();
                let arc = &self.arcs[a];
                smooth_arc(
                    a,
                    arc,
                    plan,
                    levels.get(self.arcs, a),
                    self.opts,
                    self.tol,
                    &mut work,
                )?;
                Ok(v.insert(work.segs))
            }
        }
    }

    /// Forgets what was found: the levels changed.
    pub(super) fn clear(&mut self) {
        self.found.clear();
    }
}

/// One smoothed arc, in vectors used again for every arc: the arcs kept
/// through the rounds are copied out of them once each arc's temporary
/// vectors are gone, so that they lie packed rather than among the holes
/// those leave.
#[derive(Default)]
pub(super) struct Smoothing {
    /// The arc's positions.
    pub(super) out: Vec<Coord>,
    /// What each output segment lies along.
    pub(super) segs: Vec<Seg>,
}

/// One arc smoothed at the given leg levels into `work` (its positions and
/// what each segment lies along); returns how many pieces were kept as they
/// were because their curve could not be built.
pub(super) fn smooth_arc(
    ai: usize,
    arc: &[Coord],
    plan: Plan<'_>,
    levels: &[u8],
    opts: &SmoothOptions,
    tol: f64,
    work: &mut Smoothing,
) -> Result<usize, Error> {
    let Smoothing { out, segs } = work;
    out.clear();
    segs.clear();
    let n_legs = arc.len() - 1;
    if n_legs == 0 {
        out.extend_from_slice(arc);
        return Ok(0);
    }
    let closed = is_closed(arc);
    if closed && n_legs < 3 {
        // Too few distinct positions for a ring's curve: kept as it is.
        let all: Vec<usize> = (0..=n_legs).map(|j| j % n_legs).collect();
        keep(arc, &all, out, segs);
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
    let mut kept = 0;
    // Positions in the order smoothed: a closed arc from its first cut round
    // to it again.
    let walk: Vec<usize> = if closed {
        if plan.closed_curve && !(0..n_legs).any(cuts) {
            let all: Vec<usize> = (0..=n_legs).collect();
            let (ctrl, leg_of) = refine(arc, &all, levels, true, opts.frame);
            match curve_polyline(&ctrl, true, opts, tol, plan.min_out).map_err(spline_err)? {
                Some(flat) => collect(&flat, &leg_of, out, segs),
                None => {
                    kept += 1;
                    keep(arc, &all, out, segs);
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
            keep(arc, piece, out, segs);
            continue;
        }
        let (ctrl, leg_of) = refine(arc, piece, levels, false, opts.frame);
        let min = if single_piece { plan.min_out } else { 2 };
        match curve_polyline(&ctrl, false, opts, tol, min).map_err(spline_err)? {
            Some(flat) => {
                let joint = out.len().checked_sub(1);
                collect(&flat, &leg_of, out, segs);
                // The piece ends exactly at its cut positions.
                out[joint.unwrap_or(0)] = arc[piece[0]];
                let last = out.len() - 1;
                out[last] = arc[piece[piece.len() - 1]];
            }
            None => {
                kept += 1;
                keep(arc, piece, out, segs);
            }
        }
    }
    finish(ai, out, segs, kept, closed)
}

/// Checks an arc's output and closes a closed one on its first position.
fn finish(
    ai: usize,
    out: &mut [Coord],
    segs: &[Seg],
    kept: usize,
    closed: bool,
) -> Result<usize, Error> {
    if out.iter().any(|c| !(c.x.is_finite() && c.y.is_finite())) {
        return Err(Error::Overflow { arc: ai });
    }
    if closed {
        let first = out[0];
        let last = out.len() - 1;
        out[last] = first;
    }
    debug_assert_eq!(segs.len() + 1, out.len());
    Ok(kept)
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
/// flat `[x, y, ...]`; and the original leg of each of its intervals. In
/// the geographic frame a leg runs the short way round in longitude (across
/// the antimeridian when that is shorter).
fn refine(
    arc: &[Coord],
    walk: &[usize],
    levels: &[u8],
    closed: bool,
    frame: Frame,
) -> (Vec<f64>, Vec<u32>) {
    let mut ctrl = Vec::with_capacity(2 * walk.len());
    let mut leg_of = Vec::with_capacity(walk.len());
    for w in walk.windows(2) {
        let (a, mut b) = (arc[w[0]], arc[w[1]]);
        // Longitudes of points inside a leg written as its ends write theirs.
        let convention = Convention::of([a.x, b.x]);
        if frame == Frame::Geographic {
            b.x = geodesy::unwrap_near(b.x, a.x);
        }
        let leg = w[0];
        let parts = 1u32 << levels[leg].min(MAX_LEVEL);
        for k in 0..parts {
            let t = f64::from(k) / f64::from(parts);
            let x = a.x + (b.x - a.x) * t;
            ctrl.push(if k == 0 || frame == Frame::Plane {
                x
            } else {
                convention.apply(x)
            });
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
/// positions): [`piece::flatten`] of [`piece::build`]; `None` when no curve
/// can be built on them (points too close for the parametrisation, say).
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
    let Ok(curve) = piece::build(ctrl, 2, closed, opts) else {
        return Ok(None);
    };
    piece::flatten(&curve, ctrl, 2, opts, tol, min).map(Some)
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

pub(super) fn is_closed(a: &[Coord]) -> bool {
    a.len() >= 2 && key(a[0]) == key(a[a.len() - 1])
}

/// How many of the arc's positions are its own: all but a closed arc's
/// last, which repeats its first.
pub(super) fn distinct(a: &[Coord]) -> usize {
    if is_closed(a) {
        a.len() - 1
    } else {
        a.len()
    }
}

/// The angle in degrees between the legs into and out of `b`: in the
/// plane, or, in the geographic frame (longitude and latitude), on the
/// ground, between the legs' chords through the Earth seen in the plane
/// tangent to the ellipsoid at `b` (east and north), so that a corner's
/// angle is the same at every latitude and across the antimeridian.
pub(crate) fn turning_degrees(a: Coord, b: Coord, c: Coord, frame: Frame) -> f64 {
    let ((ux, uy), (vx, vy)) = match frame {
        Frame::Plane => ((b.x - a.x, b.y - a.y), (c.x - b.x, c.y - b.y)),
        Frame::Geographic => {
            let [pa, pb, pc] = [a, b, c].map(|p| geodesy::to_ecef(p.x, p.y, 0.0));
            // libm's, as geodesy's: the same corners on every platform.
            let (lon, lat) = (b.x.to_radians(), b.y.to_radians());
            let (sl, cl) = (libm::sin(lon), libm::cos(lon));
            let (sp, cp) = (libm::sin(lat), libm::cos(lat));
            let (east, north) = ([-sl, cl, 0.0], [-sp * cl, -sp * sl, cp]);
            let on = |d: [f64; 3]| {
                let dot = |e: [f64; 3]| d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
                (dot(east), dot(north))
            };
            let diff = |p: [f64; 3], q: [f64; 3]| [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            (on(diff(pa, pb)), on(diff(pb, pc)))
        }
    };
    (ux * vy - uy * vx)
        .abs()
        .atan2(ux * vx + uy * vy)
        .to_degrees()
}
