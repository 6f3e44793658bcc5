//! Arguments from Python: float arrays read in place where they can be,
//! shape parameters, `extrapolate` and `param`, and library errors as
//! Python exceptions (with panics caught at the boundary).

use std::panic::{catch_unwind, AssertUnwindSafe};

use numpy::{PyArray1, PyReadonlyArrayDyn};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyAny;

use bzspline::{AlphaChoice, Extrapolate, Param};

/// A library error as Python's `ValueError`, with the library's message
/// (which names the index or field at fault).
pub(crate) fn value_error(e: bzspline::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Runs `f`, turning a Rust panic (a bug) into `RuntimeError` with its message.
pub(crate) fn guard<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_owned());
            Err(PyRuntimeError::new_err(format!(
                "bzspline internal error (please report it): {msg}"
            )))
        }
    }
}

/// An array-like as an aligned float64 numpy array (the same object when it
/// is one).
/// Complex numbers are refused rather than cut to their real parts.
pub(crate) fn as_float_array<'py>(
    x: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    let np = x.py().import("numpy")?;
    if np.call_method1("iscomplexobj", (x,))?.is_truthy()? {
        return Err(PyTypeError::new_err(format!(
            "{what}: complex numbers are not supported (the spline is real)"
        )));
    }
    let arr = np
        .call_method1("asarray", (x, "float64"))
        .map_err(|e| PyTypeError::new_err(format!("{what}: {e}")))?;
    // An array unpickled from a message buffer (dask's protocol 5 frames)
    // may start at an address no f64 may be read from: copied to one.
    let arr = np.call_method1("require", (arr, "float64", "A"))?;
    arr.extract()
}

/// Numbers of an array-like as a flat vector with the array's shape.
pub(crate) fn floats(x: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let a = as_float_array(x, what)?;
    let view = a.as_array();
    let shape = view.shape().to_vec();
    let flat = match view.as_slice() {
        Some(s) => s.to_vec(),
        None => view.iter().copied().collect(),
    };
    Ok((flat, shape))
}

/// The alphas as a constructor takes them back: one number when they are
/// all one (the same construction, bit for bit), else the array.
pub(crate) fn alphas_arg<'py>(py: Python<'py>, alphas: &[f64]) -> PyResult<Bound<'py, PyAny>> {
    match alphas.first() {
        Some(&a) if alphas.iter().all(|&b| b == a) => Ok(a.into_pyobject(py)?.into_any()),
        _ => Ok(PyArray1::from_slice(py, alphas).into_any()),
    }
}

/// Points as an `(n, d)` array: the numbers flat and `d`.
pub(crate) fn rows_arg(points: &Bound<'_, PyAny>) -> PyResult<(Vec<f64>, usize)> {
    let (pts, shape) = floats(points, "points")?;
    if shape.len() != 2 || shape[1] == 0 {
        return Err(PyValueError::new_err(
            "points must be an (n, d) array: one row per point",
        ));
    }
    Ok((pts, shape[1]))
}

/// `alpha=`: one alpha or one per interval; absent, the default 1/2.
pub(crate) fn alpha_arg(alpha: Option<&Bound<'_, PyAny>>) -> PyResult<AlphaChoice> {
    let Some(alpha) = alpha else {
        return Ok(AlphaChoice::default());
    };
    if let Ok(a) = alpha.extract::<f64>() {
        return Ok(AlphaChoice::One(a));
    }
    let (v, shape) = floats(alpha, "alpha")?;
    if shape.len() != 1 {
        return Err(PyValueError::new_err(
            "alpha must be a number or a 1-D array of one alpha per interval",
        ));
    }
    Ok(AlphaChoice::Each(v))
}

/// `extrapolate=`: `True` (the default) extends the end cubics, `False`
/// gives NaN outside the knots (as scipy), or a policy by name (`'clamp'`,
/// `'extend'`, `'nan'`, `'error'`): [`bzspline::Extrapolate`]'s own
/// conversions.
pub(crate) fn extrapolate_arg(v: Option<&Bound<'_, PyAny>>) -> PyResult<Extrapolate> {
    let Some(v) = v else {
        return Ok(Extrapolate::Extend);
    };
    if let Ok(b) = v.extract::<bool>() {
        return Ok(Extrapolate::from(b));
    }
    match v.extract::<String>() {
        Ok(name) => name
            .parse()
            .map_err(|e| PyValueError::new_err(format!("extrapolate {e}, True nor False"))),
        Err(_) => Err(PyValueError::new_err(
            "extrapolate must be True, False or 'clamp'",
        )),
    }
}

pub(crate) fn param_arg(p: &Bound<'_, PyAny>) -> PyResult<(Param, String)> {
    if let Ok(s) = p.extract::<String>() {
        return match s.parse::<Param>() {
            Ok(param) => Ok((param, s)),
            Err(e) => Err(PyValueError::new_err(format!(
                "param {e}, nor an array of parameters"
            ))),
        };
    }
    let (v, _) = floats(p, "param")?;
    Ok((Param::Given(v), "given".to_owned()))
}
