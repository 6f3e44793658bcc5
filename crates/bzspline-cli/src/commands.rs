//! The subcommands: each turns its arguments into a validated configuration,
//! reads the points, builds the spline, checks the results for finiteness and
//! only then writes.

use std::io::Write as _;

use anyhow::{anyhow, bail, Context, Result};
use clap::{Parser, Subcommand};
use serde_json::{json, Value};

use crate::cli::{
    usage, Abscissa, EvalArgs, FitArgs, FitFormat, SampleArgs, SmoothArgs, TableFormat,
};
use crate::fit::fit_points_reported;
use crate::input;
use crate::model::{self, Fitted, Mode, Shape, SmoothingReport};
use crate::output;
use crate::time::{self, TimeKind};

/// Fit, evaluate, sample and plot the third-degree Bezier-type spline of Stelia,
/// Potapenko and Sirenko: a C1 cubic that touches every leg of the control polygon.
#[derive(Debug, Parser)]
#[command(name = "bzspline", version)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Fit the spline and print its knots, knot values, tangent points and Bezier
    /// segments (JSON), the segments' control points (CSV) or an SVG path.
    Fit(FitArgs),
    /// Evaluate the spline (and derivatives) at given abscissas.
    Eval(EvalArgs),
    /// Sample points along the spline.
    Sample(SampleArgs),
    /// Draw the control points, the control polygon and the spline as SVG, PNG
    /// or PDF.
    ///
    /// Without FILE or --example it draws the paper's Example 1 (`-` reads
    /// standard input). The output's format is its name's ending (`.svg`,
    /// `.png`, `.pdf`); without -o, SVG goes to standard output.
    Plot(crate::plot::PlotArgs),
    /// Smooth the lines and polygons of a GeoJSON or TopoJSON document as one
    /// coverage: shared borders smoothed once, valid polygons kept valid.
    Smooth(SmoothArgs),
    /// Serve an interactive editor over HTTP.
    #[cfg(feature = "serve")]
    Serve(crate::serve::ServeArgs),
}

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
        #[cfg(feature = "serve")]
        Command::Serve(a) => crate::serve::run(&a),
    }
}

/// A number as text that parses back to the same double, as every output of
/// the command writes it ([`bzspline::text::Shortest`]).
#[must_use]
pub fn num(v: f64) -> String {
    bzspline::text::Shortest(v).to_string()
}

fn fit(a: &FitArgs) -> Result<()> {
    let shape = a.shape.validate()?;
    let points = a.input.load(a.shape.weights.as_deref())?;
    let (fitted, report) = fit_points_reported(&points, &shape)?;
    let mut sink = output::Sink::create(a.output.output.as_deref())?;
    match a.format {
        FitFormat::Json => match points.time.filter(|_| shape.mode == Mode::Function) {
            None => model::write_fit_json(&fitted, report, &mut sink).context("writing output")?,
            Some(kind) => {
                let v = with_knot_times(model::fit_json(&fitted, report), kind)?;
                model::write_json_lines(&v, &mut sink).context("writing output")?;
            }
        },
        FitFormat::Csv => {
            let dim = fitted.curve().dim();
            writeln!(sink, "{}", ["x", "y", "z", "w"][..dim.min(4)].join(","))
                .context("writing output")?;
            for seg in model::segments(&fitted) {
                for p in seg {
                    let row: Vec<String> = p.iter().map(|&v| num(v)).collect();
                    writeln!(sink, "{}", row.join(",")).context("writing output")?;
                }
            }
        }
        FitFormat::Svg => {
            if !model::write_svg(&fitted, &mut sink).context("writing output")? {
                bail!("an SVG path needs 2D points");
            }
            writeln!(sink).context("writing output")?;
        }
    }
    sink.finish()
}

/// A fit's JSON with `knot_times` after `knots`: the knots in the form of the
/// input's dates.
fn with_knot_times(fit: Value, kind: TimeKind) -> Result<Value> {
    let Value::Object(map) = fit else {
        return Ok(fit);
    };
    let mut out = serde_json::Map::new();
    for (k, v) in map {
        let times = (k == "knots").then(|| v.clone());
        out.insert(k, v);
        if let Some(Value::Array(knots)) = times {
            let strings = knots
                .iter()
                .map(|x| {
                    let x = x.as_f64().unwrap_or(f64::NAN);
                    time::format(x, kind).ok_or_else(|| anyhow!("knot {x} is outside the calendar"))
                })
                .collect::<Result<Vec<_>>>()?;
            out.insert("knot_times".to_owned(), json!(strings));
        }
    }
    Ok(Value::Object(out))
}

