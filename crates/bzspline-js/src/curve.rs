//! `Curve`: the method's curve through control points in the plane or in
//! space, open or closed, for JavaScript.

use bzspline::Bounds;
use bzspline::Flatten;
use bzspline::ParamCurve;
use bzspline::{Arclen, DEFAULT_ACCURACY};
use js_sys::Float64Array;
use wasm_bindgen::prelude::*;

use crate::args::{lib_error, numbers, param_of, points, set, Options};

/// A curve in R^d by the method: each coordinate the method's spline of one
/// shared parameter; starts and ends at the end points (open), touches every
/// leg of the control polygon and stays in the points' convex hull.
#[wasm_bindgen]
pub struct Curve {
    inner: bzspline::Curve,
}

#[wasm_bindgen]
impl Curve {
    /// `new Curve(points, {closed, param, alpha, alphas, through})`: points
    /// `[[x, y], ...]` (or `[x, y, z]`), at least 2 (3 closed, without
    /// repeating the first); `param` `"centripetal"` (the default),
    /// `"chordal"`, `"uniform"` or the parameters themselves.
    #[wasm_bindgen(constructor)]
    pub fn new(pts: &JsValue, options: &JsValue) -> Result<Curve, JsValue> {
        let (flat, dim) = points(pts, "points")?;
        let o = Options::new(options)?;
        let param = param_of(&o)?;
        let alphas = o.alphas()?;
        let inner = bzspline::CurveBuilder::new(&flat, dim.max(1))
            .closed(o.flag("closed", false)?)
            .param(param)
            .alpha_choice(alphas.as_alphas())
            .through(o.flag("through", false)?)
            .build()
            .map_err(lib_error)?;
        Ok(Curve { inner })
    }

    /// The point at parameter t (a `Float64Array` of d numbers), or for an
    /// array of parameters the points flat, d numbers each (`at` in
    /// JavaScript shapes them); `nu` gives a derivative.
    #[wasm_bindgen(js_name = _at)]
    pub fn at(&self, t: &JsValue, nu: Option<u32>) -> Result<Float64Array, JsValue> {
        let nu = nu.unwrap_or(0);
        if let Some(s) = t.as_f64() {
            let p = self.inner.deriv(s, nu).map_err(lib_error)?;
            return Ok(Float64Array::from(p.as_slice()));
        }
        let ts = numbers(t, "t")?;
        let d = self.inner.dim();
        let mut out = vec![0.0; ts.len() * d];
        self.inner
            .deriv_many(&ts, nu, &mut out)
            .map_err(lib_error)?;
        Ok(Float64Array::from(out.as_slice()))
    }

    /// The parameters of the knots.
    #[wasm_bindgen(getter)]
    pub fn knots(&self) -> Float64Array {
        Float64Array::from(self.inner.knots())
    }

    /// The shape parameters, one per leg.
    #[wasm_bindgen(getter)]
    pub fn alphas(&self) -> Float64Array {
        Float64Array::from(self.inner.alphas())
    }

    /// The dimension d.
    #[wasm_bindgen(getter)]
    pub fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// True for a closed curve.
    #[wasm_bindgen(getter)]
    pub fn closed(&self) -> bool {
        self.inner.is_closed()
    }

    /// The arc length, to `accuracy` (absolute, default 1e-9).
    pub fn arclen(&self, accuracy: Option<f64>) -> Result<f64, JsValue> {
        Arclen::arclen(&self.inner, accuracy.unwrap_or(DEFAULT_ACCURACY)).map_err(lib_error)
    }

    /// `n` points (at least 2) at equal arc-length steps from start to end,
    /// flat (`resample` in JavaScript shapes them).
    #[wasm_bindgen(js_name = _resample)]
    pub fn resample(&self, n: usize, accuracy: Option<f64>) -> Result<Vec<f64>, JsValue> {
        let p = self
            .inner
            .resample(n, accuracy.unwrap_or(DEFAULT_ACCURACY))
            .map_err(lib_error)?;
        Ok(p.coords().to_vec())
    }

    /// The point of the curve nearest to `p`: `{t, point, distance}`.
    pub fn nearest(&self, p: &JsValue) -> Result<JsValue, JsValue> {
        let q = numbers(p, "p")?;
        let n = self.inner.nearest(&q).map_err(lib_error)?;
        let o = js_sys::Object::new();
        set(&o, "t", n.param.into());
        set(&o, "point", Float64Array::from(n.point.as_slice()).into());
        set(&o, "distance", n.distance.into());
        Ok(o.into())
    }

    /// The exact bounding box of the curve: `{min, max}`, each of d numbers.
    pub fn bbox(&self) -> JsValue {
        let b = self.inner.bbox();
        let o = js_sys::Object::new();
        set(&o, "min", Float64Array::from(b.min.as_slice()).into());
        set(&o, "max", Float64Array::from(b.max.as_slice()).into());
        o.into()
    }

    /// A polyline within `tolerance` of the curve, from its start to its end,
    /// flat (`flatten` in JavaScript shapes it).
    #[wasm_bindgen(js_name = _flatten)]
    pub fn flatten(&self, tolerance: f64) -> Result<Vec<f64>, JsValue> {
        let p = self.inner.flatten(tolerance).map_err(lib_error)?;
        Ok(p.coords().to_vec())
    }

    /// Every segment's four control points, flat (`4 d` numbers a segment;
    /// `segments` in JavaScript shapes them).
    #[wasm_bindgen(js_name = _segments)]
    pub fn segments(&self) -> Vec<f64> {
        (0..self.inner.len())
            .filter_map(|k| self.inner.segment_points(k))
            .flatten()
            .collect()
    }

    /// SVG path data of a planar curve, exactly: `M x y C ...` (with `Z`
    /// for a closed curve).
    #[wasm_bindgen(js_name = svgPath)]
    pub fn svg_path(&self) -> Result<String, JsValue> {
        self.inner.to_svg_path().map_err(lib_error)
    }
}
