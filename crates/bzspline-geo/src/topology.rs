//! The topology of a coverage: its lines and rings cut into arcs (the
//! crate docs say how arcs are found).

use std::hash::{BuildHasher, Hash, Hasher};

use hashbrown::HashTable;
use rustc_hash::{FxBuildHasher, FxHashMap};

use geo_types::Coord;
use rstar::primitives::GeomWithData;
use rstar::RTree;

use crate::arcs::Arcs;
use crate::chains::{Chain, Chains};
use crate::error::Error;
pub use crate::graph::ChainKind;
use crate::graph::{junctions, key, Paths, Points};
use crate::nodes::Nodes;
use crate::options::Frame;
use crate::ragged::Ragged;

/// One arc of a chain, in its stored direction or reversed (TopoJSON writes
/// the reversed arc `k` as `!k`, that is `-k - 1`): 4 bytes, the arc's index
/// and the direction in one `u32`, for a topology holds fewer than
/// [`ArcRef::MAX_ARCS`] arcs.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct ArcRef(u32);

impl ArcRef {
    /// How many arcs a topology may hold: an index takes 31 bits.
    pub const MAX_ARCS: usize = 1 << 31;

    /// Arc `arc`, in its stored direction or `reversed`.
    ///
    /// # Panics
    ///
    /// When `arc` is not below [`ArcRef::MAX_ARCS`].
    #[must_use]
    pub fn new(arc: usize, reversed: bool) -> ArcRef {
        assert!(
            arc < ArcRef::MAX_ARCS,
            "arc {arc} past the 2^31 a topology holds"
        );
        ArcRef(((arc as u32) << 1) | u32::from(reversed))
    }

    /// The arc's index into [`Topology::arcs`].
    #[must_use]
    pub fn index(self) -> usize {
        (self.0 >> 1) as usize
    }

    /// Whether the chain runs along the arc from its last position to its
    /// first.
    #[must_use]
    pub fn reversed(self) -> bool {
        self.0 & 1 == 1
    }

    /// The reference TopoJSON writes: `k`, or `!k` (`-k - 1`) when reversed.
    #[must_use]
    pub fn to_topojson(self) -> i64 {
        let k = self.index() as i64;
        if self.reversed() {
            -k - 1
        } else {
            k
        }
    }

    /// The reference from TopoJSON's `k` or `!k`; an index of
    /// [`ArcRef::MAX_ARCS`] or more becomes `MAX_ARCS - 1`, which names no
    /// arc of any topology (one arc fewer than the most a topology holds).
    #[must_use]
    pub fn from_topojson(k: i64) -> ArcRef {
        let (index, reversed) = if k < 0 { (-(k + 1), true) } else { (k, false) };
        let index = usize::try_from(index)
            .ok()
            .filter(|&i| i < ArcRef::MAX_ARCS)
            .unwrap_or(ArcRef::MAX_ARCS - 1);
        ArcRef::new(index, reversed)
    }
}

impl std::fmt::Debug for ArcRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ArcRef")
            .field("arc", &self.index())
            .field("reversed", &self.reversed())
            .finish()
    }
}

/// Arcs, the lines and rings made of them, and which rings form a polygon.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Topology {
    arcs: Arcs,
    chains: Chains,
    polygons: Ragged<usize>,
    nodes: Nodes,
}

impl Topology {
    /// Finds the arcs of `chains` (lines and rings, each as its positions; a
    /// ring's first position is repeated at its end or not, either is
    /// accepted). `polygons` lists, for each polygon, the indices of its
    /// rings in `chains`, the shell first. Consecutive equal positions are
    /// merged.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a coordinate that is not finite;
    /// [`Error::Polygon`] for a polygon that names a chain that is not a ring.
    pub fn from_chains(
        chains: &[(ChainKind, Vec<Coord>)],
        polygons: Vec<Vec<usize>>,
    ) -> Result<Topology, Error> {
        Topology::from_chains_with_nodes(chains, polygons, Nodes::default())
    }

