//! The command's FlatGeobuf reader on arbitrary bytes, then the writer on
//! what was read: never a panic; a refusal is one line naming the file; an
//! accepted layer has finite coordinates, and what it writes reads back and
//! writes again to the same features (in the spatial index's order).
#![no_main]

use bzspline_fuzz::{fgb, finite};
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

fn sorted(fc: &Value) -> Vec<String> {
    let mut v: Vec<String> = fc["features"]
        .as_array()
        .expect("a FeatureCollection")
        .iter()
        .map(Value::to_string)
        .collect();
    v.sort();
    v
}

fuzz_target!(|bytes: &[u8]| {
    let layer = match fgb::read_from("t.fgb", bytes) {
        Ok(l) => l,
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("t.fgb"), "{m}");
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
    if let Ok(written) = fgb::to_bytes(&layer.features, Some(&layer.schema), "t") {
        let again =
            fgb::read_from("t.fgb", written.as_slice()).expect("what was written reads back");
        assert!(
            sorted(&again.features.to_value()) == sorted(&layer.features.to_value()),
            "read back otherwise:\n{:?}\n{:?}",
            layer.features,
            again.features
        );
        let twice = fgb::to_bytes(&again.features, Some(&again.schema), "t").expect("writes again");
        assert!(
            sorted(&again.features.to_value())
                == sorted(
                    &fgb::read_from("t.fgb", twice.as_slice())
                        .expect("reads")
                        .features
                        .to_value()
                )
        );
    }
});
