//! Places in one long vector, 4 bytes each while every place fits in 32
//! bits: the starts of a [`crate::Ragged`]'s rows and of [`crate::Arcs`]'
//! arcs. A coverage has millions of rows and arcs, so the 4 bytes saved on
//! each count; past 2^32 values the places are held in 8 bytes each.

use std::hash::{Hash, Hasher};

/// A vector of places (indices into another vector).
#[derive(Clone)]
pub(crate) enum Offsets {
    /// Every place below 2^32.
    Narrow(Vec<u32>),
    /// Some place at or beyond 2^32.
    Wide(Vec<usize>),
}

impl Default for Offsets {
    fn default() -> Self {
        Offsets::Narrow(Vec::new())
    }
}

impl Offsets {
    /// None yet, with room for `n`.
    pub(crate) fn with_capacity(n: usize) -> Self {
        Offsets::Narrow(Vec::with_capacity(n))
    }

    /// How many places.
    pub(crate) fn len(&self) -> usize {
        match self {
            Offsets::Narrow(v) => v.len(),
            Offsets::Wide(v) => v.len(),
        }
    }

    /// Whether there are none.
    pub(crate) fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Place `i` (panics past the last, as a slice does).
    #[inline]
    pub(crate) fn get(&self, i: usize) -> usize {
        match self {
            Offsets::Narrow(v) => v[i] as usize,
            Offsets::Wide(v) => v[i],
        }
    }

    /// Place `i`, or `None` past the last.
    #[inline]
    pub(crate) fn checked(&self, i: usize) -> Option<usize> {
        match self {
            Offsets::Narrow(v) => v.get(i).map(|&p| p as usize),
            Offsets::Wide(v) => v.get(i).copied(),
        }
    }

    /// Adds `place` after the last.
    pub(crate) fn push(&mut self, place: usize) {
        match self {
            Offsets::Narrow(v) => match u32::try_from(place) {
                Ok(p) => v.push(p),
                Err(_) => {
                    self.widen();
                    self.push(place);
                }
            },
            Offsets::Wide(v) => v.push(place),
        }
    }

    /// Makes place `i` `place` (panics past the last).
    pub(crate) fn set(&mut self, i: usize, place: usize) {
        match self {
            Offsets::Narrow(v) => match u32::try_from(place) {
                Ok(p) => v[i] = p,
                Err(_) => {
                    self.widen();
                    self.set(i, place);
                }
            },
            Offsets::Wide(v) => v[i] = place,
        }
    }

    /// Holds the places in 8 bytes each from now on.
    fn widen(&mut self) {
        if let Offsets::Narrow(v) = self {
            let mut wide = Vec::with_capacity(v.capacity().max(v.len() + 1));
            wide.extend(v.iter().map(|&p| p as usize));
            *self = Offsets::Wide(wide);
        }
    }

    /// The places in order.
    pub(crate) fn iter(&self) -> impl ExactSizeIterator<Item = usize> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }
}

impl PartialEq for Offsets {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len() && self.iter().eq(other.iter())
    }
}

impl Eq for Offsets {}

impl Hash for Offsets {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.len().hash(state);
        self.iter().for_each(|p| p.hash(state));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_past_32_bits_widen_and_keep_the_others() {
        let mut o = Offsets::with_capacity(2);
        o.push(3);
        o.push(u32::MAX as usize);
        assert!(matches!(o, Offsets::Narrow(_)));
        let narrow = o.clone();
        o.push(1 << 33);
        assert!(matches!(o, Offsets::Wide(_)));
        assert_eq!(
            o.iter().collect::<Vec<_>>(),
            [3, u32::MAX as usize, 1 << 33]
        );
        assert_eq!((o.checked(2), o.checked(3)), (Some(1 << 33), None));
        // Equal whatever the width.
        let mut w = narrow.clone();
        w.widen();
        assert!(w == narrow && matches!(w, Offsets::Wide(_)));
        let hash = |o: &Offsets| {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            o.hash(&mut h);
            h.finish()
        };
        assert_eq!(hash(&w), hash(&narrow));
        let mut s = narrow;
        s.set(0, 1 << 40);
        assert_eq!((s.get(0), s.get(1)), (1 << 40, u32::MAX as usize));
    }
}
