//! The smoothing fits of the package's `bzspline/smoothing` entry, a module
//! of their own so that a page drawing curves does not load the fit. Each
//! returns what the core module builds the result from: a smoothing spline
//! (curve) is the method's spline (curve) of its control values (points) on
//! the data's knots (`docs/method.md` §12), so the entry passes them to the
//! core's `Spline` (`Curve`) constructor, whose build is the library's, and
//! the object it returns is the fit bit for bit.

use bzspline::ParamCurve;
use js_sys::{Float64Array, Object};
use wasm_bindgen::prelude::*;

use crate::args::{lib_error, numbers, param_of, points, set, Options};

/// The fit's `lam`, GCV score, degrees of freedom and robustness weights
/// (null for a plain fit) on `o`.
fn report<T>(o: &Object, fit: &bzspline::Smoothed<T>) {
    set(o, "lam", fit.lambda.into());
    set(o, "gcv", fit.gcv.into());
    set(o, "dof", fit.dof.into());
    let robustness = match &fit.robustness {
        Some(r) => Float64Array::from(r.as_slice()).into(),
        None => JsValue::NULL,
    };
    set(o, "robustness", robustness);
}

/// What a smoothing spline's standard errors and bands need
/// ([`bzspline::Posterior`]), held by the fit's object.
#[wasm_bindgen]
pub struct Posterior {
    inner: bzspline::Posterior,
}

#[wasm_bindgen]
impl Posterior {
    /// The standard error of the fit at each x (within the knots).
    pub fn se(&self, xs: &JsValue) -> Result<Float64Array, JsValue> {
        let xs = numbers(xs, "x")?;
        let mut out = Vec::with_capacity(xs.len());
        for (i, &x) in xs.iter().enumerate() {
            out.push(self.inner.se(x, 0).map_err(|e| at_index(i, &e))?);
        }
        Ok(Float64Array::from(out.as_slice()))
    }

    /// The band at `level` around the fit's `values` at `xs`: the lower
    /// edges, then the upper, in one array of twice their length.
    pub fn band(&self, values: &[f64], xs: &[f64], level: f64) -> Result<Float64Array, JsValue> {
        let n = xs.len();
        let mut out = vec![0.0; 2 * n];
        for (i, (&v, &x)) in values.iter().zip(xs).enumerate() {
            let (lo, hi) = self.inner.band(v, x, level, 0).map_err(|e| match e {
                bzspline::Error::InvalidArgument { .. } => lib_error(e),
                e => at_index(i, &e),
            })?;
            out[i] = lo;
            out[n + i] = hi;
        }
        Ok(Float64Array::from(out.as_slice()))
    }
}

/// A library error at `x[i]`, as a `RangeError` naming the index.
fn at_index(i: usize, e: &bzspline::Error) -> JsValue {
    match e {
        bzspline::Error::InvalidArgument { .. } => lib_error(e.clone()),
        _ => crate::args::range_error(format!("x[{i}]: {e}")),
    }
}

/// `splineFit(x, y, {w, lam, alpha, alphas, robust})`: the smoothing spline
/// of the data in the method's basis (`bzspline::Spline::smoothing`, or
/// `smoothing_robust` with `robust: true`) as `{x, controls, lam, gcv, dof,
/// posterior, robustness}`: knots, control values, the `lam` used (the one
/// chosen by generalized cross-validation when `lam` is omitted or null), its
/// score and effective degrees of freedom, what its bands need, and a robust
/// fit's weights (else null). `w`: one weight per point, finite and >= 0
/// (default 1).
#[wasm_bindgen(js_name = splineFit)]
pub fn spline_fit(x: &JsValue, y: &JsValue, options: &JsValue) -> Result<Object, JsValue> {
    let x = numbers(x, "x")?;
    let y = numbers(y, "y")?;
    let o = Options::new(options)?;
    let alphas = o.alphas()?;
    let (w, how) = o.smoothing()?;
    let fit = if o.flag("robust", false)? {
        bzspline::Spline::smoothing_robust(&x, &y, w.as_deref(), alphas.as_alphas(), how)
    } else {
        bzspline::Spline::smoothing(&x, &y, w.as_deref(), alphas.as_alphas(), how)
    }
    .map_err(lib_error)?;
    let out = Object::new();
    set(&out, "x", Float64Array::from(x.as_slice()).into());
    set(
        &out,
        "controls",
        Float64Array::from(fit.fit.values()).into(),
    );
    report(&out, &fit);
    set(
        &out,
        "posterior",
        Posterior {
            inner: fit.posterior,
        }
        .into(),
    );
    Ok(out)
}

/// `curveFit(points, {w, lam, param, alpha, alphas, robust, closed})`: the
/// smoothing curve of noisy points (open, or closed round its loop; one `lam`
/// for every coordinate;
/// `bzspline::CurveBuilder::build_smoothed`) as `{points, dim, knots, alphas,
/// lam, gcv, dof, robustness}`: the control points (flat, `dim` numbers
/// each), the parameters and alphas of the fit's legs, and the fit's report.
#[wasm_bindgen(js_name = curveFit)]
pub fn curve_fit(pts: &JsValue, options: &JsValue) -> Result<Object, JsValue> {
    let (flat, dim) = points(pts, "points")?;
    let o = Options::new(options)?;
    let param = param_of(&o)?;
    let alphas = o.alphas()?;
    let (w, how) = o.smoothing()?;
    let mut b = bzspline::CurveBuilder::new(&flat, dim.max(1))
        .closed(o.flag("closed", false)?)
        .param(param)
        .alpha_choice(alphas.as_alphas())
        .smoothing(how)
        .robust(o.flag("robust", false)?);
    if let Some(w) = &w {
        b = b.weights(w);
    }
    let fit = b.build_smoothed().map_err(lib_error)?;
    let c = &fit.fit;
    let out = Object::new();
    set(&out, "points", Float64Array::from(c.points()).into());
    set(&out, "dim", (c.dim() as f64).into());
    set(&out, "knots", Float64Array::from(c.knots()).into());
    set(&out, "alphas", Float64Array::from(c.alphas()).into());
    set(&out, "closed", c.is_closed().into());
    report(&out, &fit);
    Ok(out)
}
