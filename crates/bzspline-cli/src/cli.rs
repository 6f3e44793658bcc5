//! Command-line arguments shared by the subcommands and those of fit, eval,
//! sample and smooth (clap derive; the doc comments are the help text), and
//! their validation into the configuration the commands work from. The
//! command line itself (`Cli`, `Command`) is in `commands.rs`.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};

use crate::input::{self, Points, Source};
use crate::model::{Mode, Shape};
use crate::time::DateFormat;
use bzspline::AlphaChoice;
use bzspline_io::distance::{parse_distance, Distance};
use bzspline_io::options::parse_alpha;

pub use crate::input::InputFormat;
use crate::input::{DEFAULT_MAX_BYTES, DEFAULT_MAX_POINTS};

/// Where the control points come from.
#[derive(Debug, Clone, Args)]
pub struct InputArgs {
    /// Input file: a table (CSV, TSV, whitespace), JSON points, GeoJSON (or newline-delimited),
    /// a Shapefile, GeoPackage, FlatGeobuf or GeoParquet file, or for `smooth` TopoJSON; `-` or nothing
    /// reads standard input.
    #[arg(value_name = "FILE", conflicts_with = "example")]
    pub file: Option<PathBuf>,
    /// Use the paper's Example 1 (11 points on [1, 11]) or Example 2 (a semicircle).
    #[arg(long, value_name = "1|2", value_parser = clap::value_parser!(u8).range(1..=2))]
    pub example: Option<u8>,
    /// Input format; by default from the file's extension, else from the content
    /// (`{` or `[` starts JSON, GeoJSON or TopoJSON, anything else is a table).
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub input_format: Option<InputFormat>,
    /// The layer of a GeoPackage to read (needed when it holds several).
    #[arg(long, value_name = "NAME")]
    pub layer: Option<String>,
    /// Refuse inputs with more than N control points (a table's rows, a line's
    /// positions). Fitting a table takes about 100 bytes per point for y(x) and
    /// 400 for a planar curve: at the default, 2 GB and 8 GB.
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_MAX_POINTS as u64,
        value_parser = clap::value_parser!(u64).range(2..)
    )]
    pub max_points: u64,
    /// Refuse input files (or standard input) larger than this many bytes, before
    /// reading them. JSON and GeoJSON are read into a document tree first, which
    /// takes 5 to 30 times their size in memory.
    #[arg(
        long,
        value_name = "BYTES",
        default_value_t = DEFAULT_MAX_BYTES,
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    pub max_bytes: u64,
    /// A table's column of x, by header name or number (from 1); its values
    /// may be numbers or dates (`2024-03-01`, days) and date-times
    /// (`2024-03-01T06:00:00Z`, seconds; without an offset read as UTC), in the
    /// forms --date-format lists. With --x alone, y is the first other column.
    #[arg(long = "x", value_name = "NAME|N", conflicts_with = "columns")]
    pub x: Option<String>,
    /// A table's column of y, by header name or number. With --y alone (or a
    /// table of one column), y is read over its row number: x = 0, 1, 2, ...
    #[arg(long = "y", value_name = "NAME|N", conflicts_with = "columns")]
    pub y: Option<String>,
    /// A table's columns to read, in order (x,y, or a curve's coordinates), by
    /// header name or number.
    #[arg(long, value_name = "A,B[,C]", value_delimiter = ',')]
    pub columns: Option<Vec<String>>,
    /// The form of a table's dates in x, with strftime's (and d3's) directives:
    /// `%d/%m/%Y`, `%m/%d/%Y`, `%b %d %Y` (month names), `%Y-%m` (months, read as
    /// their first day), `%Y%m%d`, `%d.%m.%Y %H:%M` (date-times, UTC) or with
    /// `%z` (an offset such as +0200), `%s` (seconds since 1970). Without it x is
    /// a number or one of 2000-01-31, 2000-01-31T13:45:00Z, 2000-01-31 13:45,
    /// 2000/01/31, 2000-01, Jan 31 2000, January 31, 2000, 31 Jan 2000; dates
    /// such as 01/02/2000, day and month either way round, are refused.
    #[arg(long, value_name = "FORMAT", value_parser = date_format)]
    pub date_format: Option<DateFormat>,
}

/// `--date-format`, checked by [`DateFormat::new`].
fn date_format(s: &str) -> Result<DateFormat, String> {
    DateFormat::new(s)
}

