//! `bzspline smooth` (and `fit`) on ESRI Shapefiles: smoothing a Shapefile
//! gives what smoothing the same features as GeoJSON gives, with the fields
//! and the coordinate system kept; every file the command writes is read by
//! GDAL (`ogrinfo`, `ogr2ogr`: the outside judge, from Debian's `gdal-bin`);
//! bad layers are refused with one line naming the file, and nothing is
//! written. The tests that need GDAL are ignored without it.

mod common;

use std::path::Path;

use common::gdal::{close, fields, gdal, gdal_features, info, numbers, path, polygons_of};
use common::{run, succeeds};
use serde_json::Value;

fn fixture(name: &str) -> String {
    common::fixture(name).display().to_string()
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)"
)]
fn a_shapefile_smooths_as_its_geojson_and_gdal_reads_the_result() {
    for name in ["mosaic", "countries"] {
        let dir = tempfile::tempdir().unwrap();
        // GDAL makes the Shapefile, and the GeoJSON of exactly its rings.
        let shp = path(dir.path(), &format!("{name}.shp"));
        gdal(
            "ogr2ogr",
            &["-f", "ESRI Shapefile", &shp, &polygons_of(dir.path(), name)],
        );
        let geojson = path(dir.path(), &format!("{name}.geojson"));
        gdal(
            "ogr2ogr",
            &[
                "-f",
                "GeoJSON",
                "-lco",
                "SIGNIFICANT_FIGURES=17",
                &geojson,
                &shp,
            ],
        );
        let out = path(dir.path(), "out.shp");
        succeeds(&["smooth", &shp, "--tolerance", "0.01", "-o", &out]);
        let ours: Value =
            serde_json::from_str(&succeeds(&["smooth", &geojson, "--tolerance", "0.01"])).unwrap();
        let ours = ours["features"].as_array().unwrap();
        let theirs = gdal_features(&out);
        let bits = bzspline_io::shp::read(Path::new(&out), u64::MAX)
            .unwrap()
            .features
            .to_value();
        let bits = bits["features"].as_array().unwrap();
        assert_eq!(theirs.len(), ours.len(), "{name}: feature count");
        for (i, a) in ours.iter().enumerate() {
            let want = numbers(&a["geometry"]["coordinates"]);
            // Bit for bit, through our reader; and GDAL reads the same.
            assert_eq!(
                numbers(&bits[i]["geometry"]["coordinates"]),
                want,
                "{name}: feature {i}"
            );
            assert!(
                close(&numbers(&theirs[i]["geometry"]["coordinates"]), &want),
                "{name}: GDAL reads feature {i} otherwise"
            );
            assert_eq!(
                a["geometry"]["type"], theirs[i]["geometry"]["type"],
                "{name}: feature {i}'s type"
            );
            assert_eq!(
                a["properties"], theirs[i]["properties"],
                "{name}: feature {i}'s fields"
            );
        }
        // The fields and the coordinate system are the input's.
        let (before, after) = (info(&shp), info(&out));
        assert_eq!(fields(&before), fields(&after), "{name}: fields changed");
        assert!(after.contains("WGS 84"), "{name}: no CRS in\n{after}");
        assert!(
            after.contains(&format!("Feature Count: {}", ours.len())),
            "{after}"
        );
    }
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)"
)]
fn geojson_written_as_a_shapefile_is_read_by_gdal() {
    let dir = tempfile::tempdir().unwrap();
    let cells = polygons_of(dir.path(), "mosaic");
    let out = path(dir.path(), "shapes.shp");
    succeeds(&["smooth", &cells, "--output-format", "shapefile", "-o", &out]);
    let info = info(&out);
    let input: Value = serde_json::from_str(&std::fs::read_to_string(&cells).unwrap()).unwrap();
    let n = input["features"].as_array().unwrap().len();
    assert!(info.contains(&format!("Feature Count: {n}")), "{info}");
    assert!(info.contains("Geometry: Polygon"), "{info}");
    assert!(info.contains("WGS 84"), "{info}");
    let ours: Value = serde_json::from_str(&succeeds(&["smooth", &cells])).unwrap();
    for (i, (a, b)) in ours["features"]
        .as_array()
        .unwrap()
        .iter()
        .zip(gdal_features(&out))
        .enumerate()
    {
        // A Shapefile turns outer rings clockwise: the same positions, maybe
        // in the other direction, so compared in order of x, then y.
        let ring = |g: &Value| -> Vec<[f64; 2]> {
            let mut r: Vec<[f64; 2]> = numbers(&g["coordinates"][0])
                .chunks(2)
                .map(|p| [p[0], p[1]])
                .collect();
            r.sort_by(|p, q| p.partial_cmp(q).unwrap());
            r
        };
        let (ra, rb) = (ring(&a["geometry"]), ring(&b["geometry"]));
        assert!(close(ra.as_flattened(), rb.as_flattened()), "feature {i}");
    }
}

