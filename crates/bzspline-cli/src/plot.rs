//! The `plot` subcommand: control points, control polygon and spline as SVG.

use anyhow::{bail, Result};
use clap::Args;

use crate::cli::{InputArgs, OutputArgs, ShapeArgs};

/// Arguments of `plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    #[command(flatten)]
    pub input: InputArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// Runs `plot`.
///
/// # Errors
///
/// Always, until plotting is implemented.
pub fn run(args: &PlotArgs) -> Result<()> {
    let _ = args;
    bail!("plot is not implemented yet")
}