impl InputArgs {
    /// What the readers take: the arguments as an [`input::Source`].
    #[must_use]
    pub fn source(&self) -> Source {
        Source {
            file: self.file.clone(),
            example: self.example,
            format: self.input_format,
            layer: self.layer.clone(),
            limits: self.limits(),
            x: self.x.clone(),
            y: self.y.clone(),
            columns: self.columns.clone(),
            date_format: self.date_format.clone(),
            weights: None,
        }
    }

    /// `--max-points` and `--max-bytes`.
    #[must_use]
    pub fn limits(&self) -> input::Limits {
        input::Limits {
            max_points: usize::try_from(self.max_points).unwrap_or(usize::MAX),
            max_bytes: self.max_bytes,
        }
    }

    /// Reads the points ([`input::load`]), with a table's column of
    /// `weights` when given, and says on standard error when GeoJSON
    /// positions were cut to x, y, z.
    ///
    /// # Errors
    ///
    /// As [`input::load`].
    pub fn load(&self, weights: Option<&str>) -> Result<Points> {
        let mut source = self.source();
        source.weights = weights.map(str::to_owned);
        let points = input::load(&source)?;
        if points.cut > 0 {
            eprintln!("note: {}", input::cut_note(&points.source, points.cut));
        }
        Ok(points)
    }
}

/// The shape of the spline.
#[derive(Debug, Clone, Args)]
pub struct ShapeArgs {
    /// One shape parameter for every interval, in [1/3, 2/3] (default 1/2); a
    /// decimal or a fraction (`1/3`, `2/3`).
    #[arg(
        long,
        value_name = "A",
        allow_hyphen_values = true,
        conflicts_with = "alphas",
        value_parser = parse_alpha
    )]
    pub alpha: Option<f64>,
    /// One shape parameter per interval, comma-separated (N-1 values for N
    /// points), each a decimal or a fraction.
    #[arg(
        long,
        value_name = "A1,...",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = bzspline_io::options::parse_fraction
    )]
    pub alphas: Option<Vec<f64>>,
    /// Treat rows as control points of a parametric curve (2D or 3D) instead of
    /// (x, y) samples of a function.
    #[arg(long)]
    pub curve: bool,
    /// Close the curve (implies --curve).
    #[arg(long)]
    pub closed: bool,
    /// Curve parameters: uniform (tau = 0, 1, ...), chordal (steps of the
    /// distances between points) or centripetal (of their square roots; the
    /// default).
    #[arg(long, value_name = "KIND", value_parser = param_parser())]
    pub param: Option<bzspline::Param>,
    /// Pass through every point instead of touching the legs of their polygon
    /// (the interpolating variant): the points are then the knot values, and
    /// the solved control values are what `fit` prints as `values`.
    #[arg(long)]
    pub through: bool,
    /// Fit the points as noisy data with a smoothing spline (knots at the
    /// points, control values minimising the squared residuals plus LAMBDA
    /// times the integral of S''^2): `auto` chooses LAMBDA by generalized
    /// cross-validation. Functions and curves, closed ones round their loop; `fit` adds `lambda`, `gcv`
    /// and `dof` to its JSON.
    #[arg(
        long,
        value_name = "auto|LAMBDA",
        conflicts_with = "through",
        allow_hyphen_values = true,
        value_parser = bzspline_io::options::parse_smoothing
    )]
    pub smooth: Option<bzspline::Smoothing>,
    /// With --smooth: a table's column of weights, by header name or number
    /// (finite, >= 0; a point of weight 0 does not pull the fit). The column
    /// is not read as a coordinate.
    #[arg(long, value_name = "NAME|N", requires = "smooth")]
    pub weights: Option<String>,
    /// With --smooth: a fit robust against outliers, re-weighted by its
    /// residuals (Tukey's biweight on six median absolute residuals, as
    /// lowess does; docs/method.md section 14); `fit` adds `robustness`, the
    /// weight each point ended with (0 for an outlier).
    #[arg(long, requires = "smooth")]
    pub robust: bool,
}

/// `--param`: one of [`bzspline::Param::NAMES`], read by the library.
fn param_parser() -> impl clap::builder::TypedValueParser<Value = bzspline::Param> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(bzspline::Param::NAMES)
        .map(|s| s.parse().unwrap_or_default())
}

/// A confidence band of a smoothing fit.
#[derive(Debug, Clone, Args)]
pub struct BandArgs {
    /// With --smooth: the pointwise confidence band at LEVEL (0.95 for 95 %)
    /// from the fit's posterior standard error, `S(x) -+ z se(x)`; `eval` and
    /// `sample` add the columns `lo` and `hi` for y(x), `NAME_lo` and
    /// `NAME_hi` for each coordinate of a curve; `plot` shades y(x)'s.
    #[arg(long, value_name = "LEVEL", requires = "smooth", value_parser = band_level)]
    pub band: Option<f64>,
}

