//! A topology's lines and rings, each as the arcs it runs along, all in one
//! vector: a coverage has millions of rings of a few arcs each, and a
//! vector for each would cost more than its references.

use crate::ragged::Ragged;
use crate::topology::{ArcRef, ChainKind};

/// A line or ring as the arcs it runs along, in order, each joined to the
/// next at a shared end position ([`Chains::get`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chain<'a> {
    /// Line or ring.
    pub kind: ChainKind,
    /// The arcs, in order.
    pub arcs: &'a [ArcRef],
}

/// Lines and rings, numbered from 0 in the order added
/// ([`Topology::chains`](crate::Topology::chains)). A chain costs 5 bytes
/// beyond its references (9 once there are 2^32 references in all).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Chains {
    kinds: Vec<ChainKind>,
    arcs: Ragged<ArcRef>,
}

impl Chains {
    /// No chains.
    #[must_use]
    pub fn new() -> Chains {
        Chains::default()
    }

    /// No chains yet, with room for `chains` chains of `arcs` references in
    /// all.
    #[must_use]
    pub fn with_capacity(chains: usize, arcs: usize) -> Chains {
        Chains {
            kinds: Vec::with_capacity(chains),
            arcs: Ragged::with_capacity(chains, arcs),
        }
    }

    /// Adds a chain of `kind` along `arcs` after the last.
    pub fn push(&mut self, kind: ChainKind, arcs: impl IntoIterator<Item = ArcRef>) {
        self.kinds.push(kind);
        self.arcs.push_row(arcs);
    }

    /// How many chains.
    #[must_use]
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// Chain `i`, or `None` past the last.
    #[must_use]
    pub fn get(&self, i: usize) -> Option<Chain<'_>> {
        Some(Chain {
            kind: *self.kinds.get(i)?,
            arcs: &self.arcs[i],
        })
    }

    /// The chains in order.
    #[must_use]
    pub fn iter(&self) -> ChainsIter<'_> {
        ChainsIter {
            chains: self,
            next: 0,
        }
    }

    /// Each chain's kind, in order.
    #[must_use]
    pub fn kinds(&self) -> &[ChainKind] {
        &self.kinds
    }

    /// Every chain's references, in order.
    #[must_use]
    pub fn refs(&self) -> &[ArcRef] {
        self.arcs.values()
    }
}

/// The chains of a [`Chains`] in order ([`Chains::iter`]).
#[derive(Clone, Debug)]
pub struct ChainsIter<'a> {
    chains: &'a Chains,
    next: usize,
}

impl<'a> Iterator for ChainsIter<'a> {
    type Item = Chain<'a>;

    fn next(&mut self) -> Option<Chain<'a>> {
        let c = self.chains.get(self.next)?;
        self.next += 1;
        Some(c)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.chains.len() - self.next;
        (n, Some(n))
    }
}

impl ExactSizeIterator for ChainsIter<'_> {}

impl<'a> IntoIterator for &'a Chains {
    type Item = Chain<'a>;
    type IntoIter = ChainsIter<'a>;

    fn into_iter(self) -> ChainsIter<'a> {
        self.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_keep_their_kind_and_arcs_in_order() {
        let r = ArcRef::new;
        let mut c = Chains::with_capacity(1, 1);
        c.push(ChainKind::Ring, [r(0, false), r(1, true)]);
        c.push(ChainKind::Line, []);
        c.push(ChainKind::Line, [r(1, false)]);
        assert_eq!((c.len(), c.is_empty()), (3, false));
        assert_eq!(
            c.get(0),
            Some(Chain {
                kind: ChainKind::Ring,
                arcs: &[r(0, false), r(1, true)]
            })
        );
        assert_eq!(c.get(1).map(|ch| ch.arcs.len()), Some(0));
        assert_eq!(c.get(3), None);
        let kinds: Vec<ChainKind> = (&c).into_iter().map(|ch| ch.kind).collect();
        assert_eq!(kinds, [ChainKind::Ring, ChainKind::Line, ChainKind::Line]);
        assert_eq!(c.iter().len(), 3);
        assert_eq!(c.refs(), &[r(0, false), r(1, true), r(1, false)]);
        assert!(Chains::new().is_empty());
    }
}
