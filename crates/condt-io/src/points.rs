//! Reading point files: the plain `x y` format and Triangle's `.node` format.
//!
//! Both refuse what they cannot read unambiguously, with the file and the line, rather than
//! guess: a Triangle `.node` file under another name, a decimal comma, a fourth column.

use super::{decimal, Columns, InputFormat, IoError, IoErrorKind, PointFile, ReadOptions};
use condt::Point;
use condt::MAX_POINTS;
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

/// Where the text after the line end at `end` begins: past a `\r\n`, `\n` or `\r`, or `end`
/// itself at the end of the text. The one reading of line ends every reader here shares.
#[inline]
fn after_line_end(bytes: &[u8], end: usize) -> usize {
    match bytes.get(end) {
        Some(b'\r') if bytes.get(end + 1) == Some(&b'\n') => end + 2,
        Some(_) => end + 1,
        None => end,
    }
}

/// Splits text into lines at LF, CRLF or a lone CR, numbering them from 1.
pub(super) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut rest = text;
    let mut number = 0;
    core::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        number += 1;
        let end = rest.find(['\n', '\r']).unwrap_or(rest.len());
        let line = &rest[..end];
        rest = &rest[after_line_end(rest.as_bytes(), end)..];
        Some((number, line))
    })
}

/// The lines of a text file as the point readers split them, for other line-based files (the
/// edge files of `condt score`) to be read alike: a UTF-8 byte-order mark at the very start
/// skipped; LF, CRLF and CR-only line ends; each line numbered from 1 as error messages number
/// it, without its line end.
///
/// ```
/// let text = "\u{feff}# edges\r0 1\r\n1 2\n\n2 0";
/// let lines: Vec<(usize, &str)> = condt_io::text_lines(text).collect();
/// assert_eq!(lines, [(1, "# edges"), (2, "0 1"), (3, "1 2"), (4, ""), (5, "2 0")]);
/// ```
pub fn text_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    numbered_lines(text.strip_prefix('\u{feff}').unwrap_or(text))
}

/// The 1-based line holding byte `offset`, with the line ends of [`numbered_lines`].
pub(super) fn line_at(bytes: &[u8], offset: usize) -> usize {
    let ends = bytes[..offset]
        .iter()
        .enumerate()
        .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
        .count();
    1 + ends
}

/// Whether `field` reads as a number once its one comma is a decimal point (`1,5`, `-0,25`):
/// a decimal comma, which no reader here takes.
pub(super) fn is_decimal_comma(field: &str) -> bool {
    field.matches(',').count() == 1 && field.replacen(',', ".", 1).parse::<f64>().is_ok()
}

/// Whether the comma of `field` stands before exactly three digits' place (`1,000`): it may
/// group thousands (an English export) as well as be a decimal comma.
pub(super) fn may_group_thousands(field: &str) -> bool {
    field
        .split_once(',')
        .is_some_and(|(_, after)| after.len() == 3)
}

/// Builds content errors for one file.
pub(super) struct Source<'a> {
    pub(super) file: &'a str,
}

impl Source<'_> {
    pub(super) fn error(&self, line: usize, message: String) -> IoError {
        IoError {
            file: self.file.to_string(),
            line: Some(line),
            kind: IoErrorKind::Content(message),
        }
    }

    pub(super) fn number(&self, line: usize, field: &str) -> Result<f64, IoError> {
        let value = match decimal::parse(field.as_bytes()) {
            Some(value) => value,
            None => field.parse().map_err(|_| {
                // `1,5;2,5` split at its comma: a semicolon-separated export with decimal commas.
                let hint = if field.contains(';') {
                    " (a semicolon does not separate columns, and a comma is no decimal point: \
                     write 1.5 2.5 or 1.5,2.5)"
                } else if is_decimal_comma(field) {
                    // `"1,5"` quoted in a CSV, or `1,5` in a tab-separated column: a European
                    // locale's export, told as the plain format's reader tells it; before three
                    // digits the comma may group thousands (`"1,000"`, an English export).
                    if may_group_thousands(field) {
                        " (a decimal comma, or thousands grouped? Write 1.5 or 1000)"
                    } else {
                        " (a decimal comma? Write 1.5, not 1,5)"
                    }
                } else if field.trim().is_empty() {
                    MISSING_HINT
                } else if field.contains(',')
                    && field.contains('.')
                    && field.replace(',', "").parse::<f64>().is_ok()
                {
                    // Excel's `"1,100.00"` (a number format grouping thousands, quoted in a
                    // CSV): "cannot read" alone did not say what to change.
                    " (thousands grouped by commas? Write 1100.5, not 1,100.5: format the cells \
                     without a thousands separator)"
                } else if is_missing_mark(field) {
                    // R's `NA` (write.csv, readr), Excel's `#N/A` (`#NV` in German): said as
                    // the empty field is (an R user's review: "cannot read" alone).
                    " (a missing value: leave rows without a point out, as R's na.omit does)"
                } else if field.len() > 2
                    && field.starts_with('"')
                    && field.ends_with('"')
                    && field[1..field.len() - 1].parse::<f64>().is_ok()
                {
                    // A plain file keeps its quotes: R's write.table quotes its row names.
                    " (quotes are no part of a number in a plain file; R's write.table quotes \
                     its row names there: write the file with row.names = FALSE)"
                } else {
                    ""
                };
                self.error(
                    line,
                    format!("cannot read {} as a number{hint}", quoted(field)),
                )
            })?,
        };
        if value.is_finite() {
            return Ok(value);
        }
        // A number too large for a double (`1e400`) reads as infinite: not the caller's NaN or
        // infinity, and said so.
        let named = field
            .trim_start_matches(['+', '-'])
            .get(..3)
            .is_some_and(|word| {
                word.eq_ignore_ascii_case("nan") || word.eq_ignore_ascii_case("inf")
            });
        let why = if named {
            // A laser scan exported with its rays that had no return (range inf or NaN, so x
            // and y NaN) is a common layout: say what to do (a robotics user's review).
            "is not finite (leave rows without a point out, as a scanner's rays without a \
             return)"
        } else {
            "is beyond the range of a double (about 1.8e308)"
        };
        Err(self.error(line, format!("coordinate {} {why}", quoted(field))))
    }

    /// Checks a field the reader ignores (`what`: a text file's third column, a `.node`
    /// attribute): any number, NaN and infinities among them (a common mark of a missing depth
    /// or height), but not a word.
    pub(super) fn ignored_number(
        &self,
        line: usize,
        field: &str,
        what: &str,
    ) -> Result<(), IoError> {
        if decimal::parse(field.as_bytes()).is_some() || field.parse::<f64>().is_ok() {
            return Ok(());
        }
        Err(self.error(
            line,
            format!(
                "cannot read {} as a number ({what} is ignored, but must be a number)",
                quoted(field)
            ),
        ))
    }

    /// Appends `p`, refusing more than [`MAX_POINTS`] points or memory the system will not give,
    /// so that a huge file is an error and not an abort.
    #[inline]
    pub(super) fn push(
        &self,
        points: &mut Vec<Point>,
        line: usize,
        p: Point,
    ) -> Result<(), IoError> {
        if points.len() == points.capacity() {
            self.grow(points, line)?;
        }
        points.push(p);
        Ok(())
    }

    #[cold]
    fn grow(&self, points: &mut Vec<Point>, line: usize) -> Result<(), IoError> {
        if points.len() == MAX_POINTS {
            return Err(self.error(
                line,
                format!("more than {MAX_POINTS} points, the most condt accepts"),
            ));
        }
        let more = points.len().max(1024).min(MAX_POINTS - points.len());
        points
            .try_reserve_exact(more)
            .map_err(|_| self.error(line, format!("out of memory after {} points", points.len())))
    }
}

/// Whether `field` is a missing value's mark that spreadsheets and R write (`NA`, `#N/A`,
/// German Excel's `#NV`, `NULL`), quotes aside.
fn is_missing_mark(field: &str) -> bool {
    let bare = field.trim().trim_matches('"');
    ["na", "#n/a", "n/a", "#nv", "null", "missing", "none"]
        .iter()
        .any(|mark| bare.eq_ignore_ascii_case(mark))
}

/// The advice on an empty or NaN coordinate: a row without a point, which a laser scan's rays
/// without a return leave in an export, is the user's to drop.
const MISSING_HINT: &str =
    " (an empty field: leave rows without a point out, as a scanner's rays without a return)";

/// The refusal of a byte-order mark anywhere but at the very start of the file (where every
/// reader skips it), on every path: it is not whitespace, and a reader that skipped it at the
/// start of a line would read a file in pieces differently from one read whole.
pub(super) const BOM_INSIDE: &str =
    "a byte-order mark (U+FEFF) inside the file; it is allowed only at the very start";

