//! A coverage of geo-types geometries: their lines and rings in one
//! [`Topology`], smoothed together and put back in the geometries' shapes.

use geo_types::{Coord, Geometry, GeometryCollection, Line, LineString, MultiLineString};
use geo_types::{MultiPolygon, Polygon};

use crate::arcs::Arcs;
use crate::assembled::Assembled;
use crate::error::Error;
use crate::levels::Levels;
use crate::nodes::Nodes;
use crate::options::{Frame, SmoothOptions};
use crate::ragged::Ragged;
use crate::shapes::Shapes;
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
    /// only counted (the topology holds their positions once).
    shapes: Shapes,
    topology: Topology,
}

/// A geometry without the positions of its lines and rings: what
/// [`rebuild`] puts them back into ([`Shapes`] holds the common ones in 4
/// bytes, where a geo-types `Geometry` takes 56).
#[derive(Clone, Debug)]
pub(crate) enum Shape {
    /// A Point or MultiPoint, as given.
    Kept(Box<Geometry<f64>>),
    /// A Line, whose ends stand in when its line has none.
    Line(Box<Line<f64>>),
    LineString,
    /// So many LineStrings.
    MultiLineString(usize),
    /// A Polygon of so many rings (a Rect's or Triangle's is one).
    Polygon(usize),
    /// Polygons of so many rings each.
    MultiPolygon(Box<[usize]>),
    Collection(Box<[Shape]>),
}

impl Shape {
    /// The shape of `g`.
    fn of(g: &Geometry<f64>) -> Shape {
        let rings = |p: &Polygon<f64>| 1 + p.interiors().len();
        match g {
            Geometry::Point(_) | Geometry::MultiPoint(_) => Shape::Kept(Box::new(g.clone())),
            Geometry::Line(l) => Shape::Line(Box::new(*l)),
            Geometry::LineString(_) => Shape::LineString,
            Geometry::MultiLineString(m) => Shape::MultiLineString(m.0.len()),
            Geometry::Polygon(p) => Shape::Polygon(rings(p)),
            Geometry::MultiPolygon(m) => Shape::MultiPolygon(m.0.iter().map(rings).collect()),
            Geometry::Rect(_) | Geometry::Triangle(_) => Shape::Polygon(1),
            Geometry::GeometryCollection(c) => {
                Shape::Collection(c.0.iter().map(Shape::of).collect())
            }
        }
    }
}

/// The inputs of a [`Coverage`] beyond its geometries, by name
/// ([`Coverage::builder`]); `I` gives the geometries.
#[derive(Debug, Clone)]
#[must_use]
pub struct CoverageBuilder<I = std::vec::IntoIter<Geometry<f64>>> {
    geometries: I,
    snap: Option<f64>,
    frame: Frame,
    nodes: Nodes,
}

impl<I: Iterator<Item = Geometry<f64>>> CoverageBuilder<I> {
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