#[test]
fn fit_reads_the_first_line_of_a_shapefile() {
    let dir = tempfile::tempdir().unwrap();
    let doc = r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"road"},"geometry":{"type":"LineString","coordinates":[[0,0],[1,2],[3,2],[4,0]]}}]}"#;
    let geojson = path(dir.path(), "road.geojson");
    std::fs::write(&geojson, doc).unwrap();
    let shp = path(dir.path(), "road.shp");
    // Through the identity: a line's smoothing with --through keeps every
    // vertex, so write it with a tolerance that adds none between.
    succeeds(&[
        "smooth",
        &geojson,
        "--through",
        "--tolerance",
        "1e9",
        "-o",
        &shp,
    ]);
    assert_eq!(
        succeeds(&["fit", &shp, "--curve"]),
        succeeds(&["fit", &geojson, "--curve"])
    );
}

#[test]
fn bad_layers_are_refused_naming_the_file_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let shp = path(dir.path(), "cells.shp");
    succeeds(&["smooth", &polygons_of(dir.path(), "mosaic"), "-o", &shp]);
    let out = path(dir.path(), "out.shp");
    let refused = |args: &[&str], code: i32, want: &str| {
        let o = run(args, None);
        assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains(want), "{args:?}: {}", o.stderr);
        assert_eq!(o.stderr.trim().lines().count(), 1, "{}", o.stderr);
        for ext in ["shp", "shx", "dbf", "prj", "cpg"] {
            assert!(
                !dir.path().join(format!("out.{ext}")).exists(),
                "out.{ext} was written"
            );
        }
    };
    // A .dbf of another layer, with fewer records.
    let other = path(dir.path(), "one.shp");
    let one = r#"{"type":"Feature","properties":{"a":1},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}"#;
    let one_path = path(dir.path(), "one.geojson");
    std::fs::write(
        &one_path,
        format!(r#"{{"type":"FeatureCollection","features":[{one}]}}"#),
    )
    .unwrap();
    succeeds(&["smooth", &one_path, "-o", &other]);
    let mixed = path(dir.path(), "mixed.shp");
    std::fs::copy(&shp, &mixed).unwrap();
    std::fs::copy(dir.path().join("cells.shx"), dir.path().join("mixed.shx")).unwrap();
    std::fs::copy(dir.path().join("one.dbf"), dir.path().join("mixed.dbf")).unwrap();
    refused(&["smooth", &mixed, "-o", &out], 1, "records in");
    // Without its .dbf.
    std::fs::remove_file(dir.path().join("mixed.dbf")).unwrap();
    refused(&["smooth", &mixed, "-o", &out], 1, "mixed.shp: its .dbf");
    // Truncated.
    let cut = path(dir.path(), "cut.shp");
    let bytes = std::fs::read(&shp).unwrap();
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    std::fs::copy(dir.path().join("cells.shx"), dir.path().join("cut.shx")).unwrap();
    std::fs::copy(dir.path().join("cells.dbf"), dir.path().join("cut.dbf")).unwrap();
    refused(&["smooth", &cut, "-o", &out], 1, "cut.shp");
    // Every file of the layer is bounded by --max-bytes.
    refused(
        &["smooth", &shp, "--max-bytes", "200", "-o", &out],
        1,
        "larger than 200 bytes (--max-bytes)",
    );
    // A Shapefile needs a name to be written to.
    refused(
        &["smooth", &shp, "--output-format", "shapefile"],
        2,
        "give -o NAME.shp",
    );
    // Lines and polygons in one layer cannot be written as one Shapefile.
    refused(
        &["smooth", &fixture("shapes.geojson"), "-o", &out],
        1,
        "a Shapefile holds one kind of geometry",
    );
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)"
)]
fn a_latin_1_table_is_read_in_the_code_page_its_cpg_names() {
    let dir = tempfile::tempdir().unwrap();
    let geojson = path(dir.path(), "towns.geojson");
    std::fs::write(
        &geojson,
        r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"Zürich"},"geometry":{"type":"LineString","coordinates":[[8.5,47.3],[8.6,47.4],[8.55,47.45]]}}]}"#,
    )
    .unwrap();
    let shp = path(dir.path(), "towns.shp");
    gdal(
        "ogr2ogr",
        &[
            "-f",
            "ESRI Shapefile",
            "-lco",
            "ENCODING=ISO-8859-1",
            &shp,
            &geojson,
        ],
    );
    let dbf = std::fs::read(dir.path().join("towns.dbf")).unwrap();
    assert!(
        dbf.windows(2).any(|w| w == b"Z\xfc"),
        "GDAL did not write Latin-1"
    );
    let out: Value = serde_json::from_str(&succeeds(&["smooth", &shp])).unwrap();
    assert_eq!(out["features"][0]["properties"]["name"], "Zürich");
    // Written back as UTF-8, with a .cpg that says so; GDAL reads it.
    let back = path(dir.path(), "back.shp");
    succeeds(&["smooth", &shp, "-o", &back]);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("back.cpg")).unwrap(),
        "UTF-8"
    );
    let read = gdal_features(&back);
    assert_eq!(read[0]["properties"]["name"], "Zürich");
}
