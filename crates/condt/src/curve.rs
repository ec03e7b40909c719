//! Curves from an edge set ([`Curve`]): polylines between vertices of degree other than two, closed
//! for cycles and lobes, in canonical order, by the graph alone (it may not look at coordinates).

use crate::adjacency::{ordered, CurveGraph, Edge};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;

/// One curve: its points in order, as input positions (a closed one does not repeat its first).
///
/// ```
/// use condt::curves_from_edges;
/// let curves = curves_from_edges(5, &[[0, 1], [2, 0], [1, 2], [3, 4]]);
/// assert_eq!(curves.len(), 2);
/// assert!(curves[0].is_closed() && !curves[1].is_closed());
/// assert_eq!(curves[0].points().collect::<Vec<_>>(), vec![0, 1, 2]);
/// assert_eq!(curves[0].edges().collect::<Vec<_>>(), vec![[0, 1], [1, 2], [2, 0]]);
/// assert_eq!(curves[1].points().collect::<Vec<_>>(), vec![3, 4]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Curve {
    /// Input positions in order, 32-bit as in the kernel, boxed at its length (memory).
    points: Box<[u32]>,
    closed: bool,
}

impl Curve {
    /// The input positions of its points, in order along the curve.
    ///
    /// ```
    /// use condt::curves_from_edges;
    /// let curve = &curves_from_edges(3, &[[2, 1], [1, 0]])[0];
    /// assert_eq!(curve.points().collect::<Vec<_>>(), vec![0, 1, 2]);
    /// ```
    pub fn points(
        &self,
    ) -> impl ExactSizeIterator<Item = usize> + DoubleEndedIterator + Clone + '_ {
        self.points.iter().map(|&i| i as usize)
    }

    /// `true` when the last point joins back to the first.
    ///
    /// ```
    /// use condt::curves_from_edges;
    /// assert!(curves_from_edges(3, &[[0, 1], [1, 2], [2, 0]])[0].is_closed());
    /// assert!(!curves_from_edges(3, &[[0, 1], [1, 2]])[0].is_closed());
    /// ```
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Number of points (a closed curve has as many edges, an open one one fewer).
    ///
    /// ```
    /// use condt::curves_from_edges;
    /// assert_eq!(curves_from_edges(4, &[[0, 1], [1, 2], [2, 3]])[0].len(), 4);
    /// ```
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// `true` for a curve without points (never produced by this crate).
    ///
    /// ```
    /// use condt::curves_from_edges;
    /// assert!(!curves_from_edges(2, &[[0, 1]])[0].is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Its edges as input positions in the order of the curve, the closing edge last.
    ///
    /// ```
    /// use condt::curves_from_edges;
    /// let open = &curves_from_edges(3, &[[2, 1], [0, 1]])[0];
    /// assert_eq!(open.edges().collect::<Vec<_>>(), vec![[0, 1], [1, 2]]);
    /// ```
    pub fn edges(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        let n = self.points.len();
        let steps = if self.closed { n } else { n.saturating_sub(1) };
        (0..steps).map(move |k| [self.points[k] as usize, self.points[(k + 1) % n] as usize])
    }

    /// Starts a closed curve at its smallest index, heading to the smaller of its two neighbours,
    /// and an open one at its smaller end, so the output never depends on the internal numbering.
    fn make_canonical(&mut self) {
        let v = &mut self.points;
        if v.len() < 2 {
            return;
        }
        if self.closed {
            let first = (0..v.len()).min_by_key(|&i| v[i]).unwrap_or(0);
            v.rotate_left(first);
            if v[v.len() - 1] < v[1] {
                v[1..].reverse();
            }
        } else if v[v.len() - 1] < v[0] {
            v.reverse();
        }
    }
}