/// `true` for a token that names a column (`x`, `lat`, `"y"`) rather than holds a number: it
/// starts with a letter or `_`, quotes aside, and is not a number (`inf`, `NaN`). Nor is it a
/// missing value's marker (`NA`, `None`, `null`) or a value in a wrapper (`np.float64(51.8)`, a
/// decimal number inside): a first line of such words is a point that failed, not a header, and
/// skipping it would drop a row without a word.
fn is_name(token: &str) -> bool {
    let bare = token.trim_matches(|c| c == '"' || c == '\'');
    let missing = ["na", "n/a", "none", "null", "nil", "missing"]
        .iter()
        .any(|marker| bare.eq_ignore_ascii_case(marker));
    let holds_decimal = bare
        .as_bytes()
        .windows(3)
        .any(|w| w[0].is_ascii_digit() && w[1] == b'.' && w[2].is_ascii_digit());
    token.parse::<f64>().is_err()
        && bare.parse::<f64>().is_err()
        && !missing
        && !holds_decimal
        && bare
            .chars()
            .next()
            .is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// A header this format may skip: none of its names contradicts the column it stands over, the
/// first read as x, the second as y (`x y`, `x y z`, `lon lat`, `long lat`, `x_m y`, `a b`).
/// Else (`id x y`, `y x`, `lat lon`) skipping it would read the wrong columns without a word.
fn check_header(fields: &[&str], line: &str) -> Result<(), String> {
    let contradicts = |(column, axis): (usize, Option<char>)| match (column, axis) {
        (_, None) => false,
        (0, Some(axis)) => axis != 'x',
        (1, Some(axis)) => axis != 'y',
        (_, Some(_)) => true,
    };
    let axes = crate::csv::header_axes(fields.iter().copied());
    if !axes.into_iter().enumerate().any(contradicts) {
        return Ok(());
    }
    // The CSV reader splits at commas only: advising `*.csv` for a header of blanks
    // (`angle range x y intensity`, a scanner's export) sent the user to a refusal that
    // advised `*.txt` back. `--columns` follows the names in either (a robotics user's review).
    let csv = if line.contains(',') {
        " (or name the file *.csv, whose reader follows the header)"
    } else {
        ""
    };
    Err(format!(
        "the header {} names x or y over another column than this format reads them from \
         (x the first, y the second); choose the x and y columns by the header's names with \
         condt's --columns X,Y{csv}, or put x and y first",
        quoted(line)
    ))
}

/// The columns of a plain line (comment already removed): separated by whitespace, or by commas
/// alone. A comma next to a field that also holds whitespace is refused: `1,5 2` is either a
/// decimal comma or a typo, and reading it as three columns would be a guess.
pub(super) fn columns(content: &str) -> Result<Vec<&str>, String> {
    if !content.contains(',') {
        return Ok(content.split_whitespace().collect());
    }
    let fields: Vec<&str> = content.split(',').map(str::trim).collect();
    if fields.iter().any(|f| f.contains(char::is_whitespace)) {
        return Err(format!(
            "both commas and blanks separate numbers in {}: a decimal comma? Write 1.5, not 1,5, \
             and separate columns by spaces or by commas",
            quoted(content.trim())
        ));
    }
    if fields.iter().any(|f| f.is_empty()) {
        return Err(format!("an empty column in {}", quoted(content.trim())));
    }
    Ok(fields)
}

/// The first three columns of a line and how many there are, kept without allocating.
#[derive(Clone, Copy)]
struct Row<'a> {
    fields: [&'a str; 3],
    count: usize,
}

impl<'a> Row<'a> {
    fn from_columns(all: &[&'a str]) -> Row<'a> {
        let mut fields = [""; 3];
        for (slot, field) in fields.iter_mut().zip(all) {
            *slot = field;
        }
        Row {
            fields,
            count: all.len(),
        }
    }
}

/// What a byte is to [`scan_line`].
const TOKEN: u8 = 0;
/// ASCII whitespace inside a line (space, tab, vertical tab, form feed: the ASCII characters
/// `char::is_whitespace` accepts, line ends aside).
const BLANK: u8 = 1;
/// `\n`, `\r` or `#`: the end of the columns.
const STOP: u8 = 2;
/// A comma or a non-ASCII byte: the line needs [`columns`].
const OTHER: u8 = 3;

/// The class of every byte, looked up once per byte instead of comparing it with each kind.
const CLASS: [u8; 256] = {
    let mut class = [TOKEN; 256];
    let mut b = 0x80;
    while b < 256 {
        class[b] = OTHER;
        b += 1;
    }
    class[b' ' as usize] = BLANK;
    class[b'\t' as usize] = BLANK;
    class[0x0b] = BLANK;
    class[0x0c] = BLANK;
    class[b'\n' as usize] = STOP;
    class[b'\r' as usize] = STOP;
    class[b'#' as usize] = STOP;
    class[b',' as usize] = OTHER;
    class
};

/// One line of `text` starting at byte `start`: where it ends, where the next one starts, and
/// its columns when the line is plain ASCII without a comma, split here in one pass without
/// allocating; `None` for any other line, which [`columns`] splits instead (the same rules: a
/// comma or non-ASCII whitespace needs them).
#[inline]
fn scan_line(text: &str, start: usize) -> (usize, usize, Option<Row<'_>>) {
    let bytes = text.as_bytes();
    let class = |i: usize| bytes.get(i).map_or(STOP, |&b| CLASS[usize::from(b)]);
    let mut i = start;
    let mut row = Row {
        fields: [""; 3],
        count: 0,
    };
    let mut simple = true;
    loop {
        while class(i) == BLANK {
            i += 1;
        }
        if class(i) == STOP {
            break;
        }
        let token = i;
        loop {
            match class(i) {
                TOKEN => i += 1,
                OTHER => {
                    simple = false;
                    i += 1;
                }
                _ => break,
            }
        }
        if row.count < 3 {
            row.fields[row.count] = &text[token..i];
        }
        row.count += 1;
    }
    // A comment runs to the line end, whatever it holds.
    let mut end = i;
    while end < bytes.len() && !matches!(bytes[end], b'\n' | b'\r') {
        end += 1;
    }
    let next = after_line_end(bytes, end);
    (end, next, simple.then_some(row))
}

/// The common line read in one pass: two or three numbers that [`decimal::parse_prefix`] takes,
/// separated by spaces or tabs, blanks around them allowed, then a line end. Gives `x`, `y`,
/// whether there is a third column, and where the next line starts; `None` for any other line
/// (a comment, a comma, other whitespace, a header, anything `str::parse` must read, an error),
/// which the general path reads from its start again. Every line taken here is one the general
/// path reads as the same point: its columns are tokens by the same splitting, and the numbers
/// are those `Source::number` returns.
///
/// Straight-line code, one step per column rather than a loop over them: each number read and
/// each blank skipped has its own branches, which the processor then predicts from what that
/// column held on the lines before (one blank after `x`, a line end after `y`), where a loop's
/// shared branches alternate. The two coordinates are read by the number reader inlined; the
/// rarer third column by a call.
#[inline(always)]
fn number_line(bytes: &[u8], start: usize) -> Option<(f64, f64, bool, usize)> {
    #[inline(always)]
    fn skip_blanks(mut text: &[u8]) -> &[u8] {
        while let [b' ' | b'\t', rest @ ..] = text {
            text = rest;
        }
        text
    }
    #[inline(always)]
    fn line_end(text: &[u8]) -> bool {
        matches!(text, [] | [b'\n' | b'\r', ..])
    }
    let line = skip_blanks(bytes.get(start..)?);
    let (x, after_x) =
        decimal::parse_prefix_short(line).or_else(|| decimal::parse_prefix_outlined(line))?;
    // A number runs up to a blank (here another column must follow) or the line end: `1.5x`,
    // `2,3` or a single column is for the general path.
    let before_y = skip_blanks(after_x);
    if before_y.len() == after_x.len() {
        return None;
    }
    let (y, after_y) = decimal::parse_prefix_short(before_y)
        .or_else(|| decimal::parse_prefix_outlined(before_y))?;
    let mut rest = skip_blanks(after_y);
    let third = !line_end(rest);
    if third {
        if rest.len() == after_y.len() {
            return None;
        }
        let (_, after_third) = decimal::parse_prefix_outlined(rest)?;
        rest = skip_blanks(after_third);
        // A fourth column, or something glued to the third: the general path reports it.
        if !line_end(rest) {
            return None;
        }
    }
    // `after_line_end` on the rest as a slice pattern: the same reading without its bounds
    // checks, 2 % of the instructions of a parse on this, the hot path.
    let end = bytes.len() - rest.len();
    let next = match rest {
        [b'\r', b'\n', ..] => end + 2,
        [_, ..] => end + 1,
        [] => end,
    };
    Some((x, y, third, next))
}

/// The points of the lines from byte `start` that [`number_line`] reads, appended to `points`
/// while it has room: where the first other line (or the end of the text) starts, and how many
/// lines were read. Clears `all_three_columns` at a line of two columns. One call for a whole
/// run of lines, so that the loop keeps its state in registers.
#[inline(never)]
fn number_lines(
    bytes: &[u8],
    mut start: usize,
    points: &mut Vec<Point>,
    all_three_columns: &mut bool,
) -> (usize, usize) {
    let before = points.len();
    let mut all_three = *all_three_columns;
    while start < bytes.len() && points.len() < points.capacity() {
        let Some((x, y, third, next)) = number_line(bytes, start) else {
            break;
        };
        points.push(Point::new(x, y));
        all_three &= third;
        start = next;
    }
    *all_three_columns = all_three;
    (start, points.len() - before)
}

/// What one stretch of lines of a plain point file holds.
struct Parsed {
    points: Vec<Point>,
    /// Whether every data line has exactly three columns (see [`node_index_column`]).
    all_three_columns: bool,
    /// The first line that holds a point, numbered within the stretch.
    first_data_line: Option<usize>,
    /// Whether any line holds a column (a header or a point); only the parallel parse, which
    /// must know whether its first piece held the file's first line with columns, asks.
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    seen_content: bool,
    /// Whether the stretch starts with Octave's text workspace header (`# Created by Octave`):
    /// its variables' names are comments only this stretch's parse counts, so the file is
    /// read whole ([`OCTAVE_VARIABLES`]).
    octave: bool,
    /// The line skipped as a header, if any: its number, and whether it names x and y over
    /// the first two columns (`x y`, `lon lat`), which alone makes a file with no point after
    /// it an empty point file rather than some other text ([`header_alone`]).
    header: Option<(usize, bool)>,
}

/// Parses the lines of `text` (a whole file, or whole lines of one; numbered from 1) into
/// points with the rules of [`parse_points`] but the last (the index-column check, which needs
/// every point). `may_hold_header`: the first line with columns may be a header (it is the
/// file's first). `expected_points` sizes the first allocation.
fn parse_lines(
    text: &str,
    source: &Source<'_>,
    may_hold_header: bool,
    expected_points: usize,
) -> Result<Parsed, IoError> {
    lines_by::<true>(text, source, may_hold_header, expected_points)
}

/// [`parse_lines`], with [`number_line`] trying each line first (`ONE_PASS`) or not: the tests
/// compare the two.
fn lines_by<const ONE_PASS: bool>(
    text: &str,
    source: &Source<'_>,
    may_hold_header: bool,
    expected_points: usize,
) -> Result<Parsed, IoError> {
    let mut points: Vec<Point> = Vec::new();
    if expected_points > 0 {
        // Only a hint: a refusal here leaves `push` to grow and report.
        let _ = points.try_reserve_exact(expected_points.min(MAX_POINTS));
    }
    let mut seen_content = !may_hold_header;
    let mut header = None;
    // The header's number of names until the first row after it has been compared with it
    // ([`row_names_error`]); the one-pass reader leaves that row to the general path.
    let mut header_names: Option<usize> = None;
    // Octave's `save` writes a text workspace by default (`# name: M`, `# type: matrix`, then
    // the rows): one n-by-2 matrix reads right, but a second variable's rows joined the
    // first's points without a word (an R and MATLAB user's review).
    let octave = may_hold_header && text.starts_with("# Created by Octave");
    let mut octave_names = 0;
    let mut first_data_line = None;
    let mut all_three_columns = true;
    let (mut start, mut number) = (0, 0);
    while start < text.len() {
        if ONE_PASS && header_names.is_none() {
            // What the general path below does with the common lines, in one pass over their
            // bytes, up to the first line it leaves to the general path (or the end, or a full
            // vector, which `Source::push` grows or refuses).
            let (next, read) =
                number_lines(text.as_bytes(), start, &mut points, &mut all_three_columns);
            if read > 0 {
                seen_content = true;
                first_data_line.get_or_insert(number + 1);
                number += read;
                start = next;
                if start >= text.len() {
                    break;
                }
            }
        }
        number += 1;
        let (end, next, simple) = scan_line(text, start);
        let line = &text[start..end];
        start = next;
        if octave && line.starts_with("# name:") {
            octave_names += 1;
            if octave_names == 2 {
                return Err(source.error(
                    number,
                    format!("{OCTAVE_VARIABLES} ({})", quoted(line.trim())),
                ));
            }
        }
        let row = match simple {
            // The first line with columns may be a header, which needs all of them.
            Some(row) if seen_content || row.count == 0 => row,
            _ => {
                let content = line.split('#').next().unwrap_or("");
                if content.contains('\u{feff}') {
                    return Err(source.error(number, BOM_INSIDE.to_string()));
                }
                let fields = columns(content).map_err(|message| source.error(number, message))?;
                if fields.is_empty() {
                    continue;
                }
                if !core::mem::replace(&mut seen_content, true) && fields.iter().all(|f| is_name(f))
                {
                    check_header(&fields, content.trim())
                        .map_err(|message| source.error(number, message))?;
                    header = Some((number, names_x_and_y(&fields)));
                    header_names = Some(fields.len());
                    continue; // a header
                }
                Row::from_columns(&fields)
            }
        };
        if row.count > 0 {
            if let (Some(names), Some((header_line, _))) = (header_names.take(), header) {
                // A single word over two columns is a title more likely than R's output (a
                // data frame of one column is no point file), and a coordinate under `x y` is
                // a third column the header leaves unnamed (`x y` over `x y z`): read on.
                if names >= 2 && row.count == names + 1 && may_be_row_name(row.fields[0]) {
                    return Err(row_names_error(source, number, row.count, header_line));
                }
            }
        }
        match row.count {
            0 => continue,
            1 => {
                // Found by a fuzzer: `1;0` said only "found one".
                let control = line
                    .chars()
                    .find(|c| c.is_control() && !matches!(c, '\t' | '\r'));
                let hint = if octave {
                    // `save('w.mat', 'x', 'y')` of two column vectors: one number a row.
                    " (an Octave text workspace of one column: save the points as one n-by-2 \
                     matrix, [x y], alone)"
                        .into()
                } else if line.contains(';') {
                    " (a semicolon does not separate columns: spaces, tabs or one comma do)".into()
                } else if let Some(c) = control {
                    // A NUL or Ctrl-Z line shows as nothing in a terminal: name what is there.
                    format!(" (the line holds the control character U+{:04X})", c as u32)
                } else {
                    String::new()
                };
                return Err(source.error(
                    number,
                    format!("expected two coordinates `x y`, found one{hint}"),
                ));
            }
            2 | 3 => {}
            n => {
                // A `.node` header is four whole numbers, the second 2; other rows of four or
                // more columns are an export with more than coordinates (`x y z intensity`).
                let node_header = n == 4
                    && may_hold_header
                    && points.is_empty()
                    && header.is_none()
                    && row.fields[1] == "2"
                    && line
                        .split('#')
                        .next()
                        .unwrap_or("")
                        .split_whitespace()
                        .all(|f| f.parse::<u64>().is_ok());
                let hint = if node_header {
                    " (a Triangle .node header `count 2 attributes markers`? Name the file \
                     *.node, or state condt's --input-format node, to read it as one)"
                } else {
                    " (choose the x and y columns by number or by the header's names with \
                     condt's --columns X,Y)"
                };
                return Err(source.error(
                    number,
                    format!("expected `x y` and at most one more column, found {n}{hint}"),
                ));
            }
        }
        first_data_line.get_or_insert(number);
        let [first, second, third] = row.fields;
        let (x, y) = (
            source.number(number, first)?,
            source.number(number, second)?,
        );
        if row.count == 3 {
            source.ignored_number(number, third, "a third column")?;
        }
        all_three_columns &= row.count == 3;
        source.push(&mut points, number, Point::new(x, y))?;
    }
    Ok(Parsed {
        points,
        all_three_columns,
        first_data_line,
        seen_content,
        octave,
        header,
    })
}

/// The refusal of a first row after the header with one column more than the header names:
/// R's `write.table` writes its row names so (`x y` over `1 1100 2000.5`, quoted or not), and
/// reading on would take the row names for x and x for y (an R user's review: a circle and a
/// square came back as 98 edges on the points (row number, x), with exit 0). A header one name
/// short of its rows says nothing of which column lacks its name: refused, never guessed.
fn row_names_error(source: &Source<'_>, line: usize, count: usize, header: usize) -> IoError {
    source.error(
        line,
        format!(
            "{count} columns, but the header on line {header} names {}{ROW_NAMES} (or name every \
             column in the header)",
            count - 1
        ),
    )
}

/// What a first row one column wider than its header may be, said by the plain and CSV readers.
pub(crate) const ROW_NAMES: &str = ": which column has no name? R's write.table writes row \
                                    names so, as a first column without a name; write the file \
                                    with row.names = FALSE";

/// Whether `field`, the first of a row one column wider than the header names, may be the row
/// name R's `write.table` writes there: quoted (its default), not a number (names of its own),
/// or the first row's number, `1`. Any other number is a coordinate: an `x y` header over rows
/// of `x y z` (a height, an intensity: a third column the plain reader ignores) was read as
/// its first two columns, and is still.
pub(crate) fn may_be_row_name(field: &str) -> bool {
    let field = field.trim();
    field == "1" || field.starts_with('"') || field.parse::<f64>().is_err()
}

/// Whether a header's first two names are x and y (`x y`, `X Y z`, `lon lat`, `"lng","lat"`).
fn names_x_and_y(fields: &[&str]) -> bool {
    matches!(
        crate::csv::header_axes(fields.iter().copied())[..],
        [Some('x'), Some('y'), ..]
    )
}

/// The refusal of a file whose only line with columns was taken for a header that does not
/// name x and y (`Error: file not found`, a log line, a title): with no point after it, nothing
/// says it is a point file at all, and reading it as an empty one would hide the mistake.
fn header_alone(source: &Source<'_>, text: &str, line: usize) -> IoError {
    let shown = numbered_lines(text)
        .find(|&(number, _)| number == line)
        .map_or("", |(_, l)| l.split('#').next().unwrap_or("").trim());
    source.error(
        line,
        format!(
            "no point: line {line} is not a point ({}), and no point follows it; a file \
             without points may hold a header only when it names the x and y columns (`x y`)",
            quoted(shown)
        ),
    )
}

/// The start of an index column, when the first of three columns counts 0, 1, 2, … or
/// 1, 2, 3, … on every line (at least two): that is a Triangle `.node` file without its header.
/// `pieces` are the parsed stretches of one file, in order. A header that names the first two
/// columns x and y (`x y z` over a profile's stations 1, 2, 3, …) says what they are: no guess.
fn node_index_column(pieces: &[Parsed]) -> Option<f64> {
    if pieces
        .first()?
        .header
        .is_some_and(|(_, names_x_and_y)| names_x_and_y)
    {
        return None;
    }
    let start = pieces.iter().find_map(|p| p.points.first())?.x;
    let total: usize = pieces.iter().map(|p| p.points.len()).sum();
    let counts = pieces.iter().all(|p| p.all_three_columns)
        && total >= 2
        && (start == 0.0 || start == 1.0)
        && pieces
            .iter()
            .flat_map(|p| &p.points)
            .enumerate()
            .all(|(i, p)| p.x == start + i as f64);
    counts.then_some(start)
}

/// The error for a file whose first column is an index column counting from `start`.
fn index_column_error(source: &Source<'_>, line: usize, start: f64) -> IoError {
    source.error(
        line,
        format!(
            "the first of three columns counts {start}, {}, {}, … like the index column of \
             a Triangle .node file: name the file *.node (or state condt's --input-format node) \
             to read it as one, or remove the column",
            start + 1.0,
            start + 2.0
        ),
    )
}

/// A guess at the number of points in `text` from the length of its first lines, so that the
/// points are allocated once instead of grown by copying (a guess 5 % high, as line lengths
/// vary; at worst the vector grows or has some room left).
fn expected_points(text: &str) -> usize {
    const SAMPLE: usize = 4096;
    if text.len() <= SAMPLE {
        return 0;
    }
    let mut cut = SAMPLE;
    while !text.is_char_boundary(cut) {
        cut -= 1;
    }
    let lines = text.as_bytes()[..cut]
        .iter()
        .filter(|&&b| b == b'\n')
        .count();
    if lines < 16 {
        return 0;
    }
    let per_line = cut / lines;
    (text.len() / per_line).saturating_add(text.len() / per_line / 20)
}

/// Parses the plain point format; `file` names the source in error messages.
///
/// One point `x y` per line, the two numbers separated by spaces, tabs or one comma; `#` starts
/// a comment; blank lines are skipped; LF, CRLF and CR-only line ends all work; a UTF-8
/// byte-order mark at the very start is skipped. Refused, with the line:
/// - a byte-order mark anywhere else (outside a comment);
/// - a single number, or four or more columns (a Triangle `.node` header `n 2 a m` among them);
/// - a line where both commas and blanks (spaces or tabs) separate numbers (`1,5 2`: a decimal comma?);
/// - a word where a number should be, NaN and infinities;
/// - more than [`MAX_POINTS`](condt::MAX_POINTS) points.
///
/// A third column is ignored (files with a constant third column `1` or a depth are common; it
/// may be NaN or infinite, a missing depth's mark, but must be a number),
/// except when the first column of every line counts 0, 1, 2, … or 1, 2, 3, …: that is the index
/// column of a Triangle `.node` file without its header, and reading it as x would be wrong, so
/// the file is refused (name it `*.node` for [`read_points`] to read it as one), unless a
/// header names the first two columns x and y (`x y z` over a profile's stations 1, 2, 3, …).
///
/// The first line that is neither blank nor a comment may be a header: when every column is a
/// name (starts with a letter, `_` or a quote, and is not a number), as in `x y` or `"lon","lat"`,
/// it is skipped. A header that names x and y (`x`, `lon`, `lng`, `long`, `longitude`; `y`, `lat`,
/// `latitude`) anywhere but in the first two columns, in that order, is refused: the points
/// would be read from the wrong columns (`id x y`, `y x`). A file with no point after its header
/// is an empty point file only when the header names x and y over the first two columns (`x y`,
/// `lon lat`); any other line alone (`Error: file not found`) is refused, naming it: nothing
/// then says the file holds points at all.
///
/// ```
/// use condt_io::parse_points;
/// let err = parse_points("id x y\n7 0 0\n9 1 0\n", "ids.txt").unwrap_err();
/// assert!(err.to_string().starts_with("ids.txt:1: the header \"id x y\" names x or y over"));
/// assert!(parse_points("x y z\n0.5 0 5\n2.5 1 5\n", "xyz.txt").is_ok());
/// assert!(parse_points("# none yet\nx y\n", "empty.txt")?.is_empty());
/// let err = parse_points("Error: file not found\n", "err.txt").unwrap_err();
/// assert!(err.to_string().starts_with("err.txt:1: no point: line 1 is not a point"));
/// # Ok::<(), condt_io::IoError>(())
/// ```
///
/// With the `parallel` feature a large text is parsed in pieces on rayon's threads; the points,
/// and the error for a bad file, are the same as without it.
///
/// ```
/// use condt::Point;
/// use condt_io::parse_points;
/// let pts = parse_points("\u{feff}x y\n# comment\n1 2\r\n3,4,9\r\t5\t6 \r", "example")?;
/// assert_eq!(pts, vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0), Point::new(5.0, 6.0)]);
///
/// let err = parse_points("0 0\n1,5 2\n", "euro.txt").unwrap_err();
/// assert_eq!(err.line, Some(2));
/// assert!(err.to_string().starts_with("euro.txt:2: both commas and blanks"));
///
/// let err = parse_points("1 0.0 0.0\n2 1.0 0.0\n3 0.0 1.0\n", "nodes.txt").unwrap_err();
/// assert_eq!(err.line, Some(1));
/// assert!(err.to_string().contains(".node"));
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn parse_points(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    #[cfg(feature = "parallel")]
    if let Some(points) = parallel::parse_pieces(text, file).and_then(parallel::join) {
        return Ok(points);
    }
    parse_points_sequentially(text, file)
}

/// [`parse_points`] on one thread (the byte-order mark already removed): the reference the
/// parallel parse falls back on for every error.
fn parse_points_sequentially(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let source = Source { file };
    let parsed = parse_lines(text, &source, true, expected_points(text))?;
    if let (true, Some((line, false))) = (parsed.points.is_empty(), parsed.header) {
        return Err(header_alone(&source, text, line));
    }
    if let Some(start) = node_index_column(core::slice::from_ref(&parsed)) {
        let line = parsed.first_data_line.unwrap_or(1);
        return Err(index_column_error(&source, line, start));
    }
    Ok(parsed.points)
}

#[cfg(feature = "parallel")]
mod parallel;

/// Parses a Triangle `.node` file; `file` names the source in error messages.
///
/// The first line that is neither blank nor a comment is the header `count 2 attributes
/// markers` (`markers` 0 or 1; as Triangle reads it, the fields after `count` may be left
/// out, dimension 2, 0 attributes and 0 markers); then `count` rows `index x y`, followed by that many attributes
/// and markers, whose indices count up by one from the first (0 or 1, as Triangle allows).
/// Attributes and markers are read and dropped. `#` starts a comment, columns are separated by
/// whitespace. The points are returned in row order: point `i` is the `i`-th row, whatever
/// number the file gives it. Anything else (a missing or extra row or column, a skipped index,
/// a dimension other than 2) is an error naming the line.
///
/// ```
/// use condt::Point;
/// use condt_io::parse_node;
/// let text = "# a triangle\n3 2 1 1\n1 0.0 0.0 7.5 1\n2 1.0 0.0 7.5 1\n3 0.0 1.0 7.5 0\n";
/// let pts = parse_node(text, "tri.node")?;
/// assert_eq!(pts, vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0)]);
///
/// // Triangle's defaults for the fields after the count: dimension 2, no attributes or markers.
/// assert_eq!(parse_node("2\n0 0 0\n1 1 1\n", "short.node")?.len(), 2);
/// let err = parse_node("2 2 0 0\n0 0 0\n2 1 1\n", "gap.node").unwrap_err();
/// assert_eq!(err.to_string(), "gap.node:3: vertex index 2, expected 1");
/// # Ok::<(), condt_io::IoError>(())
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
    if header.len() > 4 {
        return Err(source.error(
            header_line,
            format!(
                "expected the header `count 2 attributes markers`, found {} columns",
                header.len()
            ),
        ));
    }
    // Fields left out take Triangle's defaults: dimension 2, no attributes, no markers.
    let field = |k: usize, default: usize, what: &str| match header.get(k) {
        Some(field) => count(field, what),
        None => Ok(default),
    };
    let n = count(header[0], "number of vertices")?;
    let dimension = field(1, 2, "dimension")?;
    let attributes = field(2, 0, "number of attributes")?;
    let markers = field(3, 0, "number of boundary markers")?;
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
    // Index, x, y, then the attributes and markers; a count no row could hold is refused here
    // rather than wrapped around.
    let Some(columns) = attributes.checked_add(3 + markers) else {
        return Err(source.error(
            header_line,
            format!("{attributes} attributes per vertex is more than a row can hold"),
        ));
    };
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
            source.ignored_number(number, field, "an attribute or marker")?;
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
/// node file ([`parse_node`]), `.npy` a NumPy array ([`parse_npy`](super::parse_npy), read in
/// blocks straight into the points), `.csv` CSV with a header naming the columns
/// ([`parse_csv`](super::parse_csv)), `.tsv` the same with tabs between columns (two numbers a
/// line: the plain format), `.geojson` or `.json` the Point and MultiPoint geometries
/// of a GeoJSON document ([`parse_geojson`](super::parse_geojson)), `.geojsonl` or `.geojsons`
/// those of a GeoJSON sequence, one object per line
/// ([`InputFormat::GeoJsonLines`](super::InputFormat::GeoJsonLines)); `-` reads standard input.
/// Standard input and a name with any other ending, or none, are told by their content: a NumPy
/// array, a GeoJSON document or a GeoJSON sequence (the `.npy` magic bytes, a leading `{`, a
/// leading record separator U+001E), the plain format ([`parse_points`]) otherwise
/// ([`read_points_with`] reads a file, or standard input, in a format stated instead).
///
/// A text file that is not UTF-8 is refused with the line of the first bad byte. A file too
/// large for memory is an error rather than an abort, and so is one with more than
/// [`MAX_POINTS`](condt::MAX_POINTS) points.
///
/// ```no_run
/// let points = condt_io::read_points("data/shapes.txt")?;
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn read_points(path: impl AsRef<std::path::Path>) -> Result<Vec<Point>, IoError> {
    read_points_with_crs(path).map(|(points, _)| points)
}

/// [`read_points`], and a GeoJSON input's `"crs"` member as written
/// ([`parse_geojson_with_crs`](super::parse_geojson_with_crs); `None` for the other formats).
///
/// ```no_run
/// let (points, crs) = condt_io::read_points_with_crs("coast.geojson")?;
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn read_points_with_crs(
    path: impl AsRef<std::path::Path>,
) -> Result<(Vec<Point>, Option<String>), IoError> {
    read_points_with(path, &ReadOptions::default()).map(|file| (file.points, file.crs))
}

/// [`read_points`] as `options` say: in the format they state whatever the name
/// ([`ReadOptions::with_format`]; standard input, which has no name, is then read in that format
/// instead of by its content), and from the x and y columns they choose
/// ([`ReadOptions::with_columns`]: a CSV, TSV or plain text file only, refused before reading for a file
/// whose name or stated format is another; standard input is then read as CSV). Gives the
/// points and what else the file said ([`PointFile`]).
///
/// ```
/// use condt::Point;
/// use condt_io::{read_points_with, Columns, InputFormat, ReadOptions};
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("table.txt");
/// std::fs::write(&path, "id,lat,lon\n7,47.5,8.25\n")?;
/// // By its name, the plain format: a header naming x and y elsewhere is refused.
/// assert!(condt_io::read_points(&path).is_err());
/// let read = read_points_with(&path, &ReadOptions::new().with_format(InputFormat::Csv))?;
/// assert_eq!(read.points, vec![Point::new(8.25, 47.5)]);
/// assert_eq!(read.crs, None);
///
/// let path = dir.path().join("survey.csv");
/// std::fs::write(&path, "FID,POINT_X,POINT_Y\n1,2600000.5,1200000\n")?;
/// let columns = Columns::parse("POINT_X,POINT_Y")?;
/// let read = read_points_with(&path, &ReadOptions::new().with_columns(columns))?;
/// assert_eq!(read.points, vec![Point::new(2600000.5, 1200000.0)]);
/// let columns = Columns::parse("easting,northing")?;
/// let err = read_points_with(&path, &ReadOptions::new().with_columns(columns)).unwrap_err();
/// assert!(err.to_string().ends_with(":1: no column named \"easting\" (chosen for x) in the \
///     header \"FID,POINT_X,POINT_Y\"; its columns are \"FID\", \"POINT_X\", \"POINT_Y\""));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_points_with(
    path: impl AsRef<std::path::Path>,
    options: &ReadOptions,
) -> Result<PointFile, IoError> {
    let without_crs = |points| PointFile {
        points,
        ..PointFile::default()
    };
    let path = path.as_ref();
    let stdin = path.as_os_str() == "-";
    // A name that is not UTF-8 is shown lossily; the file is still opened by its own bytes.
    let shown = path.to_string_lossy();
    let name: &str = if stdin { "<stdin>" } else { &shown };
    let io_error = |err: io::Error| IoError::os(name, err);
    // `None`: standard input, told by its content below.
    let format = options.format.or_else(|| InputFormat::of_path(path));
    let columns_refused = |what: &str| IoError {
        file: name.to_string(),
        line: None,
        kind: IoErrorKind::Content(format!(
            "columns ({}) are chosen only in CSV, TSV and plain text input, and this is read as \
             {what}",
            options
                .columns
                .as_ref()
                .map_or(String::new(), |c| c.to_string())
        )),
    };
    if let Some(why) = options.columns.as_ref().and_then(Columns::problem) {
        let columns = options
            .columns
            .as_ref()
            .map_or(String::new(), |c| c.to_string());
        return Err(IoError {
            file: name.to_string(),
            line: None,
            kind: IoErrorKind::Content(format!("columns {columns}: {why}")),
        });
    }
    if let (Some(format), Some(_)) = (format, &options.columns) {
        if !matches!(
            format,
            InputFormat::Csv | InputFormat::Tsv | InputFormat::Text
        ) {
            return Err(columns_refused(&format!("the {} format", format.name())));
        }
    }
    if !stdin && format == Some(InputFormat::Npy) {
        return super::npy::read_npy_file(path, name).map(without_crs);
    }
    let bytes = if stdin {
        read_all(io::stdin().lock(), 0)
    } else {
        let file = File::open(path).map_err(io_error)?;
        let meta = file.metadata().ok();
        let size = meta.as_ref().map_or(0, |m| m.len());
        #[cfg(all(feature = "parallel", unix))]
        if format == Some(InputFormat::Text)
            && options.columns.is_none()
            && meta.as_ref().is_some_and(|m| m.is_file())
        {
            if let Some(points) = parallel::read_pieces(&file, size, name) {
                // A header is on the first line: its first kilobytes say whether it names
                // longitude and latitude.
                let mut head = [0u8; 4096];
                let got = std::os::unix::fs::FileExt::read_at(&file, &mut head, 0).unwrap_or(0);
                unchanged_since_opened(&file, meta.as_ref()).map_err(io_error)?;
                let head = String::from_utf8_lossy(&head[..got]);
                return Ok(PointFile {
                    degrees: crate::csv::names_degrees(crate::csv::first_line_with_content(&head)),
                    ..without_crs(points)
                });
            }
        }
        // `read_pieces` reads at offsets: the file is still at its start.
        read_all(&file, size)
            .and_then(|bytes| unchanged_since_opened(&file, meta.as_ref()).map(|()| bytes))
    }
    .map_err(io_error)?;
    // Standard input has no name to tell its format: a NumPy array, a GeoJSON document and a
    // GeoJSON sequence are told by their content (the magic bytes, which are not UTF-8; a `{` or
    // a record separator, which no point line starts with), anything else is read as text.
    // A name with no ending of a format (`/dev/stdin`, `/dev/fd/63` of a shell's `<(...)`) says
    // nothing either: an array there is told by its magic bytes too, which no text starts with.
    let unnamed = options.format.is_none()
        && path
            .extension()
            .and_then(|e| e.to_str())
            .and_then(InputFormat::named)
            .is_none();
    let npy = bytes.starts_with(super::npy::NPY_MAGIC) && (format.is_none() || unnamed);
    if npy && options.columns.is_some() {
        return Err(columns_refused("a NumPy array (by its magic bytes)"));
    }
    if format == Some(InputFormat::Npy) || npy {
        return super::npy::parse_npy(&bytes, name).map(without_crs);
    }
    if let Some(format) = format.filter(|_| bytes.starts_with(super::npy::NPY_MAGIC)) {
        let advice = if options.format.is_some() {
            "as its stated format: state condt's --input-format npy"
        } else {
            "by its name: name it *.npy or state condt's --input-format npy"
        };
        return Err(IoError {
            file: name.to_string(),
            line: None,
            kind: IoErrorKind::Content(format!(
                "a NumPy .npy array (by its magic bytes), but read as {} {advice}",
                format.name()
            )),
        });
    }
    // A UTF-16 byte order mark (Windows tools' "Unicode" text): no reader can make sense of the
    // bytes after it, so the error says what the file is (a GIS user's review).
    let utf16 = bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]);
    // A zip archive, NumPy's `.npz` above all: "not UTF-8 text" alone sent a Python user looking
    // for an encoding. An empty archive starts with its end record (`numpy.savez()` of nothing).
    let zip = bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06");
    // A workspace MATLAB or Octave saves without -ascii (a MAT-file's text header, or Octave's
    // own binary format), a legacy Excel workbook (an OLE2 compound file): a MAT-file was
    // refused for "both commas and blanks" in its header, a decimal comma? (an R and MATLAB
    // user's review).
    let workspace = [
        (&b"MATLAB 5.0 MAT-file"[..], MAT_FILE),
        (b"MATLAB 7.3 MAT-file", MAT_FILE),
        (b"Octave-1-L\0", MAT_FILE),
        (b"Octave-1-B\0", MAT_FILE),
        (b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", XLS_FILE),
    ]
    .into_iter()
    .find_map(|(magic, what)| bytes.starts_with(magic).then_some(what));
    // A compressed file, by its magic bytes: said so, with how to read it (a newcomer's review:
    // a gzip file was only "not UTF-8 text").
    let compressed = [
        (&b"\x1f\x8b"[..], "gzip", "gunzip -c"),
        (b"BZh", "bzip2", "bunzip2 -c"),
        (b"\xfd7zXZ\x00", "xz", "xz -dc"),
        (b"\x28\xb5\x2f\xfd", "zstd", "zstd -dc"),
    ]
    .into_iter()
    .find(|(magic, _, _)| bytes.starts_with(magic));
    // Bytes that are not UTF-8 where nothing is read (a comment, a column not chosen, a GeoJSON
    // property: a Latin-1 or CP1252 export) do not matter; where a field that is read holds
    // them, the file is refused as not UTF-8 text, at that line.
    let mut bytes = bytes;
    blank_cloudcompare_header_mark(&mut bytes);
    let (text, not_utf8) = lossy_text(bytes);
    // Told before the readers take the text; GeoJSON tells its own by its crs.
    let named_degrees = options.columns.as_ref().map_or_else(
        || crate::csv::names_degrees(crate::csv::first_line_with_content(&text)),
        crate::csv::columns_degrees,
    );
    let read = (|| -> Result<PointFile, IoError> {
        if let Some(columns) = &options.columns {
            let starts_like_json = text
                .trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n'])
                .starts_with(['{', '\u{1e}']);
            return match format {
                Some(InputFormat::Tsv) => {
                    crate::csv::parse_separated(&text, name, b'\t', Some(columns))
                }
                Some(InputFormat::Text) => crate::csv::parse_plain_columns(&text, name, columns),
                None if starts_like_json => Err(columns_refused(
                    "GeoJSON (by its leading `{` or record separator)",
                )),
                // CSV, named or stated, or standard input that is neither .npy nor GeoJSON (the
                // other formats are refused above).
                _ => crate::csv::parse_csv_columns(&text, name, Some(columns)),
            }
            .map(without_crs);
        }
        let start = text.trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n']);
        // A JSON array is no point line, nor GeoJSON (one object): say what is read instead of
        // refusing its first bracket as a number.
        if start.starts_with('[') && matches!(format, None | Some(InputFormat::Text)) {
            let line = text_lines(&text)
                .find(|(_, line)| !line.trim_start_matches('\u{feff}').trim().is_empty())
                .map_or(1, |(number, _)| number);
            return Err(IoError {
                file: name.to_string(),
                line: Some(line),
                kind: IoErrorKind::Content(
                    "a JSON array, which is no point file: GeoJSON is one object (a \
                     FeatureCollection, or a MultiPoint, for many points), or one object per \
                     line in a GeoJSON sequence (condt's --input-format geojsonl)"
                        .to_string(),
                ),
            });
        }
        // A name with no ending of a format says no more for GeoJSON than for an array: a `{` or
        // a record separator, which no point line starts with, tells it there too.
        let format = format.filter(|_| !unnamed).unwrap_or_else(|| {
            if start.starts_with('{') {
                InputFormat::GeoJson
            } else if start.starts_with('\u{1e}') {
                // RFC 8142's record separator, which no point line starts with: a GeoJSON sequence.
                InputFormat::GeoJsonLines
            } else {
                InputFormat::Text
            }
        });
        match format {
            InputFormat::Text if stdin && options.format.is_none() => {
                // A CSV table on standard input, which has no name to say so, is read as plain
                // text; when that refuses it and its first line has commas, say how to read it as
                // CSV (the refused line may be a later one: a header of names passes as a title).
                let first = text_lines(&text)
                    .find(|(_, line)| !line.split('#').next().unwrap_or("").trim().is_empty())
                    .filter(|(_, line)| line.contains(','))
                    .map(|(number, _)| number);
                parse_owned_points(text, name)
                    .map(without_crs)
                    .map_err(|mut err| {
                        // A decimal comma's refusal is not a CSV table's: its own advice stands.
                        if let (IoErrorKind::Content(message), true) =
                            (&mut err.kind, first.is_some())
                        {
                            if message.contains("decimal comma") {
                                return err;
                            }
                            message.push_str(
                                "; standard input has no name ending in .csv: state its format to \
                                 read it as CSV (condt's --input-format csv)",
                            );
                        }
                        err
                    })
            }
            InputFormat::Text => {
                // GeoJSON under a text name (`.txt`): the text reader's refusal of its first
                // line would talk of separators; say what it looks like instead.
                let like_geojson = start.starts_with(['{', '\u{1e}']);
                parse_owned_points(text, name)
                    .map(without_crs)
                    .map_err(|mut err| {
                        if let (IoErrorKind::Content(message), true) = (&mut err.kind, like_geojson)
                        {
                            *message = format!(
                                "{message}; the file starts as GeoJSON does (a `{{` or a record \
                                 separator): name it *.geojson (*.geojsonl for a sequence) or \
                                 state condt's --input-format geojson"
                            );
                        }
                        err
                    })
            }
            InputFormat::Node => parse_node(&text, name).map(without_crs),
            InputFormat::Csv => super::parse_csv(&text, name).map(without_crs),
            InputFormat::Tsv => {
                // Tabs by the name. A header on the first line with content (names only, as the
                // plain reader tells one, or x and y columns named as the CSV reader's header
                // names them among any others: `id lon lat 2020`) goes to the CSV reader; else the
                // plain format reads it, which takes comments, blanks and empty fields, but its
                // lines with tabs between values are split at tabs ([`tab_separated_lines`]):
                // three numbers or more are refused, as the README says of CSV (an `id x y`
                // export read as `x y z` came back as wrong points, a newcomer's review). The
                // header line is split at tabs, as the CSV reader splits it: a name may hold
                // blanks (`elevation (m)`), which are no columns.
                let first = tab_fields(crate::csv::first_line_with_content(&text));
                let header = !first.is_empty()
                    && (first.iter().all(|f| is_name(f))
                        || crate::csv::names_x_and_y_columns(first.iter().copied()));
                if header {
                    crate::csv::parse_separated(&text, name, b'\t', None).map(without_crs)
                } else {
                    tab_separated_lines(&text, name)?;
                    parse_owned_points(text, name).map(without_crs)
                }
            }
            InputFormat::GeoJson => {
                super::geojson_points::parse_geojson_file(&text, name).map_err(|mut err| {
                    // GeoJSON lines (NDJSON, a GeoJSON sequence) read as one document: its second
                    // object is trailing characters. Say how to read one object per line.
                    // Only where the trailing line starts an object: a stray `}` needs no such hint.
                    let starts_object = err
                        .line
                        .and_then(|line| text.lines().nth(line.checked_sub(1)?))
                        .is_some_and(|line| {
                            line.trim_start_matches(['\u{1e}', ' ', '\t', '\r'])
                                .starts_with('{')
                        });
                    if let IoErrorKind::Content(message) = &mut err.kind {
                        if starts_object && message.starts_with("trailing characters") {
                            message.push_str(match (stdin, options.format.is_some()) {
                                (true, false) => {
                                    "; standard input is read as one GeoJSON document: state its \
                                     format to read one GeoJSON object per line (condt's \
                                     --input-format geojsonl)"
                                }
                                (true, true) => {
                                    "; a GeoJSON document is one object: to read one GeoJSON \
                                     object per line, state condt's --input-format geojsonl"
                                }
                                (false, _) => {
                                    "; a GeoJSON document is one object: to read one GeoJSON \
                                     object per line, name the file *.geojsonl or state condt's \
                                     --input-format geojsonl"
                                }
                            });
                        }
                    }
                    err
                })
            }
            InputFormat::GeoJsonLines => super::geojson_points::parse_geojson_lines(&text, name),
            // Read above from the bytes, which are these.
            InputFormat::Npy => super::npy::parse_npy(text.as_bytes(), name).map(without_crs),
        }
    })();
    // Where the reader quotes the replaced bytes (U+FFFD), the line's problem is them; where it
    // names another problem on such a line, that stands, with a word on the bytes.
    // A GIS file condt has no reader for, by its name's ending where no format was stated: a
    // shapefile's .dbf was "not UTF-8 text", its .shp "found one coordinate (U+0000)", its .prj
    // sent the user to --columns, and a GPX track to `cannot read "<?xml" as a number` (a GIS
    // user's review).
    let gis = options
        .format
        .is_none()
        .then(|| path.extension().and_then(|e| e.to_str()))
        .flatten()
        .and_then(gis_file);
    read.map_err(|mut err| {
        if let (Some(what), IoErrorKind::Content(message)) = (gis, &mut err.kind) {
            *message = what.to_string();
            err.line = None;
        } else if let (true, IoErrorKind::Content(message)) = (utf16, &mut err.kind) {
            *message = "UTF-16 text (the file starts with its byte order mark): condt reads \
                        UTF-8; save the file as UTF-8"
                .to_string();
            err.line = Some(1);
        } else if let (Some((_, kind, tool)), IoErrorKind::Content(message)) =
            (compressed, &mut err.kind)
        {
            *message = format!(
                "{kind}-compressed data, not points: decompress it first (`{tool} FILE | condt \
                 COMMAND -`, or to a file)"
            );
            err.line = None;
        } else if let (true, IoErrorKind::Content(message)) = (zip, &mut err.kind) {
            *message = "a zip archive (such as NumPy's .npz, or an Excel .xlsx or OpenDocument \
                        .ods workbook), not points: save the array as .npy (numpy.save) or as \
                        text, a sheet as CSV (Excel: CSV UTF-8)"
                .to_string();
            err.line = None;
        } else if let (Some(what), IoErrorKind::Content(message)) = (workspace, &mut err.kind) {
            *message = what.to_string();
            err.line = None;
        } else if let (Some(line), IoErrorKind::Content(message)) = (err.line, &mut err.kind) {
            if message.contains('\u{fffd}') {
                *message = "not UTF-8 text".to_string();
            } else if not_utf8.binary_search(&line).is_ok() {
                message.push_str(" (the line also holds bytes that are not UTF-8)");
            }
        }
        err
    })
    .map(|file| PointFile {
        degrees: file.degrees || named_degrees,
        ..file
    })
}

/// The refusal of an Octave text workspace's second variable.
const OCTAVE_VARIABLES: &str = "a second variable in an Octave text workspace, whose rows would \
                                join the first's points: save the n-by-2 matrix alone (save \
                                -ascii FILE P, or dlmwrite('points.csv', P))";

/// The refusal of a MATLAB or Octave workspace file (`save` without `-ascii`).
const MAT_FILE: &str = "a MATLAB or Octave workspace (.mat, binary), not points: write the n-by-2 \
                        matrix as text (MATLAB: writematrix(P, 'points.csv'); Octave: \
                        dlmwrite('points.csv', P), or save -ascii)";

/// The refusal of a legacy Excel workbook (an OLE2 compound file).
const XLS_FILE: &str = "an Excel .xls workbook (an OLE2 compound file), not points: save the \
                        sheet as CSV (CSV UTF-8) with x and y columns";

/// What a file whose name ends in `extension` (any case) is, when a GIS format condt does not
/// read, and how to get points from it; `None` for any other ending.
fn gis_file(extension: &str) -> Option<&'static str> {
    Some(match extension.to_ascii_lowercase().as_str() {
        "shp" => {
            "a shapefile, which condt does not read: export its points as CSV with x and y (or \
             lon and lat) columns, or as GeoJSON Points (GDAL, for a layer of points: \
             `ogr2ogr -f CSV points.csv FILE.shp -lco GEOMETRY=AS_XY`; of lines or polygons, \
             their vertices: QGIS's Extract vertices)"
        }
        "dbf" | "shx" | "prj" | "cpg" | "sbn" | "sbx" | "qix" => {
            "a part of a shapefile (its attribute table, index, projection or code page), which \
             holds no coordinates: the points are in the .shp, which condt does not read either: \
             export them as CSV with x and y (or lon and lat) columns, or as GeoJSON Points \
             (GDAL: `ogr2ogr -f CSV points.csv FILE.shp -lco GEOMETRY=AS_XY`)"
        }
        "gpx" => {
            "GPX, which condt does not read: export the track's points as CSV, projected to \
             metres (GDAL: `ogr2ogr -f CSV points.csv FILE.gpx track_points -t_srs EPSG:326NN \
             -lco GEOMETRY=AS_XY`, NN the UTM zone; without -t_srs, X and Y are longitude and \
             latitude, which condt reads as plane degrees)"
        }
        "kml" | "kmz" => {
            "KML, which condt does not read: export its points as CSV with x and y (or lon and \
             lat) columns, or as GeoJSON Points (GDAL: `ogr2ogr -f GeoJSON points.geojson \
             FILE.kml`, whose lines' vertices condt reads only as Points)"
        }
        "gpkg" => {
            "a GeoPackage, which condt does not read: export its points as CSV with x and y \
             columns, or as GeoJSON Points (GDAL: `ogr2ogr -f CSV points.csv FILE.gpkg \
             -lco GEOMETRY=AS_XY`)"
        }
        _ => return None,
    })
}

