//! Where the memory of smoothing a layer file goes: reads the layer (its
//! format by extension or content, as the command finds it), builds its
//! coverage, smooths it at the default tolerance and assembles the smoothed
//! geometries one at a time, printing after each step the resident memory and its peak so
//! far (Linux's `VmRSS` and `VmHWM`), in MB. It allocates with mimalloc,
//! as the command does (which also has mimalloc hand freed memory back at
//! once: `MIMALLOC_PURGE_DELAY=0 MIMALLOC_ARENA_PURGE_MULT=0` does that here).
//!
//! ```text
//! cargo run --release -p bzspline-io --all-features --example layer_memory -- FILE
//! ```
//!
//! `bench/maps/memory.py` runs it beside the command on every format.

use std::path::Path;
use std::process::ExitCode;

use bzspline_geo::{Coverage, SmoothOptions};
use bzspline_io::features::Shape;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// `VmRSS` and `VmHWM` in MB (zeros where `/proc` is not there).
fn memory() -> (u64, u64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kb = |key: &str| {
        status
            .lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
            .unwrap_or(0)
    };
    (kb("VmRSS:") / 1000, kb("VmHWM:") / 1000)
}

fn step(what: &str) {
    let (rss, peak) = memory();
    println!("{what:<16} {rss:>8} {peak:>8}");
}

fn main() -> ExitCode {
    let Some(file) = std::env::args().nth(1) else {
        eprintln!("usage: layer_memory FILE");
        return ExitCode::from(2);
    };
    let path = Path::new(&file);
    let format = bzspline_io::input::format_of(Some(path), None);
    println!("{:<16} {:>8} {:>8}", "after", "rss, MB", "peak, MB");
    step("start");
    let mut layer = match bzspline_io::files::read(path, format, None, u64::MAX) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("{e:#}");
            return ExitCode::from(1);
        }
    };
    step("reading");
    // Taken one at a time, as the command takes them.
    let geometries = layer
        .features
        .take_shapes()
        .into_iter()
        .filter_map(|s| match s {
            Shape::Plane(g) => Some(*g),
            _ => None,
        });
    let coverage = match Coverage::new(geometries) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("{file}: {e}");
            return ExitCode::from(1);
        }
    };
    step("coverage");
    let smoothed = match coverage.topology().smooth(&SmoothOptions::default()) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{file}: {e}");
            return ExitCode::from(1);
        }
    };
    step("smoothing");
    // As the command writes a layer: each geometry put together in turn.
    let out = coverage.into_assembled(smoothed.arcs);
    let positions: usize = out.iter().map(|g| geo::CoordsIter::coords_count(&g)).sum();
    step("assembling");
    println!("{} geometries, {positions} positions", out.len());
    ExitCode::SUCCESS
}
