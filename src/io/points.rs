//! Reading point files: the plain `x y` format and Triangle's `.node` format.
//!
//! Both refuse what they cannot read unambiguously, with the file and the line, rather than
//! guess: a Triangle `.node` file under another name, a decimal comma, a fourth column.

use super::{IoError, IoErrorKind};
use crate::geometry::Point;
use crate::triangulate::MAX_POINTS;
use std::fs::File;
use std::io::{self, Read};

/// Longest part of a token quoted in an error message: a file whose first "number" is 100 MB
/// long must not put 100 MB on the terminal.
const QUOTED_CHARS: usize = 40;

/// `token` quoted for an error message, cut after [`QUOTED_CHARS`] characters.
pub(super) fn quoted(token: &str) -> String {
    match token.char_indices().nth(QUOTED_CHARS) {
        None => format!("{token:?}"),
        Some((cut, _)) => format!("{:?}… ({} bytes)", &token[..cut], token.len()),
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

/// The 1-based line holding byte `offset`, with the line ends of [`numbered_lines`].
fn line_at(bytes: &[u8], offset: usize) -> usize {
    let ends = bytes[..offset]
        .iter()
        .enumerate()
        .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
        .count();
    1 + ends
}

/// Builds content errors for one file.
struct Source<'a> {
    file: &'a str,
}

impl Source<'_> {
    fn error(&self, line: usize, message: String) -> IoError {
        IoError {
            file: self.file.to_string(),
            line: Some(line),
            kind: IoErrorKind::Content(message),
        }
    }

    fn number(&self, line: usize, field: &str) -> Result<f64, IoError> {
        let value: f64 = field
            .parse()
            .map_err(|_| self.error(line, format!("cannot read {} as a number", quoted(field))))?;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.error(line, format!("coordinate {} is not finite", quoted(field))))
        }
    }

    /// Appends `p`, refusing more than [`MAX_POINTS`] points or memory the system will not give,
    /// so that a huge file is an error and not an abort.
    fn push(&self, points: &mut Vec<Point>, line: usize, p: Point) -> Result<(), IoError> {
        if points.len() == MAX_POINTS {
            return Err(self.error(
                line,
                format!("more than {MAX_POINTS} points, the most condt accepts"),
            ));
        }
        if points.len() == points.capacity() {
            let more = points.len().max(1024).min(MAX_POINTS - points.len());
            points.try_reserve_exact(more).map_err(|_| {
                self.error(line, format!("out of memory after {} points", points.len()))
            })?;
        }
        points.push(p);
        Ok(())
    }
}

