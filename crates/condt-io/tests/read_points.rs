//! The point-file readers (issue 11, items 6 and 9): Triangle `.node` files read as such, no
//! silent misreading of ambiguous lines, a byte-order mark and a header line accepted, the right
//! line for bad bytes in CR-only files, and error messages of bounded length.

use condt::Point;
use condt_io::{parse_points, read_points, read_points_with, Columns, IoError, ReadOptions};
use std::path::PathBuf;

/// A file in a fresh temporary directory, removed on drop.
struct TempFile(PathBuf);

impl TempFile {
    fn new(name: &str, content: &[u8]) -> TempFile {
        let dir = std::env::temp_dir().join(format!(
            "condt-read-points-{}-{}",
            std::process::id(),
            name.replace('.', "_")
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, content).unwrap();
        TempFile(path)
    }

    fn read(&self) -> Result<Vec<Point>, IoError> {
        read_points(self.0.to_str().unwrap())
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(self.0.parent().unwrap());
    }
}

fn points(coords: &[(f64, f64)]) -> Vec<Point> {
    coords.iter().map(|&c| Point::from(c)).collect()
}

/// Line and message of a content error.
fn content_error(result: Result<Vec<Point>, IoError>) -> (Option<usize>, String) {
    let err = result.expect_err("an error");
    (err.line, err.to_string())
}

#[test]
fn node_files_are_read_with_header_indices_attributes_and_markers() {
    let node = TempFile::new(
        "square.node",
        b"# A square and its centre, numbered from 1\n\
          5  2  1  1\n\
          1  0.0 0.0  10.5  1\n\
          2  2.0 0.0  10.5  1   # a marker of 1: on the boundary\n\
          3  2.0 2.0  10.5  1\n\
          \n\
          4  0.0 2.0  10.5  1\n\
          5  1.0 1.0  -3    0\n",
    );
    let expected = points(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0), (1.0, 1.0)]);
    assert_eq!(node.read().unwrap(), expected);
    // Numbered from 0, no attributes or markers, CR-only line ends.
    let zero = TempFile::new("zero.node", b"3 2 0 0\r0 0 0\r1 1 0\r2 0 1\r");
    assert_eq!(
        zero.read().unwrap(),
        points(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])
    );
    // An attribute of NaN or infinity (a missing value) is ignored as a plain file's third
    // column is; the coordinates must still be finite.
    let missing = TempFile::new("missing.node", b"2 2 1 0\n0 0 0 nan\n1 1 0 -inf\n");
    assert_eq!(missing.read().unwrap(), points(&[(0.0, 0.0), (1.0, 0.0)]));
    // A header may leave out the fields after the count, as Triangle reads it: dimension 2,
    // no attributes, no markers.
    for header in ["3", "3 2", "3 2 0"] {
        let short = TempFile::new(
            "short.node",
            format!("{header}\n0 0 0\n1 1 0\n2 0 1\n").as_bytes(),
        );
        assert_eq!(
            short.read().unwrap(),
            points(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]),
            "{header}"
        );
    }
    let attributes = TempFile::new("attr.node", b"2 2 1\n0 0 0 7\n1 1 0 7\n");
    assert_eq!(
        attributes.read().unwrap(),
        points(&[(0.0, 0.0), (1.0, 0.0)])
    );
}

#[test]
fn node_files_with_bad_rows_are_refused_by_line() {
    let cases: [(&[u8], usize, &str); 11] = [
        // A short header's defaults hold the rows to three columns.
        (b"2\n0 0 0 7\n1 1 0 7\n", 2, "expected 3 columns"),
        (b"2 2 0 0 0\n0 0 0\n1 1 0\n", 1, "found 5 columns"),
        (b"3 2 0 0\n1 0 0\n2 1 0\n", 3, "the file ends after 2"),
        // An attribute count no row can hold: refused at the header, not wrapped around to 0.
        (
            b"3 2 18446744073709551615 1\n0 0 0\n1 1 0\n2 0 1\n",
            1,
            "18446744073709551615 attributes per vertex is more than a row can hold",
        ),
        (
            b"1 2 18446744073709551613 0\n0 0 0\n",
            1,
            "attributes per vertex is more than a row can hold",
        ),
        // Attributes are ignored, but must be numbers.
        (
            b"1 2 1 0\n0 0 0 deep\n",
            2,
            "cannot read \"deep\" as a number (an attribute or marker is ignored",
        ),
        (
            b"2 2 0 0\n1 0 0\n2 1 0\n3 0 1\n",
            4,
            "more vertex rows than the 2",
        ),
        (b"2 2 0 1\n1 0 0 1\n2 1 0\n", 3, "expected 4 columns"),
        (b"2 3 0 0\n1 0 0 0\n2 1 0 0\n", 1, "dimension 3"),
        (b"2 2 0 0\n5 0 0\n6 1 0\n", 2, "first vertex index 5"),
        (b"1 2 0 0\n1 x 0\n", 2, "cannot read \"x\" as a number"),
    ];
    for (content, line, message) in cases {
        let file = TempFile::new("bad.node", content);
        let (at, text) = content_error(file.read());
        assert_eq!(at, Some(line), "{text}");
        assert!(text.contains(message), "{text}");
    }
}

/// Issue 11, item 9: `.node` rows without their header were read as the points (i, x).
#[test]
fn node_rows_under_another_name_are_refused() {
    let rows = TempFile::new("rows.txt", b"1 0.5 0.25\n2 3.5 1.0\n3 2.0 4.0\n4 9.0 9.0\n");
    let (line, text) = content_error(rows.read());
    assert_eq!(line, Some(1), "{text}");
    assert!(text.contains("Triangle .node"), "{text}");
    // With its header, line 1 has four columns.
    let whole = TempFile::new("whole.txt", b"2 2 0 0\n0 0.5 0.25\n1 3.5 1.0\n");
    let (line, text) = content_error(whole.read());
    assert_eq!(line, Some(1), "{text}");
    // The refusal names both ways to read it as one: the name and the stated format.
    assert!(
        text.contains("Name the file *.node, or state condt's --input-format node"),
        "{text}"
    );
    // A third column that is not an index is still ignored, as documented.
    let xyz = TempFile::new("xyz.txt", b"0.5 0.25 1\n3.5 1.0 1\n2.0 4.0 1\n");
    assert_eq!(
        xyz.read().unwrap(),
        points(&[(0.5, 0.25), (3.5, 1.0), (2.0, 4.0)])
    );
}

