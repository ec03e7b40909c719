//! CSV and GeoJSON point files give the same points, and so the same curves, as the plain
//! format; bad files are refused with their line.

use condt::{reconstruct, Params, Point};
use condt_eval::sample::{sample, Sampling, Shape};
use condt_io::read_points;
use std::process::Command;

/// The binary under test: this build's, or `CONDT_TEST_BIN` (to show a test fails on another).
fn binary() -> std::ffi::OsString {
    std::env::var_os("CONDT_TEST_BIN").unwrap_or_else(|| env!("CARGO_BIN_EXE_condt").into())
}

fn scratch_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("condt-formats-")
        .tempdir()
        .unwrap()
}

fn circle() -> Vec<Point> {
    sample(
        &[Shape::circle(Point::new(1e6, -2e6), 3.0)],
        &Sampling::new(0.3),
    )
    .unwrap()
    .points
}

#[test]
fn csv_geojson_and_plain_files_read_the_same_points() {
    let dir = scratch_dir();
    let points = circle();
    let plain: String = points
        .iter()
        .map(|p| format!("{:?} {:?}\n", p.x, p.y))
        .collect();
    let csv: String = "id,y,x\r\n".to_string()
        + &points
            .iter()
            .enumerate()
            .map(|(k, p)| format!("{k},{:?},{:?}\r\n", p.y, p.x))
            .collect::<String>();
    let (first, rest) = points.split_first().unwrap();
    let multi: Vec<String> = rest
        .iter()
        .map(|p| format!("[{:?},{:?},7]", p.x, p.y))
        .collect();
    let geojson = format!(
        "{{\"type\":\"FeatureCollection\",\"features\":[\n\
         {{\"type\":\"Feature\",\"properties\":{{}},\"geometry\":{{\"type\":\"Point\",\"coordinates\":[{:?},{:?}]}}}},\n\
         {{\"type\":\"Feature\",\"properties\":null,\"geometry\":{{\"type\":\"MultiPoint\",\"coordinates\":[{}]}}}}]}}\n",
        first.x,
        first.y,
        multi.join(",")
    );
    for (name, text) in [("c.txt", plain), ("c.CSV", csv), ("c.geojson", geojson)] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        assert_eq!(read_points(&path).unwrap(), points, "{name}");
        let out = Command::new(binary())
            .arg("reconstruct")
            .arg(&path)
            .arg("--format")
            .arg("edges")
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}");
        let expected: String = reconstruct(&points, &Params::default())
            .unwrap()
            .edges()
            .map(|[a, b]| format!("{a} {b}\n"))
            .collect();
        assert_eq!(String::from_utf8(out.stdout).unwrap(), expected, "{name}");
    }
}

#[test]
fn bad_csv_and_geojson_files_are_refused_by_file_and_line() {
    let dir = scratch_dir();
    for (name, text, message) in [
        (
            "a.csv",
            "x,y\n0,0\n1,oops\n",
            "a.csv:3: cannot read \"oops\"",
        ),
        (
            "b.json",
            "{\"type\":\"Point\",\n\"coordinates\":[1,\"2\"]}",
            "b.json:2: a position",
        ),
        (
            "c.geojson",
            "{\"type\":\"LineString\",\"coordinates\":[]}",
            "c.geojson:1: a \"LineString\"",
        ),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let out = Command::new(binary())
            .arg("reconstruct")
            .arg(&path)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{name}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(stderr.contains(message), "{stderr}");
    }
}

/// Two points too close for the stages to measure beside a far one are named by their lines,
/// as every other error about the file's content is (the library names input positions).
#[test]
fn points_too_close_to_measure_are_named_by_their_lines() {
    let dir = scratch_dir();
    let text = "# survey\nx y\n0 0\n1e-300 0\n\n0 1e-300\n1e10 1e10\n1e10 0\n";
    for (name, content) in [
        ("spread.txt", text.to_string()),
        (
            "spread.csv",
            text.replace("# survey\n", "")
                .replace(' ', ",")
                .replace("\n\n", "\n"),
        ),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, &content).unwrap();
        let out = Command::new(binary())
            .args([
                "reconstruct".as_ref(),
                path.as_os_str(),
                "-o".as_ref(),
                "/dev/null".as_ref(),
            ])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1));
        let message = String::from_utf8_lossy(&out.stderr);
        let (first, second, largest) = if name.ends_with(".txt") {
            (3, 4, 7)
        } else {
            (2, 3, 5)
        };
        assert!(
            message.contains(&format!(
                "{name}:{first}: this point and line {second}'s are closer than 2^-450 times the \
                 largest coordinate (line {largest}'s)"
            )),
            "{message}"
        );
    }
}

/// A `.tsv` file reads as its `.csv` twin, commas for its tabs: quoted names, a byte-order mark,
/// a name with blanks (`elevation (m)`) and one of digits (`2020`) beside x and y; a malformed
/// quote in a later column is refused with the file and line, as in the `.csv` (a user's
/// report: the first four were refused, and `"1"5` read as 15).
#[test]
fn a_tsv_file_reads_as_its_csv_twin() {
    let dir = scratch_dir();
    let condt = |args: &[&str], path: &std::path::Path| {
        Command::new(binary())
            .args(args)
            .arg(path)
            .output()
            .unwrap()
    };
    for (name, tsv) in [
        (
            "quoted",
            "\"name\"\t\"lon\"\t\"lat\"\n\"a\"\t1\t2\n\"b\"\t3\t4\n\"c\"\t5\t1\n",
        ),
        ("bom", "\u{feff}id\tlon\tlat\n1\t1\t2\n2\t3\t4\n3\t5\t1\n"),
        (
            "unit",
            "id\tlon\tlat\televation (m)\n1\t1\t2\t5\n2\t3\t4\t5\n3\t5\t1\t5\n",
        ),
        (
            "year",
            "id\tlon\tlat\t2020\n1\t1\t2\t5\n2\t3\t4\t5\n3\t5\t1\t5\n",
        ),
    ] {
        let tsv_path = dir.path().join(format!("{name}.tsv"));
        let csv_path = dir.path().join(format!("{name}.csv"));
        std::fs::write(&tsv_path, tsv).unwrap();
        std::fs::write(&csv_path, tsv.replace('\t', ",")).unwrap();
        for (args, expected) in [
            (&["triangulate"][..], "1 0 2\n"),
            (&["triangulate", "--edges"][..], "0 1\n0 2\n1 2\n"),
        ] {
            let (out, twin) = (condt(args, &tsv_path), condt(args, &csv_path));
            assert!(out.status.success(), "{name}: {out:?}");
            assert_eq!(String::from_utf8(out.stdout).unwrap(), expected, "{name}");
            assert_eq!(String::from_utf8(twin.stdout).unwrap(), expected, "{name}");
        }
    }
    for (name, tsv, message) in [
        (
            "bad",
            "id\tlon\tlat\na\t\"1\"5\t\"2\"0\nb\t0\t0\nc\t100\t0\n",
            ":2: text after the closing quote of a field",
        ),
        (
            "open",
            "id\tlon\tlat\na\t\"1\t2\nb\t0\t0\nc\t100\t0\n",
            ":2: a quoted field is not closed",
        ),
    ] {
        let args = ["reconstruct", "--paper", "--format", "geojson", "-q"];
        for (ending, text) in [("tsv", tsv.to_string()), ("csv", tsv.replace('\t', ","))] {
            let path = dir.path().join(format!("{name}.{ending}"));
            std::fs::write(&path, text).unwrap();
            let out = condt(&args, &path);
            assert_eq!(out.status.code(), Some(1), "{name}.{ending}: {out:?}");
            let said = String::from_utf8(out.stderr).unwrap();
            assert!(
                said.contains(&format!("{name}.{ending}{message}")),
                "{said}"
            );
        }
    }
}