/// `true` for a token that names a column (`x`, `lat`, `"y"`) rather than holds a number: it
/// starts with a letter or `_`, quotes aside, and is not a number (`inf`, `NaN`).
fn is_name(token: &str) -> bool {
    let bare = token.trim_matches(|c| c == '"' || c == '\'');
    token.parse::<f64>().is_err()
        && bare.parse::<f64>().is_err()
        && bare
            .chars()
            .next()
            .is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// The columns of a plain line (comment already removed): separated by whitespace, or by commas
/// alone. A comma next to a field that also holds whitespace is refused: `1,5 2` is either a
/// decimal comma or a typo, and reading it as three columns would be a guess.
fn columns(content: &str) -> Result<Vec<&str>, String> {
    if !content.contains(',') {
        return Ok(content.split_whitespace().collect());
    }
    let fields: Vec<&str> = content.split(',').map(str::trim).collect();
    if fields.iter().any(|f| f.contains(char::is_whitespace)) {
        return Err(format!(
            "both commas and spaces separate numbers in {}: a decimal comma? Write 1.5, not 1,5, \
             and separate columns by spaces or by commas",
            quoted(content.trim())
        ));
    }
    if fields.iter().any(|f| f.is_empty()) {
        return Err(format!("an empty column in {}", quoted(content.trim())));
    }
    Ok(fields)
}

/// Parses the plain point format; `file` names the source in error messages.
///
/// One point `x y` per line, the two numbers separated by spaces, tabs or one comma; `#` starts
/// a comment; blank lines are skipped; LF, CRLF and CR-only line ends all work; a UTF-8
/// byte-order mark is skipped. Refused, with the line:
/// - a single number, or four or more columns (a Triangle `.node` header `n 2 a m` among them);
/// - a line where both commas and spaces separate numbers (`1,5 2`: a decimal comma?);
/// - a word where a number should be, NaN and infinities;
/// - more than [`MAX_POINTS`](crate::MAX_POINTS) points.
///
/// A third column is ignored (files with a constant third column `1` or a depth are common),
/// except when the first column of every line counts 0, 1, 2, … or 1, 2, 3, …: that is the index
/// column of a Triangle `.node` file without its header, and reading it as x would be wrong, so
/// the file is refused (name it `*.node` for [`read_points`] to read it as one).
///
/// The first line that is neither blank nor a comment may be a header: when every column is a
/// name (starts with a letter, `_` or a quote, and is not a number), as in `x y` or `"lon","lat"`,
/// it is skipped.
///
/// ```
/// use condt::{io::parse_points, Point};
/// let pts = parse_points("\u{feff}x y\n# comment\n1 2\r\n3,4,9\r\t5\t6 \r", "example")?;
/// assert_eq!(pts, vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0), Point::new(5.0, 6.0)]);
///
/// let err = parse_points("0 0\n1,5 2\n", "euro.txt").unwrap_err();
/// assert_eq!(err.line, Some(2));
/// assert!(err.to_string().starts_with("euro.txt:2: both commas and spaces"));
///
/// let err = parse_points("1 0.0 0.0\n2 1.0 0.0\n3 0.0 1.0\n", "nodes.txt").unwrap_err();
/// assert_eq!(err.line, Some(1));
/// assert!(err.to_string().contains(".node"));
/// # Ok::<(), condt::io::IoError>(())
/// ```
pub fn parse_points(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let source = Source { file };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut points: Vec<Point> = Vec::new();
    let (mut seen_content, mut first_data_line) = (false, None);
    // Whether every line so far has three columns, the first counting up by one from 0 or 1.
    let mut counts_like_node_indices = true;
    for (number, raw) in numbered_lines(text) {
        let content = raw.split('#').next().unwrap_or("");
        let fields = columns(content).map_err(|message| source.error(number, message))?;
        let Some(&first) = fields.first() else {
            continue;
        };
        if !core::mem::replace(&mut seen_content, true) && fields.iter().all(|f| is_name(f)) {
            continue; // a header
        }
        first_data_line.get_or_insert(number);
        match fields.len() {
            1 => {
                return Err(source.error(
                    number,
                    "expected two coordinates `x y`, found one".to_string(),
                ))
            }
            2 | 3 => {}
            n => {
                let hint = if n == 4 && points.is_empty() {
                    " (a Triangle .node header `count 2 attributes markers`? Name the file \
                     *.node to read it as one)"
                } else {
                    ""
                };
                return Err(source.error(
                    number,
                    format!("expected `x y` and at most one more column, found {n}{hint}"),
                ));
            }
        }
        let (x, y) = (
            source.number(number, first)?,
            source.number(number, fields[1])?,
        );
        if fields.len() == 3 {
            source.number(number, fields[2])?;
        }
        counts_like_node_indices = counts_like_node_indices && fields.len() == 3 && {
            let start = if points.is_empty() { x } else { points[0].x };
            (start == 0.0 || start == 1.0) && x == start + points.len() as f64
        };
        source.push(&mut points, number, Point::new(x, y))?;
    }
    if counts_like_node_indices && points.len() >= 2 {
        let start = points[0].x;
        return Err(source.error(
            first_data_line.unwrap_or(1),
            format!(
                "the first of three columns counts {start}, {}, {}, … like the index column of \
                 a Triangle .node file: name the file *.node to read it as one, or remove the \
                 column",
                start + 1.0,
                start + 2.0
            ),
        ));
    }
    Ok(points)
}

/// Parses a Triangle `.node` file; `file` names the source in error messages.
///
/// The first line that is neither blank nor a comment is the header `count 2 attributes
/// markers` (`markers` 0 or 1); then `count` rows `index x y`, followed by that many attributes
/// and markers, whose indices count up by one from the first (0 or 1, as Triangle allows).
/// Attributes and markers are read and dropped. `#` starts a comment, columns are separated by
/// whitespace. The points are returned in row order: point `i` is the `i`-th row, whatever
/// number the file gives it. Anything else (a missing or extra row or column, a skipped index,
/// a dimension other than 2) is an error naming the line.
///
/// ```
/// use condt::{io::parse_node, Point};
/// let text = "# a triangle\n3 2 1 1\n1 0.0 0.0 7.5 1\n2 1.0 0.0 7.5 1\n3 0.0 1.0 7.5 0\n";
/// let pts = parse_node(text, "tri.node")?;
/// assert_eq!(pts, vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0)]);
///
/// let err = parse_node("2 2 0 0\n0 0 0\n2 1 1\n", "gap.node").unwrap_err();
/// assert_eq!(err.to_string(), "gap.node:3: vertex index 2, expected 1");
/// # Ok::<(), condt::io::IoError>(())
/// ```
pub fn parse_node(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let source = Source { file };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut rows = numbered_lines(text).filter_map(|(number, raw)| {
        let fields: Vec<&str> = raw.split('#').next()?.split_whitespace().collect();
        (!fields.is_empty()).then_some((number, fields))
    });
    let Some((header_line, header)) = rows.next() else {
        return Err(source.error(1, "no header line `count 2 attributes markers`".to_string()));
    };
    let count = |field: &str, what: &str| -> Result<usize, IoError> {
        field.parse::<usize>().map_err(|_| {
            source.error(
                header_line,
                format!("cannot read {} as the {what}", quoted(field)),
            )
        })
    };
    if header.len() != 4 {
        return Err(source.error(
            header_line,
            format!(
                "expected the header `count 2 attributes markers`, found {} columns",
                header.len()
            ),
        ));
    }
    let n = count(header[0], "number of vertices")?;
    let dimension = count(header[1], "dimension")?;
    let attributes = count(header[2], "number of attributes")?;
    let markers = count(header[3], "number of boundary markers")?;
    if dimension != 2 {
        return Err(source.error(
            header_line,
            format!("dimension {dimension}, only 2 is supported"),
        ));
    }
    if markers > 1 {
        return Err(source.error(
            header_line,
            format!("{markers} boundary markers per vertex, Triangle allows 0 or 1"),
        ));
    }
    let columns = 3 + attributes + markers;
    let mut points = Vec::new();
    let mut first_index = None;
    let mut last_line = header_line;
    for (number, fields) in rows {
        last_line = number;
        if points.len() == n {
            return Err(source.error(
                number,
                format!("more vertex rows than the {n} the header announces"),
            ));
        }
        if fields.len() != columns {
            return Err(source.error(
                number,
                format!(
                    "expected {columns} columns (index, x, y, {attributes} attributes, {markers} \
                     markers), found {}",
                    fields.len()
                ),
            ));
        }
        let index: u64 = fields[0].parse().map_err(|_| {
            source.error(
                number,
                format!("cannot read {} as a vertex index", quoted(fields[0])),
            )
        })?;
        let expected = *first_index.get_or_insert(index) + points.len() as u64;
        if index != expected || (points.is_empty() && index > 1) {
            return Err(source.error(
                number,
                if points.is_empty() {
                    format!("first vertex index {index}, expected 0 or 1")
                } else {
                    format!("vertex index {index}, expected {expected}")
                },
            ));
        }
        let (x, y) = (
            source.number(number, fields[1])?,
            source.number(number, fields[2])?,
        );
        for field in &fields[3..] {
            source.number(number, field)?;
        }
        source.push(&mut points, number, Point::new(x, y))?;
    }
    if points.len() < n {
        return Err(source.error(
            last_line,
            format!(
                "the header announces {n} vertices, the file ends after {}",
                points.len()
            ),
        ));
    }
    Ok(points)
}

/// Reads a point file, its format chosen by the name's ending (any case): `.node` a Triangle
/// node file ([`parse_node`]), `.csv` CSV with a header naming the columns
/// ([`parse_csv`](super::parse_csv)), `.geojson` or `.json` the Point and MultiPoint geometries
/// of a GeoJSON document ([`parse_geojson`](super::parse_geojson)), anything else the plain
/// format ([`parse_points`]); `-` reads the plain format from standard input.
///
/// A file that is not UTF-8 text is refused with the line of the first bad byte. A file too
/// large for memory is an error rather than an abort, and so is one with more than
/// [`MAX_POINTS`](crate::MAX_POINTS) points.
///
/// ```no_run
/// let points = condt::io::read_points("examples/data/shapes.txt")?;
/// # Ok::<(), condt::io::IoError>(())
/// ```
pub fn read_points(path: impl AsRef<std::path::Path>) -> Result<Vec<Point>, IoError> {
    let path = path.as_ref();
    let stdin = path.as_os_str() == "-";
    // A name that is not UTF-8 is shown lossily; the file is still opened by its own bytes.
    let shown = path.to_string_lossy();
    let name: &str = if stdin { "<stdin>" } else { &shown };
    let io_error = |err: io::Error| IoError {
        file: name.to_string(),
        line: None,
        kind: IoErrorKind::Io(err),
    };
    let bytes = if stdin {
        read_all(io::stdin().lock(), 0)
    } else {
        let file = File::open(path).map_err(io_error)?;
        let size = file.metadata().map(|m| m.len()).unwrap_or(0);
        read_all(file, size)
    }
    .map_err(io_error)?;
    let text = String::from_utf8(bytes).map_err(|e| IoError {
        file: name.to_string(),
        line: Some(line_at(e.as_bytes(), e.utf8_error().valid_up_to())),
        kind: IoErrorKind::Content("not UTF-8 text".to_string()),
    })?;
    let extension = |wanted: &str| {
        !stdin
            && path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case(wanted))
    };
    if extension("node") {
        parse_node(&text, name)
    } else if extension("csv") {
        super::parse_csv(&text, name)
    } else if extension("geojson") || extension("json") {
        super::parse_geojson(&text, name)
    } else {
        parse_points(&text, name)
    }
}

