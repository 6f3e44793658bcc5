//! A layer's features held compactly, as its reader reads them one at a
//! time: each feature's field values in the schema's order and its geometry
//! as geo-types (16 bytes a position), not as a GeoJSON document tree (about
//! 100 bytes a position as JSON values); and [`Source`], the features a
//! layer writer takes, from either form.

use std::borrow::Cow;

use bzspline_geo::Assembled;
use geo_types::{
    Coord, Geometry, GeometryCollection, LineString, MultiLineString, MultiPoint, MultiPolygon,
    Point, Polygon,
};
use serde_json::{json, Map, Value};

use values::Values;

mod values;

/// A feature's geometry. Each kind is boxed, so that a feature whose
/// geometry has been taken (to be smoothed) keeps 16 bytes of it, not 72.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// No geometry (GeoJSON's `null`).
    Null,
    /// A geometry in the plane (positions of x and y).
    Plane(Box<Geometry<f64>>),
    /// Any other geometry (positions with z; rings that are not closed), as
    /// GeoJSON.
    Json(Box<Value>),
}

impl Shape {
    /// The shape of a GeoJSON geometry (or `null`): in the plane when every
    /// position is x and y and every ring is closed, so that
    /// [`Shape::to_value`] gives back the same value, else as it is.
    #[must_use]
    pub fn from_value(v: Value) -> Shape {
        if v.is_null() {
            return Shape::Null;
        }
        match plane(&v, 0) {
            Some(g) => Shape::Plane(Box::new(g)),
            None => Shape::Json(Box::new(v)),
        }
    }

    /// The geometry as GeoJSON (`null` for none).
    #[must_use]
    pub fn to_value(&self) -> Value {
        match self {
            Shape::Null => Value::Null,
            Shape::Plane(g) => geometry_value(g),
            Shape::Json(v) => (**v).clone(),
        }
    }
}

/// Collections in collections deeper than this are left as GeoJSON.
const MAX_DEPTH: usize = 32;

fn coord(v: &Value) -> Option<Coord> {
    match v.as_array()?.as_slice() {
        [x, y] => Some(Coord {
            x: x.as_f64()?,
            y: y.as_f64()?,
        }),
        _ => None,
    }
}

/// Each member of a JSON array made by `f`, in a vector of exactly their
/// number (collecting into `Option<Vec<_>>` would grow by doubling).
fn each<T>(v: &Value, f: impl Fn(&Value) -> Option<T>) -> Option<Vec<T>> {
    let a = v.as_array()?;
    let mut out = Vec::with_capacity(a.len());
    for m in a {
        out.push(f(m)?);
    }
    Some(out)
}

fn line(v: &Value) -> Option<LineString> {
    each(v, coord).map(LineString)
}

/// A polygon's rings, every one closed (or empty), at least one.
fn polygon(v: &Value) -> Option<Polygon> {
    let a = v.as_array()?;
    let exterior = line(a.first()?)?;
    let mut interiors: Vec<LineString> = Vec::with_capacity(a.len() - 1);
    for r in &a[1..] {
        interiors.push(line(r)?);
    }
    let open = |r: &LineString| !r.0.is_empty() && !r.is_closed();
    if open(&exterior) || interiors.iter().any(open) {
        return None;
    }
    Some(Polygon::new(exterior, interiors))
}

fn plane(v: &Value, depth: usize) -> Option<Geometry> {
    let c = &v["coordinates"];
    Some(match v["type"].as_str()? {
        "Point" => Geometry::Point(Point(coord(c)?)),
        "MultiPoint" => Geometry::MultiPoint(MultiPoint(each(c, |p| coord(p).map(Point))?)),
        "LineString" => Geometry::LineString(line(c)?),
        "MultiLineString" => Geometry::MultiLineString(MultiLineString(each(c, line)?)),
        "Polygon" => Geometry::Polygon(polygon(c)?),
        "MultiPolygon" => Geometry::MultiPolygon(MultiPolygon(each(c, polygon)?)),
        "GeometryCollection" if depth < MAX_DEPTH => {
            Geometry::GeometryCollection(GeometryCollection(each(&v["geometries"], |m| {
                plane(m, depth + 1)
            })?))
        }
        _ => return None,
    })
}

