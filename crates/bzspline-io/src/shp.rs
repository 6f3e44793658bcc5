//! ESRI Shapefiles in and out: a layer's `.shp` and `.dbf` read a record at
//! a time (its `.shx` checked by its length) into the layer's features
//! (attributes as properties, in the table's field order) that the smoothing
//! and the point readers take, and written back from them, with the input's
//! fields (names, types, widths) and its `.prj` kept. Written files go to
//! staging files a record at a time and are renamed into place only when
//! every one of them is complete.
//!
//! Shapes map to GeoJSON as GDAL maps them: a Polyline of one part is a
//! LineString, of several a MultiLineString; a Polygon's outer rings
//! (clockwise) each take the inner rings that lie in them, one outer ring
//! making a Polygon and several a MultiPolygon; a ring left open is
//! closed; Z is the third coordinate and M is dropped. Multipatch shapes are
//! refused.

use std::io::{BufReader, BufWriter, Cursor, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use serde_json::{json, Map, Value};

use crate::features::{Features, Source};
use crate::layer::{self, one_line, Crs, FieldKind, Layer, Schema};
use shapefile::dbase::{self, FieldName, FieldType, FieldValue, TableInfo, TableWriterBuilder};
use shapefile::{
    Multipoint, MultipointZ, Point, PointZ, Polygon, PolygonRing, PolygonZ, Polyline, PolylineZ,
    Shape, NO_DATA,
};

/// One field of a `.dbf` as the writer fills it: the property it takes
/// (`key`), its name in the table, its type and width.
#[derive(Clone, Debug)]
pub(crate) struct Field {
    key: String,
    name: String,
    kind: FieldType,
    /// Bytes a value may take (text).
    width: usize,
}

/// A `.dbf`'s layout as read, to write the table back the same way.
#[derive(Clone)]
pub(crate) struct Dbf {
    table: TableInfo,
    fields: Vec<Field>,
}

impl std::fmt::Debug for Dbf {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Dbf")
            .field("fields", &self.fields)
            .finish_non_exhaustive()
    }
}

/// The files of one Shapefile: `x.shp`, `x.shx`, `x.dbf`, `x.prj`, `x.cpg`
/// beside each other (the extension's case follows the `.shp`'s).
fn sibling(shp: &Path, ext: &str) -> PathBuf {
    let upper = shp
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.chars().all(|c| c.is_ascii_uppercase()));
    shp.with_extension(if upper {
        ext.to_ascii_uppercase()
    } else {
        ext.to_owned()
    })
}

/// Reads the Shapefile whose `.shp` is `path`, with its `.shx` and `.dbf`
/// (both required) and its `.prj` and `.cpg` when there are ([`read_parts`]
/// says how the `.cpg` is used); no file may be larger than `max_bytes`.
/// The `.shp` and the `.dbf` are read a record at a time, never held whole.
///
/// # Errors
///
/// One line naming the file at fault: a missing `.shx` or `.dbf`, a file
/// larger than `max_bytes`, a truncated or malformed file, as many records as
/// shapes not, a Multipatch, a coordinate that is not finite (`x.shp: shape
/// 4: ...`).
pub fn read(path: &Path, max_bytes: u64) -> Result<Layer> {
    let name = path.display().to_string();
    let open = |p: &Path, what: &str| -> Result<(std::fs::File, u64)> {
        let file = std::fs::File::open(p).map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound && what != "shp" {
                anyhow!(
                    "{name}: its .{what} ({}) is missing: a Shapefile needs its .shp, .shx and .dbf",
                    p.display()
                )
            } else {
                anyhow!("{}: {e}", p.display())
            }
        })?;
        let len = file
            .metadata()
            .map_err(|e| anyhow!("{}: {e}", p.display()))?
            .len();
        if len > max_bytes {
            bail!(
                "{}: larger than {max_bytes} bytes (--max-bytes); split the input or raise the limit",
                p.display()
            );
        }
        Ok((file, len))
    };
    let (shp, shp_len) = open(path, "shp")?;
    let shx_path = sibling(path, "shx");
    let (shx, shx_len) = open(&shx_path, "shx")?;
    let (dbf, _) = open(&sibling(path, "dbf"), "dbf")?;
    // The index is checked by its header and length: its offsets are not read.
    let mut shx_head = Vec::with_capacity(4);
    shx.take(4)
        .read_to_end(&mut shx_head)
        .map_err(|e| anyhow!("{}: {e}", shx_path.display()))?;
    let prj_path = sibling(path, "prj");
    let prj = match std::fs::read(&prj_path) {
        Ok(b) => Some(String::from_utf8_lossy(&b).trim().to_owned()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => bail!("reading {}: {e}", prj_path.display()),
    };
    let cpg = match std::fs::read(sibling(path, "cpg")) {
        Ok(b) => Some(String::from_utf8_lossy(&b).trim().to_owned()),
        Err(_) => None,
    };
    let files = Parts {
        name: &name,
        shp: BufReader::with_capacity(1 << 16, shp),
        shp_len,
        shx_head: &shx_head,
        shx_len,
        dbf: BufReader::with_capacity(1 << 16, dbf),
    };
    let mut layer = files.read(cpg.as_deref())?;
    layer.schema.crs = prj.as_deref().map(Crs::from_wkt);
    Ok(layer)
}

/// Reads a Shapefile from the bytes of its `.shp`, `.shx` and `.dbf`, the
/// table's text in the code page `cpg` names (a `.cpg`'s content: `UTF-8`,
/// `1252`, ...), else in the one its header names, else as UTF-8 (bytes
/// that are not become U+FFFD); errors start with `name`.
///
/// # Errors
///
/// As [`read`].
pub fn read_parts(
    name: &str,
    shp: &[u8],
    shx: &[u8],
    dbf: &[u8],
    cpg: Option<&str>,
) -> Result<Layer> {
    Parts {
        name,
        shp,
        shp_len: shp.len() as u64,
        shx_head: shx,
        shx_len: shx.len() as u64,
        dbf: Cursor::new(dbf),
    }
    .read(cpg)
}

/// The header every `.shp` and `.shx` starts with.
const MAGIC: [u8; 4] = [0, 0, 0x27, 0x0a];

/// A Shapefile to read: its `.shp` as a stream of `shp_len` bytes, the
/// start (at least four bytes, when there are) and length of its `.shx`, and
/// its `.dbf`; errors start with `name`, the `.shp`'s.
struct Parts<'a, S, D> {
    name: &'a str,
    shp: S,
    shp_len: u64,
    shx_head: &'a [u8],
    shx_len: u64,
    dbf: D,
}

