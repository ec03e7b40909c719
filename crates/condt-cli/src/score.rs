//! `condt score`: how an edge list compares with a ground truth.
//!
//! Owns: the command's arguments, reading the two edge files with their line numbers, and
//! printing [`condt_eval::score::Score`] as text or JSON. It may not compute a metric: the library's
//! `score` does, so benches, tests and this command agree by construction.
//!
//! An edge file holds one edge `i j` per line (0-based point numbers); `#` starts a comment (a
//! line of its own or after an edge), and blank lines are skipped; its lines are split as point
//! files' are ([`condt_io::text_lines`]: LF, CRLF or CR-only line ends, a byte-order mark at the
//! start skipped). A name ending in `.npy` is a
//! NumPy array of shape `(m, 2)` of any integer type, as `condt reconstruct -o out.npy` writes it
//! ([`condt_io::parse_npy_edges`]), its problems told by row. `-` reads text from standard input,
//! for one of the three files.
//!
//! A malformed OUTPUT (a line that is not two integers, a point that does not exist, negative
//! numbers included, a self-loop, a repeated edge) is scored as a failure, as the evaluation
//! suite's scorer does, and the first problem is reported with its line; a malformed TRUTH is
//! an error. A file that is not an edge
//! list at all is an error whichever it is: bytes that are not text (not UTF-8, a NUL byte, a
//! NumPy array under another name), an `.npy` array of another dtype or shape, or text of which
//! no line is an edge though some line holds something (an empty file, or one of comments and
//! blank lines only, is an empty edge list). There this command parts from the suite's scorer,
//! which reads any file (undecodable bytes replaced) and scores such an output 0: a user handing
//! it a wrong file is told so. Messages quote a line escaped and cut short, never the file's raw
//! bytes.

use crate::cli::{
    columns_option, input_format_option, read_options, shown_operand, usage, CliError, Setting,
};
use crate::options::{self, Opt};
use condt_eval::score::{score, EdgeProblem, Score};
use condt_io::{
    parse_npy_index_rows, read_points_with, text_lines, utf8_text, IoError, IoErrorKind, PointFile,
    NPY_MAGIC,
};
use std::ffi::OsString;
use std::fmt::Write as _;
use std::io::Read;
use std::path::{Path, PathBuf};

const ABOUT: &str = "\
condt score: compare an edge list with a ground truth

Usage:
  condt score POINTS OUTPUT TRUTH [--json] [--quiet] [--input-format F] [--columns X,Y]

Example:
  condt reconstruct case.pts -o case.edges && condt score case.pts case.edges case.gt

POINTS is read as `condt reconstruct` reads its INPUT, with the same --input-format and
--columns, so that it numbers the points as the reconstruction did.
Edge files hold one edge `i j` per line, in point numbers of POINTS counted from 0 (a truth
written from 1, as R and MATLAB count, needs 1 taken off; `#` starts a comment, on a
line of its own or after an edge; blank lines are skipped); a name ending in .npy (any case)
is a NumPy array of shape (m, 2) of integers
(uint32 or int64 as `condt reconstruct -o out.npy` writes it, or any other width), either byte
order. `-` reads standard input
for one of POINTS, OUTPUT and TRUTH (POINTS as INPUT's standard input is read, an edge list as
text). Prints: exact (the edge sets are equal),
precision, recall and F1 on the edge sets, the output edges touching a point the truth gives no
edge (outlier edges), and the largest and the root-mean-square distance of the output to the
truth (each output edge sampled at 0, 1/4, 1/2, 3/4 and 1 of its length), over the diagonal of
the points' bounding box. A malformed OUTPUT (a bad line among edges, a point that does not
exist, such as -1, a self-loop, a repeated edge) scores 0 and its first problem is printed
with its line
(row, for .npy); a malformed TRUTH is an error. A file that is not an edge list (not text, an
array of another dtype or shape, text with lines but none of them an edge) is an error, OUTPUT
or TRUTH; an empty file, or one of comments and blank lines only, is an empty edge list (an
empty OUTPUT scores 0 against any edge of TRUTH). Edges are compared by point number: where
POINTS repeats a point exactly, an edge to one copy is no edge to another, and `condt
reconstruct` gives a duplicate's edges to its first copy. Notes on standard error tell what
POINTS skipped (GeoJSON features without a point, a GeoJSON sequence's later crs) and which
points of TRUTH repeat an earlier one; --quiet leaves them out.
The metrics are those of the evaluation suite's score.py.
";

/// The options of `condt score`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum ScoreId {
    Json,
    Quiet,
    InputFormat,
    Columns,
    Help,
}

