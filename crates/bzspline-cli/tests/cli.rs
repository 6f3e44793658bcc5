//! Runs the real `bzspline` binary on the fixture files and checks its output
//! against the library.

use bzspline::Arclen;
use bzspline::Flatten;
use std::io::Read;
use std::process::{Command, Stdio};

use bzspline::Spline;
use serde_json::Value;

mod common;

use common::{assert_data_error, fixture, ok, run, BIN};

fn example1() -> Spline {
    let x: Vec<f64> = (1..=11).map(f64::from).collect();
    let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
    Spline::new(&x, &f).unwrap()
}

fn example2() -> Spline {
    let x: Vec<f64> = (0..=10).map(|i| f64::from(i) / 10.0).collect();
    let f = [
        0.0,
        0.3,
        0.4,
        0.458257569,
        0.489897949,
        0.5,
        0.4898979495,
        0.458257569,
        0.4,
        0.3,
        0.0,
    ];
    Spline::new(&x, &f).unwrap()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// Checks the fit object against the library's spline, number for number.
fn check_fit_json(text: &str, s: &Spline) {
    let v: Value = serde_json::from_str(text).expect("fit prints JSON");
    for key in [
        "knots",
        "alphas",
        "knot_values",
        "tangent_points",
        "segments",
        "closed",
        "dimension",
        "svg_path",
    ] {
        assert!(v.get(key).is_some(), "key {key} missing in {text}");
    }
    let n = s.knots().len();
    assert_eq!(numbers(&v["knots"]), s.knots());
    assert_eq!(numbers(&v["alphas"]), s.alphas());
    // serde_json prints the shortest form that parses back to the same double,
    // so equality is exact.
    assert_eq!(numbers(&v["knot_values"]), s.knot_values());
    let tp = v["tangent_points"].as_array().unwrap();
    assert_eq!(tp.len(), n - 1);
    for (p, (x, f)) in tp.iter().zip(s.tangent_points()) {
        assert_eq!(numbers(p), vec![x, f]);
    }
    let segs = v["segments"].as_array().unwrap();
    assert_eq!(segs.len(), n - 1);
    for (seg, want) in segs.iter().zip(s.segments()) {
        let pts = seg.as_array().unwrap();
        assert_eq!(pts.len(), 4);
        for (p, w) in pts.iter().zip(want.p) {
            assert_eq!(numbers(p), w.to_vec());
        }
    }
    assert_eq!(v["closed"], Value::Bool(false));
    assert_eq!(v["dimension"], 1);
}

#[test]
fn fit_prints_both_examples_as_the_library_computes_them() {
    check_fit_json(&ok(&["fit", "--example", "1"]), &example1());
    check_fit_json(
        &ok(&["fit", "--example", "2", "--format", "json"]),
        &example2(),
    );
}

#[test]
fn fit_reads_a_file_and_stdin_alike() {
    let from_file = ok(&["fit", "example1.csv"]);
    check_fit_json(&from_file, &example1());
    let bytes = std::fs::read(fixture("example1.csv")).unwrap();
    for args in [&["fit"][..], &["fit", "-"][..]] {
        let o = run(args, Some(&bytes));
        assert_eq!(o.code, 0, "{}", o.stderr);
        assert_eq!(o.stdout, from_file, "stdin and file differ for {args:?}");
    }
}

#[test]
fn fit_accepts_messy_tables_tsv_and_json() {
    let csv = ok(&["fit", "messy.csv", "--format", "csv"]);
    let first: Vec<&str> = csv.lines().take(2).collect();
    assert_eq!(first, ["x,y", "0,1e-3"]);
    // 3 segments of 4 control points, after the header.
    assert_eq!(csv.lines().count(), 1 + 3 * 4);
    let s = Spline::new(&[0.0, 0.5, 1.5, 2.0], &[1e-3, 2.0, -1.0, 0.25]).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let want: Vec<Vec<f64>> = s
        .segments()
        .iter()
        .flat_map(|b| b.p.map(|p| p.to_vec()))
        .collect();
    assert_eq!(rows, want);

    let tsv = ok(&["fit", "tabs.tsv", "--format", "svg"]);
    let txt = ok(&[
        "fit",
        "tabs.txt",
        "--input-format",
        "tsv",
        "--format",
        "svg",
    ]);
    assert_eq!(tsv, txt);
    assert!(tsv.starts_with("M 0 0 C "), "{tsv}");
    assert_eq!(tsv.matches(" C ").count(), 2);

    let json = ok(&["fit", "points.json"]);
    let s = Spline::new(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, 0.0, 2.0]).unwrap();
    check_fit_json(&json, &s);
}

#[test]
fn fit_json_output_reads_back_as_input() {
    let first = ok(&["fit", "--example", "1", "-o", "-"]);
    let o = run(&["fit", "--input-format", "json"], Some(first.as_bytes()));
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(o.stdout, first);
}

#[test]
fn alphas_per_interval_reach_the_library() {
    let alphas = "0.4,0.5,0.6,0.5,0.4,0.6,0.5,0.45,0.55,0.5";
    let text = ok(&["fit", "--example", "1", "--alphas", alphas]);
    let a: Vec<f64> = alphas.split(',').map(|v| v.parse().unwrap()).collect();
    let x: Vec<f64> = (1..=11).map(f64::from).collect();
    let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
    check_fit_json(&text, &Spline::with_alphas(&x, &f, &a).unwrap());
    let text = ok(&["fit", "--example", "1", "--alpha", "0.4"]);
    check_fit_json(&text, &Spline::with_alpha(&x, &f, 0.4).unwrap());
}

#[test]
fn bad_tables_name_the_file_and_line() {
    let cases: &[(&str, &[&str])] = &[
        ("bad_nan.csv", &["bad_nan.csv:3:", "not a finite number"]),
        ("bad_inf.csv", &["bad_inf.csv:4:", "not a finite number"]),
        ("bad_overflow.csv", &["bad_overflow.csv:3:", "1e400"]),
        (
            "bad_not_increasing.csv",
            &["bad_not_increasing.csv:6:", "on line 4", "increasing"],
        ),
        (
            "bad_decreasing.csv",
            &["bad_decreasing.csv:4:", "on line 3"],
        ),
        ("bad_one_point.csv", &["bad_one_point.csv:2:", "at least 2"]),
        (
            "bad_ragged.csv",
            &["bad_ragged.csv:3:", "3 fields", "line 2 has 2"],
        ),
        (
            "bad_comma_decimal.csv",
            &["bad_comma_decimal.csv:3:", "decimal separator"],
        ),
        (
            "bad_header_middle.csv",
            &["bad_header_middle.csv:4:", "header"],
        ),
        (
            "bad_field.csv",
            &["bad_field.csv:4:", "'x' is not a number"],
        ),
        ("empty.csv", &["empty.csv:1:", "no data"]),
        ("only_comments.csv", &["only_comments.csv:3:", "no data"]),
        ("bad_utf8.csv", &["bad_utf8.csv:3:", "UTF-8"]),
        (
            "bad_quoted_newline.csv",
            &["bad_quoted_newline.csv:3:", "'a\\nb' is not a number"],
        ),
        ("bad_syntax.json", &["bad_syntax.json:4:", "invalid JSON"]),
        (
            "bad_not_increasing.json",
            &["bad_not_increasing.json: point [2]", "point [1]"],
        ),
    ];
    for (file, wants) in cases {
        for cmd in [
            &["fit", file][..],
            &["eval", file, "--at", "1"][..],
            &["sample", file, "--n", "3"][..],
        ] {
            assert_data_error(cmd, None, wants);
        }
    }
}

