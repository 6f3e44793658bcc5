//! Building a curve: [`CurveBuilder`] collects the points and every choice
//! (closed or open, parameters, alphas, repeats, through, smoothing),
//! validates them and solves: the method, its interpolating variant
//! (`docs/method.md` §11) or a smoothing fit (§12).

use std::borrow::Cow;

use super::solve::{survey, Input};
use super::{Curve, Param, ParamKind, Repeats};
use crate::error::{Error, Field};
use crate::smoothing::{self, check_positive_weights, check_weight_values, Smoothed, Smoothing};
use crate::validate::{check_alphas, check_finite, resolve_alphas, Alphas, DEFAULT_ALPHA};

/// Collects the inputs of a [`Curve`] and builds it.
///
/// # Examples
///
/// ```
/// use bzspline::{Curve, Param};
/// let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let c = Curve::builder_from(&square)
///     .closed(true)
///     .param(Param::Chordal)
///     .alpha(0.5)
///     .build()?;
/// assert_eq!(c.len(), 4); // four segments, one per leg
/// # Ok::<(), bzspline::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CurveBuilder<'a> {
    dim: usize,
    /// Borrowed from the caller until the curve copies them.
    points: Cow<'a, [f64]>,
    closed: bool,
    param: Param,
    alpha: f64,
    alphas: Option<Vec<f64>>,
    repeats: Repeats,
    through: bool,
    smoothing: Option<Smoothing>,
    weights: Option<Vec<f64>>,
    robust: bool,
}

impl<'a> CurveBuilder<'a> {
    /// A builder for the points stored flat, `dim` coordinates per point.
    #[must_use]
    pub fn new(points: &'a [f64], dim: usize) -> Self {
        CurveBuilder {
            dim,
            points: Cow::Borrowed(points),
            closed: false,
            param: Param::default(),
            alpha: DEFAULT_ALPHA,
            alphas: None,
            repeats: Repeats::Reject,
            through: false,
            smoothing: None,
            weights: None,
            robust: false,
        }
    }

    /// Open (`false`, the default) or closed.
    #[must_use]
    pub fn closed(mut self, closed: bool) -> Self {
        self.closed = closed;
        self
    }

    /// The parameter choice (default [`Param::Centripetal`]).
    #[must_use]
    pub fn param(mut self, param: Param) -> Self {
        self.param = param;
        self
    }

