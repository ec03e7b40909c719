//! Edge sets and adjacency: the graphs the ConDT stages pass to each other and curves are read from.
//!
//! Owns: the canonical edge list (sorted `[a, b]`, `a < b`) and its compressed adjacency. It may not
//! look at coordinates.

use crate::mesh::VertexId;
use alloc::vec;
use alloc::vec::Vec;

/// An undirected edge `[a, b]` with `a < b`, in vertex ids (input positions).
pub type Edge = [VertexId; 2];

/// `[a, b]` ordered so that `a < b`.
#[inline]
pub(crate) fn ordered(a: VertexId, b: VertexId) -> Edge {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// Sorts and removes repeats, the canonical form of every edge list the stages return.
pub(crate) fn canonical(mut edges: Vec<Edge>) -> Vec<Edge> {
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Compressed adjacency of an edge list over `vertex_count` vertices: the neighbours of `v` are
/// `neighbors[offsets[v]..offsets[v + 1]]`, in increasing id.
pub(crate) struct Adjacency {
    offsets: Vec<u32>,
    neighbors: Vec<VertexId>,
}

impl Adjacency {
    pub(crate) fn new(vertex_count: usize, edges: &[Edge]) -> Self {
        let mut offsets = vec![0u32; vertex_count + 1];
        for &[a, b] in edges {
            offsets[a.index() + 1] += 1;
            offsets[b.index() + 1] += 1;
        }
        for i in 0..vertex_count {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut neighbors = vec![VertexId::INFINITE; 2 * edges.len()];
        for &[a, b] in edges {
            neighbors[fill[a.index()] as usize] = b;
            fill[a.index()] += 1;
            neighbors[fill[b.index()] as usize] = a;
            fill[b.index()] += 1;
        }
        // Edges arrive sorted, so each list is sorted except where a vertex appears as `b`
        // before appearing as `a`; sort each short list to make the order independent of that.
        for v in 0..vertex_count {
            neighbors[offsets[v] as usize..offsets[v + 1] as usize].sort_unstable();
        }
        Adjacency { offsets, neighbors }
    }

    #[inline]
    pub(crate) fn neighbors(&self, v: VertexId) -> &[VertexId] {
        &self.neighbors[self.offsets[v.index()] as usize..self.offsets[v.index() + 1] as usize]
    }

    #[inline]
    pub(crate) fn degree(&self, v: VertexId) -> usize {
        (self.offsets[v.index() + 1] - self.offsets[v.index()]) as usize
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.offsets.len() - 1
    }
}

/// The degree of every vertex in `edges`, indexed by vertex id.
pub(crate) fn degrees(vertex_count: usize, edges: &[Edge]) -> Vec<u32> {
    let mut degree = vec![0u32; vertex_count];
    for &[a, b] in edges {
        degree[a.index()] += 1;
        degree[b.index()] += 1;
    }
    degree
}
