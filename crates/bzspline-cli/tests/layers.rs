//! GeoPackage, FlatGeobuf and GeoParquet beside Shapefiles: every coverage
//! the tests use goes through every format's writer and reader with its
//! geometry bit for bit and its fields and CRS kept; smoothing a layer file
//! gives what smoothing its features as GeoJSON gives; GDAL (the outside
//! judge) reads every file the command writes in the formats its build
//! reads, and the command reads GDAL's (GeoParquet, which Debian's GDAL
//! does not read, is judged by geopandas and pyarrow in the Python tests);
//! bad files are refused with one line naming the file, and nothing is
//! written.

mod common;

use std::path::Path;

use bzspline_io::files;
use bzspline_io::input::InputFormat;
use bzspline_io::smooth::job::Output;
use common::gdal::{close, fields, gdal, gdal_features, info, numbers, path, polygons_of};
use common::{run, succeeds};
use serde_json::{json, Value};

const FORMATS: [(&str, InputFormat, Output); 4] = [
    ("gpkg", InputFormat::Geopackage, Output::Geopackage),
    ("fgb", InputFormat::Flatgeobuf, Output::Flatgeobuf),
    ("shp", InputFormat::Shapefile, Output::Shapefile),
    ("parquet", InputFormat::Geoparquet, Output::Geoparquet),
];

fn read_json(file: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap()
}

/// A feature as compared across formats: its geometry (every number as
/// the double it is, members in one order) and properties (a GeoJSON
/// feature's `id` is no field of theirs; a table holds every field for
/// every feature, so a missing property reads back as null).
fn essence(f: &Value) -> Value {
    fn doubles(v: &Value) -> Value {
        match v {
            Value::Number(n) => json!(n.as_f64().unwrap()),
            Value::Array(a) => Value::Array(a.iter().map(doubles).collect()),
            other => other.clone(),
        }
    }
    let g = &f["geometry"];
    let geometry = if g.is_null() {
        Value::Null
    } else {
        json!({"type": g["type"], "coordinates": doubles(&g["coordinates"])})
    };
    let mut properties = f["properties"].as_object().cloned().unwrap_or_default();
    properties.retain(|_, v| !v.is_null());
    json!({"geometry": geometry, "properties": properties})
}

/// The features in an order of their own (FlatGeobuf's spatial index
/// orders features along a Hilbert curve).
fn sorted(features: &[Value]) -> Vec<Value> {
    let mut v: Vec<Value> = features.iter().map(essence).collect();
    v.sort_by_key(Value::to_string);
    v
}

/// Asserts that two lists hold the same features in any order, showing the
/// first that differ.
fn same_features(a: &[Value], b: &[Value], what: &str) {
    let (a, b) = (sorted(a), sorted(b));
    assert_eq!(a.len(), b.len(), "{what}: feature count");
    if let Some((x, y)) = a.iter().zip(&b).find(|(x, y)| x != y) {
        let cut = |v: &Value| v.to_string().chars().take(400).collect::<String>();
        panic!("{what}: features differ:\n{}\n{}", cut(x), cut(y));
    }
}

/// Asserts that two lists hold the same features in the same order.
fn same_order(a: &[Value], b: &[Value], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: feature count");
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let (x, y) = (essence(x), essence(y));
        if x != y {
            let cut = |v: &Value| v.to_string().chars().take(400).collect::<String>();
            panic!(
                "{what}: feature {i} differs:\n{}\n{}\n{}\n{}",
                cut(&x["geometry"]),
                cut(&y["geometry"]),
                x["properties"],
                y["properties"]
            );
        }
    }
}

/// Whether any position of a geometry has z.
fn has_z(g: &Value) -> bool {
    fn walk(c: &Value) -> bool {
        match c.as_array() {
            Some(a) if a.first().is_some_and(Value::is_number) => a.len() >= 3,
            Some(a) => a.iter().any(walk),
            None => false,
        }
    }
    walk(&g["coordinates"])
}

/// A feature with z = 0 added to every position of two numbers.
fn pad_z(f: &Value) -> Value {
    fn pad(c: &Value) -> Value {
        match c.as_array() {
            Some(a) if a.len() == 2 && a[0].is_number() => json!([a[0], a[1], 0.0]),
            Some(a) => Value::Array(a.iter().map(pad).collect()),
            None => c.clone(),
        }
    }
    let mut f = f.clone();
    if f["geometry"].is_null() {
        return f;
    }
    let c = pad(&f["geometry"]["coordinates"]);
    f["geometry"]["coordinates"] = c;
    f
}

