//! The shapes of a coverage's geometries in 4 bytes each: a layer has
//! millions of geometries, nearly all a LineString, a MultiLineString or a
//! Polygon with a count of lines or rings, which fit one `u32`; the rest
//! are held as [`Shape`]s beside them.

use std::borrow::Cow;
use std::fmt;

use rustc_hash::FxHashMap;

use crate::coverage::Shape;

/// The kind in a packed shape's top bits.
const KIND_SHIFT: u32 = 30;
/// A packed shape's count: below `2^30`.
const COUNT: u32 = (1 << KIND_SHIFT) - 1;
const LINE_STRING: u32 = 0;
const MULTI_LINE_STRING: u32 = 1;
const POLYGON: u32 = 2;
/// Held in `others`.
const OTHER: u32 = 3;

/// Shapes, numbered from 0 in the order added.
#[derive(Clone, Default)]
pub(crate) struct Shapes {
    /// Each shape's kind and count.
    packed: Vec<u32>,
    /// The shapes of kind [`OTHER`], by index.
    others: FxHashMap<usize, Shape>,
}

impl Shapes {
    /// No shapes yet, with room for `n`.
    pub(crate) fn with_capacity(n: usize) -> Shapes {
        Shapes {
            packed: Vec::with_capacity(n),
            others: FxHashMap::default(),
        }
    }

    /// Adds `s` after the last.
    pub(crate) fn push(&mut self, s: Shape) {
        let fits = |n: usize| u32::try_from(n).ok().filter(|&n| n <= COUNT);
        let packed = match s {
            Shape::LineString => Some(LINE_STRING << KIND_SHIFT),
            Shape::MultiLineString(n) => fits(n).map(|n| (MULTI_LINE_STRING << KIND_SHIFT) | n),
            Shape::Polygon(n) => fits(n).map(|n| (POLYGON << KIND_SHIFT) | n),
            _ => None,
        };
        let packed = packed.unwrap_or_else(|| {
            self.others.insert(self.packed.len(), s);
            OTHER << KIND_SHIFT
        });
        self.packed.push(packed);
    }

    /// How many shapes.
    pub(crate) fn len(&self) -> usize {
        self.packed.len()
    }

    /// Whether there are none.
    pub(crate) fn is_empty(&self) -> bool {
        self.packed.is_empty()
    }

    /// Shape `i`.
    ///
    /// # Panics
    ///
    /// When `i` is past the last shape.
    pub(crate) fn get(&self, i: usize) -> Cow<'_, Shape> {
        let p = self.packed[i];
        let n = (p & COUNT) as usize;
        match p >> KIND_SHIFT {
            LINE_STRING => Cow::Owned(Shape::LineString),
            MULTI_LINE_STRING => Cow::Owned(Shape::MultiLineString(n)),
            POLYGON => Cow::Owned(Shape::Polygon(n)),
            _ => Cow::Borrowed(&self.others[&i]),
        }
    }

    /// The shapes in order.
    pub(crate) fn iter(&self) -> impl ExactSizeIterator<Item = Cow<'_, Shape>> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }
}

impl fmt::Debug for Shapes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo_types::{Geometry, Point};

    #[test]
    fn every_shape_comes_back_as_added() {
        let all = vec![
            Shape::Polygon(1),
            Shape::LineString,
            Shape::Kept(Box::new(Geometry::Point(Point::new(1.0, 2.0)))),
            Shape::MultiLineString(3),
            Shape::Polygon(COUNT as usize),
            Shape::Polygon(COUNT as usize + 1),
            Shape::MultiPolygon(vec![2, 1].into()),
            Shape::Collection(vec![Shape::LineString, Shape::Polygon(4)].into()),
            Shape::MultiLineString(usize::MAX),
        ];
        let mut shapes = Shapes::with_capacity(2);
        for s in &all {
            shapes.push(s.clone());
        }
        assert_eq!(shapes.len(), all.len());
        for (i, s) in all.iter().enumerate() {
            assert_eq!(
                format!("{:?}", shapes.get(i)),
                format!("{s:?}"),
                "shape {i}"
            );
        }
        // Those that fit are packed, the rest held beside them.
        assert_eq!(shapes.others.len(), 5);
    }
}
