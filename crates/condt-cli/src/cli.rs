//! The command-line front end of the `condt` binary.
//!
//! Owns: argument parsing, messages and exit codes. It may not implement geometry nor check a
//! parameter's range: it calls the library and `condt_io` and reports what they say; where the
//! output goes is [`crate::output`]'s business.

use crate::options::{self, Opt};
use crate::output::{refuse_same_file, Destination};
use crate::progress::Progress;
use crate::timings::Timings;
use condt::{
    triangulate_owned, Error, Method, Params, Pipeline, Repair, Stage, Uniformity, Upcoming,
};
use condt_io::{
    read_points_with, write_curves_csv, write_edges, write_geojson_with_crs, write_html,
    write_npy_edges, write_npy_triangles, write_npy_triangulation_edges, write_polylines,
    write_svg, write_svg_stages, write_triangles, write_triangulation_edges, write_unused, Columns,
    InputFormat, IoError, PointFile, ReadOptions,
};
use std::ffi::{OsStr, OsString};
use std::fmt;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicUsize;

const USAGE: &str = "\
condt: Delaunay triangulation and curve reconstruction of planar points

Usage:
  condt reconstruct INPUT [-o OUTPUT] [options]   the curves through the points (ConDT)
  condt triangulate INPUT [-o OUTPUT] [--edges]   their Delaunay triangulation
  condt score POINTS OUTPUT TRUTH [options]       an edge list against a ground truth
  condt help COMMAND                              a command's options, with an example

INPUT is a text file with one point `x y` per line (spaces, tabs or a comma; a third column is
ignored; `#` comments and blank lines are skipped; a first line of names, such as `x y`, is a
header, and with no point after it the file is empty only if it names x and y: `Error: file
not found` alone is refused); `-` reads standard input. Standard input, and a name without an
ending below, is told by its content: a NumPy array, a GeoJSON document or a GeoJSON sequence
(the .npy magic bytes, a leading `{`, a leading record separator U+001E), else that text
(`--input-format F` states the format instead, for a file too: `--input-format csv`). By the
name's ending (any case): `.node` a Triangle node file, `.npy` a NumPy array of shape (n, 2),
float64, float32 or integers, either byte order, C or Fortran order, `.csv` CSV whose header
names the x and y columns (or lon, lat; where none is named so, easting, northing, E, N or
POINT_X, POINT_Y; `--columns X,Y` chooses others, by name or number), or of two numeric
columns without a header (tabs separate the columns when the first line with content has tabs
and no comma; a `.tsv` is read so, with tabs, but two numbers a line as plain text; a row of
empty fields only, `,,`, as spreadsheets leave them, is skipped as a blank line is and takes no
number; empty fields past the first line's, as a trailing comma leaves them, `1,2,`, are no
column), `.geojson` or `.json` the
Point and MultiPoint geometries of a GeoJSON document, `.geojsonl` or `.geojsons` those of
GeoJSON lines (one object per line, or after each RS character). Points are numbered from 0
in the order of their lines (rows, GeoJSON positions: a MultiPoint gives several, a feature
whose geometry is null none, nor an empty Point or MultiPoint, `\"coordinates\": []`, and a
note on standard error says how many); every output speaks of points by that number.
Exact duplicate points are merged into the first of them (a note on standard error says how
many): a duplicate shares that point's triangles, edges and curves, and is unused when it is.
Longitudes and latitudes (lon and lat columns, GeoJSON) are plane coordinates here, in degrees:
an east-west gap counts 1/cos(latitude) times as long as a north-south one of the same metres
(2.4 at 65 degrees), and no edge crosses the antimeridian; project such points first (a UTM
zone): `reconstruct` notes both. GPS tracks: thin the fixes to a minimum distance of 3 times
the jitter or more, which also merges stops and drives of one road (README.md, *GPS tracks*).

OUTPUT (`-o`) is written whole or not at all; without it, or with `-`, the result goes to
standard output. An existing file keeps its permissions, owner, hard links and symbolic links;
a terminal, named pipe or device is written to, never replaced. `/dev/stdout`, `/dev/stderr`,
`/dev/fd/N` and `/proc/self/fd/N` are written through that open descriptor, as `-` writes
standard output, whatever file it has open (a regular file behind descriptor 3 or more only
when opened to append: `3>>FILE`). OUTPUT may not be INPUT, nor may standard output be
opened on it (`>> INPUT`).

An option's value is the next argument or joined to it: `--u 2.5` or `--u=2.5`, `-o out.svg` or
`-oout.svg`; `--` ends the options (`condt reconstruct -- -file.txt`).

When standard error is a terminal, a progress bar follows the reading, the computation and the
writing, and is cleared at the end; `--quiet` (`-q`) shows neither it nor the notes on standard
error. The output is the same either way.

Exit codes: 0 success; 1 the input or output failed (the message names the file and line; of
points too close to measure, it names their lines where the file can be read again, else
their numbers: standard input, a pipe, .npy, GeoJSON, .tsv); 2 a wrong command line. A reader
that stops early (`| head`) ends the run silently, by SIGPIPE.
";

/// The options before a command.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum GlobalId {
    Help,
    Version,
}

const GLOBAL_OPTIONS: &[Opt<GlobalId>] = &[
    Opt {
        id: GlobalId::Help,
        short: Some('h'),
        long: "help",
        negatable: false,
        value: None,
        help: "show this help (`condt COMMAND --help`: that command's)",
    },
    Opt {
        id: GlobalId::Version,
        short: Some('V'),
        long: "version",
        negatable: false,
        value: None,
        help: "show the version",
    },
];

/// `condt --help`.
fn global_help() -> String {
    format!("{USAGE}\nOptions:\n{}", options::help(GLOBAL_OPTIONS, 20))
}

/// `--input-format`, the same for every command that reads INPUT.
const INPUT_FORMAT_HELP: &str = "read INPUT as F whatever its name: txt, node, csv, tsv, npy,
geojson or geojsonl (standard input, and a name without a format's
ending, is otherwise told by its content: .npy, GeoJSON, else txt;
`--input-format csv` reads CSV)";

/// `--columns`, the same for every command that reads INPUT.
const COLUMNS_HELP: &str = "read x and y from these columns of a CSV, TSV or plain text
INPUT (a scanner's x y z intensity): header names or numbers from 1
(Shape_X,Shape_Y, 2,3) instead of the columns named x and y (lon,
lat; easting, northing); standard input is then read as CSV";

/// `--quiet`, the same for every command that computes.
const QUIET_HELP: &str = "no progress bar and no notes on standard error (errors and
--timings lines are still written); the output is the same";

/// The options of `condt reconstruct`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum ReconstructId {
    Output,
    Paper,
    U,
    Adaptive,
    Iqr,
    NoOutlierFilter,
    OutliersFirst,
    IqrFloor,
    /// A stage's switch, from the library's table of stages ([`Stage::switch`]).
    StageSwitch(Stage),
    Smooth,
    NoManifoldFix,
    Repair,
    Method,
    InputFormat,
    Columns,
    Snap,
    Format,
    Stages,
    Crs,
    Sequential,
    Timings,
    Quiet,
    Help,
}

impl ReconstructId {
    /// Whether the option sets a ConDT stage, which a baseline method refuses.
    fn sets_a_condt_stage(self) -> bool {
        use ReconstructId::*;
        match self {
            Paper | U | Adaptive | Iqr | NoOutlierFilter | OutliersFirst | IqrFloor
            | StageSwitch(_) | Smooth | NoManifoldFix | Repair => true,
            Output | Method | InputFormat | Columns | Snap | Format | Stages | Crs | Sequential
            | Timings | Quiet | Help => false,
        }
    }
}

