//! GeoPackage feature layers in and out (OGC 12-128r18), on SQLite through
//! `rusqlite` with SQLite compiled in: a layer's rows read into a
//! [`Layer`] (attributes as properties in column order, the feature id left
//! out as GDAL leaves it out, the CRS from `gpkg_spatial_ref_sys`), and a
//! FeatureCollection written as a new GeoPackage of one layer, with the
//! input's fields and CRS and an R-tree spatial index. The file is written
//! beside its destination and renamed into place only when complete.

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use rusqlite::types::{Value as Sql, ValueRef};
use rusqlite::{params, Connection, OpenFlags};
use serde_json::{json, Map, Value};

use crate::features::{Features, Source};
use crate::geom;
use crate::layer::{self, one_line, Crs, Field, FieldKind, Layer, Schema};

/// The `application_id` of a GeoPackage: `GPKG`.
const APPLICATION_ID: i32 = 0x4750_4B47;

/// The `srs_id` a CRS known only by its WKT is written with.
const CUSTOM_SRS_ID: i32 = 100_000;

/// Whether `bytes` start like a GeoPackage: an SQLite database whose
/// header's application id is `GPKG` (or GeoPackage 1.0's `GP10`).
#[must_use]
pub fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(b"SQLite format 3\0")
        && bytes
            .get(68..72)
            .is_some_and(|id| id == b"GPKG" || id == b"GP10")
}

/// The names of a GeoPackage's feature layers, in `gpkg_contents`' order.
///
/// # Errors
///
/// A file that is not a GeoPackage.
pub fn layers(path: &Path) -> Result<Vec<String>> {
    let name = path.display().to_string();
    let conn = open(&name, path)?;
    feature_layers(&name, &conn)
}

/// Reads the feature layer `layer` of the GeoPackage at `path` (the only
/// one when `None`), no larger than `max_bytes`.
///
/// # Errors
///
/// One line naming the file (and the layer, the feature by its id, the
/// field): not a GeoPackage, no layer of that name (the layers are listed),
/// several layers and none chosen, a geometry whose `srs_id` is not its
/// column's (a mixed-CRS layer), a geometry that is not GeoPackage binary or
/// holds a coordinate that is not finite, curved geometries.
pub fn read(path: &Path, layer: Option<&str>, max_bytes: u64) -> Result<Layer> {
    let name = path.display().to_string();
    let size = std::fs::metadata(path)
        .with_context(|| format!("reading {name}"))?
        .len();
    if size > max_bytes {
        bail!("{name}: larger than {max_bytes} bytes (--max-bytes); split the input or raise the limit");
    }
    let conn = open(&name, path)?;
    read_layer(&name, &conn, layer)
}

fn open(name: &str, path: &Path) -> Result<Connection> {
    let conn = Connection::open_with_flags(
        path,
        OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
    )
    .map_err(|e| anyhow!("{name}: cannot open as a GeoPackage: {}", one_line(&e)))?;
    // The file's own views and triggers run nothing of ours.
    conn.execute_batch("PRAGMA trusted_schema = OFF;")
        .map_err(|e| anyhow!("{name}: not a GeoPackage (SQLite: {})", one_line(&e)))?;
    Ok(conn)
}

fn feature_layers(name: &str, conn: &Connection) -> Result<Vec<String>> {
    let mut st = conn
        .prepare("SELECT table_name FROM gpkg_contents WHERE data_type = 'features' ORDER BY rowid")
        .map_err(|e| {
            anyhow!(
                "{name}: not a GeoPackage (no gpkg_contents table: {})",
                one_line(&e)
            )
        })?;
    let names = st
        .query_map([], |r| r.get::<_, String>(0))
        .and_then(Iterator::collect::<rusqlite::Result<Vec<_>>>)
        .map_err(|e| anyhow!("{name}: gpkg_contents: {}", one_line(&e)))?;
    Ok(names)
}

/// A name as an SQL identifier.
fn quote(id: &str) -> String {
    format!("\"{}\"", id.replace('"', "\"\""))
}

