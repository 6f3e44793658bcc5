//! Tables: comma-, semicolon- or tab-separated values with an optional header,
//! `#` comments, blank lines, CRLF and a byte-order mark.

use anyhow::{anyhow, Result};

use super::{too_many, utf8, Points, Pos, Positions};

/// Picks the separator from the first line that is not blank or a comment:
/// a tab, else a semicolon, else a comma.
fn sniff_delimiter(text: &str) -> u8 {
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))
        .unwrap_or("");
    if first.contains('\t') {
        b'\t'
    } else if first.contains(';') {
        b';'
    } else {
        b','
    }
}

/// The first byte at or after `from` that is not blank or in a comment line: the
/// reader reports a record's position where it started reading, before the
/// line ends and comments it skipped.
fn skip_blank(text: &str, from: usize) -> usize {
    let b = text.as_bytes();
    let mut i = from;
    while i < b.len() {
        match b[i] {
            b' ' | b'\t' | b'\r' | b'\n' => i += 1,
            b'#' => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            _ => break,
        }
    }
    i
}

/// Parses one number of a table. Accepts what Rust's `f64` parser accepts
/// (`1E-3`, `+2`, `.5`) but refuses NaN, infinities and overflow.
fn parse_number(field: &str) -> std::result::Result<f64, String> {
    if field.is_empty() {
        return Err("empty field".to_owned());
    }
    match field.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("'{}' is not a finite number", show(field))),
        Err(_) => Err(format!("'{}' is not a number", show(field))),
    }
}

/// A field for a one-line message: control characters escaped, at most 40
/// characters.
fn show(field: &str) -> String {
    let mut s: String = field
        .chars()
        .take(40)
        .flat_map(char::escape_debug)
        .collect();
    if field.chars().count() > 40 {
        s.push_str("...");
    }
    s
}

/// Parses a table of numbers: an optional header line, `#` comments, blank lines,
/// CRLF, a BOM, spaces around fields; `delimiter` or one sniffed from the data.
///
/// # Errors
///
/// `FILE:LINE: ...` for invalid UTF-8, a field that is not a finite number, a row
/// with another number of fields than the first, a header after data.
pub fn parse_table(
    name: &str,
    bytes: &[u8],
    delimiter: Option<u8>,
    max_points: usize,
) -> Result<Points> {
    let text = utf8(name, bytes)?;
    let delimiter = delimiter.unwrap_or_else(|| sniff_delimiter(text));
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut coords: Vec<f64> = Vec::new();
    let mut lines: Vec<usize> = Vec::new();
    let mut header_line: Option<usize> = None;
    let mut first_width: Option<(usize, usize)> = None;
    let mut record = csv::StringRecord::new();
    // The line of byte `counted`: newlines are counted once, as records advance.
    let mut line = 1usize;
    let mut counted = 0usize;
    loop {
        let more = reader
            .read_record(&mut record)
            .map_err(|e| anyhow!("{name}: {e}"))?;
        if !more {
            break;
        }
        // The reader's own line count skips comments; count newlines instead.
        let byte = record
            .position()
            .map_or(0, |p| usize::try_from(p.byte()).unwrap_or(usize::MAX));
        // Records come in order: move the line cursor forward.
        let start = skip_blank(text, byte).min(text.len());
        if start > counted {
            line += text.as_bytes()[counted..start]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            counted = start;
        }
        if record.iter().all(str::is_empty) || record.get(0).is_some_and(|f| f.starts_with('#')) {
            continue; // a line of spaces, or an indented comment
        }
        let row_start = coords.len();
        let mut bad = None;
        for (i, field) in record.iter().enumerate() {
            match parse_number(field) {
                Ok(v) => coords.push(v),
                Err(msg) => {
                    bad = Some((i, msg));
                    break;
                }
            }
        }
        if let Some((i, msg)) = bad {
            coords.truncate(row_start);
            let numeric = record.iter().filter(|f| parse_number(f).is_ok()).count();
            if lines.is_empty() && header_line.is_none() && numeric == 0 {
                header_line = Some(line);
                continue;
            }
            let hint = if numeric == 0 {
                " (a header line in the middle of the data?)"
            } else {
                ""
            };
            return Err(anyhow!("{name}:{line}: field {}: {msg}{hint}", i + 1));
        }
        let width = coords.len() - row_start;
        match first_width {
            None => first_width = Some((width, line)),
            Some((w, first)) if w != width => {
                let hint = if delimiter == b',' && width > w {
                    " (a comma used as the decimal separator?)"
                } else {
                    ""
                };
                return Err(anyhow!(
                    "{name}:{line}: {width} fields, but line {first} has {w}{hint}"
                ));
            }
            Some(_) => {}
        }
        if lines.len() >= max_points {
            return Err(too_many(&format!("{name}:{line}"), max_points));
        }
        lines.push(line);
    }
    let last_line = text.lines().count().max(1);
    let width = first_width.map_or(0, |(w, _)| w);
    Ok(Points::new(
        name,
        (width, lines.len()),
        coords,
        Positions::Lines(lines),
        Pos::Line(last_line),
    ))
}
