//! `bzspline.Spline`: the method's spline y = S(x) for numpy arrays, in
//! scipy's conventions (calling, `derivative`, `antiderivative`,
//! `integrate`, pickling).

use bzspline::{AlphaChoice, Extrapolate, ParamCurve};
use std::sync::Arc;

use numpy::ndarray::IxDyn;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyTuple};

use crate::args::*;

/// The third-degree Bezier-type spline y = S(x) of Stelia, Potapenko and
/// Sirenko.
///
/// A C1 piecewise cubic through the first and last points that touches every
/// leg of the control polygon (x, y) and stays within the range of y; every
/// piece is one cubic Bezier segment. Built from one diagonally dominant
/// tridiagonal system, O(n).
///
/// Parameters
/// ----------
/// x : array_like, shape (n,)
///     Strictly increasing, finite knots; n >= 2.
/// y : array_like, shape (n,)
///     The control values (with ``through=True``, the values to pass through).
/// alpha : float or array_like, shape (n - 1,), default 0.5
///     The shape parameter in [1/3, 2/3], one for all intervals or one each:
///     where on its leg the curve touches the control polygon.
/// through : bool, default False
///     Pass through every (x, y) instead (the interpolating variant: the control
///     values are solved for).
/// extrapolate : {True, False, 'clamp', 'extend', 'nan', 'error'}, default True
///     Outside [x[0], x[-1]]: extend the end cubics, give NaN (as scipy), or
///     hold the end values; by name, also raise ``ValueError`` (``'error'``).
///
/// Attributes
/// ----------
/// x, knot_values, alphas, control_values, tangent_points, segments, nu,
/// extrapolate
///
/// Raises
/// ------
/// ValueError
///     For knots that are not increasing or not finite, mismatched lengths, an
///     alpha outside [1/3, 2/3], naming the index at fault.
///
/// Notes
/// -----
/// Immutable: safe to share between threads; pickles. The GIL is released while
/// it is built and evaluated.
///
/// Examples
/// --------
/// >>> s = Spline([1, 2, 3, 4], [1, 3, 3, 1])
/// >>> float(s(2.5))
/// 3.0
#[pyclass(frozen, module = "bzspline._core")]
pub(crate) struct Spline {
    inner: Arc<bzspline::Spline>,
    /// For `through`, the y it passes through (its control values are
    /// solved); empty otherwise, where the control values are the data.
    y: Vec<f64>,
    through: bool,
    /// Outside the knots (`Nan` for scipy's `extrapolate=False`); the
    /// spline evaluates by it too.
    outside: Extrapolate,
    /// The derivative order this object evaluates: from `derivative`, or -1
    /// for the antiderivative.
    nu: i32,
    /// The antiderivative, when `nu` is -1.
    anti: Option<Arc<bzspline::Antiderivative>>,
    /// Subtracted from the values of order `nu` (from `antiderivative` of a
    /// derivative: scipy's constant, which makes them 0 at the first knot).
    offset: f64,
    /// For a smoothing fit: its `lambda`, GCV score and degrees of freedom.
    smoothing: Option<[f64; 3]>,
    /// For a smoothing fit: what its standard errors need.
    posterior: Option<Arc<bzspline::Posterior>>,
    /// For a robust smoothing fit: the weight each point ended with.
    robustness: Option<Arc<Vec<f64>>>,
}

/// A posterior as a pickle holds it: knots, alphas, covariances, noise.
type PosteriorTuple = (Vec<f64>, Vec<f64>, Vec<[f64; 7]>, Option<Vec<f64>>);

/// A band's lower and upper edges.
type Edges<'py> = (Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArrayDyn<f64>>);

/// The standard error at every x, naming the index of one outside the
/// knots.
fn standard_errors(p: &bzspline::Posterior, xs: &[f64]) -> PyResult<Vec<f64>> {
    let s2 = p.noise_variance().map_err(value_error)?[0];
    xs.iter()
        .enumerate()
        .map(|(i, &x)| {
            p.unit_variance(x)
                .map(|v| (s2 * v).sqrt())
                .map_err(|e| PyValueError::new_err(format!("x[{i}]: {e}")))
        })
        .collect()
}