/// Writes a table as CSV (header line, then rows) or as a JSON object with one
/// array per column.
fn table(
    columns: &[String],
    rows: &[Vec<f64>],
    time: Option<TimeKind>,
    format: TableFormat,
) -> Result<String> {
    if !model::all_finite(rows) {
        bail!("a result overflows a double");
    }
    // The first column in the form of the input's dates, when it had them.
    let first = |v: f64| -> Result<String> {
        match time {
            None => Ok(num(v)),
            Some(k) => time::format(v, k).ok_or_else(|| anyhow!("x = {v} is outside the calendar")),
        }
    };
    Ok(match format {
        TableFormat::Csv => {
            let mut s = columns.join(",");
            s.push('\n');
            for r in rows {
                let mut cells: Vec<String> = Vec::with_capacity(r.len());
                for (j, &v) in r.iter().enumerate() {
                    cells.push(if j == 0 { first(v)? } else { num(v) });
                }
                s.push_str(&cells.join(","));
                s.push('\n');
            }
            s
        }
        TableFormat::Json => {
            let mut obj = serde_json::Map::new();
            for (j, c) in columns.iter().enumerate() {
                let col: Vec<f64> = rows.iter().map(|r| r[j]).collect();
                let col = match (j, time) {
                    (0, Some(_)) => {
                        json!(col.iter().map(|&v| first(v)).collect::<Result<Vec<_>>>()?)
                    }
                    _ => json!(col),
                };
                obj.insert(c.clone(), col);
            }
            let mut out = Vec::new();
            model::write_json_lines(&Value::Object(obj), &mut out).context("formatting JSON")?;
            String::from_utf8(out).context("formatting JSON")?
        }
    })
}

/// Column names: `x,y` and `dy`, `d2y`, ... for a function; `[t,]x,y[,z]` and
/// `dx,dy`, `d2x,d2y`, ... for a curve.
fn columns(f: &Fitted, names: Option<&[String]>, with_param: bool, derivs: &[u32]) -> Vec<String> {
    let order = |k: u32| if k == 1 { String::new() } else { k.to_string() };
    let dim = f.curve().dim();
    let default = ["x", "y", "z", "w"];
    let named: Vec<&str> = match names {
        Some(n) if n.len() == dim.max(2) && n.iter().all(|s| !s.is_empty()) => {
            n.iter().map(String::as_str).collect()
        }
        _ => default[..dim.clamp(2, 4)].to_vec(),
    };
    match f {
        Fitted::Function(_) => {
            let (x, y) = (named[0], named[1]);
            let mut c = vec![x.to_owned(), y.to_owned()];
            c.extend(derivs.iter().map(|&k| format!("d{}{y}", order(k))));
            c
        }
        Fitted::Curve(_) => {
            let names = &named[..dim.min(named.len())];
            let mut c: Vec<String> = if with_param {
                vec!["t".to_owned()]
            } else {
                vec![]
            };
            c.extend(names.iter().map(|n| (*n).to_owned()));
            for &k in derivs {
                c.extend(names.iter().map(|n| format!("d{}{n}", order(k))));
            }
            c
        }
    }
}

/// The row at abscissa (or curve parameter) `p`: `x, y, derivatives` for a
/// function, `[t,] coordinates, derivatives` for a curve.
fn row_at(
    f: &Fitted,
    p: f64,
    with_param: bool,
    derivs: &[u32],
) -> std::result::Result<Vec<f64>, bzspline::Error> {
    match f {
        Fitted::Function(s) => {
            let mut row = vec![p, s.eval(p)?];
            for &k in derivs {
                row.push(s.deriv(p, k)?);
            }
            Ok(row)
        }
        Fitted::Curve(c) => {
            let mut row = if with_param { vec![p] } else { vec![] };
            row.extend(c.eval(p)?);
            for &k in derivs {
                row.extend(c.deriv(p, k)?);
            }
            Ok(row)
        }
    }
}

/// The level of `--band`, checked against the shape: a band is of a
/// smoothing fit (clap has made sure of `--smooth`), of y(x) or, where
/// `curves` allows, of each coordinate of a curve.
pub(crate) fn band_of(shape: &Shape, band: Option<f64>, curves: bool) -> Result<Option<f64>> {
    if band.is_some() && shape.mode == Mode::Curve && !curves {
        usage!(
            "--band shades y(x) only, not a curve: `sample --band` gives each coordinate's band"
        );
    }
    Ok(band)
}

