//! Smoothing splines in the method's basis (`docs/method.md` §12): control
//! values chosen so that the method's spline minimises
//! `sum_j w_j (S(x_j) - y_j)^2 + lambda int S''(x)^2 dx`, with `lambda` given or
//! chosen by generalized cross-validation; one block-tridiagonal solve per
//! `lambda`, O(N) time and memory, the trace of the influence matrix included.

mod cyclic;
mod posterior;
mod robust;
mod system;

pub use posterior::{band_z, normal_quantile, Posterior, PosteriorParts};
pub(crate) use robust::fit_robust;
pub use robust::ROBUST_MIN_POINTS;

use crate::error::{Error, Field};
use crate::method::power_of_two_scale;
use cyclic::{CyclicFactored, CyclicGrid};
use system::{Factored, Grid, System};

/// How much a smoothing spline smooths: the weight `lambda` of the roughness
/// penalty `int S''^2` against the weighted squared residuals.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Smoothing {
    /// This `lambda` (finite, `>= 0`), in the units of the data: with `x`
    /// scaled by `c` and the weights by `v`, the same curve needs `lambda`
    /// times `v c^3`. `0` passes through every point (the interpolating
    /// variant); a large `lambda` tends to the weighted least-squares line.
    Lambda(f64),
    /// The `lambda` that minimises the generalized cross-validation score
    /// (as `scipy.interpolate.make_smoothing_spline` does when `lam` is
    /// omitted), searched over the whole range from interpolation to the
    /// straight line.
    #[default]
    Gcv,
}

/// A smoothing fit and how it was chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct Smoothed<T> {
    /// The fitted spline or curve: the method's construction of the solved
    /// control values, so every property of the method holds for it.
    pub fit: T,
    /// The `lambda` used (the one chosen, under [`Smoothing::Gcv`]), in the
    /// units of the data.
    pub lambda: f64,
    /// The generalized cross-validation score at `lambda`,
    /// `(1/n) sum_j w_j r_j^2 / (1 - dof/n)^2` with `n` the number of points of
    /// positive weight (for a curve, `r_j^2` summed over the coordinates and
    /// divided by their number); infinite when the fit interpolates
    /// (`lambda = 0`), where it is undefined.
    pub gcv: f64,
    /// The effective degrees of freedom: the trace of the influence matrix
    /// (from 2 for the straight line to `n` for interpolation).
    pub dof: f64,
    /// What the fit's standard errors and confidence bands need
    /// (`docs/method.md` §13).
    pub posterior: Posterior,
    /// The robustness weight of each point, in `[0, 1]`, that a robust fit
    /// ([`Spline::smoothing_robust`](crate::Spline::smoothing_robust),
    /// [`CurveBuilder::robust`](crate::CurveBuilder::robust)) ended with: 0
    /// for a point it judged an outlier, 1 for one it fits as well as any;
    /// the fit weighs each point by its given weight times this. `None`
    /// for a plain fit.
    pub robustness: Option<Vec<f64>>,
}

impl Smoothed<crate::Spline> {
    /// The standard error of the fit at `x`: the square root of the
    /// Bayesian posterior variance of the penalised fit (Wahba's),
    /// `sigma^2 b(x)^T M^-1 b(x)` with `M` the matrix the fit factored and
    /// `sigma^2 = RSS / (n - dof)`. O(log N) a point.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfDomain`] for `x` outside the knots (or not finite);
    /// [`Error::InvalidArgument`] when the fit passes through its points
    /// (`lambda = 0`): no residual is left to estimate the noise.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Alphas, Smoothing, Spline};
    /// let x: Vec<f64> = (0..200).map(|i| i as f64 / 199.0).collect();
    /// let y: Vec<f64> = x.iter().enumerate()
    ///     .map(|(i, &t)| (6.0 * t).sin() + if i % 2 == 0 { 0.2 } else { -0.2 })
    ///     .collect();
    /// let s = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv)?;
    /// let (lo, hi) = s.band(0.5, 0.95)?;
    /// assert!(lo < s.fit.eval(0.5)? && s.fit.eval(0.5)? < hi);
    /// assert!(hi - lo < 0.2 && s.se(0.5)? > 0.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn se(&self, x: f64) -> Result<f64, Error> {
        self.posterior.se(x, 0)
    }

    /// [`Smoothed::se`] at every `x`.
    ///
    /// # Errors
    ///
    /// As [`Smoothed::se`], for the first `x` that has none.
    pub fn se_many(&self, xs: &[f64]) -> Result<Vec<f64>, Error> {
        let s2 = self.posterior.noise_variance()?[0];
        xs.iter()
            .map(|&x| Ok((s2 * self.posterior.unit_variance(x)?).sqrt()))
            .collect()
    }

    /// The pointwise confidence band at `x`: `S(x) -+ z se(x)` with `z` the
    /// standard normal quantile of `(1 + level) / 2` (1.96 at 0.95). Across
    /// the data's points the band covers the true curve at about `level` of
    /// them on average (an across-the-function property, as for mgcv's).
    ///
    /// # Errors
    ///
    /// As [`Smoothed::se`]; [`Error::InvalidArgument`] for a level outside
    /// `(0, 1)`.
    pub fn band(&self, x: f64, level: f64) -> Result<(f64, f64), Error> {
        self.posterior.band(self.fit.eval(x)?, x, level, 0)
    }

    /// [`Smoothed::band`] at every `x`: the lower and the upper edges.
    ///
    /// # Errors
    ///
    /// As [`Smoothed::band`].
    pub fn band_many(&self, xs: &[f64], level: f64) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let z = band_z(level)?;
        let se = self.se_many(xs)?;
        let mut lo = Vec::with_capacity(xs.len());
        let mut hi = Vec::with_capacity(xs.len());
        for (&x, s) in xs.iter().zip(se) {
            let y = self.fit.eval(x)?;
            lo.push(y - z * s);
            hi.push(y + z * s);
        }
        Ok((lo, hi))
    }
}

