//! TopoJSON in and out: a `"type": "Topology"` document read into a
//! [`bzspline_geo::Topology`] (arcs decoded, quantized or not, with its
//! `transform` applied), and written back as TopoJSON with smoothed arcs
//! (absolute coordinates, no transform) or as GeoJSON features.
//!
//! Specification: <https://github.com/topojson/topojson-specification>.

use anyhow::{anyhow, bail, Result};
use bzspline_geo::{ArcRef, Arcs, ChainKind, Chains, Topology};
use geo_types::Coord;
use serde::ser::{Serialize, SerializeMap, Serializer};
use serde_json::{json, Map, Value};
use std::borrow::Cow;
use std::cell::Cell;

use crate::features::{has_z, Source, GEOMETRY_TYPES, NULL};

/// A TopoJSON document and its topology.
pub struct TopoDoc {
    /// The document as read (objects, properties, foreign members).
    root: Map<String, Value>,
    /// `(scale, translate)` of a quantized topology.
    transform: Option<([f64; 2], [f64; 2])>,
    /// The arcs and the chains of every object, in the order of the objects.
    pub topology: Topology,
    /// Where each chain comes from, for messages.
    pub origins: Vec<String>,
    /// Geometries at the top of the objects (a collection's members).
    pub features: usize,
}

/// True for a JSON value that is a TopoJSON Topology.
pub fn is_topology(v: &Value) -> bool {
    v.get("type").and_then(Value::as_str) == Some("Topology")
}

fn number(v: &Value, what: &dyn Fn() -> String) -> Result<f64> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => bail!("{}: {v} is not a finite number", what()),
    }
}

fn pair(v: &Value, what: &dyn Fn() -> String) -> Result<[f64; 2]> {
    match v.as_array().map(Vec::as_slice) {
        Some([a, b, ..]) => Ok([number(a, what)?, number(b, what)?]),
        _ => bail!("{}: expected an array of two numbers, got {v}", what()),
    }
}

/// Reads a Topology. Errors name the file, then the object and geometry, or
/// the arc and position, or the transform.
pub fn read(name: &str, v: Value) -> Result<TopoDoc> {
    let Value::Object(root) = v else {
        bail!("{name}: a Topology must be a JSON object");
    };
    let transform = match root.get("transform") {
        None | Some(Value::Null) => None,
        Some(t) => {
            let field = |f: &str| {
                t.get(f)
                    .ok_or_else(|| anyhow!("{name}: transform: no \"{f}\""))
            };
            let scale = pair(field("scale")?, &|| format!("{name}: transform: scale"))?;
            let translate = pair(field("translate")?, &|| {
                format!("{name}: transform: translate")
            })?;
            if scale.contains(&0.0) {
                bail!("{name}: transform: scale must not be zero (got {scale:?})");
            }
            Some((scale, translate))
        }
    };
    let arcs_v = match root.get("arcs") {
        Some(Value::Array(a)) => a,
        Some(_) => bail!("{name}: \"arcs\" must be an array"),
        None => bail!("{name}: a Topology needs \"arcs\""),
    };
    let mut arcs: Vec<Vec<Coord>> = Vec::with_capacity(arcs_v.len());
    for (ai, arc) in arcs_v.iter().enumerate() {
        let Some(ps) = arc.as_array() else {
            bail!("{name}: arc {ai}: expected an array of positions");
        };
        let mut out = Vec::with_capacity(ps.len());
        let (mut x, mut y) = (0.0, 0.0);
        for (pi, p) in ps.iter().enumerate() {
            let [a, b] = pair(p, &|| format!("{name}: arc {ai}, position {pi}"))?;
            let c = match transform {
                Some((s, t)) => {
                    x += a;
                    y += b;
                    Coord {
                        x: x * s[0] + t[0],
                        y: y * s[1] + t[1],
                    }
                }
                None => Coord { x: a, y: b },
            };
            if !(c.x.is_finite() && c.y.is_finite()) {
                bail!("{name}: arc {ai}, position {pi}: the decoded position is not finite");
            }
            out.push(c);
        }
        if out.is_empty() {
            bail!("{name}: arc {ai} has no positions");
        }
        arcs.push(out);
    }
    let Some(Value::Object(objects)) = root.get("objects") else {
        bail!("{name}: a Topology needs \"objects\", an object of named geometries");
    };
    let mut r = Reader {
        name,
        arcs: &arcs,
        chains: Chains::new(),
        polygons: Vec::new(),
        origins: Vec::new(),
    };
    for (oname, o) in objects {
        // Names and types are quoted with escapes: a message stays one line.
        r.geometry(o, &format!("object {oname:?}"))?;
    }
    let features = objects
        .values()
        .map(|o| match o.get("geometries") {
            Some(Value::Array(gs)) => gs.len(),
            _ => 1,
        })
        .sum();
    let (chains, polygons, origins) = (r.chains, r.polygons, r.origins);
    let topology =
        Topology::from_arcs(arcs, chains, polygons).map_err(|e| anyhow!("{name}: {e}"))?;
    let mut root = root;
    // Decoded into the topology: the arcs' JSON is let go of (the key keeps
    // its place for the document written back).
    if let Some(a) = root.get_mut("arcs") {
        *a = Value::Null;
    }
    Ok(TopoDoc {
        root,
        transform,
        topology,
        origins,
        features,
    })
}

