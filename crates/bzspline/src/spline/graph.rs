//! A spline as a planar curve, its graph `x -> (x, S(x))`: the capability
//! traits (evaluation, arc length, Bezier pieces, flattening, bounds).

use super::Spline;
use crate::curve::{Curve, CurveBuilder, Param};
use crate::error::Error;
use crate::flatten::{check_tol, steps, MAX_FLATTEN_VERTICES};
use crate::polyline::Polyline;
use crate::traits::{check_out, Arclen, BBox, BezierPieces, Bounds, Flatten, ParamCurve};

impl Spline {
    /// The graph `x -> (x, S(x))` as a planar [`Curve`] with the knots as its
    /// parameters and the spline's alphas: each coordinate is the method's
    /// spline on the same knots, and the spline of the linear data `x` is `x`
    /// itself (to rounding), so the curve is this spline's graph. What a
    /// curve can do (arc length, resampling, the nearest point) then applies
    /// to the graph.
    ///
    /// # Errors
    ///
    /// None for a spline built by this crate; the curve builder's errors
    /// otherwise.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Arclen, DEFAULT_ACCURACY, Spline};
    /// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// let g = s.graph()?;
    /// let p = g.eval(0.5)?;
    /// assert!((p[0] - 0.5).abs() < 1e-15 && (p[1] - s.eval(0.5)?).abs() < 1e-15);
    /// assert!(g.arclen(DEFAULT_ACCURACY)? > 2.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn graph(&self) -> Result<Curve, Error> {
        let flat: Vec<f64> = self
            .knots()
            .iter()
            .zip(self.values())
            .flat_map(|(&x, &y)| [x, y])
            .collect();
        CurveBuilder::new(&flat, 2)
            .param(Param::Given(self.knots().to_vec()))
            .alphas(self.alphas())
            .build()
    }
}

/// The graph `x -> (x, S(x))`, under the spline's extrapolation policy.
impl ParamCurve for Spline {
    fn dim(&self) -> usize {
        2
    }
    /// The domain `[tau_0, tau_{N-1}]`.
    fn domain(&self) -> (f64, f64) {
        self.pieces.domain()
    }
    fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, 2)?;
        out[1] = self.eval(t)?;
        out[0] = t;
        Ok(())
    }
    fn deriv_into(&self, t: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, 2)?;
        out[1] = self.deriv(t, order)?;
        out[0] = match order {
            0 => t,
            1 => 1.0,
            _ => 0.0,
        };
        Ok(())
    }
}

/// The arc length of the graph, measured on [`Spline::graph`]; parameters
/// are abscissas.
impl Arclen for Spline {
    fn arclen(&self, accuracy: f64) -> Result<f64, Error> {
        self.graph()?.arclen(accuracy)
    }
    fn params_at_lengths(&self, lengths: &[f64], accuracy: f64) -> Result<Vec<f64>, Error> {
        self.graph()?.params_at_lengths(lengths, accuracy)
    }
}

impl BezierPieces for Spline {
    fn piece_count(&self) -> usize {
        self.len()
    }
    fn piece_into(&self, k: usize, out: &mut [f64]) -> bool {
        match self.segment(k) {
            Some(s) if out.len() == 8 => {
                out.copy_from_slice(s.p.as_flattened());
                true
            }
            _ => false,
        }
    }
}

impl Flatten for Spline {
    /// The graph `(x, S(x))` flattened to a polyline within `tol` of it; see
    /// [`Curve::flatten`]. Vertices' parameters are their abscissas.
    ///
    /// # Errors
    ///
    /// As [`Curve::flatten`].
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Flatten, Spline};
    /// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// let p = s.flatten(1e-4)?;
    /// assert_eq!(p.point(0), Some(&[0.0, 0.0][..]));
    /// assert_eq!(p.point(p.len() - 1), Some(&[2.0, 0.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        check_tol(tol)?;
        let knots = self.knots();
        let mut coords = Vec::new();
        let mut params = Vec::new();
        for k in 0..self.len() {
            let c = self.unit_coefficients(k).unwrap_or([0.0; 4]);
            let accel = (2.0 * c[2]).abs().max((2.0 * c[2] + 6.0 * c[3]).abs());
            let m = steps(accel, tol)?;
            if params.len().saturating_add(m) > MAX_FLATTEN_VERTICES {
                return Err(Error::TooManyVertices { tolerance: tol });
            }
            let h = knots[k + 1] - knots[k];
            for j in usize::from(k > 0)..=m {
                let x = if j == m {
                    knots[k + 1]
                } else {
                    knots[k] + (j as f64 / m as f64) * h
                };
                let y = self.eval(x)?;
                coords.push(x);
                coords.push(y);
                params.push(x);
            }
        }
        Ok(Polyline::new(2, coords, params))
    }
}

impl Bounds for Spline {
    fn bbox(&self) -> BBox {
        let (a, b) = self.domain();
        let ((_, lo), (_, hi)) = self.range();
        BBox {
            min: vec![a, lo],
            max: vec![b, hi],
        }
    }
}