impl Spline {
    /// The posterior of a smoothing fit evaluated as itself (not a
    /// derivative or antiderivative of one).
    fn posterior_of_values(&self) -> PyResult<&bzspline::Posterior> {
        match (&self.posterior, self.nu) {
            (Some(p), 0) => Ok(p),
            (Some(_), _) => Err(PyValueError::new_err(
                "se and band are of the smoothing fit's values, not of its derivatives",
            )),
            (None, _) => Err(PyValueError::new_err(
                "se and band are for a spline from bzspline.smoothing_spline",
            )),
        }
    }

    /// The same spline evaluating order `nu` (with its antiderivative when
    /// `nu` is -1), less `offset`.
    fn of_order(
        &self,
        nu: i32,
        anti: Option<Arc<bzspline::Antiderivative>>,
        offset: f64,
    ) -> Spline {
        Spline {
            inner: Arc::clone(&self.inner),
            y: self.y.clone(),
            through: self.through,
            outside: self.outside,
            nu,
            anti,
            offset,
            smoothing: self.smoothing,
            posterior: self.posterior.clone(),
            robustness: self.robustness.clone(),
        }
    }

    /// S(x) or its derivative of order `nu` (beyond the object's own) at
    /// every x, into `out` (as long as `x`).
    fn eval_into(&self, x: &[f64], nu: u32, out: &mut [f64]) -> PyResult<()> {
        self.eval_order(x, self.nu + nu as i32, out)?;
        if nu == 0 && self.offset != 0.0 {
            out.iter_mut().for_each(|o| *o -= self.offset);
        }
        Ok(())
    }

    /// Values of the derivative of order `order` (-1: the antiderivative).
    fn eval_order(&self, x: &[f64], order: i32, out: &mut [f64]) -> PyResult<()> {
        let s = &self.inner;
        let (a, b) = s.domain();
        let Ok(order) = u32::try_from(order) else {
            let anti = self
                .anti
                .as_ref()
                .ok_or_else(|| PyRuntimeError::new_err("the antiderivative is missing"))?;
            for (o, &v) in out.iter_mut().zip(x) {
                *o = if v.is_nan() || (self.outside == Extrapolate::Nan && !(a..=b).contains(&v)) {
                    f64::NAN
                } else {
                    anti.eval(v).map_err(value_error)?
                };
            }
            return Ok(());
        };
        if order > 3 {
            for (o, &v) in out.iter_mut().zip(x) {
                *o = if v.is_nan() || (self.outside == Extrapolate::Nan && !(a..=b).contains(&v)) {
                    f64::NAN
                } else {
                    0.0
                };
            }
            return Ok(());
        }
        // NaN queries give NaN, like scipy; the library refuses them, and
        // then they are taken one by one.
        if s.deriv_many(x, order, out).is_err() {
            for (o, &v) in out.iter_mut().zip(x) {
                *o = if v.is_nan() {
                    f64::NAN
                } else {
                    s.deriv(v, order).map_err(value_error)?
                };
            }
        }
        if self.outside == Extrapolate::Nan {
            for (o, &v) in out.iter_mut().zip(x) {
                if !(a..=b).contains(&v) {
                    *o = f64::NAN;
                }
            }
        }
        Ok(())
    }
}

impl Drop for Spline {
    fn drop(&mut self) {
        crate::spare::keep(&mut self.inner);
    }
}

fn build_spline(
    x: &[f64],
    y: &[f64],
    alpha: &AlphaChoice,
    through: bool,
    outside: Extrapolate,
    py: Python<'_>,
) -> PyResult<bzspline::Spline> {
    let built = py.allow_threads(|| {
        crate::threads::install(|| {
            if through {
                bzspline::Spline::through(x, y, alpha.as_alphas())
            } else {
                crate::spare::build(x, y, alpha.as_alphas())
            }
        })
    });
    Ok(built.map_err(value_error)?.with_extrapolation(outside))
}

