//! Detours: two short routes between two branch points (not in the paper; on by default, off in
//! `Params::paper`).
//!
//! Owns: removing the edges of one of two short routes that join the same two points of three
//! edges each. It reads positions and the graph; it may not touch the triangulation, never adds
//! an edge, and does not decide when it runs ([`Params::stages`](crate::Params::stages): last).
//!
//! Why: where two points `p` and `q` with three edges each are joined by two routes through
//! points of two edges, a curve runs along one of them and the other is a detour beside it. One
//! or two outliers near a curve stay hung on two of its samples where the repair chose among
//! edges that a later step removed (an *ear*: an outlier joined to two neighbouring samples,
//! whose edge stays), or a chord skips a sample the curve also passes. Whatever the truth, one
//! of the two routes is wrong, and either leaves two branch points.
//!
//! A route from `p` back to `p`, a loop of at most [`MAX_INNER`] points besides it, is one too
//! (no sampled closed curve is that short, [`MIN_SAMPLES`]): a curve's end folded back, which
//! opens at its edge at `p` that the curve from `p`'s third neighbour turns into more sharply
//! ([`lasso_at`]; docs/condt.md, *A loop hung on a curve*).
//!
//! Rule (docs/condt.md, *Detours*): both routes have at most [`MAX_INNER`] points between `p`
//! and `q` (fewer than a branch the local outlier removal keeps), `p'` and `q'`, the third
//! neighbours of `p` and `q`, are two different points, and no third route of at most
//! [`MAX_INNER`] points (nor an edge) joins `p` and `q`. The route the curve runs on straighter
//! at both ends stays: the other's edges go where the passage from `p'` into it at `p` and the
//! passage from `q'` into it at `q` both turn more sharply than into the route that stays. Where
//! `p` and `q` disagree, both routes stay (either choice would be a guess). No constant but the
//! branch's: the curve's own passages decide.
//!
//! Order: the routes from `p` share no point, so once three routes to one point are set aside, at
//! most one pair of them ends at one point, and the comparison of the two is symmetric; a
//! detour's points have no other edges, and `p` and `q` none but `p p'` and `q q'`, so two
//! detours share no edge that either removes. Every choice is made on the graph as it came in:
//! the result depends neither on the order of the edges nor on `parallel`.

use super::found_at_vertices;
use super::gaps::cos_at;
use super::gaps::Ends;
use super::local_outliers::MIN_SAMPLES;
use super::Replaced;
use crate::adjacency::{path_edges, CurveGraph, Edge};
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;
use core::cmp::Ordering;

/// Most points of a route between its two ends: fewer than a branch of the local outlier removal
/// ([`MIN_SAMPLES`] points), which shows a curve of its own.
const MAX_INNER: usize = MIN_SAMPLES - 1;

/// A route from a point of three edges through points of two edges to the next point that has
/// another number of edges.
#[derive(Copy, Clone, Debug)]
struct Route {
    /// The points from the start's neighbour to the point before the end (`len` of them).
    inner: [VertexId; MAX_INNER],
    len: usize,
    /// The point the route ends at.
    end: VertexId,
}

impl Route {
    /// The route from `start` through its neighbour `next`, if it has at most [`MAX_INNER`] points
    /// between its ends.
    fn from(graph: &CurveGraph, start: VertexId, next: VertexId) -> Option<Route> {
        let mut route = Route {
            inner: [VertexId::INFINITE; MAX_INNER],
            len: 0,
            end: next,
        };
        for [_, here, onward] in graph.passages(start, next) {
            if route.len == MAX_INNER {
                return None;
            }
            route.inner[route.len] = here;
            route.len += 1;
            route.end = onward;
        }
        Some(route)
    }

    /// The route's first step from `start`, and its last step's start (the point before `end`).
    fn first_and_last(&self, start: VertexId) -> (VertexId, VertexId) {
        match self.len {
            0 => (self.end, start),
            n => (self.inner[0], self.inner[n - 1]),
        }
    }
}

/// A detour: the two ends `p < q` and the route between them whose edges go; or a loop's edge
/// ([`lasso_at`]): `p == q`, the loop's point, and a route of no inner point to the loop's edge's
/// other end.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Detour {
    pub(crate) p: VertexId,
    pub(crate) q: VertexId,
    route: Route,
}

