//! FlatGeobuf files in and out, through the `flatgeobuf` crate: features
//! read one at a time from the file into a [`Layer`] (columns as properties
//! in their order, the CRS from the header), and a FeatureCollection written
//! with the input's fields and CRS and a spatial index, built beside the
//! destination and renamed into place only when complete.
//!
//! A FlatGeobuf file has z for every position or for none: in a layer where
//! some geometries have z, the others are written with z = 0.
//!
//! Every feature's geometry and properties are checked against the bounds
//! of its buffer before they are decoded, so that a damaged file gives an
//! error naming the feature, never a panic.

use std::io::{BufReader, Read};
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use flatgeobuf::packed_r_tree::PackedRTree;
use flatgeobuf::{ColumnType, FgbCrs, FgbWriter, FgbWriterOptions, Geometry, GeometryType};
use geozero::{ColumnValue, GeozeroGeometry, PropertyProcessor};
use serde_json::{json, Map, Value};

use crate::features::{Features, Source};
use crate::geom;
use crate::layer::{self, one_line, Crs, Field, FieldKind, Layer, Schema};

/// The first bytes of a FlatGeobuf file (`fgb`, version 3).
#[must_use]
pub fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(b"fgb\x03fgb")
}

/// Reads the FlatGeobuf file at `path`, no larger than `max_bytes`, one
/// feature at a time.
///
/// # Errors
///
/// One line naming the file (and the feature by its number, the column):
/// not a FlatGeobuf file, a damaged header or feature, a coordinate that is
/// not finite, curved geometries.
pub fn read(path: &Path, max_bytes: u64) -> Result<Layer> {
    let name = path.display().to_string();
    let file = std::fs::File::open(path).with_context(|| format!("reading {name}"))?;
    let size = file
        .metadata()
        .with_context(|| format!("reading {name}"))?
        .len();
    if size > max_bytes {
        bail!("{name}: larger than {max_bytes} bytes (--max-bytes); split the input or raise the limit");
    }
    read_from(&name, BufReader::new(file))
}

