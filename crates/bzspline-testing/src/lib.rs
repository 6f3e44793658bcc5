//! Coverages for the tests, and checks of smoothed coverages that do not use
//! the code under test: validity from `geo`, a brute-force crossing test over
//! every pair of segments, and shared borders found from the input alone.
//! The coverage tests of `bzspline-geo`, the command's atlas tests and the
//! fuzz targets use it as a dependency.

use std::collections::{HashMap, HashSet};

use geo::{Area, Relate, Validation};
use geo_types::{Coord, Geometry, LineString, Polygon};

/// A small deterministic generator (splitmix64).
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1), 53 random bits.
    // Not an Iterator: it never ends, and every caller wants a plain f64.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [-1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.next() - 1.0
    }
}

/// The coordinate (x, y).
pub fn c(x: f64, y: f64) -> Coord {
    Coord { x, y }
}

/// A polygon of the shell and holes given.
pub fn poly(shell: Vec<Coord>, holes: Vec<Vec<Coord>>) -> Geometry<f64> {
    Geometry::Polygon(Polygon::new(
        LineString(shell),
        holes.into_iter().map(LineString).collect(),
    ))
}

/// An `nx` by `ny` mosaic of cells whose corners are jittered by up to
/// `jitter` and whose edges carry `m` positions displaced across the edge by
/// up to `amp` (edge lengths are about 1): neighbours share their edges
/// exactly, every cell is a valid polygon when `jitter + amp < 0.3`.
pub fn wiggly_grid(
    nx: usize,
    ny: usize,
    m: usize,
    jitter: f64,
    amp: f64,
    seed: u64,
) -> Vec<Geometry<f64>> {
    let mut rng = Rng(seed);
    let node: Vec<Vec<Coord>> = (0..=nx)
        .map(|i| {
            (0..=ny)
                .map(|j| {
                    let inner_x = i > 0 && i < nx;
                    let inner_y = j > 0 && j < ny;
                    let dx = if inner_x { jitter * rng.sym() } else { 0.0 };
                    let dy = if inner_y { jitter * rng.sym() } else { 0.0 };
                    c(i as f64 + dx, j as f64 + dy)
                })
                .collect()
        })
        .collect();
    // Edge from a to b with m wiggly positions between (a and b excluded).
    let mut edge = |a: Coord, b: Coord| -> Vec<Coord> {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let len = dx.hypot(dy);
        let (nx_, ny_) = (-dy / len, dx / len);
        (1..=m)
            .map(|k| {
                let t = k as f64 / (m + 1) as f64;
                let w = amp * rng.sym();
                c(a.x + dx * t + nx_ * w, a.y + dy * t + ny_ * w)
            })
            .collect()
    };
    let mut horiz: HashMap<(usize, usize), Vec<Coord>> = HashMap::new();
    let mut vert: HashMap<(usize, usize), Vec<Coord>> = HashMap::new();
    for i in 0..=nx {
        for j in 0..=ny {
            if i < nx {
                horiz.insert((i, j), edge(node[i][j], node[i + 1][j]));
            }
            if j < ny {
                vert.insert((i, j), edge(node[i][j], node[i][j + 1]));
            }
        }
    }
    let mut cells = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            let mut ring = vec![node[i][j]];
            ring.extend(&horiz[&(i, j)]);
            ring.push(node[i + 1][j]);
            ring.extend(&vert[&(i + 1, j)]);
            ring.push(node[i + 1][j + 1]);
            ring.extend(horiz[&(i, j + 1)].iter().rev());
            ring.push(node[i][j + 1]);
            ring.extend(vert[&(i, j)].iter().rev());
            ring.push(node[i][j]);
            cells.push(poly(ring, vec![]));
        }
    }
    cells
}

