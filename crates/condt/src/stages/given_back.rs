//! Confirming given-back components, after the local outlier removal and the clumps (not in the
//! paper).
//!
//! Owns: one rule on components that local rule 1 rebuilt from IQR-cut edges; it only removes
//! edges, and may not touch the triangulation.
//!
//! Rule (docs/condt.md, *Confirming given-back components*, with losses and costs): such a
//! component stays only if each of its vertices with two or more edges is separated (by rule 4's [`SEPARATION`]
//! times its longest edge) from unused points and other such components: a chance chain of outliers
//! lies in its scatter, a stretch of curve at most beside other curves. Sequential, deterministic.

use super::local_outliers::{components, without_components, SEPARATION};
use super::Outcome;
use crate::adjacency::{CurveGraph, Edge};
use crate::bits::IdBits;
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;

/// The rule on `edges`, the previous stage's output (the clumps stage's when it runs);
/// `before_local` is the local outlier removal's input.
pub(crate) fn confirm_given_back(
    tri: &Triangulation,
    edges: &[Edge],
    before_local: &[Edge],
    graph: Option<CurveGraph>,
) -> Outcome {
    if core::ptr::eq(edges, before_local) || edges.is_empty() {
        // The local outlier removal changed nothing: its curve graph goes on to the next stage.
        return Outcome::unchanged_with(graph);
    }
    drop(graph); // not read here (memory)
    let n = tri.num_points();
    let given = missing_from(edges, before_local);
    if !given.contains(&true) {
        return Outcome::UNCHANGED;
    }
    let standing = Standing::of(n, edges, &given);
    // The longest (squared) edge of the given-back components' vertices only, few: a sorted
    // list (memory).
    let members: Vec<VertexId> = (0..n as u32)
        .map(VertexId::new)
        .filter(|&v| standing.status(v) == Status::GivenBack)
        .collect();
    let slot = |v: VertexId| members.binary_search(&v).unwrap_or(0);
    let mut longest = vec![-1.0f64; members.len()];
    for &[a, b] in edges {
        if standing.status(a) == Status::GivenBack {
            let l = tri.vertex_point(a).dist2(tri.vertex_point(b));
            for v in [a, b] {
                let k = slot(v);
                longest[k] = longest[k].max(l);
            }
        }
    }
    let dropped = standing.dropped(|v| !standing.apart(tri, v, longest[slot(v)]));
    if !dropped.contains(&true) {
        return Outcome::UNCHANGED;
    }
    Outcome::from(Some(without_components(edges, &standing.root, &dropped)))
}

/// What the rule reads of each point's component: whether it has edges, and whether they are
/// all given back ([`Standing::status`]).
pub(crate) struct Standing {
    pub(crate) root: Vec<u32>,
    /// Per root, whether its component is only given back; read only for points with edges.
    only_given: Vec<bool>,
    degree: Vec<u8>,
}

/// A point's part in the rule.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(crate) enum Status {
    /// No edge: an unused point, near which a given-back component is not apart.
    Unused,
    /// On a component not all given back: a kept curve, which tells nothing about a scatter.
    Kept,
    /// On a component made only of given-back edges: the rule judges it.
    GivenBack,
}

impl Standing {
    /// The components of `edges` over `n` points, and which are only `given` back (per edge).
    pub(crate) fn of(n: usize, edges: &[Edge], given: &[bool]) -> Standing {
        let root = components(n, edges);
        // Components made only of given-back edges (read only at the roots of points with
        // edges), and each vertex's degree (up to 255).
        let mut only_given = vec![true; n];
        let mut degree = vec![0u8; n];
        for (&[a, b], &back) in edges.iter().zip(given) {
            only_given[root[a.index()] as usize] &= back;
            for v in [a, b] {
                degree[v.index()] = degree[v.index()].saturating_add(1);
            }
        }
        Standing {
            root,
            only_given,
            degree,
        }
    }