/// Reads a FlatGeobuf file from `reader`; errors start with `name`.
///
/// # Errors
///
/// As [`read`].
pub fn read_from<R: Read>(name: &str, mut reader: R) -> Result<Layer> {
    let mut magic = [0u8; 8];
    if reader.read_exact(&mut magic).is_err() || !sniff(&magic) {
        bail!("{name}: not a FlatGeobuf file (no fgb magic bytes)");
    }
    let header_buf = size_prefixed(&mut reader)
        .map_err(|e| anyhow!("{name}: its header: {e}"))?
        .ok_or_else(|| anyhow!("{name}: ends before its header"))?;
    let header = flatgeobuf::size_prefixed_root_as_header(&header_buf)
        .map_err(|e| anyhow!("{name}: its header: {}", one_line(&e)))?;
    if header.index_node_size() == 1 {
        bail!("{name}: its header declares index nodes of 1 item (at least 2, or 0 for none)");
    }
    if header.features_count() > 1 << 48 {
        bail!(
            "{name}: its header declares {} features, more than any file holds",
            header.features_count()
        );
    }
    let layer_name = header.name().unwrap_or_default().to_owned();
    let z = header.has_z();
    let declared = header.geometry_type();
    let crs = header.crs().and_then(|c| {
        let wkt = c.wkt().map(str::to_owned);
        let authority = (c.code() != 0).then(|| (c.org().unwrap_or("EPSG").to_owned(), c.code()));
        (authority.is_some() || wkt.is_some()).then_some(Crs {
            authority,
            wkt,
            projjson: None,
        })
    });
    let mut columns: Vec<(Field, ColumnType)> = Vec::new();
    for c in header.columns().iter().flatten() {
        let kind = match c.type_() {
            ColumnType::Bool => FieldKind::Boolean,
            ColumnType::Byte
            | ColumnType::UByte
            | ColumnType::Short
            | ColumnType::UShort
            | ColumnType::Int
            | ColumnType::UInt
            | ColumnType::Long
            | ColumnType::ULong => FieldKind::Integer,
            ColumnType::Float | ColumnType::Double => FieldKind::Real,
            ColumnType::DateTime => FieldKind::DateTime,
            ColumnType::Binary => FieldKind::Binary,
            _ => FieldKind::Text,
        };
        // Integers' widths in digits, as a .dbf counts them.
        let width = match c.type_() {
            ColumnType::Byte | ColumnType::UByte => Some(3),
            ColumnType::Short | ColumnType::UShort => Some(5),
            ColumnType::Int => Some(9),
            ColumnType::UInt | ColumnType::Long | ColumnType::ULong => None,
            _ => u32::try_from(c.width()).ok().filter(|&w| w > 0),
        };
        let decimals = u32::try_from(c.scale()).ok().filter(|&s| s > 0);
        columns.push((
            Field {
                name: c.name().to_owned(),
                kind,
                width,
                decimals,
            },
            c.type_(),
        ));
    }
    // The spatial index, skipped: features are read in the file's order.
    let count = header.features_count();
    if header.index_node_size() > 0 && count > 0 {
        let size = PackedRTree::index_size(count as usize, header.index_node_size()) as u64;
        let skipped = std::io::copy(&mut (&mut reader).take(size), &mut std::io::sink())
            .map_err(|e| anyhow!("{name}: reading its index: {e}"))?;
        if skipped < size {
            bail!("{name}: ends inside its spatial index");
        }
    }
    let mut features = Features::new(columns.iter().map(|(f, _)| f.name.clone()).collect());
    loop {
        let i = features.len();
        let here = format!("{name}: feature {i}");
        let Some(buf) = size_prefixed(&mut reader).map_err(|e| anyhow!("{here}: {e}"))? else {
            break;
        };
        let fbs = flatgeobuf::size_prefixed_root_as_feature(&buf)
            .map_err(|e| anyhow!("{here}: {}", one_line(&e)))?;
        let geometry = match fbs.geometry() {
            None => Value::Null,
            Some(g) => {
                check_geometry(&g, 0).map_err(|e| anyhow!("{here}: {}", one_line(&e)))?;
                if g.xy().is_none_or(|v| v.is_empty()) && g.parts().is_none_or(|p| p.is_empty()) {
                    Value::Null
                } else {
                    let mut out = if z {
                        geom::ToJson::with_z_everywhere()
                    } else {
                        geom::ToJson::new(false)
                    };
                    g.process(&mut out, declared)
                        .map_err(|e| anyhow!("{here}: {}", one_line(&e)))?;
                    out.finish()
                }
            }
        };
        let mut properties = Map::new();
        for (f, _) in &columns {
            properties.insert(f.name.clone(), Value::Null);
        }
        if let Some(bytes) = fbs.properties() {
            read_properties(bytes.bytes(), &columns, &mut properties)
                .map_err(|e| anyhow!("{here}: {}", one_line(&e)))?;
        }
        features.push(properties, geometry);
    }
    Ok(Layer {
        features,
        schema: Schema {
            name: layer_name,
            fields: columns.into_iter().map(|c| c.0).collect(),
            crs,
            #[cfg(feature = "shapefile")]
            dbf: None,
        },
    })
}

/// The next size-prefixed buffer of a stream, with its 4-byte size: `None`
/// at the end of the stream. The buffer grows as its bytes arrive, so a
/// damaged size costs no more memory than the file holds.
fn size_prefixed<R: Read>(reader: &mut R) -> Result<Option<Vec<u8>>> {
    let mut size = [0u8; 4];
    let mut got = 0;
    while got < 4 {
        match reader.read(&mut size[got..]) {
            Ok(0) if got == 0 => return Ok(None),
            Ok(0) => bail!("the file ends inside a size"),
            Ok(n) => got += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => bail!("{e}"),
        }
    }
    let n = u64::from(u32::from_le_bytes(size));
    let mut buf = size.to_vec();
    let read = reader.take(n).read_to_end(&mut buf)?;
    if (read as u64) < n {
        bail!("the file ends {} bytes short of its {n}", n - read as u64);
    }
    Ok(Some(buf))
}