    /// The same alpha on every leg (default [`DEFAULT_ALPHA`]).
    #[must_use]
    pub fn alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self.alphas = None;
        self
    }

    /// One alpha per leg: `n - 1` for an open curve, `n` for a closed one (the
    /// last is the closing leg's).
    #[must_use]
    pub fn alphas(mut self, alphas: &[f64]) -> Self {
        self.alphas = Some(alphas.to_vec());
        self
    }

    /// The alphas as an [`Alphas`] choice, as [`crate::Spline::build`] takes
    /// them (per-interval alphas are per leg here).
    #[must_use]
    pub fn alpha_choice(self, alphas: Alphas<'_>) -> Self {
        match alphas {
            Alphas::Uniform(a) => self.alpha(a),
            Alphas::PerInterval(a) => self.alphas(a),
        }
    }

    /// What to do with repeated consecutive points (default [`Repeats::Reject`]).
    #[must_use]
    pub fn repeats(mut self, repeats: Repeats) -> Self {
        self.repeats = repeats;
        self
    }

    /// Through the points (`true`) instead of touching the legs of their
    /// polygon (`false`, the default): the interpolating variant
    /// (`docs/method.md` §11). The curve passes through every point at its
    /// parameter, is C1, and touches every leg of the solved control polygon,
    /// which [`Curve::points`] returns; the parameters are chosen from the
    /// points given. Everything the default refuses is refused the same way.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Curve, Param};
    /// let pts = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]];
    /// let c = Curve::builder_from(&pts).param(Param::Chordal).through(true).build()?;
    /// for (k, p) in c.knot_points().iter().enumerate() {
    ///     assert!((p[0] - pts[k][0]).abs() < 1e-14 && (p[1] - pts[k][1]).abs() < 1e-14);
    /// }
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    #[must_use]
    pub fn through(mut self, through: bool) -> Self {
        self.through = through;
        self
    }

    /// A smoothing curve of noisy points (`docs/method.md` §12): the
    /// parameters are chosen from the points as without it, and the control
    /// points minimise `sum_j w_j |C(t_j) - P_j|^2 + lambda int |C''|^2` with
    /// one `lambda` for every coordinate (under [`Smoothing::Gcv`] the one of
    /// least cross-validation score summed over the coordinates). Open curves
    /// only; [`CurveBuilder::build_smoothed`] also returns `lambda` and the
    /// score. Each coordinate is then the function fit
    /// [`crate::Spline::smoothing`] on the curve's parameters.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Curve, Smoothing};
    /// let pts: Vec<[f64; 2]> = (0..40)
    ///     .map(|i| [i as f64, if i % 2 == 0 { 0.2 } else { -0.2 }])
    ///     .collect();
    /// let s = Curve::builder_from(&pts).smoothing(Smoothing::Lambda(1e9)).build_smoothed()?;
    /// // Smoothed hard, the zigzag of height 0.4 flattens to its
    /// // least-squares line, within 0.02 of y = 0.
    /// let worst = s.fit.knot_points().iter().fold(0.0f64, |m, p| m.max(p[1].abs()));
    /// assert!(worst < 0.02);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    ///
    /// Such a builder is built with [`CurveBuilder::build_smoothed`];
    /// [`CurveBuilder::build`] and [`CurveBuilder::build_into`] refuse it.
    #[must_use]
    pub fn smoothing(mut self, smoothing: Smoothing) -> Self {
        self.smoothing = Some(smoothing);
        self
    }

    /// One weight per point for [`CurveBuilder::smoothing`] (default all 1;
    /// finite, `>= 0`); a dropped repeat adds its weight to the point it
    /// repeats.
    #[must_use]
    pub fn weights(mut self, weights: &[f64]) -> Self {
        self.weights = Some(weights.to_vec());
        self
    }

    /// Makes [`CurveBuilder::smoothing`] robust against outliers, as
    /// [`Spline::smoothing_robust`](crate::Spline::smoothing_robust) does, the
    /// residual of a point being its distance from the fitted point; the
    /// weights it ends with are [`Smoothed::robustness`], one per point given
    /// (a dropped repeat has the weight of the point it repeats).
    #[must_use]
    pub fn robust(mut self, robust: bool) -> Self {
        self.robust = robust;
        self
    }

    /// Builds a smoothing curve ([`CurveBuilder::smoothing`], by default
    /// [`Smoothing::Gcv`]) and returns it with its `lambda`, score and
    /// degrees of freedom. A closed curve is smoothed round its loop
    /// (`docs/method.md` §15): every point is a knot of the periodic fit, and
    /// a large `lambda` draws it towards the weighted mean point rather than
    /// a line.
    ///
    /// # Errors
    ///
    /// As [`CurveBuilder::build`], and as [`crate::Spline::smoothing`] for
    /// the weights and `lambda`; [`Error::InvalidArgument`] with
    /// [`CurveBuilder::through`].
    pub fn build_smoothed(mut self) -> Result<Smoothed<Curve>, Error> {
        let smoothing = self.smoothing.take().unwrap_or_default();
        let weights = self.weights.take();
        let (robust, closed) = (self.robust, self.closed);
        if self.through {
            return Err(Error::InvalidArgument {
                what: "smoothing fits the points as noisy data: it cannot pass through them",
                value: 0.0,
            });
        }
        let dim = self.dim;
        let given = self.points.clone();
        let data = self.build()?;
        let n_in = data.point_count() + data.dropped.len();
        // A dropped point goes with the kept point before it, or with the
        // first when it closes a closed curve.
        let owner = |i: usize, kept: usize| -> usize {
            let closes = closed
                && i + 1 == n_in
                && kept > 0
                && given[i * dim..(i + 1) * dim] == data.points[..dim];
            if closes {
                0
            } else {
                kept.saturating_sub(1)
            }
        };
        let w = match weights {
            None => vec![1.0; data.point_count()],
            Some(w) => {
                // Each weight is judged where the caller put it; how many are
                // positive, after the merge.
                check_weight_values(&w, n_in)?;
                let mut kept = Vec::with_capacity(data.point_count());
                let mut drops = data.dropped.iter().peekable();
                for (i, &v) in w.iter().enumerate() {
                    if drops.peek() == Some(&&i) {
                        drops.next();
                        let at = owner(i, kept.len());
                        if let Some(k) = kept.get_mut(at) {
                            *k += v;
                        }
                    } else {
                        kept.push(v);
                    }
                }
                kept
            }
        };
        check_positive_weights(&w)?;
        let problem = smoothing::Data {
            knots: data.knots(),
            values: &data.points,
            dim,
            weights: &w,
            alphas: &data.alphas,
            closed,
        };
        let (fit, robustness) = if robust {
            let (fit, kept) = smoothing::fit_robust(problem, smoothing)?;
            // One weight a point given: a dropped one has its owner's.
            let mut all = Vec::with_capacity(n_in);
            let mut drops = data.dropped.iter().peekable();
            let mut next = 0; // the kept points so far
            for i in 0..n_in {
                if drops.peek() == Some(&&i) {
                    drops.next();
                    all.push(kept.get(owner(i, next)).copied().unwrap_or(1.0));
                } else {
                    all.push(kept.get(next).copied().unwrap_or(1.0));
                    next += 1;
                }
            }
            (fit, Some(all))
        } else {
            (smoothing::fit(problem, smoothing)?, None)
        };
        let mut c = CurveBuilder::new(&fit.controls, dim)
            .closed(closed)
            .param(Param::Given(data.knots().to_vec()))
            .alphas(&data.alphas)
            .build()?;
        if closed && !knots_agree(&c, &fit.fitted) {
            return Err(Error::InvalidArgument {
                what: "the smoothing system is too ill-conditioned for these parameters and \
                       lambda (intervals of widths many decades apart)",
                value: f64::NAN,
            });
        }
        c.dropped = data.dropped;
        Ok(Smoothed {
            fit: c,
            lambda: fit.lambda,
            gcv: fit.gcv,
            dof: fit.dof,
            posterior: fit.posterior,
            robustness,
        })
    }

    /// Validates the inputs and solves.
    ///
    /// # Errors
    ///
    /// - [`Error::InvalidArgument`] for dimension 0;
    /// - [`Error::LengthMismatch`] (field [`Field::Coordinate`]) when the number
    ///   of coordinates is not a multiple of the dimension; with
    ///   [`Field::Alpha`] or [`Field::Knot`] for a wrong number of alphas or
    ///   given parameters;
    /// - [`Error::NonFinite`] with [`Field::Coordinate`] and the point's index for
    ///   a NaN or infinite coordinate (or with the field of a bad alpha or
    ///   parameter);
    /// - [`Error::TooFewPoints`] for fewer than 2 points (3 for a closed curve),
    ///   also after dropping repeats;
    /// - [`Error::RepeatedPoint`] / [`Error::RepeatedClosingPoint`] for repeated
    ///   consecutive points under [`Repeats::Reject`];
    /// - [`Error::AlphaOutOfRange`] for an alpha outside `[1/3, 2/3]`;
    /// - the knot errors of [`crate::Spline::with_alphas`] for the parameters
    ///   (not increasing, an interval too small relative to the span);
    /// - [`Error::InvalidArgument`] when [`CurveBuilder::smoothing`] was set
    ///   (build it with [`CurveBuilder::build_smoothed`]).
    pub fn build(self) -> Result<Curve, Error> {
        let mut c = Curve::empty();
        Curve::build_from(self, &mut c)?;
        Ok(c)
    }

    /// Validates the inputs and solves into `curve`, reusing its allocations:
    /// rebuilding a curve of the same size allocates none of its own arrays
    /// (with uniform parameters and no repeated points), which saves the page
    /// faults of fresh memory on long curves; from 65,537 points the chunked
    /// solve takes a few small allocations (under 100 kB for a million points).
    /// The result is the curve [`CurveBuilder::build`] returns.
    ///
    /// # Errors
    ///
    /// As [`CurveBuilder::build`]; on error `curve` is left unchanged.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Curve, CurveBuilder};
    /// let mut c = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])?;
    /// CurveBuilder::new(&[0.0, 0.0, 1.0, 2.0, 2.0, 0.0], 2).build_into(&mut c)?;
    /// assert_eq!(c.point(1), Some(&[1.0, 2.0][..]));
    /// assert!(CurveBuilder::new(&[0.0, 0.0, 0.0, 0.0], 2).build_into(&mut c).is_err());
    /// assert_eq!(c.point(1), Some(&[1.0, 2.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn build_into(self, curve: &mut Curve) -> Result<(), Error> {
        Curve::build_from(self, curve)
    }
}

