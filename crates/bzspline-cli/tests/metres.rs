//! `--tolerance` and `--snap` with units: metres on longitude and latitude
//! are ground distances at every latitude, metres on projected data are the
//! projection's units, and a distance that cannot be measured (no
//! coordinate system, coordinates that are not longitude and latitude) is
//! refused naming the file, with nothing written.

mod common;

use bzspline_io::files;
use bzspline_io::layer::{Crs, Schema};
use bzspline_io::smooth::job::Output;
use common::gdal::path;
use common::{run, succeeds};
use serde_json::{json, Value};
use std::path::Path;

/// A wavy ring about 5 km across centred at `lat` on the meridian `lon`,
/// as GeoJSON (its east-west degrees stretched by 1/cos(lat), so that it
/// has the same shape on the ground everywhere).
fn ring_at(lon: f64, lat: f64) -> Value {
    let metres_per_degree = 111_195.0;
    let mut ring: Vec<[f64; 2]> = (0..24)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::TAU / 24.0;
            let r = 2000.0 + 400.0 * (3.0 * t).sin() + 200.0 * (5.0 * t).cos();
            let (e, n) = (r * t.cos(), r * t.sin());
            [
                lon + e / (metres_per_degree * lat.to_radians().cos()),
                lat + n / metres_per_degree,
            ]
        })
        .collect();
    ring.push(ring[0]);
    json!({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "blob"}, "geometry": {"type": "Polygon", "coordinates": [ring]}}
    ]})
}

fn positions(doc: &Value) -> usize {
    doc["features"][0]["geometry"]["coordinates"][0]
        .as_array()
        .unwrap()
        .len()
}

#[test]
fn metres_on_longitude_and_latitude_are_the_same_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let mut metres = Vec::new();
    let mut degrees = Vec::new();
    for lat in [0.0, 45.0, 70.0, 85.0] {
        let file = path(dir.path(), &format!("blob{lat}.geojson"));
        std::fs::write(&file, ring_at(20.0, lat).to_string()).unwrap();
        let out: Value =
            serde_json::from_str(&succeeds(&["smooth", &file, "--tolerance", "20m"])).unwrap();
        metres.push(positions(&out) as f64);
        let out: Value =
            serde_json::from_str(&succeeds(&["smooth", &file, "--tolerance", "0.0002deg"]))
                .unwrap();
        degrees.push(positions(&out) as f64);
    }
    let spread = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &c| (l.min(c), h.max(c)));
        hi / lo
    };
    // In metres the same ground shape gets the same vertices; a tolerance
    // in degrees is 22 m north-south but 1.9 m east-west at 85 degrees.
    assert!(spread(&metres) <= 1.1, "metres: {metres:?}");
    assert!(spread(&degrees) > 1.2, "degrees: {degrees:?}");
    let o = run(
        &[
            "smooth",
            &path(dir.path(), "blob70.geojson"),
            "--tolerance",
            "0.02km",
            "--stats",
        ],
        None,
    );
    assert!(o.stderr.contains("tolerance 20 m"), "{}", o.stderr);
}

#[test]
fn metres_on_projected_data_are_its_units() {
    let dir = tempfile::tempdir().unwrap();
    // The ring in a projection's units: kilometres of a local frame, written
    // as a layer whose .prj says metres, then feet.
    let doc = ring_at(0.0, 0.0);
    let utm = Crs::from_wkt("PROJCS[\"WGS 84 / UTM zone 31N\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]],PROJECTION[\"Transverse_Mercator\"],UNIT[\"metre\",1],AUTHORITY[\"EPSG\",\"32631\"]]");
    let feet = Crs::from_wkt("PROJCS[\"local (ft)\",GEOGCS[\"WGS 84\",UNIT[\"degree\",0.0174532925199433]],PROJECTION[\"Transverse_Mercator\"],UNIT[\"foot\",0.3048]]");
    for (name, crs, factor) in [("utm", utm, 1.0), ("feet", feet, 0.3048)] {
        let schema = Schema::new(name, Vec::new(), Some(crs));
        let scaled = scale(&doc, 111_195.0);
        let file = path(dir.path(), &format!("{name}.gpkg"));
        files::write(Path::new(&file), Output::Geopackage, &scaled, Some(&schema)).unwrap();
        let with_unit = succeeds(&["smooth", &file, "--tolerance", "20m"]);
        let bare = succeeds(&[
            "smooth",
            &file,
            "--tolerance",
            &format!("{}", 20.0 / factor),
        ]);
        assert_eq!(with_unit, bare, "{name}");
        let o = run(&["smooth", &file, "--tolerance", "0.001deg"], None);
        assert_eq!(o.code, 1, "{}", o.stderr);
        assert!(
            o.stderr.contains("the data is projected, not in degrees"),
            "{}",
            o.stderr
        );
    }
}

fn scale(doc: &Value, k: f64) -> Value {
    fn walk(v: &Value, k: f64) -> Value {
        match v {
            Value::Number(n) => json!(n.as_f64().unwrap() * k),
            Value::Array(a) => Value::Array(a.iter().map(|x| walk(x, k)).collect()),
            other => other.clone(),
        }
    }
    let mut d = doc.clone();
    let g = &mut d["features"][0]["geometry"]["coordinates"];
    *g = walk(g, k);
    d
}

#[test]
fn distances_that_cannot_be_measured_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = path(dir.path(), "out.shp");
    let refused = |args: &[&str], code: i32, want: &str| {
        let o = run(args, None);
        assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains(want), "{args:?}: {}", o.stderr);
        assert_eq!(o.stderr.trim().lines().count(), 1, "{}", o.stderr);
        assert!(!Path::new(&out).exists());
    };
    // A layer without a coordinate system.
    let bare = path(dir.path(), "bare.shp");
    let schema = Schema::new("bare", Vec::new(), None);
    files::write(
        Path::new(&bare),
        Output::Shapefile,
        &ring_at(0.0, 0.0),
        Some(&schema),
    )
    .unwrap();
    assert!(!dir.path().join("bare.prj").exists());
    refused(
        &["smooth", &bare, "--tolerance", "50m", "-o", &out],
        1,
        "bare.shp: the tolerance 50 m cannot be measured: the file states no coordinate system",
    );
    refused(
        &["smooth", &bare, "--snap", "1m", "-o", &out],
        1,
        "the snap distance 1 m cannot be measured",
    );
    succeeds(&["smooth", &bare, "--tolerance", "0.0005", "-o", &out]);
    std::fs::remove_file(&out).unwrap();
    // GeoJSON whose coordinates are not longitude and latitude.
    let big = path(dir.path(), "big.geojson");
    std::fs::write(&big, scale(&ring_at(0.0, 0.0), 1e5).to_string()).unwrap();
    refused(
        &["smooth", &big, "--tolerance", "50m", "-o", &out],
        1,
        "beyond longitude and latitude",
    );
    // A unit the option does not know, and a table's points.
    refused(
        &["smooth", &big, "--tolerance", "50miles", "-o", &out],
        2,
        "50m, 0.5km, 0.001deg",
    );
    let table = common::fixture("square.csv").display().to_string();
    refused(
        &["smooth", &table, "--tolerance", "1m", "-o", &out],
        1,
        "a table states no coordinate system",
    );
}