    /// As [`Topology::from_chains`], with `nodes` as junctions too: the
    /// chains are also cut there, and smoothing keeps them as it keeps the
    /// nodes it finds. This is how one part of a coverage is smoothed exactly
    /// as the whole would be ([`Nodes`]); the nodes' extent, when set, also
    /// stands in for the data's bounding box (the default tolerance).
    ///
    /// # Errors
    ///
    /// As [`Topology::from_chains`].
    pub fn from_chains_with_nodes(
        chains: &[(ChainKind, Vec<Coord>)],
        polygons: Vec<Vec<usize>>,
        nodes: Nodes,
    ) -> Result<Topology, Error> {
        let polygons = Ragged::from(polygons);
        check_polygons(chains.len(), &polygons, |i| chains[i].0)?;
        let paths = Paths::of(chains.iter().map(|(k, c)| (*k, c)))?;
        Ok(Topology::from_paths(paths, polygons, nodes))
    }

    /// The topology of `chains`, at least `room` of them, taken one at a
    /// time, each chain's positions let go of as soon as they are held
    /// once; without polygons ([`Topology::with_polygons`]).
    pub(crate) fn from_gathered(
        chains: impl IntoIterator<Item = (ChainKind, Vec<Coord>)>,
        room: usize,
        nodes: Nodes,
    ) -> Result<Topology, Error> {
        let paths = Paths::with_room(chains, room)?;
        Ok(Topology::from_paths(paths, Ragged::new(), nodes))
    }

    /// This topology with `polygons` grouping its rings, which they name
    /// correctly (as [`crate::Coverage`] gathers them).
    pub(crate) fn with_polygons(mut self, polygons: Ragged<usize>) -> Topology {
        debug_assert!(
            check_polygons(self.chains.len(), &polygons, |i| self.chains.kinds()[i]).is_ok()
        );
        self.polygons = polygons;
        self
    }

    /// The arcs of chains given as paths of distinct positions.
    fn from_paths(paths: Paths, polygons: Ragged<usize>, nodes: Nodes) -> Topology {
        let Paths { points, paths } = paths;
        let mut junction = junctions(points.len(), &paths).0;
        if !nodes.is_empty() {
            for (j, p) in junction.iter_mut().zip(points.iter()) {
                *j |= nodes.contains(*p);
            }
        }
        // Each path is let go of once cut, as the chains are in `Paths::of`.
        let mut b = Builder::new(&points);
        let mut out_chains = Chains::with_capacity(paths.len(), 0);
        for (kind, path) in paths {
            let arcs = match kind {
                ChainKind::Line => b.cut_line(&path, &junction),
                ChainKind::Ring => b.cut_ring(&path, &junction),
            };
            out_chains.push(kind, arcs);
        }
        let arcs = b.arcs();
        Topology {
            arcs,
            chains: out_chains,
            polygons,
            nodes,
        }
    }

    /// A topology from arcs already found (TopoJSON's): each chain lists its
    /// arcs in order, and `polygons` groups rings as in [`Topology::from_chains`].
    /// Consecutive equal positions within an arc are merged.
    ///
    /// # Errors
    ///
    /// [`Error::ArcIndex`] for a reference past the last arc;
    /// [`Error::EmptyArc`] for an arc without positions;
    /// [`Error::NonFinite`] (with the arc as `chain`) for a coordinate that is not
    /// finite; [`Error::Polygon`] as for [`Topology::from_chains`].
    pub fn from_arcs(
        arcs: Vec<Vec<Coord>>,
        chains: Chains,
        polygons: Vec<Vec<usize>>,
    ) -> Result<Topology, Error> {
        let polygons = Ragged::from(polygons);
        check_polygons(chains.len(), &polygons, |i| chains.kinds()[i])?;
        let total = arcs.iter().map(Vec::len).sum();
        let mut kept = Arcs::with_capacity(arcs.len(), total);
        for (ai, mut a) in arcs.into_iter().enumerate() {
            if let Some(pi) = a.iter().position(|c| !(c.x.is_finite() && c.y.is_finite())) {
                return Err(Error::NonFinite {
                    chain: ai,
                    position: pi,
                });
            }
            a.dedup_by(|p, q| key(*p) == key(*q));
            if a.is_empty() {
                return Err(Error::EmptyArc { arc: ai });
            }
            kept.push(a);
        }
        let arcs = kept;
        for (ci, c) in chains.iter().enumerate() {
            if let Some(r) = c.arcs.iter().find(|r| r.index() >= arcs.len()) {
                return Err(Error::ArcIndex {
                    chain: ci,
                    arc: r.to_topojson(),
                    arcs: arcs.len(),
                });
            }
        }
        Ok(Topology {
            arcs,
            chains,
            polygons,
            nodes: Nodes::default(),
        })
    }