    /// The standing a tile is sent: each vertex's component name (`root`), its [`Status`] as a
    /// number (`status`, `Status as u8`) and its degree (up to 255).
    pub(crate) fn from_parts(root: Vec<u32>, status: Vec<u8>, degree: Vec<u8>) -> Standing {
        // Only the status's two questions are read: whether a point has edges (its degree) and
        // whether its component is only given back, which holds for its root's entry.
        let mut only_given = vec![false; root.len()];
        for (v, &s) in status.iter().enumerate() {
            if s == Status::GivenBack as u8 {
                only_given[root[v] as usize] = true;
            }
        }
        let degree = degree
            .iter()
            .zip(&status)
            .map(|(&d, &s)| {
                if s == Status::Unused as u8 {
                    0
                } else {
                    d.max(1)
                }
            })
            .collect();
        Standing {
            root,
            only_given,
            degree,
        }
    }

    pub(crate) fn status(&self, v: VertexId) -> Status {
        if self.degree[v.index()] == 0 {
            Status::Unused
        } else if self.only_given[self.root[v.index()] as usize] {
            Status::GivenBack
        } else {
            Status::Kept
        }
    }

    /// Whether `v`, of a given-back component, lies apart: every Delaunay neighbour is in its
    /// component, on a kept curve, or beyond [`SEPARATION`] times `v`'s longest edge (`longest`,
    /// squared). Only unused points and other given-back components count as near: an unused
    /// point is its own root with no edge, and a point of a kept curve tells nothing about a
    /// scatter.
    pub(crate) fn apart(&self, tri: &Triangulation, v: VertexId, longest: f64) -> bool {
        let p = tri.vertex_point(v);
        tri.mesh().neighbors(v).all(|w| {
            self.root[w.index()] == self.root[v.index()]
                || self.status(w) == Status::Kept
                || p.dist2(tri.vertex_point(w)) > SEPARATION * SEPARATION * longest
        })
    }

    /// Which components go: a given-back one with a point of two or more edges that is not apart
    /// (`near(v)`, asked only of such points, at most until its component goes).
    pub(crate) fn dropped(&self, mut near: impl FnMut(VertexId) -> bool) -> Vec<bool> {
        let n = self.root.len();
        let mut dropped = vec![false; n];
        for i in 0..n {
            let r = self.root[i] as usize;
            if self.degree[i] >= 2 && self.only_given[r] && !dropped[r] {
                dropped[r] = near(VertexId::new(i as u32));
            }
        }
        dropped
    }
}

