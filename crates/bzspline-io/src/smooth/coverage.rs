//! Smoothing a GeoJSON document as one coverage (the default): its features'
//! geometries go to [`bzspline_geo::Coverage`] as geo-types, and come back
//! into the same features, with properties, ids and foreign members kept.

use anyhow::{anyhow, Result};
use bzspline_geo::{Arcs, Assembled, Coverage, SmoothOptions, Stats};
use geojson::{GeoJson, Geometry, GeometryValue};
use serde_json::Value;

/// A smoothed document and what is needed to write it as TopoJSON.
pub struct Smoothed {
    /// The document with smoothed geometries.
    pub doc: GeoJson,
    /// What smoothing did.
    pub stats: Stats,
    /// The coverage (its topology numbers the chains).
    pub coverage: Coverage,
    /// The smoothed arcs.
    pub arcs: Arcs,
}

/// The geometry slots of a document: one per feature (or the lone geometry).
fn slots(doc: &mut GeoJson) -> Vec<&mut Option<Geometry>> {
    match doc {
        GeoJson::FeatureCollection(fc) => fc.features.iter_mut().map(|f| &mut f.geometry).collect(),
        GeoJson::Feature(f) => vec![&mut f.geometry],
        GeoJson::Geometry(_) => Vec::new(),
    }
}

/// True when some position of the geometry has more than two numbers.
pub fn has_z(v: &GeometryValue) -> bool {
    let line = |l: &[geojson::Position]| l.iter().any(|p| p.len() > 2);
    match v {
        GeometryValue::Point { coordinates } => coordinates.len() > 2,
        GeometryValue::MultiPoint { coordinates } | GeometryValue::LineString { coordinates } => {
            line(coordinates)
        }
        GeometryValue::MultiLineString { coordinates } | GeometryValue::Polygon { coordinates } => {
            coordinates.iter().any(|l| line(l))
        }
        GeometryValue::MultiPolygon { coordinates } => {
            coordinates.iter().flatten().any(|l| line(l))
        }
        GeometryValue::GeometryCollection { geometries } => {
            geometries.iter().any(|g| has_z(&g.value))
        }
    }
}

/// The most positions of one line or ring of the geometry.
fn longest(v: &GeometryValue) -> usize {
    match v {
        GeometryValue::Point { .. } | GeometryValue::MultiPoint { .. } => 0,
        GeometryValue::LineString { coordinates } => coordinates.len(),
        GeometryValue::MultiLineString { coordinates } | GeometryValue::Polygon { coordinates } => {
            coordinates.iter().map(Vec::len).max().unwrap_or(0)
        }
        GeometryValue::MultiPolygon { coordinates } => coordinates
            .iter()
            .flatten()
            .map(Vec::len)
            .max()
            .unwrap_or(0),
        GeometryValue::GeometryCollection { geometries } => geometries
            .iter()
            .map(|g| longest(&g.value))
            .max()
            .unwrap_or(0),
    }
}

/// True when some geometry of the document has positions with z.
pub fn document_has_z(doc: &GeoJson) -> bool {
    match doc {
        GeoJson::FeatureCollection(fc) => fc
            .features
            .iter()
            .any(|f| f.geometry.as_ref().is_some_and(|g| has_z(&g.value))),
        GeoJson::Feature(f) => f.geometry.as_ref().is_some_and(|g| has_z(&g.value)),
        GeoJson::Geometry(g) => has_z(&g.value),
    }
}

/// Smooths every feature's geometry of `doc` as one coverage. Errors name
/// `where_` and the feature (`feature i`, or only `where_` for a lone
/// feature or geometry when not `number_single`).
pub fn smooth_document(
    mut doc: GeoJson,
    opts: &SmoothOptions,
    snap: Option<f64>,
    max_points: usize,
    where_: &str,
    number_single: bool,
) -> Result<Smoothed> {
    let place = placer(&doc, where_, number_single);
    let geoms = geometries(&mut doc, max_points, &place)?;
    let t = smooth_together(geoms, opts, snap, where_, &place)?;
    put_back(&mut doc, &t.geometries);
    Ok(Smoothed {
        doc,
        stats: t.stats,
        coverage: t.coverage,
        arcs: t.arcs,
    })
}

