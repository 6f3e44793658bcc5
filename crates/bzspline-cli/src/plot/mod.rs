//! Figures in the style of the paper's Fig. 1 and Fig. 2: control points as dots,
//! the control polygon dashed, the spline as a solid line, the tangent points
//! marked, with axes, ticks, a title and a legend; optionally the convex hull of
//! the control points, the knot points and dotted lines at the data range.
//!
//! The drawing works on plain data ([`PlotData`], one per curve, several per
//! figure) and does not depend on how the command reads or fits its input; only
//! `command.rs`, the `plot` subcommand, knows the command's input and model.
//! [`render_svg`] writes the SVG; [`render_png`] rasterises that same SVG with
//! resvg, so both formats show the same figure.

mod args;
mod axis;
mod command;
mod hull;
mod png;
mod svg;

use bzspline::ParamCurve;
use bzspline::{Curve, Spline};

pub use args::{read_overlay, FigureArgs};
pub use axis::Axis;
pub use command::{run, PlotArgs};
pub use hull::convex_hull;
pub use png::{render_pdf, render_png};
pub use svg::render_svg;

/// One curve of a figure with the polygon that defines it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlotData {
    /// Name shown in the legend (`None`: "spline" or "curve N").
    pub label: Option<String>,
    /// Control points, in order (drawn as dots joined by a dashed polygon).
    pub control: Vec<[f64; 2]>,
    /// Whether the control polygon closes (last point back to the first).
    pub closed: bool,
    /// Exact cubic Bezier pieces of the curve, drawn with SVG `C` commands. When
    /// empty, [`PlotData::curve`] is drawn instead.
    pub segments: Vec<[[f64; 2]; 4]>,
    /// The curve as a dense polyline (used when there are no segments).
    pub curve: Vec<[f64; 2]>,
    /// Points where the curve touches the legs of the control polygon.
    pub tangent_points: Vec<[f64; 2]>,
    /// The curve's points at the knots.
    pub knot_points: Vec<[f64; 2]>,
    /// Data a smoothing fit approximates, drawn as small points.
    pub observations: Vec<[f64; 2]>,
    /// A confidence band of a smoothing fit, `[x, lo, hi]` in order of x,
    /// shaded under the curve.
    pub band: Vec<[f64; 3]>,
}

impl PlotData {
    /// The figure data of a spline `y = S(x)`: control points `(tau_k, F_k)`, its
    /// exact Bezier pieces, tangent points and knot points.
    ///
    /// # Examples
    ///
    /// ```ignore
    /// let s = bzspline::Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// let d = PlotData::from_spline(&s, None);
    /// assert_eq!(d.segments.len(), 2);
    /// ```
    #[must_use]
    pub fn from_spline(s: &Spline, label: Option<String>) -> Self {
        let zip = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| [*a, *b]).collect();
        PlotData {
            label,
            control: zip(s.knots(), s.values()),
            closed: false,
            segments: s.segments().into_iter().map(|b| b.p).collect(),
            curve: Vec::new(),
            tangent_points: s
                .tangent_points()
                .into_iter()
                .map(|(x, y)| [x, y])
                .collect(),
            knot_points: zip(s.knots(), &s.knot_values()),
            observations: Vec::new(),
            band: Vec::new(),
        }
    }

    /// The figure data of a parametric curve: control points, its exact Bezier
    /// pieces, tangent points and knot points, in the `(x, y)` plane (a curve in
    /// space is projected onto it). `None` for a curve of dimension below 2.
    #[must_use]
    pub fn from_curve(c: &Curve, label: Option<String>) -> Option<Self> {
        let dim = c.dim();
        if dim < 2 {
            return None;
        }
        let xy = |p: &[f64]| match p {
            [x, y, ..] => Some([*x, *y]),
            _ => None,
        };
        let segments = (0..c.len())
            .filter_map(|k| c.segment_points(k))
            .filter_map(|v| {
                Some([
                    xy(v.get(..dim)?)?,
                    xy(v.get(dim..2 * dim)?)?,
                    xy(v.get(2 * dim..3 * dim)?)?,
                    xy(v.get(3 * dim..)?)?,
                ])
            })
            .collect();
        Some(PlotData {
            label,
            control: (0..c.point_count())
                .filter_map(|i| c.point(i).and_then(xy))
                .collect(),
            closed: c.is_closed(),
            segments,
            curve: Vec::new(),
            tangent_points: c
                .tangent_points()
                .iter()
                .filter_map(|(_, p)| xy(p))
                .collect(),
            knot_points: c.knot_points().iter().filter_map(|p| xy(p)).collect(),
            observations: Vec::new(),
            band: Vec::new(),
        })
    }

    /// A curve given only as a polyline (another method's samples), without a
    /// control polygon of its own.
    #[must_use]
    pub fn polyline(label: impl Into<String>, points: Vec<[f64; 2]>) -> Self {
        PlotData {
            label: Some(label.into()),
            curve: points,
            ..PlotData::default()
        }
    }

    /// Points of the curve for the axis ranges: the polyline, and every Bezier
    /// piece sampled (its control points can lie well outside the curve).
    fn curve_points(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        let sampled = self
            .segments
            .iter()
            .flat_map(|p| (0..=16).map(move |i| bezier_point(p, f64::from(i) / 16.0)));
        self.curve.iter().copied().chain(sampled)
    }
}

