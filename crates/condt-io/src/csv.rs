//! CSV point files with a header line naming the columns (`x,y`, or `lon,lat`, among others),
//! or of exactly two numeric columns without one (as `numpy.savetxt` writes them); columns are
//! separated by commas, or by tabs (TSV).
//!
//! Owns: [`parse_csv`]. A CSV file says which columns hold the coordinates in its header, so
//! the reader follows the header instead of taking the first two columns as the plain reader
//! does (an `id,x,y` file would otherwise be read as points `(id, x)`). The records are split by
//! the `csv` crate (RFC 4180); this module only checks what that crate lets through silently (a
//! closing quote with more of the field after it, `"1"5`, which it would read as `15`) and
//! numbers the lines.

use super::input::same_name;
use super::points::{columns, is_decimal_comma, may_group_thousands, quoted, Source};
use super::{Column, Columns, IoError, IoErrorKind};
use condt::Point;
use condt::MAX_POINTS;
use std::vec::Vec;

/// Names accepted for the first coordinate and for the second, compared without case.
const X_NAMES: [&str; 5] = ["x", "lon", "lng", "long", "longitude"];
const Y_NAMES: [&str; 3] = ["y", "lat", "latitude"];

/// Names of a projected pair, read where no column of the header has a name above: survey and
/// GIS exports (`easting`, `northing`, and surveyors' `E`, `N`, `east`, `north`; ArcGIS's
/// `POINT_X`, `POINT_Y`; QGIS's `xcoord`, `ycoord`; `x_coord`, `y_coord`). Second in rank, so
/// that a table with `x,y` beside them reads as it did before they were known. A survey's
/// `N E` read by position would put northings on x (a CLI user's review).
const PROJECTED_X_NAMES: [&str; 6] = ["easting", "e", "east", "point_x", "xcoord", "x_coord"];
const PROJECTED_Y_NAMES: [&str; 6] = ["northing", "n", "north", "point_y", "ycoord", "y_coord"];

/// The names of both ranks, for messages.
const NAMES_READ: &str =
    "x, lon, lng, long, longitude and y, lat, latitude are read, or where none \
                          is there easting and northing (E and N, east and north), POINT_X and \
                          POINT_Y, xcoord and ycoord, x_coord and y_coord";

/// The coordinate each of a header's column names stands for, `'x'` or `'y'` (case, blanks and
/// quotes around a name aside), or `None`: by the names `x`, `lon`, ... where any column has one
/// of them, else by the projected names. The one lookup of the CSV reader and of the plain
/// reader's check.
pub(crate) fn header_axes<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<Option<char>> {
    let names: Vec<String> = names.into_iter().map(column_name).collect();
    let by = |x: &[&str], y: &[&str]| -> Vec<Option<char>> {
        names
            .iter()
            .map(|name| {
                if x.contains(&name.as_str()) {
                    Some('x')
                } else if y.contains(&name.as_str()) {
                    Some('y')
                } else {
                    None
                }
            })
            .collect()
    };
    let first = by(&X_NAMES, &Y_NAMES);
    if first.iter().any(Option::is_some) {
        first
    } else {
        by(&PROJECTED_X_NAMES, &PROJECTED_Y_NAMES)
    }
}

/// A header's column name as the lookups compare it: case, and blanks and quotes around it,
/// aside.
fn column_name(name: &str) -> String {
    name.trim()
        .trim_matches(['"', '\''])
        .trim()
        .to_ascii_lowercase()
}

/// Whether `first_line`, a file's first line with content, names a longitude and a latitude
/// column as [`header_axes`] reads them (`lon,lat`, `id longitude latitude`, `# lon lat`), so the
/// points are in degrees; split at commas, tabs, semicolons and blanks alike, since only whole
/// names count here.
pub(crate) fn names_degrees(first_line: &str) -> bool {
    let names: Vec<String> = first_line
        .split([',', '\t', ';', ' '])
        .map(column_name)
        .collect();
    let has = |wanted: &[&str]| names.iter().any(|n| wanted.contains(&n.as_str()));
    has(&X_NAMES[1..]) && has(&Y_NAMES[1..])
}

/// Whether `--columns` chose a longitude and a latitude column by name (`Lon,Lat`), as
/// [`names_degrees`] tells of a header.
pub(crate) fn columns_degrees(columns: &crate::Columns) -> bool {
    let named = |column: &crate::Column, wanted: &[&str]| match column {
        crate::Column::Named(name) => wanted.contains(&name.trim().to_ascii_lowercase().as_str()),
        _ => false,
    };
    named(&columns.x, &X_NAMES[1..]) && named(&columns.y, &Y_NAMES[1..])
}

/// Whether the fields `names` of a first line name an x and a y column as a header does for
/// [`header_axes`], whatever the other fields hold (`id lon lat 2020`, `elevation (m)`): such a
/// line is a header this reader follows, not a point.
pub(crate) fn names_x_and_y_columns<'a>(names: impl IntoIterator<Item = &'a str>) -> bool {
    let axes = header_axes(names);
    axes.contains(&Some('x')) && axes.contains(&Some('y'))
}

/// Parses a CSV file with a header line; `file` names the source in error messages.
///
/// The first record that is not blank is the header: column names separated as the records
/// are, quoted or not; when it is exactly two numbers there is no header and every record is
/// `x,y`. The first coordinate is the column named `x` (or `lon`, `lng`, `long`, `longitude`), the
/// second the column named `y` (or `lat`, `latitude`), compared without case and blanks around
/// them; a header that names one of them in two columns (`x,y,lon,lat`) is an error; other
/// columns are ignored. Columns are separated by commas, or by tabs when the first line that is
/// not blank has tabs and no comma (TSV). Every following record that is not blank is a point.
/// Fields are read as RFC 4180 has them: a field may be quoted, `""` is a quote inside quotes, and a quoted field may hold commas and
/// line ends; a quoted field must end at its closing quote. Lines end at LF, CRLF or a lone CR.
/// A missing column, a field that is not a finite number, a record without the coordinate
/// columns or a malformed quoted field is an error naming the line (the line where its record
/// starts), and so is a record with more nonempty fields than the header (or, without one, than
/// two): a decimal comma would make one.
///
/// ```
/// use condt::Point;
/// use condt_io::parse_csv;
/// let pts = parse_csv("id,X,\"y\",label\n7,1.5,2,\"a, b\"\n8,3,4,c\n", "points.csv")?;
/// assert_eq!(pts, vec![Point::new(1.5, 2.0), Point::new(3.0, 4.0)]);
///
/// // Two numeric columns need no header; with more, which are x and y would be a guess.
/// assert_eq!(parse_csv("1.5,2\n3,4\n", "pairs.csv")?.len(), 2);
/// assert!(parse_csv("7,1.5,2\n", "rows.csv").unwrap_err().to_string().contains("no header"));
///
/// let err = parse_csv("name,value\na,1\n", "table.csv").unwrap_err();
/// assert_eq!(err.line, Some(1));
/// assert!(err.to_string().contains("no x column"));
///
/// let err = parse_csv("x,y,lon,lat\n1,2,3,4\n", "both.csv").unwrap_err();
/// assert!(err.to_string().contains("names the x coordinate in two columns (1 and 3)"));
///
/// let err = parse_csv("x,y\n1,5,2,5\n", "decimal_commas.csv").unwrap_err();
/// assert_eq!(err.to_string(), "decimal_commas.csv:2: 4 fields, but the header has 2");
/// assert_eq!(parse_csv("x,y\n1,2,\n", "trailing_comma.csv")?.len(), 1);
///
/// let err = parse_csv("x,y\n1,2\n\"1\"5,3\n", "quotes.csv").unwrap_err();
/// assert_eq!(err.to_string(), "quotes.csv:3: text after the closing quote of a field");
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn parse_csv(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    parse_csv_columns(text, file, None)
}