#[test]
fn bad_stdin_is_named_stdin() {
    assert_data_error(
        &["fit"],
        Some(b"1,2\n3,4\n2,1\n"),
        &["<stdin>:3:", "on line 2"],
    );
}

#[test]
fn bad_alphas_name_which() {
    // Alphas out of range are usage errors (tests/usage.rs); a count that
    // does not match the data is the data's error.
    assert_data_error(
        &["fit", "--example", "1", "--alphas", "0.5,0.5"],
        None,
        &["--alphas has 2 values", "need 10"],
    );
    assert_data_error(
        &["fit", "example1.csv", "--alphas", "0.5,0.5"],
        None,
        &["--alphas has 2 values", "example1.csv"],
    );
}

/// One way to write numbers everywhere: the shortest text that reads back
/// exactly, never hundreds of digits.
#[test]
fn huge_values_are_written_short_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("big.csv");
    std::fs::write(&p, "0,1e300\n1,-2e300\n2,3e300\n").unwrap();
    let p = p.to_str().unwrap();
    let svg = ok(&["fit", p, "--format", "svg"]);
    assert!(svg.starts_with("M 0 1e300 C "), "{svg}");
    assert!(svg.split(' ').all(|w| w.len() <= 24), "{svg}");
    let csv = ok(&["fit", p, "--format", "csv"]);
    assert!(csv.lines().nth(1) == Some("0,1e300"), "{csv}");
    let json = ok(&["fit", p]);
    assert!(json.contains("\"values\": [1e300,-2e300,3e300]"), "{json}");
    let sample = ok(&["sample", p, "--n", "3"]);
    for line in sample.lines().skip(1) {
        for cell in line.split(',') {
            let v: f64 = cell.parse().unwrap();
            assert_eq!(bzspline::text::Shortest(v).to_string(), cell);
        }
    }
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["fit", "--alpha", "0.5", "--alphas", "0.5"][..],
        &["fit", "--example", "3"][..],
        &["eval", "--example", "1"][..],
        &["sample", "--example", "1"][..],
        &["sample", "--example", "1", "--n", "3", "--step", "1"][..],
        &["fit", "--format", "xml"][..],
        &["nonsense"][..],
        &["smooth", "shapes.geojson", "--tolerance", "0"][..],
        &["smooth", "shapes.geojson", "--tolerance", "-1"][..],
        &["smooth", "shapes.geojson", "--tolerance", "x"][..],
        &["smooth", "shapes.geojson", "--snap", "-1"][..],
        &["smooth", "shapes.geojson", "--keep-angle", "200"][..],
        &["smooth", "shapes.geojson", "--independent", "--snap", "0.1"][..],
        &[
            "smooth",
            "shapes.geojson",
            "--independent",
            "--output-format",
            "topojson",
        ][..],
        &["smooth", "lines.geojsonl", "--output-format", "topojson"][..],
        &["smooth", "shapes.geojson", "--output-format", "shapefile"][..],
    ] {
        let o = run(args, None);
        assert_eq!(o.code, 2, "{args:?}: {}", o.stderr);
        assert!(o.stdout.is_empty());
    }
}

#[test]
fn output_file_is_written_on_success() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit.json");
    let o = run(
        &["fit", "--example", "2", "-o", out.to_str().unwrap()],
        None,
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stdout.is_empty(), "stdout should be empty with -o");
    let text = std::fs::read_to_string(&out).unwrap();
    check_fit_json(&text, &example2());
}

fn csv_rows(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines
        .next()
        .expect("a header")
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse().expect("a number")).collect())
        .collect();
    (header, rows)
}

