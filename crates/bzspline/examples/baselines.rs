//! The reference kernels that the speed targets were set against, timed on
//! this machine, printed as one JSON object.
//!
//! ```text
//! cargo run --release -p bzspline --example baselines -- --n 1000000 --m 10000000
//! ```
//!
//! The targets quote, for the machine they were set on, a plain Thomas sweep
//! (about 7 ns per unknown), the same sweep with the division off the chain of
//! dependent operations (about 3.7), a walking-pointer Horner evaluation of
//! sorted queries (about 1.9 ns per query), a branchless binary search on 16
//! queries at a time (about 30 ns per random query), a one-core memory stream
//! (about 39 GB/s) and the page faults of a fresh allocation (about 3 ns per
//! f64); beside them, the scaling stream on two threads at once, and a
//! construction's own traffic (16 bytes read and 48 written a point) with no
//! arithmetic: the floor of a rebuild in place with plain stores. None of these uses bzspline: they say how fast this machine is at the
//! work the targets were scaled from, so that `bench/compare.py` can scale the
//! targets to it.
//!
//! Options as for the `throughput` example: `--n` unknowns and pieces (default
//! 1e6), `--m` sorted queries (default 1e7), `--mr` random queries (default
//! `min(m, 1e6)`), `--repeats` (default 7; the median is printed, after one
//! warm-up run, or the smallest with `BZ_MIN=1`), `--seed` (default 1). The
//! streams run over `--stream` doubles (default 2^25, 256 MiB an array).

#[allow(dead_code)] // the benchmarks' data, which these kernels do not use
mod common;

use std::hint::{black_box, select_unpredictable};

use common::{args_or_exit, f_median, median_ns, Rng};

/// A tridiagonal system `a[i] x[i-1] + b[i] x[i] + c[i] x[i+1] = d[i]`
/// (`a[0]` and `c[n-1]` unused), strictly diagonally dominant.
struct System {
    a: Vec<f64>,
    b: Vec<f64>,
    c: Vec<f64>,
    d: Vec<f64>,
}

impl System {
    /// Off-diagonals in `[0.5, 1.5)`, diagonal `4` (dominant, as the
    /// spline's system is), right-hand side in `[-1, 1)`.
    fn random(n: usize, rng: &mut Rng) -> Self {
        let mut s = System {
            a: Vec::with_capacity(n),
            b: vec![4.0; n],
            c: Vec::with_capacity(n),
            d: Vec::with_capacity(n),
        };
        for _ in 0..n {
            s.a.push(0.5 + rng.next());
            s.c.push(0.5 + rng.next());
            s.d.push(2.0 * rng.next() - 1.0);
        }
        s
    }

    /// The largest `|A x - d|` over the rows (NaN when one is NaN).
    fn residual(&self, x: &[f64]) -> f64 {
        let n = x.len();
        (0..n)
            .map(|i| {
                let mut r = self.b[i] * x[i] - self.d[i];
                if i > 0 {
                    r += self.a[i] * x[i - 1];
                }
                if i + 1 < n {
                    r += self.c[i] * x[i + 1];
                }
                r.abs()
            })
            .fold(0.0, worst)
    }
}

/// The larger of two magnitudes, NaN when either is (`f64::max` drops a NaN).
fn worst(m: f64, r: f64) -> f64 {
    if r > m || r.is_nan() {
        r
    } else {
        m
    }
}

/// The textbook Thomas sweep: each row's pivot is divided by the previous
/// one's, so the divisions form one chain. `cp` and `dp` are scratch.
fn thomas(s: &System, cp: &mut [f64], dp: &mut [f64], x: &mut [f64]) {
    let n = x.len();
    let m = 1.0 / s.b[0];
    cp[0] = s.c[0] * m;
    dp[0] = s.d[0] * m;
    for i in 1..n {
        let m = 1.0 / (s.b[i] - s.a[i] * cp[i - 1]);
        cp[i] = s.c[i] * m;
        dp[i] = (s.d[i] - s.a[i] * dp[i - 1]) * m;
    }
    x[n - 1] = dp[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = dp[i] - cp[i] * x[i + 1];
    }
}

