//! What `bzspline smooth FILE` runs on a file's bytes, for the
//! `smooth_document` target: the JSON read, TopoJSON smoothed on its own arcs
//! and written back, GeoJSON checked, smoothed as one coverage (or ring by
//! ring when its positions carry z, or with `independent`) and written. The
//! dispatch follows the command's `smooth::Job`, which needs its arguments.

use anyhow::{anyhow, Result};
use bzspline_geo::SmoothOptions;
use serde_json::Value;

use crate::input;
use crate::topojson;
use bzspline_io::smooth::{coverage, independent};

/// The source name errors start with.
pub const NAME: &str = "f.json";

/// Smooths a document as the command does and gives the output document.
///
/// # Errors
///
/// The command's one-line errors, starting with [`NAME`].
pub fn smooth(bytes: &[u8], opts: &SmoothOptions, independent: bool) -> Result<Value> {
    let text = input::utf8(NAME, bytes)?;
    let value: Value = serde_json::from_str(text)
        .map_err(|e| anyhow!("{NAME}:{}: invalid JSON: {e}", e.line()))?;
    if topojson::is_topology(&value) && !independent {
        let topo = topojson::read(NAME, value)?;
        let s = topo
            .topology
            .smooth(opts)
            .map_err(|e| anyhow!("{NAME}: {}", topo.describe(&e)))?;
        let _ = topo.to_geojson(&s.arcs, None)?;
        return Ok(topo.to_topojson(&s.arcs));
    }
    let value = if topojson::is_topology(&value) {
        let topo = topojson::read(NAME, value)?;
        topo.to_geojson(topo.topology.arcs(), None)
            .map_err(|e| anyhow!("{NAME}: {e}"))?
    } else {
        value
    };
    let (doc, _) = input::to_geojson(NAME, value)?;
    if independent || coverage::document_has_z(&doc) {
        let o = independent::Options {
            alpha: opts.alpha,
            param: opts.param.clone(),
            tolerance: opts
                .tolerance
                .unwrap_or_else(|| bzspline_io::smooth::default_tolerance(&doc)),
            limits: input::Limits {
                max_points: crate::MAX_POINTS * 16,
                max_bytes: u64::MAX,
            },
            through: opts.through,
        };
        let out = independent::smooth_document(doc, &o, NAME, true)?;
        return Ok(serde_json::to_value(&out)?);
    }
    let s = coverage::smooth_document(doc, opts, None, crate::MAX_POINTS * 16, NAME, true)?;
    Ok(serde_json::to_value(&s.doc)?)
}
