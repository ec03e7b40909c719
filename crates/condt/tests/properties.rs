//! Properties that must hold for every finite input, checked with quickcheck on arbitrary point
//! sets built to contain duplicates, collinear runs and cocircular points.

mod common;

use common::*;
use condt::{triangulate, Error, Point};
use quickcheck::{Arbitrary, Gen, QuickCheck, TestResult};
use std::collections::BTreeSet;

/// A point set of small dyadic coordinates (multiples of 1/4 within ±64): exact under
/// translation by powers of two, and full of duplicates, collinear runs and cocircular points.
#[derive(Clone, Debug)]
struct PointSet(Vec<Point>);

fn small_coordinate(g: &mut Gen) -> f64 {
    (i16::arbitrary(g) % 256) as f64 / 4.0
}

impl Arbitrary for PointSet {
    fn arbitrary(g: &mut Gen) -> Self {
        let mut pts = Vec::new();
        let pieces = 1 + usize::arbitrary(g) % 4;
        for _ in 0..pieces {
            let count = usize::arbitrary(g) % (g.size() + 1);
            match u8::arbitrary(g) % 4 {
                // Scattered points.
                0 => pts.extend(
                    (0..count).map(|_| Point::new(small_coordinate(g), small_coordinate(g))),
                ),
                // A collinear run with a small integer direction.
                1 => {
                    let start = Point::new(small_coordinate(g), small_coordinate(g));
                    let (dx, dy) = ((i8::arbitrary(g) % 5) as f64, (i8::arbitrary(g) % 5) as f64);
                    pts.extend(
                        (0..count)
                            .map(|k| Point::new(start.x + dx * k as f64, start.y + dy * k as f64)),
                    );
                }
                // Points of a tiny lattice: duplicates and cocircular squares.
                2 => pts.extend((0..count).map(|_| {
                    Point::new((u8::arbitrary(g) % 4) as f64, (u8::arbitrary(g) % 4) as f64)
                })),
                // Repeats of points already drawn.
                _ => {
                    for _ in 0..count {
                        if let Some(&p) = pts.get(usize::arbitrary(g) % (pts.len() + 1)) {
                            pts.push(p);
                        }
                    }
                }
            }
        }
        PointSet(pts)
    }

    fn shrink(&self) -> Box<dyn Iterator<Item = Self>> {
        let pairs: Vec<(f64, f64)> = self.0.iter().map(|p| (p.x, p.y)).collect();
        Box::new(
            pairs
                .shrink()
                .map(|v| PointSet(v.into_iter().map(Point::from).collect())),
        )
    }
}

fn quickcheck() -> QuickCheck {
    QuickCheck::new()
        .tests(400)
        .max_tests(4000)
        .rng(Gen::new(60))
}

#[test]
fn every_triangulation_validates() {
    fn prop(set: PointSet) -> bool {
        let tri = triangulate(&set.0).expect("finite input");
        tri.validate()
            .map_err(|e| panic!("{e} on {:?}", set.0))
            .is_ok()
    }
    quickcheck().quickcheck(prop as fn(PointSet) -> bool);
}

/// `Mesh::adjacent` (the two rings walked in turn, for speed at hubs) answers as a walk of one
/// ring does, for every pair of vertices, on sets full of ties and duplicates and on a fan.
#[test]
fn adjacency_is_what_either_ring_says() {
    fn check(points: &[Point]) {
        let tri = triangulate(points).expect("finite input");
        let mesh = tri.mesh();
        let vertices: Vec<_> = tri.distinct_points().map(|i| tri.vertex(i)).collect();
        for &a in &vertices {
            for &b in &vertices {
                let on_ring = mesh.neighbors(a).any(|w| w == b);
                assert_eq!(mesh.adjacent(a, b), on_ring, "{a:?} {b:?} of {points:?}");
            }
        }
    }
    fn prop(set: PointSet) -> bool {
        check(&set.0);
        true
    }
    quickcheck().quickcheck(prop as fn(PointSet) -> bool);
    let mut fan: Vec<Point> = (0..200).map(|k| Point::new(k as f64, 0.0)).collect();
    fan.push(Point::new(100.5, 3.0));
    check(&fan);
}

