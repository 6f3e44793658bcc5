//! A coverage of geo-types geometries: their lines and rings in one
//! [`Topology`], smoothed together and put back in the geometries' shapes.

use geo_types::{Coord, Geometry, GeometryCollection, Line, LineString, MultiLineString};
use geo_types::{MultiPolygon, Polygon};

use crate::arcs::Arcs;
use crate::error::Error;
use crate::levels::Levels;
use crate::nodes::Nodes;
use crate::options::{Frame, SmoothOptions};
use crate::ragged::Ragged;
use crate::smooth::Stats;
use crate::topology::{snap_in, ChainKind, Topology};

/// Where a chain came from: the geometry, the member of a multi-geometry or
/// collection (0 for a single one), the ring of a polygon (0 the shell).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Origin {
    geometry: usize,
    member: usize,
    ring: usize,
    polygon: bool,
}

/// Geometries whose lines and rings are smoothed as one coverage: a border
/// that two polygons (or a polygon and a line) share is smoothed once and
/// comes out identical in both.
///
/// Points and MultiPoints pass through; Rects and Triangles are smoothed as
/// the polygons they are and come out as Polygons; a Line is a two-position
/// line and keeps its positions. The coverage holds each position once, in
/// its topology: the geometries given are not kept beside it.
///
/// # Examples
///
/// ```
/// use bzspline_geo::{Coverage, SmoothOptions};
/// use geo_types::{polygon, Geometry};
///
/// let a = polygon![(x: 0.0, y: 0.0), (x: 2.0, y: 0.0), (x: 2.0, y: 1.0), (x: 1.0, y: 2.0), (x: 0.0, y: 1.0)];
/// let b = polygon![(x: 2.0, y: 0.0), (x: 4.0, y: 0.0), (x: 4.0, y: 2.0), (x: 2.0, y: 1.0)];
/// let coverage = Coverage::new(vec![Geometry::Polygon(a), Geometry::Polygon(b)])?;
/// let (out, stats) = coverage.smooth(&SmoothOptions::default().tolerance(1e-3))?;
/// assert_eq!(stats.shared_arcs, 1);
/// // The border (2, 0) - (2, 1) is in both, unchanged: its ends are nodes
/// // and it is straight.
/// let ring = |g: &Geometry| match g {
///     Geometry::Polygon(p) => p.exterior().0.clone(),
///     _ => unreachable!(),
/// };
/// assert!(ring(&out[0]).contains(&(2.0, 1.0).into()));
/// assert!(ring(&out[1]).contains(&(2.0, 1.0).into()));
/// # Ok::<(), bzspline_geo::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Coverage {
    /// Each geometry's shape: its points as given, its lines and rings
    /// without positions (the topology holds them once).
    geometries: Vec<Geometry<f64>>,
    topology: Topology,
    origins: Vec<Origin>,
}

/// The inputs of a [`Coverage`] beyond its geometries, by name
/// ([`Coverage::builder`]).
#[derive(Debug, Clone)]
#[must_use]
pub struct CoverageBuilder {
    geometries: Vec<Geometry<f64>>,
    snap: Option<f64>,
    frame: Frame,
    nodes: Nodes,
}

impl CoverageBuilder {
    /// Merges positions closer than `distance` first, and puts positions
    /// that close to another line's or ring's edge into it
    /// ([`crate::snap`]); `None` (the default) does not snap.
    pub fn snap(mut self, distance: impl Into<Option<f64>>) -> Self {
        self.snap = distance.into();
        self
    }

    /// What the positions are, for [`CoverageBuilder::snap`]: in the
    /// geographic frame the snap distance is an angle of a great circle in
    /// degrees, measured on the ground ([`crate::snap_in`]). The default is
    /// the plane; smoothing takes its frame from its options.
    pub fn frame(mut self, frame: Frame) -> Self {
        self.frame = frame;
        self
    }

    /// Smooths the geometries as one part of a larger coverage, with the
    /// nodes of the whole ([`crate::parts`]): the part's lines and rings are
    /// cut as the whole coverage would cut them, and smoothed the same where
    /// the part also holds the features that meet its extent (see the module
    /// docs of [`crate::parts`]); with the nodes' extent the default
    /// tolerance is the whole's. Snapping is done within the part; snap the
    /// whole first when parts must agree on it.
    pub fn nodes(mut self, nodes: Nodes) -> Self {
        self.nodes = nodes;
        self
    }

    /// Finds the topology.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a coordinate that is not finite
    /// ([`Coverage::describe`] names the geometry); [`Error::InvalidOption`]
    /// for a snap distance that is not a finite non-negative number.
    pub fn build(self) -> Result<Coverage, Error> {
        let mut geometries = self.geometries;
        let (mut chains, origins, polygons) = gather(&mut geometries);
        if let Some(eps) = self.snap {
            snap_in(&mut chains, eps, self.frame)?;
        }
        let topology = Topology::from_owned_chains(chains, polygons, self.nodes)?;
        Ok(Coverage {
            geometries,
            topology,
            origins,
        })
    }
}

