//! [`Repair::Needs`](super::Repair::Needs). Rule and reasons: [`super`]; [`NEED_RATIO`]'s are here.
//!
//! Owns: the choice, at a vertex of three or more edges, of the pair it keeps. It reads positions
//! and the triangulation; it may not edit the graph (the repair in [`super`] applies the choice).

use super::{
    angle_above, angle_at, paper_choice, Branches, PAIR_ANGLE, PAIR_COS2, STRAIGHT_ANGLE,
    STRAIGHT_COS2,
};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;
use core::cmp::Ordering;

/// A neighbour's need counts only for an edge up to this many times the vertex's second shortest.
/// Why the second: a curve's own edges at a sample are among its shortest (Algorithm 1 keeps two),
/// but at a sharp tip the chord beside the apex comes first. The slack covers sides cut into
/// unequal pieces; a needy neighbour farther away is another curve's end or an outlier.
pub(crate) const NEED_RATIO: f64 = 1.3;

/// Pairs `(angle, a, b)` with `a < b`: [`choice`]'s scratch space, reused from vertex to vertex.
pub(super) type Pairs = Vec<(f64, VertexId, VertexId)>;

/// What the non-manifold vertex `v` keeps ([`VertexId::INFINITE`] in unused slots); `around` is
/// its adjacency, `branches` the graph's vertices of degree three or more.
pub(super) fn choice(
    tri: &Triangulation,
    v: VertexId,
    around: &[VertexId],
    branches: &Branches,
    pairs: &mut Pairs,
) -> [VertexId; 4] {
    if let Some(crossing) = crossing(tri, v, around, branches, pairs) {
        return crossing;
    }
    match needed_pair(tri, v, around, branches) {
        Some([a, b]) => [a, b, VertexId::INFINITE, VertexId::INFINITE],
        None => paper_choice(tri, v, around),
    }
}

/// Step 2 of [`super`]'s documentation: the best pair holding a needed edge, or `None`.
fn needed_pair(
    tri: &Triangulation,
    v: VertexId,
    around: &[VertexId],
    branches: &Branches,
) -> Option<[VertexId; 2]> {
    let p = tri.vertex_point(v);
    let length2 = |w: VertexId| p.dist2(tri.vertex_point(w));
    // The two shortest squared lengths at `v` (ties count twice).
    let (mut first, mut second) = (f64::INFINITY, f64::INFINITY);
    for &w in around {
        let l = length2(w);
        if l < first {
            second = first;
            first = l;
        } else if l < second {
            second = l;
        }
    }
    let bound = NEED_RATIO * NEED_RATIO * second;
    let needed = |w: VertexId| !branches.is_branch(w) && length2(w) <= bound;
    let mut best: Option<((bool, u32, f64), [VertexId; 2])> = None;
    for (i, &a) in around.iter().enumerate() {
        for &b in &around[i + 1..] {
            if passes_an_ear_by_its_far_side(tri, v, a, b, around, branches, needed) {
                continue;
            }
            let count = u32::from(needed(a)) + u32::from(needed(b));
            // A pair with one needed edge must be straight: its angle only if so.
            let theta = match count {
                0 => continue,
                1 => match angle_above(tri, v, a, b, PAIR_ANGLE, PAIR_COS2) {
                    Some(theta) => theta,
                    None => continue,
                },
                _ => angle_at(tri, v, a, b),
            };
            let straight = theta > PAIR_ANGLE;
            let key = (
                straight,
                count,
                theta / (libm::sqrt(length2(a)) + libm::sqrt(length2(b))),
            );
            let pair = [a.min(b), a.max(b)];
            let better = best.is_none_or(|(k, q)| {
                (key.0, key.1)
                    .cmp(&(k.0, k.1))
                    .then(key.2.total_cmp(&k.2))
                    .then(q.cmp(&pair))
                    == Ordering::Greater
            });
            if better {
                best = Some((key, pair));
            }
        }
    }
    best.map(|(_, pair)| pair)
}

