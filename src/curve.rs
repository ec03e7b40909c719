//! Curves from an edge set: ordered polylines, closed or open.
//!
//! Owns: turning a graph whose vertices mostly have degree two into polylines. It may not look at
//! coordinates: the order along a curve is the graph's.
//!
//! A polyline runs between vertices whose degree is not two (ends and branch points); what is
//! left once those are walked are cycles of degree-two vertices, reported as closed curves. A
//! polyline that leaves a branch vertex and comes back to it (one lobe of a figure eight) is
//! closed too.

use crate::graph::{ordered, Adjacency, Edge};
use crate::mesh::VertexId;
use alloc::vec;
use alloc::vec::Vec;

/// One reconstructed curve: its vertices in order along it. A closed curve does not repeat its
/// first vertex at the end.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Curve {
    /// The vertices in order.
    pub vertices: Vec<VertexId>,
    /// `true` when the last vertex joins back to the first.
    pub closed: bool,
}

/// Splits `edges` (sorted, `a < b`) over `vertex_count` vertices into curves. Every edge lies on
/// exactly one curve. Deterministic: curves come in order of their smallest starting vertex.
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
    let graph = Adjacency::new(vertex_count, edges);
    let mut used = vec![false; edges.len()];
    let index_of = |a: VertexId, b: VertexId| {
        edges
            .binary_search(&ordered(a, b))
            .expect("edge of the graph")
    };
    let mut curves = Vec::new();
    let walk = |start: VertexId, first: VertexId, used: &mut Vec<bool>| {
        let mut path = vec![start];
        let mut current = first;
        used[index_of(start, first)] = true;
        loop {
            path.push(current);
            if graph.degree(current) != 2 {
                break;
            }
            let next = graph
                .neighbors(current)
                .iter()
                .copied()
                .find(|&w| !used[index_of(current, w)]);
            let Some(next) = next else { break };
            used[index_of(current, next)] = true;
            current = next;
        }
        let closed = path.len() > 2 && path.first() == path.last();
        if closed {
            path.pop();
        }
        Curve {
            vertices: path,
            closed,
        }
    };
    // Polylines between ends and branch points first, then the remaining pure cycles.
    for pass_wants_degree_two in [false, true] {
        for i in 0..vertex_count {
            let v = VertexId::new(i as u32);
            let degree = graph.degree(v);
            if degree == 0 || (degree == 2) != pass_wants_degree_two {
                continue;
            }
            for &w in graph.neighbors(v) {
                if !used[index_of(v, w)] {
                    curves.push(walk(v, w, &mut used));
                }
            }
        }
    }
    curves
}
