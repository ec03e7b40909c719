//! Plain-text results: triangles, edge lists and polylines, one item per line.
//!
//! Owns the decimal formatting of indices: a line is built in a buffer by hand (no `fmt`
//! machinery per number) and the buffer goes to the writer in large blocks, so the output is
//! streamed in constant memory whatever its size.

use crate::reconstruct::Reconstruction;
use crate::triangulate::Triangulation;
use std::io::{self, Write};
use std::vec::Vec;

/// Bytes gathered before they go to the writer.
const BLOCK: usize = 1 << 16;

/// "00", "01", … "99": the decimal digits of every number below 100.
const PAIRS: [u8; 200] = {
    let mut pairs = [0u8; 200];
    let mut n = 0;
    while n < 100 {
        pairs[2 * n] = b'0' + (n / 10) as u8;
        pairs[2 * n + 1] = b'0' + (n % 10) as u8;
        n += 1;
    }
    pairs
};

/// Lines of indices built in a block and handed to `out` when the block is full.
struct Lines<'a> {
    out: &'a mut dyn Write,
    block: Vec<u8>,
}

impl<'a> Lines<'a> {
    fn new(out: &'a mut dyn Write) -> Lines<'a> {
        Lines {
            out,
            block: Vec::with_capacity(BLOCK + 64),
        }
    }

    /// Appends the decimal digits of `value`. They are written two at a time from the right
    /// into the first half of a 40-byte scratch array, and the 20 bytes from the first digit
    /// on are appended as one fixed-size copy, then cut to the digit count: no digit count up
    /// front, no call per number. Indices below 2^32 (all of them in practice) are divided in
    /// 32-bit arithmetic, which multiplies instead of dividing in fewer instructions.
    #[inline]
    fn number(&mut self, value: usize) {
        const END: usize = 20;
        let mut scratch = [0u8; 2 * END];
        let mut at = END;
        let mut put_pair = |at: &mut usize, pair: usize| {
            *at -= 2;
            scratch[*at] = PAIRS[2 * pair];
            scratch[*at + 1] = PAIRS[2 * pair + 1];
        };
        let mut rest = value;
        if let Ok(mut small) = u32::try_from(value) {
            while small >= 100 {
                put_pair(&mut at, (small % 100) as usize);
                small /= 100;
            }
            rest = small as usize;
        } else {
            while rest >= 100 {
                put_pair(&mut at, rest % 100);
                rest /= 100;
            }
        }
        if rest >= 10 {
            put_pair(&mut at, rest);
        } else {
            at -= 1;
            scratch[at] = b'0' + rest as u8;
        }
        let start = self.block.len();
        let digits: &[u8; END] = scratch[at..at + END]
            .try_into()
            .expect("20 digits from a position below 20");
        self.block.extend_from_slice(digits);
        self.block.truncate(start + END - at);
    }

    #[inline]
    fn text(&mut self, text: &[u8]) {
        self.block.extend_from_slice(text);
    }

    /// Ends a line, handing the block on when it is full.
    #[inline]
    fn end(&mut self) -> io::Result<()> {
        self.block.push(b'\n');
        if self.block.len() >= BLOCK {
            self.out.write_all(&self.block)?;
            self.block.clear();
        }
        Ok(())
    }

    /// One line of indices separated by spaces.
    #[inline]
    fn line(&mut self, indices: &[usize]) -> io::Result<()> {
        for (k, &i) in indices.iter().enumerate() {
            if k > 0 {
                self.block.push(b' ');
            }
            self.number(i);
        }
        self.end()
    }

    fn finish(mut self) -> io::Result<()> {
        self.out.write_all(&self.block)?;
        self.block.clear();
        Ok(())
    }
}

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
    let mut lines = Lines::new(out);
    for edge in result.edges() {
        lines.line(&edge)?;
    }
    lines.finish()
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
    let mut lines = Lines::new(out);
    for curve in result.curves() {
        lines.text(if curve.is_closed() {
            b"closed"
        } else {
            b"open"
        });
        for i in curve.points() {
            lines.text(b" ");
            lines.number(i);
        }
        lines.end()?;
    }
    lines.finish()
}