/// Appends the band's `lo` and `hi` at `p` to a row of [`row_at`]: after a
/// function's `x, y, ...`, around `y`; after a curve's, around each
/// coordinate in turn (the row's coordinates start at `from`).
fn with_band(
    row: &mut Vec<f64>,
    level: Option<f64>,
    report: Option<&SmoothingReport>,
    p: f64,
    (from, dim): (usize, usize),
) -> std::result::Result<(), bzspline::Error> {
    let (Some(level), Some(r)) = (level, report) else {
        return Ok(());
    };
    for c in 0..dim {
        let (lo, hi) = r.posterior.band(row[from + c], p, level, c)?;
        row.push(lo);
        row.push(hi);
    }
    Ok(())
}

/// Where a row's values start and how many there are: a function's `y`
/// after `x`; a curve's coordinates, after `t` when `with_param`.
fn values_of(f: &Fitted, with_param: bool) -> (usize, usize) {
    match f {
        Fitted::Function(_) => (1, 1),
        Fitted::Curve(_) => (usize::from(with_param), f.curve().dim()),
    }
}

/// The columns of `f`'s rows with the band's after them, when one is
/// asked: `lo`, `hi` for a function; `NAME_lo`, `NAME_hi` for each
/// coordinate of a curve.
fn band_columns(
    mut columns: Vec<String>,
    band: Option<f64>,
    f: &Fitted,
    with_param: bool,
) -> Vec<String> {
    if band.is_none() {
        return columns;
    }
    if let Fitted::Function(_) = f {
        columns.push("lo".to_owned());
        columns.push("hi".to_owned());
        return columns;
    }
    let (from, dim) = values_of(f, with_param);
    let names: Vec<String> = columns[from..from + dim].to_vec();
    for n in names {
        columns.push(format!("{n}_lo"));
        columns.push(format!("{n}_hi"));
    }
    columns
}

fn eval(a: &EvalArgs) -> Result<()> {
    let shape = a.shape.validate()?;
    if shape.mode == Mode::Curve && a.extrapolate != bzspline::Extrapolate::Error {
        usage!("--extrapolate applies to y(x) only (a closed curve is periodic)");
    }
    let (given, qpos): (Vec<Abscissa>, Vec<String>) = match (&a.at, &a.at_file) {
        (Some(xs), _) => {
            let pos = (1..=xs.len()).map(|i| format!("--at value {i}")).collect();
            (xs.clone(), pos)
        }
        (None, Some(path)) => {
            let limits = a.input.limits();
            let (name, bytes) = input::read_source(Some(path), limits.max_bytes)?;
            let select = input::Select {
                dates: a.input.date_format.clone(),
                ..Default::default()
            };
            let t = input::parse_table_with(&name, &bytes, None, limits.max_points, &select)?;
            input::check_columns(&t, &[1], "1 (one abscissa per line)")?;
            let pos = (0..t.len()).map(|i| t.at(i)).collect();
            let xs = t
                .column(0)
                .into_iter()
                .map(|v| match t.time {
                    Some(k) => Abscissa::Time(v, k),
                    None => Abscissa::Number(v, v.to_string()),
                })
                .collect();
            (xs, pos)
        }
        (None, None) => usage!("give --at X1,... or --at-file FILE"),
    };
    let band = band_of(&shape, a.band.band, true)?;
    let points = a.input.load(a.shape.weights.as_deref())?;
    let (fitted, report) = fit_points_reported(&points, &shape)?;
    let fitted = match fitted {
        Fitted::Function(s) => Fitted::Function(s.with_extrapolation(a.extrapolate)),
        other => other,
    };
    // Dates for data whose x holds dates, numbers otherwise.
    let data_time = points.time.filter(|_| shape.mode == Mode::Function);
    let mut queries = Vec::with_capacity(given.len());
    for (x, pos) in given.iter().zip(&qpos) {
        let dates = a.input.date_format.as_ref().filter(|_| data_time.is_some());
        let x = match x.read(dates) {
            Ok(x) => x,
            // Values of --at are arguments: a bad one is a usage error.
            Err(e) if a.at.is_some() => usage!("{pos}: {e}"),
            Err(e) => bail!("{pos}: {e}"),
        };
        queries.push(match (x, data_time) {
            (Abscissa::Number(v, _), None) => v,
            (Abscissa::Time(v, k), Some(want)) => time::convert(v, k, want),
            (Abscissa::Text(_), _) => unreachable!("read above"),
            (Abscissa::Number(v, _), Some(_)) => {
                bail!(
                    "{pos}: {v} is a number, but x in {} holds dates",
                    points.source
                )
            }
            (Abscissa::Time(..), None) => {
                bail!("{pos}: a date, but x in {} holds numbers", points.source)
            }
        });
    }
    let mut rows = Vec::with_capacity(queries.len());
    for (x, pos) in queries.iter().zip(&qpos) {
        let mut row =
            row_at(&fitted, *x, true, &a.derivative).map_err(|e| anyhow!("{pos}: {e}"))?;
        with_band(
            &mut row,
            band,
            report.as_ref(),
            *x,
            values_of(&fitted, true),
        )
        .map_err(|e| anyhow!("{pos}: {e}"))?;
        if !row.iter().all(|v| v.is_finite()) {
            bail!("{pos}: the result at {x} overflows a double");
        }
        rows.push(row);
    }
    let names = points.names.as_deref();
    let time = points.time.filter(|_| shape.mode == Mode::Function);
    let text = table(
        &band_columns(
            columns(&fitted, names, true, &a.derivative),
            band,
            &fitted,
            true,
        ),
        &rows,
        time,
        a.format,
    )?;
    output::emit(a.output.output.as_deref(), text.as_bytes())
}

