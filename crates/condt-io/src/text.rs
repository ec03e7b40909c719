//! Plain-text results: triangles, edge lists and polylines, one item per line.
//!
//! Owns the decimal formatting of indices: a line is built in a buffer by hand (no `fmt`
//! machinery per number) and the buffers go to the writer in large blocks, so the output is
//! streamed in bounded memory whatever its size (a few batches of pieces, see
//! [`write_pieces`]); a triangulation's sorted edge list also holds 8 bytes per edge while it
//! is written ([`sorted_edge_keys`] says why).

use super::pieces::{write_pieces, Cursor, ROOM};
use condt::Reconstruction;
use condt::Triangulation;
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

/// The most decimal digits an index can have (`usize::MAX` on 64 bits has 20).
const MAX_DIGITS: usize = 20;

/// The eight decimal digits of `value` (below 10^8, leading zeros included) as the bytes of
/// a `u64`, the most significant digit in the lowest byte, found without a loop or a branch:
/// the value is split into two 4-digit halves, one per 32-bit lane, each lane into two 2-digit
/// quarters, each quarter into two digits, every split a multiplication by a reciprocal and a
/// shift that act on all lanes at once (exact for these ranges: `x * 10486 >> 20` is `x / 100`
/// below 43,699, `x * 103 >> 10` is `x / 10` below 179, and no lane's product reaches the next).
#[inline(always)]
fn eight_digits(value: u32) -> u64 {
    debug_assert!(value < 100_000_000);
    let value = u64::from(value);
    let merged = (value / 10_000) | ((value % 10_000) << 32);
    let hundreds = ((merged * 10_486) >> 20) & 0x0000_007f_0000_007f;
    let merged = hundreds | ((merged - hundreds * 100) << 16);
    let tens = ((merged * 103) >> 10) & 0x000f_000f_000f_000f;
    tens | ((merged - tens * 10) << 8)
}

/// Writes the decimal digits of `value` at the start of `dst` (at least [`MAX_DIGITS`] bytes
/// long) and returns how many there are; bytes of `dst` after them may be overwritten too.
/// Below 10^8 (every index of a file of under a hundred million points) the digits come from
/// [`eight_digits`] as one 8-byte store, shifted past the leading zeros: about twenty
/// instructions and no branch to mispredict when the digit count changes from line to line.
#[inline(always)]
fn put_number(dst: &mut [u8], value: usize) -> usize {
    if let Some(small) = u32::try_from(value).ok().filter(|&v| v < 100_000_000) {
        let digits = eight_digits(small);
        let leading = ((digits.trailing_zeros() / 8) as usize).min(7);
        let ascii = (digits + 0x3030_3030_3030_3030) >> (8 * leading);
        dst[..8].copy_from_slice(&ascii.to_le_bytes());
        8 - leading
    } else {
        put_large_number(dst, value)
    }
}

/// [`put_number`] for values of 10^8 and more: the digits two at a time from the right.
#[cold]
fn put_large_number(dst: &mut [u8], value: usize) -> usize {
    let count = value.checked_ilog10().map_or(1, |log| log as usize + 1);
    let digits = &mut dst[..count];
    let mut end = count;
    let mut rest = value;
    while rest >= 100 {
        let pair = rest % 100;
        digits[end - 2] = PAIRS[2 * pair];
        digits[end - 1] = PAIRS[2 * pair + 1];
        end -= 2;
        rest /= 100;
    }
    if rest >= 10 {
        digits[end - 2] = PAIRS[2 * rest];
        digits[end - 1] = PAIRS[2 * rest + 1];
    } else {
        digits[end - 1] = b'0' + rest as u8;
    }
    count
}

/// Writes `indices` as one line (separated by spaces, ended by `\n`) at the start of `room`,
/// which holds three indices of [`MAX_DIGITS`] digits and their separators; returns its length.
#[inline]
fn put_line<const K: usize>(room: &mut [u8; ROOM], indices: [usize; K]) -> usize {
    const { assert!(K * (MAX_DIGITS + 1) <= ROOM) };
    let mut at = 0;
    for (k, i) in indices.into_iter().enumerate() {
        if k > 0 {
            room[at] = b' ';
            at += 1;
        }
        at += put_number(&mut room[at..], i);
    }
    room[at] = b'\n';
    at + 1
}

/// Triangles per piece of [`write_pieces`]: about 160 kB of text, small enough that the
/// batches in flight add about 2 MB to the peak memory (650 kB pieces added 8 MB), large
/// enough that a batch costs little to hand between threads.
const TRIANGLES_PER_PIECE: usize = 1 << 13;

