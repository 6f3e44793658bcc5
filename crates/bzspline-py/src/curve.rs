//! `bzspline.Curve`: the method's curve in R^d, open or closed, for numpy
//! arrays.

use bzspline::Bounds;
use bzspline::Flatten;
use bzspline::ParamCurve;
use std::sync::Arc;

use numpy::ndarray::{ArrayD, IxDyn};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyTuple};

use bzspline::{Arclen, Param, DEFAULT_ACCURACY};

use crate::args::*;

/// A curve in R^d by the method: open or closed, any parametrisation.
///
/// Each coordinate is the method's spline of the parameter; the curve starts
/// and ends at the end points (an open curve), touches every leg of the control
/// polygon and stays in the convex hull of the points.
///
/// Parameters
/// ----------
/// points : array_like, shape (n, d)
///     The control points, d >= 1 (n >= 2 open, n >= 3 closed).
/// closed : bool, default False
///     A closed curve (the points as a ring; do not repeat the first).
/// param : {'centripetal', 'chordal', 'uniform'} or array_like, default 'centripetal'
///     How the knots follow the points, or the knots themselves (n of them;
///     n + 1 for a closed curve).
/// alpha : float or array_like, default 0.5
///     The shape parameter in [1/3, 2/3], one for all legs or one each.
/// through : bool, default False
///     Pass through every point instead (the interpolating variant).
///
/// Attributes
/// ----------
/// knots, knot_points, dim, segments
///
/// Raises
/// ------
/// ValueError
///     For too few or non-finite points, repeated consecutive points, bad knots
///     or alphas, naming the index at fault.
///
/// Notes
/// -----
/// Immutable: safe to share between threads; pickles.
///
/// Examples
/// --------
/// >>> c = Curve([[0, 0], [1, 0], [1, 1], [0, 1]], closed=True)
/// >>> c.dim
/// 2
#[pyclass(frozen, module = "bzspline._core")]
pub(crate) struct Curve {
    inner: Arc<bzspline::Curve>,
    points: Vec<f64>,
    closed: bool,
    through: bool,
    param: String,
    /// For a smoothing fit: its `lambda`, GCV score and degrees of freedom.
    smoothing: Option<[f64; 3]>,
    /// For a robust smoothing fit: the weight each point ended with.
    robustness: Option<Vec<f64>>,
}