impl<S: Read, D: Read + Seek> Parts<'_, S, D> {
    /// The layer, a record of the `.shp` and of the `.dbf` at a time.
    fn read(mut self, cpg: Option<&str>) -> Result<Layer> {
        let name = self.name;
        let shx_name = sibling(Path::new(name), "shx").display().to_string();
        let dbf_name = sibling(Path::new(name), "dbf").display().to_string();
        // The number of shapes the index holds, each in 8 bytes after its
        // header.
        let count = self
            .shx_len
            .checked_sub(100)
            .filter(|b| b % 8 == 0 && self.shx_head.starts_with(&MAGIC))
            .and_then(|b| usize::try_from(b / 8).ok())
            .ok_or_else(|| anyhow!("{shx_name}: not a Shapefile index (no .shx header)"))?;
        let mut shp_head = [0u8; 100];
        if self.shp_len < 100
            || self.shp.read_exact(&mut shp_head).is_err()
            || !shp_head.starts_with(&MAGIC)
        {
            bail!("{name}: not a Shapefile (no .shp header)");
        }
        // A field descriptor's byte 17 holds its decimals: the table's
        // header (its length in bytes 8 and 9) read first, then again by
        // the table's reader.
        let mut dbf_head = Vec::new();
        let header_len = {
            let mut start = [0u8; 10];
            match self.dbf.read_exact(&mut start) {
                Ok(()) => u64::from(u16::from_le_bytes([start[8], start[9]])),
                Err(_) => 0,
            }
        };
        self.dbf
            .seek(SeekFrom::Start(0))
            .and_then(|_| (&mut self.dbf).take(header_len).read_to_end(&mut dbf_head))
            .and_then(|_| self.dbf.seek(SeekFrom::Start(0)))
            .map_err(|e| anyhow!("{dbf_name}: {e}"))?;
        let mut builder = dbase::ReaderBuilder::new();
        if let Some(code_page) = cpg.and_then(dbase::encoding::DynEncoding::from_name) {
            builder = builder.with_encoding(code_page);
        }
        let mut table = builder
            .build(self.dbf)
            .map_err(|e| anyhow!("{dbf_name}: not a dBASE table: {}", one_line(&e)))?;
        let fields: Vec<Field> = table
            .fields()
            .iter()
            .map(|f| Field {
                key: f.name().to_owned(),
                name: f.name().to_owned(),
                kind: f.field_type(),
                width: usize::from(f.length()),
            })
            .collect();
        let neutral = table
            .fields()
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let decimals = dbf_head.get(32 + 32 * i + 17).copied().map_or(0, u32::from);
                let width = u32::from(f.length());
                let kind = match f.field_type() {
                    FieldType::Numeric if decimals == 0 => FieldKind::Integer,
                    FieldType::Integer => FieldKind::Integer,
                    FieldType::Numeric
                    | FieldType::Float
                    | FieldType::Double
                    | FieldType::Currency => FieldKind::Real,
                    FieldType::Logical => FieldKind::Boolean,
                    FieldType::Date => FieldKind::Date,
                    FieldType::DateTime => FieldKind::DateTime,
                    FieldType::Character | FieldType::Memo => FieldKind::Text,
                };
                layer::Field {
                    name: f.name().to_owned(),
                    kind,
                    width: Some(width),
                    decimals: Some(decimals),
                }
            })
            .collect();
        let records = table.header().num_records as usize;
        if count != records {
            bail!("{name}: {count} shapes but {records} records in {dbf_name}: the files do not belong together");
        }
        let mut features = Features::new(fields.iter().map(|f| f.name.clone()).collect());
        let mut rows = table.iter_records();
        let mut shapes = Records {
            name,
            shp: &mut self.shp,
            at: 100,
            len: self.shp_len,
            content: Vec::new(),
        };
        let mut i = 0;
        while let Some(content) = shapes.next(i)? {
            if i == count {
                bail!(
                    "{shx_name}: not the index of {name}: it holds {count} shapes, the .shp more"
                );
            }
            // Each record on its own: the reader cannot run past it.
            let size = i32::try_from(content.len())
                .map_err(|_| anyhow!("{name}: shape {i}: too large"))?;
            let shape =
                <Shape as shapefile::ReadableShape>::read_from(&mut Cursor::new(content), size)
                    .map_err(|e| anyhow!("{name}: shape {i}: {}", one_line(&e)))?;
            let record = rows
                .next()
                .ok_or_else(|| anyhow!("{dbf_name}: record {i} is missing"))?
                .map_err(|e| anyhow!("{dbf_name}: record {i}: {}", one_line(&e)))?;
            let geometry = geometry(shape).map_err(|e| anyhow!("{name}: shape {i}: {e}"))?;
            let mut properties = Map::new();
            for f in &fields {
                let v = record.get(&f.name).map_or(Value::Null, field_json);
                properties.insert(f.name.clone(), v);
            }
            features.push(properties, geometry);
            i += 1;
        }
        if i != count {
            bail!("{shx_name}: not the index of {name}: it holds {count} shapes, the .shp {i}");
        }
        Ok(Layer {
            features,
            schema: Schema {
                name: Path::new(name)
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                fields: neutral,
                crs: None,
                dbf: Some(Dbf {
                    table: table.into_table_info(),
                    fields,
                }),
            },
        })
    }
}

/// The records of a `.shp` after its header, read one at a time into one
/// buffer: each checked to lie within the file, with the parts and points it
/// declares fitting in it (so that no reader allocates for more than the
/// file holds).
struct Records<'a, S> {
    name: &'a str,
    shp: &'a mut S,
    /// Where the next record starts, and the file's length.
    at: u64,
    len: u64,
    content: Vec<u8>,
}

impl<S: Read> Records<'_, S> {
    /// The content of record `n`, the next one; `None` at the end.
    fn next(&mut self, n: usize) -> Result<Option<&[u8]>> {
        if self.at >= self.len {
            return Ok(None);
        }
        let name = self.name;
        let bad = |what: &str| anyhow!("{name}: shape {n}: {what}");
        let mut head = [0u8; 8];
        if self.len - self.at < 8 || self.shp.read_exact(&mut head).is_err() {
            return Err(bad("the file ends inside its record header"));
        }
        let words = i32::from_be_bytes([head[4], head[5], head[6], head[7]]);
        let words = u64::try_from(words).map_err(|_| bad("a negative record length"))?;
        let len = 2 * words;
        if len > self.len - self.at - 8 {
            return Err(bad("the record runs past the end of the file"));
        }
        let size = usize::try_from(len).map_err(|_| bad("too large"))?;
        self.content.clear();
        self.content.resize(size, 0);
        if self.shp.read_exact(&mut self.content).is_err() {
            return Err(bad("the record runs past the end of the file"));
        }
        self.at += 8 + len;
        check_record(&self.content).map_err(bad)?;
        Ok(Some(&self.content))
    }
}