/// Edges per piece of [`write_pieces`] (about 110 kB of text for a million points).
const EDGES_PER_PIECE: usize = 1 << 13;

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

    /// Appends the decimal digits of `value`: [`put_number`] into 20 bytes appended as one
    /// fixed-size copy, then cut to the digit count (no call per number, no growth check per
    /// digit).
    #[inline]
    fn number(&mut self, value: usize) {
        let start = self.block.len();
        self.block.extend_from_slice(&[0u8; MAX_DIGITS]);
        let used = put_number(&mut self.block[start..], value);
        self.block.truncate(start + used);
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
/// condt_io::write_edges(&mut out, &r)?;
/// assert_eq!(String::from_utf8(out)?, "0 1\n0 2\n1 2\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// With the `parallel` feature the lines are formatted in pieces on rayon's threads (the bytes
/// are the same).
pub fn write_edges(out: &mut dyn Write, result: &Reconstruction) -> io::Result<()> {
    let edges = result.edge_list();
    write_pieces(out, edges.len(), EDGES_PER_PIECE, &|range, buf| {
        let mut cursor = Cursor::new(buf);
        for &[a, b] in &edges[range] {
            let used = put_line(cursor.room(), [a as usize, b as usize]);
            cursor.advance(used);
        }
        cursor.finish()
    })
}

/// One curve per line: `closed` or `open`, then its input indices in order.
///
/// ```
/// use condt::{reconstruct, Params};
/// use condt::Point;
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut out = Vec::new();
/// condt_io::write_polylines(&mut out, &r)?;
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

/// The points left out, one input index per line, ascending ([`Reconstruction::unused`]: the
/// points with no edge in the result, the outliers; an exact duplicate of such a point is left
/// out with it).
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
/// pts.push(Point::new(10.0, 50.0));
/// let r = reconstruct(&pts, &Params::default())?;
/// let mut out = Vec::new();
/// condt_io::write_unused(&mut out, &r)?;
/// assert_eq!(String::from_utf8(out)?, "21\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_unused(out: &mut dyn Write, result: &Reconstruction) -> io::Result<()> {
    let mut lines = Lines::new(out);
    for &i in result.unused() {
        lines.number(i);
        lines.end()?;
    }
    lines.finish()
}

/// The curves' coordinates as CSV, for tools that index from 1 or plot lines from coordinates
/// (R, MATLAB, Octave, Julia, spreadsheets): a header `curve,closed,point,x,y`, then one row
/// per point of each curve, in the order of [`write_polylines`]'s lines and points: `curve` the
/// curve's number and `point` the point's input number, both from 0 as every output counts,
/// `closed` 1 or 0, and the input coordinates (shortest decimals that read back as the same
/// doubles). A closed curve's first point is written again at its end, as a ring is, so that a
/// line drawn through a curve's rows closes. Every field is a number: `csvread(FILE, 1, 0)`,
/// `read.csv` and `readdlm(FILE, ',', header = true)` read it as it is.
///
/// # Errors
/// `InvalidInput` when `input` is not the input of `result` (another number of points); the
/// writer's errors.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// let r = reconstruct(&square, &Params::paper())?;
/// let mut out = Vec::new();
/// condt_io::write_curves_csv(&mut out, &r, &square)?;
/// assert_eq!(
///     String::from_utf8(out)?,
///     "curve,closed,point,x,y\n0,1,0,0,0\n0,1,1,1,0\n0,1,2,1,1\n0,1,3,0,1\n0,1,0,0,0\n"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_curves_csv(
    out: &mut dyn Write,
    result: &Reconstruction,
    input: &[condt::Point],
) -> io::Result<()> {
    use crate::geojson::Coordinate;
    crate::check_input(result, input)?;
    let mut out = io::BufWriter::new(out);
    writeln!(out, "curve,closed,point,x,y")?;
    for (k, curve) in result.curves().iter().enumerate() {
        let closed = u8::from(curve.is_closed());
        let closing = curve.points().next().filter(|_| curve.is_closed());
        for i in curve.points().chain(closing) {
            let p = input[i];
            let (x, y) = (Coordinate(p.x), Coordinate(p.y));
            writeln!(out, "{k},{closed},{i},{x},{y}")?;
        }
    }
    out.flush()
}

