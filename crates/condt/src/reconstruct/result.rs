//! What a reconstruction leaves: the [`Reconstruction`], its [`StageReport`]s and [`Smoothing`],
//! and the tally of the last graph in input positions. It may not run a stage.

use super::history::History;
use super::params::Params;
use super::pipeline::{first_graph, on_worker, Stopwatch};
use crate::adjacency::{CurveGraph, Edge};
use crate::bits::IdBits;
use crate::curve::{curves_in_input_positions, Curve};
use crate::geometry::Point;
use crate::graph::Graph;
use crate::mesh::VertexId;
use crate::prefetch::PREFETCH_FROM;
use crate::stages::Stage;
use crate::threads::{mapped, sort_unstable_by_key};
use crate::triangulate::Triangulation;
#[cfg(doc)]
use crate::{reconstruct, reconstruct_owned};
use alloc::borrow::Cow;
use alloc::vec::Vec;
use core::time::Duration;

/// Everything a reconstruction computed, stage by stage, in input positions. Exact duplicates
/// are one point, under its smallest input position ([`Triangulation::vertex`]).
///
/// ```
/// use condt::{reconstruct, Params, Point, Stage};
/// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.1)].map(Point::from);
/// let result = reconstruct(&pts, &Params::default())?;
/// let first = result.stages().next().unwrap();
/// assert!(first.stage == Stage::Proximity && first.applied);
/// assert_eq!(result.stages().count(), Params::default().stages().len());
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone)]
pub struct Reconstruction {
    pub(super) params: Params,
    pub(super) triangulation: Triangulation,
    pub(super) history: History,
    /// The last stage's output, from which the history gives back every earlier stage's.
    pub(super) final_edges: Vec<Edge>,
    /// The final edges, sorted, in input positions (32-bit, as the kernel stores indices).
    pub(super) edges: Vec<[u32; 2]>,
    pub(super) degrees: Degrees,
    pub(super) curves: Vec<Curve>,
    pub(super) unused: Vec<usize>,
    pub(super) triangulation_time: Duration,
    pub(super) curves_time: Duration,
    pub(super) smoothing: Option<Smoothing>,
}

/// A summary, as [`Triangulation`]'s: every field printed was about 60 bytes a point (1.2 MB
/// for 20,000 points, an integrator's review), its edges in vertex ids that read like input
/// positions. The edges themselves: [`Reconstruction::edges`].
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// let shown = format!("{:?}", reconstruct(&square, &Params::paper())?);
/// assert_eq!(shown, "Reconstruction { points: 4, edges: 4, curves: 1, unused: 0, .. }");
/// # Ok::<(), condt::Error>(())
/// ```
impl core::fmt::Debug for Reconstruction {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Reconstruction")
            .field("points", &self.triangulation.num_points())
            .field("edges", &self.edges.len())
            .field("curves", &self.curves.len())
            .field("unused", &self.unused.len())
            .finish_non_exhaustive()
    }
}

/// What the smoothing passes ([`Params::smooth`]) did ([`Reconstruction::smoothing`]).
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// // 30 samples on three quarters of a circle, every other one 4 % out: loose ends, so passes run.
/// let t = |k: usize| k as f64 * 1.5 * std::f64::consts::PI / 29.0;
/// let r = |k: usize| if k % 2 == 0 { 1.04 } else { 1.0 };
/// let p: Vec<Point> = (0..30).map(|k| Point::new(r(k) * t(k).cos(), r(k) * t(k).sin())).collect();
/// let result = reconstruct(&p, &Params::default())?;
/// assert!(result.smoothing().is_some_and(|s| s.passes >= 1 && s.moved > 0));
/// assert_ne!(result.stage_point(2), p[2]);
/// assert_eq!(result.curves().len(), 1);
/// assert!(reconstruct(&p, &Params::paper())?.smoothing().is_none());
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Smoothing {
    /// How many passes ran (at least one); the result is the last one's.
    pub passes: usize,
    /// How many points the last pass moved (from the positions the pass before it saw, both
    /// relative to the set's corner: see [`Reconstruction::stage_point`] for the points it did
    /// not move).
    pub moved: usize,
    /// Wall-clock time of the first reconstruction, every pass but the last, and every smoothing
    /// (zero without `std` and on `wasm32-unknown-unknown`); the result's stage and triangulation
    /// times are the last pass's.
    pub earlier_passes: Duration,
}