/// Checks that a geometry's arrays agree before the reader indexes them:
/// x and y in pairs, a z for every pair, part ends in order within the
/// pairs, parts nested at most 32 deep.
fn check_geometry(g: &Geometry, depth: usize) -> Result<()> {
    if depth > 32 {
        bail!("geometries nested more than 32 deep");
    }
    let pairs = match g.xy() {
        Some(xy) if xy.len() % 2 != 0 => bail!("its geometry has an odd number of x and y values"),
        Some(xy) => xy.len() / 2,
        None => 0,
    };
    if let Some(z) = g.z() {
        if z.len() != pairs {
            bail!(
                "its geometry has {} z values for {pairs} positions",
                z.len()
            );
        }
    }
    if let Some(ends) = g.ends() {
        let mut prev = 0usize;
        for e in ends.iter() {
            let e = e as usize;
            if e < prev || e > pairs {
                bail!("its geometry's part ends do not index its positions in order");
            }
            prev = e;
        }
    }
    if let Some(parts) = g.parts() {
        for p in parts.iter() {
            check_geometry(&p, depth + 1)?;
        }
    }
    Ok(())
}

/// Decodes a feature's properties (a column index, then its value, for
/// each one present) into `out`, every read within `bytes`.
fn read_properties(
    bytes: &[u8],
    columns: &[(Field, ColumnType)],
    out: &mut Map<String, Value>,
) -> Result<()> {
    let mut at = 0usize;
    let take = |at: &mut usize, n: usize| -> Result<&[u8]> {
        let s = bytes
            .get(*at..at.saturating_add(n))
            .ok_or_else(|| anyhow!("its properties run past their buffer"))?;
        *at += n;
        Ok(s)
    };
    // A trailing byte after the last value is tolerated, as GDAL writes.
    while at + 1 < bytes.len() {
        let idx = usize::from(u16::from_le_bytes([bytes[at], bytes[at + 1]]));
        at += 2;
        let (field, kind) = columns
            .get(idx)
            .ok_or_else(|| anyhow!("a property of column {idx}, of {}", columns.len()))?;
        let arr = |s: &[u8]| -> [u8; 8] {
            let mut a = [0u8; 8];
            a[..s.len()].copy_from_slice(s);
            a
        };
        let v = match *kind {
            ColumnType::Bool => json!(take(&mut at, 1)?[0] != 0),
            ColumnType::Byte => json!(take(&mut at, 1)?[0] as i8),
            ColumnType::UByte => json!(take(&mut at, 1)?[0]),
            ColumnType::Short => {
                let a = arr(take(&mut at, 2)?);
                json!(i16::from_le_bytes([a[0], a[1]]))
            }
            ColumnType::UShort => {
                let a = arr(take(&mut at, 2)?);
                json!(u16::from_le_bytes([a[0], a[1]]))
            }
            ColumnType::Int => {
                let a = arr(take(&mut at, 4)?);
                json!(i32::from_le_bytes([a[0], a[1], a[2], a[3]]))
            }
            ColumnType::UInt => {
                let a = arr(take(&mut at, 4)?);
                json!(u32::from_le_bytes([a[0], a[1], a[2], a[3]]))
            }
            ColumnType::Long => json!(i64::from_le_bytes(arr(take(&mut at, 8)?))),
            ColumnType::ULong => json!(u64::from_le_bytes(arr(take(&mut at, 8)?))),
            ColumnType::Float => {
                let a = arr(take(&mut at, 4)?);
                let x = f32::from_le_bytes([a[0], a[1], a[2], a[3]]);
                // The float's own shortest decimal, not its binary expansion.
                number(x.to_string().parse().unwrap_or(f64::from(x)))
            }
            ColumnType::Double => number(f64::from_le_bytes(arr(take(&mut at, 8)?))),
            _ => {
                let a = arr(take(&mut at, 4)?);
                let n = u32::from_le_bytes([a[0], a[1], a[2], a[3]]) as usize;
                let s = take(&mut at, n)?;
                if *kind == ColumnType::Binary {
                    Value::from(layer::hex(s))
                } else {
                    Value::from(
                        std::str::from_utf8(s)
                            .map_err(|_| anyhow!("property {:?} is not valid UTF-8", field.name))?,
                    )
                }
            }
        };
        out.insert(field.name.clone(), v);
    }
    Ok(())
}

