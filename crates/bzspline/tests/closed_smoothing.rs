//! Smoothing closed curves (`docs/method.md` §15): the periodic fit against
//! the normal equations assembled densely from the method's own closed basis
//! curves (`B` their knot values, `R` the Gram matrix of their second
//! derivatives from their Bezier control points) and solved by Gaussian
//! elimination: control points, degrees of freedom and standard errors; the
//! limits (interpolation, the weighted mean point); GCV's choice; a noisy
//! closed contour; and the closing knot as smooth as any other.

mod common;

use bzspline::{Curve, Param, Smoothing};
use common::{gauss_solve, Rng};

/// The closed basis curves on the knots: first coordinate 1 at point `k`,
/// 0 elsewhere (the second, the point's index, only keeps consecutive
/// points apart; on given parameters the coordinates are independent).
fn basis(knots: &[f64], alphas: &[f64]) -> Vec<Curve> {
    let n = knots.len() - 1;
    (0..n)
        .map(|k| {
            let e: Vec<f64> = (0..n)
                .flat_map(|j| [if j == k { 1.0 } else { 0.0 }, j as f64])
                .collect();
            Curve::builder(&e, 2)
                .closed(true)
                .param(Param::Given(knots.to_vec()))
                .alphas(alphas)
                .build()
                .unwrap()
        })
        .collect()
}

/// `B^T W B + lambda R` (row-major) of the closed basis, `R` integrated
/// exactly: on each piece `S''` is linear, its end values in the local
/// variable `6 (P0 - 2 P1 + P2)` and `6 (P1 - 2 P2 + P3)` from the Bezier
/// control points, and `int S''^2 dtau = (a0^2 + a0 a1 + a1^2) / (3 h^3)`.
fn normal_matrix(knots: &[f64], w: &[f64], b: &[Curve], lambda: f64) -> Vec<f64> {
    let n = b.len();
    let kv: Vec<Vec<f64>> = b
        .iter()
        .map(|c| c.knot_points().iter().map(|p| p[0]).collect())
        .collect();
    let ends = |c: &Curve, p: usize| {
        let s = c.segment_points(p).unwrap();
        let q = [s[0], s[2], s[4], s[6]]; // the first coordinate
        (
            6.0 * (q[0] - 2.0 * q[1] + q[2]),
            6.0 * (q[1] - 2.0 * q[2] + q[3]),
        )
    };
    let mut m = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            m[i * n + k] = (0..n).map(|j| kv[i][j] * w[j] * kv[k][j]).sum();
        }
    }
    for p in 0..n {
        let h = knots[p + 1] - knots[p];
        for i in 0..n {
            let (a0, a1) = ends(&b[i], p);
            for k in 0..n {
                let (b0, b1) = ends(&b[k], p);
                m[i * n + k] +=
                    lambda * (a0 * b0 + 0.5 * (a0 * b1 + a1 * b0) + a1 * b1) / (3.0 * h * h * h);
            }
        }
    }
    m
}

/// Random increasing closed-curve parameters (n + 1).
fn params(rng: &mut Rng, n: usize) -> Vec<f64> {
    rng.grid(n + 1, 1.0)
}

