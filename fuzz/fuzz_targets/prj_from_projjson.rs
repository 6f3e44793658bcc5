//! A CRS's PROJJSON, as a GeoParquet file gives it, written as the WKT 1 of
//! a Shapefile's `.prj` (`bzspline_io::wkt1`), on arbitrary JSON: never a
//! panic; what it writes is one GEOGCS or PROJCS with its quotes paired and
//! its brackets balanced, and no number outside the quotes is infinite or
//! NaN.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(bytes) else {
        return;
    };
    let Some(wkt) = bzspline_io::wkt1::from_projjson(&v) else {
        return;
    };
    assert!(
        wkt.starts_with("GEOGCS[") || wkt.starts_with("PROJCS["),
        "{wkt}"
    );
    let (mut depth, mut quoted, mut outside) = (0i64, false, String::new());
    for c in wkt.chars() {
        match c {
            '"' => quoted = !quoted,
            _ if quoted => {}
            '[' => depth += 1,
            ']' => {
                depth -= 1;
                assert!(depth >= 0, "{wkt}");
            }
            _ => outside.push(c),
        }
    }
    assert!(!quoted && depth == 0, "{wkt}");
    assert!(
        !outside.contains("inf") && !outside.contains("NaN"),
        "{wkt}"
    );
});