/// A scanner's export, `x y z intensity` separated by blanks, could not be read at all (a
/// review: the plain reader refuses a fourth column, and `--columns` took CSV and TSV only); its
/// refusal suggested a Triangle `.node` header even under a header line or with fractions.
#[test]
fn columns_choose_x_and_y_of_plain_text() {
    let scan = b"# scan 7\nX Y Z Intensity\n500000.25 5000000.5 1.2 80\n\
                 500001  5000002\t1.5 81 # a comment\n\n500002.5 5000001 1.25 79\r\n";
    let file = TempFile::new("scan.txt", scan);
    let with = |spec: &str| {
        let options = ReadOptions::new().with_columns(Columns::parse(spec).unwrap());
        read_points_with(&file.0, &options).map(|read| read.points)
    };
    let expected = points(&[
        (500000.25, 5000000.5),
        (500001.0, 5000002.0),
        (500002.5, 5000001.0),
    ]);
    assert_eq!(with("1,2").unwrap(), expected);
    assert_eq!(with("x,y").unwrap(), expected);
    assert_eq!(with("X, Y").unwrap(), expected);
    let swapped: Vec<Point> = expected.iter().map(|p| Point::new(p.y, p.x)).collect();
    assert_eq!(with("Y,X").unwrap(), swapped);
    // Other columns, and the lines errors name are the file's.
    assert_eq!(
        with("z,intensity").unwrap(),
        points(&[(1.2, 80.0), (1.5, 81.0), (1.25, 79.0)])
    );
    let err = with("x,w").unwrap_err();
    assert_eq!(err.line, Some(2), "{err}");
    assert!(err.to_string().contains("no column named \"w\""), "{err}");
    let short = TempFile::new("short.txt", b"x y z\n1 2 3\n\n4 5\n");
    let options = ReadOptions::new().with_columns(Columns::parse("1,2").unwrap());
    let err = read_points_with(&short.0, &options).unwrap_err();
    assert_eq!(err.line, Some(4), "{err}");
    assert!(err.to_string().contains("a row cut short"), "{err}");
    // Without them, the refusal names the option; a `.node` header (whole numbers, 2 second)
    // still gets its own hint.
    let (line, text) = content_error(file.read());
    assert_eq!(line, Some(3), "{text}");
    assert!(
        text.contains("--columns X,Y") && !text.contains(".node"),
        "{text}"
    );
    let fractions = TempFile::new("xyzi.txt", b"0.5 2.5 1.2 80\n1.5 2.5 1.2 80\n");
    let (line, text) = content_error(fractions.read());
    assert_eq!(line, Some(1), "{text}");
    assert!(
        text.contains("--columns X,Y") && !text.contains(".node"),
        "{text}"
    );
    // Split as the plain reader splits: commas alone separate too, comments go (a review: the
    // comma form kept them and misread the header), a decimal comma is refused as there; a
    // quote, which in the TSV read would join lines and drop points silently, is refused.
    let commas = TempFile::new("commas.txt", b"# scan, exported\nx,y,z\n0,0,1 # c\n1,0,1\n");
    let options = ReadOptions::new().with_columns(Columns::parse("x,y").unwrap());
    let read = read_points_with(&commas.0, &options).unwrap();
    assert_eq!(read.points, points(&[(0.0, 0.0), (1.0, 0.0)]));
    for (text, line, words) in [
        (
            &b"x y note\n0 0 \"a\n1 0 b\"\n0 1 c\n"[..],
            2,
            "a quote in plain text",
        ),
        (b"x y\n1,5 2,5 3 4\n", 2, "decimal comma"),
        (b"x y\n0 0\n\xef\xbb\xbf1 1\n", 3, "byte-order mark"),
    ] {
        let file = TempFile::new("refused.txt", text);
        let err = read_points_with(&file.0, &options).unwrap_err();
        assert_eq!(err.line, Some(line), "{err}");
        assert!(err.to_string().contains(words), "{err}");
    }
    let header = TempFile::new("node.txt", b"3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n");
    let (_, text) = content_error(header.read());
    assert!(text.contains("Triangle .node"), "{text}");
}

/// A semicolon-separated export with decimal commas split at its commas: the number refused
/// says why (a review found only "cannot read "00;5000000" as a number").
#[test]
fn a_semicolon_in_a_number_says_that_it_separates_nothing() {
    let err = parse_points("500000,00;5000000,00\n", "eu.txt").unwrap_err();
    assert_eq!(err.line, Some(1));
    assert!(
        err.to_string()
            .contains("a semicolon does not separate columns"),
        "{err}"
    );
    // In a CSV the same row, split at its commas, is no header either: it is told as a point
    // written in another locale.
    let err = condt_io::parse_csv("500000,00;5000000,00\n1,2\n", "eu.csv").unwrap_err();
    assert_eq!(err.line, Some(1));
    let said = err.to_string();
    assert!(
        said.contains("is a point with semicolons between its columns and decimal commas"),
        "{said}"
    );
}

/// Issue 11, item 9: `1,5 2` was read as the point (1, 5).
#[test]
fn a_decimal_comma_is_refused_by_line() {
    for text in ["0 0\n1,5 2\n", "0 0\n1,5\t2,5\n", "0 0\n1.5, 2 3\n"] {
        let err = parse_points(text, "euro.txt").unwrap_err();
        assert_eq!(err.line, Some(2), "{err}");
        assert!(err.to_string().contains("decimal comma"), "{err}");
    }
    // Commas alone, with or without spaces after them, separate columns.
    assert_eq!(
        parse_points("1,5\n2, 6\n3 ,7\n", "csv.txt").unwrap(),
        points(&[(1.0, 5.0), (2.0, 6.0), (3.0, 7.0)])
    );
    let err = parse_points("1,,5\n", "csv.txt").unwrap_err();
    assert_eq!(err.line, Some(1));
}

/// Issue 11, item 9: a byte-order mark and a header line `x y` were refused outright.
#[test]
fn a_byte_order_mark_and_a_header_line_are_accepted() {
    let file = TempFile::new("bom.txt", b"\xef\xbb\xbfx y\n1 2\n3 4\n");
    assert_eq!(file.read().unwrap(), points(&[(1.0, 2.0), (3.0, 4.0)]));
    for header in ["x y", "X,Y", "\"lon\",\"lat\"", "x y z", "# note\n\nx\ty"] {
        let text = format!("{header}\n1 2\n");
        assert_eq!(
            parse_points(&text, "h.txt").unwrap(),
            points(&[(1.0, 2.0)]),
            "{header}"
        );
    }
    // Only the first line may be a header, and only when every column is a name.
    for (text, line) in [
        ("1 2\nx y\n", 2),
        ("x 1\n1 2\n", 1),
        ("1.2.3 4\n1 2\n", 1),
        ("\"1\",\"2\"\n1 2\n", 1),
        ("\"inf\" x\n1 2\n", 1),
    ] {
        let err = parse_points(text, "h.txt").unwrap_err();
        assert_eq!(err.line, Some(line), "{text:?}: {err}");
    }
    // "nan" and "inf" are numbers, and not finite ones.
    let err = parse_points("nan inf\n", "h.txt").unwrap_err();
    assert!(err.to_string().contains("not finite"), "{err}");
}

/// Issue 11, item 9: in a CR-only file the "not UTF-8" error named line 1 whatever the line.
#[test]
fn bad_bytes_in_a_cr_only_file_are_reported_on_their_line() {
    let file = TempFile::new("cr.txt", b"0 0\r1 0\r\r0 \xff1\r");
    let (line, text) = content_error(file.read());
    assert_eq!(line, Some(4), "{text}");
    assert!(text.ends_with("cr.txt:4: not UTF-8 text"), "{text}");
    let file = TempFile::new("crlf.txt", b"0 0\r\n1 0\r\n\xfe\r\n");
    assert_eq!(content_error(file.read()).0, Some(3));
}

/// A plain header of projected names is read as the CSV reader reads it: `easting northing`
/// over the first two columns is skipped, `northing easting` is refused (x would be read from
/// the northing), and beside x and y those names are other columns, as before.
#[test]
fn a_plain_header_of_projected_names_says_which_column_is_x() {
    let expected = vec![
        Point::new(500000.0, 4000000.0),
        Point::new(500010.0, 4000010.0),
    ];
    for text in [
        "easting northing\n500000 4000000\n500010 4000010\n",
        "POINT_X,POINT_Y\n500000,4000000\n500010,4000010\n",
        "x y northing\n500000 4000000 9\n500010 4000010 9\n",
    ] {
        assert_eq!(parse_points(text, "p.txt").unwrap(), expected, "{text}");
    }
    for text in [
        "northing easting\n4000000 500000\n",
        "ycoord xcoord\n4000000 500000\n",
    ] {
        let err = parse_points(text, "p.txt").unwrap_err();
        assert_eq!(err.line, Some(1), "{err}");
        assert!(
            err.to_string().contains("names x or y over another column"),
            "{err}"
        );
    }
}

