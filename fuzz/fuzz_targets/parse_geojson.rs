//! The command's GeoJSON reader on arbitrary bytes: never a panic; accepted
//! documents give rows of one width and finite numbers; refusals are one line
//! naming the file.
#![no_main]

use bzspline_fuzz::{check_points, input, MAX_POINTS};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    check_points(
        "g.geojson",
        &input::parse_geojson_points("g.geojson", bytes, MAX_POINTS),
    );
});
