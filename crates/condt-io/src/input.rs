//! How a point file is to be read when its name does not say it all, and what reading it gives.
//!
//! Owns: [`InputFormat`] (the formats by name, and a file's format by its name's ending),
//! [`ReadOptions`] and [`PointFile`], which [`read_points_with`](crate::read_points_with) takes
//! and returns. The readers themselves are in their modules.

use condt::Point;
use std::path::Path;

/// A point file's format: what [`read_points`](crate::read_points) tells by a name's ending,
/// and what [`ReadOptions::with_format`] states whatever the name (standard input has none).
///
/// ```
/// use condt_io::InputFormat;
/// assert_eq!(InputFormat::named("CSV"), Some(InputFormat::Csv));
/// assert_eq!(InputFormat::named("json"), Some(InputFormat::GeoJson));
/// assert_eq!(InputFormat::named("xlsx"), None);
/// assert_eq!(InputFormat::of_path("pts.TSV"), Some(InputFormat::Tsv));
/// assert_eq!(InputFormat::of_path("pts.dat"), Some(InputFormat::Text));
/// assert_eq!(InputFormat::of_path("sites.geojsonl"), Some(InputFormat::GeoJsonLines));
/// assert_eq!(InputFormat::of_path("-"), None, "standard input: told by its content");
/// assert_eq!(InputFormat::Npy.name(), "npy");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum InputFormat {
    /// The plain format, one `x y` per line ([`parse_points`](crate::parse_points)).
    Text,
    /// A Triangle `.node` file ([`parse_node`](crate::parse_node)).
    Node,
    /// CSV with a header naming the columns ([`parse_csv`](crate::parse_csv)).
    Csv,
    /// CSV with tabs between the columns, as a name ending in `.tsv` is read: by the CSV reader
    /// when its first line is a header, else as the plain format (which takes tabs too).
    Tsv,
    /// A NumPy array of shape `(n, 2)` ([`parse_npy`](crate::parse_npy)).
    Npy,
    /// The Point and MultiPoint geometries of a GeoJSON document
    /// ([`parse_geojson`](crate::parse_geojson)).
    GeoJson,
    /// A GeoJSON sequence: one GeoJSON object (a Feature, a geometry, a collection) per line,
    /// as GDAL writes `.geojsonl`, or one after each record separator U+001E (RFC 8142,
    /// `.geojsons`); each is read as a [`GeoJson`](InputFormat::GeoJson) document, and the
    /// points are numbered across them in order.
    GeoJsonLines,
}

impl InputFormat {
    /// Every format, in the order the help lists them.
    pub const ALL: [InputFormat; 7] = [
        InputFormat::Text,
        InputFormat::Node,
        InputFormat::Csv,
        InputFormat::Tsv,
        InputFormat::Npy,
        InputFormat::GeoJson,
        InputFormat::GeoJsonLines,
    ];

    /// The format of a name (any case): `txt` (or `text`), `node`, `csv`, `tsv`, `npy`,
    /// `geojson` (or `json`), `geojsonl` (or `geojsons`); `None` for any other.
    pub fn named(name: &str) -> Option<InputFormat> {
        let name = name.to_ascii_lowercase();
        Some(match name.as_str() {
            "txt" | "text" => InputFormat::Text,
            "node" => InputFormat::Node,
            "csv" => InputFormat::Csv,
            "tsv" => InputFormat::Tsv,
            "npy" => InputFormat::Npy,
            "geojson" | "json" => InputFormat::GeoJson,
            "geojsonl" | "geojsons" => InputFormat::GeoJsonLines,
            _ => return None,
        })
    }

    /// The name [`named`](InputFormat::named) reads as this format (the one the help shows).
    pub fn name(self) -> &'static str {
        match self {
            InputFormat::Text => "txt",
            InputFormat::Node => "node",
            InputFormat::Csv => "csv",
            InputFormat::Tsv => "tsv",
            InputFormat::Npy => "npy",
            InputFormat::GeoJson => "geojson",
            InputFormat::GeoJsonLines => "geojsonl",
        }
    }

    /// The format [`read_points`](crate::read_points) reads `path` in by its name's ending
    /// (any case; the plain format for any other ending, or none); `None` for `-`, standard
    /// input, whose format is told by its content.
    pub fn of_path(path: impl AsRef<Path>) -> Option<InputFormat> {
        let path = path.as_ref();
        if path.as_os_str() == "-" {
            return None;
        }
        let by_name = path
            .extension()
            .and_then(|e| e.to_str())
            .and_then(InputFormat::named);
        Some(by_name.unwrap_or(InputFormat::Text))
    }
}

/// How [`read_points_with`](crate::read_points_with) reads a point file; the default reads it
/// as [`read_points`](crate::read_points) does.
///
/// ```
/// use condt_io::{InputFormat, ReadOptions};
/// let options = ReadOptions::new().with_format(InputFormat::Csv);
/// assert_eq!(options.format, Some(InputFormat::Csv));
/// assert_eq!(ReadOptions::default().format, None);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// The format to read the file in whatever its name (or its content, on standard input);
    /// `None`: by the name's ending, standard input by its content.
    pub format: Option<InputFormat>,
}

impl ReadOptions {
    /// The default: the format told by the name or the content.
    pub fn new() -> ReadOptions {
        ReadOptions::default()
    }

    /// These options, the file read as `format`.
    pub fn with_format(mut self, format: InputFormat) -> ReadOptions {
        self.format = Some(format);
        self
    }
}

/// A point file as [`read_points_with`](crate::read_points_with) read it: its points, and what
/// else it said that a caller may carry on or tell.
///
/// ```
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("sites.geojson");
/// std::fs::write(&path, r#"{"type": "FeatureCollection", "features": [
///   {"type": "Feature", "properties": {}, "geometry": null},
///   {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": []}},
///   {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}}
/// ]}"#)?;
/// let read = condt_io::read_points_with(&path, &condt_io::ReadOptions::new())?;
/// assert_eq!(read.points, vec![condt::Point::new(1.0, 2.0)]);
/// assert_eq!((read.null_geometries, read.empty_geometries), (1, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct PointFile {
    /// The points, numbered from 0 in the file's order.
    pub points: Vec<Point>,
    /// A GeoJSON input's top-level `"crs"` member as written
    /// ([`parse_geojson_with_crs`](crate::parse_geojson_with_crs)); `None` for other formats.
    pub crs: Option<String>,
    /// GeoJSON features whose geometry is `null`: they give no point (0 for other formats).
    pub null_geometries: usize,
    /// GeoJSON Point and MultiPoint geometries whose coordinates are `[]` (empty geometries,
    /// RFC 7946, section 3.1): they give no point either (0 for other formats).
    pub empty_geometries: usize,
}