/// [`parse_csv`], x and y read from `columns` when given instead of the columns the header
/// names x and y.
pub(crate) fn parse_csv_columns(
    text: &str,
    file: &str,
    columns: Option<&Columns>,
) -> Result<Vec<Point>, IoError> {
    // Tab-separated values (spreadsheets' and GIS tools' other export) are told by their first
    // line with content: tabs and no comma.
    let first = first_line_with_content(text);
    let tabs = first.contains('\t') && !first.contains(',');
    parse_separated(text, file, if tabs { b'\t' } else { b',' }, columns)
}

/// Plain text read from the columns `chosen`: a scanner's `x y z intensity` export, which the
/// plain reader refuses beyond three columns. Each line is split as the plain reader splits it
/// (`#` starts a comment; blanks, or commas alone, separate the columns; a decimal comma and an
/// empty column refused), its fields joined by tabs and read as TSV, so that a header and
/// columns by name or number mean what they mean there, on the same line numbers. Quotes mean
/// nothing in plain text, and a quote in a TSV would join lines: a line holding one is refused.
/// The joined copy costs the text's size again, and the read is sequential.
pub(crate) fn parse_plain_columns(
    text: &str,
    file: &str,
    chosen: &Columns,
) -> Result<Vec<Point>, IoError> {
    if let (Column::Number(x), Column::Number(y)) = (&chosen.x, &chosen.y) {
        if let Some(points) = plain_numbered_columns(text, &Source { file }, *x - 1, *y - 1) {
            return Ok(points);
        }
    }
    plain_columns_in_general(text, file, chosen)
}

/// [`parse_plain_columns`] for every text: the lines joined by tabs, read by the CSV reader.
fn plain_columns_in_general(
    text: &str,
    file: &str,
    chosen: &Columns,
) -> Result<Vec<Point>, IoError> {
    let source = Source { file };
    let mut tabbed = String::with_capacity(text.len());
    for (number, line) in crate::text_lines(text) {
        let content = line.split('#').next().unwrap_or("");
        if content.contains('\u{feff}') {
            return Err(source.error(number, crate::points::BOM_INSIDE.to_string()));
        }
        if content.contains('"') {
            return Err(source.error(
                number,
                format!(
                    "a quote in plain text, where quotes mean nothing: {} (a CSV file: condt's \
                     --input-format csv)",
                    quoted(content.trim())
                ),
            ));
        }
        let fields = crate::points::columns(content).map_err(|m| source.error(number, m))?;
        for (k, field) in fields.iter().enumerate() {
            if k > 0 {
                tabbed.push('\t');
            }
            tabbed.push_str(field);
        }
        tabbed.push('\n');
    }
    parse_separated(&tabbed, file, b'\t', Some(chosen)).map_err(|mut err| {
        // A message quotes the line it read, which has tabs for the file's blanks: quote the
        // file's own line instead (a CLI user's review: "1\t2\t3" of a line `1 2  3`).
        if let (Some(line), IoErrorKind::Content(message)) = (err.line, &mut err.kind) {
            let read = tabbed.split('\n').nth(line - 1).unwrap_or_default();
            let own = crate::text_lines(text).find(|&(number, _)| number == line);
            if let Some((_, own)) = own {
                let own = own.split('#').next().unwrap_or("").trim();
                *message = message.replace(&quoted(read), &quoted(own));
            }
            // Names chosen over a first line of numbers: a header written as a comment above it
            // is named (`numpy.savetxt(header=...)` writes `# angle range x y intensity`).
            if message.contains(NUMBERS_NOT_A_HEADER) {
                let above = crate::text_lines(text).take_while(|&(number, _)| number < line);
                let width = read.split('\t').count();
                if let Some(header) = commented_header(above.map(|(_, l)| l), chosen, width) {
                    message.push_str(&format!(
                        "; the comment {} above names them: without its `#` it is the header",
                        quoted(header)
                    ));
                }
            }
        }
        err
    })
}

/// What the refusal of columns chosen by name over a first line of numbers says of that line.
const NUMBERS_NOT_A_HEADER: &str = "numbers, not a header naming them";

/// [`parse_plain_columns`] for columns chosen by number (0-based `x` and `y`), read straight from
/// the lines, without the tab-joined copy and the CSV reader: a scanner's `x y z intensity`
/// export of 1M points read in 0.23-0.25 s instead of 0.47-0.59 (docs/performance.md, *Chosen
/// columns of plain text*). `None` wherever a line needs the general reading (a
/// comma, a quote, a vertical tab, a character beyond ASCII, a row of another width than the
/// first, a header without
/// the chosen columns, a field that is no finite number, too many points): that reading then
/// reads the whole text and gives its own message, so the two agree by construction on every
/// text this one reads.
fn plain_numbered_columns(
    text: &str,
    source: &Source<'_>,
    x: usize,
    y: usize,
) -> Option<Vec<Point>> {
    let mut width = None;
    let mut points = Vec::new();
    for (number, line) in crate::text_lines(text) {
        let content = line.split('#').next().unwrap_or("");
        // ASCII only (a byte-order mark, or any other character beyond it, goes the general
        // way), where ASCII blanks split as the plain reader's Unicode ones do but for the
        // vertical tab, which only the plain reader's split (Unicode's) takes for a blank.
        if content
            .bytes()
            .any(|b| b == b',' || b == b'"' || b == 0x0b || !b.is_ascii())
        {
            return None;
        }
        let (mut count, mut x_field, mut y_field) = (0, None, None);
        for (k, field) in content.split_ascii_whitespace().enumerate() {
            if k == x {
                x_field = Some(field);
            }
            if k == y {
                y_field = Some(field);
            }
            count = k + 1;
        }
        if count == 0 {
            continue;
        }
        let (x_field, y_field) = (x_field?, y_field?);
        match width {
            // As the general reading tells a header: a first line whose chosen fields are no
            // numbers (a labelled point has a number there).
            None if x_field.parse::<f64>().is_err() && y_field.parse::<f64>().is_err() => {
                width = Some(count);
                continue;
            }
            None => width = Some(count),
            Some(width) if width != count => return None,
            Some(_) => {}
        }
        let point = Point::new(
            source.number(number, x_field).ok()?,
            source.number(number, y_field).ok()?,
        );
        if points.len() == MAX_POINTS {
            return None;
        }
        points.try_reserve(1).ok()?;
        points.push(point);
    }
    Some(points)
}

/// The refusal of a first row of `count` numbers, more than two, without a header: which two
/// are x and y would be a guess (an `id x y` export).
pub(crate) fn numbers_without_header(count: usize) -> String {
    format!(
        "{count} numbers and no header: a CSV of two columns is read as x, y without one, with \
         more a header line must name the x and y columns (or --columns X,Y their numbers from 1)"
    )
}

/// The first line of `text` that is not blank (lines end at LF, CR or CRLF), without the
/// byte-order mark that may start the text: no reader takes it for part of the first name.
pub(crate) fn first_line_with_content(text: &str) -> &str {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text.split(['\r', '\n']);
    lines.find(|l| !l.trim().is_empty()).unwrap_or("")
}

