//! The piecewise cubic under [`Spline`](crate::Spline) and
//! [`Curve`](crate::Curve): knots, the power-basis coefficients of every piece
//! in its local variable `t = (x - tau_k) / h_k` for each of `dim`
//! coordinates, one power-of-two scale per coordinate, and the search summary
//! of the knots. It locates a parameter among the knots and evaluates values
//! and derivatives in `t`, once for both types; they add what their domains
//! mean (a spline's extrapolation and exact end values, a curve's periodicity
//! and exact end points).

use crate::fast::batch::Batch;
use crate::fast::search::Summary;
use crate::fast::Piece;
use crate::poly::deriv_of;

/// Knots, pieces and scales; see the module docs.
///
/// Piece `k` runs from `knots[k]` to `knots[k + 1]`; its coordinate `c` is
/// `coefs[k * dim + c]`, in units of `scales[c]` (the unscaled coefficient is
/// the stored one times the scale). The summary is always that of `knots`.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Pieces {
    knots: Vec<f64>,
    coefs: Vec<Piece>,
    scales: Vec<f64>,
    /// The largest of `scales`: the unit of geometry that mixes coordinates,
    /// and a spline's one scale.
    unit: f64,
    summary: Summary,
}

/// The parts of [`Pieces`] a construction writes (the scales go through
/// [`Pieces::set_scales`]). Whoever changes `knots`
/// leaves `summary` as the summary of the new knots (see [`Summary::of`]).
pub(crate) struct PartsMut<'a> {
    pub(crate) knots: &'a mut Vec<f64>,
    pub(crate) coefs: &'a mut Vec<Piece>,
    pub(crate) summary: &'a mut Summary,
}

impl Pieces {
    /// Pieces on `knots` (at least two) with `coefs` (`dim` per piece) in units
    /// of `scales` (`dim` of them).
    pub(crate) fn from_parts(knots: Vec<f64>, coefs: Vec<Piece>, scales: Vec<f64>) -> Self {
        debug_assert_eq!(coefs.len(), knots.len().saturating_sub(1) * scales.len());
        let mut summary = Summary::default();
        summary.of(&knots);
        let mut p = Pieces {
            knots,
            coefs,
            scales: Vec::new(),
            unit: 1.0,
            summary,
        };
        p.set_scales(scales.into_iter());
        p
    }

    /// Makes `scales` the scales of the coordinates (their allocation is kept
    /// when it holds them, else one of exactly their length is made).
    pub(crate) fn set_scales(&mut self, scales: impl ExactSizeIterator<Item = f64>) {
        self.scales.clear();
        self.scales.reserve_exact(scales.len());
        self.scales.extend(scales);
        self.unit = self.scales.iter().fold(0.0f64, |m, s| m.max(*s));
    }

    /// The parts, for a construction that writes them in place.
    pub(crate) fn parts_mut(&mut self) -> PartsMut<'_> {
        PartsMut {
            knots: &mut self.knots,
            coefs: &mut self.coefs,
            summary: &mut self.summary,
        }
    }

    /// Forms the search summary again after the knots changed.
    pub(crate) fn knots_changed(&mut self) {
        self.summary.of(&self.knots);
    }

    /// The knots.
    #[inline]
    pub(crate) fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The number of pieces.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.knots.len().saturating_sub(1)
    }

    /// The number of coordinates.
    #[inline]
    pub(crate) fn dim(&self) -> usize {
        self.scales.len()
    }

    /// `(knots[0], knots[last])`.
    #[inline]
    pub(crate) fn domain(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// The width `h_k` of piece `k`.
    #[inline]
    pub(crate) fn width(&self, k: usize) -> f64 {
        self.knots[k + 1] - self.knots[k]
    }

    /// The scale of coordinate `c`.
    #[inline]
    pub(crate) fn scale(&self, c: usize) -> f64 {
        self.scales[c]
    }

    /// The largest scale (for a spline, its one scale).
    #[inline]
    pub(crate) fn unit(&self) -> f64 {
        self.unit
    }

    /// The scale of every coordinate.
    #[inline]
    pub(crate) fn scales(&self) -> &[f64] {
        &self.scales
    }

    /// Every piece, `dim` per interval.
    #[inline]
    pub(crate) fn coefs(&self) -> &[Piece] {
        &self.coefs
    }

    /// The stored (scaled) coefficients of coordinate `c` of piece `k`.
    #[inline]
    pub(crate) fn piece(&self, k: usize, c: usize) -> &[f64; 4] {
        &self.coefs[k * self.scales.len() + c].0
    }

    /// The piece that answers at `x`: the last `k` with `knots[k] <= x`, held
    /// to `0 ..= len() - 1` (queries past either end map to the end pieces).
    #[inline]
    pub(crate) fn locate(&self, x: f64) -> usize {
        self.summary.locate(&self.knots, x).min(self.len() - 1)
    }

    /// The derivative of order `order` in `t` (not divided by the width) of
    /// coordinate `c` of piece `k`, unscaled.
    #[inline]
    pub(crate) fn value(&self, k: usize, c: usize, t: f64, order: u32) -> f64 {
        deriv_of(self.piece(k, c), t, order) * self.scales[c]
    }

    /// The batch evaluator over the one coordinate of a spline.
    pub(crate) fn batch(&self) -> Batch<'_> {
        debug_assert_eq!(self.scales.len(), 1);
        Batch {
            knots: &self.knots,
            summary: &self.summary,
            coefs: &self.coefs,
            scale: self.scales[0],
        }
    }

    /// Bytes of heap memory held.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.knots.capacity() + self.scales.capacity()) * core::mem::size_of::<f64>()
            + self.coefs.capacity() * core::mem::size_of::<Piece>()
            + self.summary.heap_bytes()
    }

    /// Whether the summary's index is formed (see [`Summary`]).
    #[cfg(test)]
    pub(crate) fn summary(&self) -> &Summary {
        &self.summary
    }
}