/// Checks that the parts and points a record's content declares fit in it,
/// and that its parts index its points in order.
fn check_record(rec: &[u8]) -> std::result::Result<(), &'static str> {
    let len = rec.len();
    if len < 4 {
        return Ok(());
    }
    let le = |at: usize| i32::from_le_bytes([rec[at], rec[at + 1], rec[at + 2], rec[at + 3]]);
    let count = |at: usize| usize::try_from(le(at)).map_err(|_| "a negative count");
    let need = match le(0) {
        // Polylines, polygons and multipatches: parts, then points.
        3 | 5 | 13 | 15 | 23 | 25 | 31 if len >= 44 => {
            let (parts, points) = (count(36)?, count(40)?);
            let need = 44u64 + 4 * parts as u64 + 16 * points as u64;
            if need <= len as u64 {
                // Each part starts within the points, in order.
                let mut prev = 0;
                for k in 0..parts {
                    let first = count(44 + 4 * k)?;
                    if first < prev || first > points {
                        return Err("its parts do not index its points in order");
                    }
                    prev = first;
                }
            }
            need
        }
        // Multipoints: points.
        8 | 18 | 28 if len >= 40 => 40 + 16 * count(36)? as u64,
        3 | 5 | 13 | 15 | 23 | 25 | 31 | 8 | 18 | 28 => u64::MAX,
        _ => 0,
    };
    if need > len as u64 {
        return Err("its parts and points do not fit in its record");
    }
    Ok(())
}

/// A shape as a GeoJSON geometry (`null` for a null shape).
fn geometry(shape: Shape) -> Result<Value> {
    fn xy(p: &Point) -> Result<Value> {
        finite(&[p.x, p.y])?;
        Ok(json!([p.x, p.y]))
    }
    fn xyz(p: &PointZ) -> Result<Value> {
        finite(&[p.x, p.y, p.z])?;
        Ok(json!([p.x, p.y, p.z]))
    }
    fn line<P>(pts: &[P], f: fn(&P) -> Result<Value>) -> Result<Value> {
        pts.iter()
            .map(f)
            .collect::<Result<Vec<_>>>()
            .map(Value::from)
    }
    fn lines<P>(parts: &[Vec<P>], f: fn(&P) -> Result<Value>) -> Result<Value> {
        Ok(match parts {
            [one] => json!({"type": "LineString", "coordinates": line(one, f)?}),
            _ => json!({"type": "MultiLineString", "coordinates":
                parts.iter().map(|p| line(p, f)).collect::<Result<Vec<_>>>()?}),
        })
    }
    fn polygons<P: shapefile::record::traits::HasXY>(
        rings: &[PolygonRing<P>],
        f: fn(&P) -> Result<Value>,
    ) -> Result<Value> {
        // Each inner ring goes to the last outer ring before it that holds
        // its first point, else to the last outer ring before it.
        let mut polys: Vec<(Vec<[f64; 2]>, Vec<Value>)> = Vec::new();
        for ring in rings {
            let pts = ring.points();
            let mut coords = line(pts, f)?;
            // A ring left open in the file is closed, as its writer would.
            if let Some(a) = coords.as_array_mut() {
                if a.len() > 1 && a.first() != a.last() {
                    a.push(a[0].clone());
                }
            }
            match ring {
                PolygonRing::Outer(_) => {
                    let flat = pts.iter().map(|p| [p.x(), p.y()]).collect();
                    polys.push((flat, vec![coords]));
                }
                PolygonRing::Inner(_) => {
                    let first = pts.first().map(|p| [p.x(), p.y()]);
                    let home = polys
                        .iter()
                        .rposition(|(outer, _)| first.is_some_and(|q| contains(outer, q)))
                        .or(polys.len().checked_sub(1));
                    match home {
                        Some(k) => polys[k].1.push(coords),
                        None => polys.push((Vec::new(), vec![coords])),
                    }
                }
            }
        }
        Ok(match polys.len() {
            1 => json!({"type": "Polygon", "coordinates": polys.pop().map(|p| p.1)}),
            _ => json!({"type": "MultiPolygon", "coordinates":
                polys.into_iter().map(|p| p.1).collect::<Vec<_>>()}),
        })
    }
    let m_xy = |p: &shapefile::PointM| Point::new(p.x, p.y);
    Ok(match shape {
        Shape::NullShape => Value::Null,
        Shape::Point(p) => json!({"type": "Point", "coordinates": xy(&p)?}),
        Shape::PointM(p) => json!({"type": "Point", "coordinates": xy(&m_xy(&p))?}),
        Shape::PointZ(p) => json!({"type": "Point", "coordinates": xyz(&p)?}),
        Shape::Multipoint(m) => json!({"type": "MultiPoint", "coordinates": line(m.points(), xy)?}),
        Shape::MultipointM(m) => {
            let pts: Vec<Point> = m.points().iter().map(m_xy).collect();
            json!({"type": "MultiPoint", "coordinates": line(&pts, xy)?})
        }
        Shape::MultipointZ(m) => {
            json!({"type": "MultiPoint", "coordinates": line(m.points(), xyz)?})
        }
        Shape::Polyline(l) => lines(l.parts(), xy)?,
        Shape::PolylineM(l) => {
            let parts: Vec<Vec<Point>> = l
                .parts()
                .iter()
                .map(|p| p.iter().map(m_xy).collect())
                .collect();
            lines(&parts, xy)?
        }
        Shape::PolylineZ(l) => lines(l.parts(), xyz)?,
        Shape::Polygon(p) => polygons(p.rings(), xy)?,
        Shape::PolygonM(p) => {
            let rings: Vec<PolygonRing<Point>> = p
                .rings()
                .iter()
                .map(|r| {
                    let pts = r.points().iter().map(m_xy).collect();
                    match r {
                        PolygonRing::Outer(_) => PolygonRing::Outer(pts),
                        PolygonRing::Inner(_) => PolygonRing::Inner(pts),
                    }
                })
                .collect();
            polygons(&rings, xy)?
        }
        Shape::PolygonZ(p) => polygons(p.rings(), xyz)?,
        Shape::Multipatch(_) => bail!("a Multipatch (3D surface) is not supported"),
    })
}

fn finite(v: &[f64]) -> Result<()> {
    match v.iter().find(|c| !c.is_finite()) {
        Some(c) => bail!("a coordinate is {c}, not a finite number"),
        None => Ok(()),
    }
}

/// Whether the ring (closed or not) holds `p`, by the even-odd rule.
fn contains(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    let n = ring.len();
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + n - 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            inside = !inside;
        }
    }
    inside
}

/// A field's value as JSON: numbers as numbers (whole ones of a field
/// without decimals as integers), dates as `YYYY-MM-DD`, empty as `null`.
fn field_json(v: &FieldValue) -> Value {
    let number = |x: f64| {
        if x.fract() == 0.0 && x.abs() < 9.0e15 {
            json!(x as i64)
        } else {
            json!(x)
        }
    };
    match v {
        FieldValue::Character(s) => s.clone().map_or(Value::Null, Value::from),
        FieldValue::Memo(s) => Value::from(s.clone()),
        FieldValue::Numeric(x) => x.map_or(Value::Null, number),
        // The float's own shortest decimal, not its binary expansion.
        FieldValue::Float(x) => x.map_or(Value::Null, |f| {
            number(f.to_string().parse::<f64>().unwrap_or(f64::from(f)))
        }),
        FieldValue::Logical(b) => b.map_or(Value::Null, Value::from),
        FieldValue::Date(d) => d.map_or(Value::Null, |d| {
            json!(format!("{:04}-{:02}-{:02}", d.year(), d.month(), d.day()))
        }),
        FieldValue::Integer(i) => json!(i),
        FieldValue::Currency(x) | FieldValue::Double(x) => json!(x),
        FieldValue::DateTime(t) => {
            let (d, tm) = (t.date(), t.time());
            json!(format!(
                "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z",
                d.year(),
                d.month(),
                d.day(),
                tm.hours(),
                tm.minutes(),
                tm.seconds()
            ))
        }
    }
}

