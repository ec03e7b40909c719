//! NumPy `.npy` files: points in (float64, float32 or an integer type up to 2^53, shape
//! `(n, 2)`) and out (float64,
//! `write_npy_points`), indices out (edges
//! `(m, 2)`, triangles `(t, 3)`, as uint32 when every index fits, int64 otherwise), and edges
//! in again (`(m, 2)`, any signed or unsigned integer type, for `condt score`).
//!
//! Owns the NPY format (versions 1.0, 2.0 and 3.0 of NumPy's `format` module): the magic
//! string, the version, the header length, the header (a Python dictionary literal with
//! `descr`, `fortran_order` and `shape`) and the raw data after it. It reads and writes in
//! blocks, so neither direction holds a second copy of the data.
//!
//! Reading refuses, naming the file, anything it cannot read exactly: another dtype or shape, a
//! header it cannot parse, a file shorter or longer than its header says, and NaN or infinite
//! coordinates (with the row). Both byte orders and both memory orders (C and Fortran) are read.

use super::pieces::{write_pieces, Cursor, ROOM};
use super::{IoError, IoErrorKind};
use condt::mesh::VertexId;
use condt::Point;
use condt::Reconstruction;
use condt::{Triangulation, MAX_POINTS};
use core::ops::Range;
use core::sync::atomic::{AtomicUsize, Ordering};
use std::fs::File;
use std::io::{self, Read, Write};
use std::string::String;
use std::vec::Vec;

/// The first six bytes of every `.npy` file (the first is not UTF-8: no text file starts so).
///
/// ```
/// use condt::Point;
/// use condt_io::{write_npy_points, NPY_MAGIC};
/// let mut bytes = Vec::new();
/// write_npy_points(&mut bytes, &[Point::new(1.0, 2.0)])?;
/// // How a NumPy array is told from a text file by its content (standard input has no name).
/// assert!(bytes.starts_with(NPY_MAGIC));
/// assert!(std::str::from_utf8(NPY_MAGIC).is_err());
/// # Ok::<(), std::io::Error>(())
/// ```
pub const NPY_MAGIC: &[u8; 6] = b"\x93NUMPY";

/// Longest header read: NumPy's own writer needs about 128 bytes; this bounds what a damaged
/// length field can make us allocate.
const MAX_HEADER: usize = 1 << 16;

/// Bytes read or written at a time.
const BLOCK: usize = 1 << 20;

/// The element types a point file may hold.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Float {
    F64,
    F32,
    /// An integer type (`numpy.argwhere` of an image's mask gives int64 pixel places): exact
    /// as a double up to 2^53, and refused beyond.
    Int(Index),
}

/// The largest magnitude an integer coordinate may have: every integer up to 2^53 is a double.
const EXACT_INTEGERS: i128 = 1 << 53;

/// What the header of a point file says.
#[derive(Debug, PartialEq)]
struct Header {
    float: Float,
    big_endian: bool,
    fortran_order: bool,
    rows: usize,
}

/// A value of the header dictionary.
#[derive(Debug, PartialEq)]
enum Value {
    Text(String),
    Bool(bool),
    Tuple(Vec<u64>),
    /// A number: no known key takes one, but an unknown key is told as such, not by its value.
    Number(String),
}

fn content(file: &str, message: String) -> IoError {
    IoError {
        file: file.to_string(),
        line: None,
        kind: IoErrorKind::Content(message),
    }
}

/// Reads a Python dictionary literal of the kind NumPy writes: string keys, and string,
/// `True`/`False` or tuple-of-integers values.
struct Literal<'a> {
    text: &'a [u8],
    at: usize,
}

impl Literal<'_> {
    fn skip_space(&mut self) {
        while self.text.get(self.at).is_some_and(u8::is_ascii_whitespace) {
            self.at += 1;
        }
    }

    /// Skips spaces, then takes `byte` if it is next.
    fn take(&mut self, byte: u8) -> bool {
        self.skip_space();
        let found = self.text.get(self.at) == Some(&byte);
        if found {
            self.at += 1;
        }
        found
    }

    fn expect(&mut self, byte: u8) -> Result<(), String> {
        if self.take(byte) {
            Ok(())
        } else {
            Err(format!(
                "expected '{}' at byte {} of the header",
                byte as char, self.at
            ))
        }
    }

    fn string(&mut self) -> Result<String, String> {
        self.skip_space();
        let quote = match self.text.get(self.at) {
            Some(&q @ (b'\'' | b'"')) => q,
            _ => {
                return Err(format!(
                    "expected a quoted name at byte {} of the header",
                    self.at
                ))
            }
        };
        let start = self.at + 1;
        let length = self.text[start..]
            .iter()
            .position(|&b| b == quote)
            .ok_or_else(|| "a quoted name in the header does not end".to_string())?;
        self.at = start + length + 1;
        Ok(String::from_utf8_lossy(&self.text[start..start + length]).into_owned())
    }

    fn word(&mut self) -> &[u8] {
        self.skip_space();
        let start = self.at;
        while self
            .text
            .get(self.at)
            .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
        {
            self.at += 1;
        }
        &self.text[start..self.at]
    }

    /// The text from here to the next `,`, `)` or `}` (at most 30 characters), for a message
    /// about what could not be read: `-50`, `[('x', '<f8')`, not an empty quote.
    fn raw(&self) -> String {
        let rest = &self.text[self.at.min(self.text.len())..];
        let end = rest
            .iter()
            .position(|b| matches!(b, b',' | b')' | b'}'))
            .unwrap_or(rest.len());
        let shown: String = String::from_utf8_lossy(&rest[..end])
            .chars()
            .take(30)
            .collect();
        shown.trim().to_string()
    }

    fn value(&mut self) -> Result<Value, String> {
        self.skip_space();
        match self.text.get(self.at) {
            Some(b'\'' | b'"') => self.string().map(Value::Text),
            Some(b'(') => {
                self.at += 1;
                let mut items = Vec::new();
                while !self.take(b')') {
                    let raw = self.raw();
                    let word = self.word();
                    let item = core::str::from_utf8(word)
                        .ok()
                        .and_then(|w| w.parse::<u64>().ok())
                        .ok_or_else(|| format!("the shape holds {raw:?}, not a size"))?;
                    items.push(item);
                    if !self.take(b',') {
                        self.expect(b')')?;
                        break;
                    }
                }
                Ok(Value::Tuple(items))
            }
            _ => {
                let raw = self.raw();
                match self.word() {
                    b"True" => Ok(Value::Bool(true)),
                    b"False" => Ok(Value::Bool(false)),
                    word if !word.is_empty() && word.iter().all(u8::is_ascii_digit) => {
                        Ok(Value::Number(String::from_utf8_lossy(word).into_owned()))
                    }
                    _ if raw.starts_with('[') => Err(format!(
                        "cannot read {raw:?} in the header (a structured element type? \
                         points are float64, float32 or integers, edges integers)"
                    )),
                    _ => Err(format!("cannot read {raw:?} in the header")),
                }
            }
        }
    }

    /// The dictionary's entries, in order.
    fn dictionary(&mut self) -> Result<Vec<(String, Value)>, String> {
        self.expect(b'{')?;
        let mut entries = Vec::new();
        while !self.take(b'}') {
            let key = self.string()?;
            self.expect(b':')?;
            entries.push((key, self.value()?));
            if !self.take(b',') {
                self.expect(b'}')?;
                break;
            }
        }
        self.skip_space();
        if self.at != self.text.len() {
            return Err("the header goes on after its dictionary".to_string());
        }
        Ok(entries)
    }
}

