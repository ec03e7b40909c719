//! CSV and GeoJSON point files give the same points, and so the same curves, as the plain
//! format; bad files are refused with their line.

use condt::{reconstruct, Params, Point};
use condt_eval::sample::{sample, Sampling, Shape};
use condt_io::read_points;
use std::process::Command;

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
        let out = Command::new(env!("CARGO_BIN_EXE_condt"))
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
        let out = Command::new(env!("CARGO_BIN_EXE_condt"))
            .arg("reconstruct")
            .arg(&path)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{name}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(stderr.contains(message), "{stderr}");
    }
}
