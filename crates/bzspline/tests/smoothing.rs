//! Smoothing splines (`docs/method.md` §12): checked against the normal
//! equations `(B^T W B + lambda R) F = B^T W y` assembled densely from the
//! method's own basis splines (B their knot values, R the Gram matrix of
//! their second derivatives integrated exactly piece by piece) and solved by
//! Gaussian elimination; the trace against the dense influence matrix; the
//! exact limits (lambda = 0 is the interpolating variant, a huge lambda the
//! weighted least-squares line); weights; the defining conditions of the
//! method on the fitted control polygon; and every refusal.

mod common;

use bzspline::{Alphas, Curve, Error, Field, Param, Smoothing, Spline};
use common::{basis, gauss_solve, max_abs, normal_matrix, Rng};

/// The dense solution: control values and the trace of the influence matrix.
fn dense(x: &[f64], y: &[f64], w: &[f64], alphas: &[f64], lambda: f64) -> (Vec<f64>, f64) {
    let n = x.len();
    let b = basis(x, alphas);
    let kv: Vec<Vec<f64>> = b.iter().map(Spline::knot_values).collect(); // kv[k][j] = B_k(x_j)
    let m = normal_matrix(x, w, &b, lambda);
    let rhs: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|j| kv[i][j] * w[j] * y[j]).sum())
        .collect();
    let f = gauss_solve(m.clone(), rhs).unwrap();
    // tr(A) = sum_j w_j (B M^-1 B^T)_jj: column j of M^-1 B^T W e_j.
    let mut tr = 0.0;
    for j in 0..n {
        let col: Vec<f64> = (0..n).map(|i| kv[i][j] * w[j]).collect();
        let z = gauss_solve(m.clone(), col).unwrap();
        tr += (0..n).map(|i| kv[i][j] * z[i]).sum::<f64>();
    }
    (f, tr)
}

fn noisy(rng: &mut Rng, n: usize) -> (Vec<f64>, Vec<f64>) {
    let x = rng.grid(n, 1.5);
    let (a, b) = (x[0], x[n - 1]);
    let y = x
        .iter()
        .map(|&t| (6.0 * (t - a) / (b - a)).sin() + 0.3 * rng.uniform(-1.0, 1.0))
        .collect();
    (x, y)
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = max_abs(b);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (p, q)| m.max((p - q).abs() / scale))
}

#[test]
fn control_values_and_trace_match_the_dense_normal_equations() {
    let mut rng = Rng::new(29);
    for case in 0..300 {
        let n = rng.int(3, 24);
        let (x, y) = noisy(&mut rng, n);
        let alphas = rng.alphas(n - 1);
        let mut w: Vec<f64> = (0..n).map(|_| rng.uniform(0.1, 3.0)).collect();
        if case % 3 == 0 {
            // A few weights of zero, the ends included.
            for _ in 0..n / 4 {
                let j = rng.int(0, n - 1);
                w[j] = 0.0;
            }
            if w.iter().filter(|&&v| v > 0.0).count() < 2 {
                w[0] = 1.0;
                w[n - 1] = 1.0;
            }
        }
        let span = x[n - 1] - x[0];
        let lambda = 10f64.powf(rng.uniform(-8.0, 2.0)) * span.powi(3);
        let s = Spline::smoothing(
            &x,
            &y,
            Some(&w),
            Alphas::PerInterval(&alphas),
            Smoothing::Lambda(lambda),
        )
        .unwrap();
        let (f, tr) = dense(&x, &y, &w, &alphas, lambda);
        let e = rel(s.fit.values(), &f);
        assert!(
            e < 1e-7,
            "case {case}: n = {n}, lambda = {lambda:e}, control values off by {e:e}"
        );
        assert!(
            (s.dof - tr).abs() < 1e-7 * n as f64,
            "case {case}: trace {} against the dense {tr}",
            s.dof
        );
        assert_eq!(s.lambda, lambda);
    }
}