/// Whether a line of `bytes` holds, before any `#`, two tabs or more, or one beside a blank: the
/// lines [`tab_separated_lines`] may refuse. One pass over the bytes answers for the common
/// `.tsv` of `x<TAB>y` lines without splitting them (speed: `condt triangulate big.tsv --timings`
/// of 1M random points, 21.8 MB, reads in 0.060-0.064 s against 0.030-0.034 s without the check,
/// five alternated runs; a diff review measured 0.12 s with the check's first version, which
/// split every line).
fn may_refuse(bytes: &[u8]) -> bool {
    let (mut tabs, mut other, mut comment) = (0u32, false, false);
    for &b in bytes {
        match b {
            b'\n' | b'\r' => {
                if tabs > 1 || (tabs == 1 && other) {
                    return true;
                }
                (tabs, other, comment) = (0, false, false);
            }
            _ if comment => {}
            b'#' => comment = true,
            b'\t' => tabs += 1,
            b' ' | 0x0c => other = true,
            _ => {}
        }
    }
    tabs > 1 || (tabs == 1 && other)
}

/// `Ok` when every line of a `.tsv` without a header that has a tab between its values has at
/// most two fields between tabs, each without a blank: the plain reader, which reads such a file,
/// splits at any blank and leaves a third value unread, so `10<TAB>2 345.5` came back as the
/// point (10, 2) and `1<TAB>0 7` as (1, 0), with exit 0 (a hostile-input review). A line without
/// a tab is the plain format's, as the README says of a `.tsv` of two numbers a line.
fn tab_separated_lines(text: &str, name: &str) -> Result<(), IoError> {
    // Bytes, not chars: every byte this looks for is ASCII (speed: splitting with `tab_fields`
    // instead read 1M `x<TAB>y<SPACE>` lines, `condt triangulate --timings`, in 0.17 s, not 0.07).
    let bytes = text.as_bytes();
    if !may_refuse(bytes) {
        return Ok(());
    }
    let at = |line: &[u8]| line_at(bytes, line.as_ptr() as usize - bytes.as_ptr() as usize);
    let mut first = true;
    for line in bytes.split(|&b| b == b'\n' || b == b'\r') {
        // A tab that only indents the line or ends it separates nothing: `<TAB>1 2` is plain.
        let content = line.split(|&b| b == b'#').next().unwrap_or(line);
        let content = content
            .strip_prefix("\u{feff}".as_bytes())
            .unwrap_or(content);
        let content = content.trim_ascii();
        if content.is_empty() {
            continue;
        }
        let first_line = core::mem::replace(&mut first, false);
        if !content.contains(&b'\t') {
            continue;
        }
        let fields = content.split(|&b| b == b'\t').map(<[u8]>::trim_ascii);
        let mut count = 0;
        for field in fields.filter(|f| !f.is_empty()) {
            if field.iter().any(u8::is_ascii_whitespace) {
                let message = format!(
                    "cannot read {:?} as a number: a .tsv's columns are separated by tabs, and \
                     a blank within one is no separator (nor a thousands separator)",
                    String::from_utf8_lossy(field)
                );
                return Err(Source { file: name }.error(at(line), message));
            }
            count += 1;
        }
        if count > 2 {
            let numbers = content.split(|&b| b == b'\t').map(<[u8]>::trim_ascii);
            let numbers = numbers
                .filter(|f| !f.is_empty())
                .all(|f| core::str::from_utf8(f).is_ok_and(|f| f.trim().parse::<f64>().is_ok()));
            let message = match numbers && first_line {
                // The first line of numbers is refused as CSV's is, as the README says.
                true => crate::csv::numbers_without_header(count),
                false => format!(
                    "{count} values between tabs where a .tsv without a header has x and y: a \
                     header line must name the x and y columns (or --columns X,Y their numbers \
                     from 1)"
                ),
            };
            return Err(Source { file: name }.error(at(line), message));
        }
    }
    Ok(())
}