/// A polygon's rings with each ring's positions in order of x, then y: a
/// Shapefile turns outer rings clockwise and holes counter-clockwise.
fn unoriented(g: &Value) -> Vec<Vec<[u64; 2]>> {
    let mut rings = Vec::new();
    let mut walk = |r: &Value| {
        let mut pts: Vec<[u64; 2]> = numbers(r)
            .chunks(2)
            .map(|p| [p[0].to_bits(), p[1].to_bits()])
            .collect();
        pts.sort_unstable();
        rings.push(pts);
    };
    match g["type"].as_str() {
        Some("Polygon") => g["coordinates"]
            .as_array()
            .unwrap()
            .iter()
            .for_each(&mut walk),
        Some("MultiPolygon") => g["coordinates"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|p| p.as_array().unwrap())
            .for_each(&mut walk),
        _ => walk(&g["coordinates"]),
    }
    rings
}

/// The coverages the tests use, and with `BZSPLINE_ATLAS` the public ones.
fn coverages() -> Vec<(String, Value)> {
    let mut out: Vec<(String, Value)> = ["countries", "mosaic", "shapes"]
        .iter()
        .map(|n| {
            let f = common::fixture(&format!("{n}.geojson"));
            ((*n).to_owned(), read_json(&f.display().to_string()))
        })
        .collect();
    if let Some(dir) = std::env::var_os("BZSPLINE_ATLAS").filter(|d| !d.is_empty()) {
        for n in ["countries", "states", "counties"] {
            let f = Path::new(&dir).join(format!("{n}.geojson"));
            out.push((format!("atlas {n}"), read_json(&f.display().to_string())));
        }
    }
    out
}

#[test]
fn every_coverage_round_trips_through_every_format() {
    let dir = tempfile::tempdir().unwrap();
    for (name, doc) in coverages() {
        let features = doc["features"].as_array().unwrap();
        let kinds: std::collections::BTreeSet<&str> = features
            .iter()
            .filter_map(|f| f["geometry"]["type"].as_str())
            .map(|t| t.trim_start_matches("Multi"))
            .collect();
        for (ext, format, output) in FORMATS {
            if ext == "shp" && kinds.len() > 1 {
                continue; // a Shapefile holds one kind of geometry
            }
            let file = path(dir.path(), &format!("layer.{ext}"));
            files::write(Path::new(&file), output, &doc, None)
                .unwrap_or_else(|e| panic!("{name} as {ext}: {e}"));
            let back = files::read(Path::new(&file), format, None, u64::MAX).unwrap();
            let back_fc = back.features.to_value();
            let got = back_fc["features"].as_array().unwrap();
            assert_eq!(got.len(), features.len(), "{name} as {ext}");
            match ext {
                "gpkg" | "parquet" => {
                    // z for every position of a geometry or none: the 2D
                    // members of a geometry with z come back with z = 0.
                    let want: Vec<Value> = features
                        .iter()
                        .map(|f| {
                            if has_z(&f["geometry"]) {
                                pad_z(f)
                            } else {
                                f.clone()
                            }
                        })
                        .collect();
                    same_order(&want, got, &format!("{name} as {ext}"));
                }
                "fgb" => {
                    // z for every position or none: 2D geometries of a
                    // layer with z come back with z = 0.
                    let z = features.iter().any(|f| has_z(&f["geometry"]));
                    let want: Vec<Value> = features
                        .iter()
                        .map(|f| if z { pad_z(f) } else { f.clone() })
                        .collect();
                    same_features(&want, got, &format!("{name} as {ext}"));
                }
                _ => {
                    for (i, (a, b)) in features.iter().zip(got).enumerate() {
                        assert_eq!(
                            unoriented(&a["geometry"]),
                            unoriented(&b["geometry"]),
                            "{name} as {ext}: feature {i}"
                        );
                        assert_eq!(
                            essence(a)["properties"],
                            essence(b)["properties"],
                            "{name}: feature {i}"
                        );
                    }
                }
            }
            let crs = back.schema.crs.as_ref().and_then(|c| c.epsg());
            assert_eq!(crs, Some(4326), "{name} as {ext}: CRS");
            // Written on from what was read, into each other format: the
            // fields and the CRS travel.
            for (ext2, format2, output2) in FORMATS {
                if ext2 == ext || (ext2 == "shp" && kinds.len() > 1) {
                    continue;
                }
                let file2 = path(dir.path(), &format!("again.{ext2}"));
                files::write(
                    Path::new(&file2),
                    output2,
                    &back.features,
                    Some(&back.schema),
                )
                .unwrap_or_else(|e| panic!("{name} from {ext} to {ext2}: {e}"));
                let again = files::read(Path::new(&file2), format2, None, u64::MAX).unwrap();
                let names = |s: &bzspline_io::layer::Schema| -> Vec<String> {
                    s.fields.iter().map(|f| f.name.clone()).collect()
                };
                assert_eq!(
                    names(&again.schema),
                    names(&back.schema),
                    "{name}: {ext} to {ext2}"
                );
                let kinds = |s: &bzspline_io::layer::Schema| -> Vec<_> {
                    s.fields.iter().map(|f| f.kind).collect()
                };
                assert_eq!(
                    kinds(&again.schema),
                    kinds(&back.schema),
                    "{name}: {ext} to {ext2}"
                );
                let crs = again.schema.crs.as_ref().and_then(|c| c.epsg());
                assert_eq!(crs, Some(4326), "{name}: {ext} to {ext2}: CRS");
            }
        }
    }
}