/// `--band`: a level the library accepts ([`bzspline::band_z`]).
fn band_level(s: &str) -> Result<f64, String> {
    let v = parse_number(s)?;
    bzspline::band_z(v).map(|_| v).map_err(|e| e.to_string())
}

/// Where the result goes.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Write to FILE (atomically: nothing is written on error) instead of
    /// standard output.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
}

/// Arguments of `fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    #[command(flatten)]
    pub output: OutputArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = FitFormat::Json)]
    pub format: FitFormat,
}

/// Output formats of `fit`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FitFormat {
    /// One JSON object: knots, alphas, knot values, tangent points, segments.
    Json,
    /// The segments' control points, one per row, a column per coordinate.
    Csv,
    /// The SVG path string (`M ... C ...`).
    Svg,
}

/// `--extrapolate`: the library's policies by their names
/// ([`bzspline::Extrapolate::name`]), but for `nan`: the command writes no
/// NaN.
fn extrapolate_parser() -> impl clap::builder::TypedValueParser<Value = bzspline::Extrapolate> {
    use bzspline::Extrapolate;
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(
        [Extrapolate::Error, Extrapolate::Clamp, Extrapolate::Extend].map(Extrapolate::name),
    )
    .map(|s| s.parse().unwrap_or_default())
}

/// Table formats of `eval` and `sample`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TableFormat {
    /// Comma-separated values with a header line.
    Csv,
    /// A JSON object with one array per column.
    Json,
}

/// Arguments of `eval`.
#[derive(Debug, Args)]
pub struct EvalArgs {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    #[command(flatten)]
    pub output: OutputArgs,
    /// Abscissas (curve parameters with --curve), comma-separated: numbers, or
    /// dates and date-times when the data's x holds them (in the form of
    /// --date-format when it is given).
    #[arg(
        long,
        value_name = "X1,...",
        value_delimiter = ',',
        allow_hyphen_values = true,
        required_unless_present = "at_file",
        conflicts_with = "at_file",
        value_parser = abscissa
    )]
    pub at: Option<Vec<Abscissa>>,
    /// Read the abscissas from a file, one per line (`#` comments allowed).
    #[arg(long, value_name = "XS")]
    pub at_file: Option<PathBuf>,
    /// Also print this derivative (1, 2 or 3); repeat or give a list.
    #[arg(long, value_name = "K", value_delimiter = ',',
          value_parser = clap::value_parser!(u32).range(1..=3))]
    pub derivative: Vec<u32>,
    /// Outside the span: error, clamp to the end values, or extend the end cubics.
    #[arg(long, value_name = "POLICY", default_value = "error", value_parser = extrapolate_parser())]
    pub extrapolate: bzspline::Extrapolate,
    #[command(flatten)]
    pub band: BandArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = TableFormat::Csv)]
    pub format: TableFormat,
}

/// Arguments of `sample`.
#[derive(Debug, Args)]
#[command(group(clap::ArgGroup::new("spacing").required(true)))]
pub struct SampleArgs {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    #[command(flatten)]
    pub output: OutputArgs,
    /// Number of points, evenly spaced in x (in the parameter for curves).
    #[arg(long, short = 'n', value_name = "K", group = "spacing",
          value_parser = at_least_two)]
    pub n: Option<usize>,
    /// Distance along the curve between consecutive points.
    #[arg(long, value_name = "S", group = "spacing", value_parser = positive,
          allow_negative_numbers = true)]
    pub step: Option<f64>,
    /// Largest distance between the curve and the polyline through the points.
    #[arg(long, value_name = "T", group = "spacing", value_parser = positive,
          allow_negative_numbers = true)]
    pub tolerance: Option<f64>,
    /// Also print this derivative (1 or 2); repeat or give a list.
    #[arg(long, value_name = "K", value_delimiter = ',',
          value_parser = clap::value_parser!(u32).range(1..=2))]
    pub derivative: Vec<u32>,
    #[command(flatten)]
    pub band: BandArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = TableFormat::Csv)]
    pub format: TableFormat,
}

