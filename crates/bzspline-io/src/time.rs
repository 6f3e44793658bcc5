//! Dates and times as x: dates (`2024-03-01`, and the other unambiguous forms
//! of [`AUTO_FORMS`]), read as days since 1970-01-01, and date-times
//! (`2024-03-01T06:00:00Z`, with an offset such as `+02:00`, or naive and then
//! read as UTC), read as seconds since 1970-01-01T00:00:00Z; any other form
//! through a [`DateFormat`] (strftime's directives); and the way back, in
//! ISO 8601.

use jiff::civil::Date;
use jiff::fmt::strtime;
use jiff::fmt::temporal::Pieces;
use jiff::tz::{Offset, TimeZone};
use jiff::Timestamp;

/// The forms read as dates without a [`DateFormat`], for messages and help.
pub const AUTO_FORMS: &str = "2000-01-31, 2000-01-31T13:45:00Z or 2000-01-31 13:45 (with an offset such as +02:00, or read as UTC), 2000/01/31, 2000-01 (a month), Jan 31 2000, January 31, 2000, 31 Jan 2000";

/// Forms with a month's name, tried in order.
const NAMED: [&str; 7] = [
    "%b %d %Y",
    "%B %d %Y",
    "%b %d, %Y",
    "%B %d, %Y",
    "%d %b %Y",
    "%d %B %Y",
    "%a %b %d %Y",
];

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
    let b = text.as_bytes();
    let digits = |r: std::ops::Range<usize>| b[r].iter().all(u8::is_ascii_digit);
    // A month, `2000-01`: its first day.
    if b.len() == 7 && b[4] == b'-' && digits(0..4) && digits(5..7) {
        return with_format("%Y-%m", text).ok();
    }
    // `2000/01/31`: year first, so not ambiguous.
    if b.len() == 10 && b[4] == b'/' && b[7] == b'/' && digits(0..4) {
        return with_format("%Y/%m/%d", text).ok();
    }
    if b.first().is_some_and(u8::is_ascii_alphabetic)
        || b.iter().any(u8::is_ascii_alphabetic)
            && b.first().is_some_and(u8::is_ascii_digit)
            && b.len() < 20
    {
        if let Some(t) = NAMED.iter().find_map(|f| with_format(f, text).ok()) {
            return Some(t);
        }
    }
    // Only text that starts like a date: jiff's parser takes more forms
    // (week dates, ordinal dates) than a table's x column should.
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

/// Whether `text` is a date whose day and month could be either way round
/// (`01/02/2000`, `1-2-00`, `01.02.2000`): such dates need a
/// [`DateFormat`].
#[must_use]
pub fn ambiguous(text: &str) -> bool {
    let parts: Vec<&str> = text.trim().split(['/', '-', '.']).collect();
    let number = |p: &str, lo: usize, hi: usize| {
        (lo..=hi).contains(&p.len()) && p.bytes().all(|c| c.is_ascii_digit())
    };
    parts.len() == 3 && number(parts[0], 1, 2) && number(parts[1], 1, 2) && number(parts[2], 2, 4)
}

/// The message for text that is neither a number nor a date of a known
/// form. Text with a digit in it may be a date in another form, so the
/// message lists the forms read and names `--date-format`; a word (a
/// header, `NA`) gets the plain message.
#[must_use]
pub fn not_a_number_or_date(text: &str) -> String {
    if text.bytes().any(|c| c.is_ascii_digit()) {
        format!(
            "'{text}' is not a number or a date (dates are read as {AUTO_FORMS}; give --date-format for any other form)"
        )
    } else {
        format!("'{text}' is not a number or a date")
    }
}

/// A date format with strftime's (and d3-time-format's) directives: `%Y`
/// `%m` `%d`, `%b` (a month's name), `%H` `%M` `%S`, `%z` (an offset),
/// `%s` (seconds since 1970). A format without a day reads the first day of
/// the month (`%Y-%m`); without an hour, dates; with one, date-times, at the
/// offset `%z` gives or else in UTC.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DateFormat(String);

impl DateFormat {
    /// Checks a format: it must have directives jiff knows and name a date.
    ///
    /// # Errors
    ///
    /// The words of a message (the caller names the option).
    pub fn new(format: &str) -> Result<DateFormat, String> {
        let a = jiff::civil::date(2001, 2, 3).at(4, 5, 6, 0);
        let b = jiff::civil::date(2009, 8, 7).at(4, 5, 6, 0);
        let write = |d: jiff::civil::DateTime| {
            let tm = strtime::BrokenDownTime::from(
                &d.to_zoned(TimeZone::UTC).map_err(|e| e.to_string())?,
            );
            tm.to_string(format).map_err(|e| e.to_string())
        };
        let (x, y) = (write(a)?, write(b)?);
        if x == y {
            return Err(format!(
                "{format:?} names no date: give a year, a month and a day, for example %d/%m/%Y"
            ));
        }
        Ok(DateFormat(format.to_owned()))
    }

