//! Properties of the spline over random data (proptest, bounded strategies,
//! fixed case counts): convex hull, Bezier export, derivative, invariance under
//! linear functions and scaling, exact straight lines, extreme knot spacing.

use bzspline::ParamCurve;
use bzspline::{Extrapolate, Spline, ALPHA_MAX, ALPHA_MIN};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

const CASES: u32 = 256;

/// One data set: knots, values and per-interval alphas of matching lengths.
#[derive(Clone, Debug)]
struct Data {
    knots: Vec<f64>,
    values: Vec<f64>,
    alphas: Vec<f64>,
}

impl Data {
    fn spline(&self) -> Spline {
        match Spline::with_alphas(&self.knots, &self.values, &self.alphas) {
            Ok(s) => s,
            Err(e) => panic!("valid data refused: {e}: {self:?}"),
        }
    }

    fn width(&self, k: usize) -> f64 {
        self.knots[k + 1] - self.knots[k]
    }

    /// The narrowest of intervals `k - 1`, `k`, `k + 1`: a sample of piece `k`
    /// at `t = 1` (or rounded across a knot) is answered by a neighbour.
    fn near_width(&self, k: usize) -> f64 {
        let lo = k.saturating_sub(1);
        let hi = (k + 1).min(self.knots.len() - 2);
        (lo..=hi)
            .map(|i| self.width(i))
            .fold(f64::INFINITY, f64::min)
    }

    fn max_abs(&self) -> f64 {
        self.values
            .iter()
            .fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()))
    }

    /// Sample points `tau_k + t h_k` of piece `k`, `t = j / per_piece`.
    fn samples(&self, k: usize, per_piece: u32) -> impl Iterator<Item = (f64, f64)> + '_ {
        (0..=per_piece).map(move |j| {
            let t = f64::from(j) / f64::from(per_piece);
            (t, self.knots[k] + t * self.width(k))
        })
    }
}

/// A shape parameter: often exactly a bound, otherwise anywhere between.
fn alpha() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(ALPHA_MIN),
        1 => Just(ALPHA_MAX),
        1 => Just(0.5),
        4 => ALPHA_MIN..=ALPHA_MAX,
    ]
}

/// `count` widths `10^e`, `e` uniform in `[-decades/2, decades/2]`.
fn widths(count: usize, decades: f64) -> impl Strategy<Value = Vec<f64>> {
    vec(
        (-decades / 2.0..=decades / 2.0).prop_map(|e| 10f64.powf(e)),
        count,
    )
}

/// Knots from a start in `[-offset, offset]` and widths spread over `decades`.
fn knots(n: usize, decades: f64, offset: f64) -> impl Strategy<Value = Vec<f64>> {
    (-offset..=offset, widths(n - 1, decades)).prop_map(|(start, w)| {
        let mut x = start;
        let mut k = vec![x];
        for w in w {
            x += w;
            k.push(x);
        }
        k
    })
}

/// `n` values of a common magnitude `10^[-3, 3]`.
fn values(n: usize) -> impl Strategy<Value = Vec<f64>> {
    (-3.0..=3.0f64, vec(-1.0..=1.0f64, n))
        .prop_map(|(e, v)| v.into_iter().map(|x| x * 10f64.powf(e)).collect())
}

prop_compose! {
    /// A data set with 2..=`max_n` knots.
    fn data(max_n: usize, decades: f64, offset: f64)(n in 2..=max_n)(
        knots in knots(n, decades, offset),
        values in values(n),
        alphas in vec(alpha(), n - 1),
    ) -> Data {
        Data { knots, values, alphas }
    }
}

/// Moderate grids: widths within three decades, knots within 100 of 0.
fn moderate() -> impl Strategy<Value = Data> {
    data(24, 3.0, 100.0)
}

fn cubic(c: &[f64; 4], t: f64) -> f64 {
    c[0] + t * (c[1] + t * (c[2] + t * c[3]))
}

