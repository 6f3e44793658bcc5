//! Command-line options of `bzspline plot` and the files they name.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context as _};
use serde::Deserialize;

use super::{PlotData, PlotOptions, DENSE_POINTS};

/// Options of the figure (the `plot` subcommand).
#[derive(clap::Args, Clone, Debug, PartialEq)]
pub struct FigureArgs {
    /// Width of the figure in pixels.
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(100..=20_000))]
    pub width: u32,
    /// Height of the figure in pixels.
    #[arg(long, default_value_t = 500, value_parser = clap::value_parser!(u32).range(100..=20_000))]
    pub height: u32,
    /// Title above the plot.
    #[arg(long)]
    pub title: Option<String>,
    /// Label of the horizontal axis (default: the header's name of the x
    /// column, else "x").
    #[arg(long)]
    pub xlabel: Option<String>,
    /// Label of the vertical axis (default: the header's name of the y column,
    /// else "y").
    #[arg(long)]
    pub ylabel: Option<String>,
    /// Do not draw the control points (a clean chart line).
    #[arg(long, overrides_with = "points")]
    pub no_points: bool,
    /// Draw the control points as dots even past 300 points (where
    /// they are drawn as small marks).
    #[arg(long, overrides_with = "no_points")]
    pub points: bool,
    /// Do not draw the dashed control polygon (not drawn by default past
    /// 300 points).
    #[arg(long, overrides_with = "polygon")]
    pub no_polygon: bool,
    /// Draw the dashed control polygon, also past 300 points.
    #[arg(long, overrides_with = "no_polygon")]
    pub polygon: bool,
    /// Do not mark the points where the curve touches the control polygon
    /// (not marked by default past 300 points).
    #[arg(long, overrides_with = "tangents")]
    pub no_tangents: bool,
    /// Mark the points where the curve touches the control polygon, also
    /// past 300 points.
    #[arg(long, overrides_with = "no_tangents")]
    pub tangents: bool,
    /// Shade the convex hull of the control points.
    #[arg(long)]
    pub hull: bool,
    /// Mark the curve's points at the knots.
    #[arg(long)]
    pub knots: bool,
    /// Dotted lines at the smallest and largest control value.
    #[arg(long)]
    pub data_range: bool,
    /// Same scale on both axes (always on for curves).
    #[arg(long)]
    pub equal_aspect: bool,
    /// Draw one spline per shape parameter in the list, e.g. `1/3,1/2,2/3`.
    #[arg(long, value_name = "A,...", value_delimiter = ',', value_parser = bzspline_io::options::parse_alpha)]
    pub alpha_sweep: Vec<f64>,
    /// Add the curves of a JSON file to the figure (repeatable):
    /// `[{"label": "...", "points": [[x, y], ...]}, ...]`.
    #[arg(long, value_name = "FILE")]
    pub overlay: Vec<PathBuf>,
    /// Pixels of the PNG per SVG pixel.
    #[arg(long, default_value_t = 1.0, value_parser = parse_scale)]
    pub scale: f32,
}

impl FigureArgs {
    /// The drawing options these arguments ask for; `names` are the data's
    /// column names (the axis labels unless given), `n` the number of
    /// points: past [`DENSE_POINTS`] the figure is a chart (the points as
    /// small marks, no control polygon or tangent rings) unless asked.
    #[must_use]
    pub fn options(&self, names: Option<&[String]>, n: usize) -> PlotOptions {
        let dense = n > DENSE_POINTS;
        let chosen = |on: bool, off: bool, default: bool| {
            if on {
                true
            } else if off {
                false
            } else {
                default
            }
        };
        let name = |i: usize, default: &str| {
            names
                .and_then(|n| n.get(i))
                .filter(|n| !n.is_empty())
                .map_or_else(|| default.to_owned(), Clone::clone)
        };
        PlotOptions {
            width: self.width,
            height: self.height,
            title: self.title.clone(),
            x_label: self.xlabel.clone().unwrap_or_else(|| name(0, "x")),
            y_label: self.ylabel.clone().unwrap_or_else(|| name(1, "y")),
            show_tangents: chosen(self.tangents, self.no_tangents, !dense),
            show_hull: self.hull,
            show_knots: self.knots,
            show_points: !self.no_points,
            show_polygon: chosen(self.polygon, self.no_polygon, !dense),
            dense: dense && !self.points,
            show_range: self.data_range,
            equal_aspect: self.equal_aspect,
            png_scale: self.scale,
            x_time: None,
            through: false,
            smoothing: false,
            band_level: None,
        }
    }
}