#[pymethods]
impl Spline {
    #[new]
    #[pyo3(signature = (x, y, alpha=None, through=false, extrapolate=None))]
    #[pyo3(text_signature = "(x, y, alpha=0.5, through=False, extrapolate=True)")]
    fn new(
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
        alpha: Option<&Bound<'_, PyAny>>,
        through: bool,
        extrapolate: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        guard(|| {
            // Contiguous float64 arrays are read where they lie (no copy).
            let (xa, ya) = (as_float_array(x, "x")?, as_float_array(y, "y")?);
            let (xv, yv) = (xa.as_array(), ya.as_array());
            if xv.ndim() != 1 || yv.ndim() != 1 {
                return Err(PyValueError::new_err("x and y must be 1-D arrays"));
            }
            let (xc, yc);
            let x = match xv.as_slice() {
                Some(s) => s,
                None => {
                    xc = xv.iter().copied().collect::<Vec<f64>>();
                    &xc
                }
            };
            let y = match yv.as_slice() {
                Some(s) => s,
                None => {
                    yc = yv.iter().copied().collect::<Vec<f64>>();
                    &yc
                }
            };
            let alpha = alpha_arg(alpha)?;
            let outside = extrapolate_arg(extrapolate)?;
            let inner = build_spline(x, y, &alpha, through, outside, py)?;
            Ok(Spline {
                inner: Arc::new(inner),
                y: if through { y.to_vec() } else { Vec::new() },
                through,
                outside,
                nu: 0,
                anti: None,
                offset: 0.0,
                smoothing: None,
                posterior: None,
                robustness: None,
            })
        })
    }

