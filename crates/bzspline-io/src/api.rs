//! `POST /api/fit`: the request body, its validation and the response.

use serde::Deserialize;
use serde_json::{json, Value};

use bzspline::{AlphaChoice, BezierPieces, CubicBez, Param};

use crate::model::{self, FitSpec, Mode, Shape};

/// A refused request: the HTTP status and a message for the JSON body.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApiError {
    /// The status code.
    pub status: u16,
    /// What was wrong, in words.
    pub message: String,
}

impl ApiError {
    /// A refusal with `status` and `message`. Control characters (which can
    /// come from the request, in a field name quoted by the JSON reader) are
    /// escaped, so that the message stays one line in the server's log.
    pub fn new(status: u16, message: impl Into<String>) -> Self {
        let message: String = message.into();
        let message = if message.chars().any(char::is_control) {
            message
                .chars()
                .map(|c| {
                    if c.is_control() {
                        c.escape_default().to_string()
                    } else {
                        c.to_string()
                    }
                })
                .collect()
        } else {
            message
        };
        ApiError { status, message }
    }

    /// The JSON body: `{"error": message, "status": status}`.
    #[must_use]
    pub fn body(&self) -> Value {
        json!({ "error": self.message, "status": self.status })
    }
}

/// The request body as sent; every field but `points` is optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRequest {
    points: Vec<Vec<Value>>,
    #[serde(default)]
    mode: Option<String>,
    #[serde(default)]
    closed: Option<bool>,
    #[serde(default)]
    param: Option<String>,
    #[serde(default)]
    alpha: Option<Value>,
    #[serde(default)]
    alphas: Option<Vec<Value>>,
    #[serde(default)]
    samples: Option<usize>,
    /// Through the points (the interpolating variant).
    #[serde(default)]
    through: Option<bool>,
    /// A smoothing fit: `"auto"` or a lambda (as `--smooth`).
    #[serde(default)]
    smooth: Option<Value>,
    /// One weight per point for the smoothing fit (as `--weights`).
    #[serde(default)]
    weights: Option<Vec<Value>>,
    /// The smoothing fit made robust (as `--robust`).
    #[serde(default)]
    robust: Option<bool>,
}

/// A validated request.
#[derive(Debug, Clone, PartialEq)]
pub struct FitRequest {
    /// What to build.
    pub spec: FitSpec<'static>,
    /// Samples per segment for the curvature comb (0 for none).
    pub samples: usize,
}

/// Limits applied while parsing.
#[derive(Debug, Clone, Copy)]
pub struct ParseLimits {
    /// Most control points accepted.
    pub max_points: usize,
    /// Most comb samples accepted in total.
    pub max_samples: usize,
}

fn number(v: &Value, what: impl Fn() -> String) -> Result<f64, ApiError> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(ApiError::new(
            422,
            format!(
                "{} = {v} is not a finite number (JSON has no NaN or infinity; JSON.stringify writes them as null)",
                what()
            ),
        )),
    }
}

/// A shape parameter: a number, or a string holding a decimal or a fraction
/// (`"1/3"`).
fn alpha_of(v: &Value, what: impl Fn() -> String) -> Result<f64, ApiError> {
    match v {
        Value::String(text) => crate::options::parse_fraction(text)
            .map_err(|e| ApiError::new(422, format!("{}: {e}", what()))),
        _ => number(v, what),
    }
}

