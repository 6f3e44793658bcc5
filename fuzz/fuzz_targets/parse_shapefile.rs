//! The command's Shapefile reader on arbitrary bytes, split into a `.shp`,
//! a `.shx` and a `.dbf` by two lengths (16-bit, little-endian) in the first
//! four bytes, then the writer on what was
//! read: never a panic; a refusal is one line naming a file of the layer; an
//! accepted layer has finite coordinates, and what it writes (when it holds
//! one kind of geometry) reads back and writes again to the same files.
#![no_main]

use bzspline_fuzz::{finite, shp};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let [a0, a1, b0, b1, rest @ ..] = bytes else {
        return;
    };
    let i = usize::from(u16::from_le_bytes([*a0, *a1])).min(rest.len());
    let j = (i + usize::from(u16::from_le_bytes([*b0, *b1]))).min(rest.len());
    let (shp_bytes, shx, dbf) = (&rest[..i], &rest[i..j], &rest[j..]);
    let layer = match shp::read_parts("t.shp", shp_bytes, shx, dbf, None) {
        Ok(l) => l,
        Err(e) => {
            let m = e.to_string();
            assert!(
                ["t.shp", "t.shx", "t.dbf"].iter().any(|f| m.starts_with(f)),
                "{m}"
            );
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
            g.is_null() || finite(&g["coordinates"]),
            "non-finite coordinates read"
        );
    }
    // What is written reads back, and writes again to the same files: the
    // first write closes open rings and orders them as their kind wants.
    if let Ok(files) = shp::write(&layer.features, Some(&layer.schema)) {
        let get = |files: &shp::Files, ext: &str| {
            files
                .iter()
                .find(|(e, _)| *e == ext)
                .expect("written")
                .1
                .clone()
        };
        let again = shp::read_parts(
            "t.shp",
            &get(&files, "shp"),
            &get(&files, "shx"),
            &get(&files, "dbf"),
            Some("UTF-8"),
        )
        .expect("what was written reads back");
        let twice =
            shp::write(&again.features, Some(&again.schema)).expect("what was read back writes");
        for ext in ["shp", "shx"] {
            assert!(
                get(&files, ext) == get(&twice, ext),
                "a second write changed the .{ext}"
            );
        }
    }
});