    /// S(x), or its derivative of order `nu`, at every x.
    ///
    /// Parameters
    /// ----------
    /// x : array_like
    ///     Any shape; float64 contiguous input is read in place.
    /// nu : int, default 0
    ///     The derivative order (at least 0); orders above 3 are 0.
    /// out : numpy.ndarray, optional
    ///     A writable, contiguous float64 array of x's shape: the results go there
    ///     and `out` is returned, no new array.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Of x's shape (a 0-d input gives a 0-d array). NaN for NaN queries, and
    ///     outside the knots when ``extrapolate=False``.
    #[pyo3(signature = (x, nu=0, out=None))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        nu: i64,
        out: Option<Bound<'py, PyArrayDyn<f64>>>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        guard(|| {
            let nu = u32::try_from(nu)
                .map_err(|_| PyValueError::new_err(format!("nu = {nu} must be at least 0")))?;
            // A contiguous float64 array is read where it lies (no copy).
            let arr = as_float_array(x, "x")?;
            let view = arr.as_array();
            let shape = view.shape().to_vec();
            if let Some(o) = out {
                {
                    let mut w = o.try_readwrite().map_err(|e| {
                        PyValueError::new_err(format!("out must be writable and not x: {e}"))
                    })?;
                    if w.shape() != shape.as_slice() {
                        return Err(PyValueError::new_err(format!(
                            "out has shape {:?}, x has {shape:?}",
                            w.shape()
                        )));
                    }
                    let dst = w
                        .as_slice_mut()
                        .map_err(|_| PyValueError::new_err("out must be C-contiguous"))?;
                    match view.as_slice() {
                        Some(xs) => py.allow_threads(|| self.eval_into(xs, nu, dst))?,
                        None => {
                            let xs: Vec<f64> = view.iter().copied().collect();
                            py.allow_threads(|| self.eval_into(&xs, nu, dst))?
                        }
                    }
                }
                return Ok(o);
            }
            // numpy allocates the result: it asks for huge pages for large
            // arrays, which makes first writing them several times cheaper.
            let fresh = PyArrayDyn::<f64>::zeros(py, IxDyn(&shape), false);
            {
                let mut w = fresh.readwrite();
                let dst = w
                    .as_slice_mut()
                    .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
                match view.as_slice() {
                    Some(xs) => py.allow_threads(|| self.eval_into(xs, nu, dst))?,
                    None => {
                        let xs: Vec<f64> = view.iter().copied().collect();
                        py.allow_threads(|| self.eval_into(&xs, nu, dst))?
                    }
                }
            }
            Ok(fresh)
        })
    }

    /// The derivative of order `nu` as a new object (evaluated by the same
    /// pieces).
    ///
    /// Parameters
    /// ----------
    /// nu : int, default 1
    ///     The order, at least 0. Orders above 3 are 0 everywhere.
    ///
    /// Returns
    /// -------
    /// Spline
    ///     Calling it gives the derivative; of an antiderivative, `derivative()`
    ///     is the spline again.
    #[pyo3(signature = (nu=1))]
    fn derivative(&self, nu: i64) -> PyResult<Self> {
        let nu = u32::try_from(nu)
            .map_err(|_| PyValueError::new_err(format!("nu = {nu} must be at least 0")))?;
        let order = self
            .nu
            .saturating_add(i32::try_from(nu).unwrap_or(i32::MAX));
        let anti = if order < 0 { self.anti.clone() } else { None };
        Ok(self.of_order(order, anti, if nu == 0 { self.offset } else { 0.0 }))
    }

    /// The antiderivative as a new object: `F(x)`, the integral of S from
    /// the first knot to x, a quartic on every interval (as scipy, `F` is 0 at
    /// the first knot; outside the knots it integrates what `extrapolate`
    /// gives). Of a derivative of order k, the derivative of order k - 1 less
    /// its value at the first knot.
    ///
    /// Parameters
    /// ----------
    /// nu : int, default 1
    ///     The order; only 1 (one integration) is offered. For more, use
    ///     `to_ppoly().antiderivative(nu)`.
    ///
    /// Returns
    /// -------
    /// Spline
    ///     Calling it gives F; `derivative()` of it is the spline again.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     For `nu` other than 1, or the antiderivative of an antiderivative.
    #[pyo3(signature = (nu=1))]
    fn antiderivative(&self, py: Python<'_>, nu: i64) -> PyResult<Self> {
        if nu != 1 || self.nu < 0 {
            return Err(PyValueError::new_err(format!(
                "antiderivative(nu={nu}) of order {}: one integration of the spline or a derivative is offered; to_ppoly().antiderivative(nu) gives more",
                self.nu
            )));
        }
        let order = self.nu - 1;
        let (anti, offset) = if order < 0 {
            let inner = Arc::clone(&self.inner);
            let a = py.allow_threads(move || guard(|| Ok(inner.antiderivative())))?;
            (Some(Arc::new(a)), 0.0)
        } else {
            let x0 = self.inner.domain().0;
            let v = self.inner.deriv(x0, order as u32).map_err(value_error)?;
            (None, v)
        };
        Ok(self.of_order(order, anti, offset))
    }

    /// The integral of S from a to b.
    ///
    /// Parameters
    /// ----------
    /// a, b : float
    ///     The bounds; b < a gives the negative.
    ///
    /// Returns
    /// -------
    /// float
    ///     Exact up to rounding; NaN when a bound is outside the knots and
    ///     ``extrapolate=False``.
    fn integrate(&self, a: f64, b: f64) -> PyResult<f64> {
        if self.nu != 0 {
            return Err(PyValueError::new_err(
                "integrate applies to the spline, not to a derivative or antiderivative",
            ));
        }
        let (lo, hi) = self.inner.domain();
        if self.outside == Extrapolate::Nan && (a < lo || b > hi || b < lo || a > hi) {
            return Ok(f64::NAN);
        }
        let v = self.inner.integral(a, b).map_err(value_error)?;
        Ok(v - self.offset * (b - a))
    }

    /// The points inside the domain where S' = 0.
    ///
    /// Returns
    /// -------
    /// list of (float, float, str)
    ///     ``(x, y, kind)`` in increasing x, kind 'minimum', 'maximum' or
    ///     'stationary'.
    fn extrema(&self) -> Vec<(f64, f64, &'static str)> {
        self.inner
            .extrema()
            .into_iter()
            .map(|e| {
                let kind = match e.kind {
                    bzspline::ExtremumKind::Minimum => "minimum",
                    bzspline::ExtremumKind::Maximum => "maximum",
                    _ => "stationary",
                };
                (e.x, e.y, kind)
            })
            .collect()
    }

    /// The knots.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.knots())
    }

    /// The knot values S(x_k).
    #[getter]
    fn knot_values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.knot_values().into_pyarray(py)
    }

    /// The shape parameters, one per interval.
    #[getter]
    fn alphas<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.alphas())
    }

    /// The control values F_k (for `through=True`, the solved ones).
    #[getter]
    fn control_values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.values())
    }

    /// The points where S touches each leg of the control polygon, `(n-1, 2)`.
    #[getter]
    fn tangent_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self
            .inner
            .tangent_points()
            .into_iter()
            .map(|(x, y)| vec![x, y])
            .collect();
        PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Every piece as the four control points of a cubic Bezier segment,
    /// `(n-1, 4, 2)`.
    #[getter]
    fn segments<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let segs: Vec<Vec<Vec<f64>>> = self
            .inner
            .segments()
            .into_iter()
            .map(|b| b.p.iter().map(|p| p.to_vec()).collect())
            .collect();
        PyArray3::from_vec3(py, &segs).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The power-basis coefficients of every piece.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (n - 1, 4)
    ///     Row k: piece k in powers of ``x - x[k]``, lowest order first (scipy's
    ///     ``PPoly`` wants them highest first, transposed: see ``to_ppoly``).
    fn power_coefficients<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = (0..self.inner.len())
            .filter_map(|k| self.inner.power_coefficients(k).map(|c| c.to_vec()))
            .collect();
        PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The graph as SVG path data, exactly: one ``C`` command per piece.
    ///
    /// Returns
    /// -------
    /// str
    ///     ``M x0 y0 C ...``, each number the shortest that reads back the same.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     When a control point overflows a double.
    fn svg_path(&self) -> PyResult<String> {
        let mut s = String::new();
        match bzspline::write_svg_path(&*self.inner, false, &mut s) {
            Ok(true) => Ok(s),
            _ => Err(PyValueError::new_err(
                "a control point of the path overflows a double",
            )),
        }
    }

    /// `extrapolate`: True (extend), False (NaN) or the policy's name.
    #[getter]
    fn extrapolate(&self, py: Python<'_>) -> PyObject {
        match self.outside {
            Extrapolate::Extend => true
                .into_pyobject(py)
                .map(|b| b.to_owned().into_any().unbind()),
            Extrapolate::Nan => false
                .into_pyobject(py)
                .map(|b| b.to_owned().into_any().unbind()),
            other => other
                .name()
                .into_pyobject(py)
                .map(|s| s.into_any().unbind()),
        }
        .unwrap_or_else(|_| py.None())
    }

    /// The derivative order this object evaluates: 0 for the spline, -1 for
    /// its antiderivative.
    #[getter]
    fn nu(&self) -> i32 {
        self.nu
    }

    /// The constant subtracted from the values (the antiderivative of a
    /// derivative: its value at the first knot); 0 otherwise.
    #[getter]
    fn _offset(&self) -> f64 {
        self.offset
    }

    /// The standard error of a smoothing fit at ``x``: the square root of
    /// the Bayesian posterior variance of the penalised fit (Wahba's, as R's
    /// mgcv gives with ``predict(..., se.fit=TRUE)``), with the noise
    /// variance estimated as the weighted residual sum of squares over
    /// ``n - dof``. O(N) once with the fit, then O(log N) a point.
    ///
    /// Parameters
    /// ----------
    /// x : array_like
    ///     Points within the knots.
    ///
    /// Returns
    /// -------
    /// ndarray
    ///     The standard errors, of the shape of ``x``.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     For a spline that is not from :func:`bzspline.smoothing_spline`
    ///     (or is a derivative of one), a fit through every point
    ///     (``lam=0``), or an ``x`` outside the knots (its index named).
    ///
    /// Examples
    /// --------
    /// >>> import numpy as np, bzspline
    /// >>> x = np.linspace(0, 1, 200)
    /// >>> y = np.sin(6 * x) + np.random.default_rng(0).normal(0, 0.2, 200)
    /// >>> s = bzspline.smoothing_spline(x, y)
    /// >>> bool(0 < s.se(0.5) < 0.1)
    /// True
    fn se<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        guard(|| {
            let p = self.posterior_of_values()?;
            let (xs, shape) = floats(x, "x")?;
            let se = py.allow_threads(|| standard_errors(p, &xs))?;
            PyArray1::from_vec(py, se).reshape(shape)
        })
    }

    /// The pointwise confidence band of a smoothing fit at ``x``:
    /// ``s(x) -+ z * s.se(x)`` with ``z`` the standard normal quantile of
    /// ``(1 + level) / 2``. Across the data's points it covers the true
    /// curve at about ``level`` of them on average.
    ///
    /// Parameters
    /// ----------
    /// x : array_like
    ///     Points within the knots.
    /// level : float, default 0.95
    ///     Strictly between 0 and 1.
    ///
    /// Returns
    /// -------
    /// (ndarray, ndarray)
    ///     The lower and upper edges, each of the shape of ``x``.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     As :meth:`se`, and for a level outside (0, 1).
    ///
    /// Examples
    /// --------
    /// >>> import numpy as np, bzspline
    /// >>> x = np.linspace(0, 1, 200)
    /// >>> y = np.sin(6 * x) + np.random.default_rng(0).normal(0, 0.2, 200)
    /// >>> lo, hi = bzspline.smoothing_spline(x, y).band(x, level=0.9)
    /// >>> bool(np.all(lo < hi))
    /// True
    #[pyo3(signature = (x, level=0.95))]
    fn band<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        level: f64,
    ) -> PyResult<Edges<'py>> {
        guard(|| {
            let p = self.posterior_of_values()?;
            let (xs, shape) = floats(x, "x")?;
            let s = &self.inner;
            let (lo, hi) = py.allow_threads(|| -> PyResult<(Vec<f64>, Vec<f64>)> {
                let mut lo = Vec::with_capacity(xs.len());
                let mut hi = Vec::with_capacity(xs.len());
                for (i, &x) in xs.iter().enumerate() {
                    let at = |e: bzspline::Error| PyValueError::new_err(format!("x[{i}]: {e}"));
                    let (a, b) =
                        p.band(s.eval(x).map_err(at)?, x, level, 0)
                            .map_err(|e| match e {
                                bzspline::Error::InvalidArgument { .. } => value_error(e),
                                e => at(e),
                            })?;
                    lo.push(a);
                    hi.push(b);
                }
                Ok((lo, hi))
            })?;
            Ok((
                PyArray1::from_vec(py, lo).reshape(shape.clone())?,
                PyArray1::from_vec(py, hi).reshape(shape)?,
            ))
        })
    }

    /// For a spline from :func:`bzspline.smoothing_spline`: the ``lam`` used
    /// (the one chosen by cross-validation when none was given); else None.
    #[getter]
    fn lam(&self) -> Option<f64> {
        self.smoothing.map(|s| s[0])
    }

    /// For a smoothing spline: the generalized cross-validation score at
    /// ``lam``; else None.
    #[getter]
    fn gcv(&self) -> Option<f64> {
        self.smoothing.map(|s| s[1])
    }

    /// For a smoothing spline: its effective degrees of freedom (the trace
    /// of the influence matrix, from 2 for a line to n for interpolation);
    /// else None.
    #[getter]
    fn dof(&self) -> Option<f64> {
        self.smoothing.map(|s| s[2])
    }

    /// For a spline from ``smoothing_spline(..., robust=True)``: the
    /// robustness weight each point ended with, in [0, 1] (0 for a point
    /// judged an outlier); the fit weighs each point by ``w`` times this.
    /// Else None.
    #[getter]
    fn robustness<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.robustness
            .as_deref()
            .map(|r| PyArray1::from_slice(py, r))
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(PyObject, Bound<'py, PyTuple>)> {
        let restore = py
            .import("bzspline._core")?
            .getattr("_spline_from_parts")?
            .unbind();
        let args = PyTuple::new(
            py,
            [
                PyArray1::from_slice(py, self.inner.knots()).into_any(),
                // The data: for `through` kept aside, else the control values.
                PyArray1::from_slice(
                    py,
                    if self.through {
                        &self.y
                    } else {
                        self.inner.values()
                    },
                )
                .into_any(),
                alphas_arg(py, self.inner.alphas())?,
                self.through.into_pyobject(py)?.to_owned().into_any(),
                self.extrapolate(py).into_bound(py),
                self.nu.into_pyobject(py)?.into_any(),
                self.offset.into_pyobject(py)?.into_any(),
                self.smoothing.into_pyobject(py)?.into_any(),
                posterior_arg(py, self.posterior.as_deref())?,
                match self.robustness.as_deref() {
                    Some(r) => PyArray1::from_slice(py, r).into_any(),
                    None => py.None().into_bound(py),
                },
            ],
        )?;
        Ok((restore, args))
    }

    fn __repr__(&self) -> String {
        format!(
            "Spline(n={}, domain=({}, {}), through={}{})",
            self.inner.knots().len(),
            bzspline::text::Shortest(self.inner.domain().0),
            bzspline::text::Shortest(self.inner.domain().1),
            if self.through { "True" } else { "False" },
            if self.nu != 0 {
                format!(", nu={}", self.nu)
            } else {
                String::new()
            }
        )
    }
}

