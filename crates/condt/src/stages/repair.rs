//! Stage 2, non-manifold repair (Algorithm 2).
//!
//! Owns: what happens at vertices of the proximity graph with three or more edges. It reads point
//! positions and the graph; it may not touch the triangulation.
//!
//! At a vertex `v` of degree >= 3 the paper keeps its shortest edge `e1` and the edge with the best
//! score `(θ/π)(Lmin/Le)` among those at an angle `θ > 2π/3` to it; edges between vertices of
//! degree <= 2 stay. Open readings: `docs/condt.md`, *Readings* 2 to 4.
//!
//! Needs before score ([`Repair::Needs`]) keeps the sharp tips and sampled crossings Algorithm 2
//! cuts (`docs/condt.md`, *Needs before score*), deciding at each `v` of degree >= 3, in order:
//! 1. **Crossing.** If two disjoint pairs of edges at `v` are each nearly straight (above 150°),
//!    `v` keeps the four, paired so that the less straight pair is straightest
//!    ([`Repair::CrossingAware`] takes the straightest pair first). Why 150°: chords of an
//!    `ε`-sampled curve turn by at most about `ε` radians, so with `ε <= 1/2` a passage is
//!    straighter than 180° − 28.6°. A pair counts only if its curve goes on beyond `v` on at
//!    least one side: not if both its ends close a loop (every other edge of the end, and of
//!    each neighbour of `v` it leads to, leads to another neighbour of `v`). Why: such a curve
//!    meets nothing beyond `v` but `v`'s own neighbours, a closed loop of a few samples, which
//!    the same bound rules out (its turns add up to 360°, more than 12 samples' worth at
//!    28.6°): a 5-point staircase's middle point offered its ends' second edges is no crossing
//!    ([`Repair::CrossingAware`] keeps its test without this rule). The bound says nothing of a
//!    curve that ends one sample past `v`: two 3-sample strokes crossing read as loops too.
//! 2. **Needs.** A neighbour `w` of degree <= 2 needs `vw` (without it `w` is an end or alone, and
//!    nothing restores it later) if `vw` is at most `NEED_RATIO` times `v`'s second shortest edge.
//!    `v` keeps the best pair holding a needed edge, among pairs straight enough for Algorithm 2
//!    (`θ > 2π/3`) or with both edges needed (if bent, a corner whose apex has a third edge),
//!    ranked by: straight enough (a needy stray point beside a curve must not bend it), the number
//!    of needed edges, `θ` over the path length through `v` (Algorithm 2's preference for short,
//!    straight edges), smaller ids. A pair that reaches an *ear* (a triangle `v`-`u`-`w` whose `u`
//!    and `w` have no other edges) by the edge it does not need, leaving out the needed one, is
//!    no candidate unless it runs through `v` above 150°: both stay on the curve either way, the
//!    needed edge gives the shorter path, and a turn of over 30° is no sampled curve's passage
//!    (a 4-connected staircase's end: `needs::passes_an_ear_by_its_far_side`).
//! 3. **Score.** Otherwise Algorithm 2's own choice.
//! 4. **Consent.** An edge between two vertices of degree >= 3 survives only if both keep it (as
//!    [`Repair::Mutual`]); an edge to a vertex of degree <= 2, if `v` keeps it.
//!
//! Each vertex decides from degrees and positions alone, ties by id, so the result depends neither
//! on the edges' order nor on threads. Lengths equal only after rounding are no tie: the shortest
//! edge is found exactly, as Algorithm 1 finds it, since ids follow the input's orientation.
//! Measured: `docs/perf-log.md`, *`stages/repair.rs`*.

use crate::adjacency::{degrees, ordered, Edge};
use crate::bits::IdBits;
use crate::mesh::VertexId;
use crate::predicates::compare_distances;
use crate::prefetch::{prefetch, PREFETCH_FROM};
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;
use core::f64::consts::PI;

