//! Stage 2, non-manifold repair (Algorithm 2).
//!
//! Owns: what happens at vertices of the proximity graph with three or more edges. It reads point
//! positions and the graph; it may not touch the triangulation.
//!
//! At a vertex `v` of degree >= 3 the paper keeps its shortest edge `e1` and the edge with the best
//! score `(θ/π)(Lmin/Le)` among those making an angle `θ > 2π/3` with it; edges between two
//! vertices of degree <= 2 are kept as they are. Readings of what the paper leaves open, with the
//! evidence, are in `docs/condt.md` (notes 2 to 4).
//!
//! # Needs before score ([`Repair::Needs`])
//!
//! Algorithm 2 looks only at the vertex it repairs, and fails in two places:
//!
//! - *Sharp corners.* At a tip of angle `α < 60°` sampled `h` apart, the two samples beside the
//!   apex are `2h sin(α/2) < h` apart: that chord is the shortest edge `e1` of both. A partner
//!   must lie more than 120° from `e1`, but the sides of the tip lie at `90° + α/2 < 120°` from
//!   it, so each of the two samples keeps the chord alone, and the tip (the apex and both of its
//!   edges) vanishes together with the next edge down each side. A five-pointed star (36° tips)
//!   loses every tip.
//! - *Self-intersections.* A curve crossing itself at a sample gives that sample four edges in
//!   the proximity graph; Algorithm 2 keeps two.
//!
//! `Needs` decides at every vertex `v` of degree >= 3, in this order:
//!
//! 1. **Crossing.** If two disjoint pairs of edges at `v` are each nearly straight (angle at `v`
//!    above 150°), `v` keeps those four edges. Of several such pairings it takes the one whose
//!    less straight pair is straightest, so that both passages are as straight as they can be
//!    together ([`Repair::CrossingAware`] takes the straightest pair first and pairs it with
//!    what is left). Why 150°: consecutive chords of a curve sampled at spacing
//!    `ε · lfs` turn by at most about `ε` radians, so a passage through a sample of an
//!    `ε`-sampling with `ε <= 1/2` is straighter than 180° − 28.6°.
//! 2. **Needs.** A neighbour `w` of degree <= 2 needs the edge `vw`: dropping it leaves `w` an
//!    end or alone, and nothing restores it later. The need counts only if `vw` is at most 1.3
//!    times as long as `v`'s second shortest edge: a curve's own edges at a sample are among its
//!    shortest (Algorithm 1 keeps each point's two shortest), and at a sharp tip the chord takes
//!    the first place, the sides the second; the slack covers sides cut into pieces of different
//!    lengths, and a needy neighbour farther than that is the end of another curve or an outlier.
//!    `v` keeps the best pair of its edges holding at least one needed edge, among pairs that
//!    are straight enough for Algorithm 2 (`θ > 2π/3`) or whose two edges are both needed,
//!    ranked by: straight enough, then the number of needed edges, then `θ` over the length of
//!    the path through `v` (the two lengths added: Algorithm 2's preference for short, straight
//!    edges, for a pair), then the smaller ids.
//!    A straight pair comes first so that a needy stray point beside a curve does not bend it; a
//!    bent pair of two needed edges is a corner whose apex has a third edge.
//! 3. **Score.** When no pair holds a needed edge, Algorithm 2's own choice: the shortest edge
//!    and its best partner beyond 120°.
//! 4. **Consent.** An edge between two vertices of degree >= 3 survives only if both keep it
//!    (as [`Repair::Mutual`]); an edge to a vertex of degree <= 2 survives if `v` keeps it.
//!
//! At a sharp tip the chord joins two vertices of degree 3 whose other two neighbours need
//! them along a straight side, so neither keeps the chord and the tip stays. At a sampled
//! crossing step 1 keeps the four edges, and consent removes the chords between the two curves'
//! samples next to it, which neither end keeps. Each vertex decides from the graph's degrees and
//! the positions alone, with ties broken by vertex id, so the result does not depend on the
//! order of the edges or on threads; the pairs a crossing compares live in one buffer reused
//! from vertex to vertex.
//!
//! It keeps sharp corners and self-intersections that `Paper` loses; the measurements on the
//! evaluation suite are in `docs/perf-log.md`.