/// A scanner's export `angle range x y intensity` separated by blanks is refused for its header,
/// and the refusal's advice works: it named `*.csv`, whose reader (commas only) refused the file
/// again with "name the file *.txt" (a robotics user's review). `--columns x,y` reads it.
#[test]
fn a_header_over_other_columns_advises_what_reads_it() {
    let scan =
        b"angle range x y intensity\n-135.0 2.83 1.68 -0.005 185\n-134.75 2.84 1.69 -0.014 185\n";
    let file = TempFile::new("scan_blanks.txt", scan);
    let (line, text) = content_error(file.read());
    assert_eq!(line, Some(1), "{text}");
    assert!(text.contains("--columns X,Y"), "{text}");
    assert!(!text.contains("*.csv"), "{text}");
    let renamed = TempFile::new("scan_blanks.csv", scan);
    assert!(
        renamed.read().is_err(),
        "the CSV reader splits at commas only"
    );
    let options = ReadOptions::new().with_columns(Columns::parse("x,y").unwrap());
    let read = read_points_with(&file.0, &options).unwrap();
    assert_eq!(read.points, points(&[(1.68, -0.005), (1.69, -0.014)]));
    // A header of commas may also be read as a CSV.
    let commas = b"angle,range,x,y\n-135.0,2.83,1.68,-0.005\n";
    let file = TempFile::new("scan_commas.txt", commas);
    let (_, text) = content_error(file.read());
    assert!(
        text.contains("--columns X,Y") && text.contains("*.csv"),
        "{text}"
    );
    let renamed = TempFile::new("scan_commas.csv", commas);
    assert_eq!(renamed.read().unwrap(), points(&[(1.68, -0.005)]));
}

/// A laser scan exported with its rays that had no return (`angle,range,x,y` rows of `inf,nan,nan`
/// or of empty fields) is refused at that row, and the message says what to do with such rows
/// (a robotics user's review: it said only that "nan" is not finite).
#[test]
fn a_scan_row_without_a_return_is_refused_with_advice() {
    for (text, words) in [
        (
            &b"angle,range,x,y\n0,1,1,0\n0.5,inf,nan,nan\n"[..],
            "\"nan\" is not finite",
        ),
        (
            b"angle,range,x,y\n0,1,1,0\n0.5,inf,inf,-inf\n",
            "\"inf\" is not finite",
        ),
        (
            b"angle,range,x,y\n0,1,1,0\n0.5,,,2\n",
            "cannot read \"\" as a number",
        ),
    ] {
        let file = TempFile::new("no_return.csv", text);
        let (line, said) = content_error(file.read());
        assert_eq!(line, Some(3), "{said}");
        assert!(said.contains(words), "{said}");
        assert!(said.contains("leave rows without a point out"), "{said}");
    }
    // A number beyond a double is told as such, without that advice.
    let file = TempFile::new("beyond.csv", b"x,y\n1e400,0\n");
    let (_, said) = content_error(file.read());
    assert!(said.contains("beyond the range of a double"), "{said}");
    assert!(!said.contains("without a return"), "{said}");
}

/// Bytes that are not UTF-8 where nothing is read (a Latin-1 comment, a CP1252 column that is
/// not chosen, a GeoJSON property) do not refuse the file; in a field that is read they do, at
/// their line.
#[test]
fn bytes_that_are_not_utf8_matter_only_where_they_are_read() {
    let square = vec![
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(0.0, 1.0),
    ];
    for (name, bytes) in [
        (
            "comment.txt",
            &b"0 0 # M\xfcnchen\n1 0\n# \xe9t\xe9\n0 1\n"[..],
        ),
        (
            "latin1.csv",
            b"x,y,name\n0,0,M\xfcnchen\n1,0,a\n0,1,\xff\xfe\n",
        ),
        ("header.csv", b"x,y,Stra\xdfe\n0,0,1\n1,0,2\n0,1,3\n"),
        (
            "props.geojson",
            b"{\"type\":\"MultiPoint\",\"name\":\"\xe9\",\"coordinates\":[[0,0],[1,0],[0,1]]}",
        ),
    ] {
        let file = TempFile::new(name, bytes);
        assert_eq!(file.read().expect(name), square, "{name}");
    }
    for (name, bytes, line) in [
        ("field.txt", &b"0 0\n1 \xe9\n0 1\n"[..], 2),
        ("field.csv", b"x,y,n\n0,0,a\n1,0,b\n0,\xe91,c\n", 4),
    ] {
        let file = TempFile::new(name, bytes);
        let (at, text) = content_error(file.read());
        assert_eq!(at, Some(line), "{text}");
        assert!(
            text.ends_with(&format!("{name}:{line}: not UTF-8 text")),
            "{text}"
        );
    }
    // A line wrong for another reason keeps its reason (a review: four columns beside a Latin-1
    // comment were told "not UTF-8 text"), with a word on the bytes.
    for (name, bytes, line, reason) in [
        (
            "four.txt",
            &b"0 0\n1 0 5 6 # caf\xe9\n0 1\n"[..],
            2,
            "found 4",
        ),
        ("word.csv", b"x,y\n0,0\n1,abc,caf\xe9\n", 3, "3 fields"),
        ("alone.txt", b"0 0\n1 0\n\xff\xfe\n", 3, "found one"),
    ] {
        let file = TempFile::new(name, bytes);
        let (at, text) = content_error(file.read());
        assert_eq!(at, Some(line), "{text}");
        let note = "(the line also holds bytes that are not UTF-8)";
        assert!(text.contains(reason) && text.ends_with(note), "{text}");
    }
}

/// Issue 11, item 6: a file whose first number is 100 MB long put 100 MB on stderr. 10 MB here,
/// which the old message would have copied whole just the same (100 MB takes 20 s in a debug
/// build).
#[test]
fn a_10_mb_token_gives_a_short_message() {
    let mut content = vec![b'7'; 10_000_000];
    content.extend_from_slice(b"x 1\n2 3\n");
    let file = TempFile::new("long.txt", &content);
    let (line, text) = content_error(file.read());
    assert_eq!(line, Some(1));
    assert!(text.len() < 200, "{} bytes of message", text.len());
    assert!(text.contains("(10000001 bytes)"), "{text}");
    // A 10 MB comment is no error at all.
    let mut content = b"1 2 # ".to_vec();
    content.extend(std::iter::repeat_n(b'c', 10_000_000));
    let file = TempFile::new("comment.txt", &content);
    assert_eq!(file.read().unwrap(), points(&[(1.0, 2.0)]));
}

/// A deterministic xorshift generator for the large texts below.
struct Xorshift(u64);

impl Xorshift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A coordinate written in one of several common ways, with the value it stands for.
    fn coordinate(&mut self) -> (String, f64) {
        let r = self.next();
        let unit = (r >> 11) as f64 / (1u64 << 53) as f64;
        match r % 6 {
            // Shortest round-trip form: up to 17 significant digits.
            0 | 1 => (format!("{unit}"), unit),
            2 => {
                let v = -(unit * 1000.0);
                (format!("{v}"), v)
            }
            3 => {
                let text = format!("{:.3}", unit * 50.0);
                let v = text.parse().unwrap();
                (text, v)
            }
            4 => {
                let text = format!("{:e}", unit * 1e-7);
                let v = text.parse().unwrap();
                (text, v)
            }
            _ => {
                let v = (r % 1000) as f64;
                (format!("{}", r % 1000), v)
            }
        }
    }
}