/// A hexagonal mosaic, `n` by `n` cells of radius 1, each edge with `m`
/// positions displaced by up to `amp`.
pub fn hexagons(n: usize, m: usize, amp: f64, seed: u64) -> Vec<Geometry<f64>> {
    let mut rng = Rng(seed);
    let r = 1.0;
    let w = 3f64.sqrt() * r;
    // Corners rounded to a grid so that neighbours compute the same bits.
    let q = |v: f64| (v * 1e9).round() / 1e9;
    let mut edges: HashMap<[i64; 4], Vec<Coord>> = HashMap::new();
    let kx = |p: Coord| ((p.x * 1e6).round() as i64, (p.y * 1e6).round() as i64);
    let mut cells = Vec::new();
    for row in 0..n {
        for col in 0..n {
            let cx = col as f64 * w + if row % 2 == 1 { w / 2.0 } else { 0.0 };
            let cy = row as f64 * 1.5 * r;
            let corners: Vec<Coord> = (0..6)
                .map(|k| {
                    let a = std::f64::consts::PI / 180.0 * (60.0 * k as f64 + 30.0);
                    c(q(cx + r * a.cos()), q(cy + r * a.sin()))
                })
                .collect();
            let mut ring = Vec::new();
            for k in 0..6 {
                let (a, b) = (corners[k], corners[(k + 1) % 6]);
                ring.push(a);
                let (ka, kb) = (kx(a), kx(b));
                let mids = if let Some(e) = edges.get(&[kb.0, kb.1, ka.0, ka.1]) {
                    e.iter().rev().copied().collect()
                } else {
                    let (dx, dy) = (b.x - a.x, b.y - a.y);
                    let mids: Vec<Coord> = (1..=m)
                        .map(|j| {
                            let t = j as f64 / (m + 1) as f64;
                            let d = amp * rng.sym();
                            c(a.x + dx * t - dy * d, a.y + dy * t + dx * d)
                        })
                        .collect();
                    edges.insert([ka.0, ka.1, kb.0, kb.1], mids.clone());
                    mids
                };
                ring.extend(mids);
            }
            ring.push(corners[0]);
            cells.push(poly(ring, vec![]));
        }
    }
    cells
}

/// Voronoi cells of `n` random points in the unit square (geo's `Voronoi`;
/// clipped by geo to a box around the points), positions rounded to 1e-6,
/// each edge given `m` positions displaced across it by up to
/// `amp` of its length; the positions depend only on the edge, so the two
/// cells that share it get them bit for bit.
pub fn voronoi_mosaic(n: usize, m: usize, amp: f64, seed: u64) -> Vec<Geometry<f64>> {
    use geo::Voronoi;
    let mut rng = Rng(seed);
    let pts = geo_types::MultiPoint(
        (0..n)
            .map(|_| geo_types::Point::new(rng.next(), rng.next()))
            .collect(),
    );
    let Ok(cells) = pts.voronoi_cells() else {
        return Vec::new();
    };
    let clip = Polygon::new(
        LineString(vec![
            c(-0.5, -0.5),
            c(1.5, -0.5),
            c(1.5, 1.5),
            c(-0.5, 1.5),
            c(-0.5, -0.5),
        ]),
        vec![],
    );
    cells
        .into_iter()
        .filter(|cell| cell.exterior().0.len() >= 4 && cell.relate(&clip).is_within())
        .map(|cell| {
            // geo computes a vertex for each cell that meets it, a few ulps
            // apart (up to about 1e-8): rounded to a grid of 1e-6 they agree.
            let q = |v: f64| (v * 1e6).round() / 1e6;
            let r: Vec<Coord> = cell
                .exterior()
                .0
                .iter()
                .map(|p| c(q(p.x), q(p.y)))
                .collect();
            let mut ring = Vec::new();
            for w in r.windows(2) {
                let (a, b) = (w[0], w[1]);
                ring.push(a);
                let (p, q, flip) = if bits(a) <= bits(b) {
                    (a, b, false)
                } else {
                    (b, a, true)
                };
                let mut e = Rng(seed
                    ^ p.x.to_bits()
                    ^ p.y.to_bits().rotate_left(17)
                    ^ q.x.to_bits().rotate_left(31)
                    ^ q.y.to_bits().rotate_left(47));
                let (dx, dy) = (q.x - p.x, q.y - p.y);
                let mut mids: Vec<Coord> = (1..=m)
                    .map(|k| {
                        let t = k as f64 / (m + 1) as f64;
                        let d = amp * e.sym();
                        c(p.x + dx * t - dy * d, p.y + dy * t + dx * d)
                    })
                    .collect();
                if flip {
                    mids.reverse();
                }
                ring.extend(mids);
            }
            ring.push(r[r.len() - 1]);
            poly(ring, vec![])
        })
        .collect()
}

/// Every segment of the geometry's lines and rings.
pub fn segments(g: &Geometry<f64>) -> Vec<(Coord, Coord)> {
    let mut out = Vec::new();
    let mut line = |l: &LineString<f64>| out.extend(l.0.windows(2).map(|w| (w[0], w[1])));
    match g {
        Geometry::LineString(l) => line(l),
        Geometry::MultiLineString(m) => m.0.iter().for_each(line),
        Geometry::Polygon(p) => {
            line(p.exterior());
            p.interiors().iter().for_each(line);
        }
        Geometry::MultiPolygon(m) => m.0.iter().for_each(|p| {
            line(p.exterior());
            p.interiors().iter().for_each(&mut line);
        }),
        _ => {}
    }
    out
}

