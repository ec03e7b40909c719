//! The checks behind the fuzz targets, one public function per target, each taking the raw
//! fuzzer bytes and panicking on a finding.
//!
//! They depend on nothing but `condt` and `std`, so that `tests/fuzz_corpus.rs` can include this
//! file and replay every saved corpus entry and crash on stable Rust, without libFuzzer. A
//! failing check prints its points as Rust source, ready to paste into a test.

use condt::{Error, Method, Params, Point, Repair, Stage, Uniformity, MAX_POINTS};
use condt_io::parse_points as parse;
use condt_io::{parse_csv, parse_geojson, parse_node, parse_npy};
use condt_io::{write_edges, write_geojson, write_polylines, write_svg, write_svg_stages};
use std::collections::BTreeSet;
use std::fmt::Write as _;

/// Reads the fuzzer's bytes front to back; past the end every read yields zeros, so any input
/// decodes to something.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn array<const N: usize>(&mut self) -> [u8; N] {
        let mut out = [0; N];
        for b in &mut out {
            *b = self.byte();
        }
        out
    }

    fn f64_bits(&mut self) -> f64 {
        f64::from_le_bytes(self.array())
    }

    /// A value a user could pass by mistake or on purpose: the boundaries of every parameter's
    /// range, signed zeros, non-finite values, extremes, or any bit pattern.
    fn nasty_f64(&mut self) -> f64 {
        const SPECIAL: [f64; 16] = [
            0.0,
            -0.0,
            -1.0,
            0.5,
            1.0,
            1.7,
            2.75,
            1e-300,
            1e300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let tag = self.byte();
        if tag < 128 {
            SPECIAL[tag as usize % SPECIAL.len()]
        } else if tag < 192 {
            // Small values around the useful range of `u` and `k`.
            f64::from(i16::from_le_bytes(self.array())) / 256.0
        } else {
            self.f64_bits()
        }
    }
}

/// Decodes points. A random bit pattern is almost always a huge or tiny number, which leaves the
/// interesting sets (duplicates, collinear runs, cocircular quadruples, points a few ulps apart,
/// a wide dynamic range) out of reach; so a tag byte before each point picks its encoding.
fn decode_points(bytes: &mut Bytes) -> Vec<Point> {
    let mut points: Vec<Point> = Vec::new();
    while !bytes.is_empty() {
        let tag = bytes.byte();
        let p = match tag % 4 {
            // Any bit pattern, NaN and infinities included.
            0 => Point::new(bytes.f64_bits(), bytes.f64_bits()),
            // A small integer grid: duplicates, collinear and cocircular points.
            1 => {
                let [x, y] = bytes.array::<2>().map(|b| f64::from(b as i8));
                Point::new(x, y)
            }
            // A 16-bit grid scaled by 2^e, e in -32..32 from the tag: the same shapes at other
            // magnitudes, and a spread of magnitudes within one set.
            2 => {
                let scale = pow2(i32::from(tag >> 2) - 32);
                let x = f64::from(i16::from_le_bytes(bytes.array()));
                let y = f64::from(i16::from_le_bytes(bytes.array()));
                Point::new(x * scale, y * scale)
            }
            // An earlier point moved by a few ulps in each coordinate: near-degenerate
            // configurations the predicates must decide exactly.
            _ => match points.len() {
                0 => Point::new(0.0, 0.0),
                n => {
                    let base = points[bytes.byte() as usize % n];
                    let [dx, dy] = bytes.array::<2>().map(|b| i64::from(b as i8 % 4));
                    Point::new(nudge(base.x, dx), nudge(base.y, dy))
                }
            },
        };
        points.push(p);
    }
    points
}

/// 2^e for a small `e`, exact.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((1023 + e) as u64) << 52)
}

/// `x` moved by `ulps` representable steps (a finite `x` stays finite or becomes infinite).
fn nudge(x: f64, ulps: i64) -> f64 {
    let mut x = x;
    for _ in 0..ulps.unsigned_abs() {
        x = if ulps > 0 { x.next_up() } else { x.next_down() };
    }
    x
}