/// A byte-order mark after the first line that the parallel reader starts a piece at (past
/// byte 1 MiB) is refused with its line from standard input with `--sequential`, from
/// standard input, and from the file: one answer on every path.
#[test]
fn a_byte_order_mark_inside_the_file_is_refused_on_every_path() {
    use std::io::Write;
    let mut text = String::new();
    let mut i = 0u64;
    while text.len() < 5 << 19 {
        text.push_str(&format!("{}.25 {}\n", i, 2 * i + 1));
        i += 1;
    }
    let cut = (1 << 20) + text[1 << 20..].find('\n').unwrap() + 1;
    let line = 1 + text[..cut].matches('\n').count();
    text.insert(cut, '\u{feff}');
    let dir = scratch_dir();
    let file = dir.path().join("bom.txt");
    std::fs::write(&file, &text).unwrap();
    let runs: [(&[&str], bool); 4] = [
        (&["reconstruct", "-", "--sequential"], true),
        (&["reconstruct", "-"], true),
        (&["reconstruct", "FILE", "--sequential"], false),
        (&["triangulate", "FILE"], false),
    ];
    for (args, stdin) in runs {
        let args: Vec<&std::ffi::OsStr> = args
            .iter()
            .map(|a| {
                if *a == "FILE" {
                    file.as_os_str()
                } else {
                    a.as_ref()
                }
            })
            .collect();
        let mut child = Command::new(binary())
            .args(&args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let mut input = child.stdin.take().unwrap();
        if stdin {
            // The run may stop reading at the error.
            if let Err(e) = input.write_all(text.as_bytes()) {
                assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
            }
        }
        drop(input);
        let out = child.wait_with_output().unwrap();
        let said = String::from_utf8_lossy(&out.stderr);
        let name = if stdin {
            "<stdin>".to_string()
        } else {
            file.display().to_string()
        };
        assert_eq!(out.status.code(), Some(1), "{args:?}: {said}");
        assert!(
            said.contains(&format!("{name}:{line}: ")) && said.contains("byte-order mark"),
            "{args:?}: {said}"
        );
    }
}

/// `condt ARGS` with `input` on standard input.
fn condt_with_stdin(args: &[&str], input: &[u8]) -> std::process::Output {
    use std::io::Write;
    let mut child = Command::new(binary())
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut pipe = child.stdin.take().unwrap();
    // The run may stop reading at an error.
    let _ = pipe.write_all(input);
    drop(pipe);
    child.wait_with_output().unwrap()
}

/// `condt reconstruct PATH -o /dev/null`: its exit status and what it said on standard error.
fn reconstruct_to_nowhere(path: &std::path::Path) -> (std::process::ExitStatus, String) {
    let run = condt_with_stdin(
        &["reconstruct", path.to_str().unwrap(), "-o", "/dev/null"],
        b"",
    );
    (
        run.status,
        String::from_utf8_lossy(&run.stderr).into_owned(),
    )
}

/// A CSV table on standard input, which has no name to say it is CSV, is read as CSV with
/// `--input-format csv` (its header followed: `id,lat,lon`), giving what the same file named
/// `.csv` gives; without the option it is read as plain text as before (a GIS review: only the
/// plain reader's `x,y` worked), and its refusal says how to read it as CSV. The option also
/// overrules a file's name.
#[test]
fn csv_on_standard_input_is_read_with_input_format() {
    let points = circle();
    let csv: String = "id,lat,lon\n".to_string()
        + &points
            .iter()
            .enumerate()
            .map(|(k, p)| format!("{k},{:?},{:?}\n", p.y, p.x))
            .collect::<String>();
    let expected: String = reconstruct(&points, &Params::default())
        .unwrap()
        .edges()
        .map(|[a, b]| format!("{a} {b}\n"))
        .collect();
    for args in [
        &[
            "reconstruct",
            "-",
            "--input-format",
            "csv",
            "--format",
            "edges",
        ][..],
        &[
            "reconstruct",
            "--input-format=CSV",
            "-",
            "--format=edges",
            "--sequential",
        ],
    ] {
        let out = condt_with_stdin(args, csv.as_bytes());
        let said = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {said}");
        assert_eq!(String::from_utf8(out.stdout).unwrap(), expected, "{args:?}");
    }
    let out = condt_with_stdin(&["reconstruct", "-", "--format", "edges"], csv.as_bytes());
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains("<stdin>:1: ") && said.contains("--input-format csv"),
        "{said}"
    );
    // A header the plain reader takes as a title, over an index column it refuses on line 2:
    // the hint still names the option, and the index column's names `--input-format node`.
    let indexed = "FID,Shape_X,Shape_Y\n1,0,0\n2,1,0\n3,1,1\n";
    let out = condt_with_stdin(&["reconstruct", "-", "-o", "-"], indexed.as_bytes());
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains("<stdin>:2: ")
            && said.contains("--input-format csv")
            && said.contains("--input-format node"),
        "{said}"
    );
    // A decimal comma keeps its own advice: reading it as CSV would be wrong too.
    let out = condt_with_stdin(&["reconstruct", "-", "-o", "-"], b"1,5 2,5\n3,5 4,5\n");
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("decimal comma") && !said.contains("--input-format"),
        "{said}"
    );
    // `x,y` on standard input was read before, by the plain reader, and still is.
    let plain = "x,y\n0,0\n1,0\n0.5,2\n";
    let out = condt_with_stdin(&["triangulate", "-"], plain.as_bytes());
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0 1 2\n");
    let out = condt_with_stdin(
        &["triangulate", "-", "--input-format", "csv"],
        plain.as_bytes(),
    );
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0 1 2\n");
    // The option overrules a name: a `.txt` holding CSV, a `.csv` holding plain text.
    let dir = scratch_dir();
    for (name, text, format) in [
        ("table.txt", csv.as_str(), "csv"),
        ("plain.csv", "0 0\n1 0 # a comment\n0.5 2\n", "txt"),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let path = path.to_str().unwrap();
        let refused = condt_with_stdin(&["triangulate", path], b"");
        assert_eq!(refused.status.code(), Some(1), "{name}");
        let out = condt_with_stdin(&["triangulate", path, "--input-format", format], b"");
        assert!(out.status.success(), "{name}");
        assert!(!out.stdout.is_empty(), "{name}");
    }
    // An unknown format, or two different ones, is a usage error naming the formats.
    let out = condt_with_stdin(&["triangulate", "-", "--input-format", "xlsx"], b"");
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{said}");
    assert!(said.contains("txt, node, csv, tsv, npy, geojson"), "{said}");
    let out = condt_with_stdin(
        &[
            "triangulate",
            "-",
            "--input-format",
            "csv",
            "--input-format",
            "tsv",
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(2));
}

