//! Unit tests of curves: the fused and coordinate-by-coordinate solves,
//! the defining conditions open and closed, evaluation, segments and the
//! range of a double.

use super::*;
use crate::fast::Piece;
use crate::spline::tests::Rng;
use crate::spline::{Spline, ALPHA_MAX, ALPHA_MIN};
use crate::traits::Arclen;
use crate::traits::Bounds;
use crate::validate::Alphas;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn building_into_a_curve_gives_the_built_curve_and_keeps_it_on_error() {
    let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let helix: Vec<f64> = (0..9)
        .flat_map(|i| {
            let t = f64::from(i);
            [t.cos(), t.sin(), 0.3 * t]
        })
        .collect();
    let repeated = [0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0, 0.0];
    let wave = [0.0, 2.0, 1.0, 3.0, 2.5, 4.0, 0.5, 1.0];
    let builders = [
        Curve::builder(&square, 2),
        Curve::builder(&square, 2)
            .closed(true)
            .param(Param::Chordal),
        Curve::builder(&helix, 3)
            .param(Param::Centripetal)
            .alpha(0.4),
        Curve::builder(&helix, 3).closed(true).alpha(0.6),
        Curve::builder(&wave, 1).param(Param::Given((0..8).map(f64::from).collect())),
        Curve::builder(&repeated, 2).repeats(Repeats::Drop),
        Curve::builder(&helix, 9).closed(true),
    ];
    for b in &builders {
        let want = b.clone().build().unwrap();
        for seed in &builders {
            let mut c = seed.clone().build().unwrap();
            b.clone().build_into(&mut c).unwrap();
            assert_eq!(c, want, "{b:?} into {seed:?}");
        }
        // A refused build leaves the curve as it was.
        let mut c = want.clone();
        let bad = [
            Curve::builder(&repeated, 2),
            Curve::builder(&square, 2).alpha(0.9),
            Curve::builder(&square, 2).param(Param::Given(vec![0.0, 1.0, 1.0, 2.0])),
            Curve::builder(&[0.0, 0.0, 1e-300, 0.0, 1.0, 0.0], 2).param(Param::Chordal),
        ];
        for e in bad {
            assert!(e.clone().build_into(&mut c).is_err(), "{e:?}");
            assert_eq!(c, want);
        }
    }
}

#[test]
fn fused_open_curves_match_the_coordinate_by_coordinate_solve() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for dim in 1..=3 {
        for n in [2usize, 3, 4, 5, 6, 17, 64, 257] {
            for (param, uniform) in [
                (Param::Uniform, true),
                (Param::Chordal, false),
                (Param::Centripetal, true),
            ] {
                // Coordinates of different magnitudes in each dimension.
                let pts: Vec<f64> = (0..n * dim)
                    .map(|i| (rng.next() - 0.5) * [1.0, 1e-200, 3e250][i % dim])
                    .collect();
                let alphas: Vec<f64> = (0..n - 1)
                    .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
                    .collect();
                let b = Curve::builder(&pts, dim).param(param.clone());
                let fast = if uniform {
                    b.alpha(alphas[0])
                } else {
                    b.alphas(&alphas)
                }
                .build()
                .unwrap();
                let widths: Vec<f64> = fast.knots().windows(2).map(|w| w[1] - w[0]).collect();
                let mut slow = fast.clone();
                slow.solve_general(&widths);
                let what = format!("dim {dim} n {n} {param:?}");
                assert_solved_alike(&fast, &slow, 1e-13, &what);
            }
        }
    }
}

/// The deviations of `fast` within `tol` of `slow`'s and the pieces within
/// `4 tol` (scaled numbers lie in [-2, 2]: compared absolutely).
fn assert_solved_alike(fast: &Curve, slow: &Curve, tol: f64, what: &str) {
    assert_eq!(fast.d.len(), slow.d.len(), "{what}");
    for (i, (p, q)) in fast.d.iter().zip(&slow.d).enumerate() {
        assert!(
            (p - q).abs() <= tol,
            "{what}: deviation {i}: want {q}, got {p}"
        );
    }
    let (fc, sc) = (fast.pieces.coefs(), slow.pieces.coefs());
    assert_eq!(fc.len(), sc.len(), "{what}");
    for (i, (Piece(p), Piece(q))) in fc.iter().zip(sc).enumerate() {
        for j in 0..4 {
            assert!(
                (p[j] - q[j]).abs() <= 4.0 * tol,
                "{what}: piece {i} coef {j}: want {}, got {}",
                q[j],
                p[j]
            );
        }
    }
}

