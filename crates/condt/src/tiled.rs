//! What a run split in tiles needs from the library (Python's `condt.dask`): the stages' global
//! rules run on edges gathered from the tiles, and the per-point tests a tile computes for them.
//!
//! Owns: the gathered entry points, in input positions. A tile holds the whole set's Delaunay
//! star at the points it owns (its certificate, in the Python package), so a test at such a point
//! that reads only its star and the graph there is the whole set's; a rule that needs the whole
//! graph (a quantile, a component's tally, a guard over every point) runs once on the gathered
//! edges, here. It may not implement a rule: each function calls the stage's own code, which the
//! one-machine run calls too, and reads positions in the stages' frame.
//!
//! ```
//! // The driver names each point's component in the gathered edges, for the tiles' tests.
//! let labels = condt::tiled::component_labels(4, &[[0, 1], [2, 3]])?;
//! assert_eq!(labels, vec![0, 0, 2, 2]);
//! # Ok::<(), condt::Error>(())
//! ```

use crate::adjacency::{ordered, CurveGraph, Edge};
use crate::error::Error;
use crate::graph::Graph;
use crate::mesh::VertexId;
use crate::predicates::Orientation;
use crate::stages::gaps::{self, Ends, Partner, Target, Walk};
use crate::stages::hooks;
use crate::stages::local_outliers::{
    components, separated_at, separated_counts_until, smooth_and_regular, turn_at, Passage,
};
use crate::stages::outliers::IqrRule;
use crate::stages::tips::{self, Candidate};
use crate::stages::{clumps, given_back, junctions, local_outliers, Step};
use alloc::vec::Vec;

/// Algorithm 3 on edges gathered from elsewhere, without their triangulation: which of `edges`
/// (pairs of positions in `points`) [`Graph::remove_outliers`] keeps of a graph of those edges,
/// or with `floor` [`Graph::remove_outliers_floored`], and whether it fired. Lengths are measured
/// in the stages' own frame, so the answer is the stage's. For a run split in tiles (Python's
/// `condt.dask`): each tile repairs its part, and the rule, global, runs once on what they send.
///
/// # Errors
/// [`Error::InvalidParameter`] named `k` as [`Graph::remove_outliers`], or named `edge` (the
/// position) for an end not in `points`, an edge from a point to itself or an edge listed twice
/// (either way round: it would count twice in the quartiles);
/// [`Error::NonFinite`] for a NaN or infinite point, [`Error::TooManyPoints`] beyond
/// [`MAX_POINTS`](crate::MAX_POINTS).
///
/// ```
/// use condt::{remove_gathered_outliers, triangulate, Point, Uniformity};
/// let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
/// pts.push(Point::new(10.0, 6.0));
/// let tri = triangulate(&pts)?;
/// let graph = tri.proximity_graph(Uniformity::Fixed(2.75))?;
/// let (fired, kept) = remove_gathered_outliers(&pts, &graph.edges(), 1.7, false)?;
/// let stage = graph.remove_outliers(1.7)?;
/// assert_eq!((fired, kept), (stage.fired, stage.graph.edges()));
/// # Ok::<(), condt::Error>(())
/// ```
pub fn remove_gathered_outliers(
    points: &[crate::Point],
    edges: &[[usize; 2]],
    k: f64,
    floor: bool,
) -> Result<(bool, Vec<[usize; 2]>), Error> {
    let rule = IqrRule { factor: k, floor };
    Step::Outliers(rule).check()?;
    let lengths = gathered_lengths(points, edges)?;
    let cut = crate::stages::outliers::iqr_cut(edges, |e| e, &lengths, points.len(), rule);
    Ok(match cut {
        Some(kept) => (true, kept),
        None => (false, edges.to_vec()),
    })
}

/// Repairing again ([`crate::OutlierRemoval::repair_again`]) on edges gathered from elsewhere: the edges
/// of `proximity` that it repairs again, those not above the IQR cut threshold of `repaired` (the
/// repair's output), or `None` where Algorithm 3 cuts none of `repaired` (the step then changes
/// nothing). Pairs of positions in `points`; lengths measured in the stages' own frame, so the
/// answer is the stage's. For a run split in tiles (Python's `condt.dask`): each tile repairs
/// its part of the answer.
///
/// # Errors
/// As [`remove_gathered_outliers`].
///
/// ```
/// use condt::{gathered_repair_again_input, triangulate, Point, Repair, Uniformity};
/// let side = |t: f64| [(t, 0.0), (10.0, t), (10.0 - t, 10.0), (0.0, 10.0 - t)];
/// let mut pts: Vec<Point> = (0..10).flat_map(|k| side(k as f64)).map(Point::from).collect();
/// pts.extend([Point::new(-0.9, -0.9), Point::new(30.0, 30.0)]);
/// let tri = triangulate(&pts)?;
/// let proximity = tri.proximity_graph(Uniformity::Fixed(2.75))?;
/// let repaired = proximity.repair(Repair::Needs);
/// let short = gathered_repair_again_input(&pts, &repaired.edges(), &proximity.edges(), 1.7, false)?;
/// let again = tri.graph_from_edges(short.unwrap()).repair(Repair::Needs);
/// let stage = repaired.remove_outliers(1.7)?.repair_again(&repaired, &proximity, Repair::Needs);
/// assert_eq!(again.edges(), stage.edges());
/// # Ok::<(), condt::Error>(())
/// ```
pub fn gathered_repair_again_input(
    points: &[crate::Point],
    repaired: &[[usize; 2]],
    proximity: &[[usize; 2]],
    k: f64,
    floor: bool,
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    let rule = IqrRule { factor: k, floor };
    Step::Outliers(rule).check()?;
    let lengths = gathered_lengths(points, repaired)?;
    let cut = crate::stages::outliers::iqr_cut(repaired, |e| e, &lengths, points.len(), rule);
    if cut.is_none_or(|kept| kept.len() == repaired.len()) {
        return Ok(None);
    }
    let threshold = crate::stages::outliers::iqr_thresholds_of(lengths, rule).cut;
    let proximity_lengths = gathered_lengths(points, proximity)?;
    Ok(Some(
        proximity
            .iter()
            .zip(proximity_lengths)
            .filter(|&(_, length2)| length2 <= threshold)
            .map(|(&edge, _)| edge)
            .collect(),
    ))
}

/// The squared length of each of `edges` (pairs of positions in `points`) in the stages' frame.
fn gathered_lengths(points: &[crate::Point], edges: &[[usize; 2]]) -> Result<Vec<f64>, Error> {
    let stages = crate::triangulate::choose_frames(points)?.stages;
    // Checked as the other gathered edges: a loop is refused, not measured as length 0.
    let point = |v: VertexId| stages.apply(points[v.index()]);
    // A repeat would count twice in the quartiles: refused, as by the other gathered calls.
    let edges = graph_edges(points.len(), edges)?;
    Ok(edges
        .iter()
        .map(|&[a, b]| point(a).dist2(point(b)))
        .collect())
}

/// Each position's component in the graph of `edges` (pairs of positions below `n`), named by its
/// smallest position: what the driver of a split run sends each tile for [`clump_tests`].
///
/// # Errors
/// [`Error::InvalidParameter`] named `edge` (the larger end) for an end not below `n`, a loop
/// or an edge listed twice (either way round), or named `n` when `n` exceeds the curve graphs'
/// 2^29 - 1 points (more than [`MAX_POINTS`](crate::MAX_POINTS)).
///
/// ```
/// let labels = condt::tiled::component_labels(5, &[[3, 4], [1, 3]])?;
/// assert_eq!(labels, vec![0, 1, 2, 1, 1]);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn component_labels(n: usize, edges: &[[usize; 2]]) -> Result<Vec<u32>, Error> {
    let edges = graph_edges(n, edges)?;
    Ok(components(n, &edges))
}

/// The clump rule's tests at each input position of `graph`'s triangulation, for a tile of a split
/// run: bit 0 when the point has two edges and passes smoothly, bit 1 when it has edges and lies
/// apart from everything outside its component (rule 4's separation), bits 2 and 3 when it has two
/// edges and turns counter-clockwise (bit 2) or clockwise (bit 3) from its neighbour of smaller
/// position to the other (rule 4's convex cycles), bit 4 when it has two edges and its passage
/// counts as a curve's in the clump rule (smooth, or a pixel chain's step); 0 without edges.
/// `labels` names each position's component in the whole set's graph ([`component_labels`], any names
/// that are equal exactly within a component); the tests are the whole set's at every point
/// whose Delaunay star and graph the tile holds. Only the positions that `at` selects are tested
/// (a tile selects the points it owns, whose tests are its to send); the others get 0.
///
/// # Errors
/// [`Error::InvalidParameter`] named `labels` when `labels` is shorter than the triangulation's
/// points.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // A zig-zag of 6 points far from a smooth arc: its middle points are bent, not smooth.
/// let on_arc = |k: f64| Point::new(10.0 * (0.1 * k).cos(), 10.0 * (0.1 * k).sin());
/// let mut pts: Vec<Point> = (0..30).map(|k| on_arc(k as f64)).collect();
/// pts.extend([(40.0, 0.0), (41.0, 1.0), (40.2, 1.1), (41.3, 2.0), (40.1, 2.2), (41.0, 3.1)]
///     .map(Point::from));
/// let tri = triangulate(&pts)?;
/// let edges: Vec<[usize; 2]> = (0..29).chain(30..35).map(|i| [i, i + 1]).collect();
/// let labels = tiled::component_labels(pts.len(), &edges)?;
/// let graph = tri.graph_from_edges(edges.iter().copied());
/// let tests = tiled::clump_tests(&graph, &labels, |_| true)?;
/// assert_eq!(tests[10], 0b10111); // on the arc: smooth, apart from the zig-zag, turning left
/// assert_eq!(tests[32] & 0b10011, 0b10); // in the zig-zag: bent
/// # Ok::<(), condt::Error>(())
/// ```
pub fn clump_tests(
    graph: &Graph<'_>,
    labels: &[u32],
    at: impl Fn(usize) -> bool,
) -> Result<Vec<u8>, Error> {
    let tri = graph.triangulation();
    one_per_point(tri.num_points(), "labels", labels.len())?;
    let edges = graph.listed();
    let curve = CurveGraph::new(tri.num_points(), edges);
    let root = by_vertex(tri, labels);
    Ok((0..tri.num_points())
        .map(|position| {
            let v = tri.vertex(position);
            if !at(position) || tri.first_at(position) != position || curve.degree(v) == 0 {
                return 0; // a merged duplicate is tested at its vertex's own position
            }
            let (smooth, step, turn) = if curve.degree(v) == 2 {
                let [y, z] = curve.first_two(v);
                let (low, high) = if tri.input_of(y) < tri.input_of(z) {
                    (y, z)
                } else {
                    (z, y)
                };
                let turn = match turn_at(tri, low, v, high) {
                    Orientation::Ccw => 0b100,
                    Orientation::Cw => 0b1000,
                    Orientation::Collinear => 0,
                };
                let smooth = smooth_and_regular(tri, v, y, z);
                // As `clumps::passes`, the smooth test not made twice.
                (smooth, smooth || clumps::grid_step_at(tri, v, y, z), turn)
            } else {
                (false, false, 0)
            };
            u8::from(smooth)
                | u8::from(separated_at(tri, &curve, &root, v)) << 1
                | turn
                | u8::from(step) << 4
        })
        .collect())
}