/// A text of about `lines` lines (several megabytes: large enough to be parsed in pieces with
/// the `parallel` feature) in every layout the plain format allows, with its points.
fn large_text(lines: usize, seed: u64) -> (String, Vec<Point>) {
    let mut rng = Xorshift(seed);
    // The header names the third column some rows have: `x y` over a first row of three
    // columns whose first field is `1` is R's row names, refused.
    let mut text = String::from("# generated\nx y z\n");
    let mut expected = Vec::new();
    for k in 0..lines {
        let (x, xv) = rng.coordinate();
        let (y, yv) = rng.coordinate();
        let line = match rng.next() % 12 {
            0 => format!("{x}\t{y}\r\n"),
            1 => format!("{x},{y}\n"),
            2 => format!("  {x} {y} 7 # a comment, with a comma\n"),
            3 => format!("{x} {y}\r"),
            4 => format!("{x}\u{a0}{y}\n"),
            5 => format!("\n# {k}\n{x} {y}\n"),
            6 => format!("{x} , {y} , 1\n"),
            _ => format!("{x} {y}\n"),
        };
        text.push_str(&line);
        expected.push(Point::new(xv, yv));
    }
    (text, expected)
}

/// Issue 12, item 3: the fast reader (and, with `parallel`, its pieces on several threads)
/// reads every layout as the rules say, to the last bit of every coordinate.
#[test]
fn a_large_text_in_every_layout_is_read_exactly() {
    let (text, expected) = large_text(150_000, 0x9e37_79b9_7f4a_7c15);
    assert!(
        text.len() > 4 << 20,
        "{} bytes: too small to be split",
        text.len()
    );
    let read = parse_points(&text, "large.txt").unwrap();
    assert_eq!(read.len(), expected.len());
    for (k, (got, want)) in read.iter().zip(&expected).enumerate() {
        assert_eq!(
            (got.x.to_bits(), got.y.to_bits()),
            (want.x.to_bits(), want.y.to_bits()),
            "point {k}"
        );
    }
    // A first megabytes of comments only: the header rule still applies to the first real line.
    let mut commented = "# nothing yet\n".repeat(200_000);
    commented.push_str(&text);
    assert_eq!(parse_points(&commented, "late.txt").unwrap(), read);
}

/// Issue 12, item 3: a bad line anywhere in a large text is reported with its own line and the
/// message it gets alone, however the text was split.
#[test]
fn a_bad_line_late_in_a_large_text_is_reported_on_its_line() {
    let (text, _) = large_text(150_000, 7);
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let base_line = |k: usize| {
        lines[..k]
            .iter()
            .map(|l| l.matches('\n').count() + l.matches('\r').count() - l.matches("\r\n").count())
            .sum::<usize>()
            + 1
    };
    for (bad, at) in [
        ("3 x\n", 140_000),
        ("1 2 3 4\n", 100_001),
        ("5\n", 149_999),
        ("1,5 2\n", 75_000),
        ("x y\n", 120_000),
        ("inf 2\n", 3),
        ("1e999 0\n", 149_000),
    ] {
        let mut broken: String = lines[..at].concat();
        let line = base_line(at);
        broken.push_str(bad);
        broken.push_str(&lines[at..].concat());
        let err = parse_points(&broken, "big.txt").unwrap_err();
        // The same line alone, after a first point (so no header and no first-line hint).
        let alone = parse_points(&format!("0 0\n{bad}"), "big.txt").unwrap_err();
        let message = alone
            .to_string()
            .replacen("big.txt:2:", &format!("big.txt:{line}:"), 1);
        assert_eq!(err.line, Some(line), "{bad:?}: {err}");
        assert_eq!(err.to_string(), message, "{bad:?}");
    }
}

/// Issue 12, item 3: the index-column rule looks at every line of a large file, split or not.
#[test]
fn an_index_column_in_a_large_text_is_refused_and_a_break_in_it_is_not() {
    let mut text = String::from("# nodes\n\n");
    for i in 0..200_000 {
        text.push_str(&format!("{} {}.25 {}.5\n", i + 1, i % 977, i % 13));
    }
    let err = parse_points(&text, "nodes.txt").unwrap_err();
    assert_eq!(err.line, Some(3), "{err}");
    assert!(err.to_string().contains("counts 1, 2, 3"), "{err}");
    // One index out of step near the end: an ordinary third column, read as x y.
    let text = text.replacen("199990 ", "5 ", 1);
    let points = parse_points(&text, "nodes.txt").unwrap();
    assert_eq!(points.len(), 200_000);
    assert_eq!(
        points[199_989],
        Point::new(5.0, (199_989 % 977) as f64 + 0.25)
    );
}

/// A header naming the first two columns x and y says what they are: a profile whose stations
/// count 1, 2, 3, … is read as x, small or large (the parallel reader), and without the header
/// the same rows are still refused as a `.node` file's index column.
#[test]
fn a_header_naming_x_and_y_overrules_the_index_column_guess() {
    for rows in [4, 200_000] {
        let body: String = (1..=rows)
            .map(|i| format!("{i} {}.5 7\n", i % 13))
            .collect();
        let points = parse_points(&format!("x y z\n{body}"), "profile.txt").unwrap();
        assert_eq!(points.len(), rows);
        assert_eq!(points[2], Point::new(3.0, 3.5));
        let err = parse_points(&body, "profile.txt").unwrap_err();
        assert!(err.to_string().contains("counts 1, 2, 3"), "{err}");
        let err = parse_points(&format!("id a b\n{body}"), "profile.txt").unwrap_err();
        assert!(err.to_string().contains("counts 1, 2, 3"), "{err}");
    }
}

/// A `.tsv` file is read by the CSV reader, its columns named by its header: the plain reader
/// would take its id column for a `.node` file's index.
#[test]
fn a_tsv_file_is_read_by_its_header() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("stations.TSV");
    std::fs::write(
        &path,
        "id\tlat\tlon\n1\t47.3\t8.5\n2\t47.3\t8.51\n3\t47.31\t8.52\n",
    )
    .unwrap();
    let read = read_points(&path).unwrap();
    assert_eq!(read, points(&[(8.5, 47.3), (8.51, 47.3), (8.52, 47.31)]));
    // Two numbers first: the plain format, with its comments.
    std::fs::write(&path, "# survey\n1.5\t2\n3\t4 # last\n").unwrap();
    assert_eq!(
        read_points(&path).unwrap(),
        points(&[(1.5, 2.0), (3.0, 4.0)])
    );
}

/// A `.tsv` of three numbers or more a line follows the CSV reader's rule, as the README says: a
/// header or `--columns` must name x and y (an `id x y` survey export had been read as `x y z`:
/// its ids as x, its x as y, with no word), after comments too; two numbers are the plain
/// format's, with its comments, blanks and empty fields (a diff review: the CSV reader had
/// refused those).
#[test]
fn a_tsv_of_numbers_follows_the_csv_rule() {
    let expected = points(&[(1.0, 2.0), (3.0, 4.0), (5.0, 1.0)]);
    for (name, text) in [
        ("two.tsv", &b"1\t2\n3\t4\n5\t1\n"[..]),
        ("commented.tsv", b"1\t2\n# c\n3\t4 # d\n5 1\n"),
        ("leading.tsv", b"\t1\t2\n\t3\t4\n\t5\t1\n"),
    ] {
        let file = TempFile::new(name, text);
        assert_eq!(file.read().unwrap(), expected, "{name}");
    }
    for (name, text, at) in [
        (
            "ids.tsv",
            &b"1000\t10.0\t0.0\n1007\t9.87\t0.78\n1013\t9.5\t1.5\n"[..],
            1,
        ),
        ("noted.tsv", b"# survey\n17\t0\t0\n23\t1\t0\n5\t0\t1\n", 2),
    ] {
        let file = TempFile::new(name, text);
        let (line, message) = content_error(file.read());
        assert_eq!(line, Some(at), "{name}: {message}");
        assert!(message.contains("3 numbers and no header"), "{message}");
    }
}