#[test]
fn eval_matches_the_library() {
    let s = example1();
    let text = ok(&[
        "eval",
        "--example",
        "1",
        "--at",
        "1,1.5,2.5,7.25,11",
        "--derivative",
        "1",
        "--derivative",
        "2,3",
    ]);
    let (header, rows) = csv_rows(&text);
    assert_eq!(header, ["x", "y", "dy", "d2y", "d3y"]);
    assert_eq!(rows.len(), 5);
    for r in &rows {
        let x = r[0];
        assert_eq!(r[1], s.eval(x).unwrap(), "y at {x}");
        for k in 1..=3 {
            assert_eq!(r[1 + k as usize], s.deriv(x, k).unwrap(), "d{k}y at {x}");
        }
    }
    let text = ok(&[
        "eval",
        "example1.csv",
        "--at-file",
        "xs.txt",
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(numbers(&v["x"]), [1.5, 2.5, 10.75]);
    let want: Vec<f64> = [1.5, 2.5, 10.75]
        .iter()
        .map(|&x| s.eval(x).unwrap())
        .collect();
    assert_eq!(numbers(&v["y"]), want);
}

#[test]
fn eval_outside_the_span_follows_the_policy() {
    assert_data_error(
        &["eval", "--example", "1", "--at-file", "xs_outside.txt"],
        None,
        &["xs_outside.txt:2:", "outside the domain [1, 11]"],
    );
    assert_data_error(
        &["eval", "--example", "1", "--at", "2,0"],
        None,
        &["--at value 2", "outside"],
    );
    let (_, rows) = csv_rows(&ok(&[
        "eval",
        "--example",
        "1",
        "--at",
        "0,12",
        "--extrapolate",
        "clamp",
    ]));
    assert_eq!(rows, [vec![0.0, 1.0], vec![12.0, 1.5]]);
    let s = example1().with_extrapolation(bzspline::Extrapolate::Extend);
    let (_, rows) = csv_rows(&ok(&[
        "eval",
        "--example",
        "1",
        "--at",
        "0.5",
        "--extrapolate",
        "extend",
    ]));
    assert_eq!(rows[0][1], s.eval(0.5).unwrap());
}

#[test]
fn sample_n_matches_the_library() {
    let s = example2();
    let text = ok(&["sample", "--example", "2", "--n", "21", "--derivative", "1"]);
    let (header, rows) = csv_rows(&text);
    assert_eq!(header, ["x", "y", "dy"]);
    assert_eq!(rows.len(), 21);
    assert_eq!(rows[0][0], 0.0);
    assert_eq!(rows[20][0], 1.0, "the last point is the end of the span");
    for r in &rows {
        assert_eq!(r[1], s.eval(r[0]).unwrap());
        assert_eq!(r[2], s.deriv(r[0], 1).unwrap());
    }
}

#[test]
fn sample_tolerance_keeps_the_knots_and_the_chords_close() {
    let s = example1();
    let text = ok(&["sample", "--example", "1", "--tolerance", "0.01"]);
    let (_, rows) = csv_rows(&text);
    let xs: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    for k in s.knots() {
        assert!(xs.contains(k), "knot {k} missing");
    }
    for w in rows.windows(2) {
        let xm = 0.5 * (w[0][0] + w[1][0]);
        let chord = 0.5 * (w[0][1] + w[1][1]);
        let slope = (w[1][1] - w[0][1]) / (w[1][0] - w[0][0]);
        let dist = (s.eval(xm).unwrap() - chord).abs() / slope.hypot(1.0);
        assert!(dist <= 0.01 * 1.0001, "distance {dist} at x = {xm}");
    }
}

#[test]
fn a_closed_pipe_is_not_an_error() {
    let mut child = Command::new(BIN)
        .args(["sample", "--example", "1", "--n", "1000000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 16];
    stdout.read_exact(&mut first).unwrap();
    assert_eq!(&first[..6], b"x,y\n1,", "unexpected start of output");
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(
        out.stderr.is_empty(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The README's Rust start (and `docs/library.md`'s), kept compiling and true.
#[test]
fn readme_library_snippet_holds() -> Result<(), bzspline::Error> {
    let tau: Vec<f64> = (1..=11).map(f64::from).collect();
    let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
    let s = Spline::with_alpha(&tau, &f, 0.5)?;
    assert_eq!(s.eval(2.5)?, 3.0);
    assert!(s.deriv(2.5, 1)?.abs() < 1e-12);
    assert_eq!(s.knot_values().len(), 11);
    assert_eq!(s.segments().len(), 10);
    Ok(())
}

/// The guide's tour (`docs/command.md`) and maps page show this output;
/// keep it true.
#[test]
fn readme_tour_output_is_current() {
    let dir = tempfile::tempdir().unwrap();
    let pts = dir.path().join("pts.csv");
    std::fs::write(&pts, "# x, y\n0, 0\n1, 2\n2, 1\n4, 3\n").unwrap();
    let p = pts.to_str().unwrap();
    assert_eq!(
        ok(&["eval", p, "--at", "0.5,1,3", "--derivative", "1,2"]),
        "x,y,dy,d2y\n0.5,1,2,-1.1081081081081083\n1,1.722972972972973,0.6148648648648649,-6.27027027027027\n3,2,1,0.22972972972972971\n"
    );
    assert_eq!(
        ok(&["sample", p, "--n", "5", "--format", "json"]),
        "{\n  \"x\": [0,1,2,3,4],\n  \"y\": [0,1.722972972972973,1.2297297297297298,2,3]\n}\n"
    );
    let readme = common::guide();
    let fit = ok(&["fit", p]);
    assert!(
        readme.contains(&fit),
        "the guide's fit output is stale:\n{fit}"
    );
    for args in [
        &["fit", "square.csv", "--closed", "--format", "svg"][..],
        &[
            "eval",
            "square.csv",
            "--closed",
            "--at",
            "0.5,1",
            "--derivative",
            "1",
        ][..],
        &["sample", "square.csv", "--closed", "--step", "0.5"][..],
    ] {
        let out = ok(args);
        assert!(
            readme.contains(&out),
            "the guide's output of {args:?} is stale:\n{out}"
        );
    }
    for args in [
        &["eval", "noisy.csv", "--smooth", "auto", "--at", "1.5,4.7,8"][..],
        &["fit", "noisy.csv", "--smooth", "auto"][..],
    ] {
        let out = ok(args);
        let tail: String = out
            .lines()
            .rev()
            .take(4)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .map(|l| format!("{l}\n"))
            .collect();
        assert!(
            readme.contains(&tail),
            "the guide's output of {args:?} is stale:\n{tail}"
        );
    }
    let road = dir.path().join("road.geojson");
    std::fs::write(
        &road,
        r#"{"type":"Feature","properties":{"name":"road"},"geometry":{"type":"LineString","coordinates":[[0,0],[1,2],[3,2],[4,0]]}}"#,
    )
    .unwrap();
    let out = ok(&["smooth", road.to_str().unwrap(), "--tolerance", "0.1"]);
    assert!(
        readme.contains(&out),
        "the guide's smooth output is stale:\n{out}"
    );
}

fn square() -> bzspline::Curve {
    bzspline::Curve::closed(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap()
}

fn helix(param: bzspline::Param) -> bzspline::Curve {
    let pts = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 2.0],
        [0.0, 1.0, 3.0],
        [0.0, 0.0, 4.0],
    ];
    bzspline::Curve::builder_from(&pts)
        .param(param)
        .build()
        .unwrap()
}

fn points(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(numbers)
        .collect()
}

#[test]
fn fit_closed_curve_pulls_the_square_inside() {
    let text = ok(&["fit", "square.csv", "--closed"]);
    let v: Value = serde_json::from_str(&text).unwrap();
    let c = square();
    assert_eq!(v["closed"], Value::Bool(true));
    assert_eq!(v["dimension"], 2);
    assert_eq!(numbers(&v["knots"]), c.knots());
    assert_eq!(numbers(&v["knots"]).len(), 5, "N + 1 knots");
    let kv = points(&v["knot_values"]);
    assert_eq!(kv.len(), 5, "N + 1 knot values");
    assert_eq!(kv[0], kv[4], "last knot value = first");
    for (got, want) in kv
        .iter()
        .zip([[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]])
    {
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-15, "knot value {got:?}, want {want:?}");
        }
    }
    assert_eq!(kv[..4], c.knot_points()[..]);
    let segs = v["segments"].as_array().unwrap();
    assert_eq!(segs.len(), 4);
    for (k, seg) in segs.iter().enumerate() {
        let flat: Vec<f64> = points(seg).concat();
        assert_eq!(flat, c.segment_points(k).unwrap());
    }
    let path = v["svg_path"].as_str().unwrap();
    assert!(path.ends_with('Z'), "{path}");
    assert_eq!(
        ok(&["fit", "square.csv", "--closed", "--format", "svg"]),
        format!("{path}\n")
    );
}

#[test]
fn fit_3d_curve_lists_control_points_per_row() {
    let c = helix(bzspline::Param::Chordal);
    let text = ok(&[
        "fit",
        "helix.csv",
        "--curve",
        "--param",
        "chordal",
        "--format",
        "csv",
    ]);
    let (header, rows) = csv_rows(&text);
    assert_eq!(header, ["x", "y", "z"]);
    assert_eq!(rows.len(), 4 * c.len());
    let want: Vec<f64> = (0..c.len())
        .flat_map(|k| c.segment_points(k).unwrap())
        .collect();
    assert_eq!(rows.concat(), want);
    let v: Value = serde_json::from_str(&ok(&["fit", "helix.csv", "--curve"])).unwrap();
    assert_eq!(v["dimension"], 3);
    assert_eq!(v["svg_path"], Value::Null);
    // Without --param, the library's default (centripetal).
    assert_eq!(
        points(&v["knot_values"]),
        helix(bzspline::Param::default()).knot_points()
    );
}

#[test]
fn eval_and_sample_curves_match_the_library() {
    let c = helix(bzspline::Param::Centripetal);
    let text = ok(&[
        "eval",
        "helix.csv",
        "--curve",
        "--param",
        "centripetal",
        "--at",
        "0,0.7,2.1",
        "--derivative",
        "1",
    ]);
    let (header, rows) = csv_rows(&text);
    assert_eq!(header, ["t", "x", "y", "z", "dx", "dy", "dz"]);
    for r in &rows {
        assert_eq!(r[1..4], c.eval(r[0]).unwrap()[..]);
        assert_eq!(r[4..7], c.deriv(r[0], 1).unwrap()[..]);
    }
    let c = square();
    let (header, rows) = csv_rows(&ok(&["sample", "square.csv", "--closed", "--n", "9"]));
    assert_eq!(header, ["x", "y"]);
    assert_eq!(rows.len(), 9);
    assert_eq!(
        rows[0], rows[8],
        "a closed curve's samples end where they start"
    );
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r[..], c.eval(i as f64 * 0.5).unwrap()[..]);
    }
}

#[test]
fn sample_step_walks_equal_arc_lengths() {
    let c = square();
    let total = c.arclen(1e-12).unwrap();
    let (_, rows) = csv_rows(&ok(&["sample", "square.csv", "--closed", "--step", "0.25"]));
    assert_eq!(rows.len(), (total / 0.25).floor() as usize + 2);
    assert_eq!(rows[0], rows[rows.len() - 1]);
    // Chords are a little shorter than the arcs between consecutive points.
    for w in rows[..rows.len() - 1].windows(2) {
        let chord = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        assert!(chord <= 0.25 + 1e-9 && chord > 0.2, "chord {chord}");
    }
    // For y(x) the step is taken along the graph (x, S(x)).
    let (_, rows) = csv_rows(&ok(&["sample", "--example", "1", "--step", "0.5"]));
    let s = example1();
    assert_eq!(rows[0], [1.0, 1.0]);
    assert_eq!(rows[rows.len() - 1], [11.0, 1.5]);
    for r in &rows {
        assert!((r[1] - s.eval(r[0]).unwrap()).abs() < 1e-12);
    }
    // The graph as a curve with the knots as parameters: its parameter is x.
    let flat: Vec<f64> = s
        .knots()
        .iter()
        .zip(s.values())
        .flat_map(|(&x, &y)| [x, y])
        .collect();
    let graph = bzspline::CurveBuilder::new(&flat, 2)
        .param(bzspline::Param::Given(s.knots().to_vec()))
        .build()
        .unwrap();
    for w in rows[..rows.len() - 1].windows(2) {
        let arc = graph.arclen_range(w[0][0], w[1][0], 1e-12).unwrap();
        assert!((arc - 0.5).abs() < 1e-6, "arc {arc} from x = {}", w[0][0]);
    }
    let last = &rows[rows.len() - 2..];
    assert!(graph.arclen_range(last[0][0], last[1][0], 1e-12).unwrap() <= 0.5 + 1e-6);
}

#[test]
fn bad_curves_name_the_lines() {
    assert_data_error(
        &["fit", "bad_closed_repeat.csv", "--closed"],
        None,
        &["bad_closed_repeat.csv:5:", "first point (line 2)"],
    );
    assert_data_error(
        &["fit", "bad_repeat.csv", "--curve", "--param", "chordal"],
        None,
        &["bad_repeat.csv:4:", "line 3"],
    );
    assert_data_error(
        &["fit", "square.csv", "--closed", "--alphas", "0.5,0.5,0.5"],
        None,
        &["--alphas has 3 values", "need 4"],
    );
    assert_data_error(
        &["fit", "helix.csv"],
        None,
        &["helix.csv:2:", "3 columns, expected 2"],
    );
}

#[test]
fn smooth_keeps_properties_closes_rings_and_carries_z() {
    // The trail has z: the document is smoothed ring by ring, as with
    // --independent (said on stderr without it).
    let text = ok(&[
        "smooth",
        "shapes.geojson",
        "--tolerance",
        "0.01",
        "--independent",
    ]);
    let o = run(&["smooth", "shapes.geojson", "--tolerance", "0.01"], None);
    assert_eq!((o.code, &o.stdout), (0, &text));
    assert!(
        o.stderr.contains("positions with z: smoothed ring by ring"),
        "{}",
        o.stderr
    );
    assert_eq!(text.lines().count(), 1);
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["name"], "shapes", "foreign member of the collection");
    let f = v["features"].as_array().unwrap();
    assert_eq!(f.len(), 6);

    // The road: the library's centripetal curve, flattened, ends exact.
    assert_eq!(f[0]["id"], 7);
    assert_eq!(f[0]["properties"]["lanes"], 2);
    let road = points(&f[0]["geometry"]["coordinates"]);
    let c = bzspline::Curve::builder_from(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])
        .param(bzspline::Param::Centripetal)
        .build()
        .unwrap();
    let want = c.flatten(0.01).unwrap();
    assert_eq!(road.concat(), want.coords());
    assert_eq!(road[0], [0.0, 0.0]);
    assert_eq!(road[road.len() - 1], [4.0, 0.0]);

    // The lake: both rings closed, first = last, inside the outer square.
    assert_eq!(f[1]["source"], "survey", "foreign member of a feature");
    let rings = f[1]["geometry"]["coordinates"].as_array().unwrap();
    assert_eq!(rings.len(), 2);
    for r in rings {
        let r = points(r);
        assert!(r.len() > 5);
        assert_eq!(r[0], r[r.len() - 1], "ring not closed");
        assert!(r.iter().flatten().all(|&v| (0.0..=10.0).contains(&v)));
    }

    // The trail: z is carried along and stays within the vertices' range.
    let lines = f[2]["geometry"]["coordinates"].as_array().unwrap();
    let first = points(&lines[0]);
    assert!(first.iter().all(|p| p.len() == 3));
    assert_eq!(first[0], [0.0, 0.0, 100.0]);
    assert_eq!(first[first.len() - 1], [2.0, 0.0, 120.0]);
    assert!(first.iter().all(|p| (100.0..=120.0).contains(&p[2])));

    assert_eq!(f[3]["geometry"]["type"], "MultiPolygon");
    assert_eq!(numbers(&f[4]["geometry"]["coordinates"]), vec![3.0, 3.0]);
    assert_eq!(f[5]["geometry"], Value::Null);
}

