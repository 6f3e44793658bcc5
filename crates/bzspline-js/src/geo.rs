//! Map smoothing for the package's `bzspline/geo` entry: a GeoJSON or
//! TopoJSON document (as JSON text) smoothed by [`bzspline_io::smooth::job`],
//! the code `bzspline smooth` runs, so that the output is the command's, bit
//! for bit.

use bzspline::Param;
use bzspline_geo::SmoothOptions;
use bzspline_io::distance::Unit;
use bzspline_io::smooth::job::{Job, Output, Settings};
use wasm_bindgen::prelude::*;

use crate::args::{range_error, type_error, Options};

/// Smooths the document in `text` (GeoJSON, or a TopoJSON Topology) and
/// returns the smoothed document as JSON text: by default the same kind as
/// went in, `output: "geojson"` or `"topojson"` to choose. Options:
/// `tolerance` and `snap` (numbers in the data's units, or strings with a
/// unit: `"50m"`, `"2km"`, `"0.001deg"`), `keepAngle`, `independent`, `through`, `alpha`,
/// `param`, `object` (the TopoJSON object to write as GeoJSON), `name` (the
/// object a GeoJSON input becomes in TopoJSON, `collection` by default).
#[wasm_bindgen(js_name = smoothText)]
pub fn smooth_text(text: &str, options: &JsValue) -> Result<String, JsValue> {
    let o = Options::new(options)?;
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| type_error(format!("invalid JSON: {e}")))?;
    let topology = bzspline_io::topojson::is_topology(&value);
    let mut lib = SmoothOptions::default();
    if let AlphaOne(Some(a)) = AlphaOne::of(&o)? {
        lib = lib.alpha(a);
    }
    if let Some(p) = o.string("param")? {
        lib = lib.param(p.parse::<Param>().map_err(range_error)?);
    }
    let tolerance = o.distance("tolerance")?;
    let snap = o.distance("snap")?;
    lib.tolerance = tolerance.map(|d| d.value);
    lib.keep_angle = o.number("keepAngle")?;
    lib.through = o.flag("through", false)?;
    let output = match o.string("output")?.as_deref() {
        None if topology => Output::Topojson,
        None | Some("geojson") => Output::Geojson,
        Some("topojson") => Output::Topojson,
        Some(other) => {
            return Err(range_error(format!(
                "output must be \"geojson\" or \"topojson\" (found {other:?})"
            )))
        }
    };
    let settings = Settings {
        options: lib,
        independent: o.flag("independent", false)?,
        snap: snap.map(|d| d.value),
        tolerance_unit: tolerance.map_or(Unit::Data, |d| d.unit),
        snap_unit: snap.map_or(Unit::Data, |d| d.unit),
        object: o.string("object")?,
        output,
        object_name: o.string("name")?.unwrap_or_default(),
        limits: bzspline_io::input::Limits::default(),
    };
    settings.check().map_err(range_error)?;
    let mut job = Job::new(settings);
    let out = job
        .document("document", value)
        .map_err(|e| range_error(format!("{e:#}")))?;
    let mut bytes = Vec::new();
    bzspline_io::model::write_json_compact(&mut bytes, &out)
        .map_err(|e| range_error(format!("{e:#}")))?;
    String::from_utf8(bytes).map_err(range_error)
}

/// The one alpha of the options (`alphas` do not apply to maps).
struct AlphaOne(Option<f64>);

impl AlphaOne {
    fn of(o: &Options) -> Result<Self, JsValue> {
        if o.get("alphas").is_some() {
            return Err(type_error("smooth takes one alpha, not alphas"));
        }
        if o.get("alpha").is_none() {
            return Ok(AlphaOne(None));
        }
        match o.alphas()? {
            bzspline::AlphaChoice::One(a) => Ok(AlphaOne(Some(a))),
            bzspline::AlphaChoice::Each(_) => Err(type_error("smooth takes one alpha")),
        }
    }
}
