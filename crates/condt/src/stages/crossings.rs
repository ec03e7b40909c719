//! Restoring crossings (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: turning a bent passage and a chord beside it into the crossing they cut short. It reads
//! positions, the graph and the Delaunay rings; it may not touch the triangulation, and does not
//! decide when it runs ([`Params::stages`](crate::Params::stages): after the junctions, before the tips).
//!
//! Why: where two curves cross at a sample `x` at a narrow angle, Algorithm 1 can pair the
//! samples next to `x` (the chord `c d`) and give `x` two arms of different curves (a bent
//! passage `a x b`): two V shapes, no point loose, so gap closing sees nothing.
//!
//! Rule, each test with its reason: docs/condt.md, *Crossings read as two bends*. `c d` gives way
//! to `x c` and `x d` when `a x b` bends (below [`STRAIGHT`]), `c`, `d` are Delaunay neighbours of
//! `x` of degree two with `a x c` and `b x d` straight, the four arms are within
//! [`GAP_RATIO`](super::gaps::GAP_RATIO) of each other, the passages at `c` and `d` are
//! straighter through `x` than along the chord, and each arm is a branch (`Ends::branch`). All choices are made on the graph as it came in; a point
//! in two choices, or where two chords pass, takes part in none: the result depends neither on
//! the order nor on `parallel`.

use super::found_at_vertices;
use super::gaps::{one_sampling, Ends, STRAIGHT};
use super::{alone, Replaced};
use crate::adjacency::ordered;
use crate::mesh::VertexId;
use alloc::vec::Vec;

/// Whether the vectors `u` and `w` from one point make a straight passage ([`STRAIGHT`]), without
/// a square root (speed).
fn straight(u: (f64, f64), w: (f64, f64)) -> bool {
    let dot = u.0 * w.0 + u.1 * w.1;
    let norms2 = (u.0 * u.0 + u.1 * u.1) * (w.0 * w.0 + w.1 * w.1);
    dot < 0.0 && dot * dot > STRAIGHT * STRAIGHT * norms2
}

/// A crossing to restore: at `x`, the chord `c d` replaced by `x c` and `x d`.
#[derive(Copy, Clone, Debug, PartialEq)]
struct Crossing {
    x: VertexId,
    c: VertexId,
    d: VertexId,
}

impl Ends<'_> {
    /// Whether the passage at `c` (degree two) is straighter through `x` than along `d`, its
    /// neighbour that `x` replaces.
    pub(super) fn straighter(&self, c: VertexId, d: VertexId, x: VertexId) -> bool {
        let other = self.graph.onward(c, d);
        self.cos_of(c, other, x) < self.cos_of(c, other, d)
    }

    /// The crossing `x` restores, if exactly one chord passes (two would be a guess).
    fn crossing_at(&self, x: VertexId) -> Option<Crossing> {
        if self.graph.degree(x) != 2 {
            return None;
        }
        let [a, b] = self.graph.first_two(x);
        let px = self.point(x);
        let arm = |v: VertexId| {
            let p = self.point(v);
            (p.x - px.x, p.y - px.y)
        };
        let (to_a, to_b) = (arm(a), arm(b));
        // Both of `x`'s own arms must be branches whatever the chord: tested before the ring walk,
        // which most points on scattered sets would pay for nothing (speed).
        if straight(to_a, to_b) || !self.branch(x, a, &[]) || !self.branch(x, b, &[]) {
            return None;
        }
        let mesh = self.tri.mesh();
        let mut found: Option<Crossing> = None;
        for c in mesh.neighbors(x) {
            if c == a || c == b {
                continue;
            }
            // `c` continues `a` or `b` straight through `x`; `d` must continue the other.
            let to_c = arm(c);
            let (other, to_other) = if straight(to_a, to_c) {
                (b, to_b)
            } else if straight(to_b, to_c) {
                (a, to_a)
            } else {
                continue;
            };
            if self.graph.degree(c) != 2 {
                continue;
            }
            for d in self.graph.first_two(c) {
                let passes = d != x
                    && d != other
                    && straight(to_other, arm(d))
                    && self.graph.degree(d) == 2
                    && mesh.adjacent(x, d)
                    && one_sampling(&[a, b, c, d].map(|w| px.dist2(self.point(w))))
                    && self.straighter(c, d, x)
                    && self.straighter(d, c, x)
                    && self.branch(d, c, &[])
                    && self.branch(c, d, &[]);
                if !passes {
                    continue;
                }
                // Each chord is met from both its ends: keep it once, smaller end first.
                let (c, d) = (c.min(d), c.max(d));
                match found {
                    None => found = Some(Crossing { x, c, d }),
                    Some(k) if (k.c, k.d) == (c, d) => {}
                    Some(_) => return None,
                }
            }
        }
        found
    }
}

