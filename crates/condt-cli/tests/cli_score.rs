//! `condt score`: the metrics of an edge list against a ground truth, from the command line.

use condt::Point;
use condt_eval::sample::{sample, Sampling, Shape};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary under test: this build's, or `CONDT_TEST_BIN` (to show a test fails on another).
fn binary() -> std::ffi::OsString {
    std::env::var_os("CONDT_TEST_BIN").unwrap_or_else(|| env!("CARGO_BIN_EXE_condt").into())
}

fn condt(args: &[&Path]) -> Output {
    Command::new(binary())
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

/// A sampled circle's points and true edges, written to `circle.pts` and `circle.gt` in `dir`,
/// and how many true edges there are.
fn sampled_circle(dir: &Path) -> (PathBuf, PathBuf, usize) {
    let circle = sample(
        &[Shape::circle(Point::new(3.0, -1.0), 2.0)],
        &Sampling::new(0.3),
    )
    .unwrap();
    (
        write(dir, "circle.pts", &points_text(&circle.points)),
        write(dir, "circle.gt", &edges_text(&circle.edges)),
        circle.edges.len(),
    )
}

#[test]
fn a_reconstruction_of_a_sampled_circle_scores_exact_against_its_truth() {
    let dir = scratch_dir();
    let (points, truth, true_edges) = sampled_circle(dir.path());
    let output = dir.path().join("circle.edges");
    let run = Command::new(binary())
        .args([Path::new("reconstruct"), &points, Path::new("-o"), &output])
        .output()
        .unwrap();
    assert!(run.status.success());
    let json = score_json(&points, &output, &truth);
    assert_eq!(json_value(&json, "exact"), "true");
    assert_eq!(json_value(&json, "f1"), "1.0");
    assert_eq!(json_value(&json, "max_dist"), "0.0");
    assert_eq!(json_value(&json, "n_gt"), true_edges.to_string());
    assert_eq!(json_value(&json, "malformed"), "null");
}

/// A truth written on a later copy of a duplicate point (a ring exported with its first point
/// again at the end) is never matched, as edges are compared by point number and the
/// reconstruction gives a duplicate's edges to its first copy: a note says so, unless --quiet.
#[test]
fn a_truth_on_a_later_copy_of_a_point_is_noted() {
    let dir = scratch_dir();
    let mut ring: Vec<Point> = (0..12)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 12.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    ring.push(ring[0]);
    let points = write(dir.path(), "ring.txt", &points_text(&ring));
    let polyline: Vec<[usize; 2]> = (0..12).map(|k| [k, k + 1]).collect();
    let truth = write(dir.path(), "ring.gt", &edges_text(&polyline));
    let mut closed = polyline.clone();
    closed[11] = [0, 11];
    let output = write(dir.path(), "ring.edges", &edges_text(&closed));
    let scored = condt(&[Path::new("score"), &points, &output, &truth]);
    assert!(scored.status.success());
    let notes = String::from_utf8_lossy(&scored.stderr);
    assert!(
        notes.contains("ring.gt names 1 point that repeats an earlier point exactly (12 = 0)"),
        "{notes}"
    );
    let quiet = condt(&[
        Path::new("score"),
        &points,
        &output,
        &truth,
        Path::new("-q"),
    ]);
    assert!(quiet.status.success() && quiet.stderr.is_empty());
    // No note where the truth names first copies only.
    let scored = condt(&[Path::new("score"), &points, &output, &output]);
    assert!(scored.status.success() && scored.stderr.is_empty());
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
        // A negative number is an edge to a point that does not exist (`-0` is 0), one too
        // large for any integer likewise, named as written.
        ("0 1\n1 -1\n", "line 2: point -1 does not exist"),
        ("0 1\n-0 -1\n", "line 2: point -1 does not exist"),
        (
            "0 1\n1 99999999999999999999999\n",
            "line 2: point 99999999999999999999999 does not exist",
        ),
        // Two ends out of range: the first is named, as the library reports it.
        ("0 1\n7 9\n", "line 2: point 7 does not exist"),
        ("0 1\n-1 -5\n", "line 2: point -1 does not exist"),
        ("0 1\n9 -1\n", "line 2: point 9 does not exist"),
        ("0 1\n1 2 3\n", "line 2: not an edge `i j`: \\\"1 2 3\\\""),
        ("0 1\n1 -\n", "line 2: not an edge `i j`: \\\"1 -\\\""),
    ] {
        let output = write(dir.path(), "o.edges", output);
        let json = score_json(&points, &output, &truth);
        assert_eq!(json_value(&json, "malformed"), format!("\"{problem}\""));
        assert_eq!(json_value(&json, "f1"), "0.0");
        assert_eq!(json_value(&json, "exact"), "false");
    }
    // A single line with a point that does not exist is a malformed edge list, scored 0, not
    // a file that is no edge list.
    let output = write(dir.path(), "o.edges", "0 -1\n");
    let json = score_json(&points, &output, &truth);
    assert_eq!(
        json_value(&json, "malformed"),
        "\"line 1: point -1 does not exist\""
    );
    // `n_out` counts valid edges, each once, as `score.py` does (a Python researcher's review).
    assert_eq!(json_value(&json, "n_out"), "0");
    let output = write(dir.path(), "twice.edges", "0 1\n1 2\n1 0\n");
    let json = score_json(&points, &output, &truth);
    assert_eq!(json_value(&json, "n_out"), "2");
}