/// Rows between two rescalings of the continuants in [`thomas_off_chain`].
const RESCALE: usize = 64;

/// The Thomas sweep with the division off the chain: the pivots are ratios
/// `p[i] = t[i] / t[i-1]` of the continuants `t[i] = b[i] t[i-1] - a[i]
/// c[i-1] t[i-2]`, a recurrence of multiplications only; each row's division
/// `t[i-1] / t[i]` depends on the chain but nothing on the chain depends on
/// it. The continuants grow about fourfold a row and are rescaled every
/// [`RESCALE`] rows.
fn thomas_off_chain(s: &System, cp: &mut [f64], dp: &mut [f64], x: &mut [f64]) {
    let n = x.len();
    let (mut t2, mut t1) = (1.0, s.b[0]);
    let r = 1.0 / t1;
    cp[0] = s.c[0] * r;
    dp[0] = s.d[0] * r;
    let mut i = 1;
    while i < n {
        let end = (i + RESCALE).min(n);
        while i < end {
            let t = s.b[i] * t1 - (s.a[i] * s.c[i - 1]) * t2;
            let r = t1 / t;
            cp[i] = s.c[i] * r;
            dp[i] = s.d[i] * r - (s.a[i] * r) * dp[i - 1];
            (t2, t1) = (t1, t);
            i += 1;
        }
        let k = 1.0 / t1;
        (t2, t1) = (t2 * k, 1.0);
    }
    x[n - 1] = dp[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = dp[i] - cp[i] * x[i + 1];
    }
}

/// Pieces `[c0, c1, c2, c3]` in powers of `x - knots[j]`, one per interval.
struct Pieces {
    knots: Vec<f64>,
    coefs: Vec<[f64; 4]>,
}

impl Pieces {
    fn random(n: usize, rng: &mut Rng) -> Self {
        let mut knots = Vec::with_capacity(n);
        let mut x = 0.0;
        for _ in 0..n {
            knots.push(x);
            x += 0.5 + rng.next();
        }
        let coefs = (0..n - 1)
            .map(|_| [rng.next(), rng.next(), rng.next(), rng.next()])
            .collect();
        Pieces { knots, coefs }
    }

    #[inline(always)]
    fn horner(&self, j: usize, q: f64) -> f64 {
        let c = &self.coefs[j];
        let t = q - self.knots[j];
        c[0] + t * (c[1] + t * (c[2] + t * c[3]))
    }

    /// Sorted queries, with a pointer to the piece that walks forward.
    fn walk(&self, qs: &[f64], out: &mut [f64]) {
        let last = self.coefs.len() - 1;
        let mut j = 0;
        for (q, o) in qs.iter().zip(out) {
            while j < last && self.knots[j + 1] <= *q {
                j += 1;
            }
            *o = self.horner(j, *q);
        }
    }

    /// Queries in any order, 16 at a time: a branchless binary search (the
    /// step is a conditional move) advancing the 16 in lockstep, so that
    /// their memory accesses overlap.
    fn search16(&self, qs: &[f64], out: &mut [f64]) {
        const LANES: usize = 16;
        let last = self.coefs.len() - 1;
        let mut qc = qs.chunks_exact(LANES);
        let mut oc = out.chunks_exact_mut(LANES);
        for (q, o) in (&mut qc).zip(&mut oc) {
            let mut base = [0usize; LANES];
            let mut len = self.knots.len();
            while len > 1 {
                let half = len / 2;
                for (b, q) in base.iter_mut().zip(q) {
                    // A conditional move: the comparison is a coin toss.
                    *b = select_unpredictable(self.knots[*b + half] <= *q, *b + half, *b);
                }
                len -= half;
            }
            for ((b, q), o) in base.iter().zip(q).zip(o.iter_mut()) {
                *o = self.horner((*b).min(last), *q);
            }
        }
        for (q, o) in qc.remainder().iter().zip(oc.into_remainder()) {
            let j = self.knots.partition_point(|k| k <= q).clamp(1, last + 1) - 1;
            *o = self.horner(j, *q);
        }
    }
}

