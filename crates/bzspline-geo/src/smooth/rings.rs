//! What smoothing must keep of rings: each ring's winding, holes inside
//! their shells, and the areas, from shoelace sums over arcs.

use geo_types::{Coord, Rect};

use super::bounds;
use crate::arcs::Arcs;
use crate::ragged::Ragged;
use crate::topology::{ChainKind, Topology};

/// A ring of no polygon (a line's chain) in [`RingFacts::polygon_of`].
pub(super) const NO_POLYGON: u32 = u32::MAX;

/// What the input says about its rings, for the checks after smoothing.
pub(super) struct RingFacts {
    /// The polygon each ring belongs to ([`NO_POLYGON`] for none).
    pub(super) polygon_of: Vec<u32>,
    /// Each ring's winding in the input: the sign of its shoelace sum, as
    /// `f64::signum` gives it (0 for a line).
    pub(super) sign_in: Vec<i8>,
    /// Per polygon, whether each hole lies inside the shell in the input.
    pub(super) inside_in: Ragged<bool>,
}

impl RingFacts {
    pub(super) fn of(t: &Topology, shoelace: &Shoelace, cross_in: &[f64]) -> RingFacts {
        let mut polygon_of = vec![NO_POLYGON; t.chains().len()];
        for (pi, p) in t.polygons().iter().enumerate() {
            for &c in p {
                polygon_of[c] = u32::try_from(pi).expect("fewer than 2^32 - 1 polygons");
            }
        }
        let sign_in = (0..t.chains().len())
            .map(|ci| match t.chain(ci).kind {
                ChainKind::Ring => shoelace.ring(t, ci, &|a| cross_in[a]).signum() as i8,
                ChainKind::Line => 0,
            })
            .collect();
        let polygons = t.polygons();
        let mut inside_in = Ragged::with_capacity(polygons.len(), polygons.values().len());
        for p in polygons.iter() {
            inside_in.push_row(holes_inside(t, p, t.arcs()));
        }
        RingFacts {
            polygon_of,
            sign_in,
            inside_in,
        }
    }
}

/// For each hole of `rings` (shell first), whether it lies inside the shell.
pub(super) fn holes_inside(t: &Topology, rings: &[usize], arcs: &Arcs) -> Vec<bool> {
    if rings.len() < 2 {
        return Vec::new();
    }
    let shell = t.chain_coords(rings[0], arcs);
    rings[1..]
        .iter()
        .map(|&h| {
            let hole = t.chain_coords(h, arcs);
            hole.iter().find_map(|&p| locate(p, &shell)).unwrap_or(true)
        })
        .collect()
}

/// Signed areas by the shoelace formula, summed over arcs: a ring's area is
/// half the sum of its arcs' cross products (negated for a reversed arc), so
/// no ring is assembled. Coordinates are taken about the centre of the data,
/// which keeps the products small far from the origin, and scaled by a power
/// of two where products of the data's size would underflow or overflow
/// ([`crate::crossings::unit_scale`]), so that a ring's sign is kept.
pub(super) struct Shoelace {
    origin: Coord,
    scale: f64,
}

impl Shoelace {
    pub(super) fn about(arcs: &Arcs, extent: Option<Rect<f64>>) -> Shoelace {
        let (lo, hi) = bounds(arcs, extent);
        let mid = |a: f64, b: f64| {
            if a.is_finite() {
                a / 2.0 + b / 2.0
            } else {
                0.0
            }
        };
        let half = (hi[0] - lo[0]).max(hi[1] - lo[1]) / 2.0;
        Shoelace {
            origin: Coord {
                x: mid(lo[0], hi[0]),
                y: mid(lo[1], hi[1]),
            },
            scale: crate::crossings::unit_scale(half),
        }
    }

    /// The sum of `x_i y_{i+1} - x_{i+1} y_i` along an arc.
    pub(super) fn arc(&self, a: &[Coord]) -> f64 {
        let (o, s) = (self.origin, self.scale);
        if s == 1.0 {
            return a
                .windows(2)
                .map(|w| (w[0].x - o.x) * (w[1].y - o.y) - (w[1].x - o.x) * (w[0].y - o.y))
                .sum();
        }
        a.windows(2)
            .map(|w| {
                let (x0, y0) = ((w[0].x - o.x) * s, (w[0].y - o.y) * s);
                let (x1, y1) = ((w[1].x - o.x) * s, (w[1].y - o.y) * s);
                x0 * y1 - x1 * y0
            })
            .sum()
    }

    /// The signed area of ring `ci` (positive counter-clockwise), from
    /// each arc's sum of cross products ([`Shoelace::arc`]) by its index.
    pub(super) fn ring(&self, t: &Topology, ci: usize, cross: &impl Fn(usize) -> f64) -> f64 {
        t.chain(ci)
            .arcs
            .iter()
            .map(|r| {
                if r.reversed() {
                    -cross(r.index())
                } else {
                    cross(r.index())
                }
            })
            .sum::<f64>()
            / 2.0
    }

    /// Area of the polygons: shells less holes, in the data's units.
    pub(super) fn polygons(&self, t: &Topology, cross: &impl Fn(usize) -> f64) -> f64 {
        self.scaled_polygons(t, cross) / self.scale / self.scale
    }

    /// Area of the polygons in the scaled units of the cross products.
    fn scaled_polygons(&self, t: &Topology, cross: &impl Fn(usize) -> f64) -> f64 {
        t.polygons()
            .iter()
            .map(|p| {
                p.iter()
                    .enumerate()
                    .map(|(k, &c)| {
                        let a = self.ring(t, c, cross).abs();
                        if k == 0 {
                            a
                        } else {
                            -a
                        }
                    })
                    .sum::<f64>()
            })
            .sum()
    }
}

/// Whether `p` is inside the closed `ring` (winding number with exact
/// orientation); `None` on its boundary.
fn locate(p: Coord, ring: &[Coord]) -> Option<bool> {
    let orient = |a: Coord, b: Coord| crate::crossings::orient_at_any_scale(a, b, p);
    let mut wn = 0i64;
    for w in ring.windows(2) {
        let (a, b) = (w[0], w[1]);
        let o = orient(a, b);
        if o == 0.0
            && p.x >= a.x.min(b.x)
            && p.x <= a.x.max(b.x)
            && p.y >= a.y.min(b.y)
            && p.y <= a.y.max(b.y)
        {
            return None;
        }
        if a.y <= p.y {
            if b.y > p.y && o > 0.0 {
                wn += 1;
            }
        } else if b.y <= p.y && o < 0.0 {
            wn -= 1;
        }
    }
    Some(wn != 0)
}