/// Parses and checks a request body.
///
/// # Errors
///
/// 400 when the body is not JSON, 422 when it is JSON of the wrong shape, has a
/// value that is not a finite number, an unknown `mode` or `param`, or more
/// points or samples than `limits` allow.
pub fn parse(body: &[u8], limits: ParseLimits) -> Result<FitRequest, ApiError> {
    let value: Value = serde_json::from_slice(body)
        .map_err(|e| ApiError::new(400, format!("the body is not valid JSON: {e}")))?;
    let raw: RawRequest = serde_json::from_value(value).map_err(|e| {
        ApiError::new(
            422,
            format!("the request does not have the expected fields: {e}"),
        )
    })?;
    if raw.points.len() > limits.max_points {
        return Err(ApiError::new(
            422,
            format!(
                "{} points exceed the limit of {} (--max-points)",
                raw.points.len(),
                limits.max_points
            ),
        ));
    }
    let mut points = Vec::with_capacity(2 * raw.points.len());
    for (i, p) in raw.points.iter().enumerate() {
        if p.len() != 2 {
            return Err(ApiError::new(
                422,
                format!("points[{i}] has {} coordinates, expected 2", p.len()),
            ));
        }
        for (j, c) in p.iter().enumerate() {
            points.push(number(c, || format!("points[{i}][{j}]"))?);
        }
    }
    let mode = match raw.mode.as_deref() {
        None | Some("function") => Mode::Function,
        Some("curve") => Mode::Curve,
        Some(other) => {
            return Err(ApiError::new(
                422,
                format!("mode {other:?} is not \"function\" or \"curve\""),
            ))
        }
    };
    let param = match raw.param.as_deref() {
        None => Param::default(),
        Some(name) => name
            .parse()
            .map_err(|e| ApiError::new(422, format!("param {e}")))?,
    };
    let alpha = match &raw.alpha {
        None | Some(Value::Null) => None,
        Some(v) => Some(alpha_of(v, || "alpha".to_owned())?),
    };
    let alphas = match &raw.alphas {
        None => None,
        Some(list) => Some(
            list.iter()
                .enumerate()
                .map(|(k, v)| alpha_of(v, || format!("alphas[{k}]")))
                .collect::<Result<Vec<f64>, ApiError>>()?,
        ),
    };
    let smoothing = match &raw.smooth {
        None | Some(Value::Null) => None,
        Some(Value::String(text)) => Some(
            crate::options::parse_smoothing(text)
                .map_err(|e| ApiError::new(422, format!("smooth {e}")))?,
        ),
        Some(v) => {
            let l = number(v, || "smooth".to_owned())?;
            Some(bzspline::Smoothing::Lambda(l).check().map_err(|_| {
                ApiError::new(
                    422,
                    format!("smooth {} (got {l})", crate::options::LAMBDA_RULE),
                )
            })?)
        }
    };
    let weights = match &raw.weights {
        None => None,
        Some(list) => Some(
            list.iter()
                .enumerate()
                .map(|(j, v)| number(v, || format!("weights[{j}]")))
                .collect::<Result<Vec<f64>, ApiError>>()?,
        ),
    };
    let robust = raw.robust.unwrap_or(false);
    if (robust || weights.is_some()) && smoothing.is_none() {
        return Err(ApiError::new(
            422,
            "weights and robust are for a smoothing fit: give smooth too",
        ));
    }
    let samples = raw.samples.unwrap_or(0);
    let total = samples.saturating_mul(raw.points.len());
    if total > limits.max_samples {
        return Err(ApiError::new(
            422,
            format!(
                "{samples} samples per segment on {} points exceed the limit of {} samples (--max-samples)",
                raw.points.len(),
                limits.max_samples
            ),
        ));
    }
    Ok(FitRequest {
        spec: FitSpec {
            points: points.into(),
            dim: 2,
            weights: weights.map(Into::into),
            shape: Shape {
                mode,
                closed: raw.closed.unwrap_or(false),
                param,
                // One per interval takes precedence over one for all.
                alphas: match (alphas, alpha) {
                    (Some(each), _) => AlphaChoice::Each(each),
                    (None, Some(one)) => AlphaChoice::One(one),
                    (None, None) => AlphaChoice::default(),
                },
                through: raw.through.unwrap_or(false),
                smoothing,
                robust,
            },
        },
        samples,
    })
}

/// Builds the fit and its JSON, with the curvature comb when asked for and
/// `build_ms`, the milliseconds the library took to build the fit.
///
/// # Errors
///
/// 422 with the library's message when the library refuses the data.
pub fn fit(req: &FitRequest) -> Result<Value, ApiError> {
    let started = std::time::Instant::now();
    let (fitted, report) =
        model::build_reported(&req.spec).map_err(|e| ApiError::new(422, e.to_string()))?;
    let build_ms = started.elapsed().as_secs_f64() * 1e3;
    let mut out = model::fit_json(&fitted, report);
    out["build_ms"] = json!(build_ms);
    if req.samples > 0 {
        out["comb"] = comb(fitted.pieces(), req.samples);
    }
    Ok(out)
}

