//! Distances as the smoothing options take them (`--tolerance 50m`,
//! `--snap 0.5m`, `2km`, `0.001deg`; a bare number in the data's own
//! units), parsed once for the command and every binding, and what a
//! distance means for data whose coordinates are longitude and latitude,
//! projected, or of no known system ([`Space`]).

use std::fmt;

use bzspline_geo::geodesy::METRES_PER_DEGREE;
use bzspline_geo::Frame;

use crate::layer::Crs;

/// The unit a distance is given in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Unit {
    /// The data's coordinate units (a bare number).
    #[default]
    Data,
    /// Metres (`m`, or `km` times 1,000) on the ground.
    Metres,
    /// Degrees of longitude and latitude (`deg`), on geographic data.
    Degrees,
}

/// A distance and its unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Distance {
    /// The number, in `unit` (kilometres already in metres).
    pub value: f64,
    /// What the number counts.
    pub unit: Unit,
}

impl Distance {
    /// A distance in the data's units.
    #[must_use]
    pub fn data(value: f64) -> Distance {
        Distance {
            value,
            unit: Unit::Data,
        }
    }
}

impl fmt::Display for Distance {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.unit {
            Unit::Data => write!(f, "{}", self.value),
            Unit::Metres => write!(f, "{} m", self.value),
            Unit::Degrees => write!(f, "{} deg", self.value),
        }
    }
}

/// What the accepted forms are, for messages.
pub const DISTANCE_FORMS: &str =
    "a number in the data's units, or with a unit: 50m, 0.5km, 0.001deg";

/// A distance as the options write it: a number, then optionally `m`,
/// `km`, `deg` (or `°`), with or without a space between. The number must
/// be finite; the option's own range (a tolerance above 0, a snap distance
/// of at least 0) is checked by the library when it is used.
///
/// # Errors
///
/// Anything else, as the words of the option's message.
pub fn parse_distance(s: &str) -> Result<Distance, String> {
    let t = s.trim();
    let bad = || format!("must be {DISTANCE_FORMS} (got {s:?})");
    let lower = t.to_ascii_lowercase();
    let (number, scale, unit) = [
        ("km", 1000.0, Unit::Metres),
        ("m", 1.0, Unit::Metres),
        ("deg", 1.0, Unit::Degrees),
        ("°", 1.0, Unit::Degrees),
    ]
    .into_iter()
    .find_map(|(suffix, k, u)| lower.strip_suffix(suffix).map(|n| (n, k, u)))
    .unwrap_or((lower.as_str(), 1.0, Unit::Data));
    let value: f64 = number.trim().parse().map_err(|_| bad())?;
    if !value.is_finite() {
        return Err(bad());
    }
    let value = value * scale;
    Ok(Distance { value, unit })
}

/// What a layer's coordinates are, as far as the file says.
#[derive(Clone, Debug, PartialEq)]
pub enum Space {
    /// Longitude and latitude in degrees.
    Geographic,
    /// Projected coordinates, with the metres one unit is (when known).
    Projected {
        /// Metres in one coordinate unit.
        metres: Option<f64>,
    },
    /// No known coordinate system, and why (for messages).
    Unknown(String),
}

impl Space {
    /// The space a CRS describes: geographic by its WKT (`GEOGCS`,
    /// `GEOGCRS`) or EPSG code (4326, 4269, 4258, 4283, 4167, 4674, 4612,
    /// 6318); projected with the linear unit its WKT names, or EPSG:3857,
    /// the UTM zones on WGS 84 and ETRS89-LAEA/LCC (3035, 3034) in metres.
    #[must_use]
    pub fn of_crs(crs: Option<&Crs>) -> Space {
        let Some(crs) = crs else {
            return Space::Unknown("no coordinate system is given".into());
        };
        if let Some(wkt) = &crs.wkt {
            let upper = wkt.trim_start().to_ascii_uppercase();
            if upper.starts_with("GEOGCS") || upper.starts_with("GEOGCRS") {
                return Space::Geographic;
            }
            if upper.starts_with("PROJCS") || upper.starts_with("PROJCRS") {
                return Space::Projected {
                    metres: linear_unit(wkt).or_else(|| known_projected(crs.epsg())),
                };
            }
        }
        if let Some(p) = crs
            .projjson
            .as_deref()
            .and_then(|p| serde_json::from_str::<serde_json::Value>(p).ok())
        {
            match p["type"].as_str() {
                Some("GeographicCRS") => return Space::Geographic,
                Some("ProjectedCRS") => {
                    return Space::Projected {
                        metres: projjson_unit(&p).or_else(|| known_projected(crs.epsg())),
                    }
                }
                _ => {}
            }
        }
        match crs.epsg() {
            Some(4326 | 4269 | 4258 | 4283 | 4167 | 4674 | 4612 | 6318) => Space::Geographic,
            code => match known_projected(code) {
                Some(m) => Space::Projected { metres: Some(m) },
                None => Space::Unknown(match (code, &crs.authority) {
                    (Some(c), _) => format!("EPSG:{c} is not a coordinate system bzspline knows"),
                    (None, Some((o, c))) => {
                        format!("{o}:{c} is not a coordinate system bzspline knows")
                    }
                    (None, None) => "its coordinate system is not one bzspline knows".into(),
                }),
            },
        }
    }