#[pymethods]
impl Curve {
    #[new]
    #[pyo3(signature = (points, closed=false, param=None, alpha=None, through=false))]
    #[pyo3(
        text_signature = "(points, closed=False, param='centripetal', alpha=0.5, through=False)"
    )]
    fn new(
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        closed: bool,
        param: Option<&Bound<'_, PyAny>>,
        alpha: Option<&Bound<'_, PyAny>>,
        through: bool,
    ) -> PyResult<Self> {
        guard(|| {
            let (pts, dim) = rows_arg(points)?;
            let (param, name) = match param {
                Some(p) => param_arg(p)?,
                None => (Param::default(), Param::default().to_string()),
            };
            let alpha = alpha_arg(alpha)?;
            let built = py.allow_threads(|| {
                crate::threads::install(|| {
                    bzspline::CurveBuilder::new(&pts, dim)
                        .closed(closed)
                        .param(param)
                        .alpha_choice(alpha.as_alphas())
                        .through(through)
                        .build()
                })
            });
            Ok(Curve {
                inner: Arc::new(built.map_err(value_error)?),
                points: pts,
                closed,
                through,
                param: name,
                smoothing: None,
                robustness: None,
            })
        })
    }

    /// The point, or derivative of order `nu`, at every parameter t.
    ///
    /// Parameters
    /// ----------
    /// t : array_like
    ///     Parameters, any shape, within ``knots[0]`` .. ``knots[-1]`` (a closed
    ///     curve wraps).
    /// nu : int, default 0
    ///     The derivative order, at least 0.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``t.shape + (d,)``.
    #[pyo3(signature = (t, nu=0))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        nu: i64,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        guard(|| {
            let nu = u32::try_from(nu)
                .map_err(|_| PyValueError::new_err(format!("nu = {nu} must be at least 0")))?;
            let (t, mut shape) = floats(t, "t")?;
            let c = &self.inner;
            shape.push(c.dim());
            let fresh = PyArrayDyn::<f64>::zeros(py, IxDyn(&shape), false);
            {
                let mut w = fresh.readwrite();
                let dst = w
                    .as_slice_mut()
                    .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
                py.allow_threads(|| c.deriv_many(&t, nu, dst))
                    .map_err(value_error)?;
            }
            Ok(fresh)
        })
    }

    /// The parameters of the knots.
    #[getter]
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.knots())
    }

    /// The curve's points at the knots, `(m, d)`.
    #[getter]
    fn knot_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        PyArray2::from_vec2(py, &self.inner.knot_points())
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The dimension d.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// The arc length.
    ///
    /// Parameters
    /// ----------
    /// accuracy : float, optional
    ///     The largest error allowed, relative to the length.
    ///
    /// Returns
    /// -------
    /// float
    #[pyo3(signature = (accuracy=DEFAULT_ACCURACY))]
    fn arclen(&self, py: Python<'_>, accuracy: f64) -> PyResult<f64> {
        let c = &self.inner;
        py.allow_threads(|| Arclen::arclen(&**c, accuracy))
            .map_err(value_error)
    }

    /// Points at equal arc-length steps along the curve.
    ///
    /// Parameters
    /// ----------
    /// n : int, optional
    ///     How many points, at least 2, from start to end.
    /// step : float, optional
    ///     Or one point every `step` of arc length (and the end point).
    /// accuracy : float, optional
    ///     Relative accuracy of the lengths.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (m, d)
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     Unless exactly one of `n` (at least 2) and `step` (positive) is given.
    #[pyo3(signature = (n=None, step=None, accuracy=DEFAULT_ACCURACY))]
    fn resample<'py>(
        &self,
        py: Python<'py>,
        n: Option<usize>,
        step: Option<f64>,
        accuracy: f64,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = &self.inner;
        let rows: Vec<Vec<f64>> = match (n, step) {
            (Some(n), None) => {
                let p = py
                    .allow_threads(|| c.resample(n, accuracy))
                    .map_err(value_error)?;
                (0..p.len())
                    .filter_map(|i| p.point(i).map(<[f64]>::to_vec))
                    .collect()
            }
            (None, Some(step)) if step.is_finite() && step > 0.0 => {
                let total = Arclen::arclen(&**c, accuracy).map_err(value_error)?;
                let count = (total / step).floor();
                if count > 1e7 {
                    return Err(PyValueError::new_err(format!(
                        "step = {step} gives more than 10^7 points"
                    )));
                }
                let mut lengths: Vec<f64> = (0..=count as usize).map(|i| i as f64 * step).collect();
                lengths.retain(|l| total - l > accuracy);
                let mut ts = c
                    .params_at_lengths(&lengths, accuracy)
                    .map_err(value_error)?;
                ts.push(c.domain().1);
                ts.iter()
                    .map(|&t| c.eval(t).map_err(value_error))
                    .collect::<PyResult<_>>()?
            }
            _ => {
                return Err(PyValueError::new_err(
                    "give one of n (at least 2) or step (a positive number)",
                ))
            }
        };
        PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The point of the curve nearest to `p`.
    ///
    /// Parameters
    /// ----------
    /// p : array_like, shape (d,)
    ///
    /// Returns
    /// -------
    /// (float, numpy.ndarray, float)
    ///     ``(t, point, distance)``: the parameter, the point ``c(t)``, its distance.
    fn nearest<'py>(
        &self,
        py: Python<'py>,
        p: &Bound<'py, PyAny>,
    ) -> PyResult<(f64, Bound<'py, PyArray1<f64>>, f64)> {
        let (q, _) = floats(p, "p")?;
        let n = self.inner.nearest(&q).map_err(value_error)?;
        Ok((n.param, n.point.into_pyarray(py), n.distance))
    }

    /// The exact bounding box of the curve (not of its control points).
    ///
    /// Returns
    /// -------
    /// (numpy.ndarray, numpy.ndarray)
    ///     ``(min, max)``, each of shape (d,).
    fn bbox<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        let b = self.inner.bbox();
        (b.min.into_pyarray(py), b.max.into_pyarray(py))
    }

    /// The curvature at every parameter t.
    ///
    /// Parameters
    /// ----------
    /// t : array_like
    ///     Any shape.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Of t's shape: ``|c' x c''| / |c'|^3``, unsigned, 0 on a straight
    ///     part, in the plane and in space alike.
    fn curvature<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let (t, shape) = floats(t, "t")?;
        let c = &self.inner;
        let out = py.allow_threads(|| {
            t.iter()
                .map(|&s| c.curvature(s).map_err(value_error))
                .collect::<PyResult<Vec<f64>>>()
        })?;
        let arr = ArrayD::from_shape_vec(IxDyn(&shape), out)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(arr.into_pyarray(py))
    }

    /// A polyline within `tolerance` of the curve.
    ///
    /// Parameters
    /// ----------
    /// tolerance : float
    ///     Positive: the largest distance between the curve and the polyline.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (m, d)
    ///     Starts and ends at the curve's ends (a closed curve's end is its start).
    fn flatten<'py>(&self, py: Python<'py>, tolerance: f64) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = &self.inner;
        let p = py
            .allow_threads(|| c.flatten(tolerance))
            .map_err(value_error)?;
        let rows: Vec<Vec<f64>> = (0..p.len())
            .filter_map(|i| p.point(i).map(<[f64]>::to_vec))
            .collect();
        PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Every segment as four control points, `(m, 4, d)`.
    #[getter]
    fn segments<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let d = self.inner.dim();
        let segs: Vec<Vec<Vec<f64>>> = (0..self.inner.len())
            .filter_map(|k| self.inner.segment_points(k))
            .map(|p| p.chunks(d).map(<[f64]>::to_vec).collect())
            .collect();
        PyArray3::from_vec3(py, &segs).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// SVG path data of a planar curve, exactly: one ``C`` command per segment.
    ///
    /// Returns
    /// -------
    /// str
    ///     ``M x y C ...``, with ``Z`` at the end of a closed curve.
    ///
    /// Raises
    /// ------
    /// ValueError
    ///     For a curve that is not planar.
    fn svg_path(&self) -> PyResult<String> {
        self.inner.to_svg_path().map_err(value_error)
    }

    /// For a curve from :func:`bzspline.smoothing_curve`: the ``lam`` used;
    /// else None (and after pickling, which keeps the curve).
    #[getter]
    fn lam(&self) -> Option<f64> {
        self.smoothing.map(|s| s[0])
    }

    /// For a smoothing curve: its generalized cross-validation score; else None.
    #[getter]
    fn gcv(&self) -> Option<f64> {
        self.smoothing.map(|s| s[1])
    }

    /// For a smoothing curve: its effective degrees of freedom; else None.
    #[getter]
    fn dof(&self) -> Option<f64> {
        self.smoothing.map(|s| s[2])
    }

    /// For a curve from ``smoothing_curve(..., robust=True)``: the
    /// robustness weight each point given ended with, in [0, 1] (0 for a
    /// point judged an outlier); else None.
    #[getter]
    fn robustness<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.robustness
            .as_deref()
            .map(|r| PyArray1::from_slice(py, r))
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(PyObject, Bound<'py, PyTuple>)> {
        let cls = py.get_type::<Curve>().into_any().unbind();
        let d = self.inner.dim();
        let rows: Vec<Vec<f64>> = self.points.chunks(d).map(<[f64]>::to_vec).collect();
        let points = PyArray2::from_vec2(py, &rows)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
            .into_any();
        let param = if self.param == "given" {
            PyArray1::from_slice(py, self.inner.knots()).into_any()
        } else {
            self.param.clone().into_pyobject(py)?.into_any()
        };
        let args = PyTuple::new(
            py,
            [
                points,
                self.closed.into_pyobject(py)?.to_owned().into_any(),
                param,
                alphas_arg(py, self.inner.alphas())?,
                self.through.into_pyobject(py)?.to_owned().into_any(),
            ],
        )?;
        Ok((cls, args))
    }

    fn __repr__(&self) -> String {
        format!(
            "Curve(points={}, dim={}, closed={}, param='{}')",
            self.inner.point_count(),
            self.inner.dim(),
            if self.closed { "True" } else { "False" },
            self.param
        )
    }
}

