//! Rows of different lengths in one vector: the rings of every polygon, or a
//! value per leg of every arc, held in two allocations rather than one per
//! row (a coverage has millions of polygons and arcs, and each small vector
//! costs more than its few values).

use std::fmt;
use std::ops::{Index, IndexMut};

use crate::offsets::Offsets;

/// Rows of values of different lengths, numbered from 0 in the order added
/// ([`Topology::polygons`](crate::Topology::polygons)): `rows[i]` is row
/// `i`'s values (indexing past the last row panics, as a slice's does). A
/// row costs 4 bytes beyond its values (8 once there are 2^32 values in
/// all), where a `Vec<Vec<T>>` costs 24 and an allocation each.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Ragged<T> {
    starts: Offsets,
    values: Vec<T>,
}

impl<T> Default for Ragged<T> {
    fn default() -> Self {
        let mut starts = Offsets::default();
        starts.push(0);
        Ragged {
            starts,
            values: Vec::new(),
        }
    }
}

impl<T> Ragged<T> {
    /// No rows yet, with room for `rows` rows and `values` values in all.
    #[must_use]
    pub fn with_capacity(rows: usize, values: usize) -> Self {
        let mut starts = Offsets::with_capacity(rows + 1);
        starts.push(0);
        Ragged {
            starts,
            values: Vec::with_capacity(values),
        }
    }

    /// Adds a row of `values` after the last.
    pub fn push_row(&mut self, values: impl IntoIterator<Item = T>) {
        self.values.extend(values);
        self.starts.push(self.values.len());
    }

    /// No rows.
    #[must_use]
    pub fn new() -> Self {
        Ragged::default()
    }

    /// How many rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.starts.len() - 1
    }

    /// Whether there are no rows.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i`'s values, or `None` past the last row.
    #[must_use]
    pub fn get(&self, i: usize) -> Option<&[T]> {
        let end = self.starts.checked(i + 1)?;
        Some(&self.values[self.starts.get(i)..end])
    }

    /// The rows in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[T]> + '_ {
        (0..self.len()).map(|i| &self.values[self.starts.get(i)..self.starts.get(i + 1)])
    }

    /// Every value of every row, in order.
    #[must_use]
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// The rows as a vector each.
    #[must_use]
    pub fn to_vecs(&self) -> Vec<Vec<T>>
    where
        T: Clone,
    {
        self.iter().map(<[T]>::to_vec).collect()
    }
}

impl<T: Clone> Ragged<T> {
    /// Rows of `lengths` values each, every value `value`.
    #[must_use]
    pub fn filled(lengths: impl ExactSizeIterator<Item = usize>, value: T) -> Self {
        let mut starts = Offsets::with_capacity(lengths.len() + 1);
        starts.push(0);
        let mut total = 0;
        for n in lengths {
            total += n;
            starts.push(total);
        }
        Ragged {
            starts,
            values: vec![value; total],
        }
    }
}

impl<T> From<Vec<Vec<T>>> for Ragged<T> {
    fn from(rows: Vec<Vec<T>>) -> Self {
        let total = rows.iter().map(Vec::len).sum();
        let mut out = Ragged::with_capacity(rows.len(), total);
        for r in rows {
            out.push_row(r);
        }
        out
    }
}

impl<T: fmt::Debug> fmt::Debug for Ragged<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T> Index<usize> for Ragged<T> {
    type Output = [T];

    fn index(&self, row: usize) -> &[T] {
        &self.values[self.starts.get(row)..self.starts.get(row + 1)]
    }
}

impl<T> IndexMut<usize> for Ragged<T> {
    fn index_mut(&mut self, row: usize) -> &mut [T] {
        &mut self.values[self.starts.get(row)..self.starts.get(row + 1)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_keep_their_values_and_lengths() {
        let mut r: Ragged<u8> = Ragged::with_capacity(3, 4);
        r.push_row([1, 2]);
        r.push_row([]);
        r.push_row([3, 4, 5]);
        assert_eq!(&r[0], &[1, 2]);
        assert!(r[1].is_empty());
        r[2][1] = 9;
        assert_eq!(
            r.iter().collect::<Vec<_>>(),
            vec![&[1, 2][..], &[], &[3, 9, 5]]
        );
        assert_eq!(r.values(), &[1, 2, 3, 9, 5]);
        let f = Ragged::filled([2, 0, 1].into_iter(), 7u8);
        assert_eq!(f.iter().collect::<Vec<_>>(), vec![&[7, 7][..], &[], &[7]]);
        assert_eq!(Ragged::<u8>::default().iter().count(), 0);
        assert_eq!((f.len(), f.get(1), f.get(3)), (3, Some(&[][..]), None));
        let v = vec![vec![1u8], vec![], vec![2, 3]];
        assert_eq!(Ragged::from(v.clone()).to_vecs(), v);
        assert_eq!(format!("{:?}", Ragged::from(v.clone())), format!("{v:?}"));
    }
}
