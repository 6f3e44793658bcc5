//! The command's JSON reader on arbitrary bytes: never a panic; accepted
//! documents give rows of one width and finite numbers; refusals are one line
//! naming the file.
#![no_main]

use bzspline_fuzz::{check_points, input, MAX_POINTS};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    check_points("p.json", &input::parse_json("p.json", bytes, MAX_POINTS));
});
