//! Tables: comma-, semicolon-, tab- or whitespace-separated values with an
//! optional header naming the columns, `#` comments, blank lines, CRLF and a
//! byte-order mark; the columns chosen by name or number, the first of them
//! holding numbers or dates.

use anyhow::{anyhow, bail, Result};

use super::{too_many, utf8, Points, Pos, Positions};
use crate::time::{self, DateFormat, TimeKind};

/// A column, by its header name or its number (from 1).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Col {
    /// The column whose header is this name.
    Name(String),
    /// The column with this number, 1 for the first.
    Index(usize),
}

impl Col {
    /// A number from 1 is an index, anything else a name.
    #[must_use]
    pub fn parse(text: &str) -> Col {
        match text.trim().parse::<usize>() {
            Ok(i) if i >= 1 => Col::Index(i),
            _ => Col::Name(text.trim().to_owned()),
        }
    }
}

impl std::fmt::Display for Col {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Col::Name(n) => write!(f, "'{}'", show(n)),
            Col::Index(i) => write!(f, "{i}"),
        }
    }
}

/// Which columns of a table are read, in order: `--columns`, or `--x` and
/// `--y`; every column when nothing is chosen; and how the first of them
/// writes its dates.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Select {
    /// The abscissa (`--x`).
    pub x: Option<Col>,
    /// The ordinate (`--y`); alone, it is read over its row index.
    pub y: Option<Col>,
    /// The columns of a curve's coordinates, or x and y (`--columns`).
    pub columns: Option<Vec<Col>>,
    /// The form of the first column's dates (`--date-format`); without it,
    /// numbers and the forms of [`time::AUTO_FORMS`].
    pub dates: Option<DateFormat>,
    /// A column of weights for a smoothing fit (`--weights`): finite numbers
    /// `>= 0`, read into [`Points::weights`] and left out of the columns read
    /// when none are chosen.
    pub weights: Option<Col>,
}

/// The chosen columns of a table whose rows have `width` fields, by number
/// (from 0): every column but the weights when none are chosen; a `y`
/// chosen alone comes back as the only column. Then the weights' column.
fn resolve(
    select: &Select,
    header: Option<&[String]>,
    width: usize,
    name: &str,
) -> Result<(Vec<usize>, Option<usize>)> {
    let find = |c: &Col, opt: &str| -> Result<usize> {
        match c {
            Col::Index(i) if *i <= width => Ok(i - 1),
            Col::Index(i) => Err(anyhow!(
                "{name}: no column {i} ({opt}): the rows have {width} field{}",
                if width == 1 { "" } else { "s" }
            )),
            Col::Name(n) => match header {
                Some(h) => h.iter().position(|f| f == n).ok_or_else(|| {
                    anyhow!(
                        "{name}: no column named {c} ({opt}); the header names {}",
                        h.iter()
                            .map(|f| format!("'{}'", show(f)))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                }),
                None => Err(anyhow!(
                    "{name}: no header line to find the column named {c} ({opt}) in"
                )),
            },
        }
    };
    let weights = match &select.weights {
        Some(c) => Some(find(c, "--weights")?),
        None => None,
    };
    let not_weights = |j: &usize| Some(*j) != weights;
    let cols = match (&select.columns, &select.x, &select.y) {
        (Some(cols), _, _) => cols
            .iter()
            .map(|c| find(c, "--columns"))
            .collect::<Result<_>>()?,
        (None, Some(x), Some(y)) => vec![find(x, "--x")?, find(y, "--y")?],
        (None, Some(x), None) => {
            let x = find(x, "--x")?;
            let y = (0..width)
                .filter(not_weights)
                .find(|&j| j != x)
                .ok_or_else(|| {
                    anyhow!("{name}: --x names the only column: no y to read beside it")
                })?;
            vec![x, y]
        }
        (None, None, Some(y)) => vec![find(y, "--y")?],
        (None, None, None) => (0..width).filter(not_weights).collect(),
    };
    if let Some(w) = weights {
        if cols.contains(&w) {
            bail!(
                "{name}: --weights names column {}, which is read as a coordinate too",
                w + 1
            );
        }
    }
    Ok((cols, weights))
}

/// Picks the separator from the first line that is not blank or a comment:
/// a tab, else a semicolon, else a comma, else (for fields apart by spaces
/// only) runs of whitespace, given as `b' '`.
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
    } else if first.contains(',') || !first.contains(' ') {
        b','
    } else {
        b' '
    }
}

