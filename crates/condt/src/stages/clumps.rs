//! Clumps: non-curve components (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: removing whole components whose points mostly are not where a curve passes. It reads
//! positions and the graph; it may not touch the triangulation, adds no edge, and does not decide
//! when it runs ([`Params::stages`](crate::Params::stages): right after the local outlier removal,
//! before its given-back check).
//!
//! Rule (docs/condt.md, *Clumps*, with measurements and losses): a component apart from the rest
//! (rule 4's test; one that is not is a piece of a noisy band, rule 4's to judge) goes when under
//! half of its points pass ([`passes`]: smoothly and evenly, or as a pixel chain's step), or
//! exactly half and every point of it is apart (a tie shows no majority either; a piece of a
//! noisy curve is not apart at its ends), unless the clumps and the components not apart would
//! hold [`OUTLIER_SHARE`] or more of the points with edges; and not one that gap closing, a tip's
//! or hook's move or a junction join would join to a component that stays ([`unless_joined`]: a
//! stretch of a noisy curve cut off at both ends).
//! Why half: a
//! curve's ends, corners and junctions are a minority at any sampling dense enough for the
//! proximity graph; a random zig-zag passes smoothly at most one time in three.
//! Sequential; O(n) beyond the union-find, and only where there are clumps, the joins (gap
//! closing's, the tips', the hooks' and the junctions' searches at the loose ends, on rayon's
//! threads when
//! `parallel`).

use super::local_outliers::{
    components, merged_along, only_smooth_cycles, separated_at, separated_counts_until,
    smooth_and_regular, without_components, would_join, MIN_SAMPLES, OUTLIER_SHARE,
};
use super::Outcome;
use crate::adjacency::{CurveGraph, Edge};
use crate::geometry::Point;
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;

/// Removes the clumps from `edges` (each once, any order), keeping the rest in order; the outcome
/// is unchanged when there is none or when the quarter guard ([`OUTLIER_SHARE`]) holds.
pub(crate) fn remove_clumps(
    tri: &Triangulation,
    edges: &[Edge],
    graph: Option<CurveGraph>,
    parallel: bool,
) -> Outcome {
    let n = tri.num_points();
    let graph = graph.unwrap_or_else(|| CurveGraph::new(n, edges));
    // Where every point passes smoothly there is no clump: the stage's cost is skipped.
    debug_assert!(!graph.proven_smooth_cycles() || only_smooth_cycles(tri, &graph));
    if graph.proven_smooth_cycles() || only_smooth_cycles(tri, &graph) {
        return Outcome::unchanged_with(Some(graph));
    }
    let root = components(n, edges);
    let smooth = |v| {
        let [y, z] = graph.first_two(v);
        passes(tri, v, y, z)
    };
    let apart = |v| separated_at(tri, &graph, &root, v);
    let counts =
        |size: &[u32], guard| separated_counts_until(&graph, &root, Some((size, guard)), apart);
    let joins = || would_join(tri, &graph, parallel);
    let Some(clump) = clumps_of(&graph, &root, smooth, counts, apart)
        .and_then(|clump| unless_joined(&graph, &root, clump, joins()))
    else {
        return Outcome::unchanged_with(Some(graph));
    };
    let kept = without_components(edges, &root, &clump);
    drop((root, clump));
    Outcome::changed(edges, kept, Some(graph))
}

/// Whether the rule counts the passage of a point `v` of two edges, `y` and `z`, as a curve's:
/// [`smooth_and_regular`], or a step of a pixel chain ([`grid_step_at`]).
pub(crate) fn passes(tri: &Triangulation, v: VertexId, y: VertexId, z: VertexId) -> bool {
    smooth_and_regular(tri, v, y, z) || grid_step_at(tri, v, y, z)
}

/// [`grid_step`] at the point `v` between `y` and `z` (a tile, which has the smooth test at
/// hand already, asks it alone).
pub(crate) fn grid_step_at(tri: &Triangulation, v: VertexId, y: VertexId, z: VertexId) -> bool {
    let point = |w: VertexId| tri.vertex_point(w);
    grid_step(point(v), point(y), point(z))
}

/// How many units in the last place of the largest coordinate the two lengths of a [`grid_step`]
/// may differ by, and its angle fall short of a right one: the rounding of coordinates that
/// went through a few operations (a pixel's centre, an affine map to map units).
const ROUNDING_ULPS: f64 = 64.0;

