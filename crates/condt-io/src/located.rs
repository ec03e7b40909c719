//! Where a point was read: the line of a text file that holds the point at a given input
//! position, for messages about points that the library names by position (two points too close
//! to measure). Owns only that count; it may not read points (the readers do) and gives no line
//! where its count of point lines disagrees with the number of points read.

use super::input::{InputFormat, ReadOptions};
use super::points::{line_at, text_lines};
use std::path::Path;
use std::string::String;
use std::vec::Vec;

/// The lines (from 1) of the points at `positions` in the file at `path`, read with `options` into
/// `count` points; `None` where no line says it: standard input or a named pipe (read once),
/// `.npy` and GeoJSON (no line a point, also where the content, not the name, says so), a `.tsv`
/// (read as CSV or as plain text by its first line), text that is not UTF-8, or a file whose
/// point lines do not number `count` or `count` and one header.
///
/// ```
/// use condt_io::{point_lines, ReadOptions};
/// let dir = std::env::temp_dir().join(format!("condt-doc-lines-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let path = dir.join("survey.txt");
/// std::fs::write(&path, "# a survey\nx y\n0 0\n\n1 0 # a note\n0 1\n")?;
/// let lines = point_lines(&path, &ReadOptions::new(), 3, &[0, 2]);
/// assert_eq!(lines, Some(vec![3, 6]));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn point_lines(
    path: impl AsRef<Path>,
    options: &ReadOptions,
    count: usize,
    positions: &[usize],
) -> Option<Vec<usize>> {
    let path = path.as_ref();
    let format = options.format.or_else(|| InputFormat::of_path(path))?;
    // A regular file only: a named pipe (or a terminal behind `/dev/stdin`) was read once, and a
    // second open would wait for a writer.
    if !std::fs::metadata(path).is_ok_and(|meta| meta.is_file()) {
        return None;
    }
    let text = String::from_utf8(std::fs::read(path).ok()?).ok()?;
    // A name without a format's ending is read by its content: GeoJSON there has no point lines.
    let start = text.trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n']);
    if options.format.is_none() && start.starts_with(['{', '[', '\u{1e}']) {
        return None;
    }
    let lines: Vec<usize> = match format {
        InputFormat::Text | InputFormat::Node => text_lines(&text)
            .filter(|(_, line)| !line.split('#').next().unwrap_or("").trim().is_empty())
            .map(|(number, _)| number)
            .collect(),
        // Records, not lines: a quoted field may hold a line end; a record is where it starts.
        InputFormat::Csv => {
            let bytes = text.strip_prefix('\u{feff}').unwrap_or(&text).as_bytes();
            let mut reader = ::csv::ReaderBuilder::new()
                .has_headers(false)
                .flexible(true)
                .from_reader(bytes);
            let mut lines = Vec::new();
            // The line of the last record's start, counted on from there.
            let (mut scanned, mut line) = (0, 1);
            for record in reader.records() {
                let record = record.ok()?;
                if record.iter().any(|field| !field.trim().is_empty()) {
                    // The reader's position lies before the blank lines it skipped (its own
                    // line number too): the record starts past them.
                    let mut start = usize::try_from(record.position()?.byte()).ok()?;
                    while matches!(bytes.get(start), Some(b'\r' | b'\n')) {
                        start += 1;
                    }
                    line += line_at(&bytes[scanned..start], start - scanned) - 1;
                    scanned = start;
                    lines.push(line);
                }
            }
            lines
        }
        // A `.tsv` is read as CSV or as plain text by its first line, with or without comments:
        // no count here would follow both.
        InputFormat::Tsv | InputFormat::Npy | InputFormat::GeoJson | InputFormat::GeoJsonLines => {
            return None;
        }
    };
    // A header line (names, or a `.node` file's counts) holds no point.
    let skipped = lines.len().checked_sub(count).filter(|&extra| extra <= 1)?;
    positions
        .iter()
        .map(|&k| lines.get(k + skipped).copied())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes `text` as `name` in a fresh directory and returns the lines of `positions`.
    fn lines_of(name: &str, text: &str, count: usize, positions: &[usize]) -> Option<Vec<usize>> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        point_lines(&path, &ReadOptions::new(), count, positions)
    }

    #[test]
    fn a_point_is_found_on_its_line_past_comments_blanks_and_a_header() {
        let text = "\u{feff}# survey\r\nx y\r\n0 0\r\n\r\n  # note\r\n1 0\r\n0 1 # last\r\n";
        assert_eq!(lines_of("p.txt", text, 3, &[2, 0, 1]), Some(vec![7, 3, 6]));
        // Without the header, the same lines: the count tells.
        let text = "0 0\n# note\n1 0\n";
        assert_eq!(lines_of("p.txt", text, 2, &[1]), Some(vec![3]));
        // A `.node` file's first line holds its counts.
        let node = "2 2 0 0\n1 0 0\n2 1 0\n";
        assert_eq!(lines_of("p.node", node, 2, &[0, 1]), Some(vec![2, 3]));
    }

    #[test]
    fn a_csv_record_is_found_on_the_line_it_starts() {
        let text = "label,x,y\n\"two\nlines\",0,0\n,,\nc,1,0\n";
        assert_eq!(lines_of("p.csv", text, 2, &[0, 1]), Some(vec![2, 5]));
        // Past blank lines too, which the reader's own line number did not count (a tester's
        // review: a blank line 3 was named for the point on line 5), and past line ends of
        // every kind.
        let text = "x,y\n0,0\n\n\n1,0\n\n0,1\n,,\n2,0\n";
        assert_eq!(
            lines_of("p.csv", text, 4, &[0, 1, 2, 3]),
            Some(vec![2, 5, 7, 9])
        );
        let text = "x,y\r\n\r\n0,0\r\r1,0\n\r\n\"a\nb\",2\n";
        assert_eq!(lines_of("p.csv", text, 3, &[0, 1, 2]), Some(vec![3, 5, 7]));
    }

    #[test]
    fn no_line_where_the_count_disagrees_or_no_line_holds_a_point() {
        assert_eq!(lines_of("p.txt", "0 0\n1 0\n", 5, &[0]), None);
        assert_eq!(lines_of("p.txt", "a b\nc d\n0 0\n", 1, &[0]), None);
        assert_eq!(lines_of("p.txt", "0 0\n1 0\n", 2, &[2]), None);
        let geojson = r#"{"type":"MultiPoint","coordinates":[[0,0],[1,0]]}"#;
        assert_eq!(lines_of("p.geojson", geojson, 2, &[0]), None);
        // GeoJSON told by its content, under a name of no format, whose lines happen to number
        // its points; and a `.tsv`, whose reading depends on its first line.
        let pretty = "{\"type\": \"MultiPoint\",\n\"coordinates\": [[0, 0],\n[1, 0]]\n}\n";
        assert_eq!(lines_of("p.dat", pretty, 3, &[0]), None);
        assert_eq!(lines_of("p.tsv", "name\tx\ty\n#1\t0\t0\n", 1, &[0]), None);
    }

    /// A named pipe was read once: no second open (which would wait for a writer).
    #[cfg(unix)]
    #[test]
    fn a_named_pipe_is_not_opened_again() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("points.txt");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|status| status.success()) {
            return; // no mkfifo here: nothing to test
        }
        // On another thread, so that a regression fails here instead of hanging the test run.
        let (sender, receiver) = std::sync::mpsc::channel();
        let path = fifo.clone();
        std::thread::spawn(move || {
            let _ = sender.send(point_lines(&path, &ReadOptions::new(), 1, &[0]));
        });
        match receiver.recv_timeout(std::time::Duration::from_secs(20)) {
            Ok(lines) => assert_eq!(lines, None),
            Err(_) => {
                // Wake the blocked open with a writer that closes at once, then fail.
                let _ = std::fs::OpenOptions::new().write(true).open(&fifo);
                panic!("point_lines waited on a named pipe for a writer");
            }
        }
    }
}