/// The other end of the ear `v`-`a`-`b` hanging on `v` at its neighbour `a`, if any: `a` and `b`
/// have two edges or fewer, those of `a` lead to `v` and `b`, so those of `b` to `a` and `v`.
fn ear(v: VertexId, a: VertexId, around: &[VertexId], branches: &Branches) -> Option<VertexId> {
    if branches.is_branch(a) {
        return None;
    }
    let mut onward = branches.onward(a, v);
    let b = onward.next()?;
    (onward.next().is_none() && !branches.is_branch(b) && around.contains(&b)).then_some(b)
}

/// Whether the pair `a`, `b` of `v` reaches an ear by the edge `v` does not need and leaves out
/// the one it needs, through `v` at no more than [`STRAIGHT_ANGLE`] (step 2 of [`super`]). An
/// ear `v`-`u`-`w` is a triangle whose `u` and `w` have no other edges: whichever edge to `v`
/// stays, both stay on the curve, as a path ending at `u` or at `w`, so their needs are one, and
/// the needed (shorter) edge meets it with the shorter path (Algorithm 1's preference); `u`'s
/// edge, beyond [`NEED_RATIO`], counts for nothing. Such a pair wins only by being straight
/// enough (a needy stray point beside a curve must not bend it), but the ear's `w` is no stray,
/// and a pair that turns by over 30° is no passage of a sampled curve through `v` (step 1's
/// bound): a 4-connected staircase's end, `u` its last pixel and `w` the corner, turns by 45°.
/// Where both edges are needed nothing is decided here: an apex and the sample beside it look
/// alike once the edge from that sample on is missing (gap closing restores it), and a straight
/// passage is left to the ranking (a noisy wiggle whose edge onward is missing).
fn passes_an_ear_by_its_far_side(
    tri: &Triangulation,
    v: VertexId,
    a: VertexId,
    b: VertexId,
    around: &[VertexId],
    branches: &Branches,
    needed: impl Fn(VertexId) -> bool,
) -> bool {
    [(a, b), (b, a)].into_iter().any(|(u, other)| {
        !needed(u) && ear(v, u, around, branches).is_some_and(|w| w != other && needed(w))
    }) && angle_above(tri, v, a, b, STRAIGHT_ANGLE, STRAIGHT_COS2).is_none()
}

/// Whether the neighbour `w` of `v` turns back: it has edges besides `vw`, and every one of them
/// leads to another neighbour of `v`.
fn turns_back(v: VertexId, w: VertexId, around: &[VertexId], branches: &Branches) -> bool {
    let mut onward = branches.onward(w, v).peekable();
    onward.peek().is_some() && onward.all(|u| around.contains(&u))
}

/// Whether the neighbour `w` of `v` closes a loop around `v` (step 1 of [`super`]): it
/// [`turns_back`], and so does every neighbour of `v` it leads to, so that beyond `v` its curve
/// meets nothing but `v`'s neighbours.
fn closes_a_loop(v: VertexId, w: VertexId, around: &[VertexId], branches: &Branches) -> bool {
    turns_back(v, w, around, branches)
        && branches
            .onward(w, v)
            .all(|u| turns_back(v, u, around, branches))
}

