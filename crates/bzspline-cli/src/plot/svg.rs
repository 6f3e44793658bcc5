//! The figure as an SVG document, written by hand: every number is finite and
//! every text escaped.

use std::fmt::Write as _;

use super::axis;
use super::{convex_hull, Axis, PlotData, PlotOptions};

/// Colours of the curves, in order: a palette that stays distinct for the usual
/// forms of colour blindness (after Okabe and Ito), starting with a deep blue.
pub const PALETTE: [&str; 6] = [
    "#0b5fa5", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9",
];
const INK: &str = "#222222";
const AXIS: &str = "#444444";
const GRID: &str = "#e6e6e6";
const POLYGON: &str = "#7a7a7a";
const HULL: &str = "#0b5fa5";
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";
const TICK_FONT: f64 = 12.0;
const LABEL_FONT: f64 = 13.0;
const TITLE_FONT: f64 = 16.0;
/// Rough advance of one character in em for the fonts above (for layout only).
const CHAR_EM: f64 = 0.56;

/// Writes a finite number with at most two decimals (0 for a non-finite value,
/// which the layout never produces).
struct Num(f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = if self.0.is_finite() { self.0 } else { 0.0 };
        let s = format!("{v:.2}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        f.write_str(if s == "-0" || s.is_empty() { "0" } else { s })
    }
}

/// `s` with the XML special characters escaped and the characters XML 1.0 does
/// not allow removed.
#[must_use]
pub fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(' '),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {}
            c => out.push(c),
        }
    }
    out
}

fn text_width(s: &str, size: f64) -> f64 {
    // The count of characters in a label is small, so the conversion is exact.
    s.chars().count() as f64 * size * CHAR_EM
}

/// Maps data coordinates to pixels inside the plot area.
struct Frame {
    x: Axis,
    y: Axis,
    left: f64,
    top: f64,
    w: f64,
    h: f64,
}

impl Frame {
    fn px(&self, p: [f64; 2]) -> (Num, Num) {
        (
            Num(self.left + self.x.unit(p[0]) * self.w),
            Num(self.top + (1.0 - self.y.unit(p[1])) * self.h),
        )
    }
}

/// One entry of the legend: how its symbol is drawn and its text.
enum Key {
    Line {
        color: String,
        dash: Option<&'static str>,
        width: f64,
    },
    Dot,
    /// A small faint point: an observation.
    Speck,
    Ring(String),
    Square(String),
    Area,
    /// A confidence band, in its curve's colour.
    Band(String),
}

/// The figure of one or more curves as an SVG document.
///
/// Non-finite coordinates are skipped; every number written is finite.
///
/// # Examples
///
/// ```ignore
/// let s = bzspline::Spline::new(&[1.0, 2.0, 3.0], &[1.0, 3.0, 2.0])?;
/// let svg = render_svg(&[PlotData::from_spline(&s, None)], &PlotOptions::default());
/// assert!(svg.starts_with("<svg"));
/// ```
#[must_use]
pub fn render_svg(data: &[PlotData], opts: &PlotOptions) -> String {
    let width = f64::from(opts.width.max(16));
    let height = f64::from(opts.height.max(16));
    let controls = distinct_controls(data);
    let all_control: Vec<[f64; 2]> = controls
        .iter()
        .flat_map(|(c, _)| c.iter().copied())
        .collect();
    let (xa, ya, ticks) = axes(data, opts, width, height);
    let (keys, range) = legend(data, opts, &all_control);
    let legend = Legend::lay_out(keys, width);
    let f = frame(xa, ya, ticks, opts, (width, height), legend.height);
    draw(data, opts, &controls, &f, &legend, range, (width, height))
}