/// GeoJSON features with a null geometry (and empty Points) were skipped without a word: one
/// note on standard error now says how many and why, not with `--quiet`, and the output is the
/// same as for the document without them.
#[test]
fn null_geometries_are_noted_once_and_not_with_quiet() {
    let points = circle();
    let feature = |p: &Point| {
        format!(
            "{{\"type\":\"Feature\",\"properties\":{{}},\"geometry\":{{\"type\":\"Point\",\"coordinates\":[{:?},{:?}]}}}}",
            p.x, p.y
        )
    };
    let null = "{\"type\":\"Feature\",\"properties\":{\"id\":7},\"geometry\":null}";
    let empty = "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[]}}";
    let collection = |features: Vec<String>| {
        format!(
            "{{\"type\":\"FeatureCollection\",\"features\":[{}]}}",
            features.join(",\n")
        )
    };
    let plain = collection(points.iter().map(feature).collect());
    let mut features: Vec<String> = points.iter().map(feature).collect();
    features.insert(3, null.to_string());
    features.insert(0, null.to_string());
    features.push(empty.to_string());
    let gappy = collection(features);
    for command in [
        &["reconstruct", "-", "--format", "edges"][..],
        &["triangulate", "-"],
    ] {
        let reference = condt_with_stdin(command, plain.as_bytes());
        assert!(reference.status.success());
        assert!(
            !String::from_utf8_lossy(&reference.stderr).contains("skipped"),
            "{command:?}"
        );
        let out = condt_with_stdin(command, gappy.as_bytes());
        assert!(out.status.success(), "{command:?}");
        assert_eq!(out.stdout, reference.stdout, "{command:?}");
        let said = String::from_utf8(out.stderr).unwrap();
        let notes: Vec<&str> = said.lines().filter(|l| l.contains("skipped")).collect();
        assert_eq!(
            notes,
            [
                "condt: <stdin>: skipped 2 features with a null geometry and 1 empty Point or \
              MultiPoint: they hold no point (the points are numbered without them)"
            ],
            "{command:?}: {said}"
        );
        let mut quiet = command.to_vec();
        quiet.push("--quiet");
        let out = condt_with_stdin(&quiet, gappy.as_bytes());
        assert!(out.status.success() && out.stderr.is_empty(), "{quiet:?}");
        assert_eq!(out.stdout, reference.stdout, "{quiet:?}");
    }
}

/// GeoJSON lines on standard input: read one object per line with `--input-format geojsonl`;
/// without it, read as one document as before, the refusal says how to read them.
#[test]
fn geojson_lines_on_standard_input() {
    let lines = "{\"type\":\"Point\",\"coordinates\":[0,0]}\n\
                 {\"type\":\"Point\",\"coordinates\":[1,0]}\n\
                 {\"type\":\"Point\",\"coordinates\":[0.5,2]}\n";
    let out = condt_with_stdin(
        &["triangulate", "-", "--input-format", "geojsonl"],
        lines.as_bytes(),
    );
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0 1 2\n");
    let out = condt_with_stdin(&["triangulate", "-"], lines.as_bytes());
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains("<stdin>:2: trailing characters") && said.contains("--input-format geojsonl"),
        "{said}"
    );
}

/// `--columns X,Y` reads x and y from a CSV's columns by header name or number (ArcGIS's
/// `POINT_X,POINT_Y`, `easting,northing`), the same points as the plain file; a missing column
/// is refused naming the file, the header line and its columns; a file read in another format
/// is a usage error before anything is read.
#[test]
fn columns_choose_the_x_and_y_of_a_csv() {
    let points = circle();
    let expected: String = reconstruct(&points, &Params::default())
        .unwrap()
        .edges()
        .map(|[a, b]| format!("{a} {b}\n"))
        .collect();
    let csv: String = "FID,Shape,POINT_Y,POINT_X\n".to_string()
        + &points
            .iter()
            .enumerate()
            .map(|(k, p)| format!("{k},Point,{:?},{:?}\n", p.y, p.x))
            .collect::<String>();
    let dir = scratch_dir();
    let path = dir.path().join("survey.csv");
    std::fs::write(&path, &csv).unwrap();
    let path = path.to_str().unwrap();
    for columns in ["POINT_X,POINT_Y", "point_x,point_y", "4,3", "4,POINT_Y"] {
        let out = condt_with_stdin(
            &[
                "reconstruct",
                path,
                "--columns",
                columns,
                "--format",
                "edges",
            ],
            b"",
        );
        assert!(out.status.success(), "{columns}: {:?}", out);
        assert_eq!(
            String::from_utf8(out.stdout).unwrap(),
            expected,
            "{columns}"
        );
    }
    // Standard input with --columns is read as CSV.
    let out = condt_with_stdin(
        &[
            "reconstruct",
            "-",
            "--columns=POINT_X,POINT_Y",
            "--format=edges",
        ],
        csv.as_bytes(),
    );
    assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
    // A plain text file of four blank-separated columns (a scanner's `y x z intensity`): the
    // columns by number, or by the names of its first line.
    let scan: String = "Y X Z I\n".to_string()
        + &points
            .iter()
            .map(|p| format!("{:?} {:?} 1.5 80\n", p.y, p.x))
            .collect::<String>();
    let scan_path = dir.path().join("scan.txt");
    std::fs::write(&scan_path, &scan).unwrap();
    for columns in ["2,1", "x,y"] {
        let out = condt_with_stdin(
            &[
                "reconstruct",
                scan_path.to_str().unwrap(),
                "--columns",
                columns,
                "--format=edges",
            ],
            b"",
        );
        assert!(out.status.success(), "{columns}: {out:?}");
        assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
    }
    // Piped in, with columns, it is read as CSV unless stated: the refusal says how.
    let piped = condt_with_stdin(
        &["reconstruct", "-", "--columns", "x,y", "--format=edges"],
        scan.as_bytes(),
    );
    let said = String::from_utf8_lossy(&piped.stderr);
    assert!(said.contains("condt's --input-format txt"), "{said}");
    let stated = condt_with_stdin(
        &[
            "reconstruct",
            "-",
            "--columns=x,y",
            "--input-format=txt",
            "--format=edges",
        ],
        scan.as_bytes(),
    );
    assert_eq!(String::from_utf8(stated.stdout).unwrap(), expected);
    // Without it, ArcGIS's names are read as x and y (no column is named x, y, lon or lat),
    // in whichever order they stand.
    let out = condt_with_stdin(&["reconstruct", path, "--format", "edges"], b"");
    assert!(out.status.success(), "{out:?}");
    assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
    // Names that are neither: no x column, the option named.
    let unnamed = dir.path().join("unnamed.csv");
    std::fs::write(
        &unnamed,
        csv.replacen("POINT_Y,POINT_X", "Shape_Y,Shape_X", 1),
    )
    .unwrap();
    let out = condt_with_stdin(&["triangulate", unnamed.to_str().unwrap()], b"");
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("the header has no x column") && said.contains("--columns X,Y"),
        "{said}"
    );
    let out = condt_with_stdin(&["triangulate", path, "--columns", "easting,northing"], b"");
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains(&format!(
            "{path}:1: no column named \"easting\" (chosen for x) in the header \
             \"FID,Shape,POINT_Y,POINT_X\"; its columns are \"FID\", \"Shape\", \"POINT_Y\", \
             \"POINT_X\""
        )),
        "{said}"
    );
    for (args, words) in [
        (
            &["triangulate", "pts.node", "--columns", "a,b"][..],
            "pts.node is read as node by its name",
        ),
        (
            &[
                "triangulate",
                path,
                "--columns",
                "a,b",
                "--input-format",
                "geojson",
            ],
            "is read as geojson by --input-format",
        ),
        (
            &["triangulate", path, "--columns", "a"],
            "expected two columns",
        ),
        (
            &["triangulate", path, "--columns", "2,2"],
            "the same column",
        ),
        (
            &["triangulate", path, "--columns", "0,1"],
            "numbered from 1",
        ),
    ] {
        let out = condt_with_stdin(args, b"");
        let said = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {said}");
        assert!(said.contains(words), "{args:?}: {said}");
    }
}

