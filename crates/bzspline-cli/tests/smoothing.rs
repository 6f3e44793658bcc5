//! `--smooth`: the smoothing spline of noisy data through `fit`, `eval`,
//! `sample` and `plot`, checked against the library number for number.

use bzspline::{Alphas, Curve, Param, Smoothing, Spline};
use serde_json::Value;

mod common;

use common::run;

/// A noisy sine as a CSV table, and its columns.
fn noisy(n: usize) -> (String, Vec<f64>, Vec<f64>) {
    let mut state = 12345u64;
    let mut unit = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let x: Vec<f64> = (0..n).map(|i| i as f64 * 0.05).collect();
    let y: Vec<f64> = x.iter().map(|&t| t.sin() + 0.6 * unit()).collect();
    let mut csv = String::from("x,y\n");
    for (a, b) in x.iter().zip(&y) {
        csv.push_str(&format!("{a},{b}\n"));
    }
    (csv, x, y)
}

fn ok_stdin(args: &[&str], stdin: &str) -> String {
    let o = run(args, Some(stdin.as_bytes()));
    assert_eq!(o.code, 0, "{args:?}: {}", o.stderr);
    o.stdout
}

/// A curve fit's control points (`values`), flat.
fn control_points(v: &Value) -> Vec<f64> {
    v["values"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(numbers)
        .collect()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn fit_prints_the_librarys_smoothing_spline_with_lambda_gcv_and_dof() {
    let (csv, x, y) = noisy(120);
    for (arg, how) in [("auto", Smoothing::Gcv), ("0.25", Smoothing::Lambda(0.25))] {
        let v: Value = serde_json::from_str(&ok_stdin(&["fit", "--smooth", arg], &csv)).unwrap();
        let s = Spline::smoothing(&x, &y, None, Alphas::default(), how).unwrap();
        assert_eq!(numbers(&v["values"]), s.fit.values(), "--smooth {arg}");
        assert_eq!(
            numbers(&v["knot_values"]),
            s.fit.knot_values(),
            "--smooth {arg}"
        );
        assert_eq!(v["lambda"].as_f64(), Some(s.lambda));
        assert_eq!(v["gcv"].as_f64(), Some(s.gcv));
        assert_eq!(v["dof"].as_f64(), Some(s.dof));
    }
    // Without --smooth the object has no smoothing keys.
    let v: Value = serde_json::from_str(&ok_stdin(&["fit"], &csv)).unwrap();
    assert!(v.get("lambda").is_none());
    // --alpha reaches the fit.
    let v: Value =
        serde_json::from_str(&ok_stdin(&["fit", "--smooth", "1", "--alpha", "1/3"], &csv)).unwrap();
    let s = Spline::smoothing(
        &x,
        &y,
        None,
        Alphas::Uniform(1.0 / 3.0),
        Smoothing::Lambda(1.0),
    )
    .unwrap();
    assert_eq!(numbers(&v["values"]), s.fit.values());
}

#[test]
fn eval_and_sample_use_the_fit() {
    let (csv, x, y) = noisy(80);
    let s = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv)
        .unwrap()
        .fit;
    let out = ok_stdin(&["eval", "--smooth", "auto", "--at", "0.5,1.7,3.9"], &csv);
    let got: Vec<f64> = out
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    for (g, at) in got.iter().zip([0.5, 1.7, 3.9]) {
        assert_eq!(*g, s.eval(at).unwrap());
    }
    let out = ok_stdin(&["sample", "--smooth", "auto", "-n", "5"], &csv);
    assert_eq!(out.lines().count(), 6);
}

#[test]
fn bands_are_the_librarys_and_wrap_the_fit() {
    let (csv, x, y) = noisy(120);
    let s = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv).unwrap();
    let at = [0.0, 0.5, 1.7, 3.9, x[x.len() - 1]];
    let list: Vec<String> = at.iter().map(f64::to_string).collect();
    let out = ok_stdin(
        &[
            "eval",
            "--smooth",
            "auto",
            "--band",
            "0.9",
            "--at",
            &list.join(","),
        ],
        &csv,
    );
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("x,y,lo,hi"));
    for (line, &t) in lines.zip(&at) {
        let v: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        let (lo, hi) = s.band(t, 0.9).unwrap();
        assert_eq!(v, [t, s.fit.eval(t).unwrap(), lo, hi], "at {t}");
        assert!(v[2] < v[1] && v[1] < v[3]);
    }
    let out = ok_stdin(
        &[
            "sample", "--smooth", "auto", "--band", "0.95", "-n", "7", "--format", "json",
        ],
        &csv,
    );
    let v: Value = serde_json::from_str(&out).unwrap();
    let (lo, hi, mid) = (numbers(&v["lo"]), numbers(&v["hi"]), numbers(&v["y"]));
    assert_eq!(lo.len(), 7);
    // A 95 % band is wider than a 90 % one, by the ratio of their z.
    for (i, t) in numbers(&v["x"]).iter().enumerate() {
        let (a, b) = s.band(*t, 0.9).unwrap();
        let ratio = (hi[i] - lo[i]) / (b - a);
        assert!(
            (ratio - 1.959_963_984_540_054 / 1.644_853_626_951_472_2).abs() < 1e-9,
            "{ratio}"
        );
        assert!(lo[i] < mid[i] && mid[i] < hi[i]);
    }
    // The plot shades it under the curve, and says so.
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("noisy.csv");
    let fig = dir.path().join("band.svg");
    std::fs::write(&data, &csv).unwrap();
    let o = run(
        &[
            "plot",
            data.to_str().unwrap(),
            "--smooth",
            "auto",
            "--band",
            "0.95",
            "-o",
            fig.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    let svg = std::fs::read_to_string(&fig).unwrap();
    assert!(svg.contains(r#"fill-opacity="0.18" stroke="none" points=""#));
    assert!(svg.contains(">95 % band<"), "no legend entry");
}

#[test]
fn bands_are_refused_where_there_are_none() {
    let (csv, _, _) = noisy(40);
    for (args, code, want) in [
        (&["eval", "--band", "0.95", "--at", "1"][..], 2, "--smooth"),
        (
            &["eval", "--smooth", "auto", "--band", "95", "--at", "1"][..],
            2,
            "strictly between 0 and 1",
        ),
        (
            &["eval", "--smooth", "auto", "--band", "0", "--at", "1"][..],
            2,
            "strictly between 0 and 1",
        ),
        (
            &[
                "plot", "--smooth", "auto", "--band", "0.9", "--curve", "-o", "x.svg",
            ][..],
            2,
            "y(x) only",
        ),
        (
            &["sample", "--smooth", "0", "--band", "0.9", "-n", "3"][..],
            1,
            "no residual degrees of freedom",
        ),
        (
            &[
                "eval",
                "--smooth",
                "auto",
                "--band",
                "0.9",
                "--at",
                "99",
                "--extrapolate",
                "clamp",
            ][..],
            1,
            "--at value 1",
        ),
    ] {
        let o = run(args, Some(csv.as_bytes()));
        assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains(want), "{args:?}: {}", o.stderr);
        assert!(o.stdout.is_empty(), "{args:?}");
    }
}

#[test]
fn curves_smooth_on_their_parameters() {
    let (csv, x, y) = noisy(60);
    let out = ok_stdin(
        &["fit", "--curve", "--param", "uniform", "--smooth", "auto"],
        &csv,
    );
    let v: Value = serde_json::from_str(&out).unwrap();
    let pts: Vec<[f64; 2]> = x.iter().zip(&y).map(|(a, b)| [*a, *b]).collect();
    let c = Curve::builder_from(&pts)
        .param(Param::Uniform)
        .smoothing(Smoothing::Gcv)
        .build_smoothed()
        .unwrap();
    let got = control_points(&v);
    assert_eq!(got, c.fit.points());
    assert_eq!(v["lambda"].as_f64(), Some(c.lambda));
    // A noisy closed contour, smoothed round its loop.
    let mut ring = String::from("x,y\n");
    let mut pts = Vec::new();
    for (i, e) in y.iter().enumerate() {
        let a = std::f64::consts::TAU * i as f64 / y.len() as f64;
        let p = [5.0 * a.cos() + 0.2 * (e - a.sin()), 3.0 * a.sin()];
        ring.push_str(&format!("{},{}\n", p[0], p[1]));
        pts.push(p);
    }
    let out = ok_stdin(&["fit", "--closed", "--smooth", "auto"], &ring);
    let v: Value = serde_json::from_str(&out).unwrap();
    let c = Curve::builder_from(&pts)
        .closed(true)
        .smoothing(Smoothing::Gcv)
        .build_smoothed()
        .unwrap();
    let got = control_points(&v);
    assert_eq!(got, c.fit.points());
    assert_eq!(v["closed"].as_bool(), Some(true));
    assert_eq!(v["dof"].as_f64(), Some(c.dof));
    // Each coordinate's band, around it, the library's.
    let out = ok_stdin(
        &[
            "eval", "--closed", "--smooth", "auto", "--band", "0.9", "--at", "0,1.5",
        ],
        &ring,
    );
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("t,x,y,x_lo,x_hi,y_lo,y_hi"));
    let z = bzspline::band_z(0.9).unwrap();
    for line in lines {
        let row: Vec<f64> = line.split(',').map(|f| f.parse().unwrap()).collect();
        let se = c.se(row[0]).unwrap();
        let p = c.fit.eval(row[0]).unwrap();
        for k in 0..2 {
            assert_eq!(row[1 + k], p[k]);
            let (lo, hi) = (row[3 + 2 * k], row[4 + 2 * k]);
            assert!(lo < p[k] && p[k] < hi, "{line}");
            let want = z * se[k];
            assert!(
                ((hi - p[k]) - want).abs() <= 1e-12 * want.max(p[k].abs()),
                "{line}"
            );
        }
    }
}

#[test]
fn plot_draws_the_data_and_the_fit() {
    let (csv, _, _) = noisy(50);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit.svg");
    let data = dir.path().join("noisy.csv");
    std::fs::write(&data, csv).unwrap();
    let o = run(
        &[
            "plot",
            data.to_str().unwrap(),
            "--smooth",
            "auto",
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    let svg = std::fs::read_to_string(&out).unwrap();
    // 50 observations and the legend's one.
    assert_eq!(svg.matches(r#"r="2.2""#).count(), 51);
    assert!(svg.contains(">data<"));
    assert!(svg.contains("fitted control polygon"));
}

#[test]
fn bad_smoothing_is_refused() {
    for (args, code, want) in [
        (
            &["fit", "--smooth", "-1"][..],
            2,
            "must be auto or a number of at least 0",
        ),
        (
            &["fit", "--smooth", "lots"][..],
            2,
            "must be auto or a number",
        ),
        (
            &["fit", "--smooth", "auto", "--through"][..],
            2,
            "cannot be used with",
        ),
    ] {
        let o = run(args, None);
        assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains(want), "{args:?}: {}", o.stderr);
    }
    let o = run(&["fit", "--smooth", "auto"], Some(b"x,y\n0,1\n1,2\n"));
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(o.stderr.contains("need at least 3"), "{}", o.stderr);
    let o = run(
        &["fit", "--smooth", "auto"],
        Some(b"x,y\n0,1\n1,2\n1,3\n2,2\n"),
    );
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(
        o.stderr.contains("<stdin>:4:") && o.stderr.contains("strictly increasing"),
        "{}",
        o.stderr
    );
}

/// The guide's noisy-data section (`docs/command.md`) shows this output;
/// keep it true.
#[test]
fn the_guides_smoothing_output_is_current() {
    let guide = common::guide();
    let noisy = common::fixture("noisy.csv");
    let noisy = noisy.to_str().unwrap();
    let spikes = common::fixture("spikes.csv");
    let spikes = spikes.to_str().unwrap();
    for args in [
        &[
            "eval",
            spikes,
            "--smooth",
            "auto",
            "--x",
            "x",
            "--y",
            "y",
            "--at",
            "1.5,4.7,8",
        ][..],
        &[
            "eval",
            spikes,
            "--smooth",
            "auto",
            "--weights",
            "w",
            "--robust",
            "--at",
            "1.5,4.7,8",
        ][..],
        &["eval", noisy, "--smooth", "auto", "--at", "1.5,4.7,8"][..],
        &[
            "eval",
            noisy,
            "--smooth",
            "auto",
            "--band",
            "0.95",
            "--at",
            "1.5,4.7,8",
        ][..],
    ] {
        let o = run(args, None);
        assert_eq!(o.code, 0, "{}", o.stderr);
        assert!(
            guide.contains(&o.stdout),
            "the guide's output of {args:?} is stale:\n{}",
            o.stdout
        );
    }
}

/// The noisy sine with a weight column and one gross outlier.
fn weighted(n: usize) -> (String, Vec<f64>, Vec<f64>, Vec<f64>) {
    let (_, x, mut y) = noisy(n);
    y[n / 3] += 8.0;
    let w: Vec<f64> = (0..n).map(|i| [1.0, 0.5, 2.0, 0.0][i % 4]).collect();
    let mut csv = String::from("w,x,y\n");
    for i in 0..n {
        csv.push_str(&format!("{},{},{}\n", w[i], x[i], y[i]));
    }
    (csv, x, y, w)
}

#[test]
fn weights_and_robust_fits_are_the_librarys() {
    let (csv, x, y, w) = weighted(150);
    let fit = |args: &[&str]| -> Value {
        let mut all = vec!["fit", "--smooth", "auto", "--x", "x", "--y", "y"];
        all.extend_from_slice(args);
        serde_json::from_str(&ok_stdin(&all, &csv)).unwrap()
    };
    let how = Smoothing::Gcv;
    // By name and by number.
    for col in ["w", "1"] {
        let v = fit(&["--weights", col]);
        let s = Spline::smoothing(&x, &y, Some(&w), Alphas::default(), how).unwrap();
        assert_eq!(numbers(&v["values"]), s.fit.values(), "--weights {col}");
        assert_eq!(v["lambda"].as_f64(), Some(s.lambda));
        assert!(v.get("robustness").is_none());
    }
    // Without --x and --y, every column but the weights is read.
    let v: Value = serde_json::from_str(&ok_stdin(
        &["fit", "--smooth", "auto", "--weights", "w"],
        &csv,
    ))
    .unwrap();
    assert_eq!(v["dimension"].as_u64(), Some(1));
    let r = Spline::smoothing_robust(&x, &y, Some(&w), Alphas::default(), how).unwrap();
    let v = fit(&["--weights", "w", "--robust"]);
    assert_eq!(numbers(&v["values"]), r.fit.values());
    assert_eq!(numbers(&v["robustness"]), r.robustness.clone().unwrap());
    assert_eq!(numbers(&v["robustness"])[150 / 3], 0.0, "the outlier");
    // eval uses the same fit, bands included.
    let o = ok_stdin(
        &[
            "eval",
            "--smooth",
            "auto",
            "--x",
            "x",
            "--y",
            "y",
            "--weights",
            "w",
            "--robust",
            "--band",
            "0.9",
            "--at",
            "1.5",
        ],
        &csv,
    );
    let row: Vec<f64> = o
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|f| f.parse().unwrap())
        .collect();
    let (lo, hi) = r.band(1.5, 0.9).unwrap();
    assert_eq!(row, [1.5, r.fit.eval(1.5).unwrap(), lo, hi], "{o}");
}

#[test]
fn bad_weights_name_their_line() {
    let table = "x,y,w\n0,1,1\n1,2,1\n2,1,-1\n3,0,1\n";
    for (args, stdin, code, want) in [
        (&["fit", "--weights", "w"][..], table, 2, "--smooth"),
        (&["fit", "--robust"][..], table, 2, "--smooth"),
        (
            &["fit", "--smooth", "auto", "--weights", "w"][..],
            table,
            1,
            "<stdin>:4: field 3: weight -1 is negative",
        ),
        (
            &["fit", "--smooth", "auto", "--weights", "w"][..],
            "x,y,w\n0,1,1\n1,2,nan\n2,1,1\n",
            1,
            "<stdin>:3: field 3: 'nan' is not a finite number (a weight)",
        ),
        (
            &["fit", "--smooth", "auto", "--weights", "v"][..],
            table,
            1,
            "no column named 'v' (--weights)",
        ),
        (
            &[
                "fit",
                "--smooth",
                "auto",
                "--weights",
                "2",
                "--columns",
                "x,y",
            ][..],
            "x,y,w\n0,1,1\n1,2,1\n2,1,1\n",
            1,
            "--weights names column 2, which is read as a coordinate too",
        ),
        (
            &[
                "fit",
                "--smooth",
                "auto",
                "--weights",
                "w",
                "--input-format",
                "json",
            ][..],
            "[[0,1],[1,2],[2,1]]",
            1,
            "--date-format and --weights are for tables",
        ),
        (
            &["fit", "--smooth", "auto", "--robust"][..],
            "x,y\n0,1\n1,2\n2,1\n3,3\n",
            1,
            "need at least 5",
        ),
    ] {
        let o = run(args, Some(stdin.as_bytes()));
        assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains(want), "{args:?}: {}", o.stderr);
    }
}
