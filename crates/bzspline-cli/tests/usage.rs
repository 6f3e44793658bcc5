//! Every option's bad values: exit code 2, one line on standard error that
//! starts with `error: ` and names the option, nothing on standard output and
//! no file written to `-o`, whatever the data (the options are checked before
//! any is read).

mod common;

use common::run;

/// `(arguments, text the message must contain)`; each runs with `-o OUT`.
const CASES: &[(&[&str], &str)] = &[
    // Input options.
    (&["fit", "--example", "3"], "--example"),
    (&["fit", "--example", "x"], "--example"),
    (&["fit", "--example", "1", "example1.csv"], "--example"),
    (
        &["fit", "--example", "1", "--input-format", "xml"],
        "--input-format",
    ),
    (
        &["fit", "--example", "1", "--max-points", "1"],
        "--max-points",
    ),
    (
        &["fit", "--example", "1", "--max-points", "x"],
        "--max-points",
    ),
    (
        &["fit", "--example", "1", "--max-bytes", "0"],
        "--max-bytes",
    ),
    // Shape options.
    (&["fit", "--example", "1", "--alpha", "0.333"], "--alpha"),
    (&["fit", "--example", "1", "--alpha", "0.7"], "--alpha"),
    (&["fit", "--example", "1", "--alpha", "3/4"], "--alpha"),
    (&["fit", "--example", "1", "--alpha", "1/0"], "--alpha"),
    (&["fit", "--example", "1", "--alpha", "NaN"], "--alpha"),
    (&["fit", "--example", "1", "--alpha", "x"], "--alpha"),
    (&["fit", "--example", "1", "--alphas", "0.5,x"], "--alphas"),
    (
        &["fit", "--example", "1", "--alphas", "0.5,0.2"],
        "--alphas value 2",
    ),
    (
        &["fit", "--example", "1", "--alphas", "0.5,inf"],
        "--alphas",
    ),
    (
        &["fit", "--example", "1", "--alpha", "0.5", "--alphas", "0.5"],
        "--alpha",
    ),
    (&["fit", "--example", "1", "--param", "spiral"], "--param"),
    (&["fit", "--example", "1", "--param", "chordal"], "--param"),
    (&["fit", "--example", "1", "--format", "xml"], "--format"),
    // eval.
    (&["eval", "--example", "1"], "--at"),
    (&["eval", "--example", "1", "--at", "x"], "--at"),
    (&["eval", "--example", "1", "--at", "inf"], "--at"),
    (&["eval", "--example", "1", "--at", "2024-02-30"], "--at"),
    (
        &[
            "eval",
            "--example",
            "1",
            "--at",
            "1",
            "--at-file",
            "example1.csv",
        ],
        "--at",
    ),
    (
        &["eval", "--example", "1", "--at", "1", "--derivative", "4"],
        "--derivative",
    ),
    (
        &["eval", "--example", "1", "--at", "1", "--derivative", "0"],
        "--derivative",
    ),
    (
        &[
            "eval",
            "--example",
            "1",
            "--at",
            "1",
            "--extrapolate",
            "far",
        ],
        "--extrapolate",
    ),
    (
        &[
            "eval",
            "--example",
            "2",
            "--curve",
            "--at",
            "1",
            "--extrapolate",
            "clamp",
        ],
        "--extrapolate",
    ),
    (
        &["eval", "--example", "1", "--at", "1", "--format", "xml"],
        "--format",
    ),
    // sample.
    (&["sample", "--example", "1"], "--n"),
    (&["sample", "--example", "1", "--n", "1"], "--n"),
    (&["sample", "--example", "1", "--n", "0"], "--n"),
    (&["sample", "--example", "1", "--n", "x"], "--n"),
    (
        &["sample", "--example", "1", "--n", "3", "--step", "1"],
        "--n",
    ),
    (&["sample", "--example", "1", "--step", "0"], "--step"),
    (&["sample", "--example", "1", "--step", "-1"], "--step"),
    (&["sample", "--example", "1", "--step", "inf"], "--step"),
    (
        &["sample", "--example", "1", "--tolerance", "0"],
        "--tolerance",
    ),
    (
        &["sample", "--example", "1", "--tolerance", "nan"],
        "--tolerance",
    ),
    (
        &["sample", "--example", "1", "--n", "3", "--derivative", "5"],
        "--derivative",
    ),
    // plot.
    (&["plot", "--example", "1", "--width", "0"], "--width"),
    (&["plot", "--example", "1", "--height", "99999"], "--height"),
    (
        &["plot", "--example", "1", "--alpha-sweep", "0.5,0.9"],
        "--alpha-sweep",
    ),
    (
        &[
            "plot",
            "--example",
            "1",
            "--alpha-sweep",
            "0.5",
            "--alpha",
            "0.5",
        ],
        "--alpha-sweep",
    ),
    (&["plot", "--example", "1", "--scale", "nan"], "--scale"),
    // smooth.
    (
        &["smooth", "shapes.geojson", "--tolerance", "0"],
        "--tolerance",
    ),
    (
        &["smooth", "shapes.geojson", "--tolerance", "-1"],
        "--tolerance",
    ),
    (
        &["smooth", "shapes.geojson", "--tolerance", "x"],
        "--tolerance",
    ),
    (&["smooth", "shapes.geojson", "--snap", "-1"], "--snap"),
    (
        &["smooth", "shapes.geojson", "--keep-angle", "200"],
        "--keep-angle",
    ),
    (&["smooth", "shapes.geojson", "--alpha", "0.9"], "--alpha"),
    (
        &["smooth", "shapes.geojson", "--independent", "--snap", "0.1"],
        "--snap",
    ),
    (
        &["smooth", "shapes.geojson", "--output-format", "kml"],
        "--output-format",
    ),
    // No such command or option.
    (&["nonsense"], "nonsense"),
    (
        &["fit", "--example", "1", "--no-such-option"],
        "--no-such-option",
    ),
];

#[test]
fn every_bad_option_value_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    // An ending every command takes (plot writes by the name's ending).
    let out = dir.path().join("out.svg");
    let out_s = out.to_str().unwrap().to_owned();
    let mut problems = Vec::new();
    for (args, want) in CASES {
        let mut all = args.to_vec();
        all.extend(["-o", &out_s]);
        let o = run(&all, None);
        let mut wrong = Vec::new();
        if o.code != 2 {
            wrong.push(format!("exit code {}", o.code));
        }
        if o.stderr.lines().count() != 1 || !o.stderr.starts_with("error: ") {
            wrong.push("stderr is not one line starting with `error: `".to_owned());
        }
        if !o.stderr.contains(want) {
            wrong.push(format!("stderr lacks {want:?}"));
        }
        if !o.stdout.is_empty() {
            wrong.push("stdout is not empty".to_owned());
        }
        if out.exists() {
            wrong.push("-o was written".to_owned());
            let _ = std::fs::remove_file(&out);
        }
        if !wrong.is_empty() {
            problems.push(format!(
                "{args:?}: {}: {}",
                wrong.join("; "),
                o.stderr.trim()
            ));
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
    // A figure in a format plot does not write.
    let jpg = dir.path().join("fig.jpg");
    let o = run(
        &["plot", "--example", "1", "-o", jpg.to_str().unwrap()],
        None,
    );
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(
        o.stderr.contains(".svg, .png or .pdf") && !jpg.exists(),
        "{}",
        o.stderr
    );
}
