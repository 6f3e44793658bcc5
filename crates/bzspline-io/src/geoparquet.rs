//! GeoParquet files in and out, through the `parquet` crate (without
//! Arrow): rows read one row group at a time into a [`Layer`] (the primary
//! geometry column's WKB as the geometry, the other columns as properties
//! in their order, the CRS from the `geo` metadata), and a FeatureCollection
//! written as GeoParquet 1.1 with WKB geometries, the input's fields and
//! CRS, built beside the destination and renamed into place only when
//! complete.
//!
//! The geometry column is the one the file's `geo` metadata names as
//! primary, in the WKB encoding; a Parquet file without that metadata is
//! read when one of its columns has Parquet's own `GEOMETRY` logical type.
//! GeoParquet writes the CRS as PROJJSON: a CRS read as PROJJSON is written
//! back as it was, WGS 84 longitude and latitude (GeoJSON's) is left out,
//! which means OGC:CRS84 in GeoParquet, and a CRS known only by WKT or an
//! authority code, which needs PROJ to turn into PROJJSON, is written as
//! that text (GDAL and geopandas read it).

use std::collections::BTreeSet;
use std::fs::File;
use std::path::Path;
use std::sync::Arc;

use anyhow::{anyhow, bail, Context, Result};
use parquet::basic::{
    Compression, ConvertedType, LogicalType, Repetition, TimeUnit, Type as Physical,
};
use parquet::data_type::{BoolType, ByteArray, ByteArrayType, DoubleType, Int32Type, Int64Type};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::record::Field as Cell;
use parquet::schema::types::{Type, TypePtr};
use serde_json::{json, Map, Value};

use crate::features::{has_z, Features, Source};
use crate::geom;
use crate::layer::{self, one_line, Crs, Field, FieldKind, Layer, Schema};

/// Rows a row group of a written file holds at most.
const ROW_GROUP: usize = 65_536;

/// The first bytes of a Parquet file.
#[must_use]
pub fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PAR1")
}

/// Reads the GeoParquet file at `path`, no larger than `max_bytes`, one row
/// group at a time.
///
/// # Errors
///
/// One line naming the file (and the feature by its row, the column): not
/// a Parquet file, no geometry column, an encoding other than WKB, a
/// damaged page, a geometry that is not WKB or has a coordinate that is
/// not finite.
pub fn read(path: &Path, max_bytes: u64) -> Result<Layer> {
    let name = path.display().to_string();
    let file = File::open(path).with_context(|| format!("reading {name}"))?;
    let size = file
        .metadata()
        .with_context(|| format!("reading {name}"))?
        .len();
    if size > max_bytes {
        bail!("{name}: larger than {max_bytes} bytes (--max-bytes); split the input or raise the limit");
    }
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    contained(&name, || {
        let reader = SerializedFileReader::new(file)
            .map_err(|e| anyhow!("{name}: not a Parquet file ({})", one_line(&e)))?;
        read_with(&name, &reader, &stem, size)
    })
}

/// Reads a GeoParquet file held in memory; errors start with `name`.
///
/// # Errors
///
/// As [`read`].
pub fn read_bytes(name: &str, bytes: Vec<u8>) -> Result<Layer> {
    let size = bytes.len() as u64;
    contained(name, || {
        let reader = SerializedFileReader::new(bytes::Bytes::from(bytes))
            .map_err(|e| anyhow!("{name}: not a Parquet file ({})", one_line(&e)))?;
        read_with(name, &reader, "", size)
    })
}

std::thread_local! {
    /// Whether this thread is inside [`contained`].
    static CONTAINED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs a read of the Parquet crate, whose page decoders assert rather than
/// fail on some damaged pages (apache/arrow-rs#9705, #10107): such a panic
/// becomes an error naming the file, and is not printed. The panic hook in
/// place is kept for every other panic (a hook of this module runs first
/// and passes them on).
fn contained<T>(name: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !CONTAINED.with(std::cell::Cell::get) {
                previous(info);
            }
        }));
    });
    CONTAINED.with(|c| c.set(true));
    let out = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    CONTAINED.with(|c| c.set(false));
    out.unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Err(anyhow!(
            "{name}: a damaged page or footer ({})",
            one_line(&what)
        ))
    })
}

/// The primary geometry column and what the file says of it.
struct GeoColumn {
    name: String,
    crs: Option<Crs>,
    /// Columns derived from the geometry (GeoParquet 1.1's bounding box
    /// covering), left out of the fields.
    covering: Vec<String>,
}