/// Step 1 ([`super`]): the pairing of two disjoint pairs above [`STRAIGHT_ANGLE`], not both ends of
/// either [`closes_a_loop`], whose less straight pair is straightest (ties: the straighter other
/// pair, then smaller ids), or `None`.
fn crossing(
    tri: &Triangulation,
    v: VertexId,
    around: &[VertexId],
    branches: &Branches,
    pairs: &mut Pairs,
) -> Option<[VertexId; 4]> {
    if around.len() < 4 {
        return None;
    }
    pairs.clear();
    // A passage whose curve goes on beyond `v` on neither side is no curve through `v`. Asked only
    // of straight pairs (speed: the rings of most vertices have none).
    let goes_on = |w: VertexId| !closes_a_loop(v, w, around, branches);
    for (i, &a) in around.iter().enumerate() {
        for &b in &around[i + 1..] {
            if let Some(theta) = angle_above(tri, v, a, b, STRAIGHT_ANGLE, STRAIGHT_COS2) {
                if goes_on(a) || goes_on(b) {
                    pairs.push((theta, a.min(b), a.max(b)));
                }
            }
        }
    }
    pairs.sort_unstable_by(|x, y| y.0.total_cmp(&x.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let disjoint = |x: &(f64, VertexId, VertexId), y: &(f64, VertexId, VertexId)| {
        x.1 != y.1 && x.1 != y.2 && x.2 != y.1 && x.2 != y.2
    };
    // In descending order, the first pair with a disjoint straighter pair before it is the
    // weaker pair of the best pairing; its partner is the straightest such.
    (1..pairs.len()).find_map(|q| {
        pairs[..q]
            .iter()
            .find(|p| disjoint(p, &pairs[q]))
            .map(|p| [p.1, p.2, pairs[q].1, pairs[q].2])
    })
}

#[cfg(test)]
mod tests {
    use crate::sample::{sample, Sample, Sampling, Shape};
    use crate::{triangulate, Error, Point, Repair, Uniformity};
    use alloc::vec::Vec;
    use core::f64::consts::PI;

    /// The proximity graph of `points` after `repair`, in input positions, sorted.
    fn repaired(points: &[Point], repair: Repair) -> Result<Vec<[usize; 2]>, Error> {
        let tri = triangulate(points)?;
        let proximity = tri.proximity_graph(Uniformity::default())?;
        Ok(proximity.repair(repair).edges())
    }

    /// Degree of every point in `edges`.
    fn degrees(count: usize, edges: &[[usize; 2]]) -> Vec<usize> {
        let mut degree = alloc::vec![0; count];
        for &[a, b] in edges {
            degree[a] += 1;
            degree[b] += 1;
        }
        degree
    }

    /// A five-pointed star with 36-degree tips (corners 0, 2, 4, 6, 8 are the tips).
    fn star(epsilon: f64) -> (Sample, Vec<usize>) {
        let inner = libm::cos(0.4 * PI) / libm::cos(0.2 * PI);
        let corners: Vec<Point> = (0..10)
            .map(|k| {
                let angle = 0.5 * PI + k as f64 * PI / 5.0;
                let r = if k % 2 == 0 { 1.0 } else { inner };
                Point::new(r * libm::cos(angle), r * libm::sin(angle))
            })
            .collect();
        let s = sample(&[Shape::Polygon(corners.clone())], &Sampling::new(epsilon)).unwrap();
        let tips = (0..5)
            .map(|k| {
                let tip = corners[2 * k];
                s.points.iter().position(|&p| p == tip).unwrap()
            })
            .collect();
        (s, tips)
    }

    #[test]
    fn a_star_keeps_its_tips() -> Result<(), Error> {
        let (s, tips) = star(0.5);
        let paper = repaired(&s.points, Repair::Paper)?;
        let paper_degree = degrees(s.points.len(), &paper);
        // Algorithm 2: beside each tip the chord between the two nearest samples is their
        // shortest edge, no side lies beyond 120 degrees from it, and the tip is cut off.
        assert!(
            tips.iter().all(|&t| paper_degree[t] < 2),
            "Paper keeps a tip: {paper_degree:?}"
        );
        assert_eq!(repaired(&s.points, Repair::Needs)?, s.edges);
        Ok(())
    }

    #[test]
    fn a_vertex_keeps_the_straight_passage_its_neighbours_need() -> Result<(), Error> {
        // Centre 0 with three neighbours of degree one: 3 is the nearest but lies 110 degrees
        // from 2, the others' straight passage 1-0-2 is what they need.
        let c = 0.9 * libm::cos(70f64.to_radians());
        let s = 0.9 * libm::sin(70f64.to_radians());
        let pts = [(0.0, 0.0), (1.0, 0.0), (-1.0, 0.0), (c, s)].map(Point::from);
        let tri = triangulate(&pts)?;
        let star = tri.graph_from_edges([[0, 1], [0, 2], [0, 3]]);
        // Algorithm 2 keeps the shortest edge 0-3 and finds no partner beyond 120 degrees.
        assert_eq!(star.repair(Repair::Paper).edges(), [[0, 3]]);
        assert_eq!(star.repair(Repair::Needs).edges(), [[0, 1], [0, 2]]);
        Ok(())
    }

    #[test]
    fn a_far_neighbour_of_degree_one_needs_nothing() -> Result<(), Error> {
        // A curve 3-1-0-2-5 whose inner points 0, 1, 2 all have a third edge; 6 hangs off 0,
        // 160 degrees from 1 but 2.5 times as far as 0's curve edges.
        let far = 2.5 * libm::cos(160f64.to_radians());
        let far_y = 2.5 * libm::sin(160f64.to_radians());
        let pts = [
            (0.0, 0.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (2.0, 0.2),
            (1.0, 1.0),
            (-2.0, -0.2),
            (far, far_y),
            (-1.0, -1.0),
        ]
        .map(Point::from);
        let tri = triangulate(&pts)?;
        let graph = tri.graph_from_edges([[0, 1], [0, 2], [0, 6], [1, 3], [1, 4], [2, 5], [2, 7]]);
        let kept = graph.repair(Repair::Needs).edges();
        assert_eq!(kept, [[0, 1], [0, 2], [1, 3], [2, 5]]);
        Ok(())
    }

    #[test]
    fn the_choice_does_not_depend_on_the_input_order() -> Result<(), Error> {
        let (s, _) = star(0.5);
        let reversed: Vec<Point> = s.points.iter().rev().copied().collect();
        let last = s.points.len() - 1;
        let mut back: Vec<[usize; 2]> = repaired(&reversed, Repair::Needs)?
            .into_iter()
            .map(|[a, b]| [(last - b).min(last - a), (last - b).max(last - a)])
            .collect();
        back.sort_unstable();
        assert_eq!(back, repaired(&s.points, Repair::Needs)?);
        Ok(())
    }

    #[test]
    fn a_plus_sign_keeps_its_four_arms() -> Result<(), Error> {
        let pts = [(0.0, 0.0), (1.0, 0.0), (-1.1, 0.0), (0.0, 1.2), (0.0, -1.3)].map(Point::from);
        let tri = triangulate(&pts)?;
        let plus = tri.graph_from_edges([[0, 1], [0, 2], [0, 3], [0, 4]]);
        assert_eq!(plus.repair(Repair::Needs).edges(), plus.edges());
        assert_eq!(plus.repair(Repair::Paper).num_edges(), 2);
        Ok(())
    }

    #[test]
    fn a_staircase_whose_arms_turn_back_is_no_crossing() -> Result<(), Error> {
        // 0 and 4 offer their second shortest edges (2.24 long, within u = 2.75 of 1 and 1.41) to
        // 2, which gets four: 1-2-4 (162 degrees) and 0-2-3 (153) pass the crossing's angles. But
        // each of the four turns back: its one other edge leads to another of 2's neighbours
        // (0-1, 3-4), so neither passage goes on beyond 2, and keeping all four would close two
        // loops of three samples. (With a sixth point 5 2, 4 keeps 4-5 instead and 2 has three.)
        let pts = [(0.0, 0.0), (1.0, 0.0), (2.0, 1.0), (3.0, 1.0), (4.0, 2.0)].map(Point::from);
        let tri = triangulate(&pts)?;
        let proximity = tri.proximity_graph(Uniformity::default())?;
        let path = [[0, 1], [1, 2], [2, 3], [3, 4]];
        assert_eq!(
            proximity.edges(),
            [[0, 1], [0, 2], [1, 2], [2, 3], [2, 4], [3, 4]]
        );
        assert_eq!(proximity.repair(Repair::Needs).edges(), path);
        let r = crate::reconstruct(&pts, &crate::Params::default())?;
        assert!(r.edges().eq(path));
        assert_eq!(r.curves().len(), 1);
        Ok(())
    }

    #[test]
    fn an_ear_at_a_staircase_end_keeps_its_shorter_edge() -> Result<(), Error> {
        // A 4-connected staircase: each end hangs on the first corner as an ear, 0-1-2 and
        // 4-5-6, whose tips 0 and 6 offer their second edge (1.41, within u = 2.75 of 1) to 2
        // and 4. At 2, 0-2 is beyond 1.3 times 2's second shortest edge (not needed) and 1-2
        // is needed; the pair 0-2-3 (135 degrees, straight enough) used to beat the corner
        // 1-2-3, leaving 1 an end (1-0-2-3). 0 and 1 stay on either way, 1-2 gives the shorter
        // path, and 0-2-3 turns by 45 degrees, more than a sampled curve's passage.
        let pts = [(0, 0), (1, 0), (1, 1), (2, 1), (2, 2), (3, 2), (3, 3)]
            .map(|(x, y)| Point::new(f64::from(x), f64::from(y)));
        let tri = triangulate(&pts)?;
        let proximity = tri.proximity_graph(Uniformity::default())?;
        assert_eq!(
            proximity.edges(),
            [
                [0, 1],
                [0, 2],
                [1, 2],
                [2, 3],
                [3, 4],
                [4, 5],
                [4, 6],
                [5, 6]
            ]
        );
        let path = [[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 6]];
        assert_eq!(proximity.repair(Repair::Needs).edges(), path);
        let r = crate::reconstruct(&pts, &crate::Params::default())?;
        assert!(r.edges().eq(path));
        Ok(())
    }

    #[test]
    fn a_narrow_crossing_whose_arms_go_on_keeps_them_past_its_chords() -> Result<(), Error> {
        // Two lines crossing at 0 at 40 degrees, sampled 1 apart: the arms on one side are 0.68
        // apart and joined by a chord (1-3, 2-4), but each arm runs on along its line.
        let at = |line: f64, t: f64| {
            let angle = line * 40f64.to_radians();
            (t * libm::cos(angle), t * libm::sin(angle))
        };
        let pts = [
            (0.0, 0.0),
            at(0.0, 1.0),
            at(0.0, -1.0),
            at(1.0, 1.0),
            at(1.0, -1.0),
            at(0.0, 2.0),
            at(0.0, -2.0),
            at(1.0, 2.0),
            at(1.0, -2.0),
        ]
        .map(Point::from);
        let tri = triangulate(&pts)?;
        let lines = [
            [0, 1],
            [0, 2],
            [0, 3],
            [0, 4],
            [1, 5],
            [2, 6],
            [3, 7],
            [4, 8],
        ];
        let chords = [[1, 3], [2, 4]];
        let graph = tri.graph_from_edges(lines.iter().chain(&chords).copied());
        assert_eq!(graph.repair(Repair::Needs).edges(), lines);
        // Without the lines' next samples, every arm turns back into a chord: each passage
        // closes two loops of three samples around 0, and neither is a curve through it.
        let short = tri.graph_from_edges([[0, 1], [0, 2], [0, 3], [0, 4], [1, 3], [2, 4]]);
        assert_eq!(short.repair(Repair::Needs).degrees()[0], 2);
        // With them on one side only, each passage goes on beyond 0 there: still a crossing (the
        // rule asks each curve through 0 to go on, not each arm), and the chord there goes.
        let half = [
            [0, 1],
            [0, 2],
            [0, 3],
            [0, 4],
            [1, 3],
            [2, 4],
            [2, 6],
            [4, 8],
        ];
        let kept = tri.graph_from_edges(half).repair(Repair::Needs);
        assert_eq!(kept.degrees()[0], 4);
        assert!(!kept.edges().contains(&[2, 4]));
        Ok(())
    }

    #[test]
    fn a_figure_eight_keeps_its_crossing() -> Result<(), Error> {
        let eight = sample(
            &[Shape::FigureEight {
                center: Point::new(0.0, 0.0),
                size: 2.0,
            }],
            &Sampling::new(0.1),
        )
        .unwrap();
        let paper = repaired(&eight.points, Repair::Paper)?;
        assert_eq!(degrees(eight.points.len(), &paper)[0], 2);
        assert_eq!(repaired(&eight.points, Repair::Needs)?, eight.edges);
        Ok(())
    }
}