    /// The arcs' positions.
    #[must_use]
    pub fn arcs(&self) -> &Arcs {
        &self.arcs
    }

    /// The chains, the rest let go of ([`crate::Coverage::into_geometries`],
    /// [`crate::Coverage::into_assembled`]).
    pub(crate) fn into_chains(self) -> Chains {
        self.chains
    }

    /// The nodes given ([`Topology::from_chains_with_nodes`]); none otherwise.
    #[must_use]
    pub fn nodes(&self) -> &Nodes {
        &self.nodes
    }

    /// The lines and rings, in the order given.
    #[must_use]
    pub fn chains(&self) -> &Chains {
        &self.chains
    }

    /// Chain `i`.
    ///
    /// # Panics
    ///
    /// When `i` is past the last chain.
    #[must_use]
    pub fn chain(&self, i: usize) -> Chain<'_> {
        match self.chains.get(i) {
            Some(c) => c,
            None => panic!("chain {i} of {}", self.chains.len()),
        }
    }

    /// Each polygon's rings (indices into [`Topology::chains`]), shell first.
    #[must_use]
    pub fn polygons(&self) -> &Ragged<usize> {
        &self.polygons
    }

    /// The chain an error names, or for an error about an arc the first chain
    /// that uses the arc; `None` for errors about neither.
    #[must_use]
    pub fn chain_of(&self, e: &Error) -> Option<usize> {
        match e {
            Error::NonFinite { chain, .. } | Error::ArcIndex { chain, .. } => Some(*chain),
            Error::Overflow { arc } | Error::Spline { arc, .. } | Error::EmptyArc { arc } => self
                .chains
                .iter()
                .position(|c| c.arcs.iter().any(|r| r.index() == *arc)),
            _ => None,
        }
    }

    /// How many chain references each arc has (2 or more: a shared border).
    #[must_use]
    pub fn uses(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.arcs.len()];
        for r in self.chains.refs() {
            uses[r.index()] += 1;
        }
        uses
    }

    /// The positions of chain `i` assembled from `arcs` (these arcs, or
    /// smoothed ones with the same indices): each arc in its direction, the
    /// position two arcs share written once; a ring ends on its first position
    /// and has at least four (a collapsed one repeats its first).
    ///
    /// # Panics
    ///
    /// When `i` is not a chain's index or `arcs` is shorter than the arcs.
    #[must_use]
    pub fn chain_coords(&self, i: usize, arcs: &Arcs) -> Vec<Coord> {
        chain_coords(self.chain(i), arcs)
    }
}

fn check_polygons(
    n: usize,
    polygons: &Ragged<usize>,
    kind: impl Fn(usize) -> ChainKind,
) -> Result<(), Error> {
    for (pi, p) in polygons.iter().enumerate() {
        if let Some(&c) = p.iter().find(|&&c| c >= n || kind(c) != ChainKind::Ring) {
            return Err(Error::Polygon {
                polygon: pi,
                chain: c,
            });
        }
    }
    Ok(())
}

