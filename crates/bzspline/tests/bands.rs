//! Confidence bands of smoothing fits (`docs/method.md` §13): the standard
//! error against the dense posterior variance `sigma^2 b(x)^T M^-1 b(x)`, `M`
//! the normal equations' matrix assembled from the method's own basis
//! splines and inverted by Gaussian elimination; the band's coverage of the
//! true curve by simulation; the normal quantile against the distribution
//! function integrated numerically; and every refusal.

mod common;

use bzspline::{band_z, normal_quantile, Alphas, Curve, Error, Smoothing, Spline};
use common::{basis, gauss_solve, normal_matrix, Rng};

#[test]
fn standard_errors_are_the_dense_posterior_variance() {
    let mut rng = Rng::new(41);
    let mut worst = 0.0f64;
    for case in 0..200 {
        let n = rng.int(4, 20);
        let x = rng.grid(n, 1.0);
        let (a, z) = (x[0], x[n - 1]);
        let y: Vec<f64> = x
            .iter()
            .map(|&t| (5.0 * (t - a) / (z - a)).sin() + 0.3 * rng.uniform(-1.0, 1.0))
            .collect();
        let alphas = rng.alphas(n - 1);
        let mut w: Vec<f64> = (0..n).map(|_| rng.uniform(0.2, 3.0)).collect();
        if case % 4 == 0 {
            // Weights of zero, the ends among them.
            w[0] = 0.0;
            w[rng.int(1, n - 2)] = 0.0;
        }
        let span = z - a;
        let lambda = 10f64.powf(rng.uniform(-5.0, 0.0)) * span.powi(3);
        let s = Spline::smoothing(
            &x,
            &y,
            Some(&w),
            Alphas::PerInterval(&alphas),
            Smoothing::Lambda(lambda),
        )
        .unwrap();
        let b = basis(&x, &alphas);
        let m = normal_matrix(&x, &w, &b, lambda);
        let positive = w.iter().filter(|&&v| v > 0.0).count() as f64;
        let rss: f64 = (0..n)
            .map(|j| w[j] * (y[j] - s.fit.eval(x[j]).unwrap()).powi(2))
            .sum();
        if positive - s.dof < 1e-3 {
            continue; // next to interpolation: no residual to speak of
        }
        let sigma2 = rss / (positive - s.dof);
        // At the knots, at random points and at the ends.
        let mut at: Vec<f64> = x.clone();
        at.extend((0..3 * n).map(|_| rng.uniform(a, z)));
        for &t in &at {
            let bx: Vec<f64> = b.iter().map(|s| s.eval(t).unwrap()).collect();
            let minv_b = gauss_solve(m.clone(), bx.clone()).unwrap();
            let var: f64 = bx.iter().zip(&minv_b).map(|(p, q)| p * q).sum();
            let want = (sigma2 * var).sqrt();
            let got = s.se(t).unwrap();
            let e = (got - want).abs() / want.max(1e-300);
            worst = worst.max(e);
            assert!(
                e < 1e-10,
                "case {case}: n = {n}, lambda = {lambda:e}, x = {t}: se {got} against the dense {want}"
            );
        }
    }
    eprintln!("largest relative difference from the dense se: {worst:e}");
}

/// The 95 % band's average coverage of the true curve across the data
/// points, over many draws: Wahba's intervals cover about their level on
/// average across the function (not at every point).
#[test]
fn the_95_percent_band_covers_about_95_percent_of_the_points() {
    type Truth = fn(f64) -> f64;
    let truths: [(&str, Truth); 3] = [
        ("sine", |t| (2.0 * std::f64::consts::PI * t).sin()),
        ("chirp", |t| (8.0 * t * t + 1.0 * t).sin()),
        ("bump", |t| 2.0 * (-((t - 0.5) / 0.08).powi(2)).exp()),
    ];
    let mut rng = Rng::new(7);
    for (name, f) in truths {
        for (n, draws) in [(200, 200), (2000, 50)] {
            for sigma in [0.1, 0.5] {
                let x: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
                let truth: Vec<f64> = x.iter().map(|&t| f(t)).collect();
                let (mut covered, mut total) = (0usize, 0usize);
                for _ in 0..draws {
                    let y: Vec<f64> = truth.iter().map(|&v| v + sigma * rng.gaussian()).collect();
                    let s =
                        Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv).unwrap();
                    let (lo, hi) = s.band_many(&x, 0.95).unwrap();
                    for j in 0..n {
                        covered += usize::from(lo[j] <= truth[j] && truth[j] <= hi[j]);
                        total += 1;
                    }
                }
                let c = covered as f64 / total as f64;
                eprintln!("{name}, n = {n}, sigma = {sigma}: coverage {c:.4}");
                assert!(
                    (0.92..=0.985).contains(&c),
                    "{name}, n = {n}, sigma = {sigma}: the 95 % band covered {c:.4}"
                );
            }
        }
    }
}

