//! Property tests at the edges of what is accepted (proptest, fixed case
//! counts): each alpha bound is accepted and the double just outside it is
//! refused, for splines and for open and closed curves, on random data; curves
//! whose parameters spread over twelve orders of magnitude keep tangency, C1,
//! their end points and the box of their control points; the end values of a
//! spline are exact at any magnitude; and a curve near `f64::MAX` found by
//! fuzzing.

use bzspline::Bounds;
use bzspline::ParamCurve;
use bzspline::{Curve, Error, Param, Spline, ALPHA_MAX, ALPHA_MIN};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

const CASES: u32 = 128;

fn config() -> ProptestConfig {
    ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/bounds.txt",
        ))),
        ..ProptestConfig::with_cases(CASES)
    }
}

/// The next double below a positive `x`.
fn below(x: f64) -> f64 {
    f64::from_bits(x.to_bits() - 1)
}

/// The next double above a positive `x`.
fn above(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

fn alpha() -> impl Strategy<Value = f64> {
    prop_oneof![Just(ALPHA_MIN), Just(ALPHA_MAX), ALPHA_MIN..=ALPHA_MAX]
}

/// Increasing knots with widths `10^e`, `e` in `[-decades/2, decades/2]`.
fn knots(n: usize, decades: f64) -> impl Strategy<Value = Vec<f64>> {
    (
        -1.0..=1.0f64,
        vec(
            (-decades / 2.0..=decades / 2.0).prop_map(|e| 10f64.powf(e)),
            n - 1,
        ),
    )
        .prop_map(|(start, widths)| {
            let mut x = start;
            let mut k = vec![x];
            for w in widths {
                x += w;
                k.push(x);
            }
            k
        })
}

prop_compose! {
    /// Knots, values and alphas of a spline with 2..=16 knots.
    fn spline_data()(n in 2usize..=16)(
        knots in knots(n, 3.0),
        values in vec(-100.0..=100.0f64, n),
        alphas in vec(alpha(), n - 1),
        at in 0..n - 1,
    ) -> (Vec<f64>, Vec<f64>, Vec<f64>, usize) {
        (knots, values, alphas, at)
    }
}

prop_compose! {
    /// Distinct-enough points of a curve (dimension 1 to 3), its alphas and a leg.
    fn curve_data()(dim in 1usize..=3, n in 3usize..=10, closed in any::<bool>())(
        pts in vec(-10.0..=10.0f64, n * dim),
        alphas in vec(alpha(), n),
        at in 0..if closed { n } else { n - 1 },
        dim in Just(dim),
        closed in Just(closed),
    ) -> (Vec<f64>, usize, bool, Vec<f64>, usize) {
        (pts, dim, closed, alphas, at)
    }
}

fn curve(pts: &[f64], dim: usize, closed: bool, alphas: &[f64]) -> Result<Curve, Error> {
    let n = pts.len() / dim;
    let legs = if closed { n } else { n - 1 };
    Curve::builder(pts, dim)
        .closed(closed)
        .alphas(&alphas[..legs])
        .build()
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn spline_accepts_each_alpha_bound_and_refuses_the_next_double(
        (knots, values, mut alphas, at) in spline_data(),
    ) {
        for bound in [ALPHA_MIN, ALPHA_MAX] {
            alphas[at] = bound;
            prop_assert!(Spline::with_alphas(&knots, &values, &alphas).is_ok(), "{bound} refused");
            prop_assert!(Spline::with_alpha(&knots, &values, bound).is_ok());
        }
        for bad in [below(ALPHA_MIN), above(ALPHA_MAX)] {
            alphas[at] = bad;
            prop_assert_eq!(
                Spline::with_alphas(&knots, &values, &alphas).err(),
                Some(Error::AlphaOutOfRange { interval: at, value: bad })
            );
            let uniform = Spline::with_alpha(&knots, &values, bad).err();
            prop_assert!(
                matches!(uniform, Some(Error::AlphaOutOfRange { value, .. }) if value == bad),
                "{uniform:?}"
            );
        }
    }

    #[test]
    fn curve_accepts_each_alpha_bound_and_refuses_the_next_double(
        (pts, dim, closed, mut alphas, at) in curve_data(),
    ) {
        alphas[at] = ALPHA_MIN;
        let first = curve(&pts, dim, closed, &alphas);
        // Random points are (rarely) too close to each other; the alphas are
        // not what is tested then.
        let Ok(_) = first else { return Ok(()) };
        alphas[at] = ALPHA_MAX;
        prop_assert!(curve(&pts, dim, closed, &alphas).is_ok(), "ALPHA_MAX refused");
        for bad in [below(ALPHA_MIN), above(ALPHA_MAX)] {
            alphas[at] = bad;
            let e = curve(&pts, dim, closed, &alphas).err();
            prop_assert!(
                matches!(e, Some(Error::AlphaOutOfRange { interval, value }) if interval == at && value == bad),
                "leg {at}, alpha {bad}: {e:?}"
            );
            let uniform = Curve::builder(&pts, dim).closed(closed).alpha(bad).build().err();
            prop_assert!(
                matches!(uniform, Some(Error::AlphaOutOfRange { value, .. }) if value == bad),
                "{uniform:?}"
            );
        }
    }

    #[test]
    fn curve_with_parameters_over_twelve_orders_of_magnitude(
        (pts, dim, closed, alphas, _at) in curve_data(),
        params in knots(11, 12.0),
    ) {
        let n = pts.len() / dim;
        let given = params[..n + usize::from(closed)].to_vec();
        let legs = if closed { n } else { n - 1 };
        let c = Curve::builder(&pts, dim)
            .closed(closed)
            .param(Param::Given(given.clone()))
            .alphas(&alphas[..legs])
            .build();
        let c = match c {
            Ok(c) => c,
            Err(Error::RepeatedPoint { .. } | Error::RepeatedClosingPoint { .. }) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("refused: {e}"))),
        };
        prop_assert_eq!(c.knots(), &given[..]);
        let tol = 1e-9 * 10.0;
        // End points (open) or a closed loop.
        let (lo, hi) = c.domain();
        if closed {
            let (a, b) = (c.eval(lo)?, c.eval(hi)?);
            for j in 0..dim {
                prop_assert!((a[j] - b[j]).abs() <= tol, "loop does not close: {a:?} vs {b:?}");
            }
        } else {
            prop_assert_eq!(c.eval(lo)?, pts[..dim].to_vec());
            prop_assert_eq!(c.eval(hi)?, pts[(n - 1) * dim..].to_vec());
        }
        let h = |k: usize| given[k + 1] - given[k];
        // Tangency: the curve passes through the leg's point at x_k.
        for (k, (x, tp)) in c.tangent_points().into_iter().enumerate() {
            let a = alphas[k];
            let (p, q) = (&pts[k * dim..(k + 1) * dim], (k + 1) % n);
            let q = &pts[q * dim..(q + 1) * dim];
            let at = c.eval(x)?;
            // x_k is rounded to a double: on a narrow interval far from 0 a few
            // ulps of x are a visible part of h, and C moves by its slope times them.
            let ulps = 4.0 * f64::EPSILON * x.abs() / h(k);
            for j in 0..dim {
                let want = a * p[j] + (1.0 - a) * q[j];
                let slack = tol + (q[j] - p[j]).abs() * ulps;
                prop_assert!((tp[j] - want).abs() <= tol, "leg {k}: tangent point {tp:?}");
                prop_assert!((at[j] - want).abs() <= slack, "leg {k}: C(x_k) = {at:?}, want {want}");
            }
        }
        // C1 at every interior knot (and the closing one), relative to the
        // narrower of the two intervals; every control point in the box.
        let segs: Vec<Vec<f64>> = (0..c.len()).map(|k| c.segment_points(k).expect("segment")).collect();
        let last = if closed { c.len() } else { c.len() - 1 };
        for k in 1..=last {
            let (l, r) = (&segs[k - 1], &segs[k % c.len()]);
            let (hl, hr) = (h(k - 1), h(k % c.len()));
            let hmin = hl.min(hr);
            for j in 0..dim {
                prop_assert_eq!(l[3 * dim + j], r[j], "C0 at knot {}", k);
                let dl = (l[3 * dim + j] - l[2 * dim + j]) * (hmin / hl);
                let dr = (r[dim + j] - r[j]) * (hmin / hr);
                prop_assert!((dl - dr).abs() <= tol, "C1 at knot {k}, coordinate {j}: {dl} vs {dr}");
            }
        }
        let bb = c.bbox();
        for j in 0..dim {
            let cmin = pts.iter().skip(j).step_by(dim).copied().fold(f64::INFINITY, f64::min);
            let cmax = pts.iter().skip(j).step_by(dim).copied().fold(f64::NEG_INFINITY, f64::max);
            prop_assert!(bb.min[j] >= cmin - tol && bb.max[j] <= cmax + tol, "box {bb:?}");
        }
    }

    #[test]
    fn spline_end_values_are_exact_at_any_magnitude(
        n in 2usize..=8,
        e_values in vec(-320.0..=308.0f64, 8),
        signs in vec(any::<bool>(), 8),
        mantissas in vec(1.0..=1.79f64, 8),
    ) {
        let knots: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let values: Vec<f64> = (0..n)
            .map(|i| {
                let v = mantissas[i] * 10f64.powf(e_values[i]);
                if signs[i] { -v } else { v }
            })
            .collect();
        prop_assume!(values.iter().all(|v| v.is_finite()));
        let s = Spline::new(&knots, &values)?;
        prop_assert_eq!(s.eval(0.0)?, values[0]);
        prop_assert_eq!(s.eval((n - 1) as f64)?, values[n - 1]);
        let kv = s.knot_values();
        prop_assert_eq!(kv[0], values[0]);
        prop_assert_eq!(kv[n - 1], values[n - 1]);
        prop_assert!(kv.iter().all(|v| v.is_finite()));
    }
}