/// The options of `condt reconstruct` other than the stages' switches, which
/// [`reconstruct_options`] puts after `--outliers-first`.
const RECONSTRUCT_BASE_OPTIONS: &[Opt<ReconstructId>] = &[
    Opt {
        id: ReconstructId::Output,
        short: Some('o'),
        long: "output",
        negatable: false,
        value: Some("FILE"),
        help: "write to FILE instead of standard output",
    },
    Opt {
        id: ReconstructId::Paper,
        short: None,
        long: "paper",
        negatable: false,
        value: None,
        help: "the paper's pipeline (Algorithms 1-3 as docs/condt.md reads them)
instead of the default; the options below still adjust it",
    },
    Opt {
        id: ReconstructId::U,
        short: None,
        long: "u",
        negatable: false,
        value: Some("X"),
        help: "uniformity parameter u, a finite number greater than 0 (default 2.75)",
    },
    Opt {
        id: ReconstructId::Adaptive,
        short: None,
        long: "adaptive",
        negatable: false,
        value: None,
        help: "adaptive uniformity (section 4.1 of the paper)",
    },
    Opt {
        id: ReconstructId::Iqr,
        short: None,
        long: "iqr",
        negatable: false,
        value: Some("K"),
        help: "outlier factor, a finite number, 0 or more (default 1.7)",
    },
    Opt {
        id: ReconstructId::NoOutlierFilter,
        short: None,
        long: "no-outlier-filter",
        negatable: false,
        value: None,
        help: "skip outlier removal",
    },
    Opt {
        id: ReconstructId::IqrFloor,
        short: None,
        long: "iqr-floor",
        negatable: true,
        value: None,
        help: "(default on; off with --paper) the outlier filter cuts no edge up to
1.5 times the median edge: on evenly spaced samples the paper's
threshold falls onto the spacing and cuts stretches a little wider",
    },
    Opt {
        id: ReconstructId::OutliersFirst,
        short: None,
        long: "outliers-first",
        negatable: false,
        value: None,
        help: "remove outliers before the non-manifold repair (see docs/condt.md)",
    },
    Opt {
        id: ReconstructId::Smooth,
        short: None,
        long: "smooth",
        negatable: true,
        value: None,
        help: "(default on; off with --paper) when one point in a hundred or more
ends or branches the result, move each point with two edges
meeting at a wide angle halfway to its neighbours' midpoint and
run the stages again on the moved points, up to three times
(edges stay between the input points; drawings show the moved
ones); for noisy samples",
    },
    Opt {
        id: ReconstructId::NoManifoldFix,
        short: None,
        long: "no-manifold-fix",
        negatable: false,
        value: None,
        help: "keep every proximity edge (self-intersecting curves); the same as
--repair off",
    },
    Opt {
        id: ReconstructId::Repair,
        short: None,
        long: "repair",
        negatable: false,
        value: Some("MODE"),
        help: "needs (default; paper with --paper), paper, mutual, crossing or off",
    },
    Opt {
        id: ReconstructId::Method,
        short: None,
        long: "method",
        negatable: false,
        value: Some("M"),
        help: "condt (default), or a classical baseline on the same Delaunay
triangulation: nn-crust (Dey and Kumar) or crust (Amenta, Bern
and Eppstein); a baseline takes none of the ConDT options",
    },
    Opt {
        id: ReconstructId::InputFormat,
        short: None,
        long: "input-format",
        negatable: false,
        value: Some("F"),
        help: INPUT_FORMAT_HELP,
    },
    Opt {
        id: ReconstructId::Columns,
        short: None,
        long: "columns",
        negatable: false,
        value: Some("X,Y"),
        help: COLUMNS_HELP,
    },
    Opt {
        id: ReconstructId::Snap,
        short: None,
        long: "snap",
        negatable: false,
        value: Some("D"),
        help: SNAP_HELP,
    },
    Opt {
        id: ReconstructId::Format,
        short: None,
        long: "format",
        negatable: false,
        value: Some("F"),
        help: "edges, npy, txt, svg, geojson, html, csv or unused",
    },
    Opt {
        id: ReconstructId::Stages,
        short: None,
        long: "stages",
        negatable: false,
        value: None,
        help: "draw every stage (SVG output only)",
    },
    Opt {
        id: ReconstructId::Crs,
        short: None,
        long: "crs",
        negatable: false,
        value: Some("CRS"),
        help: "the coordinate reference system a GeoJSON output names (GeoJSON
output only): EPSG:32632 (written as a named crs,
urn:ogc:def:crs:EPSG::32632), another name, a crs member's JSON
object (not PROJJSON, which GDAL reads as EPSG:4326), or null;
instead of a GeoJSON input's own. Without it, a GIS reads an
output from other inputs as longitude and latitude",
    },
    Opt {
        id: ReconstructId::Sequential,
        short: None,
        long: "sequential",
        negatable: false,
        value: None,
        help: "do not use threads (the result is the same)",
    },
    Opt {
        id: ReconstructId::Timings,
        short: None,
        long: "timings",
        negatable: false,
        value: None,
        help: "on standard error, one line `condt: time STEP SECONDS s` per step:
read, snap (with --snap), earlier-passes (when smoothing ran; its
line ends in a note in parentheses), triangulation, each stage of
the last pass, curves, other, write, notes (without --quiet),
total",
    },
    Opt {
        id: ReconstructId::Quiet,
        short: Some('q'),
        long: "quiet",
        negatable: false,
        value: None,
        help: QUIET_HELP,
    },
    Opt {
        id: ReconstructId::Help,
        short: Some('h'),
        long: "help",
        negatable: false,
        value: None,
        help: "show this help",
    },
];

/// The options of `condt reconstruct`: the fixed ones, and a `--[no-]FLAG` for every stage
/// the library's table gives a switch, so a new stage needs no change here (but its usage line
/// in `RECONSTRUCT_ABOUT`, which is written by hand).
fn reconstruct_options() -> Vec<Opt<ReconstructId>> {
    let switches = Stage::ALL.into_iter().filter_map(|stage| {
        stage.switch().map(|switch| Opt {
            id: ReconstructId::StageSwitch(stage),
            short: None,
            long: switch.flag,
            negatable: true,
            value: None,
            help: switch.help,
        })
    });
    let at = RECONSTRUCT_BASE_OPTIONS
        .iter()
        .position(|opt| opt.id == ReconstructId::OutliersFirst)
        .map_or(RECONSTRUCT_BASE_OPTIONS.len(), |k| k + 1);
    let mut options: Vec<Opt<ReconstructId>> = RECONSTRUCT_BASE_OPTIONS[..at].to_vec();
    options.extend(switches);
    options.extend_from_slice(&RECONSTRUCT_BASE_OPTIONS[at..]);
    options
}

const RECONSTRUCT_ABOUT: &str = "\
condt reconstruct: the curves through unorganized planar points (ConDT)

Usage:
  condt reconstruct INPUT [-o OUTPUT] [--paper] [--u X | --adaptive]
                    [--iqr K | --no-outlier-filter] [--[no-]iqr-floor]
                    [--no-manifold-fix | --repair MODE]
                    [--outliers-first] [--[no-]repair-again] [--[no-]local-outliers]
                    [--[no-]confirm-given-back] [--[no-]clumps] [--[no-]close-gaps]
                    [--[no-]junctions] [--[no-]crossings] [--[no-]tips] [--[no-]spikes]
                    [--[no-]hooks] [--[no-]tails] [--[no-]detours] [--[no-]smooth]
                    [--method condt|nn-crust|crust]
                    [--input-format F] [--columns X,Y] [--snap D] [--format F] [--stages]
                    [--crs CRS] [--sequential] [--timings] [--quiet]

Example:
  condt reconstruct data/shapes.txt -o shapes.svg --stages

Output format by OUTPUT's extension or --format (which wins; a note says so where the extension
names another): `edges` (.edges: one edge `i j` per line, i < j, sorted), `npy` (.npy: the same
edges as a NumPy array of shape (m, 2), uint32 when every point number fits, int64 otherwise),
`txt` (.txt: one curve per line, `closed` or `open` then its point numbers; the default on
standard output and for a name without an extension, such as /dev/null), `svg` (.svg: the points
and curves; with --stages the Delaunay triangulation and the graph after every stage that ran,
side by side; a panel is shaped like the points' bounding box, from 1:4 to 4:1; y grows upwards,
as in a plot, so image rows, which count down, show upside down), `geojson` (.geojson or .json:
one LineString per curve, in the order of the txt lines, on the input's coordinates; a GeoJSON
input's `crs` member is carried on, a GeoJSON sequence's first, or --crs names one), `html`
(.html: a self-contained page to explore every stage: layers, pan and zoom, and a click on a
point or an edge tells why it was kept or dropped), `csv` (.csv: the curves' coordinates, a
header `curve,closed,point,x,y` and one row per point of each curve in the order of the txt
lines, a closed curve's first point again at its end; every field a number, for R, MATLAB,
Julia and spreadsheets), `unused` (by --format only: the numbers of the points with no edge in
the result, the outliers, one per line, ascending). A summary goes to standard error: points,
curves, and how many points are unused.

Point numbers count from 0: the input's first point (its first row after any header) is 0, in
every output and message. R, MATLAB, Octave and Julia count from 1: add 1 before indexing the
points there (R: pts[e$V1 + 1, ]; MATLAB: P(E(:, 1) + 1, :)), or read each curve's coordinates
from the csv output (read.csv, readmatrix, CSV.read) or the GeoJSON one (jsondecode).

The default pipeline is the paper's (Algorithms 1-3) with the outlier filter's spacing floor,
the repair `needs` (run again without the edges the outlier filter cut), local outlier removal,
clumps, confirming given-back components, gap closing, junctions, crossings, tips, spikes,
hooks, outlier tails, detours and smoothing passes; --no-local-outliers keeps sparsely sampled
curves of 3 or 4 points and closed ones of 6, which the local removal takes for outliers (closed
ones of 5, which turn too sharply at every point for the clumps, with --no-clumps too);
--paper runs the paper's pipeline alone. Options that contradict each other are an error; an
option given twice with the same value (`--u 2 --u 2.0`) is taken once.
";

/// `condt reconstruct --help`.
fn reconstruct_help() -> String {
    format!(
        "{RECONSTRUCT_ABOUT}\nOptions:\n{}",
        options::help(&reconstruct_options(), 24)
    )
}

/// `--snap`'s help, the same for both commands.
const SNAP_HELP: &str = "move each point within distance D of an earlier point that stays
onto the nearest such point (an exact duplicate where its first copy
went), before anything else (`condt::snap`):
layers exported piece by piece repeat shared borders with rounding
differences, and a curve cannot run along both copies (a GPS stop's
pile of fixes, snapped at its spread, becomes one point). The points
moved become exact duplicates, merged as those are. Off by default:
only you know how far apart two samples may be and still be one";

/// The options of `condt triangulate`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum TriangulateId {
    Output,
    Edges,
    InputFormat,
    Columns,
    Snap,
    Timings,
    Quiet,
    Help,
}

const TRIANGULATE_OPTIONS: &[Opt<TriangulateId>] = &[
    Opt {
        id: TriangulateId::Output,
        short: Some('o'),
        long: "output",
        negatable: false,
        value: Some("FILE"),
        help: "write to FILE instead of standard output",
    },
    Opt {
        id: TriangulateId::Edges,
        short: None,
        long: "edges",
        negatable: false,
        value: None,
        help: "write edges instead of triangles (an OUTPUT ending in .edges gets
edges without it)",
    },
    Opt {
        id: TriangulateId::InputFormat,
        short: None,
        long: "input-format",
        negatable: false,
        value: Some("F"),
        help: INPUT_FORMAT_HELP,
    },
    Opt {
        id: TriangulateId::Columns,
        short: None,
        long: "columns",
        negatable: false,
        value: Some("X,Y"),
        help: COLUMNS_HELP,
    },
    Opt {
        id: TriangulateId::Snap,
        short: None,
        long: "snap",
        negatable: false,
        value: Some("D"),
        help: SNAP_HELP,
    },
    Opt {
        id: TriangulateId::Timings,
        short: None,
        long: "timings",
        negatable: false,
        value: None,
        help: "on standard error, one line `condt: time STEP SECONDS s` per step:
read, snap (with --snap), triangulation, write, notes (without
--quiet), total",
    },
    Opt {
        id: TriangulateId::Quiet,
        short: Some('q'),
        long: "quiet",
        negatable: false,
        value: None,
        help: QUIET_HELP,
    },
    Opt {
        id: TriangulateId::Help,
        short: Some('h'),
        long: "help",
        negatable: false,
        value: None,
        help: "show this help",
    },
];