/// The axes of everything drawn, with as many ticks as fit (their labels side
/// by side with a gap); also the tick counts asked for, which an equal
/// aspect ratio uses again.
fn axes(
    data: &[PlotData],
    opts: &PlotOptions,
    width: f64,
    height: f64,
) -> (Axis, Axis, (usize, usize)) {
    // Data ranges over everything drawn.
    let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
    let mut ys = (f64::INFINITY, f64::NEG_INFINITY);
    let mut grow = |p: [f64; 2]| {
        if p[0].is_finite() && p[1].is_finite() {
            xs = (xs.0.min(p[0]), xs.1.max(p[0]));
            ys = (ys.0.min(p[1]), ys.1.max(p[1]));
        }
    };
    for d in data {
        d.curve_points().for_each(&mut grow);
        d.control.iter().copied().for_each(&mut grow);
        d.tangent_points.iter().copied().for_each(&mut grow);
        d.observations.iter().copied().for_each(&mut grow);
        for &[x, lo, hi] in &d.band {
            grow([x, lo]);
            grow([x, hi]);
        }
    }
    // At most one tick per 55 px across and per 45 px up (the values are small).
    let x_ticks = ((width - 120.0) / 55.0).clamp(2.0, 12.0) as usize;
    let y_ticks = ((height - 130.0) / 45.0).clamp(2.0, 10.0) as usize;
    // Date ticks no finer than the data's dates (months for monthly data).
    let finest = opts.x_time.map(|kind| {
        let data_x = data
            .iter()
            .flat_map(|d| d.control.iter().chain(&d.observations).map(|p| p[0]));
        axis::resolution(data_x, kind)
    });
    let x_axis = |ticks: usize| match opts.x_time {
        Some(kind) => Axis::calendar(
            xs.0,
            xs.1,
            0.03,
            ticks,
            kind,
            finest.unwrap_or(axis::Unit::Clock),
        ),
        None => Axis::new(xs.0, xs.1, 0.03, ticks),
    };
    // Fewer ticks until their labels fit side by side with a gap.
    let mut xa = x_axis(x_ticks);
    for fewer in (2..x_ticks).rev() {
        let widest = xa
            .ticks
            .iter()
            .map(|t| text_width(&xa.label(*t), TICK_FONT))
            .fold(0.0, f64::max);
        if (widest + 12.0) * xa.ticks.len() as f64 <= width - 120.0 {
            break;
        }
        xa = x_axis(fewer);
    }
    let ya = Axis::new(ys.0, ys.1, 0.05, y_ticks);
    (xa, ya, (x_ticks, y_ticks))
}

/// The legend's entries, and the data range (its lines' ordinates) when
/// shown.
#[allow(clippy::type_complexity)] // entries and an optional pair
fn legend(
    data: &[PlotData],
    opts: &PlotOptions,
    all_control: &[[f64; 2]],
) -> (Vec<(Key, String)>, Option<(f64, f64)>) {
    let mut keys: Vec<(Key, String)> = Vec::new();
    let solved = if opts.through {
        "solved "
    } else if opts.smoothing {
        "fitted "
    } else {
        ""
    };
    if data.iter().any(|d| !d.observations.is_empty()) {
        keys.push((Key::Speck, "data".into()));
    }
    if opts.show_points && !all_control.is_empty() {
        keys.push((Key::Dot, format!("{solved}control points")));
    }
    if opts.show_polygon && !all_control.is_empty() {
        keys.push((
            Key::Line {
                color: POLYGON.into(),
                dash: Some("6 4"),
                width: 1.3,
            },
            format!("{solved}control polygon"),
        ));
    }
    for (i, d) in data.iter().enumerate() {
        let label = d.label.clone().unwrap_or_else(|| {
            if data.len() == 1 {
                "spline".into()
            } else {
                format!("curve {}", i + 1)
            }
        });
        keys.push((
            Key::Line {
                color: color(i).into(),
                dash: None,
                width: 2.4,
            },
            label,
        ));
    }
    if let Some(level) = opts.band_level {
        keys.push((
            Key::Band(color(0).into()),
            format!("{} % band", Num(level * 100.0)),
        ));
    }
    let tangent_color = if data.len() == 1 { color(0) } else { AXIS };
    if opts.show_tangents && data.iter().any(|d| !d.tangent_points.is_empty()) {
        keys.push((Key::Ring(tangent_color.into()), "tangent points".into()));
    }
    if opts.show_knots && data.iter().any(|d| !d.knot_points.is_empty()) {
        let name = if opts.through {
            "points (passed through)"
        } else {
            "knot points"
        };
        keys.push((Key::Square(tangent_color.into()), name.into()));
    }
    if opts.show_hull && all_control.len() >= 3 {
        keys.push((Key::Area, "convex hull".into()));
    }
    // The data's range: the control ordinates, or through the points the knot
    // points (the solved controls are not the data).
    let data_points: Vec<[f64; 2]> = if opts.through {
        data.iter()
            .flat_map(|d| d.knot_points.iter().copied())
            .collect()
    } else {
        all_control.to_vec()
    };
    let range = if opts.show_range && !data_points.is_empty() {
        let lo = data_points
            .iter()
            .map(|p| p[1])
            .fold(f64::INFINITY, f64::min);
        let hi = data_points
            .iter()
            .map(|p| p[1])
            .fold(f64::NEG_INFINITY, f64::max);
        keys.push((
            Key::Line {
                color: AXIS.into(),
                dash: Some("2 3"),
                width: 1.2,
            },
            "data range".into(),
        ));
        Some((lo, hi))
    } else {
        None
    };

    (keys, range)
}

