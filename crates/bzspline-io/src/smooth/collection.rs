//! A GeoJSON FeatureCollection read one feature at a time: each feature
//! checked and converted as the whole document would be
//! ([`crate::input::check_document`], geojson's types), its geometry kept
//! as geo-types and the rest of it (properties, id, foreign members) as the
//! compact JSON text of geojson's [`Feature`] without coordinates, read
//! again when the feature is written, never the document's JSON tree. A collection in the plane is smoothed where it is and written a
//! feature at a time, to the same text as the document would give; anything
//! else (positions with z or of more than 3 numbers, a refusal of any kind,
//! another type of document) is left to the document's path, which reads it
//! again and says what is wrong.

use std::borrow::Cow;
use std::fmt;
use std::sync::OnceLock;

use geojson::{Feature, FeatureCollection, GeometryValue};
use serde::de::{self, DeserializeSeed, MapAccess, SeqAccess, Visitor};
use serde::Deserializer;
use serde_json::{Map, Value};

use bzspline_geo::Assembled;

use crate::features::{Source, NULL};

/// One feature: geojson's as compact JSON, its geometry's coordinates
/// taken out (an empty collection in their place), and that geometry in the
/// plane. The text takes a few bytes beyond the properties' own, where
/// geojson's `Feature` with its maps of JSON values takes hundreds.
struct Item {
    rest: Box<str>,
    /// Whether the feature has a geometry.
    geometry: bool,
    shape: Option<geo_types::Geometry<f64>>,
}

/// A FeatureCollection read one feature at a time.
pub struct Collection {
    /// The collection without features (its bbox and foreign members).
    head: FeatureCollection,
    items: Vec<Item>,
    /// The geometries smoothed as one coverage, each put together when the
    /// feature is written ([`Collection::put_assembled`]).
    assembled: Option<Assembled>,
    /// Every feature's properties, read from its text the first time a
    /// writer of another format asks for one ([`Source`]).
    properties: OnceLock<Vec<Map<String, Value>>>,
}

/// A feature as the document's path would take it, `None` where that path
/// would refuse it, cut its positions or find z.
fn item(mut v: Value) -> Option<Item> {
    if v.get("type").and_then(Value::as_str) != Some("Feature") {
        return None;
    }
    if crate::input::check_document(&mut v).ok()? > 0 {
        return None;
    }
    let mut feature: Feature = serde_json::from_value(v).ok()?;
    let shape = match feature.geometry.as_mut() {
        None => None,
        Some(g) => {
            if super::coverage::has_z(&g.value) {
                return None;
            }
            let shape = geo_types::Geometry::try_from(&g.value).ok()?;
            g.value = GeometryValue::GeometryCollection { geometries: vec![] };
            Some(shape)
        }
    };
    let rest = serde_json::to_string(&feature).ok()?.into_boxed_str();
    Some(Item {
        rest,
        geometry: feature.geometry.is_some(),
        shape,
    })
}

/// The `features` array, one feature at a time.
struct Features;

impl<'de> DeserializeSeed<'de> for Features {
    type Value = Vec<Item>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Vec<Item>, D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Features {
    type Value = Vec<Item>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an array of features")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<Item>, A::Error> {
        let mut items = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1 << 16));
        while let Some(v) = seq.next_element::<Value>()? {
            items.push(item(v).ok_or_else(|| de::Error::custom("declined"))?);
        }
        Ok(items)
    }
}

/// The document: its members, the features apart.
struct Top;

impl<'de> Visitor<'de> for Top {
    type Value = (Map<String, Value>, Vec<Item>);
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a FeatureCollection")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut members = Map::new();
        let mut items = None;
        while let Some(key) = map.next_key::<String>()? {
            if key == "features" {
                if items.is_some() {
                    return Err(de::Error::custom("declined"));
                }
                items = Some(map.next_value_seed(Features)?);
            } else {
                let v: Value = map.next_value()?;
                if members.insert(key, v).is_some() {
                    return Err(de::Error::custom("declined"));
                }
            }
        }
        let items = items.ok_or_else(|| de::Error::custom("declined"))?;
        Ok((members, items))
    }
}

impl Collection {
    /// Reads `text` as a FeatureCollection in the plane, one feature at a
    /// time; `None` for anything the document's path must read (what it
    /// would refuse included).
    #[must_use]
    pub fn read(text: &str) -> Option<Collection> {
        Self::parse(serde_json::Deserializer::from_str(text))
    }