const TRIANGULATE_ABOUT: &str = "\
condt triangulate: the Delaunay triangulation of planar points

Usage:
  condt triangulate INPUT [-o OUTPUT] [--edges] [--input-format F] [--columns X,Y] [--snap D]
                    [--timings] [--quiet]

Example:
  condt triangulate data/shapes.txt --edges -o shapes.edges

Writes one triangle `i j k` per line, counter-clockwise, in point numbers, which count from 0
(the input's first point: add 1 in R, MATLAB or Julia, which count from 1); with --edges one
edge `i j` (i < j) per line instead, sorted. What is written follows OUTPUT's extension (any
case): .txt, or a name without one (standard output, /dev/null), gets that text; .edges gets
the edges, with or without --edges; .npy gets the same as a NumPy array, of shape (t, 3) or
with --edges (m, 2), uint32 when every point number fits, int64 otherwise. Any other extension
(.svg, .geojson, .html: `condt reconstruct` draws those) is refused before anything is read.
Points all on one line have no triangles: their chain of edges is written only with --edges,
and a note on standard error says so.
";

/// `condt triangulate --help`.
fn triangulate_help() -> String {
    format!(
        "{TRIANGULATE_ABOUT}\nOptions:\n{}",
        options::help(TRIANGULATE_OPTIONS, 20)
    )
}

/// Why a command failed, and with which exit code.
#[derive(Debug)]
pub(crate) enum CliError {
    /// The command line is wrong (exit code 2).
    Usage(String),
    /// A command's own options are wrong (exit code 2): the help to read is that command's.
    CommandUsage {
        message: String,
        command: &'static str,
    },
    /// The input could not be read (exit code 1).
    Io(IoError),
    /// The points cannot be triangulated (exit code 1).
    Input(String),
    /// The output could not be written (exit code 1).
    File { file: String, error: io::Error },
    /// The reader of standard output or of a pipe went away: not reported (see
    /// [`crate::output::end_by_broken_pipe`]).
    BrokenPipe,
}

impl CliError {
    /// The process exit code for this error.
    /// A usage error of `command`'s options, whose help is the one to read.
    fn of_command(self, command: &'static str) -> CliError {
        match self {
            CliError::Usage(message) => CliError::CommandUsage { message, command },
            other => other,
        }
    }

    pub(crate) fn exit_code(&self) -> i32 {
        match self {
            CliError::Usage(_) | CliError::CommandUsage { .. } => 2,
            CliError::Io(_) | CliError::Input(_) | CliError::File { .. } => 1,
            CliError::BrokenPipe => 141,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Usage(message) => write!(f, "{message}\n\nRun `condt --help` for usage."),
            CliError::CommandUsage { message, command } => write!(
                f,
                "{message}\n\nRun `condt help {command}` for its options."
            ),
            CliError::Io(err) => write!(f, "{err}"),
            CliError::Input(message) => write!(f, "{message}"),
            CliError::File { file, error } => write!(f, "{file}: {error}"),
            CliError::BrokenPipe => write!(f, "the reader of the output went away"),
        }
    }
}

impl From<IoError> for CliError {
    fn from(err: IoError) -> Self {
        CliError::Io(err)
    }
}

/// A line on standard error. A failing standard error (`2>/dev/full`) cannot be told about, and
/// must not stop the run: the error is dropped.
pub(crate) fn note(message: fmt::Arguments<'_>) {
    let _ = writeln!(io::stderr().lock(), "condt: {message}");
}

pub(crate) fn usage(message: impl Into<String>) -> CliError {
    CliError::Usage(message.into())
}

/// An argument as text, for options and their values; file names need not be text.
fn text<'a>(arg: &'a OsStr, what: &str) -> Result<&'a str, CliError> {
    arg.to_str()
        .ok_or_else(|| usage(format!("{what} {}: not valid UTF-8", arg.to_string_lossy())))
}

/// Options of `condt triangulate`.
#[derive(Debug, Default, PartialEq)]
struct TriangulateArgs {
    /// `None`: standard input.
    input: Option<PathBuf>,
    /// `None`: standard output.
    output: Option<PathBuf>,
    /// Edges instead of triangles: `--edges`, or an OUTPUT ending in `.edges`.
    edges: bool,
    /// A NumPy array instead of text: an OUTPUT ending in `.npy`.
    npy: bool,
    /// How INPUT is read (`--input-format`).
    read: ReadOptions,
    /// `--snap D`: the distance, and D as typed.
    snap: Option<(f64, String)>,
    timings: bool,
    quiet: bool,
}

/// What `triangulate` writes to an OUTPUT by its extension (any case): `(edges, npy)`, edges
/// being forced on by `.edges` and left to `--edges` otherwise. A name without an extension is
/// text, as standard output is (`/dev/null`, a pipe's name); an extension it has no writer for
/// is refused rather than given text that its name says is something else.
fn triangulate_output(output: Option<&Path>) -> Result<(bool, bool), CliError> {
    let Some((path, extension)) = output.and_then(|p| Some((p, p.extension()?))) else {
        return Ok((false, false));
    };
    let lower = extension.to_string_lossy().to_ascii_lowercase();
    match lower.as_str() {
        "txt" => Ok((false, false)),
        "edges" => Ok((true, false)),
        "npy" => Ok((false, true)),
        _ => Err(usage(format!(
            "{}: triangulate cannot write {}; it writes text (.txt, or a name without an \
             extension), edges (.edges, as --edges) or a NumPy array (.npy)",
            path.display(),
            if lower.is_empty() {
                "a name ending in a dot".to_string()
            } else {
                format!("a .{} file", extension.to_string_lossy())
            },
        ))),
    }
}

/// Where `-o` and INPUT go while the arguments are read.
#[derive(Default)]
struct Paths {
    output: Option<OsString>,
}

impl Paths {
    /// `-o FILE` (`flag` as written, `value` `None` when the command line ended before it).
    fn output(&mut self, flag: &str, value: Option<OsString>) -> Result<(), CliError> {
        let value = value.ok_or_else(|| usage(format!("{flag} needs a file name")))?;
        if value.is_empty() {
            return Err(usage(format!(
                "{flag} needs a file name, and was given an empty one (use - for standard output)"
            )));
        }
        // Twice with the same name is taken once, as every option is (the help says so).
        match &self.output {
            Some(given) if *given != value => Err(usage(format!(
                "{flag} is given twice, with {} and {}: give one of them",
                given.to_string_lossy(),
                value.to_string_lossy()
            ))),
            _ => {
                self.output = Some(value);
                Ok(())
            }
        }
    }

    /// INPUT (the one operand) and OUTPUT, `-` standing for the standard streams.
    fn finish(
        self,
        command: &str,
        operands: Vec<OsString>,
    ) -> Result<(Option<PathBuf>, Option<PathBuf>), CliError> {
        let mut operands = operands.into_iter();
        let input = operands
            .next()
            .ok_or_else(|| usage(format!("{command} needs an INPUT file (or -)")))?;
        if input.is_empty() {
            return Err(usage(
                "INPUT is an empty file name (use - for standard input)",
            ));
        }
        if let Some(extra) = operands.next() {
            return Err(usage(format!(
                "unexpected extra argument {}",
                extra.to_string_lossy()
            )));
        }
        let stream = |p: OsString| (p != "-").then(|| PathBuf::from(p));
        Ok((stream(input), self.output.and_then(stream)))
    }
}

fn parse_triangulate(args: &[OsString]) -> Result<TriangulateArgs, CliError> {
    let lexed = options::lex(args, TRIANGULATE_OPTIONS, "")?;
    let mut edges = false;
    let mut timings = false;
    let mut quiet = false;
    let mut paths = Paths::default();
    let mut input_format = Setting::new();
    let mut columns = Setting::new();
    let mut snap = Setting::new();
    for given in lexed.given {
        match given.id {
            TriangulateId::Output => paths.output(&given.flag, given.value)?,
            TriangulateId::Edges => edges = true,
            TriangulateId::InputFormat => {
                input_format_option(&mut input_format, &given.flag, given.value.as_ref())?
            }
            TriangulateId::Columns => {
                columns_option(&mut columns, &given.flag, given.value.as_ref())?
            }
            TriangulateId::Snap => snap_option(&mut snap, &given.flag, given.value.as_ref())?,
            TriangulateId::Timings => timings = true,
            TriangulateId::Quiet => quiet = true,
            // Answered before the arguments are read (`run`).
            TriangulateId::Help => {}
        }
    }
    let (input, output) = paths.finish("triangulate", lexed.operands)?;
    let read = read_options(input_format, columns, input.as_deref())?;
    let (edges_by_name, npy) = triangulate_output(output.as_deref())?;
    Ok(TriangulateArgs {
        input,
        output,
        edges: edges || edges_by_name,
        npy,
        read,
        snap: snap.get(),
        timings,
        quiet,
    })
}

/// What to print on standard output when the run succeeds (help, version).
pub(crate) type Printed = String;