struct Reader<'a> {
    name: &'a str,
    arcs: &'a [Vec<Coord>],
    chains: Chains,
    polygons: Vec<Vec<usize>>,
    origins: Vec<String>,
}

impl Reader<'_> {
    fn refs(&self, v: &Value, at: &str) -> Result<Vec<ArcRef>> {
        let name = self.name;
        let Some(list) = v.as_array() else {
            bail!("{name}: {at}: expected an array of arc indices, got {v}");
        };
        list.iter()
            .map(|k| {
                let Some(k) = k.as_i64() else {
                    bail!("{name}: {at}: arc index {k} is not an integer");
                };
                let r = ArcRef::from_topojson(k);
                if r.index() >= self.arcs.len() {
                    bail!(
                        "{name}: {at}: arc {k} is out of range (there are {} arcs)",
                        self.arcs.len()
                    );
                }
                Ok(r)
            })
            .collect()
    }

    fn chain(&mut self, kind: ChainKind, v: &Value, at: String) -> Result<usize> {
        let arcs = self.refs(v, &at)?;
        self.chains.push(kind, arcs);
        self.origins.push(at);
        Ok(self.chains.len() - 1)
    }

    fn polygon(&mut self, v: &Value, at: &str) -> Result<()> {
        let Some(rings) = v.as_array() else {
            bail!("{}: {at}: expected an array of rings", self.name);
        };
        let mut ids = Vec::with_capacity(rings.len());
        for (ri, ring) in rings.iter().enumerate() {
            ids.push(self.chain(ChainKind::Ring, ring, format!("{at}, ring {ri}"))?);
        }
        self.polygons.push(ids);
        Ok(())
    }

    fn list<'v>(&self, v: &'v Value, at: &str) -> Result<&'v Vec<Value>> {
        v.as_array()
            .ok_or_else(|| anyhow!("{}: {at}: expected an array, got {v}", self.name))
    }

    /// Reads one geometry object (recursively for collections).
    fn geometry(&mut self, g: &Value, at: &str) -> Result<()> {
        let name = self.name;
        let ty = g.get("type").and_then(Value::as_str);
        let arcs = || {
            g.get("arcs")
                .ok_or_else(|| anyhow!("{name}: {at}: a {} needs \"arcs\"", ty.unwrap_or("?")))
        };
        match ty {
            None if g.get("type").is_some_and(Value::is_null) => {}
            Some("Point" | "MultiPoint") => {}
            Some("LineString") => {
                self.chain(ChainKind::Line, arcs()?, at.to_owned())?;
            }
            Some("MultiLineString") => {
                for (li, l) in self.list(arcs()?, at)?.iter().enumerate() {
                    self.chain(ChainKind::Line, l, format!("{at}, line {li}"))?;
                }
            }
            Some("Polygon") => self.polygon(arcs()?, at)?,
            Some("MultiPolygon") => {
                for (pi, p) in self.list(arcs()?, at)?.iter().enumerate() {
                    self.polygon(p, &format!("{at}, polygon {pi}"))?;
                }
            }
            Some("GeometryCollection") => {
                let Some(gs) = g.get("geometries") else {
                    bail!("{name}: {at}: a GeometryCollection needs \"geometries\"");
                };
                for (gi, sub) in self.list(gs, at)?.iter().enumerate() {
                    self.geometry(sub, &format!("{at}, geometry {gi}"))?;
                }
            }
            Some(other) => bail!("{name}: {at}: unknown geometry type {other:?}"),
            None => bail!("{name}: {at}: a geometry object needs a \"type\""),
        }
        Ok(())
    }
}

