//! The command on public coverages: US states and counties (us-atlas) and
//! world countries (world-atlas), as TopoJSON and as the GeoJSON that
//! topojson-client's `topo2geo` makes of them. The folder named by
//! `BZSPLINE_ATLAS` holds them (`bash bench/atlas.sh` fills it, as `.ci/run`
//! does); without it these tests are reported as ignored, with the reason
//! (the build script sets `cfg(atlas)` when the variable is set).
//!
//! Checked with helpers independent of the code under test: every pair of
//! features that shared an edge in the input shares one in the output;
//! crossings (a grid search over every pair of segments in a cell) are none
//! where the input had none; every polygon valid in the input is valid
//! (geo's `Validation`); every ring is a ring.

use bzspline_testing as common;

use std::path::{Path, PathBuf};
use std::process::Command;

use geo_types::Geometry;

const BIN: &str = env!("CARGO_BIN_EXE_bzspline");

fn geometries(path: &Path) -> Vec<Geometry<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let doc: geojson::GeoJson = text
        .parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let geojson::GeoJson::FeatureCollection(fc) = doc else {
        panic!("{}: not a FeatureCollection", path.display())
    };
    fc.features
        .iter()
        .map(|f| match &f.geometry {
            Some(g) => Geometry::try_from(&g.value).expect("geo-types"),
            None => Geometry::GeometryCollection(geo_types::GeometryCollection(vec![])),
        })
        .collect()
}

fn smooth(input: &Path, out: &Path, extra: &[&str]) -> String {
    let o = Command::new(BIN)
        .arg("smooth")
        .arg(input)
        .args(extra)
        .arg("--stats")
        .arg("-o")
        .arg(out)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{}: {stderr}", input.display());
    stderr
}

/// Checks one data set: `topo` (TopoJSON) and `geo` (its features as GeoJSON)
/// smoothed both ways, against the GeoJSON input.
fn check(dir: &Path, topo: &str, object: &str, geo: &str) {
    let input = geometries(&dir.join(geo));
    let pairs = common::neighbours(&input);
    let crossings_in = common::grid_crossings(&input);
    let tmp = std::env::temp_dir().join(format!("bzspline-atlas-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    for (source, extra) in [
        (dir.join(topo), vec!["--object", object]),
        (dir.join(geo), vec![]),
    ] {
        let out_path = tmp.join(format!("{object}.geojson"));
        let stats = smooth(&source, &out_path, &extra);
        let output = geometries(&out_path);
        assert_eq!(output.len(), input.len(), "{}", source.display());
        let lost: Vec<(usize, usize, String)> = pairs
            .iter()
            .filter_map(|&(a, b)| {
                common::share_segment(&output[a], &output[b])
                    .err()
                    .map(|e| (a, b, e))
            })
            .collect();
        assert!(
            lost.is_empty(),
            "{}: {} of {} neighbouring pairs lost their border, first {:?}",
            source.display(),
            lost.len(),
            pairs.len(),
            lost.first()
        );
        let crossings_out = common::grid_crossings(&output);
        assert!(
            crossings_out <= crossings_in,
            "{}: {crossings_out} crossings after, {crossings_in} before",
            source.display()
        );
        common::valid_stays_valid(&input, &output)
            .unwrap_or_else(|e| panic!("{}: {e}", source.display()));
        eprintln!(
            "{}: {} features, {} neighbouring pairs kept, crossings {crossings_in} -> {crossings_out}\n{stats}",
            source.display(),
            input.len(),
            pairs.len()
        );
    }
}

/// The folder named by `BZSPLINE_ATLAS`; a test run without it (`--ignored`)
/// fails rather than check nothing.
fn atlas() -> PathBuf {
    let dir = std::env::var_os("BZSPLINE_ATLAS")
        .map(PathBuf::from)
        .expect("BZSPLINE_ATLAS must name the folder of bash bench/atlas.sh");
    assert!(
        dir.is_dir(),
        "BZSPLINE_ATLAS={} is not a folder",
        dir.display()
    );
    dir
}

#[test]
#[cfg_attr(
    not(atlas),
    ignore = "needs the public coverages: BZSPLINE_ATLAS=$(bash bench/atlas.sh)"
)]
fn us_states_keep_their_borders() {
    let dir = atlas();
    check(&dir, "us-atlas/states-10m.json", "states", "states.geojson");
}