fn coord_value(c: &Coord) -> Value {
    json!([c.x, c.y])
}

fn line_value(l: &LineString) -> Value {
    Value::Array(l.0.iter().map(coord_value).collect())
}

fn polygon_value(p: &Polygon) -> Value {
    Value::Array(
        std::iter::once(p.exterior())
            .chain(p.interiors())
            .map(line_value)
            .collect(),
    )
}

/// A geometry in the plane as GeoJSON.
#[must_use]
pub fn geometry_value(g: &Geometry) -> Value {
    let (kind, coordinates) = match g {
        Geometry::Point(p) => ("Point", coord_value(&p.0)),
        Geometry::MultiPoint(m) => (
            "MultiPoint",
            Value::Array(m.0.iter().map(|p| coord_value(&p.0)).collect()),
        ),
        Geometry::LineString(l) => ("LineString", line_value(l)),
        Geometry::MultiLineString(m) => (
            "MultiLineString",
            Value::Array(m.0.iter().map(line_value).collect()),
        ),
        Geometry::Polygon(p) => ("Polygon", polygon_value(p)),
        Geometry::MultiPolygon(m) => (
            "MultiPolygon",
            Value::Array(m.0.iter().map(polygon_value).collect()),
        ),
        Geometry::GeometryCollection(c) => {
            return json!({
                "type": "GeometryCollection",
                "geometries": c.0.iter().map(geometry_value).collect::<Vec<_>>(),
            })
        }
        Geometry::Line(l) => (
            "LineString",
            Value::Array(vec![coord_value(&l.start), coord_value(&l.end)]),
        ),
        Geometry::Rect(r) => ("Polygon", polygon_value(&r.to_polygon())),
        Geometry::Triangle(t) => ("Polygon", polygon_value(&t.to_polygon())),
    };
    json!({"type": kind, "coordinates": coordinates})
}

/// A layer's features, in order, with the names of their fields: each
/// feature's geometry and its field values in the schema's order (a
/// feature lacking a field holds null for it). Two are equal when they
/// have the same fields, values and geometries, however these are held.
#[derive(Clone, Debug, Default)]
pub struct Features {
    names: Vec<String>,
    count: usize,
    /// One a feature, or none while they are taken ([`Features::take_shapes`])
    /// or once smoothed as a coverage ([`Features::put_assembled`]).
    shapes: Vec<Shape>,
    /// The geometries smoothed as a coverage, and whether each feature had
    /// one.
    assembled: Option<(Assembled, Vec<bool>)>,
    values: Values,
}

impl PartialEq for Features {
    fn eq(&self, other: &Features) -> bool {
        self.names == other.names
            && self.count == other.count
            && self.values == other.values
            && (0..self.count).all(|i| self.shape(i) == other.shape(i))
    }
}

impl Features {
    /// No features yet, of the fields named `names` (in order).
    #[must_use]
    pub fn new(names: Vec<String>) -> Features {
        Features {
            names,
            ..Features::default()
        }
    }

    /// Adds a feature: its properties (each field's value taken by name,
    /// `null` for a field it lacks, the one value for fields of one name;
    /// others dropped) and its GeoJSON geometry (or `null`).
    pub fn push(&mut self, properties: Map<String, Value>, geometry: Value) {
        for n in &self.names {
            self.values.push(properties.get(n).unwrap_or(&NULL));
        }
        self.shapes.push(Shape::from_value(geometry));
        self.count += 1;
    }

    /// The features of a GeoJSON FeatureCollection (a Feature or geometry
    /// as the collection of it), with fields `names`.
    #[must_use]
    pub fn from_value(doc: &Value, names: Vec<String>) -> Features {
        let fc = crate::files::as_collection(doc);
        let mut out = Features::new(names);
        for f in fc["features"].as_array().into_iter().flatten() {
            let props = f["properties"].as_object().cloned().unwrap_or_default();
            out.push(props, f["geometry"].clone());
        }
        out
    }