#[test]
fn smoothing_a_layer_file_gives_what_its_geojson_gives() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["countries", "mosaic"] {
        let doc = read_json(&polygons_of(dir.path(), name));
        for (ext, format, output) in FORMATS {
            let file = path(dir.path(), &format!("{name}.{ext}"));
            files::write(Path::new(&file), output, &doc, None).unwrap();
            // Its GeoJSON: the same features, in the file's order.
            let layer = files::read(Path::new(&file), format, None, u64::MAX).unwrap();
            let geojson = path(dir.path(), &format!("{name}-{ext}.geojson"));
            std::fs::write(&geojson, layer.features.to_value().to_string()).unwrap();
            // The same text: a layer's features are written one at a time,
            // a document's as one tree.
            let a = succeeds(&["smooth", &file, "--tolerance", "0.01"]);
            let b = succeeds(&["smooth", &geojson, "--tolerance", "0.01"]);
            assert!(a == b, "{name} as {ext}: the outputs differ");
            let each = |f: &str| succeeds(&["smooth", f, "--tolerance", "0.01", "--independent"]);
            assert!(
                each(&file) == each(&geojson),
                "{name} as {ext}: --independent: the outputs differ"
            );
            let a: Value = serde_json::from_str(&a).unwrap();
            // Written to a file of the same format, then read: the same.
            let out = path(dir.path(), &format!("out.{ext}"));
            succeeds(&["smooth", &file, "--tolerance", "0.01", "-o", &out]);
            let back = files::read(Path::new(&out), format, None, u64::MAX).unwrap();
            let back = back.features.to_value();
            let (a, b) = (
                a["features"].as_array().unwrap(),
                back["features"].as_array().unwrap(),
            );
            match ext {
                "fgb" => same_features(a, b, &format!("{name} as {ext}")),
                "gpkg" | "parquet" => same_order(a, b, &format!("{name} as {ext}")),
                _ => {
                    for (i, (f, g)) in a.iter().zip(b).enumerate() {
                        assert_eq!(
                            unoriented(&f["geometry"]),
                            unoriented(&g["geometry"]),
                            "{name}: {i}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)"
)]
fn gdal_reads_what_we_write_and_we_read_what_gdal_writes() {
    for name in ["mosaic", "countries"] {
        let dir = tempfile::tempdir().unwrap();
        let cells = polygons_of(dir.path(), name);
        for (ext, driver) in [("gpkg", "GPKG"), ("fgb", "FlatGeobuf")] {
            // GDAL makes the layer, and the GeoJSON of exactly its features.
            let input = path(dir.path(), &format!("{name}.{ext}"));
            gdal("ogr2ogr", &["-f", driver, "-nln", name, &input, &cells]);
            let geojson = path(dir.path(), &format!("{name}-{ext}.geojson"));
            gdal(
                "ogr2ogr",
                &[
                    "-f",
                    "GeoJSON",
                    "-lco",
                    "SIGNIFICANT_FIGURES=17",
                    &geojson,
                    &input,
                ],
            );
            let ours: Value =
                serde_json::from_str(&succeeds(&["smooth", &geojson, "--tolerance", "0.01"]))
                    .unwrap();
            let ours = ours["features"].as_array().unwrap();
            for (ext2, format2, _) in FORMATS {
                if ext2 == "parquet" {
                    continue; // Debian's GDAL has no Parquet driver
                }
                let out = path(dir.path(), &format!("out.{ext2}"));
                succeeds(&["smooth", &input, "--tolerance", "0.01", "-o", &out]);
                let theirs = gdal_features(&out);
                let bits = files::read(Path::new(&out), format2, None, u64::MAX).unwrap();
                let bits = bits.features.to_value();
                let bits = bits["features"].as_array().unwrap();
                assert_eq!(theirs.len(), ours.len(), "{name}.{ext} to {ext2}: count");
                // GDAL's reading against ours, feature by feature in the
                // written file's order.
                for (i, (t, b)) in theirs.iter().zip(bits).enumerate() {
                    if ext2 == "shp" {
                        assert_eq!(
                            unoriented(&t["geometry"]).len(),
                            unoriented(&b["geometry"]).len()
                        );
                    } else {
                        assert!(
                            close(
                                &numbers(&t["geometry"]["coordinates"]),
                                &numbers(&b["geometry"]["coordinates"])
                            ),
                            "{name}.{ext} to {ext2}: GDAL reads feature {i} otherwise"
                        );
                    }
                    assert_eq!(
                        t["properties"], b["properties"],
                        "{name}.{ext} to {ext2}: {i}"
                    );
                }
                // Our reading of our file: exactly the smoothing of GDAL's
                // GeoJSON.
                if ext2 == "shp" {
                    for (i, (a, b)) in ours.iter().zip(bits).enumerate() {
                        assert_eq!(
                            unoriented(&a["geometry"]),
                            unoriented(&b["geometry"]),
                            "{i}"
                        );
                    }
                } else {
                    same_features(ours, bits, &format!("{name}.{ext} to {ext2}"));
                }
                let (before, after) = (info(&input), info(&out));
                assert!(
                    after.contains("WGS 84"),
                    "{name}.{ext} to {ext2}: no CRS in\n{after}"
                );
                assert!(
                    after.contains(&format!("Feature Count: {}", ours.len())),
                    "{after}"
                );
                if ext2 == ext {
                    assert_eq!(
                        fields(&before),
                        fields(&after),
                        "{name}.{ext}: fields changed"
                    );
                }
            }
        }
    }
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)"
)]
fn a_geopackage_of_several_layers_needs_one_chosen() {
    let dir = tempfile::tempdir().unwrap();
    let cells = polygons_of(dir.path(), "mosaic");
    let gpkg = path(dir.path(), "two.gpkg");
    gdal("ogr2ogr", &["-f", "GPKG", "-nln", "cells", &gpkg, &cells]);
    gdal("ogr2ogr", &["-update", "-nln", "more", &gpkg, &cells]);
    let out = path(dir.path(), "out.gpkg");
    let o = run(&["smooth", &gpkg, "-o", &out], None);
    assert_eq!(o.code, 1, "{}", o.stderr);
    assert!(
        o.stderr.contains(
            "two.gpkg: holds 2 feature layers (cells, more): choose one with --layer NAME"
        ),
        "{}",
        o.stderr
    );
    assert!(!Path::new(&out).exists());
    succeeds(&["smooth", &gpkg, "--layer", "more", "-o", &out]);
    let summary = info(&out);
    assert!(summary.contains("Layer name: more"), "{summary}");
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's ogr2ogr and ogrinfo (apt-get install gdal-bin)"
)]
fn geopackages_carry_a_spatial_index_that_gdal_uses_and_keeps() {
    let dir = tempfile::tempdir().unwrap();
    let cells = polygons_of(dir.path(), "mosaic");
    let doc = read_json(&cells);
    let gpkg = path(dir.path(), "cells.gpkg");
    succeeds(&["smooth", &cells, "-o", &gpkg]);
    let back = files::read(Path::new(&gpkg), InputFormat::Geopackage, None, u64::MAX).unwrap();
    let t = back.schema.name.clone();
    let sql = |q: &str| gdal("ogrinfo", &["-ro", &gpkg, "-sql", q]);
    assert!(
        sql(&format!("SELECT HasSpatialIndex('{t}', 'geom')"))
            .contains("HasSpatialIndex (Integer) = 1"),
        "GDAL sees no spatial index"
    );
    // A window's features through the index, against every feature's
    // envelope checked by brute force.
    let back = back.features.to_value();
    let features = back["features"].as_array().unwrap();
    assert_eq!(features.len(), doc["features"].as_array().unwrap().len());
    let (x0, y0, x1, y1) = (0.3, 0.2, 0.9, 0.6);
    let want = features
        .iter()
        .filter(|f| {
            let p = numbers(&f["geometry"]["coordinates"]);
            let (xs, ys): (Vec<f64>, Vec<f64>) = p.chunks(2).map(|c| (c[0], c[1])).unzip();
            let (a, b) = (
                xs.iter().copied().fold(f64::INFINITY, f64::min),
                xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            );
            let (c, d) = (
                ys.iter().copied().fold(f64::INFINITY, f64::min),
                ys.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            );
            a <= x1 && b >= x0 && c <= y1 && d >= y0
        })
        .count();
    let window = sql(&format!(
        "SELECT COUNT(*) AS n FROM \"rtree_{t}_geom\" WHERE maxx >= {x0} AND minx <= {x1} AND maxy >= {y0} AND miny <= {y1}"
    ));
    assert!(
        window.contains(&format!("n (Integer) = {want}")),
        "{window}\nwant {want}"
    );
    assert!(want > 0 && want < features.len());
    // GDAL's edits keep it in step through the triggers.
    gdal(
        "ogrinfo",
        &[
            &gpkg,
            "-sql",
            "UPDATE cells SET geom = (SELECT geom FROM cells WHERE fid = 2) WHERE fid = 1",
        ],
    );
    gdal(
        "ogrinfo",
        &[&gpkg, "-sql", "DELETE FROM cells WHERE fid = 3"],
    );
    let rows = sql(
        "SELECT id, minx, maxx, miny, maxy FROM rtree_cells_geom WHERE id IN (1, 2, 3) ORDER BY id",
    );
    let boxes: Vec<f64> = rows
        .lines()
        .filter(|l| l.contains(" = ") && !l.contains("id ("))
        .map(|l| l.split(" = ").nth(1).unwrap().trim().parse().unwrap())
        .collect();
    assert_eq!(boxes.len(), 8, "{rows}");
    // The index holds 32-bit floats, rounded outward by each SQLite.
    for k in 0..4 {
        assert!((boxes[k] - boxes[k + 4]).abs() < 1e-6, "{rows}");
    }
    assert!(!rows.contains("id (Integer64) = 3"), "{rows}");
}

#[test]
fn fit_reads_the_first_line_of_a_layer_file() {
    let dir = tempfile::tempdir().unwrap();
    let doc = json!({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "road"},
        "geometry": {"type": "LineString", "coordinates": [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]}}]});
    let geojson = path(dir.path(), "road.geojson");
    std::fs::write(&geojson, doc.to_string()).unwrap();
    let want = succeeds(&["fit", &geojson, "--curve"]);
    for (ext, _, output) in FORMATS {
        let file = path(dir.path(), &format!("road.{ext}"));
        files::write(Path::new(&file), output, &doc, None).unwrap();
        assert_eq!(succeeds(&["fit", &file, "--curve"]), want, "{ext}");
        // Known by its content too.
        let hidden = path(dir.path(), &format!("road-{ext}.bin"));
        if ext != "shp" {
            std::fs::copy(&file, &hidden).unwrap();
            assert_eq!(
                succeeds(&["fit", &hidden, "--curve"]),
                want,
                "{ext} by content"
            );
        }
    }
}

