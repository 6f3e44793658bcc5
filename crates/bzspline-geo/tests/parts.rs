//! Parts of a coverage smoothed alone, each with the nodes of the whole
//! (`bzspline_geo::nodes`), against the whole coverage smoothed at once:
//! every feature must come out the same, bit for bit.

mod common;

use bzspline_geo::nodes::{across, extent, meetings, Nodes};
use bzspline_geo::{coverage_chains, Coverage, SmoothOptions, Stats};
use common::*;
use geo_types::{Geometry, LineString};
use proptest::prelude::*;

fn whole(gs: &[Geometry<f64>], opts: &SmoothOptions) -> (Vec<Geometry<f64>>, Stats) {
    Coverage::new(gs.to_vec(), None)
        .and_then(|c| c.smooth(opts))
        .unwrap_or_else(|e| panic!("smoothing failed: {e}"))
}

/// Smooths the features of each part alone, with the nodes found across the
/// parts, and puts the results back in the features' order.
fn by_parts(gs: &[Geometry<f64>], part: &[usize], opts: &SmoothOptions) -> Vec<Geometry<f64>> {
    let k = part.iter().max().map_or(0, |&p| p + 1);
    let members: Vec<Vec<usize>> = (0..k)
        .map(|p| (0..gs.len()).filter(|&i| part[i] == p).collect())
        .collect();
    let pieces: Vec<Vec<Geometry<f64>>> = members
        .iter()
        .map(|m| m.iter().map(|&i| gs[i].clone()).collect())
        .collect();
    let mut met = Vec::new();
    for p in &pieces {
        met.extend(meetings(&coverage_chains(p)).unwrap());
    }
    let mut nodes = across(met);
    if let Some(e) = extent(&coverage_chains(gs)) {
        nodes = nodes.with_extent(e);
    }
    let mut out: Vec<Option<Geometry<f64>>> = vec![None; gs.len()];
    for (m, p) in members.iter().zip(pieces) {
        let (smoothed, _) = Coverage::with_nodes(p, None, nodes.clone())
            .and_then(|c| c.smooth(opts))
            .unwrap();
        for (&i, g) in m.iter().zip(smoothed) {
            out[i] = Some(g);
        }
    }
    out.into_iter().map(Option::unwrap).collect()
}

/// A wiggly grid with a lake whose island is its own feature, a road that
/// ends on a corner of the grid, and a road that runs along a grid border.
fn mosaic(nx: usize, ny: usize, m: usize, amp: f64, seed: u64) -> Vec<Geometry<f64>> {
    let mut gs = wiggly_grid(nx, ny, m, 0.1, amp, seed);
    let far = 10.0 + nx as f64;
    let island = vec![
        c(far + 1.0, 1.0),
        c(far + 1.6, 0.9),
        c(far + 2.0, 1.5),
        c(far + 1.5, 2.1),
        c(far + 0.9, 1.7),
        c(far + 1.0, 1.0),
    ];
    let shell = vec![
        c(far, 0.0),
        c(far + 3.0, 0.0),
        c(far + 3.0, 3.0),
        c(far, 3.0),
        c(far, 0.0),
    ];
    gs.push(poly(shell, vec![island.iter().rev().copied().collect()]));
    gs.push(poly(island, vec![]));
    // A road from the grid's origin corner out and away.
    gs.push(Geometry::LineString(LineString(vec![
        c(0.0, 0.0),
        c(-1.0, -0.5),
        c(-2.0, 0.2),
        c(-3.0, -0.4),
    ])));
    // A road along the bottom of the first cell, then away from the grid.
    let Geometry::Polygon(first) = &gs[0] else {
        unreachable!()
    };
    let ring = &first.exterior().0;
    let bottom: Vec<_> = ring
        .iter()
        .take_while(|p| p.y.abs() < 0.5 || p.x < 0.5)
        .take(m + 2)
        .copied()
        .chain([c(0.5, -2.0), c(1.5, -3.0)])
        .collect();
    gs.push(Geometry::LineString(LineString(bottom)));
    gs
}

#[test]
fn the_nodes_of_the_whole_change_nothing_for_the_whole() {
    let gs = mosaic(4, 3, 3, 0.1, 3);
    let opts = SmoothOptions::default();
    let (plain, _) = whole(&gs, &opts);
    let nodes = Nodes::of(&coverage_chains(&gs)).unwrap();
    let (given, _) = Coverage::with_nodes(gs.clone(), None, nodes)
        .and_then(|c| c.smooth(&opts))
        .unwrap();
    assert_eq!(plain, given);
}

#[test]
fn each_feature_in_its_own_part_smooths_as_the_whole() {
    let gs = mosaic(3, 3, 4, 0.1, 8);
    let opts = SmoothOptions::default();
    let (all, stats) = whole(&gs, &opts);
    assert_eq!(stats.refined_legs, 0, "{stats:?}");
    let alone: Vec<usize> = (0..gs.len()).collect();
    assert_eq!(by_parts(&gs, &alone, &opts), all);
    // Without the nodes the parts do not agree: each square is smoothed as
    // one closed curve and the shared borders part.
    let naive: Vec<Geometry<f64>> = gs
        .iter()
        .flat_map(|g| whole(std::slice::from_ref(g), &opts).0)
        .collect();
    assert_ne!(naive, all);
}

#[test]
fn the_order_of_the_features_does_not_matter() {
    let gs = mosaic(4, 4, 3, 0.1, 21);
    let opts = SmoothOptions::default().tolerance(1e-3);
    let (all, _) = whole(&gs, &opts);
    let mut order: Vec<usize> = (0..gs.len()).collect();
    order.reverse();
    order.swap(1, 5);
    let shuffled: Vec<Geometry<f64>> = order.iter().map(|&i| gs[i].clone()).collect();
    let (out, _) = whole(&shuffled, &opts);
    for (k, &i) in order.iter().enumerate() {
        assert_eq!(out[k], all[i], "feature {i}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn parts_smooth_as_the_whole(
        nx in 1usize..5,
        ny in 1usize..5,
        m in 0usize..5,
        amp in 0.0f64..0.1,
        seed in any::<u64>(),
        k in 1usize..5,
        assign in any::<u64>(),
        tol in prop::option::of(1e-4f64..1e-2),
        alpha in (1.0f64 / 3.0)..(2.0 / 3.0),
        keep in prop::option::of(10.0f64..90.0),
        through in any::<bool>(),
    ) {
        let gs = mosaic(nx, ny, m, amp, seed);
        let mut opts = SmoothOptions::default().alpha(alpha).through(through);
        if let Some(t) = tol {
            opts = opts.tolerance(t);
        }
        if let Some(a) = keep {
            opts = opts.keep_angle(a);
        }
        let (all, stats) = whole(&gs, &opts);
        // Refinement is decided within a part: exact when the whole needed
        // none.
        prop_assume!(stats.refined_legs == 0);
        let mut r = assign;
        let part: Vec<usize> = (0..gs.len())
            .map(|_| {
                r = r.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                ((r >> 33) % k as u64) as usize
            })
            .collect();
        prop_assert_eq!(by_parts(&gs, &part, &opts), all);
    }
}
