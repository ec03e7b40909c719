//! GeoJSON point input: the Point and MultiPoint geometries of a GeoJSON document.
//!
//! Owns: [`parse_geojson`] and the small JSON reader it needs (the library takes no JSON
//! dependency). It reads coordinates as they are written (GeoJSON's longitude, latitude order
//! becomes x, y); it may not project them.

use super::points::{line_at, quoted};
use super::{IoError, IoErrorKind};
use condt::Point;
use condt::MAX_POINTS;
use std::string::String;
use std::vec::Vec;

/// Deepest nesting of arrays and objects read; deeper documents are refused rather than risk
/// the stack (GeoJSON points need five levels).
const MAX_DEPTH: usize = 64;

/// Parses the points of a GeoJSON document; `file` names the source in error messages.
///
/// Read: a FeatureCollection, a Feature, a GeometryCollection or a bare geometry; every Point
/// gives one point and every MultiPoint its points, in the order they are written (a third
/// coordinate is ignored). A Feature without a geometry (`null`) gives none. Any other geometry
/// (LineString, Polygon, …) is an error naming its line, as are JSON syntax errors and
/// coordinates that are not numbers.
///
/// ```
/// use condt::Point;
/// use condt_io::parse_geojson;
/// let text = r#"{"type": "FeatureCollection", "features": [
///   {"type": "Feature", "properties": {"name": "a"},
///    "geometry": {"type": "Point", "coordinates": [1.5, 2]}},
///   {"type": "Feature", "properties": null,
///    "geometry": {"type": "MultiPoint", "coordinates": [[3, 4, 100], [5, 6]]}}
/// ]}"#;
/// let pts = parse_geojson(text, "points.geojson")?;
/// assert_eq!(pts, vec![Point::new(1.5, 2.0), Point::new(3.0, 4.0), Point::new(5.0, 6.0)]);
///
/// let err = parse_geojson(r#"{"type": "LineString",
///   "coordinates": [[0, 0], [1, 1]]}"#, "line.geojson").unwrap_err();
/// assert_eq!(err.line, Some(1));
/// assert!(err.to_string().contains("LineString"));
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn parse_geojson(text: &str, file: &str) -> Result<Vec<Point>, IoError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut reader = Reader {
        bytes: text.as_bytes(),
        at: 0,
    };
    let fail = |reader: &Reader, at: usize, message: String| IoError {
        file: file.to_string(),
        line: Some(reader.line_of(at)),
        kind: IoErrorKind::Content(message),
    };
    let document = reader
        .value(0)
        .map_err(|(at, message)| fail(&reader, at, message))?;
    reader.skip_space();
    if reader.at < reader.bytes.len() {
        return Err(fail(
            &reader,
            reader.at,
            "text after the end of the JSON document".to_string(),
        ));
    }
    let mut points = Vec::new();
    collect(&document, &mut points).map_err(|(at, message)| fail(&reader, at, message))?;
    Ok(points)
}

/// A JSON value with the byte offset where it starts (for messages).
#[derive(Debug)]
struct Value {
    at: usize,
    kind: Kind,
}

#[derive(Debug)]
enum Kind {
    Null,
    Bool,
    Number(f64),
    Text(String),
    Array(Vec<Value>),
    Object(Vec<(String, Value)>),
}

impl Value {
    fn field(&self, name: &str) -> Option<&Value> {
        match &self.kind {
            Kind::Object(fields) => fields.iter().find(|(k, _)| k == name).map(|(_, v)| v),
            _ => None,
        }
    }

    fn text(&self) -> Option<&str> {
        match &self.kind {
            Kind::Text(t) => Some(t),
            _ => None,
        }
    }
}

type Failure = (usize, String);

