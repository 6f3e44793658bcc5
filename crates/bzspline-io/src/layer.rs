//! A layer of features as the GIS file formats hold one: its features as a
//! GeoJSON FeatureCollection (what the smoothing and the point readers
//! take) and its schema, the fields (names, types, widths) and the
//! coordinate reference system, in terms every format's writer maps to its
//! own, so that a layer read from one format is written to another with its
//! fields and CRS.

use serde_json::Value;

use crate::features::{Features, Source};

/// A coordinate reference system as a file states it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Crs {
    /// The organisation and its code (`EPSG`, 4326), when the file gives one.
    pub authority: Option<(String, i32)>,
    /// The definition as WKT (a `.prj`, a GeoPackage's `definition`), when
    /// the file gives one.
    pub wkt: Option<String>,
    /// The definition as PROJJSON (a GeoParquet file's), when the file gives
    /// one.
    pub projjson: Option<String>,
}

/// OGC WKT 1 of EPSG:4326 (WGS 84 longitude and latitude), as GeoPackage's
/// specification writes it.
pub const WGS84_WKT: &str = "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AXIS[\"Latitude\",NORTH],AXIS[\"Longitude\",EAST],AUTHORITY[\"EPSG\",\"4326\"]]";

/// The `.prj` of WGS 84 longitude and latitude as ESRI writes it: what a
/// Shapefile written from GeoJSON carries.
pub const ESRI_WGS84_PRJ: &str = "GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",6378137.0,298.257223563]],PRIMEM[\"Greenwich\",0.0],UNIT[\"Degree\",0.0174532925199433]]";

impl Crs {
    /// WGS 84 longitude and latitude: the coordinates of GeoJSON (RFC 7946).
    #[must_use]
    pub fn wgs84() -> Crs {
        Crs {
            authority: Some(("EPSG".to_owned(), 4326)),
            wkt: Some(WGS84_WKT.to_owned()),
            projjson: None,
        }
    }

    /// A CRS from its WKT (a `.prj`), with the authority the WKT names for
    /// the whole CRS (`AUTHORITY["EPSG","4326"]`, WKT 2's `ID["EPSG",4326]`)
    /// or, for ESRI's WKT of WGS 84 longitude and latitude, which names
    /// none, EPSG:4326.
    #[must_use]
    pub fn from_wkt(wkt: &str) -> Crs {
        let wkt = wkt.trim();
        Crs {
            authority: top_authority(wkt).or_else(|| {
                let squeezed: String = wkt
                    .chars()
                    .filter(|c| !c.is_whitespace())
                    .collect::<String>()
                    .to_ascii_uppercase();
                (squeezed.starts_with("GEOGCS[\"GCS_WGS_1984\"")
                    && squeezed.contains("DATUM[\"D_WGS_1984\"")
                    && squeezed.contains("PRIMEM[\"GREENWICH\",0")
                    && squeezed.contains("UNIT[\"DEGREE\""))
                .then(|| ("EPSG".to_owned(), 4326))
            }),
            wkt: Some(wkt.to_owned()),
            projjson: None,
        }
    }

    /// A CRS from its PROJJSON (a GeoParquet file's `crs`), with the
    /// authority its `id` names; OGC's CRS84 reads as EPSG:4326.
    #[must_use]
    pub fn from_projjson(p: &serde_json::Value) -> Crs {
        let id = &p["id"];
        let authority = match (id["authority"].as_str(), &id["code"]) {
            (Some(org), Value::Number(n)) => n
                .as_i64()
                .and_then(|c| i32::try_from(c).ok())
                .map(|c| (org.to_owned(), c)),
            (Some(org), Value::String(c))
                if org.eq_ignore_ascii_case("ogc") && c.eq_ignore_ascii_case("crs84") =>
            {
                Some(("EPSG".to_owned(), 4326))
            }
            (Some(org), Value::String(c)) => c.parse().ok().map(|c| (org.to_owned(), c)),
            _ => None,
        };
        Crs {
            authority,
            wkt: None,
            projjson: Some(p.to_string()),
        }
    }

    /// A CRS as people write one: an authority and code (`EPSG:4326`,
    /// `OGC:CRS84`, `urn:ogc:def:crs:EPSG::3857`, the URL form
    /// `http://www.opengis.net/def/crs/EPSG/0/4326`) or WKT (1 or 2). OGC's
    /// CRS84 is longitude and latitude on WGS 84, so it reads as EPSG:4326.
    ///
    /// # Errors
    ///
    /// Text that is none of these, as the words of a message.
    pub fn parse(text: &str) -> Result<Crs, String> {
        let t = text.trim();
        let bad = || {
            format!(
                "{t:?} is not a coordinate system: give AUTHORITY:CODE (EPSG:4326, OGC:CRS84) or WKT"
            )
        };
        if t.contains('[') {
            return Ok(Crs::from_wkt(t));
        }
        // The authority and the code are the last two fields of every form.
        let fields: Vec<&str> = t
            .split([':', '/'])
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .collect();
        let (org, code) = match fields.as_slice() {
            [.., org, "0", code] | [.., org, code] => (*org, *code),
            _ => return Err(bad()),
        };
        let is_version = org.chars().all(|c| c.is_ascii_digit() || c == '.');
        let (org, code) = if is_version && fields.len() >= 3 {
            // `urn:ogc:def:crs:EPSG:9.9:4326` puts a version between.
            (fields[fields.len() - 3], code)
        } else {
            (org, code)
        };
        if org.eq_ignore_ascii_case("ogc") && code.eq_ignore_ascii_case("crs84") {
            return Ok(Crs::wgs84());
        }
        if !org.chars().all(|c| c.is_ascii_alphanumeric()) {
            return Err(bad());
        }
        let code: i32 = code.parse().map_err(|_| bad())?;
        if org.eq_ignore_ascii_case("epsg") && code == 4326 {
            return Ok(Crs::wgs84());
        }
        Ok(Crs {
            authority: Some((org.to_ascii_uppercase(), code)),
            wkt: None,
            projjson: None,
        })
    }

    /// The text of a `.prj`: ESRI's WKT for WGS 84 longitude and latitude
    /// (as GDAL writes it), the file's WKT 1 as it is, else whatever WKT
    /// the file gave (WKT 2, which GDAL's Shapefile driver reads as no CRS),
    /// else the WKT 1 of its PROJJSON ([`crate::wkt1`]); `None` when there
    /// is none of these.
    #[must_use]
    pub fn prj(&self) -> Option<String> {
        if self.epsg() == Some(4326) {
            return Some(ESRI_WGS84_PRJ.to_owned());
        }
        self.wkt.clone().or_else(|| {
            let p: Value = serde_json::from_str(self.projjson.as_deref()?).ok()?;
            crate::wkt1::from_projjson(&p)
        })
    }

    /// The EPSG code, when the authority is EPSG.
    #[must_use]
    pub fn epsg(&self) -> Option<i32> {
        match &self.authority {
            Some((org, code)) if org.eq_ignore_ascii_case("epsg") => Some(*code),
            _ => None,
        }
    }
}

/// The authority of a WKT's outermost object: its last `AUTHORITY[...]`
/// or `ID[...]` at the first level of brackets.
fn top_authority(wkt: &str) -> Option<(String, i32)> {
    let bytes = wkt.as_bytes();
    let (mut depth, mut in_text, mut found) = (0usize, false, None);
    for (i, &b) in bytes.iter().enumerate() {
        match b {
            b'"' => in_text = !in_text,
            b'[' | b'(' if !in_text => {
                depth += 1;
                if depth == 2 {
                    let head = wkt[..i].trim_end();
                    let word_at = head
                        .rfind(|c: char| !c.is_ascii_alphanumeric())
                        .map_or(0, |k| k + 1);
                    let word = head[word_at..].to_ascii_uppercase();
                    if word == "AUTHORITY" || word == "ID" {
                        let body = &wkt[i + 1..];
                        let end = body.find([']', ')'])?;
                        let mut parts = body[..end].split(',').map(|p| p.trim().trim_matches('"'));
                        let org = parts.next()?.to_owned();
                        let code = parts.next()?.parse().ok()?;
                        found = Some((org, code));
                    }
                }
            }
            b']' | b')' if !in_text => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    found
}

/// What values a field holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldKind {
    /// `true` or `false`.
    Boolean,
    /// Whole numbers.
    Integer,
    /// Numbers.
    Real,
    /// Text.
    Text,
    /// `YYYY-MM-DD`.
    Date,
    /// ISO 8601 date and time.
    DateTime,
    /// Bytes (kept as hexadecimal text in the features' properties).
    Binary,
}

/// One field of a layer's table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    /// The name.
    pub name: String,
    /// The values it holds.
    pub kind: FieldKind,
    /// The characters (text) or digits (numbers) it holds, when the format
    /// says.
    pub width: Option<u32>,
    /// The digits after the decimal point, when the format says.
    pub decimals: Option<u32>,
}

/// What a layer holds besides its features: its name, fields and CRS.
#[derive(Clone, Debug, Default)]
pub struct Schema {
    /// The layer's name (a GeoPackage's table, a Shapefile's file name).
    pub name: String,
    /// The fields, in order.
    pub fields: Vec<Field>,
    /// The coordinate reference system, when the file states one.
    pub crs: Option<Crs>,
    /// A `.dbf`'s exact layout, to write a Shapefile read back the same way.
    #[cfg(feature = "shapefile")]
    pub(crate) dbf: Option<crate::shp::Dbf>,
}

impl Schema {
    /// A schema of a layer's name, fields and CRS.
    #[must_use]
    pub fn new(name: impl Into<String>, fields: Vec<Field>, crs: Option<Crs>) -> Schema {
        Schema {
            name: name.into(),
            fields,
            crs,
            #[cfg(feature = "shapefile")]
            dbf: None,
        }
    }

    /// The fields' names, in order.
    pub fn field_names(&self) -> impl Iterator<Item = &str> {
        self.fields.iter().map(|f| f.name.as_str())
    }
}

/// A new file in `dir` for a layer being written, readable by others as a
/// file the user made (`rw-r--r--`, not a temporary file's `rw-------`),
/// renamed onto its destination once complete.
///
/// # Errors
///
/// When the file cannot be created.
#[cfg(any(
    feature = "shapefile",
    feature = "geopackage",
    feature = "flatgeobuf",
    feature = "geoparquet"
))]
pub(crate) fn staging_file(
    dir: &std::path::Path,
    suffix: &str,
) -> std::io::Result<tempfile::NamedTempFile> {
    let mut b = tempfile::Builder::new();
    b.prefix(".bzspline-").suffix(suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o644));
    }
    b.tempfile_in(dir)
}