/// One triangle `i j k` per line, counter-clockwise, in input indices, in the order of
/// [`Triangulation::triangles`].
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(Point::from))?;
/// let mut out = Vec::new();
/// condt_io::write_triangles(&mut out, &tri)?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(text.lines().count(), 1);
/// let mut corners: Vec<&str> = text.split_whitespace().collect();
/// corners.sort();
/// assert_eq!(corners, ["0", "1", "2"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// With the `parallel` feature the lines are formatted in pieces on rayon's threads (the bytes
/// are the same).
pub fn write_triangles(out: &mut dyn Write, tri: &Triangulation) -> io::Result<()> {
    let mesh = tri.mesh();
    // Pieces of triangle indices, ghosts included: the order of `Triangulation::triangles`.
    write_pieces(
        out,
        mesh.num_triangles_with_ghosts(),
        TRIANGLES_PER_PIECE,
        &|range, buf| {
            let mut cursor = Cursor::new(buf);
            for corners in mesh.triangle_corners(range) {
                if corners.iter().any(|v| v.is_infinite()) {
                    continue;
                }
                let used = put_line(cursor.room(), corners.map(|v| tri.input_of(v)));
                cursor.advance(used);
            }
            cursor.finish()
        },
    )
}

/// The edges `[a, b]` of a triangulation (`a < b`, input indices), sorted, each as the key
/// `a << 32 | b` (input positions are below [`MAX_POINTS`](condt::MAX_POINTS) < 2^32): read in
/// one pass over the half-edges in mesh order, then sorted (on rayon's threads with the
/// `parallel` feature). Walking the points in input order instead and sorting each one's
/// neighbours needs no memory beyond one point's ring, but the rings of consecutive input
/// positions lie anywhere in the mesh, so every step of the walk is a cache miss: 1.05 s for
/// the 3M edges of 1M uniform points, against about 0.1 s for this at 8 bytes per edge.
/// An `OutOfMemory` error when the keys do not fit.
pub(super) fn sorted_edge_keys(tri: &Triangulation) -> io::Result<Vec<u64>> {
    let mesh = tri.mesh();
    let mut keys: Vec<u64> = Vec::new();
    keys.try_reserve_exact(mesh.num_half_edges() / 2)
        .map_err(|_| io::Error::new(io::ErrorKind::OutOfMemory, "no memory for the edges"))?;
    keys.extend(tri.edges().map(|[a, b]| (a as u64) << 32 | b as u64));
    #[cfg(feature = "parallel")]
    if condt::parallel_available() {
        use rayon::slice::ParallelSliceMut;
        keys.par_sort_unstable();
        return Ok(keys);
    }
    keys.sort_unstable();
    Ok(keys)
}

/// The edge `[a, b]` of a key of [`sorted_edge_keys`].
#[inline]
pub(super) fn edge_of_key(key: u64) -> [usize; 2] {
    [(key >> 32) as usize, (key & u64::from(u32::MAX)) as usize]
}

