//! Curves from an edge set: ordered polylines, closed or open.
//!
//! Owns: turning a graph whose vertices mostly have degree two into polylines. It may not look at
//! coordinates: the order along a curve is the graph's.
//!
//! A polyline runs between vertices whose degree is not two (ends and branch points); what is
//! left once those are walked are cycles of degree-two vertices, reported as closed curves. A
//! polyline that leaves a branch vertex and comes back to it (one lobe of a figure eight) is
//! closed too.

use crate::graph::{Adjacency, Edge};
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
    let mut curves = Vec::new();
    // Polylines between ends and branch points first, then the remaining pure cycles.
    for cycles in [false, true] {
        for i in 0..vertex_count {
            let v = VertexId::new(i as u32);
            let degree = graph.degree(v);
            if degree == 0 || (degree == 2) != cycles {
                continue;
            }
            for &(w, edge) in graph.incident(v) {
                if !used[edge as usize] {
                    used[edge as usize] = true;
                    curves.push(walk(&graph, &mut used, v, w));
                }
            }
        }
    }
    curves
}

/// Follows degree-two vertices from `start` through `first` until an end, a branch point, or
/// back to `start`; marks the edges it crosses.
fn walk(graph: &Adjacency, used: &mut [bool], start: VertexId, first: VertexId) -> Curve {
    let mut path = vec![start.index() as u32];
    let mut current = first;
    loop {
        path.push(current.index() as u32);
        if graph.degree(current) != 2 {
            break;
        }
        let Some(&(next, edge)) = graph
            .incident(current)
            .iter()
            .find(|&&(_, e)| !used[e as usize])
        else {
            break;
        };
        used[edge as usize] = true;
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
}
