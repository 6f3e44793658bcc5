//! `Spline`: the method's spline y = S(x) for JavaScript, with values,
//! derivatives, integrals, extrema and its exact Bezier pieces.

use bzspline::ParamCurve;
use std::rc::Rc;

use bzspline::{Extrapolate, ExtremumKind};
use js_sys::{Array, Float64Array};
use wasm_bindgen::prelude::*;

use crate::args::{kind, lib_error, numbers, range_error, set, type_error, Options};

/// The third-degree Bezier-type spline y = S(x) of Stelia, Potapenko and
/// Sirenko: C1, through the first and last points, touching every leg of
/// the control polygon, within the range of y; every piece one cubic Bezier
/// segment.
#[wasm_bindgen]
pub struct Spline {
    inner: Rc<bzspline::Spline>,
    /// Outside the knots (`Nan` for `extrapolate: false`); the spline
    /// evaluates by it too.
    outside: Extrapolate,
    /// The derivative order this object evaluates (from `derivative`).
    nu: u32,
}

/// The `extrapolate` option: true (extend, the default), false (NaN, as
/// scipy) or a policy by name (`"clamp"`, `"extend"`, `"nan"`):
/// [`Extrapolate`]'s own conversions. Not `"error"`: a value outside the
/// knots is a number here, never an exception.
fn outside_of(o: &Options) -> Result<Extrapolate, JsValue> {
    match o.get("extrapolate") {
        None => Ok(Extrapolate::Extend),
        Some(v) => match (v.as_bool(), v.as_string()) {
            (Some(b), _) => Ok(Extrapolate::from(b)),
            (_, Some(name)) => match name.parse() {
                Ok(Extrapolate::Error) | Err(_) => Err(type_error(format!(
                    "extrapolate must be true, false, \"clamp\", \"extend\" or \"nan\" (found \"{name}\")"
                ))),
                Ok(e) => Ok(e),
            },
            _ => Err(type_error(format!(
                "extrapolate must be true, false or \"clamp\" (found {})",
                kind(&v)
            ))),
        },
    }
}

#[wasm_bindgen]
impl Spline {
    /// `new Spline(x, y, {alpha, alphas, through, extrapolate})`: x strictly
    /// increasing and finite, y as many; alpha in [1/3, 2/3] (0.5 by
    /// default; a number, such as `1/3`) or alphas one per interval; `through` to
    /// pass through every (x, y); `extrapolate` true (extend the end cubics),
    /// false (NaN) or `"clamp"`.
    #[wasm_bindgen(constructor)]
    pub fn new(x: &JsValue, y: &JsValue, options: &JsValue) -> Result<Spline, JsValue> {
        let x = numbers(x, "x")?;
        let y = numbers(y, "y")?;
        let o = Options::new(options)?;
        let alphas = o.alphas()?;
        let through = o.flag("through", false)?;
        let outside = outside_of(&o)?;
        let built = if through {
            bzspline::Spline::through(&x, &y, alphas.as_alphas())
        } else {
            bzspline::Spline::build(&x, &y, alphas.as_alphas())
        }
        .map_err(lib_error)?;
        Ok(Spline {
            inner: Rc::new(built.with_extrapolation(outside)),
            outside,
            nu: 0,
        })
    }

    /// S(x) (or this object's derivative) at x: a number for a number, a
    /// `Float64Array` for an array or typed array. NaN for NaN, and outside
    /// the knots with `extrapolate: false`.
    pub fn at(&self, x: &JsValue) -> Result<JsValue, JsValue> {
        if let Some(v) = x.as_f64() {
            return Ok(self.value(v).into());
        }
        if let Some(xs) = x.dyn_ref::<Float64Array>() {
            return self.values_of_array(xs).map(Into::into);
        }
        let xs = numbers(x, "x")?;
        let mut out = vec![0.0; xs.len()];
        self.values(&xs, &mut out)?;
        Ok(Float64Array::from(out.as_slice()).into())
    }

    /// The derivative of order `nu` (default 1) as a new `Spline`-like object
    /// whose `at` gives S^(nu); orders above 3 are 0.
    pub fn derivative(&self, nu: Option<u32>) -> Spline {
        Spline {
            inner: Rc::clone(&self.inner),
            outside: self.outside,
            nu: self.nu.saturating_add(nu.unwrap_or(1)),
        }
    }

    /// The integral of S from a to b (b < a gives the negative); NaN when a
    /// bound is outside the knots with `extrapolate: false`.
    pub fn integrate(&self, a: f64, b: f64) -> Result<f64, JsValue> {
        if self.nu != 0 {
            return Err(range_error(
                "integrate applies to the spline, not to a derivative",
            ));
        }
        let (lo, hi) = self.inner.domain();
        let inside = |v: f64| (lo..=hi).contains(&v);
        if self.outside == Extrapolate::Nan && !(inside(a) && inside(b)) {
            return Ok(f64::NAN);
        }
        self.inner.integral(a, b).map_err(lib_error)
    }