/// Samples of the signed curvature along the planar segments of a fit:
/// `[x, y, nx, ny, k]` with the unit normal `(nx, ny)` (the tangent turned
/// left) and the curvature `k` at the point `(x, y)`, `samples + 1` per
/// segment (none for a curve in space).
fn comb(pieces: &dyn BezierPieces, samples: usize) -> Value {
    let count = pieces.piece_count();
    let mut teeth = Vec::with_capacity(count.saturating_mul(samples.saturating_add(1)));
    let mut c = [0.0; 8];
    for k in 0..count {
        if !pieces.piece_into(k, &mut c) {
            continue;
        }
        let s = CubicBez::new(core::array::from_fn(|j| [c[2 * j], c[2 * j + 1]]));
        for i in 0..=samples {
            let t = i as f64 / samples as f64;
            let p = s.eval(t);
            let d = s.deriv(t);
            let dd = s.deriv2(t);
            let speed = d[0].hypot(d[1]);
            if !speed.is_finite() || speed <= 0.0 {
                continue;
            }
            let k = (d[0] * dd[1] - d[1] * dd[0]) / (speed * speed * speed);
            if k.is_finite() {
                teeth.push([p[0], p[1], -d[1] / speed, d[0] / speed, k]);
            }
        }
    }
    json!(teeth)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: ParseLimits = ParseLimits {
        max_points: 5,
        max_samples: 100,
    };

    /// Found by the serve_api fuzz target: a field name with a newline in it
    /// was quoted into the message, which the server logs as one line.
    #[test]
    fn messages_stay_one_line_whatever_the_request_holds() {
        let body = br#"{"nti\\\no\\\npoints": [[0,0],[1,2],[3,2],[4,0]], "alphas": [0.66]}"#;
        let e = parse(body, LIMITS).unwrap_err();
        assert_eq!(e.status, 422);
        assert!(e.message.contains("unknown field"), "{}", e.message);
        assert!(!e.message.contains('\n'), "{:?}", e.message);
        assert!(e.message.contains(r"\n"), "escaped: {:?}", e.message);
    }

    #[test]
    fn smooth_takes_auto_or_a_lambda_and_reports_them() {
        let body = br#"{"points": [[0,0],[1,2],[2,1],[3,3],[4,2]], "smooth": "auto"}"#;
        let out = fit(&parse(body, LIMITS).unwrap()).unwrap();
        let (lambda, dof) = (
            out["lambda"].as_f64().unwrap(),
            out["dof"].as_f64().unwrap(),
        );
        assert!(lambda > 0.0 && (2.0..=5.0).contains(&dof), "{out}");
        assert!(out["gcv"].as_f64().is_some());
        let body = br#"{"points": [[0,0],[1,2],[2,1],[3,3],[4,2]], "smooth": 0.5}"#;
        let out = fit(&parse(body, LIMITS).unwrap()).unwrap();
        assert_eq!(out["lambda"].as_f64(), Some(0.5));
        for bad in [r#""lots""#, "-1", r#""-1""#] {
            let body = format!(r#"{{"points": [[0,0],[1,2],[2,1]], "smooth": {bad}}}"#);
            let e = parse(body.as_bytes(), LIMITS).unwrap_err();
            assert_eq!(e.status, 422);
            assert!(e.message.starts_with("smooth"), "{}", e.message);
        }
        // Without smooth, no smoothing keys.
        let out = fit(&parse(br#"{"points": [[0,0],[1,2],[2,1]]}"#, LIMITS).unwrap()).unwrap();
        assert!(out.get("lambda").is_none());
    }

    #[test]
    fn weights_and_robust_reach_the_library() {
        let pts = [[0.0, 0.0], [1.0, 2.0], [2.0, 1.0], [3.0, 9.0], [4.0, 2.0]];
        let (x, y): (Vec<f64>, Vec<f64>) = pts.iter().map(|p| (p[0], p[1])).unzip();
        let w = [1.0, 2.0, 1.0, 0.5, 1.0];
        let body = json!({"points": pts, "smooth": "auto", "weights": w, "robust": true});
        let out = fit(&parse(body.to_string().as_bytes(), LIMITS).unwrap()).unwrap();
        let s = bzspline::Spline::smoothing_robust(
            &x,
            &y,
            Some(&w),
            bzspline::Alphas::default(),
            bzspline::Smoothing::Gcv,
        )
        .unwrap();
        assert_eq!(out["lambda"].as_f64(), Some(s.lambda));
        assert_eq!(out["robustness"], json!(s.robustness.unwrap()));
        for (body, want) in [
            (json!({"points": pts, "weights": w}), "give smooth too"),
            (json!({"points": pts, "robust": true}), "give smooth too"),
            (
                json!({"points": pts, "smooth": "auto", "weights": [1, "a"]}),
                "weights[1]",
            ),
        ] {
            let e = parse(body.to_string().as_bytes(), LIMITS).unwrap_err();
            assert_eq!(e.status, 422);
            assert!(e.message.contains(want), "{}", e.message);
        }
        let body = json!({"points": pts, "smooth": "auto", "weights": [1, 1, -1, 1, 1]});
        let e = fit(&parse(body.to_string().as_bytes(), LIMITS).unwrap()).unwrap_err();
        assert!(e.message.contains("negative"), "{}", e.message);
    }

    #[test]
    fn refusals_carry_their_status() {
        let status = |body: &str| parse(body.as_bytes(), LIMITS).unwrap_err().status;
        assert_eq!(status("{"), 400);
        assert_eq!(status("{}"), 422);
        assert_eq!(status(r#"{"points": [[0, null], [1, 2]]}"#), 422);
        assert_eq!(
            status(r#"{"points": [[0,1],[1,2],[2,3],[3,4],[4,5],[5,6]]}"#),
            422
        );
        assert_eq!(
            status(r#"{"points": [[0,1],[1,2]], "mode": "spiral"}"#),
            422
        );
        assert_eq!(status(r#"{"points": [[0,1],[1,2]], "samples": 60}"#), 422);
    }

    #[test]
    fn alphas_may_be_fractions() {
        let body = br#"{"points": [[0,1],[1,2],[2,0]], "alpha": "1/3"}"#;
        let req = parse(body, LIMITS).unwrap();
        assert_eq!(req.spec.shape.alphas, AlphaChoice::One(bzspline::ALPHA_MIN));
        let body = br#"{"points": [[0,1],[1,2],[2,0]], "alphas": ["2/3", 0.5]}"#;
        let req = parse(body, LIMITS).unwrap();
        assert_eq!(
            req.spec.shape.alphas,
            AlphaChoice::Each(vec![2.0 / 3.0, 0.5])
        );
        assert!(fit(&req).is_ok());
        let body = br#"{"points": [[0,1],[1,2],[2,0]], "alpha": "1/0"}"#;
        let e = parse(body, LIMITS).unwrap_err();
        assert_eq!(e.status, 422);
        assert!(e.message.starts_with("alpha: "), "{}", e.message);
    }

    #[test]
    fn alpha_out_of_range_is_the_library_message() {
        let req = parse(br#"{"points": [[0,1],[1,2],[2,0]], "alpha": 0.9}"#, LIMITS).unwrap();
        let e = fit(&req).unwrap_err();
        assert_eq!(e.status, 422);
        assert!(e.message.contains("outside [1/3, 2/3]"), "{}", e.message);
    }

    #[test]
    fn comb_teeth_lie_on_the_fitted_curve() {
        let body = br#"{"points": [[0,1],[1,3],[2,0],[4,2]], "samples": 5}"#;
        let req = parse(body, LIMITS).unwrap();
        let v = fit(&req).unwrap();
        let teeth = v["comb"].as_array().unwrap();
        assert_eq!(teeth.len(), 3 * 6, "{v}");
        let s = bzspline::Spline::new(&[0.0, 1.0, 2.0, 4.0], &[1.0, 3.0, 0.0, 2.0]).unwrap();
        for t in teeth {
            let (x, y) = (t[0].as_f64().unwrap(), t[1].as_f64().unwrap());
            assert!((s.eval(x).unwrap() - y).abs() < 1e-12, "({x}, {y})");
            let (nx, ny) = (t[2].as_f64().unwrap(), t[3].as_f64().unwrap());
            assert!((nx.hypot(ny) - 1.0).abs() < 1e-12);
            // The normal is the tangent (1, S') turned left.
            let d = s.deriv(x, 1).unwrap();
            assert!((nx * 1.0 + ny * d).abs() < 1e-9 && ny > 0.0);
        }
    }

    #[test]
    fn comb_of_a_straight_polygon_is_flat() {
        let req = parse(br#"{"points": [[0,0],[1,1],[2,2]], "samples": 4}"#, LIMITS).unwrap();
        let v = fit(&req).unwrap();
        let teeth = v["comb"].as_array().unwrap();
        assert_eq!(teeth.len(), 10, "{v}");
        for t in teeth {
            assert!(
                t[4].as_f64().unwrap().abs() < 1e-12,
                "curvature of a line: {t}"
            );
        }
    }
}