impl Detour {
    /// The points between the detour's ends, which lose their edges.
    pub(crate) fn inner(&self) -> &[VertexId] {
        &self.route.inner[..self.route.len]
    }

    /// The edges the detour loses, from `p` to its route's end (`q`, or a loop's edge's end).
    pub(crate) fn removed(&self) -> impl Iterator<Item = Edge> + '_ {
        path_edges(self.p, self.inner(), self.route.end)
    }
}

/// The detour at the point `p` of three edges, as the smaller end of the two, if the module's rule
/// removes one.
fn detour_at(tri: &Triangulation, graph: &CurveGraph, p: VertexId) -> Option<Detour> {
    if graph.degree(p) != 3 {
        return None;
    }
    let around = [0, 1, 2].map(|k| graph.neighbor(p, k));
    let routes = around.map(|next| Route::from(graph, p, next));
    // Three routes to one point: no curve runs on beyond them, and which two were paired would
    // depend on the order of `p`'s neighbours.
    if matches!(routes, [Some(a), Some(b), Some(c)] if a.end == b.end && b.end == c.end) {
        return None;
    }
    if let Some(lasso) = lasso_at(tri, p, &around, &routes) {
        return Some(lasso);
    }
    // The two routes that end at one point `q > p` of three edges, and `p`'s third neighbour.
    let (i, j, k) = [(0, 1, 2), (0, 2, 1), (1, 2, 0)]
        .into_iter()
        .find(|&(i, j, _)| match (routes[i], routes[j]) {
            (Some(a), Some(b)) => a.end == b.end && a.end > p && graph.degree(a.end) == 3,
            _ => false,
        })?;
    let (a, b) = (routes[i]?, routes[j]?);
    let (q, p_third) = (a.end, around[k]);
    let ((a_first, a_last), (b_first, b_last)) = (a.first_and_last(p), b.first_and_last(p));
    let at_q = [0, 1, 2].map(|m| graph.neighbor(q, m));
    let mut others = at_q.into_iter().filter(|&w| w != a_last && w != b_last);
    let (Some(q_third), None) = (others.next(), others.next()) else {
        return None;
    };
    // One point beyond both ends: no curve runs on beyond them to tell which route it takes.
    if q_third == p_third {
        return None;
    }
    let point = |v: VertexId| tri.vertex_point(v);
    // `Less`: the passage into route `a` is the straighter (a smaller cosine: -1 straight on).
    let straighter = |at: VertexId, from: VertexId, into_a: VertexId, into_b: VertexId| {
        let (pa, pf) = (point(at), point(from));
        cos_at(pa, pf, point(into_a)).total_cmp(&cos_at(pa, pf, point(into_b)))
    };
    let cut = match (
        straighter(p, p_third, a_first, b_first),
        straighter(q, q_third, a_last, b_last),
    ) {
        (Ordering::Less, Ordering::Less) => b,
        (Ordering::Greater, Ordering::Greater) => a,
        _ => return None,
    };
    Some(Detour { p, q, route: cut })
}

/// A loop of at most [`MAX_INNER`] points hung on `p` (routes from `p` back to `p` through two of
/// its neighbours, `around`, with `routes` from each): the loop's edge at `p` into which the
/// curve from `p`'s third neighbour turns more sharply, as a detour of no inner point; `None`
/// where the two turn alike. Why: no sampled closed curve is that short (over six samples, as
/// [`MIN_SAMPLES`] says), so the loop is a curve's end folded back (a stroke's last pixels in an
/// L, an end sample joined to the one two before it), which runs on straighter.
fn lasso_at(
    tri: &Triangulation,
    p: VertexId,
    around: &[VertexId; 3],
    routes: &[Option<Route>; 3],
) -> Option<Detour> {
    let (i, j, k) = [(0, 1, 2), (0, 2, 1), (1, 2, 0)]
        .into_iter()
        .find(|&(i, j, _)| matches!((routes[i], routes[j]), (Some(a), Some(b)) if a.end == p && b.end == p))?;
    let point = |v: VertexId| tri.vertex_point(v);
    let (at, from) = (point(p), point(around[k]));
    let cut =
        match cos_at(at, from, point(around[i])).total_cmp(&cos_at(at, from, point(around[j]))) {
            Ordering::Less => around[j],
            Ordering::Greater => around[i],
            Ordering::Equal => return None,
        };
    let route = Route {
        inner: [VertexId::INFINITE; MAX_INNER],
        len: 0,
        end: cut,
    };
    Some(Detour { p, q: p, route })
}

