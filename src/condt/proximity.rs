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
//! The pass is a pure function per vertex over an immutable mesh, so it runs on rayon under the
//! `parallel` feature with the very same function, and gives the same result.

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
    let vertex_count = tri.points().len();
    let choose = |i: usize| {
        let v = VertexId::new(i as u32);
        if tri.vertex_of_input(i) == v {
            kept_neighbors(tri, v, uniformity)
        } else {
            [VertexId::INFINITE; 2]
        }
    };
    let kept: Vec<[VertexId; 2]> = if parallel {
        per_vertex_parallel(vertex_count, &choose)
    } else {
        (0..vertex_count).map(choose).collect()
    };
    let mut edges = Vec::with_capacity(2 * vertex_count);
    for (i, pair) in kept.iter().enumerate() {
        for &w in pair.iter().filter(|w| !w.is_infinite()) {
            edges.push(ordered(VertexId::new(i as u32), w));
        }
    }
    canonical_by_buckets(vertex_count, &edges)
}

#[cfg(feature = "parallel")]
fn per_vertex_parallel(
    count: usize,
    choose: &(dyn Fn(usize) -> [VertexId; 2] + Sync),
) -> Vec<[VertexId; 2]> {
    use rayon::prelude::*;
    (0..count).into_par_iter().map(choose).collect()
}

#[cfg(not(feature = "parallel"))]
fn per_vertex_parallel(
    count: usize,
    choose: &dyn Fn(usize) -> [VertexId; 2],
) -> Vec<[VertexId; 2]> {
    (0..count).map(choose).collect()
}
