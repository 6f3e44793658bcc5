//! Readers for control points: CSV/TSV, JSON, GeoJSON and the paper's examples.
//! Every point keeps where it came from, so that errors (the readers' own and the
//! library's, which carry 0-based indices) name the file and line at fault.

use std::fmt;
use std::io::Read;
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use serde_json::Value;

use crate::cli::{InputArgs, InputFormat};

/// Where a point came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pos {
    /// A line of a text table (1-based).
    Line(usize),
    /// An element of a JSON array (0-based).
    Item(usize),
    /// Coordinate `index` (0-based) of GeoJSON feature `feature` (0-based).
    Coord {
        /// The feature (or geometry) in the document.
        feature: usize,
        /// The position in its coordinate list.
        index: usize,
    },
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Pos::Line(l) => write!(f, "line {l}"),
            Pos::Item(i) => write!(f, "point [{i}]"),
            Pos::Coord { feature, index } => write!(f, "feature {feature}, coordinate {index}"),
        }
    }
}

/// Where each row of a [`Points`] came from, stored compactly: a table keeps one
/// line number per row, a JSON array or a GeoJSON coordinate list none at all.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Positions {
    /// Row `i` is on line `lines[i]` of a table.
    Lines(Vec<usize>),
    /// Row `i` is element `i` of a JSON array.
    Items,
    /// Row `i` is coordinate `i` of GeoJSON feature `feature`.
    Coords {
        /// The feature (or geometry) in the document.
        feature: usize,
    },
    /// Row `i` is the only coordinate of Point feature `features[i]`.
    Features(Vec<usize>),
}

/// Points read from one source: rows of numbers, all of one width, stored flat,
/// each with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct Points {
    /// The source's name in messages: the path, `<stdin>` or `example 1`.
    pub source: String,
    /// Numbers per row.
    pub width: usize,
    /// Number of rows (kept apart from `coords` for rows of width 0).
    pub len: usize,
    /// The numbers, row after row.
    pub coords: Vec<f64>,
    /// Where each row came from.
    pub pos: Positions,
    /// Where the source ended (the last line of a table), for "no data" errors.
    pub end: Pos,
}

impl Points {
    /// `len` rows of `width` numbers from a flat list, with their positions.
    fn new(
        source: &str,
        (width, len): (usize, usize),
        coords: Vec<f64>,
        pos: Positions,
        end: Pos,
    ) -> Self {
        Points {
            source: source.to_owned(),
            width,
            len,
            coords,
            pos,
            end,
        }
    }

    /// Number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there are no rows.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Row `i` (empty past the last row).
    #[must_use]
    pub fn row(&self, i: usize) -> &[f64] {
        self.coords
            .get(i * self.width..(i + 1) * self.width)
            .unwrap_or_default()
    }

    /// The rows in order.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = &[f64]> + '_ {
        (0..self.len).map(|i| self.row(i))
    }

    /// Column `j` of every row.
    #[must_use]
    pub fn column(&self, j: usize) -> Vec<f64> {
        self.rows()
            .map(|r| r.get(j).copied().unwrap_or(0.0))
            .collect()
    }

    /// Where row `i` came from (the end of the source past the last row).
    #[must_use]
    pub fn pos(&self, i: usize) -> Pos {
        if i >= self.len {
            return self.end;
        }
        match &self.pos {
            Positions::Lines(l) => l.get(i).map_or(self.end, |&l| Pos::Line(l)),
            Positions::Items => Pos::Item(i),
            Positions::Coords { feature } => Pos::Coord {
                feature: *feature,
                index: i,
            },
            Positions::Features(f) => f
                .get(i)
                .map_or(self.end, |&feature| Pos::Coord { feature, index: 0 }),
        }
    }

    /// `FILE:LINE` (or `FILE: point [i]`) for row `i`.
    #[must_use]
    pub fn at(&self, i: usize) -> String {
        locate(&self.source, self.pos(i))
    }

    /// The position of row `i` in words (`line 4`).
    #[must_use]
    pub fn pos_words(&self, i: usize) -> String {
        self.pos(i).to_string()
    }
}

