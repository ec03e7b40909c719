//! Hooks: a loose end that hooks back beside its curve put back in line (not in the paper; on by
//! default, off in `Params::paper`).
//!
//! Owns: replacing one edge `a b` by `a c` and `b x`, where the loose end `c` hangs from `b`. It
//! reads positions, the graph and the Delaunay rings; it may not touch the triangulation, and does
//! not decide when it runs ([`Params::stages`](crate::Params::stages): after the spikes, before
//! the outlier tails).
//!
//! Why: noise of a fraction of a spacing can put a sample `b` nearer the sample `a` before it than
//! the sample `c` that lies between them along the curve. Algorithm 1 then joins `a b`, `c` hangs
//! from `b` (the passage `a b c` turns back), and the curve's next sample `x` is left a loose end
//! or without edges: the curve is cut where it runs on. Gap closing joins ends that face each
//! other; `c` faces back the way it came.
//!
//! Rule (each test with its reason: docs/condt.md, *Hooks*): for a loose end `c` whose neighbour
//! `b` has degree two, `b`'s other neighbour `a` degree two (its other neighbour `a'`), `c` a
//! Delaunay neighbour of `a`, and `x` a Delaunay neighbour of `b` other than `a` and `c` that is a
//! loose end (its neighbour `x'` none of `a`, `b`, `c`) or has no edge: `a b` gives way to `a c`
//! and `b x` when `a c` is within [`GAP_RATIO`] of `a a'` (the edge it continues), `b x` within
//! [`GAP_RATIO`] of the longer of `a c` and `c b` (the end's last two edges, as gap closing
//! measures a gap) and, for a loose end `x`, of the longer of `x`'s last two edges (gap closing's
//! own measure, `Ends::short`), and the sharpest passage the move makes (at `a`, `c`, `b`, and
//! at `x` when it is a loose end) is wider than the hook's at `b`, or every one of them but
//! `c`'s is smooth ([`SMOOTH_COS`]: `c` becomes a tip's apex with smooth sides, a shape the tips
//! and spikes steps accept too). A loose end with two moves, or a point in two moves, takes part
//! in none: the result depends neither on the order nor on `parallel`.

use super::gaps::{Ends, GAP_RATIO};
use super::local_outliers::SMOOTH_COS;
use super::{alone, Replaced};
use crate::adjacency::{ordered, Edge};
use crate::mesh::VertexId;
use alloc::vec::Vec;

/// A move: the loose end `c`, hanging from `b`, put between `a` and `b`; `b` joins `x`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
struct Unhook {
    c: VertexId,
    b: VertexId,
    a: VertexId,
    x: VertexId,
}

/// What a loose end found: its one move, or that it has more than one (it then takes part in
/// none, and no other move may take it).
enum Found {
    One(Unhook),
    Several(VertexId),
}

impl Ends<'_> {
    /// The move the loose end `c` starts, if any (the module's rule).
    fn unhook_at(&self, c: VertexId) -> Option<Found> {
        let graph = &*self.graph;
        let (b, a) = (self.along(c), self.beyond(c)?);
        if graph.degree(a) != 2 {
            return None;
        }
        let before_a = graph.onward(a, b);
        let (pa, pb, pc) = (self.point(a), self.point(b), self.point(c));
        let within = |gap2: f64, of2: f64| gap2 <= GAP_RATIO * GAP_RATIO * of2;
        let hook = self.cos_of(b, a, c);
        // The passages at `a` and `c` do not depend on `x`: tested once, before the ring. Either
        // every passage the move makes is wider than the hook, or `c` becomes a tip's apex: every
        // passage but `c`'s smooth.
        let at_a = self.cos_of(a, before_a, c);
        let wider = at_a.max(self.cos_of(c, a, b)) < hook;
        let apex = at_a < SMOOTH_COS;
        if !(wider || apex) || !within(pa.dist2(pc), pa.dist2(self.point(before_a))) {
            return None;
        }
        let bends_less = |rest: f64| (wider && rest < hook) || (apex && rest < SMOOTH_COS);
        let mesh = self.tri.mesh();
        if !mesh.adjacent(a, c) {
            return None;
        }
        let last_two = pa.dist2(pc).max(pc.dist2(pb));
        let mut found = None;
        for x in mesh.neighbors(b) {
            if x == a || x == c {
                continue;
            }
            let at_b = self.cos_of(b, c, x);
            let passes = within(pb.dist2(self.point(x)), last_two)
                && match graph.degree(x) {
                    0 => bends_less(at_b),
                    1 => {
                        let beyond = self.along(x);
                        ![a, b, c].contains(&beyond)
                            && self.short(x, b, true)
                            && bends_less(at_b.max(self.cos_of(x, beyond, b)))
                    }
                    _ => false,
                };
            if passes {
                if found.is_some() {
                    return Some(Found::Several(c));
                }
                found = Some(Found::One(Unhook { c, b, a, x }));
            }
        }
        found
    }
}

