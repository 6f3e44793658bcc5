//! One workload repeated R times, for instruction counts under callgrind: the
//! count of a run with 13 repetitions less that of a run with 3, divided by 10
//! and by the points or queries of one repetition, is the cost per point or
//! query without the set-up.
//!
//! ```text
//! cargo build --release -p bzspline --example instructions
//! for r in 3 13; do
//!   valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!     target/release/examples/instructions build $r 2>&1 | grep Collected
//! done
//! ```
//!
//! Workloads (N = 10^5 control points; knots with random widths in
//! `[0.5, 1.5)`, values a sine plus noise, as in the `throughput` example):
//! `build` (rebuild with one alpha), `build_alphas` (one alpha per interval),
//! `through` (the interpolating variant, fresh), `sorted` and `random`
//! (10^6 batch queries), `curve` (a planar curve rebuilt into its own
//! allocations), `closed` (the same points closed into a ring, rebuilt the
//! same way), `flatten` (a 10^5-point spiral to 1e-3 of its size), `ceval`
//! (10^6 single `Curve::eval_into` in order), `seval` (10^5 single
//! `Spline::eval` in random order). It prints the divisor to use.

#[allow(dead_code)] // the timing helpers the other examples use
mod common;

use bzspline::Bounds;
use bzspline::Flatten;
use bzspline::ParamCurve;
use std::hint::black_box;

use bzspline::{Alphas, Curve, CurveBuilder, Spline};
use common::{Data, Rng};

const N: usize = 100_000;
const M: usize = 1_000_000;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(mode), Some(Ok(r))) = (args.get(1), args.get(2).map(|r| r.parse::<usize>())) else {
        eprintln!("usage: instructions WORKLOAD REPEATS (see the source for the workloads)");
        std::process::exit(2);
    };
    let mut rng = Rng::seeded(1);
    let Data {
        knots,
        values,
        alphas,
        sorted,
        random,
    } = Data::new(&mut rng, N, M, M);
    let pts: Vec<[f64; 2]> = knots.iter().zip(&values).map(|(x, y)| [*x, *y]).collect();
    let spiral = common::spiral(&mut rng, N);
    let (Ok(mut s), Ok(mut c), Ok(mut cc), Ok(sc)) = (
        Spline::new(&knots, &values),
        Curve::open(&pts),
        Curve::closed(&pts),
        Curve::open(&spiral),
    ) else {
        eprintln!("instructions: the data did not build");
        std::process::exit(1);
    };
    let b = sc.bbox();
    let size = (b.max[0] - b.min[0]).hypot(b.max[1] - b.min[1]);
    let mut out = vec![0.0; M];
    let per = match mode.as_str() {
        "sorted" | "random" | "ceval" => M,
        _ => N,
    };
    for _ in 0..r {
        let ok = match mode.as_str() {
            "build" => s
                .rebuild(black_box(&knots), black_box(&values), Alphas::default())
                .is_ok(),
            "build_alphas" => s
                .rebuild(&knots, &values, Alphas::PerInterval(&alphas))
                .is_ok(),
            "through" => black_box(Spline::through(&knots, &values, Alphas::default())).is_ok(),
            "sorted" => s.eval_many(black_box(&sorted), &mut out).is_ok(),
            "random" => s.eval_many(black_box(&random), &mut out).is_ok(),
            "closed" => CurveBuilder::new(black_box(pts.as_flattened()), 2)
                .closed(true)
                .build_into(&mut cc)
                .is_ok(),
            "curve" => CurveBuilder::new(black_box(pts.as_flattened()), 2)
                .build_into(&mut c)
                .is_ok(),
            "flatten" => black_box(sc.flatten(1e-3 * size)).is_ok(),
            "ceval" => {
                let mut o = [0.0; 2];
                let (a0, a1) = c.domain();
                (0..M).all(|i| {
                    let ok = c
                        .eval_into(a0 + (a1 - a0) * (i as f64 + 0.5) / M as f64, &mut o)
                        .is_ok();
                    black_box(o);
                    ok
                })
            }
            "seval" => random[..N].iter().all(|&x| black_box(s.eval(x)).is_ok()),
            other => {
                eprintln!("instructions: unknown workload {other:?}");
                std::process::exit(2);
            }
        };
        if !ok {
            eprintln!("instructions: {mode} failed");
            std::process::exit(1);
        }
    }
    black_box(out);
    println!("{per}");
}