fn parse_scale(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= 16.0 => Ok(v),
        _ => Err(format!("{s:?} is not a number in (0, 16]")),
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Overlay {
    label: String,
    points: Vec<[f64; 2]>,
    #[serde(default)]
    segments: Vec<[[f64; 2]; 4]>,
}

/// The curves of an overlay file: a JSON array of
/// `{"label": NAME, "points": [[x, y], ...]}` (optionally also `"segments"`, cubic
/// Bezier pieces `[[x0, y0], [x1, y1], [x2, y2], [x3, y3]]` drawn instead of the
/// points).
///
/// # Errors
///
/// Names the file, and the line and column of a JSON error.
pub fn read_overlay(path: &Path) -> anyhow::Result<Vec<PlotData>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("reading overlay {}", path.display()))?;
    let list: Vec<Overlay> = serde_json::from_str(&text)
        .with_context(|| format!("parsing overlay {}", path.display()))?;
    if list.is_empty() {
        bail!("overlay {} holds no curve", path.display());
    }
    list.into_iter()
        .enumerate()
        .map(|(i, o)| {
            if o.points.len() < 2 && o.segments.is_empty() {
                return Err(anyhow!(
                    "overlay {}: curve {} ({:?}) has fewer than 2 points",
                    path.display(),
                    i + 1,
                    o.label
                ));
            }
            let mut d = PlotData::polyline(o.label, o.points);
            d.segments = o.segments;
            Ok(d)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        plot: FigureArgs,
    }

    #[test]
    fn arguments_become_options() {
        let cli = Cli::try_parse_from([
            "t",
            "--width",
            "640",
            "--title",
            "T",
            "--no-tangents",
            "--hull",
            "--alpha-sweep",
            "1/3, 0.5,2/3",
        ])
        .unwrap();
        let o = cli.plot.options(None, 10);
        assert_eq!((o.width, o.height), (640, 500));
        assert_eq!(o.title.as_deref(), Some("T"));
        assert!(!o.show_tangents && o.show_hull && !o.show_knots);
        assert_eq!(cli.plot.alpha_sweep, vec![1.0 / 3.0, 0.5, 2.0 / 3.0]);
        assert!(Cli::try_parse_from(["t", "--width", "0"]).is_err());
        assert!(Cli::try_parse_from(["t", "--scale", "nan"]).is_err());
        assert!(bzspline_io::options::parse_fraction("1/0").is_err());
        assert!(Cli::try_parse_from(["t", "--alpha-sweep", "0.5,0.7"]).is_err());
        let e = Cli::try_parse_from(["t", "--alpha-sweep", "0.5,x"])
            .err()
            .unwrap();
        assert!(e.to_string().contains("\"x\""), "{e}");
    }

    #[test]
    fn many_points_make_a_chart_unless_asked() {
        let parse = |a: &[&str]| Cli::try_parse_from([&["t"], a].concat()).unwrap().plot;
        let few = parse(&[]).options(None, DENSE_POINTS);
        assert!(few.show_polygon && few.show_tangents && few.show_points && !few.dense);
        let many = parse(&[]).options(None, DENSE_POINTS + 1);
        assert!(!many.show_polygon && !many.show_tangents && many.show_points && many.dense);
        let asked = parse(&["--polygon", "--tangents", "--points"]).options(None, 5000);
        assert!(asked.show_polygon && asked.show_tangents && !asked.dense);
        // The last of a pair wins.
        let o = parse(&["--polygon", "--no-polygon"]).options(None, 10);
        assert!(!o.show_polygon);
        let o = parse(&["--no-points", "--points"]).options(None, 10);
        assert!(o.show_points);
    }

    #[test]
    fn overlay_files_are_read_and_checked() {
        let dir = tempfile::tempdir().unwrap();
        let good = dir.path().join("good.json");
        std::fs::write(&good, r#"[{"label": "a", "points": [[0, 1], [1, 2]]}]"#).unwrap();
        let d = read_overlay(&good).unwrap();
        assert_eq!(d[0].curve, vec![[0.0, 1.0], [1.0, 2.0]]);
        assert_eq!(d[0].label.as_deref(), Some("a"));
        let bad = dir.path().join("bad.json");
        std::fs::write(&bad, "[{\"label\": \"a\",\n \"points\": [[0, 1e999]]}]").unwrap();
        let e = format!("{:#}", read_overlay(&bad).unwrap_err());
        assert!(e.contains("bad.json") && e.contains("line 2"), "{e}");
        std::fs::write(&bad, r#"[{"label": "a", "points": [[0, 1]]}]"#).unwrap();
        let e = format!("{:#}", read_overlay(&bad).unwrap_err());
        assert!(e.contains("curve 1"), "{e}");
    }
}