/// The three entries of a header dictionary, whatever the array holds.
struct Entries {
    descr: String,
    fortran_order: bool,
    shape: Vec<u64>,
}

/// The entries of a header dictionary; an unknown key or a missing one is refused.
fn entries(text: &[u8]) -> Result<Entries, String> {
    let entries = Literal { text, at: 0 }.dictionary()?;
    let (mut descr, mut fortran_order, mut shape) = (None, None, None);
    for (key, value) in entries {
        match (key.as_str(), value) {
            ("descr", Value::Text(d)) => descr = Some(d),
            ("fortran_order", Value::Bool(f)) => fortran_order = Some(f),
            ("shape", Value::Tuple(s)) => shape = Some(s),
            (key @ ("descr" | "fortran_order" | "shape"), value) => {
                let shown = match value {
                    Value::Text(text) => format!("'{text}'"),
                    Value::Bool(true) => "True".to_string(),
                    Value::Bool(false) => "False".to_string(),
                    Value::Tuple(items) => shown_shape(&items),
                    Value::Number(number) => number,
                };
                return Err(format!("the header's '{key}' is {shown}"));
            }
            (other, _) => return Err(format!("the header has an unknown key '{other}'")),
        }
    }
    Ok(Entries {
        descr: descr.ok_or("the header has no 'descr' (the element type)")?,
        fortran_order: fortran_order.ok_or("the header has no 'fortran_order'")?,
        shape: shape.ok_or("the header has no 'shape'")?,
    })
}

/// The shape as NumPy prints it: `(2,)`, `(1, 3)`.
fn shown_shape(shape: &[u64]) -> String {
    let shown: Vec<String> = shape.iter().map(u64::to_string).collect();
    match &shown[..] {
        // Python's spelling of a one-element tuple, as numpy prints the shape.
        [one] => format!("({one},)"),
        _ => format!("({})", shown.join(", ")),
    }
}

/// How to save the layouts other tools hand over as (n, 2), as Python's `condt.reconstruct`
/// says of the same arrays: an image user saved OpenCV's contours, (n, 1, 2), or a mask, and
/// got the bare shape. Empty for other shapes.
fn shape_hint(shape: &[u64]) -> &'static str {
    match shape {
        [2, _] => "; points by column? save points.T",
        [_, 1, 2] => "; OpenCV's contour layout? save points.reshape(-1, 2)",
        [_, _, 1, 2] => "; OpenCV's contours stacked? save numpy.vstack(contours).reshape(-1, 2)",
        [_, _, 2] => "; contours stacked? save numpy.vstack(contours)",
        [_, 3] | [_, 4] => "; save the two coordinate columns, such as points[:, :2]",
        // A colour image saved whole: its pixels are no points until an edge image or a mask
        // picks them (a diff review: `(48, 64, 3)` was told its shape alone).
        [h, w, 3 | 4] if *h >= 5 && *w >= 5 => {
            "; a colour image? make an edge image or a mask of it first (skimage.color.rgb2gray, \
             then a threshold or skimage.feature.canny), then save points: \
             numpy.argwhere(edges)[:, ::-1] gives its pixels as (x, y)"
        }
        // An image or a mask saved whole (every pixel of a filled mask would be a point); a table
        // of 5 columns or more reads so too. A label image's regions each hold many values, so
        // neither of a mask's fixes gives its borders (a label-image user's review): the
        // subpixel boundaries do, with the pixel corners where three regions meet.
        [h, w] if *h >= 5 && *w >= 5 => {
            "; an image or a mask? save points: numpy.argwhere(edges)[:, ::-1] gives an edge \
             image's pixels as (x, y), and mask & ~scipy.ndimage.binary_erosion(mask) a filled \
             mask's boundary; a label image (regions numbered)? b = \
             skimage.segmentation.find_boundaries(labels, mode='subpixel'), then \
             numpy.argwhere(b)[:, ::-1] / 2 gives the borders between regions, junctions included; \
             a table? save the two coordinate columns, such as points[:, :2]"
        }
        _ => "",
    }
}

/// The meaning of a header dictionary for a point file.
fn point_header(text: &[u8]) -> Result<Header, String> {
    let Entries {
        descr,
        fortran_order,
        shape,
    } = entries(text)?;
    let (float, big_endian) = match descr.as_str() {
        "<f8" => (Float::F64, false),
        ">f8" => (Float::F64, true),
        "<f4" => (Float::F32, false),
        ">f4" => (Float::F32, true),
        other => match Index::of(other) {
            Some((index, big_endian)) => (Float::Int(index), big_endian),
            None => {
                // A mask saved whole is bools: its shape says more of the fix than its type.
                return Err(format!(
                    "element type {other:?} is not supported: points are float64 ('<f8', \
                     '>f8'), float32 ('<f4', '>f4') or integers ('<i8', '<u2', ...){}",
                    shape_hint(&shape)
                ));
            }
        },
    };
    let rows = match shape[..] {
        [rows, 2] => usize::try_from(rows).unwrap_or(usize::MAX),
        _ => {
            return Err(format!(
                "shape {} is not (n, 2): one row `x y` per point{}",
                shown_shape(&shape),
                shape_hint(&shape)
            ));
        }
    };
    if rows > MAX_POINTS {
        return Err(format!(
            "{rows} points, more than {MAX_POINTS}, the most condt accepts"
        ));
    }
    Ok(Header {
        float,
        big_endian,
        fortran_order,
        rows,
    })
}