#[test]
fn bad_layer_files_are_refused_naming_the_file_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let cells = read_json(&polygons_of(dir.path(), "mosaic"));
    let out = path(dir.path(), "out.gpkg");
    std::fs::write(&out, "what was there").unwrap();
    let refused = |args: &[&str], code: i32, want: &str| {
        let o = run(args, None);
        assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains(want), "{args:?}: {}", o.stderr);
        assert_eq!(o.stderr.trim().lines().count(), 1, "{}", o.stderr);
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "what was there");
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| n.starts_with(".bzspline"))
            .collect();
        assert!(left.is_empty(), "left behind: {left:?}");
    };
    let gpkg = path(dir.path(), "cells.gpkg");
    files::write(Path::new(&gpkg), Output::Geopackage, &cells, None).unwrap();
    let fgb = path(dir.path(), "cells.fgb");
    files::write(Path::new(&fgb), Output::Flatgeobuf, &cells, None).unwrap();
    let parquet = path(dir.path(), "cells.parquet");
    files::write(Path::new(&parquet), Output::Geoparquet, &cells, None).unwrap();
    refused(
        &["smooth", &gpkg, "--layer", "roads", "-o", &out],
        1,
        "cells.gpkg: no layer \"roads\"; its feature layers: cells",
    );
    for (file, what) in [(&gpkg, "gpkg"), (&fgb, "fgb"), (&parquet, "parquet")] {
        let bytes = std::fs::read(file).unwrap();
        let cut = path(dir.path(), &format!("cut.{what}"));
        std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
        refused(&["smooth", &cut, "-o", &out], 1, &format!("cut.{what}"));
        refused(
            &["smooth", file, "--max-bytes", "100", "-o", &out],
            1,
            "larger than 100 bytes (--max-bytes)",
        );
    }
    let text = path(dir.path(), "notes.gpkg");
    std::fs::write(
        &text,
        "not a database at all, but long enough to be read as one",
    )
    .unwrap();
    refused(
        &["smooth", &text, "-o", &out],
        1,
        "notes.gpkg: not a GeoPackage",
    );
    refused(
        &[
            "smooth",
            &common::fixture("mosaic.geojson").display().to_string(),
            "--layer",
            "x",
            "-o",
            &out,
        ],
        2,
        "--layer chooses a layer of a GeoPackage",
    );
    refused(
        &["smooth", &gpkg, "--output-format", "geopackage"],
        2,
        "give -o NAME.gpkg",
    );
    // A property that its field cannot hold: named, and nothing written.
    let mixed = json!({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"n": 1}, "geometry": {"type": "Point", "coordinates": [0.0, 0.0]}},
    ]});
    let schema = files::read(Path::new(&gpkg), InputFormat::Geopackage, None, u64::MAX)
        .unwrap()
        .schema;
    let mut wrong = schema.clone();
    wrong.fields = vec![bzspline_io::layer::Field {
        name: "n".into(),
        kind: bzspline_io::layer::FieldKind::Boolean,
        width: None,
        decimals: None,
    }];
    for output in [Output::Geopackage, Output::Flatgeobuf, Output::Geoparquet] {
        let e = files::write(Path::new(&out), output, &mixed, Some(&wrong))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("feature 0: field \"n\": 1 is not true or false"),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "what was there");
    }
}