#[test]
fn counts_follow_euler_with_the_hull_size() {
    fn prop(set: PointSet) -> bool {
        let tri = triangulate(&set.0).expect("finite input");
        let (v, e, t) = (
            tri.num_vertices(),
            tri.edges().count(),
            tri.triangles().count(),
        );
        if tri.is_degenerate() {
            // A chain: no triangle, one edge between consecutive distinct points.
            return t == 0 && e == v.saturating_sub(1);
        }
        let h = tri.hull().count();
        t == 2 * v - 2 - h && e == 3 * v - 3 - h
    }
    quickcheck().quickcheck(prop as fn(PointSet) -> bool);
}

#[test]
fn hull_is_convex_and_contains_every_point() {
    fn prop(set: PointSet) -> bool {
        let tri = triangulate(&set.0).expect("finite input");
        assert_hull_convex_and_enclosing(&tri);
        true
    }
    quickcheck().quickcheck(prop as fn(PointSet) -> bool);
}

#[test]
fn permuting_the_input_permutes_the_edges() {
    fn prop(set: PointSet, seed: u64) -> bool {
        let tri = triangulate(&set.0).expect("finite input");
        let mut order: Vec<usize> = (0..set.0.len()).collect();
        Rng::new(seed).shuffle(&mut order);
        let shuffled: Vec<Point> = order.iter().map(|&i| set.0[i]).collect();
        let other = triangulate(&shuffled).expect("finite input");
        // Name each vertex of the shuffled run by the original representative of its point.
        let rename = |j: usize| tri.input_of(tri.vertex(order[j]));
        let mapped: BTreeSet<(usize, usize)> = other
            .edges()
            .map(|[a, b]| {
                let (a, b) = (rename(a), rename(b));
                (a.min(b), a.max(b))
            })
            .collect();
        mapped == edge_set(&tri)
    }
    quickcheck().quickcheck(prop as fn(PointSet, u64) -> bool);
}

#[test]
fn translating_by_a_power_of_two_keeps_the_edges() {
    fn prop(set: PointSet, shift: (u8, u8), signs: (bool, bool)) -> bool {
        let power =
            |k: u8, negative: bool| if negative { -1.0 } else { 1.0 } * 2f64.powi((k % 40) as i32);
        let (dx, dy) = (power(shift.0, signs.0), power(shift.1, signs.1));
        let moved: Vec<Point> = set
            .0
            .iter()
            .map(|p| Point::new(p.x + dx, p.y + dy))
            .collect();
        let (a, b) = (
            triangulate(&set.0).expect("finite"),
            triangulate(&moved).expect("finite"),
        );
        edge_set(&a) == edge_set(&b)
    }
    quickcheck().quickcheck(prop as fn(PointSet, (u8, u8), (bool, bool)) -> bool);
}

#[test]
fn arbitrary_doubles_are_triangulated_or_refused_for_a_stated_reason() {
    fn prop(raw: Vec<(f64, f64)>) -> TestResult {
        let pts: Vec<Point> = raw.iter().map(|&(x, y)| Point::new(x, y)).collect();
        match triangulate(&pts) {
            Ok(tri) => {
                if let Err(e) = tri.validate() {
                    panic!("{e} on {pts:?}");
                }
                TestResult::passed()
            }
            Err(Error::NonFinite { index }) => TestResult::from_bool(!pts[index].is_finite()),
            Err(other) => panic!("unexpected {other}"),
        }
    }
    QuickCheck::new()
        .tests(1000)
        .quickcheck(prop as fn(Vec<(f64, f64)>) -> TestResult);
}

/// A token of the characters numbers are written with, in any order: most are not numbers.
#[derive(Clone, Debug)]
struct NumberishToken(String);

