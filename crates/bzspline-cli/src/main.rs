//! The `bzspline` command: fit, evaluate, sample and plot the Bezier-type spline of
//! Stelia, Potapenko and Sirenko, and smooth GeoJSON lines with it.

use clap::Parser;

mod cli;
mod commands;
mod fit;
mod input;
mod model;
mod output;
mod plot;
#[cfg(feature = "serve")]
mod serve;
mod smooth;
mod topojson;

fn main() {
    let args = commands::Cli::parse();
    if let Err(e) = commands::run(args) {
        if output::is_broken_pipe(&e) {
            std::process::exit(0);
        }
        let chain: Vec<String> = e.chain().map(ToString::to_string).collect();
        // One line, whatever the messages contain.
        eprintln!("error: {}", chain.join(": ").replace(['\n', '\r'], " "));
        let usage = e.downcast_ref::<cli::UsageError>().is_some();
        std::process::exit(if usage { 2 } else { 1 });
    }
}