/// The points as Rust source, for a test reproducing a finding.
fn as_rust(points: &[Point]) -> String {
    let mut s = String::from("let points = [\n");
    for p in points {
        let _ = writeln!(s, "    Point::new({:?}, {:?}),", p.x, p.y);
    }
    s.push_str("];");
    s
}

fn finite(p: Point) -> bool {
    p.x.is_finite() && p.y.is_finite()
}

/// Checks an error the triangulation may return for `points`: it must be about the input, and
/// true of it.
fn check_input_error(points: &[Point], err: Error, context: &str, measuring: bool) {
    let fail = |why: &str| panic!("{context}: {why} ({err:?})\n{}", as_rust(points));
    assert!(!err.to_string().is_empty());
    match err {
        Error::NonFinite { index } => {
            if points.get(index).is_none_or(|&p| finite(p)) {
                fail("NonFinite names a finite point or none");
            }
        }
        Error::TooManyPoints { count, limit } => {
            if count != points.len() || count <= limit || limit != MAX_POINTS {
                fail("TooManyPoints for an accepted size");
            }
        }
        // The stages measure down to 2^-450 times the largest magnitude (its power of two within
        // a factor 2): two distinct finite points nearer than that, named by position.
        Error::TooCloseToMeasure { first, second, .. } => {
            let largest = points
                .iter()
                .map(|p| p.x.abs().max(p.y.abs()))
                .fold(0.0, f64::max);
            let near = match (points.get(first), points.get(second)) {
                (Some(&p), Some(&q)) if first < second && p != q => {
                    (p.x - q.x).hypot(p.y - q.y) < 2f64.powi(-449) * largest
                }
                _ => false,
            };
            if !measuring || !near {
                fail("TooCloseToMeasure for points the stages measure, or from triangulate");
            }
        }
        Error::InvalidParameter { .. } | Error::InvalidTriangulation(_) => {
            fail("an error that is not about the points")
        }
        // Every finite set triangulates (exact integer predicates beyond the fast range), so
        // no other refusal is true of any input.
        _ => fail("a refusal other than a non-finite point, too many or too close points"),
    }
}

/// Target `triangulate`: any decoded point set either triangulates into a mesh that passes the
/// exact [`validate`](condt::Triangulation::validate) check and keeps every input point, or is
/// refused with an error that is true of it.
pub fn triangulate(data: &[u8]) {
    let points = decode_points(&mut Bytes(data));
    let tri = match condt::triangulate(&points) {
        Ok(tri) => tri,
        Err(err) => return check_input_error(&points, err, "triangulate", false),
    };
    let fail = |why: String| panic!("triangulate: {why}\n{}", as_rust(&points));
    if let Err(violation) = tri.validate() {
        fail(format!("validate() failed: {violation}"));
    }
    if !points.iter().all(|&p| finite(p)) {
        fail("accepted a non-finite point".into());
    }
    if tri.num_points() != points.len() {
        fail(format!(
            "{} points kept of {}",
            tri.num_points(),
            points.len()
        ));
    }
    // Every input position maps to a vertex at the same coordinates (a duplicate to the one
    // kept), and the vertices are exactly the distinct points.
    for (i, &p) in points.iter().enumerate() {
        let kept = tri.input_of(tri.vertex(i));
        if points[kept] != p || tri.point(i) != p {
            fail(format!(
                "point {i} maps to point {kept} at other coordinates"
            ));
        }
    }
    let distinct: BTreeSet<(u64, u64)> = points
        .iter()
        // -0.0 and 0.0 are the same point.
        .map(|p| ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits()))
        .collect();
    if tri.num_vertices() != distinct.len() || tri.distinct_points().count() != distinct.len() {
        fail(format!(
            "{} vertices for {} distinct points",
            tri.num_vertices(),
            distinct.len()
        ));
    }
}