/// A layer read: its features and its schema.
#[derive(Clone, Debug)]
pub struct Layer {
    /// One feature per record, in order, with a value for each of the
    /// schema's fields.
    pub features: Features,
    /// The name, fields and CRS.
    pub schema: Schema,
}

/// Fields for properties that come with no table (GeoJSON): each property
/// in the order first seen, of the kind that holds every value it takes
/// (text when kinds mix or a value is an array or object), text as wide as
/// its longest value.
#[must_use]
pub fn infer_fields(features: &dyn Source) -> Vec<Field> {
    #[derive(Default)]
    struct Seen {
        text: usize,
        whole: bool,
        fraction: bool,
        boolean: bool,
        other: bool,
    }
    let mut order: Vec<(String, Seen)> = Vec::new();
    for i in 0..features.count() {
        let props = features.properties(i);
        for (k, v) in props.iter() {
            let at = match order.iter().position(|(n, _)| n == k) {
                Some(at) => at,
                None => {
                    order.push((k.clone(), Seen::default()));
                    order.len() - 1
                }
            };
            let s = &mut order[at].1;
            match v {
                Value::Null => {}
                Value::Bool(_) => s.boolean = true,
                Value::Number(n) if n.is_i64() || n.is_u64() => s.whole = true,
                Value::Number(_) => s.fraction = true,
                Value::String(t) => s.text = s.text.max(t.chars().count()),
                _ => s.other = true,
            }
        }
    }
    order
        .into_iter()
        .map(|(name, s)| {
            let numeric = s.whole || s.fraction;
            let texty = s.text > 0 || s.other;
            let kinds = usize::from(texty) + usize::from(numeric) + usize::from(s.boolean);
            let kind = if kinds > 1 || texty {
                FieldKind::Text
            } else if s.boolean {
                FieldKind::Boolean
            } else if s.fraction {
                FieldKind::Real
            } else if s.whole {
                FieldKind::Integer
            } else {
                FieldKind::Text
            };
            Field {
                name,
                kind,
                width: None,
                decimals: None,
            }
        })
        .collect()
}