impl TopoDoc {
    /// The error with the object and geometry of its chain (or of the first
    /// chain that uses its arc).
    pub fn describe(&self, e: &bzspline_geo::Error) -> String {
        let chain = self.topology.chain_of(e);
        match chain.and_then(|c| self.origins.get(c)) {
            Some(at) => format!("{at}: {e}"),
            None => e.to_string(),
        }
    }

    /// A position of a Point or MultiPoint, decoded.
    fn point(&self, v: &Value) -> Value {
        match (self.transform, v.as_array().map(Vec::as_slice)) {
            (Some((s, t)), Some([x, y, rest @ ..])) => {
                let mut p = vec![
                    json!(x.as_f64().unwrap_or(0.0) * s[0] + t[0]),
                    json!(y.as_f64().unwrap_or(0.0) * s[1] + t[1]),
                ];
                p.extend(rest.iter().cloned());
                Value::Array(p)
            }
            _ => v.clone(),
        }
    }

    fn points(&self, g: &Value) -> Option<Value> {
        let coords = g.get("coordinates")?;
        Some(match g.get("type").and_then(Value::as_str) {
            Some("Point") => self.point(coords),
            _ => Value::Array(
                coords
                    .as_array()
                    .map(|ps| ps.iter().map(|p| self.point(p)).collect())
                    .unwrap_or_default(),
            ),
        })
    }

    /// The document with `arcs` (the topology's, smoothed) in place of its
    /// own, unquantized: no transform, no bounding box; points decoded.
    pub fn to_topojson(&self, arcs: &Arcs) -> Value {
        let mut root = self.root.clone();
        root.remove("transform");
        root.remove("bbox");
        root.insert(
            "arcs".into(),
            Value::Array(
                arcs.iter()
                    .map(|a| Value::Array(a.iter().map(|c| json!([c.x, c.y])).collect()))
                    .collect(),
            ),
        );
        if self.transform.is_some() {
            if let Some(Value::Object(objects)) = root.get_mut("objects") {
                for o in objects.values_mut() {
                    self.decode_points(o);
                }
            }
        }
        Value::Object(root)
    }

    /// Writes [`TopoDoc::to_topojson`] compact, its arcs a position at a
    /// time: the same text as that value written whole.
    ///
    /// # Errors
    ///
    /// Write errors of `w`.
    pub fn write_topojson(&self, arcs: &Arcs, mut w: impl std::io::Write) -> std::io::Result<()> {
        let mut root = self.root.clone();
        root.remove("transform");
        root.remove("bbox");
        root.insert("arcs".into(), Value::Null);
        if self.transform.is_some() {
            if let Some(Value::Object(objects)) = root.get_mut("objects") {
                for o in objects.values_mut() {
                    self.decode_points(o);
                }
            }
        }
        use crate::model::write_json_compact as json;
        w.write_all(b"{")?;
        for (i, (k, v)) in root.iter().enumerate() {
            if i > 0 {
                w.write_all(b",")?;
            }
            json(&mut w, k)?;
            w.write_all(b":")?;
            if k != "arcs" {
                json(&mut w, v)?;
                continue;
            }
            w.write_all(b"[")?;
            for (j, a) in arcs.iter().enumerate() {
                w.write_all(if j > 0 { b",[" } else { b"[" })?;
                for (m, c) in a.iter().enumerate() {
                    if m > 0 {
                        w.write_all(b",")?;
                    }
                    json(&mut w, &[c.x, c.y])?;
                }
                w.write_all(b"]")?;
            }
            w.write_all(b"]")?;
        }
        w.write_all(b"}")
    }

