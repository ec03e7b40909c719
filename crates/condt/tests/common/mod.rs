//! Point generators and checks shared by the tests and the benches.
#![allow(dead_code)]

use condt::mesh::VertexId;
use condt::predicates::{is_cocircular, orient2d, Orientation};
use condt::{reconstruct, Params, Reconstruction, Stage};
use condt::{Point, Triangulation};
use condt_eval::sample::Sample;
use std::collections::BTreeSet;

/// A small deterministic generator (xorshift64*), so every test input is reproducible by seed.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            items.swap(i, self.below(i + 1));
        }
    }
}

pub fn uniform(n: usize, seed: u64) -> Vec<Point> {
    let mut r = Rng::new(seed);
    (0..n).map(|_| Point::new(r.unit(), r.unit())).collect()
}

/// Tight Gaussian-like clusters (sums of uniforms) around a few centres.
pub fn clustered(n: usize, seed: u64) -> Vec<Point> {
    let mut r = Rng::new(seed);
    let centres: Vec<Point> = (0..1 + r.below(6))
        .map(|_| Point::new(r.unit() * 100.0, r.unit() * 100.0))
        .collect();
    (0..n)
        .map(|_| {
            let c = centres[r.below(centres.len())];
            let spread = 0.01 + r.unit();
            let dx = (r.unit() + r.unit() + r.unit() - 1.5) * spread;
            let dy = (r.unit() + r.unit() + r.unit() - 1.5) * spread;
            Point::new(c.x + dx, c.y + dy)
        })
        .collect()
}

/// `n` points spread over `curves` random ellipses with relative jitter `jitter`, shuffled: the
/// input of curve reconstruction.
pub fn on_ellipses(n: usize, curves: usize, jitter: f64, seed: u64) -> Vec<Point> {
    let mut r = Rng::new(seed);
    let per = n.div_ceil(curves.max(1));
    let mut pts = Vec::with_capacity(n);
    while pts.len() < n {
        let (cx, cy) = (r.unit() * 100.0, r.unit() * 100.0);
        let (a, b, turn) = (
            1.0 + r.unit() * 10.0,
            1.0 + r.unit() * 10.0,
            r.unit() * std::f64::consts::TAU,
        );
        for j in 0..per.min(n - pts.len()) {
            let t = j as f64 / per as f64 * std::f64::consts::TAU;
            let (x, y) = (a * t.cos(), b * t.sin());
            let (jx, jy) = ((r.unit() - 0.5) * jitter, (r.unit() - 0.5) * jitter);
            pts.push(Point::new(
                cx + x * turn.cos() - y * turn.sin() + jx,
                cy + x * turn.sin() + y * turn.cos() + jy,
            ));
        }
    }
    r.shuffle(&mut pts);
    pts
}

/// Small integer coordinates: many duplicates, collinear runs and cocircular quadruples.
pub fn small_integers(n: usize, range: i32, seed: u64) -> Vec<Point> {
    let mut r = Rng::new(seed);
    (0..n)
        .map(|_| {
            let x = r.below(range as usize) as f64;
            let y = r.below(range as usize) as f64;
            Point::new(x, y)
        })
        .collect()
}

/// The `side` x `side` integer grid, shuffled.
pub fn grid(side: usize, seed: u64) -> Vec<Point> {
    let mut pts: Vec<Point> = (0..side * side)
        .map(|i| Point::new((i % side) as f64, (i / side) as f64))
        .collect();
    Rng::new(seed).shuffle(&mut pts);
    pts
}

/// The undirected edges, in input indices, as a sorted set.
pub fn edge_set(tri: &Triangulation) -> BTreeSet<(usize, usize)> {
    tri.edges().map(|[a, b]| (a, b)).collect()
}