/// Runs the tool on `args` (without the program name); `Ok` holds what to print to stdout for
/// informational commands such as `--help`.
pub(crate) fn run(args: &[OsString]) -> Result<Printed, CliError> {
    // `--` ends the options before the command too: what follows is the command and its words.
    let (args, dashed) = match args.split_first() {
        Some((first, after)) if first == "--" => (after, true),
        _ => (args, false),
    };
    let Some((command, rest)) = args.split_first() else {
        return Err(usage("no command given"));
    };
    let command = text(command, "command")?;
    if command.starts_with('-') && !dashed {
        // `--help` and `--version` take nothing after them (`condt -V x` was answered as
        // `condt -V`, where every other extra argument is refused).
        let lexed = options::lex(args, GLOBAL_OPTIONS, "")?;
        let extra = lexed
            .operands
            .first()
            .map(|extra| extra.to_string_lossy().into_owned())
            .or_else(|| lexed.given.get(1).map(|second| second.flag.clone()));
        return match (lexed.given.first(), extra) {
            (Some(given), Some(extra)) => Err(usage(format!(
                "{} takes no argument; unexpected {extra} (`condt help COMMAND` shows a \
                 command's help)",
                given.flag
            ))),
            (Some(given), None) if given.id == GlobalId::Version => {
                Ok(format!("condt {}\n", env!("CARGO_PKG_VERSION")))
            }
            (Some(_), None) => Ok(global_help()),
            (None, _) => Err(usage("no command given")),
        };
    }
    if let ("help", [_, extra, ..]) = (command, rest) {
        return Err(usage(format!(
            "help takes one command; unexpected extra argument {}",
            extra.to_string_lossy()
        )));
    }
    match command {
        "help" => match rest.first().map(|c| c.to_str()) {
            None | Some(Some("help" | "--help" | "-h")) => Ok(global_help()),
            Some(Some("reconstruct")) => Ok(reconstruct_help()),
            Some(Some("triangulate")) => Ok(triangulate_help()),
            Some(Some("score")) => Ok(crate::score::help()),
            Some(_) => Err(usage(format!(
                "help: unknown command {}; the commands are reconstruct, triangulate and score",
                rest[0].to_string_lossy()
            ))),
        },
        "reconstruct" if options::asks_help(rest, &reconstruct_options()) => Ok(reconstruct_help()),
        "triangulate" if options::asks_help(rest, TRIANGULATE_OPTIONS) => Ok(triangulate_help()),
        "score" if options::asks_help(rest, crate::score::OPTIONS) => Ok(crate::score::help()),
        "score" => crate::score::command(rest).map_err(|e| e.of_command("score")),
        "reconstruct" => parse_reconstruct(rest)
            .and_then(reconstruct_command)
            .map(|()| String::new())
            .map_err(|e| e.of_command("reconstruct")),
        "triangulate" => parse_triangulate(rest)
            .and_then(triangulate_command)
            .map(|()| String::new())
            .map_err(|e| e.of_command("triangulate")),
        other => Err(usage(format!(
            "unknown command {other}; the commands are reconstruct, triangulate and score"
        ))),
    }
}

/// Output formats of `condt reconstruct`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Format {
    Edges,
    Npy,
    Polylines,
    Svg,
    GeoJson,
    Html,
    /// The curves' coordinates, one row per point (`condt_io::write_curves_csv`).
    Csv,
    /// The unused points' numbers; no extension names it (a list of numbers is any `.txt`).
    Unused,
}

impl Format {
    /// The format an OUTPUT's extension names (any case); none names `unused`.
    fn of_extension(extension: &str) -> Option<Format> {
        Format::named(extension).filter(|&format| format != Format::Unused)
    }

    /// The format of a name in any case, as `--input-format` takes its names.
    fn named(name: &str) -> Option<Format> {
        match name.to_ascii_lowercase().as_str() {
            "edges" => Some(Format::Edges),
            "npy" => Some(Format::Npy),
            "txt" => Some(Format::Polylines),
            "svg" => Some(Format::Svg),
            "geojson" | "json" => Some(Format::GeoJson),
            "html" | "htm" => Some(Format::Html),
            "csv" => Some(Format::Csv),
            "unused" => Some(Format::Unused),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Format::Edges => "edges",
            Format::Npy => "npy",
            Format::Polylines => "txt",
            Format::Svg => "svg",
            Format::GeoJson => "geojson",
            Format::Html => "html",
            Format::Csv => "csv",
            Format::Unused => "unused",
        }
    }
}

/// Refuses an option that asks for a step the other options leave no way to run (the help:
/// options that contradict each other are an error): repairing again without a repair before
/// the outlier filter, the given-back check without the local outlier removal, the spacing
/// floor without the filter, the filter first without both (found by a fuzzer: each was
/// accepted and did nothing).
fn refuse_steps_that_cannot_run(
    params: &Params,
    named_on: &[(Stage, String)],
    iqr_floor: Option<&str>,
    outliers_first: Option<&str>,
) -> Result<(), CliError> {
    let running = params.stages();
    for (stage, said) in named_on {
        if running.contains(stage) {
            continue;
        }
        let needs = match stage {
            Stage::RepairAgain => "the repair and then the outlier filter (it repairs again without the edges the filter cut)",
            Stage::GivenBack => "the local outlier removal (it confirms what that removal gave back)",
            _ => "other steps",
        };
        return Err(usage(format!(
            "{said} needs {needs}, which the other options turn off"
        )));
    }
    if let (Some(said), None) = (iqr_floor, params.outlier_factor) {
        return Err(usage(format!(
            "{said} sets the outlier filter's spacing floor, but the filter is off (--no-outlier-filter)"
        )));
    }
    if let Some(said) = outliers_first {
        if params.outlier_factor.is_none() || params.repair == Repair::Off {
            return Err(usage(format!(
                "{said} runs the outlier filter before the repair, but one of them is off \
                 (--no-outlier-filter or --no-manifold-fix)"
            )));
        }
    }
    Ok(())
}

/// Options of `condt reconstruct`.
#[derive(Debug, PartialEq)]
struct ReconstructArgs {
    /// `None`: standard input.
    input: Option<PathBuf>,
    /// `None`: standard output.
    output: Option<PathBuf>,
    params: Params,
    /// How INPUT is read (`--input-format`).
    read: ReadOptions,
    /// `--snap D`: the distance, and D as typed.
    snap: Option<(f64, String)>,
    format: Format,
    stages: bool,
    /// `--crs`, as the `"crs"` member's JSON text.
    crs: Option<String>,
    timings: bool,
    quiet: bool,
}

/// The number after `flag`, and the text it was read from; whether its value is accepted is for
/// the library to say.
fn number<'a>(flag: &str, value: Option<&'a OsString>) -> Result<(f64, &'a str), CliError> {
    let value = value.ok_or_else(|| usage(format!("{flag} needs a number")))?;
    let text = text(value, flag)?;
    let x = text
        .parse::<f64>()
        .map_err(|_| usage(format!("{flag} {text}: not a number")))?;
    Ok((x, text))
}

/// What `--u` accepts, as the library's `Uniformity::check` decides it.
const U_RANGE: &str = "a finite number greater than 0";
/// What `--iqr` accepts, as the library's `Params::check` decides it.
const IQR_RANGE: &str = "a finite number, 0 or more";

/// A number the library refused, told as the user typed it with the option they typed: the
/// parsed value would say `inf` for `1e400` and `NaN` for `nan`, and the library's name `k` is
/// not an option.
fn out_of_range(flag: &str, typed: &str, range: &str) -> CliError {
    usage(format!(
        "{flag} {typed}: out of range ({flag} takes {range})"
    ))
}

/// A parameter the library refused, told with the option that set it.
fn refused(err: Error) -> CliError {
    let flag = match err {
        Error::InvalidParameter { name: "u", .. } => "--u",
        Error::InvalidParameter { name: "k", .. } => "--iqr",
        _ => "",
    };
    usage(format!("{flag}: {err}"))
}

/// One setting that several options can make: the first option that set it is kept, so that a
/// second one saying otherwise is reported instead of silently winning.
pub(crate) struct Setting<T> {
    value: Option<(T, String)>,
}

impl<T: PartialEq> Setting<T> {
    pub(crate) fn new() -> Self {
        Setting { value: None }
    }

    fn set(&mut self, value: T, said: impl Into<String>) -> Result<(), CliError> {
        self.set_alike(value, said, T::eq)
    }

    /// [`set`](Setting::set), a second value that is `same` as the first being no contradiction.
    fn set_alike(
        &mut self,
        value: T,
        said: impl Into<String>,
        same: impl Fn(&T, &T) -> bool,
    ) -> Result<(), CliError> {
        let said = said.into();
        match &self.value {
            Some((old, old_said)) if !same(old, &value) => Err(usage(format!(
                "{old_said} and {said} contradict each other: give one of them"
            ))),
            Some(_) => Ok(()),
            None => {
                self.value = Some((value, said));
                Ok(())
            }
        }
    }

    fn get(self) -> Option<T> {
        self.value.map(|(value, _)| value)
    }
}

/// `--input-format F` (`flag` as written), checked and set once.
pub(crate) fn input_format_option(
    setting: &mut Setting<InputFormat>,
    flag: &str,
    value: Option<&OsString>,
) -> Result<(), CliError> {
    let names = InputFormat::ALL.map(InputFormat::name).join(", ");
    let value = value.ok_or_else(|| usage(format!("{flag} needs a format: {names}")))?;
    let name = text(value, flag)?;
    let chosen = InputFormat::named(name).ok_or_else(|| {
        usage(format!(
            "{flag} {name}: unknown input format; the formats are {names}"
        ))
    })?;
    setting.set(chosen, format!("{flag} {name}"))
}

/// What `--snap` accepts, as the library's `condt::snap` decides it.
const SNAP_RANGE: &str = "a finite distance, 0 or more";

/// `--snap D` (`flag` as written), checked by the library (`condt::snap` of no points) and set
/// once, kept with its text for the note.
fn snap_option(
    setting: &mut Setting<(f64, String)>,
    flag: &str,
    value: Option<&OsString>,
) -> Result<(), CliError> {
    let (distance, typed) = number(flag, value)?;
    condt::snap(&mut [], distance).map_err(|_| out_of_range(flag, typed, SNAP_RANGE))?;
    setting.set_alike(
        (distance, typed.to_string()),
        format!("{flag} {typed}"),
        |a, b| a.0 == b.0,
    )
}

/// `--columns X,Y` (`flag` as written), checked and set once.
pub(crate) fn columns_option(
    setting: &mut Setting<Columns>,
    flag: &str,
    value: Option<&OsString>,
) -> Result<(), CliError> {
    let value = value.ok_or_else(|| {
        usage(format!(
            "{flag} needs the x and y columns, names or numbers from 1: POINT_X,POINT_Y or 2,3"
        ))
    })?;
    let spec = text(value, flag)?;
    let columns = Columns::parse(spec).map_err(|why| usage(format!("{flag} {why}")))?;
    // Given twice, the same columns as the header lookup finds them (`POINT_X,POINT_Y` and
    // `point_x,point_y`) are taken once, the first as written.
    setting.set_alike(columns, format!("{flag} {spec}"), Columns::same)
}