#[test]
fn closed_curves_through_the_open_sweeps_match_the_cyclic_solve() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for dim in 1..=3 {
        for n in [3usize, 5, 40, 64, 65, 200, 1001, 70_001] {
            for (param, uniform) in [
                (Param::Uniform, true),
                (Param::Chordal, false),
                (Param::Centripetal, true),
            ] {
                let pts: Vec<f64> = (0..n * dim)
                    .map(|i| (rng.next() - 0.5) * [1.0, 1e-200, 3e250][i % dim])
                    .collect();
                let alphas: Vec<f64> = (0..n)
                    .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
                    .collect();
                let b = Curve::builder(&pts, dim).closed(true).param(param.clone());
                let built = if uniform {
                    b.alpha(alphas[0])
                } else {
                    b.alphas(&alphas)
                }
                .build()
                .unwrap();
                let widths: Vec<f64> = built.knots().windows(2).map(|w| w[1] - w[0]).collect();
                let mut slow = built.clone();
                slow.solve_general(&widths);
                let mut fast = built.clone();
                let one = uniform.then_some(alphas[0]);
                let ring = match dim {
                    1 => fast.solve_ring::<1>(&pts, one),
                    2 => fast.solve_ring::<2>(&pts, one),
                    _ => fast.solve_ring::<3>(&pts, one),
                };
                // Rings long enough for the ends' responses to lie apart
                // (about 20 rows each at these alphas), not the shortest.
                assert!(ring || n < 200, "dim {dim} n {n} {param:?}");
                assert!(
                    !ring || n >= crate::fast::ring::RING_MIN,
                    "dim {dim} n {n} {param:?}"
                );
                if !ring {
                    continue;
                }
                assert_eq!(fast.points, pts);
                let what = format!("dim {dim} n {n} {param:?}");
                assert_solved_alike(&fast, &slow, 1e-14, &what);
            }
        }
    }
}

#[test]
fn closed_curves_through_their_points_match_the_cyclic_solve() {
    let mut rng = Rng(0x0123_4567_89ab_cdef);
    for dim in 1..=3 {
        for n in [3usize, 47, 48, 200, 1001, 70_001] {
            for alphas_kind in 0..3 {
                // Widths over three decades; coordinates of different
                // magnitudes in each dimension.
                let mut knots = vec![0.0];
                for _ in 0..n {
                    let w = 10f64.powf(3.0 * rng.next() - 1.5);
                    knots.push(knots.last().unwrap() + w);
                }
                let pts: Vec<f64> = (0..n * dim)
                    .map(|i| (rng.next() - 0.5) * [1.0, 1e-200, 3e250][i % dim])
                    .collect();
                let one = [0.5, ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next()];
                let per: Vec<f64> = (0..n)
                    .map(|_| ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * rng.next())
                    .collect();
                let (alphas, resolved) = match alphas_kind {
                    0 | 1 => (Alphas::Uniform(one[alphas_kind]), vec![one[alphas_kind]; n]),
                    _ => (Alphas::PerInterval(&per), per.clone()),
                };
                let widths: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
                let want =
                    crate::method::through_controls(&widths, &resolved, &pts, dim, true).unwrap();
                let got = super::solve::through_points(&knots, &pts, dim, true, alphas).unwrap();
                let (given, uniform) = alphas.parts();
                let ring = match dim {
                    1 => super::solve::ring_controls::<1>(&knots, &pts, given, uniform),
                    2 => super::solve::ring_controls::<2>(&knots, &pts, given, uniform),
                    _ => super::solve::ring_controls::<3>(&knots, &pts, given, uniform),
                };
                // Long rings go through the open sweeps.
                assert!(
                    ring.is_some() || n < 200,
                    "dim {dim} n {n} alphas {alphas_kind}"
                );
                assert!(ring.is_none() || n >= crate::fast::ring::RING_MIN);
                assert_eq!(got.len(), want.len());
                for c in 0..dim {
                    let m = (0..n).fold(0.0f64, |m, i| m.max(pts[i * dim + c].abs()));
                    for i in 0..n {
                        let (g, w) = (got[i * dim + c], want[i * dim + c]);
                        assert!(
                            (g - w).abs() <= 1e-13 * m,
                            "dim {dim} n {n} alphas {alphas_kind}: control {i}.{c}: want {w}, got {g}"
                        );
                    }
                }
            }
        }
    }
}

const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