impl Smoothed<crate::Curve> {
    /// The standard error of each coordinate of the smoothed curve at the
    /// parameter `t` (the curve's own parameter, as its knots run), as
    /// [`Smoothed::se`] gives for a spline: every coordinate shares the
    /// matrix, each has its own noise variance.
    ///
    /// # Errors
    ///
    /// As [`Smoothed::se`], with `t` outside the knots out of domain.
    pub fn se(&self, t: f64) -> Result<Vec<f64>, Error> {
        let v = self.posterior.unit_variance(t)?;
        Ok(self
            .posterior
            .noise_variance()?
            .iter()
            .map(|s2| (s2 * v).sqrt())
            .collect())
    }
}

/// A weight below this, relative to the mean weight, counts as none where
/// conditioning is concerned (`system` starts its head block after such
/// points).
pub(crate) const NEGLIGIBLE_WEIGHT: f64 = 1e-8;

/// The solved control values of a smoothing fit, flat (`dim` per point).
pub(crate) struct Fit {
    pub(crate) controls: Vec<f64>,
    /// The fitted values at the knots, flat, in the data's units.
    pub(crate) fitted: Vec<f64>,
    pub(crate) lambda: f64,
    pub(crate) gcv: f64,
    pub(crate) dof: f64,
    pub(crate) posterior: Posterior,
}

/// Checks the weights (one per point, finite, `>= 0`, at least two positive)
/// and returns them, ones when none are given.
pub(crate) fn check_weights(weights: Option<&[f64]>, n: usize) -> Result<Vec<f64>, Error> {
    let Some(w) = weights else {
        return Ok(vec![1.0; n]);
    };
    check_weight_values(w, n)?;
    check_positive_weights(w)?;
    Ok(w.to_vec())
}

/// One weight per point, each finite and `>= 0`; the index of a bad one named.
pub(crate) fn check_weight_values(w: &[f64], n: usize) -> Result<(), Error> {
    if w.len() != n {
        return Err(Error::LengthMismatch {
            field: Field::Weight,
            expected: n,
            found: w.len(),
        });
    }
    for (index, &value) in w.iter().enumerate() {
        if !value.is_finite() {
            return Err(Error::NonFinite {
                field: Field::Weight,
                index,
                value,
            });
        }
        if value < 0.0 {
            return Err(Error::NegativeWeight { index, value });
        }
    }
    Ok(())
}

/// At least two positive weights: a line through them is what the penalty
/// cannot hold.
pub(crate) fn check_positive_weights(w: &[f64]) -> Result<(), Error> {
    let positive = w.iter().filter(|&&v| v > 0.0).count();
    if positive < 2 {
        return Err(Error::InvalidArgument {
            what: "a smoothing spline needs at least 2 points of positive weight",
            value: positive as f64,
        });
    }
    Ok(())
}

/// A smoothing problem, checked: `values` (flat, `dim` per point) at the
/// knots, one weight a point (see [`check_weights`]), one alpha an
/// interval. An open problem has a knot a point (at least 3, increasing);
/// a closed one (`closed`) a knot more, closing the loop (§15).
#[derive(Clone, Copy)]
pub(crate) struct Data<'a> {
    pub(crate) knots: &'a [f64],
    pub(crate) values: &'a [f64],
    pub(crate) dim: usize,
    pub(crate) weights: &'a [f64],
    pub(crate) alphas: &'a [f64],
    pub(crate) closed: bool,
}

impl<'a> Data<'a> {
    /// The same problem with other weights.
    pub(crate) fn with_weights(self, weights: &'a [f64]) -> Self {
        Data { weights, ..self }
    }
}

/// The smoothing fit of `data`.
pub(crate) fn fit(data: Data<'_>, smoothing: Smoothing) -> Result<Fit, Error> {
    let count = data.weights.iter().filter(|&&w| w > 0.0).count() as f64;
    fit_counted(data, smoothing, count)
}

