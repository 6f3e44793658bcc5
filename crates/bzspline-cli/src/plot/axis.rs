//! Axis ranges and "nice" tick marks (steps of 1, 2 or 5 times a power of ten,
//! or whole calendar units for dates and times).

use crate::time::{self, TimeKind};

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
    /// For values that are dates or times: their kind and the calendar unit
    /// the ticks step by (labels are then dates, months, years or times).
    pub calendar: Option<(TimeKind, Unit)>,
}

/// The calendar units date ticks step by, finest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Unit {
    /// Seconds, minutes or hours: labels with the time of day.
    Clock,
    /// Days or weeks: labels are dates.
    Day,
    /// Months: labels are year and month.
    Month,
    /// Years: labels are years.
    Year,
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
        // Half-spans: the whole one overflows between values near +-f64::MAX.
        let half = hi / 2.0 - lo / 2.0;
        if half <= f64::EPSILON / 2.0 * lo.abs().max(hi.abs()) || !half.is_normal() {
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
            calendar: None,
        }
    }

    /// An axis of dates or times (`kind`'s unit: days or seconds since 1970)
    /// with about `target` ticks at whole calendar units: seconds, minutes,
    /// hours, days, weeks, months or years, as the span asks, never finer
    /// than `finest` (the data's [`resolution`]: monthly data gets month
    /// ticks, however short the span).
    #[must_use]
    pub fn calendar(
        lo: f64,
        hi: f64,
        pad: f64,
        target: usize,
        kind: TimeKind,
        finest: Unit,
    ) -> Self {
        let mut a = Axis::new(lo, hi, pad, target);
        let to_s = time::convert(1.0, kind, TimeKind::DateTime(None));
        let (lo_s, hi_s) = (a.lo * to_s, a.hi * to_s);
        let span = hi_s - lo_s;
        if !(span.is_finite() && span > 0.0 && lo_s.abs() < 3e11 && hi_s.abs() < 3e11) {
            return a;
        }
        const DAY: f64 = 86_400.0;
        let clock = [
            1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 60.0, 120.0, 300.0, 600.0, 900.0, 1800.0, 3600.0,
            7200.0, 10800.0, 21600.0, 43200.0,
        ];
        let want = span / target.max(2) as f64;
        let (unit, ticks_s): (Unit, Vec<f64>) = if let Some(&step) = clock
            .iter()
            .find(|&&st| st >= want && finest == Unit::Clock)
        {
            (Unit::Clock, ticks(lo_s, hi_s, step))
        } else if let Some(&days) = [1.0, 2.0, 7.0, 14.0]
            .iter()
            .find(|&&d| d * DAY >= want && finest <= Unit::Day)
        {
            // Weeks start on the Monday after 1970-01-01 (a Thursday) + 4 days.
            let shift = if days >= 7.0 { 4.0 * DAY } else { 0.0 };
            let t = ticks(lo_s - shift, hi_s - shift, days * DAY);
            (Unit::Day, t.into_iter().map(|v| v + shift).collect())
        } else if let Some(&months) = [1, 2, 3, 6]
            .iter()
            .find(|&&m| f64::from(m) * 30.0 * DAY >= want && finest <= Unit::Month)
        {
            (Unit::Month, month_ticks(lo_s, hi_s, months))
        } else {
            let years = nice_step(want / (365.25 * DAY) / 2.0, 1).max(1.0);
            (
                Unit::Year,
                month_ticks(lo_s, hi_s, (years as i32).saturating_mul(12)),
            )
        };
        a.ticks = ticks_s.into_iter().map(|v| v / to_s).collect();
        a.calendar = Some((kind, unit));
        a
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
        let Some((kind, unit)) = self.calendar else {
            return format_tick(v, self.step);
        };
        let text = time::format(v, kind).unwrap_or_default();
        // `2024-03-01T06:30:00Z` and the like: keep what the unit shows.
        let (date, clock) = text.split_once('T').unwrap_or((&text, ""));
        match unit {
            Unit::Year => date
                .get(..date.len().saturating_sub(6))
                .unwrap_or(date)
                .to_owned(),
            Unit::Month => date
                .get(..date.len().saturating_sub(3))
                .unwrap_or(date)
                .to_owned(),
            Unit::Day => date.to_owned(),
            Unit::Clock => {
                let hm = clock.get(..5).unwrap_or("00:00");
                let secs = clock.get(5..8).filter(|s| *s != ":00").unwrap_or("");
                format!("{} {hm}{secs}", date.get(5..).unwrap_or(date))
            }
        }
    }
}

/// The coarsest calendar unit every date or time of `values` (in `kind`'s
/// unit) is whole in: [`Unit::Year`] when all are on the first of January at
/// midnight, [`Unit::Month`] on the first of a month, [`Unit::Day`] at
/// midnight (in the data's offset), else [`Unit::Clock`]. Looks at the first
/// 20,000 finite values: data keeps one resolution.
#[must_use]
pub fn resolution(values: impl IntoIterator<Item = f64>, kind: TimeKind) -> Unit {
    let mut finest = Unit::Year;
    for v in values.into_iter().filter(|v| v.is_finite()).take(20_000) {
        let Some(text) = time::format(v, kind) else {
            return Unit::Clock;
        };
        let (date, clock) = text.split_once('T').unwrap_or((&text, ""));
        let midnight =
            clock.is_empty() || (clock.starts_with("00:00:00") && !clock[8..].starts_with('.'));
        let n = date.len();
        let unit = if !midnight || n < 10 {
            Unit::Clock
        } else if &date[n - 2..] != "01" {
            Unit::Day
        } else if &date[n - 5..n - 3] != "01" {
            Unit::Month
        } else {
            Unit::Year
        };
        finest = finest.min(unit);
        if finest == Unit::Clock {
            break;
        }
    }
    finest
}

