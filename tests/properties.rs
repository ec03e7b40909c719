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
