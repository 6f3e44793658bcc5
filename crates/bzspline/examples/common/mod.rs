//! What the `throughput` and `baselines` examples share: the options, the
//! random numbers and the timing.

use std::time::Instant;

/// xorshift64*: uniform doubles in `[0, 1)` from a fixed seed.
pub struct Rng(pub u64);

impl Rng {
    /// The generator for `--seed`.
    pub fn seeded(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1)
    }

    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The options: `--n` (default 1e6), `--m` (1e7), `--mr` (`min(m, 1e6)`),
/// `--repeats` (7), `--seed` (1) and, where taken, `--stream` (2^25).
pub struct Args {
    pub n: usize,
    pub m: usize,
    pub mr: usize,
    pub repeats: usize,
    pub seed: u64,
    pub stream: usize,
}

/// The options from the command line; `--stream` only when `stream`, `--n`
/// at least `min_n`.
pub fn parse_args(min_n: usize, stream: bool) -> Result<Args, String> {
    let mut a = Args {
        n: 1_000_000,
        m: 10_000_000,
        mr: 0,
        repeats: 7,
        seed: 1,
        stream: 1 << 25,
    };
    let mut mr = None;
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().ok_or_else(|| format!("{flag} needs a value"))?;
        // Accept 1e6 as well as 1000000.
        let num = value
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v >= 0.0 && v.fract() == 0.0)
            .ok_or_else(|| format!("{flag}: not a count: {value}"))? as u64;
        match flag.as_str() {
            "--n" => a.n = num as usize,
            "--m" => a.m = num as usize,
            "--mr" => mr = Some(num as usize),
            "--repeats" => a.repeats = (num as usize).max(1),
            "--seed" => a.seed = num.max(1),
            "--stream" if stream => a.stream = (num as usize).max(1024),
            _ => return Err(format!("unknown option {flag}")),
        }
    }
    if a.n < min_n {
        return Err(format!("--n must be at least {min_n}"));
    }
    a.mr = mr.unwrap_or(a.m.min(1_000_000));
    Ok(a)
}

/// The options, or the error on standard error (naming the example `name`)
/// and exit code 2.
pub fn args_or_exit(name: &str, min_n: usize, stream: bool) -> Args {
    parse_args(min_n, stream).unwrap_or_else(|e| {
        eprintln!("{name}: {e}");
        std::process::exit(2);
    })
}

/// Nanoseconds `f` takes.
pub fn time_ns(f: impl FnOnce()) -> f64 {
    let start = Instant::now();
    f();
    start.elapsed().as_nanos() as f64
}

/// The median (see [`pick`]) of `repeats` timings, each the nanoseconds
/// `run` returns (so that it can do untimed work around what it times).
pub fn median_of(repeats: usize, mut run: impl FnMut() -> f64) -> f64 {
    let mut t: Vec<f64> = (0..repeats).map(|_| run()).collect();
    t.sort_by(f64::total_cmp);
    pick(&t)
}

/// Median wall time in nanoseconds of `repeats` runs of `f`, after one
/// warm-up (the smallest with `BZ_MIN=1`, see [`pick`]).
pub fn median_ns(repeats: usize, mut f: impl FnMut()) -> f64 {
    f();
    median_of(repeats, || time_ns(&mut f))
}

/// Median time of `build`, after one warm-up, keeping each result alive until
/// after its timing so that the release of the memory is not counted.
pub fn f_median<T>(repeats: usize, keep: &mut Vec<T>, mut build: impl FnMut() -> T) -> f64 {
    drop(build());
    median_of(repeats, || {
        keep.clear();
        let mut v = None;
        let e = time_ns(|| v = Some(build()));
        keep.extend(v);
        e
    })
}

/// The median, or the minimum when `BZ_MIN=1` is set (steadier on a busy
/// machine).
pub fn pick(sorted: &[f64]) -> f64 {
    if std::env::var_os("BZ_MIN").is_some_and(|v| v == "1") {
        sorted[0]
    } else {
        sorted[sorted.len() / 2]
    }
}

/// The benchmarks' data: `n` knots with random widths in `[0.5, 1.5)`, values
/// a sine plus noise, one alpha per interval in `[0.35, 0.65)`, `m` queries
/// evenly spaced over the domain and `mr` uniformly random ones, drawn from
/// `rng` in that order.
pub struct Data {
    pub knots: Vec<f64>,
    pub values: Vec<f64>,
    pub alphas: Vec<f64>,
    pub sorted: Vec<f64>,
    pub random: Vec<f64>,
}

impl Data {
    pub fn new(rng: &mut Rng, n: usize, m: usize, mr: usize) -> Self {
        let mut knots = Vec::with_capacity(n);
        let mut t = 0.0;
        for _ in 0..n {
            knots.push(t);
            t += 0.5 + rng.next();
        }
        let values: Vec<f64> = knots
            .iter()
            .map(|x| 100.0 * (0.01 * x).sin() + rng.next() - 0.5)
            .collect();
        let alphas: Vec<f64> = (0..n - 1).map(|_| 0.35 + 0.3 * rng.next()).collect();
        let (lo, hi) = (knots[0], knots[n - 1]);
        let sorted: Vec<f64> = (0..m)
            .map(|i| lo + (hi - lo) * (i as f64 + 0.5) / m as f64)
            .collect();
        let random: Vec<f64> = (0..mr).map(|_| lo + (hi - lo) * rng.next()).collect();
        Data {
            knots,
            values,
            alphas,
            sorted,
            random,
        }
    }
}

/// The flattening benchmark's curve: `n` points of a spiral of 100 turns,
/// the radius jittered by up to 0.3 (drawn from `rng`).
pub fn spiral(rng: &mut Rng, n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let th = i as f64 * (200.0 * std::f64::consts::PI / n as f64);
            let rad = 1.0 + th + 0.3 * rng.next();
            [rad * th.cos(), rad * th.sin()]
        })
        .collect()
}
