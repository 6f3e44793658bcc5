//! The error type shared by every fallible operation of the crate.

use core::fmt;

/// Which input array a value came from, for error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Field {
    /// The knots `tau` (or curve parameters).
    Knot,
    /// The control values `F` of a function.
    Value,
    /// The shape parameters `alpha`, one per interval.
    Alpha,
    /// A coordinate of a control point of a curve.
    Coordinate,
    /// A query point given to an evaluator.
    Query,
    /// A tolerance or accuracy argument.
    Tolerance,
    /// The weights of a smoothing fit, one per point.
    Weight,
}

impl Field {
    /// The name used in messages (`knots`, `values`, ...).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Field::Knot => "knots",
            Field::Value => "values",
            Field::Alpha => "alphas",
            Field::Coordinate => "points",
            Field::Query => "queries",
            Field::Tolerance => "tolerance",
            Field::Weight => "weights",
        }
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Everything that can go wrong when building or evaluating a spline.
///
/// Indices are zero-based positions in the array the caller passed: knot `i` is
/// `knots[i]`, interval `i` runs from `knots[i]` to `knots[i + 1]` and has the
/// shape parameter `alphas[i]`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// Fewer control points than the construction needs.
    TooFewPoints {
        /// How many were given.
        found: usize,
        /// The least number accepted.
        min: usize,
    },
    /// Two arrays that must have matching lengths do not.
    LengthMismatch {
        /// The array whose length is wrong.
        field: Field,
        /// The length it must have.
        expected: usize,
        /// The length it has.
        found: usize,
    },
    /// A NaN or infinite number in the input.
    NonFinite {
        /// The array it is in.
        field: Field,
        /// Its position in that array.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// `knots[index]` is not greater than `knots[index - 1]`.
    NotIncreasing {
        /// Position of the knot that is out of order.
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The knot itself.
        value: f64,
    },
    /// Interval `interval` is too narrow relative to the whole span for the
    /// coefficients to keep any precision.
    IntervalTooSmall {
        /// The interval (between `knots[interval]` and `knots[interval + 1]`).
        interval: usize,
        /// Its width.
        width: f64,
        /// The width of the whole span.
        span: f64,
    },
    /// `knots[last] - knots[0]` is not a finite number.
    SpanOverflow {
        /// The first knot.
        first: f64,
        /// The last knot.
        last: f64,
    },
    /// A shape parameter outside the theorem's range `[1/3, 2/3]`.
    AlphaOutOfRange {
        /// The interval whose alpha it is.
        interval: usize,
        /// The offending value.
        value: f64,
    },
    /// Two consecutive control points of a curve coincide, so the leg between
    /// them has no direction and a chordal or centripetal parameter step is 0.
    RepeatedPoint {
        /// Position of the second of the two equal points.
        index: usize,
    },
    /// The last control point of a closed curve coincides with the first, so the
    /// closing leg has no direction.
    RepeatedClosingPoint {
        /// Position of the last point.
        last: usize,
    },
    /// A negative weight given to a smoothing fit.
    NegativeWeight {
        /// Its position in the weights.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A query lies outside the spline's domain and the extrapolation policy is
    /// [`Extrapolate::Error`](crate::Extrapolate::Error).
    OutOfDomain {
        /// The query.
        x: f64,
        /// Start of the domain.
        min: f64,
        /// End of the domain.
        max: f64,
    },
    /// A result is too large for a double (an integral over a huge span, a
    /// far extrapolation, a derivative on a very narrow interval).
    Overflow {
        /// What overflowed, in words.
        what: &'static str,
    },
    /// An argument that is not a control point (an order, a tolerance, a
    /// buffer length) is outside what the operation accepts.
    InvalidArgument {
        /// What was wrong, in words.
        what: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// Flattening to this tolerance would take more than
    /// [`MAX_FLATTEN_VERTICES`](crate::MAX_FLATTEN_VERTICES) vertices.
    TooManyVertices {
        /// The tolerance asked for.
        tolerance: f64,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::TooFewPoints { found, min } => {
                write!(f, "need at least {min} points, found {found}")
            }
            Error::LengthMismatch {
                field,
                expected,
                found,
            } => write!(f, "{field} has {found} entries, expected {expected}"),
            Error::NonFinite {
                field,
                index,
                value,
            } => write!(f, "{field}[{index}] = {value} is not a finite number"),
            Error::NotIncreasing {
                index,
                previous,
                value,
            } => write!(
                f,
                "knots must be strictly increasing: knots[{index}] = {value} does not exceed knots[{}] = {previous}",
                index - 1
            ),
            Error::IntervalTooSmall {
                interval,
                width,
                span,
            } => write!(
                f,
                "interval {interval} (knots[{interval}]..knots[{}]) has width {width:e}, too small relative to the span {span:e}",
                interval + 1
            ),
            Error::SpanOverflow { first, last } => write!(
                f,
                "the span from {first:e} to {last:e} overflows a double"
            ),
            Error::AlphaOutOfRange { interval, value } => write!(
                f,
                "alphas[{interval}] = {value} (interval knots[{interval}]..knots[{}]) is outside [1/3, 2/3]",
                interval + 1
            ),
            Error::RepeatedPoint { index } => write!(
                f,
                "points[{index}] repeats points[{}]: consecutive control points must differ",
                index - 1
            ),
            Error::RepeatedClosingPoint { last } => write!(
                f,
                "points[{last}] repeats points[0]: a closed curve closes by itself, do not repeat the first point"
            ),
            Error::NegativeWeight { index, value } => {
                write!(f, "weights[{index}] = {value} is negative: weights must be >= 0")
            }
            Error::OutOfDomain { x, min, max } => {
                write!(f, "x = {x} is outside the domain [{min}, {max}]")
            }
            Error::Overflow { what } => write!(f, "{what} overflows a double"),
            Error::InvalidArgument { what, value } => write!(f, "{what} (got {value})"),
            Error::TooManyVertices { tolerance } => write!(
                f,
                "the flattening tolerance is too small for the curve: more than {} vertices (tolerance {tolerance})",
                crate::MAX_FLATTEN_VERTICES
            ),
        }
    }
}

impl std::error::Error for Error {}

impl Error {
    /// The error of one query answered alone, as the error of query `index`
    /// of a batch: a non-finite query names its place in the batch.
    pub(crate) fn at_query(self, index: usize) -> Error {
        match self {
            Error::NonFinite { field, value, .. } => Error::NonFinite {
                field,
                index,
                value,
            },
            e => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_index_and_values() {
        let e = Error::NotIncreasing {
            index: 3,
            previous: 2.0,
            value: 2.0,
        };
        assert_eq!(
            e.to_string(),
            "knots must be strictly increasing: knots[3] = 2 does not exceed knots[2] = 2"
        );
        let e = Error::NonFinite {
            field: Field::Value,
            index: 4,
            value: f64::NAN,
        };
        assert_eq!(e.to_string(), "values[4] = NaN is not a finite number");
        let e = Error::AlphaOutOfRange {
            interval: 1,
            value: 0.7,
        };
        assert!(e.to_string().contains("alphas[1] = 0.7"), "{e}");
    }
}