#[test]
fn a_list_of_curves_given_as_output_is_told_to_be_one() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n");
    let curves = write(dir.path(), "out.txt", "open 0 1 2\n");
    let out = condt(&[Path::new("score"), &points, &curves, &truth]);
    assert_eq!(out.status.code(), Some(1));
    let said = String::from_utf8(out.stderr).unwrap();
    assert!(
        said.contains("out.txt:1: ") && said.contains("write the edges with -o out.edges"),
        "{said}"
    );
}

#[test]
fn an_edge_line_may_end_in_a_comment_as_a_point_line_may() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0 # first\n1 0\n2 0\n");
    let truth = write(
        dir.path(),
        "t.edges",
        "# truth\n0 1 # checked\n1 2#by hand\n",
    );
    let output = write(dir.path(), "o.edges", "0 1\t# kept\n  # a note\n1 2\n");
    let json = score_json(&points, &output, &truth);
    assert_eq!(json_value(&json, "malformed"), "null");
    assert_eq!(json_value(&json, "exact"), "true");
    assert_eq!(json_value(&json, "n_gt"), "2");
    // What stands before the `#` must still be an edge.
    let output = write(dir.path(), "o.edges", "0 1\n1 # 2\n1 2\n");
    let json = score_json(&points, &output, &truth);
    assert_eq!(
        json_value(&json, "malformed"),
        "\"line 2: not an edge `i j`: \\\"1\\\"\""
    );
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

/// `condt score` with standard input (`input`) and what it said: (exit code, stdout, stderr).
fn score_with_stdin(args: &[&Path], input: &[u8]) -> (Option<i32>, String, String) {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = Command::new(binary())
        .arg("score")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A run refused on its arguments may exit before reading: a closed pipe is fine.
    let _ = child.stdin.take().unwrap().write_all(input);
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `-` reads standard input for any one of POINTS, OUTPUT and TRUTH, as text; given twice, it
/// is refused (found by a stress run: OUTPUT or TRUTH `-` gave "-: No such file or directory").
#[test]
fn a_dash_reads_standard_input_for_one_file() {
    let dir = scratch_dir();
    let square = "0 0\n1 0\n1 1\n0 1\n";
    let points = write(dir.path(), "p.txt", square);
    let truth_text = "0 1\n1 2\n2 3\n3 0\n";
    let truth = write(dir.path(), "t.edges", truth_text);
    let output = write(dir.path(), "o.edges", "0 1\n1 2\n0 2\n");
    let json = Path::new("--json");
    let dash = Path::new("-");
    let expected = score_json(&points, &output, &truth);
    for (args, input) in [
        ([dash, &output, &truth, json], square),
        ([&points, dash, &truth, json], "0 1\n1 2\n0 2\n"),
        ([&points, &output, dash, json], truth_text),
    ] {
        let (code, stdout, stderr) = score_with_stdin(&args, input.as_bytes());
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
        assert_eq!(stdout, expected, "{args:?}");
    }
    // A bad line of standard input is named as <stdin>'s.
    let (code, _, stderr) = score_with_stdin(&[&points, &output, dash], b"0 1\n1 x\n");
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("<stdin>:2:"), "{stderr}");
    for args in [
        [dash, dash, &truth],
        [&points, dash, dash],
        [dash, &output, dash],
    ] {
        let (code, _, stderr) = score_with_stdin(&args, truth_text.as_bytes());
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("standard input"), "{args:?}: {stderr}");
        assert!(!stderr.contains("No such file"), "{args:?}: {stderr}");
    }
}