mod needs;
pub(crate) use needs::NEED_RATIO;

/// How vertices of degree three or more in the proximity graph are treated: [`Repair::Needs`] by
/// default, [`Repair::Paper`] in the paper's preset.
///
/// ```
/// use condt::{Params, Repair};
/// assert_eq!(Repair::default(), Repair::Needs);
/// assert_eq!(Params::default().repair, Repair::default());
/// assert_eq!(Params::paper().repair, Repair::Paper);
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Repair {
    /// No repair: every proximity edge stays (as a self-intersecting curve's crossings need).
    Off,
    /// Algorithm 2 as printed: the non-manifold vertices' selections of two edges are united.
    Paper,
    /// Algorithm 2 with mutual consent: an edge between two non-manifold vertices survives only
    /// if both select it, so no vertex keeps more than two edges.
    Mutual,
    /// Keeps two nearly straight pairs of edges at a crossing, else [`Repair::Paper`]'s choice.
    CrossingAware,
    /// Needs before score: a non-manifold vertex keeps a crossing whole, else the best pair of
    /// edges that neighbours of degree <= 2 need (up to 1.3 times its second shortest), else
    /// Algorithm 2's choice; an edge between two such vertices needs both to keep it. Keeps the
    /// tips and crossings [`Repair::Paper`] cuts (`docs/condt.md`, *Needs before score*).
    #[default]
    Needs,
}

/// How many non-manifold vertices ahead the repair prefetches a choice's reads.
const PREFETCH_VERTICES: usize = 8;

/// Smallest angle at `v` for an edge to pair with the shortest one (Algorithm 2's `θ > 2π/3`).
const PAIR_ANGLE: f64 = 2.0 * PI / 3.0;
/// Smallest angle for two edges through a vertex to count as one nearly straight passage.
const STRAIGHT_ANGLE: f64 = 5.0 * PI / 6.0;

/// Squared cosines of [`PAIR_ANGLE`] and [`STRAIGHT_ANGLE`], for [`angle_above`]. The other
/// stages read the same two angles as cosines ([`SMOOTH_COS`](super::local_outliers::SMOOTH_COS),
/// [`STRAIGHT`](super::gaps::STRAIGHT)); a test ties the four forms together.
const PAIR_COS2: f64 = 0.25;
const STRAIGHT_COS2: f64 = 0.75;

/// The absolute cross product and the dot product of the edges at `v` to `a` and to `b`.
#[inline]
fn cross_dot(tri: &Triangulation, v: VertexId, a: VertexId, b: VertexId) -> (f64, f64) {
    let [p, q, r] = [v, a, b].map(|u| tri.vertex_point(u));
    let (ux, uy, wx, wy) = (q.x - p.x, q.y - p.y, r.x - p.x, r.y - p.y);
    ((ux * wy - uy * wx).abs(), ux * wx + uy * wy)
}

/// The angle at `v` between the edges to `a` and to `b`, in `[0, π]`.
pub(crate) fn angle_at(tri: &Triangulation, v: VertexId, a: VertexId, b: VertexId) -> f64 {
    let (cross, dot) = cross_dot(tri, v, a, b);
    libm::atan2(cross, dot)
}

/// [`angle_at`] if above `min` (obtuse, squared cosine `cos2`), else `None`. Speed: skips the arc
/// tangent (most of a choice's cost) for angles clearly at most `min` (acute, or squared cosine a
/// relative millionth under `cos2`, far beyond rounding); where computed, it is [`angle_at`]'s own.
#[inline]
fn angle_above(
    tri: &Triangulation,
    v: VertexId,
    a: VertexId,
    b: VertexId,
    min: f64,
    cos2: f64,
) -> Option<f64> {
    let (cross, dot) = cross_dot(tri, v, a, b);
    if dot >= 0.0 || dot * dot < cos2 * (1.0 - 1e-6) * (cross * cross + dot * dot) {
        return None;
    }
    let theta = libm::atan2(cross, dot);
    (theta > min).then_some(theta)
}