    fn decode_points(&self, g: &mut Value) {
        if let Some(Value::Array(gs)) = g.get_mut("geometries") {
            gs.iter_mut().for_each(|s| self.decode_points(s));
        }
        if let Some(p) = self.points(g) {
            g["coordinates"] = p;
        }
        if let Some(m) = g.as_object_mut() {
            m.remove("bbox");
        }
    }

    /// Chain `i`'s positions from `arcs`, as a GeoJSON line or ring: a ring
    /// collapsed by quantization repeats its first until it has the 4
    /// GeoJSON asks for, as topojson-client writes it.
    fn chain_positions(&self, i: usize, arcs: &Arcs) -> Vec<Coord> {
        let mut c = self.topology.chain_coords(i, arcs);
        if self.topology.chain(i).kind == ChainKind::Ring && !c.is_empty() {
            while c.len() < 4 {
                c.push(c[0]);
            }
        }
        c
    }

    /// GeoJSON features of every object (or only `object`), with the lines
    /// and rings assembled from `arcs`: a GeometryCollection object gives one
    /// feature per member, any other object one feature.
    pub fn to_geojson(&self, arcs: &Arcs, object: Option<&str>) -> Result<Value> {
        let f = self.geojson_features(arcs, object)?;
        let features: Vec<Value> = (0..f.members.len()).map(|i| f.feature(i)).collect();
        Ok(json!({"type": "FeatureCollection", "features": features}))
    }

    /// The features of [`TopoDoc::to_geojson`], each made when it is asked
    /// for ([`Source`]) or written ([`GeojsonFeatures::write_geojson`]), so
    /// that their positions are never all held as JSON values.
    ///
    /// # Errors
    ///
    /// `object` names no object of the Topology.
    pub fn geojson_features<'a>(
        &'a self,
        arcs: &'a Arcs,
        object: Option<&str>,
    ) -> Result<GeojsonFeatures<'a>> {
        let mut members = Vec::new();
        if let Some(Value::Object(objects)) = self.root.get("objects") {
            if let Some(o) = object {
                if !objects.contains_key(o) {
                    let names: Vec<&str> = objects.keys().map(String::as_str).collect();
                    bail!("no object {o:?} in the Topology (it has {names:?})");
                }
            }
            let mut next = 0usize;
            for (oname, o) in objects {
                let wanted = object.is_none_or(|w| w == oname);
                let geometries = match (o.get("type").and_then(Value::as_str), o.get("geometries"))
                {
                    (Some("GeometryCollection"), Some(Value::Array(gs))) => gs.iter().collect(),
                    _ => vec![o],
                };
                for g in geometries {
                    if wanted {
                        members.push((g, next));
                    }
                    next += chains_in(g);
                }
            }
        }
        Ok(GeojsonFeatures {
            doc: self,
            arcs,
            members,
        })
    }

    /// The GeoJSON geometry of a geometry object; `next` counts chains in the
    /// order [`read`] met them.
    fn geometry(&self, g: &Value, arcs: &Arcs, next: &mut usize) -> Value {
        let at = Cell::new(*next);
        let out = GeometryOut {
            doc: self,
            arcs,
            g,
            next: &at,
        };
        // Into a value: string keys and numbers only, which cannot fail.
        let v = serde_json::to_value(out).unwrap_or(Value::Null);
        *next = at.get();
        v
    }

    /// The geometry of an object with no arcs: a Point or MultiPoint
    /// decoded, anything else null.
    fn arcless_geometry(&self, g: &Value) -> Value {
        match g.get("type").and_then(Value::as_str) {
            ty @ Some("Point" | "MultiPoint") => {
                json!({"type": ty, "coordinates": self.points(g).unwrap_or(json!([]))})
            }
            _ => Value::Null,
        }
    }
}

