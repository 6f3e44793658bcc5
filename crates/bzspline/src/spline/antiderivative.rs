//! Integrals of a spline: `∫ S` over any interval, and the antiderivative
//! `F(x) = ∫ S` from the first knot to `x`: on every interval the integral of
//! the piece's cubic (a quartic), added to the integrals of the pieces before
//! it, summed once at construction.

use super::{Extrapolate, Spline};
use crate::curve::check_output;
use crate::error::{Error, Field};
use crate::traits::ParamCurve;

/// `F(x)`, the integral of a [`Spline`] from its first knot `tau_0` to `x`:
/// `F(tau_0) = 0`, `F' = S`, and `F(b) - F(a)` is [`Spline::integral`]`(a, b)`
/// up to rounding. Outside the domain it integrates what the spline's
/// [`Extrapolate`](crate::Extrapolate) policy gives there.
///
/// Built by [`Spline::antiderivative`] in O(N); each evaluation is one search
/// for the piece and one quartic, O(log N).
///
/// # Examples
///
/// ```
/// use bzspline::Spline;
///
/// let s = Spline::with_alpha(&[0.0, 1.0, 2.0], &[0.0, 2.0, 0.0], 0.5)?;
/// let f = s.antiderivative();
/// assert_eq!(f.eval(0.0)?, 0.0);
/// assert!((f.eval(2.0)? - s.integral(0.0, 2.0)?).abs() < 1e-15);
/// # Ok::<(), bzspline::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Antiderivative {
    spline: Spline,
    /// `F(tau_k)` for every knot, in the spline's scaled units.
    at_knots: Vec<f64>,
}

impl Spline {
    /// Integral of `S` over `[a, b]` (negative when `b < a`), exact up to rounding.
    /// Parts outside the domain follow the extrapolation policy.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a non-finite bound; [`Error::OutOfDomain`] for a
    /// bound outside the domain under [`Extrapolate::Error`]; [`Error::Overflow`]
    /// when the result exceeds the range of a double.
    pub fn integral(&self, a: f64, b: f64) -> Result<f64, Error> {
        let (lo, hi) = self.domain();
        if self.extrapolate == Extrapolate::Nan
            && !((lo..=hi).contains(&a) && (lo..=hi).contains(&b))
        {
            return Ok(f64::NAN);
        }
        for (i, &v) in [a, b].iter().enumerate() {
            if !v.is_finite() {
                return Err(Error::NonFinite {
                    field: Field::Query,
                    index: i,
                    value: v,
                });
            }
        }
        if b < a {
            return self.integral(b, a).map(|v| -v);
        }
        if self.extrapolate == Extrapolate::Error && (a < lo || b > hi) {
            let x = if a < lo { a } else { b };
            return Err(Error::OutOfDomain {
                x,
                min: lo,
                max: hi,
            });
        }
        let mut total = 0.0;
        // Parts outside the domain.
        if a < lo {
            let end = b.min(lo);
            total += match self.extrapolate {
                Extrapolate::Clamp => (end - a) * (self.values[0] / self.scale()),
                _ => self.piece_integral(0, a, end),
            };
        }
        if b > hi {
            let start = a.max(hi);
            total += match self.extrapolate {
                Extrapolate::Clamp => (b - start) * (self.values[self.len()] / self.scale()),
                _ => self.piece_integral(self.len() - 1, start, b),
            };
        }
        let (ca, cb) = (a.max(lo), b.min(hi));
        if ca < cb {
            let (ka, kb) = (self.piece_index(ca), self.piece_index(cb));
            for k in ka..=kb {
                let x0 = ca.max(self.pieces.knots()[k]);
                let x1 = cb.min(self.pieces.knots()[k + 1]);
                if x0 < x1 {
                    total += self.piece_integral(k, x0, x1);
                }
            }
        }
        let v = total * self.scale();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Error::Overflow {
                what: "the integral",
            })
        }
    }

    /// Integral of piece `k`'s cubic (scaled) from `x0` to `x1`.
    pub(crate) fn piece_integral(&self, k: usize, x0: f64, x1: f64) -> f64 {
        let c = &self.pieces.coefs()[k].0;
        let h = self.pieces.width(k);
        let prim = |t: f64| t * (c[0] + t * (c[1] / 2.0 + t * (c[2] / 3.0 + t * c[3] / 4.0)));
        let t0 = (x0 - self.pieces.knots()[k]) / h;
        let t1 = (x1 - self.pieces.knots()[k]) / h;
        (prim(t1) - prim(t0)) * h
    }

    /// The antiderivative `F(x) = ∫ S` from the first knot to `x` (a copy of
    /// the spline and one sum per knot).
    #[must_use]
    pub fn antiderivative(&self) -> Antiderivative {
        let knots = self.pieces.knots();
        let mut at_knots = Vec::with_capacity(knots.len());
        let mut total = 0.0;
        at_knots.push(total);
        for k in 0..self.len() {
            total += self.piece_integral(k, knots[k], knots[k + 1]);
            at_knots.push(total);
        }
        Antiderivative {
            spline: self.clone(),
            at_knots,
        }
    }
}

impl Antiderivative {
    /// The spline this is the antiderivative of (its derivative).
    #[must_use]
    pub fn spline(&self) -> &Spline {
        &self.spline
    }

    /// `F` at every knot: `F(tau_0) = 0`, then the integrals up to each knot.
    #[must_use]
    pub fn knot_values(&self) -> Vec<f64> {
        let scale = self.spline.scale();
        self.at_knots.iter().map(|v| v * scale).collect()
    }

    /// `F(x)`.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a query that is not finite;
    /// [`Error::OutOfDomain`] outside the domain under
    /// [`Extrapolate::Error`](crate::Extrapolate::Error); [`Error::Overflow`]
    /// when the value leaves the range of a double.
    pub fn eval(&self, x: f64) -> Result<f64, Error> {
        self.at(x, 0)
    }

    /// `F(xs[i])` into `out[i]`.
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] when `out` is not as long as `xs`; otherwise
    /// as [`Antiderivative::eval`], naming the query's index.
    pub fn eval_many(&self, xs: &[f64], out: &mut [f64]) -> Result<(), Error> {
        check_output(out, xs.len())?;
        for (i, (o, &x)) in out.iter_mut().zip(xs).enumerate() {
            *o = self.at(x, i)?;
        }
        Ok(())
    }

    fn at(&self, x: f64, index: usize) -> Result<f64, Error> {
        let s = &self.spline;
        let (lo, hi) = s.domain();
        if s.extrapolate == Extrapolate::Nan && !(lo..=hi).contains(&x) {
            return Ok(f64::NAN);
        }
        if !x.is_finite() {
            return Err(Error::NonFinite {
                field: Field::Query,
                index,
                value: x,
            });
        }
        let v = if x < lo {
            s.integral(lo, x)?
        } else if x > hi {
            self.at_knots[s.len()] * s.scale() + s.integral(hi, x)?
        } else {
            let k = s.piece_index(x);
            let x0 = s.pieces.knots()[k];
            (self.at_knots[k] + s.piece_integral(k, x0, x)) * s.scale()
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Error::Overflow {
                what: "the antiderivative",
            })
        }
    }
}