/// `true` when some edge between two real triangles has its four points exactly cocircular: then
/// the Delaunay triangulation is not unique.
pub fn has_ambiguous_edge(tri: &Triangulation) -> bool {
    let mesh = tri.mesh();
    let at = |v: VertexId| tri.point(tri.input_of(v));
    mesh.edges().any(|e| {
        let f = mesh.twin(e);
        let (c, d) = (mesh.origin(e.prev()), mesh.origin(f.prev()));
        !c.is_infinite()
            && !d.is_infinite()
            && is_cocircular(at(mesh.origin(e)), at(mesh.dest(e)), at(c), at(d))
    })
}

/// Hull vertices (counter-clockwise) turn left or go straight, and no point lies strictly outside.
pub fn assert_hull_convex_and_enclosing(tri: &Triangulation) {
    let hull: Vec<usize> = tri.hull().collect();
    if tri.is_degenerate() {
        return;
    }
    let h = hull.len();
    for i in 0..h {
        let (a, b, c) = (
            tri.point(hull[i]),
            tri.point(hull[(i + 1) % h]),
            tri.point(hull[(i + 2) % h]),
        );
        assert_ne!(
            orient2d(a, b, c),
            Orientation::Cw,
            "hull turns clockwise at {:?}",
            hull[(i + 1) % h]
        );
        for p in tri.distinct_points().map(|i| tri.point(i)) {
            assert_ne!(
                orient2d(a, b, p),
                Orientation::Cw,
                "point {p:?} outside the hull"
            );
        }
    }
}

// Reconstruction helpers shared by the pipeline tests.

/// The final edges as a set.
pub fn edges(r: &Reconstruction) -> BTreeSet<[usize; 2]> {
    r.edges().collect()
}

/// The final edges in the order the result lists them (sorted).
pub fn final_edges(r: &Reconstruction) -> Vec<[usize; 2]> {
    r.edges().collect()
}

/// The edges `stage` left, sorted; `None` when it did not run.
pub fn stage_edges(r: &Reconstruction, stage: Stage) -> Option<Vec<[usize; 2]>> {
    r.stage(stage).map(|report| report.graph.edges())
}

pub fn truth(s: &Sample) -> BTreeSet<[usize; 2]> {
    s.edges.iter().copied().collect()
}

/// The size from which the stages (and the triangulation, cut in two) take their parallel
/// paths; below it `parallel: true` runs the same sequential code. The crate's
/// `PARALLEL_FROM` (crate-private; a unit test in `stages/proximity.rs` keeps the two equal).
pub const PARALLEL_FROM: usize = 1 << 16;

/// Reconstructs with `params` and returns the result. From [`PARALLEL_FROM`] points, where the
/// parallel paths run, it reconstructs both ways and checks sequential == parallel stage by
/// stage; below, the two would run the same code, so it reconstructs once.
pub fn run(points: &[Point], params: Params) -> Reconstruction {
    if points.len() < PARALLEL_FROM {
        return reconstruct(points, &params).unwrap();
    }
    run_both(points, params)
}

/// Reconstructs sequentially and in parallel, checks that every stage, the curves and the
/// unused points agree, and returns the sequential result. The set must be past
/// [`PARALLEL_FROM`], so that the parallel run takes the parallel paths.
pub fn run_both(points: &[Point], params: Params) -> Reconstruction {
    assert!(
        points.len() >= PARALLEL_FROM,
        "{} points: below the parallel threshold both runs take the same code",
        points.len()
    );
    let sequential = reconstruct(points, &params.with_parallel(false)).unwrap();
    let parallel = reconstruct(points, &params.with_parallel(true)).unwrap();
    for (ours, theirs) in sequential.stages().zip(parallel.stages()) {
        assert_eq!(ours.stage, theirs.stage);
        assert_eq!(ours.applied, theirs.applied);
        assert_eq!(ours.graph.edges(), theirs.graph.edges(), "{}", ours.stage);
    }
    assert_eq!(sequential.stages().len(), parallel.stages().len());
    assert_eq!(final_edges(&sequential), final_edges(&parallel));
    assert_eq!(sequential.curves(), parallel.curves());
    assert_eq!(sequential.unused(), parallel.unused());
    sequential
}
