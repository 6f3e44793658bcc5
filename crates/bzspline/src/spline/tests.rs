//! Unit tests of the spline: the fused sweeps against the reference
//! assembly, the defining conditions, batches, rebuilds and the range of a
//! double.

use super::build::quick_check;
use super::*;
use crate::error::{Error, Field};
use crate::fast::search::{Summary, STRIDE};
use crate::poly::{deriv_of, horner};
use crate::traits::ParamCurve;
use crate::validate::MIN_RELATIVE_INTERVAL;

#[test]
fn the_fused_through_sweep_matches_the_reference() {
    let mut rng = Rng(0x7e120);
    for case in 0..300 {
        let n = 2 + (rng.next() * 40.0) as usize;
        let mut x = vec![rng.next() * 10.0 - 5.0];
        for _ in 1..n {
            let w = 10f64.powf(rng.next() * 4.0 - 2.0);
            x.push(x[x.len() - 1] + w);
        }
        let big = 10f64.powi((rng.next() * 600.0) as i32 - 300);
        let y: Vec<f64> = (0..n).map(|_| (rng.next() * 2.0 - 1.0) * big).collect();
        let a: Vec<f64> = (0..n - 1)
            .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
            .collect();
        for alphas in [Alphas::Uniform(a[0]), Alphas::PerInterval(&a)] {
            let fast = Spline::through(&x, &y, alphas).unwrap();
            let slow = Spline::through_checked(&x, &y, alphas).unwrap();
            let scale = fast
                .values()
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()))
                .max(f64::MIN_POSITIVE);
            for (k, (u, v)) in fast.values().iter().zip(slow.values()).enumerate() {
                assert!(
                    (u - v).abs() <= 1e-13 * scale,
                    "case {case}, G_{k}: fused {u}, reference {v}"
                );
            }
        }
    }
    // Bad input goes the step-by-step way and is named alike.
    let bad = ([0.0, 1.0, 1.0], [0.0, 1.0, 2.0]);
    assert_eq!(
        Spline::through(&bad.0, &bad.1, Alphas::default()).unwrap_err(),
        Spline::through_checked(&bad.0, &bad.1, Alphas::default()).unwrap_err()
    );
}

const EX1_X: [f64; 11] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0];
const EX1_F: [f64; 11] = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn alpha_bounds_accept_the_decimal_literals() {
    assert_eq!(ALPHA_MIN, 1.0 / 3.0);
    const { assert!(ALPHA_MAX > 2.0 / 3.0) };
    assert_eq!(ALPHA_MAX, "0.6666666666666667".parse::<f64>().unwrap());
    for a in [ALPHA_MIN, ALPHA_MAX, 1.0 / 3.0, 2.0 / 3.0] {
        assert!(Spline::with_alpha(&EX1_X, &EX1_F, a).is_ok(), "alpha {a}");
    }
    for a in [
        f64::from_bits(ALPHA_MIN.to_bits() - 1),
        f64::from_bits(ALPHA_MAX.to_bits() + 1),
    ] {
        assert!(
            matches!(
                Spline::with_alpha(&EX1_X, &EX1_F, a),
                Err(Error::AlphaOutOfRange { interval: 0, .. })
            ),
            "alpha {a} should be refused"
        );
    }
}

#[test]
fn example_1_touches_every_leg_and_is_c1() {
    for alpha in [ALPHA_MIN, 0.4, 0.5, 0.6, ALPHA_MAX] {
        let s = Spline::with_alpha(&EX1_X, &EX1_F, alpha).unwrap();
        for (k, (x, f)) in s.tangent_points().into_iter().enumerate() {
            let c = &s.pieces.coefs()[k].0;
            let t = (x - EX1_X[k]) / (EX1_X[k + 1] - EX1_X[k]);
            let y = horner(c, t) * s.scale();
            let dy = deriv_of(c, t, 1) * s.scale();
            assert!(close(y, f, 1e-13), "S(x_{k}): want {f}, got {y}");
            let slope = s.leg_slope(k).unwrap();
            assert!(close(dy, slope, 1e-13), "S'(x_{k}): want {slope}, got {dy}");
        }
        for k in 1..s.len() {
            let l = &s.pieces.coefs()[k - 1].0;
            let r = &s.pieces.coefs()[k].0;
            assert!(close(horner(l, 1.0), horner(r, 0.0), 1e-13));
            assert!(close(deriv_of(l, 1.0, 1), deriv_of(r, 0.0, 1), 1e-13));
        }
        assert_eq!(s.eval(1.0).unwrap(), 1.0);
        assert_eq!(s.eval(11.0).unwrap(), 1.5);
    }
}

