//! A coordinate reference system in PROJJSON (a GeoParquet file's `crs`)
//! written as the OGC WKT 1 of a Shapefile's `.prj`, which is what GDAL's
//! Shapefile driver (and so QGIS) reads there: a `.prj` in WKT 2 reads as
//! no CRS at all.
//!
//! A geographic CRS of two axes, or a projected one by a method of the table
//! below (those of almost every national and UTM grid), on a datum or datum
//! ensemble with its ellipsoid and prime meridian. Parameters are written in
//! the units WKT 1 takes them in (angles in the geographic CRS's unit,
//! lengths in the projected CRS's). Anything else gives `None`, never a
//! guess.

use serde_json::Value;

/// The WKT 1 of the PROJJSON `p`, when this module can write it.
#[must_use]
pub fn from_projjson(p: &Value) -> Option<String> {
    match p["type"].as_str()? {
        "GeographicCRS" => geographic(p).map(|(wkt, _)| wkt),
        "ProjectedCRS" => projcs(p),
        _ => None,
    }
}

/// Parameters of a projection: the EPSG code of each and its WKT 1 name.
type Parameters = &'static [(i64, &'static str)];

/// The WKT 1 projections by EPSG method code, and their parameters by EPSG
/// parameter code.
const METHODS: &[(i64, &str, Parameters)] = &[
    (9807, "Transverse_Mercator", NATURAL),
    (9801, "Lambert_Conformal_Conic_1SP", NATURAL),
    (9804, "Mercator_1SP", NATURAL),
    (9809, "Oblique_Stereographic", NATURAL),
    (9810, "Polar_Stereographic", NATURAL),
    (9802, "Lambert_Conformal_Conic_2SP", CONIC),
    (
        9822,
        "Albers_Conic_Equal_Area",
        &[
            (8821, "latitude_of_center"),
            (8822, "longitude_of_center"),
            (8823, "standard_parallel_1"),
            (8824, "standard_parallel_2"),
            (8826, "false_easting"),
            (8827, "false_northing"),
        ],
    ),
    (
        9820,
        "Lambert_Azimuthal_Equal_Area",
        &[
            (8801, "latitude_of_center"),
            (8802, "longitude_of_center"),
            (8806, "false_easting"),
            (8807, "false_northing"),
        ],
    ),
    (
        9805,
        "Mercator_2SP",
        &[
            (8823, "standard_parallel_1"),
            (8802, "central_meridian"),
            (8806, "false_easting"),
            (8807, "false_northing"),
        ],
    ),
    (
        9829,
        "Polar_Stereographic",
        &[
            (8832, "latitude_of_origin"),
            (8833, "central_meridian"),
            (8806, "false_easting"),
            (8807, "false_northing"),
        ],
    ),
    (
        9835,
        "Cylindrical_Equal_Area",
        &[
            (8823, "standard_parallel_1"),
            (8802, "central_meridian"),
            (8806, "false_easting"),
            (8807, "false_northing"),
        ],
    ),
    (
        9815,
        "Hotine_Oblique_Mercator_Azimuth_Center",
        &[
            (8811, "latitude_of_center"),
            (8812, "longitude_of_center"),
            (8813, "azimuth"),
            (8814, "rectified_grid_angle"),
            (8815, "scale_factor"),
            (8816, "false_easting"),
            (8817, "false_northing"),
        ],
    ),
];

/// The parameters of a projection at a natural origin.
const NATURAL: Parameters = &[
    (8801, "latitude_of_origin"),
    (8802, "central_meridian"),
    (8805, "scale_factor"),
    (8806, "false_easting"),
    (8807, "false_northing"),
];

/// The parameters of a conic projection of two standard parallels.
const CONIC: Parameters = &[
    (8821, "latitude_of_origin"),
    (8822, "central_meridian"),
    (8823, "standard_parallel_1"),
    (8824, "standard_parallel_2"),
    (8826, "false_easting"),
    (8827, "false_northing"),
];

/// A unit: its name and its factor to the metre or the radian (1 for a
/// scale).
#[derive(Clone, PartialEq)]
struct Unit {
    name: String,
    factor: f64,
    authority: String,
}

/// What a unit measures.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Length,
    Angle,
    Scale,
}

const DEGREE: f64 = 0.017_453_292_519_943_3;

impl Unit {
    /// A unit EPSG names by `code`.
    fn epsg(name: &str, factor: f64, code: i64) -> Unit {
        Unit {
            name: name.to_owned(),
            factor,
            authority: format!(",AUTHORITY[\"EPSG\",\"{code}\"]"),
        }
    }