/// The geometry column from the `geo` metadata, else the first column of
/// Parquet's `GEOMETRY` logical type.
fn geo_column(name: &str, reader: &dyn FileReader) -> Result<GeoColumn> {
    let meta = reader.metadata().file_metadata();
    let geo = meta
        .key_value_metadata()
        .and_then(|kv| kv.iter().find(|k| k.key == "geo"))
        .and_then(|k| k.value.clone());
    let Some(geo) = geo else {
        let root = meta.schema();
        for t in root.get_fields() {
            match t.get_basic_info().logical_type_ref() {
                Some(LogicalType::Geometry(g)) => {
                    let crs = match &g.crs {
                        None => Some(Crs::wgs84()),
                        Some(text) => crs_of_text(text),
                    };
                    return Ok(GeoColumn {
                        name: t.name().to_owned(),
                        crs,
                        covering: Vec::new(),
                    });
                }
                Some(LogicalType::Geography(_)) => bail!(
                    "{name}: column {:?} holds geographies (edges along great circles), which are not read; write it as geometry",
                    t.name()
                ),
                _ => {}
            }
        }
        bail!("{name}: a Parquet file without GeoParquet metadata (no \"geo\" key) and no GEOMETRY column: not a GeoParquet file");
    };
    let geo: Value = serde_json::from_str(&geo)
        .map_err(|e| anyhow!("{name}: its \"geo\" metadata is not JSON ({e})"))?;
    let primary = geo["primary_column"]
        .as_str()
        .ok_or_else(|| anyhow!("{name}: its \"geo\" metadata names no primary_column"))?
        .to_owned();
    let column = &geo["columns"][&primary];
    if !column.is_object() {
        bail!("{name}: its \"geo\" metadata does not describe its primary column {primary:?}");
    }
    let encoding = column["encoding"].as_str().unwrap_or("");
    if !encoding.eq_ignore_ascii_case("wkb") {
        bail!("{name}: column {primary:?} is encoded as {encoding:?}; only WKB is read (GDAL: ogr2ogr -lco GEOMETRY_ENCODING=WKB)");
    }
    let crs = match column.get("crs") {
        // Absent: OGC:CRS84, longitude and latitude on WGS 84.
        None => Some(Crs::wgs84()),
        Some(Value::Null) => None,
        Some(Value::String(text)) => crs_of_text(text),
        Some(p @ Value::Object(_)) => Some(Crs::from_projjson(p)),
        Some(other) => bail!("{name}: the crs of column {primary:?} is {other}, not PROJJSON"),
    };
    let covering = column["covering"]["bbox"]
        .as_object()
        .map(|b| {
            b.values()
                .filter_map(|v| v.as_array()?.first()?.as_str().map(str::to_owned))
                .collect::<BTreeSet<_>>()
                .into_iter()
                .collect()
        })
        .unwrap_or_default();
    Ok(GeoColumn {
        name: primary,
        crs,
        covering,
    })
}

/// A CRS given as text (an older GeoParquet, Parquet's GEOMETRY type):
/// PROJJSON, WKT, or an authority and code.
fn crs_of_text(text: &str) -> Option<Crs> {
    if let Ok(p @ Value::Object(_)) = serde_json::from_str::<Value>(text) {
        return Some(Crs::from_projjson(&p));
    }
    // Parquet's GEOMETRY type names a CRS kept elsewhere as `projjson:KEY`
    // or `srid:N`.
    if let Some(code) = text.strip_prefix("srid:") {
        return Crs::parse(&format!("EPSG:{code}")).ok();
    }
    Crs::parse(text).ok()
}

/// A field of a Parquet column: the kind its physical and logical types
/// hold, a group (list, map, struct) as text (its JSON).
fn field_of(t: &TypePtr) -> Field {
    let info = t.get_basic_info();
    let kind = if t.is_group() {
        FieldKind::Text
    } else {
        match (t.get_physical_type(), info.logical_type_ref()) {
            (_, Some(LogicalType::Date)) => FieldKind::Date,
            (_, Some(LogicalType::Timestamp(_))) | (Physical::INT96, _) => FieldKind::DateTime,
            (_, Some(LogicalType::Decimal(_))) => FieldKind::Real,
            (
                _,
                Some(
                    LogicalType::String
                    | LogicalType::Enum
                    | LogicalType::Json
                    | LogicalType::Uuid
                    | LogicalType::Time(_),
                ),
            ) => FieldKind::Text,
            (Physical::BOOLEAN, _) => FieldKind::Boolean,
            (Physical::INT32 | Physical::INT64, _) => match info.converted_type() {
                ConvertedType::DATE => FieldKind::Date,
                ConvertedType::TIMESTAMP_MILLIS | ConvertedType::TIMESTAMP_MICROS => {
                    FieldKind::DateTime
                }
                ConvertedType::DECIMAL => FieldKind::Real,
                ConvertedType::TIME_MILLIS | ConvertedType::TIME_MICROS => FieldKind::Text,
                _ => FieldKind::Integer,
            },
            (Physical::FLOAT | Physical::DOUBLE, _) => FieldKind::Real,
            (Physical::BYTE_ARRAY, _)
                if matches!(
                    info.converted_type(),
                    ConvertedType::UTF8 | ConvertedType::ENUM | ConvertedType::JSON
                ) =>
            {
                FieldKind::Text
            }
            _ => FieldKind::Binary,
        }
    };
    // 32-bit integers' widths in digits, as a .dbf counts them.
    let width = (kind == FieldKind::Integer && t.is_primitive())
        .then(|| match info.logical_type_ref() {
            Some(LogicalType::Integer(i)) if i.bit_width <= 8 => Some(3),
            Some(LogicalType::Integer(i)) if i.bit_width <= 16 => Some(5),
            Some(LogicalType::Integer(i)) if i.bit_width <= 32 && i.is_signed => Some(9),
            None if t.get_physical_type() == Physical::INT32 => Some(9),
            _ => None,
        })
        .flatten();
    Field {
        name: t.name().to_owned(),
        kind,
        width,
        decimals: None,
    }
}

