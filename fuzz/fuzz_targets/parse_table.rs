//! The command's CSV/TSV reader on arbitrary bytes, with the separator sniffed,
//! a tab and a semicolon: never a panic; accepted tables have rows of one width
//! and finite numbers; refusals are one line naming the file.
#![no_main]

use bzspline_fuzz::{check_points, input, MAX_POINTS};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    for delimiter in [None, Some(b'\t'), Some(b';')] {
        check_points(
            "t.csv",
            &input::parse_table("t.csv", bytes, delimiter, MAX_POINTS),
        );
    }
});
