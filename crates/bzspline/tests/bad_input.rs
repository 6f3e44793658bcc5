//! Bad input, one test per case: each checks the exact error variant and its
//! fields. Also the inputs at the edge of what is accepted, which must give
//! finite results.

use bzspline::{Curve, Error, Extrapolate, Field, Spline, ALPHA_MAX, ALPHA_MIN};

const X: [f64; 5] = [0.0, 1.0, 2.0, 3.0, 4.0];
const F: [f64; 5] = [1.0, 3.0, 2.0, 5.0, 4.0];

/// The double just below `v` (for positive `v`).
fn below(v: f64) -> f64 {
    f64::from_bits(v.to_bits() - 1)
}

/// The double just above `v` (for positive `v`).
fn above(v: f64) -> f64 {
    f64::from_bits(v.to_bits() + 1)
}

/// Bit-for-bit equality, so that NaN matches NaN and 0 does not match -0.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Asserts `r` is `Error::NonFinite` with these fields.
fn assert_non_finite<T: std::fmt::Debug>(
    r: Result<T, Error>,
    field: Field,
    index: usize,
    value: f64,
) {
    match r {
        Err(Error::NonFinite {
            field: f,
            index: i,
            value: v,
        }) => {
            assert_eq!((f, i), (field, index), "field and index");
            assert!(same(v, value), "value: want {value}, got {v}");
        }
        other => panic!("want NonFinite {{ {field:?}, {index}, {value} }}, got {other:?}"),
    }
}

/// Every non-finite double.
const NON_FINITE: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

#[test]
fn no_knots() {
    assert_eq!(
        Spline::new(&[], &[]).err(),
        Some(Error::TooFewPoints { found: 0, min: 2 })
    );
    assert_eq!(
        Spline::with_alphas(&[], &[], &[]).err(),
        Some(Error::TooFewPoints { found: 0, min: 2 })
    );
}

#[test]
fn one_knot() {
    assert_eq!(
        Spline::new(&[1.0], &[2.0]).err(),
        Some(Error::TooFewPoints { found: 1, min: 2 })
    );
    assert_eq!(
        Spline::with_alpha(&[1.0], &[2.0], 0.5).err(),
        Some(Error::TooFewPoints { found: 1, min: 2 })
    );
}

#[test]
fn values_length_differs() {
    for found in [0, 1, 4, 6] {
        let values = vec![1.0; found];
        assert_eq!(
            Spline::new(&X, &values).err(),
            Some(Error::LengthMismatch {
                field: Field::Value,
                expected: 5,
                found,
            }),
            "{found} values"
        );
    }
}

#[test]
fn alphas_length_differs() {
    for found in [0, 3, 5] {
        let alphas = vec![0.5; found];
        assert_eq!(
            Spline::with_alphas(&X, &F, &alphas).err(),
            Some(Error::LengthMismatch {
                field: Field::Alpha,
                expected: 4,
                found,
            }),
            "{found} alphas"
        );
    }
}

#[test]
fn non_finite_knot() {
    for bad in NON_FINITE {
        for index in [0, 2, 4] {
            let mut x = X;
            x[index] = bad;
            assert_non_finite(Spline::new(&x, &F), Field::Knot, index, bad);
        }
    }
}

#[test]
fn non_finite_value() {
    for bad in NON_FINITE {
        for index in [0, 3, 4] {
            let mut f = F;
            f[index] = bad;
            assert_non_finite(Spline::new(&X, &f), Field::Value, index, bad);
        }
    }
}

#[test]
fn non_finite_alpha() {
    for bad in NON_FINITE {
        for index in [0, 2, 3] {
            let mut a = [0.5; 4];
            a[index] = bad;
            assert_non_finite(Spline::with_alphas(&X, &F, &a), Field::Alpha, index, bad);
        }
        // One alpha for every interval: reported at interval 0.
        assert_non_finite(Spline::with_alpha(&X, &F, bad), Field::Alpha, 0, bad);
    }
}