/// The files of a Shapefile written: `.shp`, `.shx`, `.dbf`, `.prj` and
/// `.cpg` (UTF-8), as bytes by extension.
pub type Files = Vec<(&'static str, Vec<u8>)>;

/// Writes the features of a GeoJSON FeatureCollection as the files of a
/// Shapefile, in memory: with `schema`'s fields and CRS when given (a
/// Shapefile's table exactly as read; another format's fields as the `.dbf`
/// types nearest them), else with fields found from the properties and the
/// `.prj` of WGS 84, GeoJSON's coordinates. Names longer than the 10 bytes
/// a `.dbf` allows are cut (and numbered where two would meet, as GDAL
/// does); text fields without a width are as wide as their longest value. Every feature must be of one
/// kind (points, multipoints, lines or polygons), all with z or none; a
/// feature without geometry is a null shape record. [`write_file`] writes
/// the same bytes to files without holding them.
///
/// # Errors
///
/// A feature of another kind, a property that its field cannot hold
/// (naming the feature and field), no feature at all or none with a
/// geometry.
pub fn write(features: &dyn Source, schema: Option<&Schema>) -> Result<Files> {
    let (mut shp, mut shx, mut dbf) = (
        Cursor::new(Vec::new()),
        Cursor::new(Vec::new()),
        Cursor::new(Vec::new()),
    );
    let (nulls, prj) = write_to(features, schema, &mut shp, &mut shx, &mut dbf)?;
    let (shp, shx) = if nulls.is_empty() {
        (shp.into_inner(), shx.into_inner())
    } else {
        let (mut out, mut index) = (Cursor::new(Vec::new()), Cursor::new(Vec::new()));
        with_null_shapes(
            shp.get_ref().as_slice(),
            &nulls,
            features.count(),
            &mut out,
            &mut index,
        )?;
        (out.into_inner(), index.into_inner())
    };
    let mut files: Files = vec![("shp", shp), ("shx", shx), ("dbf", dbf.into_inner())];
    if let Some(p) = prj {
        files.push(("prj", p.into_bytes()));
    }
    files.push(("cpg", b"UTF-8".to_vec()));
    Ok(files)
}

/// Writes the Shapefile of [`write()`] as `path` (the `.shp`) and its
/// siblings, a record at a time: each file goes to a staging file in the
/// same folder, and all are renamed into place only when every one was
/// written, as [`save`] does.
///
/// # Errors
///
/// As [`write()`], each naming `path`; when a file cannot be created,
/// written or renamed.
pub fn write_file(path: &Path, features: &dyn Source, schema: Option<&Schema>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let stage = || {
        layer::staging_file(dir, "")
            .with_context(|| format!("creating a file in {}", dir.display()))
    };
    let (mut shp, mut shx, mut dbf) = (stage()?, stage()?, stage()?);
    let (nulls, prj) = {
        let (mut s, mut x, mut d) = (
            BufWriter::new(shp.as_file_mut()),
            BufWriter::new(shx.as_file_mut()),
            BufWriter::new(dbf.as_file_mut()),
        );
        let written = write_to(features, schema, &mut s, &mut x, &mut d)
            .map_err(|e| anyhow!("{}: {e}", path.display()))?;
        for (w, ext) in [(&mut s, "shp"), (&mut x, "shx"), (&mut d, "dbf")] {
            w.flush()
                .with_context(|| format!("writing {}", sibling(path, ext).display()))?;
        }
        written
    };
    if !nulls.is_empty() {
        // The records written are those with a geometry: copy them again
        // with a null shape record at each feature without one.
        let (mut out, mut index) = (stage()?, stage()?);
        let shapes = shp.as_file_mut();
        shapes
            .seek(SeekFrom::Start(0))
            .with_context(|| format!("writing {}", sibling(path, "shp").display()))?;
        {
            let (mut o, mut i) = (
                BufWriter::new(out.as_file_mut()),
                BufWriter::new(index.as_file_mut()),
            );
            with_null_shapes(
                BufReader::new(&*shapes),
                &nulls,
                features.count(),
                &mut o,
                &mut i,
            )
            .and_then(|()| Ok(o.flush().and_then(|()| i.flush())?))
            .map_err(|e| anyhow!("{}: {e}", path.display()))?;
        }
        (shp, shx) = (out, index);
    }
    let mut small: Files = Vec::new();
    if let Some(p) = prj {
        small.push(("prj", p.into_bytes()));
    }
    small.push(("cpg", b"UTF-8".to_vec()));
    let mut done = vec![
        (shp, sibling(path, "shp")),
        (shx, sibling(path, "shx")),
        (dbf, sibling(path, "dbf")),
    ];
    for (ext, bytes) in &small {
        let mut tmp = stage()?;
        tmp.write_all(bytes)
            .with_context(|| format!("writing {}", sibling(path, ext).display()))?;
        done.push((tmp, sibling(path, ext)));
    }
    persist(path, done, &small)
}

/// Writes the `.shp`, `.shx` (the records of the features with a geometry,
/// numbered from 1) and `.dbf` of [`write()`] to `shp`, `shx` and `dbf`;
/// gives the features without geometry and the `.prj`.
fn write_to<W: Write + Seek>(
    features: &dyn Source,
    schema: Option<&Schema>,
    shp: &mut W,
    shx: &mut W,
    dbf: &mut W,
) -> Result<(Vec<usize>, Option<String>)> {
    if features.is_empty() {
        bail!("no features to write as a Shapefile");
    }
    let kind = layer_kind(features)?;
    let (fields, builder) = match schema {
        Some(Schema { dbf: Some(dbf), .. }) => {
            if let Some(f) = dbf.fields.iter().find(|f| f.name.len() > 11) {
                // Read from a table whose name bytes were not UTF-8 (each
                // became U+FFFD): a .dbf holds 11 bytes of a name.
                bail!(
                    "the field name {:?} is longer than a .dbf holds (11 bytes)",
                    f.name
                );
            }
            (
                dbf.fields.clone(),
                // Text is written as UTF-8, whatever the table read held.
                TableWriterBuilder::from_table_info(dbf.table.clone())
                    .set_encoding(dbase::encoding::UnicodeLossy),
            )
        }
        Some(s) => table_for(&s.fields, features)?,
        None => table_for(&layer::infer_fields(features), features)?,
    };
    let prj = match schema {
        None => Some(layer::ESRI_WGS84_PRJ.to_owned()),
        Some(s) => s.crs.as_ref().and_then(Crs::prj),
    };
    let mut nulls = Vec::new();
    let mut table = builder.build_with_dest(dbf);
    let mut shapes = shapefile::ShapeWriter::with_shx(&mut *shp, shx);
    for i in 0..features.count() {
        let record = record(features, i, &fields).map_err(|e| anyhow!("feature {i}: {e}"))?;
        table
            .write_record(&record)
            .map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?;
        let g = &*features.geometry(i);
        if g.is_null() {
            nulls.push(i); // its null shape is spliced in afterwards
            continue;
        }
        let w = &mut shapes;
        match kind {
            Kind::Points(false) => put(w, point(g)),
            Kind::Points(true) => put(w, point_z(g)),
            Kind::MultiPoints(false) => put(w, points(g, xy_of).map(Multipoint::new)),
            Kind::MultiPoints(true) => put(w, points(g, xyz_of).map(MultipointZ::new)),
            Kind::Lines(false) => put(w, parts(g, xy_of).map(Polyline::with_parts)),
            Kind::Lines(true) => put(w, parts(g, xyz_of).map(PolylineZ::with_parts)),
            Kind::Polygons(false) => put(w, rings(g, xy_of).map(Polygon::with_rings)),
            Kind::Polygons(true) => put(w, rings(g, xyz_of).map(PolygonZ::with_rings)),
        }
        .map_err(|e| anyhow!("feature {i}: {e}"))?;
    }
    shapes
        .finalize()
        .map_err(|e| anyhow!("the shapes: {}", one_line(&e)))?;
    table
        .finalize()
        .map_err(|e| anyhow!("the table: {}", one_line(&e)))?;
    drop((shapes, table));
    // A record's offset and the file's length are counted in 16-bit words
    // in an i32: the writer itself does not check that they fit.
    let bytes = shp.seek(SeekFrom::End(0))?;
    if bytes / 2 > i32::MAX as u64 {
        bail!("the Shapefile exceeds 2 GB");
    }
    Ok((nulls, prj))
}

/// Copies the records of `shp` (a `.shp` of the features with a geometry,
/// numbered from 1) to `out`, with a null shape record (shape type 0) at each
/// of the features `nulls` (increasing) of `total`, and writes its index to
/// `index`: records renumbered, offsets and file lengths (in 16-bit words)
/// written again; the bounding box is the shapes'.
fn with_null_shapes<W: Write + Seek>(
    mut shp: impl Read,
    nulls: &[usize],
    total: usize,
    out: &mut W,
    index: &mut W,
) -> Result<()> {
    const HEADER: usize = 100;
    let cut = |_| anyhow!("a Shapefile record was cut short");
    let word = |v: usize| -> Result<[u8; 4]> {
        let v = i32::try_from(v).map_err(|_| anyhow!("the Shapefile exceeds 2 GB"))?;
        Ok(v.to_be_bytes())
    };
    let mut header = [0u8; HEADER];
    shp.read_exact(&mut header).map_err(cut)?;
    out.write_all(&header)?;
    index.write_all(&header)?;
    let (mut at, mut nulls) = (HEADER, nulls.iter().peekable());
    let mut body = Vec::new();
    for number in 1..=total {
        let start = at;
        let words = if nulls.peek() == Some(&&(number - 1)) {
            nulls.next();
            out.write_all(&word(number)?)?;
            out.write_all(&word(2)?)?;
            out.write_all(&0i32.to_le_bytes())?;
            2
        } else {
            let mut head = [0u8; 8];
            shp.read_exact(&mut head).map_err(cut)?;
            let words = i32::from_be_bytes([head[4], head[5], head[6], head[7]]);
            let words = usize::try_from(words).map_err(|_| anyhow!("a negative record length"))?;
            body.resize(2 * words, 0);
            shp.read_exact(&mut body).map_err(cut)?;
            out.write_all(&word(number)?)?;
            out.write_all(&word(words)?)?;
            out.write_all(&body)?;
            words
        };
        at += 8 + 2 * words;
        index.write_all(&word(start / 2)?)?;
        index.write_all(&word(words)?)?;
    }
    for (file, bytes) in [(out, at), (index, HEADER + 8 * total)] {
        file.seek(SeekFrom::Start(24))?;
        file.write_all(&word(bytes / 2)?)?;
        file.seek(SeekFrom::End(0))?;
    }
    Ok(())
}

/// Writes `files` beside each other as `path` (the `.shp`) and its
/// siblings: each is written to a temporary file in the same folder first,
/// and all are renamed into place only when every one was written; a
/// sibling of an earlier layer that this one has not (a `.prj`) is removed.
///
/// # Errors
///
/// When a file cannot be created, written or renamed.
pub fn save(path: &Path, files: &Files) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut done = Vec::new();
    for (ext, bytes) in files {
        let mut tmp = layer::staging_file(dir, "")
            .with_context(|| format!("creating a file in {}", dir.display()))?;
        tmp.write_all(bytes)
            .with_context(|| format!("writing {}", sibling(path, ext).display()))?;
        done.push((tmp, sibling(path, ext)));
    }
    persist(path, done, files)
}