/// One stage of a [`Reconstruction`], as [`Reconstruction::stages`] reports it.
///
/// ```
/// use condt::{reconstruct, Params, Point, Stage};
/// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
/// let result = reconstruct(&pts, &Params::paper())?;
/// let report = result.stage(Stage::Repair).unwrap();
/// assert!(!report.applied && report.graph.num_edges() == 3);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct StageReport<'r> {
    /// Which stage.
    pub stage: Stage,
    /// The graph it left.
    pub graph: Graph<'r>,
    /// Whether its rule applied (a vertex needed repair, an outlier rule fired); always at first.
    pub applied: bool,
    /// Its wall-clock time (zero without `std` and on `wasm32-unknown-unknown`).
    pub time: Duration,
}

/// How many times two points must lie nearer each other than either lies to any other point
/// for [`Reconstruction::twin_pairs`] to take them for one point given twice: Algorithm 1
/// already cuts a second edge 2.75 times (`u`) the first; sixteen is far past what noise makes
/// where twins are tens to thousands of times closer. Chance makes such pairs too: along curves
/// sampled at random, a gap `d` has no other sample within `16d` on either side with
/// probability `exp(-2 · 16 λd)` (density `λ`), which over the gaps' exponential law is one gap
/// in `2 · 16 + 1`; scattered in the plane, one point in `2 · 16²`. So pairs alone prove
/// nothing (the outlier cases of the evaluation suites have up to 25).
const TWIN_RATIO: f64 = 16.0;

/// Pairs that lie beside pairs, in at most one in this many points, are what chance makes: a
/// curve given twice makes every pair one (each sample's neighbours along the curve have their
/// twins too), where pairs that chance makes lie apart. A pair counts when each of its two
/// points has a point of another pair among its Delaunay neighbours. Measured: one such pair
/// in 425 to 667 points along sines sampled at random (20,000 points, three seeds, `--paper`
/// and `--no-smooth`; fewer with the smoothing passes), none in the evaluation
/// suites or `../shared/data`, 3 in `scripts/scale.py`'s 1M uniform random points; against
/// every pair of a circle given twice and 29 of 29 for two squares sharing a side given
/// twice. (Counting a pair with one such point, against one in 256 points, fired on randomly
/// sampled curves without the smoothing passes: a diff review.)
const TWINS_BESIDE_BY_CHANCE: usize = 64;

impl Reconstruction {
    /// The parameters it ran with: those given, but for what could not run (smoothing passes
    /// on a triangulation given or with a baseline method, threads where none can start on a
    /// set of 65,536 points or more; below that no step uses threads and none is asked for).
    ///
    /// ```
    /// use condt::{reconstruct, reconstruct_triangulation, triangulate, Method, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.params().outlier_factor, Some(1.7));
    /// assert!(reconstruct(&pts, &Params::default())?.params().smooth);
    /// let given = reconstruct_triangulation(triangulate(&pts)?, &Params::default())?;
    /// assert!(!given.params().smooth && given.smoothing().is_none());
    /// let baseline = Params::default().with_method(Method::NnCrust);
    /// assert!(!reconstruct(&pts, &baseline)?.params().smooth);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// What the smoothing pass did, or `None` when it did not run ([`Params::smooth`]).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// assert!(reconstruct(&pts, &Params::paper())?.smoothing().is_none()); // smoothing is off
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn smoothing(&self) -> Option<Smoothing> {
        self.smoothing
    }

