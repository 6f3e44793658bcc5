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