#[test]
fn gcv_score_is_the_dense_one_and_a_minimum() {
    let mut rng = Rng::new(7);
    for case in 0..40 {
        let n = rng.int(8, 30);
        let (x, y) = noisy(&mut rng, n);
        let alphas = rng.alphas(n - 1);
        let w: Vec<f64> = (0..n).map(|_| rng.uniform(0.5, 2.0)).collect();
        let a = Alphas::PerInterval(&alphas);
        let g = Spline::smoothing(&x, &y, Some(&w), a, Smoothing::Gcv).unwrap();
        // The score from the dense fit at the chosen lambda.
        let (f, tr) = dense(&x, &y, &w, &alphas, g.lambda);
        let fit = Spline::with_alphas(&x, &f, &alphas).unwrap().knot_values();
        let rss: f64 = (0..n).map(|j| w[j] * (y[j] - fit[j]).powi(2)).sum();
        let nn = n as f64;
        let score = rss / nn / (1.0 - tr / nn).powi(2);
        assert!(
            (g.gcv - score).abs() <= 1e-6 * score,
            "case {case}: gcv {} against the dense {score}",
            g.gcv
        );
        // The lambda reported reproduces the fit, bit for bit.
        let again = Spline::smoothing(&x, &y, Some(&w), a, Smoothing::Lambda(g.lambda)).unwrap();
        assert_eq!(again, g, "case {case}");
        // No lambda nearby or far scores lower, beyond the search's tolerance
        // (and the flat approach to interpolation when the least score is
        // there).
        for f in [1e-6, 1e-3, 0.1, 0.5, 0.9, 1.1, 2.0, 10.0, 1e3, 1e6] {
            let o =
                Spline::smoothing(&x, &y, Some(&w), a, Smoothing::Lambda(g.lambda * f)).unwrap();
            assert!(
                o.gcv >= g.gcv * (1.0 - 1e-3),
                "case {case}: lambda x {f} scores {} below the chosen {}",
                o.gcv,
                g.gcv
            );
        }
    }
}

#[test]
fn lambda_zero_is_the_interpolating_variant() {
    let mut rng = Rng::new(3);
    for case in 0..200 {
        let n = rng.int(3, 60);
        let x = rng.grid(n, 3.0);
        let y = rng.values(n);
        let alphas = rng.alphas(n - 1);
        let a = Alphas::PerInterval(&alphas);
        let s = Spline::smoothing(&x, &y, None, a, Smoothing::Lambda(0.0)).unwrap();
        let t = Spline::through(&x, &y, a).unwrap();
        let e = rel(s.fit.values(), t.values());
        assert!(e < 1e-11, "case {case}: {e:e}");
        assert!(
            (s.dof - n as f64).abs() < 1e-8 * n as f64,
            "case {case}: dof {}",
            s.dof
        );
    }
}

#[test]
fn a_huge_lambda_gives_the_weighted_least_squares_line() {
    let mut rng = Rng::new(5);
    for case in 0..100 {
        let n = rng.int(3, 200);
        let (x, y) = noisy(&mut rng, n);
        let w: Vec<f64> = (0..n).map(|_| rng.uniform(0.0, 2.0)).collect();
        let alphas = rng.alphas(n - 1);
        let span = x[n - 1] - x[0];
        let lambda = 1e12 * span.powi(3) * n as f64;
        let s = Spline::smoothing(
            &x,
            &y,
            Some(&w),
            Alphas::PerInterval(&alphas),
            Smoothing::Lambda(lambda),
        )
        .unwrap();
        // The weighted least-squares line, centred for accuracy.
        let sw: f64 = w.iter().sum();
        let xm = (0..n).map(|j| w[j] * x[j]).sum::<f64>() / sw;
        let ym = (0..n).map(|j| w[j] * y[j]).sum::<f64>() / sw;
        let sxy: f64 = (0..n).map(|j| w[j] * (x[j] - xm) * (y[j] - ym)).sum();
        let sxx: f64 = (0..n).map(|j| w[j] * (x[j] - xm).powi(2)).sum();
        let slope = sxy / sxx;
        for (j, v) in s.fit.knot_values().iter().enumerate() {
            let line = ym + slope * (x[j] - xm);
            assert!(
                (v - line).abs() < 1e-6,
                "case {case}: knot {j}: {v} against the line's {line}"
            );
        }
        assert!((s.dof - 2.0).abs() < 1e-6, "case {case}: dof {}", s.dof);
    }
}

