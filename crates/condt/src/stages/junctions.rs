//! Junctions: where three curves meet (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: adding one edge at a loose end that meets a curve at a junction. It reads positions, the
//! graph and the Delaunay rings; it may not touch the triangulation, never removes an edge, and
//! does not decide when it runs ([`Params::stages`](crate::Params::stages): after gap closing,
//! before the crossings).
//!
//! Why: at a junction of three curves (map borders, a T) the repair keeps two of the sample's three
//! edges, so the third curve ends one sample short; gap closing leaves such ends alone on purpose.
//! Rule (each test with its reason: docs/condt.md, *Junctions*): a loose end `a` joins the
//! Delaunay neighbour `c` with two edges that it faces within 30° ([`STRAIGHT`]; a crowded end's
//! angles read from the sample before its neighbour, as gap closing reads them), within
//! [`GAP_RATIO`] times `c`'s shorter edge (its longer where the two are not one sampling), with
//! three branches (`Ends::branch`), straightest ahead among those that pass (ties by id), and
//! chosen by no other loose end. All choices are made on the graph as it came in: the result
//! depends neither on the order of the ends nor on `parallel`.

use super::gaps::{Ends, GAP_RATIO, STRAIGHT};
use super::{alone, Outcome};
use crate::adjacency::{ordered, CurveGraph, Edge};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;

impl Ends<'_> {
    /// Whether the loose end `a` meets the degree-two point `c` at a junction (the module's rule).
    fn meets_at_junction(&self, a: VertexId, c: VertexId) -> bool {
        if self.graph.degree(c) != 2 || !self.faces(a, c) || self.turn(a, c) >= STRAIGHT {
            return false;
        }
        let [x, y] = self.graph.first_two(c);
        let (pa, pc) = (self.point(a), self.point(c));
        let (e1, e2) = (pc.dist2(self.point(x)), pc.dist2(self.point(y)));
        let (shorter, longer) = (e1.min(e2), e1.max(e2));
        // Where `c`'s edges are no one sampling by Algorithm 1's own ratio, the shorter measures
        // none: a second sample right beside the junction, as where outlines digitised apart
        // meet (a Natural Earth junction has one 1/2000 of a spacing away).
        let spacing = if longer > GAP_RATIO * GAP_RATIO * shorter {
            longer
        } else {
            shorter
        };
        pa.dist2(pc) <= GAP_RATIO * GAP_RATIO * spacing
            && self.branch(a, self.along(a), &[c, x, y])
            && self.branch(c, x, &[a, y])
            && self.branch(c, y, &[a, x])
    }

    /// The junction the loose end `a` chooses, if any: the straightest ahead that passes.
    fn junction_of(&self, a: VertexId) -> Option<VertexId> {
        // Every junction needs the end's own branch: without it (most ends on scattered points)
        // the ring is skipped (speed).
        if !self.branch(a, self.along(a), &[]) {
            return None;
        }
        self.tri
            .mesh()
            .neighbors(a)
            .filter(|&c| self.meets_at_junction(a, c))
            .map(|c| (self.turn(a, c), c))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .map(|(_, c)| c)
    }
}

/// Joins loose ends in `edges` (each once, any order) to the junctions they meet.
pub(crate) fn join_junctions(
    tri: &Triangulation,
    edges: &[Edge],
    graph: Option<CurveGraph>,
    parallel: bool,
) -> Outcome {
    let ends = Ends::new(tri, edges, graph);
    let mut choices: Vec<(VertexId, VertexId)> =
        ends.each_loose(parallel, |a| ends.junction_of(a).map(|c| (a, c)));
    // A point two loose ends chose goes to neither (each end chooses once, and a point of degree
    // two is no loose end).
    alone(tri.num_points(), &mut choices, &[], |&(a, c)| [a, c]);
    let joins: Vec<Edge> = choices.iter().map(|&(a, c)| ordered(a, c)).collect();
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
        let arms = [(1.0, branch), (-1.0, below)].map(|(sign, count)| {
            (0..count)
                .map(|k| Point::new(6.0, sign * (gap + k as f64)))
                .collect()
        });
        joins_of(&arms)
    }

    /// [`joins`] with the straight curve `0..=12` along `y = 0` and `arms`, each a curve of its
    /// own whose first point is its loose end.
    fn joins_of(arms: &[Vec<Point>]) -> Vec<[usize; 2]> {
        let line: Vec<Point> = (0..=12).map(|i| Point::new(i as f64, 0.0)).collect();
        joins_along(&line, arms)
    }

    /// [`joins_of`] with the curve through `line`, in order, in place of the straight one.
    fn joins_along(line: &[Point], arms: &[Vec<Point>]) -> Vec<[usize; 2]> {
        let mut pts = line.to_vec();
        let mut edges: Vec<[usize; 2]> = (1..line.len()).map(|i| [i - 1, i]).collect();
        for arm in arms {
            let first = pts.len();
            pts.extend_from_slice(arm);
            edges.extend((first..first + arm.len().saturating_sub(1)).map(|i| [i, i + 1]));
        }
        let tri = triangulate(&pts).unwrap();
        let listed: Vec<Edge> = edges
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let out = join_junctions(&tri, &listed, None, false)
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
    fn a_junction_continues_its_branch_straight_on() {
        // A branch leaving the curve at 45°: its end runs straight on into point 6.
        let slanted: Vec<Point> = (1..8)
            .map(|k| Point::new(6.0 + k as f64, k as f64))
            .collect();
        assert_eq!(joins_of(&[slanted]), vec![[6, 13]]);
        // A curve alongside, one spacing above, ending over point 7: every point of the line
        // lies 45° or more off its way (point 6 at 135°), so it is no junction.
        let alongside: Vec<Point> = (7..14).map(|x| Point::new(x as f64, 1.0)).collect();
        assert_eq!(joins_of(&[alongside]), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn a_sample_next_to_the_junction_does_not_hide_it() {
        // Two outlines digitised apart meet at (6, 0): the curve has a second sample 1e-4 beside
        // it. The junction's two edges are then no one sampling, and its longer edge measures the
        // gap (by its shorter one, 1e-4, the branch's end one spacing away was too far).
        let branch: Vec<Point> = (1..8).map(|k| Point::new(6.0, k as f64)).collect();
        let mut line: Vec<Point> = (0..=12).map(|i| Point::new(i as f64, 0.0)).collect();
        line.insert(7, Point::new(6.0 + 1e-4, 0.0));
        assert_eq!(
            joins_along(&line, core::slice::from_ref(&branch)),
            vec![[6, 14]]
        );
        // A curve evenly sampled five times as densely: its samples are a sampling, and the
        // branch's end, five of their spacings away, is no junction of it.
        let dense: Vec<Point> = (0..=60).map(|i| Point::new(i as f64 / 5.0, 0.0)).collect();
        assert_eq!(joins_along(&dense, &[branch]), Vec::<[usize; 2]>::new());
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