/// The positions of `chain` put together from `arcs` ([`Topology::chain_coords`]).
pub(crate) fn chain_coords(chain: Chain<'_>, arcs: &Arcs) -> Vec<Coord> {
    // Consecutive arcs share their joint, and a ring's last arc ends at
    // its first position: the count when every joint is one position
    // (a vector grown by doubling would hold a third more on average).
    let joined = (chain.arcs.iter().map(|r| arcs[r.index()].len()))
        .sum::<usize>()
        .saturating_sub(chain.arcs.len().saturating_sub(1));
    let least = if chain.kind == ChainKind::Ring { 4 } else { 0 };
    let mut out: Vec<Coord> = Vec::with_capacity(joined.max(least));
    for r in chain.arcs {
        let arc = &arcs[r.index()];
        let mut push = |c: Coord| {
            if out.last().map(|&l| key(l)) != Some(key(c)) {
                out.push(c);
            }
        };
        if r.reversed() {
            arc.iter().rev().for_each(|&c| push(c));
        } else {
            arc.iter().for_each(|&c| push(c));
        }
    }
    if chain.kind == ChainKind::Ring {
        if let Some(&first) = out.first() {
            if out.len() == 1 || key(first) != key(out[out.len() - 1]) {
                out.push(first);
            }
            // A ring collapsed to one or two positions still has the four
            // a ring needs (RFC 7946).
            while out.len() < 4 {
                out.push(first);
            }
        }
    }
    out
}

/// Cuts chains into arcs and finds each arc again when another chain runs
/// along it.
///
/// Every arc is stored in a canonical form that depends only on its
/// positions, not on which chain met it first: an open arc in the direction
/// whose sequence of positions (compared by their bits) is the smaller, a
/// closed one from its smallest position in its smaller direction. So a part
/// of a coverage holds each of its arcs exactly as the whole does.
struct Builder<'a> {
    /// Each position, by id (compared by [`key`]).
    points: &'a Points,
    /// The arcs found so far, as their positions (a closed arc ends on its
    /// first position again): held as the topology holds them, with no
    /// list of ids beside them.
    arcs: Arcs,
    /// Whether each arc is a ring without junctions (a closed arc).
    closed: Vec<bool>,
    /// The arcs by what they hold ([`Builder::found_by`]).
    index: HashTable<u32>,
    /// The arc being looked up, in its canonical form.
    scratch: Vec<u32>,
}

/// The hash an arc is found by: whether it is closed, and the bits of its
/// positions (without a closed arc's closing repeat).
fn arc_hash(closed: bool, keys: impl ExactSizeIterator<Item = (u64, u64)>) -> u64 {
    let mut h = FxBuildHasher.build_hasher();
    closed.hash(&mut h);
    keys.len().hash(&mut h);
    for k in keys {
        k.hash(&mut h);
    }
    h.finish()
}