impl Curve {
    /// Validates the builder's inputs and solves into `target`, which changes
    /// only on success.
    fn build_from(b: CurveBuilder<'_>, target: &mut Curve) -> Result<(), Error> {
        if b.smoothing.is_some() {
            // Not dispatched from here, so that a program building plain
            // curves does not carry the fit (the WebAssembly module's size).
            return Err(Error::InvalidArgument {
                what: "a smoothing curve is built with build_smoothed",
                value: 0.0,
            });
        }
        let dim = b.dim;
        if dim == 0 {
            return Err(Error::InvalidArgument {
                what: "the dimension must be at least 1",
                value: 0.0,
            });
        }
        if !b.points.len().is_multiple_of(dim) {
            return Err(Error::LengthMismatch {
                field: Field::Coordinate,
                expected: b.points.len() / dim * dim + dim,
                found: b.points.len(),
            });
        }
        // One pass: finite coordinates, repeated neighbours, largest magnitudes
        // (on the stack up to eight coordinates: a rebuild allocates nothing).
        let (mut small, mut large) = ([0.0f64; 8], Vec::new());
        let maxes: &mut [f64] = match small.get_mut(..dim) {
            Some(m) => m,
            None => {
                large.resize(dim, 0.0);
                &mut large
            }
        };
        let Some(repeats) = survey(&b.points, dim, maxes) else {
            let i = b.points.iter().position(|v| !v.is_finite()).unwrap_or(0);
            return Err(Error::NonFinite {
                field: Field::Coordinate,
                index: i / dim,
                value: b.points[i],
            });
        };
        let n = b.points.len() / dim;
        let min = if b.closed { 3 } else { 2 };
        if n < min {
            return Err(Error::TooFewPoints { found: n, min });
        }
        let legs = if b.closed { n } else { n - 1 };
        let choice = match &b.alphas {
            Some(a) => Alphas::PerInterval(a),
            None => Alphas::Uniform(b.alpha),
        };
        check_alphas(choice, legs)?;
        let (kind, given) = match b.param {
            Param::Uniform => (ParamKind::Uniform, None),
            Param::Chordal => (ParamKind::Chordal, None),
            Param::Centripetal => (ParamKind::Centripetal, None),
            Param::Given(g) => {
                let want = if b.closed { n + 1 } else { n };
                if g.len() != want {
                    return Err(Error::LengthMismatch {
                        field: Field::Knot,
                        expected: want,
                        found: g.len(),
                    });
                }
                check_finite(Field::Knot, &g)?;
                (ParamKind::Given, Some(g))
            }
        };
        let pt = |i: usize| &b.points[i * dim..(i + 1) * dim];
        let repeats = repeats || (b.closed && pt(n - 1) == pt(0));
        if !repeats {
            // Nothing to drop: the builder's points and alphas are the curve's.
            let given = given.as_deref();
            let input = Input {
                dim,
                closed: b.closed,
                kind,
                points: &b.points,
                maxes,
                dropped: Vec::new(),
                given,
                alphas: choice,
                through: b.through,
            };
            return Self::solve_into(target, input);
        }
        let (keep, dropped) = keep_list(&b.points, dim, b.closed, b.repeats)?;
        if keep.len() < min {
            return Err(Error::TooFewPoints {
                found: keep.len(),
                min,
            });
        }
        let nk = keep.len();
        let points: Vec<f64> = keep.iter().flat_map(|&i| pt(i).iter().copied()).collect();
        // Each kept leg keeps the alpha of the one original leg of nonzero length
        // it stands for: the leg that leaves the run of copies of its start.
        let legs_kept = if b.closed { nk } else { nk - 1 };
        let alphas = resolve_alphas(choice, legs)?;
        let alphas: Vec<f64> = keep[..legs_kept]
            .iter()
            .map(|&a| {
                let mut e = a + 1;
                while e < n && pt(e) == pt(a) {
                    e += 1;
                }
                alphas[e - 1]
            })
            .collect();
        let given = given.map(|g| {
            let mut v: Vec<f64> = keep.iter().map(|&i| g[i]).collect();
            if b.closed {
                v.push(g[n]);
            }
            v
        });
        let (given, alphas) = (given.as_deref(), Alphas::PerInterval(&alphas));
        // Dropped points repeat kept ones: the largest magnitudes stay.
        let input = Input {
            dim,
            closed: b.closed,
            kind,
            points: &points,
            maxes,
            dropped,
            given,
            alphas,
            through: b.through,
        };
        Self::solve_into(target, input)
    }
}

