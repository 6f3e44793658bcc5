//! The conditions that define the spline, checked piece by piece from each
//! piece's own coefficients (never through `eval`, which picks one piece at a
//! knot):
//!
//! - tangency: `S(x_k) = f_k = alpha_k F_k + (1 - alpha_k) F_{k+1}` and
//!   `S'(x_k) = s_k = (F_{k+1} - F_k) / h_k` at `x_k = tau_{k+1} - alpha_k h_k`;
//! - value and first derivative agree from both sides at every interior knot;
//! - `S(tau_0) = F_0`, `S(tau_{N-1}) = F_{N-1}`.
//!
//! Tolerances are relative: values to `1e-12 max |F|`, slopes on interval `k` to
//! `1e-12 max |F| / h_k` (the size of a slope that the data can produce there),
//! and slopes at a knot to `1e-12 max |F| / min(h_{k-1}, h_k)`.

mod common;

use bzspline::{Spline, ALPHA_MAX, ALPHA_MIN};
use common::{cubic, cubic_deriv, ex2_x, max_abs, Rng, EX1_F, EX1_X, EX2_F, SAMPLE_ALPHAS};

const REL: f64 = 1e-12;

/// Builds the spline and checks every defining condition; the message names the
/// data set on failure.
fn check(label: &str, knots: &[f64], values: &[f64], alphas: &[f64]) {
    let s = match Spline::with_alphas(knots, values, alphas) {
        Ok(s) => s,
        Err(e) => panic!("{label}: building failed: {e}"),
    };
    let n = knots.len();
    assert_eq!(s.len(), n - 1, "{label}: number of pieces");
    let m = max_abs(values);
    let tol = REL * m;
    let h: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
    let unit: Vec<[f64; 4]> = (0..n - 1)
        .map(|k| s.unit_coefficients(k).expect("piece k exists"))
        .collect();
    let power: Vec<[f64; 4]> = (0..n - 1)
        .map(|k| s.power_coefficients(k).expect("piece k exists"))
        .collect();
    assert!(s.unit_coefficients(n - 1).is_none(), "{label}: extra piece");
    // The power form divides by h^3: check it only where that keeps full
    // precision (no subnormal or infinite coefficients).
    let moderate = |v: f64| (1e-90..=1e90).contains(&v);
    let power_form_exact = moderate(m) && h.iter().all(|&w| moderate(w));

    let tangents = s.tangent_points();
    assert_eq!(tangents.len(), n - 1, "{label}: tangent points");
    for k in 0..n - 1 {
        let a = alphas[k];
        // The tangent point in the piece's local variable: x_k - tau_k = (1 - a) h_k.
        let t = 1.0 - a;
        let f = a * values[k] + (1.0 - a) * values[k + 1];
        let y = cubic(&unit[k], t);
        assert!(
            (y - f).abs() <= tol,
            "{label}: S(x_{k}) want {f}, got {y} (diff {:e}, tol {tol:e})",
            (y - f).abs()
        );
        // h_k S'(x_k) = F_{k+1} - F_k.
        let rise = values[k + 1] - values[k];
        let dy = cubic_deriv(&unit[k], t);
        assert!(
            (dy - rise).abs() <= tol,
            "{label}: h_{k} S'(x_{k}) want {rise}, got {dy} (diff {:e}, tol {tol:e})",
            (dy - rise).abs()
        );
        // The same slope from the power form, in x.
        let u = t * h[k];
        let p = &power[k];
        let dp = p[1] + u * (2.0 * p[2] + 3.0 * u * p[3]);
        let slope = rise / h[k];
        assert!(
            !power_form_exact || (dp - slope).abs() <= 4.0 * tol / h[k],
            "{label}: S'(x_{k}) from the power form want {slope}, got {dp}"
        );
        // What tangent_points reports.
        let (x, fk) = tangents[k];
        let want_x = knots[k + 1] - a * h[k];
        assert!(
            // Subnormal knots: x_k is on a grid of spacing 5e-324.
            (x - want_x).abs() <= 4.0 * f64::EPSILON * knots[k + 1].abs().max(h[k]) + 5e-324,
            "{label}: x_{k} want {want_x}, got {x}"
        );
        assert!(
            x > knots[k] && x < knots[k + 1],
            "{label}: x_{k} = {x} outside"
        );
        assert!(
            (fk - f).abs() <= 4.0 * f64::EPSILON * m,
            "{label}: f_{k} want {f}, got {fk}"
        );
    }

    let phis = s.knot_values();
    for k in 1..n - 1 {
        let (l, r) = (&unit[k - 1], &unit[k]);
        let left = cubic(l, 1.0);
        let right = r[0];
        assert!(
            (left - right).abs() <= tol,
            "{label}: S(tau_{k}) left {left}, right {right}"
        );
        // Both one-sided slopes times the narrower width (which keeps them
        // finite even where the slope itself is not representable).
        let hmin = h[k - 1].min(h[k]);
        let slope_tol = tol / hmin;
        let dl = cubic_deriv(l, 1.0) * (hmin / h[k - 1]);
        let dr = r[1] * (hmin / h[k]);
        assert!(
            (dl - dr).abs() <= tol,
            "{label}: h_min S'(tau_{k}) left {dl}, right {dr} (diff {:e}, tol {tol:e})",
            (dl - dr).abs()
        );
        if power_form_exact {
            // The same from the power coefficients.
            let (pl, pr) = (&power[k - 1], &power[k]);
            let hl = h[k - 1];
            let vl = pl[0] + hl * (pl[1] + hl * (pl[2] + hl * pl[3]));
            assert!(
                (vl - pr[0]).abs() <= tol,
                "{label}: power form S(tau_{k}) left {vl}, right {}",
                pr[0]
            );
            let pdl = pl[1] + hl * (2.0 * pl[2] + 3.0 * hl * pl[3]);
            assert!(
                (pdl - pr[1]).abs() <= 4.0 * slope_tol,
                "{label}: power form S'(tau_{k}) left {pdl}, right {}",
                pr[1]
            );
        }
        // The knot value reported is the one both pieces reach.
        let phi = phis[k];
        assert!(
            (phi - right).abs() <= tol,
            "{label}: phi_{k} {phi}, piece {right}"
        );
    }

    // The ends: from the end pieces' own coefficients and through eval.
    assert!(
        (unit[0][0] - values[0]).abs() <= tol,
        "{label}: S(tau_0) want {}, got {}",
        values[0],
        unit[0][0]
    );
    let end = cubic(&unit[n - 2], 1.0);
    assert!(
        (end - values[n - 1]).abs() <= tol,
        "{label}: S(tau_N-1) want {}, got {end}",
        values[n - 1]
    );
    assert_eq!(
        s.eval(knots[0]).ok(),
        Some(values[0]),
        "{label}: eval at tau_0"
    );
    assert_eq!(
        s.eval(knots[n - 1]).ok(),
        Some(values[n - 1]),
        "{label}: eval at tau_N-1"
    );
    let phi = s.knot_values();
    assert_eq!(phi[0], values[0], "{label}: phi_0");
    assert_eq!(phi[n - 1], values[n - 1], "{label}: phi_N-1");
}