/// Splits the edges between `num_points` points into curves, each edge on exactly one. Edges are
/// input positions, either way round, repeats allowed; loops and positions past `num_points` are
/// ignored, as are positions from `u32::MAX` on (the library's limit on points,
/// [`MAX_POINTS`](crate::MAX_POINTS), is far below). A curve runs from a point whose degree is
/// not two (an end or a branch point) to the next such point, or around a cycle of points of
/// degree two; a branch point is on each curve that meets it, and a curve that comes back to
/// the point it started from is closed, which lists that point once. Each curve starts at its
/// smallest position (an open one at its smaller end); sorted.
///
/// ```
/// use condt::curves_from_edges;
/// // A figure eight: two loops through point 0, which has degree four.
/// let curves = curves_from_edges(5, &[[0, 1], [1, 2], [2, 0], [0, 3], [3, 4], [4, 0]]);
/// assert_eq!(curves.len(), 2);
/// assert!(curves.iter().all(|c| c.is_closed() && c.len() == 3));
/// // A T: three open curves from the junction, point 0.
/// let t = curves_from_edges(7, &[[0, 1], [1, 2], [0, 3], [3, 4], [0, 5], [5, 6]]);
/// let arms: Vec<Vec<usize>> = t.iter().map(|c| c.points().collect()).collect();
/// assert_eq!(arms, [[0, 1, 2], [0, 3, 4], [0, 5, 6]]);
/// assert!(t.iter().all(|c| !c.is_closed()));
/// // A P: the loop through the branch point 0 is closed, its tail open.
/// let p = curves_from_edges(6, &[[0, 1], [1, 2], [2, 3], [3, 0], [0, 4], [4, 5]]);
/// assert!(p[0].is_closed() && p[0].points().eq([0, 1, 2, 3]));
/// assert!(!p[1].is_closed() && p[1].points().eq([0, 4, 5]));
/// ```
pub fn curves_from_edges(num_points: usize, edges: &[[usize; 2]]) -> Vec<Curve> {
    // Positions are 32-bit inside, as in the kernel; larger ones cannot name a point here.
    let count = num_points.min(u32::MAX as usize);
    let mut once: Vec<Edge> = edges
        .iter()
        .filter(|&&[a, b]| a != b && a < count && b < count)
        .map(|&[a, b]| ordered(VertexId::new(a as u32), VertexId::new(b as u32)))
        .collect();
    once.sort_unstable();
    once.dedup();
    if count <= CurveGraph::MAX_VERTICES {
        curves_of(&CurveGraph::new(count, &once), |v| v.index() as u32)
    } else {
        // Positions beyond what a curve graph holds: the points with edges, renumbered in
        // increasing order (so the walks meet them in the same order) and named back.
        let mut ends: Vec<VertexId> = once.iter().flatten().copied().collect();
        ends.sort_unstable();
        ends.dedup();
        let dense = |v: VertexId| VertexId::new(ends.binary_search(&v).unwrap_or(0) as u32);
        let renumbered: Vec<Edge> = once.iter().map(|&[a, b]| [dense(a), dense(b)]).collect();
        curves_of(&CurveGraph::new(ends.len(), &renumbered), |v| {
            ends[v.index()].index() as u32
        })
    }
}

/// The curves of `graph` (over `tri`'s vertex ids) in input positions, canonical and sorted; the
/// positions are read from the triangulation's map, not copied into the graph (memory).
pub(crate) fn curves_in_input_positions(tri: &Triangulation, graph: &CurveGraph) -> Vec<Curve> {
    curves_of(graph, |v| tri.input_of(v) as u32)
}

/// The curves of a graph already built, each vertex given as the point `name(v)`: canonical
/// ([`Curve::make_canonical`]) and sorted.
fn curves_of(graph: &CurveGraph, name: impl Fn(VertexId) -> u32) -> Vec<Curve> {
    let vertex_count = graph.vertex_count();
    // Degree-two vertices already on a curve. A path between two ends or branch points is met
    // from both of them; it is walked from the first and recognised as taken from the second.
    let mut visited = vec![false; vertex_count];
    let mut curves = Vec::new();
    // One buffer for every walk: each curve then gets one allocation of its exact size.
    let mut path = Vec::new();
    let vertices = (0..vertex_count as u32).map(VertexId::new);
    for v in vertices.clone() {
        let degree = graph.degree(v);
        if degree == 0 || degree == 2 {
            continue;
        }
        for k in 0..degree {
            let w = graph.neighbor(v, k);
            let untaken = if graph.degree(w) == 2 {
                !visited[w.index()]
            } else {
                // An edge joining two ends or branch points: taken from its smaller end.
                v < w
            };
            if untaken {
                curves.push(walk(graph, &name, &mut visited, &mut path, v, w));
            }
        }
    }
    // What is left unvisited are cycles of degree-two vertices only: every chain that reaches an
    // end or a branch point was walked from there.
    let mut back = Vec::new();
    for v in vertices {
        if graph.degree(v) == 2 && !visited[v.index()] {
            let paths = [&mut path, &mut back];
            curves.push(walk_cycle(graph, &name, &mut visited, paths, v));
        }
    }
    // Grown by doubling: up to half of it was room (memory).
    curves.shrink_to_fit();
    curves.iter_mut().for_each(Curve::make_canonical);
    // By their first two points, the order of the whole lists: no two curves share them (they
    // would share an edge). Keys computed once spare the sort a cache miss per comparison.
    curves.sort_by_cached_key(|curve| {
        let p = &curve.points;
        let at = |k: usize| u64::from(p.get(k).copied().unwrap_or(0));
        (at(0) << 32) | at(1)
    });
    curves
}

