//! The `plot` subcommand: reads and fits the points like the other commands, then
//! draws the figure as SVG or PNG.

use anyhow::{anyhow, Result};
use bzspline::ParamCurve;
use clap::Args;

use super::{read_overlay, render_pdf, render_png, render_svg, FigureArgs, PlotData};
use crate::cli::{check_alpha, usage, InputArgs, OutputArgs, ShapeArgs};
use crate::fit::{fit_points, fit_points_reported};
use crate::model::{Fitted, Mode};
use crate::output;

/// Arguments of `plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    /// Output file: SVG, PNG or PDF by its name's ending (`.svg`, `.png`,
    /// `.pdf`); without it, SVG on standard output.
    #[command(flatten)]
    pub output: OutputArgs,
    #[command(flatten)]
    pub figure: FigureArgs,
    #[command(flatten)]
    pub band: crate::cli::BandArgs,
}

/// Runs `plot`: without a file or `--example`, draws the paper's Example 1.
///
/// # Errors
///
/// Bad options, the input's faults (with file and line), a spline that cannot
/// be built, an unreadable overlay, a PNG without fonts, or a failed write.
pub fn run(a: &PlotArgs) -> Result<()> {
    let shape = a.shape.validate()?;
    let out = a.output.output.as_deref();
    let format = match out.and_then(|p| p.extension()).and_then(|e| e.to_str()) {
        None if out.is_none() => Figure::Svg,
        Some(e) if e.eq_ignore_ascii_case("svg") => Figure::Svg,
        Some(e) if e.eq_ignore_ascii_case("png") => Figure::Png,
        Some(e) if e.eq_ignore_ascii_case("pdf") => Figure::Pdf,
        Some(e) => usage!("plot writes .svg, .png or .pdf files, not .{e}"),
        None => usage!("plot writes .svg, .png or .pdf files: give -o a name that ends in one"),
    };
    let mut source = a.input.clone();
    if source.file.is_none() && source.example.is_none() {
        source.example = Some(1);
    }
    let points = source.load(a.shape.weights.as_deref())?;
    let band = crate::commands::band_of(&shape, a.band.band, false)?;
    let sweep = &a.figure.alpha_sweep;
    let mut data = Vec::new();
    if sweep.is_empty() {
        let label = (!a.figure.overlay.is_empty()).then(|| "bzspline".to_owned());
        let (fitted, report) = fit_points_reported(&points, &shape)?;
        let mut one = plot_data(&fitted, label)?;
        if let (Some(level), Some(r), Fitted::Function(s)) = (band, &report, &fitted) {
            one.band = band_samples(s, &r.posterior, level)
                .map_err(|e| anyhow!("{}: {e}", points.source))?;
        }
        data.push(one);
    } else {
        if band.is_some() {
            usage!("--band draws the band of one fit: leave out --alpha-sweep");
        }
        if a.shape.alpha.is_some() || a.shape.alphas.is_some() {
            usage!("--alpha-sweep draws one curve per alpha: leave out --alpha and --alphas");
        }
        for (i, &alpha) in sweep.iter().enumerate() {
            check_alpha(&format!("--alpha-sweep value {}", i + 1), alpha)?;
            let mut one = shape.clone();
            one.alphas = bzspline::AlphaChoice::One(alpha);
            data.push(plot_data(
                &fit_points(&points, &one)?,
                Some(super::alpha_label(alpha)),
            )?);
        }
    }
    for path in &a.figure.overlay {
        data.extend(read_overlay(path)?);
    }
    let mut opts = a.figure.options(points.names.as_deref(), points.len());
    opts.x_time = points.time.filter(|_| shape.mode == Mode::Function);
    // A curve's shape is only right with one unit as long on both axes.
    opts.equal_aspect |= shape.mode == Mode::Curve;
    // Through the points, the knot points are the data: always shown.
    opts.through = shape.through;
    opts.show_knots |= shape.through;
    // A smoothing fit: the data as points, the fitted control polygon faint.
    opts.band_level = band;
    if shape.smoothing.is_some() {
        opts.smoothing = true;
        opts.show_points = false;
        opts.show_tangents = false;
        let w = points.width.max(2);
        let obs: Vec<[f64; 2]> = points
            .coords
            .chunks_exact(w)
            .map(|p| [p[0], p[1]])
            .collect();
        if let Some(first) = data.first_mut() {
            first.observations = obs;
        }
    }
    let bytes = match format {
        Figure::Svg => render_svg(&data, &opts).into_bytes(),
        Figure::Png => render_png(&data, &opts)?,
        Figure::Pdf => render_pdf(&data, &opts)?,
    };
    output::emit(out, &bytes)
}

/// A band of a smoothing fit of y(x) to shade: at 600 abscissas evenly
/// spaced and, up to 2,000 of them, at every knot (where the standard error
/// has its kinks).
fn band_samples(
    s: &bzspline::Spline,
    posterior: &bzspline::Posterior,
    level: f64,
) -> std::result::Result<Vec<[f64; 3]>, bzspline::Error> {
    let knots = s.knots();
    let (lo, hi) = (knots[0], knots[knots.len() - 1]);
    let mut xs: Vec<f64> = (0..=600)
        .map(|i| lo + (hi - lo) * f64::from(i) / 600.0)
        .chain(knots.iter().copied().filter(|_| knots.len() <= 2000))
        .map(|x| x.clamp(lo, hi))
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs.into_iter()
        .map(|x| {
            let (a, b) = posterior.band(s.eval(x)?, x, level, 0)?;
            Ok([x, a, b])
        })
        .collect()
}

/// The file formats of a figure.
enum Figure {
    Svg,
    Png,
    Pdf,
}

/// The figure data of a fitted spline or curve.
fn plot_data(f: &Fitted, label: Option<String>) -> Result<PlotData> {
    match f {
        Fitted::Function(s) => Ok(PlotData::from_spline(s, label)),
        Fitted::Curve(c) => PlotData::from_curve(c, label)
            .ok_or_else(|| anyhow!("a curve of dimension {} cannot be drawn", c.dim())),
    }
}
