//! Robust smoothing (`docs/method.md` §14): with 1 % gross outliers the
//! robust fit's error stays close to the fit of the same data without them
//! while the plain fit's does not; the fit is the plain fit with the
//! weights it reports; those weights are the biweights of its own residuals
//! (computed here independently); and the refusals.

mod common;

use bzspline::{Alphas, Curve, Error, Smoothing, Spline, ROBUST_MIN_POINTS};
use common::Rng;

/// Root-mean-square distance of a fit from the truth at the data points.
fn rms_error(s: &Spline, x: &[f64], truth: &dyn Fn(f64) -> f64) -> f64 {
    let sum: f64 = x
        .iter()
        .map(|&t| (s.eval(t).unwrap() - truth(t)).powi(2))
        .sum();
    (sum / x.len() as f64).sqrt()
}

type Function = (&'static str, fn(f64) -> f64);

const FUNCTIONS: [Function; 3] = [
    ("sine", |t| (6.0 * t).sin()),
    ("chirp", |t| (12.0 * t * t).sin()),
    ("bump", |t| (-((t - 0.5) / 0.1).powi(2)).exp()),
];

#[test]
fn outliers_barely_move_the_robust_fit() {
    let mut rng = Rng::new(43);
    for (name, f) in FUNCTIONS {
        for n in [500, 2000] {
            for noise in [0.05, 0.2] {
                let x: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
                let clean: Vec<f64> = x.iter().map(|&t| f(t) + noise * rng.gaussian()).collect();
                let mut dirty = clean.clone();
                let mut outliers = Vec::new();
                for _ in 0..n / 100 {
                    let j = rng.int(0, n - 1);
                    let jump = rng.uniform(5.0, 10.0);
                    dirty[j] += if rng.unit() < 0.5 { jump } else { -jump };
                    outliers.push(j);
                }
                let fit = |y: &[f64], robust: bool| {
                    let how = Smoothing::Gcv;
                    if robust {
                        Spline::smoothing_robust(&x, y, None, Alphas::default(), how).unwrap()
                    } else {
                        Spline::smoothing(&x, y, None, Alphas::default(), how).unwrap()
                    }
                };
                let base = rms_error(&fit(&clean, false).fit, &x, &f);
                let plain = rms_error(&fit(&dirty, false).fit, &x, &f);
                let r = fit(&dirty, true);
                let robust = rms_error(&r.fit, &x, &f);
                let case = format!("{name} n={n} noise={noise}: clean {base:.2e}, plain {plain:.2e}, robust {robust:.2e}");
                assert!(robust < 1.3 * base, "{case}");
                assert!(plain > 1.6 * base, "{case}");
                let w = r.robustness.as_ref().unwrap();
                assert_eq!(w.len(), n);
                for &j in &outliers {
                    assert!(w[j] < 0.05, "{case}: outlier {j} kept with weight {}", w[j]);
                }
                let kept = w.iter().filter(|&&v| v > 0.5).count();
                assert!(
                    kept > n * 9 / 10,
                    "{case}: only {kept} points weighted above 1/2"
                );
                // Without outliers, robust costs next to nothing.
                let calm = rms_error(&fit(&clean, true).fit, &x, &f);
                assert!(
                    calm < 1.35 * base,
                    "{case}: robust on clean data {calm:.2e}"
                );
            }
        }
    }
}

/// Tukey's biweight of the residuals on six median absolute residuals,
/// written out directly.
fn biweights(residuals: &[f64]) -> Vec<f64> {
    let mut sorted: Vec<f64> = residuals.iter().map(|r| r.abs()).collect();
    sorted.sort_by(f64::total_cmp);
    let m = sorted.len();
    let median = if m % 2 == 1 {
        sorted[m / 2]
    } else {
        (sorted[m / 2 - 1] + sorted[m / 2]) / 2.0
    };
    residuals
        .iter()
        .map(|r| {
            let u = r.abs() / (6.0 * median);
            if u < 1.0 {
                (1.0 - u * u).powi(2)
            } else {
                0.0
            }
        })
        .collect()
}

#[test]
fn the_fit_is_the_plain_fit_with_the_weights_of_its_own_residuals() {
    let mut rng = Rng::new(44);
    for case in 0..40 {
        let n = rng.int(20, 300);
        let x = rng.grid(n, 1.0);
        let (a, z) = (x[0], x[n - 1]);
        let mut y: Vec<f64> = x
            .iter()
            .map(|&t| (4.0 * (t - a) / (z - a)).cos() + 0.1 * rng.gaussian())
            .collect();
        for _ in 0..rng.int(0, n / 20) {
            let j = rng.int(0, n - 1);
            y[j] += rng.uniform(-3.0, 3.0);
        }
        let alphas = rng.alphas(n - 1);
        let w: Vec<f64> = (0..n)
            .map(|_| if rng.int(0, 9) == 0 { 0.0 } else { 1.0 })
            .collect();
        let how = if case % 2 == 0 {
            Smoothing::Gcv
        } else {
            Smoothing::Lambda(1e-4 * (z - a).powi(3))
        };
        let r =
            Spline::smoothing_robust(&x, &y, Some(&w), Alphas::PerInterval(&alphas), how).unwrap();
        let rw = r.robustness.clone().unwrap();
        assert!(rw.iter().all(|v| (0.0..=1.0).contains(v)), "case {case}");
        // The fit is the plain fit of its lambda under the product of the
        // weights.
        let both: Vec<f64> = w.iter().zip(&rw).map(|(a, b)| a * b).collect();
        let given = Smoothing::Lambda(r.lambda);
        let plain = Spline::smoothing(&x, &y, Some(&both), Alphas::PerInterval(&alphas), given);
        assert_eq!(plain.unwrap().fit, r.fit, "case {case}");
        // And the weights are the biweights of its residuals, to the
        // iteration's settling tolerance (points of weight 0 aside).
        let kept: Vec<usize> = (0..n).filter(|&j| w[j] > 0.0).collect();
        let res: Vec<f64> = kept
            .iter()
            .map(|&j| y[j] - r.fit.eval(x[j]).unwrap())
            .collect();
        let again = biweights(&res);
        for (i, &j) in kept.iter().enumerate() {
            assert!(
                (again[i] - rw[j]).abs() < 0.02,
                "case {case}, point {j}: reported {} against {}",
                rw[j],
                again[i]
            );
        }
    }
}

#[test]
fn robust_curves_report_a_weight_for_every_point_given() {
    let mut rng = Rng::new(45);
    let n = 400;
    let mut pts = Vec::new();
    for i in 0..n {
        let t = i as f64 / (n - 1) as f64 * 3.0;
        pts.extend([
            t.cos() + 0.01 * rng.gaussian(),
            t.sin() + 0.01 * rng.gaussian(),
        ]);
    }
    // A GPS jump and a repeated point.
    pts[2 * 100 + 1] += 2.0;
    let repeat = [pts[2 * 200], pts[2 * 200 + 1]];
    pts.splice(2 * 201..2 * 201, repeat);
    // Parameters from the points would stretch around the jump; a GPS track
    // has its times, here uniform.
    let s = Curve::builder(&pts, 2)
        .param(bzspline::Param::Uniform)
        .repeats(bzspline::Repeats::Drop)
        .robust(true)
        .build_smoothed()
        .unwrap();
    let w = s.robustness.unwrap();
    assert_eq!(w.len(), n + 1);
    assert_eq!(w[100], 0.0);
    assert_eq!(w[201], w[200]);
    let p = s.fit.eval(s.fit.knots()[100]).unwrap();
    let t = 100.0 / (n - 1) as f64 * 3.0;
    assert!((p[0] - t.cos()).hypot(p[1] - t.sin()) < 0.02, "{p:?}");
}

#[test]
fn too_few_points_are_refused() {
    let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let y = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0];
    let how = Smoothing::Gcv;
    let ok = Spline::smoothing_robust(&x, &y, None, Alphas::default(), how).unwrap();
    assert!(ok.fit.knot_values().iter().all(|v| v.is_finite()));
    let w = [1.0, 1.0, 0.0, 1.0, 1.0, 1.0];
    assert!(Spline::smoothing_robust(&x, &y, Some(&w), Alphas::default(), how).is_ok());
    let w = [1.0, 1.0, 0.0, 1.0, 0.0, 1.0];
    let e = Spline::smoothing_robust(&x, &y, Some(&w), Alphas::default(), how).unwrap_err();
    assert_eq!(
        e,
        Error::TooFewPoints {
            found: 4,
            min: ROBUST_MIN_POINTS
        }
    );
    let e = Spline::smoothing_robust(&x[..4], &y[..4], None, Alphas::default(), how);
    assert!(matches!(e, Err(Error::TooFewPoints { found: 4, .. })));
}