/// [`fit`] with the number of observations `count` that the GCV score and
/// the noise variance divide by: the points of positive weight for a plain
/// fit, the sum of the robustness weights for a robust one (§14).
pub(crate) fn fit_counted(data: Data<'_>, smoothing: Smoothing, count: f64) -> Result<Fit, Error> {
    let Data {
        knots,
        values,
        dim,
        weights,
        alphas,
        closed,
    } = data;
    let n = weights.len();
    if n < 3 {
        return Err(Error::TooFewPoints { found: n, min: 3 });
    }
    check_lambda(smoothing, weights)?;
    // §12: knots spanning 1, weights of mean 1, each coordinate scaled by a
    // power of two; lambda scales by (mean weight) span^3.
    let span = knots[knots.len() - 1] - knots[0];
    let widths: Vec<f64> = knots.windows(2).map(|w| (w[1] - w[0]) / span).collect();
    let positive = weights.iter().filter(|&&w| w > 0.0).count();
    let mean_w = weights.iter().sum::<f64>() / n as f64;
    let w: Vec<f64> = weights.iter().map(|&v| v / mean_w).collect();
    let unit = mean_w * span * span * span;
    let coords: Vec<(f64, Vec<f64>)> = (0..dim)
        .map(|c| {
            let scale = power_of_two_scale((0..n).map(|i| &values[i * dim + c]));
            (scale, (0..n).map(|i| values[i * dim + c] / scale).collect())
        })
        .collect();
    // Where a point has no weight (or next to none against the others), only
    // the penalty shapes the fit there, and a lambda far below the one that
    // interpolates (h_min^3) leaves it to rounding: such lambdas are refused.
    let h_min = widths.iter().fold(1.0f64, |m, &h| m.min(h));
    let floor = if w.iter().any(|&v| v < NEGLIGIBLE_WEIGHT) {
        1e-12 * h_min * h_min * h_min
    } else {
        0.0
    };
    let problem = Problem {
        floor,
        weights: &w,
        widths: &widths,
        coords: &coords,
        count,
        mean_w,
    };
    let (lambda, f) = if closed {
        let grid = CyclicGrid::new(&widths, alphas, &w);
        let (lambda, f) = solve_for(&problem, smoothing, unit, span, || {
            CyclicFactored::new(&grid)
        })?;
        (lambda, Solution::of(f, &coords, data)?)
    } else {
        let grid = Grid::new(&widths, alphas, &w);
        let (lambda, f) = solve_for(&problem, smoothing, unit, span, || Factored::new(&grid))?;
        (lambda, Solution::of(f, &coords, data)?)
    };
    let Solution {
        controls,
        fitted,
        rss,
        dof,
        cov,
    } = f;
    if !(dof > 1.0 - 1e-6 && dof < positive as f64 * (1.0 + 1e-9) + 1e-9) {
        return Err(ill_conditioned());
    }
    // §13: sigma^2 = sum_j w_j r_j^2 / (n - dof) with the weights of mean 1.
    let residual_dof = count - dof;
    let sigma2 = (residual_dof > 1e-9 * count)
        .then(|| rss.iter().map(|r| r / (mean_w * residual_dof)).collect());
    let posterior = Posterior::new(knots, alphas, cov, sigma2);
    Ok(Fit {
        controls,
        fitted,
        lambda,
        gcv: gcv_score(rss.iter().sum::<f64>() / dim as f64, dof, count),
        dof,
        posterior,
    })
}

/// What the search for `lambda` needs of a problem, in normalised units.
struct Problem<'a> {
    /// The least lambda accepted (0: any).
    floor: f64,
    weights: &'a [f64],
    widths: &'a [f64],
    coords: &'a [(f64, Vec<f64>)],
    /// The number of observations (see [`fit_counted`]).
    count: f64,
    mean_w: f64,
}

/// The `lambda` (in the data's units), given or chosen, and the system
/// factored for it: `system` makes a new one.
fn solve_for<S: System + Send>(
    problem: &Problem<'_>,
    smoothing: Smoothing,
    unit: f64,
    span: f64,
    system: impl Fn() -> S + Sync,
) -> Result<(f64, S), Error> {
    let mut eval = Evaluator::new(problem, &system);
    let lambda = choose(&mut eval, smoothing, unit, span)?;
    let lam = lambda / unit;
    let lam = if lam.is_finite() { lam } else { f64::MAX };
    let mut f = eval.system;
    if !f.factor(lam) {
        return Err(Error::InvalidArgument {
            what: "the smoothing system is singular for these weights",
            value: lambda,
        });
    }
    Ok((lambda, f))
}

/// A factored system's solution for every coordinate, with its trace and
/// posterior covariances.
struct Solution {
    controls: Vec<f64>,
    fitted: Vec<f64>,
    rss: Vec<f64>,
    dof: f64,
    cov: Vec<[f64; 7]>,
}

impl Solution {
    fn of<S: System>(
        mut f: S,
        coords: &[(f64, Vec<f64>)],
        data: Data<'_>,
    ) -> Result<Solution, Error> {
        let (controls, fitted, rss) = controls(&mut f, coords, data)?;
        let (dof, cov) = f.trace_and_covariances();
        Ok(Solution {
            controls,
            fitted,
            rss,
            dof,
            cov,
        })
    }
}

impl Smoothing {
    /// Checks a given `lambda`: finite and `>= 0` ([`Smoothing::Gcv`] is
    /// always good). Every fit checks it; the command's `--smooth`, its
    /// server and the bindings check it here too.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] with the `lambda`.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Smoothing;
    ///
    /// assert!(Smoothing::Lambda(0.5).check().is_ok());
    /// assert!(Smoothing::Lambda(-1.0).check().is_err());
    /// assert!(Smoothing::Lambda(f64::NAN).check().is_err());
    /// ```
    pub fn check(self) -> Result<Self, Error> {
        match self {
            Smoothing::Lambda(l) if !(l.is_finite() && l >= 0.0) => Err(Error::InvalidArgument {
                what: "lambda must be a finite number >= 0",
                value: l,
            }),
            ok => Ok(ok),
        }
    }
}

/// The checks of a given `lambda`: [`Smoothing::check`], and 0 only with
/// every weight positive.
fn check_lambda(smoothing: Smoothing, weights: &[f64]) -> Result<(), Error> {
    let Smoothing::Lambda(l) = smoothing.check()? else {
        return Ok(());
    };
    if l == 0.0 && weights.contains(&0.0) {
        return Err(Error::InvalidArgument {
            what: "lambda = 0 passes through every point and needs every weight positive",
            value: l,
        });
    }
    Ok(())
}

