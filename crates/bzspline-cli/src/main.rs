//! The `bzspline` command: fit, evaluate, sample and plot the Bezier-type spline of
//! Stelia, Potapenko and Sirenko, and smooth GeoJSON lines with it.

use clap::Parser;

mod alloc;
mod cli;
mod commands;
mod fit;
mod output;
mod plot;
#[cfg(feature = "serve")]
mod serve;
mod smooth;

// The formats, from the library crate every binding shares.
use bzspline_io::{input, model, time};

fn main() {
    alloc::hand_back_at_once();
    let args = match commands::Cli::try_parse() {
        Ok(args) => args,
        // --help and --version print and exit 0.
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            // One line, as every other error: clap's message up to its usage
            // summary, which names the option and the value.
            let text = e.render().to_string();
            let parts: Vec<&str> = text
                .lines()
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more"))
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .collect();
            eprintln!("{} (see --help)", parts.join(" "));
            std::process::exit(2);
        }
    };
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
