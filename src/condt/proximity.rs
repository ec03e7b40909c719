//! Stage 1, the ConDT proximity graph (Algorithm 1, lines 2–8).
//!
//! Owns: the per-vertex choice of the two shortest Delaunay edges and the uniformity test. It reads
//! the finished triangulation only; it may not change it.
//!
//! For every vertex `p` the ring of the half-edge mesh is walked once, keeping the two shortest
//! edges `e1 <= e2` (ties: the smaller neighbour id first). `e1` is always kept; `e2` is kept when
//! - fixed `u`: `|e2| < u |e1|` (Algorithm 1, line 6, negated);
//! - adaptive (section 4.1): `|e2| < u_p |e1|` with `u_p = mean |e| / |e1|` over the ring, that is
//!   `|e2| < mean |e|`.
//!
//! Two passes compute the same function: the sequential one sweeps the half-edges once, keeping
//! the two best candidates of each origin (no chain of dependent loads); the parallel one walks
//! each vertex's ring on rayon. Both order candidates by (squared length, neighbour id), a total
//! order, so they agree exactly; the tests compare them on every input.

use super::Uniformity;
use crate::graph::{canonical_by_buckets, ordered, Edge};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;

/// The (at most two) neighbours vertex `v` keeps. No allocation.
fn kept_neighbors(tri: &Triangulation, v: VertexId, uniformity: Uniformity) -> [VertexId; 2] {
    let none = VertexId::INFINITE;
    let p = tri.point(v);
    // (squared length, neighbour): the shortest and the second shortest.
    let (mut first, mut second) = ((f64::INFINITY, none), (f64::INFINITY, none));
    let (mut length_sum, mut count) = (0.0, 0usize);
    for w in tri.neighbors(v) {
        let candidate = (p.dist2(tri.point(w)), w);
        if matches!(uniformity, Uniformity::Adaptive) {
            length_sum += libm::sqrt(candidate.0);
            count += 1;
        }
        if shorter(candidate, first) {
            second = first;
            first = candidate;
        } else if shorter(candidate, second) {
            second = candidate;
        }
    }
    if second.1 == none {
        return [first.1, none];
    }
    let keep_second = match uniformity {
        Uniformity::Fixed(u) => libm::sqrt(second.0) < u * libm::sqrt(first.0),
        Uniformity::Adaptive => libm::sqrt(second.0) < length_sum / count as f64,
    };
    [first.1, if keep_second { second.1 } else { none }]
}

/// Lexicographic (length, id): a total order, so ties never depend on the ring's start.
#[inline]
fn shorter(a: (f64, VertexId), b: (f64, VertexId)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

/// The proximity graph: the union over all vertices of their kept edges, sorted.
pub(crate) fn proximity_graph(
    tri: &Triangulation,
    uniformity: Uniformity,
    parallel: bool,
) -> Vec<Edge> {
    if parallel {
        ring_walks_in_parallel(tri, uniformity)
    } else {
        sweep_half_edges(tri, uniformity)
    }
}

/// The parallel pass: every vertex walks its own ring on rayon.
fn ring_walks_in_parallel(tri: &Triangulation, uniformity: Uniformity) -> Vec<Edge> {
    let n = tri.num_input_points();
    let choose = |i: usize| {
        let v = VertexId::new(i as u32);
        if tri.is_vertex(v) {
            kept_neighbors(tri, v, uniformity)
        } else {
            [VertexId::INFINITE; 2]
        }
    };
    let kept = per_vertex_parallel(n, &choose);
    let mut edges = Vec::with_capacity(2 * n);
    for (i, pair) in kept.iter().enumerate() {
        for &w in pair.iter().filter(|w| !w.is_infinite()) {
            edges.push(ordered(VertexId::new(i as u32), w));
        }
    }
    canonical_by_buckets(n, &edges)
}

#[cfg(feature = "parallel")]
fn per_vertex_parallel(
    count: usize,
    choose: &(dyn Fn(usize) -> [VertexId; 2] + Sync),
) -> Vec<[VertexId; 2]> {
    use rayon::prelude::*;
    (0..count)
        .into_par_iter()
        .with_min_len(1024)
        .map(choose)
        .collect()
}

/// Without the `parallel` feature, the same walks one after the other.
#[cfg(not(feature = "parallel"))]
fn per_vertex_parallel(
    count: usize,
    choose: &dyn Fn(usize) -> [VertexId; 2],
) -> Vec<[VertexId; 2]> {
    (0..count).map(choose).collect()
}

/// The sequential pass: one sweep over the half-edges in memory order, keeping the two best
/// candidates of each origin. The same minima as walking every ring, without the chain of
/// dependent loads a ring walk is; vertex ids follow insertion order, so the sweep stays local.
fn sweep_half_edges(tri: &Triangulation, uniformity: Uniformity) -> Vec<Edge> {
    let n = tri.num_input_points();
    let mesh = tri.mesh();
    let none = (f64::INFINITY, VertexId::INFINITE);
    let mut first = alloc::vec![none; n];
    let mut second = alloc::vec![none; n];
    let mut sum = alloc::vec![0.0f64; n];
    let mut count = alloc::vec![0u32; n];
    for i in 0..mesh.num_half_edges() {
        let e = crate::mesh::HalfEdgeId::new(i as u32);
        let (u, w) = (mesh.origin(e), mesh.dest(e));
        if u.is_infinite() || w.is_infinite() {
            continue;
        }
        let candidate = (tri.point(u).dist2(tri.point(w)), w);
        let k = u.index();
        if matches!(uniformity, Uniformity::Adaptive) {
            sum[k] += libm::sqrt(candidate.0);
            count[k] += 1;
        }
        if shorter(candidate, first[k]) {
            second[k] = first[k];
            first[k] = candidate;
        } else if shorter(candidate, second[k]) {
            second[k] = candidate;
        }
    }
    let mut edges = Vec::with_capacity(2 * n);
    for k in 0..n {
        let v = VertexId::new(k as u32);
        if first[k].1.is_infinite() {
            continue;
        }
        edges.push(ordered(v, first[k].1));
        if second[k].1.is_infinite() {
            continue;
        }
        let keep = match uniformity {
            Uniformity::Fixed(u) => libm::sqrt(second[k].0) < u * libm::sqrt(first[k].0),
            Uniformity::Adaptive => libm::sqrt(second[k].0) < sum[k] / count[k] as f64,
        };
        if keep {
            edges.push(ordered(v, second[k].1));
        }
    }
    canonical_by_buckets(n, &edges)
}