/// The turn of the passage `previous, at, next` (positions) from `at`'s [`clump_tests`] row,
/// which reads it from the neighbour of smaller position: the other way round when `previous`
/// is the larger.
fn turn_read(tests: u8, previous: VertexId, next: VertexId) -> Orientation {
    let (left, right) = (Orientation::Ccw, Orientation::Cw);
    let (from_low, from_high) = if previous < next {
        (left, right)
    } else {
        (right, left)
    };
    match tests & 0b1100 {
        0b100 => from_low,
        0b1000 => from_high,
        _ => Orientation::Collinear,
    }
}

/// The clump stage ([`Graph::remove_clumps`]) on edges gathered from the tiles of a split run:
/// the edges kept (in order), or `None` when it changes nothing. `edges` are pairs of positions
/// below `n`; `tests` holds each position's [`clump_tests`], from the tile that owns it; `choices`
/// every loose end's [`gap_choices`], `tips` every point's [`tip_candidates`] and `joins` the
/// [`hook_joins`] and [`junction_joins`] on this graph, in one list (a clump that gap closing, a
/// tip's move, a hook's or a junction's would join to a
/// component that stays, stays), needed only when [`gathered_clumps_found`] says so: without a
/// clump they change nothing. The rule is the stage's own, on the same graph, with the tests read
/// instead of measured.
///
/// # Errors
/// As [`component_labels`], named `tests` when `tests` is shorter than `n`, as
/// [`close_gathered_gaps`] and [`repair_gathered_tips`] for the rows, and named `edge` for a join
/// join beyond `n`.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// let on_arc = |k: f64| Point::new(10.0 * (0.1 * k).cos(), 10.0 * (0.1 * k).sin());
/// let mut pts: Vec<Point> = (0..30).map(|k| on_arc(k as f64)).collect();
/// pts.extend([(40.0, 0.0), (41.0, 1.0), (40.2, 1.1), (41.3, 2.0), (40.1, 2.2), (41.0, 3.1)]
///     .map(Point::from));
/// let tri = triangulate(&pts)?;
/// let edges: Vec<[usize; 2]> = (0..29).chain(30..35).map(|i| [i, i + 1]).collect();
/// let graph = tri.graph_from_edges(edges.iter().copied());
/// let labels = tiled::component_labels(pts.len(), &edges)?;
/// let tests = tiled::clump_tests(&graph, &labels, |_| true)?;
/// assert!(tiled::gathered_clumps_found(pts.len(), &edges, &tests)?);
/// let choices = tiled::gap_choices(&graph, |_| true);
/// let tips = tiled::tip_candidates(&graph, true, |_| true);
/// let mut joins = tiled::hook_joins(&graph, |_| true);
/// joins.extend(tiled::junction_joins(&graph, |_| true));
/// let kept = tiled::remove_gathered_clumps(pts.len(), &edges, &tests, &choices, &tips, &joins)?;
/// assert_eq!(kept, Some(graph.remove_clumps().edges()));
/// # Ok::<(), condt::Error>(())
/// ```
pub fn remove_gathered_clumps(
    n: usize,
    edges: &[[usize; 2]],
    tests: &[u8],
    choices: &[[usize; GAP_ROW]],
    tips: &[[usize; 4]],
    joins: &[[usize; 2]],
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    let gathered = GatheredClumps::new(n, edges, tests)?;
    let gathered_joins = GatheredJoins::read(n, &gathered.graph, choices, tips, joins)?;
    let Some(clump) = gathered.clump else {
        return Ok(None);
    };
    let joins = gathered_joins.joins(n, &gathered.graph);
    let root = gathered.root;
    let clump = clumps::unless_joined(&gathered.graph, &root, clump, joins);
    Ok(clump.map(|clump| {
        keeping(edges, &gathered.listed, |a| {
            !clump[root[a.index()] as usize]
        })
    }))
}

/// Whether the clump stage finds a clump on edges gathered from the tiles of a split run, before
/// asking which of them gap closing, the tips, the hooks or the junctions would join
/// ([`remove_gathered_clumps`]): without one the stage changes nothing, and a driver need not ask
/// the tiles for their choices.
///
/// # Errors
/// As [`remove_gathered_clumps`] without the rows.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// let pts: Vec<Point> = (0..12).map(|k| Point::new(k as f64, 0.0)).collect();
/// let edges: Vec<[usize; 2]> = (0..11).map(|i| [i, i + 1]).collect();
/// let tri = triangulate(&pts)?;
/// let graph = tri.graph_from_edges(edges.iter().copied());
/// let labels = tiled::component_labels(pts.len(), &edges)?;
/// let tests = tiled::clump_tests(&graph, &labels, |_| true)?;
/// assert!(!tiled::gathered_clumps_found(pts.len(), &edges, &tests)?); // a straight line
/// # Ok::<(), condt::Error>(())
/// ```
pub fn gathered_clumps_found(n: usize, edges: &[[usize; 2]], tests: &[u8]) -> Result<bool, Error> {
    Ok(GatheredClumps::new(n, edges, tests)?.clump.is_some())
}

/// The clump rule on gathered edges before its exemption for joined clumps.
struct GatheredClumps {
    listed: Vec<Edge>,
    graph: CurveGraph,
    root: Vec<u32>,
    clump: Option<Vec<bool>>,
}

impl GatheredClumps {
    fn new(n: usize, edges: &[[usize; 2]], tests: &[u8]) -> Result<GatheredClumps, Error> {
        one_per_point(n, "tests", tests.len())?;
        let listed = graph_edges(n, edges)?;
        let graph = CurveGraph::new(n, &listed);
        let root = components(n, &listed);
        let test = |v: VertexId, bit: u8| tests[v.index()] & bit != 0;
        // Every test is at hand: the counts are exact (capped as the stage caps them), which
        // decides as the stage's early stop does (docs/distributed.md).
        let counts =
            |_: &[u32], _: f64| separated_counts_until(&graph, &root, None, |v| test(v, 2));
        let passes = |v| test(v, 0b10000);
        let clump = clumps::clumps_of(&graph, &root, passes, counts, |v| test(v, 2));
        Ok(GatheredClumps {
            listed,
            graph,
            root,
            clump,
        })
    }
}

/// Gap closing's choices, the tips stage's candidate moves and the hooks' and junctions' joins,
/// gathered from the tiles, as the joins they would add to a graph (what rule 4 and the clump
/// stage ask of the four stages).
struct GatheredJoins {
    targets: Vec<(VertexId, Target)>,
    walks: Vec<(VertexId, Walk)>,
    tip_moves: Vec<Candidate>,
    end_joins: Vec<Edge>,
}

impl GatheredJoins {
    fn read(
        n: usize,
        graph: &CurveGraph,
        choices: &[[usize; GAP_ROW]],
        tips: &[[usize; 4]],
        joins: &[[usize; 2]],
    ) -> Result<GatheredJoins, Error> {
        let (targets, walks) = loose_ends_only(graph, read_choices(n, choices)?);
        let tip_moves = candidate_rows(n, graph, tips)?;
        // A join is between two points below `n` (the stage's always are, and distinct).
        let end_joins = vertex_edges(n, joins)?;
        Ok(GatheredJoins {
            targets,
            walks,
            tip_moves,
            end_joins,
        })
    }

    /// The joins on `graph` (over `n` points), as `local_outliers::would_join` finds them on a
    /// triangulation.
    fn joins(self, n: usize, graph: &CurveGraph) -> Vec<Edge> {
        let walks = self.walks;
        let mut joins = gaps::settle_joins(n, graph, &self.targets, |j| not_joined(walks, j));
        if let Some((_, moved)) = tips::settle_candidates(n, graph, self.tip_moves) {
            joins.extend(moved);
        }
        joins.extend(self.end_joins);
        joins
    }
}