pub(crate) fn bezier_point(p: &[[f64; 2]; 4], t: f64) -> [f64; 2] {
    bzspline::CubicBez::new(*p).eval(t)
}

/// How a figure looks.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotOptions {
    /// Width of the figure in pixels.
    pub width: u32,
    /// Height of the figure in pixels.
    pub height: u32,
    /// Title above the plot.
    pub title: Option<String>,
    /// Label of the horizontal axis.
    pub x_label: String,
    /// Label of the vertical axis.
    pub y_label: String,
    /// Mark the tangent points.
    pub show_tangents: bool,
    /// Shade the convex hull of all control points.
    pub show_hull: bool,
    /// Mark the knot points.
    pub show_knots: bool,
    /// Draw the control points.
    pub show_points: bool,
    /// Draw the dashed control polygon.
    pub show_polygon: bool,
    /// Dotted horizontal lines at the smallest and largest control ordinate.
    pub show_range: bool,
    /// One unit is as long on both axes (for planar curves).
    pub equal_aspect: bool,
    /// Pixels of the PNG per SVG pixel.
    pub png_scale: f32,
    /// The x values are dates or times of this kind (days or seconds since
    /// 1970): calendar ticks.
    pub x_time: Option<crate::time::TimeKind>,
    /// The curves pass through the points (the interpolating variant): the
    /// knot points are the data and the control polygon is the solved one.
    pub through: bool,
    /// The level of the confidence band drawn (0.95), for the legend.
    pub band_level: Option<f64>,
    /// The curves are smoothing fits of their observations: the control
    /// polygon is the fitted one, drawn faint.
    pub smoothing: bool,
    /// Many points: points, knots and observations are drawn as small marks
    /// in one path, and a curve of more pieces than half the plot's width
    /// in pixels as a polyline on the pixel grid, so that the SVG grows
    /// with the drawing, not with the points.
    pub dense: bool,
}

/// Past this many points a plot is drawn as a chart by default: the points
/// as small marks, no control polygon and no tangent rings.
pub const DENSE_POINTS: usize = 300;

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            width: 800,
            height: 500,
            title: None,
            x_label: "x".into(),
            y_label: "y".into(),
            show_tangents: true,
            show_hull: false,
            show_knots: false,
            show_points: true,
            show_polygon: true,
            show_range: false,
            equal_aspect: false,
            png_scale: 1.0,
            x_time: None,
            dense: false,
            through: false,
            smoothing: false,
            band_level: None,
        }
    }
}

/// `alpha = 1/3` for the common fractions, else the decimal.
pub(crate) fn alpha_label(a: f64) -> String {
    for (p, q) in [(1, 3), (1, 2), (2, 3), (2, 5), (3, 5), (3, 8), (5, 8)] {
        if (a - f64::from(p) / f64::from(q)).abs() < 1e-12 {
            return format!("\u{3b1} = {p}/{q}");
        }
    }
    format!("\u{3b1} = {a}")
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn example(n: u8, alpha: f64) -> PlotData {
        let points = crate::input::example(n);
        let (x, f) = (points.column(0), points.column(1));
        let s = Spline::with_alpha(&x, &f, alpha).unwrap();
        PlotData::from_spline(&s, None)
    }

    #[test]
    fn curves_in_the_plane_and_in_space() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let c = Curve::closed(&square).unwrap();
        let d = PlotData::from_curve(&c, None).unwrap();
        assert!(d.closed);
        assert_eq!(d.control, square.to_vec());
        assert_eq!(d.segments.len(), 4);
        assert_eq!(d.tangent_points.len(), 4);
        // docs/method.md §7: knot points pulled 0.1 inside each corner.
        let want = [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]];
        for (k, w) in d.knot_points.iter().zip(want) {
            assert!(
                (k[0] - w[0]).abs() < 1e-12 && (k[1] - w[1]).abs() < 1e-12,
                "{k:?}"
            );
        }
        for (k, seg) in d.segments.iter().enumerate() {
            assert_eq!(seg[0], d.knot_points[k], "piece {k} starts at knot {k}");
        }
        let helix = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.5],
            [-1.0, 0.0, 1.0],
            [0.0, -1.0, 1.5],
        ];
        let d = PlotData::from_curve(&Curve::open(&helix).unwrap(), Some("h".into())).unwrap();
        assert_eq!(d.control[2], [-1.0, 0.0], "projected onto (x, y)");
        assert_eq!(d.segments.len(), 3);
        let line = Curve::open(&[[0.0], [1.0], [3.0]]).unwrap();
        assert!(PlotData::from_curve(&line, None).is_none());
    }
}