#[test]
fn smooth_streams_newline_delimited_geojson() {
    let text = ok(&["smooth", "lines.geojsonl", "--tolerance", "0.01"]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2, "one output line per input feature");
    let a: Value = serde_json::from_str(lines[0]).unwrap();
    assert_eq!(a["properties"]["n"], 1);
    let b: Value = serde_json::from_str(lines[1]).unwrap();
    assert_eq!(b["type"], "LineString");
    let bytes = std::fs::read(fixture("lines.geojsonl")).unwrap();
    let o = run(
        &[
            "smooth",
            "--input-format",
            "geojsonseq",
            "--tolerance",
            "0.01",
        ],
        Some(&bytes),
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(o.stdout, text);
    assert!(
        o.stderr.is_empty(),
        "no progress bar when stderr is not a terminal"
    );
}

#[test]
fn input_limits_are_refused_with_their_option_named() {
    // Standard input past --max-bytes, a table past --max-points (at the first
    // line beyond it), and both limits in smooth, streamed or not.
    assert_data_error(
        &["fit", "--max-bytes", "8"],
        Some(b"0,0\n1,1\n2,0\n"),
        &["<stdin>: larger than 8 bytes (--max-bytes)"],
    );
    assert_data_error(
        &["sample", "--n", "3", "--max-points", "2"],
        Some(b"# x, y\n0,0\n1,1\n\n2,0\n"),
        &["<stdin>:5: more than 2 points (--max-points)"],
    );
    assert_data_error(
        &[
            "eval",
            "--example",
            "1",
            "--at-file",
            "xs.txt",
            "--max-points",
            "2",
        ],
        None,
        &["xs.txt:", "more than 2 points (--max-points)"],
    );
    assert_data_error(
        &[
            "smooth",
            "lines.geojsonl",
            "--tolerance",
            "0.1",
            "--max-points",
            "3",
        ],
        None,
        &["lines.geojsonl:3:", "more than 3 positions (--max-points)"],
    );
    assert_data_error(
        &[
            "smooth",
            "lines.geojsonl",
            "--tolerance",
            "0.1",
            "--max-bytes",
            "64",
        ],
        None,
        &["lines.geojsonl:1: a line longer than 64 bytes (--max-bytes)"],
    );
    assert_data_error(
        &[
            "smooth",
            "shapes.geojson",
            "--tolerance",
            "0.1",
            "--max-bytes",
            "64",
        ],
        None,
        &["shapes.geojson: larger than 64 bytes (--max-bytes)"],
    );
    // A feature's ring past --max-points, as one coverage and each feature
    // on its own, in a FeatureCollection in the plane (with z and without)
    // and in a layer of a GeoPackage.
    let dir = tempfile::tempdir().unwrap();
    let gpkg = dir.path().join("mosaic.gpkg");
    let gpkg = gpkg.to_str().unwrap();
    let o = run(
        &["smooth", "mosaic.geojson", "--tolerance", "0.1", "-o", gpkg],
        None,
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    for (input, named) in [
        ("shapes.geojson", "shapes.geojson: feature 0:"),
        ("mosaic.geojson", "mosaic.geojson: feature 0:"),
        (gpkg, "mosaic.gpkg: feature 0:"),
    ] {
        for apart in [&[][..], &["--independent"][..]] {
            let mut args = vec!["smooth", input, "--tolerance", "0.1", "--max-points", "3"];
            args.extend(apart);
            assert_data_error(
                &args,
                None,
                &[named, "more than 3 positions (--max-points)"],
            );
        }
    }
}

#[test]
fn smooth_errors_name_the_feature_or_line() {
    assert_data_error(
        &["smooth", "bad_lines.geojsonl", "--tolerance", "0.1"],
        None,
        &["bad_lines.geojsonl:2:", "coordinates[1]: 3 numbers, but"],
    );
    assert_data_error(
        &["smooth", "bad_dims.geojson", "--tolerance", "0.1"],
        None,
        &[
            "bad_dims.geojson: feature 1, coordinates[1]:",
            "5 numbers, but coordinates[0] has 2",
        ],
    );
    assert_data_error(
        &["smooth", "bad_number.geojson", "--tolerance", "0.1"],
        None,
        &["bad_number.geojson:2:", "invalid JSON"],
    );
}

#[test]
fn curve_fit_json_reads_back_as_input() {
    let first = ok(&["fit", "square.csv", "--closed"]);
    let o = run(
        &["fit", "--closed", "--input-format", "json"],
        Some(first.as_bytes()),
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(o.stdout, first);
}

#[test]
fn fit_reads_the_first_line_of_geojson() {
    let c = bzspline::Curve::open(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
    let want = format!("{}\n", c.to_svg_path().unwrap());
    assert_eq!(
        ok(&["fit", "shapes.geojson", "--curve", "--format", "svg"]),
        want
    );
    let c = bzspline::Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]).unwrap();
    let want = format!("{}\n", c.to_svg_path().unwrap());
    assert_eq!(
        ok(&["fit", "lines.geojsonl", "--curve", "--format", "svg"]),
        want
    );
}

#[test]
fn huge_values_are_refused_or_finite_never_hang() {
    // Fitting 1e308 values works (the library scales them) ...
    let v: Value = serde_json::from_str(&ok(&["fit", "huge.csv"])).unwrap();
    assert!(numbers(&v["knot_values"]).iter().all(|x| x.is_finite()));
    // ... but the length of the graph overflows: refused before measuring.
    assert_data_error(
        &["sample", "huge.csv", "--step", "0.5"],
        None,
        &["huge.csv:", "overflows"],
    );
}

#[test]
fn smooth_reads_a_table_or_an_example_as_one_line() {
    let v: Value =
        serde_json::from_str(&ok(&["smooth", "--example", "1", "--tolerance", "0.05"])).unwrap();
    assert_eq!(v["geometry"]["type"], "LineString");
    let got = points(&v["geometry"]["coordinates"]);
    let pts: Vec<[f64; 2]> = (1..=11)
        .zip([1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5])
        .map(|(x, y)| [f64::from(x), y])
        .collect();
    let c = bzspline::Curve::builder_from(&pts)
        .param(bzspline::Param::Centripetal)
        .build()
        .unwrap();
    assert_eq!(got.concat(), c.flatten(0.05).unwrap().coords());
    assert_eq!(got[0], [1.0, 1.0]);
    assert_eq!(got[got.len() - 1], [11.0, 1.5]);
    let v: Value =
        serde_json::from_str(&ok(&["smooth", "helix.csv", "--tolerance", "0.1"])).unwrap();
    assert!(points(&v["geometry"]["coordinates"])
        .iter()
        .all(|p| p.len() == 3));
    assert_data_error(
        &["smooth", "bad_nan.csv", "--tolerance", "0.1"],
        None,
        &["bad_nan.csv:3:", "not a finite number"],
    );
}

/// Convex hull of planar points (Andrew's monotone chain), counter-clockwise.
fn convex_hull(pts: &[Vec<f64>]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = pts.iter().map(|q| [q[0], q[1]]).collect();
    p.sort_by(|a, b| a.partial_cmp(b).unwrap());
    p.dedup();
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

fn signed_area(r: &[Vec<f64>]) -> f64 {
    r.windows(2)
        .map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1])
        .sum::<f64>()
        / 2.0
}

#[test]
fn smooth_real_country_outlines() {
    // Natural Earth's 1:110m outlines of seven countries (islands, fjords, a long thin
    // coast), as published: Polygons and MultiPolygons in longitude and latitude.
    let input: Value =
        serde_json::from_str(&std::fs::read_to_string(fixture("countries.geojson")).unwrap())
            .unwrap();
    let tolerance = 0.01;
    let text = ok(&["smooth", "countries.geojson", "--tolerance", "0.01"]);
    let output: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(output["source"], input["source"]);
    let (fin, fout) = (
        input["features"].as_array().unwrap(),
        output["features"].as_array().unwrap(),
    );
    assert_eq!(fin.len(), 7);
    assert_eq!(fout.len(), fin.len());
    let mut rings_checked = 0;
    for (a, b) in fin.iter().zip(fout) {
        assert_eq!(a["id"], b["id"]);
        assert_eq!(a["properties"], b["properties"]);
        assert_eq!(a["geometry"]["type"], b["geometry"]["type"]);
        let polygons = |g: &Value| -> Vec<Value> {
            if g["type"] == "Polygon" {
                vec![g["coordinates"].clone()]
            } else {
                g["coordinates"].as_array().unwrap().clone()
            }
        };
        let (pin, pout) = (polygons(&a["geometry"]), polygons(&b["geometry"]));
        assert_eq!(pin.len(), pout.len(), "{}: polygon count", a["id"]);
        for (ra, rb) in pin.iter().zip(&pout) {
            let (ra, rb) = (ra.as_array().unwrap(), rb.as_array().unwrap());
            assert_eq!(ra.len(), rb.len(), "{}: ring count", a["id"]);
            for (ra, rb) in ra.iter().zip(rb) {
                let (ra, rb) = (points(ra), points(rb));
                assert!(
                    rb.len() >= 4,
                    "{}: a ring has at least four positions",
                    a["id"]
                );
                assert_eq!(rb[0], rb[rb.len() - 1], "{}: ring not closed", a["id"]);
                assert!(rb.iter().flatten().all(|v| v.is_finite()));
                // The smooth ring keeps the outline's orientation (right-hand rule)...
                let (sa, sb) = (signed_area(&ra), signed_area(&rb));
                assert_eq!(sa.signum(), sb.signum(), "{}: orientation", a["id"]);
                // ...and stays inside the convex hull of the outline's vertices.
                let hull = convex_hull(&ra);
                let scale = ra.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
                for q in &rb {
                    for k in 0..hull.len() {
                        let (o, e) = (hull[k], hull[(k + 1) % hull.len()]);
                        let c = (e[0] - o[0]) * (q[1] - o[1]) - (e[1] - o[1]) * (q[0] - o[0]);
                        let len = (e[0] - o[0]).hypot(e[1] - o[1]);
                        assert!(
                            c >= -1e-12 * scale * len,
                            "{}: vertex {q:?} outside the hull",
                            a["id"]
                        );
                    }
                }
                // Vertices sit on the smooth curve: every output vertex is within the
                // tolerance-scaled reach of the outline (never farther than its longest leg).
                let longest = ra
                    .windows(2)
                    .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
                    .fold(0.0f64, f64::max);
                for q in &rb {
                    let d = ra
                        .iter()
                        .map(|p| (p[0] - q[0]).hypot(p[1] - q[1]))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        d <= longest + tolerance,
                        "{}: vertex {q:?} far from the outline",
                        a["id"]
                    );
                }
                rings_checked += 1;
            }
        }
    }
    assert_eq!(rings_checked, 17, "every ring of the seven countries");
}

