//! The interpolating variant (`docs/method.md` §11): splines and curves
//! through their points. Checked against the defining conditions on many
//! random inputs, and against the system `(T + K) G = T P` assembled densely
//! from the paper's unscaled rows and solved by Gaussian elimination.

mod common;

use bzspline::{Alphas, Curve, CurveBuilder, Param, Spline};
use common::{gauss_solve, max_abs, Rng, EX1_F, EX1_X};

/// `(T + K) G = T P` with `G_0 = P_0`, `G_{N-1} = P_{N-1}`: `T` the rows of
/// (16) (`-A`, `B1 + B2`, `-C`, widths in the coefficients), `K` the slope
/// jumps (`1/h_{k-1}`, `-(1/h_{k-1} + 1/h_k)`, `1/h_k`), the unknowns the
/// interior control values; dense Gaussian elimination with partial pivoting
/// (`common::gauss_solve`).
fn dense_controls(x: &[f64], p: &[f64], alphas: &[f64]) -> Vec<f64> {
    let n = x.len();
    let m = n - 2;
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    // Full rows over all N values, then the known ends moved to the right.
    let mut a = vec![vec![0.0; n]; m];
    let mut t = vec![vec![0.0; n]; m];
    for i in 0..m {
        let k = i + 1;
        let (hl, hr) = (h[k - 1], h[k]);
        let (al, ar) = (alphas[k - 1], alphas[k]);
        let big_a = al * al / ((1.0 - al) * (1.0 - al) * hl);
        let b1 = (2.0 / al + 1.0) / hl;
        let b2 = (2.0 / (1.0 - ar) + 1.0) / hr;
        let c = (1.0 - ar) * (1.0 - ar) / (ar * ar * hr);
        t[i][k - 1] = -big_a;
        t[i][k] = b1 + b2;
        t[i][k + 1] = -c;
        a[i][k - 1] = -big_a + 1.0 / hl;
        a[i][k] = b1 + b2 - 1.0 / hl - 1.0 / hr;
        a[i][k + 1] = -c + 1.0 / hr;
    }
    // The deviations at the ends are zero: T acts on interior values only.
    let tp = |i: usize| -> f64 { (1..n - 1).map(|j| t[i][j] * p[j]).sum() };
    let mut mat = vec![0.0; m * m];
    let mut rhs = vec![0.0; m];
    for i in 0..m {
        // T (P - G) = K G, i.e. (T + K) G = T P on the interior, with the
        // end values of G (= P) through K only.
        let k_end = (a[i][0] - t[i][0]) * p[0] + (a[i][n - 1] - t[i][n - 1]) * p[n - 1];
        rhs[i] = tp(i) - k_end;
        for j in 0..m {
            mat[i * m + j] = a[i][j + 1];
        }
    }
    let g = gauss_solve(mat, rhs).expect("the system is non-singular");
    let mut out = vec![p[0]];
    out.extend(g);
    out.push(p[n - 1]);
    out
}

#[test]
fn control_values_agree_with_the_dense_system() {
    let mut rng = Rng::new(18);
    for _ in 0..60 {
        let n = rng.int(3, 24);
        let x = rng.grid(n, 2.0);
        let p = rng.values(n);
        let a = rng.alphas(n - 1);
        let s = Spline::through(&x, &p, Alphas::PerInterval(&a)).unwrap();
        let want = dense_controls(&x, &p, &a);
        let scale = max_abs(&want).max(1.0);
        for (k, (g, w)) in s.values().iter().zip(&want).enumerate() {
            assert!(
                (g - w).abs() <= 1e-10 * scale,
                "n = {n}, G_{k}: dense {w}, solver {g}"
            );
        }
    }
}

