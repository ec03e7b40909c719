//! Edge lists in vertex ids and their adjacency: the internal form of the graphs the stages pass
//! to each other and curves are read from.
//!
//! Owns: the edge list (`[a, b]`, `a < b`, each edge once), its compressed adjacency, the curve
//! graph that keeps each vertex's first two neighbours inline for walking curves, and the O(n)
//! pair sort. It may not look at coordinates, and nothing here is public: users see edges in input
//! positions through [`Graph`](crate::Graph).

use crate::mesh::VertexId;
use alloc::vec;
use alloc::vec::Vec;

/// An undirected edge `[a, b]` with `a < b`, in vertex ids.
pub(crate) type Edge = [VertexId; 2];

/// `[a, b]` ordered so that `a < b`.
#[inline]
pub(crate) fn ordered(a: VertexId, b: VertexId) -> Edge {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// Compressed adjacency of an edge list over `vertex_count` vertices: the neighbours of `v` are
/// `neighbors[offsets[v]..offsets[v + 1]]`, in the order the edges are listed, each with the
/// position of its edge in the list.
pub(crate) struct Adjacency {
    offsets: Vec<u32>,
    neighbors: Vec<(VertexId, u32)>,
}

impl Adjacency {
    /// `edges` must list every edge once (`[a, b]` with `a < b`, in any order). Built by counting,
    /// in O(n), without sorting.
    pub(crate) fn new(vertex_count: usize, edges: &[Edge]) -> Self {
        debug_assert!(edges.iter().all(|e| e[0] < e[1]));
        let mut offsets = vec![0u32; vertex_count + 1];
        for &[a, b] in edges {
            offsets[a.index() + 1] += 1;
            offsets[b.index() + 1] += 1;
        }
        for i in 0..vertex_count {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut neighbors = vec![(VertexId::INFINITE, 0); 2 * edges.len()];
        for (k, &[a, b]) in edges.iter().enumerate() {
            neighbors[fill[a.index()] as usize] = (b, k as u32);
            fill[a.index()] += 1;
            neighbors[fill[b.index()] as usize] = (a, k as u32);
            fill[b.index()] += 1;
        }
        Adjacency { offsets, neighbors }
    }

    /// The neighbours of `v` with the positions of the joining edges.
    #[inline]
    pub(crate) fn incident(&self, v: VertexId) -> &[(VertexId, u32)] {
        &self.neighbors[self.offsets[v.index()] as usize..self.offsets[v.index() + 1] as usize]
    }
}

/// The neighbours of every vertex of a graph that is a union of curves: almost every vertex has
/// at most two. Those two are stored inline, so following a curve costs one read per step (a
/// compressed adjacency costs two dependent ones); a full [`Adjacency`] is built only when some
/// vertex has three or more.
pub(crate) struct CurveGraph {
    degree: Vec<u32>,
    first_two: Vec<[VertexId; 2]>,
    branching: Option<Adjacency>,
}

impl CurveGraph {
    /// `edges` as for [`Adjacency::new`]. Neighbours come in the order the edges are listed.
    pub(crate) fn new(vertex_count: usize, edges: &[Edge]) -> Self {
        let mut degree = vec![0u32; vertex_count];
        let mut first_two = vec![[VertexId::INFINITE; 2]; vertex_count];
        let mut branches = false;
        for &[a, b] in edges {
            for (v, w) in [(a, b), (b, a)] {
                let d = degree[v.index()];
                degree[v.index()] = d + 1;
                // Whether the slot fills is a coin toss per edge: selected, not branched on.
                let slots = &mut first_two[v.index()];
                let k = d.min(1) as usize;
                slots[k] = if d < 2 { w } else { slots[k] };
                branches |= d >= 2;
            }
        }
        let branching = branches.then(|| Adjacency::new(vertex_count, edges));
        CurveGraph {
            degree,
            first_two,
            branching,
        }
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.degree.len()
    }

    #[inline]
    pub(crate) fn degree(&self, v: VertexId) -> usize {
        self.degree[v.index()] as usize
    }

    /// The `k`-th neighbour of `v`, `k < degree(v)`.
    #[inline]
    pub(crate) fn neighbor(&self, v: VertexId, k: usize) -> VertexId {
        match &self.branching {
            Some(all) if self.degree(v) > 2 => all.incident(v)[k].0,
            _ => self.first_two[v.index()][k],
        }
    }

    /// The first two neighbours of `v` ([`VertexId::INFINITE`] where it has fewer); all of
    /// them when `degree(v) <= 2`.
    #[inline]
    pub(crate) fn first_two(&self, v: VertexId) -> [VertexId; 2] {
        self.first_two[v.index()]
    }

    /// For `v` of degree two and `from` one of its neighbours, the other one: the next step along
    /// a curve. Which slot holds `from` is a coin toss, so the other is taken by exclusive or
    /// (`x ^ y ^ x = y`) rather than by a branch the predictor would miss half the time.
    #[inline]
    pub(crate) fn onward(&self, v: VertexId, from: VertexId) -> VertexId {
        let [x, y] = self.first_two[v.index()];
        debug_assert!(from == x || from == y);
        VertexId::new(x.index() as u32 ^ y.index() as u32 ^ from.index() as u32)
    }
}

/// Sorts pairs `[a, b]` with `index(a) < bound` by `(a, b)` and drops repeats, in O(n): a
/// counting sort by the first element, then a sort of each (short) bucket by the second.
pub(crate) fn sort_pairs<T: Copy + Ord>(
    bound: usize,
    pairs: impl Iterator<Item = [T; 2]> + Clone,
    count: usize,
    index: impl Fn(T) -> usize,
) -> Vec<[T; 2]> {
    let mut ends = vec![0u32; bound + 1];
    for [a, _] in pairs.clone() {
        ends[index(a) + 1] += 1;
    }
    for i in 0..bound {
        ends[i + 1] += ends[i];
    }
    let Some(filler) = pairs.clone().next() else {
        return Vec::new();
    };
    let mut sorted = vec![filler; count];
    for pair in pairs {
        let slot = &mut ends[index(pair[0])];
        sorted[*slot as usize] = pair;
        *slot += 1;
    }
    // Each `ends[a]` has moved to the end of bucket `a`.
    let mut out = Vec::with_capacity(count);
    let mut begin = 0;
    for &end in &ends[..bound] {
        let bucket = &mut sorted[begin..end as usize];
        bucket.sort_unstable();
        let before = out.len();
        for pair in bucket.iter() {
            if out.len() == before || out.last() != Some(pair) {
                out.push(*pair);
            }
        }
        begin = end as usize;
    }
    out
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