/// Geometries smoothed as one coverage.
pub struct Together {
    /// The smoothed geometries, in order.
    pub geometries: Vec<geo_types::Geometry<f64>>,
    /// What smoothing did.
    pub stats: Stats,
    /// The coverage (its topology numbers the chains).
    pub coverage: Coverage,
    /// The smoothed arcs.
    pub arcs: Arcs,
}

/// Smooths geometries as one coverage (positions within `snap` joined
/// first), keeping the coverage and its smoothed arcs (for TopoJSON). Errors
/// name `where_`, or the geometry at fault by `place`.
pub fn smooth_together(
    geoms: Vec<geo_types::Geometry<f64>>,
    opts: &SmoothOptions,
    snap: Option<f64>,
    where_: &str,
    place: &dyn Fn(usize) -> String,
) -> Result<Together> {
    let (coverage, s) = smooth_coverage(geoms, opts, snap, where_, place)?;
    Ok(Together {
        geometries: coverage.assemble(&s.arcs),
        stats: s.stats,
        coverage,
        arcs: s.arcs,
    })
}

/// The smoothed geometries of [`smooth_together`], each put together when
/// asked for ([`Assembled`]), and what smoothing did: for a large layer,
/// without holding all its geometries at once, neither as they come in
/// (each is let go of once the coverage holds its positions, unless
/// snapping) nor smoothed.
///
/// # Errors
///
/// As [`smooth_together`].
pub fn smooth_into_assembled(
    geoms: impl IntoIterator<Item = geo_types::Geometry<f64>>,
    opts: &SmoothOptions,
    snap: Option<f64>,
    where_: &str,
    place: &dyn Fn(usize) -> String,
) -> Result<(Assembled, Stats)> {
    let (coverage, s) = smooth_coverage(geoms, opts, snap, where_, place)?;
    Ok((coverage.into_assembled(s.arcs), s.stats))
}

/// The coverage of `geoms` and its smoothing.
fn smooth_coverage(
    geoms: impl IntoIterator<Item = geo_types::Geometry<f64>>,
    opts: &SmoothOptions,
    snap: Option<f64>,
    where_: &str,
    place: &dyn Fn(usize) -> String,
) -> Result<(Coverage, bzspline_geo::Smoothed)> {
    let coverage = Coverage::builder(geoms)
        .snap(snap)
        .frame(opts.frame)
        .build()
        .map_err(|e| anyhow!("{where_}: {e}"))?;
    let s = coverage
        .topology()
        .smooth(opts)
        .map_err(|e| located(&coverage, &e, place, where_))?;
    Ok((coverage, s))
}

/// Smooths every feature's geometry of `doc` on its own, as a coverage of
/// its own (its rings and lines together, with no regard for the other
/// features: `--independent`, Python's `coverage=False`, geo-types'
/// [`bzspline_geo::Smooth`]), with `opts`' tolerance or, by default, each
/// geometry's own (of its extent's diagonal). Errors as
/// [`smooth_document`]'s.
pub fn smooth_each(
    mut doc: GeoJson,
    opts: &SmoothOptions,
    max_points: usize,
    where_: &str,
    number_single: bool,
) -> Result<(GeoJson, Stats)> {
    let place = placer(&doc, where_, number_single);
    let geoms = geometries(&mut doc, max_points, &place)?;
    let (out, total) = smooth_apart(geoms, opts, where_, &place)?;
    put_back(&mut doc, &out);
    Ok((doc, total))
}

