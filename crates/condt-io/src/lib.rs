//! # condt-io
//!
//! Reading point files and writing condt's results.
//!
//! Owns: the text formats (where the bytes go is the caller's choice: the binary writes files
//! all or nothing). It may not compute geometry; it only moves numbers in and out.
//!
//! Point files hold one point per line, `x y` ([`parse_points`] has the rules), or are Triangle
//! `.node` files ([`parse_node`]), NumPy `.npy` arrays of shape `(n, 2)` ([`parse_npy`]), CSV
//! with a header naming the columns or of two numeric columns without one ([`parse_csv`]) or
//! GeoJSON points ([`parse_geojson`]); [`read_points`] tells
//! them apart by the file name, [`read_points_with`] reads a file in the format its
//! [`ReadOptions`] state (standard input has no name). Results are written as text, one item per line, as `.npy` arrays
//! of indices ([`write_npy_edges`], [`write_npy_triangles`]), as GeoJSON ([`write_geojson`]), or
//! drawn (SVG, the HTML viewer); an
//! edge's story is told in a sentence ([`story_text`]). Edge arrays are read back by
//! [`parse_npy_edges`] (for `condt score`).

mod csv;
mod decimal;
mod degrees;
mod geojson;
mod geojson_points;
mod html;
mod input;
mod located;
mod npy;
mod pieces;
mod points;
mod story;
mod svg;
mod text;
#[cfg(test)]
extern crate alloc;
#[cfg(test)]
#[path = "../../condt/src/test_rng.rs"]
#[allow(dead_code)] // each crate uses part of the shared generator
mod test_rng;

/// The path `test_rng.rs` takes its point type from, as in `condt`.
#[cfg(test)]
mod geometry {
    pub use condt::Point;
}

pub use csv::parse_csv;
pub use degrees::Degrees;
pub use geojson::{crs_member, not_longitude_latitude, write_geojson, write_geojson_with_crs};
pub use geojson_points::{parse_geojson, parse_geojson_with_crs};
pub use html::write_html;
pub use input::{Column, Columns, InputFormat, PointFile, ReadOptions};
pub use located::point_lines;
pub use npy::{
    parse_npy, parse_npy_edges, parse_npy_index_rows, write_npy_edges, write_npy_points,
    write_npy_triangles, write_npy_triangulation_edges, NPY_MAGIC,
};
pub use points::{
    parse_node, parse_points, read_points, read_points_with, read_points_with_crs, text_lines,
    utf8_text,
};
pub use story::story_text;
pub use svg::{write_svg, write_svg_stages};
pub use text::{
    write_curves_csv, write_edges, write_polylines, write_triangles, write_triangulation_edges,
    write_unused,
};

use condt::Reconstruction;
use std::fmt;
use std::io;

/// Refuses `points` as the input of `result` when their count differs (an `InvalidInput`
/// error): the writers that draw curves on the input coordinates take them from the caller,
/// since the result keeps none ([`Reconstruction::stage_point`]).
fn check_input(result: &Reconstruction, points: &[condt::Point]) -> io::Result<()> {
    if points.len() == result.num_points() {
        return Ok(());
    }
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "{} points given as the input of a reconstruction of {}",
            points.len(),
            result.num_points()
        ),
    ))
}

/// A problem reading or writing a file, with the file's name and, for bad content, the line.
///
/// ```
/// use condt_io::{parse_points, IoErrorKind};
/// let err = parse_points("1 2\n3 x\n", "pts.txt").unwrap_err();
/// assert_eq!(err.to_string(), "pts.txt:2: cannot read \"x\" as a number");
/// assert_eq!(err.line, Some(2));
/// assert!(matches!(err.kind, IoErrorKind::Content(_)));
///
/// let err = condt_io::read_points("no/such/file.txt").unwrap_err();
/// let IoErrorKind::Io(cause) = &err.kind else { panic!("an I/O error") };
/// assert_eq!(cause.kind(), std::io::ErrorKind::NotFound);
/// assert!(std::error::Error::source(&err).is_some());
/// ```
#[derive(Debug)]
pub struct IoError {
    /// The file (`<stdin>`, `<stdout>` for the standard streams).
    pub file: String,
    /// The 1-based line of the problem, when it is about the content.
    pub line: Option<usize>,
    /// What went wrong.
    pub kind: IoErrorKind,
}

/// What went wrong in an [`IoError`].
///
/// ```
/// use condt_io::{parse_points, IoErrorKind};
/// let err = parse_points("1 2\n3\n", "pts.txt").unwrap_err();
/// // Non-exhaustive: a match needs an arm for the kinds added later.
/// let message = match &err.kind {
///     IoErrorKind::Content(message) => message.as_str(),
///     IoErrorKind::Io(cause) => panic!("not read: {cause}"),
///     _ => panic!("another kind"),
/// };
/// // The message alone: the file and the line are the error's.
/// assert_eq!(message, "expected two coordinates `x y`, found one");
/// assert_eq!(err.to_string(), format!("pts.txt:2: {message}"));
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub enum IoErrorKind {
    /// The operating system refused a read or write; kept whole, and the error's
    /// [`source`](std::error::Error::source).
    Io(io::Error),
    /// The content is not a valid point file; the message says why.
    Content(String),
}

impl IoError {
    /// The operating system's `err` on `file`, at no particular line.
    pub(crate) fn os(file: &str, err: io::Error) -> IoError {
        IoError {
            file: file.to_string(),
            line: None,
            kind: IoErrorKind::Io(err),
        }
    }
}

impl fmt::Display for IoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        match &self.kind {
            IoErrorKind::Io(err) => write!(f, ": {err}"),
            IoErrorKind::Content(message) => write!(f, ": {message}"),
        }
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            IoErrorKind::Io(err) => Some(err),
            IoErrorKind::Content(_) => None,
        }
    }
}