use crate::adjacency::{degrees, ordered, BranchAdjacency, Edge};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;
use core::f64::consts::PI;

mod needs;

/// How vertices of degree three or more in the proximity graph are treated.
///
/// The default is the default pipeline's choice, [`Repair::Needs`]; the paper's preset uses
/// [`Repair::Paper`].
///
/// ```
/// use condt::{Params, Repair};
/// assert_eq!(Repair::default(), Repair::Needs);
/// assert_eq!(Params::default().repair, Repair::default());
/// assert_eq!(Params::paper().repair, Repair::Paper);
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Repair {
    /// No repair: keep every proximity edge (needed for self-intersecting curves, whose crossings
    /// have degree four).
    Off,
    /// Algorithm 2 as printed: every non-manifold vertex selects two edges and the selections are
    /// united, so an edge selected by one end survives even if the other end did not select it.
    Paper,
    /// Algorithm 2 with mutual consent: an edge between two non-manifold vertices survives only
    /// if both select it, so no vertex keeps more than two edges.
    Mutual,
    /// Keeps up to two nearly straight pairs of edges through a vertex (a crossing), and falls
    /// back to [`Repair::Paper`]'s choice elsewhere.
    CrossingAware,
    /// Needs before score: a non-manifold vertex keeps a crossing (two disjoint nearly straight
    /// pairs of edges) whole; otherwise the best pair of edges that a neighbour of degree <= 2
    /// needs (one it would be left dangling without, not much longer than the vertex's second
    /// shortest edge), straight pairs first; otherwise Algorithm 2's choice. An edge between two
    /// non-manifold vertices survives only if both keep it. Keeps the tips of sharp corners and
    /// sampled crossings, which [`Repair::Paper`] cuts; the module documentation gives the rule,
    /// the reason for each constant and the measurements.
    #[default]
    Needs,
}

/// Smallest angle at `v` for an edge to pair with the shortest one (Algorithm 2's `θ > 2π/3`).
const PAIR_ANGLE: f64 = 2.0 * PI / 3.0;
/// Smallest angle for two edges through a vertex to count as one nearly straight passage.
const STRAIGHT_ANGLE: f64 = 5.0 * PI / 6.0;

/// The angle at `v` between the edges to `a` and to `b`, in `[0, π]`.
fn angle_at(tri: &Triangulation, v: VertexId, a: VertexId, b: VertexId) -> f64 {
    let (p, q, r) = (
        tri.vertex_point(v),
        tri.vertex_point(a),
        tri.vertex_point(b),
    );
    let (ux, uy, wx, wy) = (q.x - p.x, q.y - p.y, r.x - p.x, r.y - p.y);
    libm::atan2((ux * wy - uy * wx).abs(), ux * wx + uy * wy)
}

/// Algorithm 2, lines 10–11: the shortest edge and the best-scoring partner (if any qualifies).
/// `around` is the vertex's adjacency (neighbour, edge position); no allocation.
fn paper_choice(tri: &Triangulation, v: VertexId, around: &[(VertexId, u32)]) -> [VertexId; 2] {
    let p = tri.vertex_point(v);
    let length2 = |w: VertexId| p.dist2(tri.vertex_point(w));
    let neighbours = || around.iter().map(|&(w, _)| w);
    let shortest = neighbours()
        .min_by(|&a, &b| length2(a).total_cmp(&length2(b)).then(a.cmp(&b)))
        .expect("degree >= 3");
    let qualified = || {
        neighbours()
            .filter(move |&w| w != shortest)
            .map(move |w| (w, angle_at(tri, v, shortest, w)))
            .filter(|&(_, theta)| theta > PAIR_ANGLE)
    };
    // Lmin/Le: Lmin is the same for every candidate, so it scales all scores alike; it is kept to
    // match the paper's formula.
    let l_min = qualified()
        .map(|(w, _)| libm::sqrt(length2(w)))
        .fold(f64::INFINITY, f64::min);
    let best = qualified()
        .map(|(w, theta)| (w, theta / PI * (l_min / libm::sqrt(length2(w)))))
        .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
    [shortest, best.map_or(VertexId::INFINITE, |(w, _)| w)]
}