/// Whether each of `edges` (distinct) is missing from `before`: a merge pass matches all but a
/// short tail (the local stage keeps its input's order, then appends), and one pass over `before`
/// (memory) looks up in the tail only edges whose smaller end starts one. Exact for any lists.
pub(crate) fn missing_from(edges: &[Edge], before: &[Edge]) -> Vec<bool> {
    let mut missing = vec![false; edges.len()];
    let mut at = 0;
    let mut tail = edges.len();
    for (k, e) in edges.iter().enumerate() {
        match before[at..].iter().position(|b| b == e) {
            Some(skip) => at += skip + 1,
            None => {
                tail = k;
                break;
            }
        }
    }
    if tail < edges.len() {
        let mut unmatched: Vec<(Edge, usize)> =
            (tail..edges.len()).map(|k| (edges[k], k)).collect();
        unmatched.sort_unstable();
        missing[tail..].fill(true);
        // A bit per unmatched edge's smaller end: most edges of `before` skip the search (speed).
        let ends = IdBits::of(unmatched.iter().map(|(e, _)| e[0].index()));
        for b in before.iter().filter(|b| ends.contains(b[0].index())) {
            if let Ok(at) = unmatched.binary_search_by(|(e, _)| e.cmp(b)) {
                missing[unmatched[at].1] = false;
            }
        }
    }
    missing
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::ordered;
    use crate::{triangulate, Point};
    use alloc::borrow::Cow;

    /// `pairs` (input positions) as edges on `tri`.
    fn vertex_edges(tri: &Triangulation, pairs: &[[usize; 2]]) -> Vec<Edge> {
        pairs
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect()
    }

    /// Which edges are missing from the earlier list, against a lookup of each: on the stage's
    /// usual shape (the earlier list's edges with some removed, new ones appended) and on lists
    /// in any order, where the matching pass gives up early and the tail decides.
    #[test]
    fn missing_edges_are_found_whatever_the_order() {
        let mut rng = crate::test_rng::Xorshift::new(31);
        let e = |a: u64, b: u64| [VertexId::new(a as u32), VertexId::new(1000 + b as u32)];
        for round in 0..300 {
            let len = rng.below(30);
            let before: Vec<Edge> = (0..len).map(|k| e(k, rng.below(5))).collect();
            let mut edges: Vec<Edge> = before
                .iter()
                .copied()
                .filter(|_| rng.below(3) != 0)
                .collect();
            edges.extend((0..rng.below(4)).map(|k| e(100 + k, 0)));
            if round % 3 == 0 && edges.len() > 1 {
                let k = rng.below(edges.len() as u64) as usize;
                edges.swap(0, k);
            }
            let expected: Vec<bool> = edges.iter().map(|x| !before.contains(x)).collect();
            assert_eq!(
                missing_from(&edges, &before),
                expected,
                "{edges:?} {before:?}"
            );
        }
    }

    /// The stage's output in sorted input positions, or `None` when it changed nothing.
    fn apply(
        tri: &Triangulation,
        now: &[[usize; 2]],
        before: &[[usize; 2]],
    ) -> Option<Vec<[usize; 2]>> {
        let (now, before) = (vertex_edges(tri, now), vertex_edges(tri, before));
        confirm_given_back(tri, &now, &before, None)
            .edges
            .map(|e| crate::Graph::new(tri, Cow::Owned(e)).edges())
    }

    /// Fourteen points 0.3 apart along a gently wobbling line: a smooth, regular chain, every
    /// edge given back.
    fn chain() -> (Vec<Point>, Vec<[usize; 2]>) {
        let pts = (0..14)
            .map(|k| Point::new(0.3 * k as f64, 0.01 * libm::sin(1.7 * k as f64)))
            .collect();
        (pts, (0..13).map(|k| [k, k + 1]).collect())
    }

    #[test]
    fn a_given_back_chain_inside_a_scatter_goes() {
        // A pair of unused points 0.45 beside the chain's sixth point, within twice its spacing:
        // the chain lies inside a scatter, and eleven of its points are still apart from all
        // else, so the component rule of the local outlier removal would keep it.
        let (mut pts, given) = chain();
        pts.extend([Point::new(1.75, 0.45), Point::new(1.85, 0.46)]);
        let tri = triangulate(&pts).unwrap();
        assert_eq!(apply(&tri, &given, &[]), Some(Vec::new()));
        // The same edges, not given back (they were there before): the rule does not look.
        assert_eq!(apply(&tri, &given, &given), None);
    }

    #[test]
    fn a_given_back_chain_apart_from_everything_stays() {
        // The sparse curve beside a dense one that rule 1 is for: apart at every point.
        let (mut pts, given) = chain();
        pts.extend([Point::new(1.75, 3.0), Point::new(1.85, 3.01)]);
        let tri = triangulate(&pts).unwrap();
        assert_eq!(apply(&tri, &given, &[]), None);
    }

    #[test]
    fn a_given_back_chain_beside_a_kept_curve_stays() {
        // A kept curve 0.45 beside the chain, within twice its spacing at every point: the
        // stretch of an evenly spaced outline that the IQR rule cut, beside the outline's other
        // side. Kept; the same points left unused make a scatter, and the chain goes.
        let (mut pts, mut given) = chain();
        pts.extend((0..14).map(|k| Point::new(0.3 * k as f64, 0.45)));
        let tri = triangulate(&pts).unwrap();
        let kept: Vec<[usize; 2]> = (14..27).map(|k| [k, k + 1]).collect();
        given.extend(&kept);
        assert_eq!(apply(&tri, &given, &kept), None);
        let scattered = apply(&tri, &given[..13], &[]).expect("the chain goes");
        assert!(scattered.is_empty(), "{scattered:?}");
    }

    #[test]
    fn its_ends_may_lie_near_the_rest_of_the_curve() {
        // A given-back piece whose last point is 0.35 from the next piece of its curve (kept
        // before), within twice its spacing: an end is not asked to be apart, only the points
        // with two edges.
        let (mut pts, mut given) = chain();
        pts.extend([Point::new(4.25, 0.05), Point::new(4.55, 0.05)]);
        let tri = triangulate(&pts).unwrap();
        let before = [[14, 15]];
        given.push([14, 15]);
        assert_eq!(apply(&tri, &given, &before), None);
    }
}