#[test]
fn two_and_three_knots() {
    let s = Spline::new(&[0.0, 2.0], &[1.0, 5.0]).unwrap();
    assert_eq!(s.knot_values(), vec![1.0, 5.0]);
    assert!(close(s.eval(1.0).unwrap(), 3.0, 1e-15));
    assert!(close(s.deriv(0.3, 1).unwrap(), 2.0, 1e-15));
    assert!(s.deriv(0.3, 2).unwrap().abs() < 1e-14);
    let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0]).unwrap();
    // One unknown: -(p B1 + q B2) d = ... with p = q = 1/2, B1 = B2 = 5: d = -2/10.
    assert!(
        close(s.knot_values()[1], 0.8, 1e-15),
        "{:?}",
        s.knot_values()
    );
}

#[test]
fn straight_polygon_is_reproduced() {
    let x = [0.0, 0.3, 1.7, 2.0, 5.5];
    let f: Vec<f64> = x.iter().map(|x| 2.0 * x - 1.0).collect();
    let s = Spline::new(&x, &f).unwrap();
    for (phi, f) in s.knot_values().iter().zip(&f) {
        assert!(close(*phi, *f, 1e-14), "want {f}, got {phi}");
    }
}

#[test]
fn extrapolation_policies() {
    let s = Spline::new(&EX1_X, &EX1_F).unwrap();
    assert!(matches!(s.eval(0.5), Err(Error::OutOfDomain { .. })));
    assert!(matches!(s.eval(f64::NAN), Err(Error::NonFinite { .. })));
    let c = s.clone().with_extrapolation(Extrapolate::Clamp);
    assert_eq!(c.eval(-1e300).unwrap(), 1.0);
    assert_eq!(c.eval(f64::INFINITY).unwrap(), 1.5);
    assert_eq!(c.deriv(20.0, 1).unwrap(), 0.0);
    let e = s.with_extrapolation(Extrapolate::Extend);
    let c0 = e.power_coefficients(0).unwrap();
    let x = 0.25;
    let dx = x - 1.0;
    let want = c0[0] + dx * (c0[1] + dx * (c0[2] + dx * c0[3]));
    assert!(close(e.eval(x).unwrap(), want, 1e-13));
    assert!(matches!(e.eval(f64::INFINITY), Err(Error::Overflow { .. })));
}

#[test]
fn integral_matches_power_form() {
    let s = Spline::with_alpha(&EX1_X, &EX1_F, 0.4).unwrap();
    let mut want = 0.0;
    for k in 0..s.len() {
        let c = s.power_coefficients(k).unwrap();
        want += c[0] + c[1] / 2.0 + c[2] / 3.0 + c[3] / 4.0;
    }
    let got = s.integral(1.0, 11.0).unwrap();
    assert!(close(got, want, 1e-13), "want {want}, got {got}");
    assert!(close(s.integral(11.0, 1.0).unwrap(), -want, 1e-13));
    let split = s.integral(1.0, 4.3).unwrap() + s.integral(4.3, 11.0).unwrap();
    assert!(close(split, want, 1e-13));
    assert!(s.integral(0.0, 2.0).is_err());
}

#[test]
fn extrema_are_roots_of_the_derivative() {
    let s = Spline::new(&EX1_X, &EX1_F).unwrap();
    let ex = s.extrema();
    // 1 3 3 1 2 7 1.5 1 10 2 1.5: three maxima and two minima, alternating.
    assert_eq!(ex.len(), 5, "{ex:?}");
    for (i, e) in ex.iter().enumerate() {
        let want = if i % 2 == 0 {
            ExtremumKind::Maximum
        } else {
            ExtremumKind::Minimum
        };
        assert_eq!(e.kind, want, "{ex:?}");
    }
    for e in &ex {
        let d = s.deriv(e.x, 1).unwrap();
        assert!(d.abs() < 1e-10, "S'({}) = {d}", e.x);
    }
    let ((_, lo), (_, hi)) = s.range();
    let mut xs = vec![0.0; 10001];
    for (i, x) in xs.iter_mut().enumerate() {
        *x = 1.0 + 10.0 * i as f64 / 10000.0;
    }
    let mut ys = vec![0.0; xs.len()];
    s.eval_many(&xs, &mut ys).unwrap();
    for y in ys {
        assert!(
            y >= lo - 1e-12 && y <= hi + 1e-12,
            "{y} outside [{lo}, {hi}]"
        );
    }
}