    /// Finds the topology, taking the geometries one at a time: without
    /// snapping, each geometry's positions are let go of as soon as the
    /// topology holds them, so the geometries and the topology are never
    /// all held at once (snapping needs every position first).
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] for a coordinate that is not finite
    /// ([`Coverage::describe`] names the geometry); [`Error::InvalidOption`]
    /// for a snap distance that is not a finite non-negative number.
    pub fn build(self) -> Result<Coverage, Error> {
        let CoverageBuilder {
            geometries,
            snap,
            frame,
            nodes,
        } = self;
        // Most geometries have one line or ring: room for as many chains.
        let room = geometries.size_hint().0;
        let mut shapes = Shapes::with_capacity(room);
        let mut polygons: Ragged<usize> = Ragged::new();
        let mut taken = 0;
        let chains = geometries.flat_map(|mut g| {
            let chains = take_chains(&mut g, taken, &mut polygons);
            taken += chains.len();
            shapes.push(Shape::of(&g));
            chains
        });
        let topology = match snap {
            None => Topology::from_gathered(chains, room, nodes)?,
            Some(eps) => {
                let mut chains: Vec<(ChainKind, Vec<Coord>)> = chains.collect();
                snap_in(&mut chains, eps, frame)?;
                Topology::from_gathered(chains, room, nodes)?
            }
        };
        Ok(Coverage {
            shapes,
            topology: topology.with_polygons(polygons),
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
    pub fn new(geometries: impl IntoIterator<Item = Geometry<f64>>) -> Result<Self, Error> {
        Coverage::builder(geometries).build()
    }

    /// A coverage of `geometries` with options by name:
    /// `Coverage::builder(gs).snap(1e-6).build()`.
    pub fn builder<G: IntoIterator<Item = Geometry<f64>>>(
        geometries: G,
    ) -> CoverageBuilder<G::IntoIter> {
        CoverageBuilder {
            geometries: geometries.into_iter(),
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
        self.shapes.len()
    }

    /// Whether the coverage holds no geometry.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
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
        let mut chains: Vec<bool> = Vec::new();
        if !exact.is_empty() {
            each_origin(&self.shapes, &mut |o| {
                chains.push(exact.get(o.geometry).copied().unwrap_or(false));
            });
        }
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
        self.shapes.iter().map(|g| rebuild(&g, &mut take)).collect()
    }

    /// As [`Coverage::assemble`], letting go of the coverage on the way: its
    /// own arcs before the geometries are put together, each shape's points
    /// once they are used. For the last step of smoothing a large
    /// coverage, whose peak then holds the smoothed arcs and geometries but
    /// no longer the input's positions.
    ///
    /// # Panics
    ///
    /// When `arcs` has fewer arcs than the topology.
    #[must_use]
    pub fn into_geometries(self, arcs: &Arcs) -> Vec<Geometry<f64>> {
        let Coverage { shapes, topology } = self;
        // The chains are held together (5 bytes each beyond their arc
        // references), let go of once every geometry is put together.
        let chains = topology.into_chains();
        let mut chains = chains.iter();
        let mut take = || {
            chains
                .next()
                .map_or_else(Vec::new, |c| crate::topology::chain_coords(c, arcs))
        };
        shapes.iter().map(|g| rebuild(&g, &mut take)).collect()
    }

    /// The geometries put together from `arcs` one at a time when asked
    /// for ([`Assembled::get`] gives what [`Coverage::assemble`] gives),
    /// the coverage's own positions let go of: for writing a large
    /// coverage's smoothed geometries without holding them all at once.
    ///
    /// # Panics
    ///
    /// When `arcs` has fewer arcs than the topology.
    #[must_use]
    pub fn into_assembled(self, arcs: Arcs) -> Assembled {
        let Coverage { shapes, topology } = self;
        assert!(
            arcs.len() >= topology.arcs().len(),
            "{} arcs for a topology of {}",
            arcs.len(),
            topology.arcs().len()
        );
        Assembled::new(shapes, topology.into_chains(), arcs)
    }

    /// Where an error's chain (or, for an arc's error, the first chain that
    /// uses the arc) comes from.
    #[must_use]
    pub fn locate(&self, e: &Error) -> Option<Location> {
        let chain = self.topology.chain_of(e)?;
        // Walked again from the shapes: only an error needs it.
        let mut o = None;
        let mut i = 0;
        each_origin(&self.shapes, &mut |found| {
            if i == chain {
                o = Some(found);
            }
            i += 1;
        });
        let o = o?;
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
    let mut polygons = Ragged::new();
    let mut chains = Vec::new();
    for g in geometries {
        let got = take_chains(&mut g.clone(), chains.len(), &mut polygons);
        chains.extend(got);
    }
    chains
}

/// The chains of `g`, which are chains `first..` of the coverage, with a
/// row of `polygons` added for each of its polygons. The positions of every
/// line and ring are moved into the chains, not copied: `g` is left with
/// its lines and rings without positions, for [`Shape::of`].
fn take_chains(
    g: &mut Geometry<f64>,
    first: usize,
    polygons: &mut Ragged<usize>,
) -> Vec<(ChainKind, Vec<Coord>)> {
    let mut chains: Vec<(ChainKind, Vec<Coord>)> = Vec::new();
    visit(g, &mut |part| match part {
        Part::Line(coords) => chains.push((ChainKind::Line, coords)),
        Part::Polygon(rings) => {
            let at = first + chains.len();
            chains.extend(rings.into_iter().map(|r| (ChainKind::Ring, r)));
            polygons.push_row(at..first + chains.len());
        }
    });
    chains
}

/// Calls `f` with where each chain comes from, in the order [`take_chains`]
/// takes them out, from the geometries' shapes.
fn each_origin(shapes: &Shapes, f: &mut dyn FnMut(Origin)) {
    for (gi, g) in shapes.iter().enumerate() {
        let mut member = 0;
        parts(&g, &mut |rings| {
            match rings {
                None => f(Origin {
                    geometry: gi,
                    member,
                    ring: 0,
                    polygon: false,
                }),
                Some(n) => (0..n).for_each(|ring| {
                    f(Origin {
                        geometry: gi,
                        member,
                        ring,
                        polygon: true,
                    });
                }),
            }
            member += 1;
        });
    }
}

/// Calls `f` on every line (`None`) and polygon (`Some` of its count of
/// rings) of `s`, in the order [`visit`] meets them in its geometry.
fn parts(s: &Shape, f: &mut dyn FnMut(Option<usize>)) {
    match s {
        Shape::Kept(_) => {}
        Shape::Line(_) | Shape::LineString => f(None),
        Shape::MultiLineString(n) => (0..*n).for_each(|_| f(None)),
        Shape::Polygon(rings) => f(Some(*rings)),
        Shape::MultiPolygon(rings) => rings.iter().for_each(|&r| f(Some(r))),
        Shape::Collection(c) => c.iter().for_each(|s| parts(s, f)),
    }
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

/// The geometry of shape `s` with each line and ring, in the order
/// [`visit`] met them, from `take`.
/// How many lines and rings of the coverage's chains shape `s` takes.
pub(crate) fn chains_in(s: &Shape) -> usize {
    match s {
        Shape::Kept(_) => 0,
        Shape::Line(_) | Shape::LineString => 1,
        Shape::MultiLineString(n) | Shape::Polygon(n) => *n,
        Shape::MultiPolygon(rings) => rings.iter().sum(),
        Shape::Collection(c) => c.iter().map(chains_in).sum(),
    }
}

/// The name of the `Geometry` variant [`rebuild`] makes of `s`.
pub(crate) fn kind_of(s: &Shape) -> &'static str {
    match s {
        Shape::Kept(g) => match **g {
            Geometry::Point(_) => "Point",
            Geometry::MultiPoint(_) => "MultiPoint",
            // Only points are kept as they are.
            _ => "GeometryCollection",
        },
        Shape::Line(_) => "Line",
        Shape::LineString => "LineString",
        Shape::MultiLineString(_) => "MultiLineString",
        Shape::Polygon(_) => "Polygon",
        Shape::MultiPolygon(_) => "MultiPolygon",
        Shape::Collection(_) => "GeometryCollection",
    }
}

pub(crate) fn rebuild(s: &Shape, take: &mut dyn FnMut() -> Vec<Coord>) -> Geometry<f64> {
    let polygon = |rings: usize, take: &mut dyn FnMut() -> Vec<Coord>| {
        let shell = LineString(take());
        let holes = (1..rings).map(|_| LineString(take())).collect();
        Polygon::new(shell, holes)
    };
    match s {
        Shape::Kept(g) => (**g).clone(),
        Shape::Line(l) => {
            let c = take();
            Geometry::Line(Line::new(
                c.first().copied().unwrap_or(l.start),
                c.last().copied().unwrap_or(l.end),
            ))
        }
        Shape::LineString => Geometry::LineString(LineString(take())),
        Shape::MultiLineString(n) => Geometry::MultiLineString(MultiLineString(
            (0..*n).map(|_| LineString(take())).collect(),
        )),
        Shape::Polygon(rings) => Geometry::Polygon(polygon(*rings, take)),
        Shape::MultiPolygon(rings) => Geometry::MultiPolygon(MultiPolygon(
            rings.iter().map(|&r| polygon(r, take)).collect(),
        )),
        Shape::Collection(c) => Geometry::GeometryCollection(GeometryCollection(
            c.iter().map(|s| rebuild(s, take)).collect(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo_types::{coord, MultiPoint, Point, Rect, Triangle};

    /// A ring or line whose every x is `code` or `code + 0.5`.
    fn coded(code: f64, ring: bool) -> LineString<f64> {
        let mut c = vec![
            coord! { x: code, y: 0.0 },
            coord! { x: code + 0.5, y: 0.0 },
            coord! { x: code + 0.5, y: 1.0 },
        ];
        if ring {
            c.push(c[0]);
        }
        LineString(c)
    }

    fn polygon(gi: usize, member: usize, holes: usize) -> Polygon<f64> {
        let code = |r: usize| (gi * 1000 + member * 10 + r) as f64;
        Polygon::new(
            coded(code(0), true),
            (1..=holes).map(|r| coded(code(r), true)).collect(),
        )
    }

    /// Every kind of geometry, nested, with each line and ring's positions
    /// telling where it is: x is `1000 geometry + 10 member + ring`.
    fn geometries() -> Vec<Geometry<f64>> {
        let code = |gi: usize, member: usize| (gi * 1000 + member * 10) as f64;
        let box_at = |x: f64| Rect::new(coord! { x: x, y: 0.0 }, coord! { x: x + 0.5, y: 1.0 });
        let tri_at = |x: f64| {
            Triangle::new(
                coord! { x: x, y: 0.0 },
                coord! { x: x + 0.5, y: 0.0 },
                coord! { x: x, y: 1.0 },
            )
        };
        vec![
            Geometry::Point(Point::new(-1.0, -1.0)),
            Geometry::Polygon(polygon(1, 0, 2)),
            Geometry::LineString(coded(code(2, 0), false)),
            Geometry::MultiPolygon(MultiPolygon(vec![polygon(3, 0, 0), polygon(3, 1, 3)])),
            Geometry::MultiPoint(MultiPoint(vec![Point::new(-2.0, -2.0)])),
            Geometry::MultiLineString(MultiLineString(vec![
                coded(code(5, 0), false),
                coded(code(5, 1), false),
            ])),
            Geometry::Rect(box_at(code(6, 0))),
            Geometry::Triangle(tri_at(code(7, 0))),
            Geometry::Line(Line::new(
                coord! { x: code(8, 0), y: 0.0 },
                coord! { x: code(8, 0) + 0.5, y: 1.0 },
            )),
            Geometry::GeometryCollection(GeometryCollection(vec![
                Geometry::Polygon(polygon(9, 0, 1)),
                Geometry::Point(Point::new(-3.0, -3.0)),
                Geometry::GeometryCollection(GeometryCollection(vec![
                    Geometry::LineString(coded(code(9, 1), false)),
                    Geometry::MultiPolygon(MultiPolygon(vec![polygon(9, 2, 0), polygon(9, 3, 1)])),
                ])),
                Geometry::Rect(box_at(code(9, 4))),
            ])),
        ]
    }

    #[test]
    fn origins_walked_from_the_shapes_name_each_chain_taken_out() {
        let mut taken = geometries();
        let mut chains = Vec::new();
        for g in &mut taken {
            let got = take_chains(g, chains.len(), &mut Ragged::new());
            chains.extend(got);
        }
        let mut shapes = Shapes::with_capacity(0);
        taken.iter().for_each(|g| shapes.push(Shape::of(g)));
        let mut origins = Vec::new();
        each_origin(&shapes, &mut |o| origins.push(o));
        assert_eq!(origins.len(), chains.len());
        for (o, (kind, coords)) in origins.iter().zip(&chains) {
            assert_eq!(o.polygon, *kind == ChainKind::Ring);
            let code = (o.geometry * 1000 + o.member * 10 + o.ring) as f64;
            assert!(
                coords.iter().all(|c| c.x == code || c.x == code + 0.5),
                "{o:?}: {coords:?}"
            );
        }
        // Put back together from the positions taken out, each geometry is
        // the one given, a Rect or Triangle as its Polygon.
        let coverage = Coverage::new(geometries()).unwrap();
        assert_eq!(coverage.topology().chains().len(), chains.len());
        let mut next = chains.iter();
        let back: Vec<Geometry<f64>> = shapes
            .iter()
            .map(|s| rebuild(&s, &mut || next.next().unwrap().1.clone()))
            .collect();
        assert!(next.next().is_none());
        let as_polygon = |g: Geometry<f64>| match g {
            Geometry::Rect(r) => Geometry::Polygon(r.to_polygon()),
            Geometry::Triangle(t) => Geometry::Polygon(t.to_polygon()),
            Geometry::GeometryCollection(c) => Geometry::GeometryCollection(GeometryCollection(
                c.0.into_iter()
                    .map(|g| match g {
                        Geometry::Rect(r) => Geometry::Polygon(r.to_polygon()),
                        g => g,
                    })
                    .collect(),
            )),
            g => g,
        };
        let given: Vec<Geometry<f64>> = geometries().into_iter().map(as_polygon).collect();
        assert_eq!(back, given);
        // Assembled with the coverage let go of on the way, the same.
        let arcs = coverage.topology().arcs().clone();
        let kept = coverage.assemble(&arcs);
        assert_eq!(kept.len(), given.len());
        let assembled = coverage.clone().into_assembled(arcs.clone());
        assert_eq!(assembled.len(), kept.len());
        assert_eq!(assembled.iter().collect::<Vec<_>>(), kept);
        assert_eq!(assembled.get(kept.len() - 1), kept[kept.len() - 1]);
        let variant = |g: &Geometry<f64>| match g {
            Geometry::Point(_) => "Point",
            Geometry::Line(_) => "Line",
            Geometry::LineString(_) => "LineString",
            Geometry::Polygon(_) => "Polygon",
            Geometry::MultiPoint(_) => "MultiPoint",
            Geometry::MultiLineString(_) => "MultiLineString",
            Geometry::MultiPolygon(_) => "MultiPolygon",
            Geometry::GeometryCollection(_) => "GeometryCollection",
            Geometry::Rect(_) => "Rect",
            Geometry::Triangle(_) => "Triangle",
        };
        for (i, g) in kept.iter().enumerate() {
            assert_eq!(assembled.kind(i), variant(g), "{i}");
        }
        assert_eq!(coverage.into_geometries(&arcs), kept);
    }
}