/// Whether the passage at `p` between `q` and `r` is a step of a chain along a pixel grid: two
/// edges equal in length and at a right angle or wider, up to the rounding of the coordinates
/// ([`ROUNDING_ULPS`]). Reason: a 4-connected boundary (a staircase, the edges of a mask, Canny's
/// output) turns by a right angle at nearly every sample, so no passage is smooth and a short
/// chain of it was taken for a clump (an image user's review: of the 5,180 edge pixels of
/// `skimage.feature.canny(camera(), sigma=3)`, 1,005 were left unused, 128 without the step);
/// every turn of an 8-connected chain by a
/// right angle is such a step, and its wider ones are smooth. Random points are never this even:
/// two of their distances agree to rounding with a probability of about that rounding.
fn grid_step(p: Point, q: Point, r: Point) -> bool {
    let (to_q, to_r) = (p.dist2(q), p.dist2(r));
    let dot = (q.x - p.x) * (r.x - p.x) + (q.y - p.y) * (r.y - p.y);
    let largest = [p, q, r]
        .iter()
        .map(|a| a.x.abs().max(a.y.abs()))
        .fold(0.0, f64::max);
    // Moving each point by `moved` changes a length `step` by up to `2 moved`, its square and
    // the dot product by up to about `4 step moved`.
    let moved = ROUNDING_ULPS * f64::EPSILON * largest;
    let slack = 4.0 * libm::sqrt(to_q.max(to_r)) * moved;
    (to_q - to_r).abs() <= slack && dot <= slack
}

/// The rule on `graph` with its components `root` ([`components`]), the tests at a point given:
/// `smooth(v)` for a point of two edges ([`passes`]), `apart(v)` for a point with
/// edges ([`separated_at`]) and `counts(size, guard)`, the separated points per root as
/// [`separated_counts_until`] counts them with that limit. Which roots are clumps, or `None`
/// when none goes (no clump, or the quarter guard holds). The stage reads the triangulation for
/// the tests; a run split in tiles gathers them from the tiles ([`crate::tiled`]).
pub(crate) fn clumps_of(
    graph: &CurveGraph,
    root: &[u32],
    smooth: impl Fn(VertexId) -> bool,
    counts: impl FnOnce(&[u32], f64) -> Option<Vec<u8>>,
    apart: impl Fn(VertexId) -> bool,
) -> Option<Vec<bool>> {
    let n = root.len();
    // Per component: points with edges, and of those the ones passing smoothly.
    let (mut size, mut smooth_count) = (vec![0u32; n], vec![0u32; n]);
    for (i, &r) in root.iter().enumerate() {
        let v = VertexId::new(i as u32);
        let degree = graph.degree(v);
        size[r as usize] += u32::from(degree > 0);
        if degree == 2 {
            smooth_count[r as usize] += u32::from(smooth(v));
        }
    }
    let with_edges: u64 = size.iter().map(|&s| u64::from(s)).sum();
    // The guard below holds once the components not apart alone reach its share: the separation
    // test, the stage's main cost, stops there (on scattered points, before it starts or soon).
    let guard = OUTLIER_SHARE * with_edges as f64;
    let separated = counts(&size, guard)?;
    // A tie (exactly half passing, such as six points with two ends and one corner) shows no
    // majority of curve passages either; it goes only when every one of its points is apart, as a
    // clump lies apart whole, while a piece of a noisy curve runs on towards the curve's other
    // samples at its ends. The separation count stops at MIN_SAMPLES, so ties are tested here,
    // in one pass over the points (the test walks a Delaunay ring only for a tie's points).
    let is_apart = |r: usize| size[r] > 0 && usize::from(separated[r]) >= MIN_SAMPLES;
    let mut tie_apart: Vec<bool> = (0..n)
        .map(|r| is_apart(r) && 2 * smooth_count[r] == size[r])
        .collect();
    for (i, &r) in root.iter().enumerate() {
        let v = VertexId::new(i as u32);
        if tie_apart[r as usize] && graph.degree(v) > 0 && !apart(v) {
            tie_apart[r as usize] = false;
        }
    }
    let is_clump = |r: usize| is_apart(r) && (2 * smooth_count[r] < size[r] || tie_apart[r]);
    let points_in = |keep: &dyn Fn(usize) -> bool| -> u64 {
        (0..n)
            .filter(|&r| keep(r))
            .map(|r| u64::from(size[r]))
            .sum()
    };
    let in_clumps = points_in(&is_clump);
    // The quarter guard counts what the local outlier removal's rule 4 left only because of
    // its own guard (components not apart) with the clumps: the two rules judge one graph.
    let not_apart = points_in(&|r| usize::from(separated[r]) < MIN_SAMPLES);
    if in_clumps == 0 || (in_clumps + not_apart) as f64 >= guard {
        return None;
    }
    // One byte per component while the output is built, not the tallies (memory: the curve
    // graph is kept to hand on).
    Some((0..n).map(is_clump).collect())
}