fn read_with(name: &str, reader: &dyn FileReader, stem: &str, size: u64) -> Result<Layer> {
    check_chunks(name, reader, size)?;
    let column = geo_column(name, reader)?;
    let root = reader.metadata().file_metadata().schema();
    let Some(gt) = root.get_fields().iter().find(|t| t.name() == column.name) else {
        bail!(
            "{name}: its geometry column {:?} is not among its columns",
            column.name
        );
    };
    if !gt.is_primitive() || gt.get_physical_type() != Physical::BYTE_ARRAY {
        bail!(
            "{name}: its geometry column {:?} does not hold bytes (WKB)",
            column.name
        );
    }
    let fields: Vec<Field> = root
        .get_fields()
        .iter()
        .filter(|t| t.name() != column.name && !column.covering.iter().any(|c| c == t.name()))
        .map(field_of)
        .collect();
    check_columns(name, reader)?;
    let rows = reader
        .get_row_iter(None)
        .map_err(|e| anyhow!("{name}: {}", one_line(&e)))?;
    let mut features = Features::new(fields.iter().map(|f| f.name.clone()).collect());
    for row in rows {
        let here = format!("{name}: feature {}", features.len());
        let row = row.map_err(|e| anyhow!("{here}: {}", one_line(&e)))?;
        let mut geometry = Value::Null;
        let mut properties = Map::new();
        for f in &fields {
            properties.insert(f.name.clone(), Value::Null);
        }
        for (col, cell) in row.get_column_iter() {
            if *col == column.name {
                geometry = match cell {
                    Cell::Null => Value::Null,
                    Cell::Bytes(b) => {
                        wkb(b.data()).map_err(|e| anyhow!("{here}: {}", one_line(&e)))?
                    }
                    _ => bail!("{here}: its geometry is not WKB bytes"),
                };
                continue;
            }
            let Some(f) = fields.iter().find(|f| f.name == *col) else {
                continue;
            };
            let v = value(cell, f).map_err(|e| anyhow!("{here}, field {col:?}: {e}"))?;
            properties.insert(col.clone(), v);
        }
        features.push(properties, geometry);
    }
    Ok(Layer {
        features,
        schema: Schema::new(stem, fields, column.crs),
    })
}

/// Checks that every column chunk the footer declares lies within the file
/// (the reader would stop the program on a negative offset or size).
fn check_chunks(name: &str, reader: &dyn FileReader, size: u64) -> Result<()> {
    for (g, rg) in reader.metadata().row_groups().iter().enumerate() {
        if rg.num_rows() < 0 {
            bail!("{name}: row group {g} declares {} rows", rg.num_rows());
        }
        for c in rg.columns() {
            let start = c.dictionary_page_offset().unwrap_or(c.data_page_offset());
            let len = c.compressed_size();
            let inside = u64::try_from(start)
                .ok()
                .zip(u64::try_from(len).ok())
                .and_then(|(s, l)| s.checked_add(l))
                .is_some_and(|end| end <= size);
            if !inside {
                bail!(
                    "{name}: row group {g}, column {:?}: its {len} bytes at {start} lie outside the file's {size}",
                    c.column_path().string()
                );
            }
        }
    }
    Ok(())
}

