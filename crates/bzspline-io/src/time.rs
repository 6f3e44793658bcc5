//! Dates and times as x: ISO 8601 dates (`2024-03-01`), read as days since
//! 1970-01-01, and date-times (`2024-03-01T06:00:00Z`, with an offset such as
//! `+02:00`, or naive and then read as UTC), read as seconds since
//! 1970-01-01T00:00:00Z; and the way back, in the input's form.

use jiff::civil::Date;
use jiff::fmt::temporal::Pieces;
use jiff::tz::{Offset, TimeZone};
use jiff::Timestamp;

/// The form of a column of dates or times, which decides its unit and how
/// numbers are written back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeKind {
    /// Calendar dates: days since 1970-01-01.
    Date,
    /// Date-times: seconds since 1970-01-01T00:00:00Z, written back with the
    /// first row's offset (`None`: UTC, written with `Z`).
    DateTime(Option<Offset>),
}

const SECONDS_PER_DAY: f64 = 86_400.0;

/// A date or date-time: its number in its own kind's unit, and its kind.
/// `None` for text that is neither.
#[must_use]
pub fn parse(text: &str) -> Option<(f64, TimeKind)> {
    let text = text.trim();
    // Only text that starts like a date: jiff's parser takes more forms
    // (week dates, ordinal dates) than a table's x column should.
    let b = text.as_bytes();
    if b.len() < 10 || b[4] != b'-' || b[7] != b'-' {
        return None;
    }
    let pieces = Pieces::parse(text).ok()?;
    let date = pieces.date();
    let Some(time) = pieces.time() else {
        return (pieces.offset().is_none()).then(|| (days_of(date), TimeKind::Date));
    };
    let offset = pieces.offset().map(|o| o.to_numeric_offset());
    let civil = date.to_datetime(time);
    let tz = offset.map_or(TimeZone::UTC, TimeZone::fixed);
    let ts = tz.to_timestamp(civil).ok()?;
    let keep = offset.filter(|o| *o != Offset::UTC);
    Some((seconds_of(ts), TimeKind::DateTime(keep)))
}

/// `value` of kind `from` in the unit of kind `to` (days or seconds).
#[must_use]
pub fn convert(value: f64, from: TimeKind, to: TimeKind) -> f64 {
    match (from, to) {
        (TimeKind::Date, TimeKind::DateTime(_)) => value * SECONDS_PER_DAY,
        (TimeKind::DateTime(_), TimeKind::Date) => value / SECONDS_PER_DAY,
        _ => value,
    }
}

/// `value` (in `kind`'s unit) written in `kind`'s form: a whole number of days
/// as a date, anything else as a date-time to the nanosecond. `None` outside
/// the years -9999 to 9999.
#[must_use]
pub fn format(value: f64, kind: TimeKind) -> Option<String> {
    match kind {
        TimeKind::Date if value.fract() == 0.0 => {
            let days = value as i64;
            let date = Date::constant(1970, 1, 1)
                .checked_add(jiff::Span::new().try_days(days).ok()?)
                .ok()?;
            Some(date.to_string())
        }
        TimeKind::Date => format(value * SECONDS_PER_DAY, TimeKind::DateTime(None)),
        TimeKind::DateTime(offset) => {
            let ns = (value * 1e9).round();
            if ns.is_nan() || ns.abs() >= 4e20 {
                return None;
            }
            let ts = Timestamp::from_nanosecond(ns as i128).ok()?;
            Some(match offset {
                None => ts.to_string(),
                Some(o) => ts.display_with_offset(o).to_string(),
            })
        }
    }
}

fn days_of(date: Date) -> f64 {
    let epoch = Date::constant(1970, 1, 1);
    f64::from(epoch.until(date).map_or(0, |s| s.get_days()))
}

fn seconds_of(ts: Timestamp) -> f64 {
    ts.as_nanosecond() as f64 / 1e9
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_days_and_come_back_as_dates() {
        assert_eq!(parse("1970-01-02"), Some((1.0, TimeKind::Date)));
        let (v, k) = parse("2024-03-01").unwrap();
        assert_eq!(v, 19_783.0);
        assert_eq!(format(v, k).as_deref(), Some("2024-03-01"));
        assert_eq!(format(v + 0.5, k).as_deref(), Some("2024-03-01T12:00:00Z"));
        assert_eq!(parse("1969-12-31"), Some((-1.0, TimeKind::Date)));
    }

    #[test]
    fn date_times_are_seconds_with_their_offset() {
        let (v, k) = parse("2024-03-01T06:00:00Z").unwrap();
        assert_eq!(v, 19_783.0 * 86_400.0 + 6.0 * 3600.0);
        assert_eq!(k, TimeKind::DateTime(None));
        assert_eq!(format(v, k).as_deref(), Some("2024-03-01T06:00:00Z"));
        // A naive time is read as UTC.
        assert_eq!(parse("2024-03-01T06:00:00").unwrap().0, v);
        let (w, k) = parse("2024-03-01T08:00:00+02:00").unwrap();
        assert_eq!(w, v);
        assert_eq!(format(w, k).as_deref(), Some("2024-03-01T08:00:00+02:00"));
        assert_eq!(
            format(v + 1.5, TimeKind::DateTime(None)).as_deref(),
            Some("2024-03-01T06:00:01.5Z")
        );
        assert_eq!(convert(1.0, TimeKind::Date, k), 86_400.0);
    }

    #[test]
    fn other_text_is_no_time() {
        for t in [
            "1.5",
            "2024",
            "2024-13-01",
            "2024-02-30",
            "x",
            "2024-03-01T25:00:00Z",
            "",
        ] {
            assert_eq!(parse(t), None, "{t}");
        }
        assert_eq!(format(1e300, TimeKind::Date), None);
    }
}