impl<'a> Builder<'a> {
    fn new(points: &'a Points) -> Builder<'a> {
        Builder {
            points,
            arcs: Arcs::new(),
            closed: Vec::new(),
            index: HashTable::new(),
            scratch: Vec::new(),
        }
    }

    /// The bits of position `id`, by which arcs are put in canonical form.
    fn key(&self, id: u32) -> (u64, u64) {
        key(self.points[id as usize])
    }

    /// The arc `scratch` (closed or not), stored when it is new.
    fn find_or_add(&mut self, closed: bool) -> u32 {
        let Builder {
            points,
            arcs,
            closed: closed_arcs,
            index,
            scratch,
        } = self;
        let hash = arc_hash(closed, scratch.iter().map(|&i| key(points[i as usize])));
        let found_by = |a: usize| {
            let p = &arcs[a];
            if closed_arcs[a] {
                &p[..p.len() - 1]
            } else {
                p
            }
        };
        let found = index.find(hash, |&a| {
            closed_arcs[a as usize] == closed && {
                let p = found_by(a as usize);
                p.len() == scratch.len()
                    && p.iter()
                        .zip(scratch.iter())
                        .all(|(&c, &i)| key(c) == key(points[i as usize]))
            }
        });
        if let Some(&a) = found {
            return a;
        }
        // Arcs are counted in u32, as positions are, and a reference holds
        // an index of 31 bits: more arcs would take over 2^31 positions
        // (32 GiB), and `ArcRef::new` refuses them.
        let a = arcs.len() as u32;
        let ring = closed.then(|| points[scratch[0] as usize]);
        arcs.push(scratch.iter().map(|&i| points[i as usize]).chain(ring));
        closed_arcs.push(closed);
        index.insert_unique(hash, a, |&b| {
            let b = b as usize;
            let p = &arcs[b];
            let p = if closed_arcs[b] { &p[..p.len() - 1] } else { p };
            arc_hash(closed_arcs[b], p.iter().map(|&c| key(c)))
        });
        a
    }

    fn open_arc(&mut self, run: &[u32]) -> ArcRef {
        let reversed = run
            .iter()
            .rev()
            .map(|&i| self.key(i))
            .lt(run.iter().map(|&i| self.key(i)));
        self.scratch.clear();
        if reversed {
            self.scratch.extend(run.iter().rev());
        } else {
            self.scratch.extend_from_slice(run);
        }
        ArcRef::new(self.find_or_add(false) as usize, reversed)
    }

    fn cut_line(&mut self, path: &[u32], junction: &[bool]) -> Vec<ArcRef> {
        let mut out = Vec::new();
        if path.len() < 2 {
            if !path.is_empty() {
                out.push(self.open_arc(path));
            }
            return out;
        }
        let mut start = 0;
        for i in 1..path.len() {
            if i + 1 == path.len() || junction[path[i] as usize] {
                out.push(self.open_arc(&path[start..=i]));
                start = i;
            }
        }
        out
    }

    fn cut_ring(&mut self, path: &[u32], junction: &[bool]) -> Vec<ArcRef> {
        let k = path.len();
        if k == 0 {
            return Vec::new();
        }
        match (0..k).find(|&i| junction[path[i] as usize]) {
            Some(j) => {
                let mut rotated: Vec<u32> = Vec::with_capacity(k + 1);
                rotated.extend_from_slice(&path[j..]);
                rotated.extend_from_slice(&path[..=j]);
                self.cut_line(&rotated, junction)
            }
            None => vec![self.closed_arc(path)],
        }
    }

    /// A ring without junctions: one closed arc, found again from any start
    /// and in either direction.
    fn closed_arc(&mut self, path: &[u32]) -> ArcRef {
        let k = path.len();
        let m = (0..k).min_by_key(|&i| self.key(path[i])).unwrap_or(0);
        let fwd = (0..k).map(|j| path[(m + j) % k]);
        let bwd = (0..k).map(|j| path[(m + k - j) % k]);
        let reversed = bwd
            .clone()
            .map(|i| self.key(i))
            .lt(fwd.clone().map(|i| self.key(i)));
        self.scratch.clear();
        if reversed {
            self.scratch.extend(bwd);
        } else {
            self.scratch.extend(fwd);
        }
        ArcRef::new(self.find_or_add(true) as usize, reversed)
    }

    /// The arcs' positions.
    fn arcs(self) -> Arcs {
        self.arcs
    }
}

/// Moves every position to the first one met within `eps` of it (Euclidean
/// distance, in the order of the chains and their positions), then puts every
/// position that lies within `eps` of another line's or ring's edge into that
/// edge (a vertex that one side of a border has and the other lacks), so that
/// borders digitised twice with small differences become one. Chains are
/// changed in place.
///
/// A position is put only into edges of chains that do not hold it already
/// (a narrow bay of one ring is not closed up), at the point of the edge
/// nearest to it being strictly inside the edge; every chain that holds the
/// edge gets the position, so edges shared before stay shared. New edges
/// are searched again, a few times, for positions near them.
///
/// # Errors
///
/// [`Error::NonFinite`] for a coordinate that is not finite;
/// [`Error::InvalidOption`] for `eps` that is not a finite non-negative number
/// ([`crate::check_snap`]).
pub fn snap(chains: &mut [(ChainKind, Vec<Coord>)], eps: f64) -> Result<(), Error> {
    snap_in(chains, eps, Frame::Plane)
}

/// [`snap`] in `frame`: in the geographic frame (longitude and latitude in
/// degrees) `eps` is an angle of a great circle in degrees and distances
/// are measured on the ground, a degree of longitude counting as its
/// cosine of latitude (at the position snapped), so that a snap distance
/// in metres is the same east-west as north-south at every latitude.
///
/// # Errors
///
/// As [`snap`].
pub fn snap_in(
    chains: &mut [(ChainKind, Vec<Coord>)],
    eps: f64,
    frame: Frame,
) -> Result<(), Error> {
    crate::options::check_snap(eps)?;
    let mut reps: RTree<GeomWithData<[f64; 2], ()>> = RTree::new();
    let eps2 = eps * eps;
    for (ci, (_, coords)) in chains.iter_mut().enumerate() {
        for (pi, c) in coords.iter_mut().enumerate() {
            if !(c.x.is_finite() && c.y.is_finite()) {
                return Err(Error::NonFinite {
                    chain: ci,
                    position: pi,
                });
            }
            let p = [c.x, c.y];
            let metric = Metric::at(frame, c.y);
            let near = if frame == Frame::Plane {
                reps.nearest_neighbor(&p)
            } else {
                // The nearest on the ground among those in the window.
                reps.locate_in_envelope(&metric.window(p, eps))
                    .min_by(|a, b| {
                        metric
                            .dist2(a.geom(), &p)
                            .total_cmp(&metric.dist2(b.geom(), &p))
                    })
            };
            match near {
                Some(r) if metric.dist2(r.geom(), &p) <= eps2 => {
                    *c = Coord {
                        x: r.geom()[0],
                        y: r.geom()[1],
                    };
                }
                _ => reps.insert(GeomWithData::new(p, ())),
            }
        }
    }
    if eps > 0.0 {
        for _ in 0..SNAP_PASSES {
            if !snap_to_edges(chains, eps, frame) {
                break;
            }
        }
    }
    Ok(())
}

/// Squared distances for snapping: in the plane, or in the geographic frame
/// with a degree of longitude counted as its cosine of latitude.
#[derive(Clone, Copy)]
struct Metric {
    /// What a degree of longitude counts as (1 in the plane).
    kx: f64,
}

impl Metric {
    /// The metric about a position of latitude (or y) `y`.
    fn at(frame: Frame, y: f64) -> Metric {
        Metric {
            kx: match frame {
                Frame::Plane => 1.0,
                // Within a hair of a pole a degree of longitude is next to
                // nothing; the window stays bounded.
                Frame::Geographic => libm::cos(y.to_radians()).abs().max(1e-9),
            },
        }
    }

