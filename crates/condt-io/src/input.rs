//! How a point file is to be read when its name does not say it all, and what reading it gives.
//!
//! Owns: [`InputFormat`] (the formats by name, and a file's format by its name's ending),
//! [`ReadOptions`] and [`PointFile`], which [`read_points_with`](crate::read_points_with) takes
//! and returns. The readers themselves are in their modules.

use condt::Point;
use std::fmt;
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
    /// where its first line with content is a header, else as the plain format (which takes tabs
    /// and comments too), but a line with tabs between its values is split at tabs only: a blank
    /// within a field or a third value is refused (on the first line of numbers, as CSV refuses
    /// three numbers without a header).
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
    ///
    /// ```
    /// use condt_io::InputFormat;
    /// // The help's list: each format by the name `named` reads it by.
    /// let names: Vec<&str> = InputFormat::ALL.iter().map(|f| f.name()).collect();
    /// assert_eq!(names, ["txt", "node", "csv", "tsv", "npy", "geojson", "geojsonl"]);
    /// ```
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
    ///
    /// ```
    /// use condt_io::InputFormat;
    /// // As `--input-format` gives it: any case, the aliases too.
    /// assert_eq!(InputFormat::named("Text"), Some(InputFormat::Text));
    /// assert_eq!(InputFormat::named("geojsons"), Some(InputFormat::GeoJsonLines));
    /// // A name, not a file's ending: `of_path` reads those.
    /// assert_eq!(InputFormat::named(".csv"), None);
    /// ```
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
    ///
    /// ```
    /// use condt_io::InputFormat;
    /// assert_eq!(InputFormat::GeoJsonLines.name(), "geojsonl");
    /// // Every name shown reads back as its format (the aliases, `text` or `json`, are not shown).
    /// for format in InputFormat::ALL {
    ///     assert_eq!(InputFormat::named(format.name()), Some(format));
    /// }
    /// ```
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
    /// (any case; the plain format for any other ending, or none, where the reader still tells
    /// a NumPy array or GeoJSON by the content); `None` for `-`, standard input, whose format is
    /// told by its content.
    ///
    /// ```
    /// use condt_io::InputFormat;
    /// assert_eq!(InputFormat::of_path("data/survey.Csv"), Some(InputFormat::Csv));
    /// // Only the last ending counts; an unknown one, or none, is the plain format.
    /// assert_eq!(InputFormat::of_path("survey.csv.bak"), Some(InputFormat::Text));
    /// assert_eq!(InputFormat::of_path("points"), Some(InputFormat::Text));
    /// assert_eq!(InputFormat::of_path("-"), None);
    /// ```
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

/// A column of a CSV, TSV or plain text file: by the name its header gives it (compared without ASCII
/// case and blanks around it), or by its position, numbered from 1.
///
/// ```
/// use condt_io::{Column, Columns};
/// // Digits alone are a number; anything else is a name, kept as written.
/// let columns = Columns::parse("3, Easting")?;
/// assert_eq!(columns.x, Column::Number(3));
/// assert_eq!(columns.y, Column::Named("Easting".to_string()));
/// assert_eq!(columns.y.to_string(), "Easting");
/// // Names are one column when the header lookup would find the same one: case and blanks
/// // around them aside (`==` compares them as written).
/// assert!(columns.y.same(&Column::Named(" EASTING ".into())));
/// assert!(!columns.y.same(&Column::Named("Eastings".into())));
/// assert!(!columns.x.same(&Column::Named("3".into())), "a name, not a position");
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Column {
    /// The column whose header names it so (`POINT_X`, `easting`).
    Named(String),
    /// The column at this position, the first being 1.
    Number(usize),
}

impl Column {
    /// Whether `self` and `other` choose one column in any header, compared as the header
    /// lookup compares a name with a header's field: names equal without ASCII case and blanks
    /// around them, or equal numbers (a name and a number are not compared: that needs the
    /// header).
    ///
    /// ```
    /// use condt_io::Column;
    /// let x = Column::Named("POINT_X".into());
    /// assert!(x.same(&Column::Named(" point_x".into())));
    /// assert_ne!(x, Column::Named(" point_x".into()), "`==` compares them as written");
    /// assert!(Column::Number(2).same(&Column::Number(2)));
    /// // Whether a name is the column at a position only the header can say.
    /// assert!(!Column::Named("2".into()).same(&Column::Number(2)));
    /// ```
    pub fn same(&self, other: &Column) -> bool {
        match (self, other) {
            (Column::Named(a), Column::Named(b)) => same_name(a, b),
            (a, b) => a == b,
        }
    }
}

/// Whether a column name and a header's field (or two names) name one column: equal without
/// ASCII case and blanks around them. The one comparison of the header lookup and of
/// [`Column::same`].
pub(crate) fn same_name(a: &str, b: &str) -> bool {
    a.trim().eq_ignore_ascii_case(b.trim())
}