/// The tips stage's candidates at the points of `graph`'s triangulation that `at` selects (by
/// input position), for a tile of a split run: rows of four input positions, `[q, x, y, p]` for a
/// move of the loose end `q` (the chord `x y` given up for `q x` and `p y`) that passes every
/// test but the split test (a walk along a curve), `[u, a, b, u]` for the move of the point
/// without edges `u` onto the chord `a b`, `[u, y, x, q]` for its move as the apex beside the
/// loose end `x` (the chord `x y` given up for `u x`, `u y` and `x q`; told from a loose end's
/// row by `u`, which has no edge), `[u, u, u, u]` when `u` has several. A point's rows come
/// together. `spikes_follow` as the run's spikes step runs after the tips (the apex form then
/// leaves it the tips of two to five samples; `true` for the moves rule 4 and the clumps read,
/// as the one-machine stages do). They are the whole set's at every point whose Delaunay
/// neighbourhood (eight hops, nineteen when `spikes_follow`) and graph the tile holds.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // Two lines 0.8 apart, paired across by the chord 0-16 (as `Graph::repair_tips` shows).
/// let piece = |x0: f64, dx: f64, y: f64| (0..8).map(move |k| Point::new(x0 + dx * k as f64, y));
/// let pts: Vec<Point> = [(0.0, -1.0, 0.0), (1.0, 1.0, 0.0), (0.8, 1.0, 0.8), (-0.2, -1.0, 0.8)]
///     .iter()
///     .flat_map(|&(x0, dx, y)| piece(x0, dx, y))
///     .collect();
/// let tri = triangulate(&pts)?;
/// let mut edges: Vec<[usize; 2]> = (0..4)
///     .flat_map(|p| (0..7).map(move |k| [8 * p + k, 8 * p + k + 1]))
///     .collect();
/// edges.push([0, 16]);
/// let graph = tri.graph_from_edges(edges.iter().copied());
/// let candidates = tiled::tip_candidates(&graph, true, |_| true);
/// assert!(candidates.contains(&[8, 0, 16, 24]));
/// let kept = tiled::repair_gathered_tips(pts.len(), &edges, &candidates)?.unwrap();
/// let mut expected = graph.repair_tips().edges();
/// expected.sort();
/// let mut kept = kept;
/// kept.sort();
/// assert_eq!(kept, expected);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn tip_candidates(
    graph: &Graph<'_>,
    spikes_follow: bool,
    at: impl Fn(usize) -> bool,
) -> Vec<[usize; 4]> {
    let tri = graph.triangulation();
    let position = |v: VertexId| tri.input_of(v);
    tips::candidates(tri, graph.listed(), spikes_follow, |v| at(position(v)))
        .into_iter()
        .map(|candidate| match candidate {
            Candidate::Tip(move_) => move_.map(position),
            Candidate::Apex([u, a, b]) => [u, a, b, u].map(position),
            Candidate::ApexBeside(move_) => move_.map(position),
            Candidate::SeveralAt(u) => [position(u); 4],
        })
        .collect()
}

/// The edges the hooks stage's moves ([`Graph::unhook`]) would add to `graph`, found and settled as
/// the stage does, whose smaller end (by input position) `at` selects, for a tile of a split run:
/// rule 4 of the local outlier removal and the clump stage keep the pieces they join to a
/// component that stays ([`remove_gathered_local_outliers`], [`remove_gathered_clumps`]). Each
/// pair, smaller position first, is the whole set's at every point whose Delaunay neighbourhood
/// (eight hops: a move's points lie within two of its loose end, its tests read the stars there,
/// and a move sharing a point is found two hops beyond it) and graph the tile holds.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // The curve of `Graph::unhook`'s example: the loose end 5 hangs from 6, which 4 reached first.
/// let mut pts: Vec<Point> = (0..6).map(|k| Point::new(k as f64, 0.0)).collect();
/// pts.extend((0..5).map(|k| Point::new(5.6 + k as f64, 0.5)));
/// let tri = triangulate(&pts)?;
/// let edges = vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 6], [5, 6], [7, 8], [8, 9], [9, 10]];
/// let graph = tri.graph_from_edges(edges);
/// assert_eq!(tiled::hook_joins(&graph, |_| true), vec![[4, 5], [6, 7]]);
/// assert!(tiled::hook_joins(&graph, |i| i > 6).is_empty()); // both owned by 4 and 6
/// # Ok::<(), condt::Error>(())
/// ```
pub fn hook_joins(graph: &Graph<'_>, at: impl Fn(usize) -> bool) -> Vec<[usize; 2]> {
    let tri = graph.triangulation();
    let ends = Ends::new(tri, graph.listed(), None);
    let joins = hooks::hook_joins(&ends, false).into_iter();
    joins
        .map(|e| tri.input_edge(e))
        .filter(|&[a, _]| at(a))
        .collect()
}

/// The tips stage ([`Graph::repair_tips`]) on edges gathered from the tiles of a split run: the
/// edges after it (the input's without the chords given up, then the new ones), or `None` when it
/// changes nothing. `edges` are pairs of positions below `n`; `candidates` every point's rows of
/// [`tip_candidates`], from the tile that owns it. The split test and the settling of moves that
/// share a point are the stage's own, on the gathered graph.
///
/// # Errors
/// As [`component_labels`], for `edges` and for the positions in `candidates` (named
/// `candidate`, also for a join that is a loop, named twice or an edge `edges` keeps).
///
/// ```
/// use condt::tiled;
/// // The whole round trip is in the example of `tip_candidates`.
/// let edges = [[0, 1], [1, 2]];
/// assert_eq!(tiled::repair_gathered_tips(3, &edges, &[])?, None); // no candidate, no change
/// assert!(tiled::repair_gathered_tips(3, &edges, &[[0, 1, 2, 7]]).is_err()); // no point 7
/// # Ok::<(), condt::Error>(())
/// ```
pub fn repair_gathered_tips(
    n: usize,
    edges: &[[usize; 2]],
    candidates: &[[usize; 4]],
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    let listed = graph_edges(n, edges)?;
    let graph = CurveGraph::new(n, &listed);
    let rows = candidate_rows(n, &graph, candidates)?;
    let Some((mut chords, joins)) = tips::settle_candidates(n, &graph, rows) else {
        return Ok(None);
    };
    chords.sort_unstable();
    new_edges(&graph, &chords, &joins, "candidate")?;
    let mut out: Vec<[usize; 2]> = edges
        .iter()
        .zip(&listed)
        .filter(|(_, e)| chords.binary_search(e).is_err())
        .map(|(&edge, _)| edge)
        .collect();
    out.extend(joins.iter().map(|&[a, b]| [a.index(), b.index()]));
    Ok(Some(out))
}

/// The rows of [`tip_candidates`] on the gathered `graph` (over `n` points) as the tips stage
/// reads them, a loose end's rows together (as one tile sends them).
fn candidate_rows(
    n: usize,
    graph: &CurveGraph,
    candidates: &[[usize; 4]],
) -> Result<Vec<Candidate>, Error> {
    let vertex = |i: usize| VertexId::new(i as u32);
    let mut rows = Vec::with_capacity(candidates.len());
    for &row in candidates {
        if let Some(&end) = row.iter().find(|&&i| i >= n) {
            return Err(Error::invalid("candidate", end as f64));
        }
        let [q, x, y, p] = row.map(vertex);
        rows.push(if row.iter().all(|&i| i == row[0]) {
            Candidate::SeveralAt(q)
        } else if q == p {
            Candidate::Apex([q, x, y])
        } else if graph.degree(q) == 0 {
            Candidate::ApexBeside([q, x, y, p])
        } else {
            Candidate::Tip([q, x, y, p])
        });
    }
    rows.sort_by_key(|c| match c {
        Candidate::Tip([q, ..])
        | Candidate::Apex([q, ..])
        | Candidate::ApexBeside([q, ..])
        | Candidate::SeveralAt(q) => *q,
    });
    Ok(rows)
}

/// The width of a row of [`gap_choices`].
///
/// ```
/// assert_eq!(condt::tiled::GAP_ROW, 10); // the end, the target's kind and two points, a walk
/// ```
pub const GAP_ROW: usize = 10;

/// Gap closing's choices at the loose ends of `graph` that `at` selects (by input position), for
/// a tile of a split run: one row of input positions per loose end that chose a join or walks
/// straight on through a point, `[a, kind, t, u, walk, w0, w1, w2, w3, w4]`: the end `a`; its
/// target by `kind` (0 none, 1 the loose end `t`, 2 the crossing `t` lined up with its neighbour
/// `u`, 3 the point `t` with the loose end `u` across it); its straight walk's length and points.
/// Slots that hold nothing hold `a`. They are the whole set's at every loose end whose Delaunay
/// neighbourhood (six hops) and graph the tile holds.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// let pts: Vec<Point> = (0..6).map(|i| Point::new(i as f64, 0.1 * (i % 2) as f64)).collect();
/// let tri = triangulate(&pts)?;
/// let edges = [[0, 1], [1, 2], [3, 4], [4, 5]];
/// let graph = tri.graph_from_edges(edges);
/// let rows = tiled::gap_choices(&graph, |_| true);
/// assert!(rows.iter().any(|row| row[..3] == [2, 1, 3])); // 2 chose the loose end 3
/// let mut closed = tiled::close_gathered_gaps(pts.len(), &edges, &rows)?.unwrap();
/// closed.sort();
/// assert_eq!(closed, graph.close_gaps().edges());
/// # Ok::<(), condt::Error>(())
/// ```
pub fn gap_choices(graph: &Graph<'_>, at: impl Fn(usize) -> bool) -> Vec<[usize; GAP_ROW]> {
    let tri = graph.triangulation();
    let ends = Ends::new(tri, graph.listed(), None);
    let position = |v: VertexId| tri.input_of(v);
    let mut rows = Vec::new();
    for v in (0..tri.num_points()).map(|i| VertexId::new(i as u32)) {
        if !ends.is_loose(v) || !at(position(v)) {
            continue;
        }
        let (target, walk) = (ends.target(v), ends.straight_walk(v));
        if target == Target::None && walk.is_empty() {
            continue;
        }
        let a = position(v);
        let (kind, t, u) = match target {
            Target::None => (0, a, a),
            Target::End(b) => (1, position(b), a),
            Target::Through(c, Partner::Neighbor(x)) => (2, position(c), position(x)),
            Target::Through(c, Partner::End(d)) => (3, position(c), position(d)),
        };
        let mut row = [a; GAP_ROW];
        row[1..5].copy_from_slice(&[kind, t, u, walk.len()]);
        for (k, &w) in walk.iter().enumerate() {
            row[5 + k] = position(w);
        }
        rows.push(row);
    }
    rows
}