pub(crate) const OPTIONS: &[Opt<ScoreId>] = &[
    Opt {
        id: ScoreId::Json,
        short: None,
        long: "json",
        negatable: false,
        value: None,
        help: "one JSON object (the keys of score.py --json)",
    },
    Opt {
        id: ScoreId::Quiet,
        short: Some('q'),
        long: "quiet",
        negatable: false,
        value: None,
        help: "no notes on standard error (errors are still written); the output is
the same",
    },
    Opt {
        id: ScoreId::InputFormat,
        short: None,
        long: "input-format",
        negatable: false,
        value: Some("F"),
        help: "read POINTS as F whatever its name: txt, node, csv, tsv, npy,
geojson or geojsonl (standard input, which has no name, is otherwise
told by its content: .npy, GeoJSON, else txt), as reconstruct's
--input-format",
    },
    Opt {
        id: ScoreId::Columns,
        short: None,
        long: "columns",
        negatable: false,
        value: Some("X,Y"),
        help: "read x and y from these columns of a CSV, TSV or plain text POINTS: header
names or numbers from 1 (POINT_X,POINT_Y, 2,3), as reconstruct's
--columns; standard input is then read as CSV",
    },
    Opt {
        id: ScoreId::Help,
        short: Some('h'),
        long: "help",
        negatable: false,
        value: None,
        help: "show this help",
    },
];

/// `condt score --help`.
pub(crate) fn help() -> String {
    format!("{ABOUT}\nOptions:\n{}", options::help(OPTIONS, 20))
}

/// Runs `condt score` on its arguments (after the command name); returns what to print.
pub(crate) fn command(args: &[OsString]) -> Result<String, CliError> {
    let lexed = options::lex(args, OPTIONS, "score: ")?;
    let (mut json, mut quiet) = (false, false);
    let (mut input_format, mut columns) = (Setting::new(), Setting::new());
    for given in &lexed.given {
        match given.id {
            ScoreId::Json => json = true,
            ScoreId::Quiet => quiet = true,
            ScoreId::InputFormat => {
                input_format_option(&mut input_format, &given.flag, given.value.as_ref())?
            }
            ScoreId::Columns => columns_option(&mut columns, &given.flag, given.value.as_ref())?,
            // Answered before the arguments are read (`cli::run`).
            ScoreId::Help => {}
        }
    }
    let files: Vec<PathBuf> = lexed.operands.into_iter().map(PathBuf::from).collect();
    let [points, output, truth] = <[PathBuf; 3]>::try_from(files).map_err(|files| {
        usage(format!(
            "score needs three files, POINTS OUTPUT TRUTH; {} given",
            files.len()
        ))
    })?;
    // `/dev/stdin`, `/dev/fd/0` or a name of the pipe that standard input is read it too.
    let dashes = [&points, &output, &truth]
        .iter()
        .filter(|p| p.as_os_str() == "-" || crate::output::names_standard_input(p))
        .count();
    if dashes > 1 {
        return Err(usage(format!(
            "score: standard input (-, /dev/stdin) is given {dashes} times; it can be read \
             once: give it for one of POINTS, OUTPUT and TRUTH"
        )));
    }
    let stdin = points.as_os_str() == "-";
    let options = read_options(input_format, columns, (!stdin).then_some(points.as_path()))?;
    let PointFile {
        points: read,
        crs_dropped_at,
        null_geometries,
        empty_geometries,
        ..
    } = read_points_with(&points, &options)?;
    if !quiet {
        let shown = shown_operand(&points);
        crate::cli::note_skipped_geometries(&shown, null_geometries, empty_geometries);
        crate::cli::note_dropped_crs(&shown, crs_dropped_at);
    }
    let points = read;
    let truth = read_edges(&truth)?;
    if let Some((at, why)) = &truth.bad_line {
        let (line, why) = truth.tell(*at, why.clone());
        return Err(content(&truth.name, line, why));
    }
    if !quiet {
        note_later_copies(&truth.name, &points, &truth.edges);
    }
    let output = read_edges(&output)?;
    // A text of which no line is an edge is some other file (a drawing, GeoJSON, curves),
    // not an edge list scored 0.
    let text = matches!(output.places, Places::Lines(_));
    if let (true, true, Some((line, why))) = (text, output.edges.is_empty(), &output.bad_line) {
        // `condt reconstruct`'s default text output: a curve per line.
        let curves = why.starts_with("not an edge `i j`: \"closed ")
            || why.starts_with("not an edge `i j`: \"open ");
        let advice = if curves {
            "; it is a list of curves, as `condt reconstruct` writes .txt: write the edges with \
             -o out.edges"
        } else {
            ""
        };
        return Err(content(
            &output.name,
            Some(*line),
            format!("{why}; no line of the file is an edge `i j`: it is not an edge list{advice}"),
        ));
    }
    let result = score(&points, &output.edges, &truth.edges).map_err(|err| match err {
        condt_eval::score::ScoreError::Truth(problem) => {
            let (line, why) = truth.place(problem.position(), truth.problem_text(problem));
            content(&truth.name, line, why)
        }
        other => CliError::Input(format!("{}: {other}", truth.name)),
    })?;
    // The output's first problem: a line (row) that is not an edge or the library's, whichever
    // comes first in the file.
    let (places, unit) = match &output.places {
        Places::Rows(rows) => (rows, "row"),
        Places::Lines(lines) => (lines, "line"),
    };
    let problem = [
        output.bad_line.clone(),
        result
            .malformed
            .map(|p: EdgeProblem| (places[p.position()], output.problem_text(p))),
    ]
    .into_iter()
    .flatten()
    .min_by_key(|(at, _)| *at)
    .map(|(at, why)| format!("{unit} {at}: {why}"));
    let result = if output.bad_line.is_some() {
        Score {
            exact: false,
            precision: 0.0,
            recall: 0.0,
            f1: 0.0,
            ..result
        }
    } else {
        result
    };
    // The output's valid edges, each once, as `score.py` counts `n_out` (a Python researcher's
    // review: rows were counted, so a repeated edge made `tp + fp` fall short of it).
    let distinct = result.true_positives + result.false_positives;
    let counts = [points.len(), truth.edges.len(), distinct];
    Ok(if json {
        as_json(&result, problem.as_deref(), counts)
    } else {
        as_text(&result, problem.as_deref(), counts)
    })
}

