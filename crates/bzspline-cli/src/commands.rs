//! The subcommands: each turns its arguments into a validated configuration,
//! reads the points, builds the spline, checks the results for finiteness and
//! only then writes.

use anyhow::{anyhow, bail, Context, Result};
use bzspline::Spline;
use serde_json::{json, Value};

use crate::cli::{
    Cli, Command, EvalArgs, FitArgs, FitFormat, SampleArgs, Shape, SmoothArgs, TableFormat,
};
use crate::input::{self, Points};
use crate::model::{self, FitSpec, Fitted, Mode};
use crate::output;

/// Runs the parsed command line.
///
/// # Errors
///
/// Whatever the command reports; `main` prints it as one line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Fit(a) => fit(&a),
        Command::Eval(a) => eval(&a),
        Command::Sample(a) => sample(&a),
        Command::Plot(a) => crate::plot::run(&a),
        Command::Smooth(a) => smooth(&a),
        Command::Serve(a) => crate::serve::run(&a),
    }
}

/// Builds the spline for `points` with the validated `shape`, naming the file
/// and line of any fault.
///
/// # Errors
///
/// Rows of the wrong width, the library's refusals mapped to lines, and results
/// that overflow a double.
pub fn fit_points(points: &Points, shape: &Shape) -> Result<Fitted> {
    match shape.mode {
        Mode::Function => input::check_columns(points, &[2], "2 (x, y)")?,
        Mode::Curve => input::check_columns(points, &[2, 3], "2 or 3 coordinates")?,
    }
    let spec = FitSpec {
        points: points.rows.clone(),
        mode: shape.mode,
        closed: shape.closed,
        param: shape.param,
        alpha: shape.alpha,
        alphas: shape.alphas.clone(),
    };
    let fitted = model::build(&spec).map_err(|e| input::explain(points, &e))?;
    let finite = match &fitted {
        Fitted::Function(s) => {
            s.knot_values().iter().all(|v| v.is_finite())
                && model::all_finite(&model::segments(&fitted).concat())
                && s.tangent_points()
                    .iter()
                    .all(|(x, y)| x.is_finite() && y.is_finite())
        }
    };
    if !finite {
        bail!(
            "{}: the spline's coefficients overflow a double (values too large)",
            points.source
        );
    }
    Ok(fitted)
}

/// A number as text that parses back to the same double: integers without a
/// fraction (`3`), others in Rust's shortest round-trip form (`0.1`, `1e-7`).
#[must_use]
pub fn num(v: f64) -> String {
    let s = format!("{v:?}");
    match s.strip_suffix(".0") {
        Some(int) => int.to_owned(),
        None => s,
    }
}

fn fit(a: &FitArgs) -> Result<()> {
    let shape = a.shape.validate()?;
    let points = input::load(&a.input)?;
    let fitted = fit_points(&points, &shape)?;
    let text = match a.format {
        FitFormat::Json => json_lines(&model::fit_json(&fitted))?,
        FitFormat::Csv => {
            let segs = model::segments(&fitted);
            let dim = segs.first().and_then(|s| s.first()).map_or(2, Vec::len);
            let mut s = ["x", "y", "z"][..dim.min(3)].join(",");
            s.push('\n');
            for p in segs.iter().flatten() {
                let row: Vec<String> = p.iter().map(|&v| num(v)).collect();
                s.push_str(&row.join(","));
                s.push('\n');
            }
            s
        }
        FitFormat::Svg => {
            let path = model::svg_path(&model::segments(&fitted))
                .ok_or_else(|| anyhow!("an SVG path needs 2D points"))?;
            path + "\n"
        }
    };
    output::emit(a.output.output.as_deref(), text.as_bytes())
}

/// An object with one key per line and each value compact on its line, or any
/// other value compact; ends with a newline.
fn json_lines(v: &Value) -> Result<String> {
    let Value::Object(map) = v else {
        return Ok(serde_json::to_string(v).context("formatting JSON")? + "\n");
    };
    let mut s = String::from("{\n");
    for (i, (k, val)) in map.iter().enumerate() {
        let key = serde_json::to_string(k).context("formatting JSON")?;
        let val = serde_json::to_string(val).context("formatting JSON")?;
        let comma = if i + 1 < map.len() { "," } else { "" };
        s.push_str(&format!("  {key}: {val}{comma}\n"));
    }
    s.push_str("}\n");
    Ok(s)
}

