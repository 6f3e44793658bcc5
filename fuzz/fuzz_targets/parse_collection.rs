//! A GeoJSON FeatureCollection read one feature at a time
//! (`Job::read_collection`, what `bzspline smooth` tries first) against the
//! whole document's path (`Job::document`) on arbitrary bytes: never a
//! panic; whatever the reader takes is JSON the document's path takes too,
//! and smoothing it gives the same text, or fails with the same message. The
//! first byte picks the options (coverage or each geometry, through).
#![no_main]

use bzspline_io::smooth::job::{Job, Settings};
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

fn compact(v: &Value) -> String {
    let mut out = Vec::new();
    bzspline_io::model::write_json_compact(&mut out, v).expect("writes to memory");
    String::from_utf8(out).expect("UTF-8")
}

fuzz_target!(|bytes: &[u8]| {
    let Some((&pick, bytes)) = bytes.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let mut settings = Settings::default();
    settings.independent = pick & 1 != 0;
    settings.options.through = pick & 2 != 0;
    let mut job = Job::new(settings.clone());
    let Some(mut c) = job.read_collection(text) else {
        return;
    };
    let streamed = job
        .collection("t", &mut c)
        .map(|()| {
            let mut out = Vec::new();
            c.write_geojson(&mut out).expect("writes to memory");
            String::from_utf8(out).expect("UTF-8")
        })
        .map_err(|e| format!("{e:#}"));
    let value: Value = serde_json::from_str(text).expect("what was read is JSON");
    let whole = Job::new(settings)
        .document("t", value)
        .map(|v| compact(&v))
        .map_err(|e| format!("{e:#}"));
    assert!(
        streamed == whole,
        "read a feature at a time:\n{streamed:?}\nas a document:\n{whole:?}"
    );
});