/// The legend's entries in rows that fit the figure's width.
struct Legend {
    keys: Vec<(Key, String)>,
    widths: Vec<f64>,
    rows: Vec<Vec<usize>>,
    height: f64,
    sym: f64,
}

impl Legend {
    fn lay_out(keys: Vec<(Key, String)>, width: f64) -> Legend {
        let sym = 26.0;
        let key_widths: Vec<f64> = keys
            .iter()
            .map(|(_, t)| sym + 6.0 + text_width(t, TICK_FONT) + 18.0)
            .collect();
        let mut rows: Vec<Vec<usize>> = vec![Vec::new()];
        let mut row_w = 0.0;
        for (i, w) in key_widths.iter().enumerate() {
            if row_w + w > width - 40.0 && !rows.last().is_some_and(Vec::is_empty) {
                rows.push(Vec::new());
                row_w = 0.0;
            }
            row_w += w;
            if let Some(r) = rows.last_mut() {
                r.push(i);
            }
        }
        let height = if keys.is_empty() {
            0.0
        } else {
            20.0 * rows.len() as f64 + 8.0
        };

        Legend {
            keys,
            widths: key_widths,
            rows,
            height,
            sym,
        }
    }
}

/// The plot area inside its margins (from the text they hold: tick labels,
/// axis labels, the title and the legend), with equal units on both axes
/// when asked.
fn frame(
    xa: Axis,
    ya: Axis,
    (x_ticks, y_ticks): (usize, usize),
    opts: &PlotOptions,
    (width, height): (f64, f64),
    legend_h: f64,
) -> Frame {
    let (mut xa, mut ya) = (xa, ya);
    let y_label_w = ya
        .ticks
        .iter()
        .map(|t| text_width(&ya.label(*t), TICK_FONT))
        .fold(0.0, f64::max);
    let top = if opts.title.is_some() { 48.0 } else { 18.0 };
    let left = 14.0 + LABEL_FONT + 10.0 + y_label_w + 10.0;
    let last_x_label = xa
        .ticks
        .last()
        .map_or(0.0, |t| text_width(&xa.label(*t), TICK_FONT));
    let right = 18.0_f64.max(last_x_label / 2.0 + 6.0);
    let bottom = 8.0 + TICK_FONT + 8.0 + LABEL_FONT + 14.0 + legend_h;
    let mut w = (width - left - right).max(4.0);
    let mut h = (height - top - bottom).max(4.0);
    let (mut left, mut top) = (left, top);
    if opts.equal_aspect {
        // Widen the axis that has room to spare so that units match.
        let sx = (xa.hi / 2.0 - xa.lo / 2.0) / w;
        let sy = (ya.hi / 2.0 - ya.lo / 2.0) / h;
        if sx.is_normal() && sy.is_normal() {
            if sx > sy {
                let extra = (sx * h - (ya.hi / 2.0 - ya.lo / 2.0)) * 2.0;
                ya = Axis::new(ya.lo - extra / 2.0, ya.hi + extra / 2.0, 0.0, y_ticks);
            } else {
                let extra = (sy * w - (xa.hi / 2.0 - xa.lo / 2.0)) * 2.0;
                xa = Axis::new(xa.lo - extra / 2.0, xa.hi + extra / 2.0, 0.0, x_ticks);
            }
        }
        // Keep the plot area as computed; the axes now have equal units.
        w = w.max(4.0);
        h = h.max(4.0);
    }
    left = left.max(0.0);
    top = top.max(0.0);
    Frame {
        x: xa,
        y: ya,
        left,
        top,
        w,
        h,
    }
}

