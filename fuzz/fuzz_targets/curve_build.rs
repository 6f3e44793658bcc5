//! Building an open or closed curve in 1 to 3 dimensions from arbitrary
//! points, parameters and alphas, then asking it geometry questions. Refusals
//! are typed errors, never panics; an accepted curve passes through its end
//! points (open), is C1 and tangent to every leg and stays in the box of its
//! control points, and every query answers a finite number or an error.
#![no_main]

use bzspline::Arclen;
use bzspline::Bounds;
use bzspline::Flatten;
use bzspline::ParamCurve;
use bzspline::{Curve, CurveBuilder, Param, Repeats, ALPHA_MAX, ALPHA_MIN};
use bzspline_fuzz::Reader;
use libfuzzer_sys::fuzz_target;

/// Relative tolerance of the loose checks.
const REL: f64 = 1e-8;

fuzz_target!(|bytes: &[u8]| {
    let mut r = Reader::new(bytes);
    let flags = r.u8();
    let dim = match flags % 16 {
        0 => 0,
        1 => 4,
        f => usize::from(f % 3) + 1,
    };
    // Up to 32 points, or up to 256 in steps of 8 (rings long enough for
    // the open sweeps, from 48 points).
    let n = usize::from(r.u8() % 33) * if flags & 0x40 != 0 { 8 } else { 1 };
    let magnitude = r.pow10(-300, 300);
    let mut points = Vec::with_capacity(n * dim.max(1));
    for i in 0..n * dim.max(1) {
        // Now and then a point repeating the previous one.
        let v = if i >= dim && dim > 0 && r.u8().is_multiple_of(16) {
            points[i - dim]
        } else {
            r.value(magnitude)
        };
        points.push(v);
    }
    if flags & 0x80 != 0 {
        points.push(r.unit()); // a count that is not a multiple of dim
    }
    let closed = flags & 0x10 != 0;
    let param = match r.u8() % 5 {
        0 => Param::Uniform,
        1 => Param::Chordal,
        2 => Param::Centripetal,
        _ => {
            let count = n + usize::from(closed) + usize::from(r.u8().is_multiple_of(4));
            let mut x = r.unit() * magnitude;
            let mut given = Vec::with_capacity(count);
            for _ in 0..count {
                given.push(x);
                x += (1.0 + f64::from(r.u8())) / 256.0 * r.pow10(-6, 6) * magnitude;
                if r.u8() == 0 {
                    x = r.raw_f64();
                }
            }
            Param::Given(given)
        }
    };
    let legs = if closed { n } else { n.saturating_sub(1) };
    let mut b = CurveBuilder::new(&points, dim)
        .closed(closed)
        .param(param)
        .repeats(if flags & 0x20 != 0 {
            Repeats::Drop
        } else {
            Repeats::Reject
        });
    b = match r.u8() % 4 {
        0 => b.alpha(r.alpha()),
        1 => b.alphas(
            &(0..legs + usize::from(r.u8().is_multiple_of(8)))
                .map(|_| r.alpha())
                .collect::<Vec<_>>(),
        ),
        _ => b,
    };
    if std::env::var_os("FUZZ_DEBUG").is_some() {
        eprintln!("{b:?}");
    }
    let Ok(c) = b.build() else {
        return;
    };
    check(&c, &mut r);
});