/// One triangle `i j k` per line, counter-clockwise, in input indices, in the order of
/// [`Triangulation::triangles`].
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(Point::from))?;
/// let mut out = Vec::new();
/// condt::io::write_triangles(&mut out, &tri)?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(text.lines().count(), 1);
/// let mut corners: Vec<&str> = text.split_whitespace().collect();
/// corners.sort();
/// assert_eq!(corners, ["0", "1", "2"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_triangles(out: &mut dyn Write, tri: &Triangulation) -> io::Result<()> {
    let mut lines = Lines::new(out);
    for triangle in tri.triangles() {
        lines.line(&triangle)?;
    }
    lines.finish()
}

/// The edges of a triangulation `[a, b]` (`a < b`, input indices) in sorted order, found point
/// by point from each point's neighbours instead of collecting and sorting all of them, so that
/// they take no memory beyond one point's neighbours. `visit` is called for each.
pub(crate) fn sorted_triangulation_edges<E>(
    tri: &Triangulation,
    mut visit: impl FnMut([usize; 2]) -> Result<(), E>,
) -> Result<(), E> {
    let mut larger: Vec<usize> = Vec::new();
    for a in tri.distinct_points() {
        larger.clear();
        larger.extend(tri.neighbors(a).filter(|&b| b > a));
        larger.sort_unstable();
        for &b in &larger {
            visit([a, b])?;
        }
    }
    Ok(())
}

/// One edge `i j` per line of a triangulation, `i < j`, sorted, in input indices: the set of
/// [`Triangulation::edges`]. Points all on one line have no triangle but do have these edges.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 0.0)].map(Point::from))?;
/// let mut out = Vec::new();
/// condt::io::write_triangulation_edges(&mut out, &tri)?;
/// assert_eq!(String::from_utf8(out)?, "0 1\n0 2\n1 2\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_triangulation_edges(out: &mut dyn Write, tri: &Triangulation) -> io::Result<()> {
    let mut lines = Lines::new(out);
    sorted_triangulation_edges(tri, |edge| lines.line(&edge))?;
    lines.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::test_rng::Xorshift;
    use crate::triangulate::triangulate;

    #[test]
    fn numbers_are_written_in_decimal() {
        let mut out = Vec::new();
        let mut lines = Lines::new(&mut out);
        let values = [
            0,
            7,
            10,
            99,
            100,
            12345,
            999_999_999,
            1_000_000_000,
            u32::MAX as usize,
            u32::MAX as usize + 1,
            10_000_000_000,
            usize::MAX,
        ];
        for value in values {
            lines.number(value);
            lines.end().unwrap();
        }
        lines.finish().unwrap();
        let expected: String = values.iter().map(|v| format!("{v}\n")).collect();
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }

    #[test]
    fn output_larger_than_a_block_arrives_whole() {
        let mut out = Vec::new();
        let mut lines = Lines::new(&mut out);
        let mut expected = String::new();
        for i in 0..50_000 {
            lines.line(&[i, i + 1, 3 * i]).unwrap();
            expected.push_str(&format!("{i} {} {}\n", i + 1, 3 * i));
        }
        lines.finish().unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }

    /// The point-by-point walk gives the triangulation's edges, sorted, for random, duplicated,
    /// collinear and tiny inputs.
    #[test]
    fn sorted_edges_are_the_triangulations_edges() {
        let mut rng = Xorshift::new(12);
        let mut inputs: Vec<Vec<Point>> = vec![
            (0..20)
                .map(|i| Point::new(f64::from(i), 2.0 * f64::from(i)))
                .collect(),
            vec![Point::new(1.0, 1.0); 4],
            vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)],
            (0..30)
                .map(|i| Point::new(f64::from(i % 5), f64::from(i / 5)))
                .collect(),
        ];
        for n in [3, 10, 500] {
            let mut points: Vec<Point> =
                (0..n).map(|_| Point::new(rng.unit(), rng.unit())).collect();
            points.extend_from_slice(&points.clone()[..n / 3]);
            inputs.push(points);
        }
        for points in inputs {
            let tri = triangulate(&points).unwrap();
            let mut expected: Vec<[usize; 2]> = tri.edges().collect();
            expected.sort_unstable();
            let mut walked = Vec::new();
            sorted_triangulation_edges(&tri, |e| -> Result<(), ()> {
                walked.push(e);
                Ok(())
            })
            .unwrap();
            assert_eq!(walked, expected, "{} points", points.len());
        }
    }
}