/// The `lambda` in the data's units, given or chosen. The fit is then made
/// from it as `Smoothing::Lambda(lambda)` makes it, so the reported lambda
/// reproduces the fit bit for bit.
fn choose<S: System + Send>(
    eval: &mut Evaluator<'_, S>,
    smoothing: Smoothing,
    unit: f64,
    span: f64,
) -> Result<f64, Error> {
    match smoothing {
        Smoothing::Lambda(l) => {
            if eval.problem.floor > 0.0 && l / unit < eval.problem.floor {
                return Err(Error::InvalidArgument {
                    what: "lambda is too small for the points of weight 0 (or next to it): \
                           the fit between them would be left to rounding",
                    value: l,
                });
            }
            Ok(l)
        }
        Smoothing::Gcv => {
            let chosen = eval.search()? * unit;
            if !(chosen.is_finite() && chosen > 0.0 && unit.is_normal()) {
                return Err(Error::InvalidArgument {
                    what: "the chosen lambda is beyond the range of a double in the units of x \
                           (lambda scales as the span of x cubed): scale x; the span is",
                    value: span,
                });
            }
            Ok(chosen)
        }
    }
}

/// The control values, the fitted knot values and the residual sums of
/// squares of [`controls`].
type Solved = (Vec<f64>, Vec<f64>, Vec<f64>);

/// Solves every coordinate with the factored system: the control values
/// and the fitted knot values (both flat, in the data's units) and each
/// coordinate's weighted residual sum of squares.
/// Each solution must be the method's spline of its control values (its knot
/// values, solved again by the method, are the fitted ones): intervals of
/// widths many decades apart under a large lambda can defeat the
/// elimination, which is refused rather than returned.
fn controls<S: System>(
    f: &mut S,
    coords: &[(f64, Vec<f64>)],
    data: Data<'_>,
) -> Result<Solved, Error> {
    let (n, dim) = (data.weights.len(), coords.len());
    let weights = data.weights;
    let mut out = vec![0.0; n * dim];
    let mut fitted = vec![0.0; n * dim];
    let (mut phi, mut d, mut g) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut rss = vec![0.0; dim];
    for (c, (scale, y)) in coords.iter().enumerate() {
        f.solve(y, &mut phi, &mut d);
        for i in 0..n {
            g[i] = phi[i] - d[i];
            if !(g[i] * scale).is_finite() {
                return Err(Error::Overflow {
                    what: "a solved control value",
                });
            }
            out[i * dim + c] = g[i] * scale;
            fitted[i * dim + c] = phi[i] * scale;
            let r = (y[i] - phi[i]) * scale;
            rss[c] += weights[i] * r * r;
        }
        // A closed fit is checked where its curve is built.
        if !data.closed && !consistent(data.knots, &g, data.alphas, &phi) {
            return Err(ill_conditioned());
        }
    }
    Ok((out, fitted, rss))
}

/// `10^t` from additions and multiplications only, so that the search
/// chooses the same `lambda` on every platform (libm's `pow` is not
/// correctly rounded, and differs between them): `2^(t log2 10)` split into
/// a power of two and `2^f`, `f` in `[0, 1)`, by its Taylor series (within
/// 1e-13 of `10^t` relative, from the rounding of `t log2 10`; only its
/// determinism matters here).
fn exp10(t: f64) -> f64 {
    let y = t * std::f64::consts::LOG2_10;
    let k = y.floor();
    let z = (y - k) * std::f64::consts::LN_2;
    let mut term = 1.0;
    let mut sum = 1.0;
    for i in 1..=20 {
        term *= z / f64::from(i);
        sum += term;
    }
    let k = k.clamp(-1000.0, 1000.0) as i32;
    // 2^k in two steps, each a power of two in the normal range.
    let half = k / 2;
    sum * pow2(half) * pow2(k - half)
}

/// `2^k` for `|k| <= 1000`, exactly.
fn pow2(k: i32) -> f64 {
    f64::from_bits(((i64::from(k) + 1023) as u64) << 52)
}

/// `floor(log10 v)` for a positive finite `v`, by exact comparisons with
/// powers of ten formed by multiplication (the same on every platform).
fn decade(v: f64) -> i32 {
    let mut d = 0;
    let mut p = 1.0;
    if v >= 1.0 {
        while p * 10.0 <= v {
            p *= 10.0;
            d += 1;
        }
    } else {
        while p > v && d > -400 {
            p /= 10.0;
            d -= 1;
        }
    }
    d
}

fn ill_conditioned() -> Error {
    Error::InvalidArgument {
        what: "the smoothing system is too ill-conditioned for these knots and lambda \
               (intervals of widths many decades apart)",
        value: f64::NAN,
    }
}

/// Whether the knot values of the method's spline of the (scaled) control
/// values `g` are `phi`, to 1e-7 of their largest magnitude.
fn consistent(knots: &[f64], g: &[f64], alphas: &[f64], phi: &[f64]) -> bool {
    let Ok(s) = crate::Spline::with_alphas(knots, g, alphas) else {
        return false;
    };
    let big = phi.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
    s.knot_values()
        .iter()
        .zip(phi)
        .all(|(a, b)| (a - b).abs() <= 1e-7 * big)
}

/// `(rss / n) / (1 - dof / n)^2`; infinite when the fit interpolates
/// (`dof = n`: no residual degrees of freedom, the score is undefined).
fn gcv_score(rss: f64, dof: f64, n: f64) -> f64 {
    let den = 1.0 - dof / n;
    let s = (rss / n) / (den * den);
    if den > 0.0 && !s.is_nan() {
        s
    } else {
        f64::INFINITY
    }
}