#[test]
fn splines_pass_through_their_points_and_touch_their_control_legs() {
    let mut rng = Rng::new(7);
    for _ in 0..200 {
        let n = rng.int(2, 40);
        let x = rng.grid(n, 3.0);
        let p = rng.values(n);
        let a = rng.alphas(n - 1);
        let s = Spline::through(&x, &p, Alphas::PerInterval(&a)).unwrap();
        let scale = max_abs(&p).max(f64::MIN_POSITIVE);
        for (k, v) in s.knot_values().iter().enumerate() {
            assert!(
                (v - p[k]).abs() <= 1e-13 * scale,
                "knot {k}: {v} against {}",
                p[k]
            );
        }
        // Tangency to the legs of the solved polygon G at x_k (§1).
        let g = s.values();
        let gs = max_abs(g).max(scale);
        for k in 0..n - 1 {
            let h = x[k + 1] - x[k];
            let xk = x[k + 1] - a[k] * h;
            let leg = a[k] * g[k] + (1.0 - a[k]) * g[k + 1];
            assert!((s.eval(xk).unwrap() - leg).abs() <= 1e-12 * gs, "leg {k}");
            let slope = (g[k + 1] - g[k]) / h;
            let d = s.deriv(xk, 1).unwrap();
            assert!(
                (d - slope).abs() <= 1e-10 * (gs / h).max(slope.abs()),
                "slope at leg {k}: {d} against {slope}"
            );
        }
        // C1: the Bezier control points around each interior knot are
        // collinear with the knot and spaced by the widths (§3).
        for k in 1..n - 1 {
            let (l, r) = (s.segment(k - 1).unwrap(), s.segment(k).unwrap());
            let (hl, hr) = (x[k] - x[k - 1], x[k + 1] - x[k]);
            let left = (l.p[3][1] - l.p[2][1]) / (hl / 3.0);
            let right = (r.p[1][1] - r.p[0][1]) / (hr / 3.0);
            assert!(
                (left - right).abs() <= 1e-9 * (gs / hl.min(hr)),
                "knot {k}: slopes {left} and {right}"
            );
        }
    }
}

#[test]
fn large_splines_solved_in_chunks_pass_through_their_points() {
    // From 65,537 points the system is solved in overlapping chunks (§16),
    // side by side from 131,073 with the `rayon` feature: the knot values of
    // the spline built on the solved controls are the data, and the
    // controls' legs are touched, on uneven grids with random alphas, only
    // the extremes, and one alpha of 1/3 and of 2/3 (the weakest rows).
    let mut rng = Rng::new(31);
    for (case, n) in [(0, 70_001), (1, 140_003), (2, 70_001), (3, 140_003)] {
        let x = rng.grid(n, 3.0);
        let p = rng.values(n);
        let mut a = rng.alphas(n - 1);
        if case == 1 {
            for v in &mut a {
                *v = if *v < 0.5 { 1.0 / 3.0 } else { 2.0 / 3.0 };
            }
        }
        let alphas = match case {
            2 => Alphas::Uniform(1.0 / 3.0),
            3 => Alphas::Uniform(2.0 / 3.0),
            _ => Alphas::PerInterval(&a),
        };
        let s = Spline::through(&x, &p, alphas).unwrap();
        let scale = max_abs(&p);
        for (k, v) in s.knot_values().iter().enumerate() {
            assert!(
                (v - p[k]).abs() <= 1e-12 * scale,
                "case {case}, knot {k}: {v} against {}",
                p[k]
            );
        }
        let g = s.values();
        let gs = max_abs(g).max(scale);
        for k in (0..n - 1).step_by(97) {
            let ak = match case {
                2 => 1.0 / 3.0,
                3 => 2.0 / 3.0,
                _ => a[k],
            };
            let h = x[k + 1] - x[k];
            let leg = ak * g[k] + (1.0 - ak) * g[k + 1];
            let at = x[k + 1] - ak * h;
            let v = s.eval(at).unwrap();
            // The point itself is rounded to a few units of |x|.
            let slope = s.deriv(at, 1).unwrap().abs();
            let tol = 1e-12 * gs + slope * 4.0 * f64::EPSILON * at.abs();
            assert!(
                (v - leg).abs() <= tol,
                "case {case}, leg {k}: {v} against {leg}"
            );
        }
    }
}

