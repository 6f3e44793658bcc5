//! Synthetic coverages smoothed as a whole, checked with tests independent of
//! the code under test: shared borders, crossings by brute force, validity
//! from `geo`.

use bzspline_geo::{Coverage, SmoothOptions};
use bzspline_testing::*;
use geo::Relate;
use geo_types::{Geometry, LineString};
use proptest::prelude::*;

fn smooth(gs: &[Geometry<f64>], opts: &SmoothOptions) -> (Vec<Geometry<f64>>, bzspline_geo::Stats) {
    Coverage::new(gs.to_vec())
        .and_then(|c| c.smooth(opts))
        .unwrap_or_else(|e| panic!("smoothing failed: {e}"))
}

/// Every check at once.
fn check_all(input: &[Geometry<f64>], output: &[Geometry<f64>]) {
    assert_eq!(input.len(), output.len());
    for (a, b) in neighbours(input) {
        share_border(&output[a], &output[b])
            .unwrap_or_else(|e| panic!("neighbours {a} and {b}: {e}"));
    }
    let crossings = brute_force_crossings(output);
    assert_eq!(crossings, 0, "{crossings} pairs of segments cross");
    assert_eq!(grid_crossings(output), 0, "the grid search finds crossings");
    valid_stays_valid(input, output).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_wiggly_grid_keeps_its_borders() {
    let input = wiggly_grid(6, 5, 4, 0.15, 0.1, 7);
    for tol in [1e-3, 1e-2, 0.1] {
        let (out, stats) = smooth(&input, &SmoothOptions::default().tolerance(tol));
        assert_eq!(stats.shared_arcs, 6 * 4 + 5 * 5, "{stats:?}");
        check_all(&input, &out);
        // The shared edges moved: smoothing happened.
        assert_ne!(out, input);
    }
}

#[test]
fn a_hexagonal_mosaic_keeps_its_borders() {
    let input = hexagons(5, 3, 0.12, 11);
    let (out, stats) = smooth(&input, &SmoothOptions::default().tolerance(1e-3));
    assert!(stats.shared_arcs > 40, "{stats:?}");
    check_all(&input, &out);
}

#[test]
fn voronoi_cells_of_random_points_keep_their_borders() {
    // Seeds whose wiggled edges do not cross in the input (the test checks).
    for seed in [2, 6, 7, 11] {
        let input = voronoi_mosaic(40, 3, 0.08, seed);
        assert!(input.len() >= 20, "{} cells", input.len());
        assert_eq!(brute_force_crossings(&input), 0, "the input crosses");
        valid_stays_valid(&input, &input).unwrap();
        assert!(
            neighbours(&input).len() >= 40,
            "the cells share too few edges"
        );
        let (out, stats) = smooth(&input, &SmoothOptions::default().tolerance(1e-4));
        assert!(stats.shared_arcs > 0, "{stats:?}");
        check_all(&input, &out);
    }
}

#[test]
fn crossings_in_the_input_are_not_added_to() {
    // Seeds whose wiggled edges already cross: those crossings stay (they are
    // original edges), and smoothing adds none.
    for seed in [1, 3, 4, 5, 8] {
        let input = voronoi_mosaic(40, 3, 0.08, seed);
        let before = brute_force_crossings(&input);
        assert!(before > 0, "seed {seed}: the input does not cross");
        let (out, stats) = smooth(&input, &SmoothOptions::default().tolerance(1e-4));
        let after = brute_force_crossings(&out);
        assert!(
            after <= before,
            "seed {seed}: {before} crossings before, {after} after"
        );
        assert!(stats.input_conflicts > 0, "{stats:?}");
        for (a, b) in neighbours(&input) {
            share_segment(&out[a], &out[b])
                .unwrap_or_else(|e| panic!("seed {seed}: {a} and {b}: {e}"));
        }
    }
}

#[test]
fn smoothing_each_ring_alone_breaks_the_borders_that_the_coverage_keeps() {
    // The defect the coverage fixes: ring by ring, neighbours no longer share
    // a border.
    let input = wiggly_grid(3, 3, 4, 0.15, 0.1, 3);
    let alone = ring_by_ring(&input, &SmoothOptions::default().tolerance(1e-3));
    let broken = neighbours(&input)
        .into_iter()
        .filter(|&(a, b)| share_border(&alone[a], &alone[b]).is_err())
        .count();
    assert!(broken > 0);
    let (out, _) = smooth(&input, &SmoothOptions::default().tolerance(1e-3));
    check_all(&input, &out);
}

#[test]
fn a_polygon_in_the_notch_of_another_is_not_crossed() {
    // An L-shaped polygon and a small square in its notch, close to the
    // reflex corner: the corner's curve cuts into the notch, through the
    // square, unless the legs near the corner are refined.
    let l_shape = poly(
        vec![
            c(0.0, 0.0),
            c(4.0, 0.0),
            c(4.0, 1.0),
            c(1.0, 1.0),
            c(1.0, 4.0),
            c(0.0, 4.0),
            c(0.0, 0.0),
        ],
        vec![],
    );
    let square = poly(
        vec![
            c(1.05, 1.05),
            c(1.6, 1.05),
            c(1.6, 1.6),
            c(1.05, 1.6),
            c(1.05, 1.05),
        ],
        vec![],
    );
    let input = vec![l_shape, square];
    // Each alone: they cross.
    let alone = ring_by_ring(&input, &SmoothOptions::default().tolerance(1e-3));
    assert!(
        brute_force_crossings(&alone) > 0,
        "the test case does not provoke a crossing"
    );
    let (out, stats) = smooth(&input, &SmoothOptions::default().tolerance(1e-3));
    check_all(&input, &out);
    assert!(stats.refined_legs > 0, "{stats:?}");
    assert!(stats.rounds > 1, "{stats:?}");
}

/// Every ring smoothed on its own (the behaviour the coverage replaces),
/// each as a polygon of its own.
fn ring_by_ring(gs: &[Geometry<f64>], opts: &SmoothOptions) -> Vec<Geometry<f64>> {
    gs.iter()
        .flat_map(polygons)
        .flat_map(|p| {
            let (shell, holes) = p.into_inner();
            std::iter::once(shell).chain(holes)
        })
        .map(|r| smooth(&[poly(r.0, vec![])], opts).0[0].clone())
        .collect()
}

#[test]
fn holes_that_nearly_touch_their_shell_stay_inside() {
    // A lake near a sharp corner of its country: the shell's corner is cut
    // deeper than the lake is far from it.
    for d in [0.02, 0.3] {
        let shell = vec![
            c(0.0, 0.0),
            c(10.0, 0.0),
            c(10.0, 10.0),
            c(0.0, 10.0),
            c(0.0, 0.0),
        ];
        let e = 10.0 - d;
        let hole = vec![c(8.0, 8.0), c(8.0, e), c(e, e), c(e, 8.0), c(8.0, 8.0)];
        let input = vec![poly(shell, vec![hole])];
        for alpha in [1.0 / 3.0, 0.5, 2.0 / 3.0] {
            let opts = SmoothOptions::default().tolerance(1e-3).alpha(alpha);
            let alone = ring_by_ring(&input, &opts);
            assert!(
                brute_force_crossings(&alone) > 0,
                "d = {d}, alpha = {alpha}: no crossing to resolve"
            );
            let (out, stats) = smooth(&input, &opts);
            check_all(&input, &out);
            assert!(stats.refined_legs > 0, "{stats:?}");
        }
    }
}

#[test]
fn a_thin_peninsula_and_a_comb_stay_simple() {
    // A peninsula 0.01 wide and 3 long, and a comb of teeth 0.05 apart.
    let peninsula = poly(
        vec![
            c(0.0, 0.0),
            c(2.0, 0.0),
            c(2.0, 1.0),
            c(1.005, 1.0),
            c(1.2, 2.5),
            c(1.005, 4.0),
            c(0.995, 4.0),
            c(1.19, 2.5),
            c(0.995, 1.0),
            c(0.0, 1.0),
            c(0.0, 0.0),
        ],
        vec![],
    );
    let mut comb = vec![c(10.0, 0.0), c(14.0, 0.0)];
    for k in (0..20).rev() {
        let x = 10.0 + 0.2 * k as f64;
        comb.extend([c(x + 0.15, 1.0), c(x + 0.1, 2.0), c(x + 0.05, 1.0)]);
        let _ = x;
    }
    comb.extend([c(10.0, 1.0), c(10.0, 0.0)]);
    let comb_poly = poly(comb, vec![]);
    let input = vec![peninsula, comb_poly];
    for tol in [1e-4, 1e-2, 0.5] {
        let (out, _) = smooth(&input, &SmoothOptions::default().tolerance(tol));
        check_all(&input, &out);
    }
}

#[test]
fn islands_smaller_than_the_tolerance_stay_rings() {
    let mut input = Vec::new();
    for k in 0..10 {
        let x = k as f64;
        let s = 1e-3 * (k + 1) as f64;
        input.push(poly(
            vec![c(x, 0.0), c(x + s, 0.0), c(x + s, s), c(x, s), c(x, 0.0)],
            vec![],
        ));
        // A triangle too.
        input.push(poly(
            vec![c(x, 5.0), c(x + s, 5.0), c(x, 5.0 + s), c(x, 5.0)],
            vec![],
        ));
    }
    let (out, _) = smooth(&input, &SmoothOptions::default().tolerance(1.0));
    for g in &out {
        for p in polygons(g) {
            let distinct: std::collections::HashSet<_> = p
                .exterior()
                .0
                .iter()
                .map(|c| (c.x.to_bits(), c.y.to_bits()))
                .collect();
            assert!(distinct.len() >= 3, "{:?}", p.exterior());
        }
    }
    check_all(&input, &out);
}

#[test]
fn lines_ending_on_rings_still_end_there() {
    let ring = poly(
        vec![
            c(0.0, 0.0),
            c(2.0, 0.0),
            c(3.0, 1.0),
            c(2.0, 2.0),
            c(0.0, 2.0),
            c(0.0, 0.0),
        ],
        vec![],
    );
    let line = Geometry::LineString(LineString(vec![
        c(3.0, 1.0),
        c(4.0, 2.0),
        c(5.0, 1.0),
        c(6.0, 2.0),
    ]));
    let input = vec![ring, line];
    let (out, stats) = smooth(&input, &SmoothOptions::default().tolerance(1e-3));
    assert_eq!(stats.lines, 1);
    let Geometry::LineString(l) = &out[1] else {
        panic!()
    };
    assert_eq!(l.0[0], c(3.0, 1.0));
    assert_eq!(l.0[l.0.len() - 1], c(6.0, 2.0));
    let ring_out = &polygons(&out[0])[0];
    assert!(
        ring_out.exterior().0.contains(&c(3.0, 1.0)),
        "the node moved"
    );
    check_all(&input, &out);
}

#[test]
fn keep_angle_keeps_sharp_corners() {
    let input = wiggly_grid(2, 2, 3, 0.1, 0.05, 5);
    let (out, _) = smooth(
        &input,
        &SmoothOptions::default().tolerance(1e-3).keep_angle(30.0),
    );
    // Every input position that turns by more than 30 degrees is in the output.
    for (gi, g) in input.iter().enumerate() {
        let (pin, pout) = (polygons(g), polygons(&out[gi]));
        let (r, o) = (&pin[0].exterior().0, &pout[0].exterior().0);
        let n = r.len() - 1;
        for i in 0..n {
            let (a, b, cc) = (r[(i + n - 1) % n], r[i], r[(i + 1) % n]);
            let (ux, uy, vx, vy) = (b.x - a.x, b.y - a.y, cc.x - b.x, cc.y - b.y);
            let turn = (ux * vy - uy * vx)
                .abs()
                .atan2(ux * vx + uy * vy)
                .to_degrees();
            if turn > 30.0 {
                assert!(
                    o.contains(&b),
                    "corner {b:?} ({turn:.1} degrees) was smoothed away"
                );
            }
        }
    }
    check_all(&input, &out);
}

#[test]
fn through_the_points_keeps_every_position() {
    let input = wiggly_grid(4, 3, 4, 0.15, 0.1, 21);
    for tol in [1e-3, 0.05] {
        let (out, _) = smooth(
            &input,
            &SmoothOptions::default().tolerance(tol).through(true),
        );
        check_all(&input, &out);
        for (i, o) in input.iter().zip(&out) {
            let kept: std::collections::HashSet<(u64, u64)> = polygons(o)[0]
                .exterior()
                .0
                .iter()
                .map(|c| (c.x.to_bits(), c.y.to_bits()))
                .collect();
            for c in &polygons(i)[0].exterior().0 {
                assert!(
                    kept.contains(&(c.x.to_bits(), c.y.to_bits())),
                    "{c:?} lost at tolerance {tol}"
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn random_mosaics_stay_valid_coverages(
        nx in 1usize..5,
        ny in 1usize..5,
        m in 0usize..6,
        jitter in 0.0f64..0.2,
        amp in 0.0f64..0.12,
        seed in any::<u64>(),
        tol_exp in -4i32..0,
        alpha in (1.0f64 / 3.0)..(2.0 / 3.0),
        keep in prop::option::of(10.0f64..90.0),
        through in any::<bool>(),
    ) {
        let input = wiggly_grid(nx, ny, m, jitter, amp, seed);
        let mut opts = SmoothOptions::default()
            .tolerance(10f64.powi(tol_exp))
            .alpha(alpha)
            .through(through);
        if let Some(k) = keep {
            opts = opts.keep_angle(k);
        }
        let (out, _) = smooth(&input, &opts);
        check_all(&input, &out);
    }
}

/// Two cells whose common border was digitised twice: the left cell's side
/// has vertices the right cell's lacks, each a hair off the right's edges.
fn digitised_twice() -> Vec<Geometry<f64>> {
    let hair = 1e-9;
    let left = vec![
        c(0.0, 0.0),
        c(1.0, 0.0),
        c(1.1 + hair, 0.25),
        c(1.2, 0.5),
        c(1.1 - hair, 0.75),
        c(1.0, 1.0),
        c(0.0, 1.0),
        c(0.0, 0.0),
    ];
    let right = vec![
        c(1.0, 0.0),
        c(2.0, 0.0),
        c(2.0, 1.0),
        c(1.0, 1.0),
        c(1.2, 0.5),
        c(1.0, 0.0),
    ];
    vec![poly(left, vec![]), poly(right, vec![])]
}

#[test]
fn snapping_puts_a_vertex_near_an_edge_into_it() {
    let input = digitised_twice();
    let opts = SmoothOptions::default().tolerance(1e-4);
    // Without snapping the two sides are two borders: smoothed apart, they
    // leave slivers of gap and overlap.
    let (apart, stats) = smooth(&input, &opts);
    assert_eq!(stats.shared_arcs, 0, "{stats:?}");
    assert!(share_border(&apart[0], &apart[1]).is_err());
    assert!(
        !apart[0].relate(&apart[1]).is_touches(),
        "no sliver of overlap"
    );
    // With it, the vertices a hair off the right cell's edges go into them:
    // one border, the same positions in both, touching only.
    let coverage = Coverage::builder(input.clone()).snap(1e-6).build().unwrap();
    let (out, stats) = coverage.smooth(&opts).unwrap();
    assert_eq!(stats.shared_arcs, 1, "{stats:?}");
    share_border(&out[0], &out[1]).unwrap_or_else(|e| panic!("{e}"));
    valid_stays_valid(&input, &out).unwrap_or_else(|e| panic!("{e}"));
    // The border is one arc, cut only at the two corners it runs between.
    let topo = coverage.topology();
    let shared: Vec<usize> = (0..topo.arcs().len())
        .filter(|&k| topo.uses()[k] == 2)
        .collect();
    assert_eq!(shared.len(), 1);
    assert_eq!(
        topo.arcs()[shared[0]].len(),
        5,
        "{:?}",
        &topo.arcs()[shared[0]]
    );
    // A snap distance below the hair changes nothing.
    let (same, stats) = Coverage::builder(input.clone())
        .snap(1e-10)
        .build()
        .unwrap()
        .smooth(&opts)
        .unwrap();
    assert_eq!(stats.shared_arcs, 0, "{stats:?}");
    assert_eq!(same, apart);
}

/// Found by the `smooth_coverage` fuzz target: a sliver cell (1e-7 wide)
/// at coordinates near 1e-300, smoothed through its positions. The conflict
/// search's products of coordinate differences underflowed at that scale, so
/// a crossing the output made went unseen; the predicates now scale by a
/// power of two first. Judged here unscaled (exactly, by a power of two),
/// where geo's own validity check does not underflow.
#[test]
fn a_sliver_near_1e_minus_300_stays_valid() {
    let s = 2f64.powi(-996);
    let ring: Vec<_> = [
        (0.0, 0.0),
        (1e-7, 0.0),
        (0.24, 0.333),
        (1e-7, 0.6666),
        (1e-7, 1.0),
        (0.0, 1.0),
        (0.0, 0.0),
    ]
    .iter()
    .map(|&(x, y)| c(x * s, y * s))
    .collect();
    let input = vec![poly(ring, vec![])];
    let mut opts = SmoothOptions::default().through(true).alpha(1.0 / 3.0);
    opts.keep_angle = Some(1.0);
    let (out, _) = smooth(&input, &opts);
    let unscale = |gs: &[Geometry<f64>]| -> Vec<Geometry<f64>> {
        gs.iter()
            .map(|g| match g {
                Geometry::Polygon(p) => {
                    let r: Vec<_> = p.exterior().0.iter().map(|q| c(q.x / s, q.y / s)).collect();
                    poly(r, vec![])
                }
                other => other.clone(),
            })
            .collect()
    };
    valid_stays_valid(&unscale(&input), &unscale(&out)).unwrap_or_else(|e| panic!("{e}"));
}
