//! Construction and batch evaluation of the spline `y(x)`.
//!
//! `cargo bench -p bzspline --bench spline` (add `--features rayon` for the
//! parallel evaluators). Planar curves: construction, flattening and the local
//! re-solve after moving one point. Throughput is reported per point (construction) or per
//! query (evaluation). Large sizes take fewer samples so that the whole suite
//! runs in a few minutes.

// criterion_group! generates a public function that cannot carry a doc comment.
#![allow(missing_docs)]

use bzspline::Flatten;
use bzspline::ParamCurve;
use std::hint::black_box;
use std::time::Duration;

use bzspline::{Alphas, Curve, CurveBuilder, Spline};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

/// xorshift64*: uniform doubles in `[0, 1)` from a fixed seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Knots with random widths in `[0.5, 1.5)`, values a sine plus noise.
fn data(n: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut rng = Rng(seed | 1);
    let mut x = Vec::with_capacity(n);
    let mut t = 0.0;
    for _ in 0..n {
        x.push(t);
        t += 0.5 + rng.next();
    }
    let f = x
        .iter()
        .map(|x| 100.0 * (0.01 * x).sin() + rng.next() - 0.5)
        .collect();
    (x, f)
}

fn samples(n: usize) -> usize {
    if n >= 1_000_000 {
        10
    } else if n >= 100_000 {
        20
    } else {
        50
    }
}

fn construction(c: &mut Criterion) {
    let mut g = c.benchmark_group("construct");
    for n in [1_000usize, 10_000, 100_000, 1_000_000, 10_000_000] {
        let (x, f) = data(n, 1);
        let alphas: Vec<f64> = (0..n - 1)
            .map(|k| 0.4 + 0.2 * ((k % 7) as f64 / 7.0))
            .collect();
        g.throughput(Throughput::Elements(n as u64));
        g.sample_size(samples(n));
        g.measurement_time(Duration::from_secs(if n >= 1_000_000 { 8 } else { 3 }));
        let mut s = Spline::new(&x, &f).expect("valid data");
        g.bench_with_input(BenchmarkId::new("rebuild", n), &n, |b, _| {
            b.iter(|| s.rebuild(black_box(&x), black_box(&f), Alphas::default()));
        });
        g.bench_with_input(
            BenchmarkId::new("rebuild_per_interval_alphas", n),
            &n,
            |b, _| {
                b.iter(|| s.rebuild(black_box(&x), black_box(&f), Alphas::PerInterval(&alphas)));
            },
        );
        if n <= 1_000_000 {
            g.bench_with_input(BenchmarkId::new("fresh", n), &n, |b, _| {
                b.iter(|| Spline::new(black_box(&x), black_box(&f)));
            });
        }
    }
    g.finish();
}

fn evaluation(c: &mut Criterion) {
    let mut g = c.benchmark_group("evaluate");
    for (n, m) in [(10_000usize, 100_000usize), (1_000_000, 1_000_000)] {
        let (x, f) = data(n, 2);
        let s = Spline::new(&x, &f).expect("valid data");
        let (lo, hi) = s.domain();
        let sorted: Vec<f64> = (0..m)
            .map(|i| lo + (hi - lo) * (i as f64 + 0.5) / m as f64)
            .collect();
        let mut rng = Rng(3);
        let random: Vec<f64> = (0..m).map(|_| lo + (hi - lo) * rng.next()).collect();
        let mut out = vec![0.0; m];
        g.throughput(Throughput::Elements(m as u64));
        g.sample_size(samples(n.max(m)));
        let id = format!("n={n}/m={m}");
        for order in 0..3u32 {
            g.bench_function(BenchmarkId::new(format!("sorted_order{order}"), &id), |b| {
                b.iter(|| s.deriv_many(black_box(&sorted), order, &mut out));
            });
            g.bench_function(BenchmarkId::new(format!("random_order{order}"), &id), |b| {
                b.iter(|| s.deriv_many(black_box(&random), order, &mut out));
            });
        }
        #[cfg(feature = "rayon")]
        {
            g.bench_function(BenchmarkId::new("par_sorted", &id), |b| {
                b.iter(|| s.par_eval_many(black_box(&sorted), &mut out));
            });
            g.bench_function(BenchmarkId::new("par_random", &id), |b| {
                b.iter(|| s.par_eval_many(black_box(&random), &mut out));
            });
        }
        g.bench_function(BenchmarkId::new("pointwise_random", &id), |b| {
            b.iter(|| {
                for (x, o) in random.iter().zip(out.iter_mut()) {
                    *o = s.eval(*x).unwrap_or(f64::NAN);
                }
            });
        });
    }
    g.finish();
}

fn curves(c: &mut Criterion) {
    let mut g = c.benchmark_group("curve2d");
    for n in [1_000usize, 10_000, 100_000] {
        let (x, f) = data(n, 4);
        let pts: Vec<[f64; 2]> = x.iter().zip(&f).map(|(x, y)| [*x, *y]).collect();
        g.throughput(Throughput::Elements(n as u64));
        g.sample_size(samples(n * 10));
        g.bench_with_input(BenchmarkId::new("construct", n), &n, |b, _| {
            b.iter(|| Curve::open(black_box(&pts)));
        });
        let Ok(mut curve) = Curve::open(&pts) else {
            continue;
        };
        g.bench_with_input(BenchmarkId::new("rebuild", n), &n, |b, _| {
            b.iter(|| CurveBuilder::new(black_box(pts.as_flattened()), 2).build_into(&mut curve));
        });
        g.bench_with_input(BenchmarkId::new("flatten_1e-3", n), &n, |b, _| {
            b.iter(|| curve.flatten(black_box(1e-3)));
        });
        let mid = n / 2;
        let mut up = false;
        g.throughput(Throughput::Elements(1));
        g.bench_with_input(BenchmarkId::new("move_point", n), &n, |b, _| {
            b.iter(|| {
                up = !up;
                let y = f[mid] + if up { 1.0 } else { 0.0 };
                curve.move_point(mid, black_box(&[x[mid], y]), 1e-12)
            });
        });
    }
    g.finish();
}

criterion_group!(benches, construction, evaluation, curves);
criterion_main!(benches);