#[test]
fn example_1_with_uniform_alphas() {
    for a in SAMPLE_ALPHAS {
        check(&format!("example 1, alpha {a}"), &EX1_X, &EX1_F, &[a; 10]);
    }
}

#[test]
fn example_2_with_uniform_alphas() {
    let x = ex2_x();
    for a in SAMPLE_ALPHAS {
        check(&format!("example 2, alpha {a}"), &x, &EX2_F, &[a; 10]);
    }
}

#[test]
fn examples_with_random_per_interval_alphas() {
    let mut rng = Rng::new(0x5eed_0001);
    let x2 = ex2_x();
    for case in 0..200 {
        let alphas = rng.alphas(10);
        check(
            &format!("example 1, case {case}, {alphas:?}"),
            &EX1_X,
            &EX1_F,
            &alphas,
        );
        check(
            &format!("example 2, case {case}, {alphas:?}"),
            &x2,
            &EX2_F,
            &alphas,
        );
    }
}

#[test]
fn examples_with_alternating_extreme_alphas() {
    let alt: Vec<f64> = (0..10)
        .map(|k| if k % 2 == 0 { ALPHA_MIN } else { ALPHA_MAX })
        .collect();
    let rev: Vec<f64> = alt
        .iter()
        .map(|a| {
            if *a == ALPHA_MIN {
                ALPHA_MAX
            } else {
                ALPHA_MIN
            }
        })
        .collect();
    check("example 1, alternating", &EX1_X, &EX1_F, &alt);
    check("example 1, alternating reversed", &EX1_X, &EX1_F, &rev);
    check("example 2, alternating", &ex2_x(), &EX2_F, &alt);
}

