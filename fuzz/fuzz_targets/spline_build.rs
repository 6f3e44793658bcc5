//! Building a spline from arbitrary knots, values and alphas: refusals are
//! typed errors, never panics; accepted input gives a finite C1 spline that
//! touches every leg and stays within the values' range (checked loosely,
//! relative to the largest value). The interpolating variant on the same
//! input refuses it alike, or passes through the values (or says that a
//! solved control value overflows).
#![no_main]

use bzspline::ParamCurve;
use bzspline::{Alphas, Error, Spline, ALPHA_MAX, ALPHA_MIN};
use bzspline_fuzz::{cubic, cubic_deriv, Data, Reader};
use libfuzzer_sys::fuzz_target;

/// Relative tolerance of the loose checks.
const REL: f64 = 1e-8;

fuzz_target!(|bytes: &[u8]| {
    let d = Data::decode(&mut Reader::new(bytes));
    let built = if d.alphas.len() == 1 && d.knots.len() != 2 {
        Spline::with_alpha(&d.knots, &d.values, d.alphas[0])
    } else {
        Spline::with_alphas(&d.knots, &d.values, &d.alphas)
    };
    let alphas = if d.alphas.len() == 1 && d.knots.len() != 2 {
        Alphas::Uniform(d.alphas[0])
    } else {
        Alphas::PerInterval(&d.alphas)
    };
    let through = Spline::through(&d.knots, &d.values, alphas);
    let s = match built {
        Ok(s) => s,
        Err(e) => {
            check_refusal(&d, &e);
            // Everything the method refuses, the variant refuses alike.
            assert_eq!(through.err().map(|t| t.to_string()), Some(e.to_string()));
            return;
        }
    };
    check_accepted(&d, &s);
    match through {
        Ok(t) => {
            let big = d.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (k, (v, w)) in t.knot_values().iter().zip(&d.values).enumerate() {
                assert!(v.is_finite(), "through: knot value {k} is {v}");
                assert!(
                    (v - w).abs() <= 1e-9 * big,
                    "through: knot {k} is {v}, the value {w}"
                );
            }
        }
        Err(Error::Overflow { .. }) => {}
        Err(e) => panic!("the method accepts what the variant refuses: {e}"),
    }
});

/// A refusal must be justified by the input.
fn check_refusal(d: &Data, e: &Error) {
    let msg = e.to_string();
    assert!(!msg.is_empty());
    match *e {
        Error::NonFinite { index, value, .. } => assert!(!value.is_finite(), "{msg} (#{index})"),
        Error::AlphaOutOfRange { value, .. } => {
            assert!(!(ALPHA_MIN..=ALPHA_MAX).contains(&value), "{msg}");
        }
        Error::NotIncreasing {
            index,
            previous,
            value,
        } => {
            assert!(index >= 1 && value <= previous, "{msg}");
            assert_eq!(d.knots[index], value);
        }
        Error::TooFewPoints { found, .. } => assert!(found < 2, "{msg}"),
        _ => {}
    }
}

