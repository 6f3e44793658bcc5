//! The command's GeoPackage reader on arbitrary bytes: as a whole file
//! (SQLite's own pages, the GeoPackage tables, a layer's rows), and as one
//! geometry's GeoPackage binary blob. Never a panic; a refusal is one line
//! naming the file (or the blob's fault); a layer read has finite
//! coordinates and writes to a GeoPackage that reads back the same.
#![no_main]

use bzspline_fuzz::{finite, gpkg};
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

fn check(g: &Value) {
    match g.get("geometries").and_then(Value::as_array) {
        Some(members) => members.iter().for_each(check),
        None => assert!(
            g.is_null() || finite(&g["coordinates"]),
            "non-finite coordinates read"
        ),
    }
}

fuzz_target!(|bytes: &[u8]| {
    // One geometry's blob, in the srs_id its first bytes may name.
    match gpkg::geometry(bytes, 4326) {
        Ok(g) => check(&g),
        Err(e) => assert!(!e.to_string().contains('\n'), "{e}"),
    }
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("t.gpkg");
    std::fs::write(&path, bytes).expect("written");
    let layer = match gpkg::read(&path, None, u64::MAX) {
        Ok(l) => l,
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with(&path.display().to_string()), "{m}");
            assert!(!m.contains('\n'), "{m}");
            return;
        }
    };
    for f in layer.features.to_value()["features"]
        .as_array()
        .expect("a FeatureCollection")
    {
        check(&f["geometry"]);
    }
    let out = dir.path().join("out.gpkg");
    if gpkg::write(&out, &layer.features, Some(&layer.schema)).is_ok() {
        let again = gpkg::read(&out, None, u64::MAX).expect("what was written reads back");
        assert!(
            again.features == layer.features,
            "read back otherwise:\n{:?}\n{:?}",
            layer.features,
            again.features
        );
    }
});