fn deriv_name(k: u32) -> String {
    if k == 1 {
        "dy".to_owned()
    } else {
        format!("d{k}y")
    }
}

/// Writes a table as CSV (header line, then rows) or as a JSON object with one
/// array per column.
fn table(columns: &[String], rows: &[Vec<f64>], format: TableFormat) -> Result<String> {
    if !model::all_finite(rows) {
        bail!("a result overflows a double");
    }
    Ok(match format {
        TableFormat::Csv => {
            let mut s = columns.join(",");
            s.push('\n');
            for r in rows {
                let cells: Vec<String> = r.iter().map(|&v| num(v)).collect();
                s.push_str(&cells.join(","));
                s.push('\n');
            }
            s
        }
        TableFormat::Json => {
            let mut obj = serde_json::Map::new();
            for (j, c) in columns.iter().enumerate() {
                let col: Vec<f64> = rows.iter().map(|r| r[j]).collect();
                obj.insert(c.clone(), json!(col));
            }
            json_lines(&Value::Object(obj))?
        }
    })
}

/// The spline of a function, or an error for modes `eval`/`sample` do not
/// handle yet.
fn function_of(f: Fitted) -> Spline {
    match f {
        Fitted::Function(s) => s,
    }
}

/// The value and the requested derivatives at `x`, as one row.
fn row_at(s: &Spline, x: f64, derivs: &[u32]) -> std::result::Result<Vec<f64>, bzspline::Error> {
    let mut row = vec![x, s.eval(x)?];
    for &k in derivs {
        row.push(s.deriv(x, k)?);
    }
    Ok(row)
}

fn eval(a: &EvalArgs) -> Result<()> {
    let shape = a.shape.validate()?;
    let (queries, qpos): (Vec<f64>, Vec<String>) = match (&a.at, &a.at_file) {
        (Some(xs), _) => {
            for (i, x) in xs.iter().enumerate() {
                if !x.is_finite() {
                    bail!("--at value {} = {x} is not a finite number", i + 1);
                }
            }
            let pos = (1..=xs.len()).map(|i| format!("--at value {i}")).collect();
            (xs.clone(), pos)
        }
        (None, Some(path)) => {
            let (name, bytes) = input::read_source(Some(path))?;
            let t = input::parse_table(&name, &bytes, None)?;
            input::check_columns(&t, &[1], "1 (one abscissa per line)")?;
            let pos = (0..t.rows.len()).map(|i| t.at(i)).collect();
            (t.rows.iter().map(|r| r[0]).collect(), pos)
        }
        (None, None) => bail!("give --at X1,... or --at-file FILE"),
    };
    let points = input::load(&a.input)?;
    let s = function_of(fit_points(&points, &shape)?).with_extrapolation(a.extrapolate.into());
    let mut rows = Vec::with_capacity(queries.len());
    for (x, pos) in queries.iter().zip(&qpos) {
        let row = row_at(&s, *x, &a.derivative).map_err(|e| anyhow!("{pos}: {e}"))?;
        if !row.iter().all(|v| v.is_finite()) {
            bail!("{pos}: the result at x = {x} overflows a double");
        }
        rows.push(row);
    }
    let mut cols = vec!["x".to_owned(), "y".to_owned()];
    cols.extend(a.derivative.iter().map(|&k| deriv_name(k)));
    let text = table(&cols, &rows, a.format)?;
    output::emit(a.output.output.as_deref(), text.as_bytes())
}