/// `FILE:LINE` for lines, `FILE: point [i]` otherwise.
#[must_use]
pub fn locate(source: &str, pos: Pos) -> String {
    match pos {
        Pos::Line(l) => format!("{source}:{l}"),
        other => format!("{source}: {other}"),
    }
}

/// The paper's Example 1: tau = 1..11.
pub const EXAMPLE1: [f64; 11] = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
/// The paper's Example 2: points of `y = sqrt(x - x^2)` at x = 0, 0.1, ..., 1, with
/// the digits the paper prints.
pub const EXAMPLE2: [f64; 11] = [
    0.0,
    0.3,
    0.4,
    0.458257569,
    0.489897949,
    0.5,
    0.4898979495,
    0.458257569,
    0.4,
    0.3,
    0.0,
];

/// The paper's example `n` (1 or 2) as points `(tau, F)`.
#[must_use]
pub fn example(n: u8) -> Points {
    let coords: Vec<f64> = if n == 1 {
        EXAMPLE1
            .iter()
            .enumerate()
            .flat_map(|(i, &y)| [i as f64 + 1.0, y])
            .collect()
    } else {
        // 0.1 * i, written as i / 10 so that 0.3 is the double nearest 0.3.
        EXAMPLE2
            .iter()
            .enumerate()
            .flat_map(|(i, &y)| [i as f64 / 10.0, y])
            .collect()
    };
    Points::new(
        &format!("example {n}"),
        (2, EXAMPLE1.len()),
        coords,
        Positions::Items,
        Pos::Item(11),
    )
}

/// How much input the readers take: more is refused with an error, before
/// memory runs out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most points (rows of a table, positions of a line) in one input.
    pub max_points: usize,
    /// Most bytes in one input file or standard input.
    pub max_bytes: u64,
}

impl Limits {
    /// The command's defaults (see `--max-points` and `--max-bytes`).
    #[cfg(test)]
    pub const DEFAULT: Limits = Limits {
        max_points: crate::cli::DEFAULT_MAX_POINTS,
        max_bytes: crate::cli::DEFAULT_MAX_BYTES,
    };

    /// The limits the input arguments set.
    #[must_use]
    pub fn of(args: &InputArgs) -> Limits {
        Limits {
            max_points: usize::try_from(args.max_points).unwrap_or(usize::MAX),
            max_bytes: args.max_bytes,
        }
    }
}

/// Reads all of a file (or standard input for `None` or `-`), refusing more
/// than `max_bytes` bytes before reading them (a file) or as soon as they have
/// arrived (standard input).
///
/// # Errors
///
/// The I/O error, with the file's name; the size limit, named `--max-bytes`.
pub fn read_source(file: Option<&Path>, max_bytes: u64) -> Result<(String, Vec<u8>)> {
    let too_big = |name: &str| {
        anyhow!("{name}: larger than {max_bytes} bytes (--max-bytes); split the input or raise the limit")
    };
    match file {
        Some(p) if p != Path::new("-") => {
            let name = p.display().to_string();
            let f = std::fs::File::open(p).with_context(|| format!("reading {name}"))?;
            let size = f.metadata().map(|m| m.len()).unwrap_or(0);
            if size > max_bytes {
                return Err(too_big(&name));
            }
            let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
            f.take(max_bytes.saturating_add(1))
                .read_to_end(&mut bytes)
                .with_context(|| format!("reading {name}"))?;
            if bytes.len() as u64 > max_bytes {
                return Err(too_big(&name));
            }
            Ok((name, bytes))
        }
        _ => {
            let name = "<stdin>".to_owned();
            let mut bytes = Vec::new();
            std::io::stdin()
                .lock()
                .take(max_bytes.saturating_add(1))
                .read_to_end(&mut bytes)
                .context("reading standard input")?;
            if bytes.len() as u64 > max_bytes {
                return Err(too_big(&name));
            }
            Ok((name, bytes))
        }
    }
}