/// The fields of a `.tsv` line split at tabs, a byte-order mark, a comment and blank fields left
/// out.
fn tab_fields(line: &str) -> Vec<&str> {
    let line = line.strip_prefix('\u{feff}').unwrap_or(line);
    let content = line.split('#').next().unwrap_or("");
    content
        .split('\t')
        .map(str::trim)
        .filter(|f| !f.is_empty())
        .collect()
}

/// CloudCompare's ASCII export starts its header with `//` (`//X,Y,Z,R,G,B`, `//X Y Z`), which
/// the README sends scan users to: the mark is blanked (two spaces, so lines and columns keep
/// their numbers) where the first line with content starts with it and a letter follows.
fn blank_cloudcompare_header_mark(bytes: &mut [u8]) {
    let start = bytes.strip_prefix("\u{feff}".as_bytes()).map_or(0, |_| 3);
    let Some(first) = bytes[start..]
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .map(|at| start + at)
    else {
        return;
    };
    if bytes[first..].starts_with(b"//")
        && bytes.get(first + 2).is_some_and(u8::is_ascii_alphabetic)
    {
        bytes[first..first + 2].copy_from_slice(b"  ");
    }
}

/// `bytes` as text, each sequence that is not UTF-8 replaced by U+FFFD, and the lines (numbered
/// as the readers number them, [`line_at`]) that held one, in order.
fn lossy_text(bytes: Vec<u8>) -> (String, Vec<usize>) {
    let bytes = match String::from_utf8(bytes) {
        Ok(text) => return (text, Vec::new()),
        Err(err) => err.into_bytes(),
    };
    let mut lines = Vec::new();
    let (mut line, mut counted) = (1, 0);
    let mut offset = 0;
    for chunk in bytes.utf8_chunks() {
        offset += chunk.valid().len();
        if !chunk.invalid().is_empty() {
            line += line_at(&bytes[counted..], offset - counted) - 1;
            counted = offset;
            if lines.last() != Some(&line) {
                lines.push(line);
            }
        }
        offset += chunk.invalid().len();
    }
    (String::from_utf8_lossy(&bytes).into_owned(), lines)
}