impl fmt::Display for Column {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Column::Named(name) => write!(f, "{name}"),
            Column::Number(number) => write!(f, "{number}"),
        }
    }
}

/// The columns of a CSV, TSV or plain text file that hold x and y ([`ReadOptions::with_columns`]), instead
/// of those the header names `x` and `y` (or `lon`, `lat`, ...).
///
/// ```
/// use condt_io::{Column, Columns};
/// let columns = Columns::parse("POINT_X, POINT_Y")?;
/// assert_eq!(columns.x, Column::Named("POINT_X".into()));
/// assert_eq!(Columns::parse("2,3")?.y, Column::Number(3));
/// assert_eq!(Columns::parse("easting,3")?.to_string(), "easting,3");
/// assert!(Columns::parse("x").unwrap_err().contains("two columns"));
/// assert!(Columns::parse("0,1").unwrap_err().contains("from 1"));
/// assert!(Columns::parse("a,A").unwrap_err().contains("the same column"));
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Columns {
    /// The column of the first coordinate.
    pub x: Column,
    /// The column of the second coordinate.
    pub y: Column,
}

impl Columns {
    /// Reads `X,Y`: two column names or 1-based numbers (a field of digits alone is a
    /// number), separated by a comma, blanks around each ignored. A name holding a comma cannot
    /// be given: its number can. Refused, with why: anything but two nonempty columns, the
    /// number 0, one column for both ([`Column::same`]: two names that differ only in ASCII
    /// case are one column, as the header lookup finds them).
    ///
    /// ```
    /// use condt_io::{Column, Columns};
    /// // As `--columns` gives it: blanks around each column are ignored.
    /// let columns = Columns::parse(" lon , lat ")?;
    /// assert_eq!(columns.x, Column::Named("lon".into()));
    /// assert_eq!(Columns::parse("2, 3")?, Columns { x: Column::Number(2), y: Column::Number(3) });
    /// // Digits alone are a number: `x1` is a name.
    /// assert_eq!(Columns::parse("x1,y1")?.x, Column::Named("x1".into()));
    /// assert!(Columns::parse("lon,").unwrap_err().contains("an empty column name"));
    /// assert!(Columns::parse("x,y,z").unwrap_err().contains("expected two columns"));
    /// # Ok::<(), String>(())
    /// ```
    pub fn parse(spec: &str) -> Result<Columns, String> {
        let parts: Vec<&str> = spec.split(',').map(str::trim).collect();
        let [x, y] = parts[..] else {
            return Err(format!(
                "{spec:?}: expected two columns, x and y, separated by a comma (POINT_X,POINT_Y \
                 or 2,3)"
            ));
        };
        let column = |part: &str| -> Result<Column, String> {
            if part.is_empty() {
                return Err(format!("{spec:?}: an empty column name"));
            }
            if !part.bytes().all(|b| b.is_ascii_digit()) {
                return Ok(Column::Named(part.to_string()));
            }
            match part.parse::<usize>() {
                Ok(0) => Err(format!("{spec:?}: columns are numbered from 1")),
                Ok(number) => Ok(Column::Number(number)),
                Err(_) => Err(format!(
                    "{spec:?}: column {part} is past any file's columns"
                )),
            }
        };
        let columns = Columns {
            x: column(x)?,
            y: column(y)?,
        };
        match columns.problem() {
            Some(why) => Err(format!("{spec:?}: {why}")),
            None => Ok(columns),
        }
    }

    /// Why these columns cannot be read from any file, or `None`: the number 0, or one column for
    /// both. [`parse`](Columns::parse) never gives such columns; the fields are public, so the
    /// reader asks again.
    pub(crate) fn problem(&self) -> Option<&'static str> {
        if [&self.x, &self.y].contains(&&Column::Number(0)) {
            Some("columns are numbered from 1")
        } else if self.x.same(&self.y) {
            Some("the same column for x and y")
        } else {
            None
        }
    }
}

impl Columns {
    /// Whether `self` and `other` choose the same x and y columns in any header
    /// ([`Column::same`]: `POINT_X,POINT_Y` and `point_x, point_y` do).
    ///
    /// ```
    /// use condt_io::Columns;
    /// let given = Columns::parse("POINT_X,POINT_Y")?;
    /// assert!(given.same(&Columns::parse("point_x, Point_Y")?));
    /// assert!(!given.same(&Columns::parse("POINT_Y,POINT_X")?));
    /// # Ok::<(), String>(())
    /// ```
    pub fn same(&self, other: &Columns) -> bool {
        self.x.same(&other.x) && self.y.same(&other.y)
    }
}

impl fmt::Display for Columns {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{}", self.x, self.y)
    }
}

