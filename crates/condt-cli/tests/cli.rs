//! The `condt` binary: input formats, outputs, messages, errors and exit codes (where `-o`
//! writes is in cli_output.rs).

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// The binary under test: this build's, or `CONDT_TEST_BIN` (to show a test fails on another).
fn binary() -> std::ffi::OsString {
    std::env::var_os("CONDT_TEST_BIN").unwrap_or_else(|| env!("CARGO_BIN_EXE_condt").into())
}

fn condt(args: &[&str], stdin: &str) -> Output {
    condt_bytes(args, stdin.as_bytes())
}

fn condt_bytes(args: &[&str], stdin: &[u8]) -> Output {
    let mut child = Command::new(binary())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let written = child.stdin.take().unwrap().write_all(stdin);
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

/// A fresh directory, removed with everything in it when the guard is dropped (also when the
/// test fails).
fn scratch_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("condt-cli-")
        .tempdir()
        .unwrap()
}

/// Writes the edges of a triangle's three points to `target` (`condt triangulate - --edges -o
/// target`), which must succeed: what the output-file tests write.
fn triangle_edges_to(target: &Path) {
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
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
    let scratch = scratch_dir();
    let dir = scratch.path();
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
        std::fs::read_dir(dir).unwrap().count(),
        1,
        "no temporary file is left behind"
    );
}

#[test]
fn output_file_is_complete_and_temporary_files_are_gone() {
    let scratch = scratch_dir();
    let dir = scratch.path();
    let target = dir.join("edges.txt");
    triangle_edges_to(&target);
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "0 1\n0 2\n1 2\n");
    assert_eq!(std::fs::read_dir(dir).unwrap().count(), 1);
}

/// `-o` naming the input file by another path is refused on every system, the input untouched:
/// as written, through `.`, through a hard link, and (on Windows, whose file names ignore case)
/// in capitals; so is standard output appended to the input. On Windows the check compared
/// nothing (a Windows user's review: `condt reconstruct points.txt -o points.txt` replaced the
/// points by the curves); cli_output.rs tests the Unix names (symbolic links, `/dev/fd`).
#[test]
fn the_input_cannot_be_the_output_on_any_system() {
    let scratch = scratch_dir();
    let dir = scratch.path();
    let points = "0 0\n1 0\n1 1\n0 1\n";
    let input = dir.join("points.txt");
    std::fs::write(&input, points).unwrap();
    let hard = dir.join("hard.txt");
    std::fs::hard_link(&input, &hard).unwrap();
    let mut outputs = vec![input.clone(), dir.join(".").join("points.txt"), hard];
    if cfg!(windows) {
        outputs.push(dir.join("POINTS.TXT"));
    }
    for output in &outputs {
        for command in ["triangulate", "reconstruct"] {
            let out = Command::new(binary())
                .args([command.as_ref(), input.as_os_str(), "-o".as_ref()])
                .arg(output)
                .stdin(Stdio::null())
                .output()
                .unwrap();
            let message = String::from_utf8_lossy(&out.stderr);
            assert_eq!(
                out.status.code(),
                Some(2),
                "{command} -o {output:?}: {message}"
            );
            assert!(message.contains("is the input"), "{message}");
            assert_eq!(std::fs::read_to_string(&input).unwrap(), points);
        }
    }
    let appending = std::fs::OpenOptions::new()
        .append(true)
        .open(&input)
        .unwrap();
    let out = Command::new(binary())
        .args(["triangulate".as_ref(), input.as_os_str()])
        .stdin(Stdio::null())
        .stdout(appending)
        .output()
        .unwrap();
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{message}");
    assert!(
        message.contains("the output <stdout> is the input"),
        "{message}"
    );
    assert_eq!(std::fs::read_to_string(&input).unwrap(), points);
}

/// `-o NUL`, Windows's null device, takes the output and discards it, as `-o /dev/null` does on
/// Unix (a Windows user's review: it was refused, "Incorrect function", as the device has no
/// metadata to read).
#[cfg(windows)]
#[test]
fn the_null_device_takes_the_output_on_windows() {
    for name in ["NUL", "nul"] {
        for command in ["triangulate", "reconstruct"] {
            let out = condt(&[command, "-", "-q", "-o", name], "0 0\n1 0\n0 1\n");
            let message = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{command} -o {name}: {message}");
            assert!(out.stdout.is_empty() && message.is_empty(), "{message}");
        }
    }
}

/// An output with another hard link is rewritten in place on every system, so both names hold
/// the result (on Windows the count of links was not read, and the file renamed over one name
/// left the other with the old content).
#[test]
fn a_hard_linked_output_keeps_its_other_name_on_any_system() {
    let scratch = scratch_dir();
    let target = scratch.path().join("edges.txt");
    std::fs::write(&target, "previous content\n").unwrap();
    let other = scratch.path().join("other name.txt");
    std::fs::hard_link(&target, &other).unwrap();
    triangle_edges_to(&target);
    for name in [&target, &other] {
        assert_eq!(
            std::fs::read_to_string(name).unwrap(),
            "0 1\n0 2\n1 2\n",
            "{name:?}"
        );
    }
    assert_eq!(std::fs::read_dir(scratch.path()).unwrap().count(), 2);
}