#[test]
fn unit_square_knots_are_pulled_a_tenth_inside() {
    let c = Curve::closed(&SQUARE).unwrap();
    let want = [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]];
    for (k, w) in c.knot_points().iter().zip(want) {
        for i in 0..2 {
            assert!(close(k[i], w[i], 1e-14), "want {w:?}, got {k:?}");
        }
    }
    // Periodic evaluation and C1 across the closing knot.
    let a = c.eval(4.0).unwrap();
    let b = c.eval(0.0).unwrap();
    assert_eq!(a, b);
    let l = c.deriv(4.0 - 1e-9, 1).unwrap();
    let r = c.deriv(1e-9, 1).unwrap();
    for i in 0..2 {
        assert!((l[i] - r[i]).abs() < 1e-7, "{l:?} vs {r:?}");
    }
    assert_eq!(c.eval(5.5).unwrap(), c.eval(1.5).unwrap());
}

#[test]
fn open_curve_matches_per_coordinate_splines() {
    let pts = [[0.0, 1.0], [2.0, 3.0], [3.0, -1.0], [7.0, 0.5], [8.0, 4.0]];
    let alphas = [0.4, ALPHA_MIN, 0.6, ALPHA_MAX];
    for param in [Param::Uniform, Param::Chordal, Param::Centripetal] {
        let c = Curve::builder_from(&pts)
            .param(param.clone())
            .alphas(&alphas)
            .build()
            .unwrap();
        let kp = c.knot_points();
        for dim in 0..2 {
            let v: Vec<f64> = pts.iter().map(|p| p[dim]).collect();
            let s = Spline::with_alphas(c.knots(), &v, &alphas).unwrap();
            for (i, want) in s.knot_values().iter().enumerate() {
                assert!(
                    close(kp[i][dim], *want, 1e-12),
                    "{param:?} knot {i}: want {want}, got {}",
                    kp[i][dim]
                );
            }
        }
    }
}

#[test]
fn one_dimensional_curve_is_the_y_of_x_spline() {
    // The paper's Example 1 without its repeated value (a curve refuses
    // repeated points).
    let f = [1.0, 3.0, 3.5, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
    let c = Curve::builder(&f, 1).param(Param::Uniform).build().unwrap();
    let tau: Vec<f64> = (0..f.len()).map(|i| i as f64).collect();
    let s = Spline::new(&tau, &f).unwrap();
    // Spline::build runs its own fused sweep (same equations, another
    // order of operations): equal to rounding, not bit for bit.
    for (k, v) in c.knot_points().iter().zip(s.knot_values()) {
        assert!(close(k[0], v, 1e-13), "want {v}, got {}", k[0]);
    }
    for i in 0..=100 {
        let x = 0.1 * f64::from(i);
        let (a, b) = (c.eval(x).unwrap()[0], s.eval(x).unwrap());
        assert!(close(a, b, 1e-14), "at {x}: want {b}, got {a}");
    }
    assert_eq!(c.normal(2.5).unwrap(), vec![0.0]);
    assert!(c.tangent(2.5).unwrap()[0].abs() == 1.0);
}

#[test]
fn chordal_and_centripetal_parameters() {
    let pts = [[0.0, 0.0], [3.0, 4.0], [3.0, 13.0]];
    let c = Curve::builder_from(&pts)
        .param(Param::Chordal)
        .alpha_choice(Alphas::Uniform(0.4))
        .build()
        .unwrap();
    assert_eq!(c.knots(), &[0.0, 5.0, 14.0]);
    assert_eq!(c.alphas(), &[0.4, 0.4]);
    let c = Curve::builder_from(&pts)
        .param(Param::Centripetal)
        .build()
        .unwrap();
    assert!(close(c.knots()[1], 5f64.sqrt(), 1e-15));
    assert!(close(c.knots()[2], 5f64.sqrt() + 3.0, 1e-15));
}

#[test]
fn errors_name_the_point() {
    let e = Curve::open(&[[0.0, 0.0], [1.0, f64::NAN], [2.0, 0.0]]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::NonFinite {
                field: Field::Coordinate,
                index: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let e = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [1.0, 1.0]]).unwrap_err();
    assert_eq!(e, Error::RepeatedPoint { index: 2 });
    let e = Curve::closed(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [0.0, 0.0]]).unwrap_err();
    assert_eq!(e, Error::RepeatedClosingPoint { last: 3 });
    assert!(e.to_string().contains("points[3]"));
    assert!(matches!(
        Curve::closed(&[[0.0, 0.0], [1.0, 1.0]]),
        Err(Error::TooFewPoints { found: 2, min: 3 })
    ));
    assert!(matches!(
        Curve::builder(&[1.0, 2.0, 3.0], 2).build(),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(Curve::builder(&[1.0, 2.0], 0).build().is_err());
    assert!(matches!(
        Curve::builder_from(&SQUARE).alpha(0.7).build(),
        Err(Error::AlphaOutOfRange { .. })
    ));
    assert!(matches!(
        Curve::builder_from(&SQUARE)
            .closed(true)
            .param(Param::Given(vec![0.0, 1.0, 2.0, 3.0]))
            .build(),
        Err(Error::LengthMismatch {
            field: Field::Knot,
            expected: 5,
            found: 4
        })
    ));
}

#[test]
fn repeats_can_be_dropped() {
    let pts = [
        [0.0, 0.0],
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 1.0],
        [1.0, 1.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [0.0, 0.0],
    ];
    let alphas = [0.5, 0.4, 0.6, 0.5, 0.5, 0.45, 0.55, 0.35];
    let c = Curve::builder_from(&pts)
        .closed(true)
        .param(Param::Chordal)
        .alphas(&alphas)
        .repeats(Repeats::Drop)
        .build()
        .unwrap();
    assert_eq!(c.dropped(), &[1, 4, 5, 7]);
    assert_eq!(c.point_count(), 4);
    assert_eq!(c.alphas(), &[0.4, 0.6, 0.45, 0.55]);
    let d = Curve::builder_from(&SQUARE)
        .closed(true)
        .param(Param::Chordal)
        .alphas(&[0.4, 0.6, 0.45, 0.55])
        .build()
        .unwrap();
    assert_eq!(c.knot_points(), d.knot_points());
}

#[test]
fn geometry_of_a_circle_like_curve() {
    let n = 64;
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [a.cos(), a.sin()]
        })
        .collect();
    let c = Curve::closed(&pts).unwrap();
    // Nearly a circle of radius a little below 1.
    let len = c.arclen(1e-12).unwrap();
    assert!((len - std::f64::consts::TAU).abs() < 1e-2, "{len}");
    let k = c.curvature(10.3).unwrap();
    assert!((k - 1.0).abs() < 2e-2, "{k}");
    // Normal points inwards (counter-clockwise curve).
    let p = c.eval(10.3).unwrap();
    let nrm = c.normal(10.3).unwrap();
    assert!(nrm[0] * p[0] + nrm[1] * p[1] < -0.99);
    let bb = c.bbox();
    assert!(bb.max[0] <= 1.0 && bb.max[0] > 0.99, "{bb:?}");
    // Arc length inverse.
    let s = c.param_at_length(len / 4.0, 1e-10).unwrap();
    let back = c.arclen_range(0.0, s, 1e-12).unwrap();
    assert!((back - len / 4.0).abs() < 1e-9, "{back}");
    let r = c.resample(9, 1e-10).unwrap();
    assert_eq!(r.len(), 9);
    let near = c.nearest(&[2.0, 0.0]).unwrap();
    assert!((near.distance - 1.0).abs() < 1e-2, "{near:?}");
    assert!(near.param.abs() < 1e-9 || (near.param - 64.0).abs() < 1e-9);
}