    /// Reads a FeatureCollection in the plane from `reader` as [`Collection::read`]
    /// reads its text (a UTF-8 byte-order mark skipped), never holding the
    /// text: only each feature's while it is read. `None` as for
    /// [`Collection::read`], and where reading fails.
    #[must_use]
    pub fn read_from(mut reader: impl std::io::BufRead) -> Option<Collection> {
        if reader.fill_buf().ok()?.starts_with(b"\xEF\xBB\xBF") {
            reader.consume(3);
        }
        Self::parse(serde_json::Deserializer::from_reader(reader))
    }

    fn parse<'de, R: serde_json::de::Read<'de>>(
        mut de: serde_json::Deserializer<R>,
    ) -> Option<Collection> {
        let (mut members, items) = de.deserialize_map(Top).ok()?;
        de.end().ok()?;
        if members.get("type").and_then(Value::as_str) != Some("FeatureCollection") {
            return None;
        }
        members.insert("features".to_owned(), Value::Array(Vec::new()));
        let head: FeatureCollection = serde_json::from_value(Value::Object(members)).ok()?;
        Some(Collection {
            head,
            items,
            assembled: None,
            properties: OnceLock::new(),
        })
    }

    /// The number of features.
    #[must_use]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Each feature's geometry (an empty collection for none), taken out to
    /// be smoothed.
    pub fn take_geometries(&mut self) -> Vec<geo_types::Geometry<f64>> {
        let empty =
            || geo_types::Geometry::GeometryCollection(geo_types::GeometryCollection(vec![]));
        let assembled = self.assembled.take();
        self.items
            .iter_mut()
            .enumerate()
            .map(|(k, i)| match &assembled {
                Some(a) if i.geometry => a.get(k),
                Some(_) => empty(),
                None => i.shape.take().unwrap_or_else(empty),
            })
            .collect()
    }

    /// Puts smoothed geometries back, one for each feature, in order: those
    /// of features without geometry are dropped.
    pub fn put_geometries(&mut self, geometries: Vec<geo_types::Geometry<f64>>) {
        for (item, g) in self.items.iter_mut().zip(geometries) {
            if item.geometry {
                item.shape = Some(g);
            }
        }
    }

    /// Puts the geometries smoothed as one coverage back, one for each
    /// feature in order, each put together when the feature is written:
    /// those of features without geometry are dropped.
    ///
    /// # Panics
    ///
    /// When `assembled` is not one geometry a feature.
    pub fn put_assembled(&mut self, assembled: Assembled) {
        assert_eq!(assembled.len(), self.len(), "one geometry a feature");
        for item in &mut self.items {
            item.shape = None;
        }
        self.assembled = Some(assembled);
    }

    /// Feature `i` as the document's path gives it: read again from its
    /// text, its geometry's coordinates put back and the geometry's bbox
    /// (no longer tight) dropped (while its geometry is taken out to be
    /// smoothed, without coordinates).
    fn feature(&self, i: usize) -> serde_json::Result<Feature> {
        let item = &self.items[i];
        let mut f = self.without_coordinates(i)?;
        let assembled = match &self.assembled {
            Some(a) if item.geometry => Some(a.get(i)),
            _ => None,
        };
        if let (Some(g), Some(shape)) = (
            f.geometry.as_mut(),
            assembled.as_ref().or(item.shape.as_ref()),
        ) {
            g.value = GeometryValue::from(shape);
            g.bbox = None;
        }
        Ok(f)
    }

    /// Feature `i` read again from its text, its geometry without
    /// coordinates.
    fn without_coordinates(&self, i: usize) -> serde_json::Result<Feature> {
        serde_json::from_str(&self.items[i].rest)
    }

    /// Every feature's properties (empty for none), read once.
    fn all_properties(&self) -> &[Map<String, Value>] {
        self.properties.get_or_init(|| {
            (0..self.len())
                .map(|i| {
                    self.without_coordinates(i)
                        .ok()
                        .and_then(|f| f.properties)
                        .unwrap_or_default()
                })
                .collect()
        })
    }

    /// Writes the collection as compact GeoJSON, a feature at a time, to
    /// the text the whole document would be written as.
    ///
    /// # Errors
    ///
    /// The writer's.
    pub fn write_geojson(&self, mut w: impl std::io::Write) -> std::io::Result<()> {
        let mut head = Vec::new();
        crate::model::write_json_compact(&mut head, &self.head)?;
        // Type and bbox come first, and hold no such text.
        let marker: &[u8] = br#""features":[]"#;
        let at = head
            .windows(marker.len())
            .position(|w| w == marker)
            .ok_or_else(|| std::io::Error::other("no features member"))?;
        let open = at + marker.len() - 1;
        w.write_all(&head[..open])?;
        for i in 0..self.len() {
            if i > 0 {
                w.write_all(b",")?;
            }
            crate::model::write_json_compact(&mut w, &self.feature(i)?)?;
        }
        w.write_all(&head[open..])
    }
}

