//! The protocol by which the parts of a coverage (the partitions of a large
//! one, smoothed in separate processes) come out, bit for bit, as the whole
//! smoothed at once: which features each part holds, and the rounds of the
//! conflict search they run together.
//!
//! Every part is smoothed with the nodes of the whole ([Nodes](#nodes)) and
//! holds three kinds of features:
//!
//! - its own, whose results it keeps;
//! - the *context*: the features of other parts whose bounding box meets the
//!   part's extent ([`is_context`]). A conflict between two features means
//!   their boxes meet (every curve stays in the hull of its control points),
//!   so the owner of either holds the pair, and it judges conflicts and ring
//!   flips of its own features and the context exactly;
//! - the features *around*: those of other parts, not already context, whose
//!   box meets the extent of the part and its context together ([`outer`],
//!   [`is_around`]), held for the topology only, so that the context's arcs
//!   are cut where the whole cuts them.
//!
//! Then [`Rounds`]: each round, every part runs one round of the conflict
//! search ([`Coverage::smooth_round`](crate::Coverage::smooth_round)) from the
//! levels all parts ended the round before at, and the levels they end at are
//! merged (each leg at its highest); when no part raised any, the parts'
//! results of that round are the whole's. There are at most [`MAX_ROUNDS`].
//!
//! ## Nodes
//!
//! The [`Nodes`](crate::Nodes) are found over the whole coverage and handed
//! to every part, so that each part, smoothed alone, cuts every arc it holds
//! as the whole coverage would, and smooths it the same.
//!
//! A part of a coverage (one partition of a large one, say) finds its own
//! junctions, but not those it shares with other parts: where a border runs
//! on in another part, or another part's line ends on it, the part sees no
//! junction. [`meetings`] says, for one part, how each of its positions is
//! met; [`across`] combines the parts' meetings into the positions that are
//! junctions of the whole but maybe not of a part; given those
//! ([`CoverageBuilder::nodes`](crate::CoverageBuilder::nodes)), every part cuts
//! its chains where the whole does. Arcs are stored in a canonical form that
//! does not depend on the order of the chains, so the same arc is smoothed
//! to the same positions, bit for bit, in every part that holds it and the
//! rings that use it.
//!
//! Two things about an arc depend on more than the arc: how many positions it
//! must keep (a ring of two arcs keeps three from each), and whether it must
//! be refined (where it would come too close to another arc). A part decides
//! them right when it also holds the features of other parts that meet its
//! extent (a ring that shares an arc, and an arc that comes near one, meet
//! it), those next to them (so that their arcs are cut as in the whole), and
//! runs the rounds of the conflict search together with the other parts,
//! passing the [`Levels`] between rounds, as above.

use geo_types::{coord, Rect};

use crate::error::Error;
pub use crate::levels::{arc_key, Levels};
pub use crate::nodes::{across, chains_extent, meetings, Meeting};

/// The most rounds parts run together before giving up (the whole needs at
/// most three times [`crate::MAX_LEVEL`]; this leaves room for every part's
/// refinement to reach every other).
pub const MAX_ROUNDS: usize = 64;

/// Whether two closed boxes have a point in common.
#[must_use]
pub fn meets(a: &Rect<f64>, b: &Rect<f64>) -> bool {
    a.min().x <= b.max().x
        && b.min().x <= a.max().x
        && a.min().y <= b.max().y
        && b.min().y <= a.max().y
}

/// The smallest box holding all of `boxes`; `None` for none.
#[must_use]
pub fn extent<'a>(boxes: impl IntoIterator<Item = &'a Rect<f64>>) -> Option<Rect<f64>> {
    boxes.into_iter().copied().reduce(|e, r| {
        Rect::new(
            coord! { x: e.min().x.min(r.min().x), y: e.min().y.min(r.min().y) },
            coord! { x: e.max().x.max(r.max().x), y: e.max().y.max(r.max().y) },
        )
    })
}

