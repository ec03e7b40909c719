//! Stage 4, closing gaps (not in the paper; off by default).
//!
//! Owns: adding edges at loose ends, the vertices of degree one in the graph the earlier stages
//! left. It reads point positions, the graph and the Delaunay rings; it may not touch the
//! triangulation nor remove an edge, and it never runs before the other stages (the order is
//! [`Params::stages`](crate::Params::stages)'s).
//!
//! Why: the proximity graph keeps at most two edges per point, and the repair keeps at most two
//! per non-manifold vertex. Where a curve bends tightly, or noise moves a sample, the edge between
//! two consecutive samples can be nobody's choice: the curve falls apart into pieces whose ends
//! face each other across a gap of one edge. At a crossing sampled exactly (degree four), the
//! repair keeps one passage and drops the other, leaving two arms that point at the crossing.
//!
//! Rules. A loose end `a` with its one edge to `a'`. Its candidates are its Delaunay neighbours
//! `w` (the ring of `a` in the triangulation, so the stage is O(n) for rings of bounded size)
//! that pass both tests:
//!
//! - **facing**: the angle at `a` between `a'` and `w` exceeds [`FACING`] (120°): the join
//!   continues the end's own direction, turning by less than 60°. It is the angle Algorithm 2
//!   asks of a partner edge (`θ > 2π/3`), for the same reason: two edges through a curve vertex
//!   form a passage, not a spike.
//! - **short**: `|aw| <= GAP_RATIO · |aa'|`, [`GAP_RATIO`] = `u = 2.75`, the paper's uniformity
//!   ratio: Algorithm 1 accepts a second edge up to `u` times the first as the same sampling, so a
//!   gap no longer than that is within the sampling the graph was built for; a longer one is a
//!   real end (an open curve stops there). A ratio of lengths, so it does not depend on the
//!   scale or position of the input.
//!
//! A candidate is either
//!
//! 1. another loose end `b` that passes both tests from its own side (`a` faces `b` and `b`
//!    faces `a`, the gap short for both ends), or
//! 2. a vertex `c` of degree two through which `a` goes straight on (the missing arm of a
//!    crossing): some `x` makes the angle `a c x` larger than [`STRAIGHT`] (150°, the passage
//!    angle of [`Repair::CrossingAware`](crate::Repair::CrossingAware)), where `x` is
//!    - one of `c`'s own neighbours, and `c`'s own passage is not straight (the repair paired an
//!      arm of each curve and dropped one of each), or
//!    - another loose end that targets `c` too, with `c`'s two neighbours on strictly opposite
//!      sides of the line through `a` and `x` (the repair kept one curve and dropped both arms
//!      of the other, which crosses it).
//!
//! Each loose end takes its nearest candidate (ties by vertex id). A join between two loose ends
//! needs each to be the other's choice (mutual), so one end never joins two others; a join to a
//! vertex of degree two needs only the end's choice, and with a loose-end partner that partner's
//! choice of the same vertex. The nearest wins because at a gap the facing loose end is nearer
//! than the sample after it, and at a crossing the crossing vertex is nearer than the arm beyond
//! it. Choices are made on the graph as it came in, all at once, so the result does not depend
//! on the order in which ends are visited. Sequential; the work is proportional to the sizes of
//! the rings around loose ends and their candidates.

use super::Outcome;
use crate::adjacency::{ordered, CurveGraph, Edge};
use crate::geometry::Point;
use crate::mesh::VertexId;
use crate::predicates::{orient2d, Orientation};
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;

/// Cosine of the smallest angle at a loose end between its edge and a join (120°; see the module
/// comment).
const FACING: f64 = -0.5;
/// Cosine of the smallest angle at a crossing for two arms to be one straight passage (150°).
const STRAIGHT: f64 = -0.866_025_403_784_438_6;
/// Longest gap, as a multiple of the loose end's own edge: the paper's `u = 2.75`.
const GAP_RATIO: f64 = 2.75;

/// The cosine of the angle at `v` between the directions to `a` and to `b` (`1` when either is
/// at `v`, so a degenerate angle never passes a test).
fn cos_at(p: Point, a: Point, b: Point) -> f64 {
    let (ux, uy, wx, wy) = (a.x - p.x, a.y - p.y, b.x - p.x, b.y - p.y);
    let norms = libm::sqrt((ux * ux + uy * uy) * (wx * wx + wy * wy));
    if norms > 0.0 {
        (ux * wx + uy * wy) / norms
    } else {
        1.0
    }
}