/// Standard input's Unix names (`/dev/stdin`, `/dev/fd/0`) are refused twice as `-` is, and read
/// as it is once. Unix only: Windows has no such names (under Wine `/dev/stdin` opens the Unix
/// file of another stream, and the test failed there).
#[cfg(unix)]
#[test]
fn standard_inputs_unix_names_are_read_once() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth_text = "0 1\n1 2\n2 3\n3 0\n";
    let truth = write(dir.path(), "t.edges", truth_text);
    let output = write(dir.path(), "o.edges", "0 1\n1 2\n0 2\n");
    let json = Path::new("--json");
    let dash = Path::new("-");
    let expected = score_json(&points, &output, &truth);
    // Its other names read the same pipe, which the second reader found drained: the truth
    // read first, the output then empty, scored "0 output ... exact false" with exit 0 (a
    // tester's review).
    let (stdin, fd0) = (Path::new("/dev/stdin"), Path::new("/dev/fd/0"));
    for args in [
        [&points, stdin, stdin],
        [&points, fd0, dash],
        [&points, dash, stdin],
    ] {
        let (code, _, stderr) = score_with_stdin(&args, truth_text.as_bytes());
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("standard input"), "{args:?}: {stderr}");
    }
    // Once, it reads as `-` does.
    let (code, stdout, stderr) =
        score_with_stdin(&[&points, &output, stdin, json], truth_text.as_bytes());
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stdout, expected);
    // A regular file behind standard input opens again by any name: twice is fine there.
    let run = Command::new(binary())
        .args([Path::new("score"), &points, stdin, stdin, json])
        .stdin(std::fs::File::open(&truth).unwrap())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        String::from_utf8(run.stdout).unwrap(),
        score_json(&points, &truth, &truth)
    );
}

/// A NumPy `.npy` array of shape `(rows, 2)` with dtype `descr`, the values given as bytes.
fn npy(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + dict.len() + 1) % 64 != 0 {
        dict.push(' ');
    }
    dict.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    bytes.extend_from_slice(dict.as_bytes());
    bytes.extend_from_slice(data);
    bytes
}

/// Whether a message holds only printable ASCII and line ends: no raw bytes of a binary file.
fn printable(message: &str) -> bool {
    message
        .chars()
        .all(|c| c == '\n' || (' '..='~').contains(&c))
}

