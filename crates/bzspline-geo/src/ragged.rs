//! Rows of different lengths in one vector: a value per leg or position of
//! every arc held in two allocations rather than one per arc (a coverage
//! has millions of short arcs, and each small vector costs more than its
//! few values).

use std::ops::{Index, IndexMut};

/// Rows of values, row `i` the values from `starts[i]` to `starts[i + 1]`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Ragged<T> {
    starts: Vec<usize>,
    values: Vec<T>,
}

impl<T> Default for Ragged<T> {
    fn default() -> Self {
        Ragged {
            starts: vec![0],
            values: Vec::new(),
        }
    }
}

impl<T> Ragged<T> {
    /// Room for `rows` rows and `values` values in all.
    pub(crate) fn with_capacity(rows: usize, values: usize) -> Self {
        let mut starts = Vec::with_capacity(rows + 1);
        starts.push(0);
        Ragged {
            starts,
            values: Vec::with_capacity(values),
        }
    }

    /// Adds a row of `values` after the last.
    pub(crate) fn push_row(&mut self, values: impl IntoIterator<Item = T>) {
        self.values.extend(values);
        self.starts.push(self.values.len());
    }

    /// The rows in order.
    pub(crate) fn rows(&self) -> impl Iterator<Item = &[T]> {
        self.starts.windows(2).map(|w| &self.values[w[0]..w[1]])
    }

    /// Every value of every row, in order.
    pub(crate) fn values(&self) -> &[T] {
        &self.values
    }
}

impl<T: Clone> Ragged<T> {
    /// Rows of `lengths` values each, every value `value`.
    pub(crate) fn filled(lengths: impl ExactSizeIterator<Item = usize>, value: T) -> Self {
        let mut starts = Vec::with_capacity(lengths.len() + 1);
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

impl<T> Index<usize> for Ragged<T> {
    type Output = [T];

    fn index(&self, row: usize) -> &[T] {
        &self.values[self.starts[row]..self.starts[row + 1]]
    }
}

impl<T> IndexMut<usize> for Ragged<T> {
    fn index_mut(&mut self, row: usize) -> &mut [T] {
        &mut self.values[self.starts[row]..self.starts[row + 1]]
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
            r.rows().collect::<Vec<_>>(),
            vec![&[1, 2][..], &[], &[3, 9, 5]]
        );
        assert_eq!(r.values(), &[1, 2, 3, 9, 5]);
        let f = Ragged::filled([2, 0, 1].into_iter(), 7u8);
        assert_eq!(f.rows().collect::<Vec<_>>(), vec![&[7, 7][..], &[], &[7]]);
        assert_eq!(Ragged::<u8>::default().rows().count(), 0);
    }
}