impl Coverage {
    /// Finds the topology of `geometries` (no snapping, no outside nodes:
    /// [`Coverage::builder`] for those).
    ///
    /// # Errors
    ///
    /// As [`CoverageBuilder::build`].
    pub fn new(geometries: Vec<Geometry<f64>>) -> Result<Self, Error> {
        Coverage::builder(geometries).build()
    }

    /// A coverage of `geometries` with options by name:
    /// `Coverage::builder(gs).snap(1e-6).build()`.
    pub fn builder(geometries: Vec<Geometry<f64>>) -> CoverageBuilder {
        CoverageBuilder {
            geometries,
            snap: None,
            frame: Frame::Plane,
            nodes: Nodes::default(),
        }
    }

    /// The topology: arcs, the lines and rings made of them, the polygons.
    #[must_use]
    pub fn topology(&self) -> &Topology {
        &self.topology
    }

    /// How many geometries the coverage holds.
    #[must_use]
    pub fn len(&self) -> usize {
        self.geometries.len()
    }

    /// Whether the coverage holds no geometry.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.geometries.is_empty()
    }

    /// Smooths the coverage (see [`Topology::smooth`]) and returns the
    /// geometries with their smoothed lines and rings, and what was done.
    ///
    /// # Errors
    ///
    /// As [`Topology::smooth`].
    pub fn smooth(&self, opts: &SmoothOptions) -> Result<(Vec<Geometry<f64>>, Stats), Error> {
        let s = self.topology.smooth(opts)?;
        Ok((self.assemble(&s.arcs), s.stats))
    }

    /// As [`Coverage::smooth`], starting from the refinement levels `start`
    /// ([`Topology::smooth_from`]); also returns the levels the arcs end at.
    ///
    /// # Errors
    ///
    /// As [`Topology::smooth`].
    pub fn smooth_from(
        &self,
        opts: &SmoothOptions,
        start: &Levels,
    ) -> Result<(Vec<Geometry<f64>>, Stats, Levels), Error> {
        let s = self.topology.smooth_from(opts, start)?;
        Ok((self.assemble(&s.arcs), s.stats, s.levels))
    }

    /// One round of the conflict search ([`Topology::smooth_round`]), with
    /// the geometries `exact` marks held exactly (their neighbours all among
    /// the geometries; all when it is empty) and the rest only for the
    /// topology: the geometries at `start`'s levels, and the levels after
    /// the round.
    ///
    /// # Errors
    ///
    /// As [`Topology::smooth`].
    pub fn smooth_round(
        &self,
        opts: &SmoothOptions,
        start: &Levels,
        round: usize,
        exact: &[bool],
    ) -> Result<(Vec<Geometry<f64>>, Stats, Levels), Error> {
        let chains: Vec<bool> = if exact.is_empty() {
            Vec::new()
        } else {
            self.origins
                .iter()
                .map(|o| exact.get(o.geometry).copied().unwrap_or(false))
                .collect()
        };
        let s = self.topology.smooth_round(opts, start, round, &chains)?;
        Ok((self.assemble(&s.arcs), s.stats, s.levels))
    }

    /// The geometries with every line and ring put together from `arcs` (the
    /// topology's arcs, or smoothed ones with the same indices).
    ///
    /// # Panics
    ///
    /// When `arcs` has fewer arcs than the topology.
    #[must_use]
    pub fn assemble(&self, arcs: &Arcs) -> Vec<Geometry<f64>> {
        let mut next = 0usize;
        let mut take = || {
            let c = self.topology.chain_coords(next, arcs);
            next += 1;
            c
        };
        self.geometries
            .iter()
            .map(|g| rebuild(g, &mut take))
            .collect()
    }

    /// Where an error's chain (or, for an arc's error, the first chain that
    /// uses the arc) comes from.
    #[must_use]
    pub fn locate(&self, e: &Error) -> Option<Location> {
        let chain = self.topology.chain_of(e)?;
        let o = self.origins.get(chain)?;
        Some(Location {
            geometry: o.geometry,
            member: o.member,
            ring: o.polygon.then_some(o.ring),
        })
    }

    /// The error with its place: `geometry 4, member 1, ring 2: ...`.
    #[must_use]
    pub fn describe(&self, e: &Error) -> String {
        match self.locate(e) {
            Some(l) => format!("{l}: {e}"),
            None => e.to_string(),
        }
    }
}

/// Where in the geometries a line or ring is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Location {
    /// The geometry's index.
    pub geometry: usize,
    /// The line or polygon within a multi-geometry or collection (0 for a
    /// single one), counted over nested collections in order.
    pub member: usize,
    /// The ring of a polygon (0 the shell); `None` for a line.
    pub ring: Option<usize>,
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "geometry {}, member {}", self.geometry, self.member)?;
        if let Some(r) = self.ring {
            write!(f, ", ring {r}")?;
        }
        Ok(())
    }
}

/// The lines and rings of `geometries`, in the order a [`Coverage`] holds
/// them: for [`crate::parts::meetings`] and [`crate::nodes::Nodes::of`].
#[must_use]
pub fn coverage_chains(geometries: &[Geometry<f64>]) -> Vec<(ChainKind, Vec<Coord>)> {
    gather(&mut geometries.to_vec()).0
}