/// The `.npy` edge arrays `reconstruct -o out.npy` writes (uint32, and int64 for larger sets)
/// are read as OUTPUT and as TRUTH, and score as the same edges in text; other dtypes and
/// shapes are refused (found by a stress run: such a file scored 0, exit 0, with binary junk
/// in its "malformed" line).
#[test]
fn npy_edge_arrays_are_read() {
    let dir = scratch_dir();
    let (points, truth, _) = sampled_circle(dir.path());
    let edges = dir.path().join("circle.edges");
    let array = dir.path().join("circle.NPY");
    for output in [&edges, &array] {
        let run = Command::new(binary())
            .args([Path::new("reconstruct"), &points, Path::new("-o"), output])
            .output()
            .unwrap();
        assert!(run.status.success());
    }
    let expected = score_json(&points, &edges, &truth);
    assert_eq!(json_value(&expected, "exact"), "true");
    assert_eq!(score_json(&points, &array, &truth), expected);
    assert_eq!(score_json(&points, &edges, &array), expected);
    // int64 (what reconstruct writes past 2^32 points), C and Fortran order, either byte
    // order, and uint32 big-endian: the same edges.
    let wrong = [[0usize, 1], [1, 2], [0, 2]];
    let text = write(dir.path(), "wrong.edges", &edges_text(&wrong));
    let expected = score_json(&points, &text, &truth);
    let c_order = |put: fn(usize) -> Vec<u8>| -> Vec<u8> {
        wrong.iter().flatten().flat_map(|&i| put(i)).collect()
    };
    let columns: Vec<u8> = (0..2)
        .flat_map(|k| wrong.iter().map(move |e| e[k] as u32))
        .flat_map(u32::to_le_bytes)
        .collect();
    // The same header with `'fortran_order': True ` (the length kept).
    let mut fortran = npy("<u4", "(3, 2)", &[]);
    let at = fortran.windows(5).position(|w| w == b"False").unwrap();
    fortran[at..at + 5].copy_from_slice(b"True ");
    for (name, bytes) in [
        (
            "i8.npy",
            npy(
                "<i8",
                "(3, 2)",
                &c_order(|i| (i as i64).to_le_bytes().to_vec()),
            ),
        ),
        (
            "i8be.npy",
            npy(
                ">i8",
                "(3, 2)",
                &c_order(|i| (i as i64).to_be_bytes().to_vec()),
            ),
        ),
        (
            "u4be.npy",
            npy(
                ">u4",
                "(3, 2)",
                &c_order(|i| (i as u32).to_be_bytes().to_vec()),
            ),
        ),
        (
            "i4.npy",
            npy(
                "<i4",
                "(3, 2)",
                &c_order(|i| (i as i32).to_le_bytes().to_vec()),
            ),
        ),
        (
            "u8.npy",
            npy(
                "<u8",
                "(3, 2)",
                &c_order(|i| (i as u64).to_le_bytes().to_vec()),
            ),
        ),
        ("fortran.npy", [fortran, columns].concat()),
    ] {
        let file = dir.path().join(name);
        std::fs::write(&file, &bytes).unwrap();
        assert_eq!(score_json(&points, &file, &truth), expected, "{name}");
    }
    // A problem of the array's edges is told by its row; the output scores 0.
    let repeated = dir.path().join("repeated.npy");
    let data: Vec<u8> = [0u32, 1, 1, 2, 2, 1]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    std::fs::write(&repeated, npy("<u4", "(3, 2)", &data)).unwrap();
    let json = score_json(&points, &repeated, &truth);
    assert_eq!(
        json_value(&json, "malformed"),
        "\"row 2: edge 1 2 repeated\""
    );
    assert_eq!(json_value(&json, "f1"), "0.0");
    // A negative point number is a point that does not exist, the output's problem as a text
    // line `0 -1` is: it scores 0, told by its row, and counts as no output edge (as `condt.score`
    // in Python counts and tells the same array; found by a fuzzer: the array was refused, the
    // text line scored); in the truth it is an error.
    let negative_row = dir.path().join("negative_row.npy");
    let data: Vec<u8> = [0i64, 1, 1, 2, 0, -1]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    std::fs::write(&negative_row, npy("<i8", "(3, 2)", &data)).unwrap();
    let json = score_json(&points, &negative_row, &truth);
    assert_eq!(
        json_value(&json, "malformed"),
        "\"row 2: point -1 does not exist\""
    );
    assert_eq!(json_value(&json, "f1"), "0.0");
    assert_eq!(json_value(&json, "n_out"), "2");
    assert_eq!(json_value(&json, "tp"), "2");
    let run = Command::new(binary())
        .args([Path::new("score"), &points, &truth, &negative_row])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("row 2: point -1 does not exist"),
        "{stderr}"
    );
    // What is not an edge array is an error naming the file, in words.
    let floats: Vec<u8> = [0f64, 1.0].iter().flat_map(|x| x.to_le_bytes()).collect();
    let small: Vec<u8> = [0u32, 1].iter().flat_map(|x| x.to_le_bytes()).collect();
    for (name, bytes, said) in [
        (
            "float.npy",
            npy("<f8", "(1, 2)", &floats),
            "\"<f8\" is not supported",
        ),
        (
            "bool.npy",
            npy("|b1", "(1, 2)", &[0, 1]),
            "\"|b1\" is not supported",
        ),
        ("shape.npy", npy("<u4", "(2,)", &small), "shape (2,)"),
        ("three.npy", npy("<u4", "(1, 3)", &small), "shape (1, 3)"),
        (
            "short.npy",
            npy("<u4", "(2, 2)", &small),
            "the header announces 2 edges",
        ),
        ("long.npy", npy("<u4", "(0, 2)", &small), "bytes after"),
        ("text.npy", b"0 1\n1 2\n".to_vec(), "not a NumPy .npy file"),
    ] {
        let file = dir.path().join(name);
        std::fs::write(&file, &bytes).unwrap();
        assert_refused_either_way(&points, &truth, &file, &[name, said]);
    }
}