/// `dim` coordinates' knot values of `n` knots each, to be filled.
fn fit_knots(phis: &mut Vec<Vec<f64>>, dim: usize, n: usize) {
    phis.resize_with(dim, Vec::new);
    phis.iter_mut().for_each(|phi| phi.resize(n, 0.0));
}

/// The GCV score, in the data's units, of a fit of `problem` with the knot
/// values `phis` and the trace `trace` (`None`: singular, and so infinite).
fn gcv_of(p: &Problem<'_>, trace: Option<f64>, phis: &[Vec<f64>]) -> f64 {
    let Some(trace) = trace else {
        return f64::INFINITY;
    };
    let mut rss = 0.0;
    for ((scale, y), phi) in p.coords.iter().zip(phis) {
        let s: f64 = (p.weights.iter().zip(y).zip(phi))
            .map(|((w, y), phi)| w * (y - phi).powi(2))
            .sum();
        rss += s * scale * scale;
    }
    let s = gcv_score(rss * p.mean_w / p.coords.len() as f64, trace, p.count);
    if s.is_finite() {
        s
    } else {
        f64::INFINITY
    }
}

/// The least number of points whose search for `lambda` is shared with a
/// second thread (with the `rayon` feature): a score of 10,000 points takes
/// about half a millisecond, far beyond what handing work to a thread costs.
#[cfg(feature = "rayon")]
const PARALLEL_MIN: usize = 10_000;

/// Evaluates the GCV score of one `lambda` (normalised units).
struct Evaluator<'a, S> {
    problem: &'a Problem<'a>,
    /// Makes another system: for a second evaluator on another thread.
    #[cfg_attr(not(feature = "rayon"), allow(dead_code))]
    make: &'a (dyn Fn() -> S + Sync),
    system: S,
    /// Each coordinate's knot values.
    phis: Vec<Vec<f64>>,
    /// Each coordinate's knot values of the second of two scores taken at
    /// once.
    phis2: Vec<Vec<f64>>,
    /// Scratch for the deviations.
    d: Vec<f64>,
}

impl<'a, S: System + Send> Evaluator<'a, S> {
    fn new(problem: &'a Problem<'a>, make: &'a (dyn Fn() -> S + Sync)) -> Self {
        Evaluator {
            problem,
            make,
            system: make(),
            phis: Vec::new(),
            phis2: Vec::new(),
            d: Vec::new(),
        }
    }

    /// A second evaluator of the same problem when the search is to be
    /// shared with another thread (the `rayon` feature, more than one thread
    /// and a large problem); `None` otherwise.
    fn twin(&self) -> Option<Self> {
        #[cfg(feature = "rayon")]
        if rayon::current_num_threads() > 1 && self.problem.weights.len() >= PARALLEL_MIN {
            return Some(Evaluator::new(self.problem, self.make));
        }
        None
    }

    /// `a` on this evaluator and `b` on the twin, side by side, or both here
    /// one after the other when there is none. Every score depends on its
    /// `lambda` alone, so the results are the same bits either way.
    fn pair<R: Send>(
        &mut self,
        twin: Option<&mut Self>,
        a: impl FnOnce(&mut Self) -> R + Send,
        b: impl FnOnce(&mut Self) -> R + Send,
    ) -> (R, R) {
        #[cfg(feature = "rayon")]
        if let Some(twin) = twin {
            return rayon::join(|| a(self), || b(twin));
        }
        #[cfg(not(feature = "rayon"))]
        let _ = twin;
        (a(self), b(self))
    }

    /// The score at `exp10(t)`, in the data's units; infinite where the
    /// system cannot be solved.
    fn score(&mut self, t: f64) -> f64 {
        let p = self.problem;
        let lambda = exp10(t);
        if lambda < p.floor {
            return f64::INFINITY;
        }
        let ys: Vec<&[f64]> = p.coords.iter().map(|(_, y)| y.as_slice()).collect();
        fit_knots(&mut self.phis, ys.len(), p.weights.len());
        let trace = self
            .system
            .evaluate(lambda, &ys, &mut self.phis, &mut self.d);
        gcv_of(p, trace, &self.phis)
    }

    /// The scores of `ts[0]` and `ts[1]`, taken at once where the system
    /// can ([`System::evaluate_two`]): the bits of [`Evaluator::score`] of
    /// each.
    fn score_two(&mut self, ts: [f64; 2]) -> [f64; 2] {
        let p = self.problem;
        let lambdas = ts.map(exp10);
        if lambdas.iter().any(|&l| l < p.floor) {
            return ts.map(|t| self.score(t));
        }
        let ys: Vec<&[f64]> = p.coords.iter().map(|(_, y)| y.as_slice()).collect();
        fit_knots(&mut self.phis, ys.len(), p.weights.len());
        fit_knots(&mut self.phis2, ys.len(), p.weights.len());
        let [ta, tb] =
            self.system
                .evaluate_two(lambdas, &ys, [&mut self.phis, &mut self.phis2], &mut self.d);
        [gcv_of(p, ta, &self.phis), gcv_of(p, tb, &self.phis2)]
    }