/// Draws the figure on its frame.
fn draw(
    data: &[PlotData],
    opts: &PlotOptions,
    controls: &[(Vec<[f64; 2]>, bool)],
    f: &Frame,
    legend: &Legend,
    range: Option<(f64, f64)>,
    (width, height): (f64, f64),
) -> String {
    let mut s = String::with_capacity(16 * 1024);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="{FONT}">"#,
        w = Num(width),
        h = Num(height)
    );
    if let Some(t) = &opts.title {
        let _ = writeln!(s, "<title>{}</title>", xml_escape(t));
    }
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    if let Some(t) = &opts.title {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" font-size="{TITLE_FONT}" font-weight="bold" fill="{INK}" text-anchor="middle">{}</text>"#,
            Num(width / 2.0),
            Num(30.0),
            xml_escape(t)
        );
    }
    write_axes(&mut s, f);
    // Everything drawn from the data stays inside the plot area (markers may
    // reach a little past it).
    let _ = writeln!(
        s,
        r#"<clipPath id="plot-area"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>"#,
        Num(f.left - 6.0),
        Num(f.top - 6.0),
        Num(f.w + 12.0),
        Num(f.h + 12.0)
    );
    draw_data(&mut s, data, opts, controls, f, range);
    // Axis labels and legend.
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-size="{LABEL_FONT}" fill="{INK}" text-anchor="middle">{}</text>"#,
        Num(f.left + f.w / 2.0),
        Num(f.top + f.h + 8.0 + TICK_FONT + 8.0 + LABEL_FONT),
        xml_escape(&opts.x_label)
    );
    let (ylx, yly) = (Num(14.0 + LABEL_FONT * 0.8), Num(f.top + f.h / 2.0));
    let _ = writeln!(
        s,
        r#"<text x="{ylx}" y="{yly}" font-size="{LABEL_FONT}" fill="{INK}" text-anchor="middle" transform="rotate(-90 {ylx} {yly})">{}</text>"#,
        xml_escape(&opts.y_label)
    );
    let legend_top = height - legend.height;
    for (r, row) in legend.rows.iter().enumerate() {
        let total: f64 = row.iter().map(|i| legend.widths[*i]).sum::<f64>() - 18.0;
        let mut x = (width - total) / 2.0;
        let y = legend_top + 10.0 * 0.0 + 20.0 * r as f64 + 10.0;
        for &i in row {
            write_key(&mut s, &legend.keys[i], x, y, legend.sym);
            x += legend.widths[i];
        }
    }
    s.push_str("</svg>\n");
    s
}