/// Gap closing ([`Graph::close_gaps`]) on edges gathered from the tiles of a split run: the edges
/// with the joins after them, or `None` when it adds none. `edges` are pairs of positions below
/// `n`; `rows` every loose end's row of [`gap_choices`], from the tile that owns it. Agreement,
/// the fixed point of joins along lone edges, and the stranded runs are the stage's own code, on
/// the gathered graph.
///
/// # Errors
/// As [`component_labels`], for `edges` and for the positions in `rows` (named `choice`, also for
/// a kind or a walk length out of range, a second target or a second walk for one loose end, or
/// a join that is a loop, named twice or already one of `edges`).
///
/// ```
/// use condt::tiled;
/// // The loose ends 2 and 3 chose each other (kind 1), walking nowhere: one join.
/// let rows = [[2, 1, 3, 2, 0, 2, 2, 2, 2, 2], [3, 1, 2, 3, 0, 3, 3, 3, 3, 3]];
/// let edges = [[0, 1], [1, 2], [3, 4], [4, 5]];
/// let closed = tiled::close_gathered_gaps(6, &edges, &rows)?.unwrap();
/// assert_eq!(closed, [&edges[..], &[[2, 3]]].concat());
/// assert_eq!(tiled::close_gathered_gaps(6, &edges, &rows[..1])?, None); // 3 did not agree
/// # Ok::<(), condt::Error>(())
/// ```
pub fn close_gathered_gaps(
    n: usize,
    edges: &[[usize; 2]],
    rows: &[[usize; GAP_ROW]],
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    let listed = graph_edges(n, edges)?;
    let graph = CurveGraph::new(n, &listed);
    let (targets, walks) = loose_ends_only(&graph, read_choices(n, rows)?);
    let joins = gaps::settle_joins(n, &graph, &targets, |joined| not_joined(walks, joined));
    new_edges(&graph, &[], &joins, "choice")?;
    Ok(with_added(edges, &joins))
}

/// The loose ends' targets and straight walks in rows of [`gap_choices`], each by increasing end.
type Choices = (Vec<(VertexId, Target)>, Vec<(VertexId, Walk)>);

/// The `walks` of the loose ends not `joined` (both by increasing end): those gap closing's
/// stranded runs read.
fn not_joined(mut walks: Vec<(VertexId, Walk)>, joined: &[VertexId]) -> Vec<(VertexId, Walk)> {
    walks.retain(|(a, _)| joined.binary_search(a).is_err());
    walks
}

/// The choices whose loose ends (the row's end, and the end it joins) have one edge in `graph`,
/// as every row [`gap_choices`] makes on it does: a row that no longer fits the gathered edges
/// names no join (gap closing walks on from an end's one edge, which such an end has not); one
/// whose join would be a loop or an edge the graph has is refused after settling ([`new_edges`]).
fn loose_ends_only(graph: &CurveGraph, (mut targets, mut walks): Choices) -> Choices {
    let loose = |v: VertexId| graph.degree(v) == 1;
    targets.retain(|&(a, target)| {
        loose(a)
            && match target {
                Target::End(b) | Target::Through(_, Partner::End(b)) => loose(b),
                _ => true,
            }
    });
    walks.retain(|&(a, _)| loose(a));
    (targets, walks)
}

fn read_choices(n: usize, rows: &[[usize; GAP_ROW]]) -> Result<Choices, Error> {
    let (mut targets, mut walks) = (Vec::new(), Vec::new());
    for row in rows {
        let walk_len = row[4];
        let mut named = [row[0], row[2], row[3]]
            .into_iter()
            .chain(row[5..].iter().copied().take(walk_len));
        let bad = row[1] > 3 || walk_len > GAP_ROW - 5;
        if let Some(at) = named.find(|&i| i >= n).or(bad.then_some(row[0])) {
            return Err(Error::invalid("choice", at as f64));
        }
        let v = |i: usize| VertexId::new(row[i] as u32);
        let target = match row[1] {
            1 => Target::End(v(2)),
            2 => Target::Through(v(2), Partner::Neighbor(v(3))),
            3 => Target::Through(v(2), Partner::End(v(3))),
            _ => Target::None,
        };
        if target != Target::None {
            targets.push((v(0), target));
        }
        if walk_len > 0 {
            let mut walk = Walk::EMPTY;
            for k in 0..walk_len {
                walk.push(v(5 + k));
            }
            walks.push((v(0), walk));
        }
    }
    targets.sort_unstable_by_key(|&(a, _)| a);
    walks.sort_unstable_by_key(|&(a, _)| a);
    // A loose end chooses once: a second row for it would join it twice.
    let pairs = targets.windows(2).map(|w| (w[0].0, w[1].0));
    let mut pairs = pairs.chain(walks.windows(2).map(|w| (w[0].0, w[1].0)));
    if let Some((twice, _)) = pairs.find(|(a, b)| a == b) {
        return Err(Error::invalid("choice", twice.index() as f64));
    }
    Ok((targets, walks))
}

/// The local outlier removal's local rules 1 to 3 ([`Graph::remove_local_outliers`] without
/// rule 4, which judges whole components), for a tile of a split run: `before_outliers` is the
/// IQR stage's input, and `give_back` says whether rule 1 runs (the stage runs it when the IQR
/// stage's input has more edges than this graph, a count the driver takes on the whole set). The
/// result is the whole set's at every point whose Delaunay neighbourhood (six hops) and graphs
/// the tile holds.
///
/// # Panics
/// If `before_outliers` lives on another triangulation.
///
/// ```
/// use condt::{tiled, triangulate, Point, Repair, Uniformity};
/// let angles = (0..12).map(|k| k as f64 * std::f64::consts::TAU / 12.0);
/// let mut pts: Vec<Point> = angles.map(|t| Point::new(t.cos(), t.sin())).collect();
/// pts.extend([Point::new(6.0, 6.0), Point::new(6.3, 6.1)]);
/// let tri = triangulate(&pts)?;
/// let repaired = tri.proximity_graph(Uniformity::default())?.repair(Repair::Paper);
/// let filtered = repaired.remove_outliers(1.7)?.graph;
/// let give_back = repaired.num_edges() > filtered.num_edges();
/// // The pair far away is a curve of two points for rules 1-3; rule 4 (on the driver) drops it.
/// assert_eq!(tiled::local_rules(&filtered, &repaired, give_back).num_edges(), 13);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn local_rules<'t>(
    graph: &Graph<'t>,
    before_outliers: &Graph<'t>,
    give_back: bool,
) -> Graph<'t> {
    graph.assert_beside(&[before_outliers], "local_rules: the two graphs");
    let tri = graph.triangulation();
    let rules = local_outliers::Rules {
        give_back,
        ..local_outliers::Rules::LOCAL
    };
    let before = alloc::borrow::Cow::Borrowed(before_outliers.listed());
    let outcome =
        local_outliers::remove_local_outliers_with(tri, graph.listed(), before, &rules, false);
    graph.changed_to(outcome.edges)
}

/// Rule 1 of the local outlier removal at curves' last edges, for a tile of a split run: the
/// candidates a tile finds with the IQR stage's input `before_outliers` and output `graph` (each
/// a cut edge whose end had it alone, continuing a passage at its other end within 1.5 times
/// that end's other edge, or growing at most 1.5 times as much as that edge grew on the edge
/// before it: two hops along the curve), as pairs of input positions, smaller first. The
/// driver gives back those [`give_back_gathered_last_edges`] keeps, after rules 1 to 3.
///
/// # Panics
/// If `before_outliers` lives on another triangulation.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // 20 samples one apart along a gentle arc, then a last one 1.4 beyond, whose edge the IQR
/// // filter cut; and an outlier 3 beyond the arc's other end, whose edge it cut too.
/// let arc = |x: f64| Point::new(x, 0.005 * x * x);
/// let mut pts: Vec<Point> = (0..20).map(|k| arc(k as f64)).collect();
/// pts.extend([arc(20.4), arc(-3.0)]);
/// let tri = triangulate(&pts)?;
/// let mut chain: Vec<[usize; 2]> = (0..20).map(|k| [k, k + 1]).collect();
/// chain.push([0, 21]);
/// let before = tri.graph_from_edges(chain.iter().copied());
/// let after = tri.graph_from_edges(chain[..19].iter().copied());
/// // Only the last sample within 1.5 times the spacing is a candidate.
/// assert_eq!(tiled::last_edge_candidates(&after, &before), vec![[19, 20]]);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn last_edge_candidates(graph: &Graph<'_>, before_outliers: &Graph<'_>) -> Vec<[usize; 2]> {
    graph.assert_beside(&[before_outliers], "last_edge_candidates: the two graphs");
    let tri = graph.triangulation();
    let candidates =
        local_outliers::last_edge_candidates(tri, graph.listed(), before_outliers.listed());
    Graph::new(tri, alloc::borrow::Cow::Owned(candidates)).edges()
}

/// Rule 1 of the local outlier removal at curves' last edges on edges gathered from the tiles of
/// a split run, after rules 1 to 3 ([`local_rules`]): `edges` with the `candidates`
/// ([`last_edge_candidates`], from the tiles that own them) the rule gives back, or `None` when
/// it gives back none. It walks along the curves, so it runs here on the whole graph; the rule is
/// the stage's own code.
///
/// # Errors
/// As [`component_labels`], for `edges` and the candidates (a candidate may repeat).
///
/// ```
/// use condt::tiled;
/// // The chain 0-1-...-6 lost its edge to 7: five points of degree two behind 6 give it back.
/// let edges: Vec<[usize; 2]> = (0..6).map(|k| [k, k + 1]).collect();
/// let back = tiled::give_back_gathered_last_edges(8, &edges, &[[6, 7]])?;
/// assert_eq!(back.map(|e| e.len()), Some(7));
/// // Behind a chain of four points no curve shows: nothing comes back.
/// assert_eq!(tiled::give_back_gathered_last_edges(8, &edges[3..], &[[6, 7]])?, None);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn give_back_gathered_last_edges(
    n: usize,
    edges: &[[usize; 2]],
    candidates: &[[usize; 2]],
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    let listed = graph_edges(n, edges)?;
    // Each candidate once, whatever the tiles sent.
    let mut candidates = vertex_edges(n, candidates)?;
    candidates.sort_unstable();
    candidates.dedup();
    let back = local_outliers::last_edges(&CurveGraph::new(n, &listed), &candidates);
    Ok(with_added(edges, &back))
}

