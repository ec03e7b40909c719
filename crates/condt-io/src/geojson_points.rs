//! GeoJSON point input: the Point and MultiPoint geometries of a GeoJSON document.
//!
//! Owns: [`parse_geojson`], the GeoJSON structure on top of `serde_json`'s parser. The positions
//! go into the point vector as the parser meets them, through seeds and visitors: no tree of the
//! document is built. A member that comes before its object's `"type"` (`"coordinates"` of a
//! geometry written with sorted keys) is kept as its text, a slice of the document, and read
//! once the type is known. It reads coordinates as they are written (GeoJSON's longitude,
//! latitude order becomes x, y); it may not project them.

use super::points::line_at;
use super::points::quoted;
use super::{IoError, IoErrorKind, PointFile};
use condt::Point;
use condt::MAX_POINTS;
use core::fmt;
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde_json::value::RawValue;
use std::string::String;
use std::vec::Vec;

/// Deepest nesting of GeoJSON objects and their arrays read; deeper documents are refused rather
/// than risk the stack (GeoJSON points need five levels). Other JSON (properties) is skipped
/// without recursion.
const MAX_DEPTH: usize = 64;

/// Parses the points of a GeoJSON document; `file` names the source in error messages.
///
/// Read: a FeatureCollection, a Feature, a GeometryCollection or a bare geometry; every Point
/// gives one point and every MultiPoint its points, in the order they are written (a third
/// coordinate, a number, is ignored). A Feature without a geometry (`null`) gives none, and so
/// does an empty Point or MultiPoint (`"coordinates": []`: RFC 7946, section 3.1, allows empty
/// geometries), while a position inside a MultiPoint must hold two coordinates. Any other geometry
/// (LineString, Polygon, …) is an error naming its line, as are JSON syntax errors and
/// coordinates that are not numbers, and an object giving one of the members `type`,
/// `features`, `geometries`, `geometry` or `coordinates` twice, whether or not its type reads it,
/// since JSON leaves open which one counts and readers differ (a `crs` too). Members
/// may come in any order; strings may hold escapes (`"Po\u0069nt"` is `"Point"`); numbers are
/// read exactly as `str::parse` reads them.
///
/// ```
/// use condt::Point;
/// use condt_io::parse_geojson;
/// let text = r#"{"type": "FeatureCollection", "features": [
///   {"type": "Feature", "properties": {"name": "a"},
///    "geometry": {"type": "Point", "coordinates": [1.5, 2]}},
///   {"type": "Feature", "properties": null,
///    "geometry": {"coordinates": [[3, 4, 100], [5, 6]], "type": "MultiPoint"}}
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
    parse_geojson_with_crs(text, file).map(|(points, _)| points)
}

/// [`parse_geojson`], and the document's top-level `"crs"` member as written (or, where it has
/// none, the first feature's or geometry's: some writers repeat it on every feature; refused
/// when an object gives it twice; GeoJSON of 2008;
/// RFC 7946 dropped it, but GDAL and QGIS still read it to place projected coordinates), so that
/// a GeoJSON output can carry it on.
///
/// ```
/// let text = r#"{"type": "FeatureCollection", "crs": {"type": "name",
///   "properties": {"name": "EPSG:32632"}}, "features": []}"#;
/// let (points, crs) = condt_io::parse_geojson_with_crs(text, "utm.geojson")?;
/// assert!(points.is_empty());
/// assert_eq!(crs.as_deref(), Some(r#"{"type": "name",
///   "properties": {"name": "EPSG:32632"}}"#));
/// # Ok::<(), condt_io::IoError>(())
/// ```
pub fn parse_geojson_with_crs(
    text: &str,
    file: &str,
) -> Result<(Vec<Point>, Option<String>), IoError> {
    parse_geojson_file(text, file).map(|read| (read.points, read.crs))
}

/// [`parse_geojson_with_crs`], and how many features had a null geometry and how many Point
/// and MultiPoint geometries were empty (neither gives a point), for the caller to tell.
pub(crate) fn parse_geojson_file(text: &str, file: &str) -> Result<PointFile, IoError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    read_records(text, file, core::iter::once(0..text.len()), "")
}

/// The points of a GeoJSON sequence: one GeoJSON text per line (GeoJSON lines, `.geojsonl`, as
/// GDAL's GeoJSONSeq driver writes it), or, when the text holds a record separator (U+001E),
/// one after each (RFC 8142, `.geojsons`; a record may then span lines). Each record is read as
/// [`parse_geojson_file`] reads a document, blank lines and records skipped; the points are
/// numbered across the records in order, an error names the line in the whole file, and the
/// first top-level `"crs"` met is kept (a record giving it twice is refused); a later
/// record's that differs from it (as JSON
/// values: spacing and member order aside) is not, and the line of the first such is given
/// ([`PointFile::crs_dropped_at`]) for the caller to tell.
pub(crate) fn parse_geojson_lines(text: &str, file: &str) -> Result<PointFile, IoError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let separator = '\u{1e}';
    let mut starts: Vec<usize> = Vec::new();
    if text.contains(separator) {
        // The text before the first separator must be blank, as each record's rest is read.
        starts.push(0);
        starts.extend(text.match_indices(separator).map(|(at, _)| at + 1));
    } else {
        starts.push(0);
        let bytes = text.as_bytes();
        starts.extend(
            (0..bytes.len())
                .filter(|&i| {
                    bytes[i] == b'\n' || (bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n'))
                })
                .map(|i| i + 1),
        );
    }
    let ends = starts
        .iter()
        .skip(1)
        .map(|&next| next - 1)
        .chain([text.len()]);
    let records = starts
        .iter()
        .zip(ends)
        .map(|(&start, end)| start..end)
        .filter(|range| !text[range.clone()].trim().is_empty());
    read_records(
        text,
        file,
        records,
        "; a GeoJSON sequence holds one whole GeoJSON object per line (or after each record \
         separator, U+001E)",
    )
}