/// Up to two disjoint nearly straight pairs through `v`; `None` when there are not two.
fn crossing_choice(
    tri: &Triangulation,
    v: VertexId,
    around: &[(VertexId, u32)],
) -> Option<[VertexId; 4]> {
    let mut pairs: Vec<(f64, VertexId, VertexId)> = Vec::new();
    for (i, &(a, _)) in around.iter().enumerate() {
        for &(b, _) in &around[i + 1..] {
            let theta = angle_at(tri, v, a, b);
            if theta > STRAIGHT_ANGLE {
                pairs.push((theta, a, b));
            }
        }
    }
    pairs.sort_by(|x, y| y.0.total_cmp(&x.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let &(_, a, b) = pairs.first()?;
    let &(_, c, d) = pairs
        .iter()
        .find(|&&(_, c, d)| c != a && c != b && d != a && d != b)?;
    Some([a, b, c, d])
}

/// Applies `repair` to the proximity graph `edges` (each edge once, any order): `None` when there
/// is nothing to repair (off, or no vertex of degree three or more), so the input stands.
/// Otherwise the result lists each edge once: first the edges between manifold vertices in their
/// input order, then the selections of the non-manifold vertices in increasing vertex id.
pub(crate) fn repair(tri: &Triangulation, edges: &[Edge], repair: Repair) -> Option<Vec<Edge>> {
    if repair == Repair::Off {
        return None;
    }
    let vertex_count = tri.num_points();
    let degree = degrees(vertex_count, edges);
    let manifold = |v: VertexId| degree[v.index()] <= 2;
    if degree.iter().all(|&d| d <= 2) {
        return None;
    }
    // Only the non-manifold vertices' lists are read.
    let graph = BranchAdjacency::new(&degree, edges);
    // Scratch space of `Repair::Needs`, reused by every vertex.
    let mut pairs = needs::Pairs::new();
    // Lines 6–12: every non-manifold vertex selects its edges (up to four for a crossing).
    // One per non-manifold vertex, counted first (memory: no growth by doubling).
    let mut selections: Vec<(VertexId, [VertexId; 4])> = Vec::with_capacity(graph.branch_count());
    for i in 0..vertex_count {
        let v = VertexId::new(i as u32);
        if manifold(v) {
            continue;
        }
        let around = graph.incident(v);
        if repair == Repair::Needs {
            let chosen = needs::choice(tri, v, around, &degree, &mut pairs);
            selections.push((v, chosen));
            continue;
        }
        let crossing = if repair == Repair::CrossingAware {
            crossing_choice(tri, v, around)
        } else {
            None
        };
        let chosen = crossing.unwrap_or_else(|| {
            let [a, b] = paper_choice(tri, v, around);
            [a, b, VertexId::INFINITE, VertexId::INFINITE]
        });
        selections.push((v, chosen));
    }
    drop(graph);
    // `selections` is in increasing vertex id, so a binary search finds a vertex's choice.
    let selected_by = |w: VertexId, v: VertexId| {
        selections
            .binary_search_by_key(&w, |&(u, _)| u)
            .is_ok_and(|k| selections[k].1.contains(&v))
    };
    // Algorithm 2, lines 3–5: edges between manifold vertices stay.
    // Every edge of the output is an input edge, listed once: the input's length is room
    // enough (memory: no growth by doubling).
    let mut kept: Vec<Edge> = Vec::with_capacity(edges.len());
    kept.extend(
        edges
            .iter()
            .copied()
            .filter(|&[a, b]| manifold(a) && manifold(b)),
    );
    for &(v, chosen) in &selections {
        for &w in chosen.iter().filter(|w| !w.is_infinite()) {
            let keep = if manifold(w) {
                true
            } else if repair == Repair::Mutual || repair == Repair::Needs {
                // Both ends are non-manifold: both must select it; the smaller end lists it.
                v < w && selected_by(w, v)
            } else {
                // A union: listed by the smaller end when both selected it.
                !(w < v && selected_by(w, v))
            };
            if keep {
                kept.push(ordered(v, w));
            }
        }
    }
    kept.shrink_to_fit();
    Some(kept)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{triangulate, Point};

    /// Edges given as input positions, in the triangulation's vertex ids, sorted.
    fn edges(tri: &Triangulation, pairs: &[(usize, usize)]) -> Vec<Edge> {
        let mut listed: Vec<Edge> = pairs
            .iter()
            .map(|&(a, b)| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        listed.sort_unstable();
        listed
    }

    /// `repair`, sorted for comparison.
    fn repair(tri: &Triangulation, edges: &[Edge], mode: Repair) -> Vec<Edge> {
        let mut out = super::repair(tri, edges, mode).unwrap_or_else(|| edges.to_vec());
        out.sort_unstable();
        out
    }

    #[test]
    fn a_vertex_keeps_its_shortest_edge_and_the_best_partner_beyond_120_degrees() {
        // Centre 0 with neighbours 1 (shortest, east), 2 (west, 180 degrees) and 3 (north, 90).
        let pts = [(0.0, 0.0), (1.0, 0.0), (-2.0, 0.0), (0.0, 1.5)].map(Point::from);
        let tri = triangulate(&pts).unwrap();
        let star = edges(&tri, &[(0, 1), (0, 2), (0, 3)]);
        assert_eq!(
            repair(&tri, &star, Repair::Paper),
            edges(&tri, &[(0, 1), (0, 2)])
        );
    }

    #[test]
    fn no_partner_beyond_120_degrees_keeps_only_the_shortest_edge() {
        let pts = [(0.0, 0.0), (1.0, 0.0), (0.0, 2.0), (-0.5, 1.5)].map(Point::from);
        let tri = triangulate(&pts).unwrap();
        let star = edges(&tri, &[(0, 1), (0, 2), (0, 3)]);
        assert_eq!(repair(&tri, &star, Repair::Paper), edges(&tri, &[(0, 1)]));
    }

    /// Points 0 and 1 are both non-manifold; 0 selects the edge 0-1 (its shortest), 1 does not
    /// (its shortest points north, its partner south, and 0 lies at 90 degrees).
    fn one_sided_selection() -> (Triangulation, Vec<Edge>) {
        let pts = [
            (0.0, 0.0),
            (1.0, 0.0),
            (-1.5, 0.0),
            (0.0, -2.0),
            (1.0, 0.8),
            (1.0, -1.5),
        ]
        .map(Point::from);
        let tri = triangulate(&pts).unwrap();
        let all = edges(&tri, &[(0, 1), (0, 2), (0, 3), (1, 4), (1, 5)]);
        (tri, all)
    }

    #[test]
    fn paper_reading_unites_selections_so_one_end_can_keep_an_edge() {
        let (tri, all) = one_sided_selection();
        let expected = edges(&tri, &[(0, 1), (0, 2), (1, 4), (1, 5)]);
        assert_eq!(repair(&tri, &all, Repair::Paper), expected);
    }

    #[test]
    fn mutual_reading_needs_both_ends_to_select_an_edge() {
        let (tri, all) = one_sided_selection();
        let expected = edges(&tri, &[(0, 2), (1, 4), (1, 5)]);
        assert_eq!(repair(&tri, &all, Repair::Mutual), expected);
    }

    #[test]
    fn needs_reading_needs_both_ends_to_keep_an_edge_between_non_manifold_vertices() {
        // 0 keeps 0-1 (straight with 0-2, which 2 needs); 1 keeps its straight pair 4-1-5.
        let (tri, all) = one_sided_selection();
        let expected = edges(&tri, &[(0, 2), (1, 4), (1, 5)]);
        assert_eq!(repair(&tri, &all, Repair::Needs), expected);
    }

    #[test]
    fn crossing_aware_keeps_two_straight_pairs() {
        // A plus sign: two straight passages through the centre.
        let pts = [(0.0, 0.0), (1.0, 0.0), (-1.1, 0.0), (0.0, 1.2), (0.0, -1.3)].map(Point::from);
        let tri = triangulate(&pts).unwrap();
        let plus = edges(&tri, &[(0, 1), (0, 2), (0, 3), (0, 4)]);
        assert_eq!(repair(&tri, &plus, Repair::CrossingAware), plus);
        assert_eq!(repair(&tri, &plus, Repair::Paper).len(), 2);
    }
}