/// The most points `sample --step` produces.
const MAX_SAMPLES: f64 = 1e7;

/// Parameters at arc-length steps `step` from the start of the fit, and its
/// end.
fn params_by_step(f: &Fitted, step: f64) -> std::result::Result<Vec<f64>, bzspline::Error> {
    // The length of a Bezier segment is at most that of its control polygon:
    // bound the work (and keep the quadrature's speeds finite) before measuring.
    let dim = f.curve().dim().max(1);
    let pieces = f.pieces();
    let mut p = vec![0.0; 4 * dim];
    let mut bound = 0.0f64;
    for k in 0..pieces.piece_count() {
        if !pieces.piece_into(k, &mut p) {
            continue;
        }
        for j in 0..3 {
            let leg = (0..dim)
                .map(|i| p[(j + 1) * dim + i] - p[j * dim + i])
                .fold(0.0f64, f64::hypot);
            bound += leg;
        }
    }
    if !(3.0 * bound).is_finite() {
        return Err(bzspline::Error::Overflow {
            what: "the length of the curve",
        });
    }
    let too_many = || bzspline::Error::InvalidArgument {
        what: "--step is too small for the curve's length: too many points; step",
        value: step,
    };
    if bound / step > MAX_SAMPLES {
        return Err(too_many());
    }
    let accuracy = (step * 1e-6).max(bound * 1e-12).max(f64::MIN_POSITIVE);
    let total = f.arclen().arclen(accuracy)?;
    let count = (total / step).floor();
    if count > MAX_SAMPLES {
        return Err(too_many());
    }
    // Every step short of the end by more than the accuracy, then the end.
    let lengths: Vec<f64> = (0..=count as usize)
        .map(|i| i as f64 * step)
        .filter(|len| total - len > accuracy)
        .collect();
    let mut ts = f.arclen().params_at_lengths(&lengths, accuracy)?;
    ts.push(f.curve().domain().1);
    Ok(ts)
}

fn sample(a: &SampleArgs) -> Result<()> {
    // --n, --step and --tolerance are checked as clap parses them.
    let shape = a.shape.validate()?;
    let band = band_of(&shape, a.band.band, true)?;
    let points = a.input.load(a.shape.weights.as_deref())?;
    let (fitted, report) = fit_points_reported(&points, &shape)?;
    let lib = |e: bzspline::Error| anyhow!("{}: {e}", points.source);
    let (lo, hi) = fitted.curve().domain();
    let params: Vec<f64> = if let Some(n) = a.n {
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
        fitted
            .flattening()
            .flatten(t)
            .map_err(lib)?
            .params()
            .to_vec()
    } else if let Some(step) = a.step {
        params_by_step(&fitted, step).map_err(lib)?
    } else {
        usage!("give one of --n K, --step S or --tolerance T");
    };
    let mut rows = Vec::with_capacity(params.len());
    for p in params {
        let mut row = row_at(&fitted, p, false, &a.derivative).map_err(lib)?;
        with_band(
            &mut row,
            band,
            report.as_ref(),
            p,
            values_of(&fitted, false),
        )
        .map_err(lib)?;
        rows.push(row);
    }
    let names = points.names.as_deref();
    let time = points.time.filter(|_| shape.mode == Mode::Function);
    let text = table(
        &band_columns(
            columns(&fitted, names, false, &a.derivative),
            band,
            &fitted,
            false,
        ),
        &rows,
        time,
        a.format,
    )?;
    output::emit(a.output.output.as_deref(), text.as_bytes())
}

fn smooth(a: &SmoothArgs) -> Result<()> {
    crate::smooth::run(a)
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
}
