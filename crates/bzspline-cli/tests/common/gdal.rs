//! GDAL as the outside judge of the layer files the command reads and
//! writes (`ogr2ogr`, `ogrinfo` from Debian's `gdal-bin`), and the
//! comparisons the layer tests share.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

pub const NEEDS_GDAL: &str = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)";

pub fn path(dir: &Path, name: &str) -> String {
    dir.join(name).display().to_string()
}

/// Runs a GDAL tool and gives its standard output.
pub fn gdal(tool: &str, args: &[&str]) -> String {
    let o = Command::new(tool)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{tool}: {e} ({NEEDS_GDAL})"));
    assert!(
        o.status.success(),
        "{tool} {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The features of a vector file as GDAL reads them, as GeoJSON with every
/// double written in 17 significant digits (so each reads back the same).
pub fn gdal_features(file: &str) -> Vec<Value> {
    let dir = tempfile::tempdir().unwrap();
    let out = path(dir.path(), "read.geojson");
    gdal(
        "ogr2ogr",
        &[
            "-f",
            "GeoJSON",
            "-lco",
            "SIGNIFICANT_FIGURES=17",
            &out,
            file,
        ],
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    v["features"].as_array().unwrap().clone()
}

/// `ogrinfo`'s summary of every layer of a file.
pub fn info(file: &str) -> String {
    gdal("ogrinfo", &["-ro", "-so", "-al", file])
}

/// The field lines (`name: String (0.0)`) of an `ogrinfo` summary.
pub fn fields(info: &str) -> Vec<String> {
    info.lines()
        .filter(|l| {
            l.contains(": ")
                && l.contains(" (")
                && !l.starts_with("Layer")
                && !l.starts_with("Extent")
                && !l.starts_with("INFO")
        })
        .map(str::to_owned)
        .collect()
}

/// The polygons of a fixture, as a GeoJSON file in `dir` (a Shapefile
/// holds one kind of geometry).
pub fn polygons_of(dir: &Path, name: &str) -> String {
    let mut v: Value = serde_json::from_str(
        &std::fs::read_to_string(super::fixture(&format!("{name}.geojson"))).unwrap(),
    )
    .unwrap();
    v["features"].as_array_mut().unwrap().retain(|f| {
        f["geometry"]["type"]
            .as_str()
            .is_some_and(|t| t.ends_with("Polygon"))
    });
    let out = path(dir, &format!("{name}-polygons.geojson"));
    std::fs::write(&out, v.to_string()).unwrap();
    out
}

/// Every number of a JSON value, in order (so that `0` and `0.0` agree).
pub fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Number(n) => vec![n.as_f64().unwrap()],
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        _ => vec![],
    }
}

/// GDAL prints coordinates in decimal (its GeoJSON writer rounds some in the
/// last digit), so its reading is compared to within 1e-12.
pub fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(1.0))
}