#[test]
fn random_grids_with_widths_varying_by_1e6() {
    let mut rng = Rng::new(0x5eed_0002);
    for case in 0..2000 {
        let n = rng.int(2, 40);
        let knots = rng.grid(n, 6.0);
        let values = rng.values(n);
        let alphas = rng.alphas(n - 1);
        check(
            &format!("random case {case}: knots {knots:?} values {values:?} alphas {alphas:?}"),
            &knots,
            &values,
            &alphas,
        );
    }
}

#[test]
fn systems_large_enough_to_be_cut_into_chunks() {
    // From 65,537 points on, the system is solved in overlapping chunks; the
    // conditions hold on every piece, the chunks' seams included, for grids
    // over 10 decades and the extreme alphas, where rows damp least.
    let mut rng = Rng::new(0x5eed_0006);
    for (case, n) in [70_001, 140_001].into_iter().enumerate() {
        let knots = rng.grid(n, 10.0);
        let values = rng.values(n);
        let random = rng.alphas(n - 1);
        let alternating: Vec<f64> = (0..n - 1)
            .map(|k| if k % 2 == 0 { ALPHA_MAX } else { ALPHA_MIN })
            .collect();
        for (what, alphas) in [("random", random), ("alternating extreme", alternating)] {
            check(
                &format!("chunked case {case}, {n} knots, {what} alphas"),
                &knots,
                &values,
                &alphas,
            );
        }
    }
}

#[test]
fn grids_alternating_narrow_and_wide_intervals() {
    // Neighbouring widths differ by exactly 1e6, in both orders.
    let mut rng = Rng::new(0x5eed_0003);
    for case in 0..200 {
        let n = rng.int(3, 30);
        let first_narrow = case % 2 == 0;
        let mut knots = vec![rng.uniform(-1.0, 1.0)];
        for i in 1..n {
            let narrow = (i % 2 == 1) == first_narrow;
            let w = if narrow { 1e-3 } else { 1e3 };
            knots.push(knots[i - 1] + w);
        }
        let values = rng.values(n);
        let alphas = rng.alphas(n - 1);
        check(
            &format!("alternating case {case}: values {values:?} alphas {alphas:?}"),
            &knots,
            &values,
            &alphas,
        );
    }
}

#[test]
fn two_and_three_knots() {
    let mut rng = Rng::new(0x5eed_0004);
    for case in 0..500 {
        let n = 2 + case % 2;
        let knots = rng.grid(n, 6.0);
        let values = rng.values(n);
        let alphas = rng.alphas(n - 1);
        check(&format!("small case {case}"), &knots, &values, &alphas);
    }
}

#[test]
fn grids_at_the_ends_of_the_double_range() {
    // The same shapes on knots spanning f64::MAX, to subnormal widths, and
    // shifted far from 0; values likewise scaled.
    let mut rng = Rng::new(0x5eed_0005);
    let mut checked = [0usize; 4];
    for case in 0..300 {
        let n = rng.int(2, 20);
        let base = rng.grid(n, 4.0);
        let span = base[n - 1] - base[0];
        let values = rng.values(n);
        let alphas = rng.alphas(n - 1);
        let huge: Vec<f64> = base
            .iter()
            // A span of f64::MAX: sums of neighbouring widths can round above it.
            .map(|x| (x - base[0]) / span * f64::MAX - f64::MAX / 2.0)
            .collect();
        let tiny: Vec<f64> = base.iter().map(|x| (x - base[0]) / span * 1e-300).collect();
        let subnormal: Vec<f64> = base
            .iter()
            .map(|x| (x - base[0]) / span * 1e-305 * 1e-5)
            .collect();
        let shifted: Vec<f64> = base.iter().map(|x| x + 1e6).collect();
        for (g, (name, knots)) in [
            ("huge", &huge),
            ("tiny", &tiny),
            ("subnormal", &subnormal),
            ("shifted", &shifted),
        ]
        .into_iter()
        .enumerate()
        {
            // Rounding can merge knots of the scaled grids: such a grid is refused
            // with a typed error, which other tests cover.
            if Spline::with_alphas(knots, &values, &alphas).is_err() {
                continue;
            }
            for scale in [1.0, 1e300, 1e-300] {
                let v: Vec<f64> = values.iter().map(|f| f * scale).collect();
                check(&format!("{name} case {case}, scale {scale}: knots {knots:?} values {v:?} alphas {alphas:?}"), knots, &v, &alphas);
            }
            checked[g] += 1;
        }
    }
    // Most grids survive the scaling: the test is not vacuous.
    for (g, c) in checked.iter().enumerate() {
        assert!(*c >= 250, "grid kind {g}: only {c} of 300 checked");
    }
}