/// Reads the GeoJSON texts at `records` (byte ranges of `text`, in order) into one point list;
/// `hint` is added to a message of JSON that ends early.
fn read_records(
    text: &str,
    file: &str,
    records: impl Iterator<Item = core::ops::Range<usize>>,
    hint: &str,
) -> Result<PointFile, IoError> {
    let mut state = State {
        text,
        points: Vec::new(),
        crs: None,
        crs_dropped: None,
        nested_crs: None,
        nested_crs_dropped: None,
        failure: None,
        null_geometries: 0,
        empty_geometries: 0,
    };
    let mut crs_dropped_at = None;
    for range in records {
        let record = &text[range.clone()];
        // Offsets of members read later are taken from the record's start.
        state.text = record;
        let mut deserializer = serde_json::Deserializer::from_str(record);
        let read = Member::Object
            .read(&mut state, 0, &mut deserializer)
            .and_then(|()| deserializer.end());
        if let Err(err) = read {
            let (at, mut message) = state
                .failure
                .take()
                .unwrap_or_else(|| (offset_of(record, &err), message_of(&err)));
            if err.is_eof() {
                message.push_str(hint);
            }
            // An error at the record's end (JSON that ends early) is on its last line with
            // content, not after the line break that ends the record.
            let offset = range.start + at.min(record.trim_end().len());
            if let Some(place) = place_in_long_line(text, offset) {
                message.push_str(&place);
            }
            return Err(IoError {
                file: file.to_string(),
                line: Some(line_at(text.as_bytes(), offset)),
                kind: IoErrorKind::Content(message),
            });
        }
        if let (None, Some(at)) = (crs_dropped_at, state.crs_dropped) {
            crs_dropped_at = Some(line_at(text.as_bytes(), range.start + at));
        }
        // The features' own crs stands in for the document's where it has none; where it has
        // one, a feature's that differs is left out and told, as a later record's is.
        let nested_dropped = match (&state.crs, state.nested_crs.take()) {
            (None, Some((nested, _))) => {
                state.crs = Some(nested);
                state.nested_crs_dropped
            }
            (Some(kept), Some((nested, at))) if !same_json(kept, &nested) => Some(at),
            (Some(_), Some(_)) => state.nested_crs_dropped,
            (_, None) => None,
        };
        state.nested_crs_dropped = None;
        if let (None, Some(at)) = (crs_dropped_at, nested_dropped) {
            crs_dropped_at = Some(line_at(text.as_bytes(), range.start + at));
        }
    }
    Ok(PointFile {
        crs_dropped_at,
        null_geometries: state.null_geometries,
        empty_geometries: state.empty_geometries,
        degrees: crs_is_degrees(state.crs.as_deref()),
        points: state.points,
        crs: state.crs,
    })
}

/// Whether a GeoJSON input's coordinates are longitudes and latitudes: without a `crs`, as RFC
/// 7946 has them (WGS 84), or with one that names a geographic system: OGC's CRS84, CRS83 or
/// CRS27, or an EPSG code of one in use by national mapping (`EPSG:4326`, GDAL's
/// `urn:ogc:def:crs:EPSG::4326`; [`GEOGRAPHIC_EPSG`]). A `null` crs (no system: a drawing's
/// coordinates) is not.
fn crs_is_degrees(crs: Option<&str>) -> bool {
    crs.is_none_or(|crs| {
        let crs = crs.to_ascii_uppercase();
        let ogc = ["CRS84", "CRS83", "CRS27"]
            .iter()
            .any(|name| crs.contains(name));
        // The code after each `EPSG:` or `EPSG::`, to its last digit.
        let epsg = crs.split("EPSG:").skip(1).any(|rest| {
            let digits: String = rest
                .trim_start_matches(':')
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            digits
                .parse()
                .is_ok_and(|code: u32| GEOGRAPHIC_EPSG.contains(&code))
        });
        ogc || epsg
    })
}

/// Geographic 2D systems (longitude and latitude in degrees) a GeoJSON `crs` names most: WGS 84
/// (4326), ETRS89 (4258, Europe's INSPIRE data), NAD83 and NAD27 (4269, 4267), GDA94 and GDA2020
/// (4283, 7844), CGCS2000 (4490), JGD2011 (6668). Only 4326 was known, and ETRS89 data got no
/// note (a diff review).
const GEOGRAPHIC_EPSG: [u32; 8] = [4326, 4258, 4269, 4267, 4283, 7844, 4490, 6668];

/// Lines longer than this many bytes get the column of an error on them and the text around it:
/// a minified GeoJSON file is one line, which a line number does not narrow down.
const LONG_LINE: usize = 200;

/// Characters of context on each side of an error in a long line.
const CONTEXT_CHARS: usize = 30;