    /// The number of features.
    #[must_use]
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The fields' names.
    #[must_use]
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Feature `i`'s geometry ([`Shape::Null`] while they are taken), that
    /// of the features smoothed as a coverage put together.
    fn shape(&self, i: usize) -> Cow<'_, Shape> {
        match &self.assembled {
            Some((a, had)) if had[i] => Cow::Owned(Shape::Plane(Box::new(a.get(i)))),
            Some(_) => Cow::Owned(Shape::Null),
            None => Cow::Borrowed(self.shapes.get(i).unwrap_or(&Shape::Null)),
        }
    }

    /// Takes every feature's geometry, in order, leaving the features none
    /// until [`Features::put_shapes`] gives them back (so that a layer's
    /// geometries can be smoothed without a second vector of them).
    #[must_use]
    pub fn take_shapes(&mut self) -> Vec<Shape> {
        let mut shapes = match self.assembled.take() {
            Some((a, had)) => (0..self.count)
                .map(|i| match had[i] {
                    true => Shape::Plane(Box::new(a.get(i))),
                    false => Shape::Null,
                })
                .collect(),
            None => std::mem::take(&mut self.shapes),
        };
        shapes.resize(self.count, Shape::Null);
        shapes
    }

    /// Gives the features their geometries back, one each in order.
    ///
    /// # Panics
    ///
    /// When `shapes` is not one a feature.
    pub fn put_shapes(&mut self, shapes: Vec<Shape>) {
        assert_eq!(shapes.len(), self.count, "one shape a feature");
        self.shapes = shapes;
        self.assembled = None;
    }

    /// Gives the features their geometries back smoothed as a coverage,
    /// each put together when it is read ([`Source::geometry`]): feature
    /// `i`'s is `assembled`'s `i`, or none where `had[i]` is false.
    ///
    /// # Panics
    ///
    /// When `assembled` or `had` is not one a feature.
    pub fn put_assembled(&mut self, assembled: Assembled, had: Vec<bool>) {
        assert_eq!(assembled.len(), self.count, "one geometry a feature");
        assert_eq!(had.len(), self.count, "one mark a feature");
        self.shapes = Vec::new();
        self.assembled = Some((assembled, had));
    }

    /// Whether every geometry lies in the plane (or there is none).
    #[must_use]
    pub fn is_plane(&self) -> bool {
        self.assembled.is_some() || self.shapes.iter().all(|s| !matches!(s, Shape::Json(_)))
    }

    /// Feature `i`'s value of field `k`.
    fn value(&self, i: usize, k: usize) -> Value {
        self.values.get(i * self.names.len() + k)
    }

    /// Feature `i`'s properties.
    #[must_use]
    pub fn properties(&self, i: usize) -> Map<String, Value> {
        assert!(i < self.count, "feature {i} of {}", self.count);
        (0..self.names.len())
            .map(|k| (self.names[k].clone(), self.value(i, k)))
            .collect()
    }

    /// The features as a GeoJSON FeatureCollection.
    #[must_use]
    pub fn to_value(&self) -> Value {
        let me: &dyn Source = self;
        let features: Vec<Value> = (0..self.len()).map(|i| me.feature(i)).collect();
        json!({"type": "FeatureCollection", "features": features})
    }
}

