//! # bzspline-geo
//!
//! Smoothing of whole coverages with the bzspline curve: polygons and lines
//! that share borders keep sharing them, bit for bit, and what was valid
//! stays valid.
//!
//! A coverage is stored as its [`Topology`]: arcs, the maximal runs of edges
//! used by the same lines and rings, found the way topojson-server finds them
//! (or taken from TopoJSON as they are). Each arc is smoothed **once**, as the
//! method's open curve from node to node (a ring without nodes as a closed
//! curve), flattened to a tolerance, and written into every ring and line
//! that uses it. Where a smoothed arc would cross, touch or overlap another
//! arc or itself, where a ring would turn over or a hole leave its shell, the
//! arcs involved are refined (control points inserted along their legs, which
//! draws the curve towards the original polyline) until nothing conflicts,
//! keeping an original edge only as the last resort (below).
//!
//! What is promised, for input whose arcs do not cross:
//!
//! - shared borders come out identical in every ring and line that uses them;
//! - nodes (where arcs meet, line ends) stay exactly where they are;
//! - no two output arcs cross, touch outside their nodes, or overlap, and no
//!   arc crosses itself; rings keep their winding; holes stay in their shells;
//! - every ring is closed and keeps at least three distinct positions.
//!
//! ```
//! use bzspline_geo::{Coverage, SmoothOptions};
//! use geo_types::{Geometry, polygon};
//!
//! // Two squares side by side: one shared border.
//! let left = polygon![(x: 0.0, y: 0.0), (x: 1.0, y: 0.0), (x: 1.0, y: 1.0), (x: 0.0, y: 1.0)];
//! let right = polygon![(x: 1.0, y: 0.0), (x: 2.0, y: 0.0), (x: 2.0, y: 1.0), (x: 1.0, y: 1.0)];
//! let cov = Coverage::new(vec![Geometry::Polygon(left), Geometry::Polygon(right)])?;
//! let (smoothed, stats) = cov.smooth(&SmoothOptions::default().tolerance(1e-3))?;
//! assert_eq!((stats.arcs, stats.shared_arcs), (3, 1));
//! assert_eq!(smoothed.len(), 2);
//! # Ok::<(), bzspline_geo::Error>(())
//! ```
//!
//! ## Arcs
//!
//! A coverage's lines and rings are cut into arcs, maximal runs of edges
//! used by the same lines and rings, so that a border two polygons share is
//! stored once.
//!
//! The arcs are found the way topojson-server finds them: a position is a
//! *junction* when it ends a line or when it is met with two different pairs
//! of neighbours (two runs of edges part or join there); every line and ring
//! is cut at its junctions, and runs with the same positions in the same or
//! the opposite order become one arc. A ring without junctions is one closed
//! arc (an island, a lake, a lone polygon), found again when another ring has
//! the same positions from any start and in either direction. Positions are
//! compared exactly, bit for bit ([`snap`] merges near ones first).
//!
//! ## Smoothing
//!
//! Every arc is smoothed once, as the method's curve through its positions
//! taken as control points, flattened to a tolerance, and then refined
//! where the result would cross, touch or overlap itself or another arc, or
//! where a ring would turn over or a hole leave its shell.
//!
//! An open arc is smoothed as an open curve, which starts and ends at the
//! arc's end positions (the nodes), so arcs still meet where they met. A
//! closed arc whose start is no node (an island, a lake) is smoothed as a
//! closed curve. Positions that must stay (nodes inside an arc, and with
//! [`SmoothOptions::keep_angle`] every sharper corner) cut an arc into
//! pieces, each smoothed on its own.
//!
//! Refinement: the curve of the method touches every leg of its control
//! polygon and lies close to it, so inserting control points along the legs
//! (each leg cut into `2^level` equal parts) draws the curve towards the
//! original polyline, which did not cross. Each conflict raises the level of
//! the legs of the two segments involved (and their neighbours); a leg past
//! [`MAX_LEVEL`] is kept as the original edge, the last resort. Conflicts
//! between two original edges were in the input and are left as they are.

mod arcs;
mod assembled;
mod chains;
mod coverage;
mod crossings;
mod error;
pub mod geodesy;
mod graph;
mod levels;
mod line;
mod nodes;
mod offsets;
mod options;
pub mod parts;
mod piece;
mod positions;
mod ragged;
mod shapes;
mod smooth;
mod smoothing;
mod topology;

pub use arcs::{Arcs, ArcsIter};
pub use assembled::Assembled;
pub use chains::{Chain, Chains, ChainsIter};
pub use coverage::{coverage_chains, Coverage, CoverageBuilder, Location};
pub use error::Error;
pub use line::smooth_line;
pub use nodes::Nodes;
pub use options::{
    check_keep_angle, check_snap, check_tolerance, default_tolerance_of, Frame, SmoothOptions,
    DEFAULT_TOLERANCE_FRACTION,
};
pub use ragged::Ragged;
pub use smooth::{Smoothed, Stats, MAX_LEVEL};
pub use smoothing::Smooth;
pub use topology::{snap, snap_in, ArcRef, ChainKind, Topology};