/// One edge `i j` per line of a triangulation, `i < j`, sorted, in input indices: the set of
/// [`Triangulation::edges`]. Points all on one line have no triangle but do have these edges.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 0.0)].map(Point::from))?;
/// let mut out = Vec::new();
/// condt_io::write_triangulation_edges(&mut out, &tri)?;
/// assert_eq!(String::from_utf8(out)?, "0 1\n0 2\n1 2\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// With the `parallel` feature the lines are formatted in pieces of points on rayon's threads
/// (the bytes are the same).
pub fn write_triangulation_edges(out: &mut dyn Write, tri: &Triangulation) -> io::Result<()> {
    let keys = sorted_edge_keys(tri)?;
    write_pieces(out, keys.len(), EDGES_PER_PIECE, &|range, buf| {
        let mut cursor = Cursor::new(buf);
        for &key in &keys[range] {
            let used = put_line(cursor.room(), edge_of_key(key));
            cursor.advance(used);
        }
        cursor.finish()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pieces::on_rayon_and_one_thread;
    use crate::test_rng::Xorshift;
    use condt::triangulate;
    use condt::Point;

    #[test]
    fn numbers_are_written_in_decimal() {
        let mut out = Vec::new();
        let mut lines = Lines::new(&mut out);
        let mut values = vec![
            0,
            7,
            10,
            99,
            100,
            12345,
            99_999_999,
            100_000_000,
            999_999_999,
            1_000_000_000,
            u32::MAX as usize,
            u32::MAX as usize + 1,
            10_000_000_000,
            usize::MAX,
        ];
        // Every digit count, at its ends and in between, and random values of every size.
        let mut power = 1usize;
        while let Some(next) = power.checked_mul(10) {
            values.extend([power - 1, power, power + 1, next / 2, next - 1]);
            power = next;
        }
        let mut rng = crate::test_rng::Xorshift::new(77);
        for shift in 0..64 {
            values.extend((0..50).map(|_| (rng.below(u64::MAX) >> shift) as usize));
        }
        for &value in &values {
            lines.number(value);
            lines.end().unwrap();
        }
        lines.finish().unwrap();
        let expected: String = values.iter().map(|v| format!("{v}\n")).collect();
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }

    /// The eight digits against plain division, for every value below 10^5 and every 7th
    /// one up to 10^8 (all of them were checked once, in 0.3 s of a release build).
    #[test]
    fn eight_digits_are_those_of_division() {
        let check = |value: u32| {
            let mut expected = 0u64;
            let mut rest = value;
            for k in 0..8 {
                expected |= u64::from(rest % 10) << (8 * (7 - k));
                rest /= 10;
            }
            assert_eq!(eight_digits(value), expected, "{value}");
        };
        (0..100_000).for_each(check);
        (100_000..100_000_000).step_by(7).for_each(check);
    }

    #[test]
    fn output_larger_than_a_block_arrives_whole() {
        let mut out = Vec::new();
        let mut lines = Lines::new(&mut out);
        let mut expected = String::new();
        for i in 0..50_000 {
            for (k, value) in [i, i + 1, 3 * i].into_iter().enumerate() {
                if k > 0 {
                    lines.text(b" ");
                }
                lines.number(value);
            }
            lines.end().unwrap();
            expected.push_str(&format!("{i} {} {}\n", i + 1, 3 * i));
        }
        lines.finish().unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }

    /// Enough points for several pieces of triangles and of points, duplicates among them: the
    /// writers give the lines of `Triangulation::triangles` and of the sorted edges, in order,
    /// on rayon's threads and on one.
    #[test]
    fn pieces_give_the_lines_of_the_iterators() {
        let mut rng = Xorshift::new(31);
        let mut points = rng.unit_points(4 * EDGES_PER_PIECE);
        points.extend_from_slice(&points.clone()[..500]);
        let tri = triangulate(&points).unwrap();
        assert!(tri.mesh().num_triangles_with_ghosts() > 2 * TRIANGLES_PER_PIECE);
        let triangles: String = tri
            .triangles()
            .map(|[a, b, c]| format!("{a} {b} {c}\n"))
            .collect();
        let mut edges: Vec<[usize; 2]> = tri.edges().collect();
        edges.sort_unstable();
        let edges: String = edges.iter().map(|[a, b]| format!("{a} {b}\n")).collect();
        let run = || {
            let (mut t, mut e) = (Vec::new(), Vec::new());
            write_triangles(&mut t, &tri).unwrap();
            write_triangulation_edges(&mut e, &tri).unwrap();
            (String::from_utf8(t).unwrap(), String::from_utf8(e).unwrap())
        };
        for (t, e) in on_rayon_and_one_thread(run) {
            assert!(t == triangles && e == edges);
        }
    }

    /// A reconstruction with edges for several pieces: `write_edges` gives the lines of
    /// `Reconstruction::edges`, in order, on rayon's threads and on one.
    #[test]
    fn reconstruction_edges_in_pieces_are_its_edges() {
        let n = 3 * EDGES_PER_PIECE + 77;
        let points: Vec<Point> = (0..n)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / n as f64;
                Point::new(1000.0 * libm::cos(t), 700.0 * libm::sin(t))
            })
            .collect();
        let result = condt::reconstruct(&points, &condt::Params::default()).unwrap();
        assert!(result.edges().len() > 3 * EDGES_PER_PIECE);
        let expected: String = result.edges().map(|[a, b]| format!("{a} {b}\n")).collect();
        let run = || {
            let mut out = Vec::new();
            write_edges(&mut out, &result).unwrap();
            String::from_utf8(out).unwrap()
        };
        for out in on_rayon_and_one_thread(run) {
            assert!(out == expected);
        }
    }

    /// The sorted keys give the triangulation's edges, sorted, for random, duplicated,
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
            let mut points = rng.unit_points(n);
            points.extend_from_slice(&points.clone()[..n / 3]);
            inputs.push(points);
        }
        for points in inputs {
            let tri = triangulate(&points).unwrap();
            let mut expected: Vec<[usize; 2]> = tri.edges().collect();
            expected.sort_unstable();
            let keys = sorted_edge_keys(&tri).unwrap();
            let listed: Vec<[usize; 2]> = keys.iter().map(|&k| edge_of_key(k)).collect();
            assert_eq!(listed, expected, "{} points", points.len());
        }
    }
}