/// The chains of `geometries`, where each comes from, and which rings form
/// each polygon. The positions of every line and ring are moved into the
/// chains, not copied: each geometry is left as its shape, its lines and
/// rings without positions, for [`rebuild`].
#[allow(clippy::type_complexity)] // three parallel results, used once
fn gather(
    geometries: &mut [Geometry<f64>],
) -> (Vec<(ChainKind, Vec<Coord>)>, Vec<Origin>, Ragged<usize>) {
    let mut chains: Vec<(ChainKind, Vec<Coord>)> = Vec::new();
    let mut origins: Vec<Origin> = Vec::new();
    let mut polygons: Ragged<usize> = Ragged::new();
    for (gi, g) in geometries.iter_mut().enumerate() {
        let mut member = 0;
        visit(g, &mut |part| {
            match part {
                Part::Line(coords) => {
                    origins.push(Origin {
                        geometry: gi,
                        member,
                        ring: 0,
                        polygon: false,
                    });
                    chains.push((ChainKind::Line, coords));
                }
                Part::Polygon(rings) => {
                    let first = chains.len();
                    for (ri, r) in rings.into_iter().enumerate() {
                        origins.push(Origin {
                            geometry: gi,
                            member,
                            ring: ri,
                            polygon: true,
                        });
                        chains.push((ChainKind::Ring, r));
                    }
                    polygons.push_row(first..chains.len());
                }
            }
            member += 1;
        });
    }
    (chains, origins, polygons)
}

/// A line's positions, or a polygon's rings' (the shell first).
enum Part {
    Line(Vec<Coord>),
    Polygon(Vec<Vec<Coord>>),
}

/// Calls `f` on every line and polygon of `g`, in order, with their
/// positions taken out of `g` (a Line, Rect or Triangle keeps its own).
fn visit(g: &mut Geometry<f64>, f: &mut dyn FnMut(Part)) {
    let take = |l: &mut LineString<f64>| std::mem::take(&mut l.0);
    match g {
        Geometry::Point(_) | Geometry::MultiPoint(_) => {}
        Geometry::Line(l) => f(Part::Line(vec![l.start, l.end])),
        Geometry::LineString(l) => f(Part::Line(take(l))),
        Geometry::MultiLineString(m) => m.0.iter_mut().for_each(|l| f(Part::Line(take(l)))),
        Geometry::Polygon(p) => f(Part::Polygon(take_rings(p))),
        Geometry::MultiPolygon(m) => m.0.iter_mut().for_each(|p| f(Part::Polygon(take_rings(p)))),
        Geometry::Rect(r) => f(Part::Polygon(vec![r.to_polygon().into_inner().0 .0])),
        Geometry::Triangle(t) => f(Part::Polygon(vec![t.to_polygon().into_inner().0 .0])),
        Geometry::GeometryCollection(c) => c.0.iter_mut().for_each(|g| visit(g, f)),
    }
}

/// The rings of `p`, the shell first, leaving it as many rings without
/// positions.
fn take_rings(p: &mut Polygon<f64>) -> Vec<Vec<Coord>> {
    let hollow = || LineString(Vec::new());
    let (shell, holes) = std::mem::replace(p, Polygon::new(hollow(), Vec::new())).into_inner();
    *p = Polygon::new(hollow(), holes.iter().map(|_| hollow()).collect());
    std::iter::once(shell.0)
        .chain(holes.into_iter().map(|h| h.0))
        .collect()
}

/// `g` with each line and ring, in the order [`visit`] meets them, from `take`.
fn rebuild(g: &Geometry<f64>, take: &mut dyn FnMut() -> Vec<Coord>) -> Geometry<f64> {
    let polygon = |rings: usize, take: &mut dyn FnMut() -> Vec<Coord>| {
        let shell = LineString(take());
        let holes = (1..rings).map(|_| LineString(take())).collect();
        Polygon::new(shell, holes)
    };
    match g {
        Geometry::Point(_) | Geometry::MultiPoint(_) => g.clone(),
        Geometry::Line(l) => {
            let c = take();
            Geometry::Line(Line::new(
                c.first().copied().unwrap_or(l.start),
                c.last().copied().unwrap_or(l.end),
            ))
        }
        Geometry::LineString(_) => Geometry::LineString(LineString(take())),
        Geometry::MultiLineString(m) => Geometry::MultiLineString(MultiLineString(
            m.0.iter().map(|_| LineString(take())).collect(),
        )),
        Geometry::Polygon(p) => Geometry::Polygon(polygon(1 + p.interiors().len(), take)),
        Geometry::MultiPolygon(m) => Geometry::MultiPolygon(MultiPolygon(
            m.0.iter()
                .map(|p| polygon(1 + p.interiors().len(), take))
                .collect(),
        )),
        Geometry::Rect(_) | Geometry::Triangle(_) => Geometry::Polygon(polygon(1, take)),
        Geometry::GeometryCollection(c) => Geometry::GeometryCollection(GeometryCollection(
            c.0.iter().map(|g| rebuild(g, take)).collect(),
        )),
    }
}