/// [`parse_csv`] with columns separated by `delimiter` (`,` or a tab), x and y read from
/// `chosen` when given.
///
/// With `chosen`, the first record is a header unless it is all numbers, or, when both columns
/// are chosen by number, unless either of its chosen fields is a number (`a,1,2` is a point
/// with a label, and `a,1,NA` a point with a bad y, not a header to skip); a first record that
/// is a point must hold both columns chosen (a number past its end is refused naming it). A
/// column chosen by name needs a header that names it once.
pub(crate) fn parse_separated(
    text: &str,
    file: &str,
    delimiter: u8,
    chosen: Option<&Columns>,
) -> Result<Vec<Point>, IoError> {
    let source = Source { file };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut reader = csv::ReaderBuilder::new()
        .delimiter(delimiter)
        .has_headers(false)
        // Rows of any length: a short row gets this module's message, naming the column.
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut lines = LineCounter::new(text.as_bytes());
    let mut record = csv::StringRecord::new();
    let mut columns: Option<(usize, usize)> = None;
    // Fields per record: the header's, or two without one.
    let (mut width, mut headerless) = (0, false);
    let mut points = Vec::new();
    loop {
        let start = reader.position().byte() as usize;
        let more = reader.read_record(&mut record).map_err(|err| {
            let at = err.position().map_or(start, |p| p.byte() as usize);
            source.error(lines.line_at(at), format!("not a CSV record: {err}"))
        })?;
        if !more {
            break;
        }
        // Where this record starts and where the next one does. The crate may place a record
        // at the line end before it (the `\n` of a CRLF, empty lines it skipped), which a
        // record cannot start with.
        let mut start = record.position().map_or(start, |p| p.byte() as usize);
        while matches!(text.as_bytes().get(start), Some(b'\r' | b'\n')) {
            start += 1;
        }
        let end = reader.position().byte() as usize;
        let raw = text.get(start..end).unwrap_or_default();
        // A blank line, or a spreadsheet's empty row (only separators), holds no point.
        if record.iter().all(|field| field.trim().is_empty()) && !raw.contains('"') {
            continue;
        }
        let line = lines.line_at(start);
        check_quotes(raw.as_bytes(), delimiter).map_err(|m| source.error(line, m.to_string()))?;
        let (x_column, y_column) = match (columns, chosen) {
            (Some(columns), _) => columns,
            (None, Some(chosen)) => {
                let numbered = match (&chosen.x, &chosen.y) {
                    (Column::Number(x), Column::Number(y)) => Some((x - 1, y - 1)),
                    _ => None,
                };
                let number = |k: usize| {
                    record
                        .get(k)
                        .is_some_and(|f| f.trim().parse::<f64>().is_ok())
                };
                // A row of numbers is never a header, whichever columns are chosen.
                let is_point = match numbered {
                    Some((x, y)) => number(x) || number(y) || all_numbers(&record),
                    None => all_numbers(&record),
                };
                width = record.len();
                if is_point {
                    let Some(numbered) = numbered else {
                        return Err(source.error(
                            line,
                            format!(
                                "columns {chosen} are chosen by name, but the first line is \
                                 {NUMBERS_NOT_A_HEADER}: {}",
                                quoted(raw.trim_end_matches(['\r', '\n']))
                            ),
                        ));
                    };
                    // A chosen column past the first row's end: said of the row, not of a
                    // later field count.
                    let (x, y) = numbered;
                    if let Some((k, axis)) = [(x, "x"), (y, "y")]
                        .into_iter()
                        .find(|&(k, _)| k >= record.len())
                    {
                        return Err(source.error(
                            line,
                            format!(
                                "column {} (chosen for {axis}) does not exist: the row has {} \
                                 (a point, not a header): {}",
                                k + 1,
                                counted(record.len(), "column"),
                                quoted(raw.trim_end_matches(['\r', '\n']))
                            ),
                        ));
                    }
                    headerless = true;
                    *columns.insert(numbered)
                } else {
                    columns = Some(chosen_columns(
                        chosen, &record, raw, delimiter, &source, line,
                    )?);
                    continue;
                }
            }
            // `numpy.savetxt(..., delimiter=",")` writes no header: two numbers can only be x, y.
            (None, None) if headerless_pair(&record) => {
                (width, headerless) = (2, true);
                *columns.insert((0, 1))
            }
            (None, None) => {
                columns = Some(header_columns(&record, raw, delimiter, &source, line)?);
                width = record.len();
                continue;
            }
        };
        let first = if headerless {
            "the first line"
        } else {
            "the header"
        };
        // More fields than the first line has: a decimal comma (`1,5,2,5`) or a shifted row,
        // which read silently would be wrong coordinates. Empty ones (a trailing comma, which
        // some exporters write) hold nothing to misread.
        if record.len() > width && record.iter().skip(width).any(|f| !f.trim().is_empty()) {
            // One more on the first row under a header: R's `write.table`, whose row names
            // are a first column the header does not name (an R user's review).
            let r = if !headerless
                && points.is_empty()
                && record.len() == width + 1
                && crate::points::may_be_row_name(&record[0])
            {
                crate::points::ROW_NAMES
            } else {
                ""
            };
            return Err(source.error(
                line,
                format!("{}, but {first} has {width}{r}", fields(record.len())),
            ));
        }
        // Fewer: a row cut short (a file cut off mid-line, a field lost), whose chosen columns
        // can still be there with a wrong number in them (`500000.03,50` of a scanner's export).
        if record.len() < width {
            return Err(source.error(
                line,
                format!(
                    "{}, but {first} has {width}: a row cut short?",
                    fields(record.len())
                ),
            ));
        }
        let coordinate = |column: usize, axis: &str| -> Result<f64, IoError> {
            let field = record.get(column).ok_or_else(|| {
                source.error(
                    line,
                    format!(
                        "{}, but the {axis} column is field {}",
                        fields(record.len()),
                        column + 1
                    ),
                )
            })?;
            source.number(line, field.trim())
        };
        let point = Point::new(coordinate(x_column, "x")?, coordinate(y_column, "y")?);
        if points.len() == MAX_POINTS {
            return Err(source.error(
                line,
                format!("more than {MAX_POINTS} points, the most condt accepts"),
            ));
        }
        points
            .try_reserve(1)
            .map_err(|_| source.error(line, "too many points to hold in memory".to_string()))?;
        points.push(point);
    }
    Ok(points)
}

/// A count and its noun, plural unless the count is one: "1 column", "3 columns".
fn counted(n: usize, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

/// `n fields`, or `1 field`.
fn fields(n: usize) -> String {
    if n == 1 {
        "1 field".to_string()
    } else {
        format!("{n} fields")
    }
}

/// The last comment line of `before` (the text above the first point) that names both chosen
/// columns, one name for each of the first point's `width` columns, as
/// `numpy.savetxt(header=...)` writes a header (`# angle range x y intensity`): a header made a
/// comment, which the refusal of names without a header points at (a robotics user's review). A
/// comment of another count is no such header: without its `#`, `# x y` over `1 2 3` is refused
/// for its count, and a sentence (`# x and y in metres`) was named as the header.
fn commented_header<'t>(
    before: impl Iterator<Item = &'t str>,
    chosen: &Columns,
    width: usize,
) -> Option<&'t str> {
    let named = |column: &Column, fields: &[&str]| match column {
        Column::Named(name) => fields.iter().any(|f| same_name(f, name)),
        Column::Number(_) => false,
    };
    // Split as the line would be without its `#`: the plain reader's columns.
    before
        .map(str::trim)
        .filter(|line| {
            let fields = line
                .strip_prefix('#')
                .map(|rest| columns(rest).unwrap_or_default());
            fields.is_some_and(|fields| {
                fields.len() == width && named(&chosen.x, &fields) && named(&chosen.y, &fields)
            })
        })
        .last()
}

/// Whether the first record is a point rather than a header: exactly two fields, both numbers,
/// and maybe empty fields after them (a separator at every line's end, as some exports write).
/// With more columns, which two are x and y is a guess (`id,x,y`), so a header must say.
fn headerless_pair(record: &csv::StringRecord) -> bool {
    filled(record) == 2 && all_numbers(record)
}

/// How many fields `record` has before the empty ones that end it.
fn filled(record: &csv::StringRecord) -> usize {
    let empty_at_end = record.iter().rev().take_while(|f| f.trim().is_empty());
    record.len() - empty_at_end.count()
}

/// Whether every field of `record` reads as a number (a finite one or not: a point's check names
/// the line of a non-finite one), but the empty fields that end it.
fn all_numbers(record: &csv::StringRecord) -> bool {
    record
        .iter()
        .take(filled(record))
        .all(|f| f.trim().parse::<f64>().is_ok())
}