fn cubic_deriv(c: &[f64; 4], t: f64) -> f64 {
    c[1] + t * (2.0 * c[2] + 3.0 * t * c[3])
}

/// Checks that every sample of `s` lies in `[min F, max F]` up to rounding.
fn assert_in_hull(d: &Data, s: &Spline) -> Result<(), TestCaseError> {
    let lo = d.values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = d.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let tol = 1e-12 * d.max_abs();
    for k in 0..s.len() {
        let c = s.unit_coefficients(k).expect("piece k exists");
        for (t, x) in d.samples(k, 64) {
            let y = s.eval(x.min(d.knots[d.knots.len() - 1]))?;
            prop_assert!(
                y >= lo - tol && y <= hi + tol,
                "S({x}) = {y} outside [{lo}, {hi}]"
            );
            let y = cubic(&c, t);
            prop_assert!(
                y >= lo - tol && y <= hi + tol,
                "piece {k} at t = {t}: {y} outside [{lo}, {hi}]"
            );
        }
    }
    Ok(())
}

/// Fixed case count; failures are kept in `proptest-regressions/` of this crate
/// (the default location is not found from a workspace member's `tests/`).
fn config() -> ProptestConfig {
    ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties.txt",
        ))),
        ..ProptestConfig::with_cases(CASES)
    }
}

