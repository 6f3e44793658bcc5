//! The data-independent description of a fit ([`FitSpec`]), the fitted spline
//! ([`Fitted`]) and its JSON form. The `fit`, `plot` and `serve` commands all go
//! through [`build`] and [`fit_json`].

use std::borrow::Cow;
use std::fmt;

use bzspline::{
    AlphaChoice, Arclen, BezierPieces, Curve, CurveBuilder, Flatten, Param, ParamCurve, Smoothing,
    Spline,
};
use serde::Serialize;
use serde_json::Value;

/// What the rows of the input are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Samples `(x, y)` of a function `y(x)`.
    Function,
    /// Control points of a parametric curve in 2D or 3D.
    Curve,
}

/// How to fit points: everything but the points themselves. The command's
/// options, the server's request and the bindings all come to this.
#[derive(Debug, Clone, PartialEq)]
pub struct Shape {
    /// Function or curve.
    pub mode: Mode,
    /// Closed curve (ignored for functions).
    pub closed: bool,
    /// Curve parametrisation (ignored for functions).
    pub param: Param,
    /// One alpha for every interval (default 1/2), or one per interval (per
    /// leg of a curve, the closing leg last).
    pub alphas: AlphaChoice,
    /// Through the points (the interpolating variant) instead of touching the
    /// legs of their polygon.
    pub through: bool,
    /// A smoothing fit of the points as noisy data (`docs/method.md` §12)
    /// instead of taking them as control points; functions and curves, open or
    /// closed.
    pub smoothing: Option<Smoothing>,
    /// The smoothing fit made robust against outliers (`docs/method.md`
    /// §14); only with `smoothing`.
    pub robust: bool,
}

impl Default for Shape {
    fn default() -> Self {
        Shape {
            mode: Mode::Function,
            closed: false,
            param: Param::default(),
            alphas: AlphaChoice::default(),
            through: false,
            smoothing: None,
            robust: false,
        }
    }
}

impl Shape {
    /// Checks what can be checked before there are points: every alpha
    /// ([`AlphaChoice::check`]), a given `lambda` ([`Smoothing::check`]) and
    /// `robust` only with `smoothing`.
    ///
    /// # Errors
    ///
    /// The library's error naming the alpha (its index) or the `lambda`;
    /// [`bzspline::Error::InvalidArgument`] for `robust` without `smoothing`.
    pub fn check(&self) -> Result<(), bzspline::Error> {
        self.alphas.check()?;
        if let Some(s) = self.smoothing {
            s.check()?;
        }
        if self.robust && self.smoothing.is_none() {
            return Err(bzspline::Error::InvalidArgument {
                what: "a robust fit is a smoothing fit: give the smoothing too",
                value: 1.0,
            });
        }
        Ok(())
    }
}

/// Everything needed to build a spline: the points and their [`Shape`].
#[derive(Debug, Clone, PartialEq)]
pub struct FitSpec<'a> {
    /// The rows, flat: `x, y` for a function, the coordinates for a curve.
    pub points: Cow<'a, [f64]>,
    /// Numbers per row.
    pub dim: usize,
    /// One weight per row for a smoothing fit (finite, `>= 0`; all 1 when
    /// `None`); ignored without [`Shape::smoothing`].
    pub weights: Option<Cow<'a, [f64]>>,
    /// How to fit them.
    pub shape: Shape,
}

/// How a smoothing fit came out: its `lambda`, GCV score and degrees of
/// freedom (the `lambda`, `gcv` and `dof` keys of the `fit` object), and what
/// its confidence bands need.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SmoothingReport {
    /// The `lambda` used (chosen, under `auto`).
    pub lambda: f64,
    /// The generalized cross-validation score at `lambda`.
    pub gcv: f64,
    /// The effective degrees of freedom (trace of the influence matrix).
    pub dof: f64,
    /// The fit's posterior, for standard errors and bands.
    #[serde(skip)]
    pub posterior: bzspline::Posterior,
    /// A robust fit's robustness weight of each row
    /// ([`bzspline::Smoothed::robustness`]); the `robustness` key.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robustness: Option<Vec<f64>>,
}