/// Appends the points of `value` (a GeoJSON object) to `points`.
fn collect(value: &Value, points: &mut Vec<Point>) -> Result<(), Failure> {
    let kind = value
        .field("type")
        .and_then(Value::text)
        .ok_or((value.at, "a GeoJSON object needs a \"type\"".to_string()))?;
    let list = |name: &str| -> Result<&[Value], Failure> {
        match value.field(name).map(|v| &v.kind) {
            Some(Kind::Array(items)) => Ok(items),
            _ => Err((value.at, format!("a {kind} needs a \"{name}\" array"))),
        }
    };
    match kind {
        "FeatureCollection" => list("features")?
            .iter()
            .try_for_each(|feature| collect(feature, points)),
        "Feature" => match value.field("geometry") {
            None => Err((value.at, "a Feature needs a \"geometry\"".to_string())),
            Some(Value {
                kind: Kind::Null, ..
            }) => Ok(()),
            Some(geometry) => collect(geometry, points),
        },
        "GeometryCollection" => list("geometries")?
            .iter()
            .try_for_each(|geometry| collect(geometry, points)),
        "Point" => {
            let coordinates = value
                .field("coordinates")
                .ok_or((value.at, "a Point needs \"coordinates\"".to_string()))?;
            push(points, position(coordinates)?, value.at)?;
            Ok(())
        }
        "MultiPoint" => list("coordinates")?.iter().try_for_each(|p| {
            push(points, position(p)?, p.at)?;
            Ok(())
        }),
        other => Err((
            value.at,
            format!(
                "a {}: only Point and MultiPoint geometries are read as points",
                quoted(other)
            ),
        )),
    }
}

/// A GeoJSON position `[x, y]` or `[x, y, z]`.
fn position(value: &Value) -> Result<Point, Failure> {
    let bad = || {
        (
            value.at,
            "a position must be [x, y] or [x, y, z], numbers".to_string(),
        )
    };
    let Kind::Array(items) = &value.kind else {
        return Err(bad());
    };
    match items.as_slice() {
        [x, y] | [x, y, _] => match (&x.kind, &y.kind) {
            (Kind::Number(x), Kind::Number(y)) => Ok(Point::new(*x, *y)),
            _ => Err(bad()),
        },
        _ => Err(bad()),
    }
}