    fn dist2(self, a: &[f64; 2], b: &[f64; 2]) -> f64 {
        (self.kx * (a[0] - b[0])).powi(2) + (a[1] - b[1]).powi(2)
    }

    /// The box of positions within `eps` of `p`.
    fn window(self, p: [f64; 2], eps: f64) -> rstar::AABB<[f64; 2]> {
        let ex = eps / self.kx;
        rstar::AABB::from_corners([p[0] - ex, p[1] - eps], [p[0] + ex, p[1] + eps])
    }
}

/// Passes of [`snap_to_edges`] at most: each may make edges that come near
/// positions the one before did not see.
const SNAP_PASSES: usize = 4;

/// One pass of putting positions into the edges of other chains within
/// `eps`; false when there was none to put.
fn snap_to_edges(chains: &mut [(ChainKind, Vec<Coord>)], eps: f64, frame: Frame) -> bool {
    type Seg = GeomWithData<rstar::primitives::Line<[f64; 2]>, (usize, usize)>;
    let segs: Vec<Seg> = chains
        .iter()
        .enumerate()
        .flat_map(|(ci, (_, cs))| {
            cs.windows(2)
                .enumerate()
                .filter(|(_, w)| key(w[0]) != key(w[1]))
                .map(move |(si, w)| {
                    let line = rstar::primitives::Line::new([w[0].x, w[0].y], [w[1].x, w[1].y]);
                    GeomWithData::new(line, (ci, si))
                })
        })
        .collect();
    if segs.is_empty() {
        return false;
    }
    let tree = RTree::bulk_load(segs);
    // The chains that hold each position.
    let mut holders: FxHashMap<(u64, u64), (Coord, Vec<usize>)> = FxHashMap::default();
    for (ci, (_, cs)) in chains.iter().enumerate() {
        for &c in cs {
            let h = &mut holders.entry(key(c)).or_insert_with(|| (c, Vec::new())).1;
            if h.last() != Some(&ci) {
                h.push(ci);
            }
        }
    }
    let eps2 = eps * eps;
    // (chain, edge, where along it, position).
    let mut puts: Vec<(usize, usize, f64, Coord)> = Vec::new();
    for (p, held) in holders.values() {
        let metric = Metric::at(frame, p.y);
        let env = metric.window([p.x, p.y], eps);
        for seg in tree.locate_in_envelope_intersecting(&env) {
            let (ci, si) = seg.data;
            if held.contains(&ci) {
                continue;
            }
            let (a, b) = (seg.geom().from, seg.geom().to);
            // The nearest point of the edge in the metric about p.
            let k2 = metric.kx * metric.kx;
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let t = (k2 * (p.x - a[0]) * dx + (p.y - a[1]) * dy) / (k2 * dx * dx + dy * dy);
            if !(t > 0.0 && t < 1.0) {
                continue;
            }
            let near = [a[0] + t * dx, a[1] + t * dy];
            if metric.dist2(&near, &[p.x, p.y]) <= eps2 {
                puts.push((ci, si, t, *p));
            }
        }
    }
    if puts.is_empty() {
        return false;
    }
    puts.sort_by(|x, y| (x.0, x.1).cmp(&(y.0, y.1)).then(x.2.total_cmp(&y.2)));
    let mut k = 0;
    while k < puts.len() {
        let ci = puts[k].0;
        let end = k + puts[k..].iter().take_while(|q| q.0 == ci).count();
        let old = std::mem::take(&mut chains[ci].1);
        let mut new = Vec::with_capacity(old.len() + end - k);
        let mut next = k;
        for (si, &c) in old.iter().enumerate() {
            new.push(c);
            while next < end && puts[next].1 == si {
                new.push(puts[next].3);
                next += 1;
            }
        }
        chains[ci].1 = new;
        k = end;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(x: f64, y: f64) -> Coord {
        Coord { x, y }
    }

    fn square(x: f64, y: f64) -> Vec<Coord> {
        vec![
            c(x, y),
            c(x + 1.0, y),
            c(x + 1.0, y + 1.0),
            c(x, y + 1.0),
            c(x, y),
        ]
    }

    #[test]
    fn two_squares_share_one_arc() {
        let chains = vec![
            (ChainKind::Ring, square(0.0, 0.0)),
            (ChainKind::Ring, square(1.0, 0.0)),
        ];
        let t = Topology::from_chains(&chains, vec![vec![0], vec![1]]).unwrap();
        let uses = t.uses();
        assert_eq!(t.arcs().len(), 3, "arcs {:?}", t.arcs());
        assert_eq!(uses.iter().filter(|&&u| u == 2).count(), 1, "{uses:?}");
        // The shared arc is the edge x = 1, run in opposite directions.
        let shared = uses.iter().position(|&u| u == 2).unwrap();
        let refs: Vec<ArcRef> = t
            .chains()
            .iter()
            .flat_map(|ch| ch.arcs.iter().copied())
            .filter(|r| r.index() == shared)
            .collect();
        assert_eq!(refs.len(), 2);
        assert_ne!(refs[0].reversed(), refs[1].reversed());
        // Chains assemble back to the same rings (rotated).
        for (i, (_, given)) in chains.iter().enumerate() {
            let ring = t.chain_coords(i, t.arcs());
            assert_eq!(ring.len(), 5);
            assert_eq!(ring[0], ring[4]);
            for p in given {
                assert!(ring.contains(p), "{p:?} missing from {ring:?}");
            }
        }
    }

    #[test]
    fn an_island_filling_a_hole_is_one_closed_arc() {
        let shell = vec![
            c(0.0, 0.0),
            c(9.0, 0.0),
            c(9.0, 9.0),
            c(0.0, 9.0),
            c(0.0, 0.0),
        ];
        let hole = vec![
            c(3.0, 3.0),
            c(3.0, 5.0),
            c(5.0, 5.0),
            c(5.0, 3.0),
            c(3.0, 3.0),
        ];
        // The island runs the other way and starts elsewhere.
        let island = vec![
            c(5.0, 5.0),
            c(3.0, 5.0),
            c(3.0, 3.0),
            c(5.0, 3.0),
            c(5.0, 5.0),
        ];
        let chains = vec![
            (ChainKind::Ring, shell),
            (ChainKind::Ring, hole.clone()),
            (ChainKind::Ring, island.clone()),
        ];
        let t = Topology::from_chains(&chains, vec![vec![0, 1], vec![2]]).unwrap();
        assert_eq!(t.arcs().len(), 2);
        assert_eq!(t.chain(1).arcs[0].index(), t.chain(2).arcs[0].index());
        let h = t.chain_coords(1, t.arcs());
        let i = t.chain_coords(2, t.arcs());
        // Same positions, opposite directions, as given.
        let turn = |r: &[Coord]| -> f64 {
            r.windows(2)
                .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
                .sum()
        };
        assert!(turn(&h) * turn(&hole) > 0.0);
        assert!(turn(&i) * turn(&island) > 0.0);
    }

    #[test]
    fn a_line_ending_on_a_ring_cuts_it() {
        let chains = vec![
            (ChainKind::Ring, square(0.0, 0.0)),
            (ChainKind::Line, vec![c(1.0, 1.0), c(2.0, 2.0), c(3.0, 2.0)]),
        ];
        let t = Topology::from_chains(&chains, vec![vec![0]]).unwrap();
        // The ring is cut at (1, 1), where the line ends; a ring with one
        // junction is one arc from that junction round to it.
        let ring = t.chain(0);
        let a = &t.arcs()[ring.arcs[0].index()];
        assert_eq!(ring.arcs.len(), 1);
        assert_eq!(a[0], c(1.0, 1.0));
        assert_eq!(a[a.len() - 1], c(1.0, 1.0));
    }

    #[test]
    fn topojson_references() {
        for k in [0i64, 1, 7, -1, -2, -8] {
            assert_eq!(ArcRef::from_topojson(k).to_topojson(), k);
        }
        assert_eq!(ArcRef::from_topojson(-1), ArcRef::new(0, true));
        assert_eq!(std::mem::size_of::<ArcRef>(), 4);
        let far = ArcRef::from_topojson(1 << 40);
        assert_eq!((far.index(), far.reversed()), (ArcRef::MAX_ARCS - 1, false));
        let r = ArcRef::new(ArcRef::MAX_ARCS - 1, true);
        assert_eq!((r.index(), r.reversed()), (ArcRef::MAX_ARCS - 1, true));
        assert_eq!(
            format!("{r:?}"),
            "ArcRef { arc: 2147483647, reversed: true }"
        );
    }

    #[test]
    fn snapping_merges_near_positions() {
        let mut chains = vec![
            (ChainKind::Line, vec![c(0.0, 0.0), c(1.0, 0.0)]),
            (ChainKind::Line, vec![c(1.0 + 1e-9, 1e-9), c(2.0, 0.0)]),
        ];
        snap(&mut chains, 1e-6).unwrap();
        assert_eq!(chains[1].1[0], c(1.0, 0.0));
        assert_eq!(chains[1].1[1], c(2.0, 0.0));
    }

    #[test]
    fn bad_input_is_named() {
        let chains = vec![(ChainKind::Line, vec![c(0.0, 0.0), c(f64::NAN, 0.0)])];
        assert_eq!(
            Topology::from_chains(&chains, vec![]),
            Err(Error::NonFinite {
                chain: 0,
                position: 1
            })
        );
        let e = Topology::from_arcs(
            vec![vec![c(0.0, 0.0), c(1.0, 0.0)]],
            {
                let mut chains = Chains::new();
                chains.push(ChainKind::Line, [ArcRef::from_topojson(-3)]);
                chains
            },
            vec![],
        );
        assert_eq!(
            e,
            Err(Error::ArcIndex {
                chain: 0,
                arc: -3,
                arcs: 1
            })
        );
    }
}