    /// The `lambda` (normalised) of least GCV score: a scan of
    /// `log10 lambda` a decade apart over the whole range from interpolation
    /// to the straight line, then Brent's search between the neighbours of
    /// each of the scan's two lowest local minima.
    fn search(&mut self) -> Result<f64, Error> {
        let n = self.problem.weights.len() as f64;
        // With the span 1 and weights of mean 1, the equivalent kernel of
        // weight lambda spans about (lambda h)^(1/4) where the knots are h
        // apart: from the narrowest interval (lambda = h_min^3) to the whole
        // span (lambda = n); a decade past each.
        let h_min = self.problem.widths.iter().fold(1.0f64, |m, &h| m.min(h));
        let lo = f64::from(3 * decade(h_min) - 1);
        let hi = f64::from(decade(n) + 3);
        let mut twin = self.twin();
        let ts: Vec<f64> = (0..=(hi - lo) as usize).map(|i| lo + i as f64).collect();
        // Half on each thread, or all two at a time on one (halves of odd
        // length would leave a score alone in each).
        let mut scan = if twin.is_some() {
            let (first, second) = ts.split_at(ts.len() / 2);
            let (mut scan, rest) =
                self.pair(twin.as_mut(), |e| e.scores(first), |e| e.scores(second));
            scan.extend(rest);
            scan
        } else {
            self.scores(&ts)
        };
        // Where the score still falls towards interpolation, follow it down
        // (it levels off there; a dozen decades is far past that).
        for _ in 0..12 {
            let (t, s) = scan[0];
            if scan.len() < 2 || s >= scan[1].1 {
                break;
            }
            scan.insert(0, (t - 1.0, self.score(t - 1.0)));
        }
        let mut minima: Vec<(f64, f64)> = (0..scan.len())
            .filter(|&i| {
                let s = scan[i].1;
                s.is_finite()
                    && (i == 0 || s <= scan[i - 1].1)
                    && (i + 1 == scan.len() || s <= scan[i + 1].1)
            })
            .map(|i| scan[i])
            .collect();
        if minima.is_empty() {
            return Err(Error::InvalidArgument {
                what: "the smoothing system is singular for these weights",
                value: f64::NAN,
            });
        }
        minima.sort_by(|a, b| a.1.total_cmp(&b.1));
        let mut best = minima[0];
        let found = match minima[..] {
            [m0, m1, ..] => {
                // Side by side on two threads, or scored two at a time on one.
                let (f0, f1) = match twin.as_mut() {
                    Some(twin) => self.pair(Some(twin), |e| e.around(m0), |e| e.around(m1)),
                    None => self.around_two(m0, m1),
                };
                vec![f0, f1]
            }
            _ => vec![self.around(minima[0])],
        };
        for f in found {
            if f.1 < best.1 {
                best = f;
            }
        }
        Ok(exp10(best.0))
    }

    /// The scores of `ts` (in `log10 lambda`), each beside its `t`, two at
    /// a time.
    fn scores(&mut self, ts: &[f64]) -> Vec<(f64, f64)> {
        let mut out = Vec::with_capacity(ts.len());
        for two in ts.chunks(2) {
            match *two {
                [a, b] => {
                    let [fa, fb] = self.score_two([a, b]);
                    out.extend([(a, fa), (b, fb)]);
                }
                _ => out.extend(two.iter().map(|&t| (t, self.score(t)))),
            }
        }
        out
    }

    /// Brent's search within a decade either side of the scan's point `t`
    /// of score `s`.
    fn around(&mut self, (t, s): (f64, f64)) -> (f64, f64) {
        let mut brent = Brent::new(t - 1.0, t, s, t + 1.0);
        while let Some(u) = brent.next() {
            brent.take(self.score(u));
        }
        brent.best()
    }

    /// [`Evaluator::around`] of `m0` and of `m1`, side by side: while both
    /// searches go on, their next points are scored together.
    fn around_two(&mut self, m0: (f64, f64), m1: (f64, f64)) -> ((f64, f64), (f64, f64)) {
        let mut a = Brent::new(m0.0 - 1.0, m0.0, m0.1, m0.0 + 1.0);
        let mut b = Brent::new(m1.0 - 1.0, m1.0, m1.1, m1.0 + 1.0);
        loop {
            match (a.next(), b.next()) {
                (Some(u), Some(v)) => {
                    let [fu, fv] = self.score_two([u, v]);
                    a.take(fu);
                    b.take(fv);
                }
                (Some(u), None) => a.take(self.score(u)),
                (None, Some(v)) => b.take(self.score(v)),
                (None, None) => return (a.best(), b.best()),
            }
        }
    }
}

/// Brent's minimisation of the score on `[a, b]` (in `log10 lambda`) from
/// the point `x` of score `fx`, to a thousandth of a decade, a step at a
/// time: [`Brent::next`] names the point to score, [`Brent::take`] takes its
/// score, so that two searches can go side by side.
struct Brent {
    a: f64,
    b: f64,
    x: f64,
    w: f64,
    v: f64,
    fx: f64,
    fw: f64,
    fv: f64,
    d: f64,
    e: f64,
    /// The point named last.
    u: f64,
    steps: usize,
}

impl Brent {
    const GOLD: f64 = 0.381_966_011_250_105_1;
    const TOL: f64 = 1e-3;

    fn new(a: f64, x: f64, fx: f64, b: f64) -> Brent {
        Brent {
            a,
            b,
            x,
            w: x,
            v: x,
            fx,
            fw: fx,
            fv: fx,
            d: 0.0,
            e: 0.0,
            u: x,
            steps: 0,
        }
    }

