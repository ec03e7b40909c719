//! Edge lists in vertex ids and their adjacency: the internal form of the graphs the stages pass on
//! and curves are read from.
//!
//! Owns: the edge list (`[a, b]`, `a < b`, each edge once), [`CurveGraph`], exact-size collection
//! and the O(n) pair sort. It may not look at coordinates (it keeps, unchecked, the one fact about
//! them a stage proved, [`CurveGraph::mark_smooth_cycles`], until the graph changes); nothing here
//! is public (users see edges in input positions through [`Graph`](crate::Graph)).

use crate::mesh::VertexId;
use crate::prefetch::PREFETCH_FROM;
use alloc::vec;
use alloc::vec::Vec;

/// An undirected edge `[a, b]` with `a < b`, in vertex ids.
pub(crate) type Edge = [VertexId; 2];

#[inline]
pub(crate) fn ordered(a: VertexId, b: VertexId) -> Edge {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// The edges along the path `first`, `inner`…, `last`, in order.
pub(crate) fn path_edges(
    first: VertexId,
    inner: &[VertexId],
    last: VertexId,
) -> impl Iterator<Item = Edge> + '_ {
    let inner = inner.iter().copied();
    let path = core::iter::once(first).chain(inner).chain([last]);
    path.clone().zip(path.skip(1)).map(|(a, b)| ordered(a, b))
}

/// The neighbours of every vertex of a union of curves, where almost every vertex has at most two:
/// one 8-byte record per vertex (its first two neighbours and its degree; packed for memory), so
/// following a curve costs one read per vertex; vertices with three or more list them all in a
/// small side table.
#[derive(Clone, Debug)]
pub(crate) struct CurveGraph {
    /// Per vertex id: the first neighbour in the low [`ID_BITS`] bits with the degree (up to
    /// [`DEGREE_SATURATED`]) above, then the second neighbour; [`NO_ID`] where none.
    records: Vec<[u32; 2]>,
    /// The vertices with three or more neighbours, ascending, with where their lists start.
    branch_vertices: Vec<(VertexId, u32)>,
    /// The neighbours of the branch vertices, each vertex's in the order its edges are listed.
    branch_neighbors: Vec<VertexId>,
    /// Whether a stage proved, on its triangulation's positions, that every vertex with edges has
    /// two passing `smooth_and_regular` ([`CurveGraph::mark_smooth_cycles`]); cleared by any
    /// change. Not part of the graph: equality ignores it.
    smooth_cycles: bool,
}

impl PartialEq for CurveGraph {
    fn eq(&self, other: &Self) -> bool {
        self.records == other.records
            && self.branch_vertices == other.branch_vertices
            && self.branch_neighbors == other.branch_neighbors
    }
}

/// Bits of a vertex id in a record: ids are under [`crate::triangulate::MAX_POINTS`] < 2^29.
const ID_BITS: u32 = 29;
const ID_MASK: u32 = (1 << ID_BITS) - 1;
/// How many vertex ids ahead [`CurveGraph::prefetch_ahead`] reads: a vertex's own record comes in
/// order, its neighbours' from anywhere (ids follow BRIO rounds).
const NEIGHBORS_AHEAD: usize = 16;
/// A missing neighbour in a record (read back as [`VertexId::INFINITE`]).
const NO_ID: u32 = ID_MASK;
/// The stored degree saturates here; the side table gives the exact degree beyond.
const DEGREE_SATURATED: u32 = 7;

/// The vertex a record's id field names.
#[inline]
fn vertex_of(field: u32) -> VertexId {
    let id = field & ID_MASK;
    VertexId::new(if id == NO_ID { u32::MAX } else { id })
}

impl CurveGraph {
    /// The largest number of vertices a curve graph holds (ids must fit [`ID_BITS`]).
    pub(crate) const MAX_VERTICES: usize = NO_ID as usize;

