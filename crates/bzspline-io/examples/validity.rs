//! Counts the polygons a smoothing made invalid: feature by feature, those
//! valid (OGC rules, geo's `Validation`) in the first GeoJSON document and
//! not in the second, which must hold the same features in the same order;
//! and the borders it split: pairs of features that share an edge before
//! and none after (`bzspline-testing`'s `neighbours` and `share_segment`).
//!
//! ```text
//! cargo run --release -p bzspline-io --example validity -- BEFORE.geojson AFTER.geojson
//! ```
//!
//! Prints one JSON object: `features`, `valid_before`, `made_invalid` and the
//! first few indices made invalid, `borders` and `borders_split`.

use std::process::ExitCode;

use geo::Validation;
use geo_types::Geometry;

fn geometries(path: &str) -> Result<Vec<Option<Geometry<f64>>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let value = serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))?;
    let (doc, _) = bzspline_io::input::to_geojson(path, value).map_err(|e| format!("{e:#}"))?;
    let features = match doc {
        geojson::GeoJson::FeatureCollection(fc) => fc.features,
        geojson::GeoJson::Feature(f) => vec![f],
        geojson::GeoJson::Geometry(g) => vec![geojson::Feature::from(g)],
    };
    Ok(features
        .into_iter()
        .map(|f| f.geometry.and_then(|g| Geometry::try_from(g).ok()))
        .collect())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [before, after] = args.as_slice() else {
        eprintln!("usage: validity BEFORE.geojson AFTER.geojson");
        return ExitCode::from(2);
    };
    let (a, b) = match (geometries(before), geometries(after)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("validity: {e}");
            return ExitCode::from(1);
        }
    };
    if a.len() != b.len() {
        eprintln!("validity: {} features before, {} after", a.len(), b.len());
        return ExitCode::from(1);
    }
    let areal = |g: &Geometry<f64>| matches!(g, Geometry::Polygon(_) | Geometry::MultiPolygon(_));
    let (mut valid, mut broken) = (0usize, Vec::new());
    for (i, (p, q)) in a.iter().zip(&b).enumerate() {
        if !p.as_ref().is_some_and(|p| areal(p) && p.is_valid()) {
            continue;
        }
        valid += 1;
        if !q.as_ref().is_some_and(|q| q.is_valid()) {
            broken.push(i);
        }
    }
    let first: Vec<usize> = broken.iter().copied().take(10).collect();
    // Missing geometries as empty collections, for the border check.
    let some = |v: &[Option<Geometry<f64>>]| -> Vec<Geometry<f64>> {
        v.iter()
            .map(|g| {
                g.clone().unwrap_or_else(|| {
                    Geometry::GeometryCollection(geo_types::GeometryCollection(vec![]))
                })
            })
            .collect()
    };
    let (sa, sb) = (some(&a), some(&b));
    let pairs = bzspline_testing::neighbours(&sa);
    let split = pairs
        .iter()
        .filter(|&&(i, j)| bzspline_testing::share_segment(&sb[i], &sb[j]).is_err())
        .count();
    println!(
        "{{\"features\": {}, \"valid_before\": {valid}, \"made_invalid\": {}, \"first\": {first:?}, \"borders\": {}, \"borders_split\": {split}}}",
        a.len(),
        broken.len(),
        pairs.len()
    );
    ExitCode::SUCCESS
}