/// Refuses the columns whose values Parquet's record reader does not
/// convert (it would stop the program), naming the first.
fn check_columns(name: &str, reader: &dyn FileReader) -> Result<()> {
    use ConvertedType as C;
    for c in reader.metadata().file_metadata().schema_descr().columns() {
        let converted = c.converted_type();
        let ok = match c.physical_type() {
            Physical::INT32 => matches!(
                converted,
                C::NONE
                    | C::INT_8
                    | C::INT_16
                    | C::INT_32
                    | C::UINT_8
                    | C::UINT_16
                    | C::UINT_32
                    | C::DATE
                    | C::TIME_MILLIS
                    | C::DECIMAL
            ),
            Physical::INT64 => matches!(
                converted,
                C::NONE
                    | C::INT_64
                    | C::UINT_64
                    | C::TIME_MICROS
                    | C::TIMESTAMP_MILLIS
                    | C::TIMESTAMP_MICROS
                    | C::DECIMAL
            ),
            Physical::BYTE_ARRAY => matches!(
                converted,
                C::NONE | C::UTF8 | C::ENUM | C::JSON | C::BSON | C::DECIMAL
            ),
            Physical::FIXED_LEN_BYTE_ARRAY => matches!(converted, C::NONE | C::DECIMAL),
            _ => true,
        };
        if !ok {
            bail!(
                "{name}: column {:?} is {} annotated {converted}, which is not read",
                c.path().string(),
                c.physical_type()
            );
        }
    }
    Ok(())
}

/// A WKB geometry (ISO, or the extended WKB GDAL once wrote) as GeoJSON,
/// z kept where it has z; an empty geometry as `null`.
fn wkb(bytes: &[u8]) -> Result<Value> {
    let mut out = geom::ToJson::new(true);
    geozero::wkb::process_wkb_geom(&mut &bytes[..], &mut out)
        .map_err(|e| anyhow!("its geometry: {}", one_line(&e)))?;
    let mut g = out.finish();
    geom::fill_z(&mut g);
    Ok(g)
}

/// A Parquet value as the property of its field.
fn value(cell: &Cell, f: &Field) -> Result<Value> {
    let days = |d: i64| -> Result<jiff::civil::Date> {
        jiff::civil::date(1970, 1, 1)
            .checked_add(jiff::Span::new().try_days(d)?)
            .map_err(|e| anyhow!("{e}"))
    };
    let instant = |micros: i128| -> Result<Value> {
        let t = i64::try_from(micros)
            .ok()
            .and_then(|m| jiff::Timestamp::from_microsecond(m).ok())
            .ok_or_else(|| anyhow!("a time outside the years -9999 to 9999"))?;
        Ok(Value::from(t.to_string()))
    };
    Ok(match cell {
        Cell::Null => Value::Null,
        Cell::Bool(b) => json!(b),
        Cell::Byte(x) => json!(x),
        Cell::Short(x) => json!(x),
        Cell::Int(x) => json!(x),
        Cell::Long(x) => json!(x),
        Cell::UByte(x) => json!(x),
        Cell::UShort(x) => json!(x),
        Cell::UInt(x) => json!(x),
        Cell::ULong(x) => json!(x),
        Cell::Float16(x) => finite(f64::from(*x)),
        // The float's own shortest decimal, not its binary expansion.
        Cell::Float(x) => finite(x.to_string().parse().unwrap_or(f64::from(*x))),
        Cell::Double(x) => finite(*x),
        Cell::Decimal(_) | Cell::Group(_) | Cell::ListInternal(_) | Cell::MapInternal(_) => {
            match cell.to_json_value() {
                Value::String(s) if f.kind == FieldKind::Real => {
                    finite(s.parse().map_err(|_| anyhow!("{s:?} is not a number"))?)
                }
                v => v,
            }
        }
        Cell::Str(s) => Value::from(s.as_str()),
        Cell::Bytes(b) => match f.kind {
            FieldKind::Text => Value::from(String::from_utf8_lossy(b.data()).into_owned()),
            _ => Value::from(layer::hex(b.data())),
        },
        Cell::Date(d) => Value::from(days(i64::from(*d))?.to_string()),
        Cell::TimestampMillis(t) => instant(i128::from(*t) * 1000)?,
        Cell::TimestampMicros(t) => instant(i128::from(*t))?,
        Cell::TimeMillis(_) | Cell::TimeMicros(_) => cell.to_json_value(),
    })
}