/// Puts hooked loose ends in the graph of `ends` back in line ([`super::with_ends`]): the replaced
/// edges, and each move's two edges by increasing loose end.
pub(crate) fn unhook(ends: &Ends<'_>, parallel: bool) -> Replaced {
    let moves = settled(ends, parallel);
    let replaced = moves.iter().map(|m| ordered(m.a, m.b)).collect();
    (replaced, joins_of(&moves))
}

/// The edges the stage's moves would add on the graph of `ends`, found and settled as the stage
/// finds and settles them: rule 4 of the local outlier removal and the clump stage keep the
/// pieces they join to a component that stays, as they keep those gap closing joins
/// (`local_outliers::would_join`).
pub(crate) fn hook_joins(ends: &Ends, parallel: bool) -> Vec<Edge> {
    joins_of(&settled(ends, parallel))
}

/// Every move of the rule on the graph of `ends`, settled: a point in two moves, or a loose end
/// with two, takes part in none.
fn settled(ends: &Ends, parallel: bool) -> Vec<Unhook> {
    let mut moves = Vec::new();
    let mut claimed = Vec::new();
    for found in ends.each_loose(parallel, |c| ends.unhook_at(c)) {
        match found {
            Found::One(m) => moves.push(m),
            Found::Several(c) => claimed.push(c),
        }
    }
    alone(ends.tri.num_points(), &mut moves, &claimed, |m| {
        [m.a, m.b, m.c, m.x]
    });
    moves
}