/// Where the edges of a file are: each on its line of a text, or in its row of an array.
enum Places {
    Lines(Vec<usize>),
    Rows(Vec<usize>),
}

/// An edge file as read: its edges, where each is, and the first line that is not an edge.
struct EdgeFile {
    /// The file as messages name it (`<stdin>` for standard input).
    name: String,
    /// Each end that no point can have (negative, or beyond `usize`) is `usize::MAX` here, out
    /// of range as any index no point has; `beyond` keeps it as given.
    edges: Vec<[usize; 2]>,
    places: Places,
    bad_line: Option<(usize, String)>,
    /// `(edge, end, number as given)` for the ends no point can have, in edge order.
    beyond: Vec<(usize, usize, String)>,
}

impl EdgeFile {
    /// An edge whose ends are given as `ends`: those no point can have as `usize::MAX`, kept
    /// as given in `beyond`.
    fn push(&mut self, ends: [Result<usize, String>; 2]) {
        let position = self.edges.len();
        let edge = [0, 1].map(|end| match &ends[end] {
            Ok(index) => *index,
            Err(given) => {
                self.beyond.push((position, end, given.clone()));
                usize::MAX
            }
        });
        self.edges.push(edge);
    }

    /// The library's words for `problem`, its point number as given (cut, [`shortened`]): the
    /// library names the first end out of range, which is one no point number holds where it
    /// reads `usize::MAX` (as `condt.score` in Python names it).
    fn problem_text(&self, problem: EdgeProblem) -> String {
        let EdgeProblem::OutOfRange { position, index } = problem else {
            return problem.to_string();
        };
        let given = self
            .beyond
            .iter()
            .find(|(at, _, _)| *at == position)
            .map(|(_, _, text)| text.as_str());
        match given {
            Some(text) if index == usize::MAX => {
                format!("point {} does not exist", shortened(text))
            }
            _ => problem.to_string(),
        }
    }