    /// The graph of `edges` (each once, `[a, b]` with `a < b`, any order) over `vertex_count`
    /// vertices (at most [`CurveGraph::MAX_VERTICES`]); neighbours in the order of `edges`.
    pub(crate) fn new(vertex_count: usize, edges: &[Edge]) -> Self {
        assert!(vertex_count <= Self::MAX_VERTICES);
        let mut records = vec![[NO_ID, NO_ID]; vertex_count];
        let mut branches = false;
        for &[a, b] in edges {
            for (v, w) in [(a, b), (b, a)] {
                branches |= push(&mut records[v.index()], w) >= 2;
            }
        }
        let (branch_vertices, branch_neighbors) = if branches {
            branch_table(&records, edges)
        } else {
            (Vec::new(), Vec::new())
        };
        CurveGraph {
            records,
            branch_vertices,
            branch_neighbors,
            smooth_cycles: false,
        }
    }
    /// Records that every vertex with edges has two passing `smooth_and_regular` (clean closed
    /// curves): the local outlier removal's scan proves it, and the clump stage then need not
    /// test every vertex again (speed: on 1M points along clean curves, a tenth of the stages).
    pub(crate) fn mark_smooth_cycles(&mut self) {
        self.smooth_cycles = true;
    }
    /// Whether [`CurveGraph::mark_smooth_cycles`] holds for the graph as it is.
    pub(crate) fn proven_smooth_cycles(&self) -> bool {
        self.smooth_cycles
    }
    pub(crate) fn has_branch(&self) -> bool {
        !self.branch_vertices.is_empty()
    }
    /// Whether some vertex has exactly one neighbour: a scan of the records, stopping at the first.
    pub(crate) fn has_loose_end(&self) -> bool {
        self.records.iter().any(|r| r[0] >> ID_BITS == 1)
    }
    /// Whether some vertex has no neighbour: a scan of the records, stopping at the first.
    pub(crate) fn has_unused(&self) -> bool {
        self.records.iter().any(|r| r[0] >> ID_BITS == 0)
    }
    pub(crate) fn vertex_count(&self) -> usize {
        self.records.len()
    }

    /// Asks the cache for the record of `v`, which a loop will read soon ([`crate::prefetch`]).
    #[inline]
    pub(crate) fn prefetch(&self, v: VertexId) {
        crate::prefetch::prefetch(&self.records, v.index());
    }

    /// For a loop over the ids at `i`: asks the cache for the elements of `slice` (by vertex id)
    /// at the neighbours of vertex `i + NEIGHBORS_AHEAD`, from [`PREFETCH_FROM`] vertices on.
    #[inline]
    pub(crate) fn prefetch_ahead<T>(&self, i: usize, slice: &[T]) {
        if self.records.len() < PREFETCH_FROM {
            return;
        }
        if let Some(record) = self.records.get(i + NEIGHBORS_AHEAD) {
            // A missing neighbour reads as `NO_ID`, beyond any slice of at most `MAX_VERTICES`.
            crate::prefetch::prefetch(slice, (record[0] & ID_MASK) as usize);
            crate::prefetch::prefetch(slice, (record[1] & ID_MASK) as usize);
        }
    }
    #[inline]
    pub(crate) fn degree(&self, v: VertexId) -> usize {
        let d = self.records[v.index()][0] >> ID_BITS;
        if d < DEGREE_SATURATED {
            d as usize
        } else {
            self.branch(v).len()
        }
    }
    /// The `k`-th neighbour of `v`, `k < degree(v)`.
    #[inline]
    pub(crate) fn neighbor(&self, v: VertexId, k: usize) -> VertexId {
        let record = &self.records[v.index()];
        if record[0] >> ID_BITS > 2 {
            self.branch(v)[k]
        } else {
            vertex_of(record[k])
        }
    }
    /// Whether `a` and `b` are joined.
    #[inline]
    pub(crate) fn has_edge(&self, a: VertexId, b: VertexId) -> bool {
        (0..self.degree(a)).any(|k| self.neighbor(a, k) == b)
    }

    /// Takes `removed` (edges of this graph, each once) out, as [`CurveGraph::new`] of the rest
    /// would build: records patched in place, the side table rewritten in one pass (cheap).
    pub(crate) fn remove_edges(&mut self, removed: &[Edge]) {
        self.smooth_cycles = false;
        let mut at_branches: Vec<(VertexId, VertexId)> = Vec::new();
        for &[a, b] in removed {
            for (v, w) in [(a, b), (b, a)] {
                let record = &mut self.records[v.index()];
                let d = record[0] >> ID_BITS;
                if d > 2 {
                    at_branches.push((v, w));
                    continue;
                }
                let first = record[0] & ID_MASK;
                let w = w.index() as u32;
                debug_assert!(d >= 1 && (first == w || (d == 2 && record[1] == w)));
                *record = if d == 1 {
                    [NO_ID, NO_ID]
                } else {
                    let other = if first == w { record[1] } else { first };
                    [other | (1 << ID_BITS), NO_ID]
                };
            }
        }
        self.rewrite_branches(at_branches, false);
    }