fn number(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// A FlatGeobuf geometry type for a layer's geometries: their one type,
/// else `Unknown` (each feature then carries its own; so does a layer with
/// a feature without geometry).
fn geometry_type(features: &dyn Source) -> GeometryType {
    match geom::one_type(features, true) {
        Some("Point") => GeometryType::Point,
        Some("MultiPoint") => GeometryType::MultiPoint,
        Some("LineString") => GeometryType::LineString,
        Some("MultiLineString") => GeometryType::MultiLineString,
        Some("Polygon") => GeometryType::Polygon,
        Some("MultiPolygon") => GeometryType::MultiPolygon,
        Some("GeometryCollection") => GeometryType::GeometryCollection,
        _ => GeometryType::Unknown,
    }
}

/// A GeoJSON geometry as geozero's geometry source.
struct Json<'a>(&'a Value);

impl GeozeroGeometry for Json<'_> {
    fn process_geom<P: geozero::GeomProcessor>(&self, p: &mut P) -> geozero::error::Result<()> {
        if self.0.is_null() {
            // No geometry: an empty one, which reads back as none.
            return Ok(());
        }
        geom::emit(self.0, p)
    }
}

/// Writes the features of a GeoJSON FeatureCollection as a FlatGeobuf file
/// at `path` with a spatial index: with `schema`'s name, fields and CRS
/// when given (the layer read), else named after the file, with fields
/// found from the properties, in WGS 84 (GeoJSON's coordinates). The file
/// is built beside `path` and renamed onto it only when complete.
///
/// # Errors
///
/// A feature without geometry, a property its field cannot hold (naming
/// the feature and field), I/O errors.
pub fn write(path: &Path, features: &dyn Source, schema: Option<&Schema>) -> Result<()> {
    let stem = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = layer::staging_file(dir, "")
        .with_context(|| format!("creating a file in {}", dir.display()))?;
    // Written straight to the file: a large layer's bytes are never all
    // held at once.
    let mut out = std::io::BufWriter::new(tmp.as_file_mut());
    write_to(&mut out, features, schema, &stem)
        .and_then(|()| std::io::Write::flush(&mut out).map_err(Into::into))
        .map_err(|e| anyhow!("{}: {e}", path.display()))?;
    drop(out);
    tmp.persist(path)
        .map_err(|e| e.error)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// The bytes of the FlatGeobuf file [`write()`] writes, the layer named
/// `name` when `schema` names none.
///
/// # Errors
///
/// As [`write()`].
pub fn to_bytes(features: &dyn Source, schema: Option<&Schema>, name: &str) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    write_to(&mut out, features, schema, name)?;
    Ok(out)
}