/// What a loose end chose.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Target {
    None,
    /// Another loose end.
    End(VertexId),
    /// A vertex of degree two, the crossing, with the straight partner there.
    Crossing(VertexId, Partner),
}

/// The arm a loose end lines up with at a crossing.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Partner {
    /// The crossing's neighbour in this slot of its first two (0 or 1).
    Neighbor(usize),
    /// Another loose end across the crossing.
    End(VertexId),
}

struct Ends<'a> {
    tri: &'a Triangulation,
    graph: CurveGraph,
}

impl Ends<'_> {
    fn point(&self, v: VertexId) -> Point {
        self.tri.vertex_point(v)
    }

    fn is_loose(&self, v: VertexId) -> bool {
        self.graph.degree(v) == 1
    }

    /// The one neighbour of the loose end `a`.
    fn along(&self, a: VertexId) -> VertexId {
        self.graph.first_two(a)[0]
    }

    /// Whether the loose end `a` faces `w` and the gap is short (both tests of the module
    /// comment).
    fn faces(&self, a: VertexId, w: VertexId) -> bool {
        let (p, back, q) = (self.point(a), self.point(self.along(a)), self.point(w));
        w != self.along(a)
            && cos_at(p, back, q) < FACING
            && p.dist2(q) <= GAP_RATIO * GAP_RATIO * p.dist2(back)
    }

    /// Whether `a`, facing the degree-two vertex `c`, has a straight partner there.
    fn crossing_partner(&self, a: VertexId, c: VertexId) -> Option<Partner> {
        let (pa, pc) = (self.point(a), self.point(c));
        let [x, y] = self.graph.first_two(c);
        let (px, py) = (self.point(x), self.point(y));
        let own_straight = cos_at(pc, px, py) < STRAIGHT;
        if !own_straight {
            let (cx, cy) = (cos_at(pc, pa, px), cos_at(pc, pa, py));
            if cx.min(cy) < STRAIGHT {
                return Some(Partner::Neighbor(usize::from(cy < cx)));
            }
        }
        // Another loose end across `c`, the arm pair crossing `c`'s passage.
        self.tri
            .mesh()
            .neighbors(c)
            .filter(|&d| d != a && self.is_loose(d) && self.faces(d, c))
            .filter(|&d| cos_at(pc, pa, self.point(d)) < STRAIGHT)
            .filter(|&d| {
                let pd = self.point(d);
                let (sx, sy) = (orient2d(pa, pd, px), orient2d(pa, pd, py));
                sx != Orientation::Collinear && sy != Orientation::Collinear && sx != sy
            })
            .min_by(|&d, &e| {
                let (pd, pe) = (self.point(d), self.point(e));
                cos_at(pc, pa, pd)
                    .total_cmp(&cos_at(pc, pa, pe))
                    .then(d.cmp(&e))
            })
            .map(Partner::End)
    }

    /// The nearest candidate of the loose end `a` (ties by vertex id).
    fn target(&self, a: VertexId) -> Target {
        let pa = self.point(a);
        let mut best = Target::None;
        let mut best_key = (f64::INFINITY, VertexId::INFINITE);
        for w in self.tri.mesh().neighbors(a) {
            let key = (pa.dist2(self.point(w)), w);
            if key.0.total_cmp(&best_key.0).then(key.1.cmp(&best_key.1))
                != core::cmp::Ordering::Less
                || !self.faces(a, w)
            {
                continue;
            }
            let candidate = match self.graph.degree(w) {
                1 if self.faces(w, a) => Target::End(w),
                2 => match self.crossing_partner(a, w) {
                    Some(partner) => Target::Crossing(w, partner),
                    None => continue,
                },
                _ => continue,
            };
            best = candidate;
            best_key = key;
        }
        best
    }
}

