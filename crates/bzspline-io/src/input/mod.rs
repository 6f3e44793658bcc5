//! Readers for control points: CSV/TSV, JSON, GeoJSON and the paper's examples.
//! Every point keeps where it came from, so that errors (the readers' own and the
//! library's, which carry 0-based indices) name the file and line at fault.
//!
//! One file a format: `table.rs` ([`parse_table`]: CSV, TSV, semicolons),
//! `json.rs` ([`parse_json`]: arrays of points and `fit`'s object),
//! `geojson.rs` ([`parse_geojson_points`]: the first line, ring or run of
//! points); the check every GeoJSON geometry passes before it is converted
//! (`geometry.rs`, [`check_document`]); the paper's examples in `examples.rs`;
//! library errors mapped to lines in `explain.rs` ([`explain`]).

mod examples;
mod explain;
mod geojson;
mod geometry;
mod json;
mod table;

use std::fmt;
use std::io::Read;
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};

pub use examples::example;
pub use examples::EXAMPLE1;
pub use explain::explain;
pub use geojson::parse_geojson_points;
pub use geometry::{check_document, to_geojson, Fault, MAX_POSITION_LEN};
pub use json::parse_json;
pub use table::{parse_table, parse_table_with, Col, Select};

/// The default of the largest number of points one input may hold (the
/// command's `--max-points`): about 2 GB fitted as y(x), 8 GB as a planar
/// curve.
pub const DEFAULT_MAX_POINTS: usize = 20_000_000;
/// The default of the largest input in bytes (the command's `--max-bytes`).
pub const DEFAULT_MAX_BYTES: u64 = 1 << 30;

/// The formats the readers understand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum InputFormat {
    /// Comma-, semicolon- or tab-separated values.
    Csv,
    /// Tab-separated values.
    Tsv,
    /// A JSON array of points, or an object with `knots` and `values` (or `points`).
    Json,
    /// A GeoJSON document.
    Geojson,
    /// Newline-delimited GeoJSON, one feature or geometry per line.
    Geojsonseq,
    /// A TopoJSON Topology (`smooth` only; recognised by its content too).
    Topojson,
    /// An ESRI Shapefile: the `.shp`, with its `.shx` and `.dbf` beside it
    /// (recognised by its content too).
    Shapefile,
    /// A GeoPackage (`--layer` chooses among several layers; recognised by
    /// its content too).
    Geopackage,
    /// A FlatGeobuf file (recognised by its content too).
    Flatgeobuf,
    /// A GeoParquet file (recognised by its content too).
    Geoparquet,
}

/// Where control points come from and how much of them to take: what
/// [`load`] reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// The file; `None` or `-` for standard input.
    pub file: Option<std::path::PathBuf>,
    /// One of the paper's examples (1 or 2) instead of a file.
    pub example: Option<u8>,
    /// The format; by default from the extension, else from the content.
    pub format: Option<InputFormat>,
    /// The layer of a GeoPackage to read (needed when it holds several).
    pub layer: Option<String>,
    /// The most points (and bytes) to take.
    pub limits: Limits,
    /// A table's column of x, by header name or number (from 1).
    pub x: Option<String>,
    /// A table's column of y, by header name or number.
    pub y: Option<String>,
    /// A table's columns, in order, by header name or number.
    pub columns: Option<Vec<String>>,
    /// The form of a table's dates, with strftime's directives.
    pub date_format: Option<crate::time::DateFormat>,
    /// A table's column of weights for a smoothing fit, by header name or
    /// number.
    pub weights: Option<String>,
}

impl Default for Source {
    fn default() -> Self {
        Source {
            file: None,
            example: None,
            format: None,
            layer: None,
            limits: Limits::DEFAULT,
            x: None,
            y: None,
            columns: None,
            date_format: None,
            weights: None,
        }
    }
}

/// What the command says on standard error when `cut` GeoJSON positions of
/// `source` had more than [`MAX_POSITION_LEN`] numbers.
#[must_use]
pub fn cut_note(source: &str, cut: usize) -> String {
    format!(
        "{source}: {cut} position{} with more than {MAX_POSITION_LEN} numbers: kept x, y, z",
        if cut == 1 { "" } else { "s" }
    )
}

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
    /// The header's names of the columns, when a header named them.
    pub names: Option<Vec<String>>,
    /// The kind of dates in the first column, when it held dates (its numbers
    /// are then days or seconds since 1970, see [`crate::time`]).
    pub time: Option<crate::time::TimeKind>,
    /// GeoJSON positions of more than 3 numbers, cut to x, y, z.
    pub cut: usize,
    /// One weight per row for a smoothing fit, when a table's column was
    /// chosen for them (`--weights`).
    pub weights: Option<Vec<f64>>,
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
            names: None,
            time: None,
            cut: 0,
            weights: None,
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
    /// [`DEFAULT_MAX_POINTS`] and [`DEFAULT_MAX_BYTES`].
    pub const DEFAULT: Limits = Limits {
        max_points: DEFAULT_MAX_POINTS,
        max_bytes: DEFAULT_MAX_BYTES,
    };
}

