//! Where a spline turns: the roots of each piece's derivative and the
//! smallest and largest value over the domain.

use super::{Extremum, ExtremumKind, Spline};
use crate::fast::Piece;
use crate::poly::{deriv_of, horner, quadratic_roots};
use crate::traits::ParamCurve;

impl Spline {
    /// The points inside the domain where `S' = 0`, in increasing `x`: the real
    /// roots of each piece's derivative, classified by the sign of `S''`.
    #[must_use]
    pub fn extrema(&self) -> Vec<Extremum> {
        let mut out = Vec::new();
        for (k, Piece(c)) in self.pieces.coefs().iter().enumerate() {
            let h = self.pieces.width(k);
            let mut roots = quadratic_roots(3.0 * c[3], 2.0 * c[2], c[1]);
            roots.sort_unstable_by(f64::total_cmp);
            for t in roots {
                // Knots belong to the piece on their right; the domain's ends are
                // not interior points.
                let inside = if k == 0 {
                    t > 0.0 && t < 1.0
                } else {
                    (0.0..1.0).contains(&t)
                };
                if !inside {
                    continue;
                }
                let x = (self.pieces.knots()[k] + t * h).min(self.pieces.knots()[k + 1]);
                // Inside the hull the true value is finite; rounding above
                // f64::MAX is held at it, as in `eval`.
                let y = (horner(c, t) * self.scale()).clamp(-f64::MAX, f64::MAX);
                let curv = deriv_of(c, t, 2);
                let kind = if curv > 0.0 {
                    ExtremumKind::Minimum
                } else if curv < 0.0 {
                    ExtremumKind::Maximum
                } else {
                    ExtremumKind::Stationary
                };
                if out.last().is_some_and(|e: &Extremum| e.x >= x) {
                    continue;
                }
                out.push(Extremum { x, y, kind });
            }
        }
        out
    }
    /// The smallest and largest value of `S` on its domain, as `(x, y)` pairs.
    #[must_use]
    pub fn range(&self) -> ((f64, f64), (f64, f64)) {
        let (a, b) = self.domain();
        let ends = [(a, self.values[0]), (b, self.values[self.len()])];
        let mut lo = ends[0];
        let mut hi = ends[0];
        for (x, y) in ends
            .into_iter()
            .chain(self.extrema().into_iter().map(|e| (e.x, e.y)))
        {
            if y < lo.1 {
                lo = (x, y);
            }
            if y > hi.1 {
                hi = (x, y);
            }
        }
        (lo, hi)
    }
}