/// `--columns` for an input read as a NumPy array or GeoJSON (by its name or
/// `--input-format`) says that columns apply to CSV, TSV and plain text only: `--input-format csv`, which
/// the refusal of a text file suggests, cannot help there.
#[test]
fn columns_for_an_array_or_geojson_say_they_apply_to_tables_only() {
    for (args, words) in [
        (
            &["triangulate", "pts.npy", "--columns", "1,2"][..],
            "pts.npy is read as npy by its name: columns apply to CSV, TSV and plain text input only",
        ),
        (
            &["reconstruct", "sites.GeoJSON", "--columns", "1,2"][..],
            "sites.GeoJSON is read as geojson by its name: columns apply to CSV, TSV and plain \
             text input only",
        ),
        (
            &["triangulate", "sites.geojsonl", "--columns", "1,2"][..],
            "read as geojsonl by its name: columns apply to CSV, TSV and plain text input only",
        ),
        (
            &[
                "triangulate",
                "-",
                "--columns",
                "1,2",
                "--input-format",
                "npy",
            ][..],
            "<stdin> is read as npy by --input-format: columns apply to CSV, TSV and plain text input only",
        ),
    ] {
        let out = condt_with_stdin(args, b"");
        let said = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {said}");
        assert!(said.contains(words), "{args:?}: {said}");
        assert!(!said.contains("--input-format csv"), "{args:?}: {said}");
    }
    // A .node file may be a CSV table under another name: there the advice stands.
    let out = condt_with_stdin(&["triangulate", "pts.node", "--columns", "1,2"], b"");
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("--input-format csv reads it as CSV"),
        "{said}"
    );
}

/// `--columns` given twice is taken once when both choose the same columns as the header
/// lookup finds them (names without case and blanks around them), and refused otherwise.
#[test]
fn columns_given_twice_are_compared_as_the_header_lookup_compares() {
    let csv = b"FID,POINT_X,POINT_Y\n0,0,0\n1,1,0\n2,0.5,2\n";
    let out = condt_with_stdin(
        &[
            "triangulate",
            "-",
            "--columns",
            "POINT_X,POINT_Y",
            "--columns",
            " point_x , Point_Y",
        ],
        csv,
    );
    assert!(out.status.success(), "{out:?}");
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0 1 2\n");
    let out = condt_with_stdin(
        &[
            "triangulate",
            "-",
            "--columns",
            "POINT_X,POINT_Y",
            "--columns",
            "POINT_Y,POINT_X",
        ],
        csv,
    );
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{said}");
    assert!(
        said.contains("--columns POINT_X,POINT_Y and --columns POINT_Y,POINT_X contradict"),
        "{said}"
    );
}

/// GeoJSON lines in a file named `.json` are read as one document; the refusal names
/// `--input-format geojsonl`, which reads them.
#[test]
fn geojson_lines_in_a_json_file_are_told_of_geojsonl() {
    let dir = scratch_dir();
    let path = dir.path().join("sites.json");
    std::fs::write(
        &path,
        "{\"type\":\"Point\",\"coordinates\":[0,0]}\n\
         {\"type\":\"Point\",\"coordinates\":[1,0]}\n\
         {\"type\":\"Point\",\"coordinates\":[0.5,2]}\n",
    )
    .unwrap();
    let path = path.to_str().unwrap();
    let out = condt_with_stdin(&["triangulate", path], b"");
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{said}");
    assert!(
        said.contains(&format!("{path}:2: trailing characters"))
            && said.contains("--input-format geojsonl"),
        "{said}"
    );
    let out = condt_with_stdin(&["triangulate", path, "--input-format", "geojsonl"], b"");
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0 1 2\n");
}

/// A document whose own `crs` follows its features: the output carries the document's, and
/// the note on a feature's other crs says so (a GIS user's review: it said the first one read,
/// the feature's, was kept).
#[test]
fn a_document_crs_after_its_features_is_the_one_kept_and_noted_so() {
    let dir = scratch_dir();
    let input = dir.path().join("crs_after.geojson");
    let output = dir.path().join("out.geojson");
    std::fs::write(
        &input,
        "{\"type\":\"FeatureCollection\",\"features\":[\n\
         {\"type\":\"Feature\",\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"EPSG:32633\"}},\
         \"properties\":{},\"geometry\":{\"type\":\"MultiPoint\",\"coordinates\":\
         [[500000,4500000],[500010,4500000],[500020,4500000]]}}],\n\
         \"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"EPSG:32634\"}}}\n",
    )
    .unwrap();
    let out = Command::new(binary())
        .arg("reconstruct")
        .arg(&input)
        .arg("-o")
        .arg(&output)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}");
    assert!(
        said.contains(":2: this crs differs from the one kept (the document's own"),
        "{said}"
    );
    let written = std::fs::read_to_string(&output).unwrap();
    assert!(
        written.contains("EPSG:32634") && !written.contains("EPSG:32633"),
        "{written}"
    );
}

/// A GeoJSON sequence whose later record gives another crs: a note on standard error names
/// the file and the line, and `--quiet` leaves it out; the points are read all the same.
#[test]
fn a_later_crs_of_a_geojson_sequence_is_noted() {
    let lines = "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":\
                 {\"name\":\"EPSG:32632\"}},\"features\":[]}\n\
                 {\"type\":\"Point\",\"coordinates\":[0,0]}\n\
                 {\"type\":\"Point\",\"coordinates\":[1,0]}\n\
                 {\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":\
                 {\"name\":\"EPSG:2056\"}},\"features\":[{\"type\":\"Feature\",\"properties\":{},\
                 \"geometry\":{\"type\":\"Point\",\"coordinates\":[0.5,2]}}]}\n";
    for command in ["triangulate", "reconstruct"] {
        let out = condt_with_stdin(
            &[command, "-", "--input-format", "geojsonl"],
            lines.as_bytes(),
        );
        let said = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{said}");
        assert!(
            said.contains("condt: <stdin>:4: this crs differs from the one kept"),
            "{command}: {said}"
        );
        let out = condt_with_stdin(
            &[command, "-", "--input-format", "geojsonl", "-q"],
            lines.as_bytes(),
        );
        assert!(out.status.success() && out.stderr.is_empty(), "{out:?}");
    }
}

/// A GeoJSON sequence (RFC 8142: a record separator before each text) on standard input is told
/// by its leading record separator, as a document is by its `{`; it was read as text and refused
/// with the decimal comma's advice.
#[test]
fn a_geojson_sequence_on_standard_input_is_told_by_its_record_separator() {
    let sequence = "\u{1e}{\"type\":\"Point\",\"coordinates\":[0,0]}\n\
                    \u{1e}{\"type\":\"Point\",\"coordinates\":[1,0]}\n\
                    \u{1e}{\"type\":\"Point\",\"coordinates\":[0.5,2]}\n";
    let out = condt_with_stdin(&["triangulate", "-"], sequence.as_bytes());
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}");
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "0 1 2\n");
}