/// Found by the curve_build fuzz target: a 1-D curve through 0, -f64::MAX and
/// f64::MAX is accepted and finite everywhere, but the inner Bezier control
/// points of its middle segment are beyond the range of a double, so the SVG
/// export refuses with an overflow instead of printing `inf`.
#[test]
fn curve_near_f64_max_is_finite_but_its_bezier_form_overflows() {
    let pts = [3.082_885_742_187_499e-146, 0.0, -f64::MAX, f64::MAX];
    // Uniform parameters: the chord from 3e-146 to 0 is below the smallest
    // double in units of f64::MAX, so chordal and centripetal ones refuse.
    let c = Curve::builder(&pts, 1)
        .param(Param::Uniform)
        .alpha(ALPHA_MIN)
        .build()
        .expect("finite, distinct points");
    let (lo, hi) = c.domain();
    for i in 0..=64 {
        let s = lo + (hi - lo) * f64::from(i) / 64.0;
        let p = c.eval(s).expect("inside the domain");
        assert!(p[0].is_finite(), "C({s}) = {p:?}");
    }
    let inner_overflow = (0..c.len())
        .filter_map(|k| c.segment_points(k))
        .any(|s| s.iter().any(|v| !v.is_finite()));
    assert!(
        inner_overflow,
        "expected an inner control point beyond f64::MAX"
    );
    let planar = Curve::builder(
        &pts.iter()
            .enumerate()
            .flat_map(|(i, &y)| [i as f64, y])
            .collect::<Vec<_>>(),
        2,
    )
    .param(Param::Uniform)
    .alpha(ALPHA_MIN)
    .build()
    .expect("finite, distinct points");
    assert!(
        matches!(planar.to_svg_path(), Err(Error::Overflow { .. })),
        "{:?}",
        planar.to_svg_path()
    );
}

/// As for splines: a tiny first point beside f64::MAX underflowed in scaling,
/// so an open curve started at 0 instead of at its first control point.
#[test]
fn open_curve_end_points_are_exact_beside_f64_max() {
    let f0 = 1.568_603_515_624_999_3e-203;
    let pts = [f0, -f0, 0.0, f64::MAX, 1.0, -f0];
    let c = Curve::builder(&pts, 2).build().expect("distinct points");
    let (lo, hi) = c.domain();
    assert_eq!(c.eval(lo).expect("start"), vec![f0, -f0]);
    assert_eq!(c.eval(hi).expect("end"), vec![1.0, -f0]);
    let first = c.segment_points(0).expect("segment 0");
    assert_eq!(&first[..2], &[f0, -f0]);
    let last = c.segment_points(c.len() - 1).expect("last segment");
    assert_eq!(&last[6..], &[1.0, -f0]);
}