impl Default for Limits {
    fn default() -> Self {
        Limits::DEFAULT
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

/// The format of `file`: the explicit one, else by extension, else a layer
/// file's by its first bytes (a Shapefile, a GeoPackage, FlatGeobuf,
/// Parquet), else
/// CSV.
#[must_use]
pub fn format_of(file: Option<&Path>, explicit: Option<InputFormat>) -> InputFormat {
    explicit
        .or_else(|| format_by_extension(file))
        .or_else(|| {
            let path = file.filter(|p| *p != Path::new("-"))?;
            let mut head = Vec::new();
            std::fs::File::open(path)
                .ok()?
                .take(100)
                .read_to_end(&mut head)
                .ok()?;
            Some(sniff(&head)).filter(|f| crate::files::is_layer(*f))
        })
        .unwrap_or(InputFormat::Csv)
}

/// The format a file's extension names, if it names one.
fn format_by_extension(file: Option<&Path>) -> Option<InputFormat> {
    let ext = file
        .and_then(Path::extension)
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("csv") => Some(InputFormat::Csv),
        Some("tsv" | "tab") => Some(InputFormat::Tsv),
        Some("json") => Some(InputFormat::Json),
        Some("geojson") => Some(InputFormat::Geojson),
        Some("topojson") => Some(InputFormat::Topojson),
        Some("shp") => Some(InputFormat::Shapefile),
        Some("gpkg") => Some(InputFormat::Geopackage),
        Some("fgb") => Some(InputFormat::Flatgeobuf),
        Some("parquet" | "geoparquet") => Some(InputFormat::Geoparquet),
        Some("geojsonl" | "geojsons" | "ndjson" | "geojsonseq") => Some(InputFormat::Geojsonseq),
        _ => None,
    }
}

/// The format of data that no option or extension names (standard input, a
/// `.txt` file): a Shapefile's file code starts a `.shp`; a record separator
/// starts newline-delimited GeoJSON; `{` or
/// `[` starts JSON, which is GeoJSON or TopoJSON when a `"type"` of theirs
/// appears in its first 64 KiB; anything else is a table.
#[must_use]
pub fn sniff(bytes: &[u8]) -> InputFormat {
    // A .shp starts with its file code, 9994, big-endian.
    if bytes.starts_with(&[0, 0, 0x27, 0x0a]) {
        return InputFormat::Shapefile;
    }
    // An SQLite database whose application id is GeoPackage's.
    if bytes.starts_with(b"SQLite format 3\0")
        && bytes
            .get(68..72)
            .is_some_and(|id| id == b"GPKG" || id == b"GP10")
    {
        return InputFormat::Geopackage;
    }
    if bytes.starts_with(b"fgb\x03") {
        return InputFormat::Flatgeobuf;
    }
    if bytes.starts_with(b"PAR1") {
        return InputFormat::Geoparquet;
    }
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let Some(&first) = text.iter().find(|b| !b.is_ascii_whitespace()) else {
        return InputFormat::Csv;
    };
    match first {
        0x1e => InputFormat::Geojsonseq,
        b'{' | b'[' => {
            let head = String::from_utf8_lossy(&text[..text.len().min(1 << 16)]);
            let squeezed: String = head.chars().filter(|c| !c.is_whitespace()).collect();
            if squeezed.contains("\"type\":\"Topology\"") {
                InputFormat::Topojson
            } else if GEOJSON_TYPES
                .iter()
                .any(|t| squeezed.contains(&format!("\"type\":\"{t}\"")))
            {
                InputFormat::Geojson
            } else {
                InputFormat::Json
            }
        }
        _ => InputFormat::Csv,
    }
}

/// The first line, ring or run of points of a layer file's features
/// (Shapefile, GeoPackage, FlatGeobuf, GeoParquet), as from the same features in
/// GeoJSON.
fn layer_points(
    file: Option<&Path>,
    format: InputFormat,
    layer: Option<&str>,
    limits: Limits,
) -> Result<Points> {
    let Some(path) = file.filter(|p| *p != Path::new("-")) else {
        bail!(
            "{} is read from its file, not from standard input",
            crate::files::format_name(format)
        );
    };
    let name = path.display().to_string();
    let read = crate::files::read(path, format, layer, limits.max_bytes)?;
    let bytes = serde_json::to_vec(&read.features.to_value()).context("formatting GeoJSON")?;
    parse_geojson_points(&name, &bytes, limits.max_points)
}

/// The `type` values of GeoJSON objects, the geometries' last.
pub(crate) const GEOJSON_TYPES: [&str; 9] = [
    "FeatureCollection",
    "Feature",
    "Point",
    "MultiPoint",
    "LineString",
    "MultiLineString",
    "Polygon",
    "MultiPolygon",
    "GeometryCollection",
];

/// Loads the points named by the input arguments.
///
/// # Errors
///
/// I/O errors, and `FILE:LINE: ...` for anything wrong in the data.
pub fn load(args: &Source) -> Result<Points> {
    if let Some(n) = args.example {
        return Ok(example(n));
    }
    let file = args.file.as_deref();
    let limits = args.limits;
    let max = limits.max_points;
    let no_weights = |name: &str, format: InputFormat| -> Result<()> {
        match &args.weights {
            Some(w) => bail!(
                "{name}: --weights {w:?} reads a column of a table; this is {}",
                crate::files::format_name(format)
            ),
            None => Ok(()),
        }
    };
    if let Some(f) = args
        .format
        .or_else(|| format_by_extension(file))
        .filter(|f| crate::files::is_layer(*f))
    {
        no_weights(
            &file.map_or("<stdin>".to_owned(), |p| p.display().to_string()),
            f,
        )?;
        return layer_points(file, f, args.layer.as_deref(), limits);
    }
    let (name, bytes) = read_source(file, limits.max_bytes)?;
    let format = args
        .format
        .or_else(|| format_by_extension(file))
        .unwrap_or_else(|| sniff(&bytes));
    if crate::files::is_layer(format) {
        no_weights(&name, format)?;
        return layer_points(file, format, args.layer.as_deref(), limits);
    }
    if let Some(l) = &args.layer {
        bail!(
            "{name}: --layer {l:?} chooses a layer of a GeoPackage; this is {}",
            crate::files::format_name(format)
        );
    }
    let select = Select {
        x: args.x.as_deref().map(Col::parse),
        y: args.y.as_deref().map(Col::parse),
        columns: args
            .columns
            .as_ref()
            .map(|c| c.iter().map(|s| Col::parse(s)).collect()),
        dates: args.date_format.clone(),
        weights: args.weights.as_deref().map(Col::parse),
    };
    let table = matches!(format, InputFormat::Csv | InputFormat::Tsv);
    if !table && select != Select::default() {
        bail!("{name}: --x, --y, --columns, --date-format and --weights are for tables; this is {format:?}");
    }
    let points = match format {
        InputFormat::Csv => parse_table_with(&name, &bytes, None, max, &select),
        InputFormat::Tsv => parse_table_with(&name, &bytes, Some(b'\t'), max, &select),
        InputFormat::Json => parse_json(&name, &bytes, max),
        InputFormat::Geojson => parse_geojson_points(&name, &bytes, max),
        InputFormat::Topojson => {
            bail!("{name}: TopoJSON holds a coverage: `bzspline smooth` reads it; fit, eval, sample and plot take a table, JSON, GeoJSON or a layer file")
        }
        InputFormat::Shapefile
        | InputFormat::Geopackage
        | InputFormat::Flatgeobuf
        | InputFormat::Geoparquet => {
            unreachable!("read above")
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
    }?;
    Ok(if table { over_index(points) } else { points })
}

/// A table's one column of values as y over its row number (x = 0, 1, 2, ...); other
/// points unchanged.
fn over_index(mut p: Points) -> Points {
    if p.width != 1 {
        return p;
    }
    p.coords = p
        .coords
        .iter()
        .enumerate()
        .flat_map(|(i, &y)| [i as f64, y])
        .collect();
    p.width = 2;
    p.names = p.names.map(|n| {
        let y = n.into_iter().next().unwrap_or_default();
        vec!["index".to_owned(), y]
    });
    p.time = None;
    p
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

/// The error for an input with more than `max` points, at `at`.
pub(super) fn too_many(at: &str, max: usize) -> anyhow::Error {
    anyhow!("{at}: more than {max} points (--max-points); split the input or raise the limit")
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
            e.contains("p.geojson: coordinates[0]: the ring is not closed"),
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
        // An empty ring is not an empty polygon (that is `[]`).
        let empty = br#"{"type":"Polygon","coordinates":[[]]}"#;
        let e = parse_geojson_points("p.geojson", empty, MAX).unwrap_err();
        assert!(
            e.to_string().contains("a ring needs 4 or more positions"),
            "{e}"
        );
    }
}