/// How many chains [`TopoDoc::geometry`] takes for the geometry object `g`.
fn chains_in(g: &Value) -> usize {
    let count = |v: Option<&Value>| v.and_then(Value::as_array).map_or(0, Vec::len);
    let a = g.get("arcs");
    match g.get("type").and_then(Value::as_str) {
        Some("LineString") => 1,
        Some("MultiLineString" | "Polygon") => count(a),
        Some("MultiPolygon") => a
            .and_then(Value::as_array)
            .map_or(0, |ps| ps.iter().map(|p| count(Some(p))).sum()),
        Some("GeometryCollection") => g
            .get("geometries")
            .and_then(Value::as_array)
            .map_or(0, |gs| gs.iter().map(chains_in).sum()),
        _ => 0,
    }
}

/// The GeoJSON features of a Topology's objects with the lines and rings
/// assembled from given arcs ([`TopoDoc::geojson_features`]), one at a time.
pub struct GeojsonFeatures<'a> {
    doc: &'a TopoDoc,
    arcs: &'a Arcs,
    /// Each feature's geometry object and its first chain.
    members: Vec<(&'a Value, usize)>,
}

impl GeojsonFeatures<'_> {
    /// Feature `i`, as [`TopoDoc::to_geojson`] gives it.
    #[must_use]
    pub fn feature(&self, i: usize) -> Value {
        let at = Cell::new(self.members[i].1);
        // Into a value: string keys and numbers only, which cannot fail.
        serde_json::to_value(self.out(i, &at)).unwrap_or(Value::Null)
    }

    /// Feature `i` to write, its chains counted in `at`.
    fn out<'b>(&'b self, i: usize, at: &'b Cell<usize>) -> FeatureOut<'b> {
        let g = self.members[i].0;
        FeatureOut {
            g,
            geometry: GeometryOut {
                doc: self.doc,
                arcs: self.arcs,
                g,
                next: at,
            },
        }
    }

    fn geometry_of(&self, i: usize) -> Value {
        let (g, mut next) = self.members[i];
        self.doc.geometry(g, self.arcs, &mut next)
    }

    /// Writes the FeatureCollection of [`TopoDoc::to_geojson`], compact,
    /// a feature at a time: the same text as that value written whole.
    ///
    /// # Errors
    ///
    /// Write errors of `w`.
    pub fn write_geojson(&self, mut w: impl std::io::Write) -> std::io::Result<()> {
        w.write_all(br#"{"type":"FeatureCollection","features":["#)?;
        for i in 0..self.members.len() {
            if i > 0 {
                w.write_all(b",")?;
            }
            let at = Cell::new(self.members[i].1);
            crate::model::write_json_compact(&mut w, &self.out(i, &at))?;
        }
        w.write_all(b"]}")
    }
}

/// A feature of geometry object `g`: type, id, properties and its
/// geometry written a chain at a time.
struct FeatureOut<'a> {
    g: &'a Value,
    geometry: GeometryOut<'a>,
}

impl Serialize for FeatureOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let id = self.g.get("id");
        let mut m = s.serialize_map(Some(3 + usize::from(id.is_some())))?;
        m.serialize_entry("type", "Feature")?;
        if let Some(id) = id {
            m.serialize_entry("id", id)?;
        }
        match self.g.get("properties") {
            Some(p) => m.serialize_entry("properties", p)?,
            None => m.serialize_entry("properties", &Map::new())?,
        }
        m.serialize_entry("geometry", &self.geometry)?;
        m.end()
    }
}

/// The GeoJSON geometry of geometry object `g`, its lines and rings the
/// chains from `next` on, written a chain at a time (and, through
/// [`TopoDoc::geometry`], made into a value).
struct GeometryOut<'a> {
    doc: &'a TopoDoc,
    arcs: &'a Arcs,
    g: &'a Value,
    next: &'a Cell<usize>,
}