/// How INPUT (`None`: standard input) is read, by the options given. `--columns` with an INPUT
/// that is read in another format than CSV, TSV or plain text (by its name or `--input-format`)
/// is refused here, before anything is read.
pub(crate) fn read_options(
    input_format: Setting<InputFormat>,
    columns: Setting<Columns>,
    input: Option<&Path>,
) -> Result<ReadOptions, CliError> {
    let mut options = ReadOptions::new();
    let stated = input_format.get();
    if let Some(format) = stated {
        options = options.with_format(format);
    }
    if let Some(columns) = columns.get() {
        let format = stated.or_else(|| input.and_then(InputFormat::of_path));
        let chosen_in =
            |f: &InputFormat| matches!(f, InputFormat::Csv | InputFormat::Tsv | InputFormat::Text);
        if let Some(format) = format.filter(|f| !chosen_in(f)) {
            let by = if stated.is_some() {
                "--input-format"
            } else {
                "its name"
            };
            // A .node file can be a table under another name; an array or GeoJSON cannot.
            let advice = match format {
                InputFormat::Node => "; --input-format csv reads it as CSV",
                _ => ": columns apply to CSV, TSV and plain text input only",
            };
            return Err(usage(format!(
                "--columns {columns} chooses the columns of CSV, TSV or plain text input, but {} \
                 is read as {} by {by}{advice}",
                shown_input(input),
                format.name()
            )));
        }
        options = options.with_columns(columns);
    }
    Ok(options)
}

const REPAIR_MODES: &str = "needs, paper, mutual, crossing or off";

fn repair_mode(value: Option<&OsString>) -> Result<Repair, CliError> {
    let value = value.ok_or_else(|| usage(format!("--repair needs a mode: {REPAIR_MODES}")))?;
    // Any case, as `--input-format` takes its names.
    match value.to_str().map(str::to_ascii_lowercase).as_deref() {
        Some("paper") => Ok(Repair::Paper),
        Some("mutual") => Ok(Repair::Mutual),
        Some("crossing") => Ok(Repair::CrossingAware),
        Some("needs") => Ok(Repair::Needs),
        Some("off") => Ok(Repair::Off),
        _ => Err(usage(format!(
            "--repair {}: unknown mode; the modes are {REPAIR_MODES}",
            value.to_string_lossy()
        ))),
    }
}

fn parse_reconstruct(args: &[OsString]) -> Result<ReconstructArgs, CliError> {
    use ReconstructId as Id;
    let lexed = options::lex(args, &reconstruct_options(), "")?;
    // `--paper` chooses the starting point wherever it stands; the other options adjust it.
    let mut params = if lexed.given.iter().any(|g| g.id == Id::Paper) {
        Params::paper()
    } else {
        Params::default()
    };
    let mut paths = Paths::default();
    let mut uniformity = Setting::new();
    let mut outliers = Setting::new();
    let mut repair = Setting::new();
    // Per stage with a switch, its setting, in the table's order.
    let mut switched: Vec<(Stage, Setting<bool>)> = Vec::new();
    let mut smooth = Setting::new();
    let mut iqr_floor = Setting::new();
    // As typed, when given: an option that needs a step the others turn off is refused.
    let (mut iqr_floor_said, mut outliers_first_said) = (None::<String>, None::<String>);
    let mut format = Setting::new();
    let mut input_format = Setting::new();
    let mut columns = Setting::new();
    let mut snap = Setting::new();
    let mut method = Setting::new();
    // ConDT's own options, as written, to refuse them beside a baseline method.
    let condt_options: Vec<&str> = lexed
        .given
        .iter()
        .filter(|g| g.id.sets_a_condt_stage())
        .map(|g| g.flag.as_str())
        .collect();
    let mut stages = false;
    let mut crs = Setting::new();
    let mut timings = false;
    let mut quiet = false;
    for given in &lexed.given {
        let flag = given.flag.as_str();
        let value = given.value.as_ref();
        match given.id {
            Id::Output => paths.output(flag, given.value.clone())?,
            Id::Method => {
                let name = value
                    .ok_or_else(|| usage("--method needs a name: condt, nn-crust or crust"))?
                    .to_string_lossy();
                let chosen = match name.to_ascii_lowercase().as_str() {
                    "condt" => Method::ConDT,
                    "nn-crust" => Method::NnCrust,
                    "crust" => Method::Crust,
                    _ => {
                        return Err(usage(format!(
                        "{flag} {name}: unknown method; the methods are condt, nn-crust and crust"
                    )))
                    }
                };
                method.set(chosen, format!("{flag} {name}"))?;
            }
            // Each value is checked as it is given, so that a refused one is told as typed
            // (not as a contradiction: NaN differs from NaN) and a value repeated is compared
            // only once it is accepted.
            Id::U => {
                let (u, typed) = number(flag, value)?;
                Uniformity::Fixed(u)
                    .check()
                    .map_err(|_| out_of_range(flag, typed, U_RANGE))?;
                uniformity.set(Uniformity::Fixed(u), format!("{flag} {typed}"))?;
            }
            Id::Adaptive => uniformity.set(Uniformity::Adaptive, flag)?,
            Id::Iqr => {
                let (k, typed) = number(flag, value)?;
                Params::default()
                    .with_outlier_factor(Some(k))
                    .check()
                    .map_err(|_| out_of_range(flag, typed, IQR_RANGE))?;
                outliers.set(Some(k), format!("{flag} {typed}"))?;
            }
            Id::NoOutlierFilter => outliers.set(None, flag)?,
            Id::OutliersFirst => {
                params.outliers_first = true;
                outliers_first_said = Some(flag.to_string());
            }
            Id::StageSwitch(stage) => {
                let k = match switched.iter().position(|(s, _)| *s == stage) {
                    Some(k) => k,
                    None => {
                        switched.push((stage, Setting::new()));
                        switched.len() - 1
                    }
                };
                switched[k].1.set(given.on, flag)?;
            }
            Id::Smooth => smooth.set(given.on, flag)?,
            Id::IqrFloor => {
                iqr_floor.set(given.on, flag)?;
                if given.on {
                    iqr_floor_said = Some(flag.to_string());
                }
            }
            Id::NoManifoldFix => repair.set(Repair::Off, flag)?,
            Id::Repair => {
                let mode = repair_mode(value)?;
                repair.set(
                    mode,
                    format!(
                        "{flag} {}",
                        value.map_or("".into(), |v| v.to_string_lossy())
                    ),
                )?;
            }
            Id::Format => {
                let value = value.ok_or_else(|| {
                    usage(
                        "--format needs a name: edges, npy, txt, svg, geojson, html, csv or unused",
                    )
                })?;
                let name = text(value, flag)?;
                let chosen = Format::named(name).ok_or_else(|| {
                    usage(format!(
                        "--format {name}: unknown format; the formats are edges, npy, txt, svg, \
                         geojson, html, csv and unused"
                    ))
                })?;
                format.set(chosen, format!("--format {name}"))?;
            }
            Id::InputFormat => input_format_option(&mut input_format, flag, value)?,
            Id::Columns => columns_option(&mut columns, flag, value)?,
            Id::Snap => snap_option(&mut snap, flag, value)?,
            Id::Stages => stages = true,
            Id::Crs => {
                let value = value.ok_or_else(|| {
                    usage("--crs needs a reference system: a name such as EPSG:32632, or JSON")
                })?;
                let given = text(value, flag)?;
                let member =
                    condt_io::crs_member(given).map_err(|why| usage(format!("--crs {why}")))?;
                crs.set(member, format!("--crs {given}"))?;
            }
            Id::Timings => timings = true,
            Id::Quiet => quiet = true,
            // The starting point, chosen above.
            Id::Paper => {}
            Id::Sequential => params.parallel = false,
            // Answered before the arguments are read (`run`).
            Id::Help => {}
        }
    }
    if let Some(u) = uniformity.get() {
        params.uniformity = u;
    }
    if let Some(k) = outliers.get() {
        params.outlier_factor = k;
    }
    if let Some(mode) = repair.get() {
        params.repair = mode;
    }
    // The steps turned on by name, as typed, for the check below.
    let named_on: Vec<(Stage, String)> = switched
        .iter()
        .filter_map(|(stage, setting)| match &setting.value {
            Some((true, said)) => Some((*stage, said.clone())),
            _ => None,
        })
        .collect();
    for (stage, setting) in switched {
        if let Some(on) = setting.get() {
            params.set_stage(stage, on);
        }
    }
    if let Some(on) = smooth.get() {
        params.smooth = on;
    }
    if let Some(on) = iqr_floor.get() {
        params.iqr_floor = on;
    }
    if let Some(chosen) = method.get() {
        if chosen != Method::ConDT {
            if let Some(option) = condt_options.first() {
                return Err(usage(format!(
                    "{option} sets a ConDT stage or parameter, but --method chooses a baseline, \
                     which has none"
                )));
            }
        }
        params.method = chosen;
    }
    refuse_steps_that_cannot_run(
        &params,
        &named_on,
        iqr_floor_said.as_deref(),
        outliers_first_said.as_deref(),
    )?;
    params.check().map_err(refused)?;
    let (input, output) = paths.finish("reconstruct", lexed.operands)?;
    let read = read_options(input_format, columns, input.as_deref())?;
    let format = match (format.get(), output.as_deref()) {
        (Some(f), _) => f,
        (None, None) => Format::Polylines,
        // A name without an extension (`/dev/null`, `/dev/stdout`, a pipe's) gets the text that
        // standard output gets; an extension with no writer is refused, not given that text.
        (None, Some(path)) => match path.extension() {
            None => Format::Polylines,
            Some(extension) => {
                let extension = extension.to_str().unwrap_or("");
                Format::of_extension(extension).ok_or_else(|| {
                    usage(format!(
                        "cannot tell the format of {} from its extension; use --format",
                        path.display()
                    ))
                })?
            }
        },
    };
    if stages && format != Format::Svg {
        return Err(usage(format!(
            "--stages draws the stages in an SVG picture, but the output format is `{}`; \
             use an .svg file or --format svg",
            format.name()
        )));
    }
    let crs = crs.get();
    if crs.is_some() && format != Format::GeoJson {
        return Err(usage(format!(
            "--crs names the reference system of a GeoJSON output, but the output format is `{}`; \
             use a .geojson file or --format geojson",
            format.name()
        )));
    }
    Ok(ReconstructArgs {
        input,
        output,
        params,
        read,
        snap: snap.get(),
        format,
        stages,
        crs,
        timings,
        quiet,
    })
}