    /// Adds `added` (edges absent from this graph, each once), as [`CurveGraph::new`] of this
    /// graph's list followed by `added` would build: records filled in place, the side table
    /// rewritten in one pass when a vertex reaches three neighbours.
    pub(crate) fn add_edges(&mut self, added: &[Edge]) {
        self.smooth_cycles = false;
        let mut at_branches: Vec<(VertexId, VertexId)> = Vec::new();
        for &[a, b] in added {
            for (v, w) in [(a, b), (b, a)] {
                if push(&mut self.records[v.index()], w) >= 2 {
                    at_branches.push((v, w));
                }
            }
        }
        self.rewrite_branches(at_branches, true);
    }

    /// Rewrites the side table in one pass for the neighbours `(v, w)` added (`adding`) or removed
    /// at vertices with three or more (before or after); a removal's records are written here.
    fn rewrite_branches(&mut self, mut changes: Vec<(VertexId, VertexId)>, adding: bool) {
        if changes.is_empty() {
            return;
        }
        // Stable: each vertex's new neighbours stay in the order they were added.
        changes.sort_by_key(|&(v, _)| v);
        let old_vertices = core::mem::take(&mut self.branch_vertices);
        let old_neighbors = core::mem::take(&mut self.branch_neighbors);
        let mut vertices = Vec::with_capacity(old_vertices.len() + changes.len());
        let mut neighbors = Vec::with_capacity(old_neighbors.len() + 3 * changes.len());
        let (mut old, mut new) = (0, 0);
        while old < old_vertices.len() || new < changes.len() {
            // The smaller of the two lists' next vertices (an ended list reads as infinite).
            let v = old_vertices.get(old).map_or(VertexId::INFINITE, |e| e.0);
            let v = v.min(changes.get(new).map_or(VertexId::INFINITE, |e| e.0));
            let start = neighbors.len();
            if old_vertices.get(old).is_some_and(|&(u, _)| u == v) {
                neighbors.extend_from_slice(listed(&old_vertices, &old_neighbors, old));
                old += 1;
            } else {
                // Two neighbours before: both in the record, which the branch does not change.
                neighbors.extend_from_slice(&self.first_two(v));
            }
            let count = changes[new..].iter().take_while(|&&(u, _)| u == v).count();
            let changed = &changes[new..new + count];
            new += count;
            if adding {
                neighbors.extend(changed.iter().map(|&(_, w)| w));
            } else if count > 0 {
                let kept: Vec<VertexId> = neighbors
                    .drain(start..)
                    .filter(|w| changed.iter().all(|&(_, gone)| gone != *w))
                    .collect();
                let field = |k: usize| kept.get(k).map_or(NO_ID, |w| w.index() as u32);
                let d = kept.len() as u32;
                self.records[v.index()] =
                    [field(0) | (d.min(DEGREE_SATURATED) << ID_BITS), field(1)];
                neighbors.extend_from_slice(&kept);
            }
            if neighbors.len() - start > 2 {
                vertices.push((v, start as u32));
            } else {
                neighbors.truncate(start);
            }
        }
        self.branch_vertices = vertices;
        self.branch_neighbors = neighbors;
    }

    /// Makes this, the curve graph of a stage's `input`, that of its `output`: `input` less some
    /// edges, in order, then new edges (the form every stage's output has). Patched in place for
    /// up to one change per 64 vertices, else rebuilt (the old graph freed first).
    pub(crate) fn follow(&mut self, input: &[Edge], output: &[Edge]) {
        if !self.patch(input, output, self.vertex_count() / 64) {
            self.rebuild(output);
        }
    }

    /// [`CurveGraph::follow`] in place when it takes at most `most` changes; `false` (and the
    /// graph unchanged) otherwise.
    fn patch(&mut self, input: &[Edge], output: &[Edge], most: usize) -> bool {
        let mut removed = Vec::new();
        let mut kept = 0;
        for &edge in input {
            if output.get(kept) == Some(&edge) {
                kept += 1;
            } else if removed.len() < most {
                removed.push(edge);
            } else {
                return false;
            }
        }
        let appended = &output[kept..];
        if removed.len() + appended.len() > most {
            return false;
        }
        self.remove_edges(&removed);
        self.add_edges(appended);
        true
    }