/// Ticks at the first of every `months`-th month (from January of year 0)
/// between `lo` and `hi` seconds since 1970, in seconds.
fn month_ticks(lo: f64, hi: f64, months: i32) -> Vec<f64> {
    use jiff::civil::Date;
    let months = months.max(1);
    let Some(start) = time::format(lo, TimeKind::DateTime(None)) else {
        return Vec::new();
    };
    let (Ok(y), Ok(m)) = (start[..4].parse::<i32>(), start[5..7].parse::<i32>()) else {
        return Vec::new();
    };
    let mut index = (y * 12 + m - 1).div_euclid(months) * months;
    let mut out = Vec::new();
    while out.len() < 500 {
        let (year, month) = (index.div_euclid(12), index.rem_euclid(12) + 1);
        let Ok(d) = Date::new(year as i16, month as i8, 1) else {
            break;
        };
        let Some((v, _)) = time::parse(&d.to_string()) else {
            break;
        };
        let secs = v * 86_400.0;
        if secs > hi {
            break;
        }
        if secs >= lo {
            out.push(secs);
        }
        index += months;
    }
    out
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
        if v == 0.0 {
            "0".to_owned()
        } else {
            format!("{v:.1e}")
        }
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
    fn ticks_follow_the_data_resolution() {
        let day = |s: &str| time::parse(s).unwrap().0;
        let days = |v: &[&str]| v.iter().map(|s| day(s)).collect::<Vec<_>>();
        // Every calendar unit, and each one's data.
        let monthly = days(&["2020-01-01", "2020-02-01", "2020-03-01", "2020-04-01"]);
        let yearly = days(&["1990-01-01", "1991-01-01", "1995-01-01"]);
        let daily = days(&["2020-01-01", "2020-01-02", "2020-02-01"]);
        assert_eq!(resolution(monthly.clone(), TimeKind::Date), Unit::Month);
        assert_eq!(resolution(yearly.clone(), TimeKind::Date), Unit::Year);
        assert_eq!(resolution(daily, TimeKind::Date), Unit::Day);
        let k = TimeKind::DateTime(None);
        let secs = |v: &[&str]| {
            v.iter()
                .map(|s| time::parse(s).unwrap().0)
                .collect::<Vec<_>>()
        };
        assert_eq!(
            resolution(secs(&["2020-01-01T00:00:00Z", "2020-03-01T00:00:00Z"]), k),
            Unit::Month
        );
        assert_eq!(
            resolution(secs(&["2020-01-01T00:00:00Z", "2020-01-01T00:00:00.5Z"]), k),
            Unit::Clock
        );
        assert_eq!(resolution([f64::NAN], k), Unit::Year);
        // Four months of monthly data: month ticks, where the span alone
        // would ask for two-week ticks.
        let (lo, hi) = (monthly[0], monthly[3]);
        let free = Axis::calendar(lo, hi, 0.03, 12, TimeKind::Date, Unit::Clock);
        assert_eq!(free.calendar, Some((TimeKind::Date, Unit::Day)));
        let m = Axis::calendar(lo, hi, 0.03, 12, TimeKind::Date, Unit::Month);
        let labels: Vec<String> = m.ticks.iter().map(|t| m.label(*t)).collect();
        assert_eq!(labels, ["2020-01", "2020-02", "2020-03", "2020-04"]);
        // Six years of yearly data: one tick a year, not every few months.
        let y = Axis::calendar(yearly[0], yearly[2], 0.0, 12, TimeKind::Date, Unit::Year);
        let labels: Vec<String> = y.ticks.iter().map(|t| y.label(*t)).collect();
        assert_eq!(labels, ["1990", "1991", "1992", "1993", "1994", "1995"]);
    }

    #[test]
    fn date_axes_tick_at_calendar_units() {
        let day = |s: &str| time::parse(s).unwrap().0;
        let a = Axis::calendar(
            day("2024-01-01"),
            day("2024-01-09"),
            0.0,
            6,
            TimeKind::Date,
            Unit::Clock,
        );
        let labels: Vec<String> = a.ticks.iter().map(|t| a.label(*t)).collect();
        assert_eq!(
            labels,
            ["2024-01-02", "2024-01-04", "2024-01-06", "2024-01-08"]
        );
        let m = Axis::calendar(
            day("2023-11-20"),
            day("2024-06-10"),
            0.0,
            6,
            TimeKind::Date,
            Unit::Clock,
        );
        let labels: Vec<String> = m.ticks.iter().map(|t| m.label(*t)).collect();
        assert_eq!(labels, ["2024-01", "2024-03", "2024-05"]);
        let y = Axis::calendar(
            day("1990-06-01"),
            day("2024-06-01"),
            0.0,
            6,
            TimeKind::Date,
            Unit::Clock,
        );
        let labels: Vec<String> = y.ticks.iter().map(|t| y.label(*t)).collect();
        assert_eq!(labels, ["2000", "2010", "2020"]);
        let k = TimeKind::DateTime(None);
        let sec = |s: &str| time::parse(s).unwrap().0;
        let h = Axis::calendar(
            sec("2024-03-01T06:00:00Z"),
            sec("2024-03-01T18:00:00Z"),
            0.0,
            5,
            k,
            Unit::Clock,
        );
        let labels: Vec<String> = h.ticks.iter().map(|t| h.label(*t)).collect();
        assert_eq!(
            labels,
            [
                "03-01 06:00",
                "03-01 09:00",
                "03-01 12:00",
                "03-01 15:00",
                "03-01 18:00"
            ]
        );
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