/// A column's declared type as a field's kind and width.
fn kind_of(decl: &str) -> (FieldKind, Option<u32>) {
    let upper = decl.trim().to_ascii_uppercase();
    let (base, width) = match upper.split_once('(') {
        Some((b, rest)) => (
            b.trim().to_owned(),
            rest.trim_end_matches(')').trim().parse().ok(),
        ),
        None => (upper.clone(), None),
    };
    // Integers' widths in digits, as a .dbf counts them: what GDAL
    // declares MEDIUMINT holds 32 bits.
    let width = match base.as_str() {
        "TINYINT" => Some(3),
        "SMALLINT" => Some(5),
        "MEDIUMINT" => Some(9),
        _ => width,
    };
    let kind = match base.as_str() {
        "BOOLEAN" => FieldKind::Boolean,
        "TINYINT" | "SMALLINT" | "MEDIUMINT" | "INT" | "INTEGER" | "BIGINT" => FieldKind::Integer,
        "FLOAT" | "DOUBLE" | "REAL" | "NUMERIC" => FieldKind::Real,
        "DATE" => FieldKind::Date,
        "DATETIME" => FieldKind::DateTime,
        "BLOB" => FieldKind::Binary,
        _ => FieldKind::Text,
    };
    (kind, width)
}

/// Reads one feature layer of an open GeoPackage; errors start with `name`.
///
/// # Errors
///
/// As [`read`].
pub fn read_layer(name: &str, conn: &Connection, layer: Option<&str>) -> Result<Layer> {
    let layers = feature_layers(name, conn)?;
    let table = match (layer, layers.as_slice()) {
        (Some(l), _) if layers.iter().any(|n| n == l) => l.to_owned(),
        (Some(l), []) => bail!("{name}: no layer {l:?}: it holds no feature layer"),
        (Some(l), _) => bail!(
            "{name}: no layer {l:?}; its feature layers: {}",
            layers.join(", ")
        ),
        (None, [one]) => one.clone(),
        (None, []) => bail!("{name}: holds no feature layer"),
        (None, many) => bail!(
            "{name}: holds {} feature layers ({}): choose one with --layer NAME",
            many.len(),
            many.join(", ")
        ),
    };
    let at = format!("{name}: layer {table:?}");
    let (geom_col, srs_id): (String, i32) = conn
        .query_row(
            "SELECT column_name, srs_id FROM gpkg_geometry_columns WHERE table_name = ?1",
            [&table],
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
        .map_err(|e| {
            anyhow!(
                "{at}: no geometry column in gpkg_geometry_columns ({})",
                one_line(&e)
            )
        })?;
    let crs = conn
        .query_row(
            "SELECT organization, organization_coordsys_id, definition FROM gpkg_spatial_ref_sys WHERE srs_id = ?1",
            [srs_id],
            |r| {
                Ok((
                    r.get::<_, Option<String>>(0)?,
                    r.get::<_, Option<i64>>(1)?,
                    r.get::<_, Option<String>>(2)?,
                ))
            },
        )
        .map_err(|e| anyhow!("{at}: its srs_id {srs_id} is not in gpkg_spatial_ref_sys ({})", one_line(&e)))?;
    let crs = match crs {
        _ if srs_id == 0 || srs_id == -1 => None,
        (org, code, wkt) => {
            let wkt = wkt.filter(|w| !w.trim().eq_ignore_ascii_case("undefined"));
            let authority = match (org, code.and_then(|c| i32::try_from(c).ok())) {
                (Some(o), Some(c)) if !o.eq_ignore_ascii_case("none") => Some((o, c)),
                _ => None,
            };
            Some(Crs {
                authority,
                wkt,
                projjson: None,
            })
        }
    };
    // The columns: the integer primary key is the feature id, the geometry
    // column the geometry, the rest the fields.
    let mut columns: Vec<(String, String, bool)> = Vec::new();
    {
        let mut st = conn
            .prepare(&format!("PRAGMA table_info({})", quote(&table)))
            .map_err(|e| anyhow!("{at}: {}", one_line(&e)))?;
        let rows = st
            .query_map([], |r| {
                Ok((
                    r.get::<_, String>(1)?,
                    r.get::<_, Option<String>>(2)?.unwrap_or_default(),
                    r.get::<_, i64>(5)? > 0,
                ))
            })
            .map_err(|e| anyhow!("{at}: {}", one_line(&e)))?;
        for row in rows {
            columns.push(row.map_err(|e| anyhow!("{at}: {}", one_line(&e)))?);
        }
    }
    if columns.is_empty() {
        bail!("{at}: no such table");
    }
    let fid = columns
        .iter()
        .find(|(_, decl, pk)| *pk && decl.eq_ignore_ascii_case("integer"))
        .map(|c| c.0.clone());
    if !columns.iter().any(|c| c.0 == geom_col) {
        bail!("{at}: its geometry column {geom_col:?} is not in the table");
    }
    let fields: Vec<Field> = columns
        .iter()
        .filter(|(n, _, _)| Some(n) != fid.as_ref() && *n != geom_col)
        .map(|(n, decl, _)| {
            let (kind, width) = kind_of(decl);
            Field {
                name: n.clone(),
                kind,
                width,
                decimals: None,
            }
        })
        .collect();
    let id_sql = fid.as_deref().map_or_else(|| "rowid".to_owned(), quote);
    let mut select = format!("SELECT {id_sql}, {}", quote(&geom_col));
    for f in &fields {
        select += ", ";
        select += &quote(&f.name);
    }
    select += &format!(" FROM {} ORDER BY {id_sql}", quote(&table));
    let mut st = conn
        .prepare(&select)
        .map_err(|e| anyhow!("{at}: {}", one_line(&e)))?;
    let mut rows = st
        .query([])
        .map_err(|e| anyhow!("{at}: {}", one_line(&e)))?;
    let mut features = Features::new(fields.iter().map(|f| f.name.clone()).collect());
    while let Some(row) = rows.next().map_err(|e| anyhow!("{at}: {}", one_line(&e)))? {
        let id = match row.get_ref(0) {
            Ok(ValueRef::Integer(i)) => i,
            _ => features.len() as i64,
        };
        let here = format!("{at}, feature {id}");
        let geometry = match row
            .get_ref(1)
            .map_err(|e| anyhow!("{here}: {}", one_line(&e)))?
        {
            ValueRef::Null => Value::Null,
            ValueRef::Blob(b) => {
                geometry(b, srs_id).map_err(|e| anyhow!("{here}: {}", one_line(&e)))?
            }
            _ => bail!("{here}: its geometry is not a GeoPackage binary blob"),
        };
        let mut properties = Map::new();
        for (k, f) in fields.iter().enumerate() {
            let v = row
                .get_ref(k + 2)
                .map_err(|e| anyhow!("{here}, field {:?}: {}", f.name, one_line(&e)))?;
            // SQLite holds any value in any column: each is read as its
            // field's kind holds it, where it can be.
            let texty = matches!(
                f.kind,
                FieldKind::Text | FieldKind::Date | FieldKind::DateTime
            );
            let v = match v {
                ValueRef::Null => Value::Null,
                ValueRef::Integer(i) if f.kind == FieldKind::Boolean => json!(i != 0),
                ValueRef::Integer(i) if texty => Value::from(i.to_string()),
                ValueRef::Real(x) if texty && x.is_finite() => Value::from(x.to_string()),
                #[allow(clippy::cast_precision_loss)] // a REAL column's value
                ValueRef::Integer(i) if f.kind == FieldKind::Real => json!(i as f64),
                ValueRef::Integer(i) => json!(i),
                ValueRef::Real(x) => {
                    if x.is_finite() {
                        json!(x)
                    } else {
                        Value::Null
                    }
                }
                ValueRef::Text(t) => Value::from(String::from_utf8_lossy(t).into_owned()),
                ValueRef::Blob(b) => Value::from(layer::hex(b)),
            };
            properties.insert(f.name.clone(), v);
        }
        features.push(properties, geometry);
    }
    Ok(Layer {
        features,
        schema: Schema {
            name: table,
            fields,
            crs,
            #[cfg(feature = "shapefile")]
            dbf: None,
        },
    })
}

/// A GeoPackage binary geometry as GeoJSON: the header checked (magic,
/// version, the `srs_id` its column declares), an empty geometry as `null`,
/// the WKB after the envelope read by geozero (z kept where it has z).
///
/// # Errors
///
/// A blob that is not GeoPackage binary, of another `srs_id`, of curved
/// geometries or with a coordinate that is not finite.
pub fn geometry(blob: &[u8], srs_id: i32) -> Result<Value> {
    if blob.len() < 8 || &blob[..2] != b"GP" {
        bail!("its geometry is not GeoPackage binary (no GP header)");
    }
    if blob[2] != 0 {
        bail!(
            "its geometry is of GeoPackage binary version {}, not 0",
            blob[2]
        );
    }
    let flags = blob[3];
    if flags & 0b0010_0000 != 0 {
        bail!("its geometry is of an extended GeoPackage binary type");
    }
    let id = [blob[4], blob[5], blob[6], blob[7]];
    let id = if flags & 1 == 1 {
        i32::from_le_bytes(id)
    } else {
        i32::from_be_bytes(id)
    };
    if id != srs_id {
        bail!("its geometry is in srs_id {id} and its layer in {srs_id}: a layer of mixed coordinate systems");
    }
    let envelope = match (flags >> 1) & 0b111 {
        0 => 0,
        1 => 32,
        2 | 3 => 48,
        4 => 64,
        e => bail!(
            "its geometry header names envelope kind {}, which does not exist",
            one_line(&e)
        ),
    };
    let wkb = blob
        .get(8 + envelope..)
        .ok_or_else(|| anyhow!("its geometry ends inside its envelope"))?;
    if flags & 0b0001_0000 != 0 {
        return Ok(Value::Null);
    }
    let mut out = geom::ToJson::new(true);
    geozero::wkb::process_wkb_geom(&mut &wkb[..], &mut out)
        .map_err(|e| anyhow!("its geometry: {}", one_line(&e)))?;
    let mut g = out.finish();
    geom::fill_z(&mut g);
    Ok(g)
}

/// The GeoPackage type name of a layer's geometries: their one type, else
/// `GEOMETRY`.
fn type_name(features: &dyn Source) -> &'static str {
    match geom::one_type(features, false) {
        Some("Point") => "POINT",
        Some("MultiPoint") => "MULTIPOINT",
        Some("LineString") => "LINESTRING",
        Some("MultiLineString") => "MULTILINESTRING",
        Some("Polygon") => "POLYGON",
        Some("MultiPolygon") => "MULTIPOLYGON",
        Some("GeometryCollection") => "GEOMETRYCOLLECTION",
        _ => "GEOMETRY",
    }
}