fn check_accepted(d: &Data, s: &Spline) {
    let n = d.knots.len();
    assert!(n >= 2 && d.values.len() == n);
    assert!(s
        .alphas()
        .iter()
        .all(|a| (ALPHA_MIN..=ALPHA_MAX).contains(a)));
    assert!(d.knots.windows(2).all(|w| w[0] < w[1]));
    let m = d.max_abs();
    let lo = d.values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = d.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let tol = REL * m;

    // Ends are the end control values.
    let (a, b) = s.domain();
    assert_eq!(s.eval(a).ok(), Some(d.values[0]), "S(tau_0)");
    assert_eq!(s.eval(b).ok(), Some(d.values[n - 1]), "S(tau_N)");
    let kv = s.knot_values();
    assert!(kv.iter().all(|v| v.is_finite()), "knot values {kv:?}");
    assert!(
        kv.iter().all(|&v| v >= lo - tol && v <= hi + tol),
        "knot values {kv:?} outside [{lo}, {hi}]"
    );

    // Tangency at x_k, through the public evaluator.
    for (k, (x, f)) in s.tangent_points().into_iter().enumerate() {
        assert!(x.is_finite() && f.is_finite());
        assert!(x >= d.knots[k] && x <= d.knots[k + 1], "x_{k} = {x}");
        let y = s.eval(x).expect("x_k is inside the domain");
        // x_k is rounded to a double: when the knots sit far from 0 relative
        // to the interval, a few ulps of x are a visible part of h. Allow the
        // change of S over that distance (the unit coefficients below check
        // tangency at the exact local parameter).
        let h = d.knots[k + 1] - d.knots[k];
        let ulp = (f64::EPSILON * x.abs()).max(f64::from_bits(1));
        let rel = 4.0 * ulp / h;
        let slack = tol + m * rel * 16.0;
        assert!(
            (y - f).abs() <= slack,
            "S(x_{k}) = {y}, leg at {f}, tol {slack}"
        );
    }

    // Tangency, C1 and hull through the unit coefficients, divided by the
    // largest value so that the checks themselves cannot overflow.
    let coefs: Vec<[f64; 4]> = (0..n - 1)
        .map(|k| s.unit_coefficients(k).expect("piece exists").map(|v| v / m))
        .collect();
    if coefs.iter().flatten().all(|c| c.is_finite()) {
        let f: Vec<f64> = d.values.iter().map(|v| v / m).collect();
        let (lo, hi) = (lo / m, hi / m);
        for (k, c) in coefs.iter().enumerate() {
            let al = s.alphas()[k];
            let fk = al * f[k] + (1.0 - al) * f[k + 1];
            let rise = f[k + 1] - f[k];
            let t = 1.0 - al;
            assert!(
                (cubic(c, t) - fk).abs() <= REL,
                "piece {k}: S(x_k)/m = {} vs {fk}",
                cubic(c, t)
            );
            assert!(
                (cubic_deriv(c, t) - rise).abs() <= REL,
                "piece {k}: S'(x_k) h/m = {} vs rise {rise}",
                cubic_deriv(c, t)
            );
            if k > 0 {
                let l = &coefs[k - 1];
                let (hl, hr) = (d.knots[k] - d.knots[k - 1], d.knots[k + 1] - d.knots[k]);
                let hmin = hl.min(hr);
                assert!((cubic(l, 1.0) - c[0]).abs() <= REL, "S jumps at tau_{k}");
                let dl = cubic_deriv(l, 1.0) * (hmin / hl);
                let dr = c[1] * (hmin / hr);
                assert!(
                    (dl - dr).abs() <= REL,
                    "S' jumps at tau_{k}: {dl} vs {dr} (scaled to the narrower side)"
                );
            }
            for j in 0..=8 {
                let y = cubic(c, f64::from(j) / 8.0);
                assert!(
                    y >= lo - REL && y <= hi + REL,
                    "piece {k}: {y} outside [{lo}, {hi}] (divided by {m})"
                );
            }
        }
    }

    // Samples through the evaluator: finite and within the range.
    for k in 0..n - 1 {
        let h = d.knots[k + 1] - d.knots[k];
        for j in 0..=4 {
            let x = (d.knots[k] + h * f64::from(j) / 4.0).min(b);
            let y = s.eval(x).expect("inside the domain");
            assert!(
                y.is_finite() && y >= lo - tol && y <= hi + tol,
                "S({x}) = {y}"
            );
            if let Ok(v) = s.deriv(x, 1) {
                assert!(v.is_finite());
            }
        }
    }
    let ((_, rlo), (_, rhi)) = s.range();
    assert!(
        rlo >= lo - tol && rhi <= hi + tol,
        "range [{rlo}, {rhi}] vs [{lo}, {hi}]"
    );
    for e in s.extrema() {
        assert!(e.x.is_finite() && e.y.is_finite() && e.x >= a && e.x <= b);
    }
    for seg in s.segments() {
        assert!(seg.p.iter().flatten().all(|v| !v.is_nan()), "{seg:?}");
    }
}