/// Restores crossings in the graph of `ends` ([`super::with_ends`]): the chords, and each
/// crossing's two arms by increasing `x`.
pub(crate) fn restore_crossings(ends: &Ends<'_>, parallel: bool) -> Replaced {
    let (tri, n) = (ends.tri, ends.tri.num_points());
    // Most of the stage's cost: each point judged alone, in ranges on threads when `parallel`.
    let mut restored: Vec<Crossing> = found_at_vertices(n, parallel, |v| {
        ends.graph.prefetch_ahead(v.index(), tri.vertex_points());
        ends.crossing_at(v)
    });
    // A point in two crossings (a crossing's and a chord's end, say) takes part in none.
    alone(n, &mut restored, &[], |k| [k.x, k.c, k.d]);
    let chords = restored.iter().map(|k| ordered(k.c, k.d)).collect();
    let arms = restored
        .iter()
        .flat_map(|k| [ordered(k.x, k.c), ordered(k.x, k.d)])
        .collect();
    (chords, arms)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::Edge;
    use crate::{triangulate, Point};

    /// Two straight curves crossing at point 0 at `angle` degrees, unit spacing, `arm` samples on
    /// each of the four arms (arm k: points 1 + k * arm ..), and the edges of the V reading: `0`
    /// keeps the first sample of arms 0 and 1; the first samples of arms 2 and 3 are paired.
    fn crossed(angle: f64, arm: usize) -> (Vec<Point>, Vec<[usize; 2]>) {
        let t = angle.to_radians();
        let directions = [(1.0, 0.0), (libm::cos(t), libm::sin(t)), (-1.0, 0.0)];
        let directions = [
            directions[0],
            directions[1],
            directions[2],
            (-libm::cos(t), -libm::sin(t)),
        ];
        let mut pts = vec![Point::new(0.0, 0.0)];
        let mut edges = Vec::new();
        for (k, (dx, dy)) in directions.iter().enumerate() {
            let first = pts.len();
            pts.extend((1..=arm).map(|i| Point::new(dx * i as f64, dy * i as f64)));
            edges.extend((first..first + arm - 1).map(|i| [i, i + 1]));
            if k < 2 {
                edges.push([0, first]);
            }
        }
        edges.push([1 + 2 * arm, 1 + 3 * arm]);
        (pts, edges)
    }

    /// Runs the stage and returns its edges (input positions, sorted), or `None` if unchanged.
    fn run(pts: &[Point], pairs: &[[usize; 2]]) -> Option<Vec<[usize; 2]>> {
        let tri = triangulate(pts).unwrap();
        let edges: Vec<Edge> = pairs
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let out = crate::stages::with_ends(&tri, &edges, None, false, restore_crossings).edges?;
        Some(crate::Graph::new(&tri, alloc::borrow::Cow::Owned(out)).edges())
    }

    #[test]
    fn two_vs_at_a_narrow_crossing_become_an_x() {
        for angle in [40.0, 60.0, 90.0] {
            let arm = 7;
            let (pts, edges) = crossed(angle, arm);
            let out = run(&pts, &edges).expect("the crossing is restored");
            let degree = |v: usize| out.iter().filter(|e| e.contains(&v)).count();
            assert_eq!(degree(0), 4, "{angle}°");
            assert!(!out.contains(&[1 + 2 * arm, 1 + 3 * arm]), "{angle}°");
            assert!(out.contains(&[0, 1 + 2 * arm]) && out.contains(&[0, 1 + 3 * arm]));
            assert_eq!(out.len(), edges.len() + 1);
        }
    }

    #[test]
    fn short_arms_are_a_scatter_not_a_crossing() {
        // Four samples per arm: the chain from an arm's first sample has three points of degree
        // two before its end, under the five a branch needs.
        let (pts, edges) = crossed(40.0, 4);
        assert_eq!(run(&pts, &edges), None);
    }

    #[test]
    fn a_chord_that_continues_its_curve_stays() {
        // A straight curve 0..16 along y = 0 and, just below its edge 7-8, the apex 16 of a V (a
        // sharp corner of another curve) whose legs 17..24 and 24..31 run straight away from 8
        // and from 7: all but the passage test pass, but 7 and 8 pass straighter along their
        // edge than through 16, so it is no chord.
        let mut pts: Vec<Point> = (0..16).map(|i| Point::new(i as f64, 0.0)).collect();
        let apex = Point::new(7.5, -0.8);
        pts.push(apex);
        let norm = libm::sqrt(0.5 * 0.5 + 0.8 * 0.8);
        for dx in [-0.5, 0.5] {
            pts.extend((1..=7).map(|i| {
                let r = i as f64 / norm;
                Point::new(apex.x + dx * r, apex.y - 0.8 * r)
            }));
        }
        let mut edges: Vec<[usize; 2]> = (0..15).map(|i| [i, i + 1]).collect();
        edges.extend([[16, 17], [16, 24]]);
        edges.extend((17..23).chain(24..30).map(|i| [i, i + 1]));
        assert_eq!(run(&pts, &edges), None);
    }
}
