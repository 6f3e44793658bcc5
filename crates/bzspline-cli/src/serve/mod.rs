//! The `serve` subcommand: an interactive editor over HTTP.

use anyhow::{bail, Result};
use clap::Args;

/// Arguments of `serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// Address to listen on.
    #[arg(long, default_value = "127.0.0.1:8080")]
    pub addr: String,
}

/// Runs `serve`.
///
/// # Errors
///
/// Always, until the server is implemented.
pub fn run(args: &ServeArgs) -> Result<()> {
    let _ = args;
    bail!("serve is not implemented yet")
}