    /// Makes this the curve graph of `edges`, freeing the old one first (memory).
    pub(crate) fn rebuild(&mut self, edges: &[Edge]) {
        let n = self.vertex_count();
        *self = CurveGraph::new(0, &[]);
        *self = CurveGraph::new(n, edges);
    }

    /// All neighbours of a vertex with three or more (a binary search: such vertices are few).
    #[cold]
    fn branch(&self, v: VertexId) -> &[VertexId] {
        let at = self
            .branch_vertices
            .binary_search_by_key(&v, |&(w, _)| w)
            .unwrap_or(0);
        listed(&self.branch_vertices, &self.branch_neighbors, at)
    }

    /// The passages `[previous, here, next]` along a curve from `next` on, away from `from`, for as
    /// long as `here` has two neighbours (without end around a cycle).
    pub(crate) fn passages(
        &self,
        from: VertexId,
        next: VertexId,
    ) -> impl Iterator<Item = [VertexId; 3]> + '_ {
        let mut step = (from, next);
        core::iter::from_fn(move || {
            let (previous, here) = step;
            (self.degree(here) == 2).then(|| {
                step = (here, self.onward(here, previous));
                [previous, here, step.1]
            })
        })
    }

    /// The first two neighbours of `v` ([`VertexId::INFINITE`] where it has fewer).
    #[inline]
    pub(crate) fn first_two(&self, v: VertexId) -> [VertexId; 2] {
        let record = &self.records[v.index()];
        [vertex_of(record[0]), vertex_of(record[1])]
    }

    /// For `v` of degree two and `from` one of its neighbours, the other: the next step along a
    /// curve. Which slot holds `from` is a coin toss, so it is taken by exclusive or, not a branch.
    #[inline]
    pub(crate) fn onward(&self, v: VertexId, from: VertexId) -> VertexId {
        let record = &self.records[v.index()];
        let (x, y) = (record[0] & ID_MASK, record[1]);
        debug_assert!(from.index() as u32 == x || from.index() as u32 == y);
        VertexId::new(x ^ y ^ from.index() as u32)
    }
}

/// Adds the neighbour `w` to a record, as [`CurveGraph::new`] does; returns the degree before.
#[inline]
fn push(record: &mut [u32; 2], w: VertexId) -> u32 {
    let d = record[0] >> ID_BITS;
    let w = w.index() as u32;
    // Whether a slot fills is a coin toss per edge: selected, not branched on.
    let first = if d == 0 { w } else { record[0] & ID_MASK };
    record[0] = first | ((d + 1).min(DEGREE_SATURATED) << ID_BITS);
    record[1] = if d == 1 { w } else { record[1] };
    d
}

/// The `k`-th list of a side table.
fn listed<'a>(vertices: &[(VertexId, u32)], neighbors: &'a [VertexId], k: usize) -> &'a [VertexId] {
    let end = vertices
        .get(k + 1)
        .map_or(neighbors.len(), |&(_, next)| next as usize);
    &neighbors[vertices[k].1 as usize..end]
}

/// The side table of [`CurveGraph`]: the vertices of degree three or more, ascending, with the
/// start of their neighbours in the order of `edges`; degrees at the saturation counted here.
fn branch_table(records: &[[u32; 2]], edges: &[Edge]) -> (Vec<(VertexId, u32)>, Vec<VertexId>) {
    let stored = |v: VertexId| records[v.index()][0] >> ID_BITS;
    let mut vertices: Vec<(VertexId, u32)> = Vec::new();
    for (v, record) in records.iter().enumerate() {
        if record[0] >> ID_BITS > 2 {
            vertices.push((VertexId::new(v as u32), 0));
        }
    }
    let slot = |v: VertexId| vertices.binary_search_by_key(&v, |&(w, _)| w).ok();
    let mut degree: Vec<u32> = vertices.iter().map(|&(v, _)| stored(v)).collect();
    if degree.contains(&DEGREE_SATURATED) {
        degree.iter_mut().for_each(|d| *d = 0);
        for &[a, b] in edges {
            for v in [a, b] {
                if stored(v) > 2 {
                    if let Some(k) = slot(v) {
                        degree[k] += 1;
                    }
                }
            }
        }
    }
    let mut total = 0u32;
    for (entry, &d) in vertices.iter_mut().zip(&degree) {
        entry.1 = total;
        total += d;
    }
    let slot = |v: VertexId| vertices.binary_search_by_key(&v, |&(w, _)| w).ok();
    let mut fill: Vec<u32> = vertices.iter().map(|&(_, start)| start).collect();
    let mut neighbors = vec![VertexId::INFINITE; total as usize];
    for &[a, b] in edges {
        for (v, w) in [(a, b), (b, a)] {
            if stored(v) > 2 {
                if let Some(k) = slot(v) {
                    neighbors[fill[k] as usize] = w;
                    fill[k] += 1;
                }
            }
        }
    }
    (vertices, neighbors)
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
    // Each `ends[a]` has moved to the end of bucket `a`: each bucket sorted, then the repeats
    // (next to each other, in one bucket) dropped in place.
    let mut begin = 0;
    for &end in &ends[..bound] {
        sorted[begin..end as usize].sort_unstable();
        begin = end as usize;
    }
    sorted.dedup();
    sorted
}