/// A whitespace-separated table as a tab-separated one: every run of spaces
/// and tabs inside a line becomes one tab (lines and their count unchanged).
fn tabs_for_spaces(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for (i, line) in text.split('\n').enumerate() {
        if i > 0 {
            out.push('\n');
        }
        let line = line.trim_matches(|c| c == ' ' || c == '\t');
        let mut gap = false;
        for ch in line.chars() {
            if ch == ' ' || ch == '\t' {
                gap = true;
            } else {
                if gap {
                    out.push('\t');
                    gap = false;
                }
                out.push(ch);
            }
        }
    }
    out
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

/// The first column's field: a number, or a date or date-time of the kind the
/// column's first row set (`kind`: unset, `None` for numbers, the kind of
/// dates); with `dates`, a date in that form (numbers too: `20000131`).
fn read_x(
    field: &str,
    kind: &mut Option<Option<TimeKind>>,
    dates: Option<&DateFormat>,
) -> std::result::Result<f64, String> {
    let date = match dates {
        Some(f) => Some(f.parse(field)?),
        None => None,
    };
    if date.is_none() {
        if let Ok(v) = parse_number(field) {
            return match kind {
                Some(Some(_)) => Err(format!(
                    "'{}' is a number, but the column holds dates",
                    show(field)
                )),
                _ => {
                    *kind = Some(None);
                    Ok(v)
                }
            };
        }
    }
    match (date.or_else(|| time::parse(field)), *kind) {
        (Some((v, k)), None) => {
            *kind = Some(Some(k));
            Ok(v)
        }
        (Some((v, k)), Some(Some(want))) => Ok(time::convert(v, k, want)),
        (Some(_), Some(None)) => Err(format!(
            "'{}' is a date, but the column holds numbers",
            show(field)
        )),
        (None, _) if time::ambiguous(field) => Err(format!(
            "'{}' could be day/month or month/day: give --date-format, for example %d/%m/%Y or %m/%d/%Y (read without it: {})",
            show(field),
            time::AUTO_FORMS
        )),
        (None, _) => match field.parse::<f64>() {
            Ok(_) => parse_number(field),
            Err(_) if field.is_empty() => parse_number(field),
            Err(_) => Err(time::not_a_number_or_date(&show(field))),
        },
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

/// Parses a table of numbers, every column: see [`parse_table_with`].
///
/// # Errors
///
/// As [`parse_table_with`].
pub fn parse_table(
    name: &str,
    bytes: &[u8],
    delimiter: Option<u8>,
    max_points: usize,
) -> Result<Points> {
    parse_table_with(name, bytes, delimiter, max_points, &Select::default())
}

/// Parses a table: an optional header line (the first line in which no field
/// is a number or a date) naming the columns, `#` comments, blank lines, CRLF,
/// a BOM, spaces around fields; `delimiter` or one sniffed from the data
/// (whitespace-separated when the first line has only spaces between its
/// fields). `select` picks the columns read, in its order; the first of them
/// may hold ISO 8601 dates or date-times instead of numbers (see
/// [`crate::time`]), all of one column's rows alike.
///
/// # Errors
///
/// `FILE:LINE: ...` for invalid UTF-8, a field that is not a finite number (or
/// date, in the first column read), a row with another number of fields than
/// the first, a header after data; `FILE: ...` for a chosen column that is not
/// there.
pub fn parse_table_with(
    name: &str,
    bytes: &[u8],
    delimiter: Option<u8>,
    max_points: usize,
    select: &Select,
) -> Result<Points> {
    let text = utf8(name, bytes)?;
    let delimiter = delimiter.unwrap_or_else(|| sniff_delimiter(text));
    let spaced;
    let (text, delimiter) = if delimiter == b' ' {
        spaced = tabs_for_spaces(text);
        (spaced.as_str(), b'\t')
    } else {
        (text, delimiter)
    };
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut coords: Vec<f64> = Vec::new();
    let mut lines: Vec<usize> = Vec::new();
    let mut header: Option<Vec<String>> = None;
    let mut first_width: Option<(usize, usize)> = None;
    // The columns read (by number), fixed at the first row of data, and
    // the weights' column.
    let mut chosen: Option<Vec<usize>> = None;
    let mut weight_col: Option<usize> = None;
    let mut weights: Vec<f64> = Vec::new();
    // The first column's kind of date, fixed at the first row of data.
    let mut kind: Option<Option<TimeKind>> = None;
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
        let readable = |f: &str| {
            parse_number(f).is_ok()
                || time::parse(f).is_some()
                || time::ambiguous(f)
                || select.dates.as_ref().is_some_and(|d| d.parse(f).is_ok())
        };
        let numeric = record.iter().filter(|f| readable(f)).count();
        if lines.is_empty() && header.is_none() && numeric == 0 {
            header = Some(record.iter().map(str::to_owned).collect());
            continue;
        }
        let width = record.len();
        check_width(&mut first_width, width, (name, line), delimiter)?;
        if chosen.is_none() {
            let (cols, w) = resolve(select, header.as_deref(), width, name)?;
            chosen = Some(cols);
            weight_col = w;
        }
        let cols = chosen.as_deref().unwrap_or_default();
        read_row(
            &record,
            cols,
            (&mut kind, select.dates.as_ref()),
            numeric == 0,
            (name, line),
            &mut coords,
        )?;
        if let Some(j) = weight_col {
            weights.push(read_weight(record.get(j).unwrap_or(""), (name, line), j)?);
        }
        if lines.len() >= max_points {
            return Err(too_many(&format!("{name}:{line}"), max_points));
        }
        lines.push(line);
    }
    let last_line = text.lines().count().max(1);
    let width = chosen.as_ref().map_or(0, Vec::len);
    let mut points = Points::new(
        name,
        (width, lines.len()),
        coords,
        Positions::Lines(lines),
        Pos::Line(last_line),
    );
    if let (Some(h), Some(cols)) = (&header, &chosen) {
        points.names = Some(
            cols.iter()
                .map(|&j| h.get(j).cloned().unwrap_or_default())
                .collect(),
        );
    }
    points.time = kind.flatten();
    points.weights = weight_col.map(|_| weights);
    Ok(points)
}

/// A field of the weights' column (number `j` from 0): a finite number
/// `>= 0`.
fn read_weight(field: &str, (name, line): (&str, usize), j: usize) -> Result<f64> {
    let field_no = j + 1;
    match parse_number(field) {
        Ok(v) if v >= 0.0 => Ok(v),
        Ok(v) => bail!("{name}:{line}: field {field_no}: weight {v} is negative"),
        Err(msg) => bail!("{name}:{line}: field {field_no}: {msg} (a weight)"),
    }
}

/// Checks a row's number of fields against the first row's (kept in
/// `first` with its line).
fn check_width(
    first: &mut Option<(usize, usize)>,
    width: usize,
    (name, line): (&str, usize),
    delimiter: u8,
) -> Result<()> {
    match *first {
        None => *first = Some((width, line)),
        Some((w, at)) if w != width => {
            let hint = if delimiter == b',' && width > w {
                " (a comma used as the decimal separator?)"
            } else {
                ""
            };
            return Err(anyhow!(
                "{name}:{line}: {width} fields, but line {at} has {w}{hint}"
            ));
        }
        Some(_) => {}
    }
    Ok(())
}

/// Reads the chosen columns of a row onto `coords`: the first as x (a
/// number or a date, of one kind throughout), the others as numbers.
fn read_row(
    record: &csv::StringRecord,
    cols: &[usize],
    (kind, dates): (&mut Option<Option<TimeKind>>, Option<&DateFormat>),
    no_numbers: bool,
    (name, line): (&str, usize),
    coords: &mut Vec<f64>,
) -> Result<()> {
    for (slot, &j) in cols.iter().enumerate() {
        let field = record.get(j).unwrap_or("");
        let read = if slot == 0 {
            read_x(field, kind, dates)
        } else {
            parse_number(field)
        };
        match read {
            Ok(v) => coords.push(v),
            Err(msg) => {
                let hint = if no_numbers {
                    " (a header line in the middle of the data?)"
                } else {
                    ""
                };
                return Err(anyhow!("{name}:{line}: field {}: {msg}{hint}", j + 1));
            }
        }
    }
    Ok(())
}