/// A file the reader cannot read as its name says is told what it is and how to read it, where
/// that can be known: an array or GeoJSON under a name without a format's ending is read by its
/// content (a shell's `<(...)`, `/dev/stdin`); an array under a text name is refused naming `.npy`; a
/// JSON array, a TSV header of commas, a CSV header of spaces and a header naming x twice each
/// get their advice.
#[test]
fn files_read_in_another_format_than_they_hold_are_told_what_they_are() {
    let dir = scratch_dir();
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }";
    let padded = format!("{header:<117}\n");
    npy.extend_from_slice(&(padded.len() as u16).to_le_bytes());
    npy.extend_from_slice(padded.as_bytes());
    for v in [0.0f64, 0.0, 1.0, 0.0, 0.0, 1.0] {
        npy.extend_from_slice(&v.to_le_bytes());
    }
    let unnamed = dir.path().join("points");
    std::fs::write(&unnamed, &npy).unwrap();
    let out = condt_with_stdin(&["reconstruct", unnamed.to_str().unwrap(), "-q"], b"");
    assert!(out.status.success(), "{out:?}");
    assert_eq!(String::from_utf8(out.stdout).unwrap(), "closed 0 1 2\n");
    // GeoJSON so too (a user review: it was read as text and refused at its first line), a
    // document or a sequence, under no ending or one of no format.
    let document = r#"{"type":"MultiPoint","coordinates":[[0,0],[1,0],[0,1]]}"#;
    let sequence = "\u{1e}{\"type\":\"Point\",\"coordinates\":[0,0]}\n\u{1e}{\"type\":\"Point\",\"coordinates\":[1,0]}\n\u{1e}{\"type\":\"Point\",\"coordinates\":[0,1]}\n";
    for (name, content) in [("doc", document), ("seq", sequence), ("doc.dat", document)] {
        let path = dir.path().join(name);
        std::fs::write(&path, content).unwrap();
        let out = condt_with_stdin(&["reconstruct", path.to_str().unwrap(), "-q"], b"");
        assert!(out.status.success(), "{name}: {out:?}");
        assert_eq!(
            String::from_utf8(out.stdout).unwrap(),
            "closed 0 1 2\n",
            "{name}"
        );
    }
    let texty = dir.path().join("points.txt");
    std::fs::write(&texty, &npy).unwrap();
    let refused = |path: &std::path::Path, content: &[u8], extra: &[&str]| {
        std::fs::write(path, content).unwrap();
        let mut args = vec!["reconstruct", path.to_str().unwrap()];
        args.extend_from_slice(extra);
        let out = condt_with_stdin(&args, b"");
        assert_eq!(out.status.code(), Some(1), "{out:?}");
        String::from_utf8(out.stderr).unwrap()
    };
    let said = refused(&texty, &npy, &[]);
    assert!(
        said.contains(
            "a NumPy .npy array (by its magic bytes), but read as txt by its name: name it *.npy"
        ),
        "{said}"
    );
    let said = refused(&texty, &npy, &["--input-format", "csv"]);
    assert!(said.contains("state condt's --input-format npy"), "{said}");
    let said = refused(
        &dir.path().join("a.txt"),
        b"\n[{\"type\": \"Point\"}]\n",
        &[],
    );
    assert!(
        said.contains("a.txt:2: a JSON array, which is no point file"),
        "{said}"
    );
    // GeoJSON under a text name is told by what it looks like (a hostile-input review: the
    // refusal spoke of separators and decimal commas).
    for (file, content) in [("g.txt", document), ("g.TXT", sequence)] {
        let said = refused(&dir.path().join(file), content.as_bytes(), &[]);
        assert!(
            said.contains(&format!("{file}:1: "))
                && said.contains("the file starts as GeoJSON does")
                && said.contains("--input-format geojson"),
            "{said}"
        );
    }
    let said = refused(&dir.path().join("t.tsv"), b"x,y\n0,0\n1,0\n", &[]);
    assert!(
        said.contains("t.tsv:1: ") && said.contains("split at tabs"),
        "{said}"
    );
    // A .tsv header of spaces is told of tabs too, not of commas.
    let said = refused(&dir.path().join("sp.tsv"), b"x y\n0 0\n1 0\n", &[]);
    assert!(
        said.contains("split at tabs") && !said.contains("at commas"),
        "{said}"
    );
    let said = refused(&dir.path().join("s.csv"), b"x y\n0 0\n1 0\n", &[]);
    assert!(
        said.contains("s.csv:1: ") && said.contains("name the file *.txt"),
        "{said}"
    );
    let said = refused(&dir.path().join("d.csv"), b"X,Y,lon,lat\n0,0,5,5\n", &[]);
    assert!(
        said.contains("two columns (1 and 3)") && said.contains("--columns X,Y"),
        "{said}"
    );
}