/// The format of `file`: the explicit one, else by extension, else CSV.
#[must_use]
pub fn format_of(file: Option<&Path>, explicit: Option<InputFormat>) -> InputFormat {
    if let Some(f) = explicit {
        return f;
    }
    let ext = file
        .and_then(Path::extension)
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("tsv" | "tab") => InputFormat::Tsv,
        Some("json") => InputFormat::Json,
        Some("geojson") => InputFormat::Geojson,
        Some("topojson") => InputFormat::Topojson,
        Some("geojsonl" | "geojsons" | "ndjson" | "geojsonseq") => InputFormat::Geojsonseq,
        _ => InputFormat::Csv,
    }
}

/// Loads the points named by the input arguments.
///
/// # Errors
///
/// I/O errors, and `FILE:LINE: ...` for anything wrong in the data.
pub fn load(args: &InputArgs) -> Result<Points> {
    if let Some(n) = args.example {
        return Ok(example(n));
    }
    let file = args.file.as_deref();
    let limits = Limits::of(args);
    let (name, bytes) = read_source(file, limits.max_bytes)?;
    let max = limits.max_points;
    match format_of(file, args.input_format) {
        InputFormat::Csv => parse_table(&name, &bytes, None, max),
        InputFormat::Tsv => parse_table(&name, &bytes, Some(b'\t'), max),
        InputFormat::Json => parse_json(&name, &bytes, max),
        InputFormat::Geojson => parse_geojson_points(&name, &bytes, max),
        InputFormat::Topojson => {
            bail!("{name}: TopoJSON holds a coverage: `bzspline smooth` reads it; fit, eval, sample and plot take a table, JSON or GeoJSON")
        }
        InputFormat::Geojsonseq => {
            // The first feature of the stream.
            let text = utf8(&name, &bytes)?;
            let (i, line) = text
                .lines()
                .enumerate()
                .find(|(_, l)| {
                    !l.trim_matches(|c: char| c.is_whitespace() || c == '\u{1e}')
                        .is_empty()
                })
                .unwrap_or((0, ""));
            let line = line.trim_matches(|c: char| c.is_whitespace() || c == '\u{1e}');
            parse_geojson_points(&format!("{name}:{}", i + 1), line.as_bytes(), max)
        }
    }
}

/// The text of `bytes` without a UTF-8 byte-order mark.
///
/// # Errors
///
/// `FILE:LINE: not valid UTF-8` at the first bad byte; `FILE:1: UTF-16 text`
/// for a UTF-16 byte-order mark.
pub fn utf8<'a>(name: &str, bytes: &'a [u8]) -> Result<&'a str> {
    if bytes.starts_with(b"\xFF\xFE") || bytes.starts_with(b"\xFE\xFF") {
        return Err(anyhow!(
            "{name}:1: UTF-16 text (byte-order mark 0x{:02X}{:02X}); save it as UTF-8",
            bytes[0],
            bytes[1]
        ));
    }
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    std::str::from_utf8(bytes).map_err(|e| {
        let good = &bytes[..e.valid_up_to()];
        let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
        let col = good.len() - good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
        let bad = bytes.get(e.valid_up_to()).copied().unwrap_or(0);
        anyhow!("{name}:{line}: not valid UTF-8 (byte 0x{bad:02X} at column {col})")
    })
}

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

/// The error for an input with more than `max` points, at `at`.
fn too_many(at: &str, max: usize) -> anyhow::Error {
    anyhow!("{at}: more than {max} points (--max-points); split the input or raise the limit")
}

