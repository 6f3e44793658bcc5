//! Throughput of construction and batch evaluation, printed as one JSON object.
//!
//! ```text
//! cargo run --release -p bzspline --example throughput -- --n 1000000 --m 10000000
//! cargo run --release -p bzspline --features rayon --example throughput -- --n 1000000 --m 10000000
//! ```
//!
//! Options: `--n` control points (default 1e6), `--m` sorted queries (default
//! 1e7), `--mr` random queries (default `min(m, 1e6)`), `--repeats` timed runs
//! per figure (default 7; the median is printed, after one warm-up run),
//! `--seed` for the data (default 1). Knots have random widths in `[0.5, 1.5)`,
//! values are a sine plus noise; sorted queries are evenly spaced over the
//! domain, random ones uniform.

mod common;

use bzspline::Bounds;
use bzspline::Flatten;
use std::hint::black_box;

use bzspline::{Alphas, Curve, CurveBuilder, Spline};
use common::{args_or_exit, f_median, median_ns, median_of, time_ns, Data, Rng};

/// Control points of the flattening benchmark's spiral.
const SPIRAL: usize = 100_000;

fn main() {
    let args = args_or_exit("throughput", 2, false);
    let (n, m, mr, r) = (args.n, args.m, args.mr, args.repeats);
    let mut rng = Rng::seeded(args.seed);
    let Data {
        knots,
        values,
        alphas,
        sorted,
        random,
    } = Data::new(&mut rng, n, m, mr);

    // A fresh build, page faults of its new allocations included; the release
    // of the previous spline's memory is not timed.
    let fresh_only = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || Spline::new(&knots, &values))
    };
    // The interpolating variant, fresh like the build above.
    let through_fresh = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || {
            Spline::through(&knots, &values, Alphas::default())
        })
    };
    // The same with one alpha per interval (random in range).
    let through_alphas_fresh = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || {
            Spline::through(&knots, &values, Alphas::PerInterval(&alphas))
        })
    };
    let mut s = match Spline::new(&knots, &values) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("throughput: {e}");
            std::process::exit(1);
        }
    };
    let reuse = median_ns(r, || {
        let res = s.rebuild(black_box(&knots), black_box(&values), Alphas::default());
        black_box(res.is_ok());
    });
    // The same rebuild on one thread: with the `rayon` feature a system of
    // more than 16,384 legs is solved in chunks on every core.
    let reuse_one = one_thread(|| {
        median_ns(r, || {
            let res = s.rebuild(black_box(&knots), black_box(&values), Alphas::default());
            black_box(res.is_ok());
        })
    });
    let per_interval = median_ns(r, || {
        let res = s.rebuild(&knots, &values, Alphas::PerInterval(&alphas));
        black_box(res.is_ok());
    });
    let res = s.rebuild(&knots, &values, Alphas::default());
    assert!(res.is_ok());

    // A planar curve through the same points (default parameters) and the
    // local re-solve after moving one point.
    let pts: Vec<[f64; 2]> = knots.iter().zip(&values).map(|(x, y)| [*x, *y]).collect();
    let curve_build = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || Curve::open(&pts))
    };
    // The interpolating variant of the same curve, fresh.
    let flat: Vec<f64> = pts.iter().flatten().copied().collect();
    let curve_through = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || {
            CurveBuilder::new(&flat, 2).through(true).build()
        })
    };
    // The same curve built again into its own allocations, as `rebuild` does
    // for the spline.
    let curve_rebuild = rebuild_ns(r, &pts, false);
    // The same points closed into a ring, fresh and built again.
    let closed_build = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || Curve::closed(&pts))
    };
    let closed_rebuild = rebuild_ns(r, &pts, true);
    // Flattening as the target states it: a 1e5-point planar curve (a jittered
    // spiral of 100 turns) to a tolerance of 1e-3 of its size (the diagonal of
    // its bounding box), against building the same curve.
    let spiral = common::spiral(&mut rng, SPIRAL);
    let spiral_build = {
        let mut keep = Vec::new();
        f_median(r, &mut keep, || Curve::open(&spiral))
    };
    // Built again into its own allocations: the build without page faults,
    // the stricter measure to hold the flattening against.
    let spiral_rebuild = rebuild_ns(r, &spiral, false);
    let (spiral_flatten, spiral_vertices) = match Curve::open(&spiral) {
        Ok(c) => {
            let b = c.bbox();
            let size = (b.max[0] - b.min[0]).hypot(b.max[1] - b.min[1]);
            let mut verts = 0;
            let ns = median_ns(r, || {
                verts = black_box(c.flatten(1e-3 * size).map(|p| p.len()).unwrap_or(0));
            });
            (ns, verts)
        }
        Err(_) => (f64::NAN, 0),
    };
    let curve_move = match Curve::open(&pts) {
        Ok(mut c) => {
            let mid = n / 2;
            let mut up = false;
            median_ns(r, || {
                up = !up;
                let y = values[mid] + if up { 1.0 } else { 0.0 };
                black_box(
                    c.move_point(mid, &[knots[mid], y], 1e-12)
                        .map(|v| v.len())
                        .unwrap_or(0),
                );
            })
        }
        Err(_) => f64::NAN,
    };

    let mut out = vec![0.0; m.max(mr)];
    // A random-order batch right after a rebuild: the first large one forms
    // the search index that later ones reuse.
    let random_first = {
        let o = &mut out[..random.len()];
        let ns = median_of(r, || {
            let res = s.rebuild(black_box(&knots), black_box(&values), Alphas::default());
            assert!(res.is_ok());
            time_ns(|| {
                assert!(s.deriv_many(&random, 0, o).is_ok());
                black_box(&o);
            })
        });
        ns / random.len().max(1) as f64
    };
    let mut time_eval = |qs: &[f64], order: u32, par: bool| -> f64 {
        let o = &mut out[..qs.len()];
        let ns = median_ns(r, || {
            let res = if par {
                par_deriv(&s, qs, order, o)
            } else {
                s.deriv_many(qs, order, o)
            };
            assert!(res.is_ok());
            black_box(&o);
        });
        ns / qs.len().max(1) as f64
    };
    let sorted0 = time_eval(&sorted, 0, false);
    let sorted1 = time_eval(&sorted, 1, false);
    let sorted2 = time_eval(&sorted, 2, false);
    let random0 = time_eval(&random, 0, false);
    let random1 = time_eval(&random, 1, false);
    let par = cfg!(feature = "rayon");
    let (psorted, prandom) = if par {
        (time_eval(&sorted, 0, true), time_eval(&random, 0, true))
    } else {
        (f64::NAN, f64::NAN)
    };
    // Into a new vector each time, as a caller without a buffer does (and
    // Python's `s(x)`, which returns a new array): its page faults and its
    // release included.
    let time_new = |qs: &[f64], order: u32| -> f64 {
        let ns = median_ns(r, || {
            let mut o = vec![0.0; qs.len()];
            assert!(s.deriv_many(qs, order, &mut o).is_ok());
            black_box(&o);
        });
        ns / qs.len().max(1) as f64
    };
    let sorted0_new = time_new(&sorted, 0);
    let sorted1_new = time_new(&sorted, 1);
    // What a spline built with one alpha holds once a random-order batch has
    // formed the index of its search summary.
    let bytes = Spline::new(&knots, &values).map_or(0, |h| {
        let o = &mut out[..random.len()];
        assert!(h.deriv_many(&random, 0, o).is_ok());
        h.heap_bytes()
    });
    let num = |v: f64| {
        if v.is_finite() {
            format!("{v:.3}")
        } else {
            "null".to_string()
        }
    };
    println!(
        "{{\"n\": {n}, \"m\": {m}, \"m_random\": {mr}, \"repeats\": {r}, \
         \"construct_ns_per_point\": {}, \"construct_one_thread_ns_per_point\": {}, \
         \"construct_fresh_ns_per_point\": {}, \
         \"construct_per_interval_alphas_ns_per_point\": {}, \
         \"construct_through_fresh_ns_per_point\": {}, \
         \"construct_through_alphas_fresh_ns_per_point\": {}, \
         \"eval_sorted_ns_per_point\": {}, \"eval_sorted_new_ns_per_point\": {}, \
         \"eval_random_ns_per_point\": {}, \
         \"eval_random_first_ns_per_point\": {}, \
         \"deriv1_sorted_ns_per_point\": {}, \"deriv1_sorted_new_ns_per_point\": {}, \
         \"deriv2_sorted_ns_per_point\": {}, \
         \"deriv1_random_ns_per_point\": {}, \
         \"par_threads\": {}, \"par_eval_sorted_ns_per_point\": {}, \
         \"par_eval_random_ns_per_point\": {}, \"bytes_per_point\": {}, \
         \"curve2d_construct_ns_per_point\": {}, \"curve2d_rebuild_ns_per_point\": {}, \
         \"curve2d_through_ns_per_point\": {}, \
         \"curve2d_move_point_ns\": {}, \
         \"closed2d_construct_ns_per_point\": {}, \"closed2d_rebuild_ns_per_point\": {}, \
         \"spiral_1e5_construct_ns_per_point\": {}, \"spiral_1e5_rebuild_ns_per_point\": {}, \
         \"spiral_1e5_flatten_ns_per_point\": {}, \"spiral_1e5_flatten_vertices\": {}}}",
        num(reuse / n as f64),
        num(reuse_one / n as f64),
        num(fresh_only / n as f64),
        num(per_interval / n as f64),
        num(through_fresh / n as f64),
        num(through_alphas_fresh / n as f64),
        num(sorted0),
        num(sorted0_new),
        num(random0),
        num(random_first),
        num(sorted1),
        num(sorted1_new),
        num(sorted2),
        num(random1),
        threads(),
        num(psorted),
        num(prandom),
        num(bytes as f64 / n as f64),
        num(curve_build / n as f64),
        num(curve_rebuild / n as f64),
        num(curve_through / n as f64),
        num(curve_move),
        num(closed_build / n as f64),
        num(closed_rebuild / n as f64),
        num(spiral_build / SPIRAL as f64),
        num(spiral_rebuild / SPIRAL as f64),
        num(spiral_flatten / SPIRAL as f64),
        spiral_vertices,
    );
}