/// Algorithm 2, lines 10–11: the shortest edge and the best-scoring partner, if any; no allocation.
fn paper_choice(tri: &Triangulation, v: VertexId, around: &[VertexId]) -> [VertexId; 4] {
    let p = tri.vertex_point(v);
    let length2 = |w: VertexId| p.dist2(tri.vertex_point(w));
    let neighbours = || around.iter().copied();
    let shortest = neighbours()
        .min_by(|&a, &b| {
            compare_distances(p, tri.vertex_point(a), tri.vertex_point(b)).then(a.cmp(&b))
        })
        .expect("degree >= 3");
    let qualified = || {
        neighbours()
            .filter(move |&w| w != shortest)
            .filter_map(move |w| {
                angle_above(tri, v, shortest, w, PAIR_ANGLE, PAIR_COS2).map(|theta| (w, theta))
            })
    };
    // Lmin is the same for every candidate, so it never changes the choice: kept as in the paper.
    let l_min = qualified()
        .map(|(w, _)| libm::sqrt(length2(w)))
        .fold(f64::INFINITY, f64::min);
    let best = qualified()
        .map(|(w, theta)| (w, theta / PI * (l_min / libm::sqrt(length2(w)))))
        .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
    let partner = best.map_or(VertexId::INFINITE, |(w, _)| w);
    [shortest, partner, VertexId::INFINITE, VertexId::INFINITE]
}

