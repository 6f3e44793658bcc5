//! A curve's cubic Bezier segments: the points of tangency and the knots,
//! each segment's control points, the exact bounding box, the SVG path, and
//! the capability traits.

use super::Curve;
use crate::bezier::CubicBez;
use crate::error::Error;
use crate::method::alpha_terms;
use crate::poly::{horner, quadratic_roots};
use crate::traits::BBox;
use crate::traits::{BezierPieces, Bounds, ParamCurve};

impl Curve {
    /// `Ok` for a planar curve; otherwise [`Error::InvalidArgument`] with
    /// `what` and the dimension.
    pub(crate) fn check_planar(&self, what: &'static str) -> Result<(), Error> {
        if self.dim() != 2 {
            return Err(Error::InvalidArgument {
                what,
                value: self.dim() as f64,
            });
        }
        Ok(())
    }

    /// Where the curve touches each leg: `(x_k, alpha_k P_k + (1 - alpha_k)
    /// P_{k+1})` with `x_k = tau_{k+1} - alpha_k h_k` (docs/method.md §9, misprint 1).
    #[must_use]
    pub fn tangent_points(&self) -> Vec<(f64, Vec<f64>)> {
        let (dim, n) = (self.dim(), self.n_points());
        (0..self.len())
            .map(|k| {
                let a = self.alphas[k];
                let h = self.pieces.width(k);
                let j = (k + 1) % n;
                let p = (0..dim)
                    .map(|c| (a * self.fv(k, c) + (1.0 - a) * self.fv(j, c)) * self.pieces.scale(c))
                    .collect();
                (self.pieces.knots()[k + 1] - a * h, p)
            })
            .collect()
    }

    /// The knot points `S(tau_i)`, one per control point; an open curve's first
    /// and last are its end control points exactly.
    #[must_use]
    pub fn knot_points(&self) -> Vec<Vec<f64>> {
        let dim = self.dim();
        (0..self.n_points())
            .map(|i| (0..dim).map(|c| self.knot_coord(i, c)).collect())
            .collect()
    }

    /// The four Bezier control points of segment `k`, each coordinate
    /// multiplied back, flat (`4 * dim` numbers), or `None` past the end.
    /// Consecutive segments share their end points bit for bit. The two inner
    /// control points lie outside the convex hull and can be infinite when the
    /// points come near `f64::MAX` ([`Curve::to_svg_path`] then reports
    /// [`Error::Overflow`]).
    #[must_use]
    pub fn segment_points(&self, k: usize) -> Option<Vec<f64>> {
        if k >= self.len() {
            return None;
        }
        let (dim, n) = (self.dim(), self.n_points());
        let j = (k + 1) % n;
        let a = self.alphas[k];
        let [al, b1, b2, cr] = alpha_terms(a);
        let mut ctrl = vec![0.0; 4 * dim];
        for c in 0..dim {
            let (f0, f1) = (self.fv(k, c), self.fv(j, c));
            let (d0, d1) = (self.d[k * dim + c], self.d[j * dim + c]);
            let df = f1 - f0;
            let s0 = df - d0 * b2 + d1 * cr;
            let s1 = df + d1 * b1 - d0 * al;
            let (p0, p3) = (f0 + d0, f1 + d1);
            let s = self.pieces.scale(c);
            ctrl[c] = p0 * s;
            ctrl[dim + c] = (p0 + s0 / 3.0) * s;
            ctrl[2 * dim + c] = (p3 - s1 / 3.0) * s;
            ctrl[3 * dim + c] = p3 * s;
        }
        if !self.closed {
            // The end control points exactly, as `eval` gives them.
            if k == 0 {
                ctrl[..dim].copy_from_slice(&self.points[..dim]);
            }
            if j == n - 1 {
                ctrl[3 * dim..].copy_from_slice(&self.points[(n - 1) * dim..]);
            }
        }
        Some(ctrl)
    }

    /// Segment `k` as a [`CubicBez<D>`]; `None` past the end or when `D` is not
    /// the curve's dimension.
    #[must_use]
    pub fn segment<const D: usize>(&self, k: usize) -> Option<CubicBez<D>> {
        if D != self.dim() {
            return None;
        }
        let v = self.segment_points(k)?;
        let mut p = [[0.0; D]; 4];
        for (j, pj) in p.iter_mut().enumerate() {
            pj.copy_from_slice(&v[j * D..(j + 1) * D]);
        }
        Some(CubicBez::new(p))
    }

    /// Every segment as a [`CubicBez<D>`]; `None` when `D` is not the curve's
    /// dimension.
    #[must_use]
    pub fn segments<const D: usize>(&self) -> Option<Vec<CubicBez<D>>> {
        (0..self.len()).map(|k| self.segment::<D>(k)).collect()
    }

    /// The SVG path data of a planar curve: `M x y C x1 y1 x2 y2 x y ...`,
    /// closed with `Z`. Numbers are printed in Rust's shortest round-trip form,
    /// so they parse back to the same doubles.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when the curve is not planar;
    /// [`Error::Overflow`] when a Bezier control point exceeds the range of a
    /// double.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])?;
    /// let d = c.to_svg_path()?;
    /// assert!(d.starts_with("M 0 0 C "), "{d}");
    /// assert_eq!(d.matches('C').count(), 2);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn to_svg_path(&self) -> Result<String, Error> {
        self.check_planar("an SVG path needs a planar curve; dimension")?;
        let mut out = String::new();
        // Writing into a String cannot fail; `false` is a non-finite point.
        match crate::traits::write_svg_path(self, self.closed, &mut out) {
            Ok(true) => Ok(out),
            _ => Err(Error::Overflow {
                what: "a Bezier control point",
            }),
        }
    }
}

impl BezierPieces for Curve {
    fn piece_count(&self) -> usize {
        self.len()
    }
    fn piece_into(&self, k: usize, out: &mut [f64]) -> bool {
        match self.segment_points(k) {
            Some(p) if p.len() == out.len() => {
                out.copy_from_slice(&p);
                true
            }
            _ => false,
        }
    }
}

impl Bounds for Curve {
    /// The exact axis-aligned bounding box: per segment and coordinate, the
    /// segment's ends and the roots of its derivative (a quadratic) inside it.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Bounds, Curve};
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?;
    /// let bb = c.bbox();
    /// assert_eq!((bb.min[0], bb.max[0]), (0.0, 2.0));
    /// // The top is below the middle control point: the curve does not reach it.
    /// assert!(bb.max[1] > 0.5 && bb.max[1] < 2.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    fn bbox(&self) -> BBox {
        let dim = self.dim();
        let mut min = vec![f64::INFINITY; dim];
        let mut max = vec![f64::NEG_INFINITY; dim];
        for k in 0..self.len() {
            let j = (k + 1) % self.n_points();
            for c in 0..dim {
                let co = self.pieces.piece(k, c);
                let mut vals = vec![
                    self.fv(k, c) + self.d[k * dim + c],
                    self.fv(j, c) + self.d[j * dim + c],
                ];
                for t in quadratic_roots(3.0 * co[3], 2.0 * co[2], co[1]) {
                    if t > 0.0 && t < 1.0 {
                        vals.push(horner(co, t));
                    }
                }
                for v in vals {
                    let v = (v * self.pieces.scale(c)).clamp(-f64::MAX, f64::MAX);
                    min[c] = min[c].min(v);
                    max[c] = max[c].max(v);
                }
            }
        }
        BBox { min, max }
    }
}