    /// The Delaunay triangulation the stages walked (of the moved points after smoothing passes).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.triangulation().triangles().count(), 1);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangulation(&self) -> &Triangulation {
        &self.triangulation
    }

    /// The stages in the order they ran ([`Params::stages`]), each graph rebuilt from the final one
    /// in O(edges) per later stage (only changes are kept); the proximity graph may be recomputed.
    /// `len()` counts them without rebuilding any (`count()` would rebuild each).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert!(result.stages().map(|r| r.stage).eq(Params::paper().stages()));
    /// assert_eq!(result.stages().len(), 3);
    /// assert!(result.stages().all(|r| r.graph.num_edges() == 3));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn stages(&self) -> impl ExactSizeIterator<Item = StageReport<'_>> + '_ {
        (0..self.history.records.len()).map(move |k| self.report(k))
    }

    /// The report of `stage`, or `None` when it did not run. Only its graph is rebuilt.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point, Stage};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.stage(Stage::Outliers).map(|r| r.graph.num_edges()), Some(3));
    /// assert!(result.stage(Stage::Gaps).is_none()); // not in the paper's pipeline
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn stage(&self, stage: Stage) -> Option<StageReport<'_>> {
        Some(self.report(self.history.position(stage)?))
    }

    /// Each stage that ran and its wall-clock time (zero without `std` and on
    /// `wasm32-unknown-unknown`), graphs not rebuilt.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::default())?;
    /// assert!(result.stage_times().map(|(stage, _)| stage).eq(Params::default().stages()));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn stage_times(&self) -> impl ExactSizeIterator<Item = (Stage, Duration)> + '_ {
        self.history
            .records
            .iter()
            .map(|record| (record.stage, record.time))
    }

    /// The report of the `k`-th stage that ran, its graph rebuilt from the final one.
    pub(crate) fn report(&self, k: usize) -> StageReport<'_> {
        let first = || first_graph(&self.triangulation, &self.params);
        let edges = self.history.output_of(&self.final_edges, k, &first);
        self.history.records[k].report(k, Graph::new(&self.triangulation, edges))
    }

    /// The final graph, as the last stage left it.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.graph().edges(), result.edges().collect::<Vec<_>>());
    /// assert_eq!(result.graph().curves(), result.curves());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn graph(&self) -> Graph<'_> {
        Graph::new(&self.triangulation, Cow::Borrowed(&self.final_edges))
    }

    /// The final edges as input positions `[a, b]`, `a < b`, sorted.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.edges().collect::<Vec<_>>(), vec![[0, 1], [0, 2], [1, 2]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn edges(&self) -> impl ExactSizeIterator<Item = [usize; 2]> + Clone + '_ {
        self.edges.iter().map(|&[a, b]| [a as usize, b as usize])
    }

    /// The final edges as [`Reconstruction::edges`] gives them, as the slice kept (for writers).
    ///
    /// ```
    /// # use condt::{reconstruct, Params, Point};
    /// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
    /// let result = reconstruct(&square, &Params::default())?;
    /// assert_eq!(result.edge_list(), [[0, 1], [0, 3], [1, 2], [2, 3]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn edge_list(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// The curves, in input positions, sorted; see [`Graph::curves`] and, for where a curve
    /// starts and ends, [`curves_from_edges`](crate::curves_from_edges). An exact duplicate is
    /// on them under its point's first position only ([`Reconstruction::unused`] says more).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.curves().len(), 1);
    /// assert_eq!(result.curves()[0].points().collect::<Vec<_>>(), vec![0, 1, 2, 3]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn curves(&self) -> &[Curve] {
        &self.curves
    }

    /// Pairs of points that look like one point given twice a little apart (a border exported
    /// from both sides with a small disagreement, a grey image's contour at a level): the two lie
    /// 16 times nearer each other than either lies to any other point (the last run's
    /// positions), and at least three pairs, and more than one in 64 points, lie beside other
    /// pairs, as a curve given twice has them (each point with a point of another pair among its
    /// Delaunay neighbours): chance makes pairs, but apart. Whatever the stages made of a pair
    /// (a curve of two points, two unused points, a spur), it is one, unless a curve runs
    /// through both of its points (each with two edges or more). Each pair's two input
    /// positions, the lower first, ascending; empty when the pattern is missing.
    /// [`snap`](crate::snap) merges points within a distance.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// // A wavy ring given twice, the second copy a millionth off.
    /// let ring = |shift: f64| {
    ///     (0..60).map(move |k| {
    ///         let t = k as f64 * std::f64::consts::TAU / 60.0;
    ///         Point::new(10.0 * t.cos() + 0.3 * (5.0 * t).sin() + shift, 10.0 * t.sin())
    ///     })
    /// };
    /// let twice: Vec<Point> = ring(0.0).chain(ring(1e-6)).collect();
    /// assert_eq!(reconstruct(&twice, &Params::default())?.twin_pairs()[0], [0, 60]);
    /// let once: Vec<Point> = ring(0.0).collect();
    /// assert!(reconstruct(&once, &Params::default())?.twin_pairs().is_empty());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn twin_pairs(&self) -> Vec<[usize; 2]> {
        let tri = &self.triangulation;
        let mesh = tri.mesh();
        // In the stages' frame, whose squared lengths neither overflow nor underflow at any
        // scale (a diff review: in the input's units twins 1e-170 apart squared to 0, and pairs
        // 1e160 apart to infinity, all "16 times nearer").
        let points = tri.vertex_points();
        // The nearest neighbour of `a` when every other lies 16 times farther. The nearest
        // point is a Delaunay neighbour; the second nearest is taken among them too.
        let alone_with = |a: VertexId| -> Option<VertexId> {
            let at = points[a.index()];
            let (mut nearest, mut first, mut second) = (a, f64::INFINITY, f64::INFINITY);
            for w in mesh.neighbors(a) {
                let d2 = at.dist2(points[w.index()]);
                if d2 < first {
                    (nearest, first, second) = (w, d2, first);
                } else if d2 < second {
                    second = d2;
                }
            }
            (first > 0.0 && second >= TWIN_RATIO * TWIN_RATIO * first).then_some(nearest)
        };
        // Only points with at most one edge are asked, which keeps the walk off the curves'
        // points, and in vertex order, the triangulation's spatial one, which keeps the walks
        // in cache: 2 ms on 1M points along curves, 85 ms on 1M uniform points (every point's
        // ring by input positions took 0.1 s of a 0.45 s run along curves; those with at most
        // one edge, by input positions, 0.2 s of 5 s on uniform points). Algorithm 1 keeps no
        // second edge at a twin where `u` is fixed below 16 (the default's 2.75): a pair starts
        // as a piece of its own, unused or a curve of two points, or a spur once a later step
        // joins one of its points; it is missed only where later steps (or an adaptive `u`)
        // give both points two edges or more, a curve running through both, which reads them.
        let asked = |v: VertexId| self.degrees.get(tri.input_of(v)) <= 1;
        let mut twins: Vec<[usize; 2]> = (0..points.len())
            .map(|v| VertexId::new(v as u32))
            .filter(|&a| asked(a) && tri.is_vertex(a))
            .filter_map(|a| {
                let b = alone_with(a)?;
                // A pair both of whose points are asked is listed once, from its lower id.
                let listed_from_b = b < a && asked(b);
                let [i, j] = [tri.input_of(a), tri.input_of(b)];
                (!listed_from_b && alone_with(b) == Some(a)).then_some([i.min(j), i.max(j)])
            })
            .collect();
        twins.sort_unstable();
        // Three pairs beside pairs are a pattern, unless the points are so many that chance
        // makes them.
        let n = self.num_points();
        let beside = {
            let twin = IdBits::of(twins.iter().flatten().copied());
            let beside_a_twin =
                |a: usize, b: usize| tri.neighbors(a).any(|w| w != b && twin.contains(w));
            twins
                .iter()
                .filter(|&&[a, b]| beside_a_twin(a, b) && beside_a_twin(b, a))
                .count()
        };
        if beside >= 3 && beside * TWINS_BESIDE_BY_CHANCE > n {
            twins
        } else {
            Vec::new()
        }
    }

    /// Input positions whose point ended with no edge (outliers), ascending, exact duplicates of
    /// such a point included. The curves and edges name a point by its first position
    /// ([`Triangulation::first_at`]), so a duplicate of a point with edges is in none of them:
    /// every input position is on a curve, unused, or such a duplicate
    /// ([`Triangulation::merged`] lists them).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
    /// pts.push(Point::new(10.0, 50.0));
    /// assert_eq!(reconstruct(&pts, &Params::default())?.unused(), [21]);
    /// // Point 22 repeats point 5 (on the line), point 23 repeats the outlier 21.
    /// pts.extend([pts[5], pts[21]]);
    /// let result = reconstruct(&pts, &Params::default())?;
    /// assert_eq!(result.unused(), [21, 23]);
    /// let on_curves = |i| result.curves().iter().any(|c| c.points().any(|p| p == i));
    /// assert!(on_curves(5) && !on_curves(22));
    /// let merged: Vec<[usize; 2]> = result.triangulation().merged().collect();
    /// assert_eq!(merged, [[22, 5], [23, 21]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn unused(&self) -> &[usize] {
        &self.unused
    }

    /// The final degree of input point `index` (duplicates share their point's degree).
    ///
    /// # Panics
    /// If `index` is not an input position.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
    /// pts.push(Point::new(10.0, 50.0));
    /// let result = reconstruct(&pts, &Params::default())?;
    /// assert_eq!([0, 10, 21].map(|i| result.degree(i)), [1, 2, 0]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn degree(&self, index: usize) -> usize {
        self.degrees.get(index)
    }

    /// Input point `index` as the stages saw it, moved if smoothing passes ran. The input stays the
    /// caller's ([`reconstruct`], [`reconstruct_owned`]): a copy would cost a tenth of the peak.
    /// A pass places every point relative to the set's lower-left corner (so that a translated
    /// set is smoothed alike: docs/condt.md, *Smoothing passes*), and `(p - corner) + corner`
    /// can round: after a pass, a point the pass did not move (an end, a branch, an unused
    /// point) may read a unit in the last place off its input, which
    /// [`Smoothing::moved`] does not count.
    ///
    /// # Panics
    /// If `index` is not an input position.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?; // no smoothing: no point moves
    /// assert!((0..3).all(|i| result.stage_point(i) == pts[i]));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn stage_point(&self, index: usize) -> Point {
        self.triangulation.point(index)
    }

    /// Number of input points.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (0.0, 0.0)].map(Point::from);
    /// assert_eq!(reconstruct(&pts, &Params::paper())?.num_points(), 4); // duplicates included
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn num_points(&self) -> usize {
        self.degrees.len()
    }

    /// Wall-clock time of the triangulation (zero without `std` and on `wasm32-unknown-unknown`).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// let time = result.triangulation_time();
    /// assert!(result.timings().any(|step| step == ("triangulation", time)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangulation_time(&self) -> Duration {
        self.triangulation_time
    }

    /// Wall-clock time of the curve assembly and final tally (zero without `std` and on
    /// `wasm32-unknown-unknown`).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// assert_eq!(result.timings().last(), Some(("curves", result.curves_time())));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn curves_time(&self) -> Duration {
        self.curves_time
    }

    /// Each timed step in the order it ran, named by the words of `condt reconstruct --timings`:
    /// `earlier-passes` when smoothing passes ran (the first reconstruction and every pass but
    /// the last), `triangulation`, each stage's [`Stage::key`], and `curves` (the assembly and
    /// tally). Wall-clock times, zero without `std` and on `wasm32-unknown-unknown`.
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::paper())?;
    /// let steps: Vec<&str> = result.timings().map(|(step, _)| step).collect();
    /// assert_eq!(steps, ["triangulation", "proximity", "repair", "iqr-outliers", "curves"]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn timings(&self) -> impl Iterator<Item = (&'static str, Duration)> + '_ {
        let earlier = self.smoothing.map(|s| ("earlier-passes", s.earlier_passes));
        let stages = self.stage_times().map(|(stage, time)| (stage.key(), time));
        earlier
            .into_iter()
            .chain([("triangulation", self.triangulation_time)])
            .chain(stages)
            .chain([("curves", self.curves_time)])
    }

    /// Assembles the curves of a run that waited, `graph` the curve graph of its final edges.
    pub(super) fn assemble_curves(&mut self, graph: CurveGraph) {
        debug_assert!(graph == CurveGraph::new(self.triangulation.num_points(), &self.final_edges));
        let mut clock = Stopwatch::start();
        let tri = &self.triangulation;
        let assemble = || curves_in_input_positions(tri, &graph);
        self.curves = on_worker(self.params.parallel, tri.num_points(), assemble);
        drop(graph);
        self.curves_time += clock.lap();
    }

    /// The triangulation and triangulation time; the rest is freed here (a partial move would
    /// keep it until the variable is assigned again, after the next pass).
    pub(super) fn into_last_triangulation(self) -> (Triangulation, Duration) {
        (self.triangulation, self.triangulation_time)
    }
}