/// Up to two disjoint nearly straight pairs through `v`; `None` when there are not two.
fn crossing_choice(tri: &Triangulation, v: VertexId, around: &[VertexId]) -> Option<[VertexId; 4]> {
    let mut pairs: Vec<(f64, VertexId, VertexId)> = Vec::new();
    for (i, &a) in around.iter().enumerate() {
        for &b in &around[i + 1..] {
            if let Some(theta) = angle_above(tri, v, a, b, STRAIGHT_ANGLE, STRAIGHT_COS2) {
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

/// The neighbour lists of the vertices with three or more edges (a third or more of the vertices on
/// uniform points, few on curves), in edge order, and each such vertex's rank among them, read from
/// a bit set by vertex id: O(1) where a search over the vertices would cost a cache miss per step
/// at every edge end (speed).
struct Branches {
    /// The vertices with three or more edges.
    bits: IdBits,
    /// [`IdBits::word_ranks`] of `bits`.
    before: Vec<u32>,
    starts: Vec<u32>,
    neighbors: Vec<VertexId>,
    /// How many edges join two vertices of degree two or less.
    between_manifold: usize,
    /// Per vertex of degree two or less, by id, the exclusive or of its neighbours' ids plus one
    /// (0 for none), so that [`Branches::onward`] finds the other neighbour of one it knows; the
    /// degrees' buffer, kept (4 bytes a point through the choices: the needs repair's peak on 1M
    /// uniform points 120.8 MB instead of 116.8), and empty unless asked for.
    links: Vec<u32>,
}

impl Branches {
    /// `degree` must be the degrees of `edges` ([`degrees`]); with `links` its buffer is kept for
    /// [`Branches::onward`], which only the needs repair asks, else freed.
    fn new(mut degree: Vec<u32>, edges: &[Edge], links: bool) -> Branches {
        let mut bits = IdBits::new(degree.len());
        for (v, &d) in degree.iter().enumerate() {
            bits.insert_if(v, d > 2);
        }
        let (before, count) = bits.word_ranks();
        // Each list's end first, filled backwards from it, so `starts` ends up at the starts.
        let mut starts = Vec::with_capacity(count as usize + 1);
        let mut total = 0u32;
        starts.push(0);
        for &d in degree.iter().filter(|&&d| d > 2) {
            total += d;
            starts.push(total);
        }
        let mut branches = Branches {
            bits,
            before,
            starts,
            neighbors: vec![VertexId::INFINITE; total as usize],
            between_manifold: 0,
            links: Vec::new(),
        };
        if links {
            degree.fill(0);
        }
        for &[a, b] in edges.iter().rev() {
            let mut manifold = true;
            for (v, w) in [(a, b), (b, a)] {
                if let Some(r) = branches.rank(v) {
                    let slot = &mut branches.starts[r + 1];
                    *slot -= 1;
                    branches.neighbors[*slot as usize] = w;
                    manifold = false;
                } else if links {
                    degree[v.index()] ^= link(w);
                }
            }
            branches.between_manifold += usize::from(manifold);
        }
        // Every list is full, so each end has come down to the start of the next: shifted back.
        branches.starts.rotate_left(1);
        *branches.starts.last_mut().expect("not empty") = total;
        if links {
            branches.links = degree;
        }
        branches
    }

    /// The neighbours of `w` other than `v`, a neighbour of it: a branch's listed ones, else the
    /// one left in its link, if any. Only with the links kept ([`Branches::new`]).
    fn onward(&self, w: VertexId, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        let (listed, linked) = match self.rank(w) {
            Some(r) => (self.incident(r), None),
            None => {
                debug_assert!(!self.links.is_empty(), "onward without the links kept");
                let other = self.links[w.index()] ^ link(v);
                (&[][..], (other != 0).then(|| VertexId::new(other - 1)))
            }
        };
        listed
            .iter()
            .copied()
            .filter(move |&u| u != v)
            .chain(linked)
    }

    fn count(&self) -> usize {
        self.starts.len() - 1
    }

    /// Whether `v` has three or more edges.
    #[inline]
    fn is_branch(&self, v: VertexId) -> bool {
        self.bits.contains(v.index())
    }

    /// `v`'s rank among the vertices with three or more edges, `None` if it has two or fewer.
    #[inline]
    fn rank(&self, v: VertexId) -> Option<usize> {
        self.bits.rank(v.index(), &self.before)
    }

    /// The neighbours of the vertex of rank `r`, in the order of the edges.
    #[inline]
    fn incident(&self, r: usize) -> &[VertexId] {
        &self.neighbors[self.starts[r] as usize..self.starts[r + 1] as usize]
    }

    /// The vertices with three or more edges, ascending (so the `k`-th has rank `k`).
    fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        self.bits.iter().map(|v| VertexId::new(v as u32))
    }
}

/// `w`'s id plus one, as [`Branches::links`] holds it (never 0).
#[inline]
fn link(w: VertexId) -> u32 {
    w.index() as u32 + 1
}

/// `choose(pairs, r, v)` for every non-manifold vertex `v` of rank `r`, in rank order; on rayon's
/// threads when `parallel` (each with its own `pairs` scratch), else one after the other.
fn chosen_by_rank(
    graph: &Branches,
    parallel: bool,
    choose: impl Fn(&mut needs::Pairs, usize, VertexId) -> [VertexId; 4] + Sync,
) -> Vec<[VertexId; 4]> {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        let vertices: Vec<VertexId> = graph.vertices().collect();
        let mut selections = Vec::new();
        vertices
            .par_iter()
            .enumerate()
            .with_min_len(1 << 10)
            .map_init(needs::Pairs::new, |pairs, (r, &v)| choose(pairs, r, v))
            .collect_into_vec(&mut selections);
        return selections;
    }
    let _ = parallel;
    // Sized first (memory).
    let mut selections = Vec::with_capacity(graph.count());
    let mut pairs = needs::Pairs::new();
    selections.extend(
        graph
            .vertices()
            .enumerate()
            .map(|(r, v)| choose(&mut pairs, r, v)),
    );
    selections
}

/// Applies `repair` to the proximity graph `edges` (each edge once, any order): `None` if off or no
/// vertex has three or more edges, else each edge once, those between manifold vertices in input
/// order, then the non-manifold vertices' selections by increasing id.
pub(crate) fn repair(
    tri: &Triangulation,
    edges: &[Edge],
    repair: Repair,
    parallel: bool,
) -> Option<Vec<Edge>> {
    let (mut graph, selections) = select(tri, edges, repair, parallel)?;
    // The lists are freed, the ranks kept (memory).
    (graph.starts, graph.neighbors, graph.links) = (Vec::new(), Vec::new(), Vec::new());
    let manifold = |v: VertexId| !graph.is_branch(v);
    // Whether the non-manifold `w` selected `v`.
    let selected_by =
        |w: VertexId, v: VertexId| graph.rank(w).is_some_and(|r| selections[r].contains(&v));
    // Which of its selected edges each non-manifold vertex lists (bit `k` for `chosen[k]`), so
    // that the output can be counted before it is allocated at its exact length (memory: the
    // stage's peak); each edge is listed by one end.
    let mut count = graph.between_manifold;
    let mut listed = Vec::with_capacity(selections.len());
    for (v, chosen) in graph.vertices().zip(&selections) {
        let mut bits = 0u8;
        for (k, &w) in chosen.iter().enumerate() {
            let keep = if w.is_infinite() {
                false
            } else if manifold(w) {
                true
            } else if repair == Repair::Mutual || repair == Repair::Needs {
                // Both ends are non-manifold: both must select it; the smaller end lists it.
                v < w && selected_by(w, v)
            } else {
                // A union: listed by the smaller end when both selected it.
                !(w < v && selected_by(w, v))
            };
            bits |= u8::from(keep) << k;
        }
        count += bits.count_ones() as usize;
        listed.push(bits);
    }
    // Algorithm 2, lines 3–5: edges between manifold vertices stay.
    let mut kept: Vec<Edge> = Vec::with_capacity(count);
    kept.extend(edges.iter().filter(|&&[a, b]| manifold(a) && manifold(b)));
    for ((v, chosen), bits) in graph.vertices().zip(&selections).zip(listed) {
        for (k, &w) in chosen.iter().enumerate() {
            if bits >> k & 1 == 1 {
                kept.push(ordered(v, w));
            }
        }
    }
    debug_assert_eq!(kept.len(), count);
    Some(kept)
}

/// Each vertex of degree three or more with the neighbours it selected (lines 6–12, up to four,
/// infinite ids for none), by increasing id: the stage's evidence for the provenance, which
/// names the end that did not select an edge the repair removed (with [`Repair::Mutual`] and
/// [`Repair::Needs`] the other end may have).
pub(crate) fn selections(
    tri: &Triangulation,
    edges: &[Edge],
    repair: Repair,
) -> Vec<(VertexId, [VertexId; 4])> {
    select(tri, edges, repair, false).map_or_else(Vec::new, |(graph, selections)| {
        graph.vertices().zip(selections).collect()
    })
}

/// The branches of the proximity graph `edges` and what each selects by rank ([`repair`]):
/// `None` if the repair is off or no vertex has three or more edges.
fn select(
    tri: &Triangulation,
    edges: &[Edge],
    repair: Repair,
    parallel: bool,
) -> Option<(Branches, Vec<[VertexId; 4]>)> {
    if repair == Repair::Off {
        return None;
    }
    let vertex_count = tri.num_points();
    let degree = degrees(vertex_count, edges);
    if degree.iter().all(|&d| d <= 2) {
        return None;
    }
    // From here on the branch bits tell the manifold vertices, and the degrees' buffer holds
    // their links where the needs repair reads them, else it is freed (memory: the stage's peak).
    let graph = Branches::new(degree, edges, repair == Repair::Needs);
    // Lines 6–12: up to four edges per non-manifold vertex, by rank. Each choice reads the branch
    // bits and positions alone, so ranges of ranks are chosen on threads when `parallel` (the
    // same list).
    let prefetching = vertex_count >= PREFETCH_FROM;
    let choose = |pairs: &mut needs::Pairs, r: usize, v: VertexId| {
        if prefetching && r + PREFETCH_VERTICES < graph.count() {
            // A choice reads its neighbours' points (and branch bits, cached), misses on scattered
            // points: the lists lie in rank order, so those of a vertex a few ranks on are asked
            // for ahead.
            for &w in graph.incident(r + PREFETCH_VERTICES) {
                prefetch(tri.vertex_points(), w.index());
            }
        }
        let around = graph.incident(r);
        match repair {
            Repair::Needs => needs::choice(tri, v, around, &graph, pairs),
            Repair::CrossingAware => {
                crossing_choice(tri, v, around).unwrap_or_else(|| paper_choice(tri, v, around))
            }
            _ => paper_choice(tri, v, around),
        }
    };
    let selections: Vec<[VertexId; 4]> = chosen_by_rank(&graph, parallel, choose);
    Some((graph, selections))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{triangulate, Point};

    /// Algorithm 2's `2π/3` and the straight passage's `5π/6`, as the repair reads them (angles,
    /// squared cosines) and as the other stages do (cosines): one angle each.
    #[test]
    fn the_stages_read_the_same_two_angles() {
        use super::super::{gaps::STRAIGHT, local_outliers::SMOOTH_COS};
        for (angle, cos2, cos) in [
            (PAIR_ANGLE, PAIR_COS2, SMOOTH_COS),
            (STRAIGHT_ANGLE, STRAIGHT_COS2, STRAIGHT),
        ] {
            let exact = libm::cos(angle);
            assert!((exact * exact - cos2).abs() < 1e-15, "{angle}");
            assert!((exact - cos).abs() < 1e-15, "{angle}");
        }
    }

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
        let mut out = super::repair(tri, edges, mode, false).unwrap_or_else(|| edges.to_vec());
        out.sort_unstable();
        out
    }

    /// On random graphs, the branch lists give each vertex with three or more edges, by rank in
    /// increasing id, the full adjacency's neighbours in edge order, and no other vertex a rank;
    /// `onward` gives every vertex's other neighbours.
    #[test]
    fn branches_list_the_neighbours_of_the_full_adjacency() {
        use crate::adjacency::tests::{random_graph, Adjacency};
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut branch_vertices = 0;
        for _ in 0..500 {
            let (n, edges) = random_graph(&mut rng, 30, 3);
            let (full, degree) = (Adjacency::new(n, &edges), degrees(n, &edges));
            let branches = Branches::new(degree, &edges, true);
            let expected: Vec<VertexId> = (0..n as u32)
                .map(VertexId::new)
                .filter(|&v| full.incident(v).len() > 2)
                .collect();
            assert!(branches.vertices().eq(expected.iter().copied()));
            assert_eq!(branches.count(), expected.len());
            for v in (0..n as u32).map(VertexId::new) {
                let rank = expected.iter().position(|&w| w == v);
                assert_eq!(branches.rank(v), rank, "{edges:?}");
                if let Some(r) = rank {
                    let listed = full.incident(v).iter().map(|&(w, _)| w);
                    assert!(listed.eq(branches.incident(r).iter().copied()), "{edges:?}");
                }
                // Every vertex's other neighbours, seen from each of its neighbours.
                for &(w, _) in full.incident(v) {
                    let mut expected: Vec<VertexId> = full
                        .incident(v)
                        .iter()
                        .map(|&(u, _)| u)
                        .filter(|&u| u != w)
                        .collect();
                    let mut onward: Vec<VertexId> = branches.onward(v, w).collect();
                    expected.sort_unstable();
                    onward.sort_unstable();
                    assert_eq!(onward, expected, "{edges:?}");
                }
            }
            branch_vertices += expected.len();
        }
        assert!(branch_vertices > 1000, "the graphs have branch points");
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
