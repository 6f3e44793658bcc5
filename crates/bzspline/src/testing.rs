//! What the unit tests share: a small deterministic generator, and a pool
//! of a given number of threads.

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

/// `op` run in a pool of `threads` threads of its own.
#[cfg(feature = "rayon")]
pub(crate) fn on_threads<R: Send>(threads: usize, op: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a pool")
        .install(op)
}