/// The detours of `graph`, by increasing smaller end (on threads if `parallel`).
pub(crate) fn detours(tri: &Triangulation, graph: &CurveGraph, parallel: bool) -> Vec<Detour> {
    // A detour's ends have three edges: a graph without branches has none (one check).
    if !graph.has_branch() {
        return Vec::new();
    }
    found_at_vertices(tri.num_points(), parallel, |p| detour_at(tri, graph, p))
}

/// Cuts the detours of the graph of `ends` ([`super::with_ends`]): the module's rule.
pub(crate) fn cut_detours(ends: &Ends<'_>, parallel: bool) -> Replaced {
    let found = detours(ends.tri, &ends.graph, parallel);
    (found.iter().flat_map(Detour::removed).collect(), Vec::new())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::ordered;
    use crate::{triangulate, Point};

    /// The edges `cut_detours` leaves of `listed` (input positions) on `pts`, in input positions.
    fn kept(pts: &[Point], listed: &[[usize; 2]]) -> Vec<[usize; 2]> {
        let tri = triangulate(pts).unwrap();
        tri.graph_from_edges(listed.iter().copied())
            .cut_detours()
            .edges()
    }

    /// Points 0 to `n - 1` at unit spacing on the x axis, then `extra`.
    fn line_and(n: usize, extra: &[(f64, f64)]) -> Vec<Point> {
        let line = (0..n).map(|i| Point::new(i as f64, 0.0));
        line.chain(extra.iter().map(|&p| Point::from(p))).collect()
    }

    /// The line's edges `i, i + 1` for `i < n - 1`, then `extra`, sorted.
    fn line_edges(n: usize, extra: &[[usize; 2]]) -> Vec<[usize; 2]> {
        let mut edges: Vec<[usize; 2]> = (1..n).map(|i| [i - 1, i]).collect();
        edges.extend_from_slice(extra);
        edges.sort_unstable();
        edges
    }

    #[test]
    fn a_loop_hung_on_a_curve_loses_its_edge_off_the_straight_run() {
        // A stroke along the x axis whose last three samples fold back into a triangle (pixels
        // 5 (5, 0), 6 (6, 0), 7 (6, 1), the end sample 7 joined to 5 too): the stroke runs on
        // straight through 5 into 6, so the edge 5 7 goes and 7 is the end.
        let pts = line_and(7, &[(6.0, 1.0)]);
        let with = line_edges(7, &[[5, 7], [6, 7]]);
        assert_eq!(kept(&pts, &with), line_edges(7, &[[6, 7]]));
        // Both loop points off the line (5 (5, 0), 6 (6, 1), 7 (5, 1)): the stroke turns less
        // into 6 than into 7, so 5 7 goes.
        let pts = line_and(6, &[(6.0, 1.0), (5.0, 1.0)]);
        let with = line_edges(6, &[[5, 6], [6, 7], [5, 7]]);
        assert_eq!(kept(&pts, &with), line_edges(6, &[[5, 6], [6, 7]]));
        // A loop of six points (five besides the branch point 5) is a closed curve's: it stays.
        let ring: Vec<(f64, f64)> = (1..6)
            .map(|k| {
                let t = core::f64::consts::PI + k as f64 * core::f64::consts::TAU / 6.0;
                (8.0 + 3.0 * libm::cos(t), 3.0 * libm::sin(t))
            })
            .collect();
        let pts = line_and(6, &ring);
        let with = line_edges(6, &[[5, 6], [6, 7], [7, 8], [8, 9], [9, 10], [5, 10]]);
        assert_eq!(kept(&pts, &with), with);
    }

    /// 22 Canny edge pixels (row, column) of scikit-image's astronaut at 2048 pixels (an image
    /// user's review): the end of the stroke 0 5 6 7 ... folds back, 0 joined to 5 and to 6,
    /// and the default gave `closed 0 5 6`. The detour step opens the loop at 6 0, the edge
    /// the stroke from 7 turns into at 6 more sharply, and tells why.
    #[test]
    fn canny_pixels_whose_end_folds_back_come_back_open() {
        let pixels = [
            (62, 957),
            (63, 951),
            (63, 952),
            (63, 953),
            (63, 954),
            (63, 957),
            (63, 958),
            (63, 959),
            (63, 960),
            (63, 961),
            (63, 962),
            (63, 963),
            (64, 952),
            (64, 959),
            (66, 957),
            (66, 958),
            (66, 959),
            (67, 959),
            (67, 960),
            (67, 961),
            (67, 962),
            (68, 963),
        ];
        let pts: Vec<Point> = pixels
            .iter()
            .map(|&(r, c)| Point::new(f64::from(r), f64::from(c)))
            .collect();
        let result = crate::reconstruct(&pts, &crate::Params::default()).unwrap();
        assert!(result.curves().iter().all(|c| !c.is_closed()));
        let stories = result.provenance();
        let story = stories
            .iter()
            .find(|s| s.edge == [0, 6])
            .expect("a Delaunay edge");
        assert!(!story.kept);
        let last = story.changes.last().expect("a change");
        assert_eq!(last.stage, crate::Stage::Detours);
        assert_eq!(
            last.reason,
            crate::Reason::Detour {
                from: 6,
                to: 6,
                points: 0
            }
        );
    }

    #[test]
    fn an_outlier_hung_on_two_samples_loses_both_edges() {
        // Point 6, two spacings off the line above samples 2 and 3 and joined to both (an ear):
        // the line runs straight on through the edge between them.
        let pts = line_and(6, &[(2.4, 2.0)]);
        assert_eq!(
            kept(&pts, &line_edges(6, &[[2, 6], [3, 6]])),
            line_edges(6, &[])
        );
    }

    #[test]
    fn two_outliers_beside_a_curve_lose_their_edges() {
        // Points 8 and 9 beside samples 2 to 5, joined to 2 and 5 and to each other.
        let pts = line_and(8, &[(2.0, 2.0), (5.0, 2.2)]);
        let with = line_edges(8, &[[2, 8], [8, 9], [5, 9]]);
        assert_eq!(kept(&pts, &with), line_edges(8, &[]));
    }

    #[test]
    fn a_chord_past_a_sample_of_a_bending_curve_goes() {
        // Seven samples of an arc and the chord 2 4 past sample 3: through the sample the arc turns
        // by one sample's angle at 2 and at 4, into the chord by one and a half.
        let pts: Vec<Point> = (0..7)
            .map(|k| {
                let t = 0.15 * k as f64;
                Point::new(10.0 * libm::sin(t), 10.0 - 10.0 * libm::cos(t))
            })
            .collect();
        let arc = line_edges(7, &[]);
        assert_eq!(kept(&pts, &line_edges(7, &[[2, 4]])), arc);
        // On a straight line the chord runs straight on: a sample just off it is the detour.
        let pts = line_and(6, &[(2.5, 0.1)]);
        assert_eq!(
            kept(&pts, &line_edges(6, &[[2, 6], [3, 6]])),
            line_edges(6, &[])
        );
    }

    #[test]
    fn a_detour_whose_two_ends_disagree_stays() {
        // The line turns a right angle at sample 3: at 2 the edge 2 3 runs straight on, at 3 the
        // path through point 6 does.
        let pts = [
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (3.0, 2.0),
            (2.9, -0.9),
        ]
        .map(Point::from);
        let edges = line_edges(6, &[[2, 6], [3, 6]]);
        assert_eq!(kept(&pts, &edges), edges);
    }

    #[test]
    fn routes_of_a_branch_or_more_or_one_shared_neighbour_stay() {
        // Five points beside the line between samples 1 and 7: a branch's worth, a curve.
        let beside = [(1.5, 1.5), (2.5, 2.0), (4.0, 2.0), (5.5, 2.0), (6.5, 1.5)];
        let pts = line_and(9, &beside);
        let long = line_edges(9, &[[1, 9], [9, 10], [10, 11], [11, 12], [12, 13], [7, 13]]);
        assert_eq!(kept(&pts, &long), long);
        // Samples 2 and 3 of a line cut in two, with two ears 4 and 5 on their edge: three routes
        // between them, no curve runs on beyond.
        let pts = line_and(4, &[(2.4, 2.0), (2.5, -1.5)]);
        let twin = vec![[0, 1], [2, 3], [2, 4], [3, 4], [2, 5], [3, 5]];
        let mut sorted = twin.clone();
        sorted.sort_unstable();
        assert_eq!(kept(&pts, &twin), sorted);
    }

    #[test]
    fn routes_whose_ends_share_their_third_neighbour_stay() {
        // An ear 2 on the edge 0 1, whose ends' third neighbour 3 goes on to 4: one point beyond
        // both ends, no curve that runs on to tell which route it takes.
        let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.5), (0.5, -1.0), (0.5, -2.0)].map(Point::from);
        let edges = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [3, 4]];
        assert_eq!(kept(&pts, &edges), edges.to_vec());
    }

    #[test]
    fn a_route_of_four_points_beside_the_curve_goes() {
        // Four points beside samples 2 to 7, joined to 2 and 7 and along: the most a detour has.
        let beside = [(2.5, 2.0), (3.8, 2.2), (5.2, 2.2), (6.5, 2.0)];
        let pts = line_and(10, &beside);
        let route = [[2, 10], [10, 11], [11, 12], [12, 13], [7, 13]];
        assert_eq!(kept(&pts, &line_edges(10, &route)), line_edges(10, &[]));
    }

    #[test]
    fn three_routes_between_two_points_stay_in_any_order() {
        // Points 0 and 1 joined by three routes of two, two and three points: which two form the
        // detour would be read off the order of the edges.
        let pts = [
            (0.0, 0.0),
            (4.0, 0.0),
            (1.0, 1.0),
            (3.0, 1.0),
            (1.0, -1.0),
            (3.0, -1.0),
            (1.0, 0.2),
            (2.0, 0.3),
            (3.0, 0.2),
        ]
        .map(Point::from);
        let routes = [
            [0, 2],
            [2, 3],
            [1, 3],
            [0, 4],
            [4, 5],
            [1, 5],
            [0, 6],
            [6, 7],
            [7, 8],
        ];
        let mut edges = routes.to_vec();
        edges.push([1, 8]);
        let mut sorted = edges.clone();
        sorted.sort_unstable();
        assert_eq!(kept(&pts, &edges), sorted);
        edges.reverse();
        assert_eq!(kept(&pts, &edges), sorted);
        edges.rotate_left(4);
        assert_eq!(kept(&pts, &edges), sorted);
    }

    #[test]
    fn parallel_and_sequential_find_the_same_detours() {
        // Many lines with an ear each, enough points for the threads to split the scan.
        let rows = 12_000;
        let mut pts = Vec::new();
        let mut edges = Vec::new();
        for row in 0..rows {
            let y = 10.0 * row as f64;
            let base = pts.len();
            let ear = (2.4 + 0.001 * (row % 7) as f64, 2.0);
            pts.extend(line_and(6, &[ear]).iter().map(|p| Point::new(p.x, p.y + y)));
            let listed = line_edges(6, &[[2, 6], [3, 6]]);
            edges.extend(listed.iter().map(|&[a, b]| [a + base, b + base]));
        }
        let tri = triangulate(&pts).unwrap();
        let listed: Vec<Edge> = edges
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let graph = CurveGraph::new(tri.num_points(), &listed);
        let found = |parallel| -> Vec<Edge> {
            detours(&tri, &graph, parallel)
                .iter()
                .flat_map(|d| d.removed().collect::<Vec<_>>())
                .collect()
        };
        let sequential = found(false);
        assert_eq!(sequential.len(), 2 * rows);
        assert_eq!(found(true), sequential);
    }
}
