//! The fit the editor asks for, built with the library.
//!
//! This mirrors the shape of the command line's model (`FitSpec`, `build`,
//! `fit_json`) so that the server can switch to it by changing its imports. Until
//! the library has parametric curves, an open curve is fitted here coordinate by
//! coordinate with [`Spline`] on one shared parameter grid (the construction the
//! method describes for curves); closed curves are refused with a message.

use bzspline::{CubicBez, Error, Spline};
use serde_json::{json, Value};

/// Whether the points are samples of a function `y(x)` or vertices of a curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// `points[i] = [x_i, y_i]` with increasing `x`.
    Function,
    /// `points[i]` is a control point of a parametric curve.
    Curve,
}

/// How curve parameters are spaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    /// `tau_i = i`.
    Uniform,
    /// Steps equal to the leg lengths.
    Chordal,
    /// Steps equal to the square roots of the leg lengths.
    Centripetal,
}

/// Everything needed to build one fit.
#[derive(Clone, Debug, PartialEq)]
pub struct FitSpec {
    /// The control points.
    pub points: Vec<Vec<f64>>,
    /// Function or curve.
    pub mode: Mode,
    /// Whether a curve closes on itself.
    pub closed: bool,
    /// Curve parameters.
    pub param: ParamKind,
    /// One shape parameter for every interval.
    pub alpha: Option<f64>,
    /// One shape parameter per interval.
    pub alphas: Option<Vec<f64>>,
}

/// A built fit.
#[derive(Clone, Debug)]
pub enum Fitted {
    /// A function `y(x)`.
    Function(Spline),
    /// An open plane curve: one spline per coordinate on shared parameters.
    Curve {
        /// `x(t)`.
        x: Spline,
        /// `y(t)`.
        y: Spline,
    },
}

/// Builds the fit `spec` describes.
///
/// # Errors
///
/// The library's error for the points and alphas, or
/// [`Error::InvalidArgument`] for a closed curve (not supported yet) or a point
/// that is not in the plane.
pub fn build(spec: &FitSpec) -> Result<Fitted, Error> {
    if let Some(bad) = spec.points.iter().position(|p| p.len() != 2) {
        return Err(Error::InvalidArgument {
            what: "every point needs exactly 2 coordinates",
            value: bad as f64,
        });
    }
    let xs: Vec<f64> = spec.points.iter().map(|p| p[0]).collect();
    let ys: Vec<f64> = spec.points.iter().map(|p| p[1]).collect();
    let with = |knots: &[f64], values: &[f64]| match (&spec.alphas, spec.alpha) {
        (Some(a), _) => Spline::with_alphas(knots, values, a),
        (None, Some(a)) => Spline::with_alpha(knots, values, a),
        (None, None) => Spline::new(knots, values),
    };
    match spec.mode {
        Mode::Function => with(&xs, &ys).map(Fitted::Function),
        Mode::Curve if spec.closed => Err(Error::InvalidArgument {
            what: "closed curves are not available in this build",
            value: spec.points.len() as f64,
        }),
        Mode::Curve => {
            let tau = parameters(&spec.points, spec.param)?;
            Ok(Fitted::Curve {
                x: with(&tau, &xs)?,
                y: with(&tau, &ys)?,
            })
        }
    }
}

/// Parameter values for the points of an open curve.
fn parameters(points: &[Vec<f64>], kind: ParamKind) -> Result<Vec<f64>, Error> {
    let mut tau = Vec::with_capacity(points.len());
    let mut t = 0.0;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            let q = &points[i - 1];
            let len = (p[0] - q[0]).hypot(p[1] - q[1]);
            let step = match kind {
                ParamKind::Uniform => 1.0,
                ParamKind::Chordal => len,
                ParamKind::Centripetal => len.sqrt(),
            };
            if step.is_nan() || step <= 0.0 {
                return Err(Error::RepeatedPoint { index: i });
            }
            t += step;
        }
        tau.push(t);
    }
    Ok(tau)
}

