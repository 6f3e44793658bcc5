//! Evaluating a spline: locating the piece of a query, the value and
//! derivatives there, the extrapolation policy outside the domain, and
//! batches of queries (in order, in any order, on rayon's pool).

use super::{Extrapolate, Spline};
use crate::error::{Error, Field};
use crate::poly::deriv_of;
use crate::traits::ParamCurve;

/// Where a query falls.
pub(super) enum Locus {
    /// Piece `k` at local parameter `t`, with `1 / (h_k pre)`.
    Piece(usize, f64, f64),
    /// The last knot, where the value is the last control value exactly.
    End,
    /// Clamped to the end value of knot `k`.
    Held(usize),
    /// Outside the span (or a NaN query) under [`Extrapolate::Nan`].
    Nowhere,
}

impl Spline {
    /// The scaled knot value `phi_k / scale`.
    pub(super) fn phi(&self, k: usize) -> f64 {
        match self.pieces.coefs().get(k) {
            Some(c) => c.0[0],
            None => self.values[self.len()] / self.scale(),
        }
    }

    pub(super) fn locate_in(&self, x: f64, k: usize) -> Result<Locus, Error> {
        let (a, b) = self.domain();
        if !(a..=b).contains(&x) {
            if self.extrapolate == Extrapolate::Nan {
                return Ok(Locus::Nowhere);
            }
            if x.is_nan() {
                return Err(Error::NonFinite {
                    field: Field::Query,
                    index: 0,
                    value: x,
                });
            }
            match self.extrapolate {
                Extrapolate::Error => return Err(Error::OutOfDomain { x, min: a, max: b }),
                Extrapolate::Clamp => {
                    return Ok(Locus::Held(if x < a { 0 } else { self.len() }));
                }
                Extrapolate::Extend | Extrapolate::Nan => {}
            }
        }
        if x == b {
            return Ok(Locus::End);
        }
        // The batch evaluators compute t and 1/h the same way (pre = 1 there).
        let inv = 1.0 / (self.pieces.width(k) * self.pre);
        let t = ((x - self.pieces.knots()[k]) * self.pre) * inv;
        Ok(Locus::Piece(k, t, inv))
    }

    pub(super) fn eval_locus(&self, locus: Locus, order: u32) -> Result<f64, Error> {
        match locus {
            Locus::Held(k) => Ok(if order == 0 { self.values[k] } else { 0.0 }),
            Locus::Nowhere => Ok(f64::NAN),
            Locus::End if order == 0 => Ok(self.values[self.len()]),
            Locus::End => {
                let k = self.len() - 1;
                let inv = 1.0 / (self.pieces.width(k) * self.pre);
                self.eval_locus(Locus::Piece(k, 1.0, inv), order)
            }
            Locus::Piece(0, t, _) if order == 0 && t == 0.0 => {
                // The first control value itself: scaled by the largest value
                // it may have underflowed to 0.
                Ok(self.values[0])
            }
            Locus::Piece(k, t, inv) => {
                let mut v = deriv_of(&self.pieces.coefs()[k].0, t, order) * self.scale();
                if order == 0 && v.is_infinite() && (0.0..=1.0).contains(&t) {
                    // Rounding above f64::MAX inside the hull: the true value is
                    // within the control values, which are finite.
                    v = f64::MAX.copysign(v);
                }
                for _ in 0..order.min(4) {
                    v = v * inv * self.pre;
                }
                if !v.is_finite() {
                    return Err(Error::Overflow {
                        what: if order == 0 {
                            "the extrapolated value"
                        } else {
                            "the derivative"
                        },
                    });
                }
                Ok(v)
            }
        }
    }

    /// `S(x)`.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a NaN `x`; [`Error::OutOfDomain`] outside the
    /// domain under [`Extrapolate::Error`]; [`Error::Overflow`] when an
    /// extrapolated value overflows.
    pub fn eval(&self, x: f64) -> Result<f64, Error> {
        self.deriv(x, 0)
    }

    /// The derivative of order `order` at `x` (0 is the value; above 3 it is 0).
    ///
    /// # Errors
    ///
    /// As [`Spline::eval`]; [`Error::Overflow`] also when the derivative exceeds
    /// the range of a double (on an extremely narrow interval).
    pub fn deriv(&self, x: f64, order: u32) -> Result<f64, Error> {
        let k = self.piece_index(x);
        let locus = self.locate_in(x, k)?;
        self.eval_locus(locus, order)
    }