/// A segment's ends as bits, in order: the same key both ways round.
type SegKey = ((u64, u64), (u64, u64));

fn bits(c: Coord) -> (u64, u64) {
    ((c.x + 0.0).to_bits(), (c.y + 0.0).to_bits())
}

fn seg_key(a: Coord, b: Coord) -> SegKey {
    let (ka, kb) = (bits(a), bits(b));
    if ka <= kb {
        (ka, kb)
    } else {
        (kb, ka)
    }
}

fn orient(a: Coord, b: Coord, p: Coord) -> f64 {
    robust::orient2d(
        robust::Coord { x: a.x, y: a.y },
        robust::Coord { x: b.x, y: b.y },
        robust::Coord { x: p.x, y: p.y },
    )
}

fn on(a: Coord, b: Coord, p: Coord) -> bool {
    orient(a, b, p) == 0.0
        && p.x >= a.x.min(b.x)
        && p.x <= a.x.max(b.x)
        && p.y >= a.y.min(b.y)
        && p.y <= a.y.max(b.y)
}

/// The distinct segments of all geometries (a shared border once).
fn distinct_segments(gs: &[Geometry<f64>]) -> Vec<(Coord, Coord)> {
    let mut seen = HashSet::new();
    gs.iter()
        .flat_map(segments)
        .filter(|&(a, b)| bits(a) != bits(b) && seen.insert(seg_key(a, b)))
        .collect()
}

/// Two distinct segments meet anywhere but at a common end position, or
/// overlap.
fn pair_conflicts((a0, a1): (Coord, Coord), (b0, b1): (Coord, Coord)) -> bool {
    if a0.x.max(a1.x) < b0.x.min(b1.x)
        || b0.x.max(b1.x) < a0.x.min(a1.x)
        || a0.y.max(a1.y) < b0.y.min(b1.y)
        || b0.y.max(b1.y) < a0.y.min(a1.y)
    {
        return false;
    }
    let shared = [a0, a1]
        .iter()
        .any(|&p| bits(p) == bits(b0) || bits(p) == bits(b1));
    let d1 = orient(a0, a1, b0);
    let d2 = orient(a0, a1, b1);
    let d3 = orient(b0, b1, a0);
    let d4 = orient(b0, b1, a1);
    let proper = d1 * d2 < 0.0 && d3 * d4 < 0.0;
    let touch = on(a0, a1, b0) || on(a0, a1, b1) || on(b0, b1, a0) || on(b0, b1, a1);
    if !shared {
        return proper || touch;
    }
    // Sharing one end: they conflict when collinear and leaving it together,
    // or when the other end of one lies on the other.
    let (e, oa, ob) = if bits(a0) == bits(b0) {
        (a0, a1, b1)
    } else if bits(a0) == bits(b1) {
        (a0, a1, b0)
    } else if bits(a1) == bits(b0) {
        (a1, a0, b1)
    } else {
        (a1, a0, b0)
    };
    let together =
        d1 == 0.0 && d2 == 0.0 && (oa.x - e.x) * (ob.x - e.x) + (oa.y - e.y) * (ob.y - e.y) > 0.0;
    together || on(a0, a1, ob) || on(b0, b1, oa)
}

/// Brute force over every pair of distinct segments of all geometries: the
/// pairs that meet anywhere but at a common end position, or overlap.
pub fn brute_force_crossings(gs: &[Geometry<f64>]) -> usize {
    let segs = distinct_segments(gs);
    let mut bad = 0;
    for i in 0..segs.len() {
        for &q in &segs[i + 1..] {
            if pair_conflicts(segs[i], q) {
                bad += 1;
            }
        }
    }
    bad
}

/// The same count as [`brute_force_crossings`], with the pairs tried only
/// within the cells of a uniform grid, for inputs too large for all pairs.
pub fn grid_crossings(gs: &[Geometry<f64>]) -> usize {
    let segs = distinct_segments(gs);
    if segs.is_empty() {
        return 0;
    }
    let mean = segs
        .iter()
        .map(|(a, b)| (b.x - a.x).hypot(b.y - a.y))
        .sum::<f64>()
        / segs.len() as f64;
    let cell = (4.0 * mean).max(f64::MIN_POSITIVE);
    let (x0, y0) = segs
        .iter()
        .fold((f64::INFINITY, f64::INFINITY), |(x, y), (a, b)| {
            (x.min(a.x).min(b.x), y.min(a.y).min(b.y))
        });
    let idx = |v: f64, o: f64| ((v - o) / cell).floor() as i64;
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (k, (a, b)) in segs.iter().enumerate() {
        for i in idx(a.x.min(b.x), x0)..=idx(a.x.max(b.x), x0) {
            for j in idx(a.y.min(b.y), y0)..=idx(a.y.max(b.y), y0) {
                grid.entry((i, j)).or_default().push(k);
            }
        }
    }
    let mut bad = HashSet::new();
    for members in grid.values() {
        for (x, &i) in members.iter().enumerate() {
            for &j in &members[x + 1..] {
                if pair_conflicts(segs[i], segs[j]) {
                    bad.insert((i.min(j), i.max(j)));
                }
            }
        }
    }
    bad.len()
}

