//! `condt score`: the metrics of an edge list against a ground truth, from the command line.

use condt::Point;
use condt_eval::sample::{sample, Sampling, Shape};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn condt(args: &[&Path]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_condt"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn scratch_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("condt-score-")
        .tempdir()
        .unwrap()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn points_text(points: &[Point]) -> String {
    points
        .iter()
        .map(|p| format!("{:?} {:?}\n", p.x, p.y))
        .collect()
}

fn edges_text(edges: &[[usize; 2]]) -> String {
    edges.iter().map(|[a, b]| format!("{a} {b}\n")).collect()
}

/// The value of `key` in the command's JSON object (a flat object of numbers, booleans, null
/// and one string).
/// `condt score POINTS OUTPUT TRUTH --json`, which must succeed: its standard output.
fn score_json(points: &Path, output: &Path, truth: &Path) -> String {
    let scored = condt(&[
        Path::new("score"),
        points,
        output,
        truth,
        Path::new("--json"),
    ]);
    assert!(
        scored.status.success(),
        "{}",
        String::from_utf8_lossy(&scored.stderr)
    );
    String::from_utf8(scored.stdout).unwrap()
}

fn json_value(json: &str, key: &str) -> String {
    let start = json.find(&format!("\"{key}\": ")).expect(key) + key.len() + 4;
    let rest = &json[start..];
    let end = if let Some(quoted) = rest.strip_prefix('"') {
        // The closing quote is the first one not escaped by a backslash.
        let mut escaped = false;
        let (close, _) = quoted
            .char_indices()
            .find(|&(_, c)| {
                let closes = c == '"' && !escaped;
                escaped = c == '\\' && !escaped;
                closes
            })
            .unwrap();
        close + 2
    } else {
        rest.find([',', '}']).unwrap()
    };
    rest[..end].to_string()
}

#[test]
fn a_reconstruction_of_a_sampled_circle_scores_exact_against_its_truth() {
    let dir = scratch_dir();
    let circle = sample(
        &[Shape::circle(Point::new(3.0, -1.0), 2.0)],
        &Sampling::new(0.3),
    )
    .unwrap();
    let points = write(dir.path(), "circle.pts", &points_text(&circle.points));
    let truth = write(dir.path(), "circle.gt", &edges_text(&circle.edges));
    let output = dir.path().join("circle.edges");
    let run = Command::new(env!("CARGO_BIN_EXE_condt"))
        .args([Path::new("reconstruct"), &points, Path::new("-o"), &output])
        .output()
        .unwrap();
    assert!(run.status.success());
    let json = score_json(&points, &output, &truth);
    assert_eq!(json_value(&json, "exact"), "true");
    assert_eq!(json_value(&json, "f1"), "1.0");
    assert_eq!(json_value(&json, "max_dist"), "0.0");
    assert_eq!(json_value(&json, "n_gt"), circle.edges.len().to_string());
    assert_eq!(json_value(&json, "malformed"), "null");
}

#[test]
fn a_wrong_edge_is_counted_and_measured() {
    // A unit square; the output swaps one side for a diagonal, whose midpoint is half a side
    // from the nearest side, over a box diagonal of √2.
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n2 3\n3 0\n");
    let output = write(dir.path(), "o.edges", "# a comment\n\n1 0\n2 1\n3 2\n0 2\n");
    let json = score_json(&points, &output, &truth);
    assert_eq!(json_value(&json, "exact"), "false");
    assert_eq!(json_value(&json, "f1"), "0.75");
    assert_eq!(
        (json_value(&json, "tp"), json_value(&json, "fp")),
        ("3".into(), "1".into())
    );
    let max: f64 = json_value(&json, "max_dist").parse().unwrap();
    assert!((max - 0.5 / 2f64.sqrt()).abs() < 1e-12, "{max}");
    let text =
        String::from_utf8(condt(&[Path::new("score"), &points, &output, &truth]).stdout).unwrap();
    assert!(text.contains("f1             0.750000"), "{text}");
}

#[test]
fn a_malformed_output_scores_nothing_and_names_its_line() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n2 0\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n");
    for (output, problem) in [
        ("0 1\n1 x\n1 2\n", "line 2: not an edge `i j`: \\\"1 x\\\""),
        ("0 1\n1 2\n2 1\n", "line 3: edge 1 2 repeated"),
        ("0 1\n1 1\n", "line 2: self-loop at point 1"),
        ("0 1\n+1 2\n", "line 2: not an edge `i j`: \\\"+1 2\\\""),
        ("0 1\n1 7\n", "line 2: point 7 does not exist"),
    ] {
        let output = write(dir.path(), "o.edges", output);
        let json = score_json(&points, &output, &truth);
        assert_eq!(json_value(&json, "malformed"), format!("\"{problem}\""));
        assert_eq!(json_value(&json, "f1"), "0.0");
        assert_eq!(json_value(&json, "exact"), "false");
    }
}

#[test]
fn a_bad_truth_or_command_line_is_an_error() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n2 0\n");
    let output = write(dir.path(), "o.edges", "0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n\n1 9\n");
    let refused = condt(&[Path::new("score"), &points, &output, &truth]);
    assert_eq!(refused.status.code(), Some(1));
    let message = String::from_utf8(refused.stderr).unwrap();
    assert!(
        message.contains("t.edges:3: point 9 does not exist"),
        "{message}"
    );
    let missing = condt(&[Path::new("score"), &points, &output]);
    assert_eq!(missing.status.code(), Some(2));
    let unknown = condt(&[
        Path::new("score"),
        &points,
        &output,
        &truth,
        Path::new("--xml"),
    ]);
    assert_eq!(unknown.status.code(), Some(2));
    let absent = condt(&[
        Path::new("score"),
        &points,
        &dir.path().join("none"),
        &truth,
    ]);
    assert_eq!(absent.status.code(), Some(1));
}

/// Edge files are read with the line ends and the byte-order mark point files accept: CR-only
/// and CRLF line ends, a mark at the start; their lines numbered alike in messages.
#[test]
fn edge_files_accept_what_point_files_accept() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\r1 0\r1 1\r0 1\r");
    let lf = "# square\n0 1\n1 2\n2 3\n3 0\n";
    let truth = write(dir.path(), "truth.edges", lf);
    let expected = score_json(&points, &truth, &truth);
    for (name, text) in [
        ("cr.edges", lf.replace('\n', "\r")),
        ("crlf.edges", lf.replace('\n', "\r\n")),
        ("bom.edges", format!("\u{feff}{lf}")),
        (
            "bom-cr.edges",
            format!("\u{feff}{}", lf.replace('\n', "\r")),
        ),
    ] {
        let edges = write(dir.path(), name, &text);
        assert_eq!(
            score_json(&points, &edges, &truth),
            expected,
            "{name} as output"
        );
        assert_eq!(
            score_json(&points, &truth, &edges),
            expected,
            "{name} as truth"
        );
    }
    // A bad line is named by the same count of line ends, CR-only ones included.
    let bad = write(dir.path(), "bad.edges", "0 1\r1 2\r2 x\r3 0\r");
    let scored = condt(&[Path::new("score"), &points, &truth, &bad]);
    let said = String::from_utf8_lossy(&scored.stderr);
    assert_eq!(scored.status.code(), Some(1), "{said}");
    assert!(said.contains("bad.edges:3: "), "{said}");
}