#[test]
fn curves_have_a_standard_error_per_coordinate() {
    let mut rng = Rng::new(3);
    let n = 300;
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64 * 3.0;
            [
                t.cos() + 0.01 * rng.gaussian(),
                t.sin() + 0.2 * rng.gaussian(),
            ]
        })
        .collect();
    let s = Curve::builder_from(&pts)
        .smoothing(Smoothing::Gcv)
        .build_smoothed()
        .unwrap();
    let knots = s.fit.knots();
    let mid = 0.5 * (knots[0] + knots[knots.len() - 1]);
    let se = s.se(mid).unwrap();
    assert_eq!(se.len(), 2);
    // The noisier coordinate has the wider band (one lambda serves both,
    // so the quieter one's residuals also hold its bias).
    assert!(se[1] > 2.0 * se[0], "{se:?}");
    let var = s.posterior.noise_variance().unwrap();
    assert!(var[1] > var[0]);
}

#[test]
fn bands_are_refused_where_they_do_not_exist() {
    let x: Vec<f64> = (0..40).map(f64::from).collect();
    let y: Vec<f64> = x
        .iter()
        .map(|v| (v / 10.0).sin() + if v % 2.0 == 0.0 { 0.3 } else { -0.3 })
        .collect();
    let s = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv).unwrap();
    for level in [0.0, 1.0, -0.5, 1.5, f64::NAN] {
        assert!(
            matches!(s.band(3.0, level), Err(Error::InvalidArgument { .. })),
            "{level}"
        );
    }
    assert!(matches!(s.se(-1.0), Err(Error::OutOfDomain { .. })));
    assert!(matches!(s.se(f64::NAN), Err(Error::OutOfDomain { .. })));
    // Through every point: no residual to estimate the noise.
    let exact = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Lambda(0.0)).unwrap();
    let e = exact.se(3.0).unwrap_err().to_string();
    assert!(e.contains("no residual degrees of freedom"), "{e}");
    assert!(exact.band_many(&x, 0.9).is_err());
}

#[test]
fn normal_quantiles_invert_the_distribution_function() {
    // Phi(z) by Simpson's rule on [0, z] of the density, fine enough for
    // 1e-13, then p against it.
    let phi = |z: f64| {
        let m = 20_000;
        let h = z / f64::from(m);
        let d = |t: f64| (-0.5 * t * t).exp() / (2.0 * std::f64::consts::PI).sqrt();
        let mut s = d(0.0) + d(z);
        for i in 1..m {
            s += d(f64::from(i) * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        0.5 + s * h / 3.0
    };
    for p in [
        0.5, 0.6, 0.75, 0.9, 0.95, 0.975, 0.99, 0.995, 0.999, 0.9999, 0.999_999,
    ] {
        let z = normal_quantile(p).unwrap();
        assert!((phi(z) - p).abs() < 1e-12, "p = {p}: Phi({z}) = {}", phi(z));
        assert_eq!(normal_quantile(1.0 - p).unwrap(), -z, "{p}");
    }
    // Far tails (beyond the last branch's switch at 1e-11).
    for p in [1e-12, 1e-50, 1e-300] {
        let z = normal_quantile(p).unwrap();
        // Mills' ratio: p ~ phi(z) / |z| (1 - 1/z^2 + 3/z^4).
        let approx = (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt() / -z
            * (1.0 - 1.0 / (z * z) + 3.0 / z.powi(4));
        assert!((approx / p - 1.0).abs() < 1e-3, "{p}: {z}");
    }
    assert!((band_z(0.95).unwrap() - 1.959_963_984_540_054).abs() < 1e-15);
    for bad in [0.0, 1.0, -1.0, f64::NAN] {
        assert!(normal_quantile(bad).is_err());
    }
}
