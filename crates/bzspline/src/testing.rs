//! What the unit tests share: a small deterministic generator, generated
//! systems for the chunked solvers, and a pool of a given number of threads.

/// A xorshift generator in `[0, 1)`, one stream a seed.
pub(crate) fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Knots, values and alphas of one generated system of `n` knots: `grid` 0
/// random widths in `[0.5, 1.5)`, 1 widths over 12 decades; `alphas` 0
/// random in range, 1 only the extremes, 2 alternating 2/3 and 1/3 (the
/// weakest rows), 3 the one alpha 1/3, 4 the one alpha 2/3, 5 the one alpha
/// 1/2 (the alphas then empty).
pub(crate) fn case(
    n: usize,
    grid: u8,
    alphas: u8,
    seed: u64,
) -> (Vec<f64>, Vec<f64>, Vec<f64>, Option<f64>) {
    let mut next = rng(seed);
    let mut knots = Vec::with_capacity(n);
    let mut x = 0.0;
    for _ in 0..n {
        knots.push(x);
        x += match grid {
            0 => 0.5 + next(),
            _ => 10f64.powf(12.0 * next() - 6.0),
        };
    }
    let values: Vec<f64> = (0..n)
        .map(|i| (i as f64 * 0.01).sin() + 0.3 * (next() - 0.5))
        .collect();
    let (lo, hi) = (crate::ALPHA_MIN, crate::ALPHA_MAX);
    let (a, uniform): (Vec<f64>, _) = match alphas {
        0 => ((1..n).map(|_| lo + (hi - lo) * next()).collect(), None),
        1 => (
            (1..n).map(|_| if next() < 0.5 { lo } else { hi }).collect(),
            None,
        ),
        2 => (
            (1..n).map(|i| if i % 2 == 1 { hi } else { lo }).collect(),
            None,
        ),
        3 => (Vec::new(), Some(lo)),
        4 => (Vec::new(), Some(hi)),
        _ => (Vec::new(), Some(0.5)),
    };
    (knots, values, a, uniform)
}

/// `op` run in a pool of `threads` threads of its own.
#[cfg(feature = "rayon")]
pub(crate) fn on_threads<R: Send>(threads: usize, op: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a pool")
        .install(op)
}