#[test]
#[cfg_attr(
    not(atlas),
    ignore = "needs the public coverages: BZSPLINE_ATLAS=$(bash bench/atlas.sh)"
)]
fn us_counties_keep_their_borders() {
    let dir = atlas();
    check(
        &dir,
        "us-atlas/counties-10m.json",
        "counties",
        "counties.geojson",
    );
}

#[test]
#[cfg_attr(
    not(atlas),
    ignore = "needs the public coverages: BZSPLINE_ATLAS=$(bash bench/atlas.sh)"
)]
fn the_guide_shows_the_counties_summary() {
    let dir = atlas();
    let out = std::env::temp_dir().join(format!("bzspline-readme-{}.geojson", std::process::id()));
    let stats = smooth(
        &dir.join("us-atlas/counties-10m.json"),
        &out,
        &["--object", "counties"],
    );
    let maps =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/maps.md"))
            .unwrap();
    assert!(
        maps.contains(&stats),
        "docs/maps.md's smooth summary is stale:\n{stats}"
    );
}

#[test]
#[cfg_attr(
    not(atlas),
    ignore = "needs the public coverages: BZSPLINE_ATLAS=$(bash bench/atlas.sh)"
)]
fn world_countries_keep_their_borders() {
    let dir = atlas();
    check(
        &dir,
        "world-atlas/countries-50m.json",
        "countries",
        "countries.geojson",
    );
}

/// The edges of a polygon's rings that span more than 180 degrees of
/// longitude (a ring across the antimeridian written from one side to the
/// other), ring by ring.
fn wraps(g: &Geometry<f64>) -> Vec<usize> {
    let polygons: Vec<&geo_types::Polygon<f64>> = match g {
        Geometry::Polygon(p) => vec![p],
        Geometry::MultiPolygon(m) => m.0.iter().collect(),
        _ => vec![],
    };
    polygons
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(|r| {
            r.lines()
                .filter(|l| (l.end.x - l.start.x).abs() > 180.0)
                .count()
        })
        .collect()
}

#[test]
#[cfg_attr(
    not(atlas),
    ignore = "needs the public coverages: BZSPLINE_ATLAS=$(bash bench/atlas.sh)"
)]
fn world_countries_in_metres_stay_whole_across_the_antimeridian() {
    use geo::BoundingRect;
    let dir = atlas();
    let source = dir.join("countries.geojson");
    let input = geometries(&source);
    let tmp = tempfile::tempdir().unwrap();
    let out_path = tmp.path().join("countries-5km.geojson");
    let stats = smooth(&source, &out_path, &["--tolerance", "5km"]);
    assert!(stats.contains("tolerance 5000 m"), "{stats}");
    let output = geometries(&out_path);
    assert_eq!(output.len(), input.len());
    common::valid_stays_valid(&input, &output).unwrap_or_else(|e| panic!("{e}"));
    let pairs = common::neighbours(&input);
    for &(a, b) in &pairs {
        common::share_segment(&output[a], &output[b])
            .unwrap_or_else(|e| panic!("features {a} and {b} lost their border: {e}"));
    }
    // No ring wraps round the world where it did not: an edge across the
    // antimeridian is smoothed the short way and written as the input
    // writes it, so every ring spans it as often as before.
    for (i, (a, b)) in input.iter().zip(&output).enumerate() {
        assert_eq!(wraps(a), wraps(b), "feature {i}");
    }
    // Fiji, Russia and Antarctica (rings across the antimeridian and round
    // the pole) keep every polygon, each where it was: its bounding box
    // within a tenth of a degree.
    let names: Vec<String> = {
        let text = std::fs::read_to_string(&source).unwrap();
        let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
        doc["features"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["properties"]["name"].as_str().unwrap_or("").to_owned())
            .collect()
    };
    for name in ["Fiji", "Russia", "Antarctica"] {
        let i = names.iter().position(|n| n == name).expect(name);
        let (Geometry::MultiPolygon(a), Geometry::MultiPolygon(b)) = (&input[i], &output[i]) else {
            panic!("{name}: not a MultiPolygon");
        };
        assert_eq!(a.0.len(), b.0.len(), "{name}");
        for (k, (p, q)) in a.0.iter().zip(&b.0).enumerate() {
            let (p, q) = (p.bounding_rect().unwrap(), q.bounding_rect().unwrap());
            let off = [
                p.min().x - q.min().x,
                p.min().y - q.min().y,
                p.max().x - q.max().x,
                p.max().y - q.max().y,
            ];
            assert!(
                off.iter().all(|d| d.abs() < 0.1),
                "{name} polygon {k}: {p:?} -> {q:?}"
            );
        }
    }
}
