//! An independent check of the tridiagonal solver: the spline written on each
//! interval as a plain cubic in `x - tau_k` with four unknown coefficients per
//! piece, the defining conditions imposed directly as one dense linear system of
//! `4 (N - 1)` equations, solved by Gaussian elimination with partial pivoting.
//! Its knot values must agree with [`Spline::knot_values`].
//!
//! The same system with the paper's misprinted tangent values (weights swapped)
//! shows why the misprint matters: that curve is not tangent to the polygon.

mod common;

use bzspline::{Spline, ALPHA_MAX, ALPHA_MIN};
use common::{ex2_x, gauss_solve, max_abs, Rng, EX1_F, EX1_X, EX2_F, SAMPLE_ALPHAS};

/// The pieces `S_k(x) = sum_j c[k][j] (x - tau_k)^j` of the C1 cubic that takes
/// the value `tangent_value[k]` and the slope of leg `k` at
/// `x_k = tau_{k+1} - alpha_k h_k`, and the end values `F_0`, `F_{N-1}`.
fn dense_pieces(
    knots: &[f64],
    values: &[f64],
    alphas: &[f64],
    tangent_value: &[f64],
) -> Vec<[f64; 4]> {
    let n = knots.len();
    let pieces = n - 1;
    let m = 4 * pieces;
    let mut a = vec![0.0; m * m];
    let mut b = vec![0.0; m];
    let mut row = 0;
    let put = |row: usize, piece: usize, j: usize, v: f64, a: &mut Vec<f64>| {
        a[row * m + 4 * piece + j] += v;
    };
    for k in 0..pieces {
        let h = knots[k + 1] - knots[k];
        let x = knots[k + 1] - alphas[k] * h;
        let u = x - knots[k];
        // S_k(x_k) = f_k.
        for j in 0..4 {
            put(row, k, j, u.powi(j as i32), &mut a);
        }
        b[row] = tangent_value[k];
        row += 1;
        // S_k'(x_k) = s_k.
        for j in 1..4 {
            put(row, k, j, j as f64 * u.powi(j as i32 - 1), &mut a);
        }
        b[row] = (values[k + 1] - values[k]) / h;
        row += 1;
    }
    for k in 1..n - 1 {
        let h = knots[k] - knots[k - 1];
        // S_{k-1}(tau_k) = S_k(tau_k).
        for j in 0..4 {
            put(row, k - 1, j, h.powi(j as i32), &mut a);
        }
        put(row, k, 0, -1.0, &mut a);
        row += 1;
        // S_{k-1}'(tau_k) = S_k'(tau_k).
        for j in 1..4 {
            put(row, k - 1, j, j as f64 * h.powi(j as i32 - 1), &mut a);
        }
        put(row, k, 1, -1.0, &mut a);
        row += 1;
    }
    // S(tau_0) = F_0 and S(tau_{N-1}) = F_{N-1}.
    put(row, 0, 0, 1.0, &mut a);
    b[row] = values[0];
    row += 1;
    let h = knots[n - 1] - knots[n - 2];
    for j in 0..4 {
        put(row, pieces - 1, j, h.powi(j as i32), &mut a);
    }
    b[row] = values[n - 1];
    row += 1;
    assert_eq!(row, m, "one equation per unknown");
    let c = gauss_solve(a, b).expect("the system of the theorem's range is regular");
    c.chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// `f_k = alpha_k F_k + (1 - alpha_k) F_{k+1}`: the point of leg `k` at `x_k`.
fn leg_points(values: &[f64], alphas: &[f64]) -> Vec<f64> {
    alphas
        .iter()
        .enumerate()
        .map(|(k, &a)| a * values[k] + (1.0 - a) * values[k + 1])
        .collect()
}

/// The paper's printed `f_k`, with the weights swapped.
fn misprinted_points(values: &[f64], alphas: &[f64]) -> Vec<f64> {
    alphas
        .iter()
        .enumerate()
        .map(|(k, &a)| (1.0 - a) * values[k] + a * values[k + 1])
        .collect()
}

/// Knot values of the dense solution: `S_k(tau_k)` and the last piece's end.
fn dense_knot_values(knots: &[f64], pieces: &[[f64; 4]]) -> Vec<f64> {
    let n = knots.len();
    let mut phi: Vec<f64> = pieces.iter().map(|c| c[0]).collect();
    let h = knots[n - 1] - knots[n - 2];
    let c = &pieces[n - 2];
    phi.push(c[0] + h * (c[1] + h * (c[2] + h * c[3])));
    phi
}

/// Compares the library's knot values and power coefficients with the dense
/// solution.
fn compare(label: &str, knots: &[f64], values: &[f64], alphas: &[f64]) {
    let s = Spline::with_alphas(knots, values, alphas)
        .unwrap_or_else(|e| panic!("{label}: building failed: {e}"));
    let dense = dense_pieces(knots, values, alphas, &leg_points(values, alphas));
    let want = dense_knot_values(knots, &dense);
    let got = s.knot_values();
    let tol = 1e-12 * max_abs(values);
    assert_eq!(got.len(), want.len(), "{label}: number of knot values");
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(
            (g - w).abs() <= tol,
            "{label}: phi_{k} want {w}, got {g} (diff {:e})",
            (g - w).abs()
        );
    }
    for (k, c) in dense.iter().enumerate() {
        let p = s.power_coefficients(k).expect("piece k exists");
        let h = knots[k + 1] - knots[k];
        for j in 0..4 {
            // Coefficient j carries the unit h^-j.
            let ctol = 1e-11 * max_abs(values) / h.powi(j as i32);
            assert!(
                (p[j] - c[j]).abs() <= ctol,
                "{label}: piece {k} coefficient {j} want {}, got {}",
                c[j],
                p[j]
            );
        }
    }
}