/// Decodes arbitrary parameters, nonsense values included, over the default (so fields added
/// later keep their defaults): every field of [`Params`] is varied, each stage switched by a bit
/// of its own. A bit set switches a step off and the zeros read past the data's end leave the
/// default, so that short inputs still run the whole default pipeline.
fn decode_params(bytes: &mut Bytes) -> Params {
    let uniformity = match bytes.byte() % 4 {
        0 => Uniformity::Adaptive,
        _ => Uniformity::Fixed(bytes.nasty_f64()),
    };
    let repair = [
        Repair::Off,
        Repair::Paper,
        Repair::Mutual,
        Repair::CrossingAware,
        Repair::Needs,
    ][bytes.byte() as usize % 5];
    let outlier_factor = match bytes.byte() % 4 {
        0 => None,
        _ => Some(bytes.nasty_f64()),
    };
    let flags = bytes.byte();
    let method = match bytes.byte() % 8 {
        6 => Method::NnCrust,
        7 => Method::Crust,
        _ => Method::ConDT,
    };
    let stages_off = u32::from_le_bytes([bytes.byte(), bytes.byte(), bytes.byte(), 0]);
    let mut params = Params::default()
        .with_method(method)
        .with_uniformity(uniformity)
        .with_repair(repair)
        .with_outlier_factor(outlier_factor)
        .with_outliers_first(flags & 1 != 0)
        .with_iqr_floor(flags & 2 == 0)
        .with_smooth(flags & 4 == 0)
        .with_parallel(flags & 8 != 0);
    for (bit, stage) in Stage::ALL.into_iter().enumerate() {
        params.set_stage(stage, stages_off >> bit & 1 == 0);
    }
    params
}

/// Target `reconstruct`: the whole pipeline with arbitrary parameters returns a consistent
/// result, or an error; it never panics. Refused parameters always give
/// [`Error::InvalidParameter`], whatever the points; a result's edges join distinct input
/// positions, lie on exactly one curve each, leave every unused point alone, and every output
/// format writes it.
pub fn reconstruct(data: &[u8]) {
    let mut bytes = Bytes(data);
    let params = decode_params(&mut bytes);
    let points = decode_points(&mut bytes);
    let context = || format!("reconstruct with {params:?}\n{}", as_rust(&points));
    let result = match condt::reconstruct(&points, &params) {
        Ok(result) => result,
        Err(err) => {
            match (params.check(), err) {
                (Err(_), Error::InvalidParameter { .. }) => {}
                (Err(_), _) => panic!("refused parameters gave {err:?}: {}", context()),
                (Ok(()), _) => check_input_error(&points, err, &context(), true),
            }
            return;
        }
    };
    if params.check().is_err() {
        panic!("refused parameters ran: {}", context());
    }
    let n = points.len();
    if result.num_points() != n {
        panic!("{} points of {n}: {}", result.num_points(), context());
    }
    let edges: BTreeSet<[usize; 2]> = result.edges().collect();
    if edges.len() != result.edges().len() {
        panic!("an edge is listed twice: {}", context());
    }
    for &[a, b] in &edges {
        if a >= b || b >= n {
            panic!(
                "edge [{a}, {b}] is not an ordered pair of input positions: {}",
                context()
            );
        }
    }
    let mut on_curves = 0;
    for curve in result.curves() {
        for [a, b] in curve.edges() {
            on_curves += 1;
            if !edges.contains(&[a.min(b), a.max(b)]) {
                panic!("curve edge [{a}, {b}] is not an edge: {}", context());
            }
        }
    }
    if on_curves != edges.len() {
        panic!(
            "{on_curves} curve edges for {} edges: {}",
            edges.len(),
            context()
        );
    }
    for &i in result.unused() {
        if i >= n || result.degree(i) != 0 {
            panic!("unused point {i} has edges: {}", context());
        }
    }
    let mut out = Vec::new();
    let written = write_edges(&mut out, &result)
        .and_then(|()| write_polylines(&mut out, &result))
        .and_then(|()| write_geojson(&mut out, &result, &points))
        .and_then(|()| write_svg(&mut out, &result, &points))
        .and_then(|()| write_svg_stages(&mut out, &result));
    if let Err(err) = written {
        panic!("writing to memory failed ({err}): {}", context());
    }
}

