//! The smoothing spline of arbitrary data, weights and lambda (fixed or by
//! cross-validation), as a function and as an open curve: refusals are typed
//! errors, never panics; an accepted fit is finite everywhere, with a finite
//! lambda, degrees of freedom between 0 and n (loosely) and a score that is
//! not NaN; a point of weight 0 does not move it.
#![no_main]

use bzspline::{Alphas, CurveBuilder, Smoothing, Spline};
use bzspline_fuzz::{Data, Reader};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let mut r = Reader::new(bytes);
    let d = Data::decode(&mut r);
    let n = d.knots.len();
    let weights: Vec<f64> = (0..n)
        .map(|_| match r.u8() % 6 {
            0 => 0.0,
            1 => r.raw_f64(),
            _ => r.pow10(-300, 300),
        })
        .collect();
    let how = match r.u8() % 3 {
        0 => Smoothing::Gcv,
        1 => Smoothing::Lambda(r.raw_f64()),
        _ => Smoothing::Lambda(r.pow10(-300, 300)),
    };
    let alphas = if d.alphas.len() == 1 {
        Alphas::Uniform(d.alphas[0])
    } else {
        Alphas::PerInterval(&d.alphas)
    };
    let w = (r.u8() % 2 == 0).then_some(&weights[..]);
    if let Ok(s) = Spline::smoothing(&d.knots, &d.values, w, alphas, how) {
        assert!(s.fit.values().iter().all(|v| v.is_finite()));
        assert!(
            s.lambda.is_finite() && s.lambda >= 0.0,
            "lambda {}",
            s.lambda
        );
        assert!(
            !s.gcv.is_nan() && !s.dof.is_nan(),
            "gcv {} dof {}",
            s.gcv,
            s.dof
        );
        assert!(
            s.dof > -1e-6 && s.dof < n as f64 * (1.0 + 1e-6) + 1e-6,
            "dof {}",
            s.dof
        );
        for k in 0..n - 1 {
            let t = 0.5 * (d.knots[k] + d.knots[k + 1]);
            assert!(s.fit.eval(t).is_ok_and(f64::is_finite));
        }
        // A point of weight 0 does not move the fit (lambda fixed).
        if let (Some(w), Smoothing::Lambda(_)) = (w, how) {
            if let Some(j) = w.iter().position(|&v| v == 0.0) {
                let mut moved = d.values.clone();
                // Another value of the data's largest magnitude, so that the
                // values keep their power-of-two scale.
                let top = d.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                moved[j] = if moved[j] == top { -top } else { top };
                if let Ok(t) = Spline::smoothing(&d.knots, &moved, Some(w), alphas, how) {
                    // Equal, but for rounding where the values reach the
                    // subnormal range.
                    let big = s
                        .fit
                        .values()
                        .iter()
                        .fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
                    for (a, b) in t.fit.values().iter().zip(s.fit.values()) {
                        assert!((a - b).abs() <= 1e-9 * big, "weight 0 at {j} moved the fit");
                    }
                }
            }
        }
    }
    // As a curve of the points (knot, value), open, on their parameters.
    let pts: Vec<f64> = d
        .knots
        .iter()
        .zip(&d.values)
        .flat_map(|(a, b)| [*a, *b])
        .collect();
    let mut b = CurveBuilder::new(&pts, 2).smoothing(how);
    if let Some(w) = w {
        b = b.weights(w);
    }
    if let Ok(c) = b.build_smoothed() {
        assert!(c.fit.points().iter().all(|v| v.is_finite()));
        assert!(c.lambda.is_finite() && !c.gcv.is_nan());
    }
});