    /// The format as given.
    #[must_use]
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// Reads `text` in this format.
    ///
    /// # Errors
    ///
    /// Text that does not match, as the words of a message.
    pub fn parse(&self, text: &str) -> Result<(f64, TimeKind), String> {
        with_format(&self.0, text.trim()).map_err(|e| {
            format!(
                "'{}' does not match the date format '{}' ({e})",
                text.trim(),
                self.0
            )
        })
    }
}

/// `text` read with strftime's `format`: dates without an hour, date-times
/// with one (at their offset, or UTC).
fn with_format(format: &str, text: &str) -> Result<(f64, TimeKind), String> {
    let mut tm = strtime::parse(format, text).map_err(|e| e.to_string())?;
    if tm.day().is_none() && tm.month().is_some() {
        tm.set_day(Some(1)).map_err(|e| e.to_string())?;
    }
    if tm.hour().is_some() || format.contains("%s") {
        let ts = match tm.to_timestamp() {
            Ok(ts) => ts,
            // No offset: a naive time, read as UTC.
            Err(_) => {
                let dt = tm.to_datetime().map_err(|e| e.to_string())?;
                TimeZone::UTC.to_timestamp(dt).map_err(|e| e.to_string())?
            }
        };
        let keep = tm.offset().filter(|o| *o != Offset::UTC);
        return Ok((seconds_of(ts), TimeKind::DateTime(keep)));
    }
    let date = tm.to_date().map_err(|e| e.to_string())?;
    Ok((days_of(date), TimeKind::Date))
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
    fn unambiguous_forms_are_read_without_a_format() {
        let day = parse("2000-01-31");
        for t in [
            "2000/01/31",
            "Jan 31 2000",
            "January 31, 2000",
            "31 Jan 2000",
            "31 january 2000",
            "Mon Jan 31 2000",
        ] {
            assert_eq!(parse(t), day, "{t}");
        }
        assert_eq!(parse("2000-01"), parse("2000-01-01"));
        let noon = parse("2000-01-31T12:00:00Z");
        assert!(noon.is_some());
        assert_eq!(parse("2000-01-31 12:00:00"), noon);
        assert_eq!(parse("2000-01-31 12:00"), noon);
        // A number that looks like a date stays a number.
        assert_eq!(parse("20000131"), None);
    }

    #[test]
    fn day_and_month_either_way_round_are_ambiguous() {
        for t in ["01/02/2000", "1/2/00", "01.02.2000", "31-01-2000"] {
            assert!(ambiguous(t), "{t}");
            assert_eq!(parse(t), None, "{t}");
        }
        for t in ["2000/01/31", "2000-01-31", "20000131", "1/2", "1.5"] {
            assert!(!ambiguous(t), "{t}");
        }
    }

    #[test]
    fn formats_read_any_form() {
        let want = parse("2000-02-01").unwrap();
        let f = |fmt: &str| DateFormat::new(fmt).unwrap();
        assert_eq!(f("%d/%m/%Y").parse("01/02/2000"), Ok(want));
        assert_eq!(f("%m/%d/%Y").parse("02/01/2000"), Ok(want));
        assert_eq!(f("%Y%m%d").parse("20000201"), Ok(want));
        assert_eq!(f("%Y-%m").parse("2000-02"), Ok(want));
        assert_eq!(f("%b %d %Y").parse("Feb 1 2000"), Ok(want));
        let (v, k) = f("%d.%m.%Y %H:%M %z")
            .parse("01.02.2000 08:00 +0200")
            .unwrap();
        assert_eq!(v, want.0 * 86_400.0 + 6.0 * 3600.0);
        assert_eq!(k, TimeKind::DateTime(Some(Offset::constant(2))));
        assert_eq!(
            f("%d/%m/%Y %H:%M").parse("01/02/2000 06:00").unwrap().0,
            want.0 * 86_400.0 + 6.0 * 3600.0
        );
        let e = f("%d/%m/%Y").parse("2000-02-01").unwrap_err();
        assert!(
            e.contains("does not match the date format '%d/%m/%Y'"),
            "{e}"
        );
        assert!(f("%d/%m/%Y").parse("31/02/2000").is_err());
        assert!(DateFormat::new("%H:%M")
            .unwrap_err()
            .contains("names no date"));
        assert!(DateFormat::new("%Q%!").is_err());
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
