//! Outlier tails: a few outliers hung on an open end (not in the paper; on by default, off in
//! `Params::paper`).
//!
//! Owns: removing every edge of a short chain at a loose end that joins an even, smooth run
//! abruptly. It reads positions and the graph; it may not touch the triangulation, never adds an
//! edge, and does not decide when it runs ([`Params::stages`](crate::Params::stages): after the
//! hooks, before the detours).
//!
//! Why: an outlier one to three spacings beyond an open end is the end's nearest unused point, so
//! Algorithm 1 joins it, and it then looks like one more sample of the curve to every later stage
//! (an edge no longer than a spacing or two, at a point of degree two). What gives it away is the
//! joint: the curve before it is evenly and smoothly sampled, and the step to the outlier is both
//! longer and bent more sharply than anything on that stretch.
//!
//! Rule (docs/condt.md, *Outlier tails*): from each loose end, the tail of its first `m` points
//! (`m` = 1 to [`MAX_TAIL`], the local outlier removal's short branch) hangs by the joint `pq`
//! (`q` the tail's last point) from `p`, which starts a run of [`RUN_EDGES`] edges through points
//! of degree two. The tail is cut (all its edges) for the smallest `m` where
//! - the joint is longer than [`FLOOR_RATIO`] times the run's first edge `ℓ` (the IQR stage's
//!   floor: an edge beyond it is no longer one spacing),
//! - the run is even: each of its edges within [`NEED_RATIO`] of the next (the repair's bound for
//!   two edges of one sampling),
//! - and the joint bends: the turn at `p` is more than twice the turn the run's sharpest bend `τ`
//!   would give over the joint, `τ (ℓ + |pq|) / 2ℓ`, as a circle of that curvature would (a
//!   curve's own end, sampled more sparsely, keeps bending as its run does).
//!
//! Every choice is made on the graph as it came in: the result depends neither on the order of
//! the ends nor on `parallel`.

use super::gaps::Ends;
use super::local_outliers::MIN_SAMPLES;
use super::outliers::FLOOR_RATIO;
use super::repair::{angle_at, NEED_RATIO};
use super::Replaced;
use crate::adjacency::ordered;
use crate::mesh::VertexId;
use alloc::vec::Vec;
use core::f64::consts::PI;

/// Most points of a tail: fewer than a branch the local outlier removal keeps.
const MAX_TAIL: usize = MIN_SAMPLES - 1;
/// Edges of the run a tail hangs from: a branch past the joint (as the junctions').
const RUN_EDGES: usize = MIN_SAMPLES;
/// Points of the chain read from a loose end: the longest tail, its joint's far end and the run.
const CHAIN: usize = MAX_TAIL + RUN_EDGES + 1;

impl Ends<'_> {
    /// The tail the loose end `a` hangs and the point it hangs from (`m + 1` points from `a`),
    /// if the module's rule cuts one.
    fn tail_of(&self, a: VertexId) -> Option<([VertexId; MAX_TAIL + 1], usize)> {
        let mut chain = [VertexId::INFINITE; CHAIN];
        chain[0] = a;
        chain[1] = self.along(a);
        let mut len = 2;
        // Beyond a point of another degree the chain is no run (a walk from a loose end through
        // points of degree two cannot come back).
        for [_, _, next] in self.graph.passages(a, chain[1]).take(CHAIN - 2) {
            chain[len] = next;
            len += 1;
        }
        let dist =
            |j: usize, k: usize| libm::sqrt(self.point(chain[j]).dist2(self.point(chain[k])));
        // The turn at `chain[k]` along the chain: π less the angle there (0 straight on).
        let turn = |k: usize| PI - angle_at(self.tri, chain[k], chain[k - 1], chain[k + 1]);
        // The tail `chain[..m]` hangs from `chain[m]`, whose run is `chain[m..=m + RUN_EDGES]`.
        (1..=MAX_TAIL)
            .take_while(|&m| m + RUN_EDGES < len)
            .find(|&m| {
                // The joint's length first: on scattered points it settles nearly every end.
                let first = dist(m, m + 1);
                let joint = dist(m - 1, m);
                if joint <= FLOOR_RATIO * first {
                    return false;
                }
                let mut previous = first;
                let even = (m + 1..m + RUN_EDGES).all(|k| {
                    let next = dist(k, k + 1);
                    let pair_even = previous.max(next) <= NEED_RATIO * previous.min(next);
                    previous = next;
                    pair_even
                });
                if !even {
                    return false;
                }
                let sharpest = (m + 1..m + RUN_EDGES).map(turn).fold(0.0, f64::max);
                turn(m) * first > sharpest * (first + joint)
            })
            .map(|m| {
                let mut tail = [VertexId::INFINITE; MAX_TAIL + 1];
                tail[..=m].copy_from_slice(&chain[..=m]);
                (tail, m)
            })
    }
}