/// Reads the points of INPUT (`None`: standard input), and with `--snap` (`snap`) snaps them,
/// each step a lap of `timings`; returns the points and what `--snap` did ([`note_snapped`]).
/// With `parallel` false (`--sequential`) the reading, which otherwise splits a large text over
/// rayon's threads, runs on this thread alone (a one-thread pool; same points either way).
/// A GeoJSON input's `"crs"` member comes with the points (`None` for other formats), for a
/// GeoJSON output to carry on. `options`: `--input-format`.
fn read_input(
    input: Option<&Path>,
    parallel: bool,
    options: &ReadOptions,
    snap: &Option<(f64, String)>,
    progress: &mut Progress,
    timings: &mut Timings,
) -> Result<(PointFile, Option<(usize, String)>), CliError> {
    let path = input.unwrap_or(Path::new("-"));
    let pool = (!parallel)
        .then(|| rayon::ThreadPoolBuilder::new().num_threads(1).build().ok())
        .flatten();
    let mut read = match pool {
        Some(pool) => pool.install(|| read_points_with(path, options))?,
        None => read_points_with(path, options)?,
    };
    progress.suspend(|| timings.lap("read"));
    let snapped = snap_points(&mut read.points, snap, input, progress, timings)?;
    Ok((read, snapped))
}

/// The reconstruction's refusal of INPUT's `count` points, read with `read`: two points too close
/// to measure are named by their lines where the file's lines say them (the library names input
/// positions, which a reader of the file would count by hand).
fn reconstruction_error(
    err: Error,
    input: Option<&Path>,
    read: &ReadOptions,
    count: usize,
) -> CliError {
    let shown = shown_input(input);
    if let Error::TooCloseToMeasure {
        first,
        second,
        largest,
    } = err
    {
        let lines = input
            .and_then(|path| condt_io::point_lines(path, read, count, &[first, second, largest]));
        if let Some(&[first, second, largest]) = lines.as_deref() {
            return CliError::Input(format!(
                "{shown}:{first}: this point and line {second}'s are closer than 2^-450 times \
                 the largest coordinate (line {largest}'s): the reconstruction cannot measure \
                 lengths across that spread (the triangulation can)"
            ));
        }
    }
    CliError::Input(format!("{shown}: {err}"))
}

/// INPUT as messages name it: `<stdin>` for standard input (`None`).
pub(crate) fn shown_input(input: Option<&Path>) -> String {
    input.map_or("<stdin>".into(), |p| p.display().to_string())
}

/// A file operand as messages name it, `-` being standard input: [`shown_input`]'s names.
pub(crate) fn shown_operand(path: &Path) -> String {
    shown_input((path.as_os_str() != "-").then_some(path))
}

/// A count and its noun, plural unless the count is one: "1 point", "0 points", "2 points".
struct Counted(usize, &'static str);

impl fmt::Display for Counted {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Counted(n, noun) = *self;
        write!(f, "{n} {noun}{}", if n == 1 { "" } else { "s" })
    }
}

/// `--snap D` on the points read (nothing without it): how many points moved, and D as typed;
/// its own step on the bar and in `--timings`.
fn snap_points(
    points: &mut [condt::Point],
    snap: &Option<(f64, String)>,
    input: Option<&Path>,
    progress: &mut Progress,
    timings: &mut Timings,
) -> Result<Option<(usize, String)>, CliError> {
    let Some((distance, typed)) = snap else {
        return Ok(None);
    };
    // Up to a second a million points where the distance merges many (the bar would otherwise
    // still say "reading").
    progress.computing("snapping near duplicates");
    let moved = condt::snap(points, *distance)
        .map_err(|err| CliError::Input(format!("{}: {err}", shown_input(input))))?;
    progress.suspend(|| timings.lap("snap"));
    Ok(Some((moved, typed.clone())))
}

/// What `--snap` did, told before the merged duplicates it made.
fn note_snapped(snapped: Option<(usize, String)>) {
    if let Some((moved, typed)) = snapped {
        note(format_args!(
            "--snap {typed}: moved {} onto an earlier point within that distance",
            Counted(moved, "point")
        ));
    }
}

/// A note when the result has pairs of points given twice a little apart
/// ([`condt::Reconstruction::twin_pairs`]): each a curve of its own beside the curve it was meant
/// to be, or points left unused, which the summary alone would not tell (a GIS user's review:
/// 462 such pairs and "0 unused"; another's: a shared side given twice left unused, no hint).
/// `--snap` merges them.
fn note_twins(result: &condt::Reconstruction) {
    let twins = result.twin_pairs();
    if let Some([a, b]) = twins.first() {
        note(format_args!(
            "{} pairs of points that lie 16 times nearer each other than any other point (the \
             first: points {a} and {b}): points given twice, a little apart (a shared border \
             exported from both sides, a grey image's contour)? --snap D merges points within D",
            twins.len(),
        ));
    }
}

/// A result in many short pieces says what they may mean: a raw laser scan of 200,000 points
/// came back as 23,120 curves and 34,498 unused points, a summary that read as success (a
/// robotics user's review). Noise breaks curves into pieces of a few points that end loose (at
/// a point with one edge) or close on themselves, where a drawing's run for tens: the note
/// needs 1,000 points or more, 100 such pieces or more, and fewer than 10 points a piece on
/// average (of the evaluation suites' 1,429 cases none of 500 points or more has that; of
/// `../shared/data`'s 190 sets, six noisy ones get it). A curve between two branch points is
/// no piece: a clean street grid is many short curves between its junctions (8 by 8 blocks of
/// 8 spacings: 140 curves of 9.2 points, exact, were told they might be noise when every curve
/// counted: a README reader's review).
fn note_pieces(result: &condt::Reconstruction) {
    let loose_end = |c: &condt::Curve| {
        [c.points().next(), c.points().next_back()]
            .into_iter()
            .flatten()
            .any(|end| result.degree(end) == 1)
    };
    let (pieces, on_pieces) = result
        .curves()
        .iter()
        .filter(|c| c.is_closed() || loose_end(c))
        .fold((0, 0), |(pieces, points), c| (pieces + 1, points + c.len()));
    if result.num_points() >= 1000 && pieces >= 100 && on_pieces < 10 * pieces {
        note(format_args!(
            "the curves that end loose or close on themselves have {:.1} points on average: a \
             noisy set (a scan, a noisy trace)? Thin it to an even spacing of several times the \
             noise first (README.md, *Scans*)",
            on_pieces as f64 / pieces as f64
        ));
    }
}

/// The one rule for merged duplicates, told the same way by both commands.
fn note_duplicates(points: usize, distinct: usize) {
    let merged = points - distinct;
    if merged > 0 {
        note(format_args!(
            "{} merged into the first point at the same position ({distinct} distinct of {points})",
            Counted(merged, "exact duplicate point"),
        ));
    }
}

/// One note for the GeoJSON features of `file` that gave no point: `null` geometries that
/// many, and `empty` Points and MultiPoints (`"coordinates": []`); none when both are 0.
pub(crate) fn note_skipped_geometries(file: &str, null: usize, empty: usize) {
    let mut skipped = Vec::new();
    if null > 0 {
        skipped.push(format!("{} with a null geometry", Counted(null, "feature")));
    }
    if empty > 0 {
        skipped.push(if empty == 1 {
            "1 empty Point or MultiPoint".to_string()
        } else {
            format!("{empty} empty Points or MultiPoints")
        });
    }
    if !skipped.is_empty() {
        note(format_args!(
            "{file}: skipped {}: they hold no point (the points are numbered without them)",
            skipped.join(" and ")
        ));
    }
}

/// A note when the GeoJSON at `line` of `file` gave another `crs` than the one kept (the
/// document's own, else the first read; a document's `crs` may follow its features): it is left
/// out, not carried on, and the points are read as given.
pub(crate) fn note_dropped_crs(file: &str, line: Option<usize>) {
    if let Some(line) = line {
        note(format_args!(
            "{file}:{line}: this crs differs from the one kept (the document's own, else the \
             first one read), and every point is read as given, without conversion"
        ));
    }
}

/// A note when a GeoJSON output names no reference system but its coordinates cannot be
/// longitudes and latitudes (RFC 7946's, which GIS readers then assume): projected metres,
/// a scan's UTM coordinates, which a map would place nowhere near where they are.
fn note_projected_without_crs(output: &str, points: &[condt::Point]) {
    if let Some(p) = condt_io::not_longitude_latitude(points) {
        note(format_args!(
            "{output}: coordinates such as ({}, {}) are no longitude and latitude, which GeoJSON \
             readers take them for without a crs member: --crs names the input's system \
             (EPSG:32632, for instance)",
            p.x, p.y
        ));
    }
}

/// The first point of an input in degrees whose latitude is beyond 90 while every point would
/// be a longitude and latitude the other way round: the columns swapped (`lat,lon` values under a
/// `lon,lat` header; GeoJSON written latitude first), which reads as a mirror image and was
/// silent unless a GeoJSON output's note spoke of projected metres. Swaps of longitudes within
/// 90 cannot be told.
fn swapped_degrees(points: &[condt::Point]) -> Option<condt::Point> {
    let swapped = points
        .iter()
        .all(|p| p.x.abs() <= 90.0 && p.y.abs() <= 180.0);
    swapped
        .then(|| points.iter().copied().find(|p| p.y.abs() > 90.0))
        .flatten()
}

/// A note where `--format` writes one format to a file whose name ends as another's (`-o
/// out.edges --format svg`): the file is written as asked, and whatever opens it by its name
/// would misread it (it was silent: a reviewer's report).
fn note_format_against_name(format: Format, output: Option<&Path>) {
    let named = output
        .and_then(Path::extension)
        .and_then(OsStr::to_str)
        .and_then(Format::of_extension);
    // A list of point numbers is text: `-o outliers.txt --format unused` is what it says.
    let text_list = format == Format::Unused && named == Some(Format::Polylines);
    if let (Some(path), Some(named), false) =
        (output, named.filter(|&named| named != format), text_list)
    {
        note(format_args!(
            "{}: written in the {} format (--format {}), not the {} format its name's ending says",
            path.display(),
            format.name(),
            format.name(),
            named.name()
        ));
    }
}