impl<T> From<&bzspline::Smoothed<T>> for SmoothingReport {
    fn from(s: &bzspline::Smoothed<T>) -> Self {
        SmoothingReport {
            lambda: s.lambda,
            gcv: s.gcv,
            dof: s.dof,
            posterior: s.posterior.clone(),
            robustness: s.robustness.clone(),
        }
    }
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
pub fn build(spec: &FitSpec<'_>) -> Result<Fitted, bzspline::Error> {
    build_reported(spec).map(|(f, _)| f)
}

/// [`build`], with the [`SmoothingReport`] of a smoothing fit.
///
/// # Errors
///
/// As [`build`], and the library's refusals of a smoothing fit (fewer than 3
/// points, a closed curve).
pub fn build_reported(
    spec: &FitSpec<'_>,
) -> Result<(Fitted, Option<SmoothingReport>), bzspline::Error> {
    let rows = spec.points.len().checked_div(spec.dim).unwrap_or(0);
    let shape = &spec.shape;
    let alphas = shape.alphas.as_alphas();
    match shape.mode {
        Mode::Function => {
            if spec.dim != 2 && rows > 0 {
                return Err(bzspline::Error::LengthMismatch {
                    field: bzspline::Field::Coordinate,
                    expected: 2,
                    found: spec.dim,
                });
            }
            let (xs, ys): (Vec<f64>, Vec<f64>) =
                spec.points.chunks_exact(2).map(|p| (p[0], p[1])).unzip();
            if let Some(how) = shape.smoothing {
                let w = spec.weights.as_deref();
                let s = if shape.robust {
                    Spline::smoothing_robust(&xs, &ys, w, alphas, how)?
                } else {
                    Spline::smoothing(&xs, &ys, w, alphas, how)?
                };
                let report = SmoothingReport::from(&s);
                return Ok((Fitted::Function(s.fit), Some(report)));
            }
            Ok((
                Fitted::Function(if shape.through {
                    Spline::through(&xs, &ys, alphas)?
                } else {
                    Spline::build(&xs, &ys, alphas)?
                }),
                None,
            ))
        }
        Mode::Curve => {
            if rows == 0 {
                return Err(bzspline::Error::TooFewPoints {
                    found: 0,
                    min: if shape.closed { 3 } else { 2 },
                });
            }
            let b = CurveBuilder::new(&spec.points, spec.dim)
                .closed(shape.closed)
                .param(shape.param.clone())
                .alpha_choice(alphas)
                .through(shape.through);
            if let Some(how) = shape.smoothing {
                let mut b = b.smoothing(how).robust(shape.robust);
                if let Some(w) = &spec.weights {
                    b = b.weights(w);
                }
                let s = b.build_smoothed()?;
                let report = SmoothingReport::from(&s);
                return Ok((Fitted::Curve(s.fit), Some(report)));
            }
            Ok((Fitted::Curve(b.build()?), None))
        }
    }
}

impl Fitted {
    /// The fit as a curve: a function as its graph `x -> (x, S(x))`.
    #[must_use]
    pub fn curve(&self) -> &dyn ParamCurve {
        match self {
            Fitted::Function(s) => s,
            Fitted::Curve(c) => c,
        }
    }

    /// Its pieces, as cubic Bezier segments.
    #[must_use]
    pub fn pieces(&self) -> &dyn BezierPieces {
        match self {
            Fitted::Function(s) => s,
            Fitted::Curve(c) => c,
        }
    }

    /// Its flattening (a function's keeps every knot as a vertex).
    #[must_use]
    pub fn flattening(&self) -> &dyn Flatten {
        match self {
            Fitted::Function(s) => s,
            Fitted::Curve(c) => c,
        }
    }

    /// Its arc length (a function's, of its graph; parameters are x).
    #[must_use]
    pub fn arclen(&self) -> &dyn Arclen {
        match self {
            Fitted::Function(s) => s,
            Fitted::Curve(c) => c,
        }
    }