/// `file` as OUTPUT and as TRUTH beside `truth`: an error (exit 1, nothing scored) whose message
/// says each of `said` and holds no raw byte.
fn assert_refused_either_way(points: &Path, truth: &Path, file: &Path, said: &[&str]) {
    for args in [[points, file, truth], [points, truth, file]] {
        let out = condt(&[Path::new("score"), args[0], args[1], args[2]]);
        let message = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{said:?}: {message}");
        assert!(out.stdout.is_empty(), "{said:?}");
        for part in said {
            assert!(message.contains(part), "{part}: {message}");
        }
        assert!(printable(&message), "{said:?}: {message:?}");
    }
}

/// A file that is not a text edge list (binary bytes, an `.npy` array under another name,
/// standard input holding one, a drawing or GeoJSON with no edge line at all) is an error
/// naming it, never a score of 0 with raw bytes in its message; a text edge list with a bad
/// line among edges still scores 0.
#[test]
fn what_is_not_an_edge_list_is_an_error() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n2 3\n3 0\n");
    let edges: Vec<u8> = [0u32, 1, 1, 2]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let array = npy("<u4", "(2, 2)", &edges);
    let mut nul = b"0 1\n1 2\n".to_vec();
    nul.extend_from_slice(b"2 3\0\n");
    for (name, bytes, said) in [
        ("array.edges", array.clone(), "NumPy"),
        // Not `nul.edges`: Windows reads that name as its null device (a Windows user's review).
        ("zero byte.edges", nul, "zero byte.edges:3"),
        (
            "latin1.edges",
            b"0 1\n1 2 \xe9\n".to_vec(),
            "latin1.edges:2",
        ),
        (
            "drawing.svg",
            b"<svg xmlns=\"x\">\n</svg>\n".to_vec(),
            "drawing.svg",
        ),
        (
            "shape.geojson",
            b"{\"type\": \"FeatureCollection\",\n\"features\": []}\n".to_vec(),
            "shape.geojson",
        ),
    ] {
        let file = dir.path().join(name);
        std::fs::write(&file, &bytes).unwrap();
        assert_refused_either_way(&points, &truth, &file, &[said]);
    }
    let (code, _, stderr) = score_with_stdin(&[&points, Path::new("-"), &truth], &array);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("<stdin>") && stderr.contains("NumPy"),
        "{stderr}"
    );
    assert!(printable(&stderr), "{stderr:?}");
    // One bad line among edges: a malformed output, scored 0.
    let output = write(dir.path(), "o.edges", "0 1\nclosed 1 2\n");
    let json = score_json(&points, &output, &truth);
    assert_eq!(json_value(&json, "f1"), "0.0");
    assert!(
        json_value(&json, "malformed").starts_with("\"line 2: "),
        "{json}"
    );
}

/// Without output edges there is no distance, and the line says so without "of the box
/// diagonal" after it (found by a stress run).
#[test]
fn no_output_edges_read_as_no_distance() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n2 3\n3 0\n");
    // The two distance lines of a run, which must succeed.
    let distances = |output: &Path, truth: &Path| -> Vec<String> {
        let out = condt(&[Path::new("score"), &points, output, truth]);
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        text.lines()
            .filter(|l| l.contains("distance"))
            .map(String::from)
            .collect()
    };
    let output = write(dir.path(), "o.edges", "# nothing\n");
    assert_eq!(
        distances(&output, &truth),
        [
            "max distance   none (no output edges)",
            "rms distance   none (no output edges)"
        ]
    );
    let output = write(dir.path(), "o.edges", "0 1\n1 3\n");
    assert!(distances(&output, &truth)
        .iter()
        .all(|l| l.ends_with("of the box diagonal")));
    // Nor without truth edges to measure from, as the JSON's `null` says (the text said "inf of
    // the box diagonal": a tester's review).
    let no_truth = write(dir.path(), "none.edges", "");
    assert_eq!(
        distances(&output, &no_truth),
        [
            "max distance   none (no truth edges)",
            "rms distance   none (no truth edges)"
        ]
    );
    let json = score_json(&points, &output, &no_truth);
    assert_eq!(json_value(&json, "max_dist"), "null");
}