/// A file's bytes as text, refused as [`read_points`] refuses a text file that is not UTF-8:
/// naming `file` and the line of the first byte that is not (for other text files, such as the
/// edge files of `condt score`, to be refused alike).
///
/// ```
/// assert_eq!(condt_io::utf8_text(b"0 1\n".to_vec(), "a.edges")?, "0 1\n");
/// let err = condt_io::utf8_text(b"0 1\r\n1 \xe9\n".to_vec(), "a.edges").unwrap_err();
/// assert_eq!(err.to_string(), "a.edges:2: not UTF-8 text");
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn utf8_text(bytes: Vec<u8>, file: &str) -> Result<String, IoError> {
    String::from_utf8(bytes).map_err(|e| IoError {
        file: file.to_string(),
        line: Some(line_at(e.as_bytes(), e.utf8_error().valid_up_to())),
        kind: IoErrorKind::Content("not UTF-8 text".to_string()),
    })
}

/// [`parse_points`] on a text it may free before joining the pieces of a parallel parse, so
/// that the text and two copies of the points are never held at once.
fn parse_owned_points(text: String, file: &str) -> Result<Vec<Point>, IoError> {
    #[cfg(feature = "parallel")]
    {
        let body = text.strip_prefix('\u{feff}').unwrap_or(&text);
        if let Some(pieces) = parallel::parse_pieces(body, file) {
            drop(text);
            let total: usize = pieces.iter().map(|p| p.points.len()).sum();
            return parallel::join(pieces).ok_or_else(|| IoError {
                file: file.to_string(),
                line: None,
                kind: IoErrorKind::Content(format!("out of memory for {total} points")),
            });
        }
    }
    // Sequentially (the parallel parse, if it ran, found an error: this pass names its line).
    parse_points_sequentially(text.strip_prefix('\u{feff}').unwrap_or(&text), file)
}