    /// Resolves a tolerance (or snap distance) for data in this space: the
    /// value in the units the smoothing takes and the frame it smooths in.
    /// A bare number is in the data's units, in the plane; metres on
    /// geographic data smooth on the ellipsoid ([`Frame::Geographic`]); on
    /// projected data they become the CRS's units; degrees are the data's
    /// units on geographic data.
    ///
    /// # Errors
    ///
    /// Metres on data of an unknown system or unit, degrees on projected or
    /// unknown data, as a sentence for the user.
    pub fn resolve(&self, d: Distance) -> Result<(f64, Frame), String> {
        match (d.unit, self) {
            (Unit::Data, _) => Ok((d.value, Frame::Plane)),
            (Unit::Metres, Space::Geographic) => Ok((d.value, Frame::Geographic)),
            (Unit::Metres, Space::Projected { metres: Some(m) }) => Ok((d.value / m, Frame::Plane)),
            (Unit::Metres, Space::Projected { metres: None }) => Err(format!(
                "{d} cannot be measured: the coordinate system's linear unit is unknown; give the distance in the data's units (a bare number)"
            )),
            (Unit::Metres | Unit::Degrees, Space::Unknown(why)) => Err(format!(
                "{d} cannot be measured: {why}; give the distance in the data's units (a bare number)"
            )),
            (Unit::Degrees, Space::Geographic) => Ok((d.value, Frame::Plane)),
            (Unit::Degrees, Space::Projected { .. }) => Err(format!(
                "{d}: the data is projected, not in degrees; give metres (50m) or the data's units"
            )),
        }
    }

    /// A snap distance for data in this space, in the data's units: metres
    /// on geographic data as the same angle of a great circle (1 m is
    /// 1/111,195 of a degree), since positions are snapped in degrees.
    ///
    /// # Errors
    ///
    /// As [`Space::resolve`].
    pub fn resolve_snap(&self, d: Distance) -> Result<f64, String> {
        match (d.unit, self) {
            (Unit::Metres, Space::Geographic) => Ok(d.value / METRES_PER_DEGREE),
            _ => self.resolve(d).map(|(v, _)| v),
        }
    }

    /// The space of GeoJSON positions (RFC 7946: longitude and latitude on
    /// WGS 84) given their bounds `[min x, min y, max x, max y]`: geographic
    /// when they lie within longitude and latitude, else unknown.
    #[must_use]
    pub fn of_lonlat_bounds(bounds: [f64; 4], what: &str) -> Space {
        let [x0, y0, x1, y1] = bounds;
        if x0 >= -360.0 && x1 <= 360.0 && y0 >= -90.0 && y1 <= 90.0 {
            Space::Geographic
        } else {
            Space::Unknown(format!(
                "its coordinates reach ({x0}, {y0})-({x1}, {y1}), beyond longitude and latitude, so {what} is not longitude and latitude"
            ))
        }
    }
}

/// Metres in the unit of a PROJJSON projected CRS's first axis
/// ([`crate::wkt1`] reads PROJJSON's units).
fn projjson_unit(p: &serde_json::Value) -> Option<f64> {
    crate::wkt1::metres_in(&p["coordinate_system"]["axis"][0]["unit"])
}

/// Metres a projected CRS's unit is, for the codes known without a WKT.
fn known_projected(code: Option<i32>) -> Option<f64> {
    match code? {
        3857 | 3395 | 3034 | 3035 | 2154 | 27700 | 5070 | 3338 => Some(1.0),
        c if (32601..=32660).contains(&c) || (32701..=32760).contains(&c) => Some(1.0),
        c if (25828..=25838).contains(&c) => Some(1.0),
        _ => None,
    }
}