#[test]
#[cfg_attr(
    not(gdal),
    ignore = "needs GDAL's gdalsrsinfo (apt-get install gdal-bin)"
)]
fn a_crs_given_as_projjson_gets_a_prj_that_gdal_reads_as_the_same_crs() {
    let dir = tempfile::tempdir().unwrap();
    let shp = path(dir.path(), "x.shp");
    let countries = common::fixture("countries.geojson").display().to_string();
    succeeds(&["smooth", &countries, "-o", &shp]);
    let prj = path(dir.path(), "x.prj");
    // Geographic and projected, in metres, US feet and grads, on datums and
    // datum ensembles, by every method of the table.
    let codes = [
        4269, 4258, 4807, 7844, 32633, 2154, 27700, 3035, 5070, 2056, 3413, 3031, 27572, 6933,
        2193, 3395, 2263, 31467, 28992, 3577, 3005, 5514,
    ];
    // Krovak (EPSG:5514) is not among the methods written: no .prj, as
    // before, rather than a wrong one.
    let unwritten = [5514];
    for code in codes {
        let epsg = format!("EPSG:{code}");
        let projjson: Value =
            serde_json::from_str(&gdal("gdalsrsinfo", &["-o", "PROJJSON", &epsg])).unwrap();
        let prj_text = bzspline_io::layer::Crs::from_projjson(&projjson).prj();
        assert_eq!(prj_text.is_none(), unwritten.contains(&code), "{epsg}");
        let Some(text) = prj_text else {
            continue;
        };
        std::fs::write(&prj, &text).unwrap();
        // Read as GDAL's Shapefile driver (and so QGIS) reads a .prj: the
        // same datum, ellipsoid, projection and units, found as the same
        // EPSG code (GDAL may say it is less than sure of the match: it
        // finds no code at all in the .prj of ESRI's WKT it writes itself).
        assert_eq!(
            gdal("gdalsrsinfo", &["-o", "proj4", &shp]).trim(),
            gdal("gdalsrsinfo", &["-o", "proj4", &epsg]).trim(),
            "{epsg} as proj4, from\n{text}"
        );
        let found = gdal("gdalsrsinfo", &["-o", "epsg", &shp]);
        let last = found.lines().rfind(|l| !l.trim().is_empty());
        assert_eq!(last, Some(epsg.as_str()), "{found}\nfrom\n{text}");
    }
}