/// The SQL type a field is written as.
fn sql_type(f: &Field) -> String {
    match f.kind {
        FieldKind::Boolean => "BOOLEAN".into(),
        // 32 bits, as GDAL declares them; else 64.
        FieldKind::Integer => match f.width {
            Some(w) if w <= 9 => "MEDIUMINT".into(),
            _ => "INTEGER".into(),
        },
        FieldKind::Real => "REAL".into(),
        FieldKind::Date => "DATE".into(),
        FieldKind::DateTime => "DATETIME".into(),
        FieldKind::Binary => "BLOB".into(),
        FieldKind::Text => match f.width {
            Some(w) if w > 0 => format!("TEXT({w})"),
            _ => "TEXT".into(),
        },
    }
}

/// A property as the SQL value of its field.
fn sql_value(v: &Value, f: &Field) -> Result<Sql> {
    let bad = |what: &str| anyhow!("field {:?}: {v} is not {what}", f.name);
    Ok(match (f.kind, v) {
        (_, Value::Null) => Sql::Null,
        (FieldKind::Boolean, Value::Bool(b)) => Sql::Integer(i64::from(*b)),
        (FieldKind::Boolean, _) => return Err(bad("true or false")),
        (FieldKind::Integer, Value::Number(n)) => {
            Sql::Integer(layer::whole(n).ok_or_else(|| bad("a whole number"))?)
        }
        (FieldKind::Integer, Value::Bool(b)) => Sql::Integer(i64::from(*b)),
        (FieldKind::Integer, _) => return Err(bad("a whole number")),
        (FieldKind::Real, Value::Number(n)) => {
            Sql::Real(n.as_f64().ok_or_else(|| bad("a number"))?)
        }
        (FieldKind::Real, _) => return Err(bad("a number")),
        (FieldKind::Binary, Value::String(s)) => {
            Sql::Blob(layer::unhex(s).ok_or_else(|| bad("bytes as hexadecimal text"))?)
        }
        (_, v) => Sql::Text(layer::as_text(v).unwrap_or_default()),
    })
}