#[test]
fn the_fit_is_the_dense_normal_equations_solution() {
    let mut rng = Rng::new(47);
    let (mut worst_f, mut worst_dof, mut worst_se) = (0.0f64, 0.0f64, 0.0f64);
    for case in 0..150 {
        let n = rng.int(3, 18);
        let knots = params(&mut rng, n);
        let alphas = rng.alphas(n);
        let span = knots[n] - knots[0];
        let pts: Vec<f64> = (0..n)
            .flat_map(|j| {
                let t = std::f64::consts::TAU * (knots[j] - knots[0]) / span;
                [3.0 * t.cos(), 2.0 * t.sin()]
            })
            .map(|v| v + 0.3 * rng.uniform(-1.0, 1.0))
            .collect();
        let mut w: Vec<f64> = (0..n).map(|_| rng.uniform(0.2, 3.0)).collect();
        if case % 3 == 0 {
            w[rng.int(0, n - 1)] = 0.0;
            if n > 4 {
                w[0] = 0.0;
            }
        }
        if w.iter().filter(|&&v| v > 0.0).count() < 2 {
            w[1] = 1.0;
            w[2] = 1.0;
        }
        let lambda = 10f64.powf(rng.uniform(-6.0, 1.0)) * span.powi(3);
        let s = Curve::builder(&pts, 2)
            .closed(true)
            .param(Param::Given(knots.clone()))
            .alphas(&alphas)
            .weights(&w)
            .smoothing(Smoothing::Lambda(lambda))
            .build_smoothed()
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        assert!(s.fit.is_closed());
        let b = basis(&knots, &alphas);
        let m = normal_matrix(&knots, &w, &b, lambda);
        let kv: Vec<Vec<f64>> = b
            .iter()
            .map(|c| c.knot_points().iter().map(|p| p[0]).collect())
            .collect();
        let mut residual = 0.0;
        for c in 0..2 {
            let rhs: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| kv[i][j] * w[j] * pts[2 * j + c]).sum())
                .collect();
            let f = gauss_solve(m.clone(), rhs).unwrap();
            let got: Vec<f64> = (0..n).map(|j| s.fit.points()[2 * j + c]).collect();
            let scale = f.iter().fold(1e-300f64, |a, v| a.max(v.abs()));
            for j in 0..n {
                worst_f = worst_f.max((got[j] - f[j]).abs() / scale);
            }
            let kp = s.fit.knot_points();
            residual += (0..n)
                .map(|j| w[j] * (kp[j][c] - pts[2 * j + c]).powi(2))
                .sum::<f64>();
        }
        // tr A = sum_j w_j (B^T M^-1 B)_jj.
        let mut dof = 0.0;
        for j in 0..n {
            let col: Vec<f64> = (0..n).map(|i| kv[i][j]).collect();
            let z = gauss_solve(m.clone(), col.clone()).unwrap();
            dof += w[j] * col.iter().zip(&z).map(|(a, b)| a * b).sum::<f64>();
        }
        worst_dof = worst_dof.max((s.dof - dof).abs() / dof);
        // Standard errors, each coordinate with its own noise variance.
        let positive = w.iter().filter(|&&v| v > 0.0).count() as f64;
        if positive - dof > 1e-3 {
            for _ in 0..5 {
                let t = rng.uniform(knots[0], knots[n]);
                let bt: Vec<f64> = b.iter().map(|c| c.eval(t).unwrap()[0]).collect();
                let z = gauss_solve(m.clone(), bt.clone()).unwrap();
                let quad: f64 = bt.iter().zip(&z).map(|(a, b)| a * b).sum();
                let se = s.se(t).unwrap();
                let kp = s.fit.knot_points();
                for (c, got) in se.iter().enumerate() {
                    let rss: f64 = (0..n)
                        .map(|j| w[j] * (kp[j][c] - pts[2 * j + c]).powi(2))
                        .sum();
                    let want = (rss / (positive - dof) * quad).sqrt();
                    worst_se = worst_se.max((got - want).abs() / want.max(1e-300));
                }
            }
        }
        assert!(residual.is_finite());
    }
    assert!(worst_f < 2e-9, "control points: {worst_f:e}");
    assert!(worst_dof < 2e-9, "degrees of freedom: {worst_dof:e}");
    assert!(worst_se < 2e-9, "standard errors: {worst_se:e}");
}

#[test]
fn the_limits_are_the_loop_through_the_points_and_the_mean_point() {
    let mut rng = Rng::new(48);
    for _ in 0..30 {
        let n = rng.int(3, 40);
        let knots = params(&mut rng, n);
        let pts: Vec<f64> = (0..3 * n).map(|_| rng.uniform(-5.0, 5.0)).collect();
        let build = |lambda: f64, w: &[f64]| {
            Curve::builder(&pts, 3)
                .closed(true)
                .param(Param::Given(knots.clone()))
                .weights(w)
                .smoothing(Smoothing::Lambda(lambda))
                .build_smoothed()
                .unwrap()
        };
        let ones = vec![1.0; n];
        let through = build(0.0, &ones);
        for (j, p) in through.fit.knot_points().iter().enumerate() {
            for c in 0..3 {
                assert!((p[c] - pts[3 * j + c]).abs() < 1e-9, "{p:?}");
            }
        }
        assert!((through.dof - n as f64).abs() < 1e-6);
        let w: Vec<f64> = (0..n).map(|_| rng.uniform(0.5, 2.0)).collect();
        let span = knots[n] - knots[0];
        let flat = build(1e12 * span.powi(3), &w);
        let total: f64 = w.iter().sum();
        for c in 0..3 {
            let mean = (0..n).map(|j| w[j] * pts[3 * j + c]).sum::<f64>() / total;
            for p in flat.fit.knot_points() {
                assert!((p[c] - mean).abs() < 1e-5, "{} against {mean}", p[c]);
            }
        }
        assert!((flat.dof - 1.0).abs() < 1e-5, "dof {}", flat.dof);
    }
}