/// `n` chains from `next` on, or (with `polygons`) a list of them for each.
struct ChainsOut<'a> {
    doc: &'a TopoDoc,
    arcs: &'a Arcs,
    next: &'a Cell<usize>,
    n: usize,
    polygons: Option<&'a [Value]>,
}

/// The chain at `next`.
struct ChainOut<'a>(&'a ChainsOut<'a>);

impl Serialize for ChainOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let ChainsOut {
            doc, arcs, next, ..
        } = self.0;
        let c = doc.chain_positions(next.get(), arcs);
        next.set(next.get() + 1);
        s.collect_seq(c.iter().map(|p| [p.x, p.y]))
    }
}

impl Serialize for ChainsOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let count = |v: &Value| v.as_array().map_or(0, Vec::len);
        match self.polygons {
            Some(ps) => s.collect_seq(ps.iter().map(|p| ChainsOut {
                n: count(p),
                polygons: None,
                ..*self
            })),
            None => s.collect_seq((0..self.n).map(|_| ChainOut(self))),
        }
    }
}

impl Serialize for GeometryOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (doc, arcs, g, next) = (self.doc, self.arcs, self.g, self.next);
        let a = g
            .get("arcs")
            .and_then(Value::as_array)
            .map_or(&[][..], Vec::as_slice);
        let chains = ChainsOut {
            doc,
            arcs,
            next,
            n: a.len(),
            polygons: None,
        };
        let ty = g.get("type").and_then(Value::as_str);
        let Some(
            t @ ("LineString" | "MultiLineString" | "Polygon" | "MultiPolygon"
            | "GeometryCollection"),
        ) = ty
        else {
            return doc.arcless_geometry(g).serialize(s);
        };
        let mut m = s.serialize_map(Some(2))?;
        m.serialize_entry("type", t)?;
        match t {
            "LineString" => m.serialize_entry("coordinates", &ChainOut(&chains))?,
            "MultiLineString" | "Polygon" => m.serialize_entry("coordinates", &chains)?,
            "MultiPolygon" => m.serialize_entry(
                "coordinates",
                &ChainsOut {
                    polygons: Some(a),
                    ..chains
                },
            )?,
            _ => m.serialize_entry(
                "geometries",
                &MembersOut {
                    doc,
                    arcs,
                    next,
                    gs: g
                        .get("geometries")
                        .and_then(Value::as_array)
                        .map_or(&[][..], Vec::as_slice),
                },
            )?,
        }
        m.end()
    }
}

/// The members of a GeometryCollection, written in turn.
struct MembersOut<'a> {
    doc: &'a TopoDoc,
    arcs: &'a Arcs,
    next: &'a Cell<usize>,
    gs: &'a [Value],
}

impl Serialize for MembersOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.gs.iter().map(|g| GeometryOut {
            doc: self.doc,
            arcs: self.arcs,
            g,
            next: self.next,
        }))
    }
}

impl Source for GeojsonFeatures<'_> {
    fn count(&self) -> usize {
        self.members.len()
    }
    fn geometry(&self, i: usize) -> Cow<'_, Value> {
        Cow::Owned(self.geometry_of(i))
    }
    fn property(&self, i: usize, name: &str) -> Cow<'_, Value> {
        let p = self.members[i].0.get("properties");
        Cow::Borrowed(p.and_then(|p| p.get(name)).unwrap_or(&NULL))
    }
    fn properties(&self, i: usize) -> Cow<'_, Map<String, Value>> {
        match self.members[i]
            .0
            .get("properties")
            .and_then(Value::as_object)
        {
            Some(m) => Cow::Borrowed(m),
            None => Cow::Owned(Map::new()),
        }
    }
    fn geometry_type(&self, i: usize) -> Option<&'static str> {
        let t = self.members[i].0.get("type").and_then(Value::as_str)?;
        GEOMETRY_TYPES.iter().copied().find(|k| *k == t)
    }
    fn has_z(&self, i: usize) -> bool {
        // Arcs are in the plane: only points can carry a z.
        match self.members[i].0.get("type").and_then(Value::as_str) {
            Some("Point" | "MultiPoint" | "GeometryCollection") => has_z(&self.geometry_of(i)),
            _ => false,
        }
    }
}