/// The `srs_id` and `gpkg_spatial_ref_sys` row a CRS is written with: EPSG
/// codes as themselves, a CRS known only by its WKT as [`CUSTOM_SRS_ID`],
/// none as the undefined Cartesian system (-1).
fn srs_row(crs: Option<&Crs>) -> (i32, Option<(String, String, i32, String)>) {
    let Some(crs) = crs else {
        return (-1, None);
    };
    let wkt = crs.wkt.clone().unwrap_or_else(|| "undefined".to_owned());
    let srs_name = |w: &str| {
        w.split('"')
            .nth(1)
            .filter(|n| !n.is_empty())
            .unwrap_or("unnamed")
            .to_owned()
    };
    match (&crs.authority, crs.epsg()) {
        (_, Some(4326)) => (4326, None),
        (_, Some(code)) if code > 0 => (code, Some((srs_name(&wkt), "EPSG".into(), code, wkt))),
        (Some((org, code)), _) if crs.wkt.is_some() => (
            CUSTOM_SRS_ID,
            Some((srs_name(&wkt), org.clone(), *code, wkt)),
        ),
        (_, _) if crs.wkt.is_some() => (
            CUSTOM_SRS_ID,
            Some((srs_name(&wkt), "NONE".into(), CUSTOM_SRS_ID, wkt)),
        ),
        _ => (-1, None),
    }
}