/// Renames every staging file of `done` into place, then removes a `.prj`
/// or `.cpg` of an earlier layer at `path` that `files` does not hold.
fn persist(
    path: &Path,
    done: Vec<(tempfile::NamedTempFile, PathBuf)>,
    files: &Files,
) -> Result<()> {
    for (tmp, dest) in done {
        tmp.persist(&dest)
            .map_err(|e| e.error)
            .with_context(|| format!("writing {}", dest.display()))?;
    }
    for ext in ["prj", "cpg"] {
        if !files.iter().any(|(e, _)| *e == ext) {
            let stale = sibling(path, ext);
            if stale.exists() {
                std::fs::remove_file(&stale)
                    .with_context(|| format!("removing {}", stale.display()))?;
            }
        }
    }
    Ok(())
}

/// What one layer holds, and whether with z.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Points(bool),
    MultiPoints(bool),
    Lines(bool),
    Polygons(bool),
}

fn layer_kind(features: &dyn Source) -> Result<Kind> {
    let mut kind: Option<(usize, &str)> = None;
    let mut z = false;
    for i in 0..features.count() {
        let g = features.geometry(i);
        if g.is_null() {
            continue; // a null shape record
        }
        let Some(t) = g["type"].as_str() else {
            bail!("feature {i}: its geometry has no type");
        };
        let family = match t {
            "Point" => "points",
            "MultiPoint" => "multipoints",
            "LineString" | "MultiLineString" => "lines",
            "Polygon" | "MultiPolygon" => "polygons",
            other => bail!("feature {i}: a {other} cannot be written to a Shapefile"),
        };
        match kind {
            None => kind = Some((i, family)),
            Some((j, f)) if f != family => bail!(
                "feature {i} holds {family} and feature {j} {f}: a Shapefile holds one kind of geometry"
            ),
            _ => {}
        }
        z |= has_z(&g["coordinates"]);
    }
    if kind.is_none() {
        bail!("no feature has a geometry: a Shapefile needs one to say what it holds");
    }
    Ok(match kind.map(|k| k.1) {
        Some("points") => Kind::Points(z),
        Some("multipoints") => Kind::MultiPoints(z),
        Some("lines") => Kind::Lines(z),
        _ => Kind::Polygons(z),
    })
}