/// A Topology of the chains of a GeoJSON document's features, as
/// [`bzspline_geo::Coverage`] numbered them: one object `name`, a
/// GeometryCollection with a geometry per feature (id and properties kept).
pub fn from_features(
    name: &str,
    features: &[(Option<Value>, Value, Option<&geojson::GeometryValue>)],
    topology: &Topology,
    arcs: &Arcs,
) -> Value {
    let mut next = 0usize;
    let mut refs = || -> Value {
        let c = topology.chain(next);
        next += 1;
        Value::Array(c.arcs.iter().map(|r| json!(r.to_topojson())).collect())
    };
    let geometries: Vec<Value> = features
        .iter()
        .map(|(id, props, g)| {
            let mut o = match g {
                Some(g) => object(g, &mut refs),
                None => json!({"type": null}),
            };
            if let Some(id) = id {
                o["id"] = id.clone();
            }
            o["properties"] = props.clone();
            o
        })
        .collect();
    let arcs: Vec<Value> = arcs
        .iter()
        .map(|a| Value::Array(a.iter().map(|c| json!([c.x, c.y])).collect()))
        .collect();
    json!({
        "type": "Topology",
        "objects": {name: {"type": "GeometryCollection", "geometries": geometries}},
        "arcs": arcs,
    })
}