/// Writes the features of a GeoJSON FeatureCollection as a GeoPackage of
/// one layer at `path`: with `schema`'s name, fields and CRS when given
/// (the layer read), else named after the file, with fields found from the
/// properties, in WGS 84 (GeoJSON's coordinates). The file is built beside
/// `path` and renamed onto it only when complete.
///
/// # Errors
///
/// A property its field cannot hold (naming the feature and field), a
/// geometry that is not GeoJSON, I/O and SQLite errors.
pub fn write(path: &Path, features: &dyn Source, schema: Option<&Schema>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let tmp = layer::staging_file(dir, ".gpkg")
        .with_context(|| format!("creating a file in {}", dir.display()))?;
    let name = match schema {
        Some(s) if !s.name.is_empty() => s.name.clone(),
        _ => path
            .file_stem()
            .map_or_else(|| "layer".to_owned(), |s| s.to_string_lossy().into_owned()),
    };
    let fields = match schema {
        Some(s) => s.fields.clone(),
        None => layer::infer_fields(features),
    };
    let crs = match schema {
        Some(s) => s.crs.clone(),
        None => Some(Crs::wgs84()),
    };
    {
        let mut conn =
            Connection::open(tmp.path()).with_context(|| format!("writing {}", path.display()))?;
        fill(&mut conn, &name, &fields, crs.as_ref(), features)
            .map_err(|e| anyhow!("{}: {e}", path.display()))?;
        conn.close()
            .map_err(|(_, e)| anyhow!("writing {}: {}", path.display(), one_line(&e)))?;
    }
    tmp.persist(path)
        .map_err(|e| e.error)
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

fn fill(
    conn: &mut Connection,
    name: &str,
    fields: &[Field],
    crs: Option<&Crs>,
    features: &dyn Source,
) -> Result<()> {
    let sql = |e: rusqlite::Error| anyhow!("SQLite: {}", one_line(&e));
    conn.execute_batch(&format!(
        "PRAGMA application_id = {APPLICATION_ID};
         PRAGMA user_version = 10200;
         PRAGMA journal_mode = OFF;
         PRAGMA synchronous = OFF;
         CREATE TABLE gpkg_spatial_ref_sys (srs_name TEXT NOT NULL, srs_id INTEGER NOT NULL PRIMARY KEY, organization TEXT NOT NULL, organization_coordsys_id INTEGER NOT NULL, definition TEXT NOT NULL, description TEXT);
         CREATE TABLE gpkg_contents (table_name TEXT NOT NULL PRIMARY KEY, data_type TEXT NOT NULL, identifier TEXT UNIQUE, description TEXT DEFAULT '', last_change DATETIME NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ','now')), min_x DOUBLE, min_y DOUBLE, max_x DOUBLE, max_y DOUBLE, srs_id INTEGER, CONSTRAINT fk_gc_r_srs_id FOREIGN KEY (srs_id) REFERENCES gpkg_spatial_ref_sys(srs_id));
         CREATE TABLE gpkg_geometry_columns (table_name TEXT NOT NULL, column_name TEXT NOT NULL, geometry_type_name TEXT NOT NULL, srs_id INTEGER NOT NULL, z TINYINT NOT NULL, m TINYINT NOT NULL, CONSTRAINT pk_geom_cols PRIMARY KEY (table_name, column_name), CONSTRAINT uk_gc_table_name UNIQUE (table_name), CONSTRAINT fk_gc_tn FOREIGN KEY (table_name) REFERENCES gpkg_contents(table_name), CONSTRAINT fk_gc_srs FOREIGN KEY (srs_id) REFERENCES gpkg_spatial_ref_sys (srs_id));
         INSERT INTO gpkg_spatial_ref_sys VALUES ('Undefined cartesian SRS', -1, 'NONE', -1, 'undefined', 'undefined cartesian coordinate reference system');
         INSERT INTO gpkg_spatial_ref_sys VALUES ('Undefined geographic SRS', 0, 'NONE', 0, 'undefined', 'undefined geographic coordinate reference system');"
    ))
    .map_err(sql)?;
    conn.execute(
        "INSERT INTO gpkg_spatial_ref_sys VALUES ('WGS 84 geodetic', 4326, 'EPSG', 4326, ?1, 'longitude/latitude coordinates in decimal degrees on the WGS 84 spheroid')",
        [layer::WGS84_WKT],
    )
    .map_err(sql)?;
    let (srs_id, row) = srs_row(crs);
    if let Some((srs_name, org, code, wkt)) = row {
        conn.execute(
            "INSERT INTO gpkg_spatial_ref_sys VALUES (?1, ?2, ?3, ?4, ?5, NULL)",
            params![srs_name, srs_id, org, code, wkt],
        )
        .map_err(sql)?;
    }
    // The feature id and geometry columns, named apart from every field.
    let taken = |n: &str| fields.iter().any(|f| f.name.eq_ignore_ascii_case(n));
    let fid = ["fid", "ogc_fid", "bzspline_fid"]
        .into_iter()
        .find(|n| !taken(n))
        .unwrap_or("bzspline_fid");
    let geom_col = ["geom", "geometry", "bzspline_geom"]
        .into_iter()
        .find(|n| !taken(n))
        .unwrap_or("bzspline_geom");
    // z: 1 when every geometry has it, 2 (optional) when some do.
    let with_z = (0..features.count())
        .filter(|&i| features.geometry_type(i).is_some())
        .map(|i| features.has_z(i));
    let (all, any) = with_z.fold((true, false), |(a, o), z| (a && z, o || z));
    let z = match (any, all) {
        (false, _) => 0,
        (true, true) => 1,
        (true, false) => 2,
    };
    let mut create = format!(
        "CREATE TABLE {} ({} INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, {} {}",
        quote(name),
        quote(fid),
        quote(geom_col),
        type_name(features)
    );
    for f in fields {
        create += &format!(", {} {}", quote(&f.name), sql_type(f));
    }
    create += ")";
    let tx = conn.transaction().map_err(sql)?;
    tx.execute(&create, []).map_err(sql)?;
    let mut insert = format!("INSERT INTO {} ({}", quote(name), quote(geom_col));
    for f in fields {
        insert += ", ";
        insert += &quote(&f.name);
    }
    insert += ") VALUES (?1";
    for k in 0..fields.len() {
        insert += &format!(", ?{}", k + 2);
    }
    insert += ")";
    let mut extent: Option<[f64; 4]> = None;
    // Each feature's id and envelope, for the spatial index.
    let mut boxes: Vec<(i64, [f64; 4])> = Vec::with_capacity(features.count());
    {
        let mut st = tx.prepare(&insert).map_err(sql)?;
        for i in 0..features.count() {
            let g = &*features.geometry(i);
            let blob = if g.is_null() {
                Sql::Null
            } else {
                let env = geom::envelope(g);
                if let Some([x0, x1, y0, y1]) = env {
                    extent = Some(match extent {
                        None => [x0, x1, y0, y1],
                        Some([a, b, c, d]) => [a.min(x0), b.max(x1), c.min(y0), d.max(y1)],
                    });
                }
                let bytes = geom::to_wkb(
                    g,
                    geozero::wkb::WkbDialect::Geopackage,
                    Some(srs_id),
                    env.map_or_else(Vec::new, |e| e.to_vec()),
                )
                .map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?;
                Sql::Blob(bytes)
            };
            let mut values = Vec::with_capacity(fields.len() + 1);
            values.push(blob);
            for field in fields {
                let v = features.property(i, &field.name);
                let v = v.as_ref();
                values.push(
                    sql_value(v, field).map_err(|e| anyhow!("feature {i}: {}", one_line(&e)))?,
                );
            }
            st.execute(rusqlite::params_from_iter(values))
                .map_err(|e| anyhow!("feature {i}: SQLite: {}", one_line(&e)))?;
            if let Some(env) = geom::envelope(g) {
                boxes.push((tx.last_insert_rowid(), env));
            }
        }
    }
    spatial_index(&tx, name, fid, geom_col, &boxes).map_err(sql)?;
    let [x0, x1, y0, y1] = extent.map_or([None; 4], |e| e.map(Some));
    tx.execute(
        "INSERT INTO gpkg_contents (table_name, data_type, identifier, min_x, min_y, max_x, max_y, srs_id) VALUES (?1, 'features', ?1, ?2, ?3, ?4, ?5, ?6)",
        params![name, x0, y0, x1, y1, srs_id],
    )
    .map_err(sql)?;
    tx.execute(
        "INSERT INTO gpkg_geometry_columns VALUES (?1, ?2, ?3, ?4, ?5, 0)",
        params![name, geom_col, type_name(features), srs_id, z],
    )
    .map_err(sql)?;
    tx.commit().map_err(sql)?;
    Ok(())
}

/// The GeoPackage R-tree spatial index extension of a layer (as GDAL
/// writes it: the `rtree_<table>_<column>` table of every feature's
/// envelope, its row in `gpkg_extensions`, and the specification's triggers
/// that keep it in step when another program edits the layer; they call
/// `ST_MinX` and the like, which GDAL and QGIS provide).
fn spatial_index(
    tx: &rusqlite::Transaction,
    table: &str,
    fid: &str,
    geom: &str,
    boxes: &[(i64, [f64; 4])],
) -> rusqlite::Result<()> {
    let rtree = format!("rtree_{table}_{geom}");
    let (t, i, c, r) = (quote(table), quote(fid), quote(geom), quote(&rtree));
    tx.execute_batch(&format!(
        "CREATE VIRTUAL TABLE {r} USING rtree(id, minx, maxx, miny, maxy);
         CREATE TABLE IF NOT EXISTS gpkg_extensions (table_name TEXT, column_name TEXT, extension_name TEXT NOT NULL, definition TEXT NOT NULL, scope TEXT NOT NULL, CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name));"
    ))?;
    {
        let mut st = tx.prepare(&format!("INSERT INTO {r} VALUES (?1, ?2, ?3, ?4, ?5)"))?;
        for (id, [x0, x1, y0, y1]) in boxes {
            st.execute(params![id, x0, x1, y0, y1])?;
        }
    }
    tx.execute(
        "INSERT INTO gpkg_extensions VALUES (?1, ?2, 'gpkg_rtree_index', 'http://www.geopackage.org/spec120/#extension_rtree', 'write-only')",
        params![table, geom],
    )?;
    let trigger = |suffix: &str| quote(&format!("{rtree}_{suffix}"));
    let envelope =
        format!("NEW.{i}, ST_MinX(NEW.{c}), ST_MaxX(NEW.{c}), ST_MinY(NEW.{c}), ST_MaxY(NEW.{c})");
    tx.execute_batch(&format!(
        "CREATE TRIGGER {insert} AFTER INSERT ON {t} WHEN (NEW.{c} NOT NULL AND NOT ST_IsEmpty(NEW.{c}))
         BEGIN INSERT OR REPLACE INTO {r} VALUES ({envelope}); END;
         CREATE TRIGGER {update1} AFTER UPDATE OF {c} ON {t} WHEN OLD.{i} = NEW.{i} AND (NEW.{c} NOTNULL AND NOT ST_IsEmpty(NEW.{c}))
         BEGIN INSERT OR REPLACE INTO {r} VALUES ({envelope}); END;
         CREATE TRIGGER {update2} AFTER UPDATE OF {c} ON {t} WHEN OLD.{i} = NEW.{i} AND (NEW.{c} ISNULL OR ST_IsEmpty(NEW.{c}))
         BEGIN DELETE FROM {r} WHERE id = OLD.{i}; END;
         CREATE TRIGGER {update3} AFTER UPDATE ON {t} WHEN OLD.{i} != NEW.{i} AND (NEW.{c} NOTNULL AND NOT ST_IsEmpty(NEW.{c}))
         BEGIN DELETE FROM {r} WHERE id = OLD.{i}; INSERT OR REPLACE INTO {r} VALUES ({envelope}); END;
         CREATE TRIGGER {update4} AFTER UPDATE ON {t} WHEN OLD.{i} != NEW.{i} AND (NEW.{c} ISNULL OR ST_IsEmpty(NEW.{c}))
         BEGIN DELETE FROM {r} WHERE id IN (OLD.{i}, NEW.{i}); END;
         CREATE TRIGGER {delete} AFTER DELETE ON {t} WHEN OLD.{c} NOT NULL
         BEGIN DELETE FROM {r} WHERE id = OLD.{i}; END;",
        insert = trigger("insert"),
        update1 = trigger("update1"),
        update2 = trigger("update2"),
        update3 = trigger("update3"),
        update4 = trigger("update4"),
        delete = trigger("delete"),
    ))
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
        let path = dir.path().join("t.gpkg");
        let input = fc(json!([
            {"type": "Feature", "properties": {"name": "lake", "depth": 3, "area": 12.5, "wet": true},
             "geometry": {"type": "Polygon", "coordinates": [[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 0.0]]]}},
            {"type": "Feature", "properties": {"name": null, "depth": null, "area": 0.1, "wet": false},
             "geometry": {"type": "MultiPolygon", "coordinates": [[[[10.0, 0.0], [11.0, 1.0], [10.0, 1.5], [10.0, 0.0]]]]}},
            {"type": "Feature", "properties": {"name": "none", "depth": 1, "area": 0.0, "wet": null},
             "geometry": null},
        ]));
        write(&path, &input, None).unwrap();
        assert!(sniff(&std::fs::read(&path).unwrap()));
        let layer = read(&path, None, u64::MAX).unwrap();
        assert_eq!(layer.features.to_value(), input);
        assert_eq!(layer.schema.name, "t");
        assert_eq!(layer.schema.crs.as_ref().and_then(Crs::epsg), Some(4326));
        let kinds: Vec<FieldKind> = layer.schema.fields.iter().map(|f| f.kind).collect();
        use FieldKind::*;
        assert_eq!(kinds, [Text, Integer, Real, Boolean]);
        // Written again from what was read: the same layer.
        let again = dir.path().join("u.gpkg");
        write(&again, &layer.features, Some(&layer.schema)).unwrap();
        let back = read(&again, Some("t"), u64::MAX).unwrap();
        assert_eq!(back.features.to_value(), input);
        let e = read(&again, Some("lakes"), u64::MAX)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("no layer \"lakes\"; its feature layers: t"),
            "{e}"
        );
        let e = read(&again, None, 100).unwrap_err().to_string();
        assert!(e.contains("larger than 100 bytes"), "{e}");
    }

    #[test]
    fn properties_that_do_not_fit_are_named_and_nothing_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gpkg");
        let schema = Schema::new(
            "t",
            vec![Field {
                name: "n".into(),
                kind: FieldKind::Integer,
                width: None,
                decimals: None,
            }],
            None,
        );
        let input = fc(json!([
            {"type": "Feature", "properties": {"n": 1}, "geometry": {"type": "Point", "coordinates": [0.0, 0.0]}},
            {"type": "Feature", "properties": {"n": "two"}, "geometry": {"type": "Point", "coordinates": [1.0, 0.0]}},
        ]));
        let e = write(&path, &input, Some(&schema)).unwrap_err().to_string();
        assert!(e.contains("feature 1: field \"n\""), "{e}");
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    /// Found by fuzzing: SQLite keeps any value in any column, and an
    /// integer in a TEXT column was read as a number, then written as text.
    #[test]
    fn values_are_read_as_their_fields_hold_them() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gpkg");
        let input = fc(json!([
            {"type": "Feature", "properties": {"name": "a", "x": 1.5}, "geometry": {"type": "Point", "coordinates": [0.0, 0.0]}},
        ]));
        write(&path, &input, None).unwrap();
        let conn = Connection::open(&path).unwrap();
        // The spatial index's triggers call ST_IsEmpty and the like, which
        // GDAL and QGIS provide and plain SQLite does not: without them no
        // UPDATE of the layer can be prepared, as for GDAL's own files.
        let e = conn
            .execute("UPDATE t SET name = 7, x = 2", [])
            .unwrap_err();
        assert!(e.to_string().contains("ST_IsEmpty"), "{e}");
        let triggers: Vec<String> = conn
            .prepare("SELECT name FROM sqlite_master WHERE type = 'trigger'")
            .unwrap()
            .query_map([], |r| r.get(0))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(triggers.len(), 6);
        for t in triggers {
            conn.execute(&format!("DROP TRIGGER {}", quote(&t)), [])
                .unwrap();
        }
        conn.execute("UPDATE t SET name = 7, x = 2", []).unwrap();
        drop(conn);
        let layer = read(&path, None, u64::MAX).unwrap();
        assert_eq!(
            layer.features.to_value()["features"][0]["properties"],
            json!({"name": "7", "x": 2.0})
        );
    }

    #[test]
    fn geometry_headers_are_checked() {
        assert!(geometry(b"XX\0\x01\0\0\0\0", 0).is_err());
        let e = geometry(b"GP\0\x01\x10\x0e\0\0\x01\x01\0\0\0", 4326)
            .unwrap_err()
            .to_string();
        assert!(e.contains("mixed coordinate systems"), "{e}");
        // An empty point: no envelope, the empty flag.
        assert_eq!(
            geometry(b"GP\0\x11\xe6\x10\0\0", 4326).unwrap(),
            Value::Null
        );
    }
}