/// A GIS review: a CSV of UTM metres gave a GeoJSON output without a crs, which GDAL reads as
/// longitude and latitude, and no option could name one. `--crs` names it for any input, in
/// place of a GeoJSON input's own; it is refused for another output format.
#[test]
fn crs_names_the_reference_system_of_a_geojson_output() {
    let dir = scratch_dir();
    let csv = dir.path().join("utm.csv");
    std::fs::write(
        &csv,
        "easting,northing\n500000,4000000\n500010,4000000\n500005,4000010\n",
    )
    .unwrap();
    let out = dir.path().join("utm.geojson");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "reconstruct",
            csv.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        condt_with_stdin(&args, b"")
    };
    // Without `--crs`, metres that no longitude and latitude can be get a note (a scan
    // user's review: the output went out silently); not with `--crs` or `--quiet`.
    let note = "are no longitude and latitude, which GeoJSON readers take them for";
    let done = run(&[]);
    assert!(done.status.success(), "{done:?}");
    let said = String::from_utf8_lossy(&done.stderr);
    assert!(
        said.contains(note) && said.contains("(500000, 4000000)"),
        "{said}"
    );
    let quiet = run(&["-q"]);
    assert!(
        quiet.status.success() && quiet.stderr.is_empty(),
        "{quiet:?}"
    );
    let done = run(&["--crs", "EPSG:32632"]);
    assert!(done.status.success(), "{done:?}");
    assert!(!String::from_utf8_lossy(&done.stderr).contains(note));
    let degrees = dir.path().join("degrees.csv");
    std::fs::write(&degrees, "lon,lat\n-179.5,-89.5\n180,-89.5\n0.5,90\n").unwrap();
    let plain = condt_with_stdin(
        &[
            "reconstruct",
            degrees.to_str().unwrap(),
            "-o",
            dir.path().join("degrees.geojson").to_str().unwrap(),
        ],
        b"",
    );
    assert!(plain.status.success(), "{plain:?}");
    assert!(!String::from_utf8_lossy(&plain.stderr).contains(note));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.starts_with(
            r#"{"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},"#
        ),
        "{text}"
    );
    let object = r#"{"type":"name","properties":{"name":"EPSG:2056"}}"#;
    assert!(run(&["--crs", object]).status.success());
    assert!(std::fs::read_to_string(&out).unwrap().contains(object));
    // Instead of a GeoJSON input's own.
    let geojson = dir.path().join("in.geojson");
    std::fs::write(
        &geojson,
        r#"{"type":"MultiPoint","crs":{"type":"name","properties":{"name":"EPSG:4326"}},"coordinates":[[0,0],[1,0],[0.5,1]]}"#,
    )
    .unwrap();
    let done = condt_with_stdin(
        &[
            "reconstruct",
            geojson.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--crs",
            "EPSG:3857",
        ],
        b"",
    );
    assert!(done.status.success(), "{done:?}");
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.contains("EPSG::3857") && !text.contains("EPSG:4326"),
        "{text}"
    );
    // Refused, with its reason, before anything is read or written.
    for (extra, words) in [
        (&["--crs", "{\"type\":"][..], "is not one JSON object"),
        (&["--crs", "[1,2]"][..], "is JSON but neither"),
        (&["--crs", "4326"][..], "is JSON but neither"),
        // PROJJSON, which GDAL reads back as longitude and latitude (a GIS analyst's review).
        (
            &[
                "--crs",
                r#"{"type":"ProjectedCRS","name":"WGS 84 / UTM zone 32N"}"#,
            ][..],
            "PROJJSON",
        ),
        (
            &["--crs", "EPSG:32632", "--format", "txt"][..],
            "GeoJSON output",
        ),
        (
            &["--crs", "EPSG:32632", "--crs", "EPSG:2056"][..],
            "contradict",
        ),
    ] {
        let refused = run(extra);
        assert_eq!(refused.status.code(), Some(2), "{extra:?}");
        assert!(
            String::from_utf8_lossy(&refused.stderr).contains(words),
            "{extra:?}"
        );
    }
}

/// A user review: an input's crs member went on as written whatever it held, while Python's
/// `to_geojson(crs=...)` took the same text as `--crs` does. Both now read it as `--crs`: an
/// object and `null` as written, a string as the name it holds, anything else left out (noted).
#[test]
fn a_geojson_inputs_crs_member_goes_on_as_crs_would_take_it() {
    let dir = scratch_dir();
    let input = dir.path().join("in.geojson");
    let out = dir.path().join("out.geojson");
    for (member, carried, noted) in [
        ("null", Some("\"crs\":null,"), false),
        (
            "\"EPSG:3857\"",
            Some(r#""crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::3857"}},"#),
            false,
        ),
        ("{}", Some("\"crs\":{},"), false),
        ("[1,2]", None, true),
    ] {
        std::fs::write(
            &input,
            format!(
                r#"{{"type":"MultiPoint","crs":{member},"coordinates":[[0,0],[1,0],[0.5,1]]}}"#
            ),
        )
        .unwrap();
        let done = condt_with_stdin(
            &[
                "reconstruct",
                input.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ],
            b"",
        );
        assert!(done.status.success(), "{member}: {done:?}");
        let text = std::fs::read_to_string(&out).unwrap();
        match carried {
            Some(written) => assert!(text.contains(written), "{member}: {text}"),
            None => assert!(!text.contains("\"crs\""), "{member}: {text}"),
        }
        let said = String::from_utf8_lossy(&done.stderr);
        assert_eq!(said.contains("its crs member"), noted, "{member}: {said}");
    }
}

/// A ring of 40 points 1 km around (`lon`, `lat`), as longitudes and latitudes: its metres
/// turned into degrees on a sphere, so that on the ground it is a circle.
fn ring_in_degrees(lon: f64, lat: f64) -> Vec<(f64, f64)> {
    let metres_per_degree = 6_371_008.8_f64.to_radians();
    (0..40)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::TAU / 40.0;
            let (east, north) = (1000.0 * t.cos(), 1000.0 * t.sin());
            let y = lat + north / metres_per_degree;
            let x = lon + east / (metres_per_degree * y.to_radians().cos());
            // Wrapped into [-180, 180), as a GIS writes them.
            ((x + 180.0).rem_euclid(360.0) - 180.0, y)
        })
        .collect()
}