    /// The points inside the domain where S' = 0: `[{x, y, kind}]` in
    /// increasing x, kind `"minimum"`, `"maximum"` or `"stationary"`.
    pub fn extrema(&self) -> Array {
        self.inner
            .extrema()
            .into_iter()
            .map(|e| {
                let o = js_sys::Object::new();
                let kind = match e.kind {
                    ExtremumKind::Minimum => "minimum",
                    ExtremumKind::Maximum => "maximum",
                    _ => "stationary",
                };
                set(&o, "x", e.x.into());
                set(&o, "y", e.y.into());
                set(&o, "kind", kind.into());
                JsValue::from(o)
            })
            .collect()
    }

    /// The knots.
    #[wasm_bindgen(getter)]
    pub fn x(&self) -> Float64Array {
        Float64Array::from(self.inner.knots())
    }

    /// The knot values S(x_k).
    #[wasm_bindgen(getter, js_name = knotValues)]
    pub fn knot_values(&self) -> Float64Array {
        Float64Array::from(self.inner.knot_values().as_slice())
    }

    /// The control values F_k (for `through`, the solved ones).
    #[wasm_bindgen(getter, js_name = controlValues)]
    pub fn control_values(&self) -> Float64Array {
        Float64Array::from(self.inner.values())
    }

    /// The shape parameters, one per interval.
    #[wasm_bindgen(getter)]
    pub fn alphas(&self) -> Float64Array {
        Float64Array::from(self.inner.alphas())
    }

    /// The points where S touches each leg of the control polygon, flat
    /// (`x0, y0, x1, y1, ...`; `tangentPoints` in JavaScript shapes them).
    #[wasm_bindgen(js_name = _tangentPoints)]
    pub fn tangent_points_flat(&self) -> Vec<f64> {
        self.inner
            .tangent_points()
            .into_iter()
            .flat_map(|(x, y)| [x, y])
            .collect()
    }

    /// Every piece's four Bezier control points, flat (8 numbers a piece;
    /// `segments` in JavaScript shapes them).
    #[wasm_bindgen(js_name = _segments)]
    pub fn segments_flat(&self) -> Vec<f64> {
        self.inner
            .segments()
            .iter()
            .flat_map(|b| b.p.as_flattened().iter().copied())
            .collect()
    }

    /// The graph as SVG path data, exactly: `M x0 y0 C ...`, one `C` per
    /// piece, every number the shortest that reads back the same.
    #[wasm_bindgen(js_name = svgPath)]
    pub fn svg_path(&self) -> Result<String, JsValue> {
        let mut s = String::new();
        match bzspline::write_svg_path(&*self.inner, false, &mut s) {
            Ok(true) => Ok(s),
            _ => Err(range_error(
                "a control point of the path overflows a double",
            )),
        }
    }

    /// The derivative order this object evaluates (0 for the spline).
    #[wasm_bindgen(getter)]
    pub fn nu(&self) -> u32 {
        self.nu
    }
}

impl Spline {
    fn outside_nan(&self, v: f64) -> bool {
        let (a, b) = self.inner.domain();
        v.is_nan() || (self.outside == Extrapolate::Nan && !(a..=b).contains(&v))
    }

    fn value(&self, v: f64) -> f64 {
        if self.outside_nan(v) {
            return f64::NAN;
        }
        if self.nu > 3 {
            return 0.0;
        }
        self.inner.deriv(v, self.nu).unwrap_or(f64::NAN)
    }

    /// The values at a `Float64Array`, a block at a time through two buffers
    /// that stay in the caches, instead of copying the whole array into the
    /// module's memory and the whole result out of it.
    fn values_of_array(&self, xs: &Float64Array) -> Result<Float64Array, JsValue> {
        // 64 Ki queries a block: every block still forms the search index of
        // a spline up to 2 Mi knots (a batch forms it from N / 32 queries).
        const BLOCK: u32 = 1 << 16;
        let n = xs.length();
        let out = Float64Array::new_with_length(n);
        let size = n.min(BLOCK) as usize;
        let (mut x, mut y) = (vec![0.0; size], vec![0.0; size]);
        let mut lo = 0;
        while lo < n {
            let hi = n.min(lo + BLOCK);
            let len = (hi - lo) as usize;
            xs.subarray(lo, hi).copy_to(&mut x[..len]);
            self.values(&x[..len], &mut y[..len])?;
            out.subarray(lo, hi).copy_from(&y[..len]);
            lo = hi;
        }
        Ok(out)
    }

    fn values(&self, xs: &[f64], out: &mut [f64]) -> Result<(), JsValue> {
        if self.nu <= 3 && self.inner.deriv_many(xs, self.nu, out).is_ok() {
            if self.outside == Extrapolate::Nan {
                for (o, &v) in out.iter_mut().zip(xs) {
                    if self.outside_nan(v) {
                        *o = f64::NAN;
                    }
                }
            }
            return Ok(());
        }
        for (o, &v) in out.iter_mut().zip(xs) {
            *o = self.value(v);
        }
        Ok(())
    }
}
