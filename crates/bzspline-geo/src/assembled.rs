//! A smoothed coverage's geometries put together one at a time, when asked
//! for: a large layer is written from its smoothed arcs without all of its
//! geometries held at once.

use std::fmt;

use geo_types::Geometry;

use crate::arcs::Arcs;
use crate::chains::Chains;
use crate::coverage::{chains_in, kind_of, rebuild};
use crate::offsets::Offsets;
use crate::shapes::Shapes;
use crate::topology::chain_coords;

/// The geometries of a [`Coverage`](crate::Coverage) with every line and
/// ring put together from smoothed arcs ([`Coverage::into_assembled`](crate::Coverage::into_assembled)),
/// each made when asked for: [`Assembled::get`] gives what
/// [`Coverage::assemble`](crate::Coverage::assemble) gives at the same
/// index. It holds the geometries' shapes, their chains of arcs and the
/// arcs, not the coverage's own positions.
#[derive(Clone)]
pub struct Assembled {
    shapes: Shapes,
    /// Each geometry's first chain.
    first: Offsets,
    chains: Chains,
    arcs: Arcs,
}

impl Assembled {
    pub(crate) fn new(shapes: Shapes, chains: Chains, arcs: Arcs) -> Assembled {
        let mut first = Offsets::with_capacity(shapes.len());
        let mut next = 0;
        for s in shapes.iter() {
            first.push(next);
            next += chains_in(&s);
        }
        Assembled {
            shapes,
            first,
            chains,
            arcs,
        }
    }

    /// How many geometries.
    #[must_use]
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// Geometry `i`, put together.
    ///
    /// # Panics
    ///
    /// When `i` is past the last geometry.
    #[must_use]
    pub fn get(&self, i: usize) -> Geometry<f64> {
        let mut next = self.first.get(i);
        let mut take = || {
            let c = self.chains.get(next).map(|c| chain_coords(c, &self.arcs));
            next += 1;
            c.unwrap_or_default()
        };
        rebuild(&self.shapes.get(i), &mut take)
    }

    /// The geo-types kind of geometry `i` (`"Polygon"`, `"Line"`: the name
    /// of its `Geometry` variant), without putting it together.
    ///
    /// # Panics
    ///
    /// When `i` is past the last geometry.
    #[must_use]
    pub fn kind(&self, i: usize) -> &'static str {
        kind_of(&self.shapes.get(i))
    }

    /// The geometries in order, each put together as it comes.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Geometry<f64>> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The smoothed arcs the lines and rings are put together from.
    #[must_use]
    pub fn arcs(&self) -> &Arcs {
        &self.arcs
    }
}

impl fmt::Debug for Assembled {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Assembled")
            .field("geometries", &self.len())
            .field("chains", &self.chains.len())
            .field("arcs", &self.arcs.len())
            .finish()
    }
}