fn object(g: &geojson::GeometryValue, refs: &mut dyn FnMut() -> Value) -> Value {
    use geojson::GeometryValue as G;
    let pos = |p: &geojson::Position| json!(p.as_slice());
    match g {
        G::Point { coordinates } => json!({"type": "Point", "coordinates": pos(coordinates)}),
        G::MultiPoint { coordinates } => json!({
            "type": "MultiPoint",
            "coordinates": coordinates.iter().map(pos).collect::<Vec<_>>()
        }),
        G::LineString { .. } => json!({"type": "LineString", "arcs": refs()}),
        G::MultiLineString { coordinates } => json!({
            "type": "MultiLineString",
            "arcs": coordinates.iter().map(|_| refs()).collect::<Vec<_>>()
        }),
        G::Polygon { coordinates } => json!({
            "type": "Polygon",
            "arcs": coordinates.iter().map(|_| refs()).collect::<Vec<_>>()
        }),
        G::MultiPolygon { coordinates } => json!({
            "type": "MultiPolygon",
            "arcs": coordinates
                .iter()
                .map(|p| p.iter().map(|_| refs()).collect::<Vec<_>>())
                .collect::<Vec<_>>()
        }),
        G::GeometryCollection { geometries } => json!({
            "type": "GeometryCollection",
            "geometries": geometries.iter().map(|s| object(&s.value, refs)).collect::<Vec<_>>()
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_stay_on_one_line() {
        // Found by the parse_topojson fuzz target: a type with a newline.
        let v: Value = serde_json::from_str(
            r#"{"type":"Topology","objects":{"b\nc":{"type":"Li\neString","arcs":[0]}},"arcs":[[[0,0],[1,1]]]}"#,
        )
        .unwrap();
        let e = read("t.json", v).err().expect("refused").to_string();
        assert!(!e.contains('\n'), "{e}");
        assert!(
            e.contains(r#"object "b\nc": unknown geometry type "Li\neString""#),
            "{e}"
        );
    }

    /// The features and the Topology written a feature (or a position) at a
    /// time are the text of the values made whole, and the features a
    /// layer writer asks for are those values' features, for every kind of
    /// geometry object (nested collections, points decoded from a
    /// transform, a ring collapsed to three positions, a null geometry).
    #[test]
    fn written_as_they_go_the_outputs_are_the_whole_values() {
        let v: Value = serde_json::from_str(
            r#"{"type":"Topology","bbox":[0,0,10,10],"foreign":{"k":[1,2]},
                "transform":{"scale":[0.5,2],"translate":[1,-1]},
                "objects":{
                  "coll":{"type":"GeometryCollection","geometries":[
                    {"type":"Polygon","arcs":[[0]],"id":"a","properties":{"name":"A","n":1}},
                    {"type":"MultiPolygon","arcs":[[[1]],[[2]]],"id":7},
                    {"type":"LineString","arcs":[3],"properties":null},
                    {"type":"MultiLineString","arcs":[[3],[-4]],"bbox":[0,0,1,1]},
                    {"type":"Point","coordinates":[1,2,5],"properties":{"name":"P"}},
                    {"type":"MultiPoint","coordinates":[[1,2],[3,4]]},
                    {"type":null,"id":"nothing"},
                    {"type":"GeometryCollection","geometries":[
                      {"type":"LineString","arcs":[3]},{"type":"Point","coordinates":[0,1]}]}
                  ]},
                  "line":{"type":"LineString","arcs":[-4],"properties":{"name":"L"}}
                },
                "arcs":[[[0,0],[1,0],[0,1],[-1,-1]],[[5,5],[1,0],[0,1],[-1,-1]],
                        [[8,8],[1,0],[-1,0]],[[0,5],[2,2],[1,-3]]]}"#,
        )
        .unwrap();
        let d = read("t.json", v).unwrap();
        // Smoothed arcs stand in: every position moved.
        let arcs: Arcs = d
            .topology
            .arcs()
            .iter()
            .map(|a| {
                a.iter().map(|c| Coord {
                    x: c.x * 1.5 + 0.25,
                    y: c.y / 3.0,
                })
            })
            .collect();
        let text = |f: &dyn Fn(&mut Vec<u8>) -> std::io::Result<()>| {
            let mut out = Vec::new();
            f(&mut out).unwrap();
            String::from_utf8(out).unwrap()
        };
        for object in [None, Some("coll"), Some("line")] {
            let whole = d.to_geojson(&arcs, object).unwrap();
            let f = d.geojson_features(&arcs, object).unwrap();
            assert_eq!(
                text(&|w| f.write_geojson(w)),
                text(&|w| crate::model::write_json_compact(w, &whole)),
                "{object:?}"
            );
            let want: &dyn Source = &whole;
            assert_eq!(Source::count(&f), want.count());
            for i in 0..want.count() {
                assert_eq!(f.geometry(i), want.geometry(i), "{object:?} {i}");
                assert_eq!(f.properties(i), want.properties(i), "{object:?} {i}");
                assert_eq!(f.property(i, "name"), want.property(i, "name"));
                assert_eq!(f.geometry_type(i), want.geometry_type(i), "{i}");
                assert_eq!(f.has_z(i), want.has_z(i), "{i}");
            }
        }
        assert_eq!(Source::count(&d.geojson_features(&arcs, None).unwrap()), 9);
        assert!(d.geojson_features(&arcs, Some("nope")).is_err());
        assert_eq!(
            text(&|w| d.write_topojson(&arcs, w)),
            text(&|w| crate::model::write_json_compact(w, &d.to_topojson(&arcs)))
        );
    }

    #[test]
    fn quantized_arcs_are_delta_decoded() {
        let v: Value = serde_json::from_str(
            r#"{"type":"Topology","transform":{"scale":[0.5,2],"translate":[10,20]},
                "objects":{"l":{"type":"LineString","arcs":[0]},"p":{"type":"Point","coordinates":[2,3]}},
                "arcs":[[[2,1],[2,0],[-4,3]]]}"#,
        )
        .unwrap();
        let d = read("t.json", v).unwrap();
        let a = &d.topology.arcs()[0];
        let got: Vec<(f64, f64)> = a.iter().map(|c| (c.x, c.y)).collect();
        assert_eq!(got, vec![(11.0, 22.0), (12.0, 22.0), (10.0, 28.0)]);
        let out = d.to_topojson(d.topology.arcs());
        assert_eq!(out["objects"]["p"]["coordinates"], json!([11.0, 26.0]));
        assert!(out.get("transform").is_none());
    }
}
