//! The command's TopoJSON reader, then smoothing on the arcs it read and both
//! writers, on arbitrary bytes: never a panic; a refusal is one line naming
//! the file; an accepted Topology smooths to finite numbers (serde_json writes
//! NaN and infinities as null, so the output holds no null in its arcs) and
//! keeps its arc count.
#![no_main]

use bzspline_fuzz::{finite, topojson};
use bzspline_geo::SmoothOptions;
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let Ok(v) = serde_json::from_str::<Value>(text) else {
        return;
    };
    if !topojson::is_topology(&v) {
        return;
    }
    let doc = match topojson::read("t.json", v) {
        Ok(d) => d,
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("t.json"), "{m}");
            assert!(!m.contains('\n'), "{m}");
            return;
        }
    };
    // The default tolerance, relative to the extent, keeps vertex counts
    // bounded at any scale.
    let opts = SmoothOptions::default();
    match doc.topology.smooth(&opts) {
        Ok(s) => {
            assert_eq!(s.arcs.len(), doc.topology.arcs().len());
            let out = doc.to_topojson(&s.arcs);
            assert!(finite(&out["arcs"]), "non-finite arcs");
            let _ = doc.to_geojson(&s.arcs, None);
        }
        Err(e) => assert!(!doc.describe(&e).contains('\n')),
    }
});