/// An error when the file read has changed since it was opened (`opened`, its metadata then):
/// its size or its time of last change differ, so what was read may be the start of a file
/// still being written (a batch job picking up another's output), or part old and part new.
/// Without it such a file was reconstructed as if whole (an operations review: a file rewritten
/// by `cp` while read gave a cut-short set of points, or none, and status 0). A file whose
/// metadata cannot be read is taken as unchanged.
fn unchanged_since_opened(file: &File, opened: Option<&std::fs::Metadata>) -> io::Result<()> {
    let (Some(opened), Ok(now)) = (opened, file.metadata()) else {
        return Ok(());
    };
    if !opened.is_file() {
        return Ok(());
    }
    let size_then = opened.len();
    let size_now = now.len();
    if size_then == size_now && opened.modified().ok() == now.modified().ok() {
        return Ok(());
    }
    let sizes = if size_then == size_now {
        format!("{size_now} bytes, rewritten")
    } else {
        format!("{size_then} bytes when opened, {size_now} after")
    };
    Err(io::Error::other(format!(
        "changed while it was read ({sizes}): read it once it is complete"
    )))
}

/// Everything `reader` holds, growing the buffer with `try_reserve` so that a file larger than
/// the memory the system gives is an `OutOfMemory` error instead of an abort. `size` is a hint.
/// On Linux the buffer also stops at half the memory available when the read starts (the points
/// parsed from a text take about as much again): with memory overcommitted, `try_reserve`
/// grants what the system cannot give, and an endless stream (`/dev/zero`, a producer that never
/// stops) was ended by the OOM killer, not an error.
fn read_all(reader: impl Read, size: u64) -> io::Result<Vec<u8>> {
    read_all_within(reader, size, memory_available().unwrap_or(usize::MAX))
}

/// The memory the system says is available (`MemAvailable` of `/proc/meminfo`), where it says,
/// and no more than this process's cgroup (v2) has left under its limit (a container's or a CI
/// job's, which `MemAvailable` does not see), nor than its address space has left under its
/// limit (`ulimit -v`, RLIMIT_AS, read from `/proc/self/limits`, the address space taken from
/// `VmSize` of `/proc/self/status`: no `getrlimit` call, which would need `unsafe`).
fn memory_available() -> Option<usize> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    let system = kib.checked_mul(1024)?;
    let read = |name: &str| -> Option<usize> {
        std::fs::read_to_string(format!("/sys/fs/cgroup/{name}"))
            .ok()?
            .trim()
            .parse()
            .ok()
    };
    // `memory.max` reads `max` where there is no limit: no number, no bound.
    let left =
        read("memory.max").map(|max| max.saturating_sub(read("memory.current").unwrap_or(0)));
    let available = left.map_or(system, |left| left.min(system));
    let limits = std::fs::read_to_string("/proc/self/limits").ok();
    let status = std::fs::read_to_string("/proc/self/status").ok();
    Some(
        match address_space_left(limits.as_deref(), status.as_deref()) {
            Some(left) => left.min(available),
            None => available,
        },
    )
}

/// What the address-space limit leaves, from the texts of `/proc/self/limits` and
/// `/proc/self/status`: the soft limit of `Max address space` less `VmSize`; `None` without a
/// limit (`unlimited`) or where either cannot be read.
fn address_space_left(limits: Option<&str>, status: Option<&str>) -> Option<usize> {
    let line = limits?
        .lines()
        .find_map(|l| l.strip_prefix("Max address space"))?;
    let limit: usize = line.split_whitespace().next()?.parse().ok()?;
    let line = status?.lines().find_map(|l| l.strip_prefix("VmSize:"))?;
    let kib: usize = line.split_whitespace().next()?.parse().ok()?;
    Some(limit.saturating_sub(kib.saturating_mul(1024)))
}