fn finite(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// Writes the features of a GeoJSON FeatureCollection as a GeoParquet file
/// at `path`: with `schema`'s fields and CRS when given (the layer read),
/// else with fields found from the properties, in WGS 84 (GeoJSON's
/// coordinates). The file is built beside `path` and renamed onto it only
/// when complete.
///
/// # Errors
///
/// A property its field cannot hold (naming the feature and field), a field
/// named like the geometry column, I/O errors.
pub fn write(path: &Path, features: &dyn Source, schema: Option<&Schema>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = layer::staging_file(dir, "")
        .with_context(|| format!("creating a file in {}", dir.display()))?;
    write_to(tmp.as_file_mut(), features, schema)
        .map_err(|e| anyhow!("{}: {e}", path.display()))?;
    tmp.persist(path)
        .map_err(|e| e.error)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// The bytes of the GeoParquet file [`write()`] writes.
///
/// # Errors
///
/// As [`write()`].
pub fn to_bytes(features: &dyn Source, schema: Option<&Schema>) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    write_to(&mut out, features, schema)?;
    Ok(out)
}

/// How a field's values are stored.
#[derive(Clone, Copy, PartialEq)]
enum Store {
    Bool,
    Int32,
    Int64,
    Double,
    Text,
    Bytes,
    /// Days since 1970-01-01.
    Date,
    /// Microseconds since 1970-01-01T00:00Z.
    Instant,
}

fn store_of(f: &Field) -> Store {
    match f.kind {
        FieldKind::Boolean => Store::Bool,
        FieldKind::Integer if f.width.is_some_and(|w| w <= 9) => Store::Int32,
        FieldKind::Integer => Store::Int64,
        FieldKind::Real => Store::Double,
        FieldKind::Text => Store::Text,
        FieldKind::Binary => Store::Bytes,
        FieldKind::Date => Store::Date,
        FieldKind::DateTime => Store::Instant,
    }
}

fn column_type(name: &str, store: Store) -> Result<TypePtr> {
    let (physical, logical) = match store {
        Store::Bool => (Physical::BOOLEAN, None),
        Store::Int32 => (Physical::INT32, Some(LogicalType::integer(32, true))),
        Store::Int64 => (Physical::INT64, Some(LogicalType::integer(64, true))),
        Store::Double => (Physical::DOUBLE, None),
        Store::Text => (Physical::BYTE_ARRAY, Some(LogicalType::String)),
        Store::Bytes => (Physical::BYTE_ARRAY, None),
        Store::Date => (Physical::INT32, Some(LogicalType::Date)),
        Store::Instant => (
            Physical::INT64,
            Some(LogicalType::timestamp(true, TimeUnit::MICROS)),
        ),
    };
    Ok(Arc::new(
        Type::primitive_type_builder(name, physical)
            .with_repetition(Repetition::OPTIONAL)
            .with_logical_type(logical)
            .build()
            .map_err(|e| anyhow!("column {name:?}: {}", one_line(&e)))?,
    ))
}

/// A property's value as its column stores it; `None` for no value.
enum Stored {
    Bool(bool),
    Int(i64),
    Double(f64),
    Bytes(Vec<u8>),
}

fn stored(v: &Value, f: &Field, store: Store) -> Result<Option<Stored>> {
    let bad = |what: &str| anyhow!("field {:?}: {v} is not {what}", f.name);
    Ok(Some(match (store, v) {
        (_, Value::Null) => return Ok(None),
        (Store::Bool, Value::Bool(b)) => Stored::Bool(*b),
        (Store::Bool, _) => return Err(bad("true or false")),
        (Store::Int32 | Store::Int64, Value::Number(n)) => {
            let i = layer::whole(n).ok_or_else(|| bad("a whole number"))?;
            if store == Store::Int32 && i32::try_from(i).is_err() {
                return Err(bad("a 32-bit whole number"));
            }
            Stored::Int(i)
        }
        (Store::Int32 | Store::Int64, _) => return Err(bad("a whole number")),
        (Store::Double, Value::Number(n)) => {
            Stored::Double(n.as_f64().ok_or_else(|| bad("a number"))?)
        }
        (Store::Double, _) => return Err(bad("a number")),
        (Store::Bytes, Value::String(s)) => {
            Stored::Bytes(layer::unhex(s).ok_or_else(|| bad("bytes as hexadecimal text"))?)
        }
        (Store::Date, Value::String(s)) => {
            let d: jiff::civil::Date = s.trim().parse().map_err(|_| bad("a date YYYY-MM-DD"))?;
            let days = jiff::civil::date(1970, 1, 1)
                .until(d)
                .map_err(|_| bad("a date YYYY-MM-DD"))?
                .get_days();
            Stored::Int(i64::from(days))
        }
        (Store::Instant, Value::String(s)) => Stored::Int(
            instant(s).ok_or_else(|| bad("a date and time (ISO 8601, with its offset)"))?,
        ),
        (Store::Date | Store::Instant, _) => return Err(bad("a date as text")),
        (_, v) => Stored::Bytes(layer::as_text(v).unwrap_or_default().into_bytes()),
    }))
}

/// Microseconds since 1970-01-01T00:00Z of a date and time: with an offset
/// or `Z`, else read as UTC (a date alone is its midnight).
fn instant(s: &str) -> Option<i64> {
    let s = s.trim();
    if let Ok(t) = s.parse::<jiff::Timestamp>() {
        return Some(t.as_microsecond());
    }
    let civil: jiff::civil::DateTime = s.parse().ok().or_else(|| {
        s.parse::<jiff::civil::Date>()
            .ok()
            .map(|d| d.at(0, 0, 0, 0))
    })?;
    civil
        .to_zoned(jiff::tz::TimeZone::UTC)
        .ok()
        .map(|z| z.timestamp().as_microsecond())
}

/// Whether a layer's fields can be written with their kinds: Date and
/// DateTime fields become text when a value is not a date or time (a
/// Shapefile's or GeoPackage's text in a date column).
fn stores(features: &dyn Source, fields: &[Field]) -> Vec<Store> {
    fields
        .iter()
        .map(|f| {
            let store = store_of(f);
            let fits = |v: &Value| match (store, v) {
                (_, Value::Null) => true,
                (Store::Date, Value::String(s)) => s.trim().parse::<jiff::civil::Date>().is_ok(),
                (Store::Instant, Value::String(s)) => instant(s).is_some(),
                (Store::Date | Store::Instant, _) => false,
                _ => true,
            };
            let all = (0..features.count()).all(|i| fits(&features.property(i, &f.name)));
            if all {
                store
            } else {
                Store::Text
            }
        })
        .collect()
}

/// The `geo` metadata of a layer's geometry column.
fn geo_metadata(features: &dyn Source, crs: Option<&Crs>) -> Value {
    let mut types = BTreeSet::new();
    let mut bbox: Option<[f64; 4]> = None;
    for i in 0..features.count() {
        let g = &*features.geometry(i);
        if let Some(t) = g["type"].as_str() {
            let z = if has_z(g) { " Z" } else { "" };
            types.insert(format!("{t}{z}"));
        }
        if let Some([x0, x1, y0, y1]) = geom::envelope(g) {
            bbox = Some(match bbox {
                None => [x0, y0, x1, y1],
                Some([a, b, c, d]) => [a.min(x0), b.min(y0), c.max(x1), d.max(y1)],
            });
        }
    }
    let mut column =
        json!({"encoding": "WKB", "geometry_types": types.into_iter().collect::<Vec<_>>()});
    if let Some(b) = bbox {
        column["bbox"] = json!(b);
    }
    match crs {
        None => column["crs"] = Value::Null,
        Some(c) if c.epsg() == Some(4326) && c.projjson.is_none() => {}
        Some(c) => {
            column["crs"] = match (&c.projjson, &c.wkt, &c.authority) {
                (Some(p), _, _) => serde_json::from_str(p).unwrap_or(Value::Null),
                (None, Some(w), _) => Value::from(w.as_str()),
                (None, None, Some((org, code))) => Value::from(format!("{org}:{code}")),
                (None, None, None) => Value::Null,
            };
        }
    }
    json!({
        "version": "1.1.0",
        "primary_column": "geometry",
        "columns": {"geometry": column},
    })
}

fn write_to<W: std::io::Write + Send>(
    out: W,
    features: &dyn Source,
    schema: Option<&Schema>,
) -> Result<()> {
    let fields = match schema {
        Some(s) => s.fields.clone(),
        None => layer::infer_fields(features),
    };
    if let Some(f) = fields.iter().find(|f| f.name == "geometry") {
        bail!(
            "field {:?} has the name of the geometry column; rename it",
            f.name
        );
    }
    let crs = match schema {
        Some(s) => s.crs.clone(),
        None => Some(Crs::wgs84()),
    };
    let stores = stores(features, &fields);
    let mut columns = vec![Arc::new(
        Type::primitive_type_builder("geometry", Physical::BYTE_ARRAY)
            .with_repetition(Repetition::OPTIONAL)
            .build()
            .map_err(|e| anyhow!("{}", one_line(&e)))?,
    )];
    for (f, s) in fields.iter().zip(&stores) {
        columns.push(column_type(&f.name, *s)?);
    }
    let root = Arc::new(
        Type::group_type_builder("schema")
            .with_fields(columns)
            .build()
            .map_err(|e| anyhow!("{}", one_line(&e)))?,
    );
    let geo = geo_metadata(features, crs.as_ref());
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_key_value_metadata(Some(vec![KeyValue::new("geo".to_owned(), geo.to_string())]))
        .build();
    let mut writer = SerializedFileWriter::new(out, root, Arc::new(props))
        .map_err(|e| anyhow!("{}", one_line(&e)))?;
    let pq = |e: parquet::errors::ParquetError| anyhow!("{}", one_line(&e));
    for first in (0..features.count()).step_by(ROW_GROUP) {
        let group = first..features.count().min(first + ROW_GROUP);
        let mut rg = writer.next_row_group().map_err(pq)?;
        // The geometry column, then each field's.
        let mut col = rg
            .next_column()
            .map_err(pq)?
            .ok_or_else(|| anyhow!("no geometry column"))?;
        let mut values = Vec::with_capacity(group.len());
        let mut defs = Vec::with_capacity(group.len());
        for i in group.clone() {
            let g = features.geometry(i);
            if g.is_null() {
                defs.push(0);
                continue;
            }
            let bytes = geom::to_wkb(&g, geozero::wkb::WkbDialect::Wkb, None, Vec::new())
                .map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?;
            values.push(ByteArray::from(bytes));
            defs.push(1);
        }
        col.typed::<ByteArrayType>()
            .write_batch(&values, Some(&defs), None)
            .map_err(pq)?;
        col.close().map_err(pq)?;
        for (f, store) in fields.iter().zip(&stores) {
            let mut cells = Vec::with_capacity(group.len());
            for i in group.clone() {
                let v = features.property(i, &f.name);
                let v = v.as_ref();
                cells.push(
                    stored(v, f, *store).map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?,
                );
            }
            let defs: Vec<i16> = cells.iter().map(|c| i16::from(c.is_some())).collect();
            let mut col = rg
                .next_column()
                .map_err(pq)?
                .ok_or_else(|| anyhow!("field {:?}: no column", f.name))?;
            let cells = cells.into_iter().flatten();
            match store {
                Store::Bool => {
                    let v: Vec<bool> = cells.map(|c| matches!(c, Stored::Bool(true))).collect();
                    col.typed::<BoolType>().write_batch(&v, Some(&defs), None)
                }
                Store::Int32 | Store::Date => {
                    let v: Vec<i32> = cells
                        .map(|c| match c {
                            Stored::Int(i) => i32::try_from(i).unwrap_or_default(),
                            _ => 0,
                        })
                        .collect();
                    col.typed::<Int32Type>().write_batch(&v, Some(&defs), None)
                }
                Store::Int64 | Store::Instant => {
                    let v: Vec<i64> = cells
                        .map(|c| match c {
                            Stored::Int(i) => i,
                            _ => 0,
                        })
                        .collect();
                    col.typed::<Int64Type>().write_batch(&v, Some(&defs), None)
                }
                Store::Double => {
                    let v: Vec<f64> = cells
                        .map(|c| match c {
                            Stored::Double(x) => x,
                            _ => 0.0,
                        })
                        .collect();
                    col.typed::<DoubleType>().write_batch(&v, Some(&defs), None)
                }
                Store::Text | Store::Bytes => {
                    let v: Vec<ByteArray> = cells
                        .map(|c| match c {
                            Stored::Bytes(b) => ByteArray::from(b),
                            _ => ByteArray::new(),
                        })
                        .collect();
                    col.typed::<ByteArrayType>()
                        .write_batch(&v, Some(&defs), None)
                }
            }
            .map_err(pq)?;
            col.close().map_err(pq)?;
        }
        rg.close().map_err(pq)?;
    }
    writer.close().map_err(pq)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fc(features: Value) -> Value {
        json!({"type": "FeatureCollection", "features": features})
    }

    #[test]
    fn layers_round_trip_with_fields_and_crs() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.parquet");
        let input = fc(json!([
            {"type": "Feature", "properties": {"name": "lake", "depth": 3, "area": 12.5, "wet": true},
             "geometry": {"type": "Polygon", "coordinates": [[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 0.0]], [[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 1.0]]]}},
            {"type": "Feature", "properties": {"name": null, "depth": null, "area": 0.1, "wet": false},
             "geometry": {"type": "MultiPolygon", "coordinates": [[[[10.0, 0.0], [11.0, 1.0], [10.0, 1.5], [10.0, 0.0]]], [[[20.0, 0.0], [21.0, 1.0], [20.0, 1.5], [20.0, 0.0]]]]}},
            {"type": "Feature", "properties": {"name": "none", "depth": 1, "area": 0.0, "wet": null},
             "geometry": null},
            {"type": "Feature", "properties": {"name": "z", "depth": 2, "area": 1.0, "wet": true},
             "geometry": {"type": "LineString", "coordinates": [[0.0, 0.0, 5.0], [1.0, 2.0, 6.5]]}},
        ]));
        write(&path, &input, None).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(sniff(&bytes));
        let layer = read(&path, u64::MAX).unwrap();
        assert_eq!(layer.features.to_value(), input);
        assert_eq!(layer.schema.name, "t");
        assert_eq!(layer.schema.crs.as_ref().and_then(Crs::epsg), Some(4326));
        let kinds: Vec<FieldKind> = layer.schema.fields.iter().map(|f| f.kind).collect();
        assert_eq!(
            kinds,
            [
                FieldKind::Text,
                FieldKind::Integer,
                FieldKind::Real,
                FieldKind::Boolean
            ]
        );
        // Every prefix of the file, and the file with any byte changed, is
        // read or refused in one line naming it (the Parquet crate's
        // decoders panic on some damaged pages: found by fuzzing).
        let refused = |b: Vec<u8>| {
            if let Err(e) = read_bytes("t.parquet", b) {
                let e = e.to_string();
                assert!(e.starts_with("t.parquet: ") && !e.contains('\n'), "{e}");
            }
        };
        for cut in (0..bytes.len()).step_by(5) {
            refused(bytes[..cut].to_vec());
        }
        for at in 0..bytes.len() {
            let mut bad = bytes.clone();
            bad[at] ^= 0x5a;
            refused(bad);
        }
    }

    #[test]
    fn dates_times_and_bytes_keep_their_types() {
        let fields = vec![
            Field {
                name: "day".into(),
                kind: FieldKind::Date,
                width: None,
                decimals: None,
            },
            Field {
                name: "at".into(),
                kind: FieldKind::DateTime,
                width: None,
                decimals: None,
            },
            Field {
                name: "raw".into(),
                kind: FieldKind::Binary,
                width: None,
                decimals: None,
            },
            Field {
                name: "n".into(),
                kind: FieldKind::Integer,
                width: Some(5),
                decimals: None,
            },
        ];
        let utm = Crs::from_wkt("PROJCS[\"WGS 84 / UTM zone 33N\",GEOGCS[\"WGS 84\"],UNIT[\"metre\",1],AUTHORITY[\"EPSG\",\"32633\"]]");
        let schema = Schema::new("s", fields, Some(utm));
        let input = fc(json!([
            {"type": "Feature", "properties": {"day": "2024-02-29", "at": "2024-02-29T12:30:00Z", "raw": "00ff", "n": -7},
             "geometry": {"type": "Point", "coordinates": [500000.0, 4649776.0]}},
            {"type": "Feature", "properties": {"day": "1901-01-01", "at": null, "raw": null, "n": 12},
             "geometry": {"type": "Point", "coordinates": [1.0, 2.0]}},
        ]));
        let bytes = to_bytes(&input, Some(&schema)).unwrap();
        let layer = read_bytes("s.parquet", bytes).unwrap();
        assert_eq!(layer.features.to_value(), input);
        let kinds: Vec<FieldKind> = layer.schema.fields.iter().map(|f| f.kind).collect();
        assert_eq!(
            kinds,
            [
                FieldKind::Date,
                FieldKind::DateTime,
                FieldKind::Binary,
                FieldKind::Integer
            ]
        );
        assert_eq!(layer.schema.crs.as_ref().and_then(Crs::epsg), Some(32633));
        // A date column holding text that is no date is written as text.
        let odd = fc(
            json!([{"type": "Feature", "properties": {"day": "soon", "at": null, "raw": null, "n": null},
            "geometry": null}]),
        );
        let layer = read_bytes("s", to_bytes(&odd, Some(&schema)).unwrap()).unwrap();
        assert_eq!(layer.schema.fields[0].kind, FieldKind::Text);
        assert_eq!(layer.features.to_value(), odd);
    }

    #[test]
    fn what_is_not_geoparquet_is_named() {
        let e = read_bytes("x.parquet", b"PAR1 not really".to_vec()).unwrap_err();
        assert!(
            e.to_string().starts_with("x.parquet: not a Parquet file"),
            "{e}"
        );
        // A Parquet file without geo metadata.
        let root = Arc::new(
            Type::group_type_builder("schema")
                .with_fields(vec![column_type("a", Store::Int64).unwrap()])
                .build()
                .unwrap(),
        );
        let mut bytes = Vec::new();
        let w = SerializedFileWriter::new(&mut bytes, root, Arc::new(WriterProperties::default()))
            .unwrap();
        w.close().unwrap();
        let e = read_bytes("plain.parquet", bytes).unwrap_err().to_string();
        assert!(
            e.contains("no \"geo\" key") && e.starts_with("plain.parquet:"),
            "{e}"
        );
        // A field named like the geometry column.
        let clash =
            fc(json!([{"type": "Feature", "properties": {"geometry": 1}, "geometry": null}]));
        let e = to_bytes(&clash, None).unwrap_err().to_string();
        assert!(e.contains("\"geometry\""), "{e}");
    }
}