/// The degree of every input point in a byte, the rare degree above 254 in a sorted side list
/// (memory: the list is alive at the last step's peak).
#[derive(Clone, Default)]
pub(super) struct Degrees {
    /// The degree, or [`Degrees::LARGE`] when it is in `large`.
    small: Vec<u8>,
    /// `(input position, degree)` of every degree from [`Degrees::LARGE`] up, by position.
    pub(super) large: Vec<(u32, u32)>,
}

impl Degrees {
    /// Empty, with room for `n` input positions, taken by the calling thread. Reason: memory;
    /// [`degrees_of`] may run beside the curves on another thread, whose own malloc arena (glibc)
    /// would take the block from the system anew.
    pub(super) fn with_room(n: usize) -> Degrees {
        Degrees {
            small: Vec::with_capacity(n),
            large: Vec::new(),
        }
    }

    const LARGE: u8 = u8::MAX;

    /// Appends the degree of the next input position.
    pub(super) fn push(&mut self, degree: usize) {
        match u8::try_from(degree) {
            Ok(small) if small < Self::LARGE => self.small.push(small),
            _ => {
                let position = self.small.len() as u32;
                self.large.push((position, degree as u32));
                self.small.push(Self::LARGE);
            }
        }
    }

    pub(super) fn get(&self, index: usize) -> usize {
        match self.small[index] {
            Self::LARGE => {
                let at = self
                    .large
                    .binary_search_by_key(&(index as u32), |&(position, _)| position);
                // Every LARGE byte has its entry: `push` writes both.
                debug_assert!(at.is_ok(), "degree {index} missing from the side list");
                at.map_or(usize::from(Self::LARGE), |k| self.large[k].1 as usize)
            }
            small => usize::from(small),
        }
    }