    /// A problem of the edge at `position`, placed: its line, or (in an array, which has no
    /// lines) its row at the start of the message.
    fn place(&self, position: usize, why: String) -> (Option<usize>, String) {
        match &self.places {
            Places::Lines(lines) => self.tell(lines[position], why),
            Places::Rows(rows) => self.tell(rows[position], why),
        }
    }

    /// A problem at line (or row) `at`: the line as the error's place, a row in the message.
    fn tell(&self, at: usize, why: String) -> (Option<usize>, String) {
        match &self.places {
            Places::Lines(_) => (Some(at), why),
            Places::Rows(_) => (None, format!("row {at}: {why}")),
        }
    }
}

fn read_edges(path: &Path) -> Result<EdgeFile, CliError> {
    let stdin = path.as_os_str() == "-";
    let name = shown_operand(path);
    let os_error = |error| {
        CliError::Io(IoError {
            file: name.clone(),
            line: None,
            kind: IoErrorKind::Io(error),
        })
    };
    let bytes = if stdin {
        let mut bytes = Vec::new();
        std::io::stdin()
            .lock()
            .read_to_end(&mut bytes)
            .map_err(os_error)?;
        bytes
    } else {
        std::fs::read(path).map_err(os_error)?
    };
    let npy = !stdin
        && path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if npy {
        // Every row is an edge: a number no point can have (negative, or beyond what a point
        // number holds here) is one whose point does not exist, a malformed output's problem
        // (scored 0, told by its row, as a text line `-1 0` is by its line, and as
        // `condt.score` in Python tells it for the same array).
        let mut read = EdgeFile {
            name,
            edges: Vec::new(),
            places: Places::Rows(Vec::new()),
            bad_line: None,
            beyond: Vec::new(),
        };
        let rows = parse_npy_index_rows(&bytes, &read.name)?;
        for pair in &rows {
            read.push(pair.map(|v| usize::try_from(v).map_err(|_| v.to_string())));
        }
        read.places = Places::Rows((0..rows.len()).collect());
        return Ok(read);
    }
    // Text is read as text: an array under another name (or piped in) is told as one, and
    // never quoted as a line.
    if bytes.starts_with(NPY_MAGIC) {
        let why = if stdin {
            "a NumPy .npy array, but standard input is read as text; give the file by its name, \
             ending in .npy"
        } else {
            "a NumPy .npy array, but only a name ending in .npy is read as one: rename it"
        };
        return Err(content(&name, None, why.to_string()));
    }
    let text = utf8_text(bytes, &name)?;
    let mut lines = Vec::new();
    let mut read = EdgeFile {
        name,
        edges: Vec::new(),
        places: Places::Lines(Vec::new()),
        bad_line: None,
        beyond: Vec::new(),
    };
    // The line ends and the byte-order mark of point files, by the same reader.
    for (number, line) in text_lines(&text) {
        if line.contains('\0') {
            return Err(content(
                &read.name,
                Some(number),
                "a NUL byte: binary data, not a text edge list".to_string(),
            ));
        }
        // A comment runs from `#` to the line's end, as in point files.
        let line = line.split('#').next().unwrap_or_default().trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        match fields[..] {
            [a, b] if is_integer(a) && is_integer(b) => {
                read.push([a, b].map(point_number));
                lines.push(number);
            }
            _ => {
                if read.bad_line.is_none() {
                    let shown: String = line.chars().take(40).collect();
                    read.bad_line = Some((number, format!("not an edge `i j`: {shown:?}")));
                }
            }
        }
    }
    read.places = Places::Lines(lines);
    Ok(read)
}

/// Notes how many points of `truth` repeat an earlier point exactly: edges are compared by point
/// number, and `condt reconstruct` gives a duplicate's edges to its first copy, so such a truth
/// edge is never matched by its output (a Python researcher's review: a ring exported with its
/// first point again at its end scored one false positive and one false negative).
fn note_later_copies(name: &str, points: &[condt::Point], truth: &[[usize; 2]]) {
    let named = condt_eval::score::later_copies(points, truth);
    if let Some(words) = condt_eval::score::later_copies_named(&named) {
        // Through `note`, which drops a failed write: `eprintln!` panicked on a standard error
        // that refuses writes, and the score was lost with exit 101.
        crate::cli::note(format_args!(
            "note: {name} names {words}; edges are compared by point number, and condt \
             reconstruct gives a duplicate's edges to its first copy"
        ));
    }
}