    fn metre() -> Unit {
        Unit::epsg("metre", 1.0, 9001)
    }

    fn degree() -> Unit {
        Unit::epsg("degree", DEGREE, 9122)
    }

    /// What a bare number of `kind` is in (PROJJSON's default units).
    fn default_of(kind: Kind) -> Unit {
        match kind {
            Kind::Length => Unit::metre(),
            Kind::Angle => Unit::degree(),
            Kind::Scale => Unit::epsg("unity", 1.0, 9201),
        }
    }
}

/// The unit `u` of PROJJSON, when it measures `kind`: one named by a string
/// (`metre`, `foot`, `US survey foot`, `degree`, `unity`) or an object with
/// its name and factor to the metre, radian or unity (and its type, when
/// it says one, of that kind).
fn unit(u: &Value, kind: Kind) -> Option<Unit> {
    match (u, kind) {
        (Value::String(s), Kind::Length) => match s.as_str() {
            "metre" => Some(Unit::metre()),
            "foot" => Some(Unit::epsg("foot", 0.3048, 9002)),
            "US survey foot" => Some(Unit::epsg("US survey foot", 1200.0 / 3937.0, 9003)),
            _ => None,
        },
        (Value::String(s), Kind::Angle) if s == "degree" => Some(Unit::degree()),
        (Value::String(s), Kind::Scale) if s == "unity" => Some(Unit::default_of(Kind::Scale)),
        (Value::Object(_), _) => {
            let of_kind = match u.get("type").and_then(Value::as_str) {
                None => true,
                Some(t) => matches!(
                    (t, kind),
                    ("LinearUnit", Kind::Length)
                        | ("AngularUnit", Kind::Angle)
                        | ("ScaleUnit", Kind::Scale)
                ),
            };
            let factor = u["conversion_factor"]
                .as_f64()
                .filter(|f| *f > 0.0 && f.is_finite())?;
            of_kind.then(|| Unit {
                name: u["name"].as_str().unwrap_or("unknown").to_owned(),
                factor,
                authority: authority(u).unwrap_or_default(),
            })
        }
        _ => None,
    }
}

/// Metres in one PROJJSON length unit `u` (for [`crate::distance`]).
pub(crate) fn metres_in(u: &Value) -> Option<f64> {
    unit(u, Kind::Length).map(|u| u.factor)
}

/// `x` given in the unit `from` (the default unit of `kind` for none), in
/// `to`.
fn convert(x: f64, from: Option<&Value>, kind: Kind, to: &Unit) -> Option<f64> {
    let from = match from {
        Some(u) => unit(u, kind)?,
        None => Unit::default_of(kind),
    };
    let out = if from.factor == to.factor {
        x
    } else {
        x * from.factor / to.factor
    };
    out.is_finite().then_some(out)
}

/// A measure in `to`: a bare number (in the default unit of `kind`) or
/// `{"value": v, "unit": u}`.
fn value_in(v: &Value, kind: Kind, to: &Unit) -> Option<f64> {
    match v {
        Value::Number(n) => convert(n.as_f64()?, None, kind, to),
        Value::Object(_) => convert(v["value"].as_f64()?, Some(&v["unit"]), kind, to),
        _ => None,
    }
}

/// `,AUTHORITY["EPSG","4326"]` for an object's `id` (or first of `ids`).
fn authority(o: &Value) -> Option<String> {
    let id = o.get("id").or_else(|| o.get("ids")?.get(0))?;
    let code = match &id["code"] {
        Value::Number(n) => n.to_string(),
        Value::String(s) => s.clone(),
        _ => return None,
    };
    Some(format!(
        ",AUTHORITY[{},{}]",
        quote(id["authority"].as_str()?),
        quote(&code)
    ))
}

fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('"', ""))
}

/// A number in its shortest form that reads back the same.
fn number(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e15 {
        format!("{x:.0}")
    } else {
        format!("{x}")
    }
}