/// The two edges each move adds, `a c` and `b x`, in the moves' order.
fn joins_of(moves: &[Unhook]) -> Vec<Edge> {
    moves
        .iter()
        .flat_map(|m| [ordered(m.a, m.c), ordered(m.b, m.x)])
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::{triangulate, Point};

    /// A curve along `y = 0` (points `0..=5`, the last `c`) that steps up to `y = 0.5` at `b`
    /// (point 6, at `x = 5.6`) and runs on through `onward` more points from `x = 6.6`; its edges
    /// run `4 b c`, a hook, and from 7 on. `sharp` moves `c` off the line, beyond `b`.
    fn stepped_curve(onward: usize, sharp: bool) -> (Vec<Point>, Vec<[usize; 2]>) {
        let mut pts: Vec<Point> = (0..6).map(|k| Point::new(k as f64, 0.0)).collect();
        if sharp {
            pts[5] = Point::new(4.6, 0.9);
            pts.push(Point::new(5.0, 0.2));
        } else {
            pts.push(Point::new(5.6, 0.5));
        }
        pts.extend((0..onward).map(|k| Point::new(6.6 + k as f64, 0.5)));
        let mut edges = vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 6], [5, 6]];
        edges.extend((7..6 + onward).map(|i| [i, i + 1]));
        (pts, edges)
    }

    fn unhooked(pts: &[Point], edges: Vec<[usize; 2]>) -> Vec<[usize; 2]> {
        let tri = triangulate(pts).unwrap();
        tri.graph_from_edges(edges).unhook().edges()
    }

    #[test]
    fn a_hooked_end_goes_back_in_line_and_the_curve_runs_on() {
        let (pts, edges) = stepped_curve(4, false);
        let out = unhooked(&pts, edges.clone());
        let mut expected: Vec<[usize; 2]> = edges.into_iter().filter(|&e| e != [4, 6]).collect();
        expected.extend([[4, 5], [6, 7]]);
        expected.sort_unstable();
        assert_eq!(out, expected);
    }

    #[test]
    fn a_hooked_end_runs_on_to_a_point_without_edges() {
        // Point 7 has no edge: the curve from 8 on starts one sample late.
        let (pts, edges) = stepped_curve(4, false);
        let edges: Vec<[usize; 2]> = edges.into_iter().filter(|&e| e != [7, 8]).collect();
        let out = unhooked(&pts, edges);
        assert!(out.contains(&[4, 5]) && out.contains(&[6, 7]) && !out.contains(&[4, 6]));
    }

    #[test]
    fn a_gap_to_a_crowded_loose_end_is_read_against_its_edge_before() {
        // The curve's next samples crowd: 7 and 8 are 0.3 apart, 8 and 9 a spacing. The gap
        // `6 7` (a spacing) is over 2.75 times `7 8`, within 2.75 times `8 9`.
        let (mut pts, edges) = stepped_curve(4, false);
        for (k, x) in [(8, 6.9), (9, 7.9), (10, 8.9)] {
            pts[k] = Point::new(x, 0.5);
        }
        let out = unhooked(&pts, edges);
        assert!(out.contains(&[4, 5]) && out.contains(&[6, 7]) && !out.contains(&[4, 6]));
    }

    #[test]
    fn a_hook_with_nothing_beside_it_stays() {
        let (pts, edges) = stepped_curve(0, false);
        assert_eq!(unhooked(&pts, edges.clone()), edges);
    }

    #[test]
    fn a_move_that_turns_as_sharply_as_the_hook_is_not_made() {
        // `c` lies beyond `b`: the passage `4 c b` would turn more sharply than the hook `4 b c`.
        let (pts, edges) = stepped_curve(4, true);
        let mut sorted = edges.clone();
        sorted.sort_unstable();
        assert_eq!(unhooked(&pts, edges), sorted);
    }

    #[test]
    fn two_hooks_reaching_for_one_point_leave_it() {
        // The stepped curve, its mirror image beyond `x = 7.6`, and the point (7.6, 0.5) between,
        // without edges: both hooked ends would run on to it.
        let (mut pts, mut edges) = stepped_curve(0, false);
        let n = pts.len();
        let mirrored: Vec<Point> = pts.iter().map(|p| Point::new(15.2 - p.x, p.y)).collect();
        pts.extend(mirrored);
        edges.extend(edges.clone().iter().map(|&[i, j]| [i + n, j + n]));
        pts.push(Point::new(7.6, 0.5));
        let mut sorted = edges.clone();
        sorted.sort_unstable();
        assert_eq!(unhooked(&pts, edges.clone()), sorted);
        // Either alone is unhooked.
        let left: Vec<[usize; 2]> = edges.iter().copied().filter(|e| e[1] < n).collect();
        let out = unhooked(&pts, left);
        assert!(out.contains(&[4, 5]) && out.contains(&[6, 2 * n]));
    }

    /// A tip with its apex `c` (point 5) at (0, 9): the left side runs up through 0..=2 to `x`
    /// (point 2, a loose end), the right side down from `a` (point 4) through 6..=8. The curve
    /// reaches the left side's last sample `b` (point 3) from `a` across the tip, and `c` hangs
    /// from `b`: the move makes `c` an apex of 37°, sharper than the hook's 72°, with every other
    /// passage smooth.
    #[test]
    fn a_hooked_end_at_a_tip_goes_back_as_its_apex() {
        let pts: Vec<Point> = [
            (-2.5, -3.0),
            (-2.0, 0.0),
            (-1.5, 3.0),
            (-1.0, 6.0),
            (1.0, 6.0),
            (0.0, 9.0),
            (1.5, 3.0),
            (2.0, 0.0),
            (2.5, -3.0),
        ]
        .iter()
        .map(|&(x, y)| Point::new(x, y))
        .collect();
        let edges = vec![[0, 1], [1, 2], [3, 4], [3, 5], [4, 6], [6, 7], [7, 8]];
        let out = unhooked(&pts, edges);
        assert!(out.contains(&[4, 5]) && out.contains(&[2, 3]), "{out:?}");
        assert!(!out.contains(&[3, 4]));
    }
}
