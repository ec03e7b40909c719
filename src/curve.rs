//! Curves from an edge set: ordered polylines, closed or open.
//!
//! Owns: turning a graph whose vertices mostly have degree two into polylines. It may not look at
//! coordinates: the order along a curve is the graph's.
//!
//! A polyline runs between vertices whose degree is not two (ends and branch points); what is
//! left once those are walked are cycles of degree-two vertices, reported as closed curves. A
//! polyline that leaves a branch vertex and comes back to it (one lobe of a figure eight) is
//! closed too.

use crate::graph::{ordered, CurveGraph, Edge};
use crate::mesh::VertexId;
use alloc::vec;
use alloc::vec::Vec;

/// One curve: its points in order along it, as indices (vertex ids from [`assemble`]; input
/// positions in a [`Reconstruction`](crate::condt::Reconstruction)). A closed curve does not
/// repeat its first point at the end.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Curve {
    /// The points in order.
    pub vertices: Vec<u32>,
    /// `true` when the last vertex joins back to the first.
    pub closed: bool,
}

/// Splits `edges` over `vertex_count` vertices into curves. Every edge lies on exactly one
/// curve. An edge may be listed either way round and more than once; loops and edges reaching
/// past `vertex_count` are ignored. Deterministic: curves come in order of their smallest
/// starting vertex.
///
/// ```
/// use condt::curve::assemble;
/// use condt::VertexId;
/// let v = VertexId::new;
/// // A triangle 0-1-2 and a separate segment 3-4.
/// let edges = [[v(0), v(1)], [v(0), v(2)], [v(1), v(2)], [v(3), v(4)]];
/// let curves = assemble(5, &edges);
/// assert_eq!(curves.len(), 2);
/// assert_eq!((curves[0].vertices.len(), curves[0].closed), (2, false));
/// assert_eq!((curves[1].vertices.len(), curves[1].closed), (3, true));
/// ```
pub fn assemble(vertex_count: usize, edges: &[Edge]) -> Vec<Curve> {
    let valid = |&&[a, b]: &&Edge| a != b && a.index() < vertex_count && b.index() < vertex_count;
    let mut once: Vec<Edge> = edges
        .iter()
        .filter(valid)
        .map(|&[a, b]| ordered(a, b))
        .collect();
    once.sort_unstable();
    once.dedup();
    curves_of(&CurveGraph::new(vertex_count, &once))
}

/// [`assemble`] on a graph already built.
pub(crate) fn curves_of(graph: &CurveGraph) -> Vec<Curve> {
    let vertex_count = graph.vertex_count();
    // Degree-two vertices already on a curve. A path between two ends or branch points is met
    // from both of them; it is walked from the first and recognised as taken from the second.
    let mut visited = vec![false; vertex_count];
    let mut curves = Vec::new();
    let vertices = (0..vertex_count as u32).map(VertexId::new);
    // Polylines between ends and branch points first, then the remaining pure cycles.
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
                curves.push(walk(graph, &mut visited, v, w));
            }
        }
    }
    for v in vertices {
        if graph.degree(v) == 2 && !visited[v.index()] {
            visited[v.index()] = true;
            curves.push(walk(graph, &mut visited, v, graph.neighbor(v, 0)));
        }
    }
    curves
}

/// Follows unvisited degree-two vertices from `start` through `first` until an end, a branch
/// point, or a vertex already visited (`start` itself, on a cycle); marks what it passes.
fn walk(graph: &CurveGraph, visited: &mut [bool], start: VertexId, first: VertexId) -> Curve {
    let mut path = vec![start.index() as u32];
    let (mut previous, mut current) = (start, first);
    loop {
        path.push(current.index() as u32);
        if graph.degree(current) != 2 || visited[current.index()] {
            break;
        }
        visited[current.index()] = true;
        (previous, current) = (current, graph.onward(current, previous));
    }
    let closed = path.len() > 2 && path.first() == path.last();
    if closed {
        path.pop();
    }
    Curve {
        vertices: path,
        closed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::ordered;

    /// On random graphs (branch points, lobes, isolated edges, cycles), given with repeats,
    /// loops, reversed and out-of-range edges: every edge lies on exactly one curve, curves pass
    /// only through degree-two vertices, and an open curve ends where the degree is not two.
    #[test]
    fn every_edge_lies_on_exactly_one_curve_through_degree_two_vertices() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut random = |bound: u64| rng.below(bound);
        let mut branch_points = 0;
        for _ in 0..2000 {
            let n = 2 + random(9) as usize;
            let wanted = random(2 * n as u64);
            // As given: either way round, repeated, loops, out of range; and the graph meant.
            let (mut given, mut edges): (Vec<Edge>, Vec<Edge>) = (Vec::new(), Vec::new());
            for _ in 0..wanted {
                let (a, b) = (random(n as u64 + 1) as u32, random(n as u64) as u32);
                let (a, b) = (VertexId::new(a), VertexId::new(b));
                given.push([a, b]);
                let edge = ordered(a, b);
                if a != b && a.index() < n && !edges.contains(&edge) {
                    edges.push(edge);
                }
            }
            let degree = crate::graph::degrees(n, &edges);
            branch_points += degree.iter().filter(|&&d| d > 2).count();
            let mut walked: Vec<Edge> = Vec::new();
            for curve in assemble(n, &given) {
                let v = &curve.vertices;
                let d = |k: usize| degree[v[k] as usize];
                assert!(v.len() >= 2, "{edges:?}");
                let inner = if curve.closed {
                    1..v.len()
                } else {
                    1..v.len() - 1
                };
                assert!(inner.clone().all(|k| d(k) == 2), "{edges:?}: {curve:?}");
                if !curve.closed {
                    assert!(d(0) != 2 && d(v.len() - 1) != 2, "{edges:?}: {curve:?}");
                }
                let id = |k: usize| VertexId::new(v[k % v.len()]);
                let steps = if curve.closed { v.len() } else { v.len() - 1 };
                walked.extend((0..steps).map(|k| ordered(id(k), id(k + 1))));
            }
            walked.sort();
            edges.sort();
            assert_eq!(walked, edges);
        }
        assert!(branch_points > 1000, "the graphs have branch points");
    }
}