/// The plane segments of a fit.
fn segments(f: &Fitted) -> Vec<CubicBez<2>> {
    match f {
        Fitted::Function(s) => s.segments(),
        Fitted::Curve { x, y } => x
            .segments()
            .iter()
            .zip(y.segments())
            .map(|(sx, sy)| CubicBez::new(core::array::from_fn(|j| [sx.p[j][1], sy.p[j][1]])))
            .collect(),
    }
}

/// An SVG path of exact cubic segments (`M` then one `C` per piece).
fn svg_path(segs: &[CubicBez<2>]) -> String {
    let mut d = String::new();
    for (k, s) in segs.iter().enumerate() {
        if k == 0 {
            d.push_str(&format!("M{} {}", s.p[0][0], s.p[0][1]));
        }
        d.push_str(&format!(
            " C{} {} {} {} {} {}",
            s.p[1][0], s.p[1][1], s.p[2][0], s.p[2][1], s.p[3][0], s.p[3][1]
        ));
    }
    d
}

/// The fit as JSON: `knots`, `alphas`, `knot_values`, `tangent_points`,
/// `segments`, `closed`, `dimension` and `svg_path`.
#[must_use]
pub fn fit_json(f: &Fitted) -> Value {
    let segs = segments(f);
    let seg_json: Vec<[[f64; 2]; 4]> = segs.iter().map(|s| s.p).collect();
    match f {
        Fitted::Function(s) => json!({
            "knots": s.knots(),
            "alphas": s.alphas(),
            "knot_values": s.knot_values(),
            "tangent_points": s.tangent_points().iter().map(|&(x, y)| [x, y]).collect::<Vec<_>>(),
            "segments": seg_json,
            "closed": false,
            "dimension": 1,
            "svg_path": svg_path(&segs),
        }),
        Fitted::Curve { x, y } => {
            let kv: Vec<[f64; 2]> = x
                .knot_values()
                .into_iter()
                .zip(y.knot_values())
                .map(|(a, b)| [a, b])
                .collect();
            let tp: Vec<[f64; 2]> = x
                .tangent_points()
                .into_iter()
                .zip(y.tangent_points())
                .map(|((_, a), (_, b))| [a, b])
                .collect();
            json!({
                "knots": x.knots(),
                "alphas": x.alphas(),
                "knot_values": kv,
                "tangent_points": tp,
                "segments": seg_json,
                "closed": false,
                "dimension": 2,
                "svg_path": svg_path(&segs),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example1() -> FitSpec {
        let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
        FitSpec {
            points: f
                .iter()
                .enumerate()
                .map(|(i, &y)| vec![i as f64 + 1.0, y])
                .collect(),
            mode: Mode::Function,
            closed: false,
            param: ParamKind::Uniform,
            alpha: None,
            alphas: None,
        }
    }

    #[test]
    fn function_fit_json_has_every_key_and_exact_ends() {
        let v = fit_json(&build(&example1()).unwrap());
        for key in [
            "knots",
            "alphas",
            "knot_values",
            "tangent_points",
            "segments",
            "closed",
            "dimension",
            "svg_path",
        ] {
            assert!(v.get(key).is_some(), "missing {key} in {v}");
        }
        assert_eq!(v["knot_values"][0], 1.0);
        assert_eq!(v["knot_values"][10], 1.5);
        let d = v["svg_path"].as_str().unwrap();
        assert!(d.starts_with("M1 1 C"), "{d}");
        assert_eq!(d.matches('C').count(), 10, "{d}");
    }

    #[test]
    fn open_curve_touches_each_leg_and_rejects_repeats() {
        let mut spec = example1();
        spec.mode = Mode::Curve;
        spec.param = ParamKind::Chordal;
        let v = fit_json(&build(&spec).unwrap());
        assert_eq!(v["dimension"], 2);
        assert_eq!(v["knot_values"][0], json!([1.0, 1.0]));
        spec.points[3] = spec.points[2].clone();
        assert_eq!(
            build(&spec).unwrap_err(),
            Error::RepeatedPoint { index: 3 },
            "a repeated point must be refused"
        );
    }
}
