//! Evaluating a curve: locating the segment of a parameter, points and
//! derivatives, tangents, normals and curvature, and sampling at equal steps.

use super::{check_output, dot, norm, Curve};
use crate::error::{Error, Field};
use crate::poly::{deriv_of, horner};
use crate::polyline::Polyline;
use crate::traits::check_out;
use crate::traits::ParamCurve;

impl Curve {
    /// Segment and local parameter of `s`.
    pub(super) fn locate(&self, s: f64) -> Result<(usize, f64), Error> {
        self.locate_near(s, usize::MAX)
    }

    /// [`Curve::locate`], trying segment `hint` and the next one before the
    /// search (queries in order mostly stay in one segment or move to the
    /// next); the segment found is the one the search finds.
    pub(super) fn locate_near(&self, s: f64, hint: usize) -> Result<(usize, f64), Error> {
        if !s.is_finite() {
            return Err(Error::NonFinite {
                field: Field::Query,
                index: 0,
                value: s,
            });
        }
        let (lo, hi) = self.domain();
        let mut s = s;
        if !(lo..=hi).contains(&s) {
            if !self.closed {
                return Err(Error::OutOfDomain {
                    x: s,
                    min: lo,
                    max: hi,
                });
            }
            s = lo + (s - lo).rem_euclid(hi - lo);
            if !(lo..=hi).contains(&s) {
                s = lo;
            }
        }
        let knots = self.pieces.knots();
        // Segment k answers on [tau_k, tau_{k+1}); the search gives the same.
        let within = |k: usize| k < knots.len() - 1 && knots[k] <= s && s < knots[k + 1];
        let next = hint.wrapping_add(1);
        let k = if within(hint) {
            hint
        } else if within(next) {
            next
        } else {
            self.pieces.locate(s)
        };
        let t = ((s - knots[k]) / self.pieces.width(k)).clamp(0.0, 1.0);
        Ok((k, t))
    }

    /// Derivative of order `order` in the local `t` of segment `k`, in units of
    /// the largest scale, into `out`.
    pub(super) fn local(&self, k: usize, t: f64, order: u32, out: &mut [f64]) {
        let dim = self.dim();
        let j = (k + 1) % self.n_points();
        for (c, o) in out.iter_mut().enumerate() {
            let rel = self.pieces.scale(c) / self.pieces.unit();
            let v = if order == 0 && t == 1.0 {
                self.fv(j, c) + self.d[j * dim + c]
            } else {
                deriv_of(self.pieces.piece(k, c), t, order)
            };
            *o = v * rel;
        }
    }