/// The geographic CRS `g` and its angle unit.
fn geographic(g: &Value) -> Option<(String, Unit)> {
    let axes = g["coordinate_system"]["axis"].as_array();
    if axes.is_some_and(|a| a.len() != 2) {
        return None;
    }
    let angle = match axes.and_then(|a| a[0].get("unit")) {
        Some(u) => unit(u, Kind::Angle)?,
        None => Unit::degree(),
    };
    let datum = g.get("datum");
    let frame = match datum {
        Some(d) if d["type"].as_str()? == "GeodeticReferenceFrame" => d,
        Some(_) => return None,
        None => g.get("datum_ensemble")?,
    };
    let e = &frame["ellipsoid"];
    let metre = Unit::metre();
    let a = value_in(
        e.get("semi_major_axis").or_else(|| e.get("radius"))?,
        Kind::Length,
        &metre,
    )?;
    let rf = match (e.get("inverse_flattening"), e.get("semi_minor_axis")) {
        (Some(rf), _) => rf.as_f64()?,
        (None, Some(b)) => {
            let b = value_in(b, Kind::Length, &metre)?;
            if a == b {
                0.0
            } else {
                a / (a - b)
            }
        }
        (None, None) if e.get("radius").is_some() => 0.0,
        (None, None) => return None,
    };
    if !rf.is_finite() {
        return None;
    }
    // WKT 1 writes the prime meridian in degrees.
    let (pm_name, pm) = match datum.and_then(|d| d.get("prime_meridian")) {
        Some(pm) => (
            pm["name"].as_str()?,
            value_in(&pm["longitude"], Kind::Angle, &Unit::degree())?,
        ),
        None => ("Greenwich", 0.0),
    };
    let datum_name = match authority(frame).as_deref() {
        Some(",AUTHORITY[\"EPSG\",\"6326\"]") => "WGS_1984".to_owned(),
        // WKT 1 names a datum ensemble as the datum it stands for.
        _ => {
            let name = frame["name"].as_str()?;
            name.strip_suffix(" ensemble")
                .unwrap_or(name)
                .replace([' ', '-', '(', ')', '/'], "_")
        }
    };
    let wkt = format!(
        "GEOGCS[{},DATUM[{},SPHEROID[{},{},{}{}]{}],PRIMEM[{},{}],UNIT[{},{}{}]{}]",
        quote(g["name"].as_str()?),
        quote(&datum_name),
        quote(e["name"].as_str()?),
        number(a),
        number(rf),
        authority(e).unwrap_or_default(),
        authority(frame).unwrap_or_default(),
        quote(pm_name),
        number(pm),
        quote(&angle.name),
        number(angle.factor),
        angle.authority,
        authority(g).unwrap_or_default(),
    );
    Some((wkt, angle))
}

