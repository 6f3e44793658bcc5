//! The data-independent description of a fit ([`FitSpec`]), the fitted spline
//! ([`Fitted`]) and its JSON form. The `fit`, `plot` and `serve` commands all go
//! through [`build`] and [`fit_json`].

use bzspline::{Alphas, CubicBez, Curve, CurveBuilder, Param, Spline};
use serde_json::{json, Value};

/// What the rows of the input are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Samples `(x, y)` of a function `y(x)`.
    Function,
    /// Control points of a parametric curve in 2D or 3D.
    Curve,
}

/// How curve parameters (knots) are chosen from the control points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamKind {
    /// `tau_i = i`.
    Uniform,
    /// `h_i = |P_i - P_{i-1}|`.
    Chordal,
    /// `h_i = |P_i - P_{i-1}|^(1/2)`.
    Centripetal,
}

/// Everything needed to build a spline.
#[derive(Debug, Clone, PartialEq)]
pub struct FitSpec {
    /// The rows: `[x, y]` for a function, the coordinates for a curve.
    pub points: Vec<Vec<f64>>,
    /// Function or curve.
    pub mode: Mode,
    /// Closed curve (ignored for functions).
    pub closed: bool,
    /// Curve parametrisation (ignored for functions).
    pub param: ParamKind,
    /// One alpha for every interval (default 1/2).
    pub alpha: Option<f64>,
    /// One alpha per interval (per leg of a curve, the closing leg last);
    /// takes precedence over `alpha`.
    pub alphas: Option<Vec<f64>>,
}

/// A fitted spline.
#[derive(Debug, Clone, PartialEq)]
pub enum Fitted {
    /// A function `y(x)`.
    Function(Spline),
    /// A parametric curve in 2D or 3D, open or closed.
    Curve(Curve),
}

/// Builds the spline described by `spec`.
///
/// # Errors
///
/// The library's error, with 0-based row indices, for too few points, non-finite
/// or non-increasing x, or bad alphas; [`bzspline::Error::LengthMismatch`] (field
/// `points`) when a row of a function is not a pair (callers that know lines
/// check the columns first, see `input::check_columns`).
pub fn build(spec: &FitSpec) -> Result<Fitted, bzspline::Error> {
    match spec.mode {
        Mode::Function => {
            let mut xs = Vec::with_capacity(spec.points.len());
            let mut ys = Vec::with_capacity(spec.points.len());
            for p in &spec.points {
                match p.as_slice() {
                    [x, y] => {
                        xs.push(*x);
                        ys.push(*y);
                    }
                    _ => {
                        return Err(bzspline::Error::LengthMismatch {
                            field: bzspline::Field::Coordinate,
                            expected: 2,
                            found: p.len(),
                        })
                    }
                }
            }
            let alphas = match (&spec.alphas, spec.alpha) {
                (Some(a), _) => Alphas::PerInterval(a),
                (None, Some(a)) => Alphas::Uniform(a),
                (None, None) => Alphas::default(),
            };
            Ok(Fitted::Function(Spline::build(&xs, &ys, alphas)?))
        }
        Mode::Curve => {
            let Some(dim) = spec.points.first().map(Vec::len) else {
                return Err(bzspline::Error::TooFewPoints {
                    found: 0,
                    min: if spec.closed { 3 } else { 2 },
                });
            };
            if let Some(bad) = spec.points.iter().find(|p| p.len() != dim) {
                return Err(bzspline::Error::LengthMismatch {
                    field: bzspline::Field::Coordinate,
                    expected: dim,
                    found: bad.len(),
                });
            }
            let flat = spec.points.concat();
            let mut b = CurveBuilder::new(&flat, dim)
                .closed(spec.closed)
                .param(match spec.param {
                    ParamKind::Uniform => Param::Uniform,
                    ParamKind::Chordal => Param::Chordal,
                    ParamKind::Centripetal => Param::Centripetal,
                });
            if let Some(a) = &spec.alphas {
                b = b.alphas(a);
            } else if let Some(a) = spec.alpha {
                b = b.alpha(a);
            }
            Ok(Fitted::Curve(b.build()?))
        }
    }
}

/// The Bezier segments of a fit, each as four control points.
#[must_use]
pub fn segments(f: &Fitted) -> Vec<Vec<Vec<f64>>> {
    match f {
        Fitted::Function(s) => s.segments().iter().map(bez_points).collect(),
        Fitted::Curve(c) => (0..c.len())
            .filter_map(|k| c.segment_points(k))
            .map(|flat| flat.chunks(c.dim()).map(<[f64]>::to_vec).collect())
            .collect(),
    }
}