#[test]
fn equal_knots() {
    let x = [0.0, 1.0, 1.0, 2.0, 3.0];
    assert_eq!(
        Spline::new(&x, &F).err(),
        Some(Error::NotIncreasing {
            index: 2,
            previous: 1.0,
            value: 1.0,
        })
    );
}

#[test]
fn decreasing_knots() {
    let x = [0.0, 1.0, 2.5, 2.0, 3.0];
    assert_eq!(
        Spline::new(&x, &F).err(),
        Some(Error::NotIncreasing {
            index: 3,
            previous: 2.5,
            value: 2.0,
        })
    );
    assert_eq!(
        Spline::new(&[1.0, -1.0], &[0.0, 0.0]).err(),
        Some(Error::NotIncreasing {
            index: 1,
            previous: 1.0,
            value: -1.0,
        })
    );
}

#[test]
fn interval_too_small_relative_to_the_span() {
    assert_eq!(
        Spline::new(&[0.0, 5e-324, 1.0], &[0.0, 1.0, 0.0]).err(),
        Some(Error::IntervalTooSmall {
            interval: 0,
            width: 5e-324,
            span: 1.0,
        })
    );
    // One unit in the last place of 0.5, half a unit in the last place of the
    // span, between interior knots.
    let x = [0.0, 0.5, above(0.5), 1.0];
    assert_eq!(x[2] - x[1], f64::EPSILON / 2.0);
    assert_eq!(
        Spline::new(&x, &[0.0, 1.0, 0.0, 1.0]).err(),
        Some(Error::IntervalTooSmall {
            interval: 1,
            width: f64::EPSILON / 2.0,
            span: 1.0,
        })
    );
}

#[test]
fn interval_of_1e_15_of_the_span_is_accepted_with_finite_results() {
    let x = [0.0, 0.5, 0.5 + 1e-15, 1.0];
    let f = [0.0, 1.0, -1.0, 0.5];
    let s = Spline::new(&x, &f).expect("1e-15 of the span is accepted");
    assert!(
        s.knot_values().iter().all(|v| v.is_finite()),
        "{:?}",
        s.knot_values()
    );
    for seg in s.segments() {
        assert!(seg.p.iter().flatten().all(|v| v.is_finite()), "{seg:?}");
    }
    for k in 0..s.len() {
        let c = s.unit_coefficients(k).expect("piece k exists");
        assert!(c.iter().all(|v| v.is_finite()), "piece {k}: {c:?}");
        let p = s.power_coefficients(k).expect("piece k exists");
        assert!(p.iter().all(|v| v.is_finite()), "piece {k}: {p:?}");
    }
    // Samples across the narrow interval and the wide ones.
    let h = x[2] - x[1];
    let xs: Vec<f64> = (0..=100)
        .map(|i| f64::from(i) / 100.0)
        .chain((0..=10).map(|i| x[1] + h * f64::from(i) / 10.0))
        .collect();
    for &q in &xs {
        for order in 0..=3 {
            let v = s.deriv(q, order).expect("finite derivative");
            assert!(v.is_finite(), "S^({order})({q}) = {v}");
        }
        let v = s.eval(q).expect("inside");
        assert!((-1.0..=1.0).contains(&v), "S({q}) = {v} outside the hull");
    }
    // The tangent point inside the narrow interval is touched.
    let c = s.unit_coefficients(1).expect("piece 1 exists");
    let y = c[0] + 0.5 * (c[1] + 0.5 * (c[2] + 0.5 * c[3]));
    assert!(y.abs() <= 1e-12, "S(x_1) = {y}, want 0");
    assert!(s.integral(0.0, 1.0).expect("finite").is_finite());
}

#[test]
fn first_interval_of_1e_15_of_the_span_is_accepted_with_finite_results() {
    let x = [0.0, 1e-15, 1.0];
    let s = Spline::new(&x, &[0.0, 1.0, 0.0]).expect("1e-15 of the span is accepted");
    let phi = s.knot_values();
    assert!(phi.iter().all(|v| v.is_finite()), "{phi:?}");
    assert!(phi[1] > 0.0 && phi[1] < 1.0, "{phi:?}");
    for i in 0..=1000 {
        let q = if i <= 100 {
            1e-15 * f64::from(i) / 100.0
        } else {
            f64::from(i - 100) / 900.0
        };
        let all = s.eval_all(q).expect("finite");
        assert!(all.iter().all(|v| v.is_finite()), "at {q}: {all:?}");
        assert!(
            (0.0..=1.0).contains(&all[0]),
            "S({q}) = {} outside the hull",
            all[0]
        );
    }
}

