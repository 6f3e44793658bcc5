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