/// Reads exactly `buffer.len()` bytes unless the input ends first; returns how many it read.
fn read_up_to(reader: &mut dyn Read, buffer: &mut [u8]) -> io::Result<usize> {
    let mut filled = 0;
    while filled < buffer.len() {
        match reader.read(&mut buffer[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(filled)
}

/// The header of a point file, read up to the first data byte, and how many bytes it took.
fn read_header(reader: &mut dyn Read, file: &str) -> Result<(Header, usize), IoError> {
    let (text, length) = read_header_text(reader, file)?;
    let header = point_header(&text).map_err(|message| content(file, message))?;
    Ok((header, length))
}

/// The dictionary text of a `.npy` stream's header, read up to the first data byte, and how
/// many bytes the header took (magic, version and length included).
fn read_header_text(reader: &mut dyn Read, file: &str) -> Result<(Vec<u8>, usize), IoError> {
    let io_error = |err: io::Error| IoError::os(file, err);
    let mut start = [0u8; 8];
    let got = read_up_to(reader, &mut start).map_err(io_error)?;
    // Cut within the magic and the version (a file of 1 to 7 bytes that starts as one does): a
    // damaged array, not some other file.
    let magic = got.min(NPY_MAGIC.len());
    if got < 8 && got > 0 && start[..magic] == NPY_MAGIC[..magic] {
        return Err(content(file, "the file ends inside its header".to_string()));
    }
    if got < 8 || &start[..6] != NPY_MAGIC {
        return Err(content(
            file,
            "not a NumPy .npy file (it does not start with \\x93NUMPY)".to_string(),
        ));
    }
    let (major, minor) = (start[6], start[7]);
    let length_bytes = match (major, minor) {
        (1, 0) => 2,
        (2 | 3, 0) => 4,
        _ => {
            return Err(content(
                file,
                format!(
                    "NPY format version {major}.{minor} is not supported (1.0, 2.0 and 3.0 are)"
                ),
            ))
        }
    };
    let mut length = [0u8; 4];
    if read_up_to(reader, &mut length[..length_bytes]).map_err(io_error)? < length_bytes {
        return Err(content(file, "the file ends inside its header".to_string()));
    }
    let length = u32::from_le_bytes(length) as usize;
    if length > MAX_HEADER {
        return Err(content(
            file,
            format!("a header of {length} bytes: damaged (NumPy writes about 128)"),
        ));
    }
    let mut text = vec![0u8; length];
    if read_up_to(reader, &mut text).map_err(io_error)? < length {
        return Err(content(file, "the file ends inside its header".to_string()));
    }
    if major < 3 && !text.is_ascii() {
        return Err(content(file, "the header is not ASCII text".to_string()));
    }
    Ok((text, 8 + length_bytes + length))
}

/// The points of a `.npy` stream, read in blocks straight into the point array. `length`, the
/// stream's length in bytes when it is known (a regular file, bytes in memory), is checked
/// against what the header announces before anything is allocated for the points: a short
/// header must not make the reader allocate gigabytes for data that are not there. Of a stream
/// of unknown length (a pipe), the points are allocated as their data arrive.
fn read_npy_from(
    reader: &mut dyn Read,
    file: &str,
    length: Option<u64>,
) -> Result<Vec<Point>, IoError> {
    let (header, header_length) = read_header(reader, file)?;
    let size = match header.float {
        Float::F64 => 8,
        Float::F32 => 4,
        Float::Int(index) => index.size,
    };
    let n = header.rows;
    let mut points: Vec<Point> = Vec::new();
    if let Some(length) = length {
        // `n` is at most MAX_POINTS, so the data's size fits a u64.
        let data = 2 * n as u64 * size as u64;
        let available = length.saturating_sub(header_length as u64);
        if available < data {
            // What a read to the end would report, without reading.
            return Err(ends_early(file, n, size, available as usize));
        }
        reserve(&mut points, n, file)?;
    }
    if !header.fortran_order {
        read_rows(reader, file, &header, size, &mut points)?;
    } else {
        read_columns(reader, file, &header, size, &mut points)?;
    }
    let mut extra = [0u8; 1];
    if read_up_to(reader, &mut extra).map_err(|err| IoError::os(file, err))? > 0 {
        return Err(content(
            file,
            format!("bytes after the {n} points the header announces"),
        ));
    }
    if let Some(row) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        let p = points[row];
        let message = if let Float::Int(_) = header.float {
            format!(
                "row {row}: a coordinate beyond 2^53, past which a double (condt's \
                 coordinates) holds only some integers exactly; convert the array to float64 \
                 to accept the rounding"
            )
        } else {
            format!("row {row}: the point ({}, {}) is not finite", p.x, p.y)
        };
        return Err(content(file, message));
    }
    Ok(points)
}

/// Room for `more` points, refused as an error (not an abort) when the memory is not there.
fn reserve(points: &mut Vec<Point>, more: usize, file: &str) -> Result<(), IoError> {
    points.try_reserve_exact(more).map_err(|_| {
        content(
            file,
            format!(
                "out of memory: {} points do not fit ({} bytes)",
                points.len() + more,
                (points.len() + more).saturating_mul(16)
            ),
        )
    })
}

/// Room for the `more` points of a block about to be read, of `n` in all: nothing when a known
/// length let [`read_npy_from`] reserve them all; otherwise the vector grows with the data read
/// (doubling, never past `n`), so what is allocated follows what arrived.
fn room_for(points: &mut Vec<Point>, n: usize, more: usize, file: &str) -> Result<(), IoError> {
    if points.capacity() - points.len() >= more {
        return Ok(());
    }
    let grow = (n - points.len()).min(more.max(points.len()));
    reserve(points, grow, file)
}

/// The error for a file that ends `read` bytes into the `n` points its header announces.
fn ends_early(file: &str, n: usize, size: usize, read: usize) -> IoError {
    content(
        file,
        format!(
            "the header announces {n} points ({} bytes of data), the file ends after {read} \
             bytes of them",
            2 * n * size
        ),
    )
}

/// The points of a C-order array (row after row, `x` then `y`), appended to `points` as their
/// rows are read: each point is written once, with no zeroed array to fill first, and the
/// common little-endian float64 file is decoded without a per-value choice.
fn read_rows(
    reader: &mut dyn Read,
    file: &str,
    header: &Header,
    size: usize,
    points: &mut Vec<Point>,
) -> Result<(), IoError> {
    let n = header.rows;
    let row = 2 * size;
    let mut block = vec![0u8; BLOCK - BLOCK % row];
    while points.len() < n {
        let want = ((n - points.len()) * row).min(block.len());
        let got = read_up_to(reader, &mut block[..want]).map_err(|err| IoError::os(file, err))?;
        room_for(points, n, got / row, file)?;
        let rows = block[..got - got % row].chunks_exact(row);
        match (header.float, header.big_endian) {
            (Float::F64, false) => points.extend(rows.map(|b| {
                let (x, y) = b.split_at(8);
                Point::new(
                    f64::from_le_bytes(x.try_into().unwrap_or([0; 8])),
                    f64::from_le_bytes(y.try_into().unwrap_or([0; 8])),
                )
            })),
            (float, big_endian) => points.extend(rows.map(|b| {
                let (x, y) = b.split_at(size);
                Point::new(decode(x, float, big_endian), decode(y, float, big_endian))
            })),
        }
        if got < want {
            return Err(ends_early(file, n, size, points.len() * row + got % row));
        }
    }
    Ok(())
}

/// The points of a Fortran-order array (all `x`, then all `y`): each `x` appended to `points`
/// as it is read (its `y` zero), then each `y` written into its point.
fn read_columns(
    reader: &mut dyn Read,
    file: &str,
    header: &Header,
    size: usize,
    points: &mut Vec<Point>,
) -> Result<(), IoError> {
    let n = header.rows;
    let values = 2 * n;
    let mut block = vec![0u8; BLOCK - BLOCK % size];
    let mut done = 0usize;
    while done < values {
        let want = ((values - done) * size).min(block.len());
        let got = read_up_to(reader, &mut block[..want]).map_err(|err| IoError::os(file, err))?;
        let whole = got / size;
        let values = block[..whole * size]
            .chunks_exact(size)
            .map(|bytes| decode(bytes, header.float, header.big_endian));
        // The block's `x` values (the first column) come before its `y` values.
        let xs = n.saturating_sub(done).min(whole);
        room_for(points, n, xs, file)?;
        let mut values = values.enumerate();
        points.extend(values.by_ref().take(xs).map(|(_, x)| Point::new(x, 0.0)));
        for (k, y) in values {
            points[done + k - n].y = y;
        }
        done += whole;
        if got < want {
            return Err(ends_early(file, n, size, done * size + got % size));
        }
    }
    Ok(())
}

#[inline]
fn decode(bytes: &[u8], float: Float, big_endian: bool) -> f64 {
    match float {
        Float::F64 => {
            let raw: [u8; 8] = bytes.try_into().unwrap_or([0; 8]);
            if big_endian {
                f64::from_be_bytes(raw)
            } else {
                f64::from_le_bytes(raw)
            }
        }
        Float::F32 => {
            let raw: [u8; 4] = bytes.try_into().unwrap_or([0; 4]);
            f64::from(if big_endian {
                f32::from_be_bytes(raw)
            } else {
                f32::from_le_bytes(raw)
            })
        }
        // Beyond 2^53 the double would be another number: NaN, which the reader refuses (and
        // tells as such, `read_npy_from`), rather than a rounded place.
        Float::Int(index) => {
            let value = index.value(bytes, big_endian);
            if value.abs() <= EXACT_INTEGERS {
                value as f64
            } else {
                f64::NAN
            }
        }
    }
}

/// Parses the bytes of a NumPy `.npy` file of points: float64, float32 or any integer type
/// (either byte order), shape `(n, 2)`, C or Fortran order, NPY version 1.0, 2.0 or 3.0. `file`
/// names the source in error messages; float32 values are widened exactly, and integers are
/// read exactly up to 2^53 in magnitude (beyond, a double would be another number: refused).
///
/// ```
/// use condt::Point;
/// use condt_io::{parse_npy, write_npy_points};
/// let points = vec![Point::new(0.5, -1.0), Point::new(3.0, 1e-300)];
/// let mut bytes = Vec::new();
/// write_npy_points(&mut bytes, &points)?;
/// assert_eq!(parse_npy(&bytes, "pts.npy")?, points);
///
/// let err = parse_npy(&bytes[..bytes.len() - 3], "cut.npy").unwrap_err();
/// assert!(err.to_string().starts_with("cut.npy: the header announces 2 points"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_npy(bytes: &[u8], file: &str) -> Result<Vec<Point>, IoError> {
    let mut reader = bytes;
    read_npy_from(&mut reader, file, Some(bytes.len() as u64))
}

/// Reads a `.npy` file of points (see [`parse_npy`]) in blocks, straight into the points.
pub(super) fn read_npy_file(path: &std::path::Path, shown: &str) -> Result<Vec<Point>, IoError> {
    let mut file = File::open(path).map_err(|err| IoError::os(shown, err))?;
    // A regular file's length is known; a pipe's is not.
    let length = file
        .metadata()
        .ok()
        .filter(|m| m.is_file())
        .map(|m| m.len());
    read_npy_from(&mut file, shown, length)
}

/// An integer element type of an edge array: its width in bytes and whether it is signed.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Index {
    size: usize,
    signed: bool,
}

