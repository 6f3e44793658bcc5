//! `bzspline smooth` on coverages: shared borders in GeoJSON and TopoJSON,
//! TopoJSON in and out, the options, and bad TopoJSON.

mod common;

use std::collections::HashSet;

use common::{assert_data_error, fixture, ok, run};
use serde_json::Value;

type Seg = ((u64, u64), (u64, u64));

fn bits(p: &Value) -> (u64, u64) {
    let x = p[0].as_f64().unwrap() + 0.0;
    let y = p[1].as_f64().unwrap() + 0.0;
    (x.to_bits(), y.to_bits())
}

/// Every line and ring of a GeoJSON geometry, as positions.
fn chains(g: &Value) -> Vec<Vec<Value>> {
    let arr = |v: &Value| v.as_array().cloned().unwrap_or_default();
    match g["type"].as_str() {
        Some("LineString") => vec![arr(&g["coordinates"])],
        Some("Polygon" | "MultiLineString") => arr(&g["coordinates"]).iter().map(arr).collect(),
        Some("MultiPolygon") => arr(&g["coordinates"])
            .iter()
            .flat_map(|p| arr(p).iter().map(arr).collect::<Vec<_>>())
            .collect(),
        _ => vec![],
    }
}

fn segments(g: &Value) -> HashSet<Seg> {
    chains(g)
        .iter()
        .flat_map(|c| {
            c.windows(2)
                .map(|w| {
                    let (a, b) = (bits(&w[0]), bits(&w[1]));
                    (a.min(b), a.max(b))
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

fn features(text: &str) -> Vec<Value> {
    let v: Value = serde_json::from_str(text).unwrap();
    assert_eq!(v["type"], "FeatureCollection", "{text}");
    v["features"].as_array().unwrap().clone()
}

/// Pairs of features that share an edge.
fn neighbours(fs: &[Value]) -> Vec<(usize, usize)> {
    let segs: Vec<HashSet<Seg>> = fs.iter().map(|f| segments(&f["geometry"])).collect();
    let mut pairs = Vec::new();
    for i in 0..fs.len() {
        for j in i + 1..fs.len() {
            if !segs[i].is_disjoint(&segs[j]) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

fn input_features() -> Vec<Value> {
    features(&std::fs::read_to_string(fixture("mosaic.geojson")).unwrap())
}

#[test]
fn a_geojson_mosaic_keeps_every_shared_border() {
    let input = input_features();
    let pairs = neighbours(&input);
    assert!(pairs.len() >= 12, "{pairs:?}");
    let out = features(&ok(&["smooth", "mosaic.geojson", "--tolerance", "0.001"]));
    assert_eq!(out.len(), input.len());
    for (a, b) in &pairs {
        let (sa, sb) = (
            segments(&out[*a]["geometry"]),
            segments(&out[*b]["geometry"]),
        );
        assert!(
            !sa.is_disjoint(&sb),
            "features {a} and {b} lost their border"
        );
    }
    // Ids, properties, the collection's foreign member kept; rings closed.
    for (i, o) in input.iter().zip(&out) {
        assert_eq!(i["id"], o["id"]);
        assert_eq!(i["properties"], o["properties"]);
    }
    for f in &out[..9] {
        let ring = &chains(&f["geometry"])[0];
        assert!(ring.len() >= 4);
        assert_eq!(ring[0], ring[ring.len() - 1]);
    }
    // The road runs along a cell's border: it shares the smoothed border too.
    let road = segments(&out[9]["geometry"]);
    assert!(!road.is_disjoint(&segments(&out[3]["geometry"])));
    // Ring by ring, the borders part.
    let alone = features(&ok(&[
        "smooth",
        "mosaic.geojson",
        "--tolerance",
        "0.001",
        "--independent",
    ]));
    let kept = pairs
        .iter()
        .filter(|(a, b)| {
            !segments(&alone[*a]["geometry"]).is_disjoint(&segments(&alone[*b]["geometry"]))
        })
        .count();
    assert!(kept < pairs.len(), "--independent kept every border");
    // Each geometry on its own is each geometry as a coverage of its own:
    // smoothing the features one by one gives the same positions.
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fixture("mosaic.geojson")).unwrap()).unwrap();
    for (i, f) in doc["features"].as_array().unwrap().iter().enumerate() {
        let dir = tempfile::tempdir().unwrap();
        let one = dir.path().join("one.geojson");
        std::fs::write(&one, f.to_string()).unwrap();
        let alone_one = ok(&["smooth", one.to_str().unwrap(), "--tolerance", "0.001"]);
        let got: serde_json::Value = serde_json::from_str(&alone_one).unwrap();
        assert_eq!(got["geometry"], alone[i]["geometry"], "feature {i}");
    }
    // And it takes a keep-angle, as a coverage does.
    ok(&[
        "smooth",
        "mosaic.geojson",
        "--independent",
        "--keep-angle",
        "60",
    ]);
}

#[test]
fn a_collection_reads_alike_from_its_file_standard_input_and_after_a_bom() {
    let text = std::fs::read(fixture("mosaic.geojson")).unwrap();
    let args = ["smooth", "--tolerance", "0.001"];
    let from_file = ok(&[&args[..], &["mosaic.geojson"]].concat());
    let o = run(&[&args[..], &["-"]].concat(), Some(&text));
    assert_eq!(
        (o.code, o.stdout.as_str()),
        (0, from_file.as_str()),
        "{}",
        o.stderr
    );
    let dir = tempfile::tempdir().unwrap();
    let bom = dir.path().join("bom.geojson");
    std::fs::write(&bom, [&b"\xEF\xBB\xBF"[..], &text].concat()).unwrap();
    assert_eq!(
        ok(&[&args[..], &[bom.to_str().unwrap()]].concat()),
        from_file
    );
    // Declined from the file, read whole: the message names the line.
    let bad = dir.path().join("bad.geojson");
    // A byte of Latin-1 inside the first property's name.
    let mut latin1 = text.clone();
    let at = text
        .windows(12)
        .position(|w| w == b"\"properties\"")
        .unwrap()
        + 15;
    latin1.splice(at..at, *b"\xE9");
    let line = 1 + text[..at].iter().filter(|&&b| b == b'\n').count();
    let column = at
        - text[..at]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1)
        + 1;
    std::fs::write(&bad, latin1).unwrap();
    let name = bad.to_str().unwrap();
    assert_data_error(
        &[&args[..], &[name]].concat(),
        None,
        &[&format!(
            "{name}:{line}: not valid UTF-8 (byte 0xE9 at column {column})"
        )],
    );
}

#[test]
fn topojson_is_read_by_its_content_and_smoothed_on_its_arcs() {
    // mosaic.json is mosaic.geojson through topojson-server's geo2topo -q 1e5:
    // quantized, delta-encoded, with a transform, and named .json.
    let input = input_features();
    let out = features(&ok(&["smooth", "mosaic.json", "--tolerance", "0.001"]));
    assert_eq!(out.len(), input.len());
    for (i, o) in input.iter().zip(&out) {
        assert_eq!(i["id"], o["id"]);
        assert_eq!(i["properties"], o["properties"]);
        assert_eq!(i["geometry"]["type"], o["geometry"]["type"]);
    }
    for (a, b) in neighbours(&input) {
        assert!(
            !segments(&out[a]["geometry"]).is_disjoint(&segments(&out[b]["geometry"])),
            "features {a} and {b} lost their border"
        );
    }
    // The nodes (cell corners) are where the quantized input has them: within
    // one quantization step of the GeoJSON's.
    let corner = &chains(&input[4]["geometry"])[0][0];
    let ring = &chains(&out[4]["geometry"])[0];
    assert!(ring.iter().any(
        |p| (p[0].as_f64().unwrap() - corner[0].as_f64().unwrap()).abs() < 1e-4
            && (p[1].as_f64().unwrap() - corner[1].as_f64().unwrap()).abs() < 1e-4
    ));
}

#[test]
fn topojson_out_keeps_objects_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.topojson");
    let o = run(
        &[
            "smooth",
            "mosaic.json",
            "--tolerance",
            "0.001",
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    let topo: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let orig: Value =
        serde_json::from_str(&std::fs::read_to_string(fixture("mosaic.json")).unwrap()).unwrap();
    assert_eq!(topo["type"], "Topology");
    assert!(
        topo.get("transform").is_none(),
        "smoothed arcs are written unquantized"
    );
    assert_eq!(
        topo["objects"], orig["objects"],
        "the same objects, arcs, ids and properties"
    );
    assert_eq!(
        topo["arcs"].as_array().unwrap().len(),
        orig["arcs"].as_array().unwrap().len()
    );
    // The TopoJSON written, read as GeoJSON with no further smoothing than a
    // tolerance far below its spacing, equals the GeoJSON output.
    let as_geojson = features(&ok(&["smooth", "mosaic.json", "--tolerance", "0.001"]));
    let back = features(&ok(&[
        "smooth",
        out.to_str().unwrap(),
        "--tolerance",
        "0.001",
        "--output-format",
        "geojson",
    ]));
    assert_eq!(back.len(), as_geojson.len());
    // GeoJSON in, TopoJSON out: one object named after the file.
    let t: Value = serde_json::from_str(&ok(&[
        "smooth",
        "mosaic.geojson",
        "--tolerance",
        "0.001",
        "--output-format",
        "topojson",
    ]))
    .unwrap();
    let gs = t["objects"]["mosaic"]["geometries"].as_array().unwrap();
    assert_eq!(gs.len(), 10);
    assert_eq!(gs[0]["id"], "c00");
    assert_eq!(gs[0]["properties"]["name"], "cell 0,0");
    assert_eq!(gs[9]["type"], "LineString");
    // Shared arcs are referenced by both neighbours, once reversed.
    let refs: Vec<i64> = gs
        .iter()
        .flat_map(|g| {
            let mut v = Vec::new();
            collect_refs(&g["arcs"], &mut v);
            v
        })
        .collect();
    let n_arcs = t["arcs"].as_array().unwrap().len() as i64;
    assert!(refs
        .iter()
        .all(|&k| (k >= 0 && k < n_arcs) || (k < 0 && -k - 1 < n_arcs)));
    assert!(refs.iter().any(|&k| k < 0), "no arc is used reversed");
}

fn collect_refs(v: &Value, out: &mut Vec<i64>) {
    match v {
        Value::Number(n) => out.push(n.as_i64().unwrap()),
        Value::Array(a) => a.iter().for_each(|x| collect_refs(x, out)),
        _ => {}
    }
}

#[test]
fn object_selects_features_and_stats_summarise() {
    let o = run(
        &["smooth", "mosaic.json", "--object", "mosaic", "--stats"],
        None,
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(features(&o.stdout).len(), 10);
    for want in [
        "10 features",
        "9 rings",
        "1 lines",
        "arcs (",
        "shared",
        "positions",
        "tolerance",
        "(the default",
        "area",
    ] {
        assert!(o.stderr.contains(want), "wanted {want:?} in {}", o.stderr);
    }
    assert_data_error(
        &["smooth", "mosaic.json", "--object", "roads"],
        None,
        &["mosaic.json: no object \"roads\"", "[\"mosaic\"]"],
    );
}

#[test]
fn keep_angle_keeps_the_corners_of_cells() {
    let input = input_features();
    let out = features(&ok(&[
        "smooth",
        "mosaic.geojson",
        "--tolerance",
        "0.001",
        "--keep-angle",
        "45",
    ]));
    // The cells' corners turn by about 90 degrees: all kept.
    for (i, o) in input.iter().zip(&out).take(9) {
        let (ri, ro) = (&chains(&i["geometry"])[0], &chains(&o["geometry"])[0]);
        let n = ri.len() - 1;
        let kept: HashSet<(u64, u64)> = ro.iter().map(bits).collect();
        for k in 0..n {
            let (a, b, c) = (&ri[(k + n - 1) % n], &ri[k], &ri[(k + 1) % n]);
            let f = |p: &Value, j: usize| p[j].as_f64().unwrap();
            let (ux, uy) = (f(b, 0) - f(a, 0), f(b, 1) - f(a, 1));
            let (vx, vy) = (f(c, 0) - f(b, 0), f(c, 1) - f(b, 1));
            let turn = (ux * vy - uy * vx)
                .abs()
                .atan2(ux * vx + uy * vy)
                .to_degrees();
            if turn > 45.0 {
                assert!(
                    kept.contains(&bits(b)),
                    "{b} turns {turn:.0} degrees and was smoothed"
                );
            }
        }
    }
}

#[test]
fn snap_joins_borders_digitised_twice() {
    // Two squares whose common edge differs by 1e-9 in one position: not shared
    // exactly, shared after --snap.
    let doc = r#"{"type":"FeatureCollection","features":[
        {"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1.1,0.5],[1,1],[0,1],[0,0]]]}},
        {"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[1,0],[2,0],[2,1],[1,1],[1.100000001,0.5],[1,0]]]}}]}"#;
    let smooth = |extra: &[&str]| {
        let mut args = vec![
            "smooth",
            "--input-format",
            "geojson",
            "--tolerance",
            "0.001",
        ];
        args.extend_from_slice(extra);
        let o = run(&args, Some(doc.as_bytes()));
        assert_eq!(o.code, 0, "{}", o.stderr);
        let f = features(&o.stdout);
        !segments(&f[0]["geometry"]).is_disjoint(&segments(&f[1]["geometry"]))
    };
    assert!(!smooth(&[]), "shared without snapping");
    assert!(smooth(&["--snap", "1e-6"]), "not shared after snapping");
}

#[test]
fn bad_topojson_names_the_object_and_the_arc() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &[&str])] = &[
        (
            r#"{"type":"Topology","objects":{"land":{"type":"GeometryCollection","geometries":[{"type":"Polygon","arcs":[[0,7]]}]}},"arcs":[[[0,0],[1,0],[0,1],[0,0]]]}"#,
            &["object \"land\", geometry 0, ring 0: arc 7 is out of range (there are 1 arcs)"],
        ),
        (
            r#"{"type":"Topology","objects":{"land":{"type":"Polygon","arcs":[[-3]]}},"arcs":[[[0,0],[1,0],[0,1],[0,0]]]}"#,
            &["object \"land\", ring 0: arc -3 is out of range"],
        ),
        (
            r#"{"type":"Topology","transform":{"scale":[0,1],"translate":[0,0]},"objects":{},"arcs":[]}"#,
            &["transform: scale must not be zero"],
        ),
        (
            r#"{"type":"Topology","transform":{"scale":[1,1]},"objects":{},"arcs":[]}"#,
            &["transform: no \"translate\""],
        ),
        (
            r#"{"type":"Topology","objects":{},"arcs":[[[0,0],["x",1]]]}"#,
            &["arc 0, position 1", "not a finite number"],
        ),
        (
            r#"{"type":"Topology","transform":{"scale":[1e308,1e308],"translate":[0,0]},"objects":{},"arcs":[[[1,1],[1,1]]]}"#,
            &["arc 0, position 1: the decoded position is not finite"],
        ),
        (
            r#"{"type":"Topology","objects":{"x":{"type":"Polygon","arcs":[[0.5]]}},"arcs":[[[0,0],[1,1]]]}"#,
            &["object \"x\", ring 0: arc index 0.5 is not an integer"],
        ),
        (
            r#"{"type":"Topology","objects":{"x":{"type":"Circle","arcs":[]}},"arcs":[]}"#,
            &["object \"x\": unknown geometry type \"Circle\""],
        ),
        (r#"{"type":"Topology","objects":{}}"#, &["needs \"arcs\""]),
    ];
    for (i, (doc, wants)) in cases.iter().enumerate() {
        let path = dir.path().join(format!("bad{i}.topojson"));
        std::fs::write(&path, doc).unwrap();
        let p = path.to_str().unwrap();
        let mut want = vec![p];
        want.extend_from_slice(wants);
        assert_data_error(&["smooth", p], None, &want);
    }
}

#[test]
fn through_keeps_every_position_and_every_border() {
    let input = input_features();
    for extra in [&[][..], &["--independent"][..]] {
        let mut args = vec![
            "smooth",
            "mosaic.geojson",
            "--tolerance",
            "0.001",
            "--through",
        ];
        args.extend_from_slice(extra);
        let out = features(&ok(&args));
        for (i, o) in input.iter().zip(&out) {
            let kept: HashSet<(u64, u64)> =
                chains(&o["geometry"]).iter().flatten().map(bits).collect();
            for p in chains(&i["geometry"]).iter().flatten() {
                assert!(kept.contains(&bits(p)), "{extra:?}: {p} lost");
            }
        }
        if extra.is_empty() {
            for (a, b) in neighbours(&input) {
                assert!(
                    !segments(&out[a]["geometry"]).is_disjoint(&segments(&out[b]["geometry"])),
                    "features {a} and {b} lost their border"
                );
            }
        }
    }
}

/// The z example: a line with right-angled corners and z rising along it.
/// `--keep-angle` keeps its corners as it does in the plane (the turning
/// angle is planar; z is carried along); Python and JavaScript are checked
/// against this output in their own tests.
#[test]
fn keep_angle_keeps_corners_of_lines_with_z() {
    let smooth = |extra: &[&str]| -> Vec<Vec<f64>> {
        let mut args = vec!["smooth", "z_corners.geojson"];
        args.extend_from_slice(extra);
        let o = run(&args, None);
        assert_eq!(o.code, 0, "{args:?}: {}", o.stderr);
        assert!(o.stderr.contains("z"), "no note on z: {}", o.stderr);
        let v: Value = serde_json::from_str(&o.stdout).unwrap();
        v["coordinates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                p.as_array()
                    .unwrap()
                    .iter()
                    .map(|c| c.as_f64().unwrap())
                    .collect()
            })
            .collect()
    };
    let input = [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 2.0],
        [1.0, 1.0, 3.0],
        [2.0, 1.0, 4.0],
        [2.0, 0.0, 5.0],
    ];
    let kept = smooth(&["--keep-angle", "30"]);
    let cut = smooth(&[]);
    assert_ne!(kept, cut, "--keep-angle 30 changed nothing");
    for p in &input {
        assert!(kept.iter().any(|q| q == p), "corner {p:?} is not kept");
    }
    assert!(
        !cut.iter().any(|q| q == &input[2]),
        "without it the corners are cut"
    );
    // Between kept corners the line runs along the legs: a straight leg in
    // the plane, whatever z does.
    for q in &kept {
        let on_leg = input.windows(2).any(|w| {
            let (a, b) = (w[0], w[1]);
            ((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])).abs() < 1e-12
        });
        assert!(on_leg, "{q:?} leaves the legs");
    }
    // A turn of exactly 90 degrees is not sharper than 90: all are cut.
    assert_eq!(smooth(&["--keep-angle", "90"]), cut);
}