/// Median time of building the planar curve on `pts` (open, or `closed`
/// into a ring) again into its own allocations (`CurveBuilder::build_into`);
/// NaN when it cannot be built.
fn rebuild_ns(repeats: usize, pts: &[[f64; 2]], closed: bool) -> f64 {
    let built = if closed {
        Curve::closed(pts)
    } else {
        Curve::open(pts)
    };
    match built {
        Ok(mut c) => {
            let flat = pts.as_flattened();
            median_ns(repeats, || {
                let res = CurveBuilder::new(black_box(flat), 2)
                    .closed(closed)
                    .build_into(&mut c);
                black_box(res.is_ok());
            })
        }
        Err(_) => f64::NAN,
    }
}

#[cfg(feature = "rayon")]
fn par_deriv(s: &Spline, xs: &[f64], order: u32, out: &mut [f64]) -> Result<(), bzspline::Error> {
    s.par_deriv_many(xs, order, out)
}

#[cfg(not(feature = "rayon"))]
fn par_deriv(s: &Spline, xs: &[f64], order: u32, out: &mut [f64]) -> Result<(), bzspline::Error> {
    s.deriv_many(xs, order, out)
}

#[cfg(feature = "rayon")]
fn one_thread<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
        Ok(pool) => pool.install(f),
        Err(_) => f(),
    }
}

#[cfg(not(feature = "rayon"))]
fn one_thread<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(feature = "rayon")]
fn threads() -> usize {
    rayon::current_num_threads()
}

#[cfg(not(feature = "rayon"))]
fn threads() -> usize {
    1
}