/// Cuts the outlier tails of the graph of `ends` ([`super::with_ends`]): the module's rule.
pub(crate) fn cut_tails(ends: &Ends<'_>, parallel: bool) -> Replaced {
    let tails = ends.each_loose(parallel, |a| ends.tail_of(a));
    // Each tail's edges, the joint last. Two tails of one chain share no edge: tails of `m` and
    // `m'` points from its two ends meet only on a chain of `m + m'` points or fewer, and each
    // needs `m + 6` (its run) behind it.
    let removed = tails
        .iter()
        .flat_map(|(tail, m)| tail[..=*m].windows(2).map(|w| ordered(w[0], w[1])))
        .collect();
    (removed, Vec::new())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::Edge;
    use crate::{triangulate, Point};

    /// The edges `cut_tails` leaves of the chain through `pts` in order, in input positions.
    fn kept(pts: &[Point]) -> Vec<[usize; 2]> {
        let tri = triangulate(pts).unwrap();
        let listed: Vec<Edge> = (1..pts.len())
            .map(|i| ordered(tri.vertex(i - 1), tri.vertex(i)))
            .collect();
        let out = crate::stages::with_ends(&tri, &listed, None, false, cut_tails)
            .edges
            .unwrap_or_else(|| listed.clone());
        crate::Graph::new(&tri, alloc::borrow::Cow::Owned(out)).edges()
    }

    /// The points of `extra` (the first beside the arc, each further out), listed from the last,
    /// then samples of an arc of radius 10 at the angles `ts`: one chain from its loose end.
    fn tail_then_arc(extra: &[Point], ts: &[f64]) -> Vec<Point> {
        let mut pts: Vec<Point> = extra.iter().rev().copied().collect();
        pts.extend(
            ts.iter()
                .map(|&t| Point::new(10.0 * libm::sin(t), 10.0 - 10.0 * libm::cos(t))),
        );
        pts
    }

    /// [`tail_then_arc`] on eight unit-spaced samples (a turn of 0.1 a sample).
    fn arc_then(extra: &[Point]) -> Vec<Point> {
        let ts: Vec<f64> = (0..8).map(|k| 0.1 * k as f64).collect();
        tail_then_arc(extra, &ts)
    }

    fn chain_edges(n: usize) -> Vec<[usize; 2]> {
        (1..n).map(|i| [i - 1, i]).collect()
    }

    #[test]
    fn an_outlier_beyond_an_end_at_a_bend_is_cut() {
        // Two spacings from the arc's first sample, turned 60° off its way.
        let pts = arc_then(&[Point::new(-1.0, 1.732)]);
        assert_eq!(kept(&pts), chain_edges(pts.len())[1..].to_vec());
    }

    #[test]
    fn a_tail_of_two_outliers_goes_whole() {
        let pts = arc_then(&[Point::new(-1.0, 1.732), Point::new(-1.5, 2.5)]);
        assert_eq!(kept(&pts), chain_edges(pts.len())[2..].to_vec());
    }

    #[test]
    fn an_end_that_goes_on_bending_as_its_curve_does_stays() {
        // The arc continued at twice the spacing: longer, but bent as the arc bends.
        let t = -0.2f64;
        let pts = arc_then(&[Point::new(10.0 * libm::sin(t), 10.0 - 10.0 * libm::cos(t))]);
        assert_eq!(kept(&pts), chain_edges(pts.len()));
    }

    #[test]
    fn a_short_joint_or_an_uneven_run_is_no_tail() {
        // Turned 60° off the arc but only 1.2 spacings away: one sampling.
        let near = arc_then(&[Point::new(-0.6, 1.04)]);
        assert_eq!(kept(&near), chain_edges(near.len()));
        // The same outlier on a run whose spacing doubles after three edges: no even run.
        let ts = [0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.1];
        let uneven = tail_then_arc(&[Point::new(-1.0, 1.732)], &ts);
        assert_eq!(kept(&uneven), chain_edges(uneven.len()));
    }

    #[test]
    fn a_curve_too_short_for_a_run_is_left_alone() {
        let mut pts = arc_then(&[Point::new(-1.0, 1.732)]);
        pts.truncate(6);
        assert_eq!(kept(&pts), chain_edges(pts.len()));
    }
}