/// A `.tsv` without a header whose lines separate values by tabs is read at tabs only: a blank
/// within a field (a thousands separator: `10<TAB>2 345.5`) and a third value on a later line
/// (`1<TAB>0 7`) were read as the plain format reads them, (10, 2) and (1, 0) with exit 0 (a
/// hostile-input review). Each is refused at its line; lines without a tab stay plain.
#[test]
fn a_tsv_without_a_header_is_split_at_tabs_only() {
    for (name, text, at, said) in [
        (
            "thousands.tsv",
            &b"10\t2 345.5\n11\t2 346.5\n"[..],
            1,
            "\"2 345.5\"",
        ),
        ("third.tsv", b"0\t0\n1\t0 7\n0\t1 9\n", 2, "\"0 7\""),
        (
            "later.tsv",
            b"0\t0\r\n1\t0\r\n# c\r\n2\t1\t5\r\n",
            4,
            "3 values between tabs",
        ),
    ] {
        let file = TempFile::new(name, text);
        let (line, message) = content_error(file.read());
        assert_eq!(line, Some(at), "{name}: {message}");
        assert!(message.contains(said), "{name}: {message}");
    }
    // A tab that indents or ends a line separates nothing (the diff review: `<TAB>1 2` had
    // been refused).
    let expected = points(&[(1.0, 2.0), (3.0, 4.0), (5.0, 1.0)]);
    let plain = TempFile::new("plain.tsv", b"1 2\n3\t4 # note\n5 1 9\n");
    assert_eq!(plain.read().unwrap(), expected);
    let indented = TempFile::new("indent.tsv", b"\t1 2\n\t3 4\t\n\t5 1\n");
    assert_eq!(indented.read().unwrap(), expected);
}

/// A `.tsv` header is told as the README has it: after a byte-order mark, with a name of blanks
/// (`elevation (m)`, one field between tabs), or naming x and y beside a column named by a
/// number (`2020`), in any position; each was read as the plain format and refused. A first line
/// of numbers is still a point.
#[test]
fn a_tsv_header_is_told_after_a_mark_and_among_any_names() {
    let expected = points(&[(1.0, 2.0), (3.0, 4.0), (5.0, 1.0)]);
    for (name, text) in [
        ("bom.tsv", "\u{feff}id\tlon\tlat\n1\t1\t2\n2\t3\t4\n3\t5\t1\n"),
        (
            "unit.tsv",
            "id\tlon\tlat\televation (m)\n1\t1\t2\t5\n2\t3\t4\t5\n3\t5\t1\t5\n",
        ),
        (
            "year.tsv",
            "id\tlon\tlat\t2020\n1\t1\t2\t5\n2\t3\t4\t5\n3\t5\t1\t5\n",
        ),
        (
            "moved.tsv",
            "\u{feff}2020\tLat\tstation name\t\"X\"\r\n5\t2\ta b\t1\r\n5\t4\tc\t3\r\n5\t1\td\t5\r\n",
        ),
    ] {
        let file = TempFile::new(name, text.as_bytes());
        assert_eq!(file.read().unwrap(), expected, "{name}");
    }
    let numbers = TempFile::new("numbers.tsv", b"1\t2\n3\t4\n5\t1\n");
    assert_eq!(numbers.read().unwrap(), expected);
    // Names without x and y after a mark are a header too, refused as the CSV reader refuses
    // it (the mark made its first name no name: the plain reader called the `FID` column a
    // `.node` index).
    let fid = TempFile::new(
        "fid.tsv",
        "\u{feff}FID\tA\tB\n1\t2\t3\n2\t4\t5\n".as_bytes(),
    );
    let (line, message) = content_error(fid.read());
    assert_eq!(line, Some(1), "{message}");
    assert!(
        message.contains("the header has no x column") && message.contains("--columns X,Y"),
        "{message}"
    );
}

/// Over 2 MiB of points, with a byte-order mark starting the first line after byte 1 MiB, where
/// the parallel readers begin a piece; with the line of the mark.
fn text_with_a_mark_after_a_piece_boundary() -> (String, usize) {
    let mut text = String::new();
    let mut i = 0u64;
    while text.len() < 5 << 19 {
        text.push_str(&format!("{}.25 {}\n", i, 2 * i + 1));
        i += 1;
    }
    let cut = (1 << 20) + text[1 << 20..].find('\n').unwrap() + 1;
    let line = 1 + text[..cut].matches('\n').count();
    text.insert(cut, '\u{feff}');
    (text, line)
}

/// A byte-order mark is allowed only at the very start of the file; anywhere else it is an
/// error naming its line, whichever way the file is read: in memory or from a file, in pieces
/// on two threads or on one.
#[cfg(feature = "parallel")]
#[test]
fn a_byte_order_mark_inside_the_file_is_refused_on_every_path() {
    let (text, line) = text_with_a_mark_after_a_piece_boundary();
    let file = TempFile::new("bom.txt", text.as_bytes());
    let clean = text.replacen('\u{feff}', "", 1);
    let expected = parse_points(&clean, "clean.txt").unwrap();
    let marked_at_start = TempFile::new("bom-start.txt", format!("\u{feff}{clean}").as_bytes());
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let results = [
                ("parse_points", parse_points(&text, "bom.txt")),
                ("read_points", file.read()),
            ];
            for (path, result) in results {
                let err = match result {
                    Ok(points) => panic!("{path} on {threads} threads: {} points", points.len()),
                    Err(err) => err,
                };
                assert_eq!(err.line, Some(line), "{path}, {threads} threads: {err}");
                assert!(
                    err.to_string().contains("byte-order mark"),
                    "{path}, {threads} threads: {err}"
                );
            }
            // At the very start it is skipped, on every path.
            let start = format!("\u{feff}{clean}");
            assert!(parse_points(&start, "start.txt").unwrap() == expected);
            assert!(marked_at_start.read().unwrap() == expected);
        });
    }
    // In a small file, and inside a line, the same.
    let err = parse_points("1 2\n\u{feff}3 4\n", "small.txt").unwrap_err();
    assert_eq!(err.line, Some(2), "{err}");
    assert!(err.to_string().contains("byte-order mark"), "{err}");
    let err = parse_points("1 2\n3 \u{feff}4\n", "small.txt").unwrap_err();
    assert_eq!(err.line, Some(2), "{err}");
    assert!(err.to_string().contains("byte-order mark"), "{err}");
}