/// Any double of any magnitude, with the edges of the range often.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..=1e3f64,
        (-1e3..=1e3f64).prop_map(|x| x * 1e-300),
        (-300.0..=308.0f64, any::<bool>()).prop_map(|(e, neg)| {
            let v = 10f64.powf(e);
            if neg {
                -v
            } else {
                v
            }
        }),
        Just(0.0),
        Just(f64::MAX),
        Just(-f64::MAX),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
    ]
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn curve_stays_within_the_range_of_the_values(d in moderate()) {
        let s = d.spline();
        assert_in_hull(&d, &s)?;
        let ((_, lo), (_, hi)) = s.range();
        let tol = 1e-12 * d.max_abs();
        let min = d.values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = d.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        prop_assert!(lo >= min - tol && hi <= max + tol, "range [{lo}, {hi}] vs [{min}, {max}]");
    }

    #[test]
    fn bezier_segments_are_the_pieces(d in moderate()) {
        let s = d.spline();
        let segs = s.segments();
        prop_assert_eq!(segs.len(), s.len());
        prop_assert!(s.segment(s.len()).is_none());
        let m = d.max_abs();
        for (k, listed) in segs.iter().enumerate() {
            let seg = s.segment(k).expect("piece k exists");
            prop_assert_eq!(&seg, listed);
            let h = d.width(k);
            prop_assert_eq!(seg.p[0][0], d.knots[k]);
            prop_assert_eq!(seg.p[3][0], d.knots[k + 1]);
            for (t, x) in d.samples(k, 16) {
                let [bx, by] = seg.eval(t);
                let xtol = 4.0 * f64::EPSILON * (d.knots[k].abs() + h);
                prop_assert!((bx - x).abs() <= xtol, "piece {k}, t = {t}: x {bx} vs {x}");
                let y = s.eval(x.min(d.knots[d.knots.len() - 1]))?;
                // The rounding of x moves y by about |S'| eps |x|, |S'| <~ max|F| / h.
                let tol = 1e-12 * m * (1.0 + x.abs() / d.near_width(k));
                prop_assert!(
                    (by - y).abs() <= tol,
                    "piece {k}, t = {t}: Bezier {by}, eval {y}"
                );
            }
        }
    }

    #[test]
    fn derivative_matches_a_central_difference(d in data(16, 2.0, 10.0), t in 0.05..=0.95f64) {
        let s = d.spline();
        let m = d.max_abs();
        for k in 0..s.len() {
            let h = d.width(k);
            let x = d.knots[k] + t * h;
            let delta = 1e-4 * h;
            let fd = (s.eval(x + delta)? - s.eval(x - delta)?) / (2.0 * delta);
            let dy = s.deriv(x, 1)?;
            prop_assert!(
                (fd - dy).abs() <= 2e-6 * m / h,
                "piece {k} at {x}: S' = {dy}, central difference {fd}"
            );
            // The same slope from the unit coefficients.
            let c = s.unit_coefficients(k).expect("piece k exists");
            let du = cubic_deriv(&c, (x - d.knots[k]) / h) / h;
            prop_assert!((du - dy).abs() <= 1e-12 * m / h, "piece {k}: {du} vs {dy}");
        }
    }

    #[test]
    fn adding_a_linear_function_adds_it_to_the_curve(
        d in moderate(),
        a in -1e3..=1e3f64,
        b in -1e2..=1e2f64,
    ) {
        let s = d.spline();
        let shifted: Vec<f64> = d.knots.iter().zip(&d.values).map(|(x, f)| f + a + b * x).collect();
        let t = Spline::with_alphas(&d.knots, &shifted, &d.alphas)?;
        let big = d.max_abs() + a.abs() + b.abs() * d.knots.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tol = 1e-12 * big;
        for (k, (p, q)) in s.knot_values().iter().zip(t.knot_values()).enumerate() {
            let want = p + a + b * d.knots[k];
            prop_assert!((q - want).abs() <= tol, "phi_{k}: want {want}, got {q}");
        }
        for k in 0..s.len() {
            for (_, x) in d.samples(k, 8) {
                let x = x.min(d.knots[d.knots.len() - 1]);
                let want = s.eval(x)? + a + b * x;
                let got = t.eval(x)?;
                prop_assert!((got - want).abs() <= tol, "S({x}): want {want}, got {got}");
            }
        }
    }

    #[test]
    fn scaling_knots_and_values_scales_the_curve(
        d in moderate(),
        log_c in -3.0..=3.0f64,
        log_d in -3.0..=3.0f64,
        negative in any::<bool>(),
    ) {
        let c = 10f64.powf(log_c);
        let dv = if negative { -1.0 } else { 1.0 } * 10f64.powf(log_d);
        let s = d.spline();
        let knots: Vec<f64> = d.knots.iter().map(|x| c * x).collect();
        let values: Vec<f64> = d.values.iter().map(|f| dv * f).collect();
        let t = Spline::with_alphas(&knots, &values, &d.alphas)?;
        let m = d.max_abs() * dv.abs();
        for (k, (p, q)) in s.knot_values().iter().zip(t.knot_values()).enumerate() {
            prop_assert!((q - dv * p).abs() <= 1e-12 * m, "phi_{k}: want {}, got {q}", dv * p);
        }
        for k in 0..s.len() {
            let h = d.near_width(k);
            for (_, x) in d.samples(k, 8) {
                let x = x.min(d.knots[d.knots.len() - 1]);
                let cx = (c * x).clamp(knots[0], knots[knots.len() - 1]);
                let want = dv * s.eval(x)?;
                let got = t.eval(cx)?;
                let tol = 1e-12 * m * (1.0 + x.abs() / h);
                prop_assert!((got - want).abs() <= tol, "S_new({cx}): want {want}, got {got}");
                let want = dv / c * s.deriv(x, 1)?;
                let got = t.deriv(cx, 1)?;
                prop_assert!(
                    (got - want).abs() <= tol / (c * h),
                    "S_new'({cx}): want {want}, got {got}"
                );
            }
        }
    }

    #[test]
    fn straight_polygon_is_reproduced(
        d in moderate(),
        a in -1e3..=1e3f64,
        b in -1e2..=1e2f64,
    ) {
        let line: Vec<f64> = d.knots.iter().map(|x| a + b * x).collect();
        let s = Spline::with_alphas(&d.knots, &line, &d.alphas)?;
        let m = line.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
        for (k, (p, f)) in s.knot_values().iter().zip(&line).enumerate() {
            prop_assert!((p - f).abs() <= 1e-13 * m, "phi_{k}: want {f}, got {p}");
        }
        for k in 0..s.len() {
            let h = d.near_width(k);
            for (_, x) in d.samples(k, 8) {
                let x = x.min(d.knots[d.knots.len() - 1]);
                let y = s.eval(x)?;
                prop_assert!((y - (a + b * x)).abs() <= 1e-12 * m, "S({x}) = {y}");
                let dy = s.deriv(x, 1)?;
                prop_assert!((dy - b).abs() <= 1e-12 * m / h, "S'({x}) = {dy}, want {b}");
                let d2 = s.deriv(x, 2)?;
                prop_assert!(d2.abs() <= 1e-11 * m / (h * h), "S''({x}) = {d2}");
            }
        }
    }

    #[test]
    fn knot_spacings_over_twelve_orders_of_magnitude(d in data(30, 12.0, 1.0)) {
        let s = d.spline();
        let m = d.max_abs();
        let tol = 1e-12 * m;
        for v in s.knot_values() {
            prop_assert!(v.is_finite());
        }
        for k in 0..s.len() {
            let c = s.unit_coefficients(k).expect("piece k exists");
            prop_assert!(c.iter().all(|v| v.is_finite()), "piece {k}: {c:?}");
            let a = d.alphas[k];
            let f = a * d.values[k] + (1.0 - a) * d.values[k + 1];
            let rise = d.values[k + 1] - d.values[k];
            prop_assert!((cubic(&c, 1.0 - a) - f).abs() <= tol, "S(x_{k})");
            prop_assert!((cubic_deriv(&c, 1.0 - a) - rise).abs() <= tol, "S'(x_{k})");
            if k > 0 {
                let l = s.unit_coefficients(k - 1).expect("piece k-1 exists");
                let (hl, hr) = (d.width(k - 1), d.width(k));
                prop_assert!((cubic(&l, 1.0) - c[0]).abs() <= tol, "S(tau_{k})");
                let (dl, dr) = (cubic_deriv(&l, 1.0) / hl, c[1] / hr);
                prop_assert!(
                    (dl - dr).abs() <= tol / hl.min(hr),
                    "S'(tau_{k}): left {dl}, right {dr}"
                );
            }
            for (_, x) in d.samples(k, 4) {
                let x = x.min(d.knots[d.knots.len() - 1]);
                prop_assert!(s.eval(x)?.is_finite());
                prop_assert!(s.deriv(x, 1)?.is_finite());
            }
        }
        assert_in_hull(&d, &s)?;
    }

    #[test]
    fn any_accepted_data_gives_finite_results_or_typed_errors(
        knots in vec(wild(), 2..8),
        values in vec(wild(), 8),
        alphas in vec(alpha(), 7),
        queries in vec(wild(), 0..12),
    ) {
        let mut knots = knots;
        knots.sort_by(f64::total_cmp);
        knots.dedup();
        let n = knots.len();
        let values = &values[..n];
        let alphas = &alphas[..n - 1];
        // Refusals are covered elsewhere; here only what is accepted.
        let Ok(s) = Spline::with_alphas(&knots, values, alphas) else {
            return Ok(());
        };
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let tol = 1e-12 * lo.abs().max(hi.abs());
        prop_assert!(s.knot_values().iter().all(|v| v.is_finite()));
        prop_assert!(s.tangent_points().iter().all(|(x, y)| x.is_finite() && y.is_finite()));
        prop_assert!(s.extrema().iter().all(|e| e.x.is_finite() && e.y.is_finite()));
        let ((_, rlo), (_, rhi)) = s.range();
        prop_assert!(rlo >= lo - tol && rhi <= hi + tol, "range [{rlo}, {rhi}] vs [{lo}, {hi}]");
        let (a, b) = s.domain();
        for i in 0..=64 {
            let x = (a + (b - a) * f64::from(i) / 64.0).clamp(a, b);
            let y = s.eval(x)?;
            prop_assert!(y >= lo - tol && y <= hi + tol, "S({x}) = {y} outside [{lo}, {hi}]");
        }
        for policy in [Extrapolate::Error, Extrapolate::Clamp, Extrapolate::Extend] {
            let s = s.clone().with_extrapolation(policy);
            for &q in &queries {
                for order in 0..4 {
                    if let Ok(v) = s.deriv(q, order) {
                        prop_assert!(v.is_finite(), "{policy:?}: S^({order})({q}) = {v}");
                    }
                }
                if let Ok(v) = s.integral(a, q) {
                    prop_assert!(v.is_finite(), "{policy:?}: integral to {q} = {v}");
                }
            }
            let mut out = vec![0.0; queries.len()];
            if s.eval_many(&queries, &mut out).is_ok() {
                for (q, y) in queries.iter().zip(&out) {
                    prop_assert_eq!(s.eval(*q).ok(), Some(*y));
                }
            }
        }
    }

    #[test]
    fn integral_is_simpsons_rule_on_each_piece(d in moderate(), u in 0.0..=1.0f64, v in 0.0..=1.0f64) {
        // Simpson's rule is exact for cubics.
        let s = d.spline();
        let m = d.max_abs();
        let (a, b) = s.domain();
        let span = b - a;
        let mut total = 0.0;
        let mut scale = 0.0;
        for k in 0..s.len() {
            let (x0, x1) = (d.knots[k], d.knots[k + 1]);
            let mid = s.eval(0.5 * (x0 + x1))?;
            let piece = (x1 - x0) / 6.0 * (s.eval(x0)? + 4.0 * mid + s.eval(x1)?);
            let got = s.integral(x0, x1)?;
            let tol = 1e-12 * m * (x1 - x0) * (1.0 + x0.abs().max(x1.abs()) / (x1 - x0));
            prop_assert!((got - piece).abs() <= tol, "piece {k}: integral {got}, Simpson {piece}");
            total += piece;
            scale += m * (x1 - x0) * (1.0 + x0.abs().max(x1.abs()) / (x1 - x0));
        }
        let whole = s.integral(a, b)?;
        prop_assert!((whole - total).abs() <= 1e-12 * scale, "whole {whole}, sum {total}");
        // Additive over a split, antisymmetric in its bounds.
        let (p, q) = (a + u * span, a + v * span);
        let (p, q) = (p.min(b), q.min(b));
        let split = s.integral(a, p)? + s.integral(p, q)? + s.integral(q, b)?;
        prop_assert!((split - whole).abs() <= 1e-12 * scale, "split {split}, whole {whole}");
        prop_assert_eq!(s.integral(q, p)?, -s.integral(p, q)?);
    }

    #[test]
    fn range_is_attained_and_bounds_the_curve(d in moderate()) {
        let s = d.spline();
        let ((xlo, lo), (xhi, hi)) = s.range();
        let tol = 1e-12 * d.max_abs();
        prop_assert!((s.eval(xlo)? - lo).abs() <= tol, "minimum {lo} at {xlo}");
        prop_assert!((s.eval(xhi)? - hi).abs() <= tol, "maximum {hi} at {xhi}");
        for k in 0..s.len() {
            for (_, x) in d.samples(k, 32) {
                let y = s.eval(x.min(d.knots[d.knots.len() - 1]))?;
                prop_assert!(y >= lo - tol && y <= hi + tol, "S({x}) = {y} outside [{lo}, {hi}]");
            }
        }
        for e in s.extrema() {
            let h = d.near_width(s.piece_index(e.x));
            let slope = s.deriv(e.x, 1)?;
            prop_assert!(slope.abs() <= 1e-9 * d.max_abs() / h, "S'({}) = {slope}", e.x);
        }
    }
}