/// The value of a property as the text of a text field: text as it is,
/// anything else as its JSON.
#[must_use]
pub fn as_text(v: &Value) -> Option<String> {
    match v {
        Value::Null => None,
        Value::String(s) => Some(s.clone()),
        other => Some(other.to_string()),
    }
}

/// Another crate's error as one line: its lines joined by spaces, control
/// characters (a bad byte it quotes) written as `\u{..}` escapes.
#[must_use]
pub fn one_line(e: &dyn std::fmt::Display) -> String {
    let text = e.to_string();
    let joined = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ");
    joined
        .chars()
        .map(|c| {
            if c.is_control() {
                format!("\\u{{{:x}}}", u32::from(c))
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// A property's number as a whole number: an integer, or a float with no
/// fraction within the range of 64-bit integers.
#[must_use]
pub fn whole(n: &serde_json::Number) -> Option<i64> {
    n.as_i64().or_else(|| {
        n.as_f64()
            .filter(|x| x.fract() == 0.0 && x.abs() < 9.2e18)
            .map(|x| x as i64)
    })
}

/// Bytes as the text a [`FieldKind::Binary`] property holds: lowercase
/// hexadecimal.
#[must_use]
pub fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}

/// The bytes of a [`FieldKind::Binary`] property's text; `None` for text
/// that is not hexadecimal pairs.
#[must_use]
pub fn unhex(s: &str) -> Option<Vec<u8>> {
    if !s.len().is_multiple_of(2) {
        return None;
    }
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(s.get(i..i + 2)?, 16).ok())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn authorities_are_read_from_the_outermost_object() {
        assert_eq!(Crs::from_wkt(WGS84_WKT).epsg(), Some(4326));
        assert_eq!(
            Crs::from_wkt(crate::layer::ESRI_WGS84_PRJ).epsg(),
            Some(4326)
        );
        let utm = "PROJCS[\"WGS 84 / UTM zone 33N\",GEOGCS[\"WGS 84\",AUTHORITY[\"EPSG\",\"4326\"]],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AUTHORITY[\"EPSG\",\"32633\"]]";
        assert_eq!(Crs::from_wkt(utm).epsg(), Some(32633));
        let wkt2 = "PROJCRS[\"x\",BASEGEOGCRS[\"y\",ID[\"EPSG\",4326]],ID[\"EPSG\",3857]]";
        assert_eq!(Crs::from_wkt(wkt2).epsg(), Some(3857));
        assert_eq!(Crs::from_wkt("LOCAL_CS[\"x\"]").authority, None);
    }

    #[test]
    fn crs_are_parsed_as_people_write_them() {
        let code = |t: &str| Crs::parse(t).map(|c| c.authority);
        let epsg = |c: i32| Ok(Some(("EPSG".to_owned(), c)));
        assert_eq!(code("EPSG:3857"), epsg(3857));
        assert_eq!(code(" epsg:2193 "), epsg(2193));
        assert_eq!(code("urn:ogc:def:crs:EPSG::32633"), epsg(32633));
        assert_eq!(code("urn:ogc:def:crs:EPSG:9.8.15:27700"), epsg(27700));
        assert_eq!(
            code("http://www.opengis.net/def/crs/EPSG/0/5070"),
            epsg(5070)
        );
        for wgs84 in ["OGC:CRS84", "urn:ogc:def:crs:OGC:1.3:CRS84", "EPSG:4326"] {
            assert_eq!(Crs::parse(wgs84), Ok(Crs::wgs84()), "{wgs84}");
        }
        assert_eq!(Crs::parse(WGS84_WKT).unwrap().epsg(), Some(4326));
        for bad in ["", "4326", "EPSG:", "EPSG:x", "wgs 84", "a b:1"] {
            let e = Crs::parse(bad).unwrap_err();
            assert!(e.contains("EPSG:4326, OGC:CRS84"), "{bad}: {e}");
        }
    }

    #[test]
    fn bytes_round_trip_as_hexadecimal() {
        assert_eq!(
            unhex(&hex(&[0, 1, 0xab, 0xff])),
            Some(vec![0, 1, 0xab, 0xff])
        );
        assert_eq!(unhex("abc"), None);
        assert_eq!(unhex("zz"), None);
        assert_eq!(unhex("é1"), None);
    }

    #[test]
    fn inferred_kinds_hold_every_value() {
        let features = json!([
            {"properties": {"a": 1, "b": 1.5, "c": true, "d": "x", "e": 1, "f": null}},
            {"properties": {"a": 2, "b": 2, "c": null, "d": "longer", "e": "one", "g": [1]}},
        ]);
        let fields = infer_fields(&json!({"features": features}));
        let kinds: Vec<(&str, FieldKind)> =
            fields.iter().map(|f| (f.name.as_str(), f.kind)).collect();
        assert_eq!(
            kinds,
            [
                ("a", FieldKind::Integer),
                ("b", FieldKind::Real),
                ("c", FieldKind::Boolean),
                ("d", FieldKind::Text),
                ("e", FieldKind::Text),
                ("f", FieldKind::Text),
                ("g", FieldKind::Text),
            ]
        );
    }
}