/// A text whose only line with columns is a "header" that names no x and y columns is not an
/// empty point file: it is refused with its line (a reviewer's report: `Error: file not
/// found` alone read as a header, 0 points). A header naming x and y over the first two
/// columns, alone, is an empty point file; any header with points after it is skipped as before.
#[test]
fn a_header_alone_must_name_x_and_y() {
    for (text, line) in [
        ("Error: file not found\n", 1),
        ("# saved by a script\n\nError file not found\n", 3),
        ("a b\n# nothing else\n", 1),
        ("name value\n", 1),
        ("Error\n", 1),
    ] {
        let (at, message) = content_error(parse_points(text, "err.txt"));
        assert_eq!(at, Some(line), "{text:?}: {message}");
        assert!(
            message.starts_with(&format!(
                "err.txt:{line}: no point: line {line} is not a point"
            )),
            "{text:?}: {message}"
        );
    }
    for text in [
        "x y\n",
        "X Y z\n",
        "lon lat\n",
        "\"lng\",\"lat\"\n",
        "# c\nx y\n\n",
        "",
    ] {
        assert_eq!(parse_points(text, "e.txt").unwrap(), [], "{text:?}");
    }
    // With points after it, a header of any names is skipped.
    assert_eq!(
        parse_points("a b\n1 2\n", "ab.txt").unwrap(),
        points(&[(1.0, 2.0)])
    );
    // Read from a file, by every path of the reader, large or not.
    let dir = tempfile::tempdir().unwrap();
    let small = dir.path().join("err.txt");
    std::fs::write(&small, "Error: file not found\n").unwrap();
    let (at, message) = content_error(read_points(&small));
    assert_eq!(at, Some(1), "{message}");
    assert!(message.contains("err.txt:1: no point"), "{message}");
    // Megabytes of comments after the lone line: the parallel reader must not take it for an
    // empty file either.
    let large = dir.path().join("large.txt");
    let mut text = String::from("Error: file not found\n");
    text.push_str(
        &"# padding padding padding padding padding padding padding padding\n".repeat(80_000),
    );
    std::fs::write(&large, &text).unwrap();
    let (at, message) = content_error(read_points(&large));
    assert_eq!(at, Some(1), "{message}");
    let large_header = dir.path().join("large_header.txt");
    std::fs::write(&large_header, text.replace("Error: file not found", "x y")).unwrap();
    assert_eq!(read_points(&large_header).unwrap(), []);
}

/// A GeoJSON lines file (`.geojsonl`, one feature per line, as GDAL's GeoJSONSeq driver writes
/// it) was read as plain text and refused as "a decimal comma?"; it is read one object per line
/// (and `.geojsons`, RFC 8142, one after each record separator), its errors naming the file and
/// the line in it.
#[test]
fn geojson_lines_are_read_one_object_per_line() {
    let feature = |x: f64, y: f64| {
        format!(
            r#"{{"type": "Feature", "properties": {{"name": "a, b"}}, "geometry": {{"type": "Point", "coordinates": [{x}, {y}]}}}}"#
        )
    };
    let expected = points(&[(0.0, 0.0), (1.5, 0.0), (0.5, 2.0), (3.0, 4.0)]);
    let lines = format!(
        "{}\r\n{}\n\n{}\n{{\"type\": \"MultiPoint\", \"coordinates\": [[3, 4]]}}\n\
         {{\"type\": \"Feature\", \"properties\": {{}}, \"geometry\": null}}\n",
        feature(0.0, 0.0),
        feature(1.5, 0.0),
        feature(0.5, 2.0)
    );
    let file = TempFile::new("sites.geojsonl", lines.as_bytes());
    assert_eq!(file.read().unwrap(), expected);
    let read = condt_io::read_points_with(&file.0, &condt_io::ReadOptions::new()).unwrap();
    assert_eq!(read.null_geometries, 1);
    // RFC 8142: a record separator before each text, which may span lines.
    let sequence = format!(
        "\u{1e}{}\n\u{1e}{{\"type\": \"FeatureCollection\",\n \"features\": [{}, {}]}}\n\u{1e}{}\n",
        feature(0.0, 0.0),
        feature(1.5, 0.0),
        feature(0.5, 2.0),
        feature(3.0, 4.0)
    );
    let file = TempFile::new("sites.GEOJSONS", sequence.as_bytes());
    assert_eq!(file.read().unwrap(), expected);
    // Errors name the file and the line in it, not in the record.
    for (text, line, words) in [
        (
            format!(
                "{}\n\n{{\"type\": \"Point\", \"coordinates\": [1, \"2\"]}}\n",
                feature(0.0, 0.0)
            ),
            3,
            "a position must be",
        ),
        (
            format!(
                "{}\n{{\"type\": \"LineString\", \"coordinates\": []}}\n",
                feature(0.0, 0.0)
            ),
            2,
            "only Point and MultiPoint",
        ),
        // A pretty-printed document is not GeoJSON lines: said so.
        (
            "{\"type\": \"FeatureCollection\",\n \"features\": []}\n".to_string(),
            1,
            "one whole GeoJSON object per line",
        ),
    ] {
        let file = TempFile::new("bad.geojsonl", text.as_bytes());
        let (at, message) = content_error(file.read());
        assert_eq!(at, Some(line), "{message}");
        assert!(message.contains("bad.geojsonl:"), "{message}");
        assert!(message.contains(words), "{message}");
        assert!(!message.contains("decimal comma"), "{message}");
    }
    // A record that ends early is told on its own last line, not on the next record's.
    let truncated = "\u{1e}{\"type\":\"Point\",\"coordinates\":[0,0]}\n\
                     \u{1e}{\"type\":\"Point\",\"coordinates\":[1,0\n\
                     \u{1e}{\"type\":\"Point\",\"coordinates\":[1,1]}\n";
    let file = TempFile::new("cut.geojsons", truncated.as_bytes());
    let (at, message) = content_error(file.read());
    assert_eq!(at, Some(2), "{message}");
}

/// GeoJSON lines (NDJSON) in a file named `.json` or `.geojson` are read as one document and
/// refused at their second object; the refusal says how to read one object per line.
#[test]
fn geojson_lines_under_a_document_name_are_told_how_to_be_read() {
    let lines = "{\"type\": \"Point\", \"coordinates\": [0, 0]}\n\
                 {\"type\": \"Point\", \"coordinates\": [1, 0]}\n";
    for name in ["sites.json", "sites.GeoJSON"] {
        let file = TempFile::new(name, lines.as_bytes());
        let (line, message) = content_error(file.read());
        assert_eq!(line, Some(2), "{message}");
        assert!(
            message.contains(&format!("{name}:2: trailing characters"))
                && message.ends_with(
                    "a GeoJSON document is one object: to read one GeoJSON object per line, \
                     name the file *.geojsonl or state condt's --input-format geojsonl"
                ),
            "{message}"
        );
        let read = condt_io::read_points_with(
            &file.0,
            &condt_io::ReadOptions::new().with_format(condt_io::InputFormat::GeoJsonLines),
        )
        .unwrap();
        assert_eq!(read.points, points(&[(0.0, 0.0), (1.0, 0.0)]));
    }
    // A stray brace after a document starts no object: no word of GeoJSON lines.
    let stray = TempFile::new(
        "stray.geojson",
        b"{\"type\": \"Point\", \"coordinates\": [0, 0]}\n}\n",
    );
    let (line, message) = content_error(stray.read());
    assert_eq!(line, Some(2), "{message}");
    assert!(message.ends_with("trailing characters"), "{message}");
}

