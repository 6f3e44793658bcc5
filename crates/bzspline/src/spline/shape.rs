//! A spline's shape parameters: one per interval, or one for all, whose
//! vector is then formed only when someone asks for it.

use std::sync::OnceLock;

/// The alphas of a spline's `len` intervals. A build with one alpha writes
/// none of them (8 bytes a point nobody may read); [`Shape::as_slice`] forms
/// the vector the first time it is asked for and keeps it.
#[derive(Clone, Debug, Default)]
pub(super) struct Shape {
    /// `Some(a)` when every alpha is `a`.
    uniform: Option<f64>,
    /// The number of intervals.
    len: usize,
    /// One alpha per interval: given, or formed from `uniform` on demand.
    each: OnceLock<Vec<f64>>,
    /// The allocation of a vector no longer needed, empty, kept for the next
    /// build with one alpha per interval.
    spare: Vec<f64>,
}

impl Shape {
    /// Every one of `len` intervals with alpha `a`. The vector formed for an
    /// earlier request is kept when it still holds (same `a`, same length).
    pub(super) fn set_uniform(&mut self, a: f64, len: usize) {
        if self.uniform == Some(a) && self.len == len {
            return;
        }
        self.uniform = Some(a);
        self.len = len;
        if let Some(mut v) = self.each.take() {
            v.clear();
            self.spare = v;
        }
    }

    /// Alpha `alphas[k]` on interval `k` (the vector's allocation reused).
    pub(super) fn set_each(&mut self, alphas: &[f64]) {
        let mut each = self
            .each
            .take()
            .unwrap_or_else(|| core::mem::take(&mut self.spare));
        each.clear();
        each.extend_from_slice(alphas);
        self.uniform = None;
        self.len = alphas.len();
        self.each = OnceLock::from(each);
    }

    /// The one alpha of every interval, if there is one.
    pub(super) fn uniform(&self) -> Option<f64> {
        self.uniform
    }

    /// The alphas as given to a build: one per interval, or none when they
    /// are all [`Shape::uniform`] and nobody has asked for them yet.
    pub(super) fn given(&self) -> &[f64] {
        self.each.get().map_or(&[], Vec::as_slice)
    }

    /// One alpha per interval.
    pub(super) fn as_slice(&self) -> &[f64] {
        self.each
            .get_or_init(|| vec![self.uniform.unwrap_or(crate::DEFAULT_ALPHA); self.len])
    }

    /// The alpha of interval `k` (`k < len`).
    pub(super) fn get(&self, k: usize) -> f64 {
        match self.uniform {
            Some(a) => a,
            None => self.as_slice()[k],
        }
    }

    /// Bytes of heap memory held.
    pub(super) fn heap_bytes(&self) -> usize {
        (self.each.get().map_or(0, Vec::capacity) + self.spare.capacity())
            * core::mem::size_of::<f64>()
    }
}

/// Equal when every interval has the same alpha, whichever way each was given.
impl PartialEq for Shape {
    fn eq(&self, other: &Self) -> bool {
        match (self.uniform, other.uniform) {
            (Some(a), Some(b)) => a == b && self.len == other.len,
            _ => self.as_slice() == other.as_slice(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_alpha_is_formed_on_demand_and_kept() {
        let mut s = Shape::default();
        s.set_uniform(0.4, 3);
        assert!(s.given().is_empty());
        assert_eq!(s.heap_bytes(), 0);
        assert_eq!(s.get(2), 0.4);
        assert_eq!(s.as_slice(), &[0.4; 3]);
        assert_eq!(s.given(), &[0.4; 3]);
        // The same alpha and length again: the vector still holds.
        s.set_uniform(0.4, 3);
        assert_eq!(s.given(), &[0.4; 3]);
        s.set_uniform(0.4, 4);
        assert!(s.given().is_empty());
        assert_eq!(s.as_slice(), &[0.4; 4]);
    }

    #[test]
    fn an_allocation_given_up_is_reused() {
        let mut s = Shape::default();
        s.set_each(&[0.4, 0.5, 0.6]);
        let bytes = s.heap_bytes();
        s.set_uniform(0.5, 2);
        assert!(s.given().is_empty());
        assert_eq!(s.heap_bytes(), bytes);
        s.set_each(&[0.6, 0.4]);
        assert_eq!(s.heap_bytes(), bytes);
        assert_eq!(s.given(), &[0.6, 0.4]);
    }

    #[test]
    fn shapes_compare_by_their_alphas() {
        let (mut one, mut each) = (Shape::default(), Shape::default());
        one.set_uniform(0.5, 2);
        each.set_each(&[0.5, 0.5]);
        assert_eq!(one, each);
        assert_eq!(each, one);
        each.set_each(&[0.5, 0.6]);
        assert_ne!(one, each);
        assert_eq!(each.get(1), 0.6);
        assert_eq!(each.uniform(), None);
        let mut other = Shape::default();
        other.set_uniform(0.5, 3);
        assert_ne!(one, other);
    }
}