/// Arguments of `smooth`.
#[derive(Debug, Args)]
pub struct SmoothArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// One shape parameter for every interval, in [1/3, 2/3] (default 1/2); a
    /// decimal or a fraction (`1/3`, `2/3`).
    #[arg(long, value_name = "A", allow_hyphen_values = true, value_parser = parse_alpha)]
    pub alpha: Option<f64>,
    /// Curve parameters: uniform, chordal or centripetal.
    #[arg(long, value_name = "KIND", value_parser = param_parser(), default_value_t = bzspline::Param::default())]
    pub param: bzspline::Param,
    /// Largest distance between the smooth curve and the output polyline: a
    /// number in the data's coordinate units, or a ground distance (`50m`,
    /// `2km`) on data whose coordinate system is known (longitude and
    /// latitude: measured on the ellipsoid; projected: in its unit), or
    /// `0.001deg` on longitude and latitude. Default: 1e-4 of the diagonal of
    /// the data's bounding box (of each line's, for newline-delimited
    /// GeoJSON).
    #[arg(long, value_name = "T", value_parser = tolerance_distance, allow_negative_numbers = true)]
    pub tolerance: Option<Distance>,
    /// Smooth every feature's geometry on its own, as if it had no
    /// neighbours: each stays valid, but the borders that features share are
    /// no longer shared afterwards (Python's `coverage=False`).
    #[arg(long, conflicts_with = "snap")]
    pub independent: bool,
    /// Merge positions closer than EPS, and put a position within EPS of
    /// another line's or ring's edge into that edge, before finding the
    /// shared borders (for borders digitised twice with small differences).
    /// A number in the data's units, or `0.5m` (on longitude and latitude,
    /// on the ground: east-west as north-south) or `1e-6deg`, as for
    /// --tolerance.
    #[arg(long, value_name = "EPS", value_parser = snap_distance, allow_negative_numbers = true)]
    pub snap: Option<Distance>,
    /// Keep every position where the line turns by more than DEG degrees as a
    /// sharp corner (street blocks, buildings, survey lines); on longitude and
    /// latitude smoothed in metres, the angle on the ground.
    #[arg(long, value_name = "DEG", value_parser = degrees, allow_negative_numbers = true)]
    pub keep_angle: Option<f64>,
    /// Pass through every vertex (the interpolating variant) instead of
    /// cutting the corners: the output keeps every input position.
    #[arg(long)]
    pub through: bool,
    /// Print a summary (features, rings, arcs, refinements, positions, area
    /// change) on standard error; printed anyway when it is a terminal.
    #[arg(long)]
    pub stats: bool,
    /// Output format: GeoJSON (the default), TopoJSON or a layer file (also
    /// chosen by the output file's extension: `.topojson`, `.shp`, `.gpkg`,
    /// `.fgb`, `.parquet`).
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub output_format: Option<bzspline_io::smooth::job::Output>,
    /// With TopoJSON input and GeoJSON output: only the features of this
    /// object (all objects are smoothed together either way).
    #[arg(long, value_name = "NAME")]
    pub object: Option<String>,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// An error in the arguments found after parsing them: exit code 2.
#[derive(Debug)]
pub struct UsageError(String);

impl UsageError {
    /// The error with its message.
    #[must_use]
    pub fn new(msg: &str) -> Self {
        UsageError(msg.to_owned())
    }
}

/// Returns a [`UsageError`] (exit code 2) with the formatted message.
macro_rules! usage {
    ($($arg:tt)*) => {
        return Err($crate::cli::UsageError::new(&format!($($arg)*)).into())
    };
}
pub(crate) use usage;

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

fn parse_number(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .map_err(|_| format!("'{s}' is not a number"))
}

fn finite(s: &str) -> Result<f64, String> {
    let v = parse_number(s)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("must be a finite number (got {s})"))
    }
}

/// An abscissa of `--at`: a number, or a date or date-time, or text for
/// `--date-format` to read.
#[derive(Debug, Clone, PartialEq)]
pub enum Abscissa {
    /// A finite number, and its text.
    Number(f64, String),
    /// A date or date-time, in its kind's unit.
    Time(f64, crate::time::TimeKind),
    /// Neither: a date in the form `--date-format` gives.
    Text(String),
}

impl Abscissa {
    /// The abscissa as the data's x reads it: with a date format, a date in
    /// that form (numbers too, `20000131`).
    ///
    /// # Errors
    ///
    /// Text that is no number or date of a known form, or does not match
    /// the format.
    pub fn read(&self, dates: Option<&DateFormat>) -> Result<Abscissa, String> {
        let text = match self {
            Abscissa::Number(_, t) | Abscissa::Text(t) => t,
            Abscissa::Time(..) => return Ok(self.clone()),
        };
        match dates {
            Some(f) => f.parse(text).map(|(v, k)| Abscissa::Time(v, k)),
            None if matches!(self, Abscissa::Text(_)) => {
                Err(crate::time::not_a_number_or_date(text))
            }
            None => Ok(self.clone()),
        }
    }
}