impl Source for Collection {
    fn count(&self) -> usize {
        self.len()
    }
    fn geometry(&self, i: usize) -> Cow<'_, Value> {
        let g = self.feature(i).ok().and_then(|f| f.geometry);
        Cow::Owned(g.map_or(Value::Null, |g| {
            serde_json::to_value(g).unwrap_or(Value::Null)
        }))
    }
    fn property(&self, i: usize, name: &str) -> Cow<'_, Value> {
        Cow::Borrowed(self.all_properties()[i].get(name).unwrap_or(&NULL))
    }
    fn properties(&self, i: usize) -> Cow<'_, Map<String, Value>> {
        Cow::Borrowed(&self.all_properties()[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::Unit;
    use crate::smooth::job::{Job, Settings};
    use serde_json::json;

    fn square(x: f64, y: f64, s: f64) -> Value {
        json!([[[x, y], [x + s, y], [x + s, y + s], [x, y + s], [x, y]]])
    }

    /// A collection with what a document may carry: bbox and foreign
    /// members at both levels, ids of both kinds, null and missing
    /// properties and geometry, every geometry type, odd numbers.
    fn collection() -> Value {
        json!({"type": "FeatureCollection", "name": "edge", "bbox": [0, 0, 5, 5],
            "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:OGC:1.3:CRS84"}},
            "features": [
            {"type": "Feature", "id": "a", "bbox": [0, 0, 1, 1], "fm": true,
             "properties": {"n": 1, "s": "é", "x": null, "deep": {"k": [1, 2]}},
             "geometry": {"type": "Polygon", "bbox": [0, 0, 1, 1], "extra": 7, "coordinates": square(0.0, 0.0, 1.0)}},
            {"type": "Feature", "id": 7, "properties": null, "geometry": {"type": "Polygon", "coordinates": square(1.0, 0.0, 1.0)}},
            {"type": "Feature", "geometry": null, "properties": {"n": 2}},
            {"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon",
             "coordinates": [square(0.0, 1.0, 1.0), square(3.0, 3.0, 0.5)]}},
            {"type": "Feature", "properties": {"f": -0.0, "g": 1e300, "h": 12_345_678_901_234_567_890_u64},
             "geometry": {"type": "LineString", "coordinates": [[0, 2], [1, 2.5], [2, 2], [3, 2.5]]}},
            {"type": "Feature", "properties": {"p": true}, "geometry": {"type": "Point", "coordinates": [4, 4]}},
            {"type": "Feature", "properties": {"p": false}, "geometry": {"type": "GeometryCollection", "geometries": [
                {"type": "LineString", "coordinates": [[4, 0], [4.5, 1], [5, 0]]},
                {"type": "MultiPoint", "coordinates": [[1, 1], [2, 2]]}]}},
        ]})
    }

    fn settings(independent: bool) -> Settings {
        let mut s = Settings::default();
        s.options.tolerance = Some(0.01);
        s.independent = independent;
        s
    }

    /// The text and summary of `text` read a feature at a time, and by the
    /// document's path.
    fn both(text: &str, settings: &Settings) -> ((String, String), (String, String)) {
        let mut job = Job::new(settings.clone());
        let mut c = job.read_collection(text).expect("read a feature at a time");
        job.collection("t", &mut c).unwrap();
        let mut streamed = Vec::new();
        c.write_geojson(&mut streamed).unwrap();
        let streamed = (String::from_utf8(streamed).unwrap(), job.summary());
        // Read from a reader (after a byte-order mark), a few bytes at a
        // time: the same collection.
        let mut job = Job::new(settings.clone());
        let bytes = [b"\xEF\xBB\xBF", text.as_bytes()].concat();
        let reader = std::io::BufReader::with_capacity(7, bytes.as_slice());
        let mut c = job
            .read_collection_from(reader)
            .expect("read from a reader");
        job.collection("t", &mut c).unwrap();
        let mut from_reader = Vec::new();
        c.write_geojson(&mut from_reader).unwrap();
        let from_reader = (String::from_utf8(from_reader).unwrap(), job.summary());
        assert_eq!(from_reader, streamed, "read from a reader");
        let mut job = Job::new(settings.clone());
        let out = job
            .document("t", serde_json::from_str(text).unwrap())
            .unwrap();
        let mut whole = Vec::new();
        crate::model::write_json_compact(&mut whole, &out).unwrap();
        let whole = (String::from_utf8(whole).unwrap(), job.summary());
        (streamed, whole)
    }

    #[test]
    fn a_collection_read_a_feature_at_a_time_gives_what_its_document_gives() {
        let doc = collection();
        for independent in [false, true] {
            let (a, b) = both(&doc.to_string(), &settings(independent));
            assert_eq!(a, b, "independent: {independent}");
        }
        // The members in another order, and pretty-printed.
        let mut reordered = serde_json::Map::new();
        for k in ["features", "bbox", "name", "type", "crs"] {
            reordered.insert(k.to_owned(), doc[k].clone());
        }
        let text = serde_json::to_string_pretty(&reordered).unwrap();
        let (a, b) = both(&text, &settings(false));
        assert_eq!(a, b);
        // Many features at random, in metres on longitude and latitude.
        let mut rng = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        let features: Vec<Value> = (0..300)
            .map(|i| {
                let (x, y) = (170.0 + 0.01 * f64::from(i % 20), 60.0 + 0.01 * f64::from(i / 20));
                let mut ring = vec![json!([x, y])];
                for k in 1..8 {
                    let t = f64::from(k) / 8.0 * std::f64::consts::TAU;
                    let r = 0.004 * (0.7 + 0.3 * next());
                    ring.push(json!([x + r * t.cos(), y + r * t.sin()]));
                }
                ring[0] = json!([x + 0.004, y]);
                ring.push(ring[0].clone());
                json!({"type": "Feature", "properties": {"i": i}, "geometry": {"type": "Polygon", "coordinates": [ring]}})
            })
            .collect();
        let text = json!({"type": "FeatureCollection", "features": features}).to_string();
        let mut s = settings(false);
        s.tolerance_unit = Unit::Metres;
        s.options.tolerance = Some(20.0);
        let (a, b) = both(&text, &s);
        assert_eq!(a, b);
    }

    #[test]
    fn a_collection_gives_each_features_properties_and_geometry() {
        let doc = collection();
        let job = Job::new(settings(false));
        let c = job.read_collection(&doc.to_string()).unwrap();
        let features = doc["features"].as_array().unwrap();
        assert_eq!(c.count(), features.len());
        for (i, f) in features.iter().enumerate() {
            let want = f["properties"].as_object().cloned().unwrap_or_default();
            assert_eq!(*c.properties(i), want, "feature {i}");
            for (k, v) in &want {
                assert_eq!(*c.property(i, k), *v, "feature {i}, {k}");
            }
            assert_eq!(*c.property(i, "absent"), Value::Null);
            let g = c.geometry(i);
            assert_eq!(g["type"], f["geometry"]["type"], "feature {i}");
        }
    }

    #[test]
    fn anything_else_is_left_to_the_document() {
        let doc = collection();
        let mut z = doc.clone();
        z["features"][1]["geometry"]["coordinates"][0][1] = json!([2, 0, 5]);
        let mut cut = doc.clone();
        cut["features"][1]["geometry"]["coordinates"][0][1] = json!([2, 0, 5, 6]);
        let mut not_feature = doc.clone();
        not_feature["features"][2] = json!({"type": "Point", "coordinates": [0, 0]});
        let mut open = doc.clone();
        open["features"][1]["geometry"]["coordinates"][0]
            .as_array_mut()
            .unwrap()
            .pop();
        let mut other = doc.clone();
        other["type"] = json!("Topology");
        let mut bad_bbox = doc.clone();
        bad_bbox["bbox"] = json!("x");
        let declined = [
            z.to_string(),
            cut.to_string(),
            not_feature.to_string(),
            open.to_string(),
            other.to_string(),
            bad_bbox.to_string(),
            doc["features"][0].to_string(),
            doc["features"][0]["geometry"].to_string(),
            doc.to_string() + " x",
            r#"{"type": "FeatureCollection", "features": [], "features": []}"#.to_owned(),
            r#"{"type": "FeatureCollection"}"#.to_owned(),
            r#"{"type": "FeatureCollection", "features": {}}"#.to_owned(),
            "[1, 2]".to_owned(),
        ];
        let job = Job::new(settings(false));
        for text in declined {
            assert!(job.read_collection(&text).is_none(), "{text}");
            assert!(
                job.read_collection_from(text.as_bytes()).is_none(),
                "{text}"
            );
        }
        // Text that is not UTF-8 in a string, from a reader.
        let latin1 = doc.to_string().replace("\"a\"", "\"\u{e9}\"");
        assert!(job.read_collection(&latin1).is_some());
        let mut bytes = latin1.into_bytes();
        let at = bytes.windows(2).position(|w| w == [0xC3, 0xA9]).unwrap();
        bytes.splice(at..at + 2, [0xE9]);
        assert!(job.read_collection_from(bytes.as_slice()).is_none());
        let mut topojson = settings(false);
        topojson.output = crate::smooth::job::Output::Topojson;
        assert!(Job::new(topojson)
            .read_collection(&doc.to_string())
            .is_none());
    }
}