    /// The next point to score, or `None` when the search is done (at most
    /// 60 steps).
    fn next(&mut self) -> Option<f64> {
        const TOL: f64 = Brent::TOL;
        let (a, b, x) = (self.a, self.b, self.x);
        let m = 0.5 * (a + b);
        if self.steps >= 60 || (x - m).abs() <= 2.0 * TOL - 0.5 * (b - a) {
            return None;
        }
        let mut golden = true;
        if self.e.abs() > TOL {
            // A parabola through x, w, v.
            let (w, v, fx, fw, fv) = (self.w, self.v, self.fx, self.fw, self.fv);
            let r = (x - w) * (fx - fv);
            let q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            let mut q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * self.e).abs() && p > q * (a - x) && p < q * (b - x) {
                self.e = self.d;
                self.d = p / q;
                let u = x + self.d;
                if u - a < 2.0 * TOL || b - u < 2.0 * TOL {
                    self.d = if x < m { TOL } else { -TOL };
                }
                golden = false;
            }
        }
        if golden {
            self.e = if x < m { b - x } else { a - x };
            self.d = Brent::GOLD * self.e;
        }
        self.u = if self.d.abs() >= TOL {
            x + self.d
        } else {
            x + TOL.copysign(self.d)
        };
        Some(self.u)
    }

    /// Takes the score `fu` of the point [`Brent::next`] named.
    fn take(&mut self, fu: f64) {
        let (u, x) = (self.u, self.x);
        self.steps += 1;
        if fu <= self.fx {
            if u < x {
                self.b = x;
            } else {
                self.a = x;
            }
            (self.v, self.w, self.x) = (self.w, x, u);
            (self.fv, self.fw, self.fx) = (self.fw, self.fx, fu);
        } else {
            if u < x {
                self.a = u;
            } else {
                self.b = u;
            }
            if fu <= self.fw || self.w == x {
                (self.v, self.w) = (self.w, u);
                (self.fv, self.fw) = (self.fw, fu);
            } else if fu <= self.fv || self.v == x || self.v == self.w {
                self.v = u;
                self.fv = fu;
            }
        }
    }

    /// The least point found and its score.
    fn best(&self) -> (f64, f64) {
        (self.x, self.fx)
    }
}

impl crate::Spline {
    /// The smoothing spline of the data `(x[j], y[j])` in the method's basis
    /// (`docs/method.md` §12): knots at `x`, control values chosen to minimise
    /// `sum_j w_j (S(x_j) - y_j)^2 + lambda int S''(x)^2 dx` over the method's
    /// splines with these `alphas`, `lambda` given or chosen by generalized
    /// cross-validation. The arguments follow
    /// `scipy.interpolate.make_smoothing_spline(x, y, w, lam)`; the weights are
    /// not squared, and a point of weight 0 does not affect the fit (its knot
    /// stays). O(N) time and memory for every `lambda` tried; with the `rayon`
    /// feature and from 10,000 points the search for `lambda` runs on two
    /// threads of the current pool, with the same result as on one.
    ///
    /// The result is the method's spline of its control values
    /// ([`Spline::values`](crate::Spline::values)): C1, touching every leg of
    /// that control polygon, inside its hull. `lambda = 0` passes through the
    /// data ([`Spline::through`](crate::Spline::through)); as `lambda` grows
    /// it tends to the weighted least-squares line.
    ///
    /// # Errors
    ///
    /// - [`Error::TooFewPoints`] for fewer than 3 points;
    /// - the knot, value and alpha errors of
    ///   [`Spline::with_alphas`](crate::Spline::with_alphas) (`x` must be
    ///   strictly increasing);
    /// - [`Error::LengthMismatch`], [`Error::NonFinite`] (field
    ///   [`Field::Weight`]) or [`Error::NegativeWeight`] for bad weights, and
    ///   [`Error::InvalidArgument`] when fewer than 2 are positive;
    /// - [`Error::InvalidArgument`] for a negative or non-finite `lambda`,
    ///   `lambda = 0` with a weight 0, a `lambda` so far below the scale that
    ///   interpolates (`1e-12` of the narrowest interval's width cubed, in
    ///   units where `x` spans 1) that the fit beside a point of weight 0
    ///   would be left to rounding, a chosen `lambda` that a double cannot
    ///   hold in the units of `x`, and a system too ill-conditioned to solve
    ///   (intervals of widths many decades apart under a large `lambda`: the
    ///   fit is checked to be the method's spline of its control values);
    /// - [`Error::Overflow`] when a solved control value leaves the range of
    ///   a double.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Alphas, Smoothing, Spline};
    /// let x: Vec<f64> = (0..50).map(|i| i as f64 / 49.0).collect();
    /// // A line with a wobble: smoothing hard leaves the line.
    /// let y: Vec<f64> = x.iter().enumerate()
    ///     .map(|(i, &x)| 1.0 + 2.0 * x + if i % 2 == 0 { 0.1 } else { -0.1 })
    ///     .collect();
    /// let s = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Lambda(1e6))?;
    /// assert!((s.fit.eval(0.5)? - 2.0).abs() < 1e-3);
    /// // Chosen by cross-validation, with the score and degrees of freedom.
    /// let g = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv)?;
    /// assert!(g.lambda > 0.0 && g.dof >= 2.0 && g.dof <= 50.0);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn smoothing(
        x: &[f64],
        y: &[f64],
        weights: Option<&[f64]>,
        alphas: crate::Alphas<'_>,
        smoothing: Smoothing,
    ) -> Result<Smoothed<crate::Spline>, Error> {
        smoothing_spline(x, y, weights, alphas, smoothing, false)
    }

    /// [`Spline::smoothing`](crate::Spline::smoothing) made robust against outliers (`docs/method.md`
    /// §14): the fit is weighted again by its residuals with Tukey's
    /// biweight, `(1 - u^2)^2` for `u = |r| / (6 m)` below 1 and 0 beyond,
    /// `m` the median absolute residual (residuals standardised by the given
    /// weights), as lowess does; `lambda` is chosen again (under
    /// [`Smoothing::Gcv`]) at every step, until no weight moves by more than
    /// 1e-3 (at most 20 steps). The weights it ends with are
    /// [`Smoothed::robustness`].
    ///
    /// # Errors
    ///
    /// As [`Spline::smoothing`](crate::Spline::smoothing), and [`Error::TooFewPoints`] for fewer than
    /// [`ROBUST_MIN_POINTS`] points of positive weight.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Alphas, Smoothing, Spline};
    /// let x: Vec<f64> = (0..100).map(|i| i as f64 / 99.0).collect();
    /// let mut y: Vec<f64> = x.iter().map(|&t| (4.0 * t).sin()).collect();
    /// y[40] += 5.0; // one gross outlier
    /// let s = Spline::smoothing_robust(&x, &y, None, Alphas::default(), Smoothing::Gcv)?;
    /// assert_eq!(s.robustness.as_ref().unwrap()[40], 0.0);
    /// assert!((s.fit.eval(x[40])? - (4.0 * x[40]).sin()).abs() < 0.01);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn smoothing_robust(
        x: &[f64],
        y: &[f64],
        weights: Option<&[f64]>,
        alphas: crate::Alphas<'_>,
        smoothing: Smoothing,
    ) -> Result<Smoothed<crate::Spline>, Error> {
        smoothing_spline(x, y, weights, alphas, smoothing, true)
    }
}