#[test]
fn through_passes_the_curve_through_the_points() {
    // fit: `values` are the solved controls, `knot_values` the data.
    let v: Value = serde_json::from_str(&ok(&["fit", "--example", "1", "--through"])).unwrap();
    let knot_values = numbers(&v["knot_values"]);
    for (k, (got, want)) in knot_values.iter().zip(input_example1()).enumerate() {
        assert!(
            (got - want).abs() < 1e-13 * 10.0,
            "knot {k}: {got} against {want}"
        );
    }
    let s = bzspline::Spline::through(
        &(1..=11).map(f64::from).collect::<Vec<_>>(),
        &input_example1(),
        bzspline::Alphas::default(),
    )
    .unwrap();
    assert_eq!(numbers(&v["values"]), s.values());
    // eval at the knots gives the data; a curve, open and closed, too.
    let text = ok(&["eval", "--example", "1", "--through", "--at", "1,2,6,11"]);
    let ys: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    for (y, want) in ys.iter().zip([1.0, 3.0, 7.0, 1.5]) {
        assert!((y - want).abs() < 1e-12, "{y} against {want}");
    }
    let v: Value =
        serde_json::from_str(&ok(&["fit", "square.csv", "--closed", "--through"])).unwrap();
    let pts = points(&v["knot_values"]);
    let want = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
    for (p, w) in pts.iter().zip(want) {
        assert!(
            (p[0] - w[0]).abs() < 1e-14 && (p[1] - w[1]).abs() < 1e-14,
            "{p:?} against {w:?}"
        );
    }
    // The fit reads back as input: the solved controls give the same curve.
    let first = ok(&["fit", "--example", "1", "--through"]);
    let o = run(&["fit", "--input-format", "json"], Some(first.as_bytes()));
    assert_eq!(o.code, 0, "{}", o.stderr);
    let back: Value = serde_json::from_str(&o.stdout).unwrap();
    let again: Value = serde_json::from_str(&first).unwrap();
    assert_eq!(back["segments"], again["segments"]);
    // The figure names the solved polygon and the points passed through.
    let svg = ok(&["plot", "--example", "1", "--through"]);
    assert!(svg.contains("solved control polygon") && svg.contains("points (passed through)"));
}

