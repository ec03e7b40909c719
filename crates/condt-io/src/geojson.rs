//! GeoJSON output, written by hand (no serializer dependency).

use condt::Point;
use condt::Reconstruction;
use serde_json::value::RawValue;
use std::io::{self, Write};

/// A `FeatureCollection` with one `LineString` per curve and a boolean `closed` property; a
/// closed curve repeats its first position at the end, as GeoJSON rings do. The coordinates are
/// those of `input`, the reconstruction's input, exactly as given.
///
/// # Errors
/// `InvalidInput` when `input` has not as many points as the reconstruction's input; the
/// errors of `out`.
///
/// ```
/// use condt::{reconstruct, Params};
/// use condt::Point;
/// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from);
/// let r = reconstruct(&points, &Params::paper())?;
/// let mut out = Vec::new();
/// condt_io::write_geojson(&mut out, &r, &points)?;
/// let text = String::from_utf8(out)?;
/// assert!(text.contains(r#""coordinates":[[0,0],[1,0],[0.5,2],[0,0]]"#));
/// assert!(text.contains(r#""closed":true"#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_geojson(
    out: &mut dyn Write,
    result: &Reconstruction,
    input: &[Point],
) -> io::Result<()> {
    write_geojson_with_crs(out, result, input, None)
}

/// [`write_geojson`] with the input document's `"crs"` member, as
/// [`parse_geojson_with_crs`](crate::parse_geojson_with_crs) gave it (JSON text), written on:
/// the coordinates are the input's, so is their reference system.
///
/// # Errors
/// As [`write_geojson`], and `InvalidInput` when `crs` is not one JSON value (`"EPSG:32632"`
/// must be written as a JSON string or object, quotes included).
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let points = [(500000.0, 4e6), (500010.0, 4e6), (500005.0, 4000010.0)].map(Point::from);
/// let r = reconstruct(&points, &Params::paper())?;
/// let crs = r#"{"type":"name","properties":{"name":"EPSG:32632"}}"#;
/// let mut out = Vec::new();
/// condt_io::write_geojson_with_crs(&mut out, &r, &points, Some(crs))?;
/// let text = String::from_utf8(out)?;
/// assert!(text.starts_with(&format!(r#"{{"type":"FeatureCollection","crs":{crs},"#)));
/// assert!(condt_io::write_geojson_with_crs(&mut Vec::new(), &r, &points, Some("EPSG:32632"))
///     .is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_geojson_with_crs(
    out: &mut dyn Write,
    result: &Reconstruction,
    input: &[Point],
    crs: Option<&str>,
) -> io::Result<()> {
    super::check_input(result, input)?;
    // Written as it is, so checked first: it must not break the document.
    if let Some(crs) = crs.filter(|c| serde_json::from_str::<&RawValue>(c).is_err()) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("the crs {crs:?} is not a JSON value"),
        ));
    }
    write!(out, r#"{{"type":"FeatureCollection","#)?;
    if let Some(crs) = crs {
        write!(out, r#""crs":{crs},"#)?;
    }
    write!(out, r#""features":["#)?;
    for (k, curve) in result.curves().iter().enumerate() {
        if k > 0 {
            write!(out, ",")?;
        }
        write!(
            out,
            r#"{{"type":"Feature","properties":{{"closed":{}}},"#,
            curve.is_closed()
        )?;
        write!(out, r#""geometry":{{"type":"LineString","coordinates":["#)?;
        let closing = curve.points().next().filter(|_| curve.is_closed());
        for (k, i) in curve.points().chain(closing).enumerate() {
            let p = input[i];
            let (x, y) = (Coordinate(p.x), Coordinate(p.y));
            write!(out, "{}[{x},{y}]", if k > 0 { "," } else { "" })?;
        }
        write!(out, "]}}}}")?;
    }
    writeln!(out, "]}}")
}

/// The first point that cannot be a longitude and latitude (|x| > 180 or |y| > 90), which
/// GeoJSON readers take coordinates for when the document has no crs member: the command line
/// notes it and Python's `to_geojson` warns, naming the crs to give. `None` when every point
/// could be one.
///
/// ```
/// use condt::Point;
/// use condt_io::not_longitude_latitude;
/// let utm = [Point::new(500_000.0, 5_000_000.0)];
/// assert_eq!(not_longitude_latitude(&utm), Some(utm[0]));
/// assert_eq!(not_longitude_latitude(&[Point::new(-179.5, 89.9)]), None);
/// ```
pub fn not_longitude_latitude(points: &[Point]) -> Option<Point> {
    points
        .iter()
        .copied()
        .find(|p| p.x.abs() > 180.0 || p.y.abs() > 90.0)
}

/// The `"crs"` member a GeoJSON output carries for `given` (`condt reconstruct --crs`, and a
/// GeoJSON input's own member carried on): a JSON object as written (one JSON object, checked);
/// `null` as written (in the 2008 GeoJSON form, no crs can be assumed: coordinates of a
/// drawing, not of the earth); or a name as a named crs (the 2008 form GDAL and QGIS read),
/// `EPSG:n` in the OGC URN form GDAL writes itself; a JSON string is the name it holds.
///
/// # Errors
/// Why `given` is none of these: JSON text (a leading `{`) that is not one object, PROJJSON
/// (which GDAL would read as longitude and latitude; the message starts with "PROJJSON"), other
/// JSON (`[1, 2]`, `4326`, `true`), an empty name, or one with a control character.
///
/// ```
/// use condt_io::crs_member;
/// assert_eq!(
///     crs_member("EPSG:32632")?,
///     r#"{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}}"#
/// );
/// assert_eq!(
///     crs_member("OGC:CRS84")?,
///     r#"{"type":"name","properties":{"name":"OGC:CRS84"}}"#
/// );
/// let written = r#"{"type": "name", "properties": {"name": "EPSG:2056"}}"#;
/// assert_eq!(crs_member(written)?, written);
/// assert_eq!(crs_member("\"EPSG:32632\"")?, crs_member("EPSG:32632")?);
/// assert_eq!(crs_member(" null ")?, "null");
/// assert!(crs_member("{\"type\": ").is_err() && crs_member(" ").is_err());
/// assert!(crs_member("[1, 2]").is_err() && crs_member("4326").is_err());
/// let projjson = r#"{"type": "ProjectedCRS", "name": "WGS 84 / UTM zone 32N"}"#;
/// assert!(crs_member(projjson).unwrap_err().starts_with("PROJJSON"));
/// # Ok::<(), String>(())
/// ```
pub fn crs_member(given: &str) -> Result<String, String> {
    use serde_json::Value;
    let trimmed = given.trim();
    if trimmed.starts_with('{') {
        return match serde_json::from_str::<Value>(trimmed) {
            Ok(Value::Object(object)) if is_projjson(&object) => Err(PROJJSON_REFUSED.to_string()),
            Ok(Value::Object(_)) => Ok(trimmed.to_string()),
            _ => Err(format!("{given:?} is not one JSON object")),
        };
    }
    // Other JSON than a string or `null` (`[1, 2]`, `4326`) names nothing: refused, not taken for
    // a name the output would then carry.
    match serde_json::from_str::<Value>(trimmed) {
        Ok(Value::Null) => return Ok("null".to_string()),
        Ok(value) if !value.is_string() => {
            return Err(format!(
                "{given:?} is JSON but neither a name such as EPSG:32632, a crs object nor null"
            ))
        }
        _ => {}
    }
    // A JSON string (`"EPSG:32632"`, quotes and all) is the name it holds.
    let unquoted;
    let trimmed = match serde_json::from_str::<String>(trimmed) {
        Ok(name) if trimmed.starts_with('"') => {
            unquoted = name;
            unquoted.trim()
        }
        _ => trimmed,
    };
    if trimmed.is_empty() || trimmed.chars().any(char::is_control) {
        return Err(format!(
            "{given:?} is not a name such as EPSG:32632, a crs object nor null"
        ));
    }
    let name = match trimmed.split_once(':') {
        Some((authority, code))
            if authority.eq_ignore_ascii_case("EPSG")
                && !code.is_empty()
                && code.bytes().all(|b| b.is_ascii_digit()) =>
        {
            format!("urn:ogc:def:crs:EPSG::{code}")
        }
        _ => trimmed.to_string(),
    };
    let quoted = serde_json::to_string(&name).map_err(|e| e.to_string())?;
    Ok(format!(
        r#"{{"type":"name","properties":{{"name":{quoted}}}}}"#
    ))
}

/// Why PROJJSON (pyproj's `CRS.to_json()`, PROJ's `projinfo -o PROJJSON`) is no crs member:
/// GDAL reads GeoJSON 2008's named and linked forms alone, and a file carrying PROJJSON read back
/// as EPSG:4326, UTM metres taken for degrees without a word (a GIS analyst's review, through
/// GeoPandas). It starts with "PROJJSON" for callers that add their own advice.
pub(crate) const PROJJSON_REFUSED: &str = "PROJJSON (as pyproj's CRS.to_json() writes it) is \
    no crs member GeoJSON readers read: GDAL reads such a file as EPSG:4326, longitude and \
    latitude; give the system's name instead, such as EPSG:32632";

/// Whether a crs object is PROJJSON: a `$schema` naming it, or a `type` such as `ProjectedCRS`
/// or `GeographicCRS` (GeoJSON 2008's members are of `type` `name` or `link`).
fn is_projjson(object: &serde_json::Map<String, serde_json::Value>) -> bool {
    let text = |key: &str| object.get(key).and_then(serde_json::Value::as_str);
    text("$schema").is_some_and(|schema| schema.contains("projjson"))
        || text("type").is_some_and(|kind| kind.ends_with("CRS"))
}

/// A coordinate as a JSON number that reads back as the same double: in positional notation,
/// or with an exponent beyond 10^16 and below 10^-5, where positional notation runs to hundreds
/// of digits (`9.05e299`, not a 300-digit integer).
pub(crate) struct Coordinate(pub(crate) f64);

impl std::fmt::Display for Coordinate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = self.0.abs();
        if size >= 1e16 || (size > 0.0 && size < 1e-5) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

#[cfg(test)]
mod coordinate_tests {
    use super::Coordinate;

    /// Every coordinate reads back as the same double; far ones are written with an exponent.
    #[test]
    fn coordinates_read_back_exactly_and_short() {
        for x in [
            0.0,
            -0.0,
            5.0,
            0.1,
            -123.456,
            1e-5,
            9.99e15,
            1e16,
            9.05e299,
            1e-300,
            -2.5e-7,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            let text = Coordinate(x).to_string();
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                x.to_bits(),
                "{x}: {text}"
            );
            assert!(text.len() <= 24, "{x}: {text}");
        }
        assert_eq!(Coordinate(9.05e299).to_string(), "9.05e299");
        assert_eq!(Coordinate(12.5).to_string(), "12.5");
    }
}
