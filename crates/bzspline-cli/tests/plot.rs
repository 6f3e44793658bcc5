//! Runs `bzspline plot` and checks the figures it writes.

use std::path::Path;
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_bzspline");

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .expect("the binary runs")
}

fn count(svg: &str, tag: &str) -> usize {
    let doc = roxmltree::Document::parse(svg).expect("the SVG is well-formed XML");
    doc.descendants().filter(|n| n.has_tag_name(tag)).count()
}

#[test]
fn without_input_it_draws_example_1() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &["plot", "-o", "fig.svg", "--title", "Example 1"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.path().join("fig.svg")).unwrap();
    // 11 control points, 10 tangent points and 2 legend symbols.
    assert_eq!(count(&svg, "circle"), 23, "{svg}");
    assert!(svg.contains(">Example 1</text>"));
    // Without -o the SVG goes to standard output.
    let out = run(dir.path(), &["plot", "--example", "2", "--knots"]);
    assert!(out.status.success());
    let svg = String::from_utf8(out.stdout).unwrap();
    assert_eq!(count(&svg, "circle"), 11 + 10 + 2, "{svg}");
}

#[test]
#[cfg(feature = "png")]
fn png_by_extension_and_closed_curves() {
    let dir = tempfile::tempdir().unwrap();
    let pts = dir.path().join("pentagon.csv");
    std::fs::write(&pts, "x,y\n0,0\n4,0\n4,3\n1,4\n-1,2\n").unwrap();
    let out = run(
        dir.path(),
        &["plot", "pentagon.csv", "--closed", "--hull", "-o", "c.PNG"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        let png = std::fs::read(dir.path().join("c.PNG")).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    } else {
        // A machine without fonts: the message says what to install.
        assert!(err.contains("fonts-dejavu-core"), "{err}");
    }
    let out = run(
        dir.path(),
        &["plot", "pentagon.csv", "--closed", "-o", "c.svg"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.path().join("c.svg")).unwrap();
    assert_eq!(count(&svg, "polygon"), 1, "closed control polygon");
    assert!(svg.contains("Z\""), "the closed path is closed: {svg}");
}

#[test]
fn alpha_sweep_and_overlays() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("o.json"),
        r#"[{"label": "other <method>", "points": [[1, 1], [11, 1.5]]}]"#,
    )
    .unwrap();
    let out = run(
        dir.path(),
        &[
            "plot",
            "--alpha-sweep",
            "1/3,1/2,2/3",
            "--overlay",
            "o.json",
            "-o",
            "a.svg",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.path().join("a.svg")).unwrap();
    for label in ["α = 1/3", "α = 1/2", "α = 2/3", "other &lt;method&gt;"] {
        assert!(svg.contains(label), "{label} missing");
    }
    let bad = run(dir.path(), &["plot", "--alpha-sweep", "0.2", "-o", "b.svg"]);
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        !bad.status.success() && err.contains("outside [1/3, 2/3]"),
        "{err}"
    );
    assert!(
        !dir.path().join("b.svg").exists(),
        "nothing written on error"
    );
    let bad = run(
        dir.path(),
        &["plot", "--overlay", "missing.json", "-o", "b.svg"],
    );
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        !bad.status.success() && err.contains("missing.json"),
        "{err}"
    );
}

#[test]
#[cfg(feature = "pdf")]
fn pdf_by_extension() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), &["plot", "--example", "1", "-o", "fig.pdf"]);
    let err = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        let pdf = std::fs::read(dir.path().join("fig.pdf")).unwrap();
        assert!(pdf.starts_with(b"%PDF-"), "not a PDF");
        let text = String::from_utf8_lossy(&pdf);
        assert_eq!(
            text.matches("/Type /Page\n").count() + text.matches("/Type /Page ").count(),
            1,
            "one page"
        );
    } else {
        // A machine without fonts: the message says what to install.
        assert!(err.contains("fonts"), "{err}");
    }
}