fn json_number(source: &str, at: &str, v: &Value) -> Result<f64> {
    let x = v
        .as_f64()
        .ok_or_else(|| anyhow!("{source}: {at}: expected a number, found {v}"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(anyhow!("{source}: {at}: {x} is not a finite number"))
    }
}

/// The points of a JSON array (arrays of numbers, or numbers), flat, and their
/// width; at most `max` of them.
fn json_rows(source: &str, items: &[Value], what: &str, max: usize) -> Result<(Vec<f64>, usize)> {
    if items.len() > max {
        return Err(too_many(&format!("{source}: {what}[{max}]"), max));
    }
    let mut coords = Vec::new();
    let mut width = None;
    for (i, item) in items.iter().enumerate() {
        let start = coords.len();
        match item {
            Value::Array(a) => {
                for (j, v) in a.iter().enumerate() {
                    coords.push(json_number(source, &format!("{what}[{i}][{j}]"), v)?);
                }
            }
            Value::Number(_) => coords.push(json_number(source, &format!("{what}[{i}]"), item)?),
            other => {
                return Err(anyhow!(
                    "{source}: {what}[{i}]: expected a point (an array of numbers), found {other}"
                ))
            }
        }
        let w = coords.len() - start;
        match width {
            None => {
                width = Some(w);
                coords.reserve(w * items.len());
            }
            Some(first) if first != w => {
                return Err(anyhow!(
                    "{source}: {what}[{i}]: {w} coordinates, but {what}[0] has {first}"
                ));
            }
            Some(_) => {}
        }
    }
    Ok((coords, width.unwrap_or(0)))
}

fn parse_json_value(name: &str, bytes: &[u8]) -> Result<Value> {
    let text = utf8(name, bytes)?;
    serde_json::from_str(text).map_err(|e| anyhow!("{name}:{}: invalid JSON: {e}", e.line()))
}

/// Parses JSON: an array of points (`[[x, y], ...]` or coordinates for curves),
/// an object with `points`, or an object with `knots` and `values` (the form
/// `fit` prints).
///
/// # Errors
///
/// `FILE:LINE: invalid JSON`, or `FILE: points[i]: ...` for a bad element.
pub fn parse_json(name: &str, bytes: &[u8], max_points: usize) -> Result<Points> {
    let v = parse_json_value(name, bytes)?;
    let rows = |items: &[Value], what: &str| json_rows(name, items, what, max_points);
    let ((coords, width), len) = match &v {
        Value::Array(items) => (rows(items, "points")?, items.len()),
        Value::Object(o) => {
            if let Some(Value::Array(items)) = o.get("points") {
                (rows(items, "points")?, items.len())
            } else if let (Some(Value::Array(k)), Some(Value::Array(vals))) =
                (o.get("knots"), o.get("values"))
            {
                let (values, vw) = rows(vals, "values")?;
                if vals.first().is_some_and(Value::is_array) {
                    // A curve's control points: its knots are parameters.
                    ((values, vw), vals.len())
                } else {
                    if k.len() != vals.len() {
                        return Err(anyhow!(
                            "{name}: {} knots but {} values",
                            k.len(),
                            vals.len()
                        ));
                    }
                    let (knots, kw) = rows(k, "knots")?;
                    let mut coords = Vec::with_capacity(knots.len() + values.len());
                    for i in 0..k.len() {
                        coords.extend_from_slice(&knots[i * kw..(i + 1) * kw]);
                        coords.extend_from_slice(&values[i * vw..(i + 1) * vw]);
                    }
                    ((coords, kw + vw), k.len())
                }
            } else {
                return Err(anyhow!(
                    "{name}: expected an array of points, or an object with \"points\" or with \"knots\" and \"values\""
                ));
            }
        }
        _ => return Err(anyhow!("{name}: expected an array of points")),
    };
    Ok(Points::new(
        name,
        (width, len),
        coords,
        Positions::Items,
        Pos::Item(len),
    ))
}

/// Reads the control points of the first line in a GeoJSON document: a
/// LineString, a MultiPoint, the outer ring of a Polygon (without the position
/// that repeats the first), or the Point features of a collection in order.
///
/// # Errors
///
/// `FILE:LINE: invalid JSON`, or `FILE: feature i, coordinate j: ...`.
pub fn parse_geojson_points(name: &str, bytes: &[u8], max_points: usize) -> Result<Points> {
    let v = parse_json_value(name, bytes)?;
    let features: Vec<&Value> = match v.get("type").and_then(Value::as_str) {
        Some("FeatureCollection") => v
            .get("features")
            .and_then(Value::as_array)
            .map(|f| f.iter().collect())
            .unwrap_or_default(),
        _ => vec![&v],
    };
    let geometry = |f: &'_ Value| -> Option<Value> {
        match f.get("type").and_then(Value::as_str) {
            Some("Feature") => f.get("geometry").cloned(),
            _ => Some(f.clone()),
        }
    };
    // Point features, one row each, in document order.
    let mut coords: Vec<f64> = Vec::new();
    let mut width: Option<usize> = None;
    let mut point_features: Vec<usize> = Vec::new();
    // The first feature passed over, for the message when none has points.
    let mut skipped: Option<(usize, String)> = None;
    for (fi, f) in features.iter().enumerate() {
        let Some(g) = geometry(f) else {
            skipped.get_or_insert((fi, "a feature without geometry".to_owned()));
            continue;
        };
        let at = format!("feature {fi}: coordinates");
        let kind = g.get("type").and_then(Value::as_str).unwrap_or("");
        skipped.get_or_insert((fi, format!("a {kind:?} geometry")));
        let list = match (kind, g.get("coordinates")) {
            ("Point", Some(c)) => {
                if point_features.len() >= max_points {
                    return Err(too_many(&format!("{name}: feature {fi}"), max_points));
                }
                let (row, w) = json_rows(name, std::slice::from_ref(c), &at, 1)?;
                if let Some(first) = width.filter(|&first| first != w) {
                    return Err(anyhow!(
                        "{name}: feature {fi}, coordinate 0: {w} coordinates, expected {first}"
                    ));
                }
                width = Some(w);
                coords.extend(row);
                point_features.push(fi);
                continue;
            }
            ("LineString" | "MultiPoint", Some(Value::Array(c))) => &c[..],
            ("Polygon", Some(Value::Array(rings))) => match rings.first() {
                Some(Value::Array(c)) => {
                    if !same_position(c.first(), c.last()) {
                        return Err(anyhow!(
                            "{name}: feature {fi}: the ring is not closed (GeoJSON repeats its first position at the end)"
                        ));
                    }
                    // The repeat only closes the ring: the control points are
                    // the distinct vertices (--closed closes the curve).
                    &c[..c.len().saturating_sub(1)]
                }
                _ => continue,
            },
            _ => continue,
        };
        if !point_features.is_empty() {
            break;
        }
        // The first line: its coordinates are the control points.
        let len = list.len();
        let (coords, w) = json_rows(name, list, &at, max_points)?;
        return Ok(Points::new(
            name,
            (w, len),
            coords,
            Positions::Coords { feature: fi },
            Pos::Coord {
                feature: fi,
                index: len,
            },
        ));
    }
    if point_features.is_empty() {
        if let Some((fi, what)) = skipped {
            return Err(anyhow!(
                "{name}: feature {fi}: {what} has no control points (expected a LineString, MultiPoint, Polygon or Point)"
            ));
        }
    }
    let len = point_features.len();
    Ok(Points::new(
        name,
        (width.unwrap_or(0), len),
        coords,
        Positions::Features(point_features),
        Pos::Item(len),
    ))
}