    /// Whether it closes (a closed curve's path ends with `Z`).
    #[must_use]
    pub fn closed(&self) -> bool {
        matches!(self, Fitted::Curve(c) if c.is_closed())
    }
}

/// The Bezier segments of a fit, each as four control points.
#[must_use]
pub fn segments(f: &Fitted) -> Vec<Vec<Vec<f64>>> {
    let (pieces, dim) = (f.pieces(), f.curve().dim());
    let mut buf = vec![0.0; 4 * dim];
    let mut out = Vec::with_capacity(pieces.piece_count());
    for k in 0..pieces.piece_count() {
        if pieces.piece_into(k, &mut buf) {
            out.push(buf.chunks(dim).map(<[f64]>::to_vec).collect());
        }
    }
    out
}

/// The SVG path of a planar fit (a closed curve's ends with `Z`); `None` in 3D
/// or when a control point is not finite.
#[must_use]
pub fn svg(f: &Fitted) -> Option<String> {
    let mut out = String::new();
    match bzspline::write_svg_path(f.pieces(), f.closed(), &mut out) {
        Ok(true) => Some(out),
        _ => None,
    }
}

/// Writes the SVG path of a planar fit to `w` (a function's segment by segment,
/// without building the string first); `Ok(false)` in 3D.
///
/// # Errors
///
/// Write errors of `w`.
pub fn write_svg<W: std::io::Write>(f: &Fitted, w: &mut W) -> std::io::Result<bool> {
    match f {
        Fitted::Function(s) => write!(w, "{}", FunctionPath(s)).map(|()| true),
        other => match svg(other) {
            Some(p) => w.write_all(p.as_bytes()).map(|()| true),
            None => Ok(false),
        },
    }
}

/// The SVG path (`M x y C ...`) of a function's segments, formed while it is
/// written (by the library's [`bzspline::write_svg_path`]).
struct FunctionPath<'a>(&'a Spline);

impl fmt::Display for FunctionPath<'_> {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        // A fit is checked finite before it is written.
        bzspline::write_svg_path(self.0, false, out).map(|_| ())
    }
}

/// A function's knot values, formed while serializing.
struct KnotValues<'a>(&'a Spline);

impl Serialize for KnotValues<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let sp = self.0;
        s.collect_seq(
            (0..sp.len())
                .filter_map(|k| sp.segment(k))
                .enumerate()
                .flat_map(|(k, b)| {
                    let first = (k == 0).then_some(b.p[0][1]);
                    first.into_iter().chain(std::iter::once(b.p[3][1]))
                }),
        )
    }
}

/// A function's Bezier segments, formed while serializing.
struct FunctionSegments<'a>(&'a Spline);

impl Serialize for FunctionSegments<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let sp = self.0;
        s.collect_seq((0..sp.len()).filter_map(|k| sp.segment(k)).map(|b| b.p))
    }
}

/// A function's tangent points, formed while serializing.
struct FunctionTangents<'a>(&'a Spline);

impl Serialize for FunctionTangents<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.tangent_points().iter().map(|&(x, y)| [x, y]))
    }
}

/// Serializes a [`fmt::Display`] value as a JSON string without building it
/// first (serde_json escapes it as it is written).
struct AsStr<T>(T);

impl<T: fmt::Display> Serialize for AsStr<T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&self.0)
    }
}

/// Flat numbers serialized as points of `dim` coordinates.
struct Points<'a>(&'a [f64], usize);

impl Serialize for Points<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.chunks(self.1.max(1)))
    }
}

/// Like [`Points`], owning the numbers.
struct OwnedPoints(Vec<f64>, usize);

impl Serialize for OwnedPoints {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        Points(&self.0, self.1).serialize(s)
    }
}

/// The segments of a curve, each as four points, computed while serializing.
struct CurveSegments<'a>(&'a Curve);

impl Serialize for CurveSegments<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let c = self.0;
        let dim = c.dim();
        s.collect_seq(
            (0..c.len()).map(|k| OwnedPoints(c.segment_points(k).unwrap_or_default(), dim)),
        )
    }
}

/// The `fit` object of a function, in key order.
#[derive(Serialize)]
struct FunctionFit<'a> {
    mode: &'static str,
    closed: bool,
    dimension: usize,
    knots: &'a [f64],
    alphas: &'a [f64],
    values: &'a [f64],
    knot_values: KnotValues<'a>,
    tangent_points: FunctionTangents<'a>,
    segments: FunctionSegments<'a>,
    svg_path: AsStr<FunctionPath<'a>>,
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    smoothing: Option<SmoothingReport>,
}

