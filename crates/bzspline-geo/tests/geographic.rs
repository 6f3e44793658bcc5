//! Smoothing longitude and latitude with a tolerance in metres: one shape
//! defined in metres, placed at latitudes 0, 45, 70 and 85 and across the
//! antimeridian, comes out the same in its own metric frame wherever it is,
//! and as the same shape smoothed in the plane (the independent check: the
//! method on the metric coordinates themselves); lines across the
//! antimeridian stay near it, and rings round a pole stay round it.

use bzspline_geo::geodesy::{from_ecef, to_ecef};
use bzspline_geo::{smooth_line, Frame, SmoothOptions};

/// A point's metric frame: its ECEF position, east and north unit vectors.
struct Local {
    o: [f64; 3],
    e: [f64; 3],
    n: [f64; 3],
}

impl Local {
    fn at(lon: f64, lat: f64) -> Local {
        let (sl, cl) = lon.to_radians().sin_cos();
        let (sp, cp) = lat.to_radians().sin_cos();
        Local {
            o: to_ecef(lon, lat, 0.0),
            e: [-sl, cl, 0.0],
            n: [-sp * cl, -sp * sl, cp],
        }
    }

    /// East and north metres as longitude and latitude (on the ellipsoid
    /// below the tangent plane's point).
    fn to_lonlat(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        let p = std::array::from_fn(|i| self.o[i] + x * self.e[i] + y * self.n[i]);
        let (lon, lat, _) = from_ecef(p);
        [lon, lat]
    }

    /// Longitude and latitude as east and north metres.
    fn to_local(&self, [lon, lat]: [f64; 2]) -> [f64; 2] {
        let p = to_ecef(lon, lat, 0.0);
        let d: [f64; 3] = std::array::from_fn(|i| p[i] - self.o[i]);
        let dot = |u: [f64; 3]| d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
        [dot(self.e), dot(self.n)]
    }
}

/// A wavy ring about 5 km across, in metres.
fn shape() -> Vec<[f64; 2]> {
    (0..24)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::TAU / 24.0;
            let r = 2000.0 + 400.0 * (3.0 * t).sin() + 200.0 * (5.0 * t).cos();
            [r * t.cos(), r * t.sin()]
        })
        .collect()
}

fn flat(pts: &[[f64; 2]]) -> Vec<f64> {
    pts.iter().flatten().copied().collect()
}

fn pairs(v: &[f64]) -> Vec<[f64; 2]> {
    v.chunks_exact(2).map(|p| [p[0], p[1]]).collect()
}

