//! Axis ranges and "nice" tick marks (steps of 1, 2 or 5 times a power of ten).

/// A closed interval of data values shown along one axis, with its ticks.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// Smallest value shown.
    pub lo: f64,
    /// Largest value shown (`hi > lo`).
    pub hi: f64,
    /// Distance between neighbouring ticks.
    pub step: f64,
    /// Tick positions inside `[lo, hi]`, increasing.
    pub ticks: Vec<f64>,
}

impl Axis {
    /// An axis showing `[lo, hi]` widened by `pad` (a fraction of the span) on both
    /// sides, with about `target` ticks. Non-finite or reversed bounds fall back to
    /// `[0, 1]`; an empty span is widened so the axis is never degenerate.
    #[must_use]
    pub fn new(lo: f64, hi: f64, pad: f64, target: usize) -> Self {
        let (mut lo, mut hi) = if lo.is_finite() && hi.is_finite() && lo <= hi {
            (lo, hi)
        } else {
            (0.0, 1.0)
        };
        if hi - lo <= f64::EPSILON * lo.abs().max(hi.abs()) || !(hi - lo).is_normal() {
            // One value (or a span too small to draw): centre it in a unit-ish window.
            let w = if lo.abs() > 1.0 { lo.abs() * 0.1 } else { 1.0 };
            let mid = lo / 2.0 + hi / 2.0;
            lo = mid - w;
            hi = mid + w;
        }
        // Half-spans keep the arithmetic finite up to +-f64::MAX.
        let half = hi / 2.0 - lo / 2.0;
        let grow = half * pad.clamp(0.0, 1.0);
        lo = finite_or(lo - 2.0 * grow, -f64::MAX);
        hi = finite_or(hi + 2.0 * grow, f64::MAX);
        let step = nice_step(hi / 2.0 - lo / 2.0, target.max(2));
        let ticks = ticks(lo, hi, step);
        Axis {
            lo,
            hi,
            step,
            ticks,
        }
    }

    /// Where `v` sits along the axis: 0 at `lo`, 1 at `hi`, finite for finite `v`.
    #[must_use]
    pub fn unit(&self, v: f64) -> f64 {
        let t = (v / 2.0 - self.lo / 2.0) / (self.hi / 2.0 - self.lo / 2.0);
        finite_or(t, 0.0)
    }

    /// The label of tick value `v`, with as many decimals as the step needs and a
    /// typographic minus sign.
    #[must_use]
    pub fn label(&self, v: f64) -> String {
        format_tick(v, self.step)
    }
}

fn finite_or(v: f64, fallback: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        fallback
    }
}

/// The tick step for an axis of half-width `half` with about `target` ticks: the
/// smallest of 1, 2, 5 or 10 times a power of ten not below `2 half / target`.
#[must_use]
pub fn nice_step(half: f64, target: usize) -> f64 {
    // `target` is small (a handful of ticks), so the conversion is exact.
    let raw = half / (target.max(1) as f64) * 2.0;
    if !raw.is_finite() || raw <= 0.0 {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let norm = raw / mag;
    let mult = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|m| norm <= m * (1.0 + 1e-9))
        .unwrap_or(10.0);
    let step = mult * mag;
    if step.is_finite() && step > 0.0 {
        step
    } else {
        mag
    }
}

/// The multiples of `step` inside `[lo, hi]` (at most a few hundred).
#[must_use]
pub fn ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    if !(step > 0.0 && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let first = (lo / step - 1e-9).ceil();
    let mut out = Vec::new();
    for k in 0..500 {
        let v = (first + f64::from(k)) * step;
        if !v.is_finite() || v > hi + step * 1e-9 {
            break;
        }
        // Snap values within rounding of zero to zero so the label is "0".
        out.push(if v.abs() < step * 1e-9 { 0.0 } else { v });
    }
    out
}

/// `v` written with the decimals that a tick step of `step` needs (scientific
/// notation for very large or very small steps), with the minus sign U+2212.
#[must_use]
pub fn format_tick(v: f64, step: f64) -> String {
    let e = if step > 0.0 && step.is_finite() {
        step.log10().floor()
    } else {
        0.0
    };
    let s = if !(-5.0..=6.0).contains(&e) {
        format!("{v:.1e}")
    } else {
        // e is in -5..=6 here, so the cast is exact.
        let decimals = if e < 0.0 { (-e) as usize } else { 0 };
        format!("{v:.decimals$}")
    };
    let s = if s
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    };
    s.replace('-', "\u{2212}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_one_two_or_five_times_a_power_of_ten() {
        for (lo, hi) in [
            (0.0, 1.0),
            (1.0, 11.0),
            (-3.7, 12.2),
            (0.0, 0.5),
            (1e-7, 3e-7),
            (-1e300, 1e300),
            (-f64::MAX, f64::MAX),
            (42.0, 42.0),
        ] {
            let a = Axis::new(lo, hi, 0.05, 7);
            let e = a.step.log10().floor();
            let m = a.step / 10f64.powf(e);
            assert!(
                [1.0, 2.0, 5.0, 10.0].iter().any(|w| (m - w).abs() < 1e-9),
                "[{lo}, {hi}]: step {} is not nice",
                a.step
            );
            assert!(
                (2..=20).contains(&a.ticks.len()),
                "[{lo}, {hi}]: {:?}",
                a.ticks
            );
            assert!(a.lo.is_finite() && a.hi.is_finite() && a.lo < a.hi);
            for t in &a.ticks {
                assert!(*t >= a.lo - a.step * 1e-6 && *t <= a.hi + a.step * 1e-6);
                let u = a.unit(*t);
                assert!((-1e-6..=1.0 + 1e-6).contains(&u), "unit({t}) = {u}");
            }
        }
        assert_eq!(nice_step(5.0, 10), 1.0);
        assert_eq!(nice_step(5.5, 10), 2.0);
        assert_eq!(nice_step(0.2, 8), 0.05);
    }

    #[test]
    fn example_1_axis_and_labels() {
        let a = Axis::new(1.0, 10.0, 0.0, 6);
        assert_eq!(a.step, 2.0);
        assert_eq!(a.ticks, vec![2.0, 4.0, 6.0, 8.0, 10.0]);
        let b = Axis::new(-0.25, 0.5, 0.0, 8);
        assert_eq!(b.step, 0.1);
        let labels: Vec<String> = b.ticks.iter().map(|t| b.label(*t)).collect();
        assert_eq!(
            labels,
            [
                "\u{2212}0.2",
                "\u{2212}0.1",
                "0.0",
                "0.1",
                "0.2",
                "0.3",
                "0.4",
                "0.5"
            ]
        );
        assert_eq!(format_tick(2.5e9, 1e9), "2.5e9");
        assert_eq!(Axis::new(f64::NAN, 1.0, 0.0, 5).lo, 0.0);
    }
}
