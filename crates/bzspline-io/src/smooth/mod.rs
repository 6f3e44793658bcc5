//! A GeoJSON document smoothed: a FeatureCollection in the plane read and
//! written one feature at a time ([`collection`]); as one coverage
//! ([`coverage`], the default:
//! shared borders smoothed once, valid polygons kept valid), every feature's
//! geometry as a coverage of its own ([`coverage::smooth_each`]), or, for
//! positions with z, every line and ring on its own ([`independent`]); what a
//! document holds ([`positions`], [`chains`]) and its default tolerance.

pub mod collection;
pub mod coverage;
pub mod document;
pub mod independent;
pub mod job;

use geojson::{GeoJson, GeometryValue, Position};

/// Calls `f` on every position of the document.
pub fn each_position(doc: &GeoJson, f: &mut dyn FnMut(&Position)) {
    fn geometry(v: &GeometryValue, f: &mut dyn FnMut(&Position)) {
        match v {
            GeometryValue::Point { coordinates } => f(coordinates),
            GeometryValue::MultiPoint { coordinates }
            | GeometryValue::LineString { coordinates } => coordinates.iter().for_each(f),
            GeometryValue::MultiLineString { coordinates }
            | GeometryValue::Polygon { coordinates } => coordinates.iter().flatten().for_each(f),
            GeometryValue::MultiPolygon { coordinates } => {
                coordinates.iter().flatten().flatten().for_each(f);
            }
            GeometryValue::GeometryCollection { geometries } => {
                geometries.iter().for_each(|g| geometry(&g.value, f));
            }
        }
    }
    match doc {
        GeoJson::FeatureCollection(fc) => fc
            .features
            .iter()
            .filter_map(|x| x.geometry.as_ref())
            .for_each(|g| geometry(&g.value, f)),
        GeoJson::Feature(x) => {
            if let Some(g) = &x.geometry {
                geometry(&g.value, f);
            }
        }
        GeoJson::Geometry(g) => geometry(&g.value, f),
    }
}

/// The rings and lines of a document.
#[must_use]
pub fn chains(doc: &GeoJson) -> (usize, usize) {
    fn geometry(v: &GeometryValue) -> (usize, usize) {
        match v {
            GeometryValue::Point { .. } | GeometryValue::MultiPoint { .. } => (0, 0),
            GeometryValue::LineString { .. } => (0, 1),
            GeometryValue::MultiLineString { coordinates } => (0, coordinates.len()),
            GeometryValue::Polygon { coordinates } => (coordinates.len(), 0),
            GeometryValue::MultiPolygon { coordinates } => {
                (coordinates.iter().map(Vec::len).sum(), 0)
            }
            GeometryValue::GeometryCollection { geometries } => geometries
                .iter()
                .map(|g| geometry(&g.value))
                .fold((0, 0), |a, b| (a.0 + b.0, a.1 + b.1)),
        }
    }
    let values: Vec<&GeometryValue> = match doc {
        GeoJson::FeatureCollection(fc) => fc
            .features
            .iter()
            .filter_map(|f| f.geometry.as_ref().map(|g| &g.value))
            .collect(),
        GeoJson::Feature(f) => f.geometry.iter().map(|g| &g.value).collect(),
        GeoJson::Geometry(g) => vec![&g.value],
    };
    values
        .into_iter()
        .map(geometry)
        .fold((0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// The positions of a document.
#[must_use]
pub fn positions(doc: &GeoJson) -> usize {
    let mut n = 0;
    each_position(doc, &mut |_| n += 1);
    n
}

/// The default tolerance of a document ([`bzspline_geo::default_tolerance_of`]
/// its extent, as the coverage computes it).
#[must_use]
pub fn default_tolerance(doc: &GeoJson) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    each_position(doc, &mut |p| {
        if p.len() >= 2 {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
    });
    bzspline_geo::default_tolerance_of(lo, hi)
}