    pub(super) fn len(&self) -> usize {
        self.small.len()
    }

    pub(super) fn iter(&self) -> impl ExactSizeIterator<Item = usize> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }
}

/// The degrees as a list.
impl core::fmt::Debug for Degrees {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// How far ahead [`degrees_of`] prefetches records.
const DEGREES_PREFETCH: usize = 32;

/// Each input position's degree in a run's final curve graph, into `room`
/// ([`Degrees::with_room`]), and the positions without edges.
pub(super) fn degrees_of(
    tri: &Triangulation,
    graph: &CurveGraph,
    mut room: Degrees,
) -> (Degrees, Vec<usize>) {
    let mut unused = Vec::new();
    let order = tri.input_to_vertex();
    let prefetching = order.len() >= PREFETCH_FROM;
    for (i, &v) in order.iter().enumerate() {
        // On shuffled input each record misses.
        if let Some(&later) = order.get(i + DEGREES_PREFETCH).filter(|_| prefetching) {
            graph.prefetch(later);
        }
        let degree = graph.degree(v);
        room.push(degree);
        if degree == 0 {
            unused.push(i);
        }
    }
    // Grown by doubling: up to half of it was room, kept by the result (memory).
    unused.shrink_to_fit();
    (room, unused)
}

/// A run's final edges `last` (vertex ids) in input positions, sorted, each under its smaller
/// position. Read from the list, not from the curve graph: the last run frees its graph first, so
/// that the graph's 8 bytes a point are not alive beside these (memory: the run's peak).
pub(super) fn edges_in_input_positions(
    tri: &Triangulation,
    last: &[Edge],
    parallel: bool,
) -> Vec<[u32; 2]> {
    let in_positions = |e: &Edge| {
        let [i, j] = e.map(|v| tri.input_of(v) as u32);
        [i.min(j), i.max(j)]
    };
    let mut edges = mapped(last, in_positions, parallel);
    let n = tri.num_points();
    if n < COUNTED_BELOW {
        return counted(&edges, n);
    }
    // As one 64-bit key, the order of the pairs (speed: one comparison).
    let key = |&[i, j]: &[u32; 2]| (u64::from(i) << 32) | u64::from(j);
    sort_unstable_by_key(&mut edges, key, parallel);
    edges
}

/// Fewest points whose final edges [`edges_in_input_positions`] sorts by comparisons: below it
/// the counts and the pairs fit the second-level cache and [`counted`] takes about a tenth of
/// the sort's instructions; at 1M its scattered writes miss the cache and gain nothing
/// (docs/perf-log.md, *Rule 1's cut edges listed once; a bucketed sort of the final edges
/// dropped*), and it would hold a second list of the edges.
const COUNTED_BELOW: usize = 1 << 16;

/// `edges` (pairs of positions below `n`, distinct) sorted: a count per smaller position, each
/// pair written into its position's range, each range (a point's few edges) sorted.
fn counted(edges: &[[u32; 2]], n: usize) -> Vec<[u32; 2]> {
    // `ends[i + 1]` counts the pairs under `i`, then (summed) ends `i`'s range.
    let mut ends = alloc::vec![0u32; n + 1];
    for &[i, _] in edges {
        ends[i as usize + 1] += 1;
    }
    for i in 1..=n {
        ends[i] += ends[i - 1];
    }
    let mut sorted = alloc::vec![[0u32; 2]; edges.len()];
    // `ends[i]` walks from the start of `i`'s range (the end of `i - 1`'s) to its end.
    for &pair in edges {
        let at = &mut ends[pair[0] as usize];
        sorted[*at as usize] = pair;
        *at += 1;
    }
    let mut start = 0;
    for &end in &ends[..n] {
        sorted[start..end as usize].sort_unstable();
        start = end as usize;
    }
    sorted
}

#[cfg(test)]
mod tests {
    use super::counted;
    use alloc::vec::Vec;

    /// The counting sort gives the comparison sort's order: distinct pairs in a scrambled order,
    /// with one position holding many (a hub) and many holding none.
    #[test]
    fn counted_pairs_are_sorted_as_by_comparison() {
        let n = 500u32;
        let mut pairs: Vec<[u32; 2]> = (1..n).map(|j| [7, j]).filter(|p| p[0] < p[1]).collect();
        pairs.extend((0..n - 1).step_by(3).map(|i| [i, i + 1]));
        pairs.sort_unstable();
        pairs.dedup();
        let mut scrambled = pairs.clone();
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        for k in (1..scrambled.len()).rev() {
            scrambled.swap(k, rng.below(k as u64 + 1) as usize);
        }
        assert_ne!(scrambled, pairs);
        assert_eq!(counted(&scrambled, n as usize), pairs);
        assert_eq!(counted(&[], 0), Vec::<[u32; 2]>::new());
    }
}
