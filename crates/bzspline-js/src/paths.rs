//! The Bezier control points the d3 curves draw: for a run of points, the
//! start of the first piece and every piece's three control points after its
//! start, flat (`x0, y0`, then `x1, y1, x2, y2, x3, y3` per piece), or an
//! empty array when the run cannot be drawn so (the
//! JavaScript side then draws straight lines; a d3 curve never throws); and
//! the factories' checks of their parameters.

use bzspline::{Alphas, Param, Repeats};
use wasm_bindgen::prelude::*;

use crate::args::{alpha_value, range_error};

/// The pieces of y = S(x) through the control points (x strictly
/// increasing): `alpha` in [1/3, 2/3], `through` for the interpolating
/// variant.
#[wasm_bindgen(js_name = splinePieces)]
pub fn spline_pieces(x: &[f64], y: &[f64], alpha: f64, through: bool) -> Vec<f64> {
    let built = if through {
        bzspline::Spline::through(x, y, Alphas::Uniform(alpha))
    } else {
        bzspline::Spline::build(x, y, Alphas::Uniform(alpha))
    };
    let Ok(s) = built else {
        return Vec::new();
    };
    let mut out = Vec::with_capacity(2 + 6 * s.len());
    for b in (0..s.len()).filter_map(|k| s.segment(k)) {
        if out.is_empty() {
            out.extend_from_slice(&b.p[0]);
        }
        for p in &b.p[1..] {
            out.extend_from_slice(p);
        }
    }
    out
}

/// The pieces of the planar curve through the points (flat `x0, y0, x1,
/// y1, ...`), open or closed, repeated consecutive points dropped; `param` a
/// parametrisation's name.
#[wasm_bindgen(js_name = curvePieces)]
pub fn curve_pieces(
    points: &[f64],
    closed: bool,
    param: &str,
    alpha: f64,
    through: bool,
) -> Vec<f64> {
    let Ok(param) = param.parse::<Param>() else {
        return Vec::new();
    };
    let built = bzspline::CurveBuilder::new(points, 2)
        .closed(closed)
        .param(param)
        .alpha(alpha)
        .repeats(Repeats::Drop)
        .through(through)
        .build();
    let Ok(c) = built else {
        return Vec::new();
    };
    let mut out = Vec::with_capacity(2 + 6 * c.len());
    for k in 0..c.len() {
        if let Some(p) = c.segment_points(k) {
            out.extend_from_slice(if k == 0 { &p } else { &p[2..] });
        }
    }
    out
}

/// An alpha for the d3 curve factories, checked at once: as
/// `alpha_value`, and by [`bzspline::check_alpha`].
#[wasm_bindgen(js_name = checkAlpha)]
pub fn check_alpha(v: &JsValue) -> Result<f64, JsValue> {
    let a = alpha_value(v)?;
    bzspline::check_alpha(a).map_err(|_| range_error(format!("alpha = {a} is outside [1/3, 2/3]")))
}

/// A parametrisation's name for the d3 curve factories, checked at once by
/// [`bzspline::Param`]'s own parser.
#[wasm_bindgen(js_name = checkParam)]
pub fn check_param(name: &str) -> Result<String, JsValue> {
    name.parse::<bzspline::Param>()
        .map(|_| name.to_owned())
        .map_err(range_error)
}