impl Index {
    /// The type a NumPy `descr` names (`'<u4'`, `'>i8'`, `'|u1'`, ...) and whether it is
    /// big-endian, or `None` for any other type.
    fn of(descr: &str) -> Option<(Index, bool)> {
        let (order, kind, size) = (descr.get(..1)?, descr.get(1..2)?, descr.get(2..)?);
        let big_endian = match order {
            "<" | "|" | "=" => false,
            ">" => true,
            _ => return None,
        };
        let signed = match kind {
            "i" => true,
            "u" => false,
            _ => return None,
        };
        let size: usize = size.parse().ok().filter(|s| [1, 2, 4, 8].contains(s))?;
        Some((Index { size, signed }, big_endian && size > 1))
    }

    /// The number in `bytes` (exactly `size` of them): every signed and unsigned width up to
    /// 64 bits fits in `i128`.
    fn value(self, bytes: &[u8], big_endian: bool) -> i128 {
        let mut wide = [0u8; 8];
        if big_endian {
            wide[8 - self.size..].copy_from_slice(bytes);
            wide.reverse();
        } else {
            wide[..self.size].copy_from_slice(bytes);
        }
        let raw = u64::from_le_bytes(wide);
        if self.signed {
            // Sign-extend from the type's width.
            let shift = 64 - 8 * self.size as u32;
            i128::from(((raw << shift) as i64) >> shift)
        } else {
            i128::from(raw)
        }
    }
}