/// Simpson's rule, exact for a cubic: the integral of one piece of `s` over
/// `[a, b]` from three of its values.
fn simpson(s: &Spline, a: f64, b: f64) -> Result<f64, bzspline::Error> {
    Ok((b - a) / 6.0 * (s.eval(a)? + 4.0 * s.eval(0.5 * (a + b))? + s.eval(b)?))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..ProptestConfig::default()
    })]

    /// F(tau_0) = 0 and F is the integral of S, checked against Simpson's rule
    /// on every piece (exact for cubics) from values of S alone.
    #[test]
    fn the_antiderivative_integrates_every_piece(d in moderate(), u in vec(0.0..1.0f64, 8)) {
        let s = d.spline();
        let f = s.antiderivative();
        let n = d.knots.len();
        prop_assert_eq!(f.eval(d.knots[0])?, 0.0);
        let span = d.knots[n - 1] - d.knots[0];
        let tol = 1e-12 * n as f64 * d.max_abs() * span;
        let mut total = 0.0;
        for k in 0..n - 1 {
            let (a, b) = (d.knots[k], d.knots[k + 1]);
            let x = a + u[k % 8] * (b - a);
            let want = total + simpson(&s, a, x)?;
            prop_assert!((f.eval(x)? - want).abs() <= tol, "F({x}) = {} against {want}", f.eval(x)?);
            total += simpson(&s, a, b)?;
            prop_assert!((f.eval(b)? - total).abs() <= tol, "F({b}) = {} against {total}", f.eval(b)?);
        }
        let knots = f.knot_values();
        prop_assert_eq!(knots.len(), n);
        prop_assert!((knots[n - 1] - total).abs() <= tol);
        // Differences of F are the spline's integrals.
        let (a, b) = (d.knots[0] + u[0] * span, d.knots[0] + u[1] * span);
        prop_assert!((f.eval(b)? - f.eval(a)? - s.integral(a, b)?).abs() <= tol);
        let xs: Vec<f64> = u.iter().map(|t| d.knots[0] + t * span).collect();
        let mut out = vec![0.0; xs.len()];
        f.eval_many(&xs, &mut out)?;
        for (x, o) in xs.iter().zip(&out) {
            prop_assert_eq!(*o, f.eval(*x)?);
        }
    }

    /// Outside the knots F integrates what the extrapolation gives: the end
    /// cubics, or the end values held; under the default policy it refuses.
    #[test]
    fn the_antiderivative_follows_the_extrapolation(d in moderate(), t in 0.01..2.0f64) {
        let n = d.knots.len();
        let (lo, hi) = (d.knots[0], d.knots[n - 1]);
        let span = hi - lo;
        let (left, right) = (lo - t * span, hi + t * span);
        let tol = 1e-11 * n as f64 * d.max_abs() * span * (1.0 + t).powi(4);
        prop_assert!(d.spline().antiderivative().eval(right).is_err());
        let clamp = d.spline().with_extrapolation(Extrapolate::Clamp).antiderivative();
        let end = clamp.eval(hi)?;
        prop_assert!((clamp.eval(right)? - (end + (right - hi) * d.values[n - 1])).abs() <= tol);
        prop_assert!((clamp.eval(left)? + (lo - left) * d.values[0]).abs() <= tol);
        // The end cubics grow as (distance / width)^3: compare relative to the
        // integral's size.
        let s = d.spline().with_extrapolation(Extrapolate::Extend);
        let f = s.antiderivative();
        let (r, l) = (simpson(&s, hi, right)?, simpson(&s, left, lo)?);
        prop_assert!((f.eval(right)? - (end + r)).abs() <= tol + 1e-12 * r.abs());
        prop_assert!((f.eval(left)? + l).abs() <= tol + 1e-12 * l.abs(), "{} against {}", f.eval(left)?, -l);
    }
}

#[test]
fn the_antiderivative_names_a_bad_query() {
    let s = Spline::with_alpha(&[0.0, 1.0, 2.0, 4.0], &[1.0, 3.0, 2.0, 2.0], 0.5).unwrap();
    let f = s.antiderivative();
    let mut out = [0.0; 3];
    let e = f.eval_many(&[0.5, f64::NAN, 1.0], &mut out).unwrap_err();
    assert!(e.to_string().contains("[1]"), "{e}");
    assert!(f.eval_many(&[0.5], &mut out).is_err());
    assert!(f.eval(f64::INFINITY).is_err());
}