fn input_example1() -> Vec<f64> {
    vec![1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5]
}

/// Standard input in any format the command reads, told apart by its content.
#[test]
fn standard_input_is_sniffed() {
    let geojson = br#"{"type": "Feature", "geometry": {"type": "LineString",
        "coordinates": [[0,0],[1,2],[3,2],[4,0]]}, "properties": {}}"#;
    let json = b"[[0,0],[1,2],[3,2],[4,0]]";
    let csv = b"0,0\n1,2\n3,2\n4,0\n";
    let mut outs = Vec::new();
    for input in [&geojson[..], &json[..], &csv[..]] {
        let o = run(&["fit", "--curve", "--format", "svg"], Some(input));
        assert_eq!(o.code, 0, "{}", o.stderr);
        outs.push(o.stdout);
    }
    assert!(outs.iter().all(|o| *o == outs[0]), "{outs:?}");
    let topo = br#"{"type":"Topology","arcs":[],"objects":{}}"#;
    let o = run(&["fit"], Some(&topo[..]));
    assert_eq!(o.code, 1);
    assert!(o.stderr.contains("TopoJSON"), "{}", o.stderr);
}

/// x that runs back and forth in two columns is a path, not a function: the
/// error says how to read it.
#[test]
fn a_polygon_read_as_a_function_suggests_curve() {
    assert_data_error(
        &["fit"],
        Some(b"0,0\n2,0\n1,2\n"),
        &["<stdin>:3", "x must be strictly increasing", "--curve"],
    );
    assert_data_error(
        &["fit"],
        Some(b"0,0\n2,0\n2,2\n0,2\n0,0\n"),
        &["--closed", "leave out the last row"],
    );
    // Sorted x with a repeat is no path.
    let o = run(&["fit"], Some(b"0,0\n2,0\n2,1\n"));
    assert!(!o.stderr.contains("--curve"), "{}", o.stderr);
}

