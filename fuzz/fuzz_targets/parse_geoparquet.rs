//! The command's GeoParquet reader on arbitrary bytes, then the writer on
//! what was read: never a panic; a refusal is one line naming the file; an
//! accepted layer has finite coordinates, its CRS makes a `.prj` or none,
//! and what it writes reads back and writes again to the same features in
//! the same order.
#![no_main]

use bzspline_fuzz::{finite, geoparquet};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let layer = match geoparquet::read_bytes("t.parquet", bytes.to_vec()) {
        Ok(l) => l,
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("t.parquet"), "{m}");
            assert!(!m.contains('\n'), "{m}");
            return;
        }
    };
    for f in layer.features.to_value()["features"]
        .as_array()
        .expect("a FeatureCollection")
    {
        let g = &f["geometry"];
        assert!(
            g.is_null() || g.get("geometries").is_some() || finite(&g["coordinates"]),
            "non-finite coordinates read"
        );
    }
    // The .prj a Shapefile of the layer would get (from its PROJJSON).
    if let Some(crs) = &layer.schema.crs {
        let _ = crs.prj();
    }
    if let Ok(written) = geoparquet::to_bytes(&layer.features, Some(&layer.schema)) {
        let again =
            geoparquet::read_bytes("t.parquet", written).expect("what was written reads back");
        let twice =
            geoparquet::to_bytes(&again.features, Some(&again.schema)).expect("writes again");
        let thrice = geoparquet::read_bytes("t.parquet", twice).expect("reads");
        assert!(
            thrice.features == again.features,
            "read back otherwise:\n{:?}\n{:?}",
            again.features,
            thrice.features
        );
    }
});
