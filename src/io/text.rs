//! Plain-text results: edge lists and polylines.

use crate::reconstruct::Reconstruction;
use std::io::{self, Write};

/// One edge `i j` per line, `i < j`, sorted, in input indices.
///
/// ```
/// use condt::{reconstruct, Params};
/// use condt::Point;
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut out = Vec::new();
/// condt::io::write_edges(&mut out, &r)?;
/// assert_eq!(String::from_utf8(out)?, "0 1\n0 2\n1 2\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_edges(out: &mut dyn Write, result: &Reconstruction) -> io::Result<()> {
    for [a, b] in result.edges() {
        writeln!(out, "{a} {b}")?;
    }
    Ok(())
}

/// One curve per line: `closed` or `open`, then its input indices in order.
///
/// ```
/// use condt::{reconstruct, Params};
/// use condt::Point;
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut out = Vec::new();
/// condt::io::write_polylines(&mut out, &r)?;
/// assert_eq!(String::from_utf8(out)?, "closed 0 1 2\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_polylines(out: &mut dyn Write, result: &Reconstruction) -> io::Result<()> {
    for curve in result.curves() {
        write!(out, "{}", if curve.is_closed() { "closed" } else { "open" })?;
        for i in curve.points() {
            write!(out, " {i}")?;
        }
        writeln!(out)?;
    }
    Ok(())
}