/// Closes gaps in `edges` (each edge once, any order) by the rules of the module comment. The
/// outcome is unchanged when no gap qualifies; otherwise the input edges in their order, then the
/// joins in increasing vertex id of their loose end.
pub(crate) fn close_gaps(tri: &Triangulation, edges: &[Edge]) -> Outcome {
    let n = tri.num_points();
    let ends = Ends {
        tri,
        graph: CurveGraph::new(n, edges),
    };
    let mut targets = vec![Target::None; n];
    let mut any = false;
    for (i, target) in targets.iter_mut().enumerate() {
        let a = VertexId::new(i as u32);
        if ends.is_loose(a) {
            *target = ends.target(a);
            any |= *target != Target::None;
        }
    }
    if !any {
        return Outcome::UNCHANGED;
    }
    // Which of its two neighbours each crossing has been lined up with, one bit per slot.
    let mut lined_up = vec![0u8; n];
    for target in &targets {
        if let Target::Crossing(c, Partner::Neighbor(slot)) = *target {
            lined_up[c.index()] |= 1 << slot;
        }
    }
    let mut joins: Vec<Edge> = Vec::new();
    for (i, &target) in targets.iter().enumerate() {
        let a = VertexId::new(i as u32);
        let join = match target {
            Target::End(b) => a < b && targets[b.index()] == Target::End(a),
            // Both dropped arms come back, each in line with one of the two kept ones.
            Target::Crossing(c, Partner::Neighbor(_)) => lined_up[c.index()] == 0b11,
            // Both dropped arms come back, in line with each other.
            Target::Crossing(c, Partner::End(d)) => {
                targets[d.index()] == Target::Crossing(c, Partner::End(a))
            }
            Target::None => false,
        };
        if let Target::End(w) | Target::Crossing(w, _) = target {
            if join {
                joins.push(ordered(a, w));
            }
        }
    }
    if joins.is_empty() {
        return Outcome::UNCHANGED;
    }
    let mut out = Vec::with_capacity(edges.len() + joins.len());
    out.extend_from_slice(edges);
    out.extend_from_slice(&joins);
    Outcome {
        edges: Some(out),
        applied: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangulate;
    use core::f64::consts::PI;

    const NONE: Vec<[usize; 2]> = Vec::new();

    /// Runs the stage on `pairs` (input positions) over `pts` and returns the joins it added, as
    /// sorted input positions.
    fn joins(pts: &[Point], pairs: &[[usize; 2]]) -> Vec<[usize; 2]> {
        let tri = triangulate(pts).unwrap();
        let edges: Vec<Edge> = pairs
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let outcome = close_gaps(&tri, &edges);
        assert_eq!(outcome.applied, outcome.edges.is_some());
        let out = outcome.edges.unwrap_or_else(|| edges.clone());
        assert_eq!(&out[..edges.len()], &edges[..], "never removes an edge");
        let mut added: Vec<[usize; 2]> = out[edges.len()..]
            .iter()
            .map(|&[a, b]| {
                let (a, b) = (tri.input_of(a), tri.input_of(b));
                [a.min(b), a.max(b)]
            })
            .collect();
        added.sort_unstable();
        added
    }

    /// A chain through `0, 1, ..., n - 1`, without the edges listed in `missing` (by their
    /// smaller end).
    fn chain(n: usize, missing: &[usize]) -> Vec<[usize; 2]> {
        (0..n - 1)
            .filter(|i| !missing.contains(i))
            .map(|i| [i, i + 1])
            .collect()
    }

    /// A hairpin: two parallel legs joined by a half circle of radius 1 sampled every 30°,
    /// `(0..n)` in order along it.
    fn hairpin() -> Vec<Point> {
        let mut pts: Vec<Point> = (0..4)
            .map(|k| Point::new(-3.0 + k as f64 * 0.5, 1.0))
            .collect();
        pts.extend((1..6).map(|k| {
            let t = PI / 2.0 - k as f64 * PI / 6.0;
            Point::new(-1.5 + libm::cos(t) + 1.0, libm::sin(t))
        }));
        pts.extend((0..4).map(|k| Point::new(-1.0 - k as f64 * 0.5, -1.0)));
        pts
    }

    #[test]
    fn a_gap_at_a_tight_bend_is_closed() {
        let pts = hairpin();
        // The apex edge (a 30° turn at each end) is missing.
        assert_eq!(joins(&pts, &chain(pts.len(), &[6])), vec![[6, 7]]);
        // The same with a far offset and a tiny scale: only ratios matter.
        let moved: Vec<Point> = pts
            .iter()
            .map(|p| Point::new(1e6 + 1e-5 * p.x, -1e6 + 1e-5 * p.y))
            .collect();
        assert_eq!(joins(&moved, &chain(pts.len(), &[6])), vec![[6, 7]]);
    }

    #[test]
    fn a_gap_longer_than_u_edges_stays_open() {
        // Two unit-spaced chains along a line; the gap between 3 and 4 is `gap` long.
        let line = |gap: f64| -> Vec<Point> {
            (0..8)
                .map(|i| {
                    let x = i as f64 + if i >= 4 { gap - 1.0 } else { 0.0 };
                    Point::new(x, 0.0)
                })
                .collect()
        };
        // On a line the triangulation is a chain: still a ring around every point.
        let broken = chain(8, &[3]);
        assert_eq!(joins(&line(2.7), &broken), vec![[3, 4]]);
        assert_eq!(joins(&line(2.8), &broken), NONE);
    }

    #[test]
    fn an_open_arc_stays_open() {
        // 270° of the unit circle, 30 samples: the ends are 1.41 apart, nine times the spacing.
        let pts: Vec<Point> = (0..30)
            .map(|k| {
                let t = k as f64 * 1.5 * PI / 29.0;
                Point::new(libm::cos(t), libm::sin(t))
            })
            .collect();
        assert_eq!(joins(&pts, &chain(30, &[])), NONE);
        // Two arcs back to back, `)(`, each end near the other's but not facing it.
        let mut parens: Vec<Point> = (0..9)
            .map(|k| {
                let t = PI * (0.75 + k as f64 * 0.5 / 8.0);
                Point::new(1.05 + libm::cos(t), libm::sin(t))
            })
            .collect();
        parens.extend(
            (0..9)
                .map(|k| Point::new(-parens[k].x, parens[k].y))
                .collect::<Vec<_>>(),
        );
        let mut pairs = chain(9, &[]);
        pairs.extend(chain(9, &[]).iter().map(|&[a, b]| [a + 9, b + 9]));
        assert_eq!(joins(&parens, &pairs), NONE);
    }

    /// A plus sign: a horizontal chain `0..7` and a vertical chain `7..14`, both through the
    /// crossing, which is point 3 of the first (the vertical chain's middle, position 10, is a
    /// copy of it: the triangulation merges the two).
    fn plus() -> Vec<Point> {
        let mut pts: Vec<Point> = (0..7).map(|i| Point::new(i as f64 - 3.0, 0.0)).collect();
        pts.extend((0..7).map(|i| Point::new(0.0, (i as f64 - 3.0) * 1.1)));
        pts
    }

    #[test]
    fn a_crossings_dropped_passage_is_restored() {
        let pts = plus();
        // The repair kept the horizontal passage and dropped both vertical arms (9-3, 3-11).
        let mut pairs = chain(7, &[]);
        pairs.extend([[7, 8], [8, 9], [11, 12], [12, 13]]);
        assert_eq!(joins(&pts, &pairs), vec![[3, 9], [3, 11]]);
    }

    #[test]
    fn a_crossings_dropped_arms_are_restored_after_a_bent_passage() {
        let pts = plus();
        // The repair kept a bend, left arm to upper arm (2-3-11), and dropped the right arm
        // (3-4) and the lower arm (9-3).
        let mut pairs = chain(3, &[]);
        pairs.extend([
            [2, 3],
            [4, 5],
            [5, 6],
            [7, 8],
            [8, 9],
            [3, 11],
            [11, 12],
            [12, 13],
        ]);
        assert_eq!(joins(&pts, &pairs), vec![[3, 4], [3, 9]]);
    }

    #[test]
    fn an_end_pointing_at_a_straight_passage_without_a_partner_stays_loose() {
        // A T whose stem stops one spacing short of the bar: nothing continues across the bar,
        // so the stem is an open end, not a crossing arm.
        let mut pts: Vec<Point> = (0..7).map(|i| Point::new(i as f64 - 3.0, 0.0)).collect();
        pts.extend((1..4).map(|i| Point::new(0.0, i as f64)));
        let mut pairs = chain(7, &[]);
        pairs.extend([[7, 8], [8, 9]]);
        assert_eq!(joins(&pts, &pairs), NONE);
    }
}