/// Smooths every geometry on its own, as [`smooth_each`] does; errors name
/// the geometry by `place`.
pub fn smooth_apart(
    geoms: Vec<geo_types::Geometry<f64>>,
    opts: &SmoothOptions,
    where_: &str,
    place: &dyn Fn(usize) -> String,
) -> Result<(Vec<geo_types::Geometry<f64>>, Stats)> {
    let mut total = Stats::default();
    let mut out = Vec::with_capacity(geoms.len());
    for (i, g) in geoms.into_iter().enumerate() {
        let coverage = Coverage::new(vec![g]).map_err(|e| anyhow!("{}: {e}", place(i)))?;
        let s = coverage
            .topology()
            .smooth(opts)
            .map_err(|e| located(&coverage, &e, &|_| place(i), where_))?;
        total += &s.stats;
        out.extend(coverage.into_geometries(&s.arcs));
    }
    Ok((out, total))
}

/// The bounds `[min x, min y, max x, max y]` of the geometries' positions
/// (infinite, lower above upper, for none).
#[must_use]
pub fn bounds(geoms: &[geo_types::Geometry<f64>]) -> [f64; 4] {
    fn line(l: &geo_types::LineString<f64>, b: &mut [f64; 4]) {
        for c in &l.0 {
            *b = [b[0].min(c.x), b[1].min(c.y), b[2].max(c.x), b[3].max(c.y)];
        }
    }
    fn polygon(p: &geo_types::Polygon<f64>, b: &mut [f64; 4]) {
        line(p.exterior(), b);
        p.interiors().iter().for_each(|r| line(r, b));
    }
    fn walk(g: &geo_types::Geometry<f64>, b: &mut [f64; 4]) {
        use geo_types::Geometry as G;
        match g {
            G::Point(p) => line(&geo_types::LineString(vec![p.0]), b),
            G::MultiPoint(m) => m.0.iter().for_each(|p| walk(&G::Point(*p), b)),
            G::LineString(l) => line(l, b),
            G::MultiLineString(m) => m.0.iter().for_each(|l| line(l, b)),
            G::Polygon(p) => polygon(p, b),
            G::MultiPolygon(m) => m.0.iter().for_each(|p| polygon(p, b)),
            G::GeometryCollection(c) => c.0.iter().for_each(|m| walk(m, b)),
            G::Line(l) => line(&geo_types::LineString(vec![l.start, l.end]), b),
            G::Rect(r) => polygon(&r.to_polygon(), b),
            G::Triangle(t) => polygon(&t.to_polygon(), b),
        }
    }
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    geoms.iter().for_each(|g| walk(g, &mut b));
    b
}

/// Refuses a geometry with a line or ring of more than `max_points`
/// positions, naming it by `place`.
pub fn check_longest<'a>(
    geoms: impl IntoIterator<Item = &'a geo_types::Geometry<f64>>,
    max_points: usize,
    place: &dyn Fn(usize) -> String,
) -> Result<()> {
    fn longest(g: &geo_types::Geometry<f64>) -> usize {
        use geo_types::Geometry as G;
        match g {
            G::LineString(l) => l.0.len(),
            G::MultiLineString(m) => m.0.iter().map(|l| l.0.len()).max().unwrap_or(0),
            G::Polygon(p) => std::iter::once(p.exterior())
                .chain(p.interiors())
                .map(|l| l.0.len())
                .max()
                .unwrap_or(0),
            G::MultiPolygon(m) => {
                m.0.iter()
                    .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                    .map(|l| l.0.len())
                    .max()
                    .unwrap_or(0)
            }
            G::GeometryCollection(c) => c.0.iter().map(longest).max().unwrap_or(0),
            _ => 0,
        }
    }
    for (i, g) in geoms.into_iter().enumerate() {
        if longest(g) > max_points {
            return Err(anyhow!(
                "{}: more than {max_points} positions (--max-points)",
                place(i)
            ));
        }
    }
    Ok(())
}