/// Whether two GeoJSON positions have the same numbers (`0` and `0.0` alike).
fn same_position(a: Option<&Value>, b: Option<&Value>) -> bool {
    let coords = |v: Option<&Value>| -> Option<Vec<Option<f64>>> {
        Some(v?.as_array()?.iter().map(Value::as_f64).collect())
    };
    coords(a) == coords(b)
}

/// Checks that the rows have one of the `allowed` widths.
///
/// # Errors
///
/// `FILE:LINE: N columns, expected ...` at the first row that does not.
pub fn check_columns(points: &Points, allowed: &[usize], what: &str) -> Result<()> {
    // Every row has the width of the first.
    if !points.is_empty() && !allowed.contains(&points.width) {
        return Err(anyhow!(
            "{}: {} columns, expected {what}",
            points.at(0),
            points.width
        ));
    }
    Ok(())
}

/// Turns a library error (0-based row indices) into a message naming the source
/// and line at fault.
#[must_use]
pub fn explain(points: &Points, e: &bzspline::Error) -> anyhow::Error {
    use bzspline::{Error as E, Field};
    let n = points.len();
    match *e {
        E::TooFewPoints { found: 0, .. } => anyhow!(
            "{}: no data points (need at least 2)",
            locate(&points.source, points.end)
        ),
        E::TooFewPoints { found, min } => anyhow!(
            "{}: only {found} point{}, need at least {min}",
            points.at(found.saturating_sub(1)),
            if found == 1 { "" } else { "s" }
        ),
        E::NonFinite {
            field: Field::Alpha,
            index,
            value,
        } => anyhow!(
            "--alphas value {} = {value} is not a finite number",
            index + 1
        ),
        E::NonFinite { index, value, .. } => {
            anyhow!("{}: {value} is not a finite number", points.at(index))
        }
        E::NotIncreasing {
            index,
            previous,
            value,
        } => anyhow!(
            "{}: x = {value} does not exceed x = {previous} on {}: x must be strictly increasing",
            points.at(index),
            points.pos_words(index.saturating_sub(1))
        ),
        E::IntervalTooSmall {
            interval,
            width,
            span,
        } => anyhow!(
            "{}: too close to {} (gap {width:e} in a span of {span:e})",
            points.at(interval + 1),
            points.pos_words(interval)
        ),
        E::SpanOverflow { first, last } => anyhow!(
            "{}: the span from {first:e} to {last:e} overflows a double",
            points.at(n.saturating_sub(1))
        ),
        E::AlphaOutOfRange { interval, value } => anyhow!(
            "alpha {} = {value} (the interval from {} to {}) is outside [1/3, 2/3]",
            interval + 1,
            points.pos_words(interval),
            points.pos_words(interval + 1)
        ),
        E::LengthMismatch {
            field: Field::Alpha,
            expected,
            found,
        } => anyhow!(
            "--alphas has {found} value{}, but {n} points ({}) need {expected}, one per interval",
            if found == 1 { "" } else { "s" },
            points.source
        ),
        E::RepeatedPoint { index } => anyhow!(
            "{}: repeats the point on {}: consecutive control points must differ",
            points.at(index),
            points.pos_words(index.saturating_sub(1))
        ),
        E::RepeatedClosingPoint { last } => anyhow!(
            "{}: repeats the first point ({}): a closed curve closes by itself, leave the repeat out",
            points.at(last),
            points.pos_words(0)
        ),
        ref other => anyhow!("{}: {other}", points.source),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MAX: usize = Limits::DEFAULT.max_points;

    fn rows(p: &Points) -> Vec<Vec<f64>> {
        p.rows().map(<[f64]>::to_vec).collect()
    }

    fn table(s: &str) -> Result<Points> {
        parse_table("t.csv", s.as_bytes(), None, MAX)
    }

    #[test]
    fn tables_accept_headers_comments_bom_crlf_and_separators() {
        let p = table(
            "\u{feff}# c\r\nx, y\r\n\r\n1E-3 ; +2\r\n"
                .replace(';', ",")
                .as_str(),
        )
        .unwrap();
        assert_eq!(rows(&p), vec![vec![1e-3, 2.0]]);
        assert_eq!((p.len(), p.pos(0)), (1, Pos::Line(4)));
        let p = table("x;y\n.5;1\n  # indented comment\n2;3\n").unwrap();
        assert_eq!(rows(&p), vec![vec![0.5, 1.0], vec![2.0, 3.0]]);
        let p = table("1\t2\n3\t4\n").unwrap();
        assert_eq!(p.len(), 2);
    }

    #[test]
    fn table_errors_name_the_line() {
        let e = table("x,y\n1,2\n2,nan\n").unwrap_err().to_string();
        assert!(e.starts_with("t.csv:3: field 2"), "{e}");
        let e = table("1,2\n2,3\nx,y\n").unwrap_err().to_string();
        assert!(e.contains("t.csv:3:") && e.contains("header"), "{e}");
        let e = table("1,2\n2,1,5\n").unwrap_err().to_string();
        assert!(e.starts_with("t.csv:2: 3 fields, but line 1 has 2"), "{e}");
        let e = table("1,2\n2,1e400\n").unwrap_err().to_string();
        assert!(e.contains("t.csv:2:") && e.contains("not a finite"), "{e}");
        let e = parse_table("t.csv", b"1,2\n3,\xff\n", None, MAX)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("t.csv:2: not valid UTF-8"), "{e}");
    }

    #[test]
    fn library_errors_map_to_lines() {
        let p = table("x,y\n1,2\n# gap\n3,4\n3,5\n").unwrap();
        let e = explain(
            &p,
            &bzspline::Error::NotIncreasing {
                index: 2,
                previous: 3.0,
                value: 3.0,
            },
        )
        .to_string();
        assert!(
            e.starts_with("t.csv:5: x = 3 does not exceed x = 3 on line 4"),
            "{e}"
        );
    }

    #[test]
    fn json_accepts_pairs_and_the_fit_form() {
        let p = parse_json("a.json", b"[[0, 1], [1, 2.5]]", MAX).unwrap();
        assert_eq!(rows(&p), vec![vec![0.0, 1.0], vec![1.0, 2.5]]);
        let p = parse_json("a.json", br#"{"knots": [0, 1], "values": [3, 4]}"#, MAX).unwrap();
        assert_eq!(rows(&p), vec![vec![0.0, 3.0], vec![1.0, 4.0]]);
        let p = parse_json(
            "a.json",
            br#"{"knots": [0, 1], "values": [[3, 4], [5, 6]]}"#,
            MAX,
        )
        .unwrap();
        assert_eq!(rows(&p), vec![vec![3.0, 4.0], vec![5.0, 6.0]]);
        let e = parse_json("a.json", b"[[0, 1],\n [1, \"x\"]]", MAX).unwrap_err();
        assert!(e.to_string().contains("points[1][1]"), "{e}");
    }

    #[test]
    fn utf16_is_named_as_such() {
        for bom in [&b"\xFF\xFE0\x00"[..], &b"\xFE\xFF\x000"[..]] {
            let e = table_bytes(bom).unwrap_err().to_string();
            assert!(e.starts_with("t.csv:1: UTF-16 text"), "{e}");
        }
    }

    fn table_bytes(b: &[u8]) -> Result<Points> {
        parse_table("t.csv", b, None, MAX)
    }

    #[test]
    fn geojson_without_usable_geometry_names_the_feature_and_type() {
        let doc = br#"{"type":"FeatureCollection","features":[
            {"type":"Feature","geometry":{"type":"GeometryCollection","geometries":[]}}]}"#;
        let e = parse_geojson_points("g.geojson", doc, MAX)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(
                "g.geojson: feature 0: a \"GeometryCollection\" geometry has no control points"
            ),
            "{e}"
        );
        let empty = br#"{"type":"LineString","coordinates":[]}"#;
        let p = parse_geojson_points("g.geojson", empty, MAX).unwrap();
        assert!(p.is_empty());
        assert_eq!(
            p.end,
            Pos::Coord {
                feature: 0,
                index: 0
            }
        );
    }

    #[test]
    fn unclosed_polygon_ring_is_refused() {
        let open = br#"{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,1]]]}"#;
        let e = parse_geojson_points("p.geojson", open, MAX)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("p.geojson: feature 0: the ring is not closed"),
            "{e}"
        );
        // Closed, with the repeat written as 0.0: read as its four vertices.
        let closed = br#"{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,1],[0.0,0.0]]]}"#;
        let p = parse_geojson_points("p.geojson", closed, MAX).unwrap();
        assert_eq!(
            rows(&p),
            vec![
                vec![0.0, 0.0],
                vec![1.0, 0.0],
                vec![1.0, 1.0],
                vec![0.0, 1.0]
            ]
        );
        let empty = br#"{"type":"Polygon","coordinates":[[]]}"#;
        assert!(parse_geojson_points("p.geojson", empty, MAX)
            .unwrap()
            .is_empty());
    }
}