#[test]
fn a_point_of_weight_zero_does_not_move_the_fit() {
    let mut rng = Rng::new(11);
    for case in 0..100 {
        let n = rng.int(4, 40);
        let (x, mut y) = noisy(&mut rng, n);
        let mut w = vec![1.0; n];
        let j = rng.int(0, n - 1);
        w[j] = 0.0;
        for smoothing in [
            Smoothing::Lambda(1e-3 * (x[n - 1] - x[0]).powi(3)),
            Smoothing::Gcv,
        ] {
            let a = Spline::smoothing(&x, &y, Some(&w), Alphas::default(), smoothing).unwrap();
            y[j] += 1e3;
            let b = Spline::smoothing(&x, &y, Some(&w), Alphas::default(), smoothing).unwrap();
            assert_eq!(
                a, b,
                "case {case}: moving point {j} of weight 0 moved the fit"
            );
        }
    }
}

#[test]
fn weights_and_units_scale_as_lambda_says() {
    let mut rng = Rng::new(13);
    for case in 0..50 {
        let n = rng.int(3, 40);
        let (x, y) = noisy(&mut rng, n);
        let w: Vec<f64> = (0..n).map(|_| rng.uniform(0.2, 2.0)).collect();
        let lambda = 1e-3 * (x[n - 1] - x[0]).powi(3);
        let s = Spline::smoothing(
            &x,
            &y,
            Some(&w),
            Alphas::default(),
            Smoothing::Lambda(lambda),
        )
        .unwrap();
        // x scaled by c and weights by v: the same fit with lambda v c^3.
        let (c, v) = (8.0, 0.25);
        let xs: Vec<f64> = x.iter().map(|t| t * c).collect();
        let ws: Vec<f64> = w.iter().map(|t| t * v).collect();
        let t = Spline::smoothing(
            &xs,
            &y,
            Some(&ws),
            Alphas::default(),
            Smoothing::Lambda(lambda * v * c * c * c),
        )
        .unwrap();
        let e = rel(t.fit.values(), s.fit.values());
        assert!(e < 1e-10, "case {case}: {e:e}");
        // Doubling every weight is halving lambda.
        let w2: Vec<f64> = w.iter().map(|t| 2.0 * t).collect();
        let u = Spline::smoothing(
            &x,
            &y,
            Some(&w2),
            Alphas::default(),
            Smoothing::Lambda(2.0 * lambda),
        )
        .unwrap();
        assert!(rel(u.fit.values(), s.fit.values()) < 1e-10, "case {case}");
        // GCV picks the same curve whatever the units.
        let g = Spline::smoothing(&x, &y, Some(&w), Alphas::default(), Smoothing::Gcv).unwrap();
        let h = Spline::smoothing(&xs, &y, Some(&ws), Alphas::default(), Smoothing::Gcv).unwrap();
        assert!(rel(h.fit.values(), g.fit.values()) < 1e-6, "case {case}");
        assert!(
            (h.lambda / (g.lambda * v * c * c * c) - 1.0).abs() < 1e-6,
            "case {case}"
        );
    }
}