#[test]
fn span_overflow() {
    assert_eq!(
        Spline::new(&[-1e308, 1e308], &[0.0, 1.0]).err(),
        Some(Error::SpanOverflow {
            first: -1e308,
            last: 1e308,
        })
    );
    assert_eq!(
        Spline::new(&[-f64::MAX, 0.0, f64::MAX], &[0.0, 1.0, 2.0]).err(),
        Some(Error::SpanOverflow {
            first: -f64::MAX,
            last: f64::MAX,
        })
    );
}

#[test]
fn alpha_just_below_the_lower_bound() {
    let a = below(ALPHA_MIN);
    assert!(a < 1.0 / 3.0);
    assert_eq!(
        Spline::with_alpha(&X, &F, a).err(),
        Some(Error::AlphaOutOfRange {
            interval: 0,
            value: a
        })
    );
    assert_eq!(
        Spline::with_alphas(&X, &F, &[0.5, 0.5, a, 0.5]).err(),
        Some(Error::AlphaOutOfRange {
            interval: 2,
            value: a
        })
    );
}

#[test]
fn alpha_just_above_the_upper_bound() {
    let a = above(ALPHA_MAX);
    assert_eq!(
        Spline::with_alpha(&X, &F, a).err(),
        Some(Error::AlphaOutOfRange {
            interval: 0,
            value: a
        })
    );
    assert_eq!(
        Spline::with_alphas(&X, &F, &[0.5, 0.5, 0.5, a]).err(),
        Some(Error::AlphaOutOfRange {
            interval: 3,
            value: a
        })
    );
}

#[test]
fn alphas_far_outside_the_range() {
    for (a, interval) in [(0.0, 0), (-0.5, 1), (0.2, 2), (0.8, 3), (1.0, 0), (2.0, 1)] {
        let mut alphas = [0.5; 4];
        alphas[interval] = a;
        assert_eq!(
            Spline::with_alphas(&X, &F, &alphas).err(),
            Some(Error::AlphaOutOfRange { interval, value: a })
        );
    }
}

#[test]
fn alpha_decimal_literals_of_the_bounds_are_accepted() {
    let lo: f64 = "0.3333333333333333".parse().expect("a number");
    let hi: f64 = "0.6666666666666667".parse().expect("a number");
    assert_eq!(lo, ALPHA_MIN);
    assert_eq!(hi, ALPHA_MAX);
    assert_eq!(0.3333333333333333, ALPHA_MIN);
    assert_eq!(0.6666666666666667, ALPHA_MAX);
    for a in [lo, hi, 1.0 / 3.0, 2.0 / 3.0] {
        let s = Spline::with_alpha(&X, &F, a).expect("a bound is accepted");
        assert!(s.knot_values().iter().all(|v| v.is_finite()));
        assert_eq!(s.alphas(), &[a; 4]);
    }
    let s = Spline::with_alphas(&X, &F, &[lo, hi, hi, lo]).expect("bounds per interval");
    assert_eq!(s.alphas(), &[lo, hi, hi, lo]);
}

