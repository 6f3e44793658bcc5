//! The error type of coverage smoothing: every variant names the chain, arc,
//! polygon or option at fault.

use std::fmt;

/// Why a coverage could not be built or smoothed.
///
/// Chains, arcs and polygons are numbered from 0 in the order the
/// [`Topology`](crate::Topology) holds them; [`Coverage`](crate::Coverage)
/// turns chain numbers into geometries and rings ([`Coverage::describe`](crate::Coverage::describe)).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A coordinate is NaN or infinite (`chain` is the arc's index for
    /// [`Topology::from_arcs`](crate::Topology::from_arcs)).
    NonFinite {
        /// The chain (or arc).
        chain: usize,
        /// The position within it.
        position: usize,
    },
    /// A chain refers to an arc that does not exist.
    ArcIndex {
        /// The chain.
        chain: usize,
        /// The reference as TopoJSON writes it (`!k` is `-k - 1`).
        arc: i64,
        /// How many arcs there are.
        arcs: usize,
    },
    /// An arc has no positions.
    EmptyArc {
        /// The arc.
        arc: usize,
    },
    /// A polygon names a chain that does not exist or is not a ring.
    Polygon {
        /// The polygon.
        polygon: usize,
        /// The chain it names.
        chain: usize,
    },
    /// An option's value is out of range.
    InvalidOption {
        /// Which option (`alpha`, `tolerance`, `keep-angle`, `snap`).
        option: &'static str,
        /// What it must be (`must be a positive number`).
        rule: &'static str,
        /// The value given.
        value: f64,
    },
    /// The smoothed arc left the range of a double.
    Overflow {
        /// The arc.
        arc: usize,
    },
    /// Parts of a coverage still raised refinement levels after this many
    /// rounds together ([`crate::parts::Rounds`]).
    Rounds {
        /// The rounds run.
        rounds: usize,
    },
    /// The curve could not be built or flattened for this arc.
    Spline {
        /// The arc.
        arc: usize,
        /// What the spline said.
        source: bzspline::Error,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { chain, position } => {
                write!(
                    f,
                    "chain {chain}, position {position}: a coordinate is not a finite number"
                )
            }
            Error::ArcIndex { chain, arc, arcs } => write!(
                f,
                "chain {chain}: arc {arc} is out of range (there are {arcs} arcs)"
            ),
            Error::EmptyArc { arc } => write!(f, "arc {arc} has no positions"),
            Error::Polygon { polygon, chain } => {
                write!(f, "polygon {polygon}: chain {chain} is not a ring")
            }
            Error::InvalidOption {
                option,
                rule,
                value,
            } => write!(f, "invalid {option} ({rule}): {value}"),
            Error::Overflow { arc } => write!(f, "arc {arc}: the smoothed arc overflows a double"),
            Error::Rounds { rounds } => write!(
                f,
                "the parts still raised refinement levels after {rounds} rounds"
            ),
            Error::Spline { arc, source } => write!(f, "arc {arc}: {source}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Spline { source, .. } => Some(source),
            _ => None,
        }
    }
}