/// Parses the bytes of a NumPy `.npy` file of edges, as [`write_npy_edges`] and
/// [`write_npy_triangulation_edges`] write them (and `numpy.save` of such an array): shape
/// `(m, 2)`, any integer type (condt writes uint32 or int64; int32 is NumPy's default on some
/// systems), either byte order, C or Fortran order, NPY version 1.0, 2.0 or 3.0. Row `r` is edge
/// `r`, its two point numbers as they are (a self-loop or a repeated edge is the caller's to
/// judge). `file` names the source in error messages.
///
/// # Errors
/// Content errors naming `file`, in words (never the file's raw bytes): another dtype (float,
/// bool, ...) or shape, a file shorter or longer than its header says, a negative number
/// (with its row), or no NumPy header at all.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// use condt_io::{parse_npy_edges, write_npy_edges};
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut bytes = Vec::new();
/// write_npy_edges(&mut bytes, &r)?;
/// assert_eq!(parse_npy_edges(&bytes, "out.npy")?, [[0, 1], [0, 2], [1, 2]]);
///
/// let err = parse_npy_edges(b"0 1\n", "out.npy").unwrap_err();
/// assert!(err.to_string().starts_with("out.npy: not a NumPy .npy file"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_npy_edges(bytes: &[u8], file: &str) -> Result<Vec<[usize; 2]>, IoError> {
    let rows = parse_npy_index_rows(bytes, file)?;
    let mut edges = Vec::with_capacity(rows.len());
    for (row, pair) in rows.into_iter().enumerate() {
        let mut edge = [0usize; 2];
        for (end, v) in edge.iter_mut().zip(pair) {
            *end = usize::try_from(v).map_err(|_| {
                let why = if v < 0 { "negative" } else { "too large" };
                content(file, format!("row {row}: point number {v} is {why}"))
            })?;
        }
        edges.push(edge);
    }
    Ok(edges)
}

/// [`parse_npy_edges`] without judging the numbers: each row's two entries as they are (every
/// integer type, int64 and uint64 among them, fits in `i128`), for a caller that tells a
/// negative or too large one as a problem of its row rather than of the file (`condt score`
/// scores such an output 0, as it does a text line `-1 0` or `0 18446744073709551615`).
///
/// # Errors
/// As [`parse_npy_edges`], but for the negative and too large numbers.
///
/// ```
/// use condt_io::{parse_npy_edges, parse_npy_index_rows};
/// let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
/// let dict = "{'descr': '<i8', 'fortran_order': False, 'shape': (2, 2), }";
/// let header = format!("{dict:<117}\n");
/// bytes.extend((header.len() as u16).to_le_bytes());
/// bytes.extend(header.bytes());
/// bytes.extend([0i64, 1, 1, -1].iter().flat_map(|v| v.to_le_bytes()));
/// assert_eq!(parse_npy_index_rows(&bytes, "out.npy")?, [[0, 1], [1, -1]]);
/// let err = parse_npy_edges(&bytes, "out.npy").unwrap_err();
/// assert_eq!(err.to_string(), "out.npy: row 1: point number -1 is negative");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn parse_npy_index_rows(bytes: &[u8], file: &str) -> Result<Vec<[i128; 2]>, IoError> {
    let mut reader = bytes;
    let (text, header_length) = read_header_text(&mut reader, file)?;
    let Entries {
        descr,
        fortran_order,
        shape,
    } = entries(&text).map_err(|message| content(file, message))?;
    let Some((index, big_endian)) = Index::of(&descr) else {
        return Err(content(
            file,
            format!(
                "element type {descr:?} is not supported: edges are integers ('<u4' and '<i8' \
                 as condt writes them, or any other signed or unsigned width)"
            ),
        ));
    };
    let rows = match shape[..] {
        [rows, 2] => rows,
        _ => {
            return Err(content(
                file,
                format!(
                    "shape {} is not (m, 2): one row `i j` per edge",
                    shown_shape(&shape)
                ),
            ))
        }
    };
    let size = index.size as u64;
    let data = &bytes[header_length..];
    // Compared before anything is allocated: a damaged header must not ask for gigabytes.
    let wanted = rows.checked_mul(2 * size);
    match wanted {
        Some(wanted) if wanted == data.len() as u64 => {}
        Some(wanted) if wanted < data.len() as u64 => {
            return Err(content(
                file,
                format!("bytes after the {rows} edges the header announces"),
            ))
        }
        _ => {
            return Err(content(
                file,
                format!(
                    "the header announces {rows} edges ({} bytes of data), the file has {} \
                     bytes of them",
                    wanted.map_or_else(|| "more than 2^64".to_string(), |w| w.to_string()),
                    data.len()
                ),
            ))
        }
    }
    let rows = rows as usize;
    let size = size as usize;
    let value = |k: usize| index.value(&data[k * size..(k + 1) * size], big_endian);
    // C order holds row after row; Fortran order the first column, then the second.
    let at = |row: usize, column: usize| {
        if fortran_order {
            column * rows + row
        } else {
            2 * row + column
        }
    };
    Ok((0..rows)
        .map(|row| [value(at(row, 0)), value(at(row, 1))])
        .collect())
}

