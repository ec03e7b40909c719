//! The mesh of a point set with no triangle: all points on one line (or fewer than three distinct).
//!
//! The distinct points are chained along the line, each segment `q_s – q_{s+1}` covered by the
//! ghosts `L_s = (q_s, q_{s+1}, ∞)` at half-edges `6s..6s+3` and `R_s = (q_{s+1}, q_s, ∞)` at
//! `6s+3..6s+6` (`docs/half_edge.md`, *Collinear input*).
//!
//! Owns: building that chain's mesh. It may not be used for a set with a triangle (the insertion
//! builds those) and decides no orientation itself: the caller has found the set collinear.

use crate::geometry::Point;
use crate::mesh::{HalfEdgeId, Mesh, MeshArrays, VertexId};
use alloc::vec::Vec;

/// The chain over `points` (all collinear), the `(duplicate, kept)` pairs and the vertex order
/// (along the line, duplicates together, smallest input position first).
pub(crate) fn chain(points: &[Point]) -> (Mesh, Vec<(u32, u32)>, Vec<u32>) {
    let mut sorted: Vec<u32> = (0..points.len() as u32).collect();
    // On a line, lexicographic order is the order along it; ties (duplicates) by input index.
    sorted.sort_unstable_by(|&i, &j| {
        points[i as usize]
            .lexicographic_cmp(points[j as usize])
            .then(i.cmp(&j))
    });
    let mut merged = Vec::new();
    let mut chain: Vec<VertexId> = Vec::new();
    for (position, &i) in sorted.iter().enumerate() {
        let v = VertexId::new(position as u32);
        match chain.last() {
            Some(&last) if points[sorted[last.index()] as usize] == points[i as usize] => {
                merged.push((position as u32, last.index() as u32));
            }
            _ => chain.push(v),
        }
    }
    let segments = chain.len().saturating_sub(1);
    let mut arrays = MeshArrays::new(6 * segments, false);
    let mut mesh = arrays.builder(0);
    let inf = VertexId::INFINITE;
    let h = |i: usize| HalfEdgeId::new(i as u32);
    for s in 0..segments {
        let (a, b) = (chain[s], chain[s + 1]);
        mesh.push_triangle([a, b, inf]);
        mesh.push_triangle([b, a, inf]);
    }
    for s in 0..segments {
        let (l, r) = (6 * s, 6 * s + 3);
        mesh.link(h(l), h(r));
        // L_s's q_{s+1} → ∞ meets L_{s+1}'s ∞ → q_{s+1}, or turns round the last point into R_s.
        let after = if s + 1 < segments {
            6 * (s + 1) + 2
        } else {
            r + 2
        };
        mesh.link(h(l + 1), h(after));
        // R_s's q_s → ∞ meets R_{s-1}'s ∞ → q_s, or turns round the first point into L_0.
        let before = if s > 0 { 6 * (s - 1) + 5 } else { l + 2 };
        mesh.link(h(r + 1), h(before));
    }
    let len = mesh.len();
    (arrays.seal(len, points.len(), false), merged, sorted)
}
