//! Times the smoothing spline with lambda chosen by cross-validation on noisy
//! samples of a sine, and prints its error to the true function beside the
//! data's; then the 95 % confidence band at every data point, its time
//! against the fit's, and how much of the true curve it covers:
//! `cargo run --release --example smoothing -- [N ...]`.

use bzspline::{Alphas, Smoothing, Spline};
use std::time::Instant;

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number of points"))
        .collect();
    let sizes = if sizes.is_empty() {
        vec![1_000, 10_000, 100_000, 1_000_000]
    } else {
        sizes
    };
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut normal = move || {
        // Box-Muller from a xorshift generator.
        let mut u = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let (a, b) = (u(), u());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    };
    println!(
        "{:>9} {:>10} {:>12} {:>12} {:>8} {:>10} {:>9} {:>9} {:>9}",
        "n", "time ms", "mse fit", "mse data", "dof", "lambda", "band ms", "band/fit", "covered"
    );
    for n in sizes {
        let x: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let truth: Vec<f64> = x
            .iter()
            .map(|&t| (std::f64::consts::TAU * t).sin())
            .collect();
        let y: Vec<f64> = truth.iter().map(|&v| v + 0.3 * normal()).collect();
        let start = Instant::now();
        let s = Spline::smoothing(&x, &y, None, Alphas::default(), Smoothing::Gcv).expect("fit");
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let fit = s.fit.knot_values();
        let mse = |v: &[f64]| {
            v.iter()
                .zip(&truth)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                / n as f64
        };
        let start = Instant::now();
        let (lo, hi) = s.band_many(&x, 0.95).expect("band");
        let band_ms = start.elapsed().as_secs_f64() * 1e3;
        let covered = truth
            .iter()
            .zip(lo.iter().zip(&hi))
            .filter(|(t, (a, b))| *a <= *t && *t <= *b)
            .count() as f64
            / n as f64;
        println!(
            "{n:>9} {ms:>10.1} {:>12.3e} {:>12.3e} {:>8.1} {:>10.3e} {band_ms:>9.1} {:>9.2} {covered:>9.3}",
            mse(&fit),
            mse(&y),
            s.dof,
            s.lambda,
            band_ms / ms
        );
    }
}
