//! The nodes of a whole coverage handed to its parts, and how the parts
//! find them (the protocol in [`crate::parts`]).

use std::hash::Hasher;

use geo_types::{Coord, Rect};
use rustc_hash::{FxHashMap, FxHashSet, FxHasher};

use crate::error::Error;
use crate::graph::{junctions, key, ChainKind, Paths, UNMET};

/// Positions that are junctions (nodes of the topology) whatever a part of
/// the coverage finds by itself, and optionally the extent of the whole
/// coverage, which then stands in for a part's own bounding box (the default
/// tolerance is a fraction of its diagonal).
///
/// Positions are compared exactly, bit for bit (`-0.0` equal to `0.0`).
///
/// # Examples
///
/// ```
/// use bzspline_geo::parts::{across, meetings};
/// use bzspline_geo::{coverage_chains, Coverage, SmoothOptions};
/// use geo_types::{polygon, Geometry};
///
/// let a = Geometry::Polygon(polygon![(x: 0.0, y: 0.0), (x: 1.0, y: 0.0), (x: 1.0, y: 1.0), (x: 0.0, y: 1.0)]);
/// let b = Geometry::Polygon(polygon![(x: 1.0, y: 0.0), (x: 2.0, y: 0.0), (x: 2.0, y: 1.0), (x: 1.0, y: 1.0)]);
/// // Two parts of one coverage: each square alone has no junction.
/// let parts = [vec![a], vec![b]];
/// let mut all = Vec::new();
/// for p in &parts {
///     all.extend(meetings(&coverage_chains(p))?);
/// }
/// let nodes = across(all);
/// // The shared border's ends.
/// assert_eq!(nodes.positions(), [(1.0, 0.0).into(), (1.0, 1.0).into()]);
/// let opts = SmoothOptions::default().tolerance(1e-3);
/// let left = Coverage::builder(parts[0].clone()).nodes(nodes.clone()).build()?.smooth(&opts)?.0;
/// let right = Coverage::builder(parts[1].clone()).nodes(nodes).build()?.smooth(&opts)?.0;
/// // Each part is what the whole coverage gives.
/// let whole = Coverage::new([parts[0].clone(), parts[1].clone()].concat())?.smooth(&opts)?.0;
/// assert_eq!(whole, [left, right].concat());
/// # Ok::<(), bzspline_geo::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Nodes {
    keys: FxHashSet<(u64, u64)>,
    extent: Option<Rect<f64>>,
}

impl Nodes {
    /// Nodes at `positions`, without an extent.
    pub fn new(positions: impl IntoIterator<Item = Coord>) -> Nodes {
        Nodes {
            keys: positions.into_iter().map(key).collect(),
            extent: None,
        }
    }

    /// Every junction of `chains` (as [`Topology::from_chains`](crate::Topology::from_chains)
    /// finds them) and their extent: what a part needs when the whole
    /// coverage fits in one process.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a coordinate that is not finite.
    pub fn of(chains: &[(ChainKind, Vec<Coord>)]) -> Result<Nodes, Error> {
        let Paths { points, paths } = Paths::of(chains.iter().map(|(k, c)| (*k, c)))?;
        let (junction, _) = junctions(points.len(), &paths);
        let keys = points
            .iter()
            .zip(&junction)
            .filter(|(_, &j)| j)
            .map(|(&p, _)| key(p))
            .collect();
        Ok(Nodes {
            keys,
            extent: chains_extent(chains),
        })
    }

    /// These nodes with `extent` as the extent of the whole coverage.
    #[must_use]
    pub fn with_extent(mut self, extent: Rect<f64>) -> Nodes {
        self.extent = Some(extent);
        self
    }

    /// The extent of the whole coverage, when set.
    #[must_use]
    pub fn extent(&self) -> Option<Rect<f64>> {
        self.extent
    }

    /// Whether `c` is one of the nodes.
    #[must_use]
    pub fn contains(&self, c: Coord) -> bool {
        self.keys.contains(&key(c))
    }

    /// How many nodes there are.
    #[must_use]
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// The nodes, ordered by x then y.
    #[must_use]
    pub fn positions(&self) -> Vec<Coord> {
        let mut v: Vec<Coord> = self
            .keys
            .iter()
            .map(|&(x, y)| Coord {
                x: f64::from_bits(x),
                y: f64::from_bits(y),
            })
            .collect();
        v.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        v
    }
}

/// How one part of a coverage meets a position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Meeting {
    /// The position.
    pub position: Coord,
    /// `None` when the position is a junction of the part; otherwise a hash
    /// of the two positions every chain of the part meets it between (the
    /// same pair gives the same hash in every part and process).
    pub between: Option<u64>,
}

/// Each distinct position of one part's `chains` and how the part meets it.
/// A position that only a ring of one position has is left out (it cannot
/// make a junction).
///
/// # Errors
///
/// [`Error::NonFinite`] for a coordinate that is not finite.
pub fn meetings(chains: &[(ChainKind, Vec<Coord>)]) -> Result<Vec<Meeting>, Error> {
    let Paths { points, paths } = Paths::of(chains.iter().map(|(k, c)| (*k, c)))?;
    let (junction, seen) = junctions(points.len(), &paths);
    Ok(points
        .iter()
        .zip(junction.iter().zip(&seen))
        .filter(|(_, (&j, &s))| j || s != UNMET)
        .map(|(&p, (&j, &(a, b)))| Meeting {
            position: p,
            between: (!j).then(|| {
                let (ka, kb) = (key(points[a as usize]), key(points[b as usize]));
                let (lo, hi) = if ka <= kb { (ka, kb) } else { (kb, ka) };
                let mut h = FxHasher::default();
                for v in [lo.0, lo.1, hi.0, hi.1] {
                    h.write_u64(v);
                }
                h.finish()
            }),
        })
        .collect())
}

/// The nodes where parts meet, from the [`meetings`] of every part (in any
/// order): each position that two or more parts meet, and that one of them
/// has as a junction or that they meet between different pairs of
/// positions. Every other junction of the whole is a junction of the part
/// that holds it, which finds it by itself. No extent is set.
pub fn across(meetings: impl IntoIterator<Item = Meeting>) -> Nodes {
    // Per position: how many parts meet it, and the pair the first met it
    // between (None once any part disagrees or has a junction there).
    let mut met: FxHashMap<(u64, u64), (u32, Option<u64>)> = FxHashMap::default();
    for m in meetings {
        met.entry(key(m.position))
            .and_modify(|(n, pair)| {
                *n += 1;
                if *pair != m.between {
                    *pair = None;
                }
            })
            .or_insert((1, m.between));
    }
    Nodes {
        keys: met
            .into_iter()
            .filter(|(_, (n, pair))| *n >= 2 && pair.is_none())
            .map(|(k, _)| k)
            .collect(),
        extent: None,
    }
}

/// The bounding box of `chains`' finite positions; `None` without any.
#[must_use]
pub fn chains_extent(chains: &[(ChainKind, Vec<Coord>)]) -> Option<Rect<f64>> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for c in chains.iter().flat_map(|(_, cs)| cs) {
        if c.x.is_finite() && c.y.is_finite() {
            lo = [lo[0].min(c.x), lo[1].min(c.y)];
            hi = [hi[0].max(c.x), hi[1].max(c.y)];
        }
    }
    (lo[0] <= hi[0]).then(|| Rect::new(Coord { x: lo[0], y: lo[1] }, Coord { x: hi[0], y: hi[1] }))
}