/// The largest distance from a point of `a` to the polyline `b`.
fn farthest(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let seg = |p: [f64; 2], s: [f64; 2], t: [f64; 2]| {
        let (dx, dy) = (t[0] - s[0], t[1] - s[1]);
        let l2 = dx * dx + dy * dy;
        let u = if l2 > 0.0 {
            (((p[0] - s[0]) * dx + (p[1] - s[1]) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p[0] - s[0] - u * dx).hypot(p[1] - s[1] - u * dy)
    };
    a.iter()
        .map(|&p| {
            b.windows(2)
                .map(|w| seg(p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

fn hausdorff(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    farthest(a, b).max(farthest(b, a))
}

/// The shape placed at a point, smoothed there in metres, and carried back
/// to its metric frame.
fn smoothed_at(lon: f64, lat: f64, tolerance: f64) -> Vec<[f64; 2]> {
    let here = Local::at(lon, lat);
    let mut ring: Vec<[f64; 2]> = shape().into_iter().map(|p| here.to_lonlat(p)).collect();
    ring.push(ring[0]);
    let opts = SmoothOptions::default()
        .frame(Frame::Geographic)
        .tolerance(tolerance);
    let out = smooth_line(&flat(&ring), 2, true, &opts).unwrap();
    pairs(&out).into_iter().map(|p| here.to_local(p)).collect()
}

const PLACES: [(f64, f64); 6] = [
    (10.0, 0.0),
    (-73.0, 45.0),
    (25.0, 70.0),
    (140.0, 85.0),
    (180.0, -17.0),
    (-180.0, 65.0),
];

#[test]
fn a_shape_in_metres_comes_out_the_same_at_every_latitude() {
    let mut plane_ring = shape();
    plane_ring.push(plane_ring[0]);
    let fine = SmoothOptions::default().tolerance(0.01);
    let reference = pairs(&smooth_line(&flat(&plane_ring), 2, true, &fine).unwrap());
    let mut outs = Vec::new();
    for (lon, lat) in PLACES {
        let out = smoothed_at(lon, lat, 0.5);
        // The same shape smoothed in the plane, in metres: within the
        // tolerance, and the tangent plane's departure from the ellipsoid
        // (about 0.3 m at 2.5 km).
        let d = hausdorff(&out, &reference);
        assert!(d < 1.0, "at {lon}, {lat}: {d} m from the plane's curve");
        outs.push(out);
    }
    for (i, a) in outs.iter().enumerate() {
        for b in &outs[i + 1..] {
            assert!(hausdorff(a, b) < 2.0);
        }
    }
}

#[test]
fn the_tolerance_is_a_ground_distance_everywhere() {
    let mut plane_ring = shape();
    plane_ring.push(plane_ring[0]);
    let fine = SmoothOptions::default().tolerance(0.01);
    let curve = pairs(&smooth_line(&flat(&plane_ring), 2, true, &fine).unwrap());
    let mut counts = Vec::new();
    for (lon, lat) in PLACES {
        let out = smoothed_at(lon, lat, 20.0);
        // Every point of the (densely flattened) curve is within the
        // tolerance of the output, give or take the tangent plane's 0.3 m.
        let d = farthest(&curve, &out);
        assert!(
            d <= 20.5,
            "at {lon}, {lat}: the curve is {d} m from the output"
        );
        assert!(d > 5.0, "at {lon}, {lat}: {d} m: not flattened to 20 m");
        counts.push(out.len() as f64);
    }
    let (lo, hi) = counts
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &c| (l.min(c), h.max(c)));
    assert!(hi <= 1.1 * lo, "vertex counts {counts:?}");
}

#[test]
fn lines_across_the_antimeridian_stay_there() {
    let line = [
        178.0, 0.0, 179.0, 0.5, -179.5, 0.2, -178.0, 1.0, -177.0, 0.0,
    ];
    let opts = SmoothOptions::default()
        .frame(Frame::Geographic)
        .tolerance(100.0);
    let out = smooth_line(&line, 2, false, &opts).unwrap();
    assert!(out.len() > line.len());
    for p in out.chunks_exact(2) {
        assert!(p[0].abs() >= 176.9 && p[0].abs() <= 180.0, "{p:?}");
    }
    for w in pairs(&out).windows(2) {
        let d = (w[1][0] - w[0][0] + 540.0).rem_euclid(360.0) - 180.0;
        assert!(d.abs() < 1.0, "an edge of {d} degrees of longitude: {w:?}");
    }
    // The ends are the line's, exactly.
    assert_eq!(&out[..2], &line[..2]);
    assert_eq!(&out[out.len() - 2..], &line[line.len() - 2..]);
    // Longitudes written from 0 to 360 stay so.
    let positive: Vec<f64> = line
        .chunks_exact(2)
        .flat_map(|p| [p[0].rem_euclid(360.0), p[1]])
        .collect();
    let out = smooth_line(&positive, 2, false, &opts).unwrap();
    assert!(out.chunks_exact(2).all(|p| (176.9..=183.1).contains(&p[0])));
}

#[test]
fn a_ring_round_a_pole_stays_round_it() {
    let mut ring: Vec<f64> = (0..24)
        .flat_map(|k| [-180.0 + 15.0 * f64::from(k), 89.0])
        .collect();
    ring.extend_from_slice(&[-180.0, 89.0]);
    let opts = SmoothOptions::default()
        .frame(Frame::Geographic)
        .tolerance(10.0);
    let out = smooth_line(&ring, 2, true, &opts).unwrap();
    assert!(out.len() > ring.len());
    for p in out.chunks_exact(2) {
        assert!((88.99..89.2).contains(&p[1]), "{p:?}");
        assert!((-180.0..=180.0).contains(&p[0]), "{p:?}");
    }
    assert_eq!(&out[..2], &out[out.len() - 2..]);
}

#[test]
fn corners_are_kept_by_their_angle_on_the_ground() {
    // At every latitude and across the antimeridian: a leg due east, then
    // one turning left by 40 degrees on the ground (in degrees of longitude
    // and latitude the turn looks smaller the further from the equator).
    for (lon, lat) in [(10.0, 0.0), (10.0, 45.0), (10.0, 70.0), (179.99, 80.0)] {
        let local = Local::at(lon, lat);
        let turn = 40f64.to_radians();
        let metres = [
            [-3000.0, 0.0],
            [-1500.0, 40.0],
            [0.0, 0.0],
            [1500.0 * turn.cos(), 1500.0 * turn.sin()],
            [3000.0 * turn.cos(), 3000.0 * turn.sin() + 30.0],
        ];
        let line: Vec<f64> = metres.iter().flat_map(|&m| local.to_lonlat(m)).collect();
        let corner = [line[4], line[5]];
        let has_corner = |out: &[f64]| out.chunks_exact(2).any(|p| p == corner);
        let opts = SmoothOptions::default()
            .frame(Frame::Geographic)
            .tolerance(1.0);
        let kept = smooth_line(&line, 2, false, &opts.clone().keep_angle(30.0)).unwrap();
        assert!(
            has_corner(&kept),
            "at {lon}, {lat}: a 40-degree corner cut at keep_angle 30"
        );
        let cut = smooth_line(&line, 2, false, &opts.clone().keep_angle(50.0)).unwrap();
        assert!(
            !has_corner(&cut),
            "at {lon}, {lat}: a 40-degree corner kept at keep_angle 50"
        );
    }
}

#[test]
fn snapping_measures_on_the_ground() {
    use bzspline_geo::{snap, snap_in, ChainKind};
    use geo_types::Coord;
    // Degrees of a great circle per metre (the mean Earth radius).
    let deg = |m: f64| m / (6_371_008.8 * std::f64::consts::PI / 180.0);
    let lat: f64 = 70.0;
    let east = |m: f64| m / (6_371_008.8 * lat.to_radians().cos() * std::f64::consts::PI / 180.0);
    let c = |x: f64, y: f64| Coord { x, y };
    let ring = |pts: &[(f64, f64)]| {
        let mut v: Vec<Coord> = pts.iter().map(|&(x, y)| c(x, y)).collect();
        v.push(v[0]);
        (ChainKind::Ring, v)
    };
    // A square west of the meridian 10 E and one east of it whose shared
    // side was digitised twice: 2 m apart east-west at one corner, 4 m
    // north-south at the other; and a vertex of the second 2 m east of the
    // first's side, between its corners.
    let (x, d) = (10.0, deg(1000.0));
    let chains = vec![
        ring(&[
            (x - 2.0 * d, lat),
            (x, lat),
            (x, lat + d),
            (x - 2.0 * d, lat + d),
        ]),
        ring(&[
            (x + east(2.0), lat),
            (x + 2.0 * d, lat),
            (x + 2.0 * d, lat + d),
            (x, lat + d + deg(4.0)),
            (x + east(2.0), lat + 0.5 * d),
        ]),
    ];
    let mut ground = chains.clone();
    snap_in(&mut ground, deg(3.0), bzspline_geo::Frame::Geographic).unwrap();
    let b = &ground[1].1;
    assert_eq!(b[0], c(x, lat), "2 m east-west is within 3 m on the ground");
    assert_eq!(b[3], c(x, lat + d + deg(4.0)), "4 m north-south is not");
    // The first square's side gets the second's vertex 2 m east of it.
    assert!(
        ground[0].1.contains(&c(x + east(2.0), lat + 0.5 * d)),
        "{:?}",
        ground[0].1
    );
    // In degrees, 2 m east-west at 70 N is 5.8 m of latitude: not merged.
    let mut plane = chains.clone();
    snap(&mut plane, deg(3.0)).unwrap();
    assert_eq!(plane[1].1[0], c(x + east(2.0), lat));
}