#[test]
fn space_curve_normal_is_orthogonal_to_tangent() {
    let pts = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 2.0],
        [0.0, 1.0, 3.0],
    ];
    let c = Curve::open(&pts).unwrap();
    for s in [0.2, 1.0, 1.7, 2.9] {
        let t = c.tangent(s).unwrap();
        let n = c.normal(s).unwrap();
        assert!((norm(&t) - 1.0).abs() < 1e-14);
        assert!((norm(&n) - 1.0).abs() < 1e-14);
        assert!(dot(&t, &n).abs() < 1e-14);
    }
}

#[test]
fn exports_share_end_points() {
    let c = Curve::closed(&SQUARE).unwrap();
    let segs = c.segments::<2>().unwrap();
    assert_eq!(segs.len(), 4);
    for k in 0..4 {
        assert_eq!(segs[k].p[3], segs[(k + 1) % 4].p[0]);
    }
    assert!(c.segments::<3>().is_none());
    let svg = c.to_svg_path().unwrap();
    assert!(
        svg.starts_with("M 0.1 0.1 C") && svg.ends_with(" Z"),
        "{svg}"
    );
    let c3 = Curve::open(&[[0.0; 3], [1.0, 2.0, 3.0]]).unwrap();
    assert!(c3.to_svg_path().is_err());
    assert_eq!(c3.segment::<3>(0).unwrap().p[3], [1.0, 2.0, 3.0]);
}