fn has_z(c: &Value) -> bool {
    match c.as_array() {
        Some(a) if a.first().is_some_and(Value::is_number) => a.len() >= 3,
        Some(a) => a.iter().any(has_z),
        None => false,
    }
}

fn num(v: &Value) -> Result<f64> {
    v.as_f64()
        .ok_or_else(|| anyhow!("a coordinate is not a number"))
}

fn xy_of(p: &Value) -> Result<Point> {
    Ok(Point::new(num(&p[0])?, num(&p[1])?))
}

fn xyz_of(p: &Value) -> Result<PointZ> {
    let z = if p.get(2).is_some() { num(&p[2])? } else { 0.0 };
    Ok(PointZ::new(num(&p[0])?, num(&p[1])?, z, NO_DATA))
}

fn point(g: &Value) -> Result<Point> {
    xy_of(&g["coordinates"])
}

fn point_z(g: &Value) -> Result<PointZ> {
    xyz_of(&g["coordinates"])
}

/// Refuses an empty list: the Shapefile writer needs a point for its box.
fn some<T>(v: Vec<T>, what: &str) -> Result<Vec<T>> {
    if v.is_empty() {
        bail!("an empty {what} cannot be written to a Shapefile");
    }
    Ok(v)
}

/// Refuses a line of fewer than two positions, which a Shapefile's
/// polyline cannot hold.
fn two<T>(v: Vec<T>) -> Result<Vec<T>> {
    if v.len() < 2 {
        bail!(
            "a line of {} positions cannot be written to a Shapefile",
            v.len()
        );
    }
    Ok(v)
}

/// Writes one feature's shape (or its conversion's error).
fn put<S: shapefile::record::EsriShape, W: std::io::Write + std::io::Seek>(
    writer: &mut shapefile::ShapeWriter<W>,
    shape: Result<S>,
) -> Result<()> {
    writer
        .write_shape(&shape?)
        .map_err(|e| anyhow!("{}", one_line(&e)))
}

/// The members of a JSON array (none for anything else).
fn items(v: &Value) -> impl Iterator<Item = &Value> {
    v.as_array().into_iter().flatten()
}

/// The positions of a JSON array, converted by `f`.
fn positions<P>(v: &Value, f: fn(&Value) -> Result<P>) -> Result<Vec<P>> {
    items(v).map(f).collect()
}

/// The coordinates of each single geometry of `g`: its own for a geometry
/// of type `single`, its members' for the multi-geometry.
fn members<'a>(g: &'a Value, single: &str) -> Vec<&'a Value> {
    let c = &g["coordinates"];
    if g["type"] == single {
        vec![c]
    } else {
        items(c).collect()
    }
}

fn points<P>(g: &Value, f: fn(&Value) -> Result<P>) -> Result<Vec<P>> {
    some(positions(&g["coordinates"], f)?, "multipoint")
}

fn parts<P>(g: &Value, f: fn(&Value) -> Result<P>) -> Result<Vec<Vec<P>>> {
    let parts = members(g, "LineString")
        .into_iter()
        .map(|l| two(positions(l, f)?))
        .collect::<Result<_>>()?;
    some(parts, "line")
}

fn rings<P>(g: &Value, f: fn(&Value) -> Result<P>) -> Result<Vec<PolygonRing<P>>> {
    let mut out = Vec::new();
    for p in members(g, "Polygon") {
        for (k, r) in items(p).enumerate() {
            let pts = some(positions(r, f)?, "ring")?;
            out.push(if k == 0 {
                PolygonRing::Outer(pts)
            } else {
                PolygonRing::Inner(pts)
            });
        }
    }
    some(out, "polygon")
}

/// A `.dbf` table for fields of another format (or found from GeoJSON
/// properties): names cut to 10 bytes and made unique, each kind as the
/// `.dbf` type nearest it, text as wide as its widest value (at most 254
/// bytes) when no width is given.
fn table_for(
    fields: &[layer::Field],
    features: &dyn Source,
) -> Result<(Vec<Field>, TableWriterBuilder)> {
    let mut builder = TableWriterBuilder::new().set_encoding(dbase::encoding::UnicodeLossy);
    let mut out: Vec<Field> = Vec::new();
    for f in fields {
        let cut = |n: usize| -> String {
            f.name
                .char_indices()
                .take_while(|&(i, c)| i + c.len_utf8() <= n)
                .map(|(_, c)| c)
                .collect()
        };
        let mut name = cut(10);
        let mut k = 1;
        while out.iter().any(|o| o.name.eq_ignore_ascii_case(&name)) {
            let suffix = format!("_{k}");
            name = cut(10 - suffix.len()) + &suffix;
            k += 1;
        }
        let field_name =
            FieldName::try_from(name.as_str()).map_err(|e| anyhow!("field {:?}: {e}", f.name))?;
        let widest = || {
            (0..features.count())
                .filter_map(|i| layer::as_text(&features.property(i, &f.name)))
                .map(|t| t.len())
                .max()
                .unwrap_or(1)
                .clamp(1, 254)
        };
        let digits = |w: Option<u32>, default: u8| {
            w.and_then(|w| u8::try_from(w).ok())
                .filter(|w| (1..=20).contains(w))
                .unwrap_or(default)
        };
        let (b, kind, width) = match f.kind {
            FieldKind::Boolean => (builder.add_logical_field(field_name), FieldType::Logical, 1),
            FieldKind::Integer => {
                let w = digits(f.width, 18);
                (
                    builder.add_numeric_field(field_name, w, 0),
                    FieldType::Numeric,
                    usize::from(w),
                )
            }
            FieldKind::Real => {
                let w = digits(f.width, 24);
                let d = f
                    .decimals
                    .and_then(|d| u8::try_from(d).ok())
                    .filter(|&d| d > 0 && d < w)
                    .unwrap_or(15.min(w - 1));
                (
                    builder.add_numeric_field(field_name, w, d),
                    FieldType::Numeric,
                    usize::from(w),
                )
            }
            FieldKind::Date => (builder.add_date_field(field_name), FieldType::Date, 8),
            FieldKind::Text | FieldKind::DateTime | FieldKind::Binary => {
                let w = match f.width {
                    Some(w) if (1..=254).contains(&w) => w as usize,
                    _ => widest(),
                };
                #[allow(clippy::cast_possible_truncation)] // at most 254
                (
                    builder.add_character_field(field_name, w as u8),
                    FieldType::Character,
                    w,
                )
            }
        };
        builder = b;
        out.push(Field {
            key: f.name.clone(),
            name,
            kind,
            width,
        });
    }
    Ok((out, builder))
}