/// An output another program holds open, sharing reading and writing but not deletion (as
/// Python's `open` and C's `fopen` do), is written on Windows, in place, as it is replaced on
/// Unix (a Windows user's review: the rename over it failed, "Access denied", after the run).
#[cfg(windows)]
#[test]
fn an_output_another_program_holds_open_is_written_on_windows() {
    use std::os::windows::fs::OpenOptionsExt;
    const FILE_SHARE_READ: u32 = 1;
    const FILE_SHARE_WRITE: u32 = 2;
    let scratch = scratch_dir();
    let target = scratch.path().join("edges.txt");
    std::fs::write(&target, "previous content, longer than the edges\n").unwrap();
    let held = std::fs::OpenOptions::new()
        .read(true)
        .share_mode(FILE_SHARE_READ | FILE_SHARE_WRITE)
        .open(&target)
        .unwrap();
    triangle_edges_to(&target);
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "0 1\n0 2\n1 2\n");
    drop(held);
    assert_eq!(std::fs::read_dir(scratch.path()).unwrap().count(), 1);
}

/// A hidden output stays hidden when it is replaced on Windows (the rename cleared its
/// attributes, and it came back visible).
#[cfg(windows)]
#[test]
fn a_replaced_output_keeps_its_attributes_on_windows() {
    use std::os::windows::fs::MetadataExt;
    const FILE_ATTRIBUTE_HIDDEN: u32 = 2;
    let scratch = scratch_dir();
    let target = scratch.path().join("edges.txt");
    std::fs::write(&target, "previous content\n").unwrap();
    let status = Command::new("attrib")
        .arg("+H")
        .arg(&target)
        .status()
        .unwrap();
    assert!(status.success());
    let hidden = |path: &Path| {
        std::fs::metadata(path).unwrap().file_attributes() & FILE_ATTRIBUTE_HIDDEN != 0
    };
    assert!(hidden(&target), "attrib +H hides it");
    triangle_edges_to(&target);
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "0 1\n0 2\n1 2\n");
    assert!(hidden(&target), "still hidden");
}

/// A GeoJSON output is on the input's coordinates, so it carries on a GeoJSON input's `crs`
/// (projected coordinates read as longitudes in GIS tools without it); a nested `crs` or another
/// format gives none.
#[test]
fn a_geojson_inputs_crs_is_carried_on_to_the_geojson_output() {
    let crs = r#"{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}}"#;
    let positions = "[[500000,4000000],[500010,4000001],[500020,4000000],[500010,4000012]]";
    let with_crs = format!(
        r#"{{"type":"FeatureCollection","crs":{crs},"features":[{{"type":"Feature","properties":{{}},"geometry":{{"type":"MultiPoint","coordinates":{positions}}}}}]}}"#
    );
    let args = ["reconstruct", "-", "--format", "geojson"];
    let out = condt(&args, &with_crs);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with(&format!(
        r#"{{"type":"FeatureCollection","crs":{crs},"features":["#
    )));
    // A feature's own crs is its points' (GeoJSON 2008, section 3: an object without one takes
    // its parent's), carried where the document has none.
    let nested = format!(
        r#"{{"type":"FeatureCollection","features":[{{"type":"Feature","crs":{crs},"properties":{{}},"geometry":{{"type":"MultiPoint","coordinates":{positions}}}}}]}}"#
    );
    let text = String::from_utf8(condt(&args, &nested).stdout).unwrap();
    assert!(
        text.starts_with(&format!(
            r#"{{"type":"FeatureCollection","crs":{crs},"features":["#
        )),
        "{text}"
    );
    let plain = "500000 4000000\n500010 4000001\n500020 4000000\n500010 4000012\n";
    let out = condt(&args, plain);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with(r#"{"type":"FeatureCollection","features":["#),
        "{text}"
    );
    assert_eq!(text.split("LineString").count(), 2, "{text}");
}

/// Standard input has no name to tell its format: a NumPy array and a GeoJSON document are
/// read by their content, as their files are (a new user's report: both were refused as text).
#[test]
fn standard_input_is_told_npy_or_geojson_by_its_content() {
    let args = ["triangulate", "-", "--edges"];
    let text = condt(&args, "0 0\n1 0\n0 1\n1 1.5\n");
    assert!(text.status.success());
    let geojson = r#" {"type":"MultiPoint","coordinates":[[0,0],[1,0],[0,1],[1,1.5]]}"#;
    let out = condt(&args, geojson);
    assert_eq!(
        out.stdout,
        text.stdout,
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (4, 2), }";
    let header = format!("{dict:<117}\n");
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    npy.extend((header.len() as u16).to_le_bytes());
    npy.extend(header.bytes());
    npy.extend(
        [0.0f64, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.5]
            .iter()
            .flat_map(|v| v.to_le_bytes()),
    );
    let out = condt_bytes(&args, &npy);
    assert_eq!(
        out.stdout,
        text.stdout,
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn usage_errors_exit_with_two_and_explain() {
    // A command's own usage errors point to that command's help; the others to the overview.
    for (args, pointer) in [
        (&[][..], "condt --help"),
        (&["triangulate"], "condt help triangulate"),
        (&["frobnicate"], "condt --help"),
        (&["triangulate", "-", "--bogus"], "condt help triangulate"),
        (&["reconstruct", "-", "--u", "0"], "condt help reconstruct"),
        (&["score", "a"], "condt help score"),
    ] {
        let out = condt(args, "");
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(pointer), "{args:?}: {stderr}");
    }
    let help = condt(&["help", "help"], "");
    assert!(help.status.success());
    assert!(String::from_utf8_lossy(&help.stdout).contains("condt help COMMAND"));
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
    // An empty output is explained: where the chain is.
    let note = String::from_utf8_lossy(&out.stderr);
    assert!(note.contains("no triangles"), "{note}");
    assert!(
        note.contains("chain of 2 edges is written with --edges"),
        "{note}"
    );
    let out = condt(&["triangulate", "-", "--edges"], "0 0\n2 2\n1 1\n");
    assert_eq!(lines(&out.stdout), vec![vec![0, 2], vec![1, 2]]);
    assert!(
        out.stderr.is_empty(),
        "the chain is there: nothing to explain"
    );
    // Triangles, and no note.
    let out = condt(&["triangulate", "-"], "0 0\n2 2\n1 0\n");
    assert_eq!(lines(&out.stdout).len(), 1);
    assert!(out.stderr.is_empty());
    // One distinct point has neither.
    let out = condt(&["triangulate", "-"], "1 1\n1 1\n");
    let note = String::from_utf8_lossy(&out.stderr);
    assert!(note.contains("no triangles and no edges"), "{note}");
}

#[test]
fn help_and_version() {
    let out = condt(&["--help"], "");
    assert!(out.status.success());
    let global = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(global.contains("triangulate INPUT"));
    let out = condt(&["--version"], "");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("condt "));
    // Each command has its own help, with an example, however it is asked for.
    for (command, own) in [("reconstruct", "--repair MODE"), ("triangulate", "--edges")] {
        let mut seen = Vec::new();
        for args in [
            &[command, "--help"][..],
            &[command, "-h"],
            &[command, "in.txt", "--help"],
            &["help", command],
        ] {
            let out = condt(args, "");
            assert!(out.status.success(), "{args:?}");
            let text = String::from_utf8_lossy(&out.stdout).into_owned();
            assert!(
                text.starts_with(&format!("condt {command}:")),
                "{args:?}: {text}"
            );
            assert!(text.contains(own), "{args:?}");
            assert!(
                text.contains(&format!("Example:\n  condt {command} ")),
                "{args:?}"
            );
            assert_ne!(text, global);
            seen.push(text);
        }
        assert!(seen.windows(2).all(|w| w[0] == w[1]));
    }
    let out = condt(&["help", "frobnicate"], "");
    assert_eq!(out.status.code(), Some(2));
}