/// Number of lines as the point-file reader counts them: `\n`, `\r\n` and a lone `\r` each end
/// one, and text after the last end is one more.
fn count_lines(text: &str) -> usize {
    let bytes = text.as_bytes();
    let mut lines = 0;
    let mut i = 0;
    let mut open = false;
    while i < bytes.len() {
        match bytes[i] {
            b'\r' => {
                lines += 1;
                open = false;
                if bytes.get(i + 1) == Some(&b'\n') {
                    i += 1;
                }
            }
            b'\n' => {
                lines += 1;
                open = false;
            }
            _ => open = true,
        }
        i += 1;
    }
    lines + usize::from(open)
}

/// Target `parse_points`: the point-file parser either reads finite points, at most one a line,
/// that survive a round trip through the plainest format, or refuses with an error that names
/// the file and a line that exists. Bytes that are not UTF-8 are read as the lossy text.
pub fn parse_points(data: &[u8]) {
    const FILE: &str = "fuzz.txt";
    let text = String::from_utf8_lossy(data);
    let lines = count_lines(&text);
    match parse(&text, FILE) {
        Ok(points) => {
            assert!(
                points.iter().all(|&p| finite(p)),
                "non-finite point read from {text:?}"
            );
            assert!(
                points.len() <= lines,
                "{} points from {lines} lines of {text:?}",
                points.len()
            );
            // `{}` prints the shortest decimal that reads back to the same f64.
            let plain: String = points
                .iter()
                .map(|p| format!("{} {}\n", p.x, p.y))
                .collect();
            let again = parse(&plain, FILE)
                .unwrap_or_else(|e| panic!("{e}: re-reading {plain:?}, read from {text:?}"));
            let bits = |ps: &[Point]| -> Vec<(u64, u64)> {
                ps.iter().map(|p| (p.x.to_bits(), p.y.to_bits())).collect()
            };
            assert_eq!(
                bits(&points),
                bits(&again),
                "round trip of {text:?} through {plain:?}"
            );
        }
        Err(err) => {
            assert_eq!(err.file, FILE, "error names another file: {err}");
            if let Some(line) = err.line {
                assert!(
                    (1..=lines).contains(&line),
                    "error names line {line} of {lines}: {err}, for {text:?}"
                );
            }
            assert!(
                err.to_string().starts_with(FILE),
                "message does not start with the file: {err}"
            );
        }
    }
}

/// The readers of the other input formats, chosen by the first byte (its value modulo four):
/// `.npy` (the rest as bytes), CSV, GeoJSON and Triangle's `.node` (the rest as lossy UTF-8).
/// Each must return finite points or an error that names the file and, where it gives a line,
/// a line the text has; never panic.
pub fn parse_formats(data: &[u8]) {
    let Some((&choice, rest)) = data.split_first() else {
        return;
    };
    let text = String::from_utf8_lossy(rest);
    let (file, read) = match choice % 4 {
        0 => ("fuzz.npy", parse_npy(rest, "fuzz.npy")),
        1 => ("fuzz.csv", parse_csv(&text, "fuzz.csv")),
        2 => ("fuzz.geojson", parse_geojson(&text, "fuzz.geojson")),
        _ => ("fuzz.node", parse_node(&text, "fuzz.node")),
    };
    match read {
        Ok(points) => assert!(
            points.iter().all(|&p| finite(p)),
            "non-finite point read from {file}: {rest:?}"
        ),
        Err(err) => {
            assert_eq!(err.file, file, "error names another file: {err}");
            assert!(
                err.to_string().starts_with(file),
                "message does not start with the file: {err}"
            );
            // A `.npy` error speaks of the header or of rows, not of lines of text.
            // An error at the end of the text may name the line the end is on: the first of an
            // empty text, the one after a final line break.
            if let (Some(line), false) = (err.line, choice % 4 == 0) {
                let end_line_allowed = text.is_empty() || text.ends_with(['\n', '\r']);
                let lines = count_lines(&text) + usize::from(end_line_allowed);
                assert!(
                    (1..=lines).contains(&line),
                    "error names line {line} of {lines}: {err}, for {text:?}"
                );
            }
        }
    }
}