/// Where the byte `offset` of `text` lies in its line, when that line is longer than
/// [`LONG_LINE`]: `", at column C: "…text around it…""` (C counts characters from 1).
fn place_in_long_line(text: &str, offset: usize) -> Option<String> {
    let offset = (0..=offset.min(text.len()))
        .rev()
        .find(|&k| text.is_char_boundary(k))?;
    let start = text[..offset].rfind(['\n', '\r']).map_or(0, |k| k + 1);
    let end = text[offset..]
        .find(['\n', '\r'])
        .map_or(text.len(), |k| offset + k);
    if end - start <= LONG_LINE {
        return None;
    }
    let line = &text[start..end];
    let at = offset - start;
    let column = line[..at].chars().count() + 1;
    let before = line[..at]
        .char_indices()
        .rev()
        .nth(CONTEXT_CHARS - 1)
        .map_or(0, |(k, _)| k);
    let after = line[at..]
        .char_indices()
        .nth(CONTEXT_CHARS)
        .map_or(line.len(), |(k, _)| at + k);
    let ellipsis = |cut: bool| if cut { "…" } else { "" };
    Some(format!(
        ", at column {column}: \"{}{}{}\"",
        ellipsis(before > 0),
        &line[before..after],
        ellipsis(after < line.len())
    ))
}

/// What a read has gathered: the points, and the first error met in a member read after its
/// object's type (its byte offset in the document and its message), which the error that the
/// outer parse then returns only carries up.
struct State<'t> {
    text: &'t str,
    points: Vec<Point>,
    /// The document's own `"crs"` member, as written.
    crs: Option<String>,
    /// The offset in the first record that gave a different `"crs"` from `crs`, dropped.
    crs_dropped: Option<usize>,
    /// The first `"crs"` of a feature or geometry inside the document (GeoJSON 2008 puts it on
    /// the top object, but some writers put it on each feature), carried where the document
    /// has none; and the offset of the first that differs from it, as for `crs_dropped`.
    nested_crs: Option<(String, usize)>,
    nested_crs_dropped: Option<usize>,
    failure: Option<(usize, String)>,
    /// Features whose geometry is `null`.
    null_geometries: usize,
    /// Points and MultiPoints whose coordinates are `[]`.
    empty_geometries: usize,
}

impl State<'_> {
    /// Appends `p`, refusing more than [`MAX_POINTS`] points as every point reader does.
    fn push<E: de::Error>(&mut self, p: Point) -> Result<(), E> {
        if self.points.len() == MAX_POINTS {
            return Err(E::custom(format_args!(
                "more than {MAX_POINTS} points, the most condt accepts"
            )));
        }
        self.points.try_reserve(1).map_err(|_| {
            E::custom(format_args!(
                "cannot hold {} points in memory",
                self.points.len() + 1
            ))
        })?;
        self.points.push(p);
        Ok(())
    }

    /// Reads `member` from `raw`, a slice of the document kept while its object's type was
    /// not known; an error is kept with its place in the whole document.
    fn read_later<E: de::Error>(
        &mut self,
        member: Member,
        depth: usize,
        raw: &RawValue,
    ) -> Result<(), E> {
        let text = raw.get();
        let mut deserializer = serde_json::Deserializer::from_str(text);
        if let Err(err) = member.read(self, depth, &mut deserializer) {
            if self.failure.is_none() {
                let start = self.offset_in_text(text);
                self.failure = Some((start + offset_of(text, &err), message_of(&err)));
            }
            return Err(E::custom("(reported above)"));
        }
        Ok(())
    }

    /// Where `part`, a slice of the record being read (a member kept as raw JSON), starts in
    /// it: its offset there, by address.
    fn offset_in_text(&self, part: &str) -> usize {
        let at = (part.as_ptr() as usize).wrapping_sub(self.text.as_ptr() as usize);
        at.min(self.text.len())
    }
}

/// Whether two JSON texts hold the same value (spacing and the order of members aside; text
/// that is not JSON compared as written).
fn same_json(a: &str, b: &str) -> bool {
    match (
        serde_json::from_str::<serde_json::Value>(a),
        serde_json::from_str::<serde_json::Value>(b),
    ) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// The byte offset in `text` of the line and column `err` names (serde_json counts lines at
/// LF alone; the offset is then numbered as the other readers number lines).
fn offset_of(text: &str, err: &serde_json::Error) -> usize {
    let line_start = if err.line() <= 1 {
        0
    } else {
        text.bytes()
            .enumerate()
            .filter(|&(_, b)| b == b'\n')
            .nth(err.line() - 2)
            .map_or(text.len(), |(i, _)| i + 1)
    };
    (line_start + err.column().saturating_sub(1)).min(text.len())
}

/// The message of `err` without serde_json's "at line L column C" (the error names the line).
fn message_of(err: &serde_json::Error) -> String {
    let message = err.to_string();
    match message.rfind(" at line ") {
        Some(cut) if err.line() > 0 => message[..cut].to_string(),
        _ => message,
    }
}

/// What a member holds, and so how it is read.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Member {
    /// A GeoJSON object (the document, a feature).
    Object,
    /// A Feature's geometry: an object or `null`.
    Geometry,
    /// An array of objects: `"features"` or `"geometries"`, named in the message.
    Objects(&'static str),
    /// A Point's coordinates: a position, or `[]` for an empty Point.
    Point,
    /// A position of a MultiPoint.
    Position,
    /// A MultiPoint's coordinates.
    Positions,
}

impl Member {
    /// Reads this member from `deserializer` into `state`.
    fn read<'de, D: Deserializer<'de>>(
        self,
        state: &mut State<'_>,
        depth: usize,
        deserializer: D,
    ) -> Result<(), D::Error> {
        if depth > MAX_DEPTH {
            return Err(de::Error::custom(format_args!(
                "nested deeper than {MAX_DEPTH} levels"
            )));
        }
        let reader = Reader {
            member: self,
            state,
            depth,
        };
        // By what the value is: the visitor refuses the wrong kinds with this member's message.
        deserializer.deserialize_any(reader)
    }

    /// What this member must be, for the message when it is something else.
    fn wanted(self) -> &'static str {
        match self {
            Member::Object | Member::Geometry => "a GeoJSON object needs a \"type\"",
            Member::Objects("features") => "a FeatureCollection needs a \"features\" array",
            Member::Objects(_) => "a GeometryCollection needs a \"geometries\" array",
            Member::Point | Member::Position => POSITION,
            Member::Positions => "a MultiPoint needs a \"coordinates\" array",
        }
    }
}