/// `help COMMAND`, `--help` and `--version` refuse an argument after them, as every command
/// refuses an extra one (a reviewer's report: `condt help score extra` and `condt -V x`
/// ignored it, exit 0).
#[test]
fn help_and_version_refuse_extra_arguments() {
    for (args, said) in [
        (
            &["help", "score", "extra"][..],
            "unexpected extra argument extra",
        ),
        (
            &["help", "reconstruct", "-o"],
            "unexpected extra argument -o",
        ),
        (&["-V", "x"], "-V takes no argument; unexpected x"),
        (
            &["--version", "x"],
            "--version takes no argument; unexpected x",
        ),
        (
            &["--version", "--help"],
            "--version takes no argument; unexpected --help",
        ),
        (
            &["--help", "score"],
            "--help takes no argument; unexpected score",
        ),
        (&["-h", "x", "y"], "-h takes no argument; unexpected x"),
    ] {
        let out = condt(args, "");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?}");
        assert!(stderr.contains(said), "{args:?}: {stderr}");
        assert!(stderr.contains("condt --help"), "{args:?}: {stderr}");
    }
    for args in [&["help", "score"][..], &["-V"], &["--help"], &["help"]] {
        assert!(condt(args, "").status.success(), "{args:?}");
    }
}

/// A text whose only line with columns is words that name no x and y (an error message saved
/// in place of the points) is refused, naming its file and line; a header that names x and y
/// with no point after it is an empty point file (a reviewer's report: `Error: file not found`
/// alone read as a header, 0 points, exit 0).
#[test]
fn a_lone_line_of_words_is_not_an_empty_point_file() {
    for input in ["Error: file not found\n", "# points\na b\n", "Error\n"] {
        let out = condt(&["reconstruct", "-"], input);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{input:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{input:?}");
        assert!(stderr.contains("<stdin>:"), "{input:?}: {stderr}");
        assert!(stderr.contains("no point: line"), "{input:?}: {stderr}");
    }
    for input in ["x y\n", "# none yet\nlon,lat\n", "X Y z\n# end\n", ""] {
        let out = condt(&["triangulate", "-"], input);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{input:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{input:?}");
    }
    let help = String::from_utf8(condt(&["--help"], "").stdout).unwrap();
    let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(flat.contains("empty only if it names x and y"), "{help}");
}

/// Runs a command line expected to be refused, and returns what it said.
fn refused(args: &[&str]) -> String {
    let out = condt(args, "0 0\n1 0\n0 1\n");
    let said = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {said}");
    assert!(out.stdout.is_empty(), "{args:?}");
    said
}

#[test]
fn a_wrong_value_is_answered_with_the_choices() {
    let said = refused(&["reconstruct", "-", "--repair", "bogus"]);
    assert!(said.contains("--repair bogus"), "{said}");
    assert!(!said.contains("Some("), "{said}");
    for mode in ["needs", "paper", "mutual", "crossing", "off"] {
        assert!(said.contains(mode), "{said}");
    }
    let said = refused(&["reconstruct", "-", "--repair"]);
    assert!(
        said.contains("needs, paper, mutual, crossing or off"),
        "{said}"
    );
    let said = refused(&["reconstruct", "-", "--format", "png"]);
    assert!(
        said.contains("edges, npy, txt, svg, geojson, html, csv and unused"),
        "{said}"
    );
}

/// `--format unused` lists the points the curves leave out by their input numbers: here three
/// far points, one of them given twice (the duplicate is listed with it), around a circle whose
/// every point is on the curve. `-o NAME.txt` takes the list without a note; no ending names
/// the format.
#[test]
fn the_unused_points_are_listed_by_their_numbers() {
    let mut text = String::new();
    for k in 0..30 {
        let t = k as f64 * std::f64::consts::TAU / 30.0;
        text += &format!("{} {}\n", 10.0 * t.cos(), 10.0 * t.sin());
        if k == 12 {
            text += "40 40\n"; // 13
        }
        if k == 20 {
            text += "-45 3\n40 40\n"; // 22 and 23, a duplicate of 13
        }
    }
    let listed = condt(&["reconstruct", "-", "--format", "unused"], &text);
    assert!(
        listed.status.success(),
        "{}",
        String::from_utf8_lossy(&listed.stderr)
    );
    assert_eq!(lines(&listed.stdout), [[13], [22], [23]]);
    // The curves use every other point.
    let curves = condt(&["reconstruct", "-"], &text);
    let curves = String::from_utf8(curves.stdout).unwrap();
    let on_curves: Vec<usize> = curves
        .split_whitespace()
        .filter_map(|t| t.parse().ok())
        .collect();
    for i in 0..33 {
        assert_eq!(
            on_curves.contains(&i),
            ![13, 22, 23].contains(&i),
            "{i}: {curves}"
        );
    }
    let dir = scratch_dir();
    let target = dir.path().join("outliers.txt");
    let target = target.to_str().unwrap();
    let out = condt(
        &["reconstruct", "-", "--format", "unused", "-o", target],
        &text,
    );
    assert!(out.status.success());
    assert_eq!(std::fs::read_to_string(target).unwrap(), "13\n22\n23\n");
    assert!(!String::from_utf8_lossy(&out.stderr).contains("format its name"));
    let said = refused(&["reconstruct", "-", "-o", "out.unused"]);
    assert!(
        said.contains("cannot tell the format of out.unused"),
        "{said}"
    );
}

/// `-o NAME.csv` writes the curves' coordinates, one row per point, for R, MATLAB, Julia and
/// spreadsheets (an R and MATLAB user's review: `.csv` was refused, and the edge lists need 1
/// added to every number there): each row's coordinates are those of the input point it names,
/// the curves' rows follow the txt output's lines, and a closed curve ends at its first point.
#[test]
fn a_csv_output_gives_each_curves_coordinates() {
    let mut text = String::from("x,y\n");
    let mut points = Vec::new();
    for k in 0..30 {
        let t = k as f64 * std::f64::consts::TAU / 30.0;
        points.push((1000.0 + 10.0 * t.cos(), 2000.5 + 10.0 * t.sin()));
    }
    for k in 0..12 {
        points.push((1100.0 + 3.0 * k as f64, 2000.0 + 0.1 * (k % 2) as f64));
    }
    for (x, y) in &points {
        text += &format!("{x},{y}\n");
    }
    let dir = scratch_dir();
    let (input, target) = (dir.path().join("pts.csv"), dir.path().join("curves.csv"));
    std::fs::write(&input, &text).unwrap();
    let (input_name, target_name) = (input.to_str().unwrap(), target.to_str().unwrap());
    let out = condt(&["reconstruct", input_name, "-o", target_name, "-q"], "");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let written = std::fs::read_to_string(&target).unwrap();
    let mut rows = written.lines();
    assert_eq!(rows.next(), Some("curve,closed,point,x,y"));
    let mut curves: Vec<(bool, Vec<usize>)> = Vec::new();
    for row in rows {
        let f: Vec<&str> = row.split(',').collect();
        assert_eq!(f.len(), 5, "{row}");
        let (curve, point): (usize, usize) = (f[0].parse().unwrap(), f[2].parse().unwrap());
        let (x, y): (f64, f64) = (f[3].parse().unwrap(), f[4].parse().unwrap());
        assert_eq!((x, y), points[point], "{row}");
        if curves.len() == curve {
            curves.push((f[1] == "1", Vec::new()));
        }
        curves[curve].1.push(point);
    }
    let txt = condt(&["reconstruct", input_name, "-q"], "");
    let txt = String::from_utf8(txt.stdout).unwrap();
    assert_eq!(curves.len(), txt.lines().count(), "{txt}");
    assert_eq!(curves.len(), 2, "{txt}");
    for ((closed, mut rows), line) in curves.into_iter().zip(txt.lines()) {
        let mut words = line.split_whitespace();
        assert_eq!(closed, words.next() == Some("closed"), "{line}");
        let numbers: Vec<usize> = words.map(|w| w.parse().unwrap()).collect();
        if closed {
            assert_eq!(
                rows.pop(),
                Some(numbers[0]),
                "a closed curve ends at its start"
            );
        }
        assert_eq!(rows, numbers, "{line}");
    }
}

#[test]
fn options_that_contradict_each_other_are_refused() {
    for (a, b) in [
        (&["--no-manifold-fix"][..], &["--repair", "mutual"][..]),
        (&["--repair", "paper"], &["--repair", "crossing"]),
        (&["--u", "2"], &["--adaptive"]),
        (&["--iqr", "2"], &["--no-outlier-filter"]),
        (&["--close-gaps"], &["--no-close-gaps"]),
        (&["--local-outliers"], &["--no-local-outliers"]),
        (&["--format", "svg"], &["--format", "edges"]),
    ] {
        for args in [[a, b].concat(), [b, a].concat()] {
            let mut line = vec!["reconstruct", "-"];
            line.extend(&args);
            let said = refused(&line);
            assert!(said.contains("contradict each other"), "{line:?}: {said}");
        }
    }
    // Saying the same thing twice, or what --paper already says, is no contradiction.
    assert_reconstruct_accepts(&[
        &["--no-manifold-fix", "--repair", "off"],
        &["--paper", "--repair", "paper"],
        &["--close-gaps", "--close-gaps"],
    ]);
}

/// Each of `options` after `condt reconstruct -` runs on a circle without an error.
fn assert_reconstruct_accepts(options: &[&[&str]]) {
    for args in options {
        let mut line = vec!["reconstruct", "-"];
        line.extend(args.iter());
        let out = condt(&line, &circle_input(12));
        assert!(
            out.status.success(),
            "{line:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn stages_need_an_svg_and_an_empty_output_name_is_explained() {
    for args in [
        &["reconstruct", "-", "--stages"][..],
        &["reconstruct", "-", "--stages", "-o", "out.txt"],
        &["reconstruct", "-", "--stages", "--format", "geojson"],
    ] {
        let said = refused(args);
        assert!(said.contains("--stages"), "{args:?}: {said}");
        assert!(said.contains("svg"), "{args:?}: {said}");
    }
    let out = condt(
        &["reconstruct", "-", "--stages", "--format", "svg"],
        &circle_input(12),
    );
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("<svg"));
    for command in ["reconstruct", "triangulate"] {
        let said = refused(&[command, "-", "-o", ""]);
        assert!(said.contains("empty"), "{said}");
        assert!(!said.contains("No such file"), "{said}");
    }
    let said = refused(&["triangulate", "-", "-o", "a.txt", "-o", "b.txt"]);
    assert!(said.contains("twice"), "{said}");
}

#[test]
fn counts_of_one_are_singular() {
    let said = |input: &str| {
        let out = condt(&["reconstruct", "-"], input);
        assert!(out.status.success());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let one = said("0 0\n");
    assert!(
        one.contains("1 point, 0 curves (0 closed, 0 open), 1 unused"),
        "{one}"
    );
    let none = said("");
    assert!(none.contains("0 points, 0 curves"), "{none}");
    // Three distinct points: one closed curve; one duplicate merged.
    let three = said("0 0\n1 0\n2 0.1\n2 0.1\n");
    assert!(three.contains("1 exact duplicate point merged"), "{three}");
    assert!(
        three.contains("4 points, 1 curve (1 closed, 0 open)"),
        "{three}"
    );
    let out = condt(&["triangulate", "-"], "0 0\n1 1\n");
    assert!(out.status.success());
    let chain = String::from_utf8_lossy(&out.stderr);
    assert!(chain.contains("chain of 1 edge is written"), "{chain}");
    let out = condt(&["triangulate", "-"], "0 0\n");
    assert!(out.status.success());
    let lone = String::from_utf8_lossy(&out.stderr);
    assert!(
        lone.contains("no triangles and no edges: 1 distinct point\n"),
        "{lone}"
    );
    // With --edges: an empty edge list is told, a chain is not.
    let out = condt(&["triangulate", "-", "--edges"], "0 0\n");
    let lone = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && out.stdout.is_empty(), "{lone}");
    assert!(lone.contains("no edges: 1 distinct point\n"), "{lone}");
    let out = condt(&["triangulate", "-", "--edges"], "0 0\n1 1\n");
    assert_eq!(String::from_utf8_lossy(&out.stdout), "0 1\n");
    assert!(!String::from_utf8_lossy(&out.stderr).contains("no "));
}

#[test]
fn merged_duplicates_are_told_the_same_way_by_both_commands() {
    // All ten points the same: one distinct point, no edge, so all ten input points are unused.
    let same = "1 1\n".repeat(10);
    // Two duplicates among others: a duplicate of a point on the curve is used with it; the lone
    // point far away is the one unused point.
    // (The outlier filter drops the long edge to 2 2: one open curve 1 0 2.)
    let some = "0 0\n1 0\n0 1\n0 0\n1 0\n2 2\n";
    for (input, merged, distinct, total, unused) in [(&same[..], 9, 1, 10, 10), (some, 2, 4, 6, 1)]
    {
        let note = format!(
            "{merged} exact duplicate points merged into the first point at the same position \
             ({distinct} distinct of {total})"
        );
        for command in ["triangulate", "reconstruct"] {
            let out = condt(&[command, "-"], input);
            assert!(out.status.success());
            let said = String::from_utf8_lossy(&out.stderr);
            assert!(said.contains(&note), "{command}: {said}");
            if command == "reconstruct" {
                let summary = format!("{total} points, ");
                assert!(said.contains(&summary), "{said}");
                assert!(said.contains(&format!("), {unused} unused")), "{said}");
                // A curve lists each point once, under the first of its duplicates.
                for curve in String::from_utf8_lossy(&out.stdout).lines() {
                    let indices: Vec<&str> = curve.split(' ').skip(1).collect();
                    assert!(
                        indices.iter().all(|i| ["0", "1", "2"].contains(i)),
                        "{curve}"
                    );
                }
            }
        }
    }
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
    let scratch = scratch_dir();
    let dir = scratch.path();
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
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes.txt");
    let out = condt(&["reconstruct", input.to_str().unwrap()], "");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let closed = text.lines().filter(|l| l.starts_with("closed")).count();
    let open = text.lines().filter(|l| l.starts_with("open")).count();
    // An ellipse and a square (closed), an arc and a spiral (open).
    assert_eq!((closed, open), (2, 2), "{text}");
}

/// Issue 12, item 3: `.npy` in and out, chosen by the file names; the same results as text.
#[test]
fn npy_points_in_and_npy_indices_out_match_the_text_results() {
    let dir = scratch_dir();
    let text: String = (0..300)
        .map(|i| {
            let t = f64::from(i) * 0.021;
            format!(
                "{} {}\n",
                t.cos() * (1.0 + f64::from(i % 7) * 0.01),
                t.sin()
            )
        })
        .collect();
    let txt = dir.path().join("p.txt");
    std::fs::write(&txt, &text).unwrap();
    let points = condt_io::read_points(&txt).unwrap();
    let npy = dir.path().join("p.npy");
    let mut bytes = Vec::new();
    condt_io::write_npy_points(&mut bytes, &points).unwrap();
    std::fs::write(&npy, &bytes).unwrap();
    let (txt, npy) = (txt.to_str().unwrap(), npy.to_str().unwrap());
    /// The rows of a uint32 `.npy` file of `columns` columns.
    fn npy_rows(path: &Path, columns: usize) -> Vec<Vec<usize>> {
        let bytes = std::fs::read(path).unwrap();
        let header = usize::from(u16::from_le_bytes([bytes[8], bytes[9]])) + 10;
        assert!(bytes[10..header].starts_with(b"{'descr': '<u4', 'fortran_order': False"));
        let values: Vec<usize> = bytes[header..]
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes(b.try_into().unwrap()) as usize)
            .collect();
        values.chunks(columns).map(<[usize]>::to_vec).collect()
    }
    for (command, extra, columns) in [
        ("triangulate", None, 3),
        ("triangulate", Some("--edges"), 2),
        ("reconstruct", None, 2),
    ] {
        // `.edges` gets edges from triangulate too: its triangles go to a `.txt`.
        let ending = if (command, extra) == ("triangulate", None) {
            "txt"
        } else {
            "edges"
        };
        let text_out = dir.path().join(format!("{command}.{ending}"));
        let npy_out = dir.path().join(format!("{command}.npy"));
        let mut args = vec![command, txt, "-o", text_out.to_str().unwrap()];
        args.extend(extra);
        let out = condt(&args, "");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let mut args = vec![command, npy, "-o", npy_out.to_str().unwrap()];
        args.extend(extra);
        let out = condt(&args, "");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let expected = lines(&std::fs::read(&text_out).unwrap());
        assert!(!expected.is_empty());
        assert_eq!(npy_rows(&npy_out, columns), expected, "{command} {extra:?}");
    }
    // A bad .npy file: exit 1 and a message naming it.
    let bad = dir.path().join("bad.npy");
    std::fs::write(&bad, b"\x93NUMPY\x01\x00").unwrap();
    let out = condt(&["triangulate", bad.to_str().unwrap()], "");
    assert_eq!(out.status.code(), Some(1));
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(
        message.contains("bad.npy: the file ends inside its header"),
        "{message}"
    );
}

/// The `--timings` lines of `stderr`: (step, seconds), each line checked to read
/// `condt: time STEP SECONDS s` with an optional note in parentheses.
fn timing_lines(stderr: &[u8]) -> Vec<(String, f64)> {
    String::from_utf8_lossy(stderr)
        .lines()
        .filter_map(|line| line.strip_prefix("condt: time "))
        .map(|rest| {
            let mut words = rest.splitn(4, ' ');
            let step = words.next().unwrap_or_default().to_string();
            assert!(
                !step.is_empty() && step.chars().all(|c| c.is_ascii_lowercase() || c == '-'),
                "{rest}"
            );
            let seconds: f64 = words
                .next()
                .and_then(|s| s.parse().ok())
                .unwrap_or_else(|| panic!("no number in {rest}"));
            assert!(seconds.is_finite() && seconds >= 0.0, "{rest}");
            assert_eq!(words.next(), Some("s"), "{rest}");
            if let Some(note) = words.next() {
                assert!(note.starts_with('(') && note.ends_with(')'), "{rest}");
            }
            (step, seconds)
        })
        .collect()
}

#[test]
fn timings_print_one_parsable_line_per_step_and_change_no_output() {
    let input = data("../../../../data/shapes.txt");
    for (command, extra, expected) in [
        (
            "triangulate",
            &[][..],
            &["read", "triangulation", "write", "notes", "total"][..],
        ),
        (
            "reconstruct",
            &[],
            &[
                "read",
                "earlier-passes",
                "triangulation",
                "proximity",
                "repair",
                "iqr-outliers",
                "repair-again",
                "local-outliers",
                "clumps",
                "given-back",
                "gaps",
                "junctions",
                "crossings",
                "tips",
                "spikes",
                "hooks",
                "tails",
                "detours",
                "curves",
                "other",
                "write",
                "notes",
                "total",
            ],
        ),
        (
            "reconstruct",
            &["--paper"],
            &[
                "read",
                "triangulation",
                "proximity",
                "repair",
                "iqr-outliers",
                "curves",
                "other",
                "write",
                "notes",
                "total",
            ],
        ),
    ] {
        let mut args = vec![command, input.as_str()];
        args.extend(extra);
        let plain = condt(&args, "");
        args.push("--timings");
        let timed = condt(&args, "");
        assert!(
            plain.status.success() && timed.status.success(),
            "{}",
            String::from_utf8_lossy(&timed.stderr)
        );
        assert_eq!(
            plain.stdout, timed.stdout,
            "{args:?}: the result is the same"
        );
        assert!(timing_lines(&plain.stderr).is_empty(), "{args:?}");
        let lines = timing_lines(&timed.stderr);
        let steps: Vec<&str> = lines.iter().map(|(step, _)| step.as_str()).collect();
        assert_eq!(steps, expected, "{args:?}");
        // The steps cover the run: their sum is the total, up to each line's rounding to the
        // microsecond (a diff review: the closing notes were in no step).
        let total = lines.last().unwrap().1;
        let sum: f64 = lines[..lines.len() - 1].iter().map(|(_, s)| s).sum();
        assert!(
            (sum - total).abs() <= 1e-6 * lines.len() as f64,
            "{sum} against {total}"
        );
        // The other messages are still there, the same.
        let other = |err: &[u8]| -> Vec<String> {
            String::from_utf8_lossy(err)
                .lines()
                .filter(|l| !l.starts_with("condt: time "))
                .map(String::from)
                .collect()
        };
        assert_eq!(other(&plain.stderr), other(&timed.stderr), "{args:?}");
    }
}

/// `triangulate` chooses what it writes by the output's name as `reconstruct` does: `.edges`
/// gets edges (as `--edges`), `.txt` or a name without an extension text, `.npy` an array, and a
/// name it cannot write (a drawing, GeoJSON) is refused before anything is read or written, the
/// message naming the extension and what it can write (found by a stress run: `-o t.svg` got
/// triangles as text, `-o tri.edges` without `--edges` got triangles).
#[test]
fn triangulate_writes_what_the_output_name_says_or_refuses_it() {
    let scratch = scratch_dir();
    let dir = scratch.path();
    let square = "0 0\n1 0\n1 1\n0 1\n";
    let edges = condt(&["triangulate", "-", "--edges"], square);
    assert!(edges.status.success());
    let triangles = condt(&["triangulate", "-"], square);
    assert!(triangles.status.success());
    for (name, extra, expected) in [
        ("tri.edges", None, &edges.stdout),
        ("TRI.EDGES", None, &edges.stdout),
        ("both.edges", Some("--edges"), &edges.stdout),
        ("tri.txt", None, &triangles.stdout),
        ("edges.txt", Some("--edges"), &edges.stdout),
        ("plain", None, &triangles.stdout),
    ] {
        let target = dir.join(name);
        let mut args = vec!["triangulate", "-", "-o", target.to_str().unwrap()];
        args.extend(extra);
        let out = condt(&args, square);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(&std::fs::read(&target).unwrap(), expected, "{name}");
    }
    for name in ["t.svg", "t.geojson", "t.json", "t.html", "t.csv", "t.png"] {
        let target = dir.join(name);
        for extra in [None, Some("--edges")] {
            let mut args = vec!["triangulate", "-", "-o", target.to_str().unwrap()];
            args.extend(extra);
            let said = refused(&args);
            let extension = name.rsplit('.').next().unwrap();
            assert!(said.contains(&format!(".{extension}")), "{name}: {said}");
            for can in [".txt", ".edges", ".npy"] {
                assert!(said.contains(can), "{name}: {said}");
            }
            assert!(!target.exists(), "{name}: nothing is written");
        }
    }
    let dotted = dir.join("t.");
    let said = refused(&["triangulate", "-", "-o", dotted.to_str().unwrap()]);
    assert!(
        said.contains("cannot write a name ending in a dot;"),
        "{said}"
    );
    // The help says so.
    let help = String::from_utf8(condt(&["triangulate", "--help"], "").stdout).unwrap();
    assert!(help.contains(".edges"), "{help}");
}

/// A refused number is told as the user typed it, with the option they typed: not as the
/// library's parameter name, not as the float it parsed to, and not as a contradiction with
/// itself when given twice (found by a stress run: `--u nan --u nan` said "--u NaN and --u NaN
/// contradict each other", `--u 1e400` "u = inf", `--iqr -1` "parameter k = -1").
#[test]
fn a_refused_number_is_told_as_typed() {
    for (args, typed) in [
        (&["--u", "nan", "--u", "nan"][..], "--u nan"),
        (&["--u=nan", "--u=nan"], "--u nan"),
        (&["--u", "nan"], "--u nan"),
        (&["--u", "1e400"], "--u 1e400"),
        (&["--u", "2", "--u", "1e400"], "--u 1e400"),
        (&["--u", "-0"], "--u -0"),
        (&["--iqr", "-1"], "--iqr -1"),
        (&["--iqr", "1E999"], "--iqr 1E999"),
        (&["--iqr", "NaN", "--iqr", "NaN"], "--iqr NaN"),
    ] {
        let mut line = vec!["reconstruct", "-"];
        line.extend(args);
        let said = refused(&line);
        assert!(said.contains(typed), "{line:?}: {said}");
        assert!(!said.contains("contradict"), "{line:?}: {said}");
        assert!(!said.contains("parameter k"), "{line:?}: {said}");
        assert!(!said.contains("inf"), "{line:?}: {said}");
        assert!(said.contains("out of range"), "{line:?}: {said}");
    }
    // The same value twice is no contradiction, however it is written; two values are.
    assert_reconstruct_accepts(&[
        &["--u", "2", "--u", "2"],
        &["--u", "2", "--u=2.0"],
        &["--iqr", "1.5", "--iqr", "1.50"],
    ]);
    let said = refused(&["reconstruct", "-", "--u", "2", "--u", "3"]);
    assert!(said.contains("--u 2 and --u 3 contradict"), "{said}");
}

/// `reconstruct --help` says which switches keep small closed curves beside a large one: a
/// closed curve of 6 points needs --no-local-outliers, one of 5 (a regular pentagon turns by
/// 72 degrees at each point, sharper than a curve's passage) --no-clumps too, where its
/// coordinates are written in decimals (a CAD user's review: holes of 5 samples in a part
/// drawn in millimetres with 3 decimals were dropped with --no-local-outliers, which the help
/// said kept them).
#[test]
fn small_closed_curves_are_kept_by_the_switches_the_help_names() {
    let mut text = String::new();
    // A 10 x 6 outline sampled every 0.05, then four rings of 5 and four of 6 points, spaced
    // 0.05 along them, every coordinate written with 3 decimals.
    let side = |from: (f64, f64), step: (f64, f64), count: usize, text: &mut String| {
        for k in 0..count {
            let (x, y) = (from.0 + step.0 * k as f64, from.1 + step.1 * k as f64);
            text.push_str(&format!("{x:.3} {y:.3}\n"));
        }
    };
    side((0.0, 0.0), (0.05, 0.0), 200, &mut text);
    side((10.0, 0.0), (0.0, 0.05), 120, &mut text);
    side((10.0, 6.0), (-0.05, 0.0), 200, &mut text);
    side((0.0, 6.0), (0.0, -0.05), 120, &mut text);
    for (j, n) in [5, 5, 5, 5, 6, 6, 6, 6].into_iter().enumerate() {
        let r = n as f64 * 0.05 / std::f64::consts::TAU;
        let (cx, cy) = (1.0 + 1.1 * j as f64, 3.0);
        for k in 0..n {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            text.push_str(&format!(
                "{:.3} {:.3}\n",
                cx + r * t.cos(),
                cy + r * t.sin()
            ));
        }
    }
    let sizes = |args: &[&str]| {
        let out = condt(&[&["reconstruct", "-", "-q"][..], args].concat(), &text);
        assert!(out.status.success(), "{args:?}");
        let mut sizes: Vec<usize> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(|l| {
                assert!(l.starts_with("closed "), "{l}");
                l.split(' ').count() - 1
            })
            .collect();
        sizes.sort_unstable();
        sizes
    };
    assert_eq!(sizes(&[]), [640]);
    assert_eq!(sizes(&["--no-local-outliers"]), [6, 6, 6, 6, 640]);
    assert_eq!(
        sizes(&["--no-local-outliers", "--no-clumps"]),
        [5, 5, 5, 5, 6, 6, 6, 6, 640]
    );
    let help = String::from_utf8(condt(&["reconstruct", "--help"], "").stdout).unwrap();
    let said: String = help.split_whitespace().collect::<Vec<_>>().join(" ");
    for words in [
        "--no-local-outliers keeps sparsely sampled curves of 3 or 4 points and closed ones of 6,",
        "(closed ones of 5, which turn too sharply at every point for the clumps, with --no-clumps",
    ] {
        assert!(said.contains(words), "{words}: {help}");
    }
}

/// The usage lines of `reconstruct --help` name every option, `--method` among them, as the
/// README's do (found by a stress run).
#[test]
fn the_usage_of_reconstruct_names_method() {
    let help = String::from_utf8(condt(&["reconstruct", "--help"], "").stdout).unwrap();
    let usage = &help[help.find("Usage:").unwrap()..help.find("Example:").unwrap()];
    assert!(usage.contains("[--method condt|nn-crust|crust]"), "{usage}");
    // Every stage's switch, read from the stage table: the usage is written by hand (a new
    // contributor's review: a stage added without its usage line built and passed every test).
    let flags: String = usage.split_whitespace().collect();
    for stage in condt::Stage::ALL {
        if let Some(switch) = stage.switch() {
            let flag = switch.flag;
            assert!(
                flags.contains(&format!("[--[no-]{flag}]")),
                "the usage lacks {stage:?}'s --[no-]{flag}: {usage}"
            );
        }
    }
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
            .unwrap();
    for line in usage.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        assert!(
            readme.contains(line.trim_start()),
            "README lacks the usage line {line:?}"
        );
    }
}

/// The lists of stages written by hand name every stage of the table: README's `--timings` keys
/// and docs/condt.md's table of switches (a contributor's review: a stage left out of them
/// passed every test).
#[test]
fn the_hand_written_stage_lists_name_every_stage() {
    let read = |path: &str| {
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
    };
    let readme = read("../../README.md");
    let start = readme
        .find("`reconstruct` adds the library's own record of each")
        .unwrap();
    let keys: String = readme[start..]
        .split("the\ncurve assembly")
        .next()
        .unwrap()
        .into();
    let condt_md = read("../../docs/condt.md");
    for stage in condt::Stage::ALL {
        if matches!(stage, condt::Stage::NnCrust | condt::Stage::Crust) {
            continue; // baselines, not steps of the pipeline
        }
        let key = stage.key();
        assert!(
            keys.contains(&format!("`{key}`")),
            "README's --timings keys lack `{key}`"
        );
        if let Some(switch) = stage.switch() {
            let flag = format!("`--[no-]{}`", switch.flag);
            assert!(
                condt_md.contains(&flag),
                "docs/condt.md's table lacks {flag}"
            );
        }
    }
}

/// A user review: `--input-format CSV` was taken, `--format SVG`, `--repair MUTUAL` and
/// `--method NN-Crust` refused. Every named value takes any case, with the same output.
#[test]
fn option_values_take_any_case() {
    let input = data("rectangle_crlf_commas.txt");
    for (lower, upper) in [
        (&["--format", "svg"][..], &["--format", "SVG"][..]),
        (&["--repair", "mutual"], &["--repair", "MUTUAL"]),
        (&["--method", "nn-crust"], &["--method", "NN-Crust"]),
        (&["--input-format", "txt"], &["--input-format", "TXT"]),
    ] {
        let run = |extra: &[&str]| {
            let mut args = vec!["reconstruct", input.as_str(), "-q"];
            args.extend_from_slice(extra);
            condt(&args, "")
        };
        let (a, b) = (run(lower), run(upper));
        assert!(a.status.success() && b.status.success(), "{upper:?}: {b:?}");
        assert!(!a.stdout.is_empty());
        assert_eq!(a.stdout, b.stdout, "{upper:?}");
    }
}