/// A GIS user's review: longitudes and latitudes read as plane coordinates without a word,
/// though at 60 to 70 degrees north a fjord 2 spacings wide came back cut off by a chord in
/// degrees and whole in metres, and a coast across the antimeridian came back in two pieces.
/// An input that says it is in degrees (a header naming lon and lat, `--columns` choosing
/// them, GeoJSON without a projected crs) gets a note giving the stretch where it exceeds 5 %,
/// and one where points lie on both sides of the antimeridian; coordinates named otherwise, or
/// near the equator, get none, and `--quiet` silences both.
#[test]
fn longitudes_and_latitudes_are_noted_as_degrees_where_it_matters() {
    let dir = scratch_dir();
    let stretch = "longitudes and latitudes are read as plane coordinates";
    let antimeridian = "on both sides of the antimeridian";
    let write_csv = |name: &str, header: &str, ring: &[(f64, f64)]| {
        let path = dir.path().join(name);
        let rows: String = ring.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
        std::fs::write(&path, format!("{header}\n{rows}")).unwrap();
        path
    };
    let stderr_of = |path: &std::path::Path, extra: &[&str]| {
        let mut args = vec!["reconstruct", path.to_str().unwrap(), "-o", "/dev/null"];
        args.extend_from_slice(extra);
        let run = condt_with_stdin(&args, b"");
        assert!(run.status.success(), "{run:?}");
        String::from_utf8(run.stderr).unwrap()
    };
    let north = ring_in_degrees(25.0, 65.0);
    let said = stderr_of(&write_csv("north.csv", "lon,lat", &north), &[]);
    // cos(65.009 degrees) = 0.4225: 2.37 times.
    assert!(
        said.contains(&format!("{stretch}: at latitude 65,"))
            && said.contains("a degree of longitude is 0.42 of one of latitude")
            && said.contains("counts 2.4 times as long")
            && said.contains("(a UTM zone)")
            && !said.contains(antimeridian),
        "{said}"
    );
    let quiet = stderr_of(&write_csv("north_q.csv", "lon,lat", &north), &["-q"]);
    assert!(quiet.is_empty(), "{quiet}");
    // The same numbers under x and y: nothing says they are degrees.
    let said = stderr_of(&write_csv("plane.csv", "x,y", &north), &[]);
    assert!(!said.contains(stretch), "{said}");
    // Chosen by name among other columns; a plain file's header names them too.
    let both: Vec<String> = north
        .iter()
        .map(|(x, y)| format!("{x},{y},{x},{y}"))
        .collect();
    let path = dir.path().join("both.csv");
    std::fs::write(
        &path,
        format!("X,Y,Longitude,Latitude\n{}\n", both.join("\n")),
    )
    .unwrap();
    let said = stderr_of(&path, &["--columns", "Longitude,Latitude"]);
    assert!(said.contains(stretch), "{said}");
    let said = stderr_of(&path, &["--columns", "X,Y"]);
    assert!(!said.contains(stretch), "{said}");
    let plain = dir.path().join("north.txt");
    let rows: String = north.iter().map(|(x, y)| format!("{x} {y}\n")).collect();
    std::fs::write(&plain, format!("lon lat\n{rows}")).unwrap();
    assert!(stderr_of(&plain, &[]).contains(stretch));
    // Near the equator the stretch is under 5 %: no note.
    let said = stderr_of(
        &write_csv("equator.csv", "lon,lat", &ring_in_degrees(25.0, 10.0)),
        &[],
    );
    assert!(!said.contains(stretch), "{said}");
    // GeoJSON: degrees without a crs or with CRS84, not with a projected one.
    let coordinates: Vec<String> = north.iter().map(|(x, y)| format!("[{x},{y}]")).collect();
    for (crs, noted) in [
        ("", true),
        (
            r#""crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:OGC:1.3:CRS84"}},"#,
            true,
        ),
        (
            r#""crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32635"}},"#,
            false,
        ),
    ] {
        let path = dir.path().join("north.geojson");
        std::fs::write(
            &path,
            format!(
                r#"{{"type":"MultiPoint",{crs}"coordinates":[{}]}}"#,
                coordinates.join(",")
            ),
        )
        .unwrap();
        let said = stderr_of(&path, &[]);
        assert_eq!(said.contains(stretch), noted, "{crs}: {said}");
    }
    // A ring around the antimeridian comes out in two pieces, and the note says why.
    let across = ring_in_degrees(180.0, 65.0);
    assert!(across.iter().any(|p| p.0 > 179.9) && across.iter().any(|p| p.0 < -179.9));
    let said = stderr_of(&write_csv("across.csv", "lon,lat", &across), &[]);
    assert!(
        said.contains(antimeridian)
            && said.contains("add 360 to the negative longitudes")
            && said.contains("2 curves (0 closed, 2 open)"),
        "{said}"
    );
    // Sampled coarsely, no point within a degree of either side (a low-resolution coast, fixes
    // hours apart): the same (it was silent: a diff review). Away from it, no note.
    let coarse = |lon: f64| -> Vec<(f64, f64)> {
        (0..12)
            .map(|k| {
                let t = f64::from(k) * std::f64::consts::TAU / 12.0;
                let x = lon + 10.0 * t.cos() + 1.5;
                (((x + 180.0).rem_euclid(360.0)) - 180.0, 10.0 * t.sin())
            })
            .collect()
    };
    let sparse = coarse(180.0);
    assert!(sparse.iter().all(|p| p.0.abs() < 179.0), "{sparse:?}");
    let said = stderr_of(&write_csv("sparse.csv", "lon,lat", &sparse), &[]);
    assert!(said.contains(antimeridian), "{said}");
    let said = stderr_of(&write_csv("pacific.csv", "lon,lat", &coarse(150.0)), &[]);
    assert!(!said.contains(antimeridian), "{said}");
    // As it says: shifted, the ring is whole (and the note gone).
    let shifted: Vec<(f64, f64)> = across
        .iter()
        .map(|&(x, y)| (if x < 0.0 { x + 360.0 } else { x }, y))
        .collect();
    let said = stderr_of(&write_csv("shifted.csv", "lon,lat", &shifted), &[]);
    assert!(
        !said.contains(antimeridian) && said.contains("1 curve (1 closed, 0 open)"),
        "{said}"
    );
    // Past 180 the longitudes are still degrees, stretched as before the shift (the note on
    // the stretch went with the shift: this review).
    assert!(
        said.contains(&format!("{stretch}: at latitude 65,")) && said.contains("2.4 times"),
        "{said}"
    );
}

/// Longitudes beyond 90 under a `lat` name, with every latitude within 90: the columns were
/// swapped (a GIS user's review: a lat,lon export under a lon,lat header read as its mirror
/// image, silently but for a GeoJSON output's note about projected metres).
#[test]
fn swapped_longitude_and_latitude_columns_are_noted() {
    let dir = scratch_dir();
    let ring = ring_in_degrees(120.0, 65.0);
    let rows: String = ring.iter().map(|(x, y)| format!("{y},{x}\n")).collect();
    let path = dir.path().join("ring.csv");
    std::fs::write(&path, format!("lon,lat\n{rows}")).unwrap();
    let (status, said) = reconstruct_to_nowhere(&path);
    assert!(
        status.success()
            && said.contains("are they written latitude first (swapped columns)?")
            && said.contains("by its header's names"),
        "{said}"
    );
    // GeoJSON written latitude first has neither names nor columns: the note said it had
    // ("its coordinates are named longitude and latitude", "are the columns swapped").
    let positions: Vec<String> = ring.iter().map(|(x, y)| format!("[{y},{x}]")).collect();
    let json = dir.path().join("ring.geojson");
    std::fs::write(
        &json,
        format!(
            r#"{{"type":"MultiPoint","coordinates":[{}]}}"#,
            positions.join(",")
        ),
    )
    .unwrap();
    let run = condt_with_stdin(
        &["reconstruct", json.to_str().unwrap(), "-o", "/dev/null"],
        b"",
    );
    let said = String::from_utf8_lossy(&run.stderr);
    assert!(
        status.success()
            && said.contains("or as GeoJSON's are, longitude first")
            && said.contains("written latitude first")
            && !said.contains("are named longitude"),
        "{said}"
    );
    // The right way round, no such note.
    let rows: String = ring.iter().map(|(x, y)| format!("{y},{x}\n")).collect();
    std::fs::write(&path, format!("lat,lon\n{rows}")).unwrap();
    let (status, said) = reconstruct_to_nowhere(&path);
    assert!(
        status.success() && !said.contains("columns swapped"),
        "{said}"
    );
}

/// The help says what the stretch compares as the note and README.md do: an east-west gap in
/// degrees against a north-south one of the same metres (it said "as long as on the ground",
/// a length that a gap in degrees does not have: this review).
#[test]
fn the_help_compares_the_stretch_as_the_note_does() {
    let out = condt_with_stdin(&["--help"], b"");
    let help = String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        help.contains(
            "an east-west gap counts 1/cos(latitude) times as long as a north-south one of the \
             same metres (2.4 at 65 degrees)"
        ),
        "{help}"
    );
}