const POSITION: &str = "a position must be an array of two or more numbers, [x, y] or [x, y, z]";

/// A [`Member`] read into the state: the visitor of every level.
struct Reader<'s, 't> {
    member: Member,
    state: &'s mut State<'t>,
    depth: usize,
}

/// The member of a seed, as a seed (for `next_element_seed`, `next_value_seed`).
impl<'de> DeserializeSeed<'de> for Reader<'_, '_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        self.member.read(self.state, self.depth, deserializer)
    }
}

/// Any value of the wrong kind for the member: its message, at the parser's place.
macro_rules! refuse {
    ($($method:ident($($arg:ty)?)),*) => {
        $(fn $method<E: de::Error>(self $(, _: $arg)?) -> Result<(), E> {
            Err(E::custom(self.member.wanted()))
        })*
    };
}

impl<'de> Visitor<'de> for Reader<'_, '_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.member.wanted())
    }

    refuse!(
        visit_bool(bool),
        visit_i64(i64),
        visit_u64(u64),
        visit_f64(f64),
        visit_str(&str)
    );

    fn visit_unit<E: de::Error>(self) -> Result<(), E> {
        if self.member == Member::Geometry {
            self.state.null_geometries += 1;
            Ok(())
        } else {
            Err(E::custom(self.member.wanted()))
        }
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let depth = self.depth + 1;
        match self.member {
            Member::Objects(_) => {
                while seq
                    .next_element_seed(Reader {
                        member: Member::Object,
                        state: &mut *self.state,
                        depth,
                    })?
                    .is_some()
                {}
                Ok(())
            }
            Member::Positions => {
                let before = self.state.points.len();
                while seq
                    .next_element_seed(Reader {
                        member: Member::Position,
                        state: &mut *self.state,
                        depth,
                    })?
                    .is_some()
                {}
                if self.state.points.len() == before {
                    self.state.empty_geometries += 1;
                }
                Ok(())
            }
            Member::Point | Member::Position => {
                let x = seq.next_element_seed(Coordinate)?;
                // An empty Point (`"coordinates": []`) holds no point, as an empty MultiPoint
                // holds none (RFC 7946, 3.1: an empty geometry); a MultiPoint's position must
                // hold two coordinates.
                if x.is_none() && self.member == Member::Point {
                    self.state.empty_geometries += 1;
                    return Ok(());
                }
                let y = x.and(seq.next_element_seed(Coordinate)?);
                let (Some(x), Some(y)) = (x, y) else {
                    return Err(de::Error::custom(POSITION));
                };
                // Further coordinates (numbers, as a position's are) are ignored: z, and an M
                // measure or a time after it, which RFC 7946 (3.1.1) lets a parser ignore.
                while seq.next_element_seed(Coordinate)?.is_some() {}
                self.state.push(Point::new(x, y))
            }
            Member::Object | Member::Geometry => Err(de::Error::custom(self.member.wanted())),
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        if !matches!(self.member, Member::Object | Member::Geometry) {
            return Err(de::Error::custom(self.member.wanted()));
        }
        let depth = self.depth + 1;
        // The type once read (`None` inside when it is not a string); the member read for it,
        // whether it was met, and members met before the type, kept as text.
        let mut kind: Option<Option<String>> = None;
        let mut seen = Vec::new();
        let mut later: Vec<(Key, &'de RawValue)> = Vec::new();
        while let Some(key) = map.next_key::<Key>()? {
            if seen.contains(&key) {
                // JSON leaves open which of two equal names counts (RFC 8259, section 4):
                // reading the first, as before, could read other points than the writer meant
                // (or carry on another crs).
                return Err(de::Error::custom(format_args!(
                    "the member \"{}\" is given twice in one object",
                    key.name()
                )));
            }
            if key == Key::Crs {
                seen.push(key);
                let raw = map.next_value::<&'de RawValue>()?;
                let state = &mut *self.state;
                let at = state.offset_in_text(raw.get());
                let (first, dropped) = if self.depth == 0 {
                    (state.crs.as_deref(), &mut state.crs_dropped)
                } else {
                    let first = state.nested_crs.as_ref().map(|(crs, _)| crs.as_str());
                    (first, &mut state.nested_crs_dropped)
                };
                match first {
                    // A later record of a sequence, or a later feature, with another crs: kept
                    // out, its place kept to tell.
                    Some(first) => {
                        if dropped.is_none() && !same_json(first, raw.get()) {
                            *dropped = Some(at);
                        }
                    }
                    None if self.depth == 0 => state.crs = Some(raw.get().to_string()),
                    None => state.nested_crs = Some((raw.get().to_string(), at)),
                }
                continue;
            }
            if matches!(key, Key::Other | Key::Crs) {
                map.next_value::<IgnoredAny>()?;
                continue;
            }
            seen.push(key);
            if key == Key::Type {
                let raw = map.next_value::<&'de RawValue>()?;
                let name = serde_json::from_str::<String>(raw.get()).ok();
                // An unknown type is refused at once, on the line of the type: the error's own
                // place would be after the spacing that follows it (a pretty-printed document
                // with sorted keys put the type's line off by one; a GIS user's review).
                if let Err(refused) = wanted_member::<serde_json::Error>(name.as_deref()) {
                    let state = &mut *self.state;
                    if state.failure.is_none() {
                        state.failure =
                            Some((state.offset_in_text(raw.get()), refused.to_string()));
                    }
                    return Err(de::Error::custom("(reported above)"));
                }
                kind = Some(name);
                continue;
            }
            match &kind {
                Some(name) => match wanted_member::<A::Error>(name.as_deref())? {
                    Some((wanted, member)) if wanted == key => map.next_value_seed(Reader {
                        member,
                        state: &mut *self.state,
                        depth,
                    })?,
                    _ => {
                        map.next_value::<IgnoredAny>()?;
                    }
                },
                None => later.push((key, map.next_value::<&'de RawValue>()?)),
            }
        }
        let Some(name) = kind else {
            return Err(de::Error::custom(Member::Object.wanted()));
        };
        let Some((wanted, member)) = wanted_member::<A::Error>(name.as_deref())? else {
            return Err(de::Error::custom(Member::Object.wanted()));
        };
        if let Some(&(_, raw)) = later.iter().find(|(key, _)| *key == wanted) {
            self.state.read_later(member, depth, raw)?;
        }
        if !seen.contains(&wanted) {
            return Err(de::Error::custom(match wanted {
                Key::Geometry => "a Feature needs a \"geometry\"".to_string(),
                Key::Coordinates if member == Member::Point => {
                    "a Point needs \"coordinates\"".to_string()
                }
                _ => member.wanted().to_string(),
            }));
        }
        Ok(())
    }
}

/// The member that an object of type `name` is read by, and how; `None` for no type (not a
/// string); an error for a type that holds no points.
fn wanted_member<E: de::Error>(name: Option<&str>) -> Result<Option<(Key, Member)>, E> {
    Ok(Some(match name {
        None => return Ok(None),
        Some("FeatureCollection") => (Key::Features, Member::Objects("features")),
        Some("Feature") => (Key::Geometry, Member::Geometry),
        Some("GeometryCollection") => (Key::Geometries, Member::Objects("geometries")),
        Some("Point") => (Key::Coordinates, Member::Point),
        Some("MultiPoint") => (Key::Coordinates, Member::Positions),
        Some(other) => {
            // A GIS user's lines or outlines: what would read them (a GIS user's review).
            let vertices = match other {
                "LineString" | "MultiLineString" | "Polygon" | "MultiPolygon" => {
                    " (write its vertices as Points first: QGIS's Extract vertices, or \
                     shapely.get_coordinates)"
                }
                _ => "",
            };
            return Err(E::custom(format_args!(
                "a {}: only Point and MultiPoint geometries are read as points{vertices}",
                quoted(other)
            )));
        }
    }))
}

/// The members of a GeoJSON object that matter here.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Key {
    Type,
    Features,
    Geometries,
    Geometry,
    Coordinates,
    /// The document's coordinate reference system (kept, not applied).
    Crs,
    Other,
}

impl Key {
    /// The member's name in a document (the members read here; `Other` has none of its own).
    fn name(self) -> &'static str {
        match self {
            Key::Type => "type",
            Key::Features => "features",
            Key::Geometries => "geometries",
            Key::Geometry => "geometry",
            Key::Coordinates => "coordinates",
            Key::Crs => "crs",
            Key::Other => "(other)",
        }
    }
}

impl<'de> de::Deserialize<'de> for Key {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Key, D::Error> {
        struct KeyVisitor;
        impl Visitor<'_> for KeyVisitor {
            type Value = Key;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a member name")
            }
            fn visit_str<E: de::Error>(self, name: &str) -> Result<Key, E> {
                Ok(match name {
                    "type" => Key::Type,
                    "features" => Key::Features,
                    "geometries" => Key::Geometries,
                    "geometry" => Key::Geometry,
                    "coordinates" => Key::Coordinates,
                    "crs" => Key::Crs,
                    _ => Key::Other,
                })
            }
        }
        deserializer.deserialize_identifier(KeyVisitor)
    }
}