#[test]
fn the_fit_is_the_methods_spline_of_its_control_polygon() {
    let mut rng = Rng::new(17);
    for case in 0..100 {
        let n = rng.int(3, 80);
        let (x, y) = noisy(&mut rng, n);
        let alphas = rng.alphas(n - 1);
        let s = Spline::smoothing(&x, &y, None, Alphas::PerInterval(&alphas), Smoothing::Gcv)
            .unwrap()
            .fit;
        let f = s.values();
        let scale = max_abs(f);
        // Ends, tangency to every leg at its alpha, C1, and the hull.
        assert!((s.eval(x[0]).unwrap() - f[0]).abs() <= 1e-12 * scale);
        assert!((s.eval(x[n - 1]).unwrap() - f[n - 1]).abs() <= 1e-12 * scale);
        for (k, (t, v)) in s.tangent_points().into_iter().enumerate() {
            let slope = (f[k + 1] - f[k]) / (x[k + 1] - x[k]);
            assert!(
                (s.eval(t).unwrap() - v).abs() <= 1e-10 * scale,
                "case {case}: leg {k}"
            );
            let d = s.deriv(t, 1).unwrap();
            assert!(
                (d - slope).abs() <= 1e-8 * (scale / (x[k + 1] - x[k])),
                "case {case}: leg {k}"
            );
        }
        for k in 1..n - 1 {
            let a = s.power_coefficients(k - 1).unwrap();
            let b = s.power_coefficients(k).unwrap();
            let h = x[k] - x[k - 1];
            let left = a[1] + h * (2.0 * a[2] + 3.0 * h * a[3]);
            assert!(
                (left - b[1]).abs() <= 1e-7 * scale / h.min(x[k + 1] - x[k]),
                "case {case}: knot {k}"
            );
        }
        let ((_, lo), (_, hi)) = s.range();
        let (fmin, fmax) = f
            .iter()
            .fold((f64::MAX, f64::MIN), |m, &v| (m.0.min(v), m.1.max(v)));
        assert!(
            lo >= fmin - 1e-12 * scale && hi <= fmax + 1e-12 * scale,
            "case {case}"
        );
    }
}

#[test]
fn a_noisy_track_is_smoothed_with_one_lambda_for_every_coordinate() {
    let mut rng = Rng::new(19);
    let n = 200;
    let pts: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64 * 6.0;
            [
                t.cos() * 10.0 + rng.uniform(-0.3, 0.3),
                t.sin() * 10.0 + rng.uniform(-0.3, 0.3),
                t + rng.uniform(-0.3, 0.3),
            ]
        })
        .collect();
    let data = Curve::builder_from(&pts);
    let smooth = data
        .clone()
        .smoothing(Smoothing::Gcv)
        .build_smoothed()
        .unwrap();
    let c = &smooth.fit;
    // The parameters are the data's (centripetal by default).
    let knots = Curve::builder_from(&pts).build().unwrap().knots().to_vec();
    assert_eq!(c.knots(), &knots[..]);
    // Each coordinate is the function fit with the same lambda on those knots.
    for d in 0..3 {
        let y: Vec<f64> = pts.iter().map(|p| p[d]).collect();
        let s = Spline::smoothing(
            &knots,
            &y,
            None,
            Alphas::default(),
            Smoothing::Lambda(smooth.lambda),
        )
        .unwrap();
        let cv: Vec<f64> = c.points().chunks(3).map(|p| p[d]).collect();
        assert!(rel(&cv, s.fit.values()) < 1e-12, "coordinate {d}");
    }
    // Closer to the circle than the data.
    let off = |p: &[f64]| ((p[0] * p[0] + p[1] * p[1]).sqrt() - 10.0).abs();
    let data_err: f64 = pts.iter().map(|p| off(p)).sum::<f64>() / n as f64;
    let fit_err: f64 = c.knot_points().iter().map(|p| off(p)).sum::<f64>() / n as f64;
    assert!(
        fit_err < 0.6 * data_err,
        "fit {fit_err} against the data's {data_err}"
    );
    assert!(smooth.dof > 2.0 && smooth.dof < n as f64);
    // Given parameters are used as given.
    let given: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let g = Curve::builder_from(&pts)
        .param(Param::Given(given.clone()))
        .smoothing(Smoothing::Lambda(1.0))
        .build_smoothed()
        .unwrap();
    assert_eq!(g.fit.knots(), &given[..]);
}