/// GeoJSON without a crs member is taken for longitudes and latitudes (RFC 7946), so a drawing's
/// coordinates in it were told of latitudes and swapped columns with no word on why or how to
/// say otherwise (this review). The notes now say both; with `"crs": null` they go; a CSV's
/// header, which says degrees itself, gets no such line.
#[test]
fn geojson_drawings_are_told_how_to_say_so() {
    let dir = scratch_dir();
    let hint = "GeoJSON without a crs member is in longitude and latitude (RFC 7946)";
    // A ring drawn in a box of 100 by 80, and one in 80 by 160 (past 90 on y: "swapped").
    let ring = |cx: f64, cy: f64, r: f64| -> Vec<String> {
        (0..60)
            .map(|k| {
                let t = f64::from(k) * std::f64::consts::TAU / 60.0;
                format!("[{},{}]", cx + r * t.cos(), cy + r * t.sin())
            })
            .collect()
    };
    for (name, positions, crs, noted) in [
        ("wide.geojson", ring(50.0, 40.0, 38.0), "", true),
        ("tall.geojson", ring(40.0, 80.0, 38.0), "", true),
        (
            "wide_null.geojson",
            ring(50.0, 40.0, 38.0),
            r#""crs":null,"#,
            false,
        ),
        (
            "tall_null.geojson",
            ring(40.0, 80.0, 38.0),
            r#""crs":null,"#,
            false,
        ),
    ] {
        let path = dir.path().join(name);
        std::fs::write(
            &path,
            format!(
                r#"{{"type":"MultiPoint",{crs}"coordinates":[{}]}}"#,
                positions.join(",")
            ),
        )
        .unwrap();
        let (status, said) = reconstruct_to_nowhere(&path);
        assert!(status.success(), "{name}: {said}");
        assert_eq!(said.contains(hint), noted, "{name}: {said}");
        assert_eq!(
            said.contains("`\"crs\": null` in the file"),
            noted,
            "{name}: {said}"
        );
        assert_eq!(
            said.contains("latitude beyond 90") || said.contains("read as plane coordinates"),
            noted,
            "{name}: {said}"
        );
    }
    let path = dir.path().join("wide.csv");
    let rows: String = ring(50.0, 40.0, 38.0)
        .iter()
        .map(|p| format!("{}\n", p.trim_matches(['[', ']'])))
        .collect();
    std::fs::write(&path, format!("lon,lat\n{rows}")).unwrap();
    let (_, said) = reconstruct_to_nowhere(&path);
    assert!(
        said.contains("read as plane coordinates") && !said.contains(hint),
        "{said}"
    );
}

/// At a pole a degree of longitude is no length at all: a track that reaches latitude 90 (the
/// pole itself, or within 0.6 degrees of it) is told the stretch is over 100 times, not given
/// the ratio of a cosine of nearly zero ("0.00", "16331239353195370.0 times": this review).
#[test]
fn the_stretch_at_a_pole_is_said_in_words() {
    let dir = scratch_dir();
    // A ring of 36 fixes at latitude 89.9 (11 km around the pole) and the pole itself.
    let mut rows: String = (0..36)
        .map(|k| format!("{},89.9\n", f64::from(k * 10 - 180)))
        .collect();
    rows += "0,90\n";
    let path = dir.path().join("pole.csv");
    std::fs::write(&path, format!("lon,lat\n{rows}")).unwrap();
    let (status, said) = reconstruct_to_nowhere(&path);
    assert!(
        status.success()
            && said.contains("at latitude 90, the points' farthest")
            && said.contains("a degree of longitude is under 0.01 of one of latitude")
            && said.contains("counts over 100 times as long")
            && said.contains("(a polar stereographic projection)"),
        "{said}"
    );
    // 10 degrees away, still a number: 1 / cos(80 degrees) = 5.76.
    let rows: String = (0..36)
        .map(|k| format!("{},80\n", f64::from(k * 10 - 180)))
        .collect();
    std::fs::write(&path, format!("lon,lat\n{rows}")).unwrap();
    let (_, said) = reconstruct_to_nowhere(&path);
    assert!(
        said.contains("is 0.17 of one of latitude") && said.contains("counts 5.8 times"),
        "{said}"
    );
}

/// A GIS user's review: a shapefile's parts and a GPX track, fed by mistake, were refused as
/// "not UTF-8 text", a control character, `--columns` advice or `cannot read "<?xml" as a
/// number`. By their names' endings the refusal now says what the file is and how to export
/// its points; a file so named that reads as points is read, and a stated format keeps the
/// reader's own message.
#[test]
fn gis_files_condt_does_not_read_are_named_with_an_export() {
    let dir = scratch_dir();
    // A dBase header (version 3, a date, 2 records), a shapefile's header (file code 9994,
    // big-endian), a projection's WKT and a GPX document.
    let mut dbf = vec![3u8, 124, 5, 7, 2, 0, 0, 0, 97, 0, 39, 0];
    dbf.extend([0u8; 20]);
    dbf.extend(b"LON\0\0\0\0\0\0\0\0N\0\0\0\0\x13\x0b");
    let mut shp = vec![0u8, 0, 0x27, 0x0a];
    shp.extend([0u8; 20]);
    shp.extend([0u8, 0, 0, 50, 0xe8, 3, 0, 0, 1, 0, 0, 0]);
    let cases: [(&str, &[u8], &str); 5] = [
        ("parcels.dbf", &dbf, "a part of a shapefile"),
        (
            "parcels.shp",
            &shp,
            "a shapefile, which condt does not read",
        ),
        (
            "parcels.PRJ",
            br#"GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984"],UNIT["Degree",0.0174532925199433]]"#,
            "a part of a shapefile",
        ),
        (
            "ride.gpx",
            b"<?xml version=\"1.0\"?>\n<gpx><trk><trkseg><trkpt lat=\"65\" lon=\"25\"/>\
              </trkseg></trk></gpx>\n",
            "GPX, which condt does not read",
        ),
        (
            "coast.kml",
            b"<?xml version=\"1.0\"?>\n<kml></kml>\n",
            "KML, which condt does not read",
        ),
    ];
    // A GPX track's fixes are longitudes and latitudes: the export projects them.
    let gpx = dir.path().join("ride.gpx");
    std::fs::write(&gpx, cases[3].1).unwrap();
    let run = condt_with_stdin(&["reconstruct", gpx.to_str().unwrap()], b"");
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("-t_srs EPSG:326NN"),
        "{run:?}"
    );
    for (name, bytes, what) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let run = condt_with_stdin(&["reconstruct", path.to_str().unwrap()], b"");
        let said = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{name}: {said}");
        assert!(
            said.contains(&format!("{name}: {what}")) && said.contains("ogr2ogr -f"),
            "{name}: {said}"
        );
        // Stated as text, the text reader's own refusal stands.
        let run = condt_with_stdin(
            &[
                "reconstruct",
                path.to_str().unwrap(),
                "--input-format",
                "txt",
            ],
            b"",
        );
        let said = String::from_utf8_lossy(&run.stderr);
        assert!(
            run.status.code() == Some(1) && !said.contains("ogr2ogr"),
            "{name}: {said}"
        );
    }
    // Points in a file so named are read as points.
    let path = dir.path().join("points.prj");
    std::fs::write(&path, "0 0\n1 0\n0.5 1\n").unwrap();
    let run = condt_with_stdin(&["reconstruct", path.to_str().unwrap()], b"");
    assert!(run.status.success(), "{run:?}");
}

/// A FeatureCollection of LineStrings (a GIS user's review) is refused, as before, and the
/// message now says how to read their vertices.
#[test]
fn geojson_lines_are_refused_with_how_to_read_their_vertices() {
    let dir = scratch_dir();
    let path = dir.path().join("roads.geojson");
    std::fs::write(
        &path,
        r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{},
"geometry":{"type":"LineString","coordinates":[[0,0],[1,0],[2,1]]}}]}"#,
    )
    .unwrap();
    let run = condt_with_stdin(&["reconstruct", path.to_str().unwrap()], b"");
    let said = String::from_utf8_lossy(&run.stderr);
    assert!(
        run.status.code() == Some(1)
            && said.contains("roads.geojson:2: a \"LineString\": only Point and MultiPoint")
            && said.contains("QGIS's Extract vertices"),
        "{said}"
    );
}