#[test]
fn gauss_solver_solves_a_system_that_needs_pivoting() {
    // The first pivot is zero without row exchanges.
    let a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 0.0];
    let x = gauss_solve(a, vec![5.0, 4.0, 4.0]).expect("regular");
    for (g, w) in x.iter().zip([1.0, 2.0, 1.0]) {
        assert!((g - w).abs() < 1e-14, "want {w}, got {g}");
    }
    assert!(gauss_solve(vec![1.0, 2.0, 2.0, 4.0], vec![1.0, 2.0]).is_none());
}

#[test]
fn example_1_agrees_with_the_dense_system() {
    for a in SAMPLE_ALPHAS {
        compare(&format!("example 1, alpha {a}"), &EX1_X, &EX1_F, &[a; 10]);
    }
}

#[test]
fn example_2_agrees_with_the_dense_system() {
    let x = ex2_x();
    for a in SAMPLE_ALPHAS {
        compare(&format!("example 2, alpha {a}"), &x, &EX2_F, &[a; 10]);
    }
}

/// Knot values of Example 1 at alpha = 1/2 and of Example 2 at alpha = 1/2, as
/// the dense system gives them (rounded to 15 significant digits).
const EX1_PHI: [f64; 11] = [
    1.0,
    2.78095373877789,
    2.80953738777886,
    1.31442013901071,
    2.33466400232822,
    6.03221988427144,
    1.98753484038615,
    1.84312851959003,
    8.44375035551414,
    2.59437503555141,
    1.5,
];
const EX2_PHI: [f64; 11] = [
    0.0,
    0.279339987059615,
    0.393399870596150,
    0.454658718901883,
    0.487126766422683,
    0.497425353324945,
    0.487126766826765,
    0.454658718942704,
    0.393399870600273,
    0.279339987060027,
    0.0,
];

#[test]
fn example_knot_values_at_alpha_one_half() {
    let cases: [(Vec<f64>, &[f64; 11], &[f64; 11]); 2] = [
        (EX1_X.to_vec(), &EX1_F, &EX1_PHI),
        (ex2_x(), &EX2_F, &EX2_PHI),
    ];
    for (x, f, phi) in cases {
        let s = Spline::new(&x, f).expect("valid data");
        let dense = dense_pieces(&x, f, &[0.5; 10], &leg_points(f, &[0.5; 10]));
        let got = s.knot_values();
        let from_dense = dense_knot_values(&x, &dense);
        for k in 0..11 {
            let tol = 1e-14 * max_abs(f) * 10.0;
            assert!(
                (got[k] - phi[k]).abs() <= tol,
                "phi_{k} want {}, got {}",
                phi[k],
                got[k]
            );
            assert!(
                (from_dense[k] - phi[k]).abs() <= tol,
                "dense phi_{k} {}",
                from_dense[k]
            );
        }
        // The curve does not reach the polygon's corners: each interior knot
        // value lies between the corner and the mean of its neighbours.
        for k in 1..10 {
            let mean = 0.5 * (f[k - 1] + f[k + 1]);
            let (lo, hi) = (f[k].min(mean), f[k].max(mean));
            assert!(
                got[k] >= lo && got[k] <= hi,
                "phi_{k} = {} outside [{lo}, {hi}]",
                got[k]
            );
        }
    }
}