/// A GeoJSON sequence keeps the first record's `crs`, as a document keeps its first; a later
/// record's that differs is left out, and its line given for the caller to tell (the same crs
/// written otherwise, or none, is no difference).
#[test]
fn a_later_crs_in_a_geojson_sequence_is_told_not_dropped_silently() {
    let utm = r#"{"type": "name", "properties": {"name": "EPSG:32632"}}"#;
    let utm_again = r#"{ "properties": {"name":"EPSG:32632"},"type":"name" }"#;
    let other = r#"{"type": "name", "properties": {"name": "EPSG:2056"}}"#;
    let record = |crs: Option<&str>, x: u32| match crs {
        Some(crs) => format!(
            "{{\"type\": \"FeatureCollection\", \"crs\": {crs}, \"features\": [{{\"type\": \
             \"Feature\", \"properties\": {{}}, \"geometry\": {{\"type\": \"Point\", \
             \"coordinates\": [{x}, 0]}}}}]}}\n"
        ),
        None => format!("{{\"type\": \"Point\", \"coordinates\": [{x}, 0]}}\n"),
    };
    let read = |text: String| {
        let file = TempFile::new("crs.geojsonl", text.as_bytes());
        condt_io::read_points_with(&file.0, &condt_io::ReadOptions::new()).unwrap()
    };
    let same = read(record(Some(utm), 0) + &record(None, 1) + &record(Some(utm_again), 2));
    assert_eq!((same.points.len(), same.crs.as_deref()), (3, Some(utm)));
    assert_eq!(same.crs_dropped_at, None);
    let differs = read(
        record(None, 0)
            + &record(Some(utm), 1)
            + "\n"
            + &record(Some(other), 2)
            + &record(Some(other), 3),
    );
    assert_eq!(
        (differs.points.len(), differs.crs.as_deref()),
        (4, Some(utm))
    );
    assert_eq!(
        differs.crs_dropped_at,
        Some(4),
        "the first record that differs"
    );
    // A document's own second crs is not a sequence's record: refused, as which one the writer
    // meant is a guess (other readers take the last), naming the file.
    let file = TempFile::new(
        "two.geojson",
        format!(
        "{{\"type\": \"FeatureCollection\", \"crs\": {utm}, \"crs\": {other}, \"features\": []}}"
    )
        .as_bytes(),
    );
    let err = condt_io::read_points_with(&file.0, &condt_io::ReadOptions::new()).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("two.geojson") && text.contains("\"crs\" is given twice"),
        "{text}"
    );
    // So is a later record of a sequence giving its crs twice, on that record's line.
    let twice = record(Some(utm), 1).replacen("\"crs\"", &format!("\"crs\": {other}, \"crs\""), 1);
    let file = TempFile::new("twice.geojsonl", (record(None, 0) + &twice).as_bytes());
    let err = condt_io::read_points_with(&file.0, &condt_io::ReadOptions::new()).unwrap_err();
    assert!(err.to_string().contains("\"crs\" is given twice"), "{err}");
    assert_eq!(err.line, Some(2), "{err}");
}

/// Found by a review: `Column` and `Columns` have public fields, so columns `Columns::parse`
/// refuses can be built by hand. Column 0 panicked (a subtraction below zero) with and without a
/// header, and one column for x and y was read for both without a word; both are refused naming
/// the file, before anything is read.
#[test]
fn columns_built_by_hand_that_parse_refuses_are_refused_by_the_reader() {
    use condt_io::{read_points_with, Column, Columns, ReadOptions};
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    for text in ["1,2\n3,4\n", "a,b\n1,2\n"] {
        std::fs::write(&path, text).unwrap();
        let read = |x: Column, y: Column| {
            read_points_with(&path, &ReadOptions::new().with_columns(Columns { x, y }))
        };
        let err = read(Column::Number(0), Column::Number(2)).unwrap_err();
        assert!(err.to_string().contains("t.csv"), "{err}");
        assert!(
            err.to_string().contains("columns are numbered from 1"),
            "{err}"
        );
        let err = read(Column::Number(2), Column::Number(2)).unwrap_err();
        assert!(
            err.to_string().contains("the same column for x and y"),
            "{err}"
        );
        let err = read(Column::Named("A".into()), Column::Named("a".into())).unwrap_err();
        assert!(
            err.to_string().contains("the same column for x and y"),
            "{err}"
        );
        assert!(read(Column::Number(2), Column::Number(1)).is_ok());
    }
}

/// A refused geometry type is told on the line of its `"type"`, also where that member comes
/// last and spacing and line breaks follow it (a pretty-printed file with sorted keys), not on
/// the line where the spacing ends.
#[test]
fn a_refused_type_is_told_on_its_own_line() {
    for (text, line) in [
        (
            "{\"type\": \"Feature\", \"properties\": {},\n \"geometry\": {\"coordinates\": \
             [[0, 0], [1, 1]],\n   \"type\": \"LineString\"\n }\n}\n",
            3,
        ),
        (
            "{\"features\": [\n  {\"geometry\": {\"coordinates\": [], \"type\": \"Polygon\"  \n\n\n  \
             }, \"type\": \"Feature\"}],\n \"type\": \"FeatureCollection\"}\n",
            2,
        ),
    ] {
        let file = TempFile::new("lines.geojson", text.as_bytes());
        let (at, message) = content_error(file.read());
        assert_eq!(at, Some(line), "{message}");
        assert!(message.contains("only Point and MultiPoint"), "{message}");
    }
}

/// A MATLAB MAT-file (versions 5 and 7.3 start with a text header), Octave's binary workspace
/// and a legacy Excel `.xls` are told as such, by any name (an R and MATLAB user's review: a
/// MAT-file was refused for "both commas and blanks" in its header, "a decimal comma?").
#[test]
fn a_matlab_workspace_or_an_xls_workbook_is_told_as_such() {
    let mut mat5 =
        b"MATLAB 5.0 MAT-file, written by Octave 7.3.0, 2026-12-07 23:01:24 UTC".to_vec();
    mat5.resize(116, b' ');
    mat5.extend([
        0, 0, 0, 0, 0, 0, 0, 0, 0, 1, b'I', b'M', 14, 0, 0, 0, 0xf0, 0, 0, 0,
    ]);
    let mut mat73 = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Dec  7 23:01:24 \
                      2026 HDF5 schema 1.00 ."
        .to_vec();
    mat73.resize(128, b' ');
    mat73.extend(b"\x89HDF\r\n\x1a\n\x00\x00\x00\x00");
    let octave = b"Octave-1-L\0\x00\x01\x00\x00\x00M\xff\x06\x00\x00\x00matrix".to_vec();
    let xls = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1\0\0\0\0\0\0\0\0>\0\x03\0\xfe\xff".to_vec();
    for name in ["points.mat", "points.txt", "points.csv", "points"] {
        for bytes in [&mat5, &mat73, &octave] {
            let file = TempFile::new(name, bytes);
            let (line, message) = content_error(file.read());
            assert_eq!(line, None, "{name}: {message}");
            assert!(
                message.contains(": a MATLAB or Octave workspace")
                    && message.contains("writematrix"),
                "{name}: {message}"
            );
        }
        let file = TempFile::new(name, &xls);
        let (_, message) = content_error(file.read());
        assert!(
            message.contains(": an Excel .xls workbook"),
            "{name}: {message}"
        );
    }
}

/// A zip archive, such as NumPy's `.npz` (a Python user's review: "not UTF-8 text" sent them
/// looking for an encoding), is told as such, by any name.
#[test]
fn a_zip_archive_is_told_as_such() {
    // A zip's local file header (stored, the member `a.npy`), then the start of that member.
    let mut zip = b"PK\x03\x04\x14\x00\x00\x00\x00\x00\x00\x00\x21\x00".to_vec();
    zip.extend([
        0x9a, 0xbc, 0xde, 0xf0, 0x90, 0, 0, 0, 0x90, 0, 0, 0, 5, 0, 0, 0,
    ]);
    zip.extend(b"a.npy\x93NUMPY\x01\x00v\x00{'descr': '<f8', 'fortran_order': False, ");
    // An empty archive is its end record alone.
    let empty =
        b"PK\x05\x06\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00";
    for name in ["points.npz", "points.txt", "points"] {
        for bytes in [&zip[..], &empty[..]] {
            let file = TempFile::new(name, bytes);
            let (_, message) = content_error(file.read());
            assert!(message.contains("a zip archive"), "{name}: {message}");
            // An Excel `.xlsx` is a zip archive too: the message says what to save it as.
            assert!(message.contains("a sheet as CSV"), "{name}: {message}");
        }
    }
}