/// A spline (or its derivative of order `nu`) from the parts `__reduce__`
/// gives: how a pickled `Spline` is rebuilt.
#[pyfunction]
#[pyo3(signature = (x, y, alpha, through, extrapolate, nu, offset=0.0, smoothing=None, posterior=None, robustness=None))]
#[allow(clippy::too_many_arguments)] // the parts of a pickled Spline
pub(crate) fn _spline_from_parts(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    y: &Bound<'_, PyAny>,
    alpha: &Bound<'_, PyAny>,
    through: bool,
    extrapolate: &Bound<'_, PyAny>,
    nu: i32,
    offset: f64,
    smoothing: Option<[f64; 3]>,
    posterior: Option<&Bound<'_, PyAny>>,
    robustness: Option<Vec<f64>>,
) -> PyResult<Spline> {
    let mut s = Spline::new(py, x, y, Some(alpha), through, Some(extrapolate))?;
    let anti = (nu < 0).then(|| Arc::new(s.inner.antiderivative()));
    let posterior = match posterior.filter(|p| !p.is_none()) {
        None => None,
        Some(p) => {
            let (knots, alphas, cov, sigma2): PosteriorTuple = p.extract()?;
            Some(Arc::new(
                bzspline::Posterior::from_parts(bzspline::PosteriorParts {
                    knots: &knots,
                    alphas: &alphas,
                    cov: &cov,
                    noise: sigma2.as_deref(),
                })
                .map_err(value_error)?,
            ))
        }
    };
    s.nu = nu.max(-1);
    s.anti = anti;
    s.offset = offset;
    s.smoothing = smoothing;
    s.posterior = posterior;
    s.robustness = robustness.map(Arc::new);
    Ok(s)
}