/// `edges` (at most `room`) in one list of exact length, allocated once (collecting would double).
pub(crate) fn collect_exact<E>(room: usize, edges: impl Iterator<Item = E>) -> Vec<E> {
    let mut list = Vec::with_capacity(room);
    list.extend(edges);
    list.shrink_to_fit();
    list
}

pub(crate) fn degrees(vertex_count: usize, edges: &[Edge]) -> Vec<u32> {
    let mut degree = vec![0u32; vertex_count];
    for &[a, b] in edges {
        degree[a.index()] += 1;
        degree[b.index()] += 1;
    }
    degree
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Compressed adjacency (each vertex's neighbours with their edge's position, in list order):
    /// the reference the tests check [`CurveGraph`] and the repair's branch lists against.
    pub(crate) struct Adjacency {
        offsets: Vec<u32>,
        neighbors: Vec<(VertexId, u32)>,
    }

    impl Adjacency {
        /// `edges` must list every edge once (`[a, b]` with `a < b`, in any order). Built by
        /// counting, in O(n), without sorting.
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

    /// A random graph on 2 to `2 + most` vertices with up to `per_vertex` times as many edges,
    /// each once, listed in a scrambled order: neighbours must follow the list, not the ids.
    pub(crate) fn random_graph(
        rng: &mut crate::test_rng::Xorshift,
        most: u64,
        per_vertex: u64,
    ) -> (usize, Vec<Edge>) {
        let n = 2 + rng.below(most) as usize;
        let mut edges: Vec<Edge> = (0..rng.below(per_vertex * n as u64))
            .map(|_| {
                let (a, b) = (rng.below(n as u64) as u32, rng.below(n as u64) as u32);
                ordered(VertexId::new(a), VertexId::new(b))
            })
            .filter(|&[a, b]| a != b)
            .collect();
        edges.sort_unstable();
        edges.dedup();
        edges.reverse();
        (n, edges)
    }

    /// On random graphs with branch points, the curve graph gives every vertex the neighbours
    /// the full adjacency gives it, in the same order (that of the edge list), and,
    /// at degree two, the other neighbour from either one.
    #[test]
    fn the_curve_graph_lists_the_neighbours_of_the_full_adjacency() {
        let mut rng = crate::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let mut branch_vertices = 0;
        for _ in 0..500 {
            let (n, edges) = random_graph(&mut rng, 30, 3);
            let full = Adjacency::new(n, &edges);
            let graph = CurveGraph::new(n, &edges);
            for v in (0..n as u32).map(VertexId::new) {
                let expected: Vec<VertexId> = full.incident(v).iter().map(|&(w, _)| w).collect();
                let listed: Vec<VertexId> =
                    (0..graph.degree(v)).map(|k| graph.neighbor(v, k)).collect();
                assert_eq!(listed, expected, "{edges:?}");
                branch_vertices += usize::from(expected.len() > 2);
                if let [x, y] = expected[..] {
                    assert_eq!(graph.onward(v, x), y);
                    assert_eq!(graph.onward(v, y), x);
                }
            }
            assert_eq!(
                graph.has_branch(),
                (0..n).any(|v| full.incident(VertexId::new(v as u32)).len() > 2)
            );
        }
        assert!(branch_vertices > 1000, "the graphs have branch points");
    }

    /// Taking edges out of a curve graph in place gives the graph of the remaining list, on
    /// random graphs whose vertices reach every degree from zero to beyond the saturation.
    #[test]
    fn removing_edges_in_place_gives_the_graph_of_the_rest() {
        let mut rng = crate::test_rng::Xorshift::new(0x51_7cc1_b727_220a);
        let mut patched_branches = 0;
        for _ in 0..500 {
            let (n, edges) = random_graph(&mut rng, 25, 4);
            let mut graph = CurveGraph::new(n, &edges);
            let mut removed = Vec::new();
            let mut rest = Vec::new();
            let share = 1 + rng.below(4);
            for &e in &edges {
                if rng.below(share + 1) == 0 {
                    patched_branches += usize::from(graph.degree(e[0]) > 2);
                    removed.push(e);
                } else {
                    rest.push(e);
                }
            }
            graph.remove_edges(&removed);
            assert_eq!(
                graph,
                CurveGraph::new(n, &rest),
                "{edges:?} less {removed:?}"
            );
        }
        assert!(patched_branches > 500, "removals reach branch points");
    }

    /// `has_loose_end` agrees with the degrees, on random graphs with and without degree-one
    /// vertices (a saturated degree is never taken for one).
    #[test]
    fn a_loose_end_is_found_exactly_when_a_vertex_has_one_neighbour() {
        let mut rng = crate::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let (mut with, mut without) = (0, 0);
        for _ in 0..300 {
            let (n, edges) = random_graph(&mut rng, 25, 4);
            let graph = CurveGraph::new(n, &edges);
            let expected = (0..n as u32).any(|v| graph.degree(VertexId::new(v)) == 1);
            assert_eq!(graph.has_loose_end(), expected, "{edges:?}");
            with += usize::from(expected);
            without += usize::from(!expected);
        }
        // A cycle has none; cut once, it has two.
        let ring: Vec<Edge> = (0..6u32)
            .map(|k| ordered(VertexId::new(k), VertexId::new((k + 1) % 6)))
            .collect();
        assert!(!CurveGraph::new(6, &ring).has_loose_end());
        assert!(CurveGraph::new(6, &ring[1..]).has_loose_end());
        assert!(
            with > 0 && without > 0,
            "{with} graphs with a loose end, {without} without"
        );
    }

    /// Adding edges in place gives the graph of the list with them appended, and following a
    /// stage's output (some edges removed, others appended) gives the output's graph, on random
    /// graphs whose vertices reach every degree from zero to beyond the saturation.
    #[test]
    fn adding_and_following_edges_in_place_give_the_graph_of_the_new_list() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let (mut new_branches, mut grown_branches, mut followed) = (0, 0, 0);
        for _ in 0..500 {
            let (n, all) = random_graph(&mut rng, 25, 4);
            let share = 1 + rng.below(4);
            let (mut input, mut added) = (Vec::new(), Vec::new());
            for &e in &all {
                if rng.below(share + 1) == 0 {
                    added.push(e);
                } else {
                    input.push(e);
                }
            }
            let before = CurveGraph::new(n, &input);
            let mut graph = before.clone();
            graph.add_edges(&added);
            let whole: Vec<Edge> = input.iter().chain(&added).copied().collect();
            assert_eq!(graph, CurveGraph::new(n, &whole), "{input:?} and {added:?}");
            for v in (0..n as u32).map(VertexId::new) {
                new_branches += usize::from(before.degree(v) <= 2 && graph.degree(v) > 2);
                grown_branches +=
                    usize::from(before.degree(v) > 2 && graph.degree(v) > before.degree(v));
            }
            // A stage's output: the input less some edges, in order, then the added ones.
            let output: Vec<Edge> = input
                .iter()
                .filter(|_| rng.below(3) != 0)
                .chain(&added)
                .copied()
                .collect();
            let mut patched = before.clone();
            assert!(patched.patch(&input, &output, usize::MAX));
            assert_eq!(
                patched,
                CurveGraph::new(n, &output),
                "{input:?} to {output:?}"
            );
            let mut rebuilt = before;
            rebuilt.follow(&input, &output);
            assert_eq!(rebuilt, patched);
            followed += usize::from(output.len() != input.len());
        }
        assert!(new_branches > 200 && grown_branches > 200 && followed > 400);
    }
}