/// A feature's properties as the table's record.
fn record(features: &dyn Source, i: usize, fields: &[Field]) -> Result<dbase::Record> {
    let mut r = dbase::Record::default();
    for Field {
        key,
        name,
        kind,
        width,
    } in fields
    {
        let v = features.property(i, key);
        let v = v.as_ref();
        let bad = || anyhow!("field {name:?}: {v} does not fit a {kind:?} field");
        let text = |t: String| -> Result<FieldValue> {
            if t.len() > *width {
                bail!(
                    "field {name:?}: {} bytes of text do not fit its width of {width}",
                    t.len()
                );
            }
            Ok(FieldValue::Character(Some(t)))
        };
        let value = match (*kind, v) {
            (FieldType::Character | FieldType::Memo, Value::Null) => FieldValue::Character(None),
            (FieldType::Character | FieldType::Memo, Value::String(s)) => text(s.clone())?,
            (FieldType::Character | FieldType::Memo, other) => text(other.to_string())?,
            (FieldType::Numeric, Value::Null) => FieldValue::Numeric(None),
            (FieldType::Numeric, Value::Number(n)) => FieldValue::Numeric(n.as_f64()),
            (FieldType::Float, Value::Null) => FieldValue::Float(None),
            #[allow(clippy::cast_possible_truncation)] // a Float field holds an f32
            (FieldType::Float, Value::Number(n)) => FieldValue::Float(n.as_f64().map(|x| x as f32)),
            (FieldType::Logical, Value::Null) => FieldValue::Logical(None),
            (FieldType::Logical, Value::Bool(b)) => FieldValue::Logical(Some(*b)),
            (FieldType::Date, Value::Null) => FieldValue::Date(None),
            (FieldType::Date, Value::String(s)) => FieldValue::Date(Some(date(s).ok_or_else(bad)?)),
            (FieldType::Integer, Value::Number(n)) => FieldValue::Integer(
                n.as_i64()
                    .and_then(|i| i32::try_from(i).ok())
                    .ok_or_else(bad)?,
            ),
            (FieldType::Integer, Value::Null) => FieldValue::Integer(0),
            (FieldType::Double, Value::Number(n)) => {
                FieldValue::Double(n.as_f64().ok_or_else(bad)?)
            }
            (FieldType::Double, Value::Null) => FieldValue::Double(0.0),
            (FieldType::Currency, Value::Number(n)) => {
                FieldValue::Currency(n.as_f64().ok_or_else(bad)?)
            }
            (FieldType::Currency, Value::Null) => FieldValue::Currency(0.0),
            _ => return Err(bad()),
        };
        r.insert(name.clone(), value);
    }
    Ok(r)
}