/// The smoothing curve of noisy points (a GPS track, a digitised outline) in
/// the method's basis.
///
/// The parameters come from the points as for :class:`Curve` (centripetal
/// by default, or given, for example the times of a track); the control
/// points minimise ``sum(w * |C(t) - p|**2) + lam * integral(|C''(t)|**2)``
/// with one ``lam`` for every coordinate, chosen by generalized
/// cross-validation over their sum when omitted. O(n).
///
/// Parameters
/// ----------
/// points : array_like, shape (n, d)
///     n >= 3 points, an open curve (or closed, with ``closed=True``).
/// w : array_like, shape (n,), optional
///     Weights, finite and >= 0 (default all 1).
/// lam : float, optional
///     The penalty's weight, >= 0; None chooses it.
/// param : {'centripetal', 'chordal', 'uniform'} or array_like, optional
///     As for :class:`Curve`. On points as noisy as their spacing, chordal and
///     centripetal parameters follow the noise (cross-validation then picks
///     interpolation): give 'uniform' or the times.
/// alpha : float or array_like, default 0.5
/// closed : bool, default False
///     A closed curve (a contour, a lap), smoothed round its loop: the
///     closing leg is a leg like the others, and ``param`` given has n + 1
///     values. A large ``lam`` draws it towards the weighted mean point.
/// robust : bool, default False
///     Robust against outliers (a GPS jump), as for :func:`smoothing_spline`;
///     a point's residual is its distance from the fitted point. An outlier
///     also stretches chordal and centripetal parameters: give the times.
///
/// Returns
/// -------
/// Curve
///     Its control points solved, parameters given, with ``lam``, ``gcv`` and
///     ``dof`` set, and for a robust fit ``robustness``.
///
/// Examples
/// --------
/// >>> import numpy as np, bzspline
/// >>> t = np.linspace(0, 6, 300)
/// >>> noise = np.random.default_rng(0).normal(0, 0.2, (300, 2))
/// >>> track = np.c_[10 * np.cos(t), 10 * np.sin(t)] + noise
/// >>> c = bzspline.smoothing_curve(track, param=t)
/// >>> r = np.hypot(*c(t).T)
/// >>> bool(np.abs(r - 10).mean() < 0.5 * np.abs(np.hypot(*track.T) - 10).mean())
/// True
#[pyfunction]
#[pyo3(signature = (points, w=None, lam=None, *, param=None, alpha=None, robust=false, closed=false))]
#[allow(clippy::too_many_arguments)] // scipy's arguments and ours
pub(crate) fn smoothing_curve(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    w: Option<&Bound<'_, PyAny>>,
    lam: Option<f64>,
    param: Option<&Bound<'_, PyAny>>,
    alpha: Option<&Bound<'_, PyAny>>,
    robust: bool,
    closed: bool,
) -> PyResult<Curve> {
    guard(|| {
        let (pts, dim) = rows_arg(points)?;
        let w = w.map(|w| floats(w, "w").map(|f| f.0)).transpose()?;
        let param = match param {
            Some(p) => param_arg(p)?.0,
            None => Param::default(),
        };
        let alpha = alpha_arg(alpha)?;
        let how = lam.map_or(bzspline::Smoothing::Gcv, bzspline::Smoothing::Lambda);
        let fit = py
            .allow_threads(|| {
                let mut b = bzspline::CurveBuilder::new(&pts, dim)
                    .closed(closed)
                    .param(param)
                    .alpha_choice(alpha.as_alphas())
                    .smoothing(how)
                    .robust(robust);
                if let Some(w) = &w {
                    b = b.weights(w);
                }
                crate::threads::install(|| b.build_smoothed())
            })
            .map_err(value_error)?;
        Ok(Curve {
            points: fit.fit.points().to_vec(),
            inner: Arc::new(fit.fit),
            closed,
            through: false,
            param: "given".to_owned(),
            smoothing: Some([fit.lambda, fit.gcv, fit.dof]),
            robustness: fit.robustness,
        })
    })
}