#[test]
fn long_open_curves_pass_through_their_points() {
    // An open curve's system is solved coordinate by coordinate in chunks
    // from 65,537 points: a random walk in the plane and in space, on every
    // parametrisation, through every point.
    let mut rng = Rng::new(41);
    for (case, param) in [Param::Uniform, Param::Chordal, Param::Centripetal]
        .into_iter()
        .enumerate()
    {
        let (dim, n) = (2 + case % 2, 70_001);
        let mut at = vec![0.0; dim];
        let pts: Vec<f64> = (0..n)
            .flat_map(|_| {
                for v in &mut at {
                    *v += rng.uniform(-1.0, 1.0);
                }
                at.clone()
            })
            .collect();
        let a = rng.alphas(n - 1);
        let c = CurveBuilder::new(&pts, dim)
            .param(param)
            .alphas(&a)
            .through(true)
            .build()
            .unwrap();
        let scale = max_abs(&pts);
        for (k, q) in c.knot_points().iter().enumerate() {
            for j in 0..dim {
                let want = pts[k * dim + j];
                assert!(
                    (q[j] - want).abs() <= 1e-12 * scale,
                    "case {case}, point {k}: {q:?} against {want}"
                );
            }
        }
    }
}

#[test]
fn at_one_half_the_system_is_diagonal() {
    // §11: at alpha = 1/2 the off-diagonals of T + K vanish and the diagonal
    // is 2/(h_{k-1}/2) + 2/(h_k/2): at unit widths 8, so each deviation is an
    // eighth of the jump of the data's slope, and G = P - d.
    let s = Spline::through(&EX1_X, &EX1_F, Alphas::Uniform(0.5)).unwrap();
    let want = dense_controls(&EX1_X, &EX1_F, &[0.5; 10]);
    for (g, w) in s.values().iter().zip(&want) {
        assert!((g - w).abs() < 1e-12, "{g} {w}");
    }
    for k in 1..10 {
        let jump = (EX1_F[k + 1] - EX1_F[k]) - (EX1_F[k] - EX1_F[k - 1]);
        let d = EX1_F[k] - s.values()[k];
        assert!(
            (d - jump / 8.0).abs() < 1e-13,
            "knot {k}: d = {d}, jump / 8 = {}",
            jump / 8.0
        );
    }
}

#[test]
fn example_1_swings_little_beyond_its_data() {
    // The figures: within about [0.27, 10.003] at alpha = 1/2.
    let s = Spline::through(&EX1_X, &EX1_F, Alphas::Uniform(0.5)).unwrap();
    let ((_, lo), (_, hi)) = s.range();
    assert!((lo - 0.27).abs() < 0.01, "min {lo}");
    assert!(hi > 10.0 && hi < 10.01, "max {hi}");
}

#[test]
fn curves_pass_through_their_points_open_and_closed() {
    let mut rng = Rng::new(99);
    for case in 0..120 {
        let dim = 2 + case % 2;
        let closed = case % 3 == 0;
        let n = rng.int(if closed { 3 } else { 2 }, 30);
        let pts: Vec<f64> = (0..n * dim).map(|_| rng.uniform(-10.0, 10.0)).collect();
        let param = [Param::Uniform, Param::Chordal, Param::Centripetal][case % 3].clone();
        let legs = if closed { n } else { n - 1 };
        let a = rng.alphas(legs);
        let c = CurveBuilder::new(&pts, dim)
            .closed(closed)
            .param(param.clone())
            .alphas(&a)
            .through(true)
            .build()
            .unwrap();
        // The parameters are those of the data.
        let data = CurveBuilder::new(&pts, dim)
            .closed(closed)
            .param(param)
            .alphas(&a)
            .build()
            .unwrap();
        assert_eq!(c.knots(), data.knots());
        for (k, q) in c.knot_points().iter().take(n).enumerate() {
            for j in 0..dim {
                let want = pts[k * dim + j];
                assert!(
                    (q[j] - want).abs() <= 1e-12 * 10.0,
                    "case {case}, point {k}: {q:?}"
                );
            }
        }
        // It is the method's curve on its control points at those
        // parameters, to the bit.
        let on_controls = CurveBuilder::new(c.points(), dim)
            .closed(closed)
            .param(Param::Given(c.knots().to_vec()))
            .alphas(c.alphas())
            .build()
            .unwrap();
        assert_eq!(
            bits(&c.knot_points().concat()),
            bits(&on_controls.knot_points().concat()),
            "case {case}"
        );
        for w in c.knots().windows(2) {
            let t = 0.5 * (w[0] + w[1]);
            let (a, b) = (c.eval(t).unwrap(), on_controls.eval(t).unwrap());
            assert_eq!(bits(&a), bits(&b), "case {case} at {t}");
        }
        // It touches the legs of its control polygon at x_k.
        for (k, (t, p)) in c.tangent_points().iter().enumerate() {
            let e = c.eval(*t).unwrap();
            for j in 0..dim {
                assert!((e[j] - p[j]).abs() < 1e-11, "case {case}, leg {k}");
            }
        }
    }
}