/// `YYYY-MM-DD` as a table's date.
fn date(s: &str) -> Option<dbase::Date> {
    let mut it = s.split('-');
    let (y, m, d) = (
        it.next()?.parse().ok()?,
        it.next()?.parse().ok()?,
        it.next()?.parse().ok()?,
    );
    if it.next().is_some() {
        return None;
    }
    dbase::Date::new(d, m, y).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fc(features: Value) -> Value {
        json!({"type": "FeatureCollection", "features": features})
    }

    fn back(files: &Files) -> Layer {
        let get = |ext: &str| &files.iter().find(|(e, _)| *e == ext).unwrap().1;
        read_parts("t.shp", get("shp"), get("shx"), get("dbf"), None).unwrap()
    }

    #[test]
    fn features_without_geometry_are_null_shape_records() {
        let line =
            |x: f64| json!({"type": "LineString", "coordinates": [[x, 0.0], [x + 1.0, 2.0]]});
        let dir = tempfile::tempdir().unwrap();
        for nulls in [vec![], vec![0], vec![1], vec![2], vec![0, 2], vec![1, 2]] {
            let features: Vec<Value> = (0..3)
                .map(|i| {
                    let g = if nulls.contains(&i) {
                        Value::Null
                    } else {
                        line(i as f64)
                    };
                    json!({"type": "Feature", "properties": {"n": i}, "geometry": g})
                })
                .collect();
            let input = fc(Value::Array(features));
            let files = write(&input, None).unwrap();
            assert_eq!(
                back(&files).features.to_value(),
                input,
                "nulls at {nulls:?}"
            );
            // The .shx indexes every record; file lengths in 16-bit words.
            let (shp, shx) = (&files[0].1, &files[1].1);
            assert_eq!(shx.len(), 100 + 8 * 3);
            let words = |b: &[u8]| i32::from_be_bytes(b[24..28].try_into().unwrap()) as usize;
            assert_eq!((words(shp), words(shx)), (shp.len() / 2, shx.len() / 2));
            // Written to files a record at a time: the same bytes, and no
            // staging file left beside them.
            let path = dir.path().join("t.shp");
            write_file(&path, &input, None).unwrap();
            for (ext, bytes) in &files {
                assert_eq!(
                    std::fs::read(sibling(&path, ext)).unwrap(),
                    *bytes,
                    "{ext}, nulls at {nulls:?}"
                );
            }
            assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), files.len());
        }
        // A refusal leaves nothing behind.
        let mixed = fc(json!([
            {"type": "Feature", "properties": {}, "geometry": line(0.0)},
            {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [0, 0]}}
        ]));
        let err = write_file(&dir.path().join("u.shp"), &mixed, None).unwrap_err();
        assert!(
            err.to_string()
                .starts_with(&format!("{}:", dir.path().join("u.shp").display())),
            "{err}"
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 5);
        let none = fc(json!([{"type": "Feature", "properties": {}, "geometry": null}]));
        assert!(write(&none, None)
            .unwrap_err()
            .to_string()
            .contains("no feature has a geometry"));
    }

    #[test]
    fn polygons_with_holes_and_properties_round_trip() {
        // Outer rings clockwise and holes counter-clockwise, as a Shapefile
        // keeps them, so that the positions come back in their order.
        let square = json!([[0.0, 0.0], [0.0, 4.0], [4.0, 4.0], [4.0, 0.0], [0.0, 0.0]]);
        let hole = json!([[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0], [1.0, 1.0]]);
        let far = json!([[10.0, 0.0], [10.0, 1.5], [11.25, 1.0], [10.0, 0.0]]);
        let input = fc(json!([
            {"type": "Feature", "properties": {"name": "lake", "depth": 3, "area": 12.5, "wet": true},
             "geometry": {"type": "Polygon", "coordinates": [square, hole]}},
            {"type": "Feature", "properties": {"name": "isles", "depth": null, "area": 0.1, "wet": false},
             "geometry": {"type": "MultiPolygon", "coordinates": [[square], [far]]}},
        ]));
        let files = write(&input, None).unwrap();
        let layer = back(&files);
        assert_eq!(layer.features.to_value(), input, "read back differs");
        assert_eq!(
            layer.schema.field_names().collect::<Vec<_>>(),
            ["name", "depth", "area", "wet"]
        );
        // Written again with the schema it was read with: the same bytes.
        let again = write(&layer.features, Some(&layer.schema)).unwrap();
        assert_eq!(again[0], files[0]);
        assert_eq!(again[1], files[1]);
    }

    #[test]
    fn lines_with_z_round_trip_and_kinds_may_not_mix() {
        let input = fc(json!([
            {"type": "Feature", "properties": {"id": 1},
             "geometry": {"type": "LineString", "coordinates": [[0.0, 0.0, 5.0], [1.0, 2.0, 6.5]]}},
            {"type": "Feature", "properties": {"id": 2},
             "geometry": {"type": "MultiLineString", "coordinates": [[[3.0, 3.0, 1.0], [4.0, 3.0, 2.0]], [[5.0, 5.0, 0.0], [6.0, 6.0, 0.0]]]}},
        ]));
        assert_eq!(
            back(&write(&input, None).unwrap()).features.to_value(),
            input
        );
        let mixed = fc(json!([
            {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0.0, 0.0], [1.0, 1.0]]}},
            {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [0.0, 0.0]}},
        ]));
        let e = write(&mixed, None).unwrap_err().to_string();
        assert!(
            e.contains("feature 1 holds points and feature 0 lines"),
            "{e}"
        );
        let empty = fc(json!([]));
        assert!(write(&empty, None).is_err());
    }

    #[test]
    fn bad_files_name_what_is_wrong() {
        let input = fc(json!([
            {"type": "Feature", "properties": {"n": 1}, "geometry": {"type": "Point", "coordinates": [1.0, 2.0]}},
            {"type": "Feature", "properties": {"n": 2}, "geometry": {"type": "Point", "coordinates": [3.0, 4.0]}},
        ]));
        let files = write(&input, None).unwrap();
        let (shp, shx, dbf) = (&files[0].1, &files[1].1, &files[2].1);
        let one = fc(json!([input["features"][0].clone()]));
        let dbf1 = &write(&one, None).unwrap()[2].1;
        let e = read_parts("t.shp", shp, shx, dbf1, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("2 shapes but 1 records in t.dbf"), "{e}");
        for cut in [0, 50, 99, shp.len() - 4] {
            let e = read_parts("t.shp", &shp[..cut], shx, dbf, None);
            assert!(e.is_err(), "a .shp cut to {cut} bytes was read");
        }
        assert!(read_parts("t.shp", shp, shx, &dbf[..20], None).is_err());
    }

    #[test]
    fn files_read_a_record_at_a_time_as_their_bytes_read() {
        // Many records of every kind of polygon, so that the readers' buffers
        // turn over many times.
        let features: Vec<Value> = (0..3000)
            .map(|i| {
                let x = f64::from(i) * 10.0;
                let square = json!([[x, 0.0], [x, 4.0], [x + 4.0, 4.0], [x + 4.0, 0.0], [x, 0.0]]);
                let hole = json!([[x + 1.0, 1.0], [x + 2.0, 1.0], [x + 2.0, 2.0], [x + 1.0, 2.0], [x + 1.0, 1.0]]);
                let geometry = match i % 3 {
                    0 => json!({"type": "Polygon", "coordinates": [square]}),
                    1 => json!({"type": "Polygon", "coordinates": [square, hole]}),
                    _ => Value::Null,
                };
                json!({"type": "Feature", "properties": {"n": i, "name": format!("f{i}")}, "geometry": geometry})
            })
            .collect();
        let input = fc(Value::Array(features));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.shp");
        write_file(&path, &input, None).unwrap();
        let bytes = |ext: &str| std::fs::read(dir.path().join(format!("t.{ext}"))).unwrap();
        let (shp, shx, dbf) = (bytes("shp"), bytes("shx"), bytes("dbf"));
        let from_files = read(&path, u64::MAX).unwrap();
        let from_bytes = read_parts("t.shp", &shp, &shx, &dbf, None).unwrap();
        assert_eq!(from_files.features, from_bytes.features);
        assert_eq!(from_files.schema.fields, from_bytes.schema.fields);
        assert_eq!(from_files.features.to_value(), input);
        // A limit below any one file's size refuses it before reading.
        let e = read(&path, 1000).unwrap_err().to_string();
        assert!(e.contains("larger than 1000 bytes"), "{e}");
        // A .shp cut anywhere inside its last record, on disk.
        std::fs::write(&path, &shp[..shp.len() - 3]).unwrap();
        let e = read(&path, u64::MAX).unwrap_err().to_string();
        assert!(e.starts_with(&path.display().to_string()), "{e}");
        assert!(
            e.contains("shape 2999: the record runs past the end"),
            "{e}"
        );
    }

    #[test]
    fn an_index_of_another_count_is_named() {
        let point = |x: f64| json!({"type": "Feature", "properties": {"n": x}, "geometry": {"type": "Point", "coordinates": [x, 2.0]}});
        let files = |n: usize| write(&fc((0..n).map(|i| point(i as f64)).collect()), None).unwrap();
        let (two, three) = (files(2), files(3));
        // The .shp of three points with the index and table of two.
        let e = read_parts("t.shp", &three[0].1, &two[1].1, &two[2].1, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("t.shx: not the index of t.shp: it holds 2 shapes"),
            "{e}"
        );
        let e = read_parts("t.shp", &two[0].1, &three[1].1, &three[2].1, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("it holds 3 shapes, the .shp 2"), "{e}");
        let e = read_parts("t.shp", &two[0].1, &two[1].1[..99], &two[2].1, None)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("t.shx: not a Shapefile index"), "{e}");
    }

    #[test]
    fn properties_that_do_not_fit_their_field_are_named() {
        let input = fc(json!([
            {"type": "Feature", "properties": {"when": "2024-03-01"}, "geometry": {"type": "Point", "coordinates": [1.0, 2.0]}},
        ]));
        let layer = back(&write(&input, None).unwrap());
        let bad = fc(json!([
            {"type": "Feature", "properties": {"when": "yesterday"}, "geometry": {"type": "Point", "coordinates": [1.0, 2.0]}},
        ]));
        // A text field takes any text; a number where a logical field is not.
        assert!(write(&bad, Some(&layer.schema)).is_ok());
        let flags = back(&write(&fc(json!([{"type": "Feature", "properties": {"ok": true}, "geometry": {"type": "Point", "coordinates": [0.0, 0.0]}}])), None).unwrap());
        let wrong = fc(
            json!([{"type": "Feature", "properties": {"ok": 7}, "geometry": {"type": "Point", "coordinates": [0.0, 0.0]}}]),
        );
        let e = write(&wrong, Some(&flags.schema)).unwrap_err().to_string();
        assert!(e.contains("feature 0: field \"ok\""), "{e}");
    }
}
