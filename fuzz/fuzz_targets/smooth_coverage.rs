//! Generated coverages (`bzspline_fuzz::mosaic`) smoothed as one coverage,
//! with what the README promises asserted by judges that do not use the code
//! under test: no panic and no error; every ring closed with at least 4
//! positions; without snapping, a valid polygon stays valid (geo), two
//! polygons that shared an edge still share one (and, valid and touching
//! before, only touch after), and no pair of edges crosses or meets that did
//! not in the input (brute force over every pair).
#![no_main]

use bzspline_fuzz::judge::{
    brute_force_crossings, neighbours, polygons, share_border, share_segment, valid_stays_valid,
};
use bzspline_fuzz::mosaic::{self, geo_map};
use bzspline_geo::Coverage;
use geo::{Relate, Validation};
use geo_types::Geometry;
use libfuzzer_sys::arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let mut u = Unstructured::new(bytes);
    let Ok(case) = mosaic::case(&mut u) else {
        return;
    };
    let coverage = Coverage::builder(case.geometries.clone())
        .snap(case.snap)
        .build()
        .unwrap_or_else(|e| panic!("refused: {e}"));
    let (out, _) = coverage
        .smooth(&case.opts)
        .unwrap_or_else(|e| panic!("smoothing failed: {}", coverage.describe(&e)));
    assert_eq!(out.len(), case.geometries.len());
    for (gi, g) in out.iter().enumerate() {
        for p in polygons(g) {
            for r in std::iter::once(p.exterior()).chain(p.interiors()) {
                let n = r.0.len();
                assert!(
                    n >= 4 && r.0[0] == r.0[n - 1],
                    "geometry {gi}: a ring of {n} positions, or not closed"
                );
                assert!(r.0.iter().all(|c| c.x.is_finite() && c.y.is_finite()));
            }
        }
    }
    if case.snap.is_some() {
        return;
    }
    // Judged unscaled: dividing by a power of two is exact.
    let s = 2f64.powi(-case.exponent);
    let unscale = |gs: &[Geometry<f64>]| -> Vec<Geometry<f64>> {
        gs.iter()
            .cloned()
            .map(|mut g| {
                geo_map(&mut g, &|p| {
                    p.x *= s;
                    p.y *= s;
                });
                g
            })
            .collect()
    };
    let (input, out) = (unscale(&case.geometries), unscale(&out));
    valid_stays_valid(&input, &out).unwrap_or_else(|e| panic!("{e}"));
    for (a, b) in neighbours(&input) {
        let valid = |g: &Geometry<f64>| polygons(g).iter().all(Validation::is_valid);
        if valid(&input[a]) && valid(&input[b]) && input[a].relate(&input[b]).is_touches() {
            share_border(&out[a], &out[b]).unwrap_or_else(|e| panic!("{a} and {b}: {e}"));
        } else {
            share_segment(&out[a], &out[b]).unwrap_or_else(|e| panic!("{a} and {b}: {e}"));
        }
    }
    let (before, after) = (brute_force_crossings(&input), brute_force_crossings(&out));
    assert!(
        after <= before,
        "{before} pairs of edges met before, {after} after"
    );
});
