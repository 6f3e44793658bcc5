//! The positions of many arcs in a few large blocks: a coverage has
//! millions of short arcs, and a vector for each would cost more than its
//! few positions.

use std::fmt;
use std::ops::Index;

use geo_types::Coord;

use crate::offsets::Offsets;
use crate::positions::Positions;

/// Arcs, each a slice of positions, numbered from 0 in the order added
/// ([`Topology::arcs`](crate::Topology::arcs), [`Smoothed::arcs`](crate::Smoothed::arcs)).
///
/// The positions are held in blocks of a MiB or more, an arc's together,
/// and each arc as its place in them, so an arc costs 8 bytes beyond its
/// positions (12 once there are 2^32 positions in all; a `Vec<Vec<Coord>>`
/// costs 24 and an allocation each), and adding arcs never copies those
/// already held. `arcs[i]` is arc `i`'s positions; indexing
/// past the last arc panics, as a slice's does ([`Arcs::get`] does not).
/// Two `Arcs` are equal when they hold the same arcs, however the positions
/// are laid out.
#[derive(Clone, Default)]
pub struct Arcs {
    starts: Offsets,
    lens: Vec<u32>,
    positions: Positions,
}

impl Arcs {
    /// No arcs.
    #[must_use]
    pub fn new() -> Arcs {
        Arcs::default()
    }

    /// No arcs yet, with room for `arcs` arcs of `positions` positions in
    /// all (in one block: more are added as needed).
    #[must_use]
    pub fn with_capacity(arcs: usize, positions: usize) -> Arcs {
        Arcs {
            starts: Offsets::with_capacity(arcs),
            lens: Vec::with_capacity(arcs),
            positions: Positions::with_capacity(positions),
        }
    }

    /// How many arcs.
    #[must_use]
    pub fn len(&self) -> usize {
        self.starts.len()
    }

    /// Whether there are no arcs.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.starts.is_empty()
    }

    /// Arc `i`'s positions, or `None` past the last arc.
    #[must_use]
    pub fn get(&self, i: usize) -> Option<&[Coord]> {
        let start = self.starts.checked(i)?;
        Some(self.positions.get(start, self.lens[i] as usize))
    }

    /// The address of arc `i`'s first position: its `k`-th is at the
    /// address plus `k`, and no two arcs' positions share an address, so a
    /// value per position fits a vector of [`Arcs::span`] values.
    pub(crate) fn address(&self, i: usize) -> usize {
        self.starts.get(i)
    }

    /// One past the largest address ([`Arcs::address`]).
    pub(crate) fn span(&self) -> usize {
        self.positions.span()
    }

    /// The positions in the order held, in runs at consecutive addresses,
    /// each with the address of its first ([`Arcs::address`]): every arc's
    /// positions, and those an arc replaced by more ([`Arcs::set`]) left
    /// behind.
    pub(crate) fn runs(&self) -> impl Iterator<Item = (usize, &[Coord])> + '_ {
        self.positions.blocks()
    }

    /// The arcs in order.
    pub fn iter(&self) -> ArcsIter<'_> {
        ArcsIter {
            arcs: self,
            front: 0,
            back: self.len(),
        }
    }

    /// Adds an arc after the last.
    ///
    /// # Panics
    ///
    /// When the arc has more than `u32::MAX` positions.
    pub fn push(&mut self, arc: impl IntoIterator<Item = Coord>) {
        let mut n = 0usize;
        let start = self.positions.push(arc.into_iter().inspect(|_| n += 1));
        self.starts.push(start);
        self.lens.push(span(n));
    }

    /// Replaces arc `i`'s positions: in its place when they fit there, else
    /// after every other arc's (the old positions then go unused).
    ///
    /// # Panics
    ///
    /// When `i` is past the last arc, or `arc` has more than `u32::MAX`
    /// positions.
    pub fn set(&mut self, i: usize, arc: &[Coord]) {
        let n = span(arc.len());
        if n <= self.lens[i] {
            let start = self.starts.get(i);
            self.positions
                .get_mut(start, arc.len())
                .copy_from_slice(arc);
        } else {
            let start = self.positions.push_slice(arc);
            self.starts.set(i, start);
        }
        self.lens[i] = n;
    }

    /// The arcs as a vector each.
    #[must_use]
    pub fn to_vecs(&self) -> Vec<Vec<Coord>> {
        self.iter().map(<[Coord]>::to_vec).collect()
    }
}

