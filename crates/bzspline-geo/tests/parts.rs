//! Parts of a coverage smoothed alone, each with the nodes of the whole
//! (`bzspline_geo::parts`), against the whole coverage smoothed at once:
//! every feature must come out the same, bit for bit.

use bzspline_geo::parts::{across, chains_extent, meetings};
use bzspline_geo::Nodes;
use bzspline_geo::{coverage_chains, parts, Coverage, SmoothOptions, Stats};
use bzspline_testing::*;
use geo_types::{Geometry, LineString};
use proptest::prelude::*;

fn whole(gs: &[Geometry<f64>], opts: &SmoothOptions) -> (Vec<Geometry<f64>>, Stats) {
    Coverage::new(gs.to_vec())
        .and_then(|c| c.smooth(opts))
        .unwrap_or_else(|e| panic!("smoothing failed: {e}"))
}

/// Smooths the features of each part alone, with the nodes found across the
/// parts, and puts the results back in the features' order.
fn by_parts(gs: &[Geometry<f64>], part: &[usize], opts: &SmoothOptions) -> Vec<Geometry<f64>> {
    by_parts_with(gs, part, opts, false)
}

/// [`by_parts`], each part also holding, with `context`, the features of the
/// other parts that meet its extent (their results are not kept).
fn by_parts_with(
    gs: &[Geometry<f64>],
    part: &[usize],
    opts: &SmoothOptions,
    context: bool,
) -> Vec<Geometry<f64>> {
    let k = part.iter().max().map_or(0, |&p| p + 1);
    let members: Vec<Vec<usize>> = (0..k)
        .map(|p| {
            let own = (0..gs.len()).filter(|&i| part[i] == p);
            if context {
                own.chain(self::context(gs, part, p)).collect()
            } else {
                own.collect()
            }
        })
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
    if let Some(e) = chains_extent(&coverage_chains(gs)) {
        nodes = nodes.with_extent(e);
    }
    let mut out: Vec<Option<Geometry<f64>>> = vec![None; gs.len()];
    for (p, (m, piece)) in members.iter().zip(pieces).enumerate() {
        let (smoothed, _) = Coverage::builder(piece)
            .nodes(nodes.clone())
            .build()
            .and_then(|c| c.smooth(opts))
            .unwrap();
        for (&i, g) in m.iter().zip(smoothed) {
            if part[i] == p {
                out[i] = Some(g);
            }
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
    let (given, _) = Coverage::builder(gs.clone())
        .nodes(nodes)
        .build()
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

/// `n` features spread over `k` parts by a generator seeded with `seed`.
fn assignment(n: usize, k: usize, seed: u64) -> Vec<usize> {
    let mut r = seed;
    (0..n)
        .map(|_| {
            r = r
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((r >> 33) % k as u64) as usize
        })
        .collect()
}

#[test]
fn a_straight_border_needs_the_ring_across_it() {
    // The right cell's ring is two arcs, so the straight border it shares
    // with the middle cell keeps a middle position (a ring keeps three). A
    // part holding the middle cell but not the right one cannot know that;
    // with the features that meet its extent (as the dask path gives it) it
    // does. Found by `parts_smooth_as_the_whole`.
    let gs = mosaic(3, 1, 1, 0.0, 0);
    let opts = SmoothOptions::default().alpha(0.6028196406433045);
    let (all, stats) = whole(&gs, &opts);
    assert_eq!(stats.refined_legs, 0);
    let part = assignment(gs.len(), 2, 3620978368066230401);
    assert_ne!(by_parts(&gs, &part, &opts), all);
    assert_eq!(by_parts_with(&gs, &part, &opts, true), all);
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
        let part = assignment(gs.len(), k, assign);
        prop_assert_eq!(by_parts_with(&gs, &part, &opts, true), all);
    }
}

/// What part `p` holds by the parts protocol ([`parts::holdings`]).
fn holding(gs: &[Geometry<f64>], part: &[usize], p: usize) -> parts::Holding {
    use geo::BoundingRect;
    let boxes: Vec<_> = gs.iter().map(BoundingRect::bounding_rect).collect();
    parts::holdings(&boxes, part, p)
}

/// The features of the other parts whose bounding box meets part `p`'s
/// extent: all that can come near what part `p` holds.
fn context(gs: &[Geometry<f64>], part: &[usize], p: usize) -> Vec<usize> {
    holding(gs, part, p).context
}

/// Smooths each part by the parts protocol ([`parts`]): with its context
/// (held exactly), the features around (for the context's topology) and the
/// whole's nodes, a round of conflict search at a time
/// ([`Coverage::smooth_round`]), every part from the levels all of them ended
/// the round before at ([`parts::Rounds`]), until no part raises any;
/// returns the features in their order and how many rounds it took.
fn by_parts_agreeing(
    gs: &[Geometry<f64>],
    part: &[usize],
    opts: &SmoothOptions,
) -> (Vec<Geometry<f64>>, usize) {
    let k = part.iter().max().map_or(0, |&p| p + 1);
    let nodes = Nodes::of(&coverage_chains(gs)).unwrap();
    let holdings: Vec<parts::Holding> = (0..k).map(|p| holding(gs, part, p)).collect();
    let mut rounds = parts::Rounds::new();
    loop {
        let mut out: Vec<Option<Geometry<f64>>> = vec![None; gs.len()];
        let mut ended = Vec::with_capacity(k);
        for h in &holdings {
            let held = h.held();
            let cov = Coverage::builder(held.iter().map(|&i| gs[i].clone()))
                .nodes(nodes.clone())
                .build()
                .unwrap();
            let (smoothed, _, levels) = cov
                .smooth_round(opts, rounds.levels(), rounds.round(), &h.exact())
                .unwrap();
            ended.push(levels);
            for (&i, g) in h.own.iter().zip(smoothed) {
                out[i] = Some(g);
            }
        }
        let round = rounds.round();
        if !rounds.finish(&ended).unwrap() {
            return (out.into_iter().map(Option::unwrap).collect(), round);
        }
    }
}

/// Checks that features of different parts share their borders exactly, and
/// that nothing crosses.
fn check_parts(input: &[Geometry<f64>], out: &[Geometry<f64>]) {
    for (a, b) in neighbours(input) {
        share_border(&out[a], &out[b]).unwrap_or_else(|e| panic!("neighbours {a} and {b}: {e}"));
    }
    assert_eq!(brute_force_crossings(out), 0, "segments cross");
    valid_stays_valid(input, out).unwrap_or_else(|e| panic!("{e}"));
}

/// An L-shaped polygon with its inner corner at `(x, 0)`, a road along the
/// two edges of its notch, and a square in the notch, `gap` from the corner
/// and `size` wide: the corner's curve cuts the square unless refined when
/// the gap is small.
fn notch(x: f64, gap: f64, size: f64) -> Vec<Geometry<f64>> {
    let l_shape = poly(
        vec![
            c(x - 1.0, -1.0),
            c(x + 3.0, -1.0),
            c(x + 3.0, 0.0),
            c(x + 1.5, 0.0),
            c(x, 0.0),
            c(x, 1.5),
            c(x, 3.0),
            c(x - 1.0, 3.0),
            c(x - 1.0, -1.0),
        ],
        vec![],
    );
    let road = Geometry::LineString(LineString(vec![c(x + 1.5, 0.0), c(x, 0.0), c(x, 1.5)]));
    let (a, b) = (x + gap, x + gap + size);
    let (lo, hi) = (gap, gap + size);
    let square = poly(
        vec![c(a, lo), c(b, lo), c(b, hi), c(a, hi), c(a, lo)],
        vec![],
    );
    vec![l_shape, road, square]
}

#[test]
fn parts_that_refine_smooth_as_the_whole() {
    // An L-shaped polygon, a road along the two edges of its notch, and a
    // square in the notch, each in a part of its own: the corner's curve,
    // which the polygon and the road share, cuts through the square unless
    // refined, which only a part that sees the square can tell.
    let gs = notch(1.0, 0.05, 0.55);
    let opts = SmoothOptions::default().tolerance(1e-3);
    let (all, stats) = whole(&gs, &opts);
    assert!(
        stats.refined_legs > 0,
        "the case needs no refinement: {stats:?}"
    );
    check_parts(&gs, &all);
    // Parts without each other's context cross.
    let alone = by_parts(&gs, &[0, 1, 2], &opts);
    assert!(
        brute_force_crossings(&alone) > 0,
        "the parts alone do not cross"
    );
    let (agreed, rounds) = by_parts_agreeing(&gs, &[0, 1, 2], &opts);
    assert!(rounds >= 2, "{rounds} rounds");
    assert_eq!(rounds, stats.rounds, "rounds of the whole");
    check_parts(&gs, &agreed);
    assert_eq!(agreed, all, "the parts differ from the whole");
    // The road, smoothed in its own part, is the polygon's smoothed stretch.
    let shell = polygons(&agreed[0]);
    let ring = &shell[0].exterior().0;
    let Geometry::LineString(road) = &agreed[1] else {
        unreachable!()
    };
    assert!(road.0.len() > 3);
    assert!(
        road.0.iter().all(|p| ring.contains(p)),
        "the road left the border"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Going through the rounds of conflict search together, parts come out
    /// as the whole, refined or not: every border shared, nothing crossing.
    #[test]
    fn parts_going_round_by_round_smooth_as_the_whole(
        nx in 1usize..5,
        ny in 1usize..4,
        m in 0usize..5,
        amp in 0.0f64..0.14,
        seed in any::<u64>(),
        k in 2usize..5,
        tol_exp in -3i32..-1,
        gap in 0.005f64..0.2,
        size in 0.1f64..0.8,
    ) {
        // With notches that need refinement when their gap is small.
        let mut gs = mosaic(nx, ny, m, amp, seed);
        gs.extend(notch(-10.0, gap, size));
        gs.extend(notch(-20.0, gap * 2.0, size * 0.5));
        let opts = SmoothOptions::default().tolerance(10f64.powi(tol_exp));
        let part: Vec<usize> = (0..gs.len()).map(|i| i * k / gs.len()).collect();
        let (agreed, rounds) = by_parts_agreeing(&gs, &part, &opts);
        check_parts(&gs, &agreed);
        let (all, stats) = whole(&gs, &opts);
        prop_assert_eq!(rounds, stats.rounds);
        prop_assert_eq!(agreed, all);
    }
}