/// Walks the cycle of unvisited degree-two vertices through `start`, marking them, from both of
/// its neighbours at once, and gives its points as [`walk`] through its first neighbour would.
/// Why: a walk waits for each record to know the next, so two walks have two cache misses on the
/// way at a time. `paths` is scratch space.
fn walk_cycle(
    graph: &CurveGraph,
    name: &impl Fn(VertexId) -> u32,
    visited: &mut [bool],
    paths: [&mut Vec<u32>; 2],
    start: VertexId,
) -> Curve {
    let [out, back] = paths;
    out.clear();
    back.clear();
    visited[start.index()] = true;
    let [first, last] = graph.first_two(start);
    let (mut from_out, mut ahead) = (start, first);
    let (mut from_back, mut behind) = (start, last);
    // The vertices before `ahead` and after `behind` along the cycle are taken, and `ahead` does
    // not come after `behind`: the two meet at a vertex or at an edge.
    loop {
        visited[ahead.index()] = true;
        out.push(name(ahead));
        if ahead == behind {
            break;
        }
        visited[behind.index()] = true;
        back.push(name(behind));
        let next_out = graph.onward(ahead, from_out);
        if next_out == behind {
            break;
        }
        let next_back = graph.onward(behind, from_back);
        (from_out, ahead) = (ahead, next_out);
        (from_back, behind) = (behind, next_back);
    }
    let mut points = Vec::with_capacity(1 + out.len() + back.len());
    points.push(name(start));
    points.extend_from_slice(out);
    points.extend(back.iter().rev());
    Curve {
        points: points.into_boxed_slice(),
        closed: true,
    }
}

