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

/// Positions by id, in chunks that stay where they are: a vector of
/// millions grows by copying itself into one twice its size, holding both
/// for a moment.
#[derive(Default)]
pub(crate) struct Points {
    chunks: Vec<Vec<Coord>>,
}

/// Positions per chunk of [`Points`] (1 MiB).
const CHUNK_SHIFT: u32 = 16;

impl Points {
    /// Adds `c`; returns its id.
    fn push(&mut self, c: Coord) -> u32 {
        let id = self.len() as u32;
        match self.chunks.last_mut() {
            Some(chunk) if chunk.len() < 1 << CHUNK_SHIFT => chunk.push(c),
            _ => {
                let mut chunk = Vec::with_capacity(1 << CHUNK_SHIFT);
                chunk.push(c);
                self.chunks.push(chunk);
            }
        }
        id
    }

    /// How many positions.
    pub(crate) fn len(&self) -> usize {
        self.chunks.last().map_or(0, |last| {
            ((self.chunks.len() - 1) << CHUNK_SHIFT) + last.len()
        })
    }

    /// The positions by id.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Coord> + '_ {
        self.chunks.iter().flatten()
    }
}

impl std::ops::Index<usize> for Points {
    type Output = Coord;

    #[inline]
    fn index(&self, id: usize) -> &Coord {
        &self.chunks[id >> CHUNK_SHIFT][id & ((1 << CHUNK_SHIFT) - 1)]
    }
}

/// Chains as ids of their distinct positions.
pub(crate) struct Paths {
    /// Each distinct position once.
    pub(crate) points: Points,
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
        Paths::with_room(chains, 0)
    }

    /// As [`Paths::of`], with room for at least `room` chains from the
    /// start (when the chains' iterator cannot tell how many it holds).
    pub(crate) fn with_room<C: AsRef<[Coord]>>(
        chains: impl IntoIterator<Item = (ChainKind, C)>,
        room: usize,
    ) -> Result<Paths, Error> {
        let chains = chains.into_iter();
        // The ids by their positions' bits, the positions themselves held
        // once, in `points`.
        let mut ids: HashTable<u32> = HashTable::new();
        let hash = |k: (u64, u64)| FxBuildHasher.hash_one(k);
        let mut points = Points::default();
        let mut paths: Vec<(ChainKind, Vec<u32>)> =
            Vec::with_capacity(chains.size_hint().0.max(room));
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
                        let id = points.push(c);
                        v.insert(id);
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