/// [`read_all`] with `available` bytes of memory: holding at most half of them.
fn read_all_within(mut reader: impl Read, size: u64, available: usize) -> io::Result<Vec<u8>> {
    const CHUNK: usize = 1 << 20;
    let limit = if available == usize::MAX {
        usize::MAX
    } else {
        available / 2
    };
    let too_large = |len: usize| {
        let available = if limit < usize::MAX {
            format!(
                "; it and its points would not fit in the {available} bytes of memory available"
            )
        } else {
            String::new()
        };
        io::Error::new(
            io::ErrorKind::OutOfMemory,
            format!("cannot hold the file in memory (over {len} bytes{available})"),
        )
    };
    let mut bytes: Vec<u8> = Vec::new();
    let hint = usize::try_from(size)
        .ok()
        .filter(|&hint| hint <= limit)
        .ok_or_else(|| too_large(usize::try_from(size).unwrap_or(usize::MAX)))?;
    bytes
        .try_reserve_exact(hint.saturating_add(1))
        .map_err(|_| too_large(hint))?;
    loop {
        if bytes.capacity() - bytes.len() < CHUNK / 16 {
            // The size hint is usually exact: look for more before reserving room for it, or
            // the buffer would double just to learn that the file has ended.
            let mut probe = [0u8; 64];
            let got = loop {
                match reader.read(&mut probe) {
                    Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                    other => break other?,
                }
            };
            if got == 0 {
                return Ok(bytes);
            }
            if bytes.len() >= limit {
                return Err(too_large(bytes.len()));
            }
            let more = bytes
                .len()
                .max(CHUNK)
                .min(limit - bytes.len())
                .max(probe.len());
            bytes
                .try_reserve_exact(more)
                .map_err(|_| too_large(bytes.len() + more))?;
            bytes.extend_from_slice(&probe[..got]);
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

    /// A header is skipped only where it cannot mean other columns than the first two; found by
    /// a fuzzer: `id x y` read the ids as x, `y x` swapped the axes, both without a word.
    #[test]
    fn a_header_naming_other_columns_is_refused_not_skipped() {
        for header in [
            "id x y",
            "y x",
            "lat lon",
            "n,x,y",
            "\"y\",\"x\"",
            "N E",
            "north east",
        ] {
            let text = format!("{header}\n7.5 0 1\n9.5 1 1\n");
            let err = parse_points(&text, "h.txt").unwrap_err().to_string();
            assert!(err.starts_with("h.txt:1: the header"), "{header}: {err}");
        }
        for header in [
            "x y",
            "X Y z",
            "lon lat",
            "\"lon\",\"lat\"",
            "a b",
            "east north",
            "long lat",
            "x_m y",
            "x z",
        ] {
            let text = format!("{header}\n7.5 0\n9.5 1\n");
            let points = parse_points(&text.replace(',', " "), "h.txt").unwrap();
            assert_eq!(
                points,
                vec![Point::new(7.5, 0.0), Point::new(9.5, 1.0)],
                "{header}"
            );
        }
    }

    /// A first line of missing-value markers or wrapped numbers is a point that cannot be read,
    /// not a header to skip (a new user's report: `NA NA` first dropped a row silently).
    #[test]
    fn a_first_line_of_missing_values_is_an_error_not_a_header() {
        for first in [
            "NA NA",
            "None,None",
            "null null",
            "np.float64(51.8), np.float64(267.05)",
        ] {
            let text = format!("{first}\n0 0\n1 0\n");
            let err = parse_points(&text, "m.txt").unwrap_err().to_string();
            assert!(err.starts_with("m.txt:1: "), "{first}: {err}");
        }
        let points = parse_points("x1 y1\n0 0\n1 0\n", "m.txt").unwrap();
        assert_eq!(points.len(), 2, "names with digits are still a header");
    }

    /// The ignored third column may be NaN or infinite (found by a fuzzer: `0 0 nan`, a missing
    /// depth, was refused as a coordinate that is not finite), but not a word.
    #[test]
    fn the_ignored_third_column_may_be_nan_but_not_a_word() {
        let points = parse_points("0.5 0 nan\n1.5 0 -inf\n2.5 1 NaN\n", "z.txt").unwrap();
        assert_eq!(points.len(), 3);
        let err = parse_points("0.5 0 1\n1.5 0 abc\n", "z.txt")
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("z.txt:2: cannot read \"abc\" as a number (a third"),
            "{err}"
        );
        let err = parse_points("0.5 nan 1\n", "z.txt")
            .unwrap_err()
            .to_string();
        assert!(err.contains("not finite"), "{err}");
    }

    /// R's `write.table` writes row names as a first column its header does not name: read
    /// on, the row numbers were x and x was y, with exit 0 (an R user's review). Refused at
    /// the first row, quoted (the default) or not, blank- or tab-separated, as every path
    /// reads it: sequentially and in pieces, with the header in the first piece and its first
    /// row in a later one.
    #[test]
    fn a_header_one_name_short_of_its_rows_is_refused() {
        for text in [
            "x y\n1 1100 2000.5\n2 1099.5 2010.9\n3 1097.8 2021.3\n",
            "\"x\" \"y\"\n\"1\" 1100 2000.5\n\"2\" 1099.5 2010.9\n",
            "x\ty\r\n1\t1100\t2000.5\r\n2\t1099.5\t2010.9\r\n",
            "lon lat\np1 11 20.005\np2 10.99 20.11\n",
            "# written by R\nx y\n\n1 1100 2000.5\n",
        ] {
            let err = parse_points(text, "r.txt").unwrap_err().to_string();
            assert!(err.contains("but the header on line"), "{text:?}: {err}");
            assert!(err.contains("row.names = FALSE"), "{text:?}: {err}");
        }
        let err = parse_points("x y\n1 1100 2000.5\n", "r.txt").unwrap_err();
        assert_eq!(err.line, Some(2));
        // A single word over two columns is a title, read on as before.
        let points = parse_points("points\n1 2\n4 5\n", "r.txt").unwrap();
        assert_eq!(points, vec![Point::new(1.0, 2.0), Point::new(4.0, 5.0)]);
        // A header naming all its columns, or none at all, reads as before.
        let points = parse_points("x y z\n1 2 3\n4 5 6\n", "r.txt").unwrap();
        assert_eq!(points, vec![Point::new(1.0, 2.0), Point::new(4.0, 5.0)]);
        let points = parse_points("0.5 2 3\n4 5 6\n", "r.txt").unwrap();
        assert_eq!(points, vec![Point::new(0.5, 2.0), Point::new(4.0, 5.0)]);
        // A header naming x and y over rows with a third column, a height or an intensity, as
        // surveys and scanners export: read as before, unless its first field may be the row
        // name R writes first (`1`, quoted or not, or a word).
        for (text, first) in [
            ("x y\n10.5 0 0.5\n4 5 0.5\n", 10.5),
            (
                "Easting Northing\n512000 180000 12.3\n512001 180002 12.4\n",
                512000.0,
            ),
            ("x y\n2 7 0.5\n4 5 0.5\n", 2.0),
        ] {
            let points = parse_points(text, "h.txt").unwrap_or_else(|e| panic!("{text:?}: {e}"));
            assert_eq!(points[0].x, first, "{text:?}");
        }
        #[cfg(feature = "parallel")]
        {
            let mut text = String::from("x y\n");
            text.push_str(&"#\n".repeat(3 << 20));
            for i in 0..200_000 {
                text.push_str(&format!("{} {i}.5 7\n", i + 1));
            }
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap();
            pool.install(|| {
                let err = parse_points(&text, "big.txt").unwrap_err();
                assert_eq!(err.line, Some((3 << 20) + 2), "{err}");
                assert!(err.to_string().contains("row.names = FALSE"), "{err}");
            });
        }
    }

    /// Octave's default `save` writes a text workspace: one n-by-2 matrix reads as its rows,
    /// a second variable is refused at its name (an R and MATLAB user's review: `save('w.mat',
    /// 'M', 'N')` gave M's and N's rows as one set of points, exit 0), read whole or in pieces.
    #[test]
    fn an_octave_text_workspace_of_two_variables_is_refused() {
        let head = "# Created by Octave 7.3.0, Mon Dec 07 23:01:24 2026 UTC <root@vm>\n";
        let m = "# name: M\n# type: matrix\n# rows: 2\n# columns: 2\n 1100 2000.5\n 1099.5 2010\n";
        let n = "\n\n# name: N\n# type: matrix\n# rows: 1\n# columns: 2\n 5 6\n";
        let points = parse_points(&format!("{head}{m}"), "w.mat").unwrap();
        assert_eq!(
            points,
            vec![Point::new(1100.0, 2000.5), Point::new(1099.5, 2010.0)]
        );
        let err = parse_points(&format!("{head}{m}{n}"), "w.mat").unwrap_err();
        assert_eq!(err.line, Some(10), "{err}");
        assert!(err
            .to_string()
            .contains("a second variable in an Octave text workspace"));
        // Two column vectors, x and y, as MATLAB users often keep them: said at the first row.
        let x = "# name: x\n# type: matrix\n# rows: 2\n# columns: 1\n 1100\n 1099.5\n";
        let err = parse_points(&format!("{head}{x}"), "xy.mat").unwrap_err();
        assert_eq!(err.line, Some(6), "{err}");
        assert!(
            err.to_string().contains("one n-by-2 matrix, [x y]"),
            "{err}"
        );
        // The same comments in a file Octave did not write are comments.
        assert_eq!(parse_points(&format!("{m}{n}"), "c.txt").unwrap().len(), 3);
        #[cfg(feature = "parallel")]
        {
            let mut text = format!("{head}# name: M\n# type: matrix\n");
            for i in 0..400_000 {
                text.push_str(&format!(" {i}.5 {}\n", i % 7));
            }
            text.push_str(n);
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap();
            pool.install(|| {
                let err = parse_points(&text, "big.mat").unwrap_err();
                assert_eq!(err.line, Some(400_006), "{err}");
            });
        }
    }

    /// R's `NA` and Excel's `#N/A` are told as missing values, and a quoted number in a plain
    /// file as R's quoted row names (an R user's review: "cannot read" alone).
    #[test]
    fn missing_values_and_quoted_numbers_say_what_they_are() {
        // `#` starts a comment in a plain file: Excel's marks reach the CSV reader only.
        for (mark, read) in [("NA", true), ("#N/A", false), ("#NV", false)] {
            let text = format!("x,y\n1100,2000.5\n{mark},2010.9\n");
            let err = crate::csv::parse_csv(&text, "na.csv")
                .unwrap_err()
                .to_string();
            assert!(
                err.contains("(a missing value: leave rows"),
                "{mark}: {err}"
            );
            if !read {
                continue;
            }
            let text = format!("1100 2000.5\n{mark} 2010.9\n");
            let err = parse_points(&text, "na.txt").unwrap_err().to_string();
            assert!(
                err.contains("(a missing value: leave rows"),
                "{mark}: {err}"
            );
        }
        let err = parse_points("\"1\" 1100 2000.5\n", "q.txt")
            .unwrap_err()
            .to_string();
        assert!(err.contains("row.names = FALSE"), "{err}");
        let err = parse_points("x,y\n1,2\n3,NA\n", "na.csv").unwrap_err();
        assert_eq!(err.line, Some(3));
        // Excel's thousands separator in an English locale, quoted in its CSV.
        let err = crate::csv::parse_csv("x,y\r\n\"1,100.00\",\"2,000.50\"\r\n", "en.csv")
            .unwrap_err()
            .to_string();
        assert!(err.contains("(thousands grouped by commas?"), "{err}");
    }

    #[test]
    fn a_semicolon_separated_line_is_told_how_columns_are_separated() {
        let err = parse_points("1;0\n", "s.txt").unwrap_err().to_string();
        assert!(
            err.contains("found one (a semicolon does not separate columns"),
            "{err}"
        );
    }

    #[test]
    fn a_line_of_a_control_character_names_it() {
        for (text, code) in [("0 0\n\u{0}\n", "U+0000"), ("0 0\n\u{1a}\n", "U+001A")] {
            let err = parse_points(text, "c.txt").unwrap_err().to_string();
            assert!(
                err.contains("c.txt:2:") && err.contains(&format!("control character {code}")),
                "{err}"
            );
        }
    }

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
    fn lines_read_in_one_pass_read_as_the_general_path_reads_them() {
        // Random texts of lines that are mostly plain numbers, with every kind of deviation the
        // one-pass reader must leave to the general path: all give the same points bit for bit,
        // or the same error on the same line.
        let tokens = [
            "0",
            "-1.5",
            "+2",
            "0.13436424411240122",
            "1e3",
            "-4.5E-7",
            ".5",
            "5.",
            "00012",
            "123456789012345678901234",
            "1e400",
            "1e-400",
            "1e000001",
            "inf",
            "NaN",
            "x",
            "1,5",
            "1.5x",
            "--1",
            "1e",
            "2.2250738585072011e-308",
            "9007199254740993",
            "é",
            "#",
            "1#2",
        ];
        let blanks = [" ", "  ", "\t", " \t", "\x0b", "\u{a0}"];
        let ends = ["\n", "\r\n", "\r", "", " \n", "\t\r\n", " # note\n"];
        let mut rng = crate::test_rng::Xorshift::new(0x5851_f42d_4c95_7f2d);
        let mut next = |n: usize| rng.below(n as u64) as usize;
        let (mut same_points, mut same_errors) = (0, 0);
        for _ in 0..3000 {
            let mut text = String::new();
            if next(4) == 0 {
                text.push_str("x y\n");
            }
            for _ in 0..1 + next(12) {
                if next(3) > 0 {
                    text.push_str(blanks[0]);
                }
                // Mostly two or three columns of the common tokens.
                let columns = [2, 2, 2, 3, 3, 1, 4, 0][next(8)];
                for c in 0..columns {
                    if c > 0 {
                        text.push_str(if next(12) == 0 {
                            blanks[next(blanks.len())]
                        } else {
                            " "
                        });
                    }
                    let token = if next(10) < 8 {
                        next(5)
                    } else {
                        next(tokens.len())
                    };
                    text.push_str(tokens[token]);
                }
                text.push_str(if next(6) > 0 {
                    "\n"
                } else {
                    ends[next(ends.len())]
                });
            }
            let source = Source { file: "t" };
            // A vector that starts with room for a few points, or for none: the one-pass loop
            // stops where it is full and the general path grows it.
            let one = lines_by::<true>(&text, &source, true, [0, 3][next(2)]);
            let general = lines_by::<false>(&text, &source, true, 0);
            match (one, general) {
                (Ok(a), Ok(b)) => {
                    let bits = |p: &Parsed| -> Vec<(u64, u64)> {
                        p.points
                            .iter()
                            .map(|q| (q.x.to_bits(), q.y.to_bits()))
                            .collect()
                    };
                    assert_eq!(bits(&a), bits(&b), "{text:?}");
                    assert_eq!(a.all_three_columns, b.all_three_columns, "{text:?}");
                    assert_eq!(a.first_data_line, b.first_data_line, "{text:?}");
                    assert_eq!(a.seen_content, b.seen_content, "{text:?}");
                    same_points += 1;
                }
                (Err(a), Err(b)) => {
                    assert_eq!(a.to_string(), b.to_string(), "{text:?}");
                    same_errors += 1;
                }
                (a, b) => panic!("{text:?}: {:?} against {:?}", a.is_ok(), b.is_ok()),
            }
        }
        // Both outcomes were exercised.
        assert!(
            same_points > 300 && same_errors > 300,
            "{same_points} {same_errors}"
        );
    }

    /// The parallel parse of a text in memory (taken: the pieces are checked to exist) gives
    /// the sequential parse's points bit for bit, and its error where the text has one.
    #[cfg(feature = "parallel")]
    #[test]
    fn the_parallel_parse_equals_the_sequential_one() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let mut rng = crate::test_rng::Xorshift::new(5);
        let mut text = String::from("x y\n");
        for i in 0..200_000 {
            let sep = if i % 3 == 0 { "\t" } else { " " };
            let end = if i % 5 == 0 { "\r\n" } else { "\n" };
            text.push_str(&format!("{}{sep}{}{end}", rng.unit() * 1e6, -rng.unit()));
        }
        assert!(text.len() > 4 << 20, "large enough to be cut");
        let mut broken = text.clone();
        broken.insert_str(3 << 20, "1,5 2\n");
        pool.install(|| {
            assert!(
                parallel::parse_pieces(&text, "t").is_some(),
                "the parallel path ran"
            );
            let parallel = parse_points(&text, "t").unwrap();
            let sequential = parse_points_sequentially(&text, "t").unwrap();
            assert_eq!(parallel.len(), 200_000);
            let bits = |p: &[Point]| {
                p.iter()
                    .map(|q| (q.x.to_bits(), q.y.to_bits()))
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(&parallel), bits(&sequential));
            let (a, b) = (
                parse_points(&broken, "t").unwrap_err(),
                parse_points_sequentially(&broken, "t").unwrap_err(),
            );
            assert_eq!(a.to_string(), b.to_string());
            assert!(a.line.is_some());
        });
    }

    /// Files read in pieces straight from the disk give the points of the text parsed in
    /// one piece, bit for bit, or the same error: lines ending exactly at a piece's share and
    /// anywhere else, a header, comments, CRLF, a byte-order mark, and the cases that go to
    /// the whole-file path (CR-only line ends, a line longer than the look-ahead, a bad
    /// number or bad UTF-8 in a late piece, a node index column, a header in a later piece).
    #[cfg(all(feature = "parallel", unix))]
    #[test]
    fn files_read_in_pieces_read_as_the_whole_text() {
        let dir = tempfile::tempdir().unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let mut rng = crate::test_rng::Xorshift::new(99);
        // 16-byte lines: byte 2^20 - 1 is a line end, so a piece starts exactly at its share.
        let fixed: String = (0..200_000)
            .map(|i| format!("0.{:07} 0.{:03}\n", i, i % 1000))
            .collect();
        let mut random = String::from("\u{feff}x y\r\n# points\r\n");
        for i in 0..150_000 {
            random.push_str(&format!("{} {}\r\n", rng.unit(), -rng.unit()));
            if i % 10_000 == 0 {
                random.push_str("\r\n  # note\r\n");
            }
        }
        let mut texts = vec![fixed.clone(), random.clone()];
        texts.push(fixed.replace('\n', "\r"));
        let mut long = fixed.clone();
        long.insert_str(1_500_000, &format!("{}\n", " ".repeat(100_000)));
        texts.push(long);
        let mut bad = random.clone();
        bad.insert_str(bad.len() - 1000, "1 x\n");
        texts.push(bad);
        let mut late_header = String::from("# only a comment\n");
        late_header.push_str(&" ".repeat(3 << 20));
        late_header.push_str("\nx y\n1 2\n");
        texts.push(late_header);
        let indexed: String = (0..150_000).map(|i| format!("{i} 0.5 0.25\n")).collect();
        texts.push(indexed);
        let mut bytes_texts: Vec<Vec<u8>> = texts.iter().map(|t| t.as_bytes().to_vec()).collect();
        let mut not_utf8 = fixed.as_bytes().to_vec();
        not_utf8[2_500_000] = 0xff;
        bytes_texts.push(not_utf8);
        for (k, bytes) in bytes_texts.iter().enumerate() {
            assert!(bytes.len() > 2 * (1 << 20), "text {k} too small for pieces");
            let path = dir.path().join(format!("t{k}.txt"));
            std::fs::write(&path, bytes).unwrap();
            let shown = path.to_string_lossy().into_owned();
            let whole = match core::str::from_utf8(bytes) {
                Ok(text) => {
                    parse_points_sequentially(text.strip_prefix('\u{feff}').unwrap_or(text), &shown)
                }
                Err(_) => Err(IoError {
                    file: shown.clone(),
                    line: Some(1 + 2_500_000 / 16),
                    kind: IoErrorKind::Content("not UTF-8 text".to_string()),
                }),
            };
            let read = pool.install(|| read_points(&path));
            match (read, whole) {
                (Ok(a), Ok(b)) => {
                    let bits = |p: &[Point]| -> Vec<(u64, u64)> {
                        p.iter().map(|q| (q.x.to_bits(), q.y.to_bits())).collect()
                    };
                    assert!(bits(&a) == bits(&b), "text {k}");
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "text {k}"),
                (a, b) => panic!("text {k}: {:?} against {:?}", a.is_ok(), b.is_ok()),
            }
        }
        // The fixed-width file really is read in pieces (the whole-file path is not taken).
        let file = File::open(dir.path().join("t0.txt")).unwrap();
        let size = file.metadata().unwrap().len();
        let points = pool
            .install(|| parallel::read_pieces(&file, size, "t0"))
            .unwrap();
        assert_eq!(points.len(), 200_000);
        // A size that is not the file's: refused, for the whole-file path.
        assert!(pool
            .install(|| parallel::read_pieces(&file, size - 1, "t0"))
            .is_none());
        assert!(pool
            .install(|| parallel::read_pieces(&file, size + 1, "t0"))
            .is_none());
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

    /// A file that grows or is rewritten between its opening and the end of its reading is an
    /// error, not a cut-short set of points. The change is made before the read here (the
    /// metadata of the opening kept from before it), as a writer racing the read would.
    #[test]
    fn a_file_changed_while_it_is_read_is_an_error() {
        use std::io::Write;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("growing.txt");
        std::fs::write(&path, "0 0\n1 0\n").unwrap();
        let file = File::open(&path).unwrap();
        let opened = file.metadata().unwrap();
        assert!(unchanged_since_opened(&file, Some(&opened)).is_ok());
        std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .unwrap()
            .write_all(b"1 1\n0 1")
            .unwrap();
        let err = unchanged_since_opened(&file, Some(&opened)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "changed while it was read (8 bytes when opened, 15 after): read it once it is \
             complete"
        );
        // The same size, its time of change moved: rewritten meanwhile.
        let file = File::open(&path).unwrap();
        let opened = file.metadata().unwrap();
        let stamp = opened.modified().unwrap() + std::time::Duration::from_secs(1);
        std::fs::File::options()
            .write(true)
            .open(&path)
            .unwrap()
            .set_modified(stamp)
            .unwrap();
        let err = unchanged_since_opened(&file, Some(&opened)).unwrap_err();
        assert!(err.to_string().contains("(15 bytes, rewritten)"), "{err}");
        // Standard input's metadata is not asked: no file, nothing to compare.
        assert!(unchanged_since_opened(&file, None).is_ok());
    }

    #[test]
    fn reading_stops_at_the_end_without_growing_past_what_it_reserved() {
        let data: Vec<u8> = (0..3 * (1 << 20) + 17).map(|i| (i % 251) as u8).collect();
        assert_eq!(read_all(&data[..], 0).unwrap(), data);
        let exact = read_all(&data[..], data.len() as u64).unwrap();
        assert_eq!(exact, data);
        assert!(exact.capacity() < data.len() + 64, "{}", exact.capacity());
        assert_eq!(read_all(&data[..], 5).unwrap(), data);
        assert!(read_all(&b""[..], 0).unwrap().is_empty());
    }

    /// The address-space limit (`ulimit -v`) bounds the memory a read may take, as the
    /// machine's available memory does (a reviewer's report: under `ulimit -v 30000` a file was
    /// said not to fit in the machine's 24 GB, not in the limit in force).
    #[test]
    fn the_address_space_limit_is_read_from_proc() {
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max stack size            8388608              unlimited            bytes     \n\
                      Max address space         30720000             unlimited            bytes     \n";
        let status = "Name:\tcondt\nVmPeak:\t   20000 kB\nVmSize:\t   10000 kB\n";
        assert_eq!(
            address_space_left(Some(limits), Some(status)),
            Some(30_720_000 - 10_240_000)
        );
        let unlimited = limits.replace("30720000    ", "unlimited   ");
        assert_eq!(address_space_left(Some(&unlimited), Some(status)), None);
        assert_eq!(address_space_left(None, Some(status)), None);
        assert_eq!(address_space_left(Some(limits), None), None);
    }

    #[test]
    fn an_impossible_size_is_an_out_of_memory_error() {
        // An endless stream stops at the limit, an error rather than all the memory there is.
        let err = read_all_within(io::repeat(b'0'), 0, 10 << 20).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::OutOfMemory);
        assert!(
            err.to_string()
                .contains("the 10485760 bytes of memory available"),
            "{err}"
        );
        assert_eq!(read_all_within(&b"1 2\n"[..], 4, 8).unwrap(), b"1 2\n");
        let err = read_all_within(&b"1 2\n"[..], 4, 7).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::OutOfMemory);
        let err = read_all(&b"1 2\n"[..], u64::MAX / 2).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::OutOfMemory);
    }
}
