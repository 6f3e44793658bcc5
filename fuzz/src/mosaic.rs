//! Coverages generated from fuzzer bytes (`arbitrary`), for the
//! `smooth_coverage` target: a jittered grid of cells whose shared edges carry
//! extra positions of every awkward kind (collinear, repeated, a hair apart,
//! spikes, bulges), with holes, islands filling them, holes touching at a
//! point, a sliver column, lines ending on rings, at scales from 2^-996 to
//! 2^996, and random smoothing options.

use bzspline::Param;
use bzspline_geo::SmoothOptions;
use geo_types::{Coord, Geometry, LineString, Polygon};
use libfuzzer_sys::arbitrary::{Result, Unstructured};

/// One generated case.
#[derive(Debug)]
pub struct Case {
    /// The coverage, in scaled coordinates.
    pub geometries: Vec<Geometry<f64>>,
    /// The options smoothing runs with.
    pub opts: SmoothOptions,
    /// `--snap`, if any (scaled).
    pub snap: Option<f64>,
    /// Coordinates are the unscaled ones times `2^exponent` (plus `offset`):
    /// dividing by `2^exponent` is exact, so the judges can work unscaled.
    pub exponent: i32,
    /// Added to every coordinate (only at exponent 0).
    pub offset: f64,
}

fn c(x: f64, y: f64) -> Coord {
    Coord { x, y }
}

/// Extra positions along one edge from `a` to `b` (both ends excluded).
fn edge(u: &mut Unstructured, a: Coord, b: Coord) -> Result<Vec<Coord>> {
    let n = u.int_in_range(0..=4)?;
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let normal = c(-dy, dx);
    let mut out: Vec<Coord> = Vec::new();
    for k in 0..n {
        let t = (f64::from(k) + 1.0) / (f64::from(n) + 1.0);
        let on = c(a.x + t * dx, a.y + t * dy);
        let at = |s: f64| c(on.x + s * normal.x, on.y + s * normal.y);
        match u.int_in_range(0..=5)? {
            // Collinear.
            0 => out.push(on),
            // Repeated.
            1 => {
                let p = out.last().copied().unwrap_or(on);
                out.push(p);
                out.push(p);
            }
            // Two positions a hair apart.
            2 => {
                out.push(on);
                out.push(c(on.x + 1e-13 * dx, on.y + 1e-13 * dy + 1e-15));
            }
            // A spike out and back.
            3 => {
                out.push(on);
                out.push(at(f64::from(u.int_in_range(-40..=40)?) / 100.0));
                out.push(on);
            }
            // A bulge.
            _ => out.push(at(f64::from(u.int_in_range(-25..=25)?) / 100.0)),
        }
    }
    Ok(out)
}

/// A square ring of half-width `r` around `m`, counter-clockwise when `ccw`.
fn square(m: Coord, r: f64, ccw: bool) -> Vec<Coord> {
    let mut ring = vec![
        c(m.x - r, m.y - r),
        c(m.x + r, m.y - r),
        c(m.x + r, m.y + r),
        c(m.x - r, m.y + r),
    ];
    if !ccw {
        ring.reverse();
    }
    ring.push(ring[0]);
    ring
}