/// The metres in one linear unit of a projected CRS's WKT: WKT 1's last
/// `UNIT[...]` at the first level of brackets, WKT 2's first `LENGTHUNIT`.
fn linear_unit(wkt: &str) -> Option<f64> {
    let upper = wkt.to_ascii_uppercase();
    let number_after = |at: usize| -> Option<f64> {
        let body = &wkt[at..];
        let start = body.find('[')? + 1;
        let end = body[start..]
            .find([']', ','].as_slice())
            .map(|e| start + e)?;
        // Skip the name.
        let rest = &body[end + 1..];
        let stop = rest.find([',', ']']).unwrap_or(rest.len());
        rest[..stop].trim().parse().ok()
    };
    if upper.trim_start().starts_with("PROJCRS") {
        // The coordinate system's unit follows its CS[...] axis list.
        let cs = upper.rfind("CS[")?;
        let at = upper[cs..].find("LENGTHUNIT[")? + cs;
        return number_after(at);
    }
    // WKT 1: the UNIT at depth 1.
    let (mut depth, mut in_text, mut found) = (0usize, false, None);
    for (i, b) in upper.bytes().enumerate() {
        match b {
            b'"' => in_text = !in_text,
            b'[' if !in_text => {
                depth += 1;
                if depth == 2 && upper[..i].ends_with("UNIT") {
                    found = Some(i - 4);
                }
            }
            b']' if !in_text => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    number_after(found?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_take_a_unit() {
        let d = |v: f64, unit: Unit| Ok(Distance { value: v, unit });
        assert_eq!(parse_distance("50"), d(50.0, Unit::Data));
        assert_eq!(parse_distance("50m"), d(50.0, Unit::Metres));
        assert_eq!(parse_distance(" 0.5 m "), d(0.5, Unit::Metres));
        assert_eq!(parse_distance("2km"), d(2000.0, Unit::Metres));
        assert_eq!(parse_distance("1e-3deg"), d(1e-3, Unit::Degrees));
        assert_eq!(parse_distance("0.01°"), d(0.01, Unit::Degrees));
        for bad in ["", "m", "50 miles", "nan m", "inf", "5 5m", "50mm"] {
            let e = parse_distance(bad).unwrap_err();
            assert!(e.contains("50m, 0.5km, 0.001deg"), "{bad}: {e}");
        }
    }

    #[test]
    fn what_a_distance_means_depends_on_the_data() {
        let m = parse_distance("50m").unwrap();
        assert_eq!(Space::Geographic.resolve(m), Ok((50.0, Frame::Geographic)));
        let feet = Space::Projected {
            metres: Some(0.3048),
        };
        let (v, f) = feet.resolve(m).unwrap();
        assert!((v - 164.041_994_75).abs() < 1e-6 && f == Frame::Plane);
        assert!(Space::Unknown("no coordinate system is given".into())
            .resolve(m)
            .unwrap_err()
            .contains("no coordinate system is given"));
        assert!(Space::Projected { metres: Some(1.0) }
            .resolve(parse_distance("1deg").unwrap())
            .is_err());
        assert_eq!(
            Space::Geographic.resolve(Distance::data(0.1)),
            Ok((0.1, Frame::Plane))
        );
    }

    #[test]
    fn spaces_are_read_from_the_crs() {
        let wkt = |w: &str| Crs::from_wkt(w);
        assert_eq!(Space::of_crs(Some(&Crs::wgs84())), Space::Geographic);
        assert_eq!(
            Space::of_crs(Some(&wkt(crate::layer::ESRI_WGS84_PRJ))),
            Space::Geographic
        );
        let utm = "PROJCS[\"WGS 84 / UTM zone 33N\",GEOGCS[\"WGS 84\",UNIT[\"degree\",0.0174532925199433]],PROJECTION[\"Transverse_Mercator\"],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AUTHORITY[\"EPSG\",\"32633\"]]";
        assert_eq!(
            Space::of_crs(Some(&wkt(utm))),
            Space::Projected { metres: Some(1.0) }
        );
        let ft = "PROJCS[\"NAD83 / x (ftUS)\",GEOGCS[\"NAD83\",UNIT[\"degree\",0.0174532925199433]],UNIT[\"US survey foot\",0.304800609601219]]";
        assert_eq!(
            Space::of_crs(Some(&wkt(ft))),
            Space::Projected {
                metres: Some(0.304_800_609_601_219)
            }
        );
        let wkt2 = "PROJCRS[\"x\",BASEGEOGCRS[\"y\",ANGLEUNIT[\"degree\",0.0174532925199433]],CONVERSION[\"c\"],CS[Cartesian,2],AXIS[\"e\",east],LENGTHUNIT[\"metre\",1],ID[\"EPSG\",3857]]";
        assert_eq!(
            Space::of_crs(Some(&wkt(wkt2))),
            Space::Projected { metres: Some(1.0) }
        );
        assert!(matches!(Space::of_crs(None), Space::Unknown(_)));
        let code = |c: i32| Crs {
            authority: Some(("EPSG".into(), c)),
            wkt: None,
            projjson: None,
        };
        let projjson = |p: serde_json::Value| Crs::from_projjson(&p);
        assert_eq!(
            Space::of_crs(Some(&projjson(
                serde_json::json!({"type": "GeographicCRS", "name": "x"})
            ))),
            Space::Geographic
        );
        let ft = serde_json::json!({"type": "ProjectedCRS", "coordinate_system": {"axis": [
            {"unit": {"type": "LinearUnit", "name": "US survey foot", "conversion_factor": 0.3048006096012192}}]}});
        assert_eq!(
            Space::of_crs(Some(&projjson(ft))),
            Space::Projected {
                metres: Some(0.304_800_609_601_219_2)
            }
        );
        assert_eq!(Space::of_crs(Some(&code(4269))), Space::Geographic);
        assert_eq!(
            Space::of_crs(Some(&code(32617))),
            Space::Projected { metres: Some(1.0) }
        );
        assert!(matches!(
            Space::of_crs(Some(&code(2193))),
            Space::Unknown(_)
        ));
    }
}
