//! What `bzspline smooth FILE` runs on a file's bytes, for the
//! `smooth_document` target: the JSON read, then the command's own
//! [`Job`](bzspline_io::smooth::job::Job): TopoJSON smoothed on its own arcs
//! and written back, GeoJSON checked, smoothed as one coverage (each geometry
//! on its own with `independent`, ring by ring when its positions carry z)
//! and written.

use anyhow::{anyhow, Result};
use bzspline_geo::SmoothOptions;
use bzspline_io::smooth::job::{Job, Output, Settings};
use serde_json::Value;

use crate::input;
use crate::topojson;

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
    let topology = topojson::is_topology(&value) && !independent;
    let settings = Settings {
        options: opts.clone(),
        independent,
        output: if topology {
            Output::Topojson
        } else {
            Output::Geojson
        },
        limits: input::Limits {
            max_points: crate::MAX_POINTS * 16,
            max_bytes: u64::MAX,
        },
        ..Settings::default()
    };
    Job::new(settings).document(NAME, value)
}