fn bez_points<const D: usize>(b: &CubicBez<D>) -> Vec<Vec<f64>> {
    b.p.iter().map(|p| p.to_vec()).collect()
}

/// The SVG path (`M x y C ...`) of planar segments; `None` for 3D ones.
#[must_use]
pub fn svg_path(segments: &[Vec<Vec<f64>>]) -> Option<String> {
    use std::fmt::Write;
    let mut out = String::new();
    for (k, seg) in segments.iter().enumerate() {
        let pts: Vec<(f64, f64)> = seg
            .iter()
            .map(|p| match p.as_slice() {
                [x, y] => Some((*x, *y)),
                _ => None,
            })
            .collect::<Option<_>>()?;
        if pts.len() != 4 {
            return None;
        }
        if k == 0 {
            let _ = write!(out, "M {} {}", pts[0].0, pts[0].1);
        }
        let _ = write!(
            out,
            " C {} {} {} {} {} {}",
            pts[1].0, pts[1].1, pts[2].0, pts[2].1, pts[3].0, pts[3].1
        );
    }
    Some(out)
}

/// The SVG path of a planar fit (a closed curve's ends with `Z`); `None` in 3D.
#[must_use]
pub fn svg(f: &Fitted) -> Option<String> {
    match f {
        Fitted::Function(_) => svg_path(&segments(f)),
        Fitted::Curve(c) if c.dim() == 2 => c.to_svg_path().ok(),
        Fitted::Curve(_) => None,
    }
}

/// The `fit` JSON object: `mode` (`function` or `curve`), `closed`,
/// `dimension` (1 for a function, else the number of coordinates), `knots`,
/// `alphas`, `values` (the control values or points), `knot_values`,
/// `tangent_points` (`[x, f]` for a function, points for a curve; a curve also
/// has `tangent_params`), `segments` (four control points each) and `svg_path`
/// (null in 3D). A closed curve has N + 1 knots and N + 1 knot values, the last
/// equal to the first. Numbers are printed so that they parse back to the same
/// double.
#[must_use]
pub fn fit_json(f: &Fitted) -> Value {
    let segs = segments(f);
    match f {
        Fitted::Function(s) => {
            let svg = svg_path(&segs);
            let tangent: Vec<[f64; 2]> = s.tangent_points().iter().map(|&(x, y)| [x, y]).collect();
            json!({
                "mode": "function",
                "closed": false,
                "dimension": 1,
                "knots": s.knots(),
                "alphas": s.alphas(),
                "values": s.values(),
                "knot_values": s.knot_values(),
                "tangent_points": tangent,
                "segments": segs,
                "svg_path": svg,
            })
        }
        Fitted::Curve(c) => {
            let dim = c.dim();
            let values: Vec<&[f64]> = c.points().chunks(dim).collect();
            let mut knot_values = c.knot_points();
            if c.is_closed() {
                if let Some(first) = knot_values.first().cloned() {
                    knot_values.push(first);
                }
            }
            let tangents = c.tangent_points();
            let params: Vec<f64> = tangents.iter().map(|(t, _)| *t).collect();
            let points: Vec<&Vec<f64>> = tangents.iter().map(|(_, p)| p).collect();
            let svg = svg(f);
            json!({
                "mode": "curve",
                "closed": c.is_closed(),
                "dimension": dim,
                "knots": c.knots(),
                "alphas": c.alphas(),
                "values": values,
                "knot_values": knot_values,
                "tangent_params": params,
                "tangent_points": points,
                "segments": segs,
                "svg_path": svg,
            })
        }
    }
}

/// True when every number in `v` is finite (JSON cannot carry NaN or inf, and
/// `serde_json` would print them as `null`).
#[must_use]
pub fn all_finite(rows: &[Vec<f64>]) -> bool {
    rows.iter().flatten().all(|v| v.is_finite())
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
    fn fit_json_has_the_documented_keys_and_lengths() {
        let fitted = build(&example1()).unwrap();
        let v = fit_json(&fitted);
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
            assert!(v.get(key).is_some(), "missing key {key}");
        }
        assert_eq!(v["knots"].as_array().unwrap().len(), 11);
        assert_eq!(v["segments"].as_array().unwrap().len(), 10);
        let path = v["svg_path"].as_str().unwrap();
        assert!(path.starts_with("M 1 1 C "), "{path}");
        assert_eq!(path.matches(" C ").count(), 10);
    }

    #[test]
    fn a_row_of_three_numbers_is_refused_for_a_function() {
        let mut spec = example1();
        spec.points[3].push(0.0);
        let e = build(&spec).unwrap_err();
        assert!(
            matches!(e, bzspline::Error::LengthMismatch { found: 3, .. }),
            "{e:?}"
        );
    }
}