/// One coordinate: a JSON number, as an `f64`.
struct Coordinate;

impl<'de> DeserializeSeed<'de> for Coordinate {
    type Value = f64;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<f64, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Coordinate {
    type Value = f64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(POSITION)
    }

    fn visit_f64<E: de::Error>(self, x: f64) -> Result<f64, E> {
        Ok(x)
    }

    fn visit_i64<E: de::Error>(self, x: i64) -> Result<f64, E> {
        Ok(x as f64)
    }

    fn visit_u64<E: de::Error>(self, x: u64) -> Result<f64, E> {
        Ok(x as f64)
    }

    fn visit_bool<E: de::Error>(self, _: bool) -> Result<f64, E> {
        Err(E::custom(POSITION))
    }

    fn visit_str<E: de::Error>(self, _: &str) -> Result<f64, E> {
        Err(E::custom(POSITION))
    }

    fn visit_unit<E: de::Error>(self) -> Result<f64, E> {
        Err(E::custom(POSITION))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, _: A) -> Result<f64, A::Error> {
        Err(de::Error::custom(POSITION))
    }

    fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<f64, A::Error> {
        Err(de::Error::custom(POSITION))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bare_geometries_and_collections_are_read_in_order() {
        let pts = parse_geojson(
            r#"{"type":"GeometryCollection","geometries":[
                {"type":"MultiPoint","coordinates":[[1,2],[3,4,-7.5]]},
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

    /// An empty Point is an empty geometry, as an empty MultiPoint is (RFC 7946, 3.1): no
    /// point, no error (it was refused while the empty MultiPoint was read). A MultiPoint's
    /// empty position is still refused: a position holds two coordinates.
    #[test]
    fn empty_points_and_multipoints_give_no_point() {
        for text in [
            r#"{"type":"Point","coordinates":[]}"#,
            r#"{"coordinates":[],"type":"Point"}"#,
            r#"{"type":"MultiPoint","coordinates":[]}"#,
        ] {
            assert_eq!(parse_geojson(text, "e.geojson").unwrap(), vec![], "{text}");
        }
        let text = r#"{"type":"GeometryCollection","geometries":[
            {"type":"Point","coordinates":[]},{"type":"Point","coordinates":[1,2]}]}"#;
        assert_eq!(
            parse_geojson(text, "e.geojson").unwrap(),
            vec![Point::new(1.0, 2.0)]
        );
        let err = parse_geojson(
            "{\"type\":\"MultiPoint\",\n\"coordinates\":[[1,2],[]]}",
            "m.geojson",
        )
        .unwrap_err();
        assert_eq!(err.line, Some(2));
        assert!(err.to_string().contains("a position must be"), "{err}");
    }

    /// JSON leaves open which of two members of one name counts; Python's and JavaScript's
    /// readers take the last, and this one read the first: such an object is refused, on the
    /// line of the second.
    #[test]
    fn a_member_given_twice_is_refused() {
        let texts = [
            r#"{"type":"Feature","geometry":{"type":"Point","coordinates":[0,0]},
                "geometry":{"type":"Point","coordinates":[1,1]}}"#,
            r#"{"type":"Point","coordinates":[0,0],
                "coordinates":[1,1]}"#,
            r#"{"coordinates":[0,0],"type":"Point",
                "type":"MultiPoint"}"#,
        ];
        for text in texts {
            let err = parse_geojson(text, "twice.geojson").unwrap_err();
            assert!(
                err.to_string().contains("is given twice in one object"),
                "{err}"
            );
            assert_eq!(err.line, Some(2), "{err}");
        }
        // A second crs in one object: which one to carry on to the outputs would be a guess,
        // at the top as in a feature (whose crs is read where the document has none).
        let text = r#"{"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"A"}},
            "features":[],"crs":{"type":"name","properties":{"name":"B"}}}"#;
        let err = parse_geojson_with_crs(text, "crs.geojson").unwrap_err();
        assert!(err.to_string().contains("\"crs\" is given twice"), "{err}");
        assert_eq!(err.line, Some(2), "{err}");
        let text = r#"{"type":"Feature","crs":1,"crs":2,"geometry":{"type":"Point","coordinates":[0,0],"crs":3,"crs":4}}"#;
        assert!(parse_geojson_with_crs(text, "crs.geojson").is_err());
        let text = r#"{"type":"FeatureCollection","crs":1,"features":[{"type":"Feature","crs":2,"crs":3,
            "geometry":{"type":"Point","coordinates":[0,0]}}]}"#;
        let err = parse_geojson_with_crs(text, "crs.geojson").unwrap_err();
        assert!(err.to_string().contains("\"crs\" is given twice"), "{err}");
        // Members not read here may repeat, as before (their values are passed over).
        let text = r#"{"type":"Point","coordinates":[2,3],"bbox":[0,0,1,1],"bbox":[0,0,1,1]}"#;
        assert_eq!(
            parse_geojson(text, "ok.geojson").unwrap(),
            vec![Point::new(2.0, 3.0)]
        );
    }

    /// A position's coordinates past x and y (z, an M measure, a time: RFC 7946 3.1.1 lets a
    /// parser ignore them) are ignored, as long as they are numbers.
    #[test]
    fn coordinates_past_z_are_ignored() {
        let text = r#"{"type":"MultiPoint","coordinates":[[0,0,1,2],[1,0,1,2,3.5],[0,1,7]]}"#;
        assert_eq!(
            parse_geojson(text, "zm.geojson").unwrap(),
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(0.0, 1.0)
            ]
        );
        let text = r#"{"type":"Point","coordinates":[5,6,1,2]}"#;
        assert_eq!(
            parse_geojson(text, "zm.geojson").unwrap(),
            vec![Point::new(5.0, 6.0)]
        );
    }

    /// Features with a null geometry and empty Points and MultiPoints are counted, for the
    /// command line's note; a read later (sorted keys) counts alike.
    #[test]
    fn null_and_empty_geometries_are_counted() {
        let text = r#"{"features": [
            {"type": "Feature", "geometry": null},
            {"geometry": null, "type": "Feature"},
            {"type": "Feature", "geometry": {"coordinates": [], "type": "MultiPoint"}},
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": []}},
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": [1, 2]}}],
            "type": "FeatureCollection"}"#;
        let read = parse_geojson_file(text, "n.geojson").unwrap();
        assert_eq!(read.points, vec![Point::new(1.0, 2.0)]);
        assert_eq!((read.null_geometries, read.empty_geometries), (2, 2));
        let read = parse_geojson_file(r#"{"type":"Point","coordinates":[3,4]}"#, "p.json").unwrap();
        assert_eq!((read.null_geometries, read.empty_geometries), (0, 0));
    }

    #[test]
    fn bad_documents_are_refused_with_their_line() {
        for (text, line, words) in [
            ("{\"type\":\"Point\",\n\"coordinates\":[1]}", 2, "a position must be"),
            ("{\"type\":\"Point\",\n\"coordinates\":[1,2,3,\"m\"]}", 2, "a position must be"),
            ("{\"type\":\"Point\",\n\"coordinates\":[1,null]}", 2, "a position must be"),
            // The ignored third coordinate must be a number too.
            ("{\"type\":\"Point\",\n\"coordinates\":[1,2,\"x\"]}", 2, "a position must be"),
            ("{\"type\":\"Point\",\n\"coordinates\":[1,2,null]}", 2, "a position must be"),
            ("{\"type\":\"Point\",\n\"coordinates\":[1,2,[3]]}", 2, "a position must be"),
            ("{\"type\":\"Point\",\n\"coordinates\":7}", 2, "a position must be"),
            (
                "{\"type\":\"Point\",\"coordinates\":[1,2]}\n,",
                2,
                "trailing characters",
            ),
            (
                "{\"type\":\"Point\",\n\"coordinates\":[1,2}",
                2,
                "expected `,` or `]`",
            ),
            ("{\"features\":[]}", 1, "needs a \"type\""),
            ("{\"type\":7,\"features\":[]}", 1, "needs a \"type\""),
            ("{\"type\":\"FeatureCollection\"}", 1, "\"features\" array"),
            (
                "{\"type\":\"FeatureCollection\",\"features\":{}}",
                1,
                "\"features\" array",
            ),
            ("{\"type\":\"Feature\"}", 1, "needs a \"geometry\""),
            ("{\"type\":\"Point\"}", 1, "needs \"coordinates\""),
            (
                "\n\n{\"type\":\"Polygon\",\"coordinates\":[]}",
                3,
                "\"Polygon\": only Point and MultiPoint",
            ),
            (
                "{\"type\":\"Point\",\"coordinates\":[1e999,2]}",
                1,
                "number out of range",
            ),
            // JSON's number syntax, which `str::parse` is laxer than.
            ("{\"type\":\"Point\",\"coordinates\":[+1,2]}", 1, "expected value"),
            ("{\"type\":\"Point\",\"coordinates\":[.5,2]}", 1, "expected value"),
            ("{\"type\":\"Point\",\"coordinates\":[1.,2]}", 1, "invalid number"),
            ("{\"type\":\"Po", 1, "EOF while parsing a string"),
            ("", 1, "EOF while parsing a value"),
            ("[1,2]", 1, "needs a \"type\""),
            // A member read after the type it waited for: the line is the document's.
            (
                "{\"features\":[\n{\"geometry\":\n{\"coordinates\":\n[1,\"2\"],\"type\":\"Point\"},\n\
                 \"type\":\"Feature\"}],\n\"type\":\"FeatureCollection\"}",
                4,
                "a position must be",
            ),
            (
                "{\"coordinates\":[[1,2],\r\n[3,4],\r\n[5]],\r\n\"type\":\"MultiPoint\"}",
                3,
                "a position must be",
            ),
        ] {
            let err = parse_geojson(text, "bad.geojson").unwrap_err();
            assert_eq!(err.line, Some(line), "{text:?}: {err}");
            assert!(err.to_string().contains(words), "{err}");
            assert!(!err.to_string().contains(" column "), "{err}");
        }
    }

    /// A crs on each feature (GeoJSON 2008 puts it on the top object; some writers repeat it on
    /// every feature) is carried where the document has none, the first one met; one that
    /// differs from the crs carried is left out, and its line told, as a sequence's later
    /// record's (a CLI user's review: the features' crs was dropped without a word).
    #[test]
    fn a_crs_on_the_features_stands_in_for_the_documents() {
        let feature = |crs: &str, x: u32| {
            format!(
                r#"{{"type":"Feature","crs":{crs},"geometry":{{"type":"Point","coordinates":[{x},0]}}}}"#
            )
        };
        let utm = r#"{"type":"name","properties":{"name":"EPSG:32632"}}"#;
        let wgs = r#"{"type":"name","properties":{"name":"EPSG:4326"}}"#;
        let collection = |top: &str, features: &[String]| {
            format!(
                "{{\"type\":\"FeatureCollection\",{top}\"features\":[\n{}]}}",
                features.join(",\n")
            )
        };
        let same = collection("", &[feature(utm, 0), feature(utm, 1)]);
        let read = parse_geojson_file(&same, "f.geojson").unwrap();
        assert_eq!(
            (read.crs.as_deref(), read.crs_dropped_at),
            (Some(utm), None)
        );
        let differing = collection("", &[feature(utm, 0), feature(wgs, 1)]);
        let read = parse_geojson_file(&differing, "f.geojson").unwrap();
        assert_eq!(
            (read.crs.as_deref(), read.crs_dropped_at),
            (Some(utm), Some(3))
        );
        // The document's own crs comes first, wherever it is written; a feature's that differs
        // is told.
        let top = format!("\"crs\":{wgs},");
        let read = parse_geojson_file(&collection(&top, &[feature(utm, 0)]), "f.geojson").unwrap();
        assert_eq!(
            (read.crs.as_deref(), read.crs_dropped_at),
            (Some(wgs), Some(2))
        );
        let read = parse_geojson_file(&collection(&top, &[feature(wgs, 0)]), "f.geojson").unwrap();
        assert_eq!(
            (read.crs.as_deref(), read.crs_dropped_at),
            (Some(wgs), None)
        );
    }

    /// A minified file is one line: the error also gives the column and the text around it
    /// (a CLI user's review: a bad position among 1,000 features was reported as line 1 only).
    #[test]
    fn errors_in_a_long_line_name_their_column() {
        let features: Vec<String> = (0..1000)
            .map(|k| {
                let y = if k == 700 {
                    "null".to_string()
                } else {
                    k.to_string()
                };
                format!(
                    r#"{{"type":"Feature","geometry":{{"type":"Point","coordinates":[{k},{y}]}}}}"#
                )
            })
            .collect();
        let text = format!(
            r#"{{"type":"FeatureCollection","features":[{}]}}"#,
            features.join(",")
        );
        let err = parse_geojson(&text, "min.geojson").unwrap_err();
        assert_eq!(err.line, Some(1), "{err}");
        let shown = err.to_string();
        // A column within the position that is wrong (the line is ASCII: bytes count).
        let bracket = text.find("[700,null]").unwrap();
        let column: usize = shown
            .split("at column ")
            .nth(1)
            .unwrap()
            .split(':')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(
            (bracket + 1..=bracket + "[700,null]".len()).contains(&column),
            "{shown}"
        );
        assert!(shown.contains("[700,null]"), "{shown}");
        // Short lines keep the line alone.
        let err = parse_geojson(r#"{"type":"Point","coordinates":[1,null]}"#, "p.json");
        assert!(!err.unwrap_err().to_string().contains("column"));
    }

    #[test]
    fn escapes_and_member_order_are_json_s() {
        let text = r#"{"coordinates": [[1, 2], [3, 4]], "t\u0079pe": "Multi\u0050oint"}"#;
        assert_eq!(
            parse_geojson(text, "e.json").unwrap(),
            vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0)]
        );
        let text = r#"{"type":"Feature","geometry":{"type":"Po\u0069nt","coordinates":[5,6]},
            "properties":{"name":"a \"quoted\" \\ name \u00e9"}}"#;
        assert_eq!(
            parse_geojson(text, "e.json").unwrap(),
            vec![Point::new(5.0, 6.0)]
        );
        // Sorted keys (Python's `json.dump(..., sort_keys=True)`): every member before its type.
        let text = r#"{"features": [{"geometry": {"coordinates": [1, 2], "type": "Point"},
            "properties": {}, "type": "Feature"}, {"geometry": null, "type": "Feature"},
            {"geometry": {"coordinates": [[3, 4, 0]], "type": "MultiPoint"},
            "type": "Feature"}], "type": "FeatureCollection"}"#;
        assert_eq!(
            parse_geojson(text, "sorted.json").unwrap(),
            vec![Point::new(1.0, 2.0), Point::new(3.0, 4.0)]
        );
        // Members of other types' names are skipped whatever they hold (two of one name are
        // refused: `a_member_given_twice_is_refused`).
        let text = r#"{"type":"Point","coordinates":[1,2],"features":7}"#;
        assert_eq!(
            parse_geojson(text, "d.json").unwrap(),
            vec![Point::new(1.0, 2.0)]
        );
    }

    #[test]
    fn numbers_read_as_str_parse_reads_them() {
        let mut stream = crate::test_rng::Xorshift::new(7);
        let mut texts: Vec<String> = ["-0", "0", "-0.0", "1e-320", "9007199254740993", "-12"]
            .map(String::from)
            .to_vec();
        texts.push("123456789012345678901234567890".to_string());
        texts.push("2.2250738585072011e-308".to_string());
        for _ in 0..2000 {
            let x = f64::from_bits(stream.next_u64());
            if x.is_finite() {
                texts.push(format!("{x:?}"));
                texts.push(format!("{x:.7e}"));
            }
        }
        for text in &texts {
            let json = format!("{{\"type\":\"Point\",\"coordinates\":[{text},{text}]}}");
            let read = parse_geojson(&json, "n.json").unwrap();
            let expected = text.parse::<f64>().unwrap().to_bits();
            assert_eq!(read[0].x.to_bits(), expected, "{text}");
        }
    }

    #[test]
    fn deep_nesting_is_refused_not_a_stack_overflow() {
        let deep = "[".repeat(100_000);
        assert!(parse_geojson(&deep, "deep.json").is_err());
        // Deep properties are skipped without recursion, and end in a syntax error here.
        let deep = format!(
            "{{\"type\":\"Feature\",\"geometry\":null,\"properties\":{}",
            "[".repeat(100_000)
        );
        assert!(parse_geojson(&deep, "deep.json").is_err());
        // Collections in collections, their type before or after their members.
        for type_first in [true, false] {
            let (open, close) = if type_first {
                ("{\"type\":\"GeometryCollection\",\"geometries\":[", "]}")
            } else {
                ("{\"geometries\":[", "],\"type\":\"GeometryCollection\"}")
            };
            let deep = open.repeat(10_000) + &close.repeat(10_000);
            let err = parse_geojson(&deep, "deep.json").unwrap_err();
            assert!(err.to_string().contains("nested deeper"), "{err}");
            let shallow = open.repeat(20) + &close.repeat(20);
            assert_eq!(parse_geojson(&shallow, "s.json").unwrap(), vec![]);
        }
    }
}
