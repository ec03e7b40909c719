//! The `condt` binary: input formats, outputs, errors and exit codes.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn condt(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_condt"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let written = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    // A run refused on its options may exit before reading its input: a closed pipe is fine.
    if let Err(e) = written {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().unwrap()
}

fn data(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("condt-cli-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn lines(out: &[u8]) -> Vec<Vec<usize>> {
    String::from_utf8_lossy(out)
        .lines()
        .map(|l| l.split(' ').map(|t| t.parse().expect("an index")).collect())
        .collect()
}

#[test]
fn triangles_from_stdin_are_counter_clockwise_input_indices() {
    let out = condt(&["triangulate", "-"], "0 0\n2 0\n1 2\n1 0.5\n");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let pts = [(0.0, 0.0), (2.0, 0.0), (1.0, 2.0), (1.0, 0.5)];
    let tris = lines(&out.stdout);
    assert_eq!(tris.len(), 3);
    for t in tris {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| pts[i]);
        let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        assert!(cross > 0.0, "triangle {t:?} is not counter-clockwise");
    }
}

#[test]
fn cr_only_line_ends_tabs_and_a_third_column_are_read() {
    let out = condt(&["triangulate", &data("square_cr_tabs.txt"), "--edges"], "");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let edges = lines(&out.stdout);
    // Four sides and four spokes to the centre (point 4).
    assert_eq!(edges.len(), 8);
    assert_eq!(edges.iter().filter(|e| e[1] == 4).count(), 4);
    assert!(edges.windows(2).all(|w| w[0] < w[1]), "edges are sorted");
    assert!(edges.iter().all(|e| e[0] < e[1]));
}

#[test]
fn crlf_commas_comments_and_a_duplicate() {
    let out = condt(
        &["triangulate", &data("rectangle_crlf_commas.txt"), "--edges"],
        "",
    );
    assert!(out.status.success());
    // The last line repeats point 1: it is merged, and the tool says so.
    assert!(String::from_utf8_lossy(&out.stderr).contains("1 exact duplicate"));
    assert_eq!(lines(&out.stdout).len(), 5);
}

#[test]
fn a_malformed_line_is_reported_by_file_and_line_and_nothing_is_written() {
    let dir = scratch_dir("malformed");
    let target = dir.join("out.txt");
    std::fs::write(&target, "previous content\n").unwrap();
    let input = data("malformed_line3.txt");
    let out = condt(&["triangulate", &input, "-o", target.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1));
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(message.contains(&format!("{input}:3:")), "{message}");
    assert!(message.contains("oops"), "{message}");
    assert_eq!(
        std::fs::read_to_string(&target).unwrap(),
        "previous content\n"
    );
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "no temporary file is left behind"
    );
}

#[test]
fn output_file_is_complete_and_temporary_files_are_gone() {
    let dir = scratch_dir("output");
    let target = dir.join("edges.txt");
    let out = condt(
        &[
            "triangulate",
            "-",
            "--edges",
            "-o",
            target.to_str().unwrap(),
        ],
        "0 0\n1 0\n0 1\n",
    );
    assert!(out.status.success());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "0 1\n0 2\n1 2\n");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

#[test]
fn usage_errors_exit_with_two_and_explain() {
    for args in [
        &[][..],
        &["triangulate"],
        &["frobnicate"],
        &["triangulate", "-", "--bogus"],
    ] {
        let out = condt(args, "");
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("condt --help"));
    }
}

#[test]
fn missing_input_file_and_non_finite_values_are_errors() {
    let out = condt(&["triangulate", "/nonexistent/points.txt"], "");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/points.txt"));
    let out = condt(&["triangulate", "-"], "0 0\n1 1\nnan 2\n");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("<stdin>:3:"));
}

#[test]
fn collinear_input_has_edges_but_no_triangles() {
    let out = condt(&["triangulate", "-"], "0 0\n2 2\n1 1\n");
    assert!(out.status.success());
    assert!(out.stdout.is_empty());
    let out = condt(&["triangulate", "-", "--edges"], "0 0\n2 2\n1 1\n");
    assert_eq!(lines(&out.stdout), vec![vec![0, 2], vec![1, 2]]);
}

#[test]
fn help_and_version() {
    let out = condt(&["--help"], "");
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("triangulate INPUT"));
    let out = condt(&["--version"], "");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("condt "));
}

fn circle_input(n: usize) -> String {
    (0..n)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / n as f64;
            format!("{} {}\n", t.cos(), t.sin())
        })
        .collect()
}

#[test]
fn reconstruct_writes_polylines_to_stdout_by_default() {
    let out = condt(&["reconstruct", "-"], &circle_input(20));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 1);
    assert!(lines[0].starts_with("closed "));
    assert_eq!(lines[0].split(' ').count(), 21, "closed plus 20 indices");
}

#[test]
fn reconstruct_formats_follow_the_extension() {
    let dir = scratch_dir("formats");
    let input = dir.join("circle.txt");
    std::fs::write(&input, circle_input(16)).unwrap();
    for (name, check) in [
        ("out.edges", "0 1\n"),
        ("out.txt", "closed 0"),
        ("out.svg", "<svg"),
        ("out.geojson", "\"FeatureCollection\""),
    ] {
        let target = dir.join(name);
        let out = condt(
            &[
                "reconstruct",
                input.to_str().unwrap(),
                "-o",
                target.to_str().unwrap(),
            ],
            "",
        );
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let written = std::fs::read_to_string(&target).unwrap();
        assert!(written.contains(check), "{name}: {written}");
    }
    let edges = std::fs::read_to_string(dir.join("out.edges")).unwrap();
    assert_eq!(edges.lines().count(), 16);
}

#[test]
fn reconstruct_rejects_bad_options_and_bad_files() {
    let out = condt(&["reconstruct", "-", "--u", "2", "--adaptive"], "");
    assert_eq!(out.status.code(), Some(2));
    let out = condt(&["reconstruct", "-", "-o", "picture.png"], "0 0\n");
    assert_eq!(out.status.code(), Some(2));
    let out = condt(&["reconstruct", &data("malformed_line3.txt")], "");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("malformed_line3.txt:3:"));
}

#[test]
fn readme_example_data_gives_four_curves() {
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/shapes.txt");
    let out = condt(&["reconstruct", input.to_str().unwrap()], "");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let closed = text.lines().filter(|l| l.starts_with("closed")).count();
    let open = text.lines().filter(|l| l.starts_with("open")).count();
    // An ellipse and a square (closed), an arc and a spiral (open).
    assert_eq!((closed, open), (2, 2), "{text}");
}