/// The edges the junctions stage would join ([`Graph::join_junctions`]) at the loose ends of
/// `graph` that `at` selects (by input position), each end's own choice, for a tile of a split
/// run: rule 4 of the local outlier removal and the clump stage keep the pieces they join to a
/// component that stays ([`remove_gathered_local_outliers`], [`remove_gathered_clumps`]). Each
/// pair, smaller position first, is the whole set's at every loose end whose Delaunay
/// neighbourhood (twelve hops, a junction choice's reach) and graph the tile holds.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // A straight curve 0..=12 and, one spacing above point 6, the end 13 of a branch heading down.
/// let mut pts: Vec<Point> = (0..=12).map(|k| Point::new(k as f64, 0.0)).collect();
/// pts.extend((1..=7).map(|k| Point::new(6.0, k as f64)));
/// let tri = triangulate(&pts)?;
/// let edges: Vec<[usize; 2]> = (0..12).chain(13..19).map(|i| [i, i + 1]).collect();
/// let graph = tri.graph_from_edges(edges);
/// assert_eq!(tiled::junction_joins(&graph, |_| true), vec![[6, 13]]);
/// assert!(tiled::junction_joins(&graph, |i| i != 13).is_empty()); // owned by the end 13
/// # Ok::<(), condt::Error>(())
/// ```
pub fn junction_joins(
    graph: &Graph<'_>,
    at: impl Fn(usize) -> bool + Sync + Send,
) -> Vec<[usize; 2]> {
    let tri = graph.triangulation();
    let ends = Ends::new(tri, graph.listed(), None);
    let position = |v: VertexId| tri.input_of(v);
    let joins = junctions::junction_joins(&ends, false, |v| at(position(v)));
    joins.into_iter().map(|e| tri.input_edge(e)).collect()
}

/// The local outlier removal's rule 4 on edges gathered from the tiles of a split run, after
/// rules 1 to 3 ([`local_rules`]): the edges kept, or `None` when it drops none. `edges` are pairs
/// of positions below `n`; `tests` each position's [`clump_tests`] on this graph (the separation
/// and the smooth passage rule 4 reads too), `choices` every loose end's [`gap_choices`] on it,
/// `tips` every point's [`tip_candidates`] on it and `joins` its [`hook_joins`] and
/// [`junction_joins`] in one list (rule 4 keeps pieces gap closing, a tip's move, a hook's or a
/// junction's would join to a kept component), each from the
/// tile that owns it. The rule is the stage's own code.
///
/// # Errors
/// As [`remove_gathered_clumps`], [`close_gathered_gaps`] and [`repair_gathered_tips`].
///
/// ```
/// use condt::{tiled, triangulate, Point, Repair, Uniformity};
/// let angles = (0..12).map(|k| k as f64 * std::f64::consts::TAU / 12.0);
/// let mut pts: Vec<Point> = angles.map(|t| Point::new(t.cos(), t.sin())).collect();
/// pts.extend([Point::new(6.0, 6.0), Point::new(6.3, 6.1)]);
/// let tri = triangulate(&pts)?;
/// let repaired = tri.proximity_graph(Uniformity::default())?.repair(Repair::Paper);
/// let filtered = repaired.remove_outliers(1.7)?.graph;
/// let give_back = repaired.num_edges() > filtered.num_edges();
/// let local = tiled::local_rules(&filtered, &repaired, give_back);
/// let edges = local.edges();
/// let labels = tiled::component_labels(pts.len(), &edges)?;
/// let tests = tiled::clump_tests(&local, &labels, |_| true)?;
/// let choices = tiled::gap_choices(&local, |_| true);
/// let tips = tiled::tip_candidates(&local, true, |_| true);
/// let mut joins = tiled::hook_joins(&local, |_| true);
/// joins.extend(tiled::junction_joins(&local, |_| true));
/// let kept =
///     tiled::remove_gathered_local_outliers(pts.len(), &edges, &tests, &choices, &tips, &joins)?;
/// // The far pair goes; the circle stays, as the stage decides.
/// let stage = filtered.remove_local_outliers(&repaired).edges();
/// assert_eq!(kept, Some(stage));
/// # Ok::<(), condt::Error>(())
/// ```
pub fn remove_gathered_local_outliers(
    n: usize,
    edges: &[[usize; 2]],
    tests: &[u8],
    choices: &[[usize; GAP_ROW]],
    tips: &[[usize; 4]],
    joins: &[[usize; 2]],
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    one_per_point(n, "tests", tests.len())?;
    let listed = graph_edges(n, edges)?;
    let profile = CurveGraph::new(n, &listed);
    let root = components(n, &listed);
    let gathered_joins = GatheredJoins::read(n, &profile, choices, tips, joins)?;
    let test = |v: VertexId, bit: u8| tests[v.index()] & bit != 0;
    let separated = separated_counts_until(&profile, &root, None, |v| test(v, 2));
    let separated = separated.expect("no limit to reach");
    let passing = |at: VertexId, previous: VertexId, next: VertexId| Passage {
        smooth: test(at, 1),
        turn: turn_read(tests[at.index()], previous, next),
    };
    let joins = || gathered_joins.joins(n, &profile);
    let Some((root, kept)) =
        local_outliers::separated_with(&listed, &profile, root, &separated, passing, joins)
    else {
        return Ok(None);
    };
    Ok(Some(keeping(edges, &listed, |a| {
        kept[root[a.index()] as usize]
    })))
}

/// Each position's component label and status, as [`given_back_standing`] gives them.
///
/// ```
/// let standing: condt::tiled::GivenBackStanding = (vec![0, 0, 2], vec![2, 2, 0]);
/// assert_eq!(standing.1[2], 0); // the third point has no edge
/// ```
pub type GivenBackStanding = (Vec<u32>, Vec<u8>);

/// For the given-back check of a split run, on the driver: each position's component in the graph
/// of `edges` (pairs of positions below `n`) and its status (0 without edges, 1 on a component
/// not all given back, 2 on a component made only of edges missing from `before_local`, the local
/// outlier removal's input), for [`given_back_tests`]; `None` when no edge was given back (the
/// check then changes nothing).
///
/// # Errors
/// As [`component_labels`], for `edges` and `before_local`.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // A chain of 14 points 0.3 apart, all given back, and two stray points beside its middle.
/// let wave = |k: f64| Point::new(0.3 * k, 0.01 * (1.7 * k).sin());
/// let mut pts: Vec<Point> = (0..14).map(|k| wave(k as f64)).collect();
/// pts.extend([Point::new(1.75, 0.45), Point::new(1.85, 0.46)]);
/// let tri = triangulate(&pts)?;
/// let edges: Vec<[usize; 2]> = (0..13).map(|k| [k, k + 1]).collect();
/// let (labels, status) = tiled::given_back_standing(pts.len(), &edges, &[])?.unwrap();
/// assert_eq!((labels[5], status[5], status[14]), (0, 2, 0));
/// # Ok::<(), condt::Error>(())
/// ```
pub fn given_back_standing(
    n: usize,
    edges: &[[usize; 2]],
    before_local: &[[usize; 2]],
) -> Result<Option<GivenBackStanding>, Error> {
    let Some((_, standing)) = standing_of(n, edges, before_local)? else {
        return Ok(None);
    };
    let status = (0..n)
        .map(|i| standing.status(VertexId::new(i as u32)) as u8)
        .collect();
    Ok(Some((standing.root, status)))
}

/// The given-back check's test at each input position of `graph`'s triangulation, for a tile of
/// a split run: 1 where a point of two or more edges on a component only given back does not lie
/// apart (its component goes), else 0. `labels` and `status` are each position's, from
/// [`given_back_standing`] on the whole set; the tests are the whole set's at every point whose
/// Delaunay star and graph the tile holds. Only the positions that `at` selects are tested, as
/// for [`clump_tests`].
///
/// # Errors
/// [`Error::InvalidParameter`] named `labels` or `status` when it is shorter than the
/// triangulation's points.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // A chain of 14 points 0.3 apart, all given back, and two stray points beside its middle.
/// let wave = |k: f64| Point::new(0.3 * k, 0.01 * (1.7 * k).sin());
/// let mut pts: Vec<Point> = (0..14).map(|k| wave(k as f64)).collect();
/// pts.extend([Point::new(1.75, 0.45), Point::new(1.85, 0.46)]);
/// let tri = triangulate(&pts)?;
/// let edges: Vec<[usize; 2]> = (0..13).map(|k| [k, k + 1]).collect();
/// let (labels, status) = tiled::given_back_standing(pts.len(), &edges, &[])?.unwrap();
/// let graph = tri.graph_from_edges(edges.iter().copied());
/// let tests = tiled::given_back_tests(&graph, &labels, &status, |_| true)?;
/// assert!(tests.contains(&1)); // the strays are near the chain's middle
/// assert_eq!((tests[0], tests[14]), (0, 0)); // an end has one edge; a stray none
/// # Ok::<(), condt::Error>(())
/// ```
pub fn given_back_tests(
    graph: &Graph<'_>,
    labels: &[u32],
    status: &[u8],
    at: impl Fn(usize) -> bool,
) -> Result<Vec<u8>, Error> {
    let tri = graph.triangulation();
    let n = tri.num_points();
    one_per_point(n, "labels", labels.len())?;
    one_per_point(n, "status", status.len())?;
    let curve = CurveGraph::new(n, graph.listed());
    // The whole set's component names, renumbered among the tile's own (the standing indexes
    // its tallies by name).
    let named = by_vertex(tri, labels);
    let mut names = named.clone();
    names.sort_unstable();
    names.dedup();
    let local = |name: &u32| names.binary_search(name).unwrap_or(0) as u32;
    let standing = given_back::Standing::from_parts(
        named.iter().map(local).collect(),
        by_vertex(tri, status),
        (0..n)
            .map(|v| curve.degree(VertexId::new(v as u32)).min(255) as u8)
            .collect(),
    );
    let dropped_at = |v: VertexId| {
        let p = tri.vertex_point(v);
        let longest = (0..curve.degree(v))
            .map(|k| p.dist2(tri.vertex_point(curve.neighbor(v, k))))
            .fold(-1.0f64, f64::max);
        !standing.apart(tri, v, longest)
    };
    Ok((0..n)
        .map(|position| {
            let v = tri.vertex(position);
            let judged = at(position)
                && tri.input_of(v) == position
                && curve.degree(v) >= 2
                && standing.status(v) == given_back::Status::GivenBack;
            u8::from(judged && dropped_at(v))
        })
        .collect())
}