/// A version 1.0 header (version 2.0 when the dictionary is over 65,535 bytes, which no shape
/// here needs) for `descr` and `shape`, padded with spaces to a multiple of 64 bytes as NumPy
/// pads it.
fn header(descr: &str, shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let dims = if dims.len() == 1 {
        format!("{},", dims[0])
    } else {
        dims.join(", ")
    };
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': ({dims}), }}");
    let (version, prefix) = if dict.len() + 12 <= usize::from(u16::MAX) {
        (1u8, 10)
    } else {
        (2u8, 12)
    };
    let unpadded = prefix + dict.len() + 1;
    dict.extend(std::iter::repeat_n(' ', (64 - unpadded % 64) % 64));
    dict.push('\n');
    let mut out = Vec::with_capacity(prefix + dict.len());
    out.extend_from_slice(NPY_MAGIC);
    out.extend_from_slice(&[version, 0]);
    if version == 1 {
        out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    } else {
        out.extend_from_slice(&(dict.len() as u32).to_le_bytes());
    }
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Writes `points` as a `.npy` file: little-endian float64, shape `(n, 2)`, C order.
///
/// ```
/// use condt::Point;
/// use condt_io::write_npy_points;
/// let mut bytes = Vec::new();
/// write_npy_points(&mut bytes, &[Point::new(1.0, 2.0)])?;
/// assert_eq!(&bytes[..10], b"\x93NUMPY\x01\x00\x76\x00");
/// assert_eq!(bytes.len(), 128 + 16);
/// assert_eq!(&bytes[128..136], &1.0f64.to_le_bytes());
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn write_npy_points(out: &mut dyn Write, points: &[Point]) -> io::Result<()> {
    out.write_all(&header("<f8", &[points.len(), 2]))?;
    let mut block = Vec::with_capacity(BLOCK);
    for chunk in points.chunks(BLOCK / 16) {
        block.clear();
        for p in chunk {
            block.extend_from_slice(&p.x.to_le_bytes());
            block.extend_from_slice(&p.y.to_le_bytes());
        }
        out.write_all(&block)?;
    }
    Ok(())
}

/// Hands the rows of a range of units to a callback, for [`write_indices`].
type RowsOf<'a, const K: usize> = dyn Fn(Range<usize>, &mut dyn FnMut([usize; K])) + Sync + 'a;

/// Rows of `K` indices below `points`, written as uint32 when every index fits, int64
/// otherwise, shape `(rows, K)`. `rows_of(range, row)` hands `row` the rows of units `range`
/// (units are the caller's: triangles, points, edges), the rows of `0..units` in order being
/// the array's; the units are cut into pieces of `piece` and converted on rayon's threads with
/// the `parallel` feature ([`write_pieces`]). `rows` must be how many there are; a mismatch is
/// an error rather than a file whose header lies.
fn write_indices<const K: usize>(
    out: &mut dyn Write,
    points: usize,
    rows: usize,
    units: usize,
    piece: usize,
    rows_of: &RowsOf<'_, K>,
) -> io::Result<()> {
    const { assert!(8 * K <= ROOM) };
    let narrow = points as u64 <= 1 << 32;
    out.write_all(&header(if narrow { "<u4" } else { "<i8" }, &[rows, K]))?;
    let written = AtomicUsize::new(0);
    write_pieces(out, units, piece, &|range, buf| {
        let mut cursor = Cursor::new(buf);
        let mut count = 0;
        rows_of(range, &mut |row| {
            let room = cursor.room();
            let mut at = 0;
            for i in row {
                if narrow {
                    room[at..at + 4].copy_from_slice(&(i as u32).to_le_bytes());
                    at += 4;
                } else {
                    room[at..at + 8].copy_from_slice(&(i as i64).to_le_bytes());
                    at += 8;
                }
            }
            cursor.advance(at);
            count += 1;
        });
        written.fetch_add(count, Ordering::Relaxed);
        cursor.finish()
    })?;
    let written = written.into_inner();
    if written != rows {
        return Err(io::Error::other(format!(
            "{written} rows written under a header announcing {rows}"
        )));
    }
    Ok(())
}

/// Rows per piece of [`write_indices`]: 8,192 rows of three uint32 are 96 kB (the batches in
/// flight stay near 1 MB).
const ROWS_PER_PIECE: usize = 1 << 13;

/// The number of triangles of `tri` (`Triangulation::triangles().count()`), for the header
/// that comes before them; on rayon's threads with the `parallel` feature, as it is a pass
/// over every corner of the mesh before the first row can be written.
fn count_finite_triangles(tri: &Triangulation) -> usize {
    let mesh = tri.mesh();
    let corners = mesh.corner_slice(0..mesh.num_triangles_with_ghosts());
    let finite = |corners: &[VertexId]| !corners.iter().any(|v| v.is_infinite());
    #[cfg(feature = "parallel")]
    if condt::parallel_available() {
        use rayon::prelude::*;
        return corners.par_chunks_exact(3).filter(|c| finite(c)).count();
    }
    corners.chunks_exact(3).filter(|c| finite(c)).count()
}

/// The final edges of a reconstruction as a `.npy` array of shape `(m, 2)`, `i < j`, sorted
/// (those of [`write_edges`](super::write_edges)); uint32 when every point index fits, int64
/// otherwise.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let r = reconstruct(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from), &Params::paper())?;
/// let mut bytes = Vec::new();
/// condt_io::write_npy_edges(&mut bytes, &r)?;
/// assert!(bytes[10..128].starts_with(b"{'descr': '<u4', 'fortran_order': False, 'shape': (3, 2), }"));
/// let data: Vec<u32> = bytes[128..].chunks(4).map(|b| u32::from_le_bytes(b.try_into().unwrap())).collect();
/// assert_eq!(data, [0, 1, 0, 2, 1, 2]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_npy_edges(out: &mut dyn Write, result: &Reconstruction) -> io::Result<()> {
    let edges = result.edge_list();
    write_indices::<2>(
        out,
        result.num_points(),
        edges.len(),
        edges.len(),
        ROWS_PER_PIECE,
        &|range, row| {
            for &[a, b] in &edges[range] {
                row([a as usize, b as usize]);
            }
        },
    )
}

/// The triangles of a triangulation as a `.npy` array of shape `(t, 3)`, counter-clockwise,
/// in the order of [`write_triangles`](super::write_triangles); uint32 when every point index
/// fits, int64 otherwise.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(Point::from))?;
/// let mut bytes = Vec::new();
/// condt_io::write_npy_triangles(&mut bytes, &tri)?;
/// assert_eq!(bytes.len(), 128 + 3 * 4);
/// assert!(bytes[10..128].starts_with(b"{'descr': '<u4', 'fortran_order': False, 'shape': (1, 3), }"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_npy_triangles(out: &mut dyn Write, tri: &Triangulation) -> io::Result<()> {
    let mesh = tri.mesh();
    // Pieces of triangle indices, ghosts included: the order of `Triangulation::triangles`.
    let all = mesh.num_triangles_with_ghosts();
    let finite = |corners: &[VertexId; 3]| !corners.iter().any(|v| v.is_infinite());
    let rows = count_finite_triangles(tri);
    write_indices::<3>(
        out,
        tri.num_points(),
        rows,
        all,
        ROWS_PER_PIECE,
        &|range, row| {
            for corners in mesh.triangle_corners(range).filter(finite) {
                row(corners.map(|v| tri.input_of(v)));
            }
        },
    )
}

