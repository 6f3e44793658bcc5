//! Throughput of coverage smoothing on a county-sized mosaic (by default 60 x
//! 55 = 3,300 cells of 21 positions, about 70,000 positions), against
//! smoothing every ring on its own (what `bzspline smooth --independent`
//! does), with the peak memory that smoothing adds per input position. The
//! tolerance is the default (1e-4 of the extent's diagonal) unless given.
//!
//! ```sh
//! cargo run --release -p bzspline-geo --example coverage_throughput -- [NX NY M REPEATS [TOL]]
//! ```
//!
//! Prints one `name value` line per figure; times are the smallest of the
//! repeats. `--only coverage`, `--only independent` or `--only none` runs one
//! side (or only makes the mosaic), for instruction counts:
//! `valgrind --tool=callgrind target/release/examples/coverage_throughput 60 55 4 1 --only coverage`.

use bzspline::Flatten;
use std::time::Instant;

use bzspline::{CurveBuilder, Param};
use bzspline_geo::{Coverage, SmoothOptions};
use geo_types::{Coord, Geometry, LineString, Polygon};

/// A mosaic like the tests' wiggly grid: jittered corners, `m` positions
/// displaced across every edge, shared exactly by the two cells.
fn mosaic(nx: usize, ny: usize, m: usize) -> Vec<Geometry<f64>> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let c = |x: f64, y: f64| Coord { x, y };
    let mut node = vec![vec![c(0.0, 0.0); ny + 1]; nx + 1];
    for (i, col) in node.iter_mut().enumerate() {
        for (j, p) in col.iter_mut().enumerate() {
            let dx = if i > 0 && i < nx { 0.15 * rnd() } else { 0.0 };
            let dy = if j > 0 && j < ny { 0.15 * rnd() } else { 0.0 };
            *p = c(i as f64 + dx, j as f64 + dy);
        }
    }
    let mut edge = |a: Coord, b: Coord| -> Vec<Coord> {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        (1..=m)
            .map(|k| {
                let t = k as f64 / (m + 1) as f64;
                let w = 0.1 * rnd();
                c(a.x + dx * t - dy * w, a.y + dy * t + dx * w)
            })
            .collect()
    };
    let mut horiz = vec![vec![Vec::new(); ny + 1]; nx];
    let mut vert = vec![vec![Vec::new(); ny]; nx + 1];
    for i in 0..=nx {
        for j in 0..=ny {
            if i < nx {
                horiz[i][j] = edge(node[i][j], node[i + 1][j]);
            }
            if j < ny {
                vert[i][j] = edge(node[i][j], node[i][j + 1]);
            }
        }
    }
    let mut cells = Vec::with_capacity(nx * ny);
    for i in 0..nx {
        for j in 0..ny {
            let mut r = vec![node[i][j]];
            r.extend(&horiz[i][j]);
            r.push(node[i + 1][j]);
            r.extend(&vert[i + 1][j]);
            r.push(node[i + 1][j + 1]);
            r.extend(horiz[i][j + 1].iter().rev());
            r.push(node[i][j + 1]);
            r.extend(vert[i][j].iter().rev());
            r.push(node[i][j]);
            cells.push(Geometry::Polygon(Polygon::new(LineString(r), vec![])));
        }
    }
    cells
}

/// Every ring on its own: the closed curve through its positions, flattened.
fn independent(cells: &[Geometry<f64>], tol: f64) -> usize {
    let mut out = 0;
    for g in cells {
        let Geometry::Polygon(p) = g else { continue };
        let ring = &p.exterior().0;
        let flat: Vec<f64> = ring[..ring.len() - 1]
            .iter()
            .flat_map(|c| [c.x, c.y])
            .collect();
        let curve = CurveBuilder::new(&flat, 2)
            .closed(true)
            .param(Param::Centripetal)
            .build()
            .expect("a ring's curve");
        out += curve.flatten(tol).expect("flattened").len();
    }
    out
}

/// Resident and peak resident memory in bytes (Linux), or zeros.
fn memory() -> (u64, u64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse::<u64>().ok())
            .map_or(0, |kb| kb * 1024)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

fn main() {
    let mut only: Option<String> = None;
    let mut args: Vec<f64> = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        if a == "--only" {
            only = it.next();
        } else {
            args.push(
                a.parse()
                    .expect("numbers: NX NY M REPEATS [TOL], or --only coverage|independent|none"),
            );
        }
    }
    let run = |side: &str| only.as_deref().is_none_or(|o| o == side);
    let get = |i: usize, d: usize| args.get(i).map_or(d, |&v| v as usize);
    let (nx, ny, m, repeats) = (get(0, 60), get(1, 55), get(2, 4), get(3, 5));
    let extent = (nx as f64).hypot(ny as f64);
    let tol = args
        .get(4)
        .copied()
        .unwrap_or(extent * bzspline_geo::DEFAULT_TOLERANCE_FRACTION);
    let cells = mosaic(nx, ny, m);
    let positions: usize = cells
        .iter()
        .map(|g| match g {
            Geometry::Polygon(p) => p.exterior().0.len(),
            _ => 0,
        })
        .sum();
    let opts = SmoothOptions::default().tolerance(tol);
    let (rss_before, _) = memory();
    let mut best = [f64::INFINITY; 4];
    let mut stats = None;
    for _ in 0..repeats.max(1) {
        let (mut t_topology, mut t_total, mut t_indep) = (0.0, 0.0, 0.0);
        if run("coverage") {
            let t = Instant::now();
            let cov = Coverage::new(cells.clone()).expect("coverage");
            t_topology = t.elapsed().as_secs_f64();
            let (out, s) = cov.smooth(&opts).expect("smoothed");
            t_total = t.elapsed().as_secs_f64();
            std::hint::black_box(out);
            stats = Some(s);
        }
        if run("independent") {
            let t = Instant::now();
            std::hint::black_box(independent(&cells, tol));
            t_indep = t.elapsed().as_secs_f64();
        }
        for (b, v) in best
            .iter_mut()
            .zip([t_topology, t_total, t_indep, t_total - t_topology])
        {
            *b = b.min(v);
        }
    }
    let (_, peak) = memory();
    let Some(s) = stats else {
        println!("cells {} positions_in {positions}", cells.len());
        return;
    };
    println!("cells {}", cells.len());
    println!("tolerance {tol}");
    println!("positions_in {positions}");
    println!("positions_out {}", s.positions_out);
    println!("arcs {} shared {}", s.arcs, s.shared_arcs);
    println!("refined_legs {} rounds {}", s.refined_legs, s.rounds);
    println!("coverage_s {:.4}", best[1]);
    println!("  topology_s {:.4}", best[0]);
    println!("  smooth_and_validate_s {:.4}", best[3]);
    println!("independent_s {:.4}", best[2]);
    println!("coverage_positions_per_s {:.0}", positions as f64 / best[1]);
    println!(
        "independent_positions_per_s {:.0}",
        positions as f64 / best[2]
    );
    println!("ratio_to_independent {:.2}", best[1] / best[2]);
    println!(
        "peak_bytes_added_per_position {:.0}",
        peak.saturating_sub(rss_before) as f64 / positions as f64
    );
}
