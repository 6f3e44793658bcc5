//! The editor server's `POST /api/fit` body on arbitrary bytes: never a panic;
//! a refusal is a 4xx with a message; an accepted request gives a fit whose
//! JSON holds no null where a number belongs (serde_json writes NaN and
//! infinities as null), with one segment per leg.
#![no_main]

use bzspline_fuzz::serve_api::{fit, parse, ParseLimits};
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

/// Every null in `v`, by path, except the fields that are null by design.
fn nulls(v: &Value, path: &mut String, found: &mut Vec<String>) {
    match v {
        Value::Null => found.push(path.clone()),
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                let len = path.len();
                path.push_str(&format!("[{i}]"));
                nulls(x, path, found);
                path.truncate(len);
            }
        }
        Value::Object(o) => {
            for (k, x) in o {
                // `svg_path` is null for a curve in space.
                if k == "svg_path" && path.is_empty() {
                    continue;
                }
                let len = path.len();
                path.push('.');
                path.push_str(k);
                nulls(x, path, found);
                path.truncate(len);
            }
        }
        Value::Number(n) => assert!(n.as_f64().is_some_and(f64::is_finite), "{path}: {n}"),
        _ => {}
    }
}

fuzz_target!(|bytes: &[u8]| {
    let limits = ParseLimits {
        max_points: 2_000,
        max_samples: 20_000,
    };
    let req = match parse(bytes, limits) {
        Ok(r) => r,
        Err(e) => {
            assert!(
                (400..500).contains(&e.status),
                "status {} for {}",
                e.status,
                e.message
            );
            assert!(
                !e.message.is_empty() && !e.message.contains('\n'),
                "{:?}",
                e.message
            );
            return;
        }
    };
    match fit(&req) {
        Ok(v) => {
            let mut found = Vec::new();
            nulls(&v, &mut String::new(), &mut found);
            assert!(found.is_empty(), "nulls at {found:?}");
            let knots = v["knots"].as_array().map_or(0, Vec::len);
            let segs = v["segments"].as_array().map_or(0, Vec::len);
            assert_eq!(segs + 1, knots, "one segment per leg");
        }
        Err(e) => {
            assert_eq!(e.status, 422, "{}", e.message);
            assert!(
                !e.message.is_empty() && !e.message.contains('\n'),
                "{:?}",
                e.message
            );
        }
    }
});