impl Features {
    /// Writes the features as a GeoJSON FeatureCollection, compact, one
    /// feature at a time (numbers in their shortest form).
    ///
    /// # Errors
    ///
    /// The writer's.
    pub fn write_geojson(&self, mut w: impl std::io::Write) -> std::io::Result<()> {
        w.write_all(br#"{"type":"FeatureCollection","features":["#)?;
        for i in 0..self.len() {
            if i > 0 {
                w.write_all(b",")?;
            }
            let f = json!({
                "type": "Feature",
                "geometry": self.shape(i).to_value(),
                "properties": self.properties(i),
            });
            crate::model::write_json_compact(&mut w, &f)?;
        }
        w.write_all(b"]}")
    }
}

/// The value of a property a feature lacks.
pub(crate) static NULL: Value = Value::Null;

/// The features a layer writer takes, one at a time: a GeoJSON
/// FeatureCollection's, or a compact layer's, whose
/// geometries are made as GeoJSON on the way.
pub trait Source {
    /// The number of features.
    fn count(&self) -> usize;
    /// Feature `i`'s geometry as GeoJSON (`null` for none).
    fn geometry(&self, i: usize) -> Cow<'_, Value>;
    /// Feature `i`'s value of the property `name` (`null` for none).
    fn property(&self, i: usize, name: &str) -> Cow<'_, Value>;
    /// Feature `i`'s properties.
    fn properties(&self, i: usize) -> Cow<'_, Map<String, Value>>;
    /// Feature `i`'s geometry type (`"Polygon"`), `None` for no geometry
    /// (or one of no type GeoJSON knows).
    fn geometry_type(&self, i: usize) -> Option<&'static str> {
        let g = self.geometry(i);
        let t = g["type"].as_str()?;
        GEOMETRY_TYPES.iter().copied().find(|k| *k == t)
    }
    /// Whether some position of feature `i`'s geometry has z.
    fn has_z(&self, i: usize) -> bool {
        has_z(&self.geometry(i))
    }
}

/// The geometry types of GeoJSON (its `type` values after
/// FeatureCollection and Feature).
pub(crate) const GEOMETRY_TYPES: &[&str] = crate::input::GEOJSON_TYPES.split_at(2).1;

/// Whether any position of a GeoJSON geometry has z.
#[must_use]
pub fn has_z(g: &Value) -> bool {
    fn coords(c: &Value) -> bool {
        match c.as_array() {
            Some(a) if a.first().is_some_and(Value::is_number) => a.len() >= 3,
            Some(a) => a.iter().any(coords),
            None => false,
        }
    }
    match g.get("geometries").and_then(Value::as_array) {
        Some(members) => members.iter().any(has_z),
        None => coords(&g["coordinates"]),
    }
}

/// The GeoJSON type of a geometry in the plane.
fn plane_type(g: &Geometry) -> &'static str {
    match g {
        Geometry::Point(_) => "Point",
        Geometry::MultiPoint(_) => "MultiPoint",
        Geometry::LineString(_) | Geometry::Line(_) => "LineString",
        Geometry::MultiLineString(_) => "MultiLineString",
        Geometry::Polygon(_) | Geometry::Rect(_) | Geometry::Triangle(_) => "Polygon",
        Geometry::MultiPolygon(_) => "MultiPolygon",
        Geometry::GeometryCollection(_) => "GeometryCollection",
    }
}

/// A FeatureCollection's features (none for any other value).
impl Source for Value {
    fn count(&self) -> usize {
        self["features"].as_array().map_or(0, Vec::len)
    }
    fn geometry(&self, i: usize) -> Cow<'_, Value> {
        Cow::Borrowed(&self["features"][i]["geometry"])
    }
    fn property(&self, i: usize, name: &str) -> Cow<'_, Value> {
        Cow::Borrowed(self["features"][i]["properties"].get(name).unwrap_or(&NULL))
    }
    fn properties(&self, i: usize) -> Cow<'_, Map<String, Value>> {
        match self["features"][i]["properties"].as_object() {
            Some(m) => Cow::Borrowed(m),
            None => Cow::Owned(Map::new()),
        }
    }
}