/// How [`read_points_with`](crate::read_points_with) reads a point file; the default reads it
/// as [`read_points`](crate::read_points) does.
///
/// ```
/// use condt_io::{Columns, InputFormat, ReadOptions};
/// let options = ReadOptions::new().with_format(InputFormat::Csv);
/// assert_eq!(options.format, Some(InputFormat::Csv));
/// assert_eq!(ReadOptions::default().format, None);
/// let options = ReadOptions::new().with_columns(Columns::parse("easting,northing")?);
/// assert_eq!(options.columns.map(|c| c.to_string()).as_deref(), Some("easting,northing"));
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// The format to read the file in whatever its name (or its content, on standard input);
    /// `None`: by the name's ending, standard input by its content.
    pub format: Option<InputFormat>,
    /// The x and y columns of a CSV, TSV or plain text file; `None`: those its header names x and y.
    /// Another format is then refused; standard input without a format stated is read as CSV
    /// (unless it is a NumPy array or GeoJSON, which are refused).
    pub columns: Option<Columns>,
}

impl ReadOptions {
    /// The default: the format told by the name or the content.
    ///
    /// ```
    /// use condt_io::{read_points_with, ReadOptions};
    /// let dir = tempfile::tempdir()?;
    /// let path = dir.path().join("pts.txt");
    /// std::fs::write(&path, "0 0\n1 2\n")?;
    /// // Nothing stated: the file is read as `read_points` reads it.
    /// let options = ReadOptions::new();
    /// assert_eq!((options.format, &options.columns), (None, &None));
    /// assert_eq!(read_points_with(&path, &options)?.points, condt_io::read_points(&path)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new() -> ReadOptions {
        ReadOptions::default()
    }

    /// These options, the file read as `format`.
    ///
    /// ```
    /// use condt::Point;
    /// use condt_io::{read_points_with, InputFormat, ReadOptions};
    /// let dir = tempfile::tempdir()?;
    /// // A CSV export under a name that does not say so: by its name, the plain format.
    /// let path = dir.path().join("export.out");
    /// std::fs::write(&path, "name,x,y\nA,1,2\n")?;
    /// assert!(condt_io::read_points(&path).is_err());
    /// let options = ReadOptions::new().with_format(InputFormat::Csv);
    /// assert_eq!(read_points_with(&path, &options)?.points, vec![Point::new(1.0, 2.0)]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_format(mut self, format: InputFormat) -> ReadOptions {
        self.format = Some(format);
        self
    }

    /// These options, x and y read from `columns` of a CSV, TSV or plain text file.
    ///
    /// ```
    /// use condt::Point;
    /// use condt_io::{read_points_with, Columns, ReadOptions};
    /// let dir = tempfile::tempdir()?;
    /// let path = dir.path().join("wells.csv");
    /// // A header naming neither x nor y: the columns are chosen by position.
    /// std::fs::write(&path, "id,north,east\n1,200,100\n")?;
    /// let options = ReadOptions::new().with_columns(Columns::parse("3,2")?);
    /// assert_eq!(read_points_with(&path, &options)?.points, vec![Point::new(100.0, 200.0)]);
    /// // Other formats have no columns: refused before the file is even opened.
    /// let err = read_points_with(dir.path().join("none.npy"), &options).unwrap_err();
    /// assert!(err.to_string().contains("chosen only in CSV, TSV and plain text input"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_columns(mut self, columns: Columns) -> ReadOptions {
        self.columns = Some(columns);
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
    /// A GeoJSON input's top-level `"crs"` member as written, or where it has none its first
    /// feature's ([`parse_geojson_with_crs`](crate::parse_geojson_with_crs)); `None` for other
    /// formats.
    pub crs: Option<String>,
    /// The line of the first `"crs"` that differs from the one kept ([`crs`](PointFile::crs)):
    /// a later record's in a GeoJSON sequence (the first record's to carry one is kept), or a
    /// feature's in a document; only the one kept is carried on, and this says another was left
    /// out for the caller to tell (`condt` notes it on standard error). `None` for other formats
    /// and when every `"crs"` read is the same.
    pub crs_dropped_at: Option<usize>,
    /// GeoJSON features whose geometry is `null`: they give no point (0 for other formats).
    pub null_geometries: usize,
    /// GeoJSON Point and MultiPoint geometries whose coordinates are `[]` (empty geometries,
    /// RFC 7946, section 3.1): they give no point either (0 for other formats).
    pub empty_geometries: usize,
    /// Whether the file says its coordinates are longitudes and latitudes in degrees: a header
    /// naming the columns read `lon` (`lng`, `long`, `longitude`) and `lat` (`latitude`), or
    /// chosen by those names, or GeoJSON without a `crs` (RFC 7946's WGS 84) or with one naming
    /// a geographic system (OGC's CRS84, EPSG 4326, ETRS89's 4258, NAD83's 4269 and a few
    /// more). They are read as plane coordinates all the same; this lets a caller say what that
    /// means (`condt reconstruct` notes it where the latitude distorts them).
    pub degrees: bool,
}