/// A point number past every point is the OUTPUT's problem in an array as in text, even past
/// 2^63: the same edges score the same, 0 with the line (row) told, exit 0 (a reviewer's
/// report: `0 18446744073709551615` scored 0 in text and was a hard error in a uint64 array).
/// In TRUTH it is an error either way.
#[test]
fn a_point_number_past_every_point_scores_alike_in_text_and_in_an_array() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n2 3\n3 0\n");
    for far in [7u64, 1 << 40, i64::MAX as u64, 1 << 63, u64::MAX] {
        let text = write(dir.path(), "o.edges", &format!("0 1\n0 {far}\n"));
        let array = dir.path().join("o.npy");
        let data: Vec<u8> = [0u64, 1, 0, far]
            .iter()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        std::fs::write(&array, npy("<u8", "(2, 2)", &data)).unwrap();
        let from_text = score_json(&points, &text, &truth);
        let from_array = score_json(&points, &array, &truth);
        assert_eq!(json_value(&from_text, "f1"), "0.0", "{far}");
        let said = format!("point {far} does not exist\"");
        assert_eq!(
            json_value(&from_text, "malformed"),
            format!("\"line 2: {said}")
        );
        assert_eq!(
            json_value(&from_array, "malformed"),
            format!("\"row 1: {said}")
        );
        // The rest of the score is the same.
        let without = |json: &str| json.replace(&json_value(json, "malformed"), "");
        assert_eq!(without(&from_text), without(&from_array), "{far}");
        for file in [&text, &array] {
            let out = condt(&[Path::new("score"), &points, &truth, file]);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{far}: {stderr}");
            assert!(
                stderr.contains(&format!("point {far} does not exist")),
                "{stderr}"
            );
        }
    }
}

/// An edge array cut inside its first 8 bytes (the magic string and the version) is a damaged
/// array, said so, as from 8 bytes on (a reviewer's report: 6 and 7 bytes were said not to
/// start with the magic string they start with).
#[test]
fn an_edge_array_cut_inside_its_magic_string_ends_inside_its_header() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n2 3\n3 0\n");
    let whole = npy("<u4", "(1, 2)", &[0, 0, 0, 0, 1, 0, 0, 0]);
    for cut in [1, 4, 6, 7, 8, 9, 40] {
        let file = dir.path().join(format!("cut{cut}.npy"));
        std::fs::write(&file, &whole[..cut]).unwrap();
        assert_refused_either_way(
            &points,
            &truth,
            &file,
            &[&format!("cut{cut}.npy: the file ends inside its header")],
        );
    }
}

/// What the help says of files with no edge is what happens: an empty file, or one of comments
/// and blank lines only, is an empty edge list, as OUTPUT (scored 0 against a truth with edges)
/// and as TRUTH; text with lines but none of them an edge is an error (a reviewer's report:
/// the help called every text with no edge line an error).
#[test]
fn a_file_without_edges_is_an_empty_edge_list_as_the_help_says() {
    let help = String::from_utf8(condt(&[Path::new("help"), Path::new("score")]).stdout).unwrap();
    let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains(
            "an empty file, or one of comments and blank lines only, is an empty edge list"
        ),
        "{help}"
    );
    assert!(
        !flat.contains("text with no edge line) is an error"),
        "{help}"
    );
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n1 1\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n2 3\n3 0\n");
    for (name, text) in [
        ("empty.edges", ""),
        ("comments.edges", "# none\n\n  # here\n"),
    ] {
        let none = write(dir.path(), name, text);
        let json = score_json(&points, &none, &truth);
        assert_eq!(json_value(&json, "f1"), "0.0", "{name}");
        assert_eq!(json_value(&json, "n_out"), "0", "{name}");
        assert_eq!(json_value(&json, "malformed"), "null", "{name}");
        let json = score_json(&points, &truth, &none);
        assert_eq!(json_value(&json, "n_gt"), "0", "{name}");
        let json = score_json(&points, &none, &none);
        assert_eq!(json_value(&json, "exact"), "true", "{name}");
    }
    let words = write(dir.path(), "words.edges", "# edges\nnone here\n");
    assert_refused_either_way(&points, &truth, &words, &["words.edges:2"]);
}