/// How a first line that is no header for this reader writes a point: with semicolons between
/// its columns or decimal commas (`1,5;2,5`, `1.5;2.5`, `1,5<TAB>2,5`), as spreadsheets in many
/// European locales export it; `None` for anything else. Taken for a header, such a line was
/// said to lack an x column (a CAD user's review). A point as [`headerless_pair`] takes one: two
/// numbers, maybe a separator at the end (`1,5;2,5;`); more numbers are no point (`id;x;y`, whose
/// first two a .txt would read as x and y), and the refusal of a header without x says the rest.
fn point_of_another_locale(raw: &str) -> Option<&'static str> {
    let line = raw.trim_end_matches(['\r', '\n']);
    let separator = if line.contains(';') { ';' } else { '\t' };
    let mut fields: Vec<&str> = line.split(separator).map(str::trim).collect();
    while fields.len() > 2 && fields.last() == Some(&"") {
        fields.pop();
    }
    let number = |f: &str| f.parse::<f64>().is_ok() || is_decimal_comma(f);
    if fields.len() != 2 || !fields.iter().all(|f| number(f)) {
        return None;
    }
    // Without semicolons, a comma before exactly three digits may as well group thousands (an
    // English spreadsheet's `1,000`), which `tr`'s decimal point would read as 1.
    match (separator == ';', line.contains(',')) {
        (true, true) => Some(SEMICOLONS_AND_COMMAS),
        (true, false) if fields.iter().any(|f| may_group_thousands_by_dots(f)) => {
            Some(SEMICOLONS_THOUSANDS_OR_DECIMALS)
        }
        (true, false) => Some("semicolons between its columns"),
        (false, true) if fields.iter().any(|f| may_group_thousands(f)) => {
            Some(THOUSANDS_OR_DECIMALS)
        }
        (false, true) => Some("decimal commas"),
        (false, false) => None,
    }
}

/// How [`point_of_another_locale`] reads a tab-separated point whose comma may group thousands.
const THOUSANDS_OR_DECIMALS: &str = "commas in its numbers (decimal commas, or thousands grouped)";

/// How [`point_of_another_locale`] reads a point of semicolons and decimal commas.
const SEMICOLONS_AND_COMMAS: &str = "semicolons between its columns and decimal commas";

/// How [`point_of_another_locale`] reads a point of semicolons whose dot may group thousands.
const SEMICOLONS_THOUSANDS_OR_DECIMALS: &str =
    "semicolons between its columns and dots in its numbers (decimal points, or thousands grouped)";

/// Whether `field` has one dot, before exactly three digits (`1.100`): in a semicolon-separated
/// export it may group thousands (a German spreadsheet's `1.100`) as well as be a decimal point.
fn may_group_thousands_by_dots(field: &str) -> bool {
    field.matches('.').count() == 1
        && field
            .split_once('.')
            .is_some_and(|(_, after)| after.len() == 3 && after.bytes().all(|b| b.is_ascii_digit()))
}

/// The x and y columns named by the header `record` (its text `raw`, on `line`).
fn header_columns(
    record: &csv::StringRecord,
    raw: &str,
    delimiter: u8,
    source: &Source<'_>,
    line: usize,
) -> Result<(usize, usize), IoError> {
    let header = quoted(raw.trim_end_matches(['\r', '\n']));
    let axes = header_axes(record.iter());
    let find = |wanted: char, axis: &str| {
        let mut named = (0..record.len()).filter(|&k| axes[k] == Some(wanted));
        match (named.next(), named.next()) {
            (Some(column), None) => Ok(column),
            (None, _) => {
                // A semicolon-separated file reads as one column here: say so. With columns
                // to choose from, say how to choose them.
                let one_field = record.len() == 1;
                let tabs = delimiter == b'\t';
                let hint = if one_field && tabs {
                    "; its columns are split at tabs (a .tsv, or a first line with tabs), and \
                     this header has none: a header of commas is a .csv's, of spaces a .txt's"
                } else if raw.contains(';') {
                    "; this reader splits columns at commas, not semicolons (and a comma is no \
                     decimal point here: 1.5, not 1,5)"
                } else if one_field && raw.trim().contains(char::is_whitespace) {
                    "; this reader splits columns at commas, and this header has none: columns \
                     separated by spaces are the plain format's (name the file *.txt)"
                } else if record.len() >= 2 {
                    "; choose the x and y columns by name or number with condt's --columns X,Y"
                } else {
                    ""
                };
                // A first line of number-like fields, one of them not a number (`1O,20`, a
                // letter O), is a mistyped point rather than a header: say which field.
                let number_like = |f: &str| {
                    let f = f.trim().trim_start_matches(['-', '+', '.']);
                    f.starts_with(|c: char| c.is_ascii_digit())
                };
                let pair = || record.iter().take(2);
                let not_number = (filled(record) == 2 && pair().all(number_like))
                    .then(|| pair().find(|f| f.trim().parse::<f64>().is_err()))
                    .flatten();
                let typo = not_number.map_or(String::new(), |field| {
                    format!(
                        "; if it is a point, {} is not a number",
                        quoted(field.trim())
                    )
                });
                Err(source.error(
                    line,
                    format!("the header has no {axis} column ({NAMES_READ}): {header}{typo}{hint}"),
                ))
            }
            // Two columns for one axis (`x,y,x`, `x,y,lon,lat`): which to read would be a guess.
            (Some(first), Some(second)) => Err(source.error(
                line,
                format!(
                    "the header names the {axis} coordinate in two columns ({} and {}): {header}; \
                     keep one, or choose the x and y columns with condt's --columns X,Y",
                    first + 1,
                    second + 1
                ),
            )),
        }
    };
    if filled(record) > 2 && all_numbers(record) {
        return Err(source.error(line, numbers_without_header(filled(record))));
    }
    if let Some(written) = point_of_another_locale(raw) {
        // `tr` makes every comma a decimal point: no advice where a comma may group thousands.
        // With decimal commas, a dot can only group thousands (`1.234,5`): `tr` alone made
        // `1.100;2.000,5` the point (1.1, 2.0), so the advice drops the dots first. Without a
        // comma, a dot before three digits may group thousands as well (`1.100;2.000`).
        let convert = match written {
            THOUSANDS_OR_DECIMALS | SEMICOLONS_THOUSANDS_OR_DECIMALS => "",
            SEMICOLONS_AND_COMMAS => {
                " (`tr -d . < in.csv | tr ';,' ' .' > in.txt` turns one into the other, dropping \
                 the dots that group thousands)"
            }
            _ => " (`tr ';' ' ' < in.csv > in.txt` turns one into the other)",
        };
        return Err(source.error(
            line,
            format!(
                "{header} is a point with {written}, which this reader does not take: \
                 write 1.5,2.5 in a .csv or 1.5 2.5 in a .txt{convert}"
            ),
        ));
    }
    let x_column = find('x', "x")?;
    let y_column = find('y', "y")?;
    Ok((x_column, y_column))
}

