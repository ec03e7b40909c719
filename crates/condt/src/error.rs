//! Every way a call can refuse its input; it may use no module but the mesh's [`Violation`].

use crate::mesh::Violation;
use core::fmt;

/// Why a call into the library refused its input.
///
/// ```
/// use condt::{triangulate, Error, Params, Point, Uniformity};
/// let err = triangulate(&[Point::new(0.0, 0.0), Point::new(f64::NAN, 1.0)]).unwrap_err();
/// assert_eq!(err, Error::NonFinite { index: 1 });
/// assert_eq!(err.to_string(), "point 1 has a NaN or infinite coordinate");
/// let err = Params::default().with_uniformity(Uniformity::Fixed(-1.0)).check().unwrap_err();
/// assert_eq!(err, Error::InvalidParameter { name: "u", value: -1.0 });
/// let words = "parameter u = -1 is not accepted (u is a finite number greater than 0)";
/// assert_eq!(err.to_string(), words);
/// // An error in every build, `std` or not.
/// let boxed: Box<dyn core::error::Error> = Box::new(err);
/// assert!(boxed.source().is_none());
/// // A broken mesh is told once: in the message, not again as a source.
/// use condt::mesh::{Element, Rule, TriangleId, Violation};
/// let broken = Violation { rule: Rule::TriangleNotCcw, element: Element::Triangle(TriangleId::new(3)) };
/// let boxed: Box<dyn core::error::Error> = Box::new(Error::InvalidTriangulation(broken));
/// assert_eq!(boxed.to_string(), broken.to_string());
/// assert!(boxed.source().is_none());
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// The point at input position `index` has a NaN or infinite coordinate.
    NonFinite {
        /// Input position of the offending point.
        index: usize,
    },
    /// More points than the 32-bit mesh indices can address.
    TooManyPoints {
        /// Number of points given.
        count: usize,
        /// The largest number accepted.
        limit: usize,
    },
    /// A parameter is NaN, infinite or out of range (see [`Params`](crate::Params)).
    InvalidParameter {
        /// The parameter's name as the library spells it: the field or argument (`u`, `k`,
        /// `distance`); the command line names its own option (`--u`, `--iqr`, `--snap`).
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// Two points too close together for the reconstruction's stages to measure beside the set's
    /// largest coordinate: nearer than 2^-450 (about 3.4e-136) times its magnitude, where squared
    /// lengths and their products leave the range of a double (`docs/predicates.md`, *Lengths
    /// for the ConDT stages*). Only the reconstruction refuses such a set;
    /// [`triangulate`](crate::triangulate()) takes any spread.
    TooCloseToMeasure {
        /// Input position of one of two such points, joined by a Delaunay edge (the smaller;
        /// of several such pairs, the first by positions).
        first: usize,
        /// Input position of the other.
        second: usize,
        /// Input position of a point with the largest coordinate magnitude (the first such),
        /// which sets the scale the two are measured against: often a single stray point far
        /// from the rest.
        largest: usize,
    },
    /// [`Triangulation::validate`](crate::Triangulation::validate) or
    /// [`Mesh::check_topology`](crate::mesh::Mesh::check_topology) found a broken invariant.
    InvalidTriangulation(Violation),
}

impl Error {
    /// [`Error::InvalidParameter`] named `name`, with `value`.
    pub(crate) fn invalid(name: &'static str, value: f64) -> Error {
        Error::InvalidParameter { name, value }
    }
}

impl From<Violation> for Error {
    fn from(violation: Violation) -> Self {
        Error::InvalidTriangulation(violation)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFinite { index } => {
                write!(f, "point {index} has a NaN or infinite coordinate")
            }
            Error::TooManyPoints { count, limit } => {
                write!(f, "{count} points given, at most {limit} are supported")
            }
            Error::InvalidParameter { name, value } => {
                write!(f, "parameter {name} = {value} is not accepted")?;
                // The ranges of the two a caller sets (`Params::check`'s rules), and what the
                // value of each list's refusal is.
                match name {
                    "u" => write!(f, " (u is a finite number greater than 0)"),
                    "k" => write!(f, " (k is a finite number, 0 or more)"),
                    "order" => write!(
                        f,
                        " (an insertion order lists each position of the points once; the value \
                         is the first entry that repeats one or is past them, or the order's \
                         length where that is not the number of points)"
                    ),
                    "edge" => write!(
                        f,
                        " (an edge joins two different points of the set, and a graph lists \
                         it once; the value is its larger end, past the points, the point of a \
                         loop, or the larger end of an edge listed twice)"
                    ),
                    "candidate" => write!(
                        f,
                        " (the value is a position past the points, or the larger end of a join \
                         that is a loop, named twice or already an edge)"
                    ),
                    "choice" => write!(
                        f,
                        " (the value is a position past the points, a loose end given two rows, \
                         or the larger end of a join that is a loop, named twice or already an \
                         edge)"
                    ),
                    "labels" | "status" | "tests" => write!(
                        f,
                        " (one entry per point is needed; the value is the list's length)"
                    ),
                    "n" => write!(f, " (more points than a curve graph holds)"),
                    "distance" => write!(f, " (a snapping distance is finite, 0 or more)"),
                    _ => Ok(()),
                }
            }
            Error::TooCloseToMeasure {
                first,
                second,
                largest,
            } => write!(
                f,
                "points {first} and {second} are closer than 2^-450 times the largest coordinate \
                 (point {largest}'s): the reconstruction cannot measure lengths across that \
                 spread (the triangulation can)"
            ),
            Error::InvalidTriangulation(violation) => write!(f, "{violation}"),
        }
    }
}

// `core::error::Error` (Rust 1.81, under the crate's 1.86): an embedded caller without `std`
// can box the error or send it on with `?` as well. No `source`: the one error with a cause,
// `InvalidTriangulation`, says it in its own message (a reporter printing the chain showed
// the violation twice; an embedded review), and the variant holds it for a caller to match.
impl core::error::Error for Error {}