fn projcs(p: &Value) -> Option<String> {
    let (geogcs, angle) = geographic(&p["base_crs"])?;
    let axes = p["coordinate_system"]["axis"].as_array()?;
    if axes.len() != 2 || p["coordinate_system"]["subtype"].as_str()? != "Cartesian" {
        return None;
    }
    let length = unit(axes[0].get("unit")?, Kind::Length)?;
    if unit(axes[1].get("unit")?, Kind::Length)? != length {
        return None;
    }
    let c = &p["conversion"];
    let m = &c["method"]["id"];
    if m["authority"].as_str()? != "EPSG" {
        return None;
    }
    let code = m["code"].as_i64()?;
    let (_, projection, names) = METHODS.iter().find(|(k, _, _)| *k == code)?;
    let given = c["parameters"].as_array()?;
    let mut out = format!(
        "PROJCS[{},{geogcs},PROJECTION[{}]",
        quote(p["name"].as_str()?),
        quote(projection)
    );
    for &(pcode, name) in *names {
        let param = given.iter().find(|q| {
            q["id"]["authority"].as_str() == Some("EPSG") && q["id"]["code"].as_i64() == Some(pcode)
        })?;
        // What the parameter measures, by what it is, not by its unit.
        let kind = match name {
            "false_easting" | "false_northing" => Kind::Length,
            "scale_factor" => Kind::Scale,
            _ => Kind::Angle,
        };
        let to = match kind {
            Kind::Length => length.clone(),
            Kind::Angle => angle.clone(),
            Kind::Scale => Unit::default_of(Kind::Scale),
        };
        // Each parameter names its unit.
        let v = convert(
            param["value"].as_f64()?,
            Some(param.get("unit")?),
            kind,
            &to,
        )?;
        out.push_str(&format!(",PARAMETER[{},{}]", quote(name), number(v)));
    }
    // Every parameter the method has must be one WKT 1 is given.
    if given.len() != names.len() {
        return None;
    }
    out.push_str(&format!(
        ",UNIT[{},{}{}]{}]",
        quote(&length.name),
        number(length.factor),
        length.authority,
        authority(p).unwrap_or_default()
    ));
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// The number after `key` in `wkt`.
    fn after(wkt: &str, key: &str) -> f64 {
        let at = wkt
            .find(key)
            .unwrap_or_else(|| panic!("{key} not in {wkt}"))
            + key.len();
        let rest = &wkt[at..];
        rest[..rest.find([',', ']']).unwrap()].parse().unwrap()
    }

    fn projected(parameter_unit: Value, axis_unit: Value) -> Value {
        let grad = json!({"type": "AngularUnit", "name": "grad", "conversion_factor": 0.015707963267948967});
        json!({
            "type": "ProjectedCRS",
            "name": "P",
            "base_crs": {
                "name": "G",
                "datum": {
                    "type": "GeodeticReferenceFrame",
                    "name": "D (x)",
                    "ellipsoid": {"name": "E", "semi_major_axis": 6000000, "semi_minor_axis": 5980000},
                    "prime_meridian": {"name": "Paris", "longitude": {"value": 2.5969213, "unit": grad}}
                },
                "coordinate_system": {"subtype": "ellipsoidal", "axis": [
                    {"name": "Lat", "direction": "north", "unit": grad},
                    {"name": "Lon", "direction": "east", "unit": grad}]}
            },
            "conversion": {
                "name": "C",
                "method": {"name": "Transverse Mercator", "id": {"authority": "EPSG", "code": 9807}},
                "parameters": [
                    {"name": "a", "value": 45, "unit": "degree", "id": {"authority": "EPSG", "code": 8801}},
                    {"name": "b", "value": 54, "unit": grad, "id": {"authority": "EPSG", "code": 8802}},
                    {"name": "c", "value": 0.9996, "unit": "unity", "id": {"authority": "EPSG", "code": 8805}},
                    {"name": "d", "value": 600000, "unit": parameter_unit, "id": {"authority": "EPSG", "code": 8806}},
                    {"name": "e", "value": 0, "unit": "metre", "id": {"authority": "EPSG", "code": 8807}}
                ]
            },
            "coordinate_system": {"subtype": "Cartesian", "axis": [
                {"name": "E", "direction": "east", "unit": axis_unit},
                {"name": "N", "direction": "north", "unit": axis_unit}]},
            "id": {"authority": "EPSG", "code": 99999}
        })
    }

    #[test]
    fn parameters_are_written_in_the_units_wkt_1_takes() {
        let foot = json!({"type": "LinearUnit", "name": "US survey foot", "conversion_factor": 0.304800609601219});
        let wkt = from_projjson(&projected(json!("metre"), foot)).unwrap();
        // Lengths in the projected CRS's unit, angles in the geographic
        // CRS's (grads), the prime meridian in degrees, the flattening from
        // the semi-minor axis.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
        assert!(
            close(
                after(&wkt, "\"false_easting\","),
                600000.0 / 0.304800609601219
            ),
            "{wkt}"
        );
        assert!(close(after(&wkt, "\"latitude_of_origin\","), 50.0), "{wkt}");
        assert_eq!(after(&wkt, "\"central_meridian\","), 54.0, "{wkt}");
        assert!(close(after(&wkt, "PRIMEM[\"Paris\","), 2.33722917), "{wkt}");
        assert!(
            close(after(&wkt, "SPHEROID[\"E\",6000000,"), 300.0),
            "{wkt}"
        );
        assert!(wkt.contains("DATUM[\"D__x_\""), "{wkt}");
        assert!(
            wkt.ends_with(
                "UNIT[\"US survey foot\",0.304800609601219],AUTHORITY[\"EPSG\",\"99999\"]]"
            ),
            "{wkt}"
        );
    }

    #[test]
    fn what_wkt_1_is_not_given_here_gives_none() {
        let metre = json!("metre");
        assert!(from_projjson(&projected(metre.clone(), metre.clone())).is_some());
        // A length where the parameter is an angle's, an unknown method, a
        // parameter the method lacks, axes of two units, another CRS type.
        assert_eq!(
            from_projjson(&projected(json!("degree"), metre.clone())),
            None
        );
        let mut other = projected(metre.clone(), metre.clone());
        other["conversion"]["method"]["id"]["code"] = json!(1041);
        assert_eq!(from_projjson(&other), None);
        let mut extra = projected(metre.clone(), metre.clone());
        extra["conversion"]["parameters"][4]["id"]["code"] = json!(8827);
        assert_eq!(from_projjson(&extra), None);
        let mut mixed = projected(metre.clone(), metre.clone());
        mixed["coordinate_system"]["axis"][1]["unit"] =
            json!({"type": "LinearUnit", "name": "foot", "conversion_factor": 0.3048});
        assert_eq!(from_projjson(&mixed), None);
        for t in ["GeodeticCRS", "VerticalCRS", "CompoundCRS", "BoundCRS"] {
            assert_eq!(from_projjson(&json!({"type": t, "name": "x"})), None);
        }
    }
}