/// A dated series: computed on days since 1970, written back as dates, with
/// the header's names.
#[test]
fn dates_as_x_come_back_as_dates() {
    let csv = ok(&["sample", "daily.csv", "--n", "3"]);
    assert_eq!(
        csv.lines().next(),
        Some("day,visitors"),
        "the header's names: {csv}"
    );
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert!(rows[0].starts_with("2024-01-01,120"), "{csv}");
    assert!(rows[1].starts_with("2024-01-05,"), "the middle day: {csv}");
    assert!(rows[2].starts_with("2024-01-09,170"), "{csv}");
    // The same spline as on the day numbers (1 January 2024 is day 19723).
    let days = [19723.0, 19724.0, 19725.0, 19727.0, 19730.0, 19731.0];
    let s = Spline::new(&days, &[120.0, 135.0, 128.0, 160.0, 151.0, 170.0]).unwrap();
    let at = ok(&[
        "eval",
        "daily.csv",
        "--at",
        "2024-01-04,2024-01-04T12:00:00Z",
        "--derivative",
        "1",
    ]);
    let lines: Vec<Vec<&str>> = at.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(lines[0], ["day", "visitors", "dvisitors"]);
    assert_eq!(lines[1][0], "2024-01-04");
    assert_eq!(lines[2][0], "2024-01-04T12:00:00Z");
    let y: f64 = lines[2][1].parse().unwrap();
    assert_eq!(y, s.eval(19726.5).unwrap());
    let dy: f64 = lines[1][2].parse().unwrap();
    assert_eq!(dy, s.deriv(19726.0, 1).unwrap(), "per day");
    let fit: Value = serde_json::from_str(&ok(&["fit", "daily.csv"])).unwrap();
    assert_eq!(fit["knots"][0].as_f64(), Some(19723.0));
    assert_eq!(fit["knot_times"][5], "2024-01-09");
    let json: Value = serde_json::from_str(&ok(&[
        "sample",
        "daily.csv",
        "--n",
        "2",
        "--format",
        "json",
    ]))
    .unwrap();
    assert_eq!(json["day"], serde_json::json!(["2024-01-01", "2024-01-09"]));
}

/// Date-times with an offset, whitespace-separated columns chosen by name.
#[test]
fn date_times_and_named_columns() {
    let out = ok(&[
        "sample",
        "hourly.txt",
        "--y",
        "humidity",
        "--x",
        "time",
        "--n",
        "4",
    ]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "time,humidity");
    assert_eq!(lines[1], "2024-03-01T06:00:00+02:00,81");
    assert!(lines[2].starts_with("2024-03-01T10:00:00+02:00,"), "{out}");
    assert_eq!(lines[4], "2024-03-01T18:00:00+02:00,66");
    // By number, the same.
    assert_eq!(
        ok(&["sample", "hourly.txt", "--columns", "1,3", "--n", "4"]),
        out
    );
    // --y alone: over the row number.
    let idx = ok(&["sample", "hourly.txt", "--y", "temperature", "--n", "2"]);
    assert_eq!(idx, "index,temperature\n0,4.5\n3,8\n");
}

#[test]
fn bad_dates_and_columns_name_the_place() {
    assert_data_error(
        &["fit", "bad_date.csv"],
        None,
        &["bad_date.csv:4: field 1: '2024-01-32' is not a number or a date"],
    );
    assert_data_error(
        &["fit", "bad_mixed_date.csv"],
        None,
        &["bad_mixed_date.csv:3: field 1: '19725' is a number, but the column holds dates"],
    );
    assert_data_error(
        &["fit", "daily.csv", "--y", "sales"],
        None,
        &["daily.csv: no column named 'sales' (--y); the header names 'day', 'visitors'"],
    );
    assert_data_error(
        &["fit", "daily.csv", "--columns", "1,3"],
        None,
        &["daily.csv: no column 3 (--columns): the rows have 2 fields"],
    );
    assert_data_error(
        &["eval", "daily.csv", "--at", "3"],
        None,
        &["--at value 1: 3 is a number, but x in daily.csv holds dates"],
    );
    assert_data_error(
        &["eval", "example1.csv", "--at", "2024-01-01"],
        None,
        &["--at value 1: a date, but x in example1.csv holds numbers"],
    );
}