impl Source for Features {
    fn count(&self) -> usize {
        self.len()
    }
    fn geometry(&self, i: usize) -> Cow<'_, Value> {
        match self.shape(i) {
            Cow::Borrowed(Shape::Json(v)) => Cow::Borrowed(&**v),
            s => Cow::Owned(s.to_value()),
        }
    }
    fn property(&self, i: usize, name: &str) -> Cow<'_, Value> {
        assert!(i < self.count, "feature {i} of {}", self.count);
        match self.names.iter().position(|n| n == name) {
            Some(k) => Cow::Owned(self.value(i, k)),
            None => Cow::Borrowed(&NULL),
        }
    }
    fn properties(&self, i: usize) -> Cow<'_, Map<String, Value>> {
        Cow::Owned(Features::properties(self, i))
    }
    fn geometry_type(&self, i: usize) -> Option<&'static str> {
        // A smoothed geometry's type, without putting it together.
        if let Some((a, had)) = &self.assembled {
            return had[i].then(|| match a.kind(i) {
                "Line" => "LineString",
                kind => kind,
            });
        }
        match &*self.shape(i) {
            Shape::Null => None,
            Shape::Plane(g) => Some(plane_type(g)),
            Shape::Json(v) => {
                let t = v["type"].as_str()?;
                GEOMETRY_TYPES.iter().copied().find(|k| *k == t)
            }
        }
    }
    fn has_z(&self, i: usize) -> bool {
        if self.assembled.is_some() {
            // Smoothed in the plane.
            return false;
        }
        match &*self.shape(i) {
            Shape::Json(v) => has_z(v),
            _ => false,
        }
    }
}

impl dyn Source + '_ {
    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.count() == 0
    }

    /// Feature `i` as a GeoJSON Feature.
    #[must_use]
    pub fn feature(&self, i: usize) -> Value {
        json!({
            "type": "Feature",
            "properties": self.properties(i).into_owned(),
            "geometry": self.geometry(i).into_owned(),
        })
    }
}