#[test]
fn values_near_1e308_give_finite_results() {
    // Every result here is representable: the curve, its slopes and its Bezier
    // ordinates stay below 1.8e308.
    for f in [
        [1e308, 9e307, 1.2e308, 1.5e308, 1.7e308],
        [-1e308, -9e307, -1.2e308, -1.5e308, -1.7e308],
    ] {
        let s = Spline::new(&X, &f).expect("finite values are accepted");
        let small: Vec<f64> = f.iter().map(|v| v * 1e-300).collect();
        let t = Spline::new(&X, &small).expect("valid");
        for (a, b) in s.knot_values().iter().zip(t.knot_values()) {
            assert!(
                a.is_finite() && (a - b * 1e300).abs() <= 1e-13 * a.abs(),
                "{a} vs {b}e300"
            );
        }
        for (x, y) in s.tangent_points() {
            assert!(x.is_finite() && y.is_finite(), "tangent point ({x}, {y})");
        }
        for k in 0..s.len() {
            let slope = s.leg_slope(k).expect("leg k exists");
            assert!(slope.is_finite(), "leg {k}: {slope}");
            let c = s.unit_coefficients(k).expect("piece k exists");
            assert!(c.iter().all(|v| v.is_finite()), "piece {k}: {c:?}");
        }
        for seg in s.segments() {
            assert!(seg.p.iter().flatten().all(|v| v.is_finite()), "{seg:?}");
        }
        for i in 0..=400 {
            let x = f64::from(i) / 100.0;
            let all = s.eval_all(x).expect("representable");
            assert!(all.iter().all(|v| v.is_finite()), "at {x}: {all:?}");
            let want = t.eval(x).expect("inside") * 1e300;
            assert!(
                (all[0] - want).abs() <= 1e-13 * want.abs(),
                "S({x}) {} vs {want}",
                all[0]
            );
        }
        let ((_, lo), (_, hi)) = s.range();
        assert!(lo.is_finite() && hi.is_finite());
        assert!(s
            .extrema()
            .iter()
            .all(|e| e.x.is_finite() && e.y.is_finite()));
        // The integral, about 5e308, is not representable: a typed error.
        assert_eq!(
            s.integral(0.0, 4.0),
            Err(Error::Overflow {
                what: "the integral"
            })
        );
    }
}

#[test]
fn values_at_the_top_of_the_range_never_give_non_finite_numbers() {
    // Alternating +-1.8e308: the slopes are not representable, the values are.
    let f = [f64::MAX, -f64::MAX, f64::MAX, -f64::MAX, f64::MAX];
    let s = Spline::new(&X, &f).expect("finite values are accepted");
    let hull = f64::MAX;
    for i in 0..=400 {
        let x = f64::from(i) / 100.0;
        let y = s.eval(x).expect("values are representable");
        assert!(y.is_finite() && y.abs() <= hull, "S({x}) = {y}");
        for order in 1..=3 {
            match s.deriv(x, order) {
                Ok(v) => assert!(v.is_finite(), "S^({order})({x}) = {v}"),
                Err(e) => assert_eq!(
                    e,
                    Error::Overflow {
                        what: "the derivative"
                    }
                ),
            }
        }
    }
    for (x, y) in s.tangent_points() {
        assert_eq!(y, 0.0, "tangent point at {x}");
    }
}

#[test]
fn evaluation_outside_the_domain_with_the_default_policy() {
    let s = Spline::new(&X, &F).expect("valid");
    assert_eq!(s.extrapolation(), Extrapolate::Error);
    for x in [
        -1e-300,
        -1.0,
        4.000000000000001,
        5.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        let want = Error::OutOfDomain {
            x,
            min: 0.0,
            max: 4.0,
        };
        assert_eq!(s.eval(x), Err(want.clone()), "eval({x})");
        assert_eq!(s.deriv(x, 1), Err(want.clone()), "deriv({x})");
        assert_eq!(s.eval_all(x), Err(want.clone()), "eval_all({x})");
        let mut out = [0.0; 2];
        assert_eq!(s.eval_many(&[1.0, x], &mut out), Err(want), "eval_many");
    }
    assert_eq!(
        s.integral(-1.0, 2.0),
        Err(Error::OutOfDomain {
            x: -1.0,
            min: 0.0,
            max: 4.0
        })
    );
    assert_eq!(
        s.integral(1.0, 6.0),
        Err(Error::OutOfDomain {
            x: 6.0,
            min: 0.0,
            max: 4.0
        })
    );
    // The ends themselves are inside.
    assert_eq!(s.eval(0.0), Ok(1.0));
    assert_eq!(s.eval(4.0), Ok(4.0));
}