#[test]
fn batch_matches_pointwise_sorted_and_not() {
    let s = Spline::with_alpha(&EX1_X, &EX1_F, 0.6).unwrap();
    let xs: Vec<f64> = (0..200)
        .map(|i| 1.0 + ((i * 7919) % 1000) as f64 / 100.0)
        .collect();
    let mut sorted = xs.clone();
    sorted.sort_by(f64::total_cmp);
    for q in [&xs, &sorted] {
        for order in 0..4 {
            let mut out = vec![0.0; q.len()];
            s.deriv_many(q, order, &mut out).unwrap();
            for (x, y) in q.iter().zip(&out) {
                assert_eq!(*y, s.deriv(*x, order).unwrap(), "order {order} at {x}");
            }
        }
    }
    let mut out = vec![0.0; 3];
    assert!(matches!(
        s.eval_many(&[2.0, f64::NAN, 3.0], &mut out),
        Err(Error::NonFinite { index: 1, .. })
    ));
    assert!(s.eval_many(&[2.0], &mut out).is_err());
}

#[test]
fn huge_values_do_not_overflow() {
    // Values at the very top of the range: evaluation stays finite.
    let f = [1e308, -1.7e308, 1.7e308, f64::MAX, -f64::MAX];
    let x = [0.0, 1.0, 2.0, 3.0, 4.0];
    let s = Spline::new(&x, &f).unwrap();
    for v in s.knot_values() {
        assert!(v.is_finite());
    }
    for i in 0..=400 {
        let y = s.eval(i as f64 / 100.0).unwrap();
        assert!(y.is_finite(), "{y}");
    }
    // Values near 1e308 whose Bezier ordinates are representable: the
    // export is finite and agrees with a scaled-down copy.
    let f = [1e308, -1e308, 1e308, 5e307, -1e308];
    let s = Spline::new(&x, &f).unwrap();
    let small: Vec<f64> = f.iter().map(|v| v * 1e-300).collect();
    let t = Spline::new(&x, &small).unwrap();
    for (a, b) in s.segments().iter().zip(t.segments()) {
        for j in 0..4 {
            let (ya, yb) = (a.p[j][1], b.p[j][1] * 1e300);
            assert!(
                ya.is_finite() && close(ya, yb, 1e-13),
                "want {yb}, got {ya}"
            );
        }
    }
}

#[test]
fn tiny_interval_is_computed_or_refused() {
    let ok = Spline::new(&[0.0, 1e-15, 1.0], &[0.0, 1.0, 0.0]).unwrap();
    assert!(ok.knot_values().iter().all(|v| v.is_finite()));
    assert!(matches!(
        Spline::new(&[0.0, 5e-324, 1.0], &[0.0, 1.0, 0.0]),
        Err(Error::IntervalTooSmall { interval: 0, .. })
    ));
    assert!(matches!(
        Spline::new(&[-1e308, 1e308], &[0.0, 1.0]),
        Err(Error::SpanOverflow { .. })
    ));
}

/// A small deterministic generator (xorshift64*), uniform in `[0, 1)`;
/// the curve tests use it too.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Random data: widths over three decades, values over several, at a
/// magnitude `mag`.
fn random_data(rng: &mut Rng, n: usize, mag: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut x = Vec::with_capacity(n);
    let mut t = -3.0 + 6.0 * rng.next();
    for _ in 0..n {
        x.push(t);
        t += 10f64.powf(-1.5 + 3.0 * rng.next());
    }
    let f = (0..n)
        .map(|_| mag * (2.0 * rng.next() - 1.0) * 10f64.powf(2.0 * rng.next()))
        .collect();
    let a = (0..n.saturating_sub(1))
        .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
        .collect();
    (x, f, a)
}

/// The straightforward evaluator: binary search, `t = (x - tau_k) / h_k`,
/// Horner, division by `h` per order.
fn reference_deriv(s: &Spline, x: f64, order: u32) -> f64 {
    let k = s.piece_index(x);
    let h = s.pieces.knots()[k + 1] - s.pieces.knots()[k];
    let t = (x - s.pieces.knots()[k]) / h;
    let mut v = deriv_of(&s.pieces.coefs()[k].0, t, order) * s.scale();
    for _ in 0..order {
        v /= h;
    }
    v
}

#[test]
fn rebuilds_of_other_sizes_keep_the_summary_right() {
    // A stale summary would send the batch search to the wrong stretch
    // of knots.
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let (x, f, _) = random_data(&mut rng, 40, 1.0);
    let mut s = Spline::new(&x, &f).unwrap();
    for n in [17usize, 100, 16, 2, 33, 1000, 5, 64, 65, 3, 48, 49] {
        let (x, f, a) = random_data(&mut rng, n, 1.0);
        for alphas in [Alphas::Uniform(0.5), Alphas::PerInterval(&a)] {
            s.rebuild(&x, &f, alphas).unwrap();
            let mut want = Summary::default();
            want.of(&x);
            assert_eq!(s.pieces.summary(), &want, "n {n}");
            let q: Vec<f64> = (0..64)
                .map(|_| x[0] + (x[n - 1] - x[0]) * rng.next())
                .collect();
            let mut got = vec![0.0; q.len()];
            s.eval_many(&q, &mut got).unwrap();
            for (q, g) in q.iter().zip(&got) {
                assert_eq!(*g, s.eval(*q).unwrap(), "n {n} x {q}");
            }
        }
    }
}