/// An arc's length as stored.
fn span(n: usize) -> u32 {
    u32::try_from(n).expect("an arc has at most u32::MAX positions")
}

impl Index<usize> for Arcs {
    type Output = [Coord];

    fn index(&self, i: usize) -> &[Coord] {
        self.positions
            .get(self.starts.get(i), self.lens[i] as usize)
    }
}

/// The arcs of an [`Arcs`] in order ([`Arcs::iter`]).
#[derive(Clone, Debug)]
pub struct ArcsIter<'a> {
    arcs: &'a Arcs,
    front: usize,
    back: usize,
}

impl<'a> Iterator for ArcsIter<'a> {
    type Item = &'a [Coord];

    fn next(&mut self) -> Option<&'a [Coord]> {
        if self.front == self.back {
            return None;
        }
        self.front += 1;
        Some(&self.arcs[self.front - 1])
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.back - self.front;
        (n, Some(n))
    }
}

impl ExactSizeIterator for ArcsIter<'_> {}

impl DoubleEndedIterator for ArcsIter<'_> {
    fn next_back(&mut self) -> Option<Self::Item> {
        if self.front == self.back {
            return None;
        }
        self.back -= 1;
        Some(&self.arcs[self.back])
    }
}

impl<'a> IntoIterator for &'a Arcs {
    type Item = &'a [Coord];
    type IntoIter = ArcsIter<'a>;

    fn into_iter(self) -> ArcsIter<'a> {
        self.iter()
    }
}

impl PartialEq for Arcs {
    fn eq(&self, other: &Arcs) -> bool {
        self.len() == other.len() && self.iter().eq(other.iter())
    }
}

impl fmt::Debug for Arcs {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<A: IntoIterator<Item = Coord>> FromIterator<A> for Arcs {
    fn from_iter<I: IntoIterator<Item = A>>(iter: I) -> Arcs {
        let mut arcs = Arcs::new();
        for a in iter {
            arcs.push(a);
        }
        arcs
    }
}

impl From<Vec<Vec<Coord>>> for Arcs {
    fn from(arcs: Vec<Vec<Coord>>) -> Arcs {
        let total = arcs.iter().map(Vec::len).sum();
        let mut out = Arcs::with_capacity(arcs.len(), total);
        for a in arcs {
            out.push(a);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(x: f64) -> Coord {
        Coord { x, y: -x }
    }

    #[test]
    fn arcs_keep_their_positions_through_replacement() {
        let rows = vec![vec![c(1.0), c(2.0)], vec![], vec![c(3.0), c(4.0), c(5.0)]];
        let mut arcs = Arcs::from(rows.clone());
        assert_eq!(arcs.len(), 3);
        assert_eq!(arcs.to_vecs(), rows);
        assert_eq!(arcs.get(3), None);
        // Shorter: in place; longer: moved to the end; equality ignores where.
        arcs.set(2, &[c(6.0)]);
        arcs.set(0, &[c(7.0), c(8.0), c(9.0)]);
        arcs.set(1, &[c(10.0)]);
        let want = vec![vec![c(7.0), c(8.0), c(9.0)], vec![c(10.0)], vec![c(6.0)]];
        assert_eq!(arcs.to_vecs(), want);
        assert_eq!(arcs, want.iter().cloned().collect::<Arcs>());
        assert_ne!(arcs, Arcs::from(rows));
        assert_eq!(&arcs[0], &want[0][..]);
        assert_eq!(arcs.iter().next_back(), Some(&want[2][..]));
        assert_eq!(
            format!("{:?}", Arcs::from(vec![vec![c(0.0)]])),
            format!("{:?}", [[c(0.0)]])
        );
    }
}
