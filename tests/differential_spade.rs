//! Differential test against spade: on thousands of random point sets both triangulations must
//! agree edge for edge where the Delaunay triangulation is unique, and both must be exactly
//! Delaunay with the same numbers of edges and triangles where it is not.

mod common;

use common::*;
use condt::predicates::in_circle;
use condt::{triangulate, Point, Triangulation};
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation as _};
use std::collections::BTreeSet;

#[derive(Clone, Copy)]
struct Indexed {
    position: Point2<f64>,
    index: usize,
}

impl HasPosition for Indexed {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

struct SpadeResult {
    edges: BTreeSet<(usize, usize)>,
    triangles: usize,
    /// `true` when every interior spade edge passes our exact empty-circle test.
    delaunay: bool,
}

/// Spade's triangulation in input indices; duplicates are mapped to condt's representative so
/// that the two numberings agree whichever duplicate spade kept.
fn spade_triangulation(points: &[Point], condt: &Triangulation) -> SpadeResult {
    let vertices: Vec<Indexed> = points
        .iter()
        .enumerate()
        .map(|(index, p)| Indexed {
            position: Point2::new(p.x, p.y),
            index,
        })
        .collect();
    let dt =
        DelaunayTriangulation::<Indexed>::bulk_load(vertices).expect("spade accepts finite input");
    let name = |v: &Indexed| condt.input_of(condt.vertex(v.index));
    let edges = dt
        .undirected_edges()
        .map(|e| {
            let [a, b] = e.vertices().map(|v| name(v.data()));
            (a.min(b), a.max(b))
        })
        .collect();
    let delaunay = dt.undirected_edges().all(|e| {
        let d = e.as_directed();
        match (d.opposite_vertex(), d.rev().opposite_vertex()) {
            (Some(c), Some(q)) => {
                let p = |v: spade::handles::FixedVertexHandle| points[dt.vertex(v).data().index];
                let (a, b) = (p(d.from().fix()), p(d.to().fix()));
                // (a, b, c) is counter-clockwise in spade's face left of a -> b.
                !in_circle(a, b, p(c.fix()), p(q.fix()))
            }
            _ => true,
        }
    });
    SpadeResult {
        edges,
        triangles: dt.num_inner_faces(),
        delaunay,
    }
}

fn compare(points: &[Point], label: &str) -> bool {
    let tri = triangulate(points).unwrap_or_else(|e| panic!("{label}: {e}"));
    tri.validate().unwrap_or_else(|e| panic!("{label}: {e}"));
    let ours = edge_set(&tri);
    let theirs = spade_triangulation(points, &tri);
    let ambiguous = has_ambiguous_edge(&tri);
    if ambiguous {
        assert!(
            theirs.delaunay,
            "{label}: spade's triangulation is not Delaunay"
        );
        assert_eq!(
            ours.len(),
            theirs.edges.len(),
            "{label}: edge counts differ"
        );
        assert_eq!(
            tri.triangles().count(),
            theirs.triangles,
            "{label}: triangle counts differ"
        );
    } else {
        assert_eq!(
            ours, theirs.edges,
            "{label}: edge sets differ on a unique Delaunay triangulation"
        );
    }
    ambiguous
}

#[test]
fn uniform_sets_match_spade() {
    for seed in 0..1500 {
        let n = 3 + (seed as usize * 7919) % 300;
        compare(&uniform(n, seed), &format!("uniform n={n} seed={seed}"));
    }
}

#[test]
fn clustered_sets_match_spade() {
    for seed in 0..600 {
        let n = 3 + (seed as usize * 104_729) % 400;
        compare(&clustered(n, seed), &format!("clustered n={n} seed={seed}"));
    }
}

#[test]
fn curve_samples_match_spade() {
    for seed in 0..600 {
        let n = 10 + (seed as usize * 613) % 500;
        let curves = 1 + seed as usize % 5;
        let jitter = [0.0, 1e-9, 1e-4][seed as usize % 3];
        compare(
            &on_ellipses(n, curves, jitter, seed),
            &format!("ellipses n={n} seed={seed}"),
        );
    }
}

#[test]
fn small_integer_sets_with_duplicates_match_spade() {
    let mut ambiguous = 0;
    for seed in 0..1500 {
        let n = 3 + (seed as usize * 31) % 120;
        let range = 2 + (seed as i32 % 12);
        ambiguous += compare(
            &small_integers(n, range, seed),
            &format!("integers n={n} seed={seed}"),
        ) as usize;
    }
    // The family exists to exercise cocircular configurations; make sure it does.
    assert!(
        ambiguous > 500,
        "only {ambiguous} sets had cocircular quadruples"
    );
}

#[test]
fn larger_sets_match_spade() {
    for seed in 0..4 {
        compare(&uniform(20_000, 1000 + seed), "uniform 20k");
        compare(&on_ellipses(20_000, 20, 1e-7, 2000 + seed), "ellipses 20k");
    }
}