/// `condt score` takes `-q`/`--quiet` as the other commands do (it was an unknown option, exit
/// 2): the scores are the same, and the note on what POINTS skipped (a GeoJSON feature with a
/// null geometry) is left out.
#[test]
fn score_takes_quiet_as_the_other_commands_do() {
    let dir = scratch_dir();
    let points = write(
        dir.path(),
        "points.geojson",
        r#"{"type": "FeatureCollection", "features": [
          {"type": "Feature", "properties": {}, "geometry": null},
          {"type": "Feature", "properties": {}, "geometry":
            {"type": "MultiPoint", "coordinates": [[0, 0], [1, 0], [0.5, 2]]}}]}"#,
    );
    let edges = write(dir.path(), "out.edges", "0 1\n1 2\n0 2\n");
    let said = |args: &[&Path]| {
        let out = condt(args);
        assert!(out.status.success(), "{args:?}: {:?}", out);
        (
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        )
    };
    let score = Path::new("score");
    let (loud, note) = said(&[score, &points, &edges, &edges]);
    assert!(loud.contains("exact"), "{loud}");
    assert!(
        note.contains("skipped 1 feature with a null geometry"),
        "{note}"
    );
    for quiet in ["-q", "--quiet"] {
        let (out, note) = said(&[score, &points, &edges, &edges, Path::new(quiet)]);
        assert_eq!(out, loud, "{quiet}");
        assert_eq!(note, "", "{quiet}");
    }
    let (json, note) = said(&[
        score,
        Path::new("-q"),
        &points,
        &edges,
        &edges,
        Path::new("--json"),
    ]);
    assert!(json.starts_with('{') && note.is_empty(), "{json}{note}");
    let help = condt(&[score, Path::new("--help")]);
    assert!(String::from_utf8_lossy(&help.stdout).contains("-q, --quiet"));
}