/// The polygons' rings (shell first) of a geometry.
pub fn polygons(g: &Geometry<f64>) -> Vec<Polygon<f64>> {
    match g {
        Geometry::Polygon(p) => vec![p.clone()],
        Geometry::MultiPolygon(m) => m.0.clone(),
        _ => vec![],
    }
}

/// Pairs of geometries that share at least one edge, found from the input.
pub fn neighbours(gs: &[Geometry<f64>]) -> Vec<(usize, usize)> {
    let mut owner: HashMap<SegKey, Vec<usize>> = HashMap::new();
    for (i, g) in gs.iter().enumerate() {
        for (a, b) in segments(g) {
            if bits(a) != bits(b) {
                let e = owner.entry(seg_key(a, b)).or_default();
                if e.last() != Some(&i) {
                    e.push(i);
                }
            }
        }
    }
    let mut pairs: Vec<(usize, usize)> = owner
        .values()
        .flat_map(|o| {
            let o = o.clone();
            (0..o.len()).flat_map(move |x| {
                let o = o.clone();
                (x + 1..o.len()).map(move |y| (o[x].min(o[y]), o[x].max(o[y])))
            })
        })
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// The two geometries' boundaries have at least one segment in common, bit
/// for bit.
pub fn share_segment(out_a: &Geometry<f64>, out_b: &Geometry<f64>) -> Result<(), String> {
    let sa: HashSet<_> = segments(out_a)
        .into_iter()
        .map(|(a, b)| seg_key(a, b))
        .collect();
    if segments(out_b)
        .into_iter()
        .any(|(a, b)| sa.contains(&seg_key(a, b)))
    {
        Ok(())
    } else {
        Err("no segment in common".into())
    }
}

/// For a pair of neighbours: their output boundaries share at least one
/// segment and their interiors do not overlap (geo's DE-9IM relate).
pub fn share_border(out_a: &Geometry<f64>, out_b: &Geometry<f64>) -> Result<(), String> {
    share_segment(out_a, out_b)?;
    let m = out_a.relate(out_b);
    if !m.is_touches() {
        return Err(format!("not touching only: {m:?}"));
    }
    Ok(())
}

/// Signed area of a ring (positive counter-clockwise).
pub fn signed(ring: &LineString<f64>) -> f64 {
    Polygon::new(ring.clone(), vec![]).signed_area()
}

/// Every output polygon that was valid in the input is valid, every ring is
/// closed with at least 4 positions and keeps its winding.
pub fn valid_stays_valid(input: &[Geometry<f64>], output: &[Geometry<f64>]) -> Result<(), String> {
    for (gi, (i, o)) in input.iter().zip(output).enumerate() {
        for (pi, (pin, pout)) in polygons(i).iter().zip(polygons(o)).enumerate() {
            let rings_in: Vec<&LineString<f64>> = std::iter::once(pin.exterior())
                .chain(pin.interiors())
                .collect();
            let rings_out: Vec<&LineString<f64>> = std::iter::once(pout.exterior())
                .chain(pout.interiors())
                .collect();
            for (ri, (ri_in, ri_out)) in rings_in.iter().zip(&rings_out).enumerate() {
                let n = ri_out.0.len();
                if n < 4 || ri_out.0[0] != ri_out.0[n - 1] {
                    return Err(format!(
                        "geometry {gi} polygon {pi} ring {ri}: {n} positions or not closed"
                    ));
                }
                if signed(ri_in).signum() != signed(ri_out).signum() {
                    return Err(format!(
                        "geometry {gi} polygon {pi} ring {ri}: winding changed"
                    ));
                }
            }
            if pin.is_valid() {
                if let Err(e) = pout.check_validation() {
                    return Err(format!("geometry {gi} polygon {pi}: valid before, now {e}"));
                }
            }
        }
    }
    Ok(())
}
