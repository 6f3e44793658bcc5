//! TopoJSON in and out: a `"type": "Topology"` document read into a
//! [`bzspline_geo::Topology`] (arcs decoded, quantized or not, with its
//! `transform` applied), and written back as TopoJSON with smoothed arcs
//! (absolute coordinates, no transform) or as GeoJSON features.
//!
//! Specification: <https://github.com/topojson/topojson-specification>.

use anyhow::{anyhow, bail, Result};
use bzspline_geo::{ArcRef, Arcs, Chain, ChainKind, Topology};
use geo_types::Coord;
use serde_json::{json, Map, Value};

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
        chains: Vec::new(),
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
    chains: Vec<Chain>,
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
        self.chains.push(Chain { kind, arcs });
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

    /// GeoJSON features of every object (or only `object`), with the lines
    /// and rings assembled from `arcs`: a GeometryCollection object gives one
    /// feature per member, any other object one feature.
    pub fn to_geojson(&self, arcs: &Arcs, object: Option<&str>) -> Result<Value> {
        let Some(Value::Object(objects)) = self.root.get("objects") else {
            return Ok(json!({"type": "FeatureCollection", "features": []}));
        };
        if let Some(o) = object {
            if !objects.contains_key(o) {
                let names: Vec<&str> = objects.keys().map(String::as_str).collect();
                bail!("no object {o:?} in the Topology (it has {names:?})");
            }
        }
        let mut next = 0usize;
        let mut features = Vec::new();
        for (oname, o) in objects {
            let wanted = object.is_none_or(|w| w == oname);
            let members: Vec<&Value> =
                match (o.get("type").and_then(Value::as_str), o.get("geometries")) {
                    (Some("GeometryCollection"), Some(Value::Array(gs))) => gs.iter().collect(),
                    _ => vec![o],
                };
            for g in members {
                let geometry = self.geometry(g, arcs, &mut next);
                if wanted {
                    let mut f = Map::new();
                    f.insert("type".into(), json!("Feature"));
                    if let Some(id) = g.get("id") {
                        f.insert("id".into(), id.clone());
                    }
                    f.insert(
                        "properties".into(),
                        g.get("properties").cloned().unwrap_or(json!({})),
                    );
                    f.insert("geometry".into(), geometry);
                    features.push(Value::Object(f));
                }
            }
        }
        Ok(json!({"type": "FeatureCollection", "features": features}))
    }

    /// The GeoJSON geometry of a geometry object; `next` counts chains in the
    /// order [`read`] met them.
    fn geometry(&self, g: &Value, arcs: &Arcs, next: &mut usize) -> Value {
        let mut take = || {
            let mut c = self.topology.chain_coords(*next, arcs);
            // GeoJSON's rings have 4 or more positions: a ring collapsed by
            // quantization repeats its first, as topojson-client writes it.
            if self.topology.chains()[*next].kind == ChainKind::Ring && !c.is_empty() {
                while c.len() < 4 {
                    c.push(c[0]);
                }
            }
            *next += 1;
            Value::Array(c.iter().map(|p| json!([p.x, p.y])).collect())
        };
        let count = |v: Option<&Value>| v.and_then(Value::as_array).map_or(0, Vec::len);
        let ty = g.get("type").and_then(Value::as_str);
        let a = g.get("arcs");
        match ty {
            Some("Point" | "MultiPoint") => {
                json!({"type": ty, "coordinates": self.points(g).unwrap_or(json!([]))})
            }
            Some("LineString") => json!({"type": "LineString", "coordinates": take()}),
            Some("MultiLineString") => {
                let ls: Vec<Value> = (0..count(a)).map(|_| take()).collect();
                json!({"type": "MultiLineString", "coordinates": ls})
            }
            Some("Polygon") => {
                let rings: Vec<Value> = (0..count(a)).map(|_| take()).collect();
                json!({"type": "Polygon", "coordinates": rings})
            }
            Some("MultiPolygon") => {
                let polys: Vec<Value> = a
                    .and_then(Value::as_array)
                    .map(|ps| {
                        ps.iter()
                            .map(|p| Value::Array((0..count(Some(p))).map(|_| take()).collect()))
                            .collect()
                    })
                    .unwrap_or_default();
                json!({"type": "MultiPolygon", "coordinates": polys})
            }
            Some("GeometryCollection") => {
                let gs: Vec<Value> = g
                    .get("geometries")
                    .and_then(Value::as_array)
                    .map(|gs| gs.iter().map(|s| self.geometry(s, arcs, next)).collect())
                    .unwrap_or_default();
                json!({"type": "GeometryCollection", "geometries": gs})
            }
            _ => Value::Null,
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
        let c = &topology.chains()[next];
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