fn check(c: &Curve, r: &mut Reader<'_>) {
    let dim = c.dim();
    assert!(dim >= 1 && !c.is_empty());
    assert!(c
        .alphas()
        .iter()
        .all(|a| (ALPHA_MIN..=ALPHA_MAX).contains(a)));
    assert!(
        c.knots().windows(2).all(|w| w[0] < w[1]),
        "knots {:?}",
        c.knots()
    );
    let pts = c.points();
    assert!(pts.iter().all(|v| v.is_finite()));
    let np = c.point_count();
    // The box of the control points, and the scale of the checks.
    let mut lo = vec![f64::INFINITY; dim];
    let mut hi = vec![f64::NEG_INFINITY; dim];
    for p in pts.chunks(dim) {
        for (j, &v) in p.iter().enumerate() {
            lo[j] = lo[j].min(v);
            hi[j] = hi[j].max(v);
        }
    }
    let m = pts.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
    let tol = REL * m;
    let inside = |p: &[f64], what: &str| {
        for j in 0..dim {
            assert!(
                p[j].is_finite() && p[j] >= lo[j] - tol && p[j] <= hi[j] + tol,
                "{what}: coordinate {j} = {} outside [{}, {}]",
                p[j],
                lo[j],
                hi[j]
            );
        }
    };
    let (a, b) = c.domain();
    if !c.is_closed() {
        let p0 = c.eval(a).expect("start of the domain");
        let p1 = c.eval(b).expect("end of the domain");
        for j in 0..dim {
            assert!(
                (p0[j] - pts[j]).abs() <= tol,
                "start {p0:?} vs {:?}",
                &pts[..dim]
            );
            assert!((p1[j] - pts[(np - 1) * dim + j]).abs() <= tol, "end {p1:?}");
        }
    }
    // Tangency: the curve passes through each tangent point (loosely: the
    // parameter is rounded; see spline_build for the slack).
    for (k, (s, p)) in c.tangent_points().into_iter().enumerate() {
        assert!(s.is_finite() && p.iter().all(|v| v.is_finite()));
        let h = c.knots()[k + 1] - c.knots()[k];
        let ulp = (f64::EPSILON * s.abs()).max(f64::from_bits(1));
        let slack = tol + m * (4.0 * ulp / h) * 16.0;
        let q = c.eval(s).expect("tangent parameter inside the domain");
        for j in 0..dim {
            assert!(
                (q[j] - p[j]).abs() <= slack,
                "leg {k}: C({s}) = {q:?}, tangent point {p:?}"
            );
        }
    }
    // C1 through the Bezier control points, and the hull.
    let segs: Vec<Vec<f64>> = (0..c.len()).filter_map(|k| c.segment_points(k)).collect();
    assert_eq!(segs.len(), c.len());
    // Interior Bezier control points lie outside the hull and can exceed the
    // range of a double when the points are near it (to_svg_path then refuses).
    let all_finite = segs.iter().flatten().all(|v| v.is_finite());
    assert!(
        all_finite || m > f64::MAX / 64.0,
        "non-finite control point at scale {m}"
    );
    for (k, s) in segs.iter().enumerate() {
        inside(&s[..dim], "segment start");
        inside(&s[3 * dim..], "segment end");
        if !all_finite {
            continue;
        }
        let prev = if k > 0 {
            Some(k - 1)
        } else if c.is_closed() {
            Some(c.len() - 1)
        } else {
            None
        };
        if let Some(p) = prev {
            let knots = c.knots();
            let hl = knots[p + 1] - knots[p];
            let hr = knots[k + 1] - knots[k];
            let hmin = hl.min(hr);
            for j in 0..dim {
                let l = &segs[p];
                assert!((l[3 * dim + j] - s[j]).abs() <= tol, "C jumps at knot {k}");
                // Derivative times the narrower width: 3 (P3 - P2) hmin / hl.
                let dl = (l[3 * dim + j] - l[2 * dim + j]) * (hmin / hl);
                let dr = (s[dim + j] - s[j]) * (hmin / hr);
                assert!(
                    (dl - dr).abs() <= tol * 4.0,
                    "C' jumps at knot {k}, coordinate {j}: {dl} vs {dr}"
                );
            }
        }
    }
    let bb = c.bbox();
    inside(&bb.min, "bbox min");
    inside(&bb.max, "bbox max");
    for i in 0..=16 {
        let s = (a + (b - a) * f64::from(i) / 16.0).clamp(a, b);
        let p = c.eval(s).expect("inside the domain");
        inside(&p, "sample");
        for order in 1..4 {
            if let Ok(d) = c.deriv(s, order) {
                assert!(d.iter().all(|v| v.is_finite()), "C^({order})({s}) = {d:?}");
            }
        }
        for v in [c.tangent(s), c.normal(s)].into_iter().flatten() {
            assert!(v.iter().all(|v| v.is_finite()));
        }
        if let Ok(k) = c.curvature(s) {
            assert!(k.is_finite());
        }
    }
    // Queries at arbitrary parameters and points.
    let q = r.raw_f64();
    if let Ok(p) = c.eval(q) {
        assert!(p.iter().all(|v| v.is_finite()), "C({q}) = {p:?}");
    }
    let query: Vec<f64> = (0..dim)
        .map(|j| {
            if r.u8().is_multiple_of(4) {
                r.raw_f64()
            } else {
                lo[j] + (hi[j] - lo[j]) * r.unit()
            }
        })
        .collect();
    if let Ok(nr) = c.nearest(&query) {
        assert!(nr.param.is_finite() && nr.distance.is_finite() && nr.distance >= 0.0);
        inside(&nr.point, "nearest");
    }
    // Lengths and polylines at accuracies from 1e-2 to 1e-6 of the size (finer
    // ones are valid but slow to fuzz), and refused raw accuracies.
    let size = (0..dim).map(|j| hi[j] - lo[j]).fold(0.0, f64::max);
    let rel = r.pow10(-6, -2);
    if size.is_finite() && size > 0.0 {
        let acc = size * rel;
        if let Ok(l) = c.arclen(acc) {
            assert!(l.is_finite() && l >= 0.0, "length {l}");
        }
        if let Ok(p) = c.flatten(acc) {
            assert!(p.coords().iter().all(|v| v.is_finite()));
            assert!(p.len() >= 2);
        }
    }
    let raw = r.raw_f64();
    if raw.is_nan() || raw <= 0.0 {
        assert!(c.arclen(raw).is_err(), "accuracy {raw} accepted");
        assert!(c.flatten(raw).is_err(), "tolerance {raw} accepted");
    }
    if let Ok(p) = c.sample(usize::from(r.u8() % 64)) {
        assert!(p.coords().iter().all(|v| v.is_finite()));
    }
    if let Ok(svg) = c.to_svg_path() {
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
    }
    // Moving a point leaves a valid curve.
    let mut moved = c.clone();
    let idx = usize::from(r.u8()) % (np + 1);
    let to: Vec<f64> = (0..dim).map(|_| r.value(m)).collect();
    if moved.move_point(idx, &to, tol).is_ok() {
        let (a, b) = moved.domain();
        for s in [a, (a + b) / 2.0, b] {
            let p = moved.eval(s.clamp(a, b)).expect("inside the domain");
            assert!(p.iter().all(|v| v.is_finite()));
        }
    }
}
