//! Junctions: where three curves meet (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: adding one edge at a loose end that meets a curve at a junction. It reads point
//! positions, the graph and the Delaunay rings; it may not touch the triangulation, it never
//! removes an edge, and it does not decide when it runs (that is
//! [`Params::stages`](crate::Params::stages): last, after closing gaps).
//!
//! Why: the proximity graph and the repair keep at most two edges per point, except at
//! crossings. Where three curves meet at a sample (shared borders on a map, a T in a drawing),
//! the sample at the junction has three neighbours it needs, and the repair drops one of them:
//! the third curve ends one sample short, in a loose end facing the junction. Gap closing does
//! not join it, on purpose: one arm alone pointing at a curve may be the end of an open curve.
//!
//! Rule. A loose end `a`, with its one edge to `a'`, joins `c` when:
//!
//! - `c` is a Delaunay neighbour of `a` with two edges, and **faces** `a` as gap closing asks
//!   (ahead of the end, `|ac| <= 2.75 |aa'|`), and `|ac|` is also within 2.75 times `c`'s
//!   shorter edge: the junction's three edges belong to one sampling, by the ratio Algorithm 1
//!   uses for its second edge;
//! - **three branches of their own**: from `c` along each of its two edges, and from `a` away
//!   from `c`, the graph runs through at least five points of degree two
//!   ([`MIN_SAMPLES`], the size below which the local outlier removal calls a branch a spur)
//!   without meeting the other two branches' first points. Noise and outliers make short
//!   spurs and small loops near a curve, not three long branches;
//! - among the Delaunay neighbours of `a` that pass, `c` is the one straightest ahead of the
//!   end (the smallest angle between `a' -> a` and `a -> c`; ties by vertex id): the curve's
//!   last edge points at the junction, while the points next to it on the other curve are off
//!   to the side;
//! - no other loose end chose `c` (two would make it a crossing, gap closing's case).
//!
//! All choices are made on the graph as it came in, at once, so the result does not depend on
//! the order in which ends are visited; the stage is sequential, and the same with `parallel` on
//! or off.

use super::gaps::{cos_at, Ends, GAP_RATIO};
use super::local_outliers::MIN_SAMPLES;
use super::Outcome;
use crate::adjacency::{ordered, CurveGraph, Edge};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;

impl Ends<'_> {
    /// Whether the chain from `next` away from `from` runs through at least [`MIN_SAMPLES`]
    /// points of degree two, none of them in `avoid`.
    fn branch(&self, from: VertexId, next: VertexId, avoid: &[VertexId]) -> bool {
        let (mut prev, mut here) = (from, next);
        for _ in 0..MIN_SAMPLES {
            if self.graph.degree(here) != 2 || avoid.contains(&here) {
                return false;
            }
            let onward = self.graph.onward(here, prev);
            prev = here;
            here = onward;
        }
        true
    }

    /// Whether the loose end `a` meets the degree-two point `c` at a junction (the first two
    /// tests of the module comment).
    fn meets_at_junction(&self, a: VertexId, c: VertexId) -> bool {
        if self.graph.degree(c) != 2 || !self.faces(a, c) {
            return false;
        }
        let [x, y] = self.graph.first_two(c);
        let (pa, pc) = (self.point(a), self.point(c));
        let shorter = pc.dist2(self.point(x)).min(pc.dist2(self.point(y)));
        pa.dist2(pc) <= GAP_RATIO * GAP_RATIO * shorter
            && self.branch(a, self.along(a), &[c, x, y])
            && self.branch(c, x, &[a, y])
            && self.branch(c, y, &[a, x])
    }

    /// The junction the loose end `a` chooses, if any: the straightest ahead that passes.
    fn junction_of(&self, a: VertexId) -> Option<VertexId> {
        let (pa, back) = (self.point(a), self.point(self.along(a)));
        self.tri
            .mesh()
            .neighbors(a)
            .filter(|&c| self.meets_at_junction(a, c))
            .map(|c| (cos_at(pa, back, self.point(c)), c))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .map(|(_, c)| c)
    }
}

/// Joins loose ends in `edges` (each edge once, any order) to the junctions they meet, by the
/// rule of the module comment. The outcome is unchanged when no junction qualifies; otherwise
/// the input edges in their order, then the joins in increasing vertex id of their loose end.
/// `graph` is the curve graph of `edges` when the previous stage had it (built here otherwise);
/// it goes on to the curves when nothing is joined.
pub(crate) fn join_junctions(
    tri: &Triangulation,
    edges: &[Edge],
    graph: Option<CurveGraph>,
) -> Outcome {
    let n = tri.num_points();
    let ends = Ends::new(tri, edges, graph);
    let choices: Vec<(VertexId, VertexId)> = ends
        .loose()
        .filter_map(|a| ends.junction_of(a).map(|c| (a, c)))
        .collect();
    // How many loose ends chose each point, saturating at two.
    let mut chosen = vec![0u8; n];
    for &(_, c) in &choices {
        chosen[c.index()] = (chosen[c.index()] + 1).min(2);
    }
    let joins: Vec<Edge> = choices
        .iter()
        .filter(|&&(_, c)| chosen[c.index()] == 1)
        .map(|&(a, c)| ordered(a, c))
        .collect();
    drop(chosen);
    ends.joined(edges, &joins)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{triangulate, Point};

    /// A straight curve `0..=12` along `y = 0` and, above point 6, a branch of `branch` samples
    /// at `x = 6`, `y = gap, gap + 1, ...`; with `below` samples more below point 6 as well when
    /// `below > 0` (a crossing whose two arms were dropped). Returns the joins the stage adds, in
    /// input positions.
    fn joins(branch: usize, gap: f64, below: usize) -> Vec<[usize; 2]> {
        let mut pts: Vec<Point> = (0..=12).map(|i| Point::new(i as f64, 0.0)).collect();
        let mut edges: Vec<[usize; 2]> = (0..12).map(|i| [i, i + 1]).collect();
        for (sign, count) in [(1.0, branch), (-1.0, below)] {
            let first = pts.len();
            pts.extend((0..count).map(|k| Point::new(6.0, sign * (gap + k as f64))));
            edges.extend((first..first + count.saturating_sub(1)).map(|i| [i, i + 1]));
        }
        let tri = triangulate(&pts).unwrap();
        let listed: Vec<Edge> = edges
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let out = join_junctions(&tri, &listed, None)
            .edges
            .unwrap_or_else(|| listed.clone());
        assert_eq!(&out[..listed.len()], &listed[..], "never removes an edge");
        crate::Graph::new(&tri, alloc::borrow::Cow::Borrowed(&out[listed.len()..])).edges()
    }

    #[test]
    fn a_branch_one_sample_short_of_a_curve_is_joined_at_the_junction() {
        assert_eq!(joins(7, 1.0, 0), vec![[6, 13]]);
        // Sampled alike: a gap of 2.5 spacings is still one sampling, 3 is not.
        assert_eq!(joins(7, 2.5, 0), vec![[6, 13]]);
        assert_eq!(joins(7, 3.0, 0), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn a_short_spur_is_not_a_branch() {
        // Five points of degree two past the end are needed: a branch of 6 samples has 4.
        assert_eq!(joins(6, 1.0, 0), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn two_ends_meeting_one_point_are_a_crossing_not_a_junction() {
        assert_eq!(joins(7, 1.0, 7), Vec::<[usize; 2]>::new());
    }
}