/// Writes the FlatGeobuf file of [`to_bytes`] to `out`.
fn write_to(
    out: &mut impl std::io::Write,
    features: &dyn Source,
    schema: Option<&Schema>,
    name: &str,
) -> Result<()> {
    let name = match schema {
        Some(s) if !s.name.is_empty() => s.name.clone(),
        _ => name.to_owned(),
    };
    let fields = match schema {
        Some(s) => s.fields.clone(),
        None => layer::infer_fields(features),
    };
    let crs = match schema {
        Some(s) => s.crs.clone(),
        None => Some(Crs::wgs84()),
    };
    let z = (0..features.count()).any(|i| features.has_z(i));
    let (org, code) = match crs.as_ref().and_then(|c| c.authority.clone()) {
        Some((org, code)) => (Some(org), code),
        None => (None, 0),
    };
    let wkt = crs.as_ref().and_then(|c| c.wkt.clone());
    let kind = geometry_type(features);
    let mut fgb = FgbWriter::create_with_options(
        &name,
        kind,
        FgbWriterOptions {
            write_index: true,
            detect_type: false,
            promote_to_multi: false,
            has_z: z,
            crs: FgbCrs {
                org: org.as_deref(),
                code,
                wkt: wkt.as_deref(),
                ..FgbCrs::default()
            },
            ..FgbWriterOptions::default()
        },
    )
    .map_err(|e| anyhow!("{}", one_line(&e)))?;
    for f in &fields {
        let t = match f.kind {
            FieldKind::Boolean => ColumnType::Bool,
            FieldKind::Integer if f.width.is_some_and(|w| w <= 9) => ColumnType::Int,
            FieldKind::Integer => ColumnType::Long,
            FieldKind::Real => ColumnType::Double,
            FieldKind::Text => ColumnType::String,
            FieldKind::Date | FieldKind::DateTime => ColumnType::DateTime,
            FieldKind::Binary => ColumnType::Binary,
        };
        let width = match f.kind {
            FieldKind::Text => f.width.and_then(|w| i32::try_from(w).ok()).unwrap_or(-1),
            _ => -1,
        };
        fgb.add_column(&f.name, t, |_, col| {
            col.nullable = true;
            col.width = width;
        });
    }
    for i in 0..features.count() {
        let mut values = Vec::new();
        for (k, f) in fields.iter().enumerate() {
            let v = features.property(i, &f.name);
            let v = v.as_ref();
            if let Some(v) =
                column_value(v, f).map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?
            {
                values.push((k, v));
            }
        }
        let mut failed = None;
        fgb.add_feature_geom(Json(&features.geometry(i)), |w| {
            for (k, v) in &values {
                let cv = match v {
                    Cell::Bool(b) => ColumnValue::Bool(*b),
                    Cell::Int(x) => ColumnValue::Int(*x),
                    Cell::Long(x) => ColumnValue::Long(*x),
                    Cell::Double(x) => ColumnValue::Double(*x),
                    Cell::Text(s) => ColumnValue::String(s),
                    Cell::Time(s) => ColumnValue::DateTime(s),
                    Cell::Bytes(b) => ColumnValue::Binary(b),
                };
                if let Err(e) = w.property(*k, &fields[*k].name, &cv) {
                    failed = Some(e);
                }
            }
        })
        .map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?;
        if let Some(e) = failed {
            bail!("feature {i}: {}", one_line(&e));
        }
    }
    fgb.write(out).map_err(|e| anyhow!("{}", one_line(&e)))?;
    Ok(())
}

/// A property's value as its column holds it.
enum Cell {
    Bool(bool),
    Int(i32),
    Long(i64),
    Double(f64),
    Text(String),
    Time(String),
    Bytes(Vec<u8>),
}