/// The size of INPUT when it is a regular file (`None`: standard input, a pipe, a device).
fn input_size(input: Option<&Path>) -> Option<u64> {
    let meta = std::fs::metadata(input?).ok()?;
    meta.is_file().then_some(meta.len())
}

/// A note when rayon's threads cannot be started (a limit on processes or memory,
/// `RAYON_NUM_THREADS` too large): the library then runs on this thread, with the same results.
fn threads_note(quiet: bool) {
    if !quiet && !condt::parallel_available() {
        note(format_args!(
            "cannot start worker threads; running on one thread (the results are the same)"
        ));
    }
}

/// A NumPy array is bytes, not text: it is not written where standard output is a terminal (a
/// newcomer's review: `--format npy` without `-o` filled the terminal with them).
fn refuse_binary_to_a_terminal(binary: bool, destination: &Destination) -> Result<(), CliError> {
    if binary && destination.is_terminal() {
        return Err(usage(
            "a .npy array is binary and standard output is a terminal: name a file with -o, \
             or redirect the output",
        ));
    }
    Ok(())
}

/// What both commands do before reading: the note on threads, the clock, the output checked
/// against the input and made ready, and the progress bar through the reading.
fn start_command(
    input: Option<&Path>,
    output: Option<&Path>,
    quiet: bool,
    timings: bool,
) -> Result<(Timings, Destination, Progress), CliError> {
    threads_note(quiet);
    let timings = Timings::new(timings);
    refuse_same_file(input, output)?;
    let destination = Destination::prepare(output, quiet)?;
    let mut progress = Progress::new(quiet);
    if progress.is_shown() {
        progress.reading(&shown_input(input), input_size(input));
    }
    Ok((timings, destination, progress))
}

fn reconstruct_command(args: ReconstructArgs) -> Result<(), CliError> {
    let (mut timings, destination, mut progress) = start_command(
        args.input.as_deref(),
        args.output.as_deref(),
        args.quiet,
        args.timings,
    )?;
    refuse_binary_to_a_terminal(args.format == Format::Npy, &destination)?;
    let (
        PointFile {
            points,
            crs,
            crs_dropped_at,
            null_geometries,
            empty_geometries,
            degrees,
            ..
        },
        snapped,
    ) = read_input(
        args.input.as_deref(),
        args.params.parallel,
        &args.read,
        &args.snap,
        &mut progress,
        &mut timings,
    )?;
    // RFC 7946's default, the one way a file in degrees says nothing of them: a drawing's
    // coordinates in GeoJSON without a crs got the notes below with no word on how to say so.
    let geojson_without_crs = crs.is_none()
        && matches!(
            args.read
                .format
                .or_else(|| args.input.as_deref().and_then(InputFormat::of_path)),
            Some(InputFormat::GeoJson | InputFormat::GeoJsonLines)
        );
    // The input's crs member goes on as `--crs` would take it (a string member is a name, as in
    // Python's `to_geojson`); a member that is no crs (`[1, 2]`, `4326`) is noted and left out.
    let (crs, crs_not_carried) = match crs {
        Some(raw) if args.crs.is_none() && args.format == Format::GeoJson => {
            match condt_io::crs_member(&raw) {
                Ok(member) => (Some(member), None),
                Err(why) => (None, Some(why)),
            }
        }
        _ => (None, None),
    };
    let count = points.len();
    // Before the points are handed over: one pass, and only for an input in degrees.
    let swapped = if degrees {
        swapped_degrees(&points)
    } else {
        None
    };
    let degrees = degrees.then(|| condt_io::Degrees::of(&points)).flatten();
    // The SVG drawing of the result, GeoJSON and CSV are written on the input coordinates, which
    // the result does not keep (`Reconstruction::stage_point`), so for them the points stay (16
    // bytes per point through the stages). Every other output reads the result alone: the
    // points are handed over, freed once triangulated, and the stages' peak does not hold them.
    let keeps_input = match args.format {
        Format::Svg => !args.stages,
        Format::GeoJson | Format::Csv => true,
        _ => false,
    };
    let failed = |err: Error| reconstruction_error(err, args.input.as_deref(), &args.read, count);
    let inserted = AtomicUsize::new(0);
    let (pipeline, input) = if keeps_input {
        progress.computing("triangulating");
        (Pipeline::new(&points, &args.params), points)
    } else {
        let pipeline = progress.triangulating(count, &inserted, || {
            Pipeline::new_owned_observed(points, &args.params, &inserted)
        });
        (pipeline, Vec::new())
    };
    // Step by step, so that the bar can name each stage and smoothing pass: the same result
    // as `reconstruct` (`Pipeline::finish` runs this loop).
    let mut pipeline = pipeline.map_err(failed)?;
    let mut passes = 0;
    while let Some(next) = pipeline.upcoming() {
        match next {
            Upcoming::Stage(stage) if passes == 0 => progress.stage(stage.name()),
            Upcoming::Stage(stage) => progress.stage(&format!("{} (pass {passes})", stage.name())),
            _ => {
                passes += 1;
                progress.stage(&format!(
                    "smoothing pass {passes}: moving points, triangulating"
                ));
            }
        }
        pipeline.step().map_err(failed)?;
    }
    let result = pipeline.finish().map_err(failed)?;
    let call = timings.quiet_lap();
    progress.writing(
        &shown_output(args.output.as_deref()),
        destination.is_terminal(),
    );
    progress.suspend(|| timings.reconstruction(&result, call));
    destination.write(|out| {
        progress.count_written(out, |out| match args.format {
            Format::Edges => write_edges(out, &result),
            Format::Npy => write_npy_edges(out, &result),
            Format::Polylines => write_polylines(out, &result),
            Format::Svg if args.stages => write_svg_stages(out, &result),
            Format::Svg => write_svg(out, &result, &input),
            Format::GeoJson => {
                write_geojson_with_crs(out, &result, &input, args.crs.as_deref().or(crs.as_deref()))
            }
            Format::Html => write_html(out, &result, &shown_input(args.input.as_deref())),
            Format::Csv => write_curves_csv(out, &result, &input),
            Format::Unused => write_unused(out, &result),
        })
    })?;
    progress.finish();
    timings.lap("write");
    if !args.quiet {
        note_skipped_geometries(
            &shown_input(args.input.as_deref()),
            null_geometries,
            empty_geometries,
        );
        note_dropped_crs(&shown_input(args.input.as_deref()), crs_dropped_at);
        if let Some(why) = crs_not_carried {
            note(format_args!(
                "{}: its crs member {why}; the output carries none",
                shown_input(args.input.as_deref())
            ));
        }
        if args.format == Format::GeoJson && args.crs.is_none() && crs.is_none() {
            note_projected_without_crs(&shown_output(args.output.as_deref()), &input);
        }
        note_snapped(snapped);
        note_duplicates(count, result.triangulation().num_vertices());
        note_twins(&result);
        let degree_notes = degrees
            .map(|degrees| degrees.notes("README.md, *Longitude and latitude*"))
            .unwrap_or_default();
        let input_name = shown_input(args.input.as_deref());
        for said in &degree_notes {
            note(format_args!("{input_name}: {said}"));
        }
        let noted = !degree_notes.is_empty();
        if let Some(p) = swapped {
            note(format_args!(
                "{}: its coordinates are taken for longitudes and latitudes (by its header's \
                 names, or as GeoJSON's are, longitude first), but points such as ({}, {}) have \
                 a latitude beyond 90, and every point would fit the other way round: are they \
                 written latitude first (swapped columns)? The result is read as given",
                shown_input(args.input.as_deref()),
                p.x,
                p.y
            ));
        }
        if geojson_without_crs && (noted || swapped.is_some()) {
            note(format_args!(
                "{}: GeoJSON without a crs member is in longitude and latitude (RFC 7946); \
                 where its coordinates are a drawing's or another plane's, `\"crs\": null` \
                 in the file says so, and the notes above go",
                shown_input(args.input.as_deref())
            ));
        }
        note_format_against_name(args.format, args.output.as_deref());
        // Every panel draws every point: past 200,000 dots a drawing takes seconds to open
        // (Chromium, to the first screenshot: 80,000 dots, 6 MB, 2.5 s; 240,000, 18 MB, 6.8 s;
        // 800,000, 61 MB, 30 s; ellipses of 500 points with `--stages`, 2026-12-07, on a loaded
        // machine; a million was the bound before: a teacher's review). (`len`, not `count`,
        // which would rebuild every stage's graph: 18 MB more peak on 1M uniform points.)
        if args.format == Format::Svg {
            let panels = if args.stages {
                1 + result.stages().len()
            } else {
                1
            };
            if count.saturating_mul(panels) > 200_000 {
                let drawn = Counted(count, "point");
                if args.stages {
                    note(format_args!(
                        "the drawing has {panels} panels of {drawn} each, slow to open: the HTML \
                         viewer (-o out.html) shows the same stages as layers of one picture"
                    ));
                } else {
                    note(format_args!("the drawing has {drawn}, slow to open"));
                }
            }
        }
        let curves = result.curves();
        let closed = curves.iter().filter(|c| c.is_closed()).count();
        note(format_args!(
            "{}, {} ({closed} closed, {} open), {} unused",
            Counted(count, "point"),
            Counted(curves.len(), "curve"),
            curves.len() - closed,
            result.unused().len()
        ));
        note_pieces(&result);
        // The twin pairs' search is a walk of its own (85 ms on 1M uniform points): without
        // this step the lines did not add up to `total` (a diff review).
        timings.lap("notes");
    }
    timings.total();
    Ok(())
}

fn shown_output(output: Option<&Path>) -> String {
    output.map_or("<stdout>".into(), |p| p.display().to_string())
}