#[test]
fn the_variant_refuses_what_the_method_refuses() {
    let bad_knots = Spline::through(&[0.0, 0.0, 1.0], &[1.0, 2.0, 3.0], Alphas::default());
    let want = Spline::new(&[0.0, 0.0, 1.0], &[1.0, 2.0, 3.0]);
    assert_eq!(bad_knots.unwrap_err(), want.unwrap_err());
    let bad_alpha = Spline::through(&[0.0, 1.0, 2.0], &[1.0, 2.0, 3.0], Alphas::Uniform(0.2));
    assert_eq!(
        bad_alpha.unwrap_err(),
        Spline::with_alpha(&[0.0, 1.0, 2.0], &[1.0, 2.0, 3.0], 0.2).unwrap_err()
    );
    let nan = Spline::through(&[0.0, 1.0, 2.0], &[1.0, f64::NAN, 3.0], Alphas::default());
    // (NaN is not equal to itself: compare the messages.)
    assert_eq!(
        nan.unwrap_err().to_string(),
        Spline::new(&[0.0, 1.0, 2.0], &[1.0, f64::NAN, 3.0])
            .unwrap_err()
            .to_string()
    );
    let repeated = CurveBuilder::new(&[0.0, 0.0, 0.0, 0.0, 1.0, 1.0], 2)
        .param(Param::Chordal)
        .through(true)
        .build();
    let want = CurveBuilder::new(&[0.0, 0.0, 0.0, 0.0, 1.0, 1.0], 2)
        .param(Param::Chordal)
        .build();
    assert_eq!(repeated.unwrap_err(), want.unwrap_err());
    // Values near the top of the range: scaled by a power of two while
    // solved. At 1e308 the controls (G_2 = 1.375e308) stay finite and the knots
    // are the data; at f64::MAX that control is beyond the range: refused.
    let big = [1e308, -1e308, 1e308, 0.0];
    let s = Spline::through(&[0.0, 1.0, 2.0, 3.0], &big, Alphas::default()).unwrap();
    for (v, w) in s.knot_values().iter().zip(&big) {
        assert!((v - w).abs() <= 1e-13 * 1e308, "{v} {w}");
    }
    let top = [f64::MAX, -f64::MAX, f64::MAX, 0.0];
    assert!(matches!(
        Spline::through(&[0.0, 1.0, 2.0, 3.0], &top, Alphas::default()),
        Err(bzspline::Error::Overflow { .. })
    ));
    // A closed square through its corners.
    let sq = Curve::builder_from(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        .closed(true)
        .through(true)
        .build()
        .unwrap();
    assert!(
        (sq.knot_points()[2][0] - 1.0).abs() < 1e-15
            && (sq.knot_points()[2][1] - 1.0).abs() < 1e-15
    );
}

/// The bits of each number, so that equal means equal to the bit.
fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}