#[test]
fn parameters_spanning_the_whole_range_keep_the_system_regular() {
    // Neighbouring steps whose sum rounds above f64::MAX: the knot points
    // must match the same curve on parameters scaled down by 2^-1000.
    let tri = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]];
    let big = vec![2.2250738585072014e-308, 5.376052040422133e307, f64::MAX];
    assert!((big[1] - big[0]) + (big[2] - big[1]) == f64::INFINITY);
    let down = 2f64.powi(-1000);
    let small: Vec<f64> = big.iter().map(|x| x * down).collect();
    let a = Curve::builder_from(&tri)
        .param(Param::Given(big))
        .build()
        .unwrap();
    let b = Curve::builder_from(&tri)
        .param(Param::Given(small))
        .build()
        .unwrap();
    for (p, q) in a.knot_points().iter().zip(b.knot_points()) {
        for i in 0..2 {
            assert!(close(p[i], q[i], 1e-14), "want {q:?}, got {p:?}");
        }
    }
}

#[test]
fn huge_coordinates_stay_finite() {
    let pts = [
        [1e308, -1e308],
        [-1e308, 1.5e308],
        [1.7e308, 0.0],
        [0.0, 1e308],
    ];
    for closed in [false, true] {
        for param in [Param::Uniform, Param::Chordal, Param::Centripetal] {
            let c = Curve::builder_from(&pts)
                .closed(closed)
                .param(param)
                .build()
                .unwrap();
            let (lo, hi) = c.domain();
            for i in 0..=50 {
                let s = lo + (hi - lo) * i as f64 / 50.0;
                assert!(c.eval(s).unwrap().iter().all(|v| v.is_finite()));
                assert!(c.tangent(s).unwrap().iter().all(|v| v.is_finite()));
            }
            assert!(c.bbox().max.iter().all(|v| v.is_finite()));
            assert!(c.arclen(1e300).is_err() || c.arclen(1e300).unwrap().is_finite());
        }
    }
}

#[cfg(feature = "serde")]
mod serde_tests {
    use super::*;

    #[test]
    fn curve_round_trips_through_json() {
        let pts = [[0.0, 0.0], [2.0, 1.0], [3.0, -1.0], [5.0, 0.5]];
        for (closed, param) in [
            (false, Param::Chordal),
            (true, Param::Centripetal),
            (true, Param::Given(vec![0.0, 1.0, 3.0, 4.0, 6.5])),
        ] {
            let c = Curve::builder_from(&pts)
                .closed(closed)
                .param(param)
                .alphas(&[0.4, 0.5, 0.6, 0.45][..if closed { 4 } else { 3 }])
                .build()
                .unwrap();
            let json = serde_json::to_string(&c).unwrap();
            let back: Curve = serde_json::from_str(&json).unwrap();
            assert_eq!(back, c, "{json}");
        }
        // Invalid input is refused on the way in.
        let bad = r#"{"dim":2,"closed":false,"param":"Uniform","points":[0,0,0,0],"alphas":[0.5]}"#;
        let e = serde_json::from_str::<Curve>(bad).unwrap_err();
        assert!(e.to_string().contains("repeats"), "{e}");
    }
}

#[cfg(feature = "rayon")]
#[test]
fn chord_parameters_of_a_long_curve_are_its_chords_on_any_number_of_threads() {
    // From 131,073 points the legs' steps are formed in stretches side by
    // side, then summed in order: each step is the chord (or its square
    // root), and 1, 2 and 16 threads give the same bits.
    let mut rng = Rng(17);
    let n = 200_001;
    let pts: Vec<f64> = (0..2 * n).map(|_| 200.0 * rng.next() - 100.0).collect();
    for closed in [false, true] {
        for param in [Param::Chordal, Param::Centripetal] {
            let build = |threads| {
                crate::testing::on_threads(threads, || {
                    CurveBuilder::new(&pts, 2)
                        .closed(closed)
                        .param(param.clone())
                        .build()
                        .unwrap()
                        .knots()
                        .to_vec()
                })
            };
            let knots = build(2);
            let legs = if closed { n } else { n - 1 };
            assert_eq!(knots.len(), legs + 1);
            for k in 0..legs {
                let j = (k + 1) % n;
                let chord = (pts[2 * j] - pts[2 * k]).hypot(pts[2 * j + 1] - pts[2 * k + 1]);
                let want = if param == Param::Centripetal {
                    chord.sqrt()
                } else {
                    chord
                };
                // The sums' rounding, and the step's own.
                let got = knots[k + 1] - knots[k];
                let tol = 4.0 * f64::EPSILON * knots[k + 1].abs() + 1e-12 * want;
                assert!(
                    (got - want).abs() <= tol,
                    "closed {closed}, {param:?}, leg {k}: {got} against {want}"
                );
            }
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            for threads in [1, 16] {
                assert_eq!(bits(&build(threads)), bits(&knots), "{threads} threads");
            }
        }
    }
}