#[test]
fn bad_input_is_refused_with_its_place() {
    let x = [0.0, 1.0, 2.0, 3.0, 4.0];
    let y = [0.0, 1.0, 0.0, 1.0, 0.0];
    let a = Alphas::default();
    let l = Smoothing::Lambda(1.0);
    let err = |r: Result<bzspline::Smoothed<Spline>, Error>| r.unwrap_err();
    assert_eq!(
        err(Spline::smoothing(&x[..2], &y[..2], None, a, l)),
        Error::TooFewPoints { found: 2, min: 3 }
    );
    assert!(matches!(
        err(Spline::smoothing(
            &[0.0, 1.0, 1.0, 2.0],
            &y[..4],
            None,
            a,
            l
        )),
        Error::NotIncreasing { index: 2, .. }
    ));
    assert!(matches!(
        err(Spline::smoothing(
            &x,
            &[0.0, f64::NAN, 0.0, 0.0, 0.0],
            None,
            a,
            l
        )),
        Error::NonFinite {
            field: Field::Value,
            index: 1,
            ..
        }
    ));
    assert!(matches!(
        err(Spline::smoothing(
            &x,
            &y,
            Some(&[1.0, 1.0, -1.0, 1.0, 1.0]),
            a,
            l
        )),
        Error::NegativeWeight { index: 2, .. }
    ));
    assert!(matches!(
        err(Spline::smoothing(
            &x,
            &y,
            Some(&[1.0, 1.0, 1.0, f64::INFINITY, 1.0]),
            a,
            l
        )),
        Error::NonFinite {
            field: Field::Weight,
            index: 3,
            ..
        }
    ));
    assert!(matches!(
        err(Spline::smoothing(&x, &y, Some(&[1.0, 1.0]), a, l)),
        Error::LengthMismatch {
            field: Field::Weight,
            expected: 5,
            found: 2
        }
    ));
    assert!(matches!(
        err(Spline::smoothing(
            &x,
            &y,
            Some(&[0.0, 0.0, 1.0, 0.0, 0.0]),
            a,
            l
        )),
        Error::InvalidArgument { .. }
    ));
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            err(Spline::smoothing(&x, &y, None, a, Smoothing::Lambda(bad))),
            Error::InvalidArgument { .. }
        ));
    }
    assert!(matches!(
        err(Spline::smoothing(
            &x,
            &y,
            Some(&[1.0, 0.0, 1.0, 1.0, 1.0]),
            a,
            Smoothing::Lambda(0.0)
        )),
        Error::InvalidArgument { .. }
    ));
    assert!(matches!(
        err(Spline::smoothing(&x, &y, None, Alphas::Uniform(0.9), l)),
        Error::AlphaOutOfRange { .. }
    ));
    let e = err(Spline::smoothing(
        &x,
        &y,
        Some(&[1.0, 1.0, -1.0, 1.0, 1.0]),
        a,
        l,
    ));
    assert!(e.to_string().contains("weights[2]"), "{e}");
}