/// A posterior as `__reduce__` passes it: `(knots, alphas, covariances,
/// noise variances)` as lists, or None.
fn posterior_arg<'py>(
    py: Python<'py>,
    p: Option<&bzspline::Posterior>,
) -> PyResult<Bound<'py, PyAny>> {
    match p {
        None => Ok(py.None().into_bound(py)),
        Some(p) => {
            let parts = p.parts();
            Ok((
                parts.knots.to_vec(),
                parts.alphas.to_vec(),
                parts.cov.to_vec(),
                parts.noise.map(<[f64]>::to_vec),
            )
                .into_pyobject(py)?
                .into_any())
        }
    }
}

/// A contiguous copy (or the data itself) of a 1-D float array argument.
fn vector(v: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let a = as_float_array(v, what)?;
    let view = a.as_array();
    if view.ndim() != 1 {
        return Err(PyValueError::new_err(format!("{what} must be a 1-D array")));
    }
    Ok(view.iter().copied().collect())
}

/// The smoothing spline of noisy data in the method's basis.
///
/// Knots at ``x``; control values chosen to minimise
/// ``sum(w * (S(x) - y)**2) + lam * integral(S''(x)**2)`` over the method's
/// splines with this ``alpha``, in O(n) time and memory (``docs/method.md``
/// section 12). The arguments are those of
/// ``scipy.interpolate.make_smoothing_spline``; the result is a
/// :class:`Spline` (the method's spline of the solved control values: C1,
/// touching every leg of that polygon, inside its hull).
///
/// Parameters
/// ----------
/// x : array_like, shape (n,)
///     Strictly increasing, finite abscissas; n >= 3.
/// y : array_like, shape (n,)
///     The noisy values.
/// w : array_like, shape (n,), optional
///     Weights, finite and >= 0 (not squared, as scipy); default all 1. A point
///     of weight 0 does not move the fit.
/// lam : float, optional
///     The weight of the roughness penalty, >= 0. None (the default) chooses
///     it by generalized cross-validation, as scipy does; 0 passes through
///     every point (``Spline(x, y, through=True)``).
/// alpha : float or array_like, shape (n - 1,), default 0.5
///     The shape parameter in [1/3, 2/3].
/// extrapolate : {True, False, 'clamp'}, default True
///     As for :class:`Spline`.
/// robust : bool, default False
///     Robust against outliers: the fit is weighted again by its residuals
///     (Tukey's biweight on six median absolute residuals, as lowess does),
///     ``lam`` chosen again each time, until the weights settle.
///
/// Returns
/// -------
/// Spline
///     With ``lam`` (the one used), ``gcv`` (its cross-validation score) and
///     ``dof`` (the effective degrees of freedom) set, and for a robust fit
///     ``robustness``, the weight each point ended with.
///
/// Raises
/// ------
/// ValueError
///     Fewer than 3 points (5 of positive weight for a robust fit), x not
///     increasing, a negative or non-finite weight or ``lam``, fewer than 2
///     positive weights, naming the index at fault.
///
/// Examples
/// --------
/// >>> import numpy as np, bzspline
/// >>> x = np.linspace(0, 1, 200)
/// >>> y = np.sin(6 * x) + np.random.default_rng(0).normal(0, 0.2, 200)
/// >>> s = bzspline.smoothing_spline(x, y)
/// >>> bool(abs(s(0.5) - np.sin(3)) < 0.1), 2 < s.dof < 20
/// (True, True)
#[pyfunction]
#[pyo3(signature = (x, y, w=None, lam=None, *, alpha=None, extrapolate=None, robust=false))]
#[allow(clippy::too_many_arguments)] // scipy's arguments and ours
pub(crate) fn smoothing_spline(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    y: &Bound<'_, PyAny>,
    w: Option<&Bound<'_, PyAny>>,
    lam: Option<f64>,
    alpha: Option<&Bound<'_, PyAny>>,
    extrapolate: Option<&Bound<'_, PyAny>>,
    robust: bool,
) -> PyResult<Spline> {
    guard(|| {
        let (x, y) = (vector(x, "x")?, vector(y, "y")?);
        let w = w.map(|w| vector(w, "w")).transpose()?;
        let alpha = alpha_arg(alpha)?;
        let outside = extrapolate_arg(extrapolate)?;
        let how = lam.map_or(bzspline::Smoothing::Gcv, bzspline::Smoothing::Lambda);
        let fit = py
            .allow_threads(|| {
                let (w, alphas) = (w.as_deref(), alpha.as_alphas());
                crate::threads::install(|| {
                    if robust {
                        bzspline::Spline::smoothing_robust(&x, &y, w, alphas, how)
                    } else {
                        bzspline::Spline::smoothing(&x, &y, w, alphas, how)
                    }
                })
            })
            .map_err(value_error)?;
        Ok(Spline {
            inner: Arc::new(fit.fit.with_extrapolation(outside)),
            y: Vec::new(),
            through: false,
            outside,
            nu: 0,
            anti: None,
            offset: 0.0,
            smoothing: Some([fit.lambda, fit.gcv, fit.dof]),
            posterior: Some(Arc::new(fit.posterior)),
            robustness: fit.robustness.map(Arc::new),
        })
    })
}