fn abscissa(s: &str) -> Result<Abscissa, String> {
    if let Ok(v) = finite(s) {
        return Ok(Abscissa::Number(v, s.trim().to_owned()));
    }
    Ok(match crate::time::parse(s) {
        Some((v, k)) => Abscissa::Time(v, k),
        None => Abscissa::Text(s.trim().to_owned()),
    })
}

fn at_least_two(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 2 => Ok(n),
        _ => Err(format!("must be a whole number of at least 2 (got {s})")),
    }
}

/// An option's rule as the library words it (`must be ...`), for clap.
fn rule(e: &bzspline_geo::Error, s: &str) -> String {
    match e {
        bzspline_geo::Error::InvalidOption { rule, .. } => format!("{rule} (got {s})"),
        other => other.to_string(),
    }
}

fn positive(s: &str) -> Result<f64, String> {
    bzspline_geo::check_tolerance(parse_number(s)?).map_err(|e| rule(&e, s))
}

fn tolerance_distance(s: &str) -> Result<Distance, String> {
    let d = parse_distance(s)?;
    bzspline_geo::check_tolerance(d.value).map_err(|e| rule(&e, s))?;
    Ok(d)
}

fn snap_distance(s: &str) -> Result<Distance, String> {
    let d = parse_distance(s)?;
    bzspline_geo::check_snap(d.value).map_err(|e| rule(&e, s))?;
    Ok(d)
}

fn degrees(s: &str) -> Result<f64, String> {
    bzspline_geo::check_keep_angle(parse_number(s)?).map_err(|e| rule(&e, s))
}

impl ShapeArgs {
    /// Checks the shape options that do not depend on the data.
    ///
    /// # Errors
    ///
    /// A non-finite alpha, or `--param` other than uniform without `--curve`.
    pub fn validate(&self) -> Result<Shape> {
        if let Some(a) = self.alpha {
            check_alpha("--alpha", a)?;
        }
        if let Some(list) = &self.alphas {
            for (i, &a) in list.iter().enumerate() {
                check_alpha(&format!("--alphas value {}", i + 1), a)?;
            }
        }
        let curve = self.curve || self.closed;
        if !curve && self.param.is_some() {
            usage!("--param applies to curves only: add --curve");
        }
        Ok(Shape {
            mode: if curve { Mode::Curve } else { Mode::Function },
            closed: self.closed,
            param: self.param.clone().unwrap_or_default(),
            alphas: match (&self.alphas, self.alpha) {
                (Some(each), _) => AlphaChoice::Each(each.clone()),
                (None, Some(one)) => AlphaChoice::One(one),
                (None, None) => AlphaChoice::default(),
            },
            through: self.through,
            smoothing: self.smooth,
            robust: self.robust,
        })
    }
}

/// Refuses an alpha that [`bzspline::check_alpha`] refuses, before any work,
/// naming the option.
pub fn check_alpha(name: &str, a: f64) -> Result<()> {
    if bzspline::check_alpha(a).is_err() {
        if a.is_finite() {
            usage!("{name} = {a} is outside [1/3, 2/3]");
        }
        usage!("{name} = {a} is not a finite number");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::UsageError;
    use crate::commands::{Cli, Command};
    use clap::CommandFactory;
    use clap::Parser;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn alpha_and_alphas_conflict() {
        let r = Cli::try_parse_from(["bzspline", "fit", "--alpha", "0.5", "--alphas", "0.5"]);
        assert!(r.is_err(), "--alpha with --alphas must be refused");
    }

    #[test]
    fn alphas_are_parsed_as_fractions_and_checked_by_clap() {
        let cli = Cli::try_parse_from(["bzspline", "fit", "--alphas", "1/3,2/3,0.5"]).unwrap();
        let Command::Fit(f) = cli.command else {
            panic!("parsed as another command")
        };
        let shape = f.shape.validate().unwrap();
        assert_eq!(
            shape.alphas,
            bzspline::AlphaChoice::Each(vec![bzspline::ALPHA_MIN, 2.0 / 3.0, 0.5])
        );
        let e = Cli::try_parse_from(["bzspline", "fit", "--alpha", "0.9"]).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("0.9 is outside [1/3, 2/3]"), "{e}");
        let cli = Cli::try_parse_from(["bzspline", "fit", "--alphas", "0.5,0.9"]).unwrap();
        let Command::Fit(f) = cli.command else {
            panic!("parsed as another command")
        };
        let e = f.shape.validate().unwrap_err();
        assert!(e.downcast_ref::<UsageError>().is_some());
        assert!(e.to_string().contains("--alphas value 2 = 0.9"), "{e}");
    }
}