/// The `fit` object of a curve, in key order.
#[derive(Serialize)]
struct CurveFit<'a> {
    mode: &'static str,
    closed: bool,
    dimension: usize,
    knots: &'a [f64],
    alphas: &'a [f64],
    values: Points<'a>,
    knot_values: Vec<Vec<f64>>,
    tangent_params: Vec<f64>,
    tangent_points: Vec<Vec<f64>>,
    segments: CurveSegments<'a>,
    svg_path: Option<String>,
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    smoothing: Option<SmoothingReport>,
}

/// Serializes the `fit` object of `f` with `ser`.
fn serialize_fit<S: serde::Serializer>(
    f: &Fitted,
    smoothing: Option<SmoothingReport>,
    ser: S,
) -> Result<S::Ok, S::Error> {
    match f {
        Fitted::Function(s) => FunctionFit {
            mode: "function",
            closed: false,
            dimension: 1,
            knots: s.knots(),
            alphas: s.alphas(),
            values: s.values(),
            knot_values: KnotValues(s),
            tangent_points: FunctionTangents(s),
            segments: FunctionSegments(s),
            svg_path: AsStr(FunctionPath(s)),
            smoothing,
        }
        .serialize(ser),
        Fitted::Curve(c) => {
            let mut knot_values = c.knot_points();
            if c.is_closed() {
                if let Some(first) = knot_values.first().cloned() {
                    knot_values.push(first);
                }
            }
            let (tangent_params, tangent_points) = c.tangent_points().into_iter().unzip();
            CurveFit {
                mode: "curve",
                closed: c.is_closed(),
                dimension: c.dim(),
                knots: c.knots(),
                alphas: c.alphas(),
                values: Points(c.points(), c.dim()),
                knot_values,
                tangent_params,
                tangent_points,
                segments: CurveSegments(c),
                svg_path: svg(f),
                smoothing,
            }
            .serialize(ser)
        }
    }
}

/// The `fit` JSON object: `mode` (`function` or `curve`), `closed`,
/// `dimension` (1 for a function, else the number of coordinates), `knots`,
/// `alphas`, `values` (the control values or points), `knot_values`,
/// `tangent_points` (`[x, f]` for a function, points for a curve; a curve also
/// has `tangent_params`), `segments` (four control points each) and `svg_path`
/// (null in 3D). A closed curve has N + 1 knots and N + 1 knot values, the last
/// equal to the first. A smoothing fit adds `lambda`, `gcv` and `dof`, a
/// robust one `robustness` too ([`SmoothingReport`]). Numbers are printed so that they parse back to the
/// same double.
#[must_use]
pub fn fit_json(f: &Fitted, smoothing: Option<SmoothingReport>) -> Value {
    serialize_fit(f, smoothing, serde_json::value::Serializer).unwrap_or(Value::Null)
}

/// Writes the `fit` object of `f` as [`write_json_lines`] lays it out, without
/// building it in memory first.
///
/// # Errors
///
/// Write errors of `w`.
pub fn write_fit_json<W: std::io::Write>(
    f: &Fitted,
    smoothing: Option<SmoothingReport>,
    w: W,
) -> std::io::Result<()> {
    let mut ser = serde_json::Serializer::with_formatter(w, LinesFormatter::default());
    serialize_fit(f, smoothing, &mut ser).map_err(std::io::Error::from)?;
    ser.into_inner().write_all(b"\n")
}

/// Writes `v` as JSON: an object with one key per line and each value compact
/// on its line, anything else compact; then a newline.
///
/// # Errors
///
/// Write errors of `w`.
pub fn write_json_lines<W: std::io::Write>(v: &impl Serialize, w: W) -> std::io::Result<()> {
    let mut ser = serde_json::Serializer::with_formatter(w, LinesFormatter::default());
    v.serialize(&mut ser).map_err(std::io::Error::from)?;
    ser.into_inner().write_all(b"\n")
}

