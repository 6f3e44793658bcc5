//! The `smooth` subcommand: GeoJSON lines and rings through the paper's curve.

use anyhow::{bail, Result};

use crate::cli::SmoothArgs;

/// Runs `smooth`.
///
/// # Errors
///
/// Not available yet.
pub fn run(a: &SmoothArgs) -> Result<()> {
    let _ = a;
    bail!("smooth is not implemented yet")
}