#[test]
fn a_noisy_contour_is_smoothed_and_gcv_chooses_its_least_score() {
    let mut rng = Rng::new(49);
    for n in [12, 200, 3000] {
        let t: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
        let truth = |u: f64| {
            let a = std::f64::consts::TAU * u;
            let r = 10.0 + (3.0 * a).cos();
            [r * a.cos(), r * a.sin()]
        };
        let pts: Vec<f64> = (0..n)
            .flat_map(|i| truth(t[i]))
            .map(|v| v + 0.3 * rng.gaussian())
            .collect();
        let s = Curve::builder(&pts, 2)
            .closed(true)
            .param(Param::Given(t.clone()))
            .build_smoothed()
            .unwrap();
        let err = |p: &[f64], i: usize| {
            let q = truth(t[i]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        };
        let fit_err: f64 = s
            .fit
            .knot_points()
            .iter()
            .enumerate()
            .map(|(i, p)| err(p, i))
            .sum::<f64>()
            / n as f64;
        let data_err: f64 = (0..n).map(|i| err(&pts[2 * i..2 * i + 2], i)).sum::<f64>() / n as f64;
        if n < 200 {
            // Too few points for the shape: GCV's score levels off towards
            // interpolation, as for an open fit.
            continue;
        }
        assert!(
            fit_err < 0.5 * data_err,
            "n={n}: {fit_err} against {data_err}"
        );
        // No lambda on a fine grid around the chosen one scores lower.
        for k in -20..=20 {
            let l = s.lambda * 10f64.powf(f64::from(k) / 5.0);
            let other = Curve::builder(&pts, 2)
                .closed(true)
                .param(Param::Given(t.clone()))
                .smoothing(Smoothing::Lambda(l))
                .build_smoothed()
                .unwrap();
            assert!(
                other.gcv >= s.gcv * (1.0 - 1e-9),
                "n={n}: {l} scores {} < {}",
                other.gcv,
                s.gcv
            );
        }
        // C1 across the closing knot: the end of the last piece meets the
        // start of the first with the same derivative.
        let (a, z) = (t[0], t[n]);
        let d0 = s.fit.deriv(a, 1).unwrap();
        let d1 = s.fit.deriv(z, 1).unwrap();
        let p0 = s.fit.eval(a).unwrap();
        let p1 = s.fit.eval(z).unwrap();
        for c in 0..2 {
            assert!(
                (p0[c] - p1[c]).abs() < 1e-9 && (d0[c] - d1[c]).abs() < 1e-6 * d0[c].abs().max(1.0)
            );
        }
        // Bands round the loop.
        let se = s.se(0.5 * (t[0] + t[1])).unwrap();
        assert!(se.iter().all(|v| v.is_finite() && *v > 0.0), "{se:?}");
    }
}

#[test]
fn a_closed_track_with_a_jump_is_smoothed_robustly() {
    let mut rng = Rng::new(50);
    let n = 300;
    let t: Vec<f64> = (0..=n).map(|i| i as f64).collect();
    let mut pts: Vec<f64> = (0..n)
        .flat_map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [100.0 * a.cos(), 60.0 * a.sin()]
        })
        .map(|v| v + 0.5 * rng.gaussian())
        .collect();
    pts[0] += 40.0; // point 0: at the closing knot itself
    pts[2 * 150 + 1] -= 40.0;
    let s = Curve::builder(&pts, 2)
        .closed(true)
        .param(Param::Given(t))
        .robust(true)
        .build_smoothed()
        .unwrap();
    let w = s.robustness.unwrap();
    assert_eq!((w.len(), w[0], w[150]), (n, 0.0, 0.0));
    let p = &s.fit.knot_points()[0];
    assert!((p[0] - 100.0).abs() < 1.0 && p[1].abs() < 1.0, "{p:?}");
}