/// [`Spline::smoothing`], robust or not.
fn smoothing_spline(
    x: &[f64],
    y: &[f64],
    weights: Option<&[f64]>,
    alphas: crate::Alphas<'_>,
    smoothing: Smoothing,
    robust: bool,
) -> Result<Smoothed<crate::Spline>, Error> {
    let n = x.len();
    if n < 3 {
        return Err(Error::TooFewPoints { found: n, min: 3 });
    }
    crate::validate::check_knots(x)?;
    if y.len() != n {
        return Err(Error::LengthMismatch {
            field: Field::Value,
            expected: n,
            found: y.len(),
        });
    }
    crate::validate::check_finite(Field::Value, y)?;
    let resolved = crate::validate::resolve_alphas(alphas, n - 1)?;
    let w = check_weights(weights, n)?;
    let data = Data {
        knots: x,
        values: y,
        dim: 1,
        weights: &w,
        alphas: &resolved,
        closed: false,
    };
    let (fit, robustness) = if robust {
        let (f, r) = fit_robust(data, smoothing)?;
        (f, Some(r))
    } else {
        (fit(data, smoothing)?, None)
    };
    Ok(Smoothed {
        fit: crate::Spline::build(x, &fit.controls, alphas)?,
        lambda: fit.lambda,
        gcv: fit.gcv,
        dof: fit.dof,
        posterior: fit.posterior,
        robustness,
    })
}

#[cfg(test)]
mod tests {
    use super::{decade, exp10};
    #[cfg(feature = "rayon")]
    use crate::testing::{on_threads, rng};
    #[cfg(feature = "rayon")]
    use crate::{Alphas, Smoothing, Spline};

    /// The search for lambda shared with a second thread gives the bits of
    /// the search on one: lambda, the degrees of freedom and every control
    /// value, on even and uneven grids, with weights and without.
    #[cfg(feature = "rayon")]
    #[test]
    fn every_thread_count_gives_the_same_fit() {
        let n = 2 * super::PARALLEL_MIN + 1;
        for seed in 0..3u64 {
            let mut next = rng(seed);
            let mut x = vec![0.0];
            for _ in 1..n {
                let step = if seed == 1 {
                    10f64.powf(4.0 * next() - 2.0)
                } else {
                    1.0
                };
                x.push(x[x.len() - 1] + step);
            }
            let y: Vec<f64> = x
                .iter()
                .map(|t| (t / x[n - 1] * 30.0).sin() + next() - 0.5)
                .collect();
            let w: Option<Vec<f64>> = (seed == 2).then(|| (0..n).map(|_| next()).collect());
            let runs: Vec<Vec<u64>> = [1, 2, 16]
                .into_iter()
                .map(|threads| {
                    let s = on_threads(threads, || {
                        Spline::smoothing(&x, &y, w.as_deref(), Alphas::default(), Smoothing::Gcv)
                    })
                    .expect("a fit");
                    [s.lambda, s.dof]
                        .into_iter()
                        .chain(s.fit.values().iter().copied())
                        .map(f64::to_bits)
                        .collect()
                })
                .collect();
            assert_eq!(runs[0].len(), n + 2);
            assert!(
                runs[1] == runs[0],
                "seed {seed}: two threads differ from one"
            );
            assert!(
                runs[2] == runs[0],
                "seed {seed}: sixteen threads differ from one"
            );
        }
    }

    #[test]
    fn exp10_and_decade_agree_with_libm() {
        for i in -3000..=3000 {
            let t = f64::from(i) / 100.0;
            let (a, b) = (exp10(t), 10f64.powf(t));
            assert!((a / b - 1.0).abs() < 1e-13, "{t}: {a} against {b}");
        }
        // Below 1, away from exact powers of ten (where the divided powers round).
        for v in [3e-17, 2e-5, 0.5, 1.0, 9.99, 10.0, 123.0, 1e6, 3.5e9] {
            assert_eq!(decade(v), v.log10().floor() as i32, "{v}");
        }
    }
}