fn column_value(v: &Value, f: &Field) -> Result<Option<Cell>> {
    let bad = |what: &str| anyhow!("field {:?}: {v} is not {what}", f.name);
    Ok(Some(match (f.kind, v) {
        (_, Value::Null) => return Ok(None),
        (FieldKind::Boolean, Value::Bool(b)) => Cell::Bool(*b),
        (FieldKind::Boolean, _) => return Err(bad("true or false")),
        (FieldKind::Integer, Value::Number(n)) => {
            let i = layer::whole(n).ok_or_else(|| bad("a whole number"))?;
            if f.width.is_some_and(|w| w <= 9) {
                Cell::Int(i32::try_from(i).map_err(|_| bad("a 32-bit whole number"))?)
            } else {
                Cell::Long(i)
            }
        }
        (FieldKind::Integer, _) => return Err(bad("a whole number")),
        (FieldKind::Real, Value::Number(n)) => {
            Cell::Double(n.as_f64().ok_or_else(|| bad("a number"))?)
        }
        (FieldKind::Real, _) => return Err(bad("a number")),
        (FieldKind::Date | FieldKind::DateTime, v) => {
            Cell::Time(layer::as_text(v).unwrap_or_default())
        }
        (FieldKind::Binary, Value::String(s)) => Cell::Bytes(
            (0..s.len() / 2)
                .map(|i| {
                    s.get(2 * i..2 * i + 2)
                        .and_then(|h| u8::from_str_radix(h, 16).ok())
                })
                .collect::<Option<Vec<u8>>>()
                .filter(|_| s.len() % 2 == 0)
                .ok_or_else(|| bad("bytes as hexadecimal text"))?,
        ),
        (_, v) => Cell::Text(layer::as_text(v).unwrap_or_default()),
    }))
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
        let path = dir.path().join("t.fgb");
        let input = fc(json!([
            {"type": "Feature", "properties": {"name": "lake", "depth": 3, "area": 12.5, "wet": true},
             "geometry": {"type": "Polygon", "coordinates": [[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 0.0]], [[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 1.0]]]}},
            {"type": "Feature", "properties": {"name": null, "depth": null, "area": 0.1, "wet": false},
             "geometry": {"type": "MultiPolygon", "coordinates": [[[[10.0, 0.0], [11.0, 1.0], [10.0, 1.5], [10.0, 0.0]]], [[[20.0, 0.0], [21.0, 1.0], [20.0, 1.5], [20.0, 0.0]]]]}},
        ]));
        write(&path, &input, None).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(sniff(&bytes));
        let layer = read(&path, u64::MAX).unwrap();
        // The spatial index orders features along a Hilbert curve.
        let mut got = layer.features.to_value()["features"]
            .as_array()
            .unwrap()
            .clone();
        got.sort_by_key(|f| f["properties"]["area"].as_f64().map(|a| (a * 10.0) as i64));
        let mut want = input["features"].as_array().unwrap().clone();
        want.sort_by_key(|f| f["properties"]["area"].as_f64().map(|a| (a * 10.0) as i64));
        assert_eq!(got, want);
        assert_eq!(layer.schema.name, "t");
        assert_eq!(layer.schema.crs.as_ref().and_then(Crs::epsg), Some(4326));
        // Every prefix of the file fails cleanly.
        for cut in (0..bytes.len()).step_by(7) {
            let _ = read_from("t.fgb", &bytes[..cut]);
        }
    }

    /// Found by fuzzing: a feature's size prefix was allocated before its
    /// bytes were read (4 GB from a file of a few hundred bytes), and the
    /// crate's verification messages ran over several lines.
    #[test]
    fn damaged_sizes_and_headers_give_one_line_errors() {
        let input = fc(json!([
            {"type": "Feature", "properties": {"n": 1}, "geometry": {"type": "Point", "coordinates": [1.0, 2.0]}},
        ]));
        let bytes = to_bytes(&input, None, "t").unwrap();
        let header = u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize;
        let first = 12 + header + PackedRTree::index_size(1, 16);
        let mut big = bytes.clone();
        big[first..first + 4].copy_from_slice(&0xffff_fff0_u32.to_le_bytes());
        let e = read_from("t.fgb", big.as_slice()).unwrap_err().to_string();
        assert!(e.starts_with("t.fgb: feature 0: the file ends"), "{e}");
        for at in 12..12 + header {
            let mut bad = bytes.clone();
            bad[at] ^= 0xa5;
            if let Err(e) = read_from("t.fgb", bad.as_slice()) {
                let e = e.to_string();
                assert!(e.starts_with("t.fgb") && !e.contains('\n'), "{e}");
            }
        }
    }

    #[test]
    fn lines_with_z_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("z.fgb");
        let input = fc(json!([
            {"type": "Feature", "properties": {"id": 1},
             "geometry": {"type": "LineString", "coordinates": [[0.0, 0.0, 5.0], [1.0, 2.0, 6.5]]}},
        ]));
        write(&path, &input, None).unwrap();
        assert_eq!(read(&path, u64::MAX).unwrap().features.to_value(), input);
        // A feature without geometry among others.
        let some = fc(json!([
            {"type": "Feature", "properties": {"id": 1}, "geometry": {"type": "Point", "coordinates": [1.0, 2.0]}},
            {"type": "Feature", "properties": {"id": 2}, "geometry": null},
        ]));
        write(&path, &some, None).unwrap();
        let mut back = read(&path, u64::MAX).unwrap().features.to_value();
        back["features"]
            .as_array_mut()
            .unwrap()
            .sort_by_key(|f| f["properties"]["id"].as_i64());
        assert_eq!(back, some);
    }
}