/// Sum of `v` with four accumulators (a read stream).
fn sum4(v: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let mut c = v.chunks_exact(4);
    for w in &mut c {
        for (a, x) in acc.iter_mut().zip(w) {
            *a += x;
        }
    }
    acc.iter().sum::<f64>() + c.remainder().iter().sum::<f64>()
}

/// `dst = 2 src` (a read stream and a write stream).
fn scale_into(dst: &mut [f64], src: &[f64]) {
    for (d, s) in dst.iter_mut().zip(src) {
        *d = 2.0 * s;
    }
}

/// The memory traffic of a construction with no arithmetic: a point's `x`
/// and `y` read (16 bytes) and its piece (32 bytes) and copies of both (16)
/// written with plain stores, as a rebuild in place writes them (each line
/// written is first read for ownership).
fn construction_stream(x: &[f64], y: &[f64], out: (&mut [[f64; 4]], &mut [f64], &mut [f64])) {
    let (pieces, xs, ys) = out;
    let points = x.iter().zip(y).zip(xs.iter_mut().zip(ys.iter_mut()));
    for (p, ((&a, &b), (xo, yo))) in pieces.iter_mut().zip(points) {
        *p = [a, b, b, a];
        *xo = a;
        *yo = b;
    }
}

fn main() {
    let args = args_or_exit("baselines", 3, true);
    let (n, m, mr, r) = (args.n, args.m, args.mr, args.repeats);
    let mut rng = Rng::seeded(args.seed);

    let sys = System::random(n, &mut rng);
    let (mut cp, mut dp, mut x) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let plain = median_ns(r, || thomas(&sys, &mut cp, &mut dp, black_box(&mut x)));
    let plain_res = sys.residual(&x);
    let off = median_ns(r, || {
        thomas_off_chain(&sys, &mut cp, &mut dp, black_box(&mut x));
    });
    let off_res = sys.residual(&x);
    drop((sys, cp, dp, x));

    let p = Pieces::random(n, &mut rng);
    let (lo, hi) = (p.knots[0], p.knots[n - 1]);
    let sorted: Vec<f64> = (0..m)
        .map(|i| lo + (hi - lo) * (i as f64 + 0.5) / m as f64)
        .collect();
    let random: Vec<f64> = (0..mr).map(|_| lo + (hi - lo) * rng.next()).collect();
    let mut out = vec![0.0; m.max(mr)];
    let walk = median_ns(r, || p.walk(&sorted, black_box(&mut out[..m])));
    let search = median_ns(r, || p.search16(&random, black_box(&mut out[..mr])));
    drop((p, sorted, random, out));

    let len = args.stream;
    let src: Vec<f64> = (0..len).map(|i| i as f64).collect();
    let mut dst = vec![0.0; len];
    let read = median_ns(r, || {
        black_box(sum4(black_box(&src)));
    });
    let scale = median_ns(r, || {
        scale_into(&mut dst, &src);
        black_box(&dst);
    });
    // The same scaling on two threads, each over its half: what two cores
    // together can stream (the ceiling of any two-thread pass over memory).
    let scale_two = median_ns(r, || {
        let (d0, d1) = dst.split_at_mut(len / 2);
        let (s0, s1) = src.split_at(len / 2);
        std::thread::scope(|scope| {
            scope.spawn(|| scale_into(d1, s1));
            scale_into(d0, s0);
        });
        black_box(&dst);
    });
    drop(dst);
    // A construction's own traffic (64 bytes a point) over a quarter as many
    // points as a stream has doubles.
    let points = len / 4;
    let (x, y) = (&src[..points], &src[points..2 * points]);
    let (mut pieces, mut xs, mut ys) =
        (vec![[0.0; 4]; points], vec![0.0; points], vec![0.0; points]);
    let construct = median_ns(r, || {
        construction_stream(x, y, (&mut pieces, &mut xs, &mut ys));
        black_box((&pieces, &xs, &ys));
    });
    drop((pieces, xs, ys));
    let mut dst = vec![0.0; len];
    // Writing a buffer that is already mapped, against writing a fresh one
    // (its page faults); the release of the fresh one is not timed.
    let fresh = f_median(r, &mut Vec::new(), || black_box(vec![1.0f64; len]));
    let fill = median_ns(r, || {
        dst.fill(1.0);
        black_box(&dst);
    });

    let f = |v: f64| format!("{v:.3}");
    let e = |v: f64| format!("{v:.1e}");
    let gb = |bytes: f64, ns: f64| f(bytes / ns);
    println!(
        "{{\"n\": {n}, \"m\": {m}, \"m_random\": {mr}, \"stream\": {len}, \"repeats\": {r}, \
         \"thomas_ns_per_unknown\": {}, \"thomas_off_chain_ns_per_unknown\": {}, \
         \"thomas_max_residual\": {}, \"thomas_off_chain_max_residual\": {}, \
         \"horner_walk_sorted_ns_per_query\": {}, \"search16_random_ns_per_query\": {}, \
         \"stream_read_gb_per_s\": {}, \"stream_scale_gb_per_s\": {}, \
         \"stream_scale_two_threads_gb_per_s\": {}, \"construction_stream_ns_per_point\": {}, \
         \"fresh_alloc_ns_per_f64\": {}}}",
        f(plain / n as f64),
        f(off / n as f64),
        e(plain_res),
        e(off_res),
        f(walk / m.max(1) as f64),
        f(search / mr.max(1) as f64),
        gb(8.0 * len as f64, read),
        gb(16.0 * len as f64, scale),
        gb(16.0 * len as f64, scale_two),
        f(construct / points as f64),
        f(((fresh - fill) / len as f64).max(0.0)),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_sweeps_solve_the_system() {
        let mut rng = Rng(7);
        for n in [3, 4, 63, 64, 65, 129, 1000, 5000] {
            let sys = System::random(n, &mut rng);
            let (mut cp, mut dp) = (vec![0.0; n], vec![0.0; n]);
            let (mut x1, mut x2) = (vec![0.0; n], vec![0.0; n]);
            thomas(&sys, &mut cp, &mut dp, &mut x1);
            thomas_off_chain(&sys, &mut cp, &mut dp, &mut x2);
            let (r1, r2) = (sys.residual(&x1), sys.residual(&x2));
            assert!(r1 < 1e-14 && r2 < 1e-14, "n {n}: residuals {r1:e} {r2:e}");
            let diff = x1
                .iter()
                .zip(&x2)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, worst);
            assert!(diff < 1e-14, "n {n}: the sweeps differ by {diff:e}");
        }
    }

    #[test]
    fn the_search_finds_the_piece_the_walk_finds() {
        let mut rng = Rng(11);
        for n in [3, 17, 1000] {
            let p = Pieces::random(n, &mut rng);
            let (lo, hi) = (p.knots[0], p.knots[n - 1]);
            // Sorted, with the knots themselves and points outside.
            let mut qs: Vec<f64> = (0..100)
                .map(|_| lo - 1.0 + (hi - lo + 2.0) * rng.next())
                .collect();
            qs.extend_from_slice(&p.knots);
            qs.sort_by(f64::total_cmp);
            let (mut a, mut b) = (vec![0.0; qs.len()], vec![0.0; qs.len()]);
            p.walk(&qs, &mut a);
            p.search16(&qs, &mut b);
            assert_eq!(a, b, "n {n}");
        }
    }

    #[test]
    fn the_read_stream_sums_every_element() {
        let v: Vec<f64> = (0..1027).map(f64::from).collect();
        assert_eq!(sum4(&v), 1026.0 * 1027.0 / 2.0);
    }

    #[test]
    fn the_construction_stream_writes_every_point() {
        let n = 1029;
        let x: Vec<f64> = (0..n).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|v| -v).collect();
        let (mut pieces, mut xs, mut ys) = (
            vec![[f64::NAN; 4]; n as usize],
            vec![0.0; n as usize],
            vec![0.0; n as usize],
        );
        construction_stream(&x, &y, (&mut pieces, &mut xs, &mut ys));
        assert_eq!((xs, ys), (x.clone(), y.clone()));
        assert!(pieces
            .iter()
            .zip(x.iter().zip(&y))
            .all(|(p, (&a, &b))| *p == [a, b, b, a]));
    }
}
