//! CSV point files with a header line naming the columns (`x,y`, or `lon,lat`, among others).
//!
//! Owns: [`parse_csv`]. A CSV file says which columns hold the coordinates in its header, so
//! the reader follows the header instead of taking the first two columns as the plain reader
//! does (an `id,x,y` file would otherwise be read as points `(id, x)`).

use super::points::{numbered_lines, quoted, Source};
use super::IoError;
use condt::Point;
use std::vec::Vec;

/// Names accepted for the first coordinate and for the second, compared without case.
const X_NAMES: [&str; 4] = ["x", "lon", "lng", "longitude"];
const Y_NAMES: [&str; 2] = ["y", "lat"];
const Y_LONG_NAME: &str = "latitude";

/// Parses a CSV file with a header line; `file` names the source in error messages.
///
/// The first line that is not blank is the header: comma-separated column names, quoted or
/// not. The first coordinate is the column named `x` (or `lon`, `lng`, `longitude`), the second
/// the column named `y` (or `lat`, `latitude`), compared without case; other columns are
/// ignored. Every following line that is not blank is a point; fields may be quoted (`""` is a
/// quote inside quotes). A missing column, a field that is not a finite number or a row without
/// the coordinate columns is an error naming the line.
///
/// ```
/// use condt::Point;
/// use condt_io::parse_csv;
/// let pts = parse_csv("id,X,\"y\",label\n7,1.5,2,\"a, b\"\n8,3,4,c\n", "points.csv")?;
/// assert_eq!(pts, vec![Point::new(1.5, 2.0), Point::new(3.0, 4.0)]);
///
/// let err = parse_csv("name,value\na,1\n", "table.csv").unwrap_err();
/// assert_eq!(err.line, Some(1));
/// assert!(err.to_string().contains("no x column"));
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn parse_csv(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let source = Source { file };
    let error = |line: usize, message: String| source.error(line, message);
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // Lines end at LF, CRLF or a lone CR, as in every other point format.
    let mut lines = numbered_lines(text).filter(|(_, line)| !line.trim().is_empty());
    let Some((header_line, header)) = lines.next() else {
        return Ok(Vec::new());
    };
    let names = fields(header).map_err(|m| error(header_line, m))?;
    let find = |wanted: &dyn Fn(&str) -> bool, axis: &str| {
        names
            .iter()
            .position(|name| wanted(&name.trim().to_ascii_lowercase()))
            .ok_or_else(|| {
                error(
                    header_line,
                    format!(
                        "the header has no {axis} column (x, lon, lng, longitude and y, lat, \
                         latitude are read): {}",
                        quoted(header)
                    ),
                )
            })
    };
    let x_column = find(&|n| X_NAMES.contains(&n), "x")?;
    let y_column = find(&|n| Y_NAMES.contains(&n) || n == Y_LONG_NAME, "y")?;
    let mut points = Vec::new();
    for (line, row) in lines {
        let values = fields(row).map_err(|m| error(line, m))?;
        let coordinate = |column: usize, axis: &str| -> Result<f64, IoError> {
            let field = values.get(column).ok_or_else(|| {
                error(
                    line,
                    format!(
                        "{} fields, but the {axis} column is field {}",
                        values.len(),
                        column + 1
                    ),
                )
            })?;
            source.number(line, field.trim())
        };
        let point = Point::new(coordinate(x_column, "x")?, coordinate(y_column, "y")?);
        points
            .try_reserve(1)
            .map_err(|_| error(line, "too many points to hold in memory".to_string()))?;
        points.push(point);
    }
    Ok(points)
}

/// The fields of one CSV line, unquoted.
fn fields(line: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', false) if field.trim().is_empty() => {
                field.clear();
                quoted = true;
            }
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            ('"', true) => quoted = false,
            (',', false) => fields.push(core::mem::take(&mut field)),
            (c, _) => field.push(c),
        }
    }
    if quoted {
        return Err("a quoted field is not closed on its line".to_string());
    }
    fields.push(field);
    Ok(fields)
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

    #[test]
    fn the_header_chooses_the_columns_in_any_order_and_case() {
        let pts = parse_csv("Latitude,Longitude\r\n1,2\r\n\r\n3,4\r\n", "geo.csv").unwrap();
        assert_eq!(pts, vec![Point::new(2.0, 1.0), Point::new(4.0, 3.0)]);
    }

    #[test]
    fn quoted_fields_may_hold_commas_and_quotes() {
        let pts = parse_csv("name,x,y\n\"a \"\"b\"\", c\",1,2\n", "q.csv").unwrap();
        assert_eq!(pts, vec![Point::new(1.0, 2.0)]);
    }

    #[test]
    fn bad_rows_are_refused_by_line() {
        for (text, line, words) in [
            ("x,y\n1,2\n3\n", 3, "1 fields, but the y column is field 2"),
            ("x,y\n1,2\n3,abc\n", 3, "cannot read \"abc\""),
            ("x,y\n1,nan\n", 2, "\"nan\" is not finite"),
            ("x,y\n1,\"2\n", 2, "not closed"),
            ("\n\nid,y\n", 3, "no x column"),
        ] {
            let err = parse_csv(text, "bad.csv").unwrap_err();
            assert_eq!(err.line, Some(line), "{text:?}");
            assert!(err.to_string().contains(words), "{err}");
        }
    }

    #[test]
    fn an_empty_file_has_no_points_and_a_long_token_is_cut() {
        assert_eq!(parse_csv("", "e.csv").unwrap(), vec![]);
        let long = "9".repeat(1000) + "x";
        let err = parse_csv(&format!("x,y\n1,{long}\n"), "l.csv").unwrap_err();
        assert!(err.to_string().len() < 120, "{err}");
    }
}
