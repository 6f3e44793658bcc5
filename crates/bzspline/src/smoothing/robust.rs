//! Robust smoothing (`docs/method.md` §14): the smoothing fit re-weighted by
//! its residuals with Tukey's biweight on a scale of six median absolute
//! residuals, as lowess does, the smoothing chosen again at every step.

use super::{fit, fit_counted, Data, Fit, Smoothing};
use crate::error::Error;

/// The fewest points of positive weight a robust fit takes: the median of
/// fewer residuals is no scale to judge one of them by.
pub const ROBUST_MIN_POINTS: usize = 5;

/// The most re-weighting steps; the fit stops earlier when no weight moves
/// by more than [`SETTLED`].
const MAX_STEPS: usize = 20;

/// A change of every robustness weight below this ends the iteration.
const SETTLED: f64 = 1e-3;

/// The robust fit of `data` (its weights the prior ones), and the
/// robustness weights it ends with, one a point, in `[0, 1]` (the fit's
/// weights are their products with the prior ones).
pub(crate) fn fit_robust(data: Data<'_>, smoothing: Smoothing) -> Result<(Fit, Vec<f64>), Error> {
    let Data {
        values,
        dim,
        weights,
        ..
    } = data;
    let positive = weights.iter().filter(|&&w| w > 0.0).count();
    if positive < ROBUST_MIN_POINTS {
        return Err(Error::TooFewPoints {
            found: positive,
            min: ROBUST_MIN_POINTS,
        });
    }
    let n = weights.len();
    let mean_w = weights.iter().sum::<f64>() / n as f64;
    let mut robustness = vec![1.0; n];
    let mut current = fit(data, smoothing)?;
    let mut residual = vec![0.0; n];
    let mut scaled: Vec<f64> = Vec::with_capacity(positive);
    for _ in 0..MAX_STEPS {
        // Residuals standardised by the prior weights (inverse variances).
        scaled.clear();
        for (j, r) in residual.iter_mut().enumerate() {
            let d2: f64 = (0..dim)
                .map(|c| (values[j * dim + c] - current.fitted[j * dim + c]).powi(2))
                .sum();
            *r = (weights[j] / mean_w * d2).sqrt();
            if weights[j] > 0.0 {
                scaled.push(*r);
            }
        }
        let scale = 6.0 * median(&mut scaled);
        if !(scale > 0.0 && scale.is_finite()) {
            // Half the points or more fitted exactly: nothing to judge by.
            break;
        }
        let mut moved = 0.0f64;
        for (rw, &r) in robustness.iter_mut().zip(&residual) {
            let u = r / scale;
            let next = if u < 1.0 { (1.0 - u * u).powi(2) } else { 0.0 };
            moved = moved.max((next - *rw).abs());
            *rw = next;
        }
        let w: Vec<f64> = weights
            .iter()
            .zip(&robustness)
            .map(|(a, b)| a * b)
            .collect();
        // Each point counts as its robustness weight: a point judged an
        // outlier is no observation for GCV to keep the fit away from.
        let count: f64 = (0..n)
            .filter(|&j| weights[j] > 0.0)
            .map(|j| robustness[j])
            .sum();
        current = fit_counted(data.with_weights(&w), smoothing, count)?;
        if moved < SETTLED {
            break;
        }
    }
    Ok((current, robustness))
}

/// The median of `v` (not empty), the mean of the middle two for an even
/// count; `v` is reordered.
fn median(v: &mut [f64]) -> f64 {
    let (m, odd) = (v.len() / 2, v.len() % 2 == 1);
    let (below, mid, _) = v.select_nth_unstable_by(m, f64::total_cmp);
    let upper = *mid;
    if odd {
        return upper;
    }
    let lower = below.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    0.5 * (lower + upper)
}

#[cfg(test)]
mod tests {
    use super::median;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(&mut [5.0]), 5.0);
    }
}