/// The features of a GeoJSON FeatureCollection, `None` for anything else.
#[must_use]
pub fn of_collection(fc: &Value) -> Option<&dyn Source> {
    fc.get("features")
        .and_then(Value::as_array)
        .map(|_| fc as &dyn Source)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_geometries_give_back_their_geojson() {
        let cases = [
            json!({"type": "Point", "coordinates": [1.5, -2.0]}),
            json!({"type": "MultiPoint", "coordinates": [[0.0, 0.0], [1.0, 2.0]]}),
            json!({"type": "MultiPoint", "coordinates": []}),
            json!({"type": "LineString", "coordinates": [[0.0, 0.0], [1.0, 0.1]]}),
            json!({"type": "LineString", "coordinates": []}),
            json!({"type": "MultiLineString", "coordinates": [[[0.0, 0.0], [1.0, 0.1]], []]}),
            json!({"type": "Polygon", "coordinates": [[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]], []]}),
            json!({"type": "MultiPolygon", "coordinates": [[[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]]]}),
            json!({"type": "GeometryCollection", "geometries": [
                {"type": "Point", "coordinates": [0.1, 0.2]},
                {"type": "GeometryCollection", "geometries": []}]}),
        ];
        for v in cases {
            let s = Shape::from_value(v.clone());
            assert!(matches!(s, Shape::Plane(_)), "{v}");
            assert_eq!(s.to_value(), v);
        }
    }

    #[test]
    fn other_geometries_stay_geojson() {
        let cases = [
            json!({"type": "Point", "coordinates": [1.0, 2.0, 3.0]}),
            json!({"type": "LineString", "coordinates": [[0.0, 0.0], [1.0, 0.1, 2.0]]}),
            // Not closed: geo-types would close it.
            json!({"type": "Polygon", "coordinates": [[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]}),
            json!({"type": "Polygon", "coordinates": []}),
            json!({"type": "Curve", "coordinates": []}),
        ];
        for v in cases {
            assert_eq!(
                Shape::from_value(v.clone()),
                Shape::Json(Box::new(v.clone())),
                "{v}"
            );
            assert_eq!(Shape::from_value(v.clone()).to_value(), v);
        }
        assert_eq!(Shape::from_value(Value::Null), Shape::Null);
    }

    #[test]
    fn assembled_geometries_answer_as_the_same_shapes_do() {
        let square =
            |x: f64| json!([[[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 1.0], [x, 1.0], [x, 0.0]]]);
        let fc = json!({"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"a": 1}, "geometry": {"type": "Polygon", "coordinates": square(0.0)}},
            {"type": "Feature", "properties": {"a": "two"}, "geometry": null},
            {"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon", "coordinates": [square(1.0), square(3.0)]}},
            {"type": "Feature", "properties": {"a": [3]}, "geometry": {"type": "LineString", "coordinates": [[0.0, 2.0], [1.0, 2.5], [2.0, 2.0]]}},
            {"type": "Feature", "properties": {"a": null}, "geometry": {"type": "GeometryCollection", "geometries": [
                {"type": "Point", "coordinates": [5.0, 5.0]},
                {"type": "MultiLineString", "coordinates": [[[5.0, 0.0], [6.0, 1.0], [7.0, 0.0]]]}]}},
            {"type": "Feature", "properties": {"a": 6}, "geometry": {"type": "MultiPoint", "coordinates": [[9.0, 9.0]]}},
        ]});
        let mut shapes = Features::from_value(&fc, vec!["a".into()]);
        let mut assembled = shapes.clone();
        let taken = assembled.take_shapes();
        let had: Vec<bool> = taken.iter().map(|s| !matches!(s, Shape::Null)).collect();
        let empty = || Geometry::GeometryCollection(GeometryCollection(vec![]));
        let geoms: Vec<Geometry> = taken
            .into_iter()
            .map(|s| match s {
                Shape::Plane(g) => *g,
                _ => empty(),
            })
            .collect();
        let coverage = bzspline_geo::Coverage::new(geoms).unwrap();
        let smoothed = coverage
            .topology()
            .smooth(&bzspline_geo::SmoothOptions::default().tolerance(1e-3))
            .unwrap();
        let whole = coverage.assemble(&smoothed.arcs);
        assembled.put_assembled(coverage.into_assembled(smoothed.arcs), had.clone());
        let _ = shapes.take_shapes();
        shapes.put_shapes(
            whole
                .into_iter()
                .zip(&had)
                .map(|(g, &h)| {
                    if h {
                        Shape::Plane(Box::new(g))
                    } else {
                        Shape::Null
                    }
                })
                .collect(),
        );
        let (a, s): (&dyn Source, &dyn Source) = (&assembled, &shapes);
        for i in 0..fc["features"].as_array().unwrap().len() {
            assert_eq!(a.geometry(i), s.geometry(i), "{i}");
            assert_eq!(a.geometry_type(i), s.geometry_type(i), "{i}");
            assert_eq!(a.has_z(i), s.has_z(i), "{i}");
            assert_eq!(a.properties(i), s.properties(i), "{i}");
        }
        assert_eq!(a.geometry_type(1), None);
        assert_eq!(a.geometry_type(4), Some("GeometryCollection"));
        assert!(assembled.is_plane());
        assert_eq!(assembled, shapes);
        assert_eq!(assembled.to_value(), shapes.to_value());
        // Taken again, the assembled geometries come back as shapes.
        let again = assembled.take_shapes();
        assembled.put_shapes(again);
        assert_eq!(assembled, shapes);
    }

    #[test]
    fn features_are_made_back_in_the_fields_order() {
        let fc = json!({"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"b": 1, "a": "x", "extra": true},
             "geometry": {"type": "Point", "coordinates": [0.0, 1.0]}},
            {"type": "Feature", "properties": {"a": null}, "geometry": null},
        ]});
        let f = Features::from_value(&fc, vec!["a".into(), "b".into()]);
        assert!(f.is_plane());
        let back = f.to_value();
        assert_eq!(back["features"][0]["properties"], json!({"a": "x", "b": 1}));
        assert_eq!(
            back["features"][0]["geometry"],
            fc["features"][0]["geometry"]
        );
        assert_eq!(
            back["features"][1],
            json!({"type": "Feature", "properties": {"a": null, "b": null}, "geometry": null})
        );
        // A table may name two fields alike (a .dbf): the property holds
        // one value, as in GeoJSON.
        let mut twice = Features::new(vec!["a".into(), "a".into()]);
        twice.push(
            fc["features"][0]["properties"].as_object().unwrap().clone(),
            Value::Null,
        );
        assert_eq!(
            twice.to_value()["features"][0]["properties"],
            json!({"a": "x"})
        );
        let keys: Vec<&String> = back["features"][0]["properties"]
            .as_object()
            .unwrap()
            .keys()
            .collect();
        assert_eq!(keys, ["a", "b"]);
    }
}
