//! `condt score`: how an edge list compares with a ground truth.
//!
//! Owns: the command's arguments, reading the two edge files with their line numbers, and
//! printing [`condt_eval::score::Score`] as text or JSON. It may not compute a metric: the library's
//! `score` does, so benches, tests and this command agree by construction.
//!
//! An edge file holds one edge `i j` per line (0-based point numbers); `#` lines and blank lines
//! are skipped; its lines are split as point files' are ([`condt_io::text_lines`]: LF, CRLF or
//! CR-only line ends, a byte-order mark at the start skipped). A malformed OUTPUT (a line that is not two numbers, a point that does not exist, a
//! self-loop, a repeated edge) is scored as a failure, as the evaluation suite's scorer does, and
//! the first problem is reported with its line; a malformed TRUTH is an error.

use crate::cli::{usage, CliError};
use crate::options::{self, Opt};
use condt_eval::score::{score, EdgeProblem, Score};
use condt_io::{read_points, text_lines, IoError, IoErrorKind};
use std::ffi::OsString;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const ABOUT: &str = "\
condt score: compare an edge list with a ground truth

Usage:
  condt score POINTS OUTPUT.edges TRUTH.edges [--json]

Example:
  condt reconstruct case.pts -o case.edges && condt score case.pts case.edges case.gt

Edge files hold one edge `i j` per line, in point numbers of POINTS (`#` lines and blank lines
are skipped). Prints: exact (the edge sets are equal), precision, recall and F1 on the edge sets,
the output edges touching a point the truth gives no edge (outlier edges), and the largest and
the root-mean-square distance of the output to the truth (each output edge sampled at 0, 1/4,
1/2, 3/4 and 1 of its length), over the diagonal of the points' bounding box. A malformed
OUTPUT scores 0 and its first problem is printed with its line; a malformed TRUTH is an error.
The metrics are those of the evaluation suite's score.py.
";

/// The options of `condt score`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum ScoreId {
    Json,
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
    // `--help` is answered before the arguments are read (`cli::run`).
    let json = lexed.given.iter().any(|g| g.id == ScoreId::Json);
    let files: Vec<PathBuf> = lexed.operands.into_iter().map(PathBuf::from).collect();
    let [points, output, truth] = <[PathBuf; 3]>::try_from(files).map_err(|files| {
        usage(format!(
            "score needs three files, POINTS OUTPUT.edges TRUTH.edges; {} given",
            files.len()
        ))
    })?;
    let points = read_points(&points)?;
    let truth_file = read_edges(&truth)?;
    if let Some((line, why)) = truth_file.bad_line {
        return Err(content(&truth, line, why));
    }
    let output_file = read_edges(&output)?;
    let result =
        score(&points, &output_file.edges, &truth_file.edges).map_err(|err| match err {
            condt_eval::score::ScoreError::Truth(problem) => content(
                &truth,
                truth_file.lines[problem.position()],
                problem.to_string(),
            ),
            other => CliError::Input(format!("{}: {other}", truth.display())),
        })?;
    // The output's first problem: a line that is not an edge, or the library's, whichever comes
    // first in the file.
    let problem = [
        output_file.bad_line.clone(),
        result
            .malformed
            .map(|p: EdgeProblem| (output_file.lines[p.position()], p.to_string())),
    ]
    .into_iter()
    .flatten()
    .min_by_key(|(line, _)| *line)
    .map(|(line, why)| format!("line {line}: {why}"));
    let result = if output_file.bad_line.is_some() {
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
    let counts = [
        points.len(),
        truth_file.edges.len(),
        output_file.edges.len(),
    ];
    Ok(if json {
        as_json(&result, problem.as_deref(), counts)
    } else {
        as_text(&result, problem.as_deref(), counts)
    })
}

/// An edge file as read: its edges, the line of each, and the first line that is not an edge.
struct EdgeFile {
    edges: Vec<[usize; 2]>,
    lines: Vec<usize>,
    bad_line: Option<(usize, String)>,
}

fn read_edges(path: &Path) -> Result<EdgeFile, CliError> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|error| {
        CliError::Io(IoError {
            file: file.clone(),
            line: None,
            kind: IoErrorKind::Io(error),
        })
    })?;
    let text = String::from_utf8_lossy(&bytes);
    let mut read = EdgeFile {
        edges: Vec::new(),
        lines: Vec::new(),
        bad_line: None,
    };
    // The line ends and the byte-order mark of point files, by the same reader.
    for (number, line) in text_lines(&text) {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let parsed: Option<Vec<usize>> = fields.iter().map(|f| f.parse().ok()).collect();
        match parsed.as_deref() {
            Some(&[a, b]) if fields.iter().all(|f| f.bytes().all(|c| c.is_ascii_digit())) => {
                read.edges.push([a, b]);
                read.lines.push(number);
            }
            _ => {
                if read.bad_line.is_none() {
                    let shown: String = line.chars().take(40).collect();
                    read.bad_line = Some((number, format!("not an edge `i j`: {shown:?}")));
                }
            }
        }
    }
    Ok(read)
}

fn content(path: &Path, line: usize, why: String) -> CliError {
    CliError::Io(IoError {
        file: path.display().to_string(),
        line: Some(line),
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
    let distance =
        |d: Option<f64>| d.map_or("none (no output edges)".into(), |d| format!("{d:.6e}"));
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
    let _ = writeln!(
        text,
        "max distance   {} of the box diagonal",
        distance(s.max_distance)
    );
    let _ = writeln!(
        text,
        "rms distance   {} of the box diagonal",
        distance(s.rms_distance)
    );
    let _ = writeln!(text, "points         {n}");
    if let Some(problem) = problem {
        let _ = writeln!(text, "malformed      {problem}");
    }
    text
}