/// Where geometry i of `doc` is, for messages.
fn placer<'a>(
    doc: &GeoJson,
    where_: &'a str,
    number_single: bool,
) -> impl Fn(usize) -> String + 'a {
    let collection = matches!(doc, GeoJson::FeatureCollection(_));
    move |i: usize| {
        if collection || number_single {
            format!("{where_}: feature {i}")
        } else {
            where_.to_owned()
        }
    }
}

/// A coverage's error located at its geometry, member and ring.
fn located(
    coverage: &Coverage,
    e: &bzspline_geo::Error,
    place: &dyn Fn(usize) -> String,
    where_: &str,
) -> anyhow::Error {
    match coverage.locate(e) {
        Some(l) => {
            let ring = l.ring.map(|r| format!(", ring {r}")).unwrap_or_default();
            anyhow!("{}, member {}{ring}: {e}", place(l.geometry), l.member)
        }
        None => anyhow!("{where_}: {e}"),
    }
}

/// The document's geometries as geo-types, geometry i for feature i (an
/// empty collection for a feature without one).
fn geometries(
    doc: &mut GeoJson,
    max_points: usize,
    place: &dyn Fn(usize) -> String,
) -> Result<Vec<geo_types::Geometry<f64>>> {
    let empty = || geo_types::Geometry::GeometryCollection(geo_types::GeometryCollection(vec![]));
    let convert = |i: usize, g: &Geometry| -> Result<geo_types::Geometry<f64>> {
        if longest(&g.value) > max_points {
            return Err(anyhow!(
                "{}: more than {max_points} positions (--max-points)",
                place(i)
            ));
        }
        geo_types::Geometry::try_from(&g.value).map_err(|e| anyhow!("{}: {e}", place(i)))
    };
    if let GeoJson::Geometry(g) = doc {
        return Ok(vec![convert(0, g)?]);
    }
    slots(doc)
        .into_iter()
        .enumerate()
        .map(|(i, slot)| match slot {
            Some(g) => convert(i, g),
            None => Ok(empty()),
        })
        .collect()
}

/// Puts the smoothed geometries back into the document's features.
fn put_back(doc: &mut GeoJson, out: &[geo_types::Geometry<f64>]) {
    let put = |g: &mut Geometry, o: &geo_types::Geometry<f64>| {
        g.value = GeometryValue::from(o);
        // A bounding box of the input may no longer be tight: dropped.
        g.bbox = None;
    };
    if let GeoJson::Geometry(g) = doc {
        put(g, &out[0]);
    } else {
        for (slot, o) in slots(doc).into_iter().zip(out) {
            if let Some(g) = slot {
                put(g, o);
            }
        }
    }
}

/// The features of a smoothed document as (id, properties, geometry), for
/// [`crate::topojson::from_features`].
pub fn features(doc: &GeoJson) -> Vec<(Option<Value>, Value, Option<&GeometryValue>)> {
    let props = |p: &Option<geojson::JsonObject>| {
        p.as_ref()
            .map_or(Value::Object(serde_json::Map::new()), |m| {
                Value::Object(m.clone())
            })
    };
    let id = |i: &Option<geojson::feature::Id>| {
        i.as_ref().map(|i| match i {
            geojson::feature::Id::String(s) => Value::String(s.clone()),
            geojson::feature::Id::Number(n) => Value::Number(n.clone()),
        })
    };
    match doc {
        GeoJson::FeatureCollection(fc) => fc
            .features
            .iter()
            .map(|f| {
                (
                    id(&f.id),
                    props(&f.properties),
                    f.geometry.as_ref().map(|g| &g.value),
                )
            })
            .collect(),
        GeoJson::Feature(f) => vec![(
            id(&f.id),
            props(&f.properties),
            f.geometry.as_ref().map(|g| &g.value),
        )],
        GeoJson::Geometry(g) => vec![(None, Value::Object(serde_json::Map::new()), Some(&g.value))],
    }
}
