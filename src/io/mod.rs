//! Reading point files and writing results (needs `std`).
//!
//! Owns: the text formats (where the bytes go is the caller's choice: the binary writes files
//! all or nothing). It may not compute geometry; it only moves numbers in and out.
//!
//! Point files hold one point per line, `x y`, separated by spaces, tabs or a comma; a third
//! column is ignored; `#` starts a comment; blank lines are skipped; LF, CRLF and CR-only line
//! ends are all accepted.

mod geojson;
mod svg;
mod text;

pub use geojson::write_geojson;
pub use svg::write_svg;
pub use text::{write_edges, write_polylines};

use crate::geometry::Point;
use std::fmt;
use std::fs;
use std::io::{self, Read};

/// A problem reading or writing a file, with the file's name and, for bad content, the line.
///
/// ```
/// use condt::io::{parse_points, IoErrorKind};
/// let err = parse_points("1 2\n3 x\n", "pts.txt").unwrap_err();
/// assert_eq!(err.to_string(), "pts.txt:2: cannot read \"x\" as a number");
/// assert_eq!(err.line, Some(2));
/// assert!(matches!(err.kind, IoErrorKind::Content(_)));
///
/// let err = condt::io::read_points("no/such/file.txt").unwrap_err();
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
#[derive(Debug)]
#[non_exhaustive]
pub enum IoErrorKind {
    /// The operating system refused a read or write; kept whole, and the error's
    /// [`source`](std::error::Error::source).
    Io(io::Error),
    /// The content is not a valid point file; the message says why.
    Content(String),
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

fn io_error(file: &str, err: io::Error) -> IoError {
    IoError {
        file: file.to_string(),
        line: None,
        kind: IoErrorKind::Io(err),
    }
}

/// Splits text into lines at LF, CRLF or a lone CR, numbering them from 1.
fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut rest = text;
    let mut number = 0;
    core::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        number += 1;
        let end = rest.find(['\n', '\r']).unwrap_or(rest.len());
        let line = &rest[..end];
        let skip = match rest.as_bytes().get(end) {
            Some(b'\r') if rest.as_bytes().get(end + 1) == Some(&b'\n') => 2,
            Some(_) => 1,
            None => 0,
        };
        rest = &rest[end + skip..];
        Some((number, line))
    })
}

/// Parses point-file text; `file` names the source in error messages.
///
/// ```
/// use condt::{io::parse_points, Point};
/// let pts = parse_points("# x y\n1 2\r\n3,4,9\r\t5\t6 \r", "example")?;
/// assert_eq!(pts, vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0), Point::new(5.0, 6.0)]);
/// # Ok::<(), condt::io::IoError>(())
/// ```
pub fn parse_points(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let mut points = Vec::new();
    for (number, raw) in numbered_lines(text) {
        let content = raw.split('#').next().unwrap_or("");
        let mut fields = content
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty());
        let bad = |message: String| IoError {
            file: file.to_string(),
            line: Some(number),
            kind: IoErrorKind::Content(message),
        };
        let Some(first) = fields.next() else { continue };
        let Some(second) = fields.next() else {
            return Err(bad("expected two coordinates, found one".to_string()));
        };
        let _ignored_third = fields.next();
        if fields.next().is_some() {
            return Err(bad("expected two or three columns, found more".to_string()));
        }
        let parse = |field: &str| -> Result<f64, IoError> {
            let value: f64 = field
                .parse()
                .map_err(|_| bad(format!("cannot read {field:?} as a number")))?;
            if value.is_finite() {
                Ok(value)
            } else {
                Err(bad(format!("coordinate {field:?} is not finite")))
            }
        };
        points.push(Point::new(parse(first)?, parse(second)?));
    }
    Ok(points)
}

/// Reads a point file; `-` reads standard input.
///
/// ```no_run
/// let points = condt::io::read_points("examples/data/shapes.txt")?;
/// # Ok::<(), condt::io::IoError>(())
/// ```
pub fn read_points(path: &str) -> Result<Vec<Point>, IoError> {
    let (name, bytes) = if path == "-" {
        let mut bytes = Vec::new();
        io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| io_error("<stdin>", e))?;
        ("<stdin>", bytes)
    } else {
        (path, fs::read(path).map_err(|e| io_error(path, e))?)
    };
    let text = String::from_utf8(bytes).map_err(|e| {
        let line = 1 + e.as_bytes()[..e.utf8_error().valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        IoError {
            file: name.to_string(),
            line: Some(line),
            kind: IoErrorKind::Content("not UTF-8 text".to_string()),
        }
    })?;
    parse_points(&text, name)
}