impl Arbitrary for NumberishToken {
    fn arbitrary(g: &mut Gen) -> Self {
        const CHARS: &[u8] = b"0123456789012345678901234567890123456789..--+eE";
        let len = 1 + usize::arbitrary(g) % 30;
        let mut token: String = (0..len)
            .map(|_| char::from(*g.choose(CHARS).unwrap()))
            .collect();
        // Often a well-formed number: a sign, digits, a point, digits, an exponent (or, with
        // no digits, a malformed one).
        if bool::arbitrary(g) {
            let digits = |g: &mut Gen, n: usize| -> String {
                (0..n)
                    .map(|_| char::from(b'0' + u8::arbitrary(g) % 10))
                    .collect()
            };
            let (a, b) = (usize::arbitrary(g) % 9, usize::arbitrary(g) % 24);
            token = format!(
                "{}{}.{}{}",
                ["", "-", "+"][usize::arbitrary(g) % 3],
                digits(g, a),
                digits(g, b),
                match u8::arbitrary(g) % 4 {
                    0 => format!("e{}", i16::arbitrary(g) % 400),
                    _ => String::new(),
                }
            );
        }
        NumberishToken(token)
    }

    fn shrink(&self) -> Box<dyn Iterator<Item = Self>> {
        Box::new(
            self.0
                .shrink()
                .filter(|s| !s.is_empty() && !s.contains(char::is_whitespace))
                .map(NumberishToken),
        )
    }
}

#[test]
fn parsed_coordinates_are_those_of_str_parse() {
    // Lines `a b` after a first point: the text parses exactly when every token is a finite
    // number by `str::parse::<f64>`, and then to those numbers bit for bit.
    fn prop(lines: Vec<(NumberishToken, NumberishToken)>, crlf: bool) -> bool {
        let end = if crlf { "\r\n" } else { "\n" };
        let mut text = format!("0 0{end}");
        let mut expected = vec![Point::new(0.0, 0.0)];
        let mut all_finite = true;
        for (a, b) in &lines {
            text.push_str(&format!("{} {}{end}", a.0, b.0));
            match (a.0.parse::<f64>(), b.0.parse::<f64>()) {
                (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => expected.push(Point::new(x, y)),
                _ => all_finite = false,
            }
        }
        let bits = |p: &[Point]| -> Vec<(u64, u64)> {
            p.iter().map(|q| (q.x.to_bits(), q.y.to_bits())).collect()
        };
        match condt_io::parse_points(&text, "t.txt") {
            Ok(points) => all_finite && bits(&points) == bits(&expected),
            Err(_) => !all_finite,
        }
    }
    QuickCheck::new()
        .tests(3000)
        .quickcheck(prop as fn(Vec<(NumberishToken, NumberishToken)>, bool) -> bool);
}

#[test]
fn written_doubles_parse_back_bit_for_bit() {
    // Any finite doubles written in the shortest form, in exponent form, or with 15 to 20
    // significant digits come back as `str::parse` reads them.
    fn prop(raw: Vec<(f64, f64)>, style: u8) -> bool {
        let write = |v: f64| match style % 4 {
            0 => format!("{v}"),
            1 => format!("{v:e}"),
            2 => format!("{v:.*e}", 14 + usize::from(style / 4) % 6),
            _ => format!("{:.*}", usize::from(style / 4) % 20, v),
        };
        // Rounded to fewer digits, the largest doubles are written as numbers beyond the
        // range, which the reader refuses as it should: left out.
        let finite = |v: f64| write(v).parse::<f64>().is_ok_and(f64::is_finite);
        let points: Vec<(f64, f64)> = raw
            .into_iter()
            .filter(|&(x, y)| finite(x) && finite(y))
            .collect();
        let text: String = points
            .iter()
            .map(|&(x, y)| format!("{}\t{}\n", write(x), write(y)))
            .collect();
        let expected: Vec<(u64, u64)> = points
            .iter()
            .map(|&(x, y)| {
                let back = |v: f64| write(v).parse::<f64>().unwrap().to_bits();
                (back(x), back(y))
            })
            .collect();
        match condt_io::parse_points(&text, "t.txt") {
            Ok(read) => {
                read.iter()
                    .map(|p| (p.x.to_bits(), p.y.to_bits()))
                    .collect::<Vec<_>>()
                    == expected
            }
            // Nothing here is to refuse: two finite numbers a line.
            Err(e) => panic!("{e}"),
        }
    }
    QuickCheck::new()
        .tests(2000)
        .quickcheck(prop as fn(Vec<(f64, f64)>, u8) -> bool);
}