/// A compressed file is told as such, with the tool that reads it (a newcomer's review: a gzip
/// file was "not UTF-8 text"), by any name; real gzip bytes of `0 0\n1 0\n0 1\n`.
#[test]
fn a_compressed_file_is_told_as_such() {
    let gzip = b"\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03\x33\x50\x30\xe0\x32\x04\x62\x03\x05\x43\x2e\x00\x84\x52\x43\x32\x0c\x00\x00\x00";
    for (bytes, kind) in [
        (&gzip[..], "gzip"),
        (b"BZh91AY&SY\x00\x01", "bzip2"),
        (b"\xfd7zXZ\x00\x00\x04", "xz"),
        (b"\x28\xb5\x2f\xfd\x24\x0c", "zstd"),
    ] {
        for name in ["points.txt.gz", "points.csv", "points"] {
            let file = TempFile::new(name, bytes);
            let (line, message) = content_error(file.read());
            assert!(
                message.contains(&format!("{kind}-compressed data")),
                "{name}: {message}"
            );
            assert_eq!(line, None, "{message}");
        }
    }
}

/// UTF-16 text (a byte order mark, then two bytes a character) is told as such, at line 1, in
/// every text format, instead of as a first field no number reader makes sense of.
#[test]
fn utf16_text_is_told_as_such() {
    let utf16 = |text: &str, big_endian: bool| -> Vec<u8> {
        let mut bytes = if big_endian {
            vec![0xfe, 0xff]
        } else {
            vec![0xff, 0xfe]
        };
        for unit in text.encode_utf16() {
            let pair = if big_endian {
                unit.to_be_bytes()
            } else {
                unit.to_le_bytes()
            };
            bytes.extend(pair);
        }
        bytes
    };
    for (name, text) in [
        ("points.txt", "0 0\n1 0\n0 1\n"),
        ("points.csv", "x,y\n0,0\n1,0\n0,1\n"),
        (
            "points.geojson",
            "{\"type\": \"MultiPoint\", \"coordinates\": [[0, 0], [1, 0]]}\n",
        ),
    ] {
        for big_endian in [false, true] {
            let file = TempFile::new(name, &utf16(text, big_endian));
            let (at, message) = content_error(file.read());
            assert_eq!(at, Some(1), "{message}");
            assert!(message.contains("UTF-16 text"), "{name}: {message}");
        }
    }
}

/// CloudCompare's ASCII export marks its header with `//` (`//X,Y,Z`), which the README's scan
/// users meet: read as a header in `.csv`, `.txt` and `.tsv` (a newcomer's review: refused as a
/// header without an x column); lines keep their numbers; `//` before anything else is no mark.
#[test]
fn a_cloudcompare_header_is_read() {
    let expected = points(&[(0.0, 0.0), (1.0, 0.5), (0.25, 1.0)]);
    for (name, text) in [
        (
            "cc.csv",
            "//X,Y,Z,R,G,B\n0,0,1,9,9,9\n1,0.5,1,9,9,9\n0.25,1,1,9,9,9\n",
        ),
        ("cc.txt", "//X Y Z\n0 0 1\n1 0.5 1\n0.25 1 1\n"),
        (
            "cc.tsv",
            "\u{feff}\n//X\tY\tZ\n0\t0\t1\n1\t0.5\t1\n0.25\t1\t1\n",
        ),
    ] {
        let file = TempFile::new(name, text.as_bytes());
        assert_eq!(file.read().unwrap(), expected, "{name}");
    }
    let bad = TempFile::new("ccbad.csv", b"//X,Y,Z\n0,0,1\n1,oops,1\n");
    let (line, message) = content_error(bad.read());
    assert_eq!(line, Some(3), "{message}");
    let comment = TempFile::new("comment.txt", b"// 0 0\n1 1\n2 0\n");
    assert!(comment.read().is_err());
}

/// `PointFile::degrees` says where the file names its coordinates longitude and latitude (a GIS
/// user's review: nothing told a caller so, to warn that they are read as plane coordinates):
/// CSV, TSV and plain headers naming lon and lat, `--columns` choosing them by name, GeoJSON
/// without a crs or with CRS84 or EPSG 4326; not x and y, projected names, a projected or null
/// crs, a header-less file or an array.
#[test]
fn point_files_say_whether_they_are_in_degrees() {
    let csv_rows = "1,2\n3,4\n5,7\n";
    let cases: [(&str, String, bool); 15] = [
        ("a.csv", format!("lon,lat\n{csv_rows}"), true),
        ("b.csv", format!("id,\"Latitude\",\"Longitude\"\n{}", "0,1,2\n1,3,4\n2,5,7\n"), true),
        ("c.csv", format!("x,y\n{csv_rows}"), false),
        ("d.csv", format!("easting,northing\n{csv_rows}"), false),
        ("e.csv", csv_rows.to_string(), false),
        ("f.tsv", "lng\tlat\n1\t2\n3\t4\n".to_string(), true),
        ("g.txt", "long lat\n1 2\n3 4\n".to_string(), true),
        ("h.geojson", r#"{"type":"MultiPoint","coordinates":[[1,2],[3,4]]}"#.to_string(), true),
        (
            "i.geojson",
            r#"{"type":"MultiPoint","crs":{"type":"name","properties":{"name":"EPSG:4326"}},"coordinates":[[1,2]]}"#
                .to_string(),
            true,
        ),
        (
            "j.geojson",
            r#"{"type":"MultiPoint","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},"coordinates":[[1,2]]}"#
                .to_string(),
            false,
        ),
        (
            "k.geojson",
            r#"{"type":"MultiPoint","crs":null,"coordinates":[[1,2]]}"#.to_string(),
            false,
        ),
        ("l.txt", "1 2\n3 4\n".to_string(), false),
        // ETRS89 by GDAL's URN, NAD83 by OGC's name: geographic too; a code that only begins
        // like one (43260) is not.
        (
            "n.geojson",
            r#"{"type":"MultiPoint","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::4258"}},"coordinates":[[1,2]]}"#
                .to_string(),
            true,
        ),
        (
            "o.geojson",
            r#"{"type":"MultiPoint","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:OGC:1.3:CRS83"}},"coordinates":[[1,2]]}"#
                .to_string(),
            true,
        ),
        (
            "p.geojson",
            r#"{"type":"MultiPoint","crs":{"type":"name","properties":{"name":"EPSG:43260"}},"coordinates":[[1,2]]}"#
                .to_string(),
            false,
        ),
    ];
    for (name, text, degrees) in cases {
        let file = TempFile::new(name, text.as_bytes());
        let read = read_points_with(&file.0, &ReadOptions::new()).unwrap();
        assert_eq!(read.degrees, degrees, "{name}");
    }
    let file = TempFile::new("m.csv", b"a,Lon,Lat,b\n9,1,2,9\n");
    let chosen = |spec: &str| {
        let options = ReadOptions::new().with_columns(Columns::parse(spec).unwrap());
        read_points_with(&file.0, &options).unwrap().degrees
    };
    assert!(chosen("LON,LAT"));
    assert!(!chosen("2,3"), "by number: nothing names them");
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2), }";
    let padded = format!("{header:<117}\n");
    npy.extend((padded.len() as u16).to_le_bytes());
    npy.extend(padded.as_bytes());
    npy.extend(1f64.to_le_bytes());
    npy.extend(2f64.to_le_bytes());
    let file = TempFile::new("n.npy", &npy);
    assert!(
        !read_points_with(&file.0, &ReadOptions::new())
            .unwrap()
            .degrees
    );
}