/// Abscissas where the planar curve `(x, S(x))` is within `tol` of the polyline
/// through them: each Bezier piece is split in half until its inner control
/// points lie within `tol` of the chord. Knots are always included.
fn flatten_function(s: &Spline, tol: f64) -> Vec<f64> {
    fn dist_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
    }
    fn split(
        b: &bzspline::CubicBez<2>,
        t0: f64,
        t1: f64,
        tol: f64,
        depth: u32,
        out: &mut Vec<f64>,
    ) {
        let [p0, p1, p2, p3] = b.p;
        let flat = dist_to_segment(p1, p0, p3).max(dist_to_segment(p2, p0, p3)) <= tol;
        if flat || depth >= 30 {
            out.push(t1);
            return;
        }
        let (l, r) = b.subdivide(0.5);
        let tm = 0.5 * (t0 + t1);
        split(&l, t0, tm, tol, depth + 1, out);
        split(&r, tm, t1, tol, depth + 1, out);
    }
    let knots = s.knots();
    let mut xs = vec![knots[0]];
    for (k, seg) in s.segments().iter().enumerate() {
        let mut ts = Vec::new();
        split(seg, 0.0, 1.0, tol, 0, &mut ts);
        let (a, b) = (knots[k], knots[k + 1]);
        let last = ts.len().saturating_sub(1);
        for (i, t) in ts.into_iter().enumerate() {
            // The end of each piece is its knot exactly.
            xs.push(if i == last { b } else { a + t * (b - a) });
        }
    }
    xs
}

fn sample(a: &SampleArgs) -> Result<()> {
    let shape = a.shape.validate()?;
    if let Some(n) = a.n {
        if n < 2 {
            bail!("--n must be at least 2 (got {n})");
        }
    }
    if let Some(t) = a.tolerance {
        if !(t.is_finite() && t > 0.0) {
            bail!("--tolerance must be a positive number (got {t})");
        }
    }
    if let Some(st) = a.step {
        if !(st.is_finite() && st > 0.0) {
            bail!("--step must be a positive number (got {st})");
        }
    }
    let points = input::load(&a.input)?;
    let s = function_of(fit_points(&points, &shape)?);
    let (lo, hi) = s.domain();
    let xs: Vec<f64> = if let Some(n) = a.n {
        (0..n)
            .map(|i| {
                if i + 1 == n {
                    hi
                } else {
                    lo + (hi - lo) * (i as f64 / (n - 1) as f64)
                }
            })
            .collect()
    } else if let Some(t) = a.tolerance {
        flatten_function(&s, t)
    } else if a.step.is_some() {
        bail!(
            "--step needs arc length, which the library does not offer yet; use --n or --tolerance"
        );
    } else {
        bail!("give one of --n K, --step S or --tolerance T");
    };
    let mut rows = Vec::with_capacity(xs.len());
    for x in xs {
        rows.push(row_at(&s, x, &a.derivative).map_err(|e| anyhow!("{}: {e}", points.source))?);
    }
    let mut cols = vec!["x".to_owned(), "y".to_owned()];
    cols.extend(a.derivative.iter().map(|&k| deriv_name(k)));
    let text = table(&cols, &rows, a.format)?;
    output::emit(a.output.output.as_deref(), text.as_bytes())
}

fn smooth(a: &SmoothArgs) -> Result<()> {
    let _ = a;
    bail!("smooth needs parametric curves, which the library does not offer yet")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip_and_integers_are_short() {
        assert_eq!(num(3.0), "3");
        assert_eq!(num(-0.5), "-0.5");
        assert_eq!(num(1e-7), "1e-7");
        for v in [0.1, 1.0 / 3.0, 2.5e300, -7.25e-310, 0.458257569] {
            assert_eq!(num(v).parse::<f64>().unwrap(), v, "{v}");
        }
    }

    #[test]
    fn flattening_keeps_the_knots_and_meets_the_tolerance() {
        let p = input::example(1);
        let xs: Vec<f64> = p.rows.iter().map(|r| r[0]).collect();
        let ys: Vec<f64> = p.rows.iter().map(|r| r[1]).collect();
        let s = Spline::new(&xs, &ys).unwrap();
        let tol = 1e-3;
        let flat = flatten_function(&s, tol);
        for k in &xs {
            assert!(flat.contains(k), "knot {k} missing");
        }
        assert!(flat.windows(2).all(|w| w[0] < w[1]), "not increasing");
        // Midpoints of the chords are within tol of the curve (vertically a
        // bound on the distance, so compare with a margin for slope).
        for w in flat.windows(2) {
            let (y0, y1) = (s.eval(w[0]).unwrap(), s.eval(w[1]).unwrap());
            let xm = 0.5 * (w[0] + w[1]);
            let dy = (s.eval(xm).unwrap() - 0.5 * (y0 + y1)).abs();
            let slope = (y1 - y0) / (w[1] - w[0]);
            let dist = dy / slope.hypot(1.0);
            assert!(dist <= tol * 1.0001, "distance {dist} at {xm}");
        }
    }
}