/// `condt score` reads POINTS as `reconstruct` reads INPUT: `--input-format F` and
/// `--columns X,Y` (a CSV read with `--columns` was reconstructed but could not be scored);
/// `--columns` on a POINTS it cannot apply to is a usage error, and the help shows both.
#[test]
fn score_reads_points_with_input_format_and_columns() {
    let dir = scratch_dir();
    let circle = sample(
        &[Shape::circle(Point::new(3.0, -1.0), 2.0)],
        &Sampling::new(0.3),
    )
    .unwrap();
    let csv: String = "FID,Shape_Y,Shape_X\n".to_string()
        + &circle
            .points
            .iter()
            .enumerate()
            .map(|(k, p)| format!("{k},{:?},{:?}\n", p.y, p.x))
            .collect::<String>();
    let survey = write(dir.path(), "survey.csv", &csv);
    let table = write(dir.path(), "survey.txt", &csv);
    let truth = write(dir.path(), "circle.gt", &edges_text(&circle.edges));
    let output = dir.path().join("circle.edges");
    let run = Command::new(binary())
        .args([Path::new("reconstruct"), &survey, Path::new("-o"), &output])
        .args(["--columns", "Shape_X,Shape_Y"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{run:?}");
    let score = |points: &Path, extra: &[&str]| {
        Command::new(binary())
            .args([Path::new("score"), points, &output, &truth])
            .args(["--json"])
            .args(extra)
            .output()
            .unwrap()
    };
    for (points, extra) in [
        (&survey, &["--columns", "Shape_X,Shape_Y"][..]),
        (&survey, &["--columns=3,2"][..]),
        (
            &table,
            &["--input-format", "csv", "--columns", "shape_x,shape_y"][..],
        ),
    ] {
        let out = score(points, extra);
        assert!(out.status.success(), "{extra:?}: {out:?}");
        let json = String::from_utf8(out.stdout).unwrap();
        assert_eq!(json_value(&json, "exact"), "true", "{extra:?}");
        assert_eq!(
            json_value(&json, "n_points"),
            circle.points.len().to_string()
        );
    }
    // Without the option the header names no x: refused naming the file and line, and the
    // option that helps.
    let out = score(&survey, &[]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains("survey.csv:1: the header has no x column") && said.contains("--columns X,Y"),
        "{said}"
    );
    // A format the columns cannot apply to, by name or stated: a usage error before reading.
    let npy = dir.path().join("points.npy");
    for (points, extra, words) in [
        (
            &npy,
            &["--columns", "1,2"][..],
            "points.npy is read as npy by its name: columns apply to CSV, TSV and plain text input only",
        ),
        (
            &survey,
            &["--columns", "1,2", "--input-format", "geojson"][..],
            "read as geojson by --input-format: columns apply to CSV, TSV and plain text input only",
        ),
        (
            &survey,
            &["--input-format", "xlsx"][..],
            "unknown input format",
        ),
    ] {
        let out = score(points, extra);
        let said = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {said}");
        assert!(said.contains(words), "{extra:?}: {said}");
        assert!(said.contains("condt help score"), "{said}");
    }
    let help = Command::new(binary())
        .args(["score", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    assert!(
        help.contains("--input-format F") && help.contains("--columns X,Y"),
        "{help}"
    );
}

/// A GeoJSON sequence whose later record gives another crs than the first: a note names the
/// file and line (only the first is kept), and `--quiet` leaves it out.
#[test]
fn score_notes_a_dropped_crs() {
    let dir = scratch_dir();
    let record = |name: &str, coordinates: &str| {
        format!(
            "{{\"type\": \"FeatureCollection\", \"crs\": {{\"type\": \"name\", \"properties\": \
             {{\"name\": \"{name}\"}}}}, \"features\": [{{\"type\": \"Feature\", \"properties\": \
             {{}}, \"geometry\": {{\"type\": \"MultiPoint\", \"coordinates\": {coordinates}}}}}]}}\n"
        )
    };
    let points = write(
        dir.path(),
        "sites.geojsonl",
        &(record("EPSG:32632", "[[0, 0], [1, 0]]") + &record("EPSG:2056", "[[0.5, 2]]")),
    );
    let edges = write(dir.path(), "out.edges", "0 1\n1 2\n0 2\n");
    let out = condt(&[Path::new("score"), &points, &edges, &edges]);
    assert!(out.status.success(), "{out:?}");
    let note = String::from_utf8(out.stderr).unwrap();
    assert!(
        note.contains("sites.geojsonl:2: this crs differs from the one kept"),
        "{note}"
    );
    let out = condt(&[Path::new("score"), &points, &edges, &edges, Path::new("-q")]);
    assert!(out.status.success() && out.stderr.is_empty(), "{out:?}");
}

/// A point number megabytes long is cut in the messages, as the point readers cut a token: in
/// the `malformed` field of an output's score and in a ground truth's error (a power user's
/// review: a 5 MB token gave a 5 MB message).
#[test]
fn a_huge_point_number_is_cut_in_messages() {
    let dir = scratch_dir();
    let points = write(dir.path(), "p.txt", "0 0\n1 0\n0 1\n");
    let truth = write(dir.path(), "t.edges", "0 1\n1 2\n");
    let huge = format!("0 1\n{} 2\n", "9".repeat(100_000));
    let output = write(dir.path(), "o.edges", &huge);
    let json = score_json(&points, &output, &truth);
    assert!(json.len() < 1_000, "{} bytes", json.len());
    assert!(
        json.contains("(100000 characters) does not exist"),
        "{json}"
    );
    let refused = condt(&[Path::new("score"), &points, &truth, &output]);
    assert!(!refused.status.success());
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(
        message.len() < 1_000 && message.contains("(100000 characters)"),
        "{message}"
    );
}