#[test]
fn a_clean_chart_line_and_its_labels() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("daily.csv"),
        "day,visitors\n2024-01-01,120\n2024-01-02,135\n2024-01-03,128\n2024-01-05,160\n",
    )
    .unwrap();
    let out = run(
        dir.path(),
        &[
            "plot",
            "daily.csv",
            "--no-points",
            "--no-polygon",
            "--no-tangents",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = String::from_utf8(out.stdout).unwrap();
    assert_eq!(count(&svg, "circle"), 0, "no markers: {svg}");
    assert!(!svg.contains("stroke-dasharray=\"6 4\""), "no polygon");
    // The header's names label the axes; the x ticks are dates.
    assert!(
        svg.contains(">day</text>") && svg.contains(">visitors</text>"),
        "{svg}"
    );
    assert!(svg.contains(">2024-01-02</text>"), "{svg}");
    // The data is drawn inside the plot area.
    assert!(svg.contains(r#"<g clip-path="url(#plot-area)">"#));
}

/// Values near the ends of the double range: the axis holds them all.
#[test]
fn axes_hold_the_whole_finite_range() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("huge.csv"),
        "0,1e308\n1,-1e308\n2,1.5e308\n3,-1.7e308\n",
    )
    .unwrap();
    let out = run(dir.path(), &["plot", "huge.csv"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = String::from_utf8(out.stdout).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    // Every control point's dot lies inside the plot area's clip rectangle.
    let clip = doc
        .descendants()
        .find(|n| n.has_tag_name("clipPath"))
        .unwrap();
    let rect = clip.children().find(|n| n.has_tag_name("rect")).unwrap();
    let num = |n: &roxmltree::Node, a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
    let (top, h) = (num(&rect, "y"), num(&rect, "height"));
    let dots: Vec<f64> = doc
        .descendants()
        .filter(|n| n.has_tag_name("circle") && n.attribute("r") == Some("4.2"))
        .map(|n| num(&n, "cy"))
        .collect();
    assert_eq!(
        dots.len(),
        4 + 1,
        "four control points and the legend's dot"
    );
    for cy in &dots[..4] {
        assert!(
            *cy > top && *cy < top + h,
            "{cy} outside {top}..{}",
            top + h
        );
    }
}

/// The `d` of the widest-stroked path (the spline), as its commands: a
/// letter and its numbers.
fn spline_path(svg: &str) -> Vec<(char, Vec<f64>)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let d = doc
        .descendants()
        .filter(|n| n.has_tag_name("path") && n.attribute("stroke-width") == Some("2.4"))
        .filter_map(|n| n.attribute("d"))
        .max_by_key(|d| d.len())
        .expect("a spline path")
        .to_string();
    let mut out: Vec<(char, Vec<f64>)> = Vec::new();
    let mut num = String::new();
    for c in d.chars().chain(std::iter::once('E')) {
        if c.is_ascii_alphabetic() && c != 'e' || c == ',' || c == ' ' {
            if !num.is_empty() {
                out.last_mut().unwrap().1.push(num.parse().unwrap());
                num.clear();
            }
            if c.is_ascii_alphabetic() && c != 'E' {
                out.push((c, Vec::new()));
            }
        } else {
            num.push(c);
        }
    }
    out
}

/// A 5,000-point noisy series plotted with the defaults is a chart: a small
/// SVG, no control polygon or rings, and a line that draws the same pixels
/// as the spline's pieces (checked against the pieces flattened here).
#[test]
fn many_points_draw_a_small_readable_chart() {
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("t,v\n");
    let mut state = 12345u64;
    for i in 0..5000 {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let noise = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let x = f64::from(i);
        csv.push_str(&format!(
            "{x},{}\n",
            (x / 300.0).sin() * 100.0 + 20.0 * noise
        ));
    }
    std::fs::write(dir.path().join("series.csv"), csv).unwrap();
    let out = run(dir.path(), &["plot", "series.csv", "-o", "dense.svg"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.path().join("dense.svg")).unwrap();
    assert!(svg.len() < 200_000, "{} bytes", svg.len());
    assert!(
        !svg.contains("stroke-dasharray=\"6 4\""),
        "no control polygon"
    );
    assert!(count(&svg, "circle") <= 2, "only the legend's symbols");
    let line = spline_path(&svg);
    assert!(line.iter().all(|(c, _)| *c == 'M' || *c == 'L'));

    // The same figure with every point asked for draws the pieces exactly.
    let out = run(
        dir.path(),
        &["plot", "series.csv", "--points", "-o", "full.svg"],
    );
    assert!(out.status.success());
    let full = std::fs::read_to_string(dir.path().join("full.svg")).unwrap();
    assert!(full.len() > 2 * svg.len());
    let pieces = spline_path(&full);
    assert_eq!(pieces.iter().filter(|(c, _)| *c == 'C').count(), 4999);
    // Flatten every piece to 0.05 px steps and bin the points by pixel column.
    let mut columns: std::collections::BTreeMap<i64, Vec<[f64; 2]>> = Default::default();
    let mut at = [0.0; 2];
    for (c, v) in &pieces {
        if *c == 'M' {
            at = [v[0], v[1]];
            continue;
        }
        let p = [at, [v[0], v[1]], [v[2], v[3]], [v[4], v[5]]];
        let reach: f64 = (1..4)
            .map(|k| (p[k][0] - p[k - 1][0]).hypot(p[k][1] - p[k - 1][1]))
            .sum();
        let n = (reach / 0.05).ceil().max(1.0) as usize;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            let u = 1.0 - t;
            let b = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
            let q = [0, 1].map(|j| (0..4).map(|i| b[i] * p[i][j]).sum::<f64>());
            columns.entry(q[0].floor() as i64).or_default().push(q);
        }
        at = p[3];
    }
    // Every vertex of the chart's line lies on the spline.
    let mut drawn: std::collections::BTreeMap<i64, (f64, f64)> = Default::default();
    for (_, v) in &line {
        let q = [v[0], v[1]];
        let col = q[0].floor() as i64;
        let near = (col - 1..=col + 1)
            .filter_map(|c| columns.get(&c))
            .flatten()
            .map(|p| (p[0] - q[0]).hypot(p[1] - q[1]))
            .fold(f64::INFINITY, f64::min);
        assert!(near < 0.06, "vertex {q:?} is {near} px off the spline");
        let e = drawn
            .entry(col)
            .or_insert((f64::INFINITY, f64::NEG_INFINITY));
        *e = (e.0.min(q[1]), e.1.max(q[1]));
    }
    // And the line reaches the spline's lowest and highest point in every
    // pixel column (give or take the column beside it: the SVG's numbers
    // are rounded to a hundredth of a pixel, which may move a vertex on a
    // column's edge across it).
    for (col, pts) in &columns {
        let lo = pts.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let hi = pts.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        let (dlo, dhi) = (col - 1..=col + 1)
            .filter_map(|c| drawn.get(&c))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, b| {
                (a.0.min(b.0), a.1.max(b.1))
            });
        assert!(
            dlo < lo + 0.5 && dhi > hi - 0.5,
            "column {col}: spline {lo}..{hi}, drawn {dlo}..{dhi}"
        );
    }
}

#[test]
fn date_ticks_are_no_finer_than_the_data() {
    let dir = tempfile::tempdir().unwrap();
    // Four months of monthly values, a span that alone would get day ticks.
    std::fs::write(
        dir.path().join("monthly.csv"),
        "month,v\n2020-01,3\n2020-02,5\n2020-03,4\n2020-04,6\n",
    )
    .unwrap();
    let out = run(dir.path(), &["plot", "monthly.csv", "-o", "m.svg"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.path().join("m.svg")).unwrap();
    for month in ["2020-01", "2020-02", "2020-03", "2020-04"] {
        assert!(
            svg.contains(&format!(">{month}</text>")),
            "a tick at {month}"
        );
    }
    // No tick label with a day in it.
    let days = svg
        .match_indices(">2020-")
        .filter(|(i, _)| svg[i + 8..].starts_with('-'));
    assert_eq!(days.count(), 0, "{svg}");
}