/// JSON points may carry dates too, and fit's JSON of a dated series reads
/// back as dates.
#[test]
fn json_dates_and_fit_output_read_back() {
    let json = br#"[["2024-01-01", 120], ["2024-01-02", 135], ["2024-01-03", 128]]"#;
    let o = run(&["sample", "--n", "2"], Some(&json[..]));
    assert_eq!(
        o.stdout, "x,y\n2024-01-01,120\n2024-01-03,128\n",
        "{}",
        o.stderr
    );
    let fit = ok(&["fit", "daily.csv"]);
    let o = run(&["sample", "--n", "2"], Some(fit.as_bytes()));
    assert_eq!(
        o.stdout, "x,y\n2024-01-01,120\n2024-01-09,170\n",
        "{}",
        o.stderr
    );
    assert_data_error(
        &["fit"],
        Some(br#"[["2024-01-01", 1], [19724, 2]]"#),
        &["<stdin>: points[1][0]: a number, but the first values are dates"],
    );
}

/// The guide's dated series (`docs/command.md`) shows this output; keep it true.
#[test]
fn readme_dated_series_output_is_current() {
    let visitors = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/visitors.csv");
    assert_eq!(
        ok(&["sample", visitors, "--n", "5"]),
        "day,visitors\n2024-01-01,210\n2024-01-04T12:00:00Z,153.89114655213558\n2024-01-08,163.80018233344322\n2024-01-11T12:00:00Z,164.89801354404992\n2024-01-15,148\n"
    );
    assert_eq!(
        ok(&["eval", visitors, "--at", "2024-01-04,2024-01-09T12:00:00Z", "--derivative", "1"]),
        "day,visitors,dvisitors\n2024-01-04,144,16\n2024-01-09T12:00:00Z,144.0143385956696,1.266883057550963\n"
    );
}

/// The same points, every default taken: the command, the server's protocol
/// and the library give the same curve, bit for bit (Python's `Curve` is
/// checked against the command in `crates/bzspline-py/tests/test_defaults.py`).
#[test]
fn defaults_agree_across_entry_points() {
    let pts = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [3.0, 5.0]];
    let lib = bzspline::Curve::open(&pts).unwrap();
    // Centripetal: steps of the square roots of the legs (1, 1, 1 and 5).
    let want_end: f64 = 3.0 + 5f64.sqrt();
    assert!(
        (lib.knots()[4] - want_end).abs() < 1e-12,
        "{:?}",
        lib.knots()
    );
    let csv = "x,y\n0,0\n1,0\n1,1\n0,1\n3,5\n";
    let o = run(
        &["fit", "--curve", "--input-format", "csv"],
        Some(csv.as_bytes()),
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    let command: Value = serde_json::from_str(&o.stdout).unwrap();
    let body = serde_json::json!({"mode": "curve", "points": pts}).to_string();
    let limits = bzspline_io::api::ParseLimits {
        max_points: 100,
        max_samples: 100,
    };
    let req = bzspline_io::api::parse(body.as_bytes(), limits).unwrap();
    let server = bzspline_io::api::fit(&req).unwrap();
    let knots = |v: &Value| -> Vec<f64> {
        v["knots"]
            .as_array()
            .unwrap()
            .iter()
            .map(|k| k.as_f64().unwrap())
            .collect()
    };
    assert_eq!(knots(&command), lib.knots());
    assert_eq!(knots(&server), lib.knots());
    // The segments' control points, as numbers (the command writes `0`, the
    // server `0.0`).
    let segments = |v: &Value| -> Vec<Vec<f64>> {
        v["segments"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                s.as_array()
                    .unwrap()
                    .iter()
                    .flat_map(|p| p.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
                    .collect()
            })
            .collect()
    };
    let want: Vec<Vec<f64>> = (0..lib.len())
        .map(|k| lib.segment_points(k).unwrap())
        .collect();
    assert_eq!(segments(&command), want);
    assert_eq!(segments(&server), want);
}

/// `--alpha` is read by one parser everywhere: fractions work for `smooth`
/// as for `fit`, and give what the decimal gives.
#[test]
fn smooth_takes_alpha_as_a_fraction() {
    let frac = ok(&[
        "smooth",
        "mosaic.geojson",
        "--alpha",
        "1/3",
        "--tolerance",
        "0.01",
    ]);
    let dec = ok(&[
        "smooth",
        "mosaic.geojson",
        "--alpha",
        "0.3333333333333333",
        "--tolerance",
        "0.01",
    ]);
    assert_eq!(frac, dec);
    let o = run(&["smooth", "mosaic.geojson", "--alpha", "0.9"], None);
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(
        o.stderr.contains("0.9 is outside [1/3, 2/3]"),
        "{}",
        o.stderr
    );
}

/// The same monthly series written as CSVs write dates: read without a
/// format where the form is unambiguous, with `--date-format` otherwise; every
/// form gives the spline through the same day numbers (checked against the
/// library on days counted here), and what could be read two ways is
/// refused with a message naming `--date-format`.
#[test]
fn dates_in_any_form_are_the_same_days() {
    // Day numbers since 1970-01-01 of the first of Jan, Feb, Mar, May 2000.
    let days = [10957.0, 10988.0, 11017.0, 11078.0];
    let ys = [1394.46, 1366.42, 1498.58, 1420.6];
    let s = Spline::new(&days, &ys).unwrap();
    let want = s.eval(11000.0).unwrap();
    let forms: [(&[&str; 4], Option<&str>); 9] = [
        (
            &["2000-01-01", "2000-02-01", "2000-03-01", "2000-05-01"],
            None,
        ),
        (
            &["2000/01/01", "2000/02/01", "2000/03/01", "2000/05/01"],
            None,
        ),
        (&["2000-01", "2000-02", "2000-03", "2000-05"], None),
        (
            &["Jan 1 2000", "Feb 1 2000", "Mar 1 2000", "May 1 2000"],
            None,
        ),
        (
            &[
                "1 January 2000",
                "1 February 2000",
                "1 March 2000",
                "1 May 2000",
            ],
            None,
        ),
        (
            &["01/01/2000", "01/02/2000", "01/03/2000", "01/05/2000"],
            Some("%d/%m/%Y"),
        ),
        (
            &["01/01/2000", "02/01/2000", "03/01/2000", "05/01/2000"],
            Some("%m/%d/%Y"),
        ),
        (
            &["20000101", "20000201", "20000301", "20000501"],
            Some("%Y%m%d"),
        ),
        (&["2000-01", "2000-02", "2000-03", "2000-05"], Some("%Y-%m")),
    ];
    for (dates, format) in forms {
        let csv: String = std::iter::once("date,price\n".to_owned())
            .chain(dates.iter().zip(ys).map(|(d, y)| format!("\"{d}\",{y}\n")))
            .collect();
        let mut args = vec!["eval", "--input-format", "csv", "--at", "2000-02-13"];
        if let Some(f) = format {
            args.extend(["--date-format", f]);
        }
        let o = run(&args, Some(csv.as_bytes()));
        assert_eq!(o.code, 0, "{dates:?}: {}", o.stderr);
        let row: Vec<&str> = o.stdout.lines().nth(1).unwrap().split(',').collect();
        assert_eq!(row[0], "2000-02-13", "{dates:?}");
        assert_eq!(row[1].parse::<f64>().unwrap(), want, "{dates:?}");
    }
    // --at in the data's own form, with the format.
    let csv = "d,p\n01/01/2000,1\n01/02/2000,2\n01/03/2000,4\n";
    let o = run(
        &[
            "eval",
            "--input-format",
            "csv",
            "--date-format",
            "%d/%m/%Y",
            "--at",
            "15/01/2000",
        ],
        Some(csv.as_bytes()),
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(
        o.stdout.lines().nth(1).unwrap().starts_with("2000-01-15,"),
        "{}",
        o.stdout
    );
    // Day and month either way round: refused, naming the option.
    assert_data_error(
        &["fit", "--input-format", "csv"],
        Some(csv.as_bytes()),
        &["<stdin>:2: field 1: '01/01/2000' could be day/month or month/day: give --date-format"],
    );
    // A number that looks like a date stays a number without a format.
    let fit: Value = serde_json::from_str(&{
        let o = run(
            &["fit", "--input-format", "csv"],
            Some(b"d,p\n20000101,1\n20000201,2\n20000301,4\n"),
        );
        assert_eq!(o.code, 0, "{}", o.stderr);
        o.stdout
    })
    .unwrap();
    assert_eq!(fit["knots"][0].as_f64(), Some(20000101.0));
    // A field that does not match the format names its line.
    assert_data_error(
        &["fit", "--input-format", "csv", "--date-format", "%d/%m/%Y"],
        Some(b"d,p\n01/01/2000,1\n2000-02-01,2\n01/03/2000,4\n"),
        &["<stdin>:3: field 1: '2000-02-01' does not match the date format '%d/%m/%Y'"],
    );
    // A format without a date is a usage error.
    let o = run(&["fit", "--date-format", "%H:%M", "daily.csv"], None);
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(o.stderr.contains("names no date"), "{}", o.stderr);
}
