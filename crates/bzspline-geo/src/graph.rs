//! The position graph of a coverage's lines and rings: positions compared
//! bit for bit ([`key`]), chains as ids of their distinct positions
//! ([`Paths`]), and the junctions where two runs of edges part or join
//! ([`junctions`]). The topology cuts its arcs there; the nodes of a part
//! are found the same way.

use std::hash::BuildHasher;

use hashbrown::hash_table::{Entry, HashTable};
use rustc_hash::FxBuildHasher;

use geo_types::Coord;

use crate::error::Error;

/// Whether a chain is an open line or a closed ring.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ChainKind {
    /// A LineString: its end positions stay where they are.
    Line,
    /// A polygon's ring: closed, first position equal to the last.
    Ring,
}

/// Bits of a coordinate for exact comparison; `-0.0` counts as `0.0`.
pub(crate) fn key(c: Coord) -> (u64, u64) {
    ((c.x + 0.0).to_bits(), (c.y + 0.0).to_bits())
}

/// Chains as ids of their distinct positions.
pub(crate) struct Paths {
    /// Each distinct position once.
    pub(crate) points: Vec<Coord>,
    /// Each chain as ids into `points`, consecutive repeats merged and a
    /// ring's closing repeat dropped.
    pub(crate) paths: Vec<(ChainKind, Vec<u32>)>,
}

impl Paths {
    /// The paths of `chains`, taken one at a time: chains given by value are
    /// let go of as soon as their ids are found, so that their positions and
    /// the distinct positions are not all held at once.
    pub(crate) fn of<C: AsRef<[Coord]>>(
        chains: impl IntoIterator<Item = (ChainKind, C)>,
    ) -> Result<Paths, Error> {
        let chains = chains.into_iter();
        // The ids by their positions' bits, the positions themselves held
        // once, in `points`.
        let mut ids: HashTable<u32> = HashTable::new();
        let hash = |k: (u64, u64)| FxBuildHasher.hash_one(k);
        let mut points: Vec<Coord> = Vec::new();
        let mut paths: Vec<(ChainKind, Vec<u32>)> = Vec::with_capacity(chains.size_hint().0);
        for (ci, (kind, coords)) in chains.enumerate() {
            let coords = coords.as_ref();
            let mut path: Vec<u32> = Vec::with_capacity(coords.len());
            for (pi, &c) in coords.iter().enumerate() {
                if !(c.x.is_finite() && c.y.is_finite()) {
                    return Err(Error::NonFinite {
                        chain: ci,
                        position: pi,
                    });
                }
                let k = key(c);
                let found = ids.entry(
                    hash(k),
                    |&i| key(points[i as usize]) == k,
                    |&i| hash(key(points[i as usize])),
                );
                let id = match found {
                    Entry::Occupied(e) => *e.get(),
                    Entry::Vacant(v) => {
                        let id = points.len() as u32;
                        v.insert(id);
                        points.push(c);
                        id
                    }
                };
                if path.last() != Some(&id) {
                    path.push(id);
                }
            }
            if kind == ChainKind::Ring {
                while path.len() > 1 && path.first() == path.last() {
                    path.pop();
                }
            }
            paths.push((kind, path));
        }
        Ok(Paths { points, paths })
    }
}

/// A position's neighbours before any chain has met it.
pub(crate) const UNMET: (u32, u32) = (u32::MAX, u32::MAX);

/// Marks every position that ends a line or is met with two different pairs
/// of neighbours; also returns, for each position, the first pair it was
/// met with (ids, smaller first; [`UNMET`] for a position only a line's end
/// or a ring of one position has).
pub(crate) fn junctions(n: usize, paths: &[(ChainKind, Vec<u32>)]) -> (Vec<bool>, Vec<(u32, u32)>) {
    const NONE: (u32, u32) = UNMET;
    let mut seen = vec![NONE; n];
    let mut junction = vec![false; n];
    let mut meet = |p: u32, a: u32, b: u32| {
        let pair = (a.min(b), a.max(b));
        let s = &mut seen[p as usize];
        if *s == NONE {
            *s = pair;
        } else if *s != pair {
            junction[p as usize] = true;
        }
    };
    for (kind, path) in paths {
        let k = path.len();
        match kind {
            ChainKind::Line => {
                for i in 1..k.saturating_sub(1) {
                    meet(path[i], path[i - 1], path[i + 1]);
                }
            }
            ChainKind::Ring => {
                if k >= 2 {
                    for i in 0..k {
                        meet(path[i], path[(i + k - 1) % k], path[(i + 1) % k]);
                    }
                }
            }
        }
    }
    for (kind, path) in paths {
        if *kind == ChainKind::Line {
            if let (Some(&a), Some(&b)) = (path.first(), path.last()) {
                junction[a as usize] = true;
                junction[b as usize] = true;
            }
        }
    }
    (junction, seen)
}