#[test]
fn evaluation_outside_the_domain_with_clamping() {
    let s = Spline::new(&X, &F)
        .expect("valid")
        .with_extrapolation(Extrapolate::Clamp);
    for x in [-1e-300, -1.0, -1e300, f64::NEG_INFINITY] {
        assert_eq!(s.eval(x), Ok(1.0), "eval({x})");
        assert_eq!(s.eval_all(x), Ok([1.0, 0.0, 0.0, 0.0]), "eval_all({x})");
    }
    for x in [4.000000000000001, 5.0, 1e300, f64::INFINITY] {
        assert_eq!(s.eval(x), Ok(4.0), "eval({x})");
        for order in 1..=3 {
            assert_eq!(s.deriv(x, order), Ok(0.0), "deriv({x}, {order})");
        }
    }
    let mut out = [0.0; 3];
    s.eval_many(&[-2.0, 2.0, 9.0], &mut out).expect("clamped");
    assert_eq!(out, [1.0, s.knot_values()[2], 4.0]);
    // Integral: the held value times the length outside, plus the inside part.
    let inside = s.integral(0.0, 4.0).expect("inside");
    let got = s.integral(-2.0, 6.0).expect("clamped");
    let want = 2.0 * 1.0 + inside + 2.0 * 4.0;
    assert!((got - want).abs() <= 1e-13 * want, "want {want}, got {got}");
}

#[test]
fn evaluation_outside_the_domain_with_extension() {
    let s = Spline::new(&X, &F)
        .expect("valid")
        .with_extrapolation(Extrapolate::Extend);
    let first = s.power_coefficients(0).expect("piece 0");
    let last = s.power_coefficients(3).expect("piece 3");
    for (x, c, x0) in [
        (-0.5, first, 0.0),
        (-3.0, first, 0.0),
        (4.5, last, 3.0),
        (7.0, last, 3.0),
    ] {
        let u = x - x0;
        let want = c[0] + u * (c[1] + u * (c[2] + u * c[3]));
        let got = s.eval(x).expect("extended");
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "S({x}): want {want}, got {got}"
        );
        let dwant = c[1] + u * (2.0 * c[2] + 3.0 * u * c[3]);
        let dgot = s.deriv(x, 1).expect("extended");
        assert!(
            (dgot - dwant).abs() <= 1e-12 * dwant.abs().max(1.0),
            "S'({x})"
        );
    }
    // Far away the cubic overflows: a typed error, not an infinity.
    for x in [1e300, -1e300, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(
            s.eval(x),
            Err(Error::Overflow {
                what: "the extrapolated value"
            }),
            "eval({x})"
        );
        assert_eq!(
            s.deriv(x, 1),
            Err(Error::Overflow {
                what: "the derivative"
            }),
            "deriv({x})"
        );
    }
}

#[test]
fn nan_queries() {
    for policy in [Extrapolate::Error, Extrapolate::Clamp, Extrapolate::Extend] {
        let s = Spline::new(&X, &F)
            .expect("valid")
            .with_extrapolation(policy);
        assert_non_finite(s.eval(f64::NAN), Field::Query, 0, f64::NAN);
        for order in 0..=4 {
            assert_non_finite(s.deriv(f64::NAN, order), Field::Query, 0, f64::NAN);
        }
        assert_non_finite(s.eval_all(f64::NAN), Field::Query, 0, f64::NAN);
        let mut out = [0.0; 4];
        assert_non_finite(
            s.eval_many(&[0.5, 1.5, f64::NAN, 2.5], &mut out),
            Field::Query,
            2,
            f64::NAN,
        );
        assert_non_finite(
            s.deriv_many(&[f64::NAN, 1.5, 2.0, 2.5], 1, &mut out),
            Field::Query,
            0,
            f64::NAN,
        );
        assert_non_finite(s.integral(f64::NAN, 1.0), Field::Query, 0, f64::NAN);
        assert_non_finite(s.integral(1.0, f64::NAN), Field::Query, 1, f64::NAN);
        assert_non_finite(
            s.integral(1.0, f64::INFINITY),
            Field::Query,
            1,
            f64::INFINITY,
        );
    }
}