/// The edges of a triangulation as a `.npy` array of shape `(m, 2)`, `i < j`, sorted (those of
/// [`write_triangulation_edges`](super::write_triangulation_edges)); uint32 when every point
/// index fits, int64 otherwise.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)].map(Point::from))?;
/// let mut bytes = Vec::new();
/// condt_io::write_npy_triangulation_edges(&mut bytes, &tri)?;
/// let data: Vec<u32> = bytes[128..].chunks(4).map(|b| u32::from_le_bytes(b.try_into().unwrap())).collect();
/// assert_eq!(data, [0, 1, 1, 2]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_npy_triangulation_edges(out: &mut dyn Write, tri: &Triangulation) -> io::Result<()> {
    let keys = super::text::sorted_edge_keys(tri)?;
    write_indices::<2>(
        out,
        tri.num_points(),
        keys.len(),
        keys.len(),
        ROWS_PER_PIECE,
        &|range, row| {
            for &key in &keys[range] {
                row(super::text::edge_of_key(key));
            }
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pieces::on_rayon_and_one_thread;

    /// An `.npy` of shape (2, 2) with element type `descr` and these data bytes.
    fn index_file(descr: &str, data: &[u8]) -> Vec<u8> {
        let mut bytes = header(descr, &[2, 2]);
        bytes.extend_from_slice(data);
        bytes
    }

    /// Edges of any integer width and sign read as their numbers (a new user's report: int32,
    /// NumPy's default integer on some systems, and uint64 were refused by `condt score`).
    #[test]
    fn edges_of_any_integer_type_read_alike() {
        let rows = [[0i64, 1], [1, 300]];
        let numbers = rows.concat();
        let little = |size: usize| -> Vec<u8> {
            numbers
                .iter()
                .flat_map(|&v| v.to_le_bytes()[..size].to_vec())
                .collect()
        };
        let big = |size: usize| -> Vec<u8> {
            numbers
                .iter()
                .flat_map(|&v| v.to_be_bytes()[8 - size..].to_vec())
                .collect()
        };
        for (descr, data) in [
            ("<i2", little(2)),
            (">i2", big(2)),
            ("<u2", little(2)),
            ("<i4", little(4)),
            (">i4", big(4)),
            ("<u4", little(4)),
            ("<i8", little(8)),
            ("<u8", little(8)),
            (">u8", big(8)),
        ] {
            let read = parse_npy_index_rows(&index_file(descr, &data), "e.npy").unwrap();
            assert_eq!(read, rows.map(|r| r.map(i128::from)), "{descr}");
        }
        let bytes: Vec<u8> = [0u8, 1, 1, 255].to_vec();
        assert_eq!(
            parse_npy_index_rows(&index_file("|u1", &bytes), "e.npy").unwrap(),
            [[0, 1], [1, 255]]
        );
        assert_eq!(
            parse_npy_index_rows(&index_file("|i1", &bytes), "e.npy").unwrap(),
            [[0, 1], [1, -1]]
        );
        let err = parse_npy_edges(
            &index_file(
                "<i4",
                &[0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 255, 255, 255, 255],
            ),
            "e.npy",
        );
        assert_eq!(
            err.unwrap_err().to_string(),
            "e.npy: row 1: point number -1 is negative"
        );
        // uint64 beyond i64 is read as it is, for the caller to judge (`condt score` scores
        // it as a point that does not exist, as it does the same number in a text line).
        let huge: Vec<u8> = [0u64, 1, 1, u64::MAX]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        assert_eq!(
            parse_npy_index_rows(&index_file("<u8", &huge), "e.npy").unwrap(),
            [[0, 1], [1, i128::from(u64::MAX)]]
        );
        let huge_i64: Vec<u8> = [0i64, 1, i64::MIN, i64::MAX]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        assert_eq!(
            parse_npy_index_rows(&index_file(">i8", &huge_i64), "e.npy").unwrap(),
            [[0, 1], [i128::from(i64::MIN), i128::from(i64::MAX)]]
        );
        for descr in ["<f8", "|b1", "<c16", "<i3", "<U4"] {
            let err = parse_npy_index_rows(&index_file(descr, &[0; 32]), "e.npy").unwrap_err();
            assert!(
                err.to_string().contains("is not supported"),
                "{descr}: {err}"
            );
        }
    }

    /// Enough points for several pieces: the arrays hold the rows of the iterators, in order,
    /// on rayon's threads and on one.
    #[test]
    fn pieces_give_the_rows_of_the_iterators() {
        let mut rng = crate::test_rng::Xorshift::new(8);
        let mut points = rng.unit_points(2 * ROWS_PER_PIECE + 1000);
        points.extend_from_slice(&points.clone()[..300]);
        let tri = condt::triangulate(&points).unwrap();
        assert!(tri.triangles().count() > 2 * ROWS_PER_PIECE);
        let u32s = |bytes: &[u8]| -> Vec<usize> {
            bytes[128..]
                .chunks_exact(4)
                .map(|b| u32::from_le_bytes(b.try_into().unwrap()) as usize)
                .collect()
        };
        assert_eq!(count_finite_triangles(&tri), tri.triangles().count());
        let triangles: Vec<usize> = tri.triangles().flatten().collect();
        let mut edges: Vec<[usize; 2]> = tri.edges().collect();
        edges.sort_unstable();
        let edges = edges.concat();
        let run = || {
            let (mut t, mut e) = (Vec::new(), Vec::new());
            write_npy_triangles(&mut t, &tri).unwrap();
            write_npy_triangulation_edges(&mut e, &tri).unwrap();
            (u32s(&t), u32s(&e))
        };
        for (t, e) in on_rayon_and_one_thread(run) {
            assert!(t == triangles && e == edges);
        }
    }

    /// A C-order file longer than a block, cut short: the points before the cut are read in
    /// blocks and the message counts every byte that arrived.
    #[test]
    fn a_file_cut_after_the_first_block_says_how_much_arrived() {
        let n = 100_000;
        let points: Vec<Point> = (0..n).map(|i| Point::new(i as f64, -(i as f64))).collect();
        let mut bytes = Vec::new();
        write_npy_points(&mut bytes, &points).unwrap();
        assert!(bytes.len() - 128 > BLOCK);
        assert_eq!(parse_npy(&bytes, "whole.npy").unwrap(), points);
        let err = parse_npy(&bytes[..bytes.len() - 3], "cut.npy").unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "cut.npy: the header announces {n} points ({} bytes of data), the file ends \
                 after {} bytes of them",
                16 * n,
                16 * n - 3
            )
        );
    }

    /// The header counts agree with the iterators on degenerate sets too.
    #[test]
    fn counts_of_degenerate_triangulations() {
        let sets: Vec<Vec<Point>> = vec![
            vec![Point::new(0.0, 0.0)],
            vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)],
            vec![Point::new(1.0, 1.0); 3],
            (0..10).map(|i| Point::new(f64::from(i), 0.5)).collect(),
            (0..25)
                .map(|i| Point::new(f64::from(i % 5), f64::from(i / 5)))
                .collect(),
        ];
        for points in sets {
            let tri = condt::triangulate(&points).unwrap();
            assert_eq!(count_finite_triangles(&tri), tri.triangles().count());
        }
    }

    /// Indices of more than 2^32 points go out as int64, in pieces as well; a row count that
    /// is not the header's is an error.
    #[test]
    fn wide_indices_and_a_wrong_row_count() {
        let rows_of = |range: Range<usize>, row: &mut dyn FnMut([usize; 2])| {
            for i in range {
                row([i, (1 << 33) + i]);
            }
        };
        let mut out = Vec::new();
        write_indices::<2>(&mut out, (1 << 33) + 10, 10, 10, 3, &rows_of).unwrap();
        assert!(out[10..128].starts_with(b"{'descr': '<i8'"));
        let data: Vec<i64> = out[128..]
            .chunks_exact(8)
            .map(|b| i64::from_le_bytes(b.try_into().unwrap()))
            .collect();
        let expected: Vec<i64> = (0..10).flat_map(|i| [i, (1 << 33) + i]).collect();
        assert_eq!(data, expected);
        let err = write_indices::<2>(&mut Vec::new(), 100, 11, 10, 3, &rows_of).unwrap_err();
        assert_eq!(
            err.to_string(),
            "10 rows written under a header announcing 11"
        );
    }

    #[test]
    fn headers_are_padded_to_64_bytes_and_end_in_a_newline() {
        for shape in [[0usize, 2], [7, 3], [123_456_789, 2], [usize::MAX, 3]] {
            let h = header("<u4", &shape);
            assert_eq!(h.len() % 64, 0, "{shape:?}");
            assert_eq!(h.last(), Some(&b'\n'));
            let length = usize::from(u16::from_le_bytes([h[8], h[9]]));
            assert_eq!(length + 10, h.len());
            let parsed = Literal {
                text: &h[10..],
                at: 0,
            }
            .dictionary()
            .unwrap();
            assert_eq!(
                parsed[2],
                (
                    "shape".to_string(),
                    Value::Tuple(shape.iter().map(|&d| d as u64).collect())
                )
            );
        }
    }

    /// A user review: `numpy.save` of `numpy.argwhere(mask)` (int64 pixel places) was refused,
    /// though Python's `reconstruct` takes integer arrays. Every integer width and byte order
    /// reads as its doubles, up to 2^53 either way; beyond, refused with the row.
    #[test]
    fn integer_points_read_exactly_up_to_two_to_the_53() {
        // `index_file`'s array, in Fortran order when asked (the padded header keeps its length).
        let file = |descr: &str, fortran: bool, data: &[u8]| {
            let bytes = index_file(descr, data);
            let (from, to): (&[u8], &[u8]) = (b"False", b"True ");
            match bytes.windows(5).position(|w| w == from) {
                Some(at) if fortran => [&bytes[..at], to, &bytes[at + 5..]].concat(),
                _ => bytes,
            }
        };
        let limit = 1i64 << 53;
        let wide: Vec<u8> = [limit, -limit, 7, -3]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let expected = vec![
            Point::new(limit as f64, -limit as f64),
            Point::new(7.0, -3.0),
        ];
        assert_eq!(
            parse_npy(&file("<i8", false, &wide), "w.npy").unwrap(),
            expected
        );
        let columns = [limit, 7, -limit, -3];
        let fortran: Vec<u8> = columns.iter().flat_map(|v| v.to_le_bytes()).collect();
        assert_eq!(
            parse_npy(&file("<i8", true, &fortran), "f.npy").unwrap(),
            expected
        );
        let big: Vec<u8> = [1i16, -2, 300, 4]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        assert_eq!(
            parse_npy(&file(">i2", false, &big), "b.npy").unwrap(),
            vec![Point::new(1.0, -2.0), Point::new(300.0, 4.0)]
        );
        let bytes = parse_npy(&file("|u1", false, &[0, 255, 9, 1]), "u.npy").unwrap();
        assert_eq!(bytes, vec![Point::new(0.0, 255.0), Point::new(9.0, 1.0)]);
        for beyond in [limit + 1, -limit - 1, i64::MAX] {
            let data: Vec<u8> = [0, 0, 0, beyond]
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            let err = parse_npy(&file("<i8", false, &data), "x.npy")
                .unwrap_err()
                .to_string();
            assert!(
                err.starts_with("x.npy: row 1: a coordinate beyond 2^53"),
                "{err}"
            );
        }
        let data: Vec<u8> = [0, 0, 0, u64::MAX]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        assert!(parse_npy(&file("<u8", false, &data), "u8.npy").is_err());
    }

    #[test]
    fn dictionaries_in_both_quotes_and_with_or_without_trailing_commas_are_read() {
        for text in [
            "{'descr': '<f4', 'fortran_order': True, 'shape': (5, 2), }",
            "{\"shape\":(5,2),\"fortran_order\":True,\"descr\":\"<f4\"}",
            "  { 'descr' : '<f4' , 'fortran_order' : True , 'shape' : ( 5 , 2 , ) }  \n",
        ] {
            assert_eq!(
                point_header(text.as_bytes()),
                Ok(Header {
                    float: Float::F32,
                    big_endian: false,
                    fortran_order: true,
                    rows: 5
                }),
                "{text}"
            );
        }
        for (text, says) in [
            (
                "{'descr': '<c16', 'fortran_order': False, 'shape': (5, 2), }",
                "\"<c16\"",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5,), }",
                "shape (5,)",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 3), }",
                "shape (5, 3)",
            ),
            ("{'descr': '<f8', 'shape': (5, 2), }", "no 'fortran_order'"),
            (
                "{'descr': '<f8', 'fortran_order': 0, 'shape': (5, 2), }",
                "the header's 'fortran_order' is 0",
            ),
            // Found by a fuzzer: these said `cannot read "1"`, `the shape holds ""` and
            // `cannot read ""`.
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2), 'x': 1}",
                "unknown key 'x'",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (+5, 2), }",
                "the shape holds \"+5\", not a size",
            ),
            (
                "{'descr': [('x', '<f8'), ('y', '<f8')], 'fortran_order': False, 'shape': (5,), }",
                "cannot read \"[('x'\" in the header (a structured element type?",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2), 'x': True}",
                "unknown key",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (-5, 2), }",
                "not a size",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2) ",
                "expected '}'",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2)} x",
                "goes on",
            ),
            ("", "expected '{'"),
        ] {
            let err = point_header(text.as_bytes()).unwrap_err();
            assert!(err.contains(says), "{text}: {err}");
        }
    }
}