#[test]
fn random_order_batches_match_pointwise_with_and_without_the_search_index() {
    let mut rng = Rng(0x51ed_270b_0a3f_1c25);
    let mut s = Spline::new(&[0.0, 1.0], &[0.0, 1.0]).unwrap();
    for n in [40usize, 300, 2_000, 5_000] {
        for shape in 0..3 {
            let (mut x, f, _) = random_data(&mut rng, n, 1.0);
            match shape {
                // Widths over three decades, mixed: evenly spread at the
                // scale of the buckets.
                0 => {}
                // Runs of close knots between wide gaps.
                1 => {
                    let mut t = 0.0;
                    for (i, v) in x.iter_mut().enumerate() {
                        t += if i % 50 < 45 {
                            1e-3
                        } else {
                            10.0 * (1.0 + rng.next())
                        };
                        *v = t;
                    }
                }
                // Geometric: too uneven for an index.
                _ => {
                    for (i, v) in x.iter_mut().enumerate() {
                        *v = (30.0 * i as f64 / n as f64).exp();
                    }
                }
            }
            s.rebuild(&x, &f, Alphas::Uniform(0.5)).unwrap();
            assert!(
                !s.pieces.summary().indexed(),
                "n {n} shape {shape}: a rebuild forgets it"
            );
            let (lo, hi) = (x[0], x[n - 1]);
            let q: Vec<f64> = (0..n.max(100))
                .map(|_| lo + (hi - lo) * rng.next() * rng.next().sqrt())
                .collect();
            let mut got = vec![0.0; q.len()];
            for round in 0..2 {
                s.deriv_many(&q, 1, &mut got).unwrap();
                for (x, g) in q.iter().zip(&got) {
                    let want = s.deriv(*x, 1).unwrap();
                    assert_eq!(*g, want, "n {n} shape {shape} round {round} x {x}");
                }
            }
            // With a handful of entries even uneven knots keep theirs:
            // it cannot cost much.
            if n >= 300 {
                assert_eq!(
                    s.pieces.summary().indexed(),
                    shape < 2,
                    "n {n} shape {shape}"
                );
            }
        }
    }
}

#[test]
fn piece_index_is_the_last_knot_not_above_at_any_size() {
    // Past 2^18 knots, and once a batch has formed the index, the single
    // query takes the summary's search rather than one over all knots.
    let mut rng = Rng(0x6a09_e667_f3bc_c908);
    for n in [2usize, 17, 1_000, 300_000] {
        let (x, f, _) = random_data(&mut rng, n, 1.0);
        let s = Spline::new(&x, &f).unwrap();
        let (lo, hi) = (x[0], x[n - 1]);
        let mut q: Vec<f64> = (0..2_000).map(|_| lo + (hi - lo) * rng.next()).collect();
        for i in (0..n).step_by((n / 500).max(1)) {
            q.extend([x[i], x[i].next_down(), x[i].next_up()]);
        }
        q.extend([
            f64::NAN,
            f64::NEG_INFINITY,
            f64::INFINITY,
            hi.next_up(),
            lo.next_down(),
        ]);
        for indexed in [false, true] {
            if indexed {
                // A batch of random order, long enough to form it.
                let b: Vec<f64> = (0..n.div_ceil(32) + 64)
                    .map(|_| lo + (hi - lo) * rng.next())
                    .collect();
                let mut out = vec![0.0; b.len()];
                s.eval_many(&b, &mut out).unwrap();
                // One piece: the batch only walks, and never searches.
                assert_eq!(s.pieces.summary().indexed(), n > 2, "n {n}");
            }
            for &x0 in &q {
                let want = x.partition_point(|&k| k <= x0).saturating_sub(1).min(n - 2);
                assert_eq!(s.piece_index(x0), want, "n {n} x {x0} index {indexed}");
            }
        }
    }
}