    /// Value and derivatives of orders 1, 2 and 3 at `x`.
    ///
    /// # Errors
    ///
    /// As [`Spline::eval`].
    pub fn eval_all(&self, x: f64) -> Result<[f64; 4], Error> {
        let k = self.piece_index(x);
        let mut out = [0.0; 4];
        for (order, o) in out.iter_mut().enumerate() {
            let locus = self.locate_in(x, k)?;
            *o = self.eval_locus(locus, order as u32)?;
        }
        Ok(out)
    }

    /// Evaluates the derivative of order `order` (0 for values) at every `xs[i]`
    /// into `out[i]`, with the same result as [`Spline::deriv`] at each point.
    /// Queries in increasing order are the fastest (one pass over the pieces);
    /// any order is accepted.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] when `out.len() != xs.len()`; otherwise as
    /// [`Spline::eval`], with the index of the failing query in
    /// [`Error::NonFinite`]. On error the contents of `out` are unspecified.
    pub fn deriv_many(&self, xs: &[f64], order: u32, out: &mut [f64]) -> Result<(), Error> {
        crate::curve::check_output(out, xs.len())?;
        let slow = |i: usize, x: f64, o: &mut f64| -> Result<(), Error> {
            *o = self.deriv(x, order).map_err(|e| e.at_query(i))?;
            Ok(())
        };
        // The batch kernel sums the coefficients at tau_0 too; when the first
        // value underflowed in scaling (values spanning some 600 decades) only
        // the one-by-one path returns it exactly.
        let first_exact = self
            .pieces
            .coefs()
            .first()
            .is_none_or(|c| c.0[0] * self.scale() == self.values[0]);
        if self.pre != 1.0 || order > 3 || (order == 0 && !first_exact) {
            for (i, (&x, o)) in xs.iter().zip(out.iter_mut()).enumerate() {
                slow(i, x, o)?;
            }
            return Ok(());
        }
        let batch = self.pieces.batch();
        match order {
            0 => batch.run::<0, _>(xs, out, slow),
            1 => batch.run::<1, _>(xs, out, slow),
            2 => batch.run::<2, _>(xs, out, slow),
            _ => batch.run::<3, _>(xs, out, slow),
        }
    }

    /// [`Spline::deriv_many`] split over rayon's thread pool: the same results,
    /// each worker walking its own contiguous share of the queries.
    ///
    /// # Errors
    ///
    /// As [`Spline::deriv_many`] (the first failing query by index).
    #[cfg(feature = "rayon")]
    pub fn par_deriv_many(&self, xs: &[f64], order: u32, out: &mut [f64]) -> Result<(), Error> {
        use rayon::prelude::*;
        crate::curve::check_output(out, xs.len())?;
        // A few chunks per thread for balance, none so small that the start-up
        // search dominates.
        let chunk = (xs.len() / (4 * rayon::current_num_threads()).max(1)).max(1 << 14);
        let failed = xs
            .par_chunks(chunk)
            .zip(out.par_chunks_mut(chunk))
            .map(|(x, o)| self.deriv_many(x, order, o).is_err())
            .reduce(|| false, |a, b| a | b);
        if failed {
            // Rerun in order, so that the error is the one with the lowest index.
            return self.deriv_many(xs, order, out);
        }
        Ok(())
    }

    /// `S(xs[i])` into `out[i]` in parallel; see [`Spline::par_deriv_many`].
    ///
    /// # Errors
    ///
    /// As [`Spline::deriv_many`].
    #[cfg(feature = "rayon")]
    pub fn par_eval_many(&self, xs: &[f64], out: &mut [f64]) -> Result<(), Error> {
        self.par_deriv_many(xs, 0, out)
    }

    /// `S(xs[i])` into `out[i]`; see [`Spline::deriv_many`].
    ///
    /// # Errors
    ///
    /// As [`Spline::deriv_many`].
    pub fn eval_many(&self, xs: &[f64], out: &mut [f64]) -> Result<(), Error> {
        self.deriv_many(xs, 0, out)
    }
}
