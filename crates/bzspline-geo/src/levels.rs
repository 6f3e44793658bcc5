//! Refinement levels carried from one smoothing to another: how often each
//! leg of an arc was halved to resolve a conflict, by a key of the arc's
//! positions. Parts of a coverage smoothed apart merge them between rounds
//! of the conflict search ([`Topology::smooth_round`](crate::Topology::smooth_round)),
//! so that every arc comes out as the whole coverage smoothed at once gives it.

use geo_types::Coord;
use rustc_hash::{FxHashMap, FxHasher};
use std::hash::Hasher;

use crate::graph::key;

/// The key of an arc: a hash of its positions' bits, in order (arcs are
/// stored in a canonical form, so the same arc has the same key in every
/// part and process that holds it).
#[must_use]
pub fn arc_key(arc: &[Coord]) -> u64 {
    let mut h = FxHasher::default();
    h.write_usize(arc.len());
    for &c in arc {
        let (x, y) = key(c);
        h.write_u64(x);
        h.write_u64(y);
    }
    h.finish()
}

/// Per arc key, the level of every leg (0: not refined; above
/// [`MAX_LEVEL`](crate::MAX_LEVEL): kept as the original edge). Arcs not
/// listed have every leg at 0.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Levels {
    map: FxHashMap<u64, Vec<u8>>,
}

impl Levels {
    /// The levels of the arc with key `key`, when any leg is above 0.
    #[must_use]
    pub fn get(&self, key: u64) -> Option<&[u8]> {
        self.map.get(&key).map(Vec::as_slice)
    }

    /// Sets the levels of an arc (dropped when every leg is 0).
    pub fn insert(&mut self, key: u64, levels: Vec<u8>) {
        if levels.iter().any(|&l| l > 0) {
            self.map.insert(key, levels);
        } else {
            self.map.remove(&key);
        }
    }

    /// Raises every leg to at least its level in `other`; returns whether
    /// anything changed. An arc listed in both with a different number of
    /// legs (two arcs with one key) keeps the longer list.
    pub fn merge(&mut self, other: &Levels) -> bool {
        let mut changed = false;
        for (&k, theirs) in &other.map {
            match self.map.get_mut(&k) {
                Some(ours) if ours.len() == theirs.len() => {
                    for (o, &t) in ours.iter_mut().zip(theirs) {
                        if t > *o {
                            *o = t;
                            changed = true;
                        }
                    }
                }
                Some(ours) if ours.len() >= theirs.len() => {}
                _ => {
                    self.map.insert(k, theirs.clone());
                    changed = true;
                }
            }
        }
        changed
    }

    /// How many arcs have a leg above 0.
    #[must_use]
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// Whether no arc is refined.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Every refined arc's key and levels, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (u64, &[u8])> {
        self.map.iter().map(|(&k, v)| (k, v.as_slice()))
    }
}