/// Generates a case.
///
/// # Errors
///
/// When the bytes run out in a way `arbitrary` reports.
pub fn case(u: &mut Unstructured) -> Result<Case> {
    let nx: usize = u.int_in_range(1..=4)?;
    let ny: usize = u.int_in_range(1..=3)?;
    let sliver = if u.ratio(1, 4)? {
        Some(u.int_in_range(0..=nx - 1)?)
    } else {
        None
    };
    // Column positions; a sliver column is 1e-7 wide.
    let mut xs = vec![0.0];
    for i in 0..nx {
        let w = if sliver == Some(i) { 1e-7 } else { 1.0 };
        xs.push(xs[i] + w);
    }
    let mut corner = vec![vec![c(0.0, 0.0); ny + 1]; nx + 1];
    for i in 0..=nx {
        for j in 0..=ny {
            let inner = i > 0 && i < nx && j > 0 && j < ny;
            let jit = |u: &mut Unstructured| -> Result<f64> {
                Ok(if inner {
                    f64::from(u.int_in_range(-25..=25)?) / 100.0
                } else {
                    0.0
                })
            };
            let near_sliver = sliver.is_some_and(|s| i == s || i == s + 1);
            let jx = if near_sliver { 0.0 } else { jit(u)? };
            corner[i][j] = c(xs[i] + jx, j as f64 + jit(u)?);
        }
    }
    // Shared edges: horizontal h[i][j] from corner (i, j) to (i + 1, j),
    // vertical v[i][j] from (i, j) to (i, j + 1).
    let mut h = vec![vec![Vec::new(); ny + 1]; nx];
    let mut v = vec![vec![Vec::new(); ny]; nx + 1];
    for (i, col) in h.iter_mut().enumerate() {
        for (j, e) in col.iter_mut().enumerate() {
            if sliver != Some(i) {
                *e = edge(u, corner[i][j], corner[i + 1][j])?;
            }
        }
    }
    for (i, col) in v.iter_mut().enumerate() {
        for (j, e) in col.iter_mut().enumerate() {
            *e = edge(u, corner[i][j], corner[i][j + 1])?;
        }
    }
    let mut geometries = Vec::new();
    let mut lines = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            // Counter-clockwise: bottom, right, top reversed, left reversed.
            let mut ring = vec![corner[i][j]];
            ring.extend(&h[i][j]);
            ring.push(corner[i + 1][j]);
            ring.extend(&v[i + 1][j]);
            ring.push(corner[i + 1][j + 1]);
            ring.extend(h[i][j + 1].iter().rev());
            ring.push(corner[i][j + 1]);
            ring.extend(v[i][j].iter().rev());
            ring.push(corner[i][j]);
            let m = c(
                (corner[i][j].x + corner[i + 1][j + 1].x) / 2.0,
                (corner[i][j].y + corner[i + 1][j + 1].y) / 2.0,
            );
            let mut holes = Vec::new();
            if sliver != Some(i) {
                match u.int_in_range(0..=4)? {
                    // A hole, and an island filling it.
                    0 => {
                        holes.push(LineString::from(square(m, 0.1, false)));
                        geometries.push(Geometry::Polygon(Polygon::new(
                            LineString::from(square(m, 0.1, true)),
                            vec![],
                        )));
                    }
                    // Two holes touching at a point.
                    1 => {
                        holes.push(LineString::from(square(
                            c(m.x - 0.05, m.y - 0.05),
                            0.05,
                            false,
                        )));
                        holes.push(LineString::from(square(
                            c(m.x + 0.05, m.y + 0.05),
                            0.05,
                            false,
                        )));
                    }
                    // A line ending on the cell's corner.
                    2 => lines.push(Geometry::LineString(LineString::from(vec![
                        c(m.x, m.y + 0.1),
                        c(m.x + 0.05, m.y - 0.05),
                        m,
                        corner[i][j],
                    ]))),
                    _ => {}
                }
            }
            geometries.push(Geometry::Polygon(Polygon::new(
                LineString::from(ring),
                holes,
            )));
        }
    }
    geometries.extend(lines);
    let exponent = *u.choose(&[0, 0, -996, 996, -40, 40])?;
    let offset = if exponent == 0 {
        *u.choose(&[0.0, 1e8, -3.5e5])?
    } else {
        0.0
    };
    let s = 2f64.powi(exponent);
    let map = |p: &mut Coord| {
        p.x = p.x * s + offset;
        p.y = p.y * s + offset;
    };
    for g in &mut geometries {
        geo_map(g, &map);
    }
    let mut opts = SmoothOptions::default();
    if u.ratio(1, 2)? {
        opts.tolerance = Some(s * 10f64.powi(-u.int_in_range(1..=6)?));
    }
    opts.alpha = 1.0 / 3.0 + f64::from(u.int_in_range(0..=100u8)?) / 300.0;
    opts.alpha = opts.alpha.clamp(bzspline::ALPHA_MIN, bzspline::ALPHA_MAX);
    opts.param = u
        .choose(&[Param::Centripetal, Param::Uniform, Param::Chordal])?
        .clone();
    if u.ratio(1, 3)? {
        opts.keep_angle = Some(f64::from(u.int_in_range(0..=180u8)?));
    }
    opts.through = u.ratio(1, 4)?;
    let snap = if u.ratio(1, 4)? {
        Some(s * 10f64.powi(-u.int_in_range(3..=13)?))
    } else {
        None
    };
    Ok(Case {
        geometries,
        opts,
        snap,
        exponent,
        offset,
    })
}

/// Applies `f` to every position of a geometry.
pub fn geo_map(g: &mut Geometry<f64>, f: &dyn Fn(&mut Coord)) {
    let line = |l: &mut LineString<f64>| l.0.iter_mut().for_each(f);
    match g {
        Geometry::Polygon(p) => {
            p.exterior_mut(|e| line(e));
            p.interiors_mut(|is| is.iter_mut().for_each(line));
        }
        Geometry::LineString(l) => line(l),
        Geometry::MultiPolygon(m) => {
            for p in &mut m.0 {
                p.exterior_mut(|e| line(e));
                p.interiors_mut(|is| is.iter_mut().for_each(line));
            }
        }
        Geometry::MultiLineString(m) => m.0.iter_mut().for_each(line),
        _ => {}
    }
}
