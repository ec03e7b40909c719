//! Stage 3, outlier removal (Algorithm 3).
//!
//! Owns: the interquartile-range rule on squared edge lengths. It reads point positions and the
//! graph; it may not touch the triangulation.
//!
//! With the sorted squared lengths `s` of the `n` edges: `Q1 = s[n/4]`, `Q3 = s[3n/4]`,
//! `T = Q3 + k (Q3 - Q1)` (`k = 1.7` by default). The filter applies only when some vertex has
//! every one of its edges longer than the bound (squared length `> 2T`); it then keeps the edges
//! whose squared length is below `T`. `docs/condt.md` (note 5) gives the reading and the evidence.

use crate::graph::{degrees, Edge};
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;

/// The result of the outlier stage.
pub(crate) struct Filtered {
    pub(crate) edges: Vec<Edge>,
    pub(crate) applied: bool,
}

pub(crate) fn remove_outliers(tri: &Triangulation, edges: &[Edge], factor: f64) -> Filtered {
    let length2 = |&[a, b]: &Edge| tri.point(a).dist2(tri.point(b));
    let mut sorted: Vec<f64> = edges.iter().map(length2).collect();
    if sorted.is_empty() {
        return Filtered {
            edges: Vec::new(),
            applied: false,
        };
    }
    sorted.sort_unstable_by(f64::total_cmp);
    let n = sorted.len();
    let (q1, q3) = (sorted[n / 4], sorted[(3 * n / 4).min(n - 1)]);
    let threshold = q3 + factor * (q3 - q1);
    // A vertex all of whose edges exceed the bound: an isolated point tied in by long edges.
    let vertex_count = tri.points().len();
    let degree = degrees(vertex_count, edges);
    let mut long = vec![0u32; vertex_count];
    for edge in edges {
        if length2(edge) > 2.0 * threshold {
            long[edge[0].index()] += 1;
            long[edge[1].index()] += 1;
        }
    }
    let applied = (0..vertex_count).any(|v| degree[v] > 0 && long[v] == degree[v]);
    if !applied {
        return Filtered {
            edges: edges.to_vec(),
            applied,
        };
    }
    Filtered {
        edges: edges
            .iter()
            .copied()
            .filter(|e| length2(e) < threshold)
            .collect(),
        applied,
    }
}