    /// The point at parameter `s`.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a NaN or infinite `s`; [`Error::OutOfDomain`]
    /// outside the domain of an open curve (a closed curve is periodic).
    pub fn eval(&self, s: f64) -> Result<Vec<f64>, Error> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(s, &mut out)?;
        Ok(out)
    }

    /// The point at local `t` of segment `k` into `out` (`dim` numbers).
    pub(super) fn point_at(&self, k: usize, t: f64, out: &mut [f64]) {
        let dim = self.dim();
        let n = self.n_points();
        let j = (k + 1) % n;
        if !self.closed && ((k == 0 && t == 0.0) || (t == 1.0 && j == n - 1)) {
            // An open curve's end points are its end control points, also when
            // one of them underflowed in scaling beside a much larger one.
            let i = if t == 0.0 { 0 } else { n - 1 };
            out.copy_from_slice(&self.points[i * dim..(i + 1) * dim]);
            return;
        }
        for (c, o) in out.iter_mut().enumerate() {
            let v = if t == 1.0 {
                self.fv(j, c) + self.d[j * dim + c]
            } else {
                horner(self.pieces.piece(k, c), t)
            };
            let v = v * self.pieces.scale(c);
            *o = if v.is_infinite() {
                // Rounding above the largest double inside the hull.
                f64::MAX.copysign(v)
            } else {
                v
            };
        }
    }

    /// The derivative of order `order` (0..=3; higher ones are 0) with respect
    /// to the parameter at `s`. At a knot, orders 2 and 3 are those of the
    /// segment to the right.
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`]; [`Error::Overflow`] when a derivative exceeds the
    /// range of a double.
    pub fn deriv(&self, s: f64, order: u32) -> Result<Vec<f64>, Error> {
        let mut out = vec![0.0; self.dim()];
        self.deriv_into(s, order, &mut out)?;
        Ok(out)
    }

    /// The derivative of order `order` at local `t` of segment `k` into `out`.
    pub(super) fn deriv_at(
        &self,
        k: usize,
        t: f64,
        order: u32,
        out: &mut [f64],
    ) -> Result<(), Error> {
        if order == 0 {
            self.point_at(k, t, out);
            return Ok(());
        }
        let h = self.pieces.width(k);
        for (c, o) in out.iter_mut().enumerate() {
            let mut v = self.pieces.value(k, c, t, order);
            for _ in 0..order.min(4) {
                v /= h;
            }
            if !v.is_finite() {
                return Err(Error::Overflow {
                    what: "the derivative",
                });
            }
            *o = v;
        }
        Ok(())
    }

    /// [`Curve::deriv`] at every parameter of `ss`, into `out` (`dim` numbers
    /// a parameter, parameter after parameter): the same numbers as one call
    /// a parameter, found faster when the parameters come in order (each
    /// search starts from the segment of the one before).
    ///
    /// # Errors
    ///
    /// [`Error::LengthMismatch`] when `out` does not hold `dim` numbers for
    /// every parameter; otherwise as [`Curve::deriv`], naming the parameter's
    /// index. `out` is then written up to that parameter.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let ts = [0.0, 0.5, 1.5, 2.5];
    /// let mut out = [0.0; 8];
    /// c.deriv_many(&ts, 0, &mut out)?;
    /// assert_eq!(&out[2..4], c.eval(0.5)?.as_slice());
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn deriv_many(&self, ss: &[f64], order: u32, out: &mut [f64]) -> Result<(), Error> {
        let dim = self.dim();
        check_output(out, ss.len() * dim)?;
        let mut hint = usize::MAX;
        for (i, (&s, o)) in ss.iter().zip(out.chunks_exact_mut(dim)).enumerate() {
            let (k, t) = self.locate_near(s, hint).map_err(|e| e.at_query(i))?;
            self.deriv_at(k, t, order, o)?;
            hint = k;
        }
        Ok(())
    }

    /// The unit tangent at `s` (the zero vector where the derivative vanishes).
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`].
    pub fn tangent(&self, s: f64) -> Result<Vec<f64>, Error> {
        let (k, t) = self.locate(s)?;
        let mut v = vec![0.0; self.dim()];
        self.local(k, t, 1, &mut v);
        let m = norm(&v);
        if m > 0.0 {
            v.iter_mut().for_each(|x| *x /= m);
        }
        Ok(v)
    }

    /// The unit normal at `s`. In the plane it is the tangent turned by +90
    /// degrees, `(-t_y, t_x)`. In other dimensions it is the part of the second
    /// derivative orthogonal to the tangent, normalised (the principal normal);
    /// the zero vector where the curve is straight or the derivative vanishes.
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`].
    pub fn normal(&self, s: f64) -> Result<Vec<f64>, Error> {
        let tan = self.tangent(s)?;
        if self.dim() == 2 {
            return Ok(vec![-tan[1], tan[0]]);
        }
        let (k, t) = self.locate(s)?;
        let mut a = vec![0.0; self.dim()];
        self.local(k, t, 2, &mut a);
        let along = dot(&a, &tan);
        for (x, u) in a.iter_mut().zip(&tan) {
            *x -= along * u;
        }
        let m = norm(&a);
        if m > 0.0 && m.is_finite() && tan.iter().any(|x| *x != 0.0) {
            a.iter_mut().for_each(|x| *x /= m);
        } else {
            a.iter_mut().for_each(|x| *x = 0.0);
        }
        Ok(a)
    }

    /// The curvature `|r' x r''| / |r'|^3` at `s` (unsigned; 0 on a straight
    /// part).
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])?;
    /// assert_eq!(c.curvature(0.7)?, 0.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`]; [`Error::Overflow`] where the derivative vanishes or
    /// the curvature exceeds the range of a double.
    pub fn curvature(&self, s: f64) -> Result<f64, Error> {
        let (k, t) = self.locate(s)?;
        let mut v = vec![0.0; self.dim()];
        let mut a = vec![0.0; self.dim()];
        self.local(k, t, 1, &mut v);
        self.local(k, t, 2, &mut a);
        let speed = norm(&v);
        if speed == 0.0 {
            return Err(Error::Overflow {
                what: "the curvature where the derivative vanishes",
            });
        }
        let u: Vec<f64> = v.iter().map(|x| x / speed).collect();
        let along = dot(&a, &u);
        for (x, u) in a.iter_mut().zip(&u) {
            *x -= along * u;
        }
        let kappa = norm(&a) / speed / speed / self.pieces.unit();
        if kappa.is_finite() {
            Ok(kappa)
        } else {
            Err(Error::Overflow {
                what: "the curvature",
            })
        }
    }

    /// `v` in units of the largest scale back in the curve's units.
    pub(super) fn to_units(&self, v: f64, what: &'static str) -> Result<f64, Error> {
        let r = v * self.pieces.unit();
        if r.is_finite() {
            Ok(r)
        } else {
            Err(Error::Overflow { what })
        }
    }

    /// `count >= 2` points at equal parameter steps from the start to the end
    /// (a closed curve's last point is its first), with their parameters. For
    /// equal arc-length steps see [`Curve::resample`].
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for `count < 2`.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Curve, Param};
    /// // Uniform parameters: the domain is [0, 2].
    /// let c = Curve::builder_from(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
    ///     .param(Param::Uniform)
    ///     .build()?;
    /// let p = c.sample(3)?;
    /// assert_eq!(p.params(), &[0.0, 1.0, 2.0]);
    /// assert_eq!(p.point(2), Some(&[2.0, 0.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn sample(&self, count: usize) -> Result<Polyline, Error> {
        if count < 2 {
            return Err(Error::InvalidArgument {
                what: "sampling needs at least 2 points",
                value: count as f64,
            });
        }
        let (lo, hi) = self.domain();
        let mut params = Vec::with_capacity(count);
        let mut coords = Vec::with_capacity(count * self.dim());
        for i in 0..count {
            let s = if i + 1 == count {
                hi
            } else {
                (lo + (hi - lo) * (i as f64 / (count - 1) as f64)).min(hi)
            };
            coords.extend(self.eval(s)?);
            params.push(s);
        }
        Ok(Polyline::new(self.dim(), coords, params))
    }
}