/// Whether a feature of another part, with bounding box `feature`, is context
/// of the part whose extent is `part`: held and judged exactly.
#[must_use]
pub fn is_context(feature: &Rect<f64>, part: &Rect<f64>) -> bool {
    meets(feature, part)
}

/// The extent of a part and its context, which the features around it meet.
#[must_use]
pub fn outer<'a>(
    part: &'a Rect<f64>,
    context: impl IntoIterator<Item = &'a Rect<f64>>,
) -> Rect<f64> {
    extent(std::iter::once(part).chain(context)).unwrap_or(*part)
}

/// Whether a feature of another part, with bounding box `feature`, is held
/// around the part (extent `part`, with its context `outer`) for the
/// topology only: it meets `outer` and is not context.
#[must_use]
pub fn is_around(feature: &Rect<f64>, part: &Rect<f64>, outer: &Rect<f64>) -> bool {
    meets(feature, outer) && !is_context(feature, part)
}

/// The features each part holds, for a coverage whose features are all at
/// hand: `boxes[i]` is feature `i`'s bounding box (`None` when empty),
/// `part[i]` its part. For part `p`: its own features, then its context, then
/// the features around it, each in the features' order.
#[must_use]
pub fn holdings(boxes: &[Option<Rect<f64>>], part: &[usize], p: usize) -> Holding {
    let own: Vec<usize> = (0..part.len()).filter(|&i| part[i] == p).collect();
    let Some(ext) = extent(own.iter().filter_map(|&i| boxes[i].as_ref())) else {
        return Holding {
            own,
            context: Vec::new(),
            around: Vec::new(),
        };
    };
    let others = |keep: &dyn Fn(&Rect<f64>) -> bool| -> Vec<usize> {
        (0..part.len())
            .filter(|&i| part[i] != p && boxes[i].as_ref().is_some_and(keep))
            .collect()
    };
    let context = others(&|b| is_context(b, &ext));
    let out = outer(&ext, context.iter().filter_map(|&i| boxes[i].as_ref()));
    let around = others(&|b| is_around(b, &ext, &out));
    Holding {
        own,
        context,
        around,
    }
}

/// What one part holds ([`holdings`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Holding {
    /// Its own features.
    pub own: Vec<usize>,
    /// Other parts' features it judges exactly.
    pub context: Vec<usize>,
    /// Other parts' features it holds for the topology only.
    pub around: Vec<usize>,
}

impl Holding {
    /// Every feature held: own, context, around, in that order.
    #[must_use]
    pub fn held(&self) -> Vec<usize> {
        [&self.own[..], &self.context, &self.around].concat()
    }

    /// For [`Coverage::smooth_round`](crate::Coverage::smooth_round): which
    /// of [`Holding::held`] are judged exactly (own and context).
    #[must_use]
    pub fn exact(&self) -> Vec<bool> {
        let exact = self.own.len() + self.context.len();
        (0..exact + self.around.len()).map(|i| i < exact).collect()
    }
}

/// The rounds of the conflict search that parts run together: the round to
/// run and the levels to run it from, then the levels every part ended at.
///
/// # Examples
///
/// ```
/// use bzspline_geo::parts::{Levels, Rounds};
///
/// let mut rounds = Rounds::new();
/// assert_eq!(rounds.round(), 1);
/// // No part raised a level: the parts' results of round 1 are the whole's.
/// let ended = [Levels::default(), Levels::default()];
/// assert!(!rounds.finish(&ended)?);
/// # Ok::<(), bzspline_geo::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Rounds {
    round: usize,
    levels: Levels,
}

impl Rounds {
    /// Before the first round.
    #[must_use]
    pub fn new() -> Self {
        Rounds {
            round: 1,
            levels: Levels::default(),
        }
    }

    /// The round to run (from 1).
    #[must_use]
    pub fn round(&self) -> usize {
        self.round.max(1)
    }