/// Follows unvisited degree-two vertices from `start` through `first`, marking them, until an
/// end, a branch point or a visited vertex (`start`, on a cycle); `path` is scratch space.
fn walk(
    graph: &CurveGraph,
    name: &impl Fn(VertexId) -> u32,
    visited: &mut [bool],
    path: &mut Vec<u32>,
    start: VertexId,
    first: VertexId,
) -> Curve {
    path.clear();
    let (mut previous, mut current) = (start, first);
    loop {
        path.push(name(current));
        if graph.degree(current) != 2 || visited[current.index()] {
            break;
        }
        visited[current.index()] = true;
        (previous, current) = (current, graph.onward(current, previous));
    }
    // A cycle ends where it started: its last step is not repeated.
    let closed = path.len() > 1 && current == start;
    let mut points = Vec::with_capacity(path.len() + usize::from(!closed));
    points.push(name(start));
    points.extend_from_slice(&path[..path.len() - usize::from(closed)]);
    Curve {
        points: points.into_boxed_slice(),
        closed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Around a cycle, both ways at once gives what one walk gives, whether the two meet at a
    /// vertex (an even number of points) or at an edge (odd), whatever the numbering.
    #[test]
    fn a_cycle_walked_both_ways_is_the_cycle_walked_once() {
        for len in 3..12u32 {
            // The cycle visits the ids in a scrambled order: 13 k modulo `len`, plus one.
            let ids: Vec<u32> = (0..len).map(|k| (13 * k) % len + 1).collect();
            let edges: Vec<Edge> = (0..len as usize)
                .map(|k| {
                    ordered(
                        VertexId::new(ids[k]),
                        VertexId::new(ids[(k + 1) % ids.len()]),
                    )
                })
                .collect();
            let graph = CurveGraph::new(len as usize + 1, &edges);
            let name = |v: VertexId| 100 + v.index() as u32;
            for start in 1..=len {
                let start = VertexId::new(start);
                let n = len as usize + 1;
                let (mut seen, mut path) = (vec![false; n], Vec::new());
                seen[start.index()] = true;
                let once = walk(
                    &graph,
                    &name,
                    &mut seen,
                    &mut path,
                    start,
                    graph.neighbor(start, 0),
                );
                let (mut both_seen, mut back) = (vec![false; n], Vec::new());
                let both = walk_cycle(&graph, &name, &mut both_seen, [&mut path, &mut back], start);
                assert_eq!(once, both, "{len} points from {start:?}");
                assert_eq!(seen, both_seen);
            }
        }
    }

    /// Positions beyond what a curve graph holds are renumbered and named back: the same curves
    /// as the same edges between small positions, shifted.
    #[test]
    fn curves_between_huge_positions_are_those_of_small_ones_shifted() {
        let small = [
            [0, 1],
            [1, 2],
            [2, 0],
            [0, 3],
            [3, 4],
            [5, 6],
            [1, 7],
            [7, 8],
            [8, 9],
        ];
        let shift = 1usize << 30;
        let huge: Vec<[usize; 2]> = small.iter().map(|&[a, b]| [a + shift, b + shift]).collect();
        let expected: Vec<Vec<usize>> = curves_from_edges(10, &small)
            .iter()
            .map(|c| c.points().map(|p| p + shift).collect())
            .collect();
        let got: Vec<Vec<usize>> = curves_from_edges(u32::MAX as usize, &huge)
            .iter()
            .map(|c| c.points().collect())
            .collect();
        assert_eq!(got, expected);
    }

    /// On random graphs (branch points, lobes, isolated edges, cycles), given with repeats,
    /// loops, reversed and out-of-range edges: every edge lies on exactly one curve, an open curve
    /// passes only through degree-two points and ends where the degree is not two, a closed one
    /// holds at most one point of another degree (the branch point of a lobe), and each
    /// curve starts canonically (closed: at its smallest point, towards the smaller neighbour;
    /// open: at its smaller end).
    #[test]
    fn every_edge_lies_on_exactly_one_curve_through_degree_two_vertices() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut random = |bound: u64| rng.below(bound) as usize;
        let mut branch_points = 0;
        for _ in 0..2000 {
            let n = 2 + random(9);
            let wanted = random(2 * n as u64);
            // As given: either way round, repeated, loops, out of range; and the graph meant.
            let (mut given, mut edges) = (Vec::new(), Vec::new());
            for _ in 0..wanted {
                let (a, b) = (random(n as u64 + 1), random(n as u64));
                given.push([a, b]);
                let edge = [a.min(b), a.max(b)];
                if a != b && a < n && !edges.contains(&edge) {
                    edges.push(edge);
                }
            }
            let mut degree = vec![0; n];
            for &[a, b] in &edges {
                degree[a] += 1;
                degree[b] += 1;
            }
            branch_points += degree.iter().filter(|&&d| d > 2).count();
            let mut walked = Vec::new();
            for curve in curves_from_edges(n, &given) {
                let v: Vec<usize> = curve.points().collect();
                let d = |k: usize| degree[v[k]];
                assert!(v.len() >= 2, "{edges:?}");
                if curve.is_closed() {
                    // A cycle, or a lobe through one branch point (which need not come first).
                    let branching = (0..v.len()).filter(|&k| d(k) != 2).count();
                    assert!(branching <= 1, "{edges:?}: {curve:?}");
                    assert!(v.iter().all(|&p| p >= v[0]), "{curve:?}");
                    assert!(v.len() < 3 || v[1] < v[v.len() - 1], "{curve:?}");
                } else {
                    assert!((1..v.len() - 1).all(|k| d(k) == 2), "{edges:?}: {curve:?}");
                    assert!(d(0) != 2 && d(v.len() - 1) != 2, "{edges:?}: {curve:?}");
                    assert!(v[0] <= v[v.len() - 1], "{curve:?}");
                }
                walked.extend(curve.edges().map(|[a, b]| [a.min(b), a.max(b)]));
            }
            walked.sort();
            edges.sort();
            assert_eq!(walked, edges);
        }
        assert!(branch_points > 1000, "the graphs have branch points");
    }
}