#[test]
fn random_data_with_per_interval_alphas_agrees_with_the_dense_system() {
    let mut rng = Rng::new(0x5eed_0101);
    for case in 0..300 {
        let n = rng.int(2, 16);
        let knots = rng.grid(n, 2.0);
        let values = rng.values(n);
        let alphas = rng.alphas(n - 1);
        compare(
            &format!("case {case}: knots {knots:?} values {values:?} alphas {alphas:?}"),
            &knots,
            &values,
            &alphas,
        );
    }
}

#[test]
fn misprinted_tangent_values_break_tangency_away_from_one_half() {
    let knots = EX1_X;
    let values = EX1_F;
    for a in [ALPHA_MIN, 0.4, 0.6, ALPHA_MAX] {
        let alphas = [a; 10];
        let ours = leg_points(&values, &alphas);
        let printed = misprinted_points(&values, &alphas);
        let s = Spline::with_alphas(&knots, &values, &alphas).expect("valid data");
        let dense = dense_pieces(&knots, &values, &alphas, &printed);
        for (k, (x, fk)) in s.tangent_points().into_iter().enumerate() {
            let rise = values[k + 1] - values[k];
            let h = knots[k + 1] - knots[k];
            // Our f_k is the point of leg k at x_k, and the spline touches it there.
            let leg = values[k] + rise / h * (x - knots[k]);
            assert!(
                (fk - ours[k]).abs() < 1e-14 && (fk - leg).abs() < 1e-13,
                "f_{k}"
            );
            let c = s.unit_coefficients(k).expect("piece k exists");
            let t = 1.0 - a;
            let y = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
            let dy = c[1] + t * (2.0 * c[2] + 3.0 * t * c[3]);
            assert!(
                (y - leg).abs() < 1e-12,
                "alpha {a}: S(x_{k}) {y}, leg {leg}"
            );
            assert!(
                (dy - rise).abs() < 1e-12,
                "alpha {a}: h S'(x_{k}) {dy}, {rise}"
            );
            // The printed f_k is off the leg by |1 - 2 alpha| |F_{k+1} - F_k|.
            let gap = (printed[k] - leg).abs();
            let want_gap = (1.0 - 2.0 * a).abs() * rise.abs();
            assert!(
                (gap - want_gap).abs() < 1e-12,
                "alpha {a}, leg {k}: gap {gap}"
            );
            // The curve built on the printed values has the leg's slope at x_k
            // but passes beside the leg: parallel to it, not touching it.
            let p = &dense[k];
            let u = x - knots[k];
            let ym = p[0] + u * (p[1] + u * (p[2] + u * p[3]));
            let dym = p[1] + u * (2.0 * p[2] + 3.0 * u * p[3]);
            assert!((dym - rise / h).abs() < 1e-10, "printed: slope at x_{k}");
            if rise != 0.0 {
                assert!(
                    (ym - leg).abs() > 0.05 * rise.abs(),
                    "alpha {a}: the printed form touches leg {k}: S(x) {ym}, leg {leg}"
                );
                assert!((y - ym).abs() > 0.05 * rise.abs(), "alpha {a}, leg {k}");
            }
        }
    }
    // At alpha = 1/2 the two forms coincide, and so do the curves.
    let half = [0.5; 10];
    assert_eq!(
        leg_points(&values, &half),
        misprinted_points(&values, &half)
    );
    let dense = dense_pieces(&knots, &values, &half, &misprinted_points(&values, &half));
    let s = Spline::new(&knots, &values).expect("valid data");
    for (g, w) in s
        .knot_values()
        .iter()
        .zip(dense_knot_values(&knots, &dense))
    {
        assert!((g - w).abs() < 1e-12, "want {w}, got {g}");
    }
}