#[test]
fn eval_many_with_wrong_output_length() {
    let s = Spline::new(&X, &F).expect("valid");
    let xs = [0.5, 1.5, 2.5];
    for len in [0, 2, 4] {
        let mut out = vec![0.0; len];
        assert_eq!(
            s.eval_many(&xs, &mut out),
            Err(Error::LengthMismatch {
                field: Field::Query,
                expected: 3,
                found: len,
            }),
            "output of length {len}"
        );
        assert_eq!(
            s.deriv_many(&xs, 2, &mut out),
            Err(Error::LengthMismatch {
                field: Field::Query,
                expected: 3,
                found: len,
            })
        );
    }
    // Empty input and output agree.
    assert_eq!(s.eval_many(&[], &mut []), Ok(()));
}

#[test]
fn output_buffers_are_written_not_judged() {
    // Whatever `out` holds before (NaN from an earlier batch, infinities) is
    // overwritten: only its length is checked.
    let s = Spline::new(&X, &F).expect("valid");
    let xs = [0.5, 1.5, 2.0, 2.5];
    for order in 0..=3 {
        let mut want = [0.0; 4];
        s.deriv_many(&xs, order, &mut want).expect("a clean buffer");
        let mut out = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
        s.deriv_many(&xs, order, &mut out)
            .expect("a buffer holding NaN");
        assert_eq!(out, want, "order {order}");
    }
    // The same for a curve's batch and the antiderivative's.
    let c = Curve::open(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).expect("valid");
    let ts = [0.0, 0.5, 1.5, 2.5];
    let mut want = [0.0; 8];
    c.deriv_many(&ts, 0, &mut want).expect("a clean buffer");
    let mut out = [f64::NAN; 8];
    c.deriv_many(&ts, 0, &mut out)
        .expect("a buffer holding NaN");
    assert_eq!(out, want);
    let f = s.antiderivative();
    let mut want = [0.0; 4];
    f.eval_many(&xs, &mut want).expect("a clean buffer");
    let mut out = [f64::NAN, f64::INFINITY, f64::NAN, f64::NAN];
    f.eval_many(&xs, &mut out).expect("a buffer holding NaN");
    assert_eq!(out, want);
}

#[test]
fn a_fault_anywhere_in_a_large_input_is_found_and_named() {
    // From 131,073 knots the one-pass check runs in two halves side by side
    // (with the `rayon` feature): a fault at either end of either half, or
    // at the last knot, is found, and a rebuild into a spline of that size
    // refuses it too, leaving the spline as it was.
    let n = 300_001;
    let half = (n - 1) / 2 / 16 * 16;
    let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let f: Vec<f64> = x.iter().map(|v| (v * 0.01).sin()).collect();
    let a = vec![0.5; n - 1];
    let mut s = Spline::new(&x, &f).unwrap();
    let before = s.eval(1234.5).unwrap();
    for at in [1, half - 1, half, half + 1, n - 2, n - 1] {
        let mut bad_x = x.clone();
        bad_x[at] = bad_x[at - 1];
        let want = Error::NotIncreasing {
            index: at,
            previous: x[at - 1],
            value: x[at - 1],
        };
        assert_eq!(
            Spline::new(&bad_x, &f).err(),
            Some(want.clone()),
            "knot {at}"
        );
        assert_eq!(s.rebuild(&bad_x, &f, Default::default()).err(), Some(want));
        let mut bad_f = f.clone();
        bad_f[at] = f64::NAN;
        assert_non_finite(Spline::new(&x, &bad_f), Field::Value, at, f64::NAN);
        let leg = at.min(n - 2);
        let mut bad_a = a.clone();
        bad_a[leg] = above(ALPHA_MAX);
        assert!(
            matches!(
                Spline::with_alphas(&x, &f, &bad_a),
                Err(Error::AlphaOutOfRange { interval, .. }) if interval == leg
            ),
            "alpha {leg}"
        );
    }
    assert!(same(s.eval(1234.5).unwrap(), before));
}