#[test]
fn fused_build_and_batches_match_the_reference() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for (case, &n) in [2usize, 3, 4, 5, 17, 18, 33, 100, 1000, 4097]
        .iter()
        .enumerate()
    {
        for mag in [1.0, 1e-300, 1e300, 3e-7] {
            let (x, f, a) = random_data(&mut rng, n, mag);
            let fmax = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let uniform = ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next();
            for alphas in [Alphas::PerInterval(&a), Alphas::Uniform(uniform)] {
                let fast = Spline::build(&x, &f, alphas).unwrap();
                let slow = Spline::build_reference(&x, &f, alphas).unwrap();
                assert_eq!(fast.alphas(), slow.alphas());
                assert_eq!(fast.knots(), slow.knots());
                assert_eq!(fast.values(), slow.values());
                assert_eq!(fast.scale(), slow.scale());
                assert_eq!(
                    fast.pieces.summary(),
                    slow.pieces.summary(),
                    "case {case} n {n}: summary"
                );
                let tol = 1e-13 * fmax;
                for (k, (p, q)) in fast
                    .knot_values()
                    .iter()
                    .zip(slow.knot_values())
                    .enumerate()
                {
                    assert!(
                        (p - q).abs() <= tol,
                        "case {case} n {n} mag {mag}: knot value {k}: want {q}, got {p}"
                    );
                }
                for k in 0..fast.len() {
                    let (p, q) = (
                        fast.unit_coefficients(k).unwrap(),
                        slow.unit_coefficients(k).unwrap(),
                    );
                    for j in 0..4 {
                        assert!(
                            (p[j] - q[j]).abs() <= tol,
                            "case {case} n {n}: piece {k} coef {j}: want {}, got {}",
                            q[j],
                            p[j]
                        );
                    }
                }
                // Batches: sorted (several queries per piece) and random,
                // against pointwise deriv exactly and the straightforward
                // evaluator to rounding.
                let (lo, hi) = fast.domain();
                let m = 3 * n + 7;
                let mut random: Vec<f64> = (0..m).map(|_| lo + (hi - lo) * rng.next()).collect();
                random.push(hi);
                random.push(lo);
                random.extend_from_slice(&x);
                let mut sorted = random.clone();
                sorted.sort_by(f64::total_cmp);
                // Runs in order broken by jumps both ways, and descending:
                // the walk's far jumps and the hand-overs between walk and search.
                let mut jumpy: Vec<f64> = sorted
                    .chunks(37)
                    .rev()
                    .flat_map(|c| c.iter().copied())
                    .collect();
                jumpy.rotate_left(m / 3);
                let descending: Vec<f64> = sorted.iter().rev().copied().collect();
                let mut out = vec![0.0; random.len()];
                for q in [&sorted, &random, &jumpy, &descending] {
                    for order in 0..4 {
                        fast.deriv_many(q, order, &mut out).unwrap();
                        for (&xq, &y) in q.iter().zip(&out) {
                            assert_eq!(y, fast.deriv(xq, order).unwrap(), "order {order} at {xq}");
                            let want = reference_deriv(&slow, xq, order);
                            let k = fast.piece_index(xq);
                            let h = x[k + 1] - x[k];
                            let tol = 1e-13 * fmax / h.powi(order as i32);
                            assert!(
                                (y - want).abs() <= tol,
                                "case {case} n {n} order {order} at {xq}: want {want}, got {y}"
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn rebuilds_with_one_alpha_keep_the_alphas_right() {
    // The uniform hint lets a rebuild skip rewriting the alphas only when
    // they are already that one alpha.
    let mut rng = Rng(9);
    let (x, f, a) = random_data(&mut rng, 300, 1.0);
    let mut s = Spline::with_alphas(&x, &f, &a).unwrap();
    for (alpha, per) in [
        (0.4, false),
        (0.4, false),
        (0.6, false),
        (0.0, true),
        (0.6, false),
    ] {
        if per {
            s.rebuild(&x, &f, Alphas::PerInterval(&a)).unwrap();
            assert_eq!(s.alphas(), &a[..]);
        } else {
            s.rebuild(&x, &f, Alphas::Uniform(alpha)).unwrap();
            assert!(s.alphas().iter().all(|&b| b == alpha), "alpha {alpha}");
            assert_eq!(s, Spline::with_alpha(&x, &f, alpha).unwrap());
        }
    }
    // A shorter rebuild, then the full length again.
    s.rebuild(&x[..100], &f[..100], Alphas::Uniform(0.6))
        .unwrap();
    assert_eq!(s.alphas().len(), 99);
    s.rebuild(&x, &f, Alphas::Uniform(0.6)).unwrap();
    assert_eq!(s.alphas(), &[0.6; 299][..]);
}

#[test]
fn rebuild_reuses_and_keeps_the_spline_on_error() {
    let mut rng = Rng(7);
    let (x, f, a) = random_data(&mut rng, 500, 1.0);
    let mut s = Spline::with_alphas(&x, &f, &a)
        .unwrap()
        .with_extrapolation(Extrapolate::Clamp);
    let bytes = s.heap_bytes();
    // Knots, values, alphas, pieces, the summary and the one scale.
    assert_eq!(bytes, 500 * 8 * 3 - 8 + 499 * 32 + 32 * 8 + 8, "heap bytes");
    let (x2, f2, _) = random_data(&mut rng, 400, 2.0);
    s.rebuild(&x2, &f2, Alphas::Uniform(0.4)).unwrap();
    assert_eq!(
        s,
        Spline::with_alpha(&x2, &f2, 0.4)
            .unwrap()
            .with_extrapolation(Extrapolate::Clamp)
    );
    assert_eq!(s.heap_bytes(), bytes, "no reallocation");
    let before = s.clone();
    let mut bad = x2.clone();
    bad[200] = f64::NAN;
    assert!(matches!(
        s.rebuild(&bad, &f2, Alphas::default()),
        Err(Error::NonFinite {
            field: Field::Knot,
            index: 200,
            ..
        })
    ));
    assert_eq!(s, before);
    // Other knots, good, with a bad value: the check has read them all
    // (and put them in its summary) before it fails.
    let mut bad_values = f.clone();
    bad_values[3] = f64::NAN;
    assert!(s.rebuild(&x, &bad_values, Alphas::default()).is_err());
    assert_eq!(s, before);
}

#[test]
fn errors_are_those_of_the_step_by_step_validation() {
    let x = [0.0, 1.0, 2.0, 3.0];
    let f = [0.0, 1.0, 0.0, 1.0];
    let cases: [(&[f64], &[f64], Alphas<'_>); 9] = [
        (&[0.0], &[0.0], Alphas::default()),
        (&x, &f[..3], Alphas::default()),
        (&[0.0, 1.0, 1.0, 3.0], &f, Alphas::default()),
        (&[0.0, f64::INFINITY, 2.0, 3.0], &f, Alphas::default()),
        (&[0.0, 1e-17, 2.0, 3.0], &f, Alphas::default()),
        (&x, &[0.0, f64::NAN, 0.0, 1.0], Alphas::default()),
        (&x, &f, Alphas::Uniform(0.7)),
        (&x, &f, Alphas::PerInterval(&[0.5, 0.5])),
        (&x, &f, Alphas::PerInterval(&[0.5, f64::NAN, 0.2])),
    ];
    for (k, v, a) in cases {
        let got = Spline::build(k, v, a);
        let want = Spline::build_reference(k, v, a);
        assert!(got.is_err(), "{k:?} {v:?} {a:?} should fail");
        // Debug text, because a NaN in the error is not equal to itself.
        assert_eq!(format!("{got:?}"), format!("{want:?}"));
    }
}

#[test]
fn span_at_the_top_of_the_range_keeps_the_system_regular() {
    // Both widths are finite but their sum rounds to infinity; the knot
    // values must match the same data on knots scaled down by 2^-1000.
    let knots = [2.2250738585072014e-308, 5.376052040422133e307, f64::MAX];
    assert!((knots[1] - knots[0]) + (knots[2] - knots[1]) == f64::INFINITY);
    let f = [0.0, 0.0, 1.0];
    let a = [ALPHA_MIN, ALPHA_MAX];
    let s = Spline::with_alphas(&knots, &f, &a).unwrap();
    let down = 2f64.powi(-1000);
    let small: Vec<f64> = knots.iter().map(|x| x * down).collect();
    let t = Spline::with_alphas(&small, &f, &a).unwrap();
    for (got, want) in s.knot_values().iter().zip(t.knot_values()) {
        assert!(close(*got, want, 1e-14), "want {want}, got {got}");
    }
    assert!(s.knot_values()[1] < 0.1, "{:?}", s.knot_values());
}

#[test]
fn walked_blocks_with_outside_queries_and_huge_pieces_match_pointwise() {
    // Sorted blocks that leave the domain and come back, meet NaN, cross
    // pieces whose values near f64::MAX leave no margin for the batch's
    // finiteness bound, and end on the last knot: each result as the
    // pointwise evaluator gives it, under every extrapolation policy.
    let x: Vec<f64> = (0..40).map(|i| f64::from(i) * 0.5).collect();
    let f: Vec<f64> = (0..40)
        .map(|i| match i % 7 {
            3 => f64::MAX,
            4 => -0.9 * f64::MAX,
            _ => f64::from(i).sin(),
        })
        .collect();
    let (lo, hi) = (x[0], x[39]);
    let mut qs: Vec<f64> = (0..400).map(|i| -1.0 + f64::from(i) * 0.0537).collect();
    qs[100] = f64::NAN;
    qs.extend([hi, hi, lo, hi + 1.0, lo - 1.0]);
    qs.extend((0..80).map(|i| lo + f64::from(i) * 0.2461));
    let clean: Vec<f64> = qs.iter().copied().filter(|q| !q.is_nan()).collect();
    let mut answered = 0;
    for policy in [Extrapolate::Clamp, Extrapolate::Extend, Extrapolate::Error] {
        let s = Spline::new(&x, &f).unwrap().with_extrapolation(policy);
        for order in 0..4 {
            for q in [&qs, &clean] {
                answered += usize::from(batch_is_pointwise(&s, q, order));
            }
        }
    }
    // Clamped values answer every query but the NaN; derivatives and
    // extended values overflow beside the huge pieces.
    assert_eq!(answered, 1);
}

/// `deriv_many` against `deriv` query by query: the same values, or the
/// error of the first query that fails. True when every query was answered.
fn batch_is_pointwise(s: &Spline, qs: &[f64], order: u32) -> bool {
    let mut out = vec![0.0; qs.len()];
    let got = s.deriv_many(qs, order, &mut out);
    let first_err = qs
        .iter()
        .enumerate()
        .find_map(|(i, &q)| s.deriv(q, order).err().map(|e| e.at_query(i)));
    let label = format!("{:?} order {order}", s.extrapolate);
    match first_err {
        // (Compared as text: the error may hold a NaN.)
        Some(e) => {
            assert_eq!(
                format!("{got:?}"),
                format!("{:?}", Err::<(), _>(e)),
                "{label}"
            );
            false
        }
        None => {
            assert_eq!(got, Ok(()), "{label}");
            for (&q, &y) in qs.iter().zip(&out) {
                assert_eq!(Ok(y), s.deriv(q, order), "{label} at {q}");
            }
            true
        }
    }
}

#[test]
fn batch_overflow_is_the_pointwise_error() {
    // The higher derivatives overflow on the narrow first piece only: the
    // batch must stop at the same query with the same error, and agree with
    // the pointwise values where they are finite.
    let s = Spline::new(&[0.0, 1e-12, 1.0], &[0.0, 1e300, 0.0]).unwrap();
    let xs: Vec<f64> = [0.5, 0.25]
        .into_iter()
        .chain((0..100).map(|i| f64::from(i) * 1e-14))
        .collect();
    let mut failed = Vec::new();
    for order in 0..=3 {
        let mut out = vec![0.0; xs.len()];
        let batch = s.deriv_many(&xs, order, &mut out);
        match xs.iter().find_map(|&x| s.deriv(x, order).err()) {
            Some(e) => {
                assert_eq!(batch, Err(e), "order {order}");
                failed.push(order);
            }
            None => {
                assert_eq!(batch, Ok(()), "order {order}");
                for (&x, &o) in xs.iter().zip(&out) {
                    assert_eq!(Ok(o), s.deriv(x, order), "order {order} at {x}");
                }
            }
        }
    }
    assert!(
        failed.contains(&3),
        "the third derivative overflows: {failed:?}"
    );
    assert!(!failed.contains(&0), "values do not: {failed:?}");
}

#[test]
fn extrema_near_f64_max_are_finite() {
    // A maximum between two knots valued f64::MAX: at the top of the range
    // (where rounding may carry it above, and it is clamped).
    let knots = [
        -859.3884755308262,
        0.0,
        365.72855093326575,
        436.5118599248209,
        767.2605905654594,
    ];
    let f = [0.0, 0.0, -f64::MAX, f64::MAX, f64::MAX];
    let s = Spline::with_alphas(&knots, &f, &[ALPHA_MAX, ALPHA_MIN, 0.5, 0.5]).unwrap();
    let ex = s.extrema();
    let top = f64::MAX * (1.0 - 1e-15);
    assert!(ex.iter().any(|e| e.y >= top), "{ex:?}");
    assert!(ex.iter().all(|e| e.y.is_finite()), "{ex:?}");
    let ((_, lo), (_, hi)) = s.range();
    assert!(
        lo.is_finite() && hi >= top && hi.is_finite(),
        "range [{lo}, {hi}]"
    );
    for e in ex {
        let y = s.eval(e.x).unwrap();
        assert!(close(y, e.y, 1e-12), "S({}) = {y}, extremum {}", e.x, e.y);
    }
}

#[test]
fn first_value_is_exact_beside_a_value_near_the_top_of_the_range() {
    // Found by the spline_build fuzz target: F_0 divided by the scale of
    // f64::MAX underflowed to 0, so S(tau_0) was 0 instead of F_0.
    let f0 = 1.568_603_515_624_999_3e-203;
    let s = Spline::with_alpha(&[0.0, 3.906_25e-303], &[f0, f64::MAX], ALPHA_MIN).unwrap();
    assert_eq!(s.eval(0.0).unwrap(), f0, "S(tau_0) must be F_0");
    assert_eq!(
        s.eval(3.906_25e-303).unwrap(),
        f64::MAX,
        "S(tau_N) must be F_N"
    );
    assert_eq!(s.knot_values(), vec![f0, f64::MAX]);
    // The batch evaluator agrees (on knots of ordinary size, which it
    // handles without rescaling them).
    let s = Spline::new(&[0.0, 1.0, 2.0], &[f0, f64::MAX, 0.0]).unwrap();
    let xs = [0.0, 0.5, 0.0, 2.0];
    let mut out = [0.0; 4];
    s.eval_many(&xs, &mut out).unwrap();
    for (x, y) in xs.iter().zip(out) {
        assert_eq!(y, s.eval(*x).unwrap(), "batch at {x}");
    }
    assert_eq!(out[0], f0);
}

/// What the one-pass check must find, item by item: `Some(max |F|)` when the
/// span is finite and positive, every width at least `span * EPSILON` (and
/// positive), every value finite and every alpha in range.
fn brute_force_check(knots: &[f64], values: &[f64], alphas: &[f64]) -> Option<f64> {
    let n = knots.len();
    let span = knots[n - 1] - knots[0];
    let thr = (span * MIN_RELATIVE_INTERVAL).max(f64::from_bits(1));
    let ok = span.is_finite()
        && span > 0.0
        && knots.windows(2).all(|w| w[1] - w[0] >= thr)
        && values.iter().all(|v| v.is_finite())
        && alphas.iter().all(|a| (ALPHA_MIN..=ALPHA_MAX).contains(a));
    ok.then(|| values.iter().fold(0.0f64, |m, v| m.max(v.abs())))
}

/// A change to knots, values and alphas.
type Fault<'a> = dyn Fn(&mut [f64], &mut [f64], &mut [f64]) + 'a;

#[test]
fn the_one_pass_check_agrees_with_a_brute_force_check() {
    let mut rng = Rng(0x0c4e_c4ed);
    // Sizes around the lanes, the strides, the blocks of the loop and the
    // two halves.
    for n in [
        2, 3, 4, 5, 7, 8, 9, 17, 33, 40, 1025, 2051, 2066, 4100, 4113,
    ] {
        let (x, f, a) = random_data(&mut rng, n, 1.0);
        let mut positions: Vec<usize> = (0..n.min(40)).chain(n.saturating_sub(40)..n).collect();
        for b in (1024..n)
            .step_by(1024)
            .chain([(n - 1) / 2 / STRIDE * STRIDE])
        {
            positions.extend(b.saturating_sub(2)..(b + 3).min(n));
        }
        positions.extend((0..30).map(|_| (rng.next() * n as f64) as usize));
        let mut summary = Summary::default();
        let want = brute_force_check(&x, &f, &a);
        assert!(want.is_some());
        let got = quick_check(&x, &f, Alphas::PerInterval(&a), &mut summary);
        assert_eq!(got, want, "n {n}");
        let every: Vec<f64> = x.iter().step_by(STRIDE).copied().collect();
        assert_eq!(summary.every, every, "n {n}: summary");
        for &i in &positions {
            let faults: [(&str, &Fault<'_>); 8] = [
                ("NaN value", &|_, f, _| f[i] = f64::NAN),
                ("infinite value", &|_, f, _| f[i] = f64::INFINITY),
                ("negative infinite value", &|_, f, _| f[i] = -f64::INFINITY),
                ("NaN knot", &|x, _, _| x[i] = f64::NAN),
                ("repeated knot", &|x, _, _| x[i.max(1)] = x[i.max(1) - 1]),
                ("knot too close", &|x, _, _| {
                    let j = i.max(1);
                    x[j] = x[j - 1] + (x[x.len() - 1] - x[0]) * f64::EPSILON / 2.0;
                }),
                ("knot out of order", &|x, _, _| {
                    x.swap(i.max(1) - 1, i.max(1))
                }),
                ("alpha out of range", &|_, _, a| {
                    if let Some(a) = a.get_mut(i) {
                        *a = ALPHA_MAX + 1e-9;
                    }
                }),
            ];
            for (what, fault) in faults {
                let (mut x, mut f, mut a) = (x.clone(), f.clone(), a.clone());
                fault(&mut x, &mut f, &mut a);
                let want = brute_force_check(&x, &f, &a);
                let got = quick_check(&x, &f, Alphas::PerInterval(&a), &mut summary);
                assert_eq!(got, want, "n {n}: {what} at {i}");
                // Every fault but an alpha past the last leg and a last knot
                // moved close (which moves the span too) makes the input bad.
                let end = i.max(1) == n - 1;
                if !(what == "alpha out of range" && i == n - 1 || what == "knot too close" && end)
                {
                    assert!(got.is_none(), "n {n}: {what} at {i} passed");
                }
            }
        }
    }
    // Values and widths at the top of the range: nothing overflows to a
    // false alarm.
    let x = [0.0, 6e307, 1.2e308, 1.79e308];
    let f = [f64::MAX, -f64::MAX, f64::MAX, 1.0];
    let mut summary = Summary::default();
    let got = quick_check(&x, &f, Alphas::Uniform(0.5), &mut summary);
    assert_eq!(got, Some(f64::MAX));
}