/// A cursor over the document's bytes.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn line_of(&self, at: usize) -> usize {
        line_at(self.bytes, at.min(self.bytes.len()))
    }

    fn skip_space(&mut self) {
        while self
            .bytes
            .get(self.at)
            .is_some_and(|b| matches!(b, b' ' | b'\t' | b'\n' | b'\r'))
        {
            self.at += 1;
        }
    }

    fn expect(&mut self, byte: u8) -> Result<(), Failure> {
        self.skip_space();
        if self.bytes.get(self.at) == Some(&byte) {
            self.at += 1;
            Ok(())
        } else {
            Err((self.at, format!("expected '{}'", byte as char)))
        }
    }

    fn value(&mut self, depth: usize) -> Result<Value, Failure> {
        self.skip_space();
        let at = self.at;
        if depth > MAX_DEPTH {
            return Err((at, format!("nested deeper than {MAX_DEPTH} levels")));
        }
        let kind = match self.bytes.get(at) {
            None => return Err((at, "the document ends where a value was expected".into())),
            Some(b'{') => {
                self.at += 1;
                let mut fields = Vec::new();
                self.skip_space();
                if self.bytes.get(self.at) == Some(&b'}') {
                    self.at += 1;
                } else {
                    loop {
                        self.skip_space();
                        let key = self.string()?;
                        self.expect(b':')?;
                        let value = self.value(depth + 1)?;
                        fields.push((key, value));
                        self.skip_space();
                        match self.bytes.get(self.at) {
                            Some(b',') => self.at += 1,
                            Some(b'}') => {
                                self.at += 1;
                                break;
                            }
                            _ => return Err((self.at, "expected ',' or '}'".into())),
                        }
                    }
                }
                Kind::Object(fields)
            }
            Some(b'[') => {
                self.at += 1;
                let mut items = Vec::new();
                self.skip_space();
                if self.bytes.get(self.at) == Some(&b']') {
                    self.at += 1;
                } else {
                    loop {
                        items.push(self.value(depth + 1)?);
                        self.skip_space();
                        match self.bytes.get(self.at) {
                            Some(b',') => self.at += 1,
                            Some(b']') => {
                                self.at += 1;
                                break;
                            }
                            _ => return Err((self.at, "expected ',' or ']'".into())),
                        }
                    }
                }
                Kind::Array(items)
            }
            Some(b'"') => Kind::Text(self.string()?),
            Some(b't') => self.word("true", Kind::Bool)?,
            Some(b'f') => self.word("false", Kind::Bool)?,
            Some(b'n') => self.word("null", Kind::Null)?,
            Some(_) => Kind::Number(self.number()?),
        };
        Ok(Value { at, kind })
    }

    fn word(&mut self, word: &str, kind: Kind) -> Result<Kind, Failure> {
        if self.bytes[self.at..].starts_with(word.as_bytes()) {
            self.at += word.len();
            Ok(kind)
        } else {
            Err((self.at, "not a JSON value".into()))
        }
    }

    fn number(&mut self) -> Result<f64, Failure> {
        let start = self.at;
        while self
            .bytes
            .get(self.at)
            .is_some_and(|b| matches!(b, b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E'))
        {
            self.at += 1;
        }
        let token = core::str::from_utf8(&self.bytes[start..self.at]).unwrap_or("");
        match token.parse::<f64>() {
            Ok(x) if x.is_finite() && !token.is_empty() => Ok(x),
            _ => {
                let end = (start + 40).min(self.bytes.len());
                let near = String::from_utf8_lossy(&self.bytes[start..end]);
                Err((start, format!("not a JSON value: {}", quoted(&near))))
            }
        }
    }

    fn string(&mut self) -> Result<String, Failure> {
        let start = self.at;
        if self.bytes.get(self.at) != Some(&b'"') {
            return Err((start, "expected a string".into()));
        }
        self.at += 1;
        let mut text = Vec::new();
        loop {
            match self.bytes.get(self.at) {
                None => return Err((start, "a string is not closed".into())),
                Some(b'"') => {
                    self.at += 1;
                    break;
                }
                Some(b'\\') => {
                    // Escapes matter only in keys and type names, which are plain ASCII; any
                    // escaped character is kept as written after the backslash.
                    let escaped = self.bytes.get(self.at + 1).copied();
                    let Some(escaped) = escaped else {
                        return Err((start, "a string is not closed".into()));
                    };
                    text.push(escaped);
                    self.at += 2;
                }
                Some(&b) => {
                    text.push(b);
                    self.at += 1;
                }
            }
        }
        Ok(String::from_utf8_lossy(&text).into_owned())
    }
}

/// Appends `p`, refusing more than [`MAX_POINTS`] points as every point reader does.
fn push(points: &mut Vec<Point>, p: Point, at: usize) -> Result<(), Failure> {
    if points.len() == MAX_POINTS {
        return Err((
            at,
            format!("more than {MAX_POINTS} points, the most condt accepts"),
        ));
    }
    points.try_reserve(1).map_err(|_| {
        (
            at,
            format!("cannot hold {} points in memory", points.len() + 1),
        )
    })?;
    points.push(p);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bare_geometries_and_collections_are_read_in_order() {
        let pts = parse_geojson(
            r#"{"type":"GeometryCollection","geometries":[
                {"type":"MultiPoint","coordinates":[[1,2],[3,4]]},
                {"type":"Point","coordinates":[-5e-1,6.25E2]}]}"#,
            "g.json",
        )
        .unwrap();
        assert_eq!(
            pts,
            vec![
                Point::new(1.0, 2.0),
                Point::new(3.0, 4.0),
                Point::new(-0.5, 625.0)
            ]
        );
        let feature = r#"{"type":"Feature","geometry":null,"properties":{"a":[1,{"b":"\"x\""}]}}"#;
        assert_eq!(parse_geojson(feature, "f.json").unwrap(), vec![]);
    }

    #[test]
    fn bad_documents_are_refused_with_their_line() {
        for (text, line, words) in [
            ("{\"type\":\"Point\",\n\"coordinates\":[1]}", 2, "position"),
            (
                "{\"type\":\"Point\",\"coordinates\":[1,2]}\n,",
                2,
                "after the end",
            ),
            (
                "{\"type\":\"Point\",\n\"coordinates\":[1,2}",
                2,
                "expected ',' or ']'",
            ),
            ("{\"features\":[]}", 1, "needs a \"type\""),
            ("{\"type\":\"FeatureCollection\"}", 1, "\"features\" array"),
            (
                "\n\n{\"type\":\"Polygon\",\"coordinates\":[]}",
                3,
                "Polygon",
            ),
            (
                "{\"type\":\"Point\",\"coordinates\":[1e999,2]}",
                1,
                "not a JSON value",
            ),
            ("{\"type\":\"Po", 1, "not closed"),
            ("", 1, "ends where a value"),
        ] {
            let err = parse_geojson(text, "bad.geojson").unwrap_err();
            assert_eq!(err.line, Some(line), "{text:?}: {err}");
            assert!(err.to_string().contains(words), "{err}");
        }
    }

    #[test]
    fn deep_nesting_is_refused_not_a_stack_overflow() {
        let deep = "[".repeat(100_000);
        let err = parse_geojson(&deep, "deep.json").unwrap_err();
        assert!(err.to_string().contains("nested deeper"), "{err}");
    }
}