impl ParamCurve for Curve {
    /// The dimension `d` of the space.
    fn dim(&self) -> usize {
        self.pieces.dim()
    }
    /// The parameter domain `[tau_0, tau_last]`.
    fn domain(&self) -> (f64, f64) {
        (
            self.pieces.knots()[0],
            self.pieces.knots()[self.pieces.knots().len() - 1],
        )
    }
    /// [`Curve::eval`] into `out` (`dim` numbers), without allocating.
    ///
    /// # Errors
    ///
    /// As [`Curve::eval`]; [`Error::InvalidArgument`] when `out` does not hold
    /// [`Curve::dim`] numbers.
    fn eval_into(&self, s: f64, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, self.dim())?;
        let (k, t) = self.locate(s)?;
        self.point_at(k, t, out);
        Ok(())
    }
    /// [`Curve::deriv`] into `out` (`dim` numbers), without allocating.
    ///
    /// # Errors
    ///
    /// As [`Curve::deriv`]; [`Error::InvalidArgument`] when `out` does not hold
    /// [`Curve::dim`] numbers.
    fn deriv_into(&self, s: f64, order: u32, out: &mut [f64]) -> Result<(), Error> {
        check_out(out, self.dim())?;
        let (k, t) = self.locate(s)?;
        self.deriv_at(k, t, order, out)
    }
}
