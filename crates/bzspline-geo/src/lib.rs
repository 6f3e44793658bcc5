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
//! keeping an original edge only as the last resort ([`smooth`] module).
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

mod coverage;
mod crossings;
mod error;
mod graph;
pub mod levels;
pub mod line;
pub mod nodes;
pub mod parts;
pub mod smooth;
mod smoothing;
pub mod topology;

pub use coverage::{coverage_chains, Coverage, CoverageBuilder, Location};
pub use error::Error;
pub use levels::{arc_key, Levels};
pub use nodes::Nodes;
pub use smooth::{
    default_tolerance_of, SmoothOptions, Smoothed, Stats, DEFAULT_TOLERANCE_FRACTION, MAX_LEVEL,
};
pub use smoothing::Smooth;
pub use topology::{ArcRef, Chain, ChainKind, Topology};