#[test]
fn hostile_input_gives_an_error_or_a_finite_fit_never_a_panic() {
    let mut rng = Rng::new(23);
    let picks = [0.0, 1e-300, 1e-30, 1e-8, 1.0, 1e8, 1e30, 1e300];
    for case in 0..400 {
        let n = rng.int(3, 30);
        let x: Vec<f64> = match case % 4 {
            0 => rng.grid(n, 12.0),
            1 => (0..n)
                .map(|i| 1e300 * (i as f64 / n as f64 - 0.5))
                .collect(),
            2 => (0..n).map(|i| 1e-300 * i as f64).collect(),
            _ => (0..n).map(|i| 1e15 + i as f64).collect(),
        };
        let m = picks[rng.int(1, picks.len() - 1)];
        let y: Vec<f64> = (0..n).map(|_| m * rng.uniform(-1.0, 1.0)).collect();
        let w: Vec<f64> = (0..n).map(|_| picks[rng.int(0, picks.len() - 1)]).collect();
        let how = match case % 3 {
            0 => Smoothing::Gcv,
            _ => Smoothing::Lambda(picks[rng.int(0, picks.len() - 1)]),
        };
        let weights = if case % 5 == 0 { None } else { Some(&w[..]) };
        match Spline::smoothing(&x, &y, weights, Alphas::default(), how) {
            Ok(s) => {
                assert!(s.fit.values().iter().all(|v| v.is_finite()), "case {case}");
                assert!(
                    s.lambda.is_finite() && s.lambda >= 0.0,
                    "case {case}: {}",
                    s.lambda
                );
                assert!(
                    !s.dof.is_nan() && !s.gcv.is_nan() && s.gcv >= 0.0,
                    "case {case}: {} {}",
                    s.dof,
                    s.gcv
                );
                for k in 0..n - 1 {
                    let t = 0.5 * (x[k] + x[k + 1]);
                    assert!(s.fit.eval(t).unwrap().is_finite(), "case {case}");
                }
            }
            Err(e) => {
                // Every refusal names what is wrong in words.
                assert!(!e.to_string().is_empty(), "case {case}");
            }
        }
    }
}

#[test]
fn a_dropped_repeat_adds_its_weight_to_the_point_it_repeats() {
    let pts = [
        [0.0, 0.0],
        [1.0, 0.5],
        [1.0, 0.5],
        [2.0, -0.2],
        [3.0, 0.4],
        [4.0, 0.0],
    ];
    let w = [1.0, 2.0, 3.0, 1.0, 0.5, 1.0];
    let with = Curve::builder_from(&pts)
        .repeats(bzspline::Repeats::Drop)
        .weights(&w)
        .smoothing(Smoothing::Lambda(0.1))
        .build_smoothed()
        .unwrap();
    let kept = [pts[0], pts[1], pts[3], pts[4], pts[5]];
    let without = Curve::builder_from(&kept)
        .weights(&[1.0, 5.0, 1.0, 0.5, 1.0])
        .smoothing(Smoothing::Lambda(0.1))
        .build_smoothed()
        .unwrap();
    assert_eq!(with.fit.points(), without.fit.points());
    assert_eq!(with.fit.dropped(), &[2]);
    // A bad weight is named where the caller put it, before any merge.
    let bad = [1.0, 2.0, 3.0, -1.0, 0.5, 1.0];
    let e = Curve::builder_from(&pts)
        .repeats(bzspline::Repeats::Drop)
        .weights(&bad)
        .build_smoothed()
        .unwrap_err();
    assert_eq!(
        e,
        Error::NegativeWeight {
            index: 3,
            value: -1.0
        }
    );
}

#[test]
fn plain_build_refuses_a_smoothing_builder() {
    let pts: Vec<[f64; 2]> = (0..10).map(|i| [f64::from(i), f64::from(i % 3)]).collect();
    let b = Curve::builder_from(&pts).smoothing(Smoothing::Lambda(1.0));
    assert!(matches!(
        b.clone().build(),
        Err(Error::InvalidArgument { what, .. }) if what.contains("build_smoothed")
    ));
    let mut c = Curve::open(&pts).unwrap();
    let before = c.clone();
    assert!(b.clone().build_into(&mut c).is_err());
    assert_eq!(c, before);
    // The same builder smooths through build_smoothed.
    assert!(b.build_smoothed().is_ok());
}
