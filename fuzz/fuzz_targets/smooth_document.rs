//! What `bzspline smooth` runs (read, check, topology, smoothing, write) on
//! arbitrary bytes, GeoJSON and TopoJSON alike: never a panic; a refusal is
//! one line naming the file; an accepted document is written with finite
//! numbers only and every polygon ring closed with at least 4 positions.
//! The first byte picks the options (coverage or ring by ring, through).
#![no_main]

use bzspline_fuzz::document::{self, NAME};
use bzspline_fuzz::finite;
use bzspline_geo::SmoothOptions;
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

/// Every ring of every Polygon and MultiPolygon in a GeoJSON value.
fn rings<'a>(v: &'a Value, out: &mut Vec<&'a Vec<Value>>) {
    match v {
        Value::Object(o) => {
            let depth = match o.get("type").and_then(Value::as_str) {
                Some("Polygon") => Some(1),
                Some("MultiPolygon") => Some(2),
                _ => None,
            };
            match (depth, o.get("coordinates")) {
                (Some(1), Some(Value::Array(rs))) => {
                    out.extend(rs.iter().filter_map(Value::as_array));
                }
                (Some(2), Some(Value::Array(ps))) => out.extend(
                    ps.iter()
                        .filter_map(Value::as_array)
                        .flatten()
                        .filter_map(Value::as_array),
                ),
                _ => o.values().for_each(|x| rings(x, out)),
            }
        }
        Value::Array(a) => a.iter().for_each(|x| rings(x, out)),
        _ => {}
    }
}

fuzz_target!(|bytes: &[u8]| {
    let Some((&pick, bytes)) = bytes.split_first() else {
        return;
    };
    let opts = SmoothOptions::default().through(pick & 2 != 0);
    let independent = pick & 1 != 0;
    match document::smooth(bytes, &opts, independent) {
        Ok(out) => {
            if out.get("type").and_then(Value::as_str) == Some("Topology") {
                assert!(finite(&out["arcs"]), "non-finite arcs");
                return;
            }
            let mut rs = Vec::new();
            rings(&out, &mut rs);
            for r in rs {
                assert!(finite(&Value::Array(r.clone())), "non-finite ring");
                assert!(
                    r.len() >= 4 && r.first() == r.last(),
                    "a ring of {} positions, or not closed: {r:?}",
                    r.len()
                );
            }
        }
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with(NAME), "{m}");
            assert!(!m.contains('\n'), "{m}");
        }
    }
});