/// The x and y columns `chosen` in the header `record` (its text `raw`, on `line`, its fields
/// split at `delimiter`): a name must name one column (without case and blanks around it), a
/// number be one of the header's.
fn chosen_columns(
    chosen: &Columns,
    record: &csv::StringRecord,
    raw: &str,
    delimiter: u8,
    source: &Source<'_>,
    line: usize,
) -> Result<(usize, usize), IoError> {
    let header = quoted(raw.trim_end_matches(['\r', '\n']));
    // A header of one field that holds semicolons is a semicolon-separated file: said so, as
    // without chosen columns (a GIS user's review: the hint was missing here).
    let split_at = if delimiter == b'\t' { "tabs" } else { "commas" };
    let semicolons = if record.len() == 1 && raw.contains(';') {
        format!("; this reader splits columns at {split_at}, not semicolons")
    } else if record.len() == 1 && raw.trim().contains(char::is_whitespace) {
        // Standard input with columns is read as CSV: a scan's `x y z i` piped in.
        format!(
            "; this reader splits columns at {split_at}, and columns separated by blanks are \
             plain text's (condt's --input-format txt)"
        )
    } else {
        String::new()
    };
    let names = || {
        record
            .iter()
            .map(|name| quoted(name.trim()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let find = |column: &Column, axis: &str| -> Result<usize, IoError> {
        match column {
            Column::Number(number) if *number <= record.len() => Ok(number - 1),
            Column::Number(number) => Err(source.error(
                line,
                format!(
                    "column {number} is chosen for {axis}, but the header has {}: {}{semicolons}",
                    counted(record.len(), "column"),
                    names()
                ),
            )),
            Column::Named(name) => {
                let wanted = name.trim();
                let mut named = (0..record.len()).filter(|&k| same_name(&record[k], wanted));
                match (named.next(), named.next()) {
                    (Some(k), None) => Ok(k),
                    (None, _) => Err(source.error(
                        line,
                        format!(
                            "no column named {} (chosen for {axis}) in the header {header}; its \
                             columns are {}{semicolons}",
                            quoted(wanted),
                            names()
                        ),
                    )),
                    (Some(first), Some(second)) => Err(source.error(
                        line,
                        format!(
                            "the header names two columns {} ({} and {}), chosen for {axis}: \
                             {header}; choose one by its number",
                            quoted(wanted),
                            first + 1,
                            second + 1
                        ),
                    )),
                }
            }
        }
    };
    let (x, y) = (find(&chosen.x, "x")?, find(&chosen.y, "y")?);
    if x == y {
        return Err(source.error(
            line,
            format!(
                "columns {chosen} are the same column of the header {header}, x and y need two"
            ),
        ));
    }
    Ok((x, y))
}

/// Refuses what the `csv` crate reads without complaint but RFC 4180 does not allow: text after
/// the closing quote of a field (`"1"5`, which the crate reads as `15`) and a quoted field that
/// is never closed (which it ends at the end of the file). `raw` is one record as written, its
/// line end included; `delimiter` separates its fields, as the crate was told: a field starts
/// after it and a quoted one ends before it (with a comma there, a TSV's `"a"\t"b"` was refused
/// and its `"1"5` read as `15`).
fn check_quotes(raw: &[u8], delimiter: u8) -> Result<(), &'static str> {
    let mut at = 0;
    let mut field_start = true;
    while let Some(&byte) = raw.get(at) {
        if field_start && byte == b'"' {
            at += 1;
            loop {
                match (raw.get(at), raw.get(at + 1)) {
                    (None, _) => return Err("a quoted field is not closed"),
                    (Some(b'"'), Some(b'"')) => at += 2,
                    (Some(b'"'), _) => break,
                    _ => at += 1,
                }
            }
            at += 1;
            match raw.get(at) {
                Some(&b) if b == delimiter || b == b'\r' || b == b'\n' => {}
                None => {}
                // R's write.csv2 and readr's write_excel_csv2 quote their names: the refusal
                // of `"";"x";"y"` said nothing of semicolons (an R user's review).
                Some(b';') => {
                    return Err(
                        "text after the closing quote of a field: a semicolon, which \
                                separates no columns here (R's write.csv2 and spreadsheets in \
                                many European locales write semicolons between columns and \
                                decimal commas; write commas and decimal points: R's write.csv)",
                    )
                }
                // R's write.table under a `.csv` name: its columns are the plain format's.
                Some(b' ') if delimiter == b',' => {
                    return Err("text after the closing quote of a field: a blank, which \
                                separates no columns in a CSV (R's write.table writes blanks \
                                between columns: write.csv writes commas)")
                }
                Some(_) => return Err("text after the closing quote of a field"),
            }
            field_start = false;
            continue;
        }
        field_start = byte == delimiter;
        at += 1;
    }
    Ok(())
}

/// Line numbers of byte offsets met in increasing order, with the line ends of the other point
/// readers (LF, CRLF or a lone CR), counted once over the whole text.
struct LineCounter<'a> {
    bytes: &'a [u8],
    offset: usize,
    line: usize,
}

impl<'a> LineCounter<'a> {
    fn new(bytes: &'a [u8]) -> LineCounter<'a> {
        LineCounter {
            bytes,
            offset: 0,
            line: 1,
        }
    }

    /// The 1-based line holding byte `offset` (not before the last one asked for).
    fn line_at(&mut self, offset: usize) -> usize {
        let offset = offset.clamp(self.offset, self.bytes.len());
        let bytes = self.bytes;
        self.line += bytes[self.offset..offset]
            .iter()
            .enumerate()
            .filter(|&(i, &b)| {
                b == b'\n' || (b == b'\r' && bytes.get(self.offset + i + 1) != Some(&b'\n'))
            })
            .count();
        self.offset = offset;
        self.line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lone_carriage_returns_end_lines() {
        let pts = parse_csv("x,y\r1,2\r3,4\r", "mac.csv").unwrap();
        assert_eq!(pts, vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0)]);
        let err = parse_csv("x,y\r1,2\r3,z\r", "mac.csv").unwrap_err();
        assert_eq!(err.line, Some(3));
    }

    /// R's `write.table(df, sep = ",")` or `sep = "\t"` writes its row names as a first
    /// column the header does not name: the refusal says so (an R user's review), on the
    /// first row only (a later row with a field too many is a shifted row).
    #[test]
    fn a_first_row_one_field_longer_than_the_header_names_r_row_names() {
        for (text, name) in [
            ("\"x\",\"y\"\n\"1\",1100,2000.5\n", "r.csv"),
            ("x\ty\n1\t1100\t2000.5\n", "r.tsv"),
        ] {
            let err = parse_csv(text, name).unwrap_err().to_string();
            assert!(err.contains(":2: 3 fields, but the header has 2"), "{err}");
            assert!(err.contains("row.names = FALSE"), "{err}");
        }
        let err = parse_csv("x,y\n1,2\n1,2,3\n", "s.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(err, "s.csv:3: 3 fields, but the header has 2");
        // A coordinate first is no row name: the plain refusal, without R's advice.
        let err = parse_csv("x,y\n10.5,0,0.5\n", "h.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(err, "h.csv:2: 3 fields, but the header has 2");
    }

    #[test]
    fn the_header_chooses_the_columns_in_any_order_and_case() {
        let pts = parse_csv("Latitude,Longitude\r\n1,2\r\n\r\n3,4\r\n", "geo.csv").unwrap();
        assert_eq!(pts, vec![Point::new(2.0, 1.0), Point::new(4.0, 3.0)]);
        // `long`, as many GIS exports name longitude (a GIS review: refused as "no x column").
        let pts = parse_csv("id,lat,long\n7,47.3,8.5\n", "geo.csv").unwrap();
        assert_eq!(pts, vec![Point::new(8.5, 47.3)]);
    }

    /// Columns chosen by name over a plain file whose header is a comment (as
    /// `numpy.savetxt(header=...)` writes it) name that comment (a robotics user's review: the
    /// refusal said only that the first line is numbers).
    #[test]
    fn a_header_written_as_a_comment_is_named() {
        let chosen = Columns::parse("x,y").unwrap();
        let text = "# scan 7\n# angle range x y intensity\n0 1 1 0 5\n0.5 1 0.9 0.4 5\n";
        let err = parse_plain_columns(text, "scan.txt", &chosen).unwrap_err();
        assert_eq!(err.line, Some(3));
        let said = err.to_string();
        assert!(
            said.ends_with(
                "; the comment \"# angle range x y intensity\" above names them: without its `#` \
                 it is the header"
            ),
            "{said}"
        );
        // A comment that does not name both is no header, nor one of another count of names
        // than the columns: a sentence, or names that would be refused for their count.
        for text in [
            "# x only\n1 2 3\n",
            "# x and y in metres\n1 2 3\n",
            "# x y\n1 2 3\n",
        ] {
            let err = parse_plain_columns(text, "scan.txt", &chosen).unwrap_err();
            assert!(!err.to_string().contains("above names them"), "{err}");
        }
        // Without its `#`, the header the refusal names reads the file.
        let header = "angle range x y intensity\n0 1 1 0 5\n0.5 1 0.9 0.4 5\n";
        let read = parse_plain_columns(header, "scan.txt", &chosen).unwrap();
        assert_eq!(read, vec![Point::new(1.0, 0.0), Point::new(0.9, 0.4)]);
    }

    /// A first line that is a point written with semicolons between its columns or with decimal
    /// commas is told as one, not taken for a header without an x column (a CAD user's review).
    #[test]
    fn a_point_of_another_locale_is_not_taken_for_a_header() {
        for (text, written) in [
            ("1.5;2.5\n3;4\n", "semicolons between its columns"),
            (
                "1,5;-2,5\n3;4\n",
                "semicolons between its columns and decimal commas",
            ),
            ("1,5\t2,5\n3\t4\n", "decimal commas"),
            // A separator at every line's end, as some exports write.
            (
                "1,5;2,5;\n3;4;\n",
                "semicolons between its columns and decimal commas",
            ),
        ] {
            let err = parse_csv(text, "locale.csv").unwrap_err();
            assert_eq!(err.line, Some(1), "{text}");
            let message = err.to_string();
            assert!(
                message.contains(&format!("is a point with {written}, which this reader"))
                    && !message.contains("header"),
                "{message}"
            );
        }
        // A comma before three digits of a tab-separated point may group thousands: said so,
        // without the `tr` line that would read `1,000` as 1.
        let message = parse_csv("1,000\t2,5\n3\t4\n", "locale.csv")
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("is a point with commas in its numbers (decimal commas, or thousands")
                && !message.contains("tr "),
            "{message}"
        );
        // More numbers than a point's are no point: told as a first line without an x column
        // (`tr` to a .txt would read `id;x;y`'s id and x as the point).
        for text in ["1;2;3\n4;5;6\n", "5;-3;2,5;0,25\n"] {
            let message = parse_csv(text, "locale.csv").unwrap_err().to_string();
            assert!(
                !message.contains("is a point") && message.contains("not semicolons"),
                "{message}"
            );
        }
    }

    /// The `tr` advice for a point of semicolons and decimal commas drops the dots that group
    /// thousands first (an R and Excel user's review: `tr ';,' ' .'` made `1.100;2.000,5` the
    /// point (1.1, 2.0) without a word), and a semicolon point whose dot stands before three
    /// digits gets no advice: `1.100` may be 1100 (a German spreadsheet) or 1.1.
    #[test]
    fn the_tr_advice_keeps_thousands_apart_from_decimals() {
        let message = parse_csv("1100;2000,5\n1.099,45;2.010,95\n", "de.csv")
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("`tr -d . < in.csv | tr ';,' ' .' > in.txt`"),
            "{message}"
        );
        let message = parse_csv("1.100;2.000\n1.099;2.010\n", "de.csv")
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("(decimal points, or thousands grouped)") && !message.contains("tr "),
            "{message}"
        );
        let message = parse_csv("1.5;2.25\n3;4\n", "de.csv")
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("`tr ';' ' ' < in.csv > in.txt`"),
            "{message}"
        );
    }

    /// A quoted field followed by a semicolon (R's write.csv2, `"";"x";"y"`) or a blank (R's
    /// write.table under a `.csv` name, `"x" "y"`) says which separator it met and what
    /// writes commas (an R user's review: "text after the closing quote" alone).
    #[test]
    fn a_quoted_field_before_a_semicolon_or_a_blank_names_it() {
        let err = parse_csv("\"\";\"x\";\"y\"\n\"1\";1100;2000,5\n", "r2.csv").unwrap_err();
        assert_eq!(err.line, Some(1));
        let message = err.to_string();
        assert!(
            message.contains("a semicolon") && message.contains("R's write.csv)"),
            "{message}"
        );
        let message = parse_csv("\"x\" \"y\"\n\"1\" 1100 2000.5\n", "r.csv")
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("a blank") && message.contains("write.csv writes commas"),
            "{message}"
        );
        let message = parse_csv("x,y\n\"1\"5,2\n", "q.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(message, "q.csv:2: text after the closing quote of a field");
    }

    /// A header naming one coordinate twice is refused, not resolved by column order (a new
    /// user's report: `x,y,x` and `lat,lon,x` were read without a word).
    #[test]
    fn a_coordinate_named_in_two_columns_is_refused() {
        for (header, axis) in [
            ("x,y,x", "x"),
            ("x,y,lon,lat", "x"),
            ("lat,lon,x", "x"),
            ("y,x,lat", "y"),
        ] {
            let err = parse_csv(&format!("{header}\n1,2,3,4\n"), "h.csv").unwrap_err();
            assert_eq!(err.line, Some(1), "{header}");
            let message = err.to_string();
            assert!(
                message.contains(&format!("the {axis} coordinate in two columns")),
                "{message}"
            );
        }
        let err = parse_csv("x;y\n1;2\n", "semi.csv").unwrap_err().to_string();
        assert!(err.contains("not semicolons"), "{err}");
        assert!(
            !err.contains("--columns"),
            "one column, nothing to choose: {err}"
        );
        // And with the columns chosen, by name or number, as the header's one field is no
        // column of either (a GIS user's review).
        for spec in ["Shape_X,Shape_Y", "2,1"] {
            let chosen = Columns::parse(spec).unwrap();
            let err = parse_csv_columns("Shape_X;Shape_Y\n1;2\n", "semi.csv", Some(&chosen))
                .unwrap_err()
                .to_string();
            assert!(err.contains("at commas, not semicolons"), "{spec}: {err}");
        }
    }

    /// A decimal comma in a field the CSV reader did not split there (quoted, as a
    /// comma-separated export quotes it, or in a tab-separated table) is named as one, as the
    /// plain format's reader names it (a CAD user's review: a European locale's probe export).
    #[test]
    fn a_decimal_comma_in_a_field_is_named() {
        for (text, name) in [
            ("x,y\n\"1,5\",\"2,5\"\n", "q.csv"),
            ("x\ty\n1,5\t2,5\n", "t.csv"),
            ("x\ty\n0.5\t-0,25\n", "t.tsv"),
        ] {
            let err = parse_csv(text, name).unwrap_err().to_string();
            assert!(
                err.contains(":2: cannot read")
                    && err.ends_with("(a decimal comma? Write 1.5, not 1,5)"),
                "{name}: {err}"
            );
        }
        // Before three digits the comma may group thousands.
        let err = parse_csv("x,y\n\"1,000\",2\n", "q.csv")
            .unwrap_err()
            .to_string();
        assert!(
            err.ends_with("(a decimal comma, or thousands grouped? Write 1.5 or 1000)"),
            "{err}"
        );
        // A word with a comma is no decimal comma.
        let err = parse_csv("x,y\n\"a,b\",1\n", "w.csv")
            .unwrap_err()
            .to_string();
        assert!(!err.contains("decimal comma"), "{err}");
    }

    /// A header without x (or y) but with columns to choose from names the option that
    /// chooses them.
    #[test]
    fn a_header_without_x_and_y_names_the_columns_option() {
        for (text, axis) in [
            ("FID,A,B\n1,2,3\n", "x"),
            ("easting\tlat\n1\t2\n", "x"),
            ("x,northing\n1,2\n", "y"),
        ] {
            let err = parse_csv(text, "t.csv").unwrap_err();
            assert_eq!(err.line, Some(1), "{err}");
            let err = err.to_string();
            assert!(
                err.contains(&format!("the header has no {axis} column"))
                    && err.ends_with(
                        "; choose the x and y columns by name or number with condt's \
                         --columns X,Y"
                    ),
                "{err}"
            );
        }
    }

    /// Survey and GIS exports' names (`easting`, `northing`, `POINT_X`, `POINT_Y`, `xcoord`,
    /// `ycoord`) are read where no column is named x, y, lon or lat, in either order; beside
    /// such a column they are other columns, as before they were known.
    #[test]
    fn projected_names_are_read_where_no_column_is_named_x_or_y() {
        let expected = vec![
            Point::new(500000.0, 4000000.0),
            Point::new(500010.0, 4000002.5),
        ];
        for text in [
            "id,Easting,Northing\n1,500000,4000000\n2,500010,4000002.5\n",
            "Northing,Easting\n4000000,500000\n4000002.5,500010\n",
            "FID;x\tPOINT_Y\tPOINT_X\n1\t4000000\t500000\n2\t4000002.5\t500010\n",
            "xcoord,ycoord,z\n500000,4000000,7\n500010,4000002.5,7\n",
            "N,E\n4000000,500000\n4000002.5,500010\n",
            "id,east,north\n1,500000,4000000\n2,500010,4000002.5\n",
        ] {
            assert_eq!(parse_csv(text, "p.csv").unwrap(), expected, "{text}");
        }
        let beside = "x,y,easting,northing\n0,1,500000,4000000\n";
        assert_eq!(
            parse_csv(beside, "p.csv").unwrap(),
            vec![Point::new(0.0, 1.0)]
        );
        // Only one rank is read: x beside northing has no y column, as before.
        let err = parse_csv("x,northing\n1,2\n", "p.csv").unwrap_err();
        assert!(
            err.to_string().contains("the header has no y column"),
            "{err}"
        );
        let err = parse_csv("easting,northing,POINT_X\n1,2,3\n", "p.csv").unwrap_err();
        assert!(
            err.to_string()
                .contains("x coordinate in two columns (1 and 3)"),
            "{err}"
        );
    }

    /// A first line with tabs and no comma makes the file tab-separated (TSV); with a comma in
    /// it, tabs are part of the fields as before.
    #[test]
    fn tabs_separate_columns_when_the_first_line_has_no_comma() {
        let tsv = "\nid\tlon\t\"lat\"\r\n1\t8.5\t47.3\n\t\t\n2\t\"8.25\"\t47\n";
        let expected = vec![Point::new(8.5, 47.3), Point::new(8.25, 47.0)];
        assert_eq!(parse_csv(tsv, "p.tsv").unwrap(), expected);
        let err = parse_csv("id,lon\tlat\n1,8.5\t47.3\n", "p.csv").unwrap_err();
        assert!(err.to_string().contains("no x column"), "{err}");
    }

    /// A TSV's quotes follow the rules of a CSV's, its tab in place of the comma: a quoted field
    /// ends at a tab, a comma is text, and text after a closing quote or a quote left open in a
    /// later column is refused naming its line (both were checked as if commas separated the
    /// fields: a quoted first field was refused, and `"1"5` read as `15`).
    #[test]
    fn quotes_in_a_tsv_end_at_its_tabs() {
        let tsv = "\"name\"\t\"lon\"\t\"lat\"\n\"a\"\t1\t2\na,\"b\"\t\"3\"\t\"4\"\r\n";
        let expected = vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0)];
        assert_eq!(parse_csv(tsv, "q.tsv").unwrap(), expected);
        assert_eq!(
            parse_separated(tsv, "q.tsv", b'\t', None).unwrap(),
            expected
        );
        for (text, message) in [
            (
                "id\tlon\tlat\na\t\"1\"5\t\"2\"0\n",
                "bad.tsv:2: text after the closing quote of a field",
            ),
            (
                "id\tlon\tlat\nb\t0\t0\na\t\"1\"\t\"2\" \n",
                "bad.tsv:3: text after the closing quote of a field",
            ),
            (
                "id\tlon\tlat\na\t\"1\t2\nb\t0\t0\n",
                "bad.tsv:2: a quoted field is not closed",
            ),
        ] {
            let err = parse_separated(text, "bad.tsv", b'\t', None).unwrap_err();
            assert_eq!(err.to_string(), message, "{text:?}");
        }
    }

    /// `--columns`: x and y from the columns chosen by header name (any case) or number, even
    /// where the header names no x and y (`POINT_X`, `easting`) or names them elsewhere; a
    /// missing or doubled name is refused naming the header line and its columns.
    #[test]
    fn chosen_columns_by_name_or_number() {
        let read = |text: &str, spec: &str| {
            parse_csv_columns(text, "c.csv", Some(&Columns::parse(spec).unwrap()))
        };
        let arcgis =
            "FID,Shape,POINT_X,POINT_Y\n1,Point,2600000.5,1200000\n2,Point,2600010,1200003\n";
        let expected = vec![
            Point::new(2_600_000.5, 1_200_000.0),
            Point::new(2_600_010.0, 1_200_003.0),
        ];
        // ArcGIS's names are read without the option too (where no column is named x, y,
        // lon or lat).
        assert_eq!(parse_csv(arcgis, "c.csv").unwrap(), expected);
        assert_eq!(read(arcgis, "POINT_X,POINT_Y").unwrap(), expected);
        assert_eq!(read(arcgis, " point_x , Point_Y ").unwrap(), expected);
        assert_eq!(read(arcgis, "3,4").unwrap(), expected);
        assert_eq!(read(arcgis, "POINT_X,4").unwrap(), expected);
        // Over a header that names x and y, the chosen columns win; tabs as before.
        let swapped = "x\ty\teasting\tnorthing\n0\t0\t5\t6\n";
        assert_eq!(
            read(swapped, "easting,northing").unwrap(),
            vec![Point::new(5.0, 6.0)]
        );
        // Without a header, numbers choose among any number of columns; a labelled row is a
        // point, and a bad value in one is refused, not skipped as a header.
        assert_eq!(
            read("7,1.5,2,9\n8,3,4,9\n", "2,3").unwrap(),
            vec![Point::new(1.5, 2.0), Point::new(3.0, 4.0)]
        );
        assert_eq!(
            read("a,1.5,2\n", "2,3").unwrap(),
            vec![Point::new(1.5, 2.0)]
        );
        let err = read("a,1,NA\nb,2,3\n", "2,3").unwrap_err();
        assert_eq!(
            (err.line, err.to_string().contains("\"NA\"")),
            (Some(1), true),
            "{err}"
        );
        for (text, spec, line, message) in [
            (
                "\nFID,X,Y\n1,2,3\n",
                "easting,northing",
                2,
                "c.csv:2: no column named \"easting\" (chosen for x) in the header \"FID,X,Y\"; \
                 its columns are \"FID\", \"X\", \"Y\"",
            ),
            (
                "FID,X,Y\n1,2,3\n",
                "X,northing",
                1,
                "c.csv:1: no column named \"northing\" (chosen for y) in the header \"FID,X,Y\"; \
                 its columns are \"FID\", \"X\", \"Y\"",
            ),
            (
                "x,X,y\n1,2,3\n",
                "x,y",
                1,
                "c.csv:1: the header names two columns \"x\" (1 and 2), chosen for x: \"x,X,y\"; \
                 choose one by its number",
            ),
            (
                "FID,X,Y\n1,2,3\n",
                "2,5",
                1,
                "c.csv:1: column 5 is chosen for y, but the header has 3 columns: \"FID\", \"X\", \
                 \"Y\"",
            ),
            (
                "1,2,3\n",
                "X,Y",
                1,
                "c.csv:1: columns X,Y are chosen by name, but the first line is numbers, not a \
                 header naming them: \"1,2,3\"",
            ),
            (
                "FID,X,Y\n1,2\n",
                "2,3",
                2,
                "c.csv:2: 2 fields, but the header has 3: a row cut short?",
            ),
            // A first row of numbers is a point, not a header, whatever columns are chosen: a
            // chosen column past its end does not exist (it once read as "the header has 1
            // columns").
            (
                "\n5\n6\n",
                "2,3",
                2,
                "c.csv:2: column 2 (chosen for x) does not exist: the row has 1 column (a point, \
                 not a header): \"5\"",
            ),
            (
                "1.5,2\n3,4\n",
                "2,3",
                1,
                "c.csv:1: column 3 (chosen for y) does not exist: the row has 2 columns \
                 (a point, not a header): \"1.5,2\"",
            ),
            (
                "1\t2\n",
                "4,3",
                1,
                "c.csv:1: column 4 (chosen for x) does not exist: the row has 2 columns \
                 (a point, not a header): \"1\\t2\"",
            ),
            // A labelled point (its chosen x a number) likewise.
            (
                "a,1.5\n",
                "2,3",
                1,
                "c.csv:1: column 3 (chosen for y) does not exist: the row has 2 columns (a point, \
                 not a header): \"a,1.5\"",
            ),
            (
                "FID\n1\n",
                "1,2",
                1,
                "c.csv:1: column 2 is chosen for y, but the header has 1 column: \"FID\"",
            ),
        ] {
            let err = read(text, spec).unwrap_err();
            assert_eq!(err.line, Some(line), "{err}");
            assert_eq!(err.to_string(), message);
        }
    }

    /// The plain reader's straight path for numbered columns reads what the general one reads, on
    /// random files (headers, comments, blank lines, line ends of every kind, labelled points,
    /// and now and then a line the straight path leaves to the general one: a comma, a word, a
    /// row of another width, a character beyond ASCII); where it gives up, the general reading
    /// answers, error messages included.
    #[test]
    fn plain_numbered_columns_read_as_the_general_reading_does() {
        let mut rng = crate::test_rng::Xorshift::new(0x5851_f42d_4c95_7f2d);
        let mut straight = 0;
        for _ in 0..400 {
            let width = 2 + rng.below(4) as usize;
            let ends = ["\n", "\r\n", "\r"];
            let end = ends[rng.below(3) as usize];
            let mut text = String::new();
            if rng.below(2) == 0 {
                text.push_str("# a scan");
                text.push_str(end);
            }
            if rng.below(2) == 0 {
                let names: Vec<String> = (0..width).map(|k| format!("c{k}")).collect();
                text.push_str(&names.join(" "));
                text.push_str(end);
            }
            for row in 0..rng.below(30) {
                let mut fields: Vec<String> = (0..width)
                    .map(|_| format!("{}", (rng.unit() - 0.5) * 1e3))
                    .collect();
                match rng.below(160) {
                    0 => fields[0] = "x".to_string(),
                    1 => fields.push("7".to_string()),
                    2 => fields[1] = format!("{},5", row),
                    3 => fields[0] = "é".to_string(),
                    4 => fields[0] = "1e400".to_string(),
                    5 => fields.clear(),
                    6 => fields.push("# note".to_string()),
                    // A vertical tab: a blank to the plain reader, not to an ASCII split.
                    7 => fields[0] = format!("{}\u{b}5", fields[0]),
                    _ => {}
                }
                text.push_str(&fields.join(if rng.below(2) == 0 { " " } else { "\t  " }));
                text.push_str(end);
            }
            // Two columns (a column past the width now and then), never the same one twice.
            let x = 1 + rng.below(width as u64 + 1);
            let y = 1 + (x + rng.below(width as u64)) % (width as u64 + 1);
            let chosen = Columns::parse(&format!("{x},{y}")).unwrap();
            let general = plain_columns_in_general(&text, "s.txt", &chosen);
            let source = Source { file: "s.txt" };
            if let Some(points) =
                plain_numbered_columns(&text, &source, x as usize - 1, y as usize - 1)
            {
                straight += 1;
                assert_eq!(general.as_ref().ok(), Some(&points), "{text:?} {x},{y}");
            }
            let read = parse_plain_columns(&text, "s.txt", &chosen);
            assert_eq!(
                read.map_err(|e| e.to_string()),
                general.map_err(|e| e.to_string()),
                "{text:?} {x},{y}"
            );
        }
        assert!(
            straight > 100,
            "the straight path read only {straight} texts"
        );
    }

    /// The plain reader's chosen columns: a message quotes the file's line as written, not the
    /// tab-separated line read from it.
    #[test]
    fn plain_columns_quote_the_line_as_written() {
        let chosen = Columns::parse("4,5").unwrap();
        let err =
            parse_plain_columns("# survey\n1 2  3 # first\n4 5 6\n", "s.txt", &chosen).unwrap_err();
        assert_eq!(
            err.to_string(),
            "s.txt:2: column 4 (chosen for x) does not exist: the row has 3 columns (a point, \
             not a header): \"1 2  3\""
        );
    }

    /// A first line of two number-like fields, one mistyped (a letter O for a zero), is read
    /// as a header, as any non-number is, but the message names the field that is no number.
    #[test]
    fn a_mistyped_first_point_is_named_as_well_as_a_missing_header() {
        let err = parse_csv("1O,20\n3,4\n", "t.csv").unwrap_err().to_string();
        assert!(
            err.contains("the header has no x column")
                && err.contains("if it is a point, \"1O\" is not a number"),
            "{err}"
        );
        let err = parse_csv("id,name\n1,2\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(!err.contains("is not a number"), "{err}");
        let err = parse_csv("1O,20,\n3,4,\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("if it is a point, \"1O\" is not a number"),
            "{err}"
        );
    }

    /// A separator at the end of every line (some exports write one) leaves two numbers and an
    /// empty field: a point, not a header (a CLI user's review: "the header has no x column").
    #[test]
    fn a_separator_ending_each_line_is_no_column() {
        let points = parse_csv("0,0,\n1,0,\n0,1,\n", "t.csv").unwrap();
        assert_eq!(
            points,
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(0.0, 1.0)
            ]
        );
        let err = parse_csv("0,0,5,\n1,0,5,\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(err.contains("3 numbers and no header"), "{err}");
        let err = parse_csv("0,0,\n1,0,7\n", "t.csv").unwrap_err().to_string();
        assert!(err.starts_with("t.csv:2:"), "{err}");
    }

    #[test]
    fn quoted_fields_may_hold_commas_and_quotes() {
        let pts = parse_csv("name,x,y\n\"a \"\"b\"\", c\",1,2\n", "q.csv").unwrap();
        assert_eq!(pts, vec![Point::new(1.0, 2.0)]);
    }

    #[test]
    fn bad_rows_are_refused_by_line() {
        for (text, line, words) in [
            (
                "x,y\n1,2\n3\n",
                3,
                "1 field, but the header has 2: a row cut short?",
            ),
            // A row cut short that still holds x and y: a scanner's export cut off mid-line
            // read 500000.03,50 as a point; so does a row that lost a field.
            (
                "x,y,z,i\n1,2,3,4\n5,6",
                3,
                "2 fields, but the header has 4: a row cut short?",
            ),
            ("x,y\n1,2\n3,abc\n", 3, "cannot read \"abc\""),
            ("x,y\n1,nan\n", 2, "\"nan\" is not finite"),
            (
                "x,y\n1,-1e400\n",
                2,
                "\"-1e400\" is beyond the range of a double",
            ),
            ("x,y\n1,\"2\n", 2, "not closed"),
            ("x,y\n1,2\n\"1\"5,3\n", 3, "after the closing quote"),
            ("x,y\r\n1,2\r\n3,\"4\" \r\n", 3, "after the closing quote"),
            ("x,y\r1,2\r\r3,\"4\"x\r", 4, "after the closing quote"),
            ("\n\nid,y\n", 3, "no x column"),
        ] {
            let err = parse_csv(text, "bad.csv").unwrap_err();
            assert_eq!(err.line, Some(line), "{text:?}");
            assert!(err.to_string().contains(words), "{err}");
        }
    }

    #[test]
    fn quoted_fields_follow_rfc_4180() {
        // A line end inside quotes belongs to the field; the record's line is where it starts,
        // and the lines after it count on.
        let text = "label,x,y\n\"two\nlines\",1,\"2\"\n\"\",3,4\nc,5,bad\n";
        let err = parse_csv(text, "q.csv").unwrap_err();
        assert_eq!(err.line, Some(5), "{err}");
        let pts = parse_csv(&text.replace("bad", "6"), "q.csv").unwrap();
        assert_eq!(
            pts,
            vec![
                Point::new(1.0, 2.0),
                Point::new(3.0, 4.0),
                Point::new(5.0, 6.0)
            ]
        );
        // A quote inside an unquoted field is text, as the crate reads it (and not a number).
        let err = parse_csv("x,y\n1,2\"\n", "q.csv").unwrap_err();
        assert!(err.to_string().contains("cannot read \"2\\\"\""), "{err}");
        // Blank lines, with blanks on them or not, are skipped anywhere.
        let pts = parse_csv("\n  \nx,y\n\n \t\n1,2\n\n", "b.csv").unwrap();
        assert_eq!(pts, vec![Point::new(1.0, 2.0)]);
    }

    #[test]
    fn an_empty_file_has_no_points_and_a_long_token_is_cut() {
        assert_eq!(parse_csv("", "e.csv").unwrap(), vec![]);
        let long = "9".repeat(1000) + "x";
        let err = parse_csv(&format!("x,y\n1,{long}\n"), "l.csv").unwrap_err();
        assert!(err.to_string().len() < 120, "{err}");
    }
}