fn triangulate_command(args: TriangulateArgs) -> Result<(), CliError> {
    let (mut timings, destination, mut progress) = start_command(
        args.input.as_deref(),
        args.output.as_deref(),
        args.quiet,
        args.timings,
    )?;
    let (
        PointFile {
            points,
            crs_dropped_at,
            null_geometries,
            empty_geometries,
            ..
        },
        snapped,
    ) = read_input(
        args.input.as_deref(),
        true,
        &args.read,
        &args.snap,
        &mut progress,
        &mut timings,
    )?;
    progress.computing("triangulating");
    let count = points.len();
    // The output reads only the triangulation: the points are handed over (16 bytes per point
    // of the peak).
    let tri = triangulate_owned(points)
        .map_err(|err| CliError::Input(format!("{}: {err}", shown_input(args.input.as_deref()))))?;
    progress.writing(
        &shown_output(args.output.as_deref()),
        destination.is_terminal(),
    );
    progress.suspend(|| timings.lap("triangulation"));
    destination.write(|out| {
        progress.count_written(out, |out| match (args.edges, args.npy) {
            (true, false) => write_triangulation_edges(out, &tri),
            (false, false) => write_triangles(out, &tri),
            (true, true) => write_npy_triangulation_edges(out, &tri),
            (false, true) => write_npy_triangles(out, &tri),
        })
    })?;
    progress.finish();
    timings.lap("write");
    if !args.quiet {
        note_skipped_geometries(
            &shown_input(args.input.as_deref()),
            null_geometries,
            empty_geometries,
        );
        note_dropped_crs(&shown_input(args.input.as_deref()), crs_dropped_at);
        note_snapped(snapped);
        note_duplicates(count, tri.num_vertices());
        note_no_triangles(&tri, args.edges);
        timings.lap("notes");
    }
    timings.total();
    Ok(())
}

/// An output without triangles (or, with `--edges`, without edges) is explained: where the
/// chain of edges is, or that there is none.
fn note_no_triangles(tri: &condt::Triangulation, edges: bool) {
    if tri.triangles().next().is_some() {
        return;
    }
    let distinct = tri.num_vertices();
    let chain = tri.edges().count();
    if edges {
        // An empty edge list is explained too; a chain of edges needs no word.
        if chain == 0 {
            note(format_args!(
                "no edges: {}",
                Counted(distinct, "distinct point")
            ));
        }
    } else if chain == 0 {
        note(format_args!(
            "no triangles and no edges: {}",
            Counted(distinct, "distinct point")
        ));
    } else {
        note(format_args!(
            "no triangles: the {distinct} distinct points lie on one line; \
             their chain of {} is written with --edges",
            Counted(chain, "edge")
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strings(args: &[&str]) -> Vec<OsString> {
        args.iter().map(OsString::from).collect()
    }

    #[test]
    fn options_are_parsed_in_any_order() {
        let a = parse_triangulate(&strings(&["--edges", "in.txt", "-o", "out.txt"])).unwrap();
        assert_eq!(
            a,
            TriangulateArgs {
                input: Some("in.txt".into()),
                output: Some("out.txt".into()),
                edges: true,
                npy: false,
                read: ReadOptions::new(),
                snap: None,
                timings: false,
                quiet: false,
            }
        );
    }

    #[test]
    fn triangulate_output_by_extension() {
        for (output, edges, npy) in [
            ("out.edges", true, false),
            ("OUT.Edges", true, false),
            ("out.npy", false, true),
            ("out.txt", false, false),
            ("/dev/null", false, false),
            ("-", false, false),
        ] {
            let a = parse_triangulate(&strings(&["in.txt", "-o", output])).unwrap();
            assert_eq!((a.edges, a.npy), (edges, npy), "{output}");
        }
        let a = parse_triangulate(&strings(&["in.txt", "-o", "out.npy", "--edges"])).unwrap();
        assert_eq!((a.edges, a.npy), (true, true));
    }

    /// `-o` twice with one name is taken once, as every option is; with two names it is refused
    /// (found by a fuzzer: `-o x -o x` was refused, against the help).
    #[test]
    fn an_output_given_twice_alike_is_taken_once() {
        let a = parse_reconstruct(&strings(&["in.txt", "-o", "a.txt", "--output=a.txt"])).unwrap();
        assert_eq!(a.output.as_deref(), Some(Path::new("a.txt")));
        let a = parse_triangulate(&strings(&["in.txt", "-oa.txt", "-o", "a.txt"])).unwrap();
        assert_eq!(a.output.as_deref(), Some(Path::new("a.txt")));
        match parse_reconstruct(&strings(&["in.txt", "-o", "a.txt", "-o", "b.txt"])) {
            Err(CliError::Usage(message)) => {
                assert!(message.contains("a.txt and b.txt"), "{message}")
            }
            other => panic!("{other:?}"),
        }
    }

    /// An option that asks for a step the others leave no way to run is refused, naming it
    /// (found by a fuzzer: each was accepted and did nothing); the same options alone run.
    #[test]
    fn a_step_the_other_options_turn_off_is_refused() {
        for (args, named) in [
            (
                &["--confirm-given-back", "--no-local-outliers"][..],
                "--confirm-given-back",
            ),
            (&["--paper", "--confirm-given-back"], "--confirm-given-back"),
            (&["--repair-again", "--no-manifold-fix"], "--repair-again"),
            (&["--repair-again", "--no-outlier-filter"], "--repair-again"),
            (&["--repair-again", "--outliers-first"], "--repair-again"),
            (&["--iqr-floor", "--no-outlier-filter"], "--iqr-floor"),
            (
                &["--outliers-first", "--no-manifold-fix"],
                "--outliers-first",
            ),
        ] {
            let mut line = vec!["in.txt"];
            line.extend_from_slice(args);
            match parse_reconstruct(&strings(&line)) {
                Err(CliError::Usage(message)) => assert!(message.starts_with(named), "{message}"),
                other => panic!("{args:?}: {other:?}"),
            }
        }
        for args in [
            &["--paper", "--repair-again"][..],
            &["--paper", "--local-outliers", "--confirm-given-back"],
            &["--outliers-first"],
            &["--no-iqr-floor", "--no-outlier-filter"],
            &["--no-confirm-given-back", "--no-local-outliers"],
        ] {
            let mut line = vec!["in.txt"];
            line.extend_from_slice(args);
            assert!(parse_reconstruct(&strings(&line)).is_ok(), "{args:?}");
        }
    }

    #[test]
    fn reconstruct_options_and_format_by_extension() {
        // A name without an extension gets text, as standard output does; an unknown one is
        // refused.
        for output in ["-o/dev/null", "--output=/dev/stdout", "-oresult"] {
            let a = parse_reconstruct(&strings(&["in.txt", output])).unwrap();
            assert_eq!(a.format, Format::Polylines, "{output}");
        }
        assert!(parse_reconstruct(&strings(&["in.txt", "-o", "out.dat"])).is_err());
        let a = parse_reconstruct(&strings(&[
            "in.txt",
            "-o",
            "out.svg",
            "--stages",
            "--adaptive",
            "--iqr",
            "2",
            "--close-gaps",
        ]))
        .unwrap();
        assert_eq!(a.format, Format::Svg);
        assert!(a.stages);
        assert_eq!(a.params.uniformity, Uniformity::Adaptive);
        assert_eq!(a.params.outlier_factor, Some(2.0));
        assert!(a.params.close_gaps);
        let b = parse_reconstruct(&strings(&[
            "in.txt",
            "--no-manifold-fix",
            "--no-outlier-filter",
        ]))
        .unwrap();
        assert_eq!(
            (b.format, b.params.repair, b.params.outlier_factor),
            (Format::Polylines, Repair::Off, None)
        );
        assert!(
            b.params.local_outliers && b.params.close_gaps,
            "the defaults"
        );
        let c = parse_reconstruct(&strings(&["--local-outliers", "in.txt", "--no-close-gaps"]))
            .unwrap();
        assert!(c.params.local_outliers && !c.params.close_gaps);
        assert!(c.params.confirm_given_back, "the default");
        let e = parse_reconstruct(&strings(&["in.txt", "--no-confirm-given-back"])).unwrap();
        assert!(e.params.local_outliers && !e.params.confirm_given_back);
        assert!(e.params.smooth, "on by default");
        let no_smooth = parse_reconstruct(&strings(&["--no-smooth", "in.txt"])).unwrap();
        assert!(!no_smooth.params.smooth && no_smooth.params.local_outliers);
        let smooth = parse_reconstruct(&strings(&["--smooth", "in.txt", "--paper"])).unwrap();
        assert!(smooth.params.smooth && smooth.params.repair == Repair::Paper);
        let paper = parse_reconstruct(&strings(&["in.txt", "--paper"])).unwrap();
        assert_eq!(paper.params, condt::Params::paper());
        let paper_plus =
            parse_reconstruct(&strings(&["--close-gaps", "--paper", "in.txt"])).unwrap();
        assert!(paper_plus.params.close_gaps && !paper_plus.params.local_outliers);
        let d = parse_reconstruct(&strings(&["in.txt", "--repair", "needs"])).unwrap();
        assert_eq!(d.params.repair, Repair::Needs);
        for bad in [
            &["in.txt", "--u", "2", "--adaptive"][..],
            &["in.txt", "-o", "out.png"],
            &["in.txt", "--u", "nan"],
            &["in.txt", "--u", "-1"],
            &["in.txt", "--iqr", "inf"],
            &["in.txt", "--repair", "x"],
            &["in.txt", "--smooth", "--no-smooth"],
        ] {
            assert_eq!(
                parse_reconstruct(&strings(bad)).unwrap_err().exit_code(),
                2,
                "{bad:?}"
            );
        }
    }

    #[test]
    fn usage_errors_exit_with_two() {
        for bad in [
            &["in.txt", "-o"][..],
            &["in.txt", "-o", "out.svg"],
            &["in.txt", "-o", "out.SVG", "--edges"],
            &["--frobnicate", "in.txt"],
            &[],
            &["a", "b"],
        ] {
            let err = parse_triangulate(&strings(bad)).unwrap_err();
            assert_eq!(err.exit_code(), 2, "{bad:?}");
        }
    }
}