/// The given-back check ([`Graph::confirm_given_back`]) on edges gathered from the tiles of a
/// split run: the edges kept, or `None` when it drops none. `edges` and `before_local` as for
/// [`given_back_standing`]; `tests` each position's [`given_back_tests`], from the tile that owns
/// it. The rule is the stage's own code.
///
/// # Errors
/// As [`given_back_standing`], and named `tests` when `tests` is shorter than `n`.
///
/// ```
/// use condt::{tiled, triangulate, Point};
/// // A chain of 14 points 0.3 apart, all given back, and two stray points beside its middle.
/// let wave = |k: f64| Point::new(0.3 * k, 0.01 * (1.7 * k).sin());
/// let mut pts: Vec<Point> = (0..14).map(|k| wave(k as f64)).collect();
/// pts.extend([Point::new(1.75, 0.45), Point::new(1.85, 0.46)]);
/// let tri = triangulate(&pts)?;
/// let edges: Vec<[usize; 2]> = (0..13).map(|k| [k, k + 1]).collect();
/// let (labels, status) = tiled::given_back_standing(pts.len(), &edges, &[])?.unwrap();
/// let graph = tri.graph_from_edges(edges.iter().copied());
/// let tests = tiled::given_back_tests(&graph, &labels, &status, |_| true)?;
/// let kept = tiled::confirm_gathered_given_back(pts.len(), &edges, &[], &tests)?;
/// // The chain lies in a scatter and goes, as the stage decides.
/// assert_eq!(kept, Some(vec![]));
/// assert!(graph.confirm_given_back(&tri.graph_from_edges([])).edges().is_empty());
/// # Ok::<(), condt::Error>(())
/// ```
pub fn confirm_gathered_given_back(
    n: usize,
    edges: &[[usize; 2]],
    before_local: &[[usize; 2]],
    tests: &[u8],
) -> Result<Option<Vec<[usize; 2]>>, Error> {
    one_per_point(n, "tests", tests.len())?;
    let Some((listed, standing)) = standing_of(n, edges, before_local)? else {
        return Ok(None);
    };
    let dropped = standing.dropped(|v| tests[v.index()] != 0);
    if !dropped.contains(&true) {
        return Ok(None);
    }
    let root = &standing.root;
    Ok(Some(keeping(edges, &listed, |a| {
        !dropped[root[a.index()] as usize]
    })))
}

/// The given-back check's reading of `edges` against `before_local` (pairs of positions below
/// `n`): the edges as the stages' edges and each point's standing, or `None` when no edge was
/// given back.
fn standing_of(
    n: usize,
    edges: &[[usize; 2]],
    before_local: &[[usize; 2]],
) -> Result<Option<(Vec<Edge>, given_back::Standing)>, Error> {
    let listed = graph_edges(n, edges)?;
    let given = given_back::missing_from(&listed, &graph_edges(n, before_local)?);
    if !given.contains(&true) {
        return Ok(None);
    }
    let standing = given_back::Standing::of(n, &listed, &given);
    Ok(Some((listed, standing)))
}

/// `values`, one per input position of `tri`, listed by vertex id instead.
fn by_vertex<T: Copy>(tri: &crate::Triangulation, values: &[T]) -> Vec<T> {
    let vertices = (0..tri.num_points() as u32).map(VertexId::new);
    vertices.map(|v| values[tri.input_of(v)]).collect()
}

/// The rows of `edges` (as `listed`, the stages' edges) whose smaller end `keep` keeps: a rule
/// that drops whole components asks it of any one point.
fn keeping(
    edges: &[[usize; 2]],
    listed: &[Edge],
    keep: impl Fn(VertexId) -> bool,
) -> Vec<[usize; 2]> {
    let kept = edges.iter().zip(listed).filter(|&(_, &[a, _])| keep(a));
    kept.map(|(&edge, _)| edge).collect()
}

/// `edges` with `added` after them, or `None` when `added` is empty.
fn with_added(edges: &[[usize; 2]], added: &[Edge]) -> Option<Vec<[usize; 2]>> {
    let positions = added.iter().map(|&[a, b]| [a.index(), b.index()]);
    (!added.is_empty()).then(|| edges.iter().copied().chain(positions).collect())
}

/// `Ok` when the `joins` a gathered stage settled on are new edges: no loop, none twice, none an
/// edge of `graph` outside the sorted `removed`. Rows no tile sends (a gap's target that is its
/// own end, a tip's apex row joining an end to its own neighbour) can name such a join: refused
/// by `name` with the join's larger end, not returned as edges the next gathered call refuses.
fn new_edges(
    graph: &CurveGraph,
    removed: &[Edge],
    joins: &[Edge],
    name: &'static str,
) -> Result<(), Error> {
    let mut added: Vec<Edge> = joins.iter().map(|&[a, b]| ordered(a, b)).collect();
    added.sort_unstable();
    let in_graph = |[a, b]: Edge| graph.has_edge(a, b) && removed.binary_search(&[a, b]).is_err();
    let wrong = (0..added.len()).find(|&i| {
        let [a, b] = added[i];
        a == b || (i > 0 && added[i - 1] == added[i]) || in_graph(added[i])
    });
    match wrong {
        Some(i) => Err(Error::invalid(name, added[i][1].index() as f64)),
        None => Ok(()),
    }
}

/// `Ok` when an array `name` of `len` entries holds one per point of `n`.
fn one_per_point(n: usize, name: &'static str, len: usize) -> Result<(), Error> {
    if len < n {
        return Err(Error::invalid(name, len as f64));
    }
    Ok(())
}

/// `edges` (pairs of distinct positions below `n`) as the stages' edges, a position standing for
/// a vertex. A loop is no edge (`Graph` drops them): refused, also by [`gathered_lengths`].
fn vertex_edges(n: usize, edges: &[[usize; 2]]) -> Result<Vec<Edge>, Error> {
    if n > CurveGraph::MAX_VERTICES {
        return Err(Error::invalid("n", n as f64));
    }
    edges
        .iter()
        .map(|&[a, b]| {
            if a.max(b) >= n || a == b {
                return Err(Error::invalid("edge", a.max(b) as f64));
            }
            Ok(ordered(VertexId::new(a as u32), VertexId::new(b as u32)))
        })
        .collect()
}