/// Draws what comes from the data, clipped to the plot area: the hull, the
/// data range, the observations, the control polygons, the curves and their
/// marked points.
fn draw_data(
    s: &mut String,
    data: &[PlotData],
    opts: &PlotOptions,
    controls: &[(Vec<[f64; 2]>, bool)],
    f: &Frame,
    range: Option<(f64, f64)>,
) {
    let all_control: Vec<[f64; 2]> = controls
        .iter()
        .flat_map(|(c, _)| c.iter().copied())
        .collect();
    let _ = writeln!(s, r#"<g clip-path="url(#plot-area)">"#);
    if opts.show_hull && all_control.len() >= 3 {
        let hull = convex_hull(&all_control);
        let _ = write!(
            s,
            r#"<polygon fill="{HULL}" fill-opacity="0.07" stroke="{HULL}" stroke-opacity="0.35" stroke-width="1" points=""#
        );
        write_points(s, f, &hull);
        let _ = writeln!(s, r#""/>"#);
    }
    if let Some((lo, hi)) = range {
        for v in [lo, hi] {
            let (x0, y) = f.px([f.x.lo, v]);
            let (x1, _) = f.px([f.x.hi, v]);
            let _ = writeln!(
                s,
                r#"<line x1="{x0}" y1="{y}" x2="{x1}" y2="{y}" stroke="{AXIS}" stroke-width="1.2" stroke-dasharray="2 3"/>"#
            );
        }
    }
    for (i, d) in data.iter().enumerate() {
        if d.band.len() >= 2 {
            // The band: its upper edge left to right, its lower edge back.
            let edge: Vec<[f64; 2]> = d
                .band
                .iter()
                .map(|b| [b[0], b[2]])
                .chain(d.band.iter().rev().map(|b| [b[0], b[1]]))
                .collect();
            let _ = write!(
                s,
                r#"<polygon fill="{}" fill-opacity="0.18" stroke="none" points=""#,
                color(i)
            );
            write_points(s, f, &edge);
            let _ = writeln!(s, r#""/>"#);
        }
    }
    for d in data {
        if opts.dense {
            write_marks(s, f, &d.observations, INK, 0.45, 3.0);
            continue;
        }
        for p in d.observations.iter().filter(|p| finite(p)) {
            let (x, y) = f.px(*p);
            let _ = writeln!(
                s,
                r#"<circle cx="{x}" cy="{y}" r="2.2" fill="{INK}" fill-opacity="0.45"/>"#
            );
        }
    }
    if opts.show_points && opts.dense {
        // Many points: faint marks under the curve, which stays readable.
        for (c, _) in controls {
            write_marks(s, f, c, INK, 0.35, 2.6);
        }
    }
    if opts.show_polygon {
        let faint = if opts.smoothing { 0.35 } else { 1.0 };
        for (c, closed) in controls {
            let tag = if *closed { "polygon" } else { "polyline" };
            let _ = write!(
                s,
                r#"<{tag} fill="none" stroke="{POLYGON}" stroke-opacity="{faint}" stroke-width="1.3" stroke-dasharray="6 4" stroke-linejoin="round" points=""#
            );
            write_points(s, f, c);
            let _ = writeln!(s, r#""/>"#);
        }
    }
    // The first curve is the subject of the figure: draw it last, on top.
    for (i, d) in data.iter().enumerate().rev() {
        write_curve(s, f, d, color(i), opts.dense);
    }
    for (i, d) in data.iter().enumerate() {
        let c = if data.len() == 1 { color(0) } else { color(i) };
        if opts.show_knots && opts.dense {
            write_marks(s, f, &d.knot_points, c, 1.0, 4.0);
        } else if opts.show_knots {
            for p in d.knot_points.iter().filter(|p| finite(p)) {
                let (x, y) = f.px(*p);
                let _ = writeln!(
                    s,
                    r#"<rect x="{}" y="{}" width="7" height="7" fill="{c}" transform="rotate(45 {x} {y})"/>"#,
                    Num(x.0 - 3.5),
                    Num(y.0 - 3.5)
                );
            }
        }
        if opts.show_tangents {
            for p in d.tangent_points.iter().filter(|p| finite(p)) {
                let (x, y) = f.px(*p);
                let _ = writeln!(
                    s,
                    r#"<circle cx="{x}" cy="{y}" r="4" fill="white" stroke="{c}" stroke-width="1.8"/>"#
                );
            }
        }
    }
    if opts.show_points && !opts.dense {
        for (c, _) in controls {
            for p in c.iter().filter(|p| finite(p)) {
                let (x, y) = f.px(*p);
                let _ = writeln!(s, r#"<circle cx="{x}" cy="{y}" r="4.2" fill="{INK}"/>"#);
            }
        }
    }
    let _ = writeln!(s, "</g>");
}

fn color(i: usize) -> &'static str {
    PALETTE[i % PALETTE.len()]
}

fn finite(p: &[f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

/// The control polygons to draw, each once (several curves of one data set
/// share their polygon).
fn distinct_controls(data: &[PlotData]) -> Vec<(Vec<[f64; 2]>, bool)> {
    let mut out: Vec<(Vec<[f64; 2]>, bool)> = Vec::new();
    for d in data {
        if d.control.is_empty() || out.iter().any(|(c, cl)| *c == d.control && *cl == d.closed) {
            continue;
        }
        out.push((d.control.clone(), d.closed));
    }
    out
}

fn write_points(s: &mut String, f: &Frame, pts: &[[f64; 2]]) {
    let mut first = true;
    for p in pts.iter().filter(|p| finite(p)) {
        let (x, y) = f.px(*p);
        let _ = write!(s, "{}{x},{y}", if first { "" } else { " " });
        first = false;
    }
}

/// Points as one path of round dots `size` pixels across, one per half
/// pixel at most: the size of the SVG follows the drawing, not the points.
fn write_marks(s: &mut String, f: &Frame, pts: &[[f64; 2]], color: &str, opacity: f64, size: f64) {
    let mut seen = std::collections::HashSet::new();
    let mut path = String::new();
    for p in pts.iter().filter(|p| finite(p)) {
        let (x, y) = f.px(*p);
        if seen.insert(((x.0 * 2.0).round() as i64, (y.0 * 2.0).round() as i64)) {
            let _ = write!(path, "M{x},{y}h0");
        }
    }
    if !path.is_empty() {
        let _ = writeln!(
            s,
            r#"<path d="{path}" stroke="{color}" stroke-opacity="{opacity}" stroke-width="{size}" stroke-linecap="round" fill="none"/>"#
        );
    }
}

/// The pieces in pixels, flattened: each cut into chords no longer than a
/// pixel (a chord of a cubic that short strays from it by far less than a
/// pixel), then thinned to the pixel grid. Where x never decreases (a graph
/// y(x)), every pixel column keeps its first, lowest, highest and last
/// point, which draws the same pixels as the whole polyline; elsewhere a
/// point within half a pixel of the last kept one is dropped.
fn dense_polyline(f: &Frame, segs: &[&[[f64; 2]; 4]]) -> Vec<[f64; 2]> {
    let px = |p: [f64; 2]| {
        let (x, y) = f.px(p);
        [x.0, y.0]
    };
    let mut pts: Vec<[f64; 2]> = Vec::new();
    for seg in segs {
        let c = seg.map(px);
        let reach = (1..4)
            .map(|k| (c[k][0] - c[k - 1][0]).hypot(c[k][1] - c[k - 1][1]))
            .sum::<f64>();
        let n = (reach.ceil() as usize).clamp(1, 64);
        if pts.last() != Some(&c[0]) {
            pts.push(c[0]);
        }
        for k in 1..=n {
            let t = k as f64 / n as f64;
            let u = 1.0 - t;
            let b = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
            pts.push([
                b[0] * c[0][0] + b[1] * c[1][0] + b[2] * c[2][0] + b[3] * c[3][0],
                b[0] * c[0][1] + b[1] * c[1][1] + b[2] * c[2][1] + b[3] * c[3][1],
            ]);
        }
    }
    if pts.windows(2).all(|w| w[1][0] >= w[0][0]) {
        let mut out: Vec<[f64; 2]> = Vec::new();
        let mut start = 0;
        while start < pts.len() {
            let column = pts[start][0].floor();
            let end = pts[start..]
                .iter()
                .position(|p| p[0].floor() != column)
                .map_or(pts.len(), |k| start + k);
            let run = &pts[start..end];
            let by_y = |a: &&[f64; 2], b: &&[f64; 2]| a[1].total_cmp(&b[1]);
            let lo = run
                .iter()
                .enumerate()
                .min_by(|a, b| by_y(&a.1, &b.1))
                .map_or(0, |m| m.0);
            let hi = run
                .iter()
                .enumerate()
                .max_by(|a, b| by_y(&a.1, &b.1))
                .map_or(0, |m| m.0);
            let mut keep = [0, lo, hi, run.len() - 1];
            keep.sort_unstable();
            let mut last = None;
            for k in keep {
                if last != Some(k) {
                    out.push(run[k]);
                    last = Some(k);
                }
            }
            start = end;
        }
        out
    } else {
        let mut out: Vec<[f64; 2]> = Vec::with_capacity(pts.len());
        for (i, p) in pts.iter().enumerate() {
            let near = out
                .last()
                .is_some_and(|q: &[f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]) < 0.5);
            if !near || i + 1 == pts.len() {
                out.push(*p);
            }
        }
        out
    }
}

fn write_curve(s: &mut String, f: &Frame, d: &PlotData, color: &str, dense: bool) {
    let mut path = String::new();
    let segs: Vec<&[[f64; 2]; 4]> = d.segments.iter().filter(|p| p.iter().all(finite)).collect();
    if dense && segs.len() as f64 > f.w / 2.0 {
        for (i, p) in dense_polyline(f, &segs).iter().enumerate() {
            let _ = write!(
                path,
                "{}{},{}",
                if i == 0 { "M" } else { "L" },
                Num(p[0]),
                Num(p[1])
            );
        }
    } else if !segs.is_empty() {
        let segs_first = segs.first().map(|p| p[0]);
        let mut last: Option<[f64; 2]> = None;
        for p in segs {
            if last != Some(p[0]) {
                let (x, y) = f.px(p[0]);
                let _ = write!(path, "M{x},{y}");
            }
            let (a, b, c) = (f.px(p[1]), f.px(p[2]), f.px(p[3]));
            let _ = write!(path, "C{},{} {},{} {},{}", a.0, a.1, b.0, b.1, c.0, c.1);
            last = Some(p[3]);
        }
        if d.closed && segs_first == last {
            path.push('Z');
        }
    } else {
        for (i, p) in d.curve.iter().filter(|p| finite(p)).enumerate() {
            let (x, y) = f.px(*p);
            let _ = write!(path, "{}{x},{y}", if i == 0 { "M" } else { "L" });
        }
    }
    if !path.is_empty() {
        let _ = writeln!(
            s,
            r#"<path d="{path}" fill="none" stroke="{color}" stroke-width="2.4" stroke-linejoin="round" stroke-linecap="round"/>"#
        );
    }
}

fn write_axes(s: &mut String, f: &Frame) {
    let (l, t, r, b) = (f.left, f.top, f.left + f.w, f.top + f.h);
    let _ = writeln!(s, r#"<g stroke="{GRID}" stroke-width="1">"#);
    for v in &f.x.ticks {
        let (x, _) = f.px([*v, f.y.lo]);
        let _ = writeln!(
            s,
            r#"<line x1="{x}" y1="{}" x2="{x}" y2="{}"/>"#,
            Num(t),
            Num(b)
        );
    }
    for v in &f.y.ticks {
        let (_, y) = f.px([f.x.lo, *v]);
        let _ = writeln!(
            s,
            r#"<line x1="{}" y1="{y}" x2="{}" y2="{y}"/>"#,
            Num(l),
            Num(r)
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<path d="M{},{} H{} M{},{} V{}" fill="none" stroke="{AXIS}" stroke-width="1.2"/>"#,
        Num(l),
        Num(b),
        Num(r),
        Num(l),
        Num(b),
        Num(t)
    );
    let _ = writeln!(s, r#"<g font-size="{TICK_FONT}" fill="{AXIS}">"#);
    for v in &f.x.ticks {
        let (x, _) = f.px([*v, f.y.lo]);
        let _ = writeln!(
            s,
            r#"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="{AXIS}" stroke-width="1.2"/>"#,
            Num(b),
            Num(b + 5.0)
        );
        let _ = writeln!(
            s,
            r#"<text x="{x}" y="{}" text-anchor="middle">{}</text>"#,
            Num(b + 8.0 + TICK_FONT),
            xml_escape(&f.x.label(*v))
        );
    }
    for v in &f.y.ticks {
        let (_, y) = f.px([f.x.lo, *v]);
        let _ = writeln!(
            s,
            r#"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="{AXIS}" stroke-width="1.2"/>"#,
            Num(l - 5.0),
            Num(l)
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="end">{}</text>"#,
            Num(l - 8.0),
            Num(y.0 + TICK_FONT * 0.35),
            xml_escape(&f.y.label(*v))
        );
    }
    let _ = writeln!(s, "</g>");
}

fn write_key(s: &mut String, (key, text): &(Key, String), x: f64, y: f64, sym: f64) {
    let (x0, x1, xm) = (Num(x), Num(x + sym), Num(x + sym / 2.0));
    let yy = Num(y);
    match key {
        Key::Line { color, dash, width } => {
            let dash = dash
                .map(|d| format!(r#" stroke-dasharray="{d}""#))
                .unwrap_or_default();
            let _ = writeln!(
                s,
                r#"<line x1="{x0}" y1="{yy}" x2="{x1}" y2="{yy}" stroke="{color}" stroke-width="{}"{dash}/>"#,
                Num(*width)
            );
        }
        Key::Dot => {
            let _ = writeln!(s, r#"<circle cx="{xm}" cy="{yy}" r="4.2" fill="{INK}"/>"#);
        }
        Key::Speck => {
            let _ = writeln!(
                s,
                r#"<circle cx="{xm}" cy="{yy}" r="2.2" fill="{INK}" fill-opacity="0.45"/>"#
            );
        }
        Key::Ring(c) => {
            let _ = writeln!(
                s,
                r#"<circle cx="{xm}" cy="{yy}" r="4" fill="white" stroke="{c}" stroke-width="1.8"/>"#
            );
        }
        Key::Square(c) => {
            let _ = writeln!(
                s,
                r#"<rect x="{}" y="{}" width="7" height="7" fill="{c}" transform="rotate(45 {xm} {yy})"/>"#,
                Num(x + sym / 2.0 - 3.5),
                Num(y - 3.5)
            );
        }
        Key::Band(c) => {
            let _ = writeln!(
                s,
                r#"<rect x="{x0}" y="{}" width="{}" height="12" fill="{c}" fill-opacity="0.18"/>"#,
                Num(y - 6.0),
                Num(sym)
            );
        }
        Key::Area => {
            let _ = writeln!(
                s,
                r#"<rect x="{x0}" y="{}" width="{}" height="12" fill="{HULL}" fill-opacity="0.07" stroke="{HULL}" stroke-opacity="0.35"/>"#,
                Num(y - 6.0),
                Num(sym)
            );
        }
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-size="{TICK_FONT}" fill="{INK}">{}</text>"#,
        Num(x + sym + 6.0),
        Num(y + TICK_FONT * 0.35),
        xml_escape(text)
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::tests::example;

    fn count(doc: &roxmltree::Document<'_>, tag: &str) -> usize {
        doc.descendants().filter(|n| n.has_tag_name(tag)).count()
    }

    #[test]
    fn svg_of_example_1_is_well_formed_and_complete() {
        let opts = PlotOptions {
            title: Some("Example 1 <alpha = 1/2> & \"more\"".into()),
            show_hull: true,
            show_knots: true,
            ..PlotOptions::default()
        };
        let svg = render_svg(&[example(1, 0.5)], &opts);
        let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
        // 11 control points + 10 tangent points + 2 legend symbols.
        assert_eq!(count(&doc, "circle"), 11 + 10 + 2, "{svg}");
        let curve = doc
            .descendants()
            .find(|n| n.attribute("stroke") == Some(PALETTE[0]) && n.has_tag_name("path"))
            .expect("the spline is drawn");
        assert_eq!(curve.attribute("d").unwrap().matches('C').count(), 10);
        assert_eq!(count(&doc, "polygon"), 1, "convex hull");
        let title = doc
            .descendants()
            .find(|n| n.text() == Some("Example 1 <alpha = 1/2> & \"more\""));
        assert!(title.is_some(), "title escaped and read back");
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
    }

    #[test]
    fn several_curves_share_one_polygon_and_get_a_legend() {
        let data: Vec<PlotData> = [1.0 / 3.0, 0.5, 2.0 / 3.0]
            .iter()
            .map(|a| {
                let mut d = example(1, *a);
                d.label = Some(format!("alpha = {a:.3}"));
                d
            })
            .collect();
        let svg = render_svg(&data, &PlotOptions::default());
        let doc = roxmltree::Document::parse(&svg).unwrap();
        assert_eq!(count(&doc, "polyline"), 1, "one control polygon");
        for d in &data {
            let label = d.label.as_deref().unwrap();
            assert!(
                doc.descendants().any(|n| n.text() == Some(label)),
                "{label}"
            );
        }
        for c in &PALETTE[..3] {
            assert!(svg.contains(&format!(r#"stroke="{c}" stroke-width="2.4""#)));
        }
    }

    #[test]
    fn closed_curve_with_equal_axes() {
        // A closed rectangle and a rounded curve inside it: piece k runs from the
        // middle of side k round corner k + 1 to the middle of side k + 1.
        let sq = [[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [0.0, 1.0]];
        let mid = |k: usize| {
            let (a, b) = (sq[k % 4], sq[(k + 1) % 4]);
            [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
        };
        let segments = (0..4)
            .map(|k| [mid(k), sq[(k + 1) % 4], sq[(k + 1) % 4], mid(k + 1)])
            .collect();
        let d = PlotData {
            control: sq.to_vec(),
            closed: true,
            segments,
            ..PlotData::default()
        };
        let opts = PlotOptions {
            equal_aspect: true,
            ..PlotOptions::default()
        };
        let svg = render_svg(&[d], &opts);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let poly = doc
            .descendants()
            .find(|n| n.has_tag_name("polygon"))
            .expect("a closed control polygon");
        let xy: Vec<f64> = poly
            .attribute("points")
            .unwrap()
            .split([' ', ','])
            .map(|v| v.parse().unwrap())
            .collect();
        // One unit is as long across as up: the 4 x 1 rectangle keeps its shape.
        let (w, h) = ((xy[2] - xy[0]).abs(), (xy[5] - xy[3]).abs());
        assert!((w / h - 4.0).abs() < 0.02, "width {w}, height {h}");
        let path = doc
            .descendants()
            .find(|n| n.attribute("stroke") == Some(PALETTE[0]) && n.has_tag_name("path"))
            .unwrap();
        let d = path.attribute("d").unwrap();
        assert_eq!(d.matches('M').count(), 1, "the pieces join: {d}");
        assert!(d.ends_with('Z'), "{d}");
    }

    #[test]
    fn odd_input_gives_a_finite_figure() {
        let data = [
            PlotData::polyline(
                "wild",
                vec![[f64::NAN, 1.0], [-f64::MAX, 1e308], [f64::MAX, -1e308]],
            ),
            PlotData::polyline("empty", Vec::new()),
            PlotData::polyline("\u{1}ctl\u{7}", vec![[3.0, 3.0]]),
        ];
        let tiny = PlotOptions {
            width: 0,
            height: 0,
            ..PlotOptions::default()
        };
        for opts in [PlotOptions::default(), tiny] {
            let svg = render_svg(&data, &opts);
            assert!(roxmltree::Document::parse(&svg).is_ok(), "{svg}");
            assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
        }
        let svg = render_svg(&[], &PlotOptions::default());
        assert!(roxmltree::Document::parse(&svg).is_ok());
    }
}