/// Whether `field` is an integer as an edge line writes one: digits, a `-` before them allowed
/// (a negative number is an edge to a point that does not exist, not a line that is no edge).
fn is_integer(field: &str) -> bool {
    let digits = field.strip_prefix('-').unwrap_or(field);
    !digits.is_empty() && digits.bytes().all(|c| c.is_ascii_digit())
}

/// An integer field ([`is_integer`]) as a point number, or as given where no point can have it
/// (negative, or beyond `usize`); `-0` is 0.
fn point_number(field: &str) -> Result<usize, String> {
    let digits = field.strip_prefix('-').unwrap_or(field);
    match digits.parse::<usize>() {
        Ok(0) => Ok(0),
        Ok(index) if digits.len() == field.len() => Ok(index),
        _ => Err(field.to_string()),
    }
}

/// A content error of `file`, at `line` when it has lines.
fn content(file: &str, line: Option<usize>, why: String) -> CliError {
    CliError::Io(IoError {
        file: file.to_string(),
        line,
        kind: IoErrorKind::Content(why),
    })
}

/// A number as JSON: non-finite values (a distance to an empty truth) have no JSON spelling and
/// are written as null.
fn json_number(x: Option<f64>) -> String {
    match x {
        Some(x) if x.is_finite() => format!("{x:?}"),
        _ => "null".into(),
    }
}

fn as_json(s: &Score, problem: Option<&str>, [n, n_gt, n_out]: [usize; 3]) -> String {
    let malformed = problem.map_or("null".to_string(), |p| {
        format!("\"{}\"", p.replace('\\', "\\\\").replace('"', "\\\""))
    });
    format!(
        "{{\"exact\": {}, \"f1\": {}, \"fn\": {}, \"fp\": {}, \"malformed\": {malformed}, \
         \"max_dist\": {}, \"n_gt\": {n_gt}, \"n_out\": {n_out}, \"n_points\": {n}, \
         \"outlier_edges\": {}, \"precision\": {}, \"recall\": {}, \"rms_dist\": {}, \"tp\": {}}}\n",
        s.exact,
        json_number(Some(s.f1)),
        s.false_negatives,
        s.false_positives,
        json_number(s.max_distance),
        s.outlier_edges,
        json_number(Some(s.precision)),
        json_number(Some(s.recall)),
        json_number(s.rms_distance),
        s.true_positives,
    )
}

fn as_text(s: &Score, problem: Option<&str>, [n, n_gt, n_out]: [usize; 3]) -> String {
    let mut text = String::new();
    // A distance is a fraction of the diagonal; with no output edge there is none, and with no
    // truth edge to measure from none either (the JSON's `null` for both).
    let distance = |d: Option<f64>| match d {
        None => "none (no output edges)".into(),
        Some(d) if !d.is_finite() => "none (no truth edges)".into(),
        Some(d) => format!("{d:.6e} of the box diagonal"),
    };
    let _ = writeln!(text, "exact          {}", s.exact);
    let _ = writeln!(text, "precision      {:.6}", s.precision);
    let _ = writeln!(text, "recall         {:.6}", s.recall);
    let _ = writeln!(text, "f1             {:.6}", s.f1);
    let _ = writeln!(
        text,
        "edges          {n_out} output, {n_gt} truth, {} in both, {} extra, {} missed",
        s.true_positives, s.false_positives, s.false_negatives
    );
    let _ = writeln!(text, "outlier edges  {}", s.outlier_edges);
    let _ = writeln!(text, "max distance   {}", distance(s.max_distance));
    let _ = writeln!(text, "rms distance   {}", distance(s.rms_distance));
    let _ = writeln!(text, "points         {n}");
    if let Some(problem) = problem {
        let _ = writeln!(text, "malformed      {problem}");
    }
    text
}

/// A point number as given, cut after 40 characters: a number megabytes long must not fill the
/// terminal (or the `malformed` field of the JSON), as the point readers cut a token.
fn shortened(text: &str) -> String {
    match text.char_indices().nth(40) {
        None => text.to_string(),
        Some((cut, _)) => format!("{}… ({} characters)", &text[..cut], text.chars().count()),
    }
}