/// [`vertex_edges`] of a graph's edges, each listed once: a repeat (in either direction) would
/// count twice in a degree or a component's tally, a wrong answer rather than an error, so it
/// is refused by name (`edge`, its larger end).
fn graph_edges(n: usize, edges: &[[usize; 2]]) -> Result<Vec<Edge>, Error> {
    let listed = vertex_edges(n, edges)?;
    // The driver sends its edges sorted: then no repeat is possible, and no copy is sorted.
    if listed.windows(2).all(|pair| pair[0] < pair[1]) {
        return Ok(listed);
    }
    let mut sorted = listed.clone();
    sorted.sort_unstable();
    match sorted.windows(2).find(|pair| pair[0] == pair[1]) {
        Some(pair) => Err(Error::invalid("edge", pair[0][1].index() as f64)),
        None => Ok(listed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{triangulate, Point};

    /// Found by a review of the public API: loops `[i, i]` among gathered edges were measured as
    /// edges of length 0 (630 of them beside a line of 20 edges came back as all that was kept).
    #[test]
    fn a_gathered_loop_is_refused_by_name() {
        let pts: Vec<crate::Point> = (0..4).map(|i| crate::Point::new(i as f64, 0.0)).collect();
        let refused = Error::InvalidParameter {
            name: "edge",
            value: 2.0,
        };
        let edges = [[0, 1], [2, 2], [2, 3]];
        let outliers = remove_gathered_outliers(&pts, &edges, 1.7, false);
        assert_eq!(outliers.unwrap_err(), refused);
        let again = gathered_repair_again_input(&pts, &edges, &[[0, 1]], 1.7, false);
        assert_eq!(again.unwrap_err(), refused);
        assert!(remove_gathered_outliers(&pts, &[[0, 1], [2, 3]], 1.7, false).is_ok());
    }

    /// Found by a review of the public API: a loop or an edge listed twice counted in the other
    /// gathered rules' degrees and tallies (gap closing lost its join, a loop's point counted as
    /// given back), and a loose end's second row was joined twice. Each is refused by name.
    #[test]
    fn gathered_loops_repeats_and_second_rows_are_refused() {
        let edges = [[0, 1], [1, 2], [3, 4], [4, 5]];
        // The loose ends 2 and 3 choose each other (kind 1), walking nowhere.
        let rows = [
            [2, 1, 3, 2, 0, 2, 2, 2, 2, 2],
            [3, 1, 2, 3, 0, 3, 3, 3, 3, 3],
        ];
        let joined = close_gathered_gaps(6, &edges, &rows).unwrap().unwrap();
        assert!(joined.contains(&[2, 3]));
        let edge = |value: f64| Error::InvalidParameter {
            name: "edge",
            value,
        };
        for (wrong, larger) in [([2, 2], 2.0), ([2, 1], 2.0), ([4, 5], 5.0)] {
            let mut given = edges.to_vec();
            given.push(wrong);
            assert_eq!(close_gathered_gaps(6, &given, &rows), Err(edge(larger)));
            assert_eq!(component_labels(6, &given), Err(edge(larger)));
            // The message names each cause (a repeat was told of as a loop or past the points).
            let told = edge(larger).to_string();
            assert!(
                told.contains("a loop") && told.contains("listed twice"),
                "{told}"
            );
            assert_eq!(repair_gathered_tips(6, &given, &[]), Err(edge(larger)));
            assert_eq!(
                given_back_standing(6, &edges, &given).err(),
                Some(edge(larger))
            );
            assert_eq!(
                given_back_standing(6, &given, &edges).err(),
                Some(edge(larger))
            );
        }
        let twice = close_gathered_gaps(6, &edges, &[rows[0], rows[1], rows[0]]);
        assert_eq!(twice, Err(Error::invalid("choice", 2.0)));
    }

    /// Found by an embedded user's review: rows no tile sends settled on joins that were loops or
    /// edges the graph had, returned as edges the next gathered call refuses; and a repeated
    /// edge counted twice in Algorithm 3's quartiles, changing its answer.
    #[test]
    fn joins_that_are_no_new_edges_and_repeats_in_the_quartiles_are_refused() {
        // A gap's target that is its own end; an end choosing its own neighbour.
        let own_end = [[0, 3, 0, 0, 0, 0, 0, 0, 0, 0]];
        assert_eq!(
            close_gathered_gaps(3, &[[0, 1], [2, 1]], &own_end),
            Err(Error::invalid("choice", 0.0))
        );
        let neighbours = [
            [0, 1, 1, 0, 0, 0, 0, 0, 0, 0],
            [1, 1, 0, 1, 0, 1, 1, 1, 1, 1],
        ];
        assert_eq!(
            close_gathered_gaps(2, &[[0, 1]], &neighbours),
            Err(Error::invalid("choice", 1.0))
        );
        // A tip's apex joined to the end it already has an edge to.
        assert_eq!(
            repair_gathered_tips(3, &[[1, 0]], &[[0, 2, 1, 0]]),
            Err(Error::invalid("candidate", 1.0))
        );
        let told = Error::invalid("candidate", 1.0).to_string();
        assert!(told.contains("already an edge"), "{told}");
        // Twenty points on a line and one apart: Algorithm 3 cuts the long edge to the lone
        // point; listed many times over, that edge moved the quartiles and was kept.
        let mut points: Vec<Point> = (0..20).map(|i| Point::new(i as f64, 0.0)).collect();
        points.push(Point::new(19.0, 30.0));
        let line: Vec<[usize; 2]> = (0..19).map(|i| [i, i + 1]).chain([[19, 20]]).collect();
        let (fired, kept) = remove_gathered_outliers(&points, &line, 1.5, false).unwrap();
        assert!(fired && kept.len() == 19);
        let repeated: Vec<[usize; 2]> = line.iter().copied().chain([[20, 19]; 20]).collect();
        assert_eq!(
            remove_gathered_outliers(&points, &repeated, 1.5, false),
            Err(Error::invalid("edge", 20.0))
        );
        assert_eq!(
            gathered_repair_again_input(&points, &line, &repeated, 1.5, false),
            Err(Error::invalid("edge", 20.0))
        );
    }

    /// Rule 4's rows on the graph of `edges` after rules 1 to 3 (every point's, as the tiles
    /// send them), and the stage's own result on that graph.
    struct Rule4Rows {
        n: usize,
        listed: Vec<[usize; 2]>,
        tests: Vec<u8>,
        choices: Vec<[usize; GAP_ROW]>,
        tips: Vec<[usize; 4]>,
        hooks: Vec<[usize; 2]>,
        junctions: Vec<[usize; 2]>,
        stage: Vec<[usize; 2]>,
    }

    fn rule_4_rows(pts: &[crate::Point], edges: &[[usize; 2]]) -> Rule4Rows {
        let tri = crate::triangulate(pts).unwrap();
        let graph = tri.graph_from_edges(edges.iter().copied());
        let local = local_rules(&graph, &graph, false);
        let listed = local.edges();
        let labels = component_labels(pts.len(), &listed).unwrap();
        let tests = clump_tests(&local, &labels, |_| true).unwrap();
        Rule4Rows {
            n: pts.len(),
            tests,
            choices: gap_choices(&local, |_| true),
            tips: tip_candidates(&local, true, |_| true),
            hooks: hook_joins(&local, |_| true),
            junctions: junction_joins(&local, |_| true),
            stage: graph.remove_local_outliers(&graph).edges(),
            listed,
        }
    }

    /// Rule 4 on gathered edges keeps a piece that a tip's move joins to a kept curve, as the
    /// stage does (the stage's test's points and edges). Gathered without the tips' rows, the
    /// piece goes.
    #[test]
    fn gathered_rule_4_keeps_what_a_tip_s_move_joins_as_the_stage_does() {
        let (pts, edges, curve_len) = crate::test_graphs::tip_piece_beside_a_curve();
        let r = rule_4_rows(&pts, &edges);
        let (n, listed, tests) = (r.n, &r.listed, &r.tests);
        let gathered =
            remove_gathered_local_outliers(n, listed, tests, &r.choices, &r.tips, &r.hooks);
        assert_eq!(r.stage.len(), edges.len());
        assert_eq!(gathered.unwrap().unwrap_or(listed.clone()), r.stage);
        let without =
            remove_gathered_local_outliers(n, listed, tests, &r.choices, &[], &r.hooks).unwrap();
        assert_eq!(without.map(|kept| kept.len()), Some(curve_len - 1));
    }

    /// Rule 4 on gathered edges keeps a piece that a hook's move joins to a kept curve, as the
    /// stage does; gathered without the hook joins, the piece goes. Joins naming a point beyond
    /// the set are refused by name.
    #[test]
    fn gathered_rule_4_keeps_what_a_hook_joins_as_the_stage_does() {
        let (pts, edges, curve_len) = crate::test_graphs::hooked_piece_beside_a_curve();
        let r = rule_4_rows(&pts, &edges);
        let (n, listed, tests) = (r.n, &r.listed, &r.tests);
        assert_eq!(r.hooks, vec![[11, 12], [13, curve_len]]);
        let gathered =
            remove_gathered_local_outliers(n, listed, tests, &r.choices, &r.tips, &r.hooks);
        assert_eq!(r.stage.len(), edges.len());
        assert_eq!(gathered.unwrap().unwrap_or(listed.clone()), r.stage);
        let without =
            remove_gathered_local_outliers(n, listed, tests, &r.choices, &r.tips, &[]).unwrap();
        assert_eq!(without.map(|kept| kept.len()), Some(curve_len - 1));
        let beyond = remove_gathered_local_outliers(n, listed, tests, &[], &[], &[[0, n]]);
        assert!(matches!(
            beyond,
            Err(Error::InvalidParameter { name: "edge", .. })
        ));
    }

    /// Rule 4 on gathered edges keeps a piece that a junction joins to a kept curve, as the stage
    /// does (the stage's test's comb); gathered without the junction joins, the short tooth goes.
    /// A join is owned by its loose end.
    #[test]
    fn gathered_rule_4_keeps_what_a_junction_joins_as_the_stage_does() {
        let (pts, edges, end) = crate::test_graphs::comb_with_a_short_tooth();
        let r = rule_4_rows(&pts, &edges);
        let (n, listed, tests) = (r.n, &r.listed, &r.tests);
        assert!(r.hooks.is_empty());
        assert_eq!(r.junctions, vec![[13, 39], [15, end], [17, 59]]);
        let tri = crate::triangulate(&pts).unwrap();
        let graph = tri.graph_from_edges(edges.iter().copied());
        assert_eq!(
            junction_joins(&graph, |i| i != end),
            vec![[13, 39], [17, 59]]
        );
        let gathered =
            remove_gathered_local_outliers(n, listed, tests, &r.choices, &r.tips, &r.junctions);
        assert_eq!(r.stage.len(), edges.len());
        assert_eq!(gathered.unwrap().unwrap_or(listed.clone()), r.stage);
        let without =
            remove_gathered_local_outliers(n, listed, tests, &r.choices, &r.tips, &r.hooks);
        assert_eq!(
            without.unwrap().map(|kept| kept.len()),
            Some(edges.len() - 7)
        );
    }

    /// Rule 4 on gathered edges keeps a convex pupil whose corners leave it under three quarters
    /// passing, and drops one that turns back at a sample, as the stage does: the turns read
    /// from the tiles' rows, whichever way a cycle is walked.
    #[test]
    fn gathered_rule_4_keeps_a_convex_ring_as_the_stage_does() {
        let ring = |radius: f64, count: usize, at: &dyn Fn(usize) -> f64| -> Vec<crate::Point> {
            (0..count)
                .map(|k| {
                    let t = core::f64::consts::TAU * k as f64 / count as f64;
                    let r = radius * at(k);
                    crate::Point::new(r * libm::cos(t), r * libm::sin(t))
                })
                .collect()
        };
        for (pupil, kept) in [
            ([1.3, 1.0, 1.0, 1.3, 1.0, 1.3, 1.0, 1.0], true),
            ([1.3, 1.0, 1.0, 1.3, 1.0, 1.0, 0.67, 1.0], false),
        ] {
            let mut pts = ring(10.0, 50, &|_| 1.0);
            pts.extend(ring(3.4, 18, &|_| 1.0));
            pts.extend(ring(1.5, 8, &|k| pupil[k]));
            let mut edges: Vec<[usize; 2]> = Vec::new();
            for (first, count) in [(0, 50), (50, 18), (68, 8)] {
                edges.extend((0..count).map(|k| [first + k, first + (k + 1) % count]));
            }
            // The cycles listed backwards too: a walk then starts the other way round, and the
            // rows' turns must not depend on it.
            let backwards: Vec<[usize; 2]> = edges.iter().rev().map(|&[a, b]| [b, a]).collect();
            for edges in [edges, backwards] {
                let r = rule_4_rows(&pts, &edges);
                let (n, listed, tests) = (r.n, &r.listed, &r.tests);
                let gathered =
                    remove_gathered_local_outliers(n, listed, tests, &r.choices, &r.tips, &r.hooks);
                assert_eq!(gathered.unwrap().unwrap_or(listed.clone()), r.stage);
                let pupil_edges = r.stage.iter().filter(|&&[a, _]| a >= 68).count();
                assert_eq!(pupil_edges, if kept { 8 } else { 0 });
            }
        }
    }

    /// The clump stage on gathered edges keeps a zig-zag piece that gap closing joins to a
    /// curve, as the stage does; gathered without the rows, the piece goes.
    #[test]
    fn gathered_clumps_keep_what_gap_closing_joins_as_the_stage_does() {
        let (pts, edges, curve_len) = crate::test_graphs::zig_zag_piece_in_a_gap();
        let tri = crate::triangulate(&pts).unwrap();
        let graph = tri.graph_from_edges(edges.iter().copied());
        let listed = graph.edges();
        let n = pts.len();
        let labels = component_labels(n, &listed).unwrap();
        let tests = clump_tests(&graph, &labels, |_| true).unwrap();
        assert!(gathered_clumps_found(n, &listed, &tests).unwrap());
        let choices = gap_choices(&graph, |_| true);
        let tips = tip_candidates(&graph, true, |_| true);
        let hooks = hook_joins(&graph, |_| true);
        let gathered = remove_gathered_clumps(n, &listed, &tests, &choices, &tips, &hooks).unwrap();
        assert_eq!(
            gathered.unwrap_or(listed.clone()),
            graph.remove_clumps().edges()
        );
        assert_eq!(graph.remove_clumps().num_edges(), edges.len());
        let without = remove_gathered_clumps(n, &listed, &tests, &[], &[], &[]).unwrap();
        assert_eq!(without.map(|kept| kept.len()), Some(curve_len - 1));
        // Rows naming a point beyond the set are refused by name, clumps or not.
        let mut row = choices[0];
        row[2] = n;
        let refused = remove_gathered_clumps(n, &listed, &tests, &[row], &[], &[]);
        assert!(matches!(
            refused,
            Err(Error::InvalidParameter { name: "choice", .. })
        ));
        let line: Vec<[usize; 2]> = (0..3).map(|i| [i, i + 1]).collect();
        let refused_tip = remove_gathered_clumps(n, &line, &tests, &[], &[[0, 1, 2, n]], &[]);
        assert!(matches!(
            refused_tip,
            Err(Error::InvalidParameter {
                name: "candidate",
                ..
            })
        ));
    }

    /// Found by a review of the public API: gap-closing rows naming a point without an edge (a
    /// stale row) read that point's missing edge as a position (a panic, index out of bounds);
    /// and an `n` of 2^29 or more tripped the curve graph's assertion. Such rows name no join;
    /// such an `n` is refused by name.
    #[test]
    fn gathered_gap_rows_that_fit_no_loose_end_join_nothing() {
        let mut row = [0; GAP_ROW];
        row[1] = 1; // point 0 joins the loose end 1, but 0 has no edge
        assert_eq!(close_gathered_gaps(2, &[], &[row]), Ok(None));
        assert_eq!(close_gathered_gaps(3, &[[1, 2]], &[row]), Ok(None));
        let tests = [0u8; 2];
        assert!(remove_gathered_local_outliers(2, &[], &tests, &[row], &[], &[]).is_ok());
        // A tip row whose loose end has no edge joins nothing either.
        assert!(remove_gathered_local_outliers(2, &[], &tests, &[], &[[0, 1, 1, 1]], &[]).is_ok());
        for n in [1 << 29, u32::MAX as usize] {
            let refused = Err(Error::InvalidParameter {
                name: "n",
                value: n as f64,
            });
            assert_eq!(close_gathered_gaps(n, &[], &[]), refused);
            assert_eq!(repair_gathered_tips(n, &[], &[]), refused);
        }
    }

    /// Found by a review of the public API: a gathered tip candidate whose loose end lies on a
    /// loop (or has no edge) sent the split test's walk round the loop forever. Such a row names
    /// no move; the edges stay.
    #[test]
    fn a_tip_candidate_whose_end_is_no_loose_end_makes_no_move() {
        // The loop 0-4-5; the chain 3-1-2-6 with its chord 1-2; the pieces 8-9 and 10-11, whose
        // ends 8 and 10 are loose; 7 has no edge.
        let edges = [
            [0, 4],
            [4, 5],
            [0, 5],
            [1, 2],
            [1, 3],
            [2, 6],
            [8, 9],
            [10, 11],
        ];
        for row in [[0, 1, 2, 10], [7, 1, 2, 10], [8, 1, 2, 5]] {
            assert_eq!(
                repair_gathered_tips(12, &edges, &[row]),
                Ok(None),
                "{row:?}"
            );
        }
        // Loose ends on both sides move: the chord 1-2 gives way to 8-1 and 10-2.
        let moved = repair_gathered_tips(12, &edges, &[[8, 1, 2, 10]])
            .unwrap()
            .unwrap();
        assert!(moved.contains(&[1, 8]) && moved.contains(&[2, 10]) && !moved.contains(&[1, 2]));
    }

    /// The tips stage's apex beside a loose end, split in tiles: the tile's row names the move,
    /// and the gathered rule makes it as the stage does; a row that does not fit the gathered
    /// graph makes none.
    #[test]
    fn the_apex_beside_a_loose_end_is_gathered_as_the_stage_makes_it() {
        // A 40° tip whose sample 0 has no edge; point 1 (loose) is paired across to 2 on the other
        // side, and 9 begins its own side beyond it (the stage's test has the reasons).
        let t = 40f64.to_radians();
        let mut pts = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)];
        let along = |r: f64| Point::new(r * libm::cos(t), r * libm::sin(t));
        pts.extend((0..7).map(|k| along(1.532 + k as f64)));
        pts.extend((0..7).map(|k| Point::new(2.0 + k as f64, 0.0)));
        let mut edges: Vec<[usize; 2]> = (2..8).chain(9..15).map(|i| [i, i + 1]).collect();
        edges.push([1, 2]);
        let tri = triangulate(&pts).unwrap();
        let graph = tri.graph_from_edges(edges.iter().copied());
        let rows = tip_candidates(&graph, true, |_| true);
        assert!(rows.contains(&[0, 2, 1, 9]), "{rows:?}");
        let mut gathered = repair_gathered_tips(pts.len(), &edges, &rows)
            .unwrap()
            .unwrap();
        gathered.sort_unstable();
        let mut expected = graph.repair_tips().edges();
        expected.sort_unstable();
        assert_eq!(gathered, expected);
        assert!(gathered.contains(&[1, 9]) && !gathered.contains(&[1, 2]));
        // Rows that do not fit: 3 has edges; 3 is no loose end; 2 is not 1's neighbour.
        for row in [[3, 2, 1, 9], [0, 2, 3, 9], [0, 4, 1, 9]] {
            assert_eq!(
                repair_gathered_tips(pts.len(), &edges, &[row]),
                Ok(None),
                "{row:?}"
            );
        }
    }

    /// Points on two noisy arcs with strays, the local outlier removal's input and output on
    /// them.
    fn scene() -> (Vec<Point>, Vec<[usize; 2]>, Vec<[usize; 2]>) {
        let mut rng = crate::test_rng::Xorshift::new(5);
        let mut pts: Vec<Point> = (0..400)
            .map(|k| {
                let t = (k % 200) as f64 * 0.03;
                let r = if k < 200 { 10.0 } else { 14.0 };
                let (dx, dy) = (0.3 * rng.unit() - 0.15, 0.3 * rng.unit() - 0.15);
                Point::new(r * libm::cos(t) + dx, r * libm::sin(t) + dy)
            })
            .collect();
        pts.extend((0..40).map(|_| Point::new(30.0 * rng.unit() - 15.0, 30.0 * rng.unit())));
        let params = crate::Params::default();
        let tri = triangulate(&pts).unwrap();
        let repaired = tri
            .proximity_graph(params.uniformity)
            .unwrap()
            .repair(params.repair);
        let cut = repaired.remove_outliers(1.5).unwrap().graph;
        let local = cut.remove_local_outliers(&repaired);
        (pts, cut.edges(), local.edges())
    }

    #[test]
    fn component_names_are_names_not_places() {
        // A tile is sent the whole set's names, which run past its own points: the tests must
        // read them only as equal or not.
        let (pts, _, after) = scene();
        // As if the outer arc's edges had all been given back.
        let before: Vec<[usize; 2]> = after.iter().copied().filter(|e| e[0] < 200).collect();
        let tri = triangulate(&pts).unwrap();
        let graph = tri.graph_from_edges(after.iter().copied());
        let labels = component_labels(pts.len(), &after).unwrap();
        let far: Vec<u32> = labels.iter().map(|&l| 3 * l + 1_000_000).collect();
        let all = |_| true;
        let tests = clump_tests(&graph, &labels, all).unwrap();
        assert_eq!(tests, clump_tests(&graph, &far, all).unwrap());
        // A tile asks only for its own points: theirs are the same, the others 0.
        let some = |i: usize| i % 3 == 0;
        let asked = clump_tests(&graph, &labels, some).unwrap();
        assert!(tests.iter().filter(|&&t| t != 0).count() > pts.len() / 2);
        for (i, (&t, &a)) in tests.iter().zip(&asked).enumerate() {
            assert_eq!(a, if some(i) { t } else { 0 });
        }
        let (names, status) = given_back_standing(pts.len(), &after, &before)
            .unwrap()
            .unwrap();
        let far: Vec<u32> = names.iter().map(|&l| 3 * l + 1_000_000).collect();
        assert!(status.contains(&2));
        let tests = given_back_tests(&graph, &names, &status, all).unwrap();
        assert_eq!(tests, given_back_tests(&graph, &far, &status, all).unwrap());
        assert!(tests.contains(&1));
        let asked = given_back_tests(&graph, &names, &status, some).unwrap();
        for (i, (&t, &a)) in tests.iter().zip(&asked).enumerate() {
            assert_eq!(a, if some(i) { t } else { 0 });
        }
        // Too few labels or statuses are refused, not read past.
        assert!(clump_tests(&graph, &names[1..], all).is_err());
        assert!(given_back_tests(&graph, &names, &status[1..], all).is_err());
    }
}