    /// The levels every part runs this round from.
    #[must_use]
    pub fn levels(&self) -> &Levels {
        &self.levels
    }

    /// Ends the round with the levels each part ended it at: `true` when some
    /// part raised a level, so another round is to run (from the merged
    /// levels); `false` when none did, and the parts' results of this round
    /// are the whole's.
    ///
    /// # Errors
    ///
    /// [`Error::Rounds`] when levels were still raised in round
    /// [`MAX_ROUNDS`].
    pub fn finish<'a>(
        &mut self,
        ended: impl IntoIterator<Item = &'a Levels>,
    ) -> Result<bool, Error> {
        let mut changed = false;
        for l in ended {
            changed |= self.levels.merge(l);
        }
        if !changed {
            return Ok(false);
        }
        if self.round() >= MAX_ROUNDS {
            return Err(Error::Rounds { rounds: MAX_ROUNDS });
        }
        self.round = self.round() + 1;
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(x0: f64, y0: f64, x1: f64, y1: f64) -> Rect<f64> {
        Rect::new(coord! { x: x0, y: y0 }, coord! { x: x1, y: y1 })
    }

    #[test]
    fn boxes_meet_when_closed() {
        assert!(meets(&r(0.0, 0.0, 1.0, 1.0), &r(1.0, 1.0, 2.0, 2.0)));
        assert!(!meets(&r(0.0, 0.0, 1.0, 1.0), &r(1.5, 0.0, 2.0, 1.0)));
        assert_eq!(
            extent([&r(0.0, 0.0, 1.0, 1.0), &r(2.0, -1.0, 3.0, 0.5)]),
            Some(r(0.0, -1.0, 3.0, 1.0))
        );
        assert_eq!(extent(std::iter::empty()), None);
    }

    #[test]
    fn a_part_holds_its_neighbours_and_theirs() {
        // Five unit cells in a row, parts 0 0 1 1 1: part 0's extent is
        // [0, 2]; cell 2 touches it (context), cell 3 touches cell 2 (around),
        // cell 4 is too far.
        let boxes: Vec<_> = (0..5)
            .map(|i| Some(r(i as f64, 0.0, i as f64 + 1.0, 1.0)))
            .collect();
        let part = [0, 0, 1, 1, 1];
        let h = holdings(&boxes, &part, 0);
        assert_eq!((h.own, h.context, h.around), (vec![0, 1], vec![2], vec![3]));
        let h = holdings(&boxes, &part, 1);
        assert_eq!(h.held(), vec![2, 3, 4, 1, 0]);
        assert_eq!(h.exact(), vec![true, true, true, true, false]);
        // An empty feature belongs to no neighbourhood.
        let mut boxes = boxes;
        boxes[2] = None;
        assert_eq!(holdings(&boxes, &part, 0).context, Vec::<usize>::new());
    }

    #[test]
    fn rounds_stop_when_nothing_is_raised_and_give_up_at_the_cap() {
        let mut rounds = Rounds::new();
        assert!(!rounds.finish(std::iter::empty()).unwrap());
        let mut raised = Levels::default();
        raised.insert(7, vec![0, 2, 1]);
        let mut rounds = Rounds::new();
        assert!(rounds.finish([&raised]).unwrap());
        assert_eq!(rounds.round(), 2);
        assert_eq!(rounds.levels(), &raised);
        // The same levels again: nothing raised, done.
        assert!(!rounds.finish([&raised, &Levels::default()]).unwrap());
        let mut rounds = Rounds::new();
        for k in 0..MAX_ROUNDS as u8 - 1 {
            let mut l = rounds.levels().clone();
            l.insert(1, vec![k + 1]);
            assert!(rounds.finish([&l]).unwrap());
        }
        let mut l = rounds.levels().clone();
        l.insert(1, vec![MAX_ROUNDS as u8]);
        assert_eq!(
            rounds.finish([&l]),
            Err(Error::Rounds { rounds: MAX_ROUNDS })
        );
    }
}