/// Writes `v` as compact JSON, numbers as every output writes them.
///
/// # Errors
///
/// Write errors of `w`.
pub fn write_json_compact<W: std::io::Write>(w: W, v: &impl Serialize) -> std::io::Result<()> {
    let mut ser = serde_json::Serializer::with_formatter(w, Compact);
    v.serialize(&mut ser).map_err(std::io::Error::from)
}

/// serde_json's compact layout with numbers in their shortest form.
struct Compact;

impl serde_json::ser::Formatter for Compact {
    fn write_f64<W: ?Sized + std::io::Write>(&mut self, w: &mut W, v: f64) -> std::io::Result<()> {
        write!(w, "{}", bzspline::text::Shortest(v))
    }
}

/// A JSON layout: the keys of the outermost object on lines of their own,
/// everything else compact.
#[derive(Default)]
struct LinesFormatter {
    depth: usize,
}

impl serde_json::ser::Formatter for LinesFormatter {
    fn begin_array<W: ?Sized + std::io::Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.depth += 1;
        w.write_all(b"[")
    }

    fn end_array<W: ?Sized + std::io::Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.depth = self.depth.saturating_sub(1);
        w.write_all(b"]")
    }

    fn begin_object<W: ?Sized + std::io::Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.depth += 1;
        w.write_all(b"{")
    }

    fn end_object<W: ?Sized + std::io::Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.depth = self.depth.saturating_sub(1);
        w.write_all(if self.depth == 0 { b"\n}" } else { b"}" })
    }

    fn begin_object_key<W: ?Sized + std::io::Write>(
        &mut self,
        w: &mut W,
        first: bool,
    ) -> std::io::Result<()> {
        match (self.depth, first) {
            (1, true) => w.write_all(b"\n  "),
            (1, false) => w.write_all(b",\n  "),
            (_, true) => Ok(()),
            (_, false) => w.write_all(b","),
        }
    }

    fn begin_object_value<W: ?Sized + std::io::Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        w.write_all(if self.depth == 1 { b": " } else { b":" })
    }

    /// Numbers as every output writes them ([`bzspline::text::Shortest`]).
    fn write_f64<W: ?Sized + std::io::Write>(&mut self, w: &mut W, v: f64) -> std::io::Result<()> {
        write!(w, "{}", bzspline::text::Shortest(v))
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

    fn example1() -> FitSpec<'static> {
        let f = crate::input::EXAMPLE1;
        FitSpec {
            points: f
                .iter()
                .enumerate()
                .flat_map(|(i, &y)| [i as f64 + 1.0, y])
                .collect(),
            dim: 2,
            weights: None,
            shape: Shape {
                param: Param::Uniform,
                ..Shape::default()
            },
        }
    }

    #[test]
    fn fit_json_has_the_documented_keys_and_lengths() {
        let fitted = build(&example1()).unwrap();
        let v = fit_json(&fitted, None);
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
    fn the_streamed_object_is_the_value_laid_out() {
        let mut closed = example1();
        closed.points = Cow::Borrowed(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]);
        closed.shape.mode = Mode::Curve;
        closed.shape.closed = true;
        for spec in [example1(), closed] {
            let f = build(&spec).unwrap();
            let (mut a, mut b) = (Vec::new(), Vec::new());
            write_fit_json(&f, None, &mut a).unwrap();
            write_json_lines(&fit_json(&f, None), &mut b).unwrap();
            assert_eq!(String::from_utf8(a).unwrap(), String::from_utf8(b).unwrap());
        }
        let mut out = Vec::new();
        write_json_lines(&serde_json::json!({"a": [1, {"b": 2}], "c": "d"}), &mut out).unwrap();
        assert_eq!(out, b"{\n  \"a\": [1,{\"b\":2}],\n  \"c\": \"d\"\n}\n");
    }

    #[test]
    fn a_row_of_three_numbers_is_refused_for_a_function() {
        let mut spec = example1();
        spec.points = Cow::Owned(vec![0.0, 1.0, 2.0, 1.0, 2.0, 3.0]);
        spec.dim = 3;
        let e = build(&spec).unwrap_err();
        assert!(
            matches!(e, bzspline::Error::LengthMismatch { found: 3, .. }),
            "{e:?}"
        );
    }
}