/// The clumps `clump` (per root of `root`, [`clumps_of`]) less those that `joins`, the edges gap
/// closing, the moves of the tips and hooks stages and the junction joins would add to `graph`,
/// join to a component
/// that stays, directly or through other clumps, between points with edges; `None` when none is
/// left.
/// Reason: a piece of a noisy curve can zig-zag and stand apart from the rest at its middle
/// samples, yet its ends run on to the curve's loose ends, and those joins need evidence on both
/// sides (rule 4's third exemption, [`merged_along`], which this reads); a clump of outliers
/// lies apart whole.
pub(crate) fn unless_joined(
    graph: &CurveGraph,
    root: &[u32],
    mut clump: Vec<bool>,
    mut joins: Vec<Edge>,
) -> Option<Vec<bool>> {
    // A point without edges (a tip's apex, a point gap closing runs through) is no piece of a
    // curve yet: a join to it shows nothing on that side.
    joins.retain(|&[a, b]| graph.degree(a) > 0 && graph.degree(b) > 0);
    let mut stays = vec![false; root.len()];
    for (i, &r) in root.iter().enumerate() {
        if graph.degree(VertexId::new(i as u32)) > 0 && !clump[r as usize] {
            stays[r as usize] = true;
        }
    }
    let (joined_root, stays) = merged_along(root.to_vec(), stays, joins);
    for (&r, &joined) in root.iter().zip(&joined_root) {
        if stays[joined as usize] {
            clump[r as usize] = false;
        }
    }
    clump.iter().any(|&c| c).then_some(clump)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::ordered;
    use crate::{triangulate, Point};

    /// A smooth circle of 40 samples and, far from it, `extra` joined as one path; returns the
    /// input positions of the edges the stage keeps.
    fn kept(extra: &[(f64, f64)]) -> Vec<[usize; 2]> {
        let mut pts: Vec<Point> = (0..40)
            .map(|k| {
                let t = core::f64::consts::TAU * k as f64 / 40.0;
                Point::new(10.0 * libm::cos(t), 10.0 * libm::sin(t))
            })
            .collect();
        let mut pairs: Vec<[usize; 2]> = (0..40).map(|k| [k, (k + 1) % 40]).collect();
        let first = pts.len();
        pts.extend(extra.iter().map(|&p| Point::from(p)));
        pairs.extend((first..pts.len() - 1).map(|i| [i, i + 1]));
        let tri = triangulate(&pts).unwrap();
        let edges: Vec<Edge> = pairs
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let out = remove_clumps(&tri, &edges, None, false)
            .edges
            .unwrap_or_else(|| edges.clone());
        crate::Graph::new(&tri, alloc::borrow::Cow::Borrowed(&out[..])).edges()
    }

    #[test]
    fn a_zig_zag_clump_apart_from_the_curve_goes() {
        let clump = [
            (40.0, 0.0),
            (41.0, 1.0),
            (40.2, 1.1),
            (41.3, 2.0),
            (40.1, 2.2),
            (41.0, 3.1),
        ];
        let out = kept(&clump);
        assert_eq!(out.len(), 40, "the circle stays, the clump goes: {out:?}");
        assert!(out.iter().all(|&[a, b]| a < 40 && b < 40));
    }

    #[test]
    fn a_six_point_chain_with_one_corner_apart_from_the_curve_goes() {
        // Two ends, three smooth passages and a corner of 70°: exactly half passing, all apart.
        let chain = [
            (40.0, 0.0),
            (41.0, 0.0),
            (42.0, 0.1),
            (43.0, 0.3),
            (44.0, 0.6),
            (43.4, 1.4),
        ];
        let out = kept(&chain);
        assert_eq!(out.len(), 40, "the circle stays, the chain goes: {out:?}");
    }

    /// A 4-connected pixel staircase turns by a right angle at every sample, so none of its
    /// passages is smooth; its steps are even, so it is a curve, not a clump: kept as it is
    /// given, scaled, turned by a quarter, mirrored, and turned by 30° (where its lengths and
    /// angles are equal only up to rounding). A zig-zag whose steps differ by 1 % still goes.
    #[test]
    fn a_pixel_staircase_apart_from_the_curve_stays() {
        let staircase: Vec<(f64, f64)> = (0..12)
            .map(|k| (40.0 + ((k + 1) / 2) as f64, (k / 2) as f64))
            .collect();
        let (sin, cos) = (0.5, libm::sqrt(0.75));
        type Move<'a> = &'a dyn Fn((f64, f64)) -> (f64, f64);
        let moves: [Move; 5] = [
            &|p| p,
            &|(x, y)| (x * 0.375, y * 0.375),
            &|(x, y)| (-y, x),
            &|(x, y)| (-x, y),
            &|(x, y)| (x * cos - y * sin + 1e6, x * sin + y * cos + 1e6),
        ];
        for (m, moved) in moves.iter().enumerate() {
            let chain: Vec<(f64, f64)> = staircase.iter().map(|&p| moved(p)).collect();
            let out = kept(&chain);
            assert_eq!(
                out.len(),
                51,
                "move {m}: the circle and the staircase stay: {out:?}"
            );
        }
        let uneven: Vec<(f64, f64)> = staircase
            .iter()
            .enumerate()
            .map(|(k, &(x, y))| (x + 0.01 * (k % 3) as f64, y))
            .collect();
        assert_eq!(kept(&uneven).len(), 40, "an uneven zig-zag goes");
    }

    #[test]
    fn a_small_smooth_arc_apart_from_the_curve_stays() {
        let arc: Vec<(f64, f64)> = (0..7)
            .map(|k| {
                (
                    40.0 + 3.0 * libm::cos(0.3 * k as f64),
                    3.0 * libm::sin(0.3 * k as f64),
                )
            })
            .collect();
        assert_eq!(kept(&arc).len(), 46);
    }

    /// Noise zig-zags a stretch of a circle, cut off from it at both ends: a clump by its shape,
    /// but gap closing joins it to the circle's loose ends, so it stays.
    #[test]
    fn a_zig_zag_piece_that_gap_closing_joins_to_a_curve_stays() {
        let (pts, pairs, curve_len) = crate::test_graphs::zig_zag_piece_in_a_gap();
        let tri = triangulate(&pts).unwrap();
        let edges: Vec<Edge> = pairs
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let graph = CurveGraph::new(pts.len(), &edges);
        let root = components(pts.len(), &edges);
        let smooth = |v| {
            let [y, z] = graph.first_two(v);
            passes(&tri, v, y, z)
        };
        let apart = |v| separated_at(&tri, &graph, &root, v);
        let counts =
            |size: &[u32], guard| separated_counts_until(&graph, &root, Some((size, guard)), apart);
        let clump = clumps_of(&graph, &root, smooth, counts, apart).expect("a clump by its shape");
        let piece = root[tri.vertex(curve_len).index()] as usize;
        assert!(clump[piece]);
        let outcome = remove_clumps(&tri, &edges, None, false);
        assert!(
            outcome.edges.is_none(),
            "the piece stays: gap closing joins it"
        );
        let closed = crate::Graph::new(&tri, alloc::borrow::Cow::Borrowed(&edges[..]));
        assert_eq!(closed.close_gaps().num_edges(), edges.len() + 2);
    }

    /// A join to a point without edges shows no curve on that side: a clump joined to the rest
    /// only through such a point still goes.
    #[test]
    fn a_join_through_a_point_without_edges_keeps_no_clump() {
        // Points 0-1-2 a curve that stays, 3-4 a clump, 5 without edges.
        let v = |i: u32| VertexId::new(i);
        let edges = [[v(0), v(1)], [v(1), v(2)], [v(3), v(4)]];
        let graph = CurveGraph::new(6, &edges);
        let root = components(6, &edges);
        let clump: Vec<bool> = (0..6).map(|r| r == 3).collect();
        let through_point = vec![[v(2), v(5)], [v(4), v(5)]];
        assert_eq!(
            unless_joined(&graph, &root, clump.clone(), through_point),
            Some(clump.clone())
        );
        assert_eq!(
            unless_joined(&graph, &root, clump, vec![[v(2), v(4)]]),
            None
        );
    }

    #[test]
    fn nothing_goes_when_clumps_are_a_quarter_of_the_points() {
        // Fourteen zig-zag points beside the 40 of the circle: more than a quarter of 54.
        let clump: Vec<(f64, f64)> = (0..14)
            .map(|k| (40.0 + (k % 2) as f64, 0.7 * k as f64))
            .collect();
        assert_eq!(kept(&clump).len(), 53);
    }
}
