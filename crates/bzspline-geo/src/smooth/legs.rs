//! The refinement level of every leg of every arc through the rounds of the
//! conflict search, held only for the arcs refined: most arcs of a coverage
//! never are, and a row for every arc took 4 bytes an arc beyond its legs.

use rustc_hash::FxHashMap;

use crate::arcs::Arcs;
use crate::ragged::Ragged;

/// Each arc's legs' levels: 0 for every leg of an arc not listed.
pub(super) struct Legs {
    /// The row in `rows` of each arc listed.
    row_of: FxHashMap<u32, u32>,
    rows: Ragged<u8>,
    /// As many zeros as the longest arc has legs: an arc not listed.
    zeros: Vec<u8>,
}

impl Legs {
    /// Every leg of every arc of `arcs` at 0.
    pub(super) fn new(arcs: &Arcs) -> Legs {
        let longest = arcs.iter().map(<[_]>::len).max().unwrap_or(1);
        Legs {
            row_of: FxHashMap::default(),
            rows: Ragged::new(),
            zeros: vec![0; longest.saturating_sub(1)],
        }
    }

    /// The levels of the legs of arc `a` of `arcs` (the arcs these are
    /// for).
    pub(super) fn get(&self, arcs: &Arcs, a: usize) -> &[u8] {
        match self.row_of.get(&(a as u32)) {
            Some(&r) => &self.rows[r as usize],
            None => &self.zeros[..arcs[a].len() - 1],
        }
    }

    /// The levels of the legs of arc `a` of `arcs`, to change (listed from
    /// now on).
    pub(super) fn get_mut(&mut self, arcs: &Arcs, a: usize) -> &mut [u8] {
        let legs = arcs[a].len() - 1;
        let rows = &mut self.rows;
        let r = *self.row_of.entry(a as u32).or_insert_with(|| {
            rows.push_row(std::iter::repeat_n(0, legs));
            (rows.len() - 1) as u32
        });
        &mut self.rows[r as usize]
    }

    /// The arcs listed, with their levels, in no order.
    pub(super) fn listed(&self) -> impl Iterator<Item = (usize, &[u8])> + '_ {
        self.row_of
            .iter()
            .map(|(&a, &r)| (a as usize, &self.rows[r as usize]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo_types::Coord;

    #[test]
    fn arcs_not_listed_are_at_zero_and_a_change_lists_one() {
        let c = |x: f64| Coord { x, y: 0.0 };
        let arcs = Arcs::from(vec![vec![c(0.0), c(1.0), c(2.0)], vec![c(5.0), c(6.0)]]);
        let mut legs = Legs::new(&arcs);
        assert_eq!(legs.get(&arcs, 0), &[0, 0]);
        assert_eq!(legs.get(&arcs, 1), &[0]);
        legs.get_mut(&arcs, 0)[1] = 3;
        legs.get_mut(&arcs, 0)[0] = 1;
        assert_eq!(legs.get(&arcs, 0), &[1, 3]);
        assert_eq!(legs.get(&arcs, 1), &[0]);
        assert_eq!(legs.listed().collect::<Vec<_>>(), vec![(0, &[1u8, 3][..])]);
    }
}