/// The points a builder keeps and those it drops as repeats of the point
/// before them (and, closed, of the first), or the refusal of a repeat under
/// [`Repeats::Reject`].
fn keep_list(
    points: &[f64],
    dim: usize,
    closed: bool,
    repeats: Repeats,
) -> Result<(Vec<usize>, Vec<usize>), Error> {
    let n = points.len() / dim;
    let pt = |i: usize| &points[i * dim..(i + 1) * dim];
    let mut keep: Vec<usize> = Vec::with_capacity(n);
    let mut dropped = Vec::new();
    for i in 0..n {
        if let Some(&last) = keep.last() {
            if pt(i) == pt(last) {
                match repeats {
                    Repeats::Reject => return Err(Error::RepeatedPoint { index: i }),
                    Repeats::Drop => {
                        dropped.push(i);
                        continue;
                    }
                }
            }
        }
        keep.push(i);
    }
    if closed {
        while keep.len() > 1 {
            let last = keep[keep.len() - 1];
            if pt(last) != pt(keep[0]) {
                break;
            }
            match repeats {
                Repeats::Reject => return Err(Error::RepeatedClosingPoint { last }),
                Repeats::Drop => {
                    dropped.push(last);
                    keep.pop();
                }
            }
        }
        dropped.sort_unstable();
    }
    Ok((keep, dropped))
}

/// Whether the knot points of the curve built from a closed fit's control
/// points are the fitted ones, to 1e-7 of their largest magnitude: the check
/// that the elimination held.
fn knots_agree(c: &Curve, fitted: &[f64]) -> bool {
    let big = fitted.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
    let kp = c.knot_points();
    kp.iter()
        .flatten()
        .zip(fitted)
        .all(|(a, b)| (a - b).abs() <= 1e-7 * big)
        && kp.iter().map(Vec::len).sum::<usize>() >= fitted.len()
}