/// Everything `reader` holds, growing the buffer with `try_reserve` so that a file larger than
/// the memory the system gives is an `OutOfMemory` error instead of an abort. `size` is a hint.
fn read_all(mut reader: impl Read, size: u64) -> io::Result<Vec<u8>> {
    const CHUNK: usize = 1 << 20;
    let too_large = |len: usize| {
        io::Error::new(
            io::ErrorKind::OutOfMemory,
            format!("cannot hold the file in memory (over {len} bytes)"),
        )
    };
    let mut bytes: Vec<u8> = Vec::new();
    let hint = usize::try_from(size).map_err(|_| too_large(usize::MAX))?;
    bytes
        .try_reserve_exact(hint.saturating_add(1))
        .map_err(|_| too_large(hint))?;
    loop {
        if bytes.capacity() - bytes.len() < CHUNK / 16 {
            let more = bytes.len().max(CHUNK);
            bytes
                .try_reserve_exact(more)
                .map_err(|_| too_large(bytes.len() + more))?;
        }
        let room = (bytes.capacity() - bytes.len()) as u64;
        // Reads at most what was reserved, so `read_to_end` never grows the buffer itself.
        if (&mut reader).take(room).read_to_end(&mut bytes)? == 0 {
            return Ok(bytes);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_tokens_are_cut_in_messages() {
        assert_eq!(quoted("abc"), "\"abc\"");
        let long = "9".repeat(10_000_000);
        let message = quoted(&long);
        assert!(message.len() < 80, "{message}");
        assert!(message.ends_with("… (10000000 bytes)"));
        let err = parse_points(&format!("{long}x 1\n"), "big.txt").unwrap_err();
        assert!(err.to_string().len() < 120, "{err}");
    }

    #[test]
    fn line_numbers_count_cr_lf_and_crlf_alike() {
        let bytes = b"a\rb\r\nc\nd\r\re";
        let lines: Vec<usize> = (0..bytes.len()).map(|i| line_at(bytes, i)).collect();
        assert_eq!(lines, [1, 1, 2, 2, 2, 3, 3, 4, 4, 5, 6]);
        let text = core::str::from_utf8(bytes).unwrap();
        let numbered: Vec<(usize, &str)> = numbered_lines(text).collect();
        assert_eq!(
            numbered,
            [(1, "a"), (2, "b"), (3, "c"), (4, "d"), (5, ""), (6, "e")]
        );
    }

    #[test]
    fn reading_stops_at_the_end_without_growing_past_what_it_reserved() {
        let data: Vec<u8> = (0..3 * (1 << 20) + 17).map(|i| (i % 251) as u8).collect();
        assert_eq!(read_all(&data[..], 0).unwrap(), data);
        assert_eq!(read_all(&data[..], data.len() as u64).unwrap(), data);
        assert_eq!(read_all(&data[..], 5).unwrap(), data);
        assert!(read_all(&b""[..], 0).unwrap().is_empty());
    }

    #[test]
    fn an_impossible_size_is_an_out_of_memory_error() {
        let err = read_all(&b"1 2\n"[..], u64::MAX / 2).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::OutOfMemory);
    }
}
