//! [`Graph`]: a stage's edges in input positions, and the methods a user chains to run the stages
//! one at a time. It may not implement a stage's rule ([`crate::stages`]) nor order the stages.

use crate::adjacency::{degrees, ordered, sort_pairs, CurveGraph, Edge};
use crate::curve::{curves_in_input_positions, Curve};
use crate::error::Error;
use crate::stages::outliers::IqrRule;
use crate::stages::{proximity, Earlier, Repair, Step, Uniformity};
use crate::triangulate::Triangulation;
use alloc::borrow::Cow;
use alloc::vec::Vec;

/// A stage's edges on its triangulation, read in input positions; stage methods return new graphs.
///
/// ```
/// use condt::{triangulate, Point, Repair};
/// let pts = [(0.0, 0.0), (1.0, 0.0), (-1.1, 0.0), (0.0, 1.2), (0.0, -1.3)].map(Point::from);
/// let tri = triangulate(&pts)?;
/// let all_four = tri.graph_from_edges([[0, 1], [0, 2], [0, 3], [0, 4]]);
/// assert_eq!(all_four.degrees()[0], 4);
/// // The paper's repair keeps the shortest edge and one partner beyond 120 degrees.
/// assert_eq!(all_four.repair(Repair::Paper).edges(), vec![[0, 1], [0, 2]]);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone)]
pub struct Graph<'t> {
    tri: &'t Triangulation,
    /// Each edge once, `[a, b]` with `a < b`, in vertex ids, in the order the stage listed them.
    edges: Cow<'t, [Edge]>,
}

/// What [`Graph::remove_outliers`] (or [`Graph::remove_outliers_floored`]) did.
///
/// ```
/// use condt::{triangulate, Point, Uniformity};
/// let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
/// pts.push(Point::new(10.0, 6.0));
/// let tri = triangulate(&pts)?;
/// let removal = tri.proximity_graph(Uniformity::Fixed(2.75))?.remove_outliers(1.7)?;
/// assert!(removal.fired && removal.graph.degrees()[21] == 0);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct OutlierRemoval<'t> {
    /// The graph after the stage (the input itself when the rule did not fire).
    pub graph: Graph<'t>,
    /// Whether Algorithm 3's rule fired: some point had every edge longer than `2 √T`.
    pub fired: bool,
    /// The rule as it ran, for [`OutlierRemoval::repair_again`].
    rule: IqrRule,
}

impl<'t> OutlierRemoval<'t> {
    /// Repairs again without the cut edges ([`Params::repair_again`](crate::Params::repair_again)):
    /// `repaired` is this stage's input and `proximity` the repair's, `repair` as that ran. If
    /// this stage cut an edge (its graph differs from `repaired`; with the spacing floor the rule
    /// can fire and cut nothing), `proximity` less every edge above the cut's threshold, taken
    /// from `repaired`, repaired by `repair`; otherwise this stage's graph, as when `repaired` is
    /// empty. Other graphs than the documented ones give a graph, not the pipeline's.
    ///
    /// # Panics
    /// If `repaired` or `proximity` lives on another triangulation.
    ///
    /// ```
    /// use condt::{triangulate, Point, Repair, Uniformity};
    /// // A square outline, 10 points a side, an outlier off a corner and one far away.
    /// let side = |t: f64| [(t, 0.0), (10.0, t), (10.0 - t, 10.0), (0.0, 10.0 - t)];
    /// let mut pts: Vec<Point> = (0..10).flat_map(|k| side(k as f64)).map(Point::from).collect();
    /// pts.extend([Point::new(-0.9, -0.9), Point::new(30.0, 30.0)]);
    /// let tri = triangulate(&pts)?;
    /// let proximity = tri.proximity_graph(Uniformity::Fixed(2.75))?;
    /// let repaired = proximity.repair(Repair::Needs);
    /// let cut = repaired.remove_outliers(1.7)?;
    /// assert!(cut.fired);
    /// let again = cut.repair_again(&repaired, &proximity, Repair::Needs).edges();
    /// assert!(again.len() == 40 && again.iter().all(|&[a, b]| a < 40 && b < 40));
    /// // Given an empty graph for `repaired`: this stage's graph.
    /// let none = tri.graph_from_edges([]);
    /// assert_eq!(cut.repair_again(&none, &none, Repair::Needs).edges(), cut.graph.edges());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn repair_again(
        &self,
        repaired: &Graph<'t>,
        proximity: &Graph<'t>,
        repair: Repair,
    ) -> Graph<'t> {
        let this = &self.graph;
        this.assert_beside(&[repaired, proximity], "repair_again: the graphs");
        // An empty `repaired` (not this stage's input) has no quartiles to take a threshold from.
        if repaired.edges.is_empty() {
            return this.clone();
        }
        let step = Step::RepairAgain {
            rule: self.rule,
            mode: repair,
        };
        this.step_with(step, [&repaired.edges, &this.edges, &proximity.edges])
            .0
    }
}

/// Shows the size and the edges in input positions, not the whole triangulation it borrows.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
/// let graph = tri.graph_from_edges([[0, 1]]);
/// assert_eq!(format!("{graph:?}"), "Graph { num_edges: 1, edges: [[0, 1]] }");
/// # Ok::<(), condt::Error>(())
/// ```
impl core::fmt::Debug for Graph<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Graph")
            .field("num_edges", &self.num_edges())
            .field("edges", &self.edges())
            .finish()
    }
}

impl<'t> Graph<'t> {
    pub(crate) fn new(tri: &'t Triangulation, edges: Cow<'t, [Edge]>) -> Self {
        Graph { tri, edges }
    }

    /// The edges in vertex ids, in the stage's order (explanations run a stage again on them).
    pub(crate) fn listed(&self) -> &[Edge] {
        &self.edges
    }

    /// The triangulation the graph lives on.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let graph = tri.graph_from_edges([[0, 1]]);
    /// assert!(std::ptr::eq(graph.triangulation(), &tri));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangulation(&self) -> &'t Triangulation {
        self.tri
    }

    /// Number of edges.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.graph_from_edges([[0, 1], [1, 0], [1, 2]]).num_edges(), 2);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn num_edges(&self) -> usize {
        self.edges.len()
    }

    /// The edges as input positions `[a, b]`, `a < b`, sorted. O(n) with a counting sort.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.graph_from_edges([[2, 1], [1, 0]]).edges(), vec![[0, 1], [1, 2]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn edges(&self) -> Vec<[usize; 2]> {
        self.edges_u32()
            .into_iter()
            .map(|[a, b]| [a as usize, b as usize])
            .collect()
    }

    /// [`Graph::edges`] as 32-bit input positions: half the memory, for lists held at once
    /// (the provenance holds every stage's).
    pub(crate) fn edges_u32(&self) -> Vec<[u32; 2]> {
        let tri = self.tri;
        let pairs = self.edges.iter().map(|&[a, b]| {
            let (a, b) = (tri.input_of(a) as u32, tri.input_of(b) as u32);
            [a.min(b), a.max(b)]
        });
        sort_pairs(tri.num_points(), pairs, self.edges.len(), |a| a as usize)
    }

    /// The degree of every input point (exact duplicates share their point's degree).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (0.0, 0.0)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// assert_eq!(tri.graph_from_edges([[0, 1], [0, 2]]).degrees(), vec![2, 1, 1, 2]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn degrees(&self) -> Vec<usize> {
        let by_vertex = degrees(self.tri.num_points(), &self.edges);
        (0..self.tri.num_points())
            .map(|i| by_vertex[self.tri.vertex(i).index()] as usize)
            .collect()
    }

    /// Algorithm 2: the non-manifold repair, in the reading `repair` names.
    ///
    /// ```
    /// use condt::{triangulate, Point, Repair};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (-1.1, 0.0), (0.0, 1.2)].map(Point::from))?;
    /// let star = tri.graph_from_edges([[0, 1], [0, 2], [0, 3]]);
    /// assert_eq!(star.repair(Repair::Paper).edges(), vec![[0, 1], [0, 2]]);
    /// assert_eq!(star.repair(Repair::Off).num_edges(), 3);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn repair(&self, repair: Repair) -> Graph<'t> {
        self.step(Step::Repair(repair)).0
    }

    /// Algorithm 3: the IQR outlier removal with factor `k` (the paper uses 1.7).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] named `k` when `k` is NaN, infinite or negative.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&(0..6).map(|i| Point::new(i as f64, 0.0)).collect::<Vec<_>>())?;
    /// let even = tri.graph_from_edges((0..5).map(|i| [i, i + 1]));
    /// assert!(!even.remove_outliers(1.7)?.fired); // no edge stands out
    /// assert!(even.remove_outliers(f64::NAN).is_err());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn remove_outliers(&self, k: f64) -> Result<OutlierRemoval<'t>, Error> {
        self.cut(k, false)
    }

    /// Algorithm 3 with the spacing floor ([`Params::iqr_floor`](crate::Params::iqr_floor), the
    /// default's reading): it fires as [`Graph::remove_outliers`] does, but cuts no edge up to
    /// 1.5 times the median edge.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] named `k` when `k` is NaN, infinite or negative.
    ///
    /// ```
    /// use condt::{triangulate, Point, Uniformity};
    /// // Unit spacing along a line, the last three edges 4 % longer, and a point far above it.
    /// let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
    /// for p in &mut pts[18..] {
    ///     p.x = 17.0 + (p.x - 17.0) * 1.04;
    /// }
    /// pts.push(Point::new(10.0, 3.0));
    /// let tri = triangulate(&pts)?;
    /// let graph = tri.proximity_graph(Uniformity::Fixed(2.75))?;
    /// let (paper, floored) = (graph.remove_outliers(1.7)?, graph.remove_outliers_floored(1.7)?);
    /// assert!(paper.fired && floored.fired);
    /// assert!(!paper.graph.edges().contains(&[19, 20]));
    /// assert!(floored.graph.edges().contains(&[19, 20]));
    /// assert!(floored.graph.edges().iter().all(|e| !e.contains(&21)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn remove_outliers_floored(&self, k: f64) -> Result<OutlierRemoval<'t>, Error> {
        self.cut(k, true)
    }

    fn cut(&self, factor: f64, floor: bool) -> Result<OutlierRemoval<'t>, Error> {
        let rule = IqrRule { factor, floor };
        let step = Step::Outliers(rule);
        step.check()?;
        let (graph, fired) = self.step(step);
        Ok(OutlierRemoval { graph, fired, rule })
    }

    /// The local outlier removal ([`Params::local_outliers`](crate::Params::local_outliers)) on
    /// the IQR stage's output; `before_outliers` (its input, or this graph) holds the cut edges.
    ///
    /// # Panics
    /// If `before_outliers` lives on another triangulation.
    ///
    /// ```
    /// use condt::{triangulate, Point, Repair, Uniformity};
    /// let angles = (0..12).map(|k| k as f64 * std::f64::consts::TAU / 12.0);
    /// let mut pts: Vec<Point> = angles.map(|t| Point::new(t.cos(), t.sin())).collect();
    /// pts.extend([Point::new(6.0, 6.0), Point::new(6.3, 6.1)]);
    /// let tri = triangulate(&pts)?;
    /// let repaired = tri.proximity_graph(Uniformity::default())?.repair(Repair::Paper);
    /// let filtered = repaired.remove_outliers(1.7)?;
    /// assert!(filtered.graph.edges().contains(&[12, 13])); // a two-point "curve"
    /// assert_eq!(filtered.graph.remove_local_outliers(&repaired).num_edges(), 12); // the circle
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn remove_local_outliers(&self, before_outliers: &Graph<'t>) -> Graph<'t> {
        self.assert_beside(&[before_outliers], "remove_local_outliers: the two graphs");
        let earlier: [&[Edge]; 3] = [&before_outliers.edges, &self.edges, &self.edges];
        self.step_with(Step::LocalOutliers, earlier).0
    }

    /// Confirms given-back components, `before_local` being the local outlier removal's input
    /// ([`Params::confirm_given_back`](crate::Params::confirm_given_back)).
    ///
    /// # Panics
    /// If `before_local` lives on another triangulation.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // A chain of 14 points 0.3 apart, and two stray points 0.45 beside its middle.
    /// let wave = |k: f64| Point::new(0.3 * k, 0.01 * (1.7 * k).sin());
    /// let mut pts: Vec<Point> = (0..14).map(|k| wave(k as f64)).collect();
    /// pts.extend([Point::new(1.75, 0.45), Point::new(1.85, 0.46)]);
    /// let tri = triangulate(&pts)?;
    /// // Every chain edge given back, the strays unused: the chain lies in a scatter, and goes.
    /// let given = tri.graph_from_edges((0..13).map(|k| [k, k + 1]));
    /// assert!(given.confirm_given_back(&tri.graph_from_edges([])).edges().is_empty());
    /// // The stray points as a kept curve of their own: only unused points count, the chain stays.
    /// let before = tri.graph_from_edges([[14, 15]]);
    /// let given = tri.graph_from_edges((0..13).map(|k| [k, k + 1]).chain([[14, 15]]));
    /// assert_eq!(given.confirm_given_back(&before).edges().len(), 14);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn confirm_given_back(&self, before_local: &Graph<'t>) -> Graph<'t> {
        self.assert_beside(&[before_local], "confirm_given_back: the two graphs");
        let earlier: [&[Edge]; 3] = [&self.edges, &before_local.edges, &self.edges];
        self.step_with(Step::ConfirmGivenBack, earlier).0
    }

    /// Removes clump components ([`Params::clumps`](crate::Params::clumps)); never adds an edge.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // A smooth arc of 30 samples and, far away, a zig-zag of 6 (a sixth of the points
    /// // with edges: under the quarter).
    /// let on_arc = |k: f64| Point::new(10.0 * (0.1 * k).cos(), 10.0 * (0.1 * k).sin());
    /// let mut pts: Vec<Point> = (0..30).map(|k| on_arc(k as f64)).collect();
    /// pts.extend([(40.0, 0.0), (41.0, 1.0), (40.2, 1.1), (41.3, 2.0), (40.1, 2.2), (41.0, 3.1)]
    ///     .map(Point::from));
    /// let tri = triangulate(&pts)?;
    /// let graph = tri.graph_from_edges((0..29).chain(30..35).map(|i| [i, i + 1]));
    /// let arc: Vec<[usize; 2]> = (0..29).map(|i| [i, i + 1]).collect();
    /// assert_eq!(graph.remove_clumps().edges(), arc);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn remove_clumps(&self) -> Graph<'t> {
        self.step(Step::RemoveClumps).0
    }

    /// Closes gaps at loose ends ([`Params::close_gaps`](crate::Params::close_gaps)); adds only.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts: Vec<Point> = (0..6).map(|i| Point::new(i as f64, 0.1 * (i % 2) as f64)).collect();
    /// let tri = triangulate(&pts)?;
    /// let broken = tri.graph_from_edges([[0, 1], [1, 2], [3, 4], [4, 5]]);
    /// assert_eq!(broken.close_gaps().edges(), vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 5]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn close_gaps(&self) -> Graph<'t> {
        self.step(Step::CloseGaps).0
    }

    /// Joins loose ends at junctions ([`Params::junctions`](crate::Params::junctions)); removes
    /// only a chord that ran past a loose end at a junction, which takes its place.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // A line 0..=12 along y = 0 and a branch 13..=19 ending one sample above point 6: a T.
    /// let mut pts: Vec<Point> = (0..=12).map(|i| Point::new(i as f64, 0.0)).collect();
    /// pts.extend((1..=7).map(|k| Point::new(6.0, k as f64)));
    /// let tri = triangulate(&pts)?;
    /// let edges = (0..12).chain(13..19).map(|i| [i, i + 1]);
    /// let joined = tri.graph_from_edges(edges).join_junctions();
    /// assert_eq!(joined.num_edges(), 19);
    /// assert!(joined.edges().contains(&[6, 13]));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn join_junctions(&self) -> Graph<'t> {
        self.step(Step::JoinJunctions).0
    }

    /// Restores crossings read as two bends ([`Params::crossings`](crate::Params::crossings)):
    /// a chord between two neighbours of a bent passage gives way to the crossing's other arms.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // Two lines crossing at point 0 at 40°, arms of seven unit-spaced samples (1..=7 along +x,
    /// // 8..=14 at 40°, 15..=21 along -x, 22..=28 at 220°), read as two bends: 0 kept the first
    /// // two arms, and the first samples of the others (0.68 apart) were paired.
    /// let t = 40f64.to_radians();
    /// let arms = [(1.0, 0.0), (t.cos(), t.sin()), (-1.0, 0.0), (-t.cos(), -t.sin())];
    /// let mut pts = vec![Point::new(0.0, 0.0)];
    /// for (dx, dy) in arms {
    ///     pts.extend((1..=7).map(|i| Point::new(dx * i as f64, dy * i as f64)));
    /// }
    /// let tri = triangulate(&pts)?;
    /// let mut edges: Vec<[usize; 2]> = (0..4)
    ///     .flat_map(|k| (1..7).map(move |i| [7 * k + i, 7 * k + i + 1]))
    ///     .collect();
    /// edges.extend([[0, 1], [0, 8], [15, 22]]);
    /// let restored = tri.graph_from_edges(edges).restore_crossings().edges();
    /// assert!(restored.contains(&[0, 15]) && restored.contains(&[0, 22]));
    /// assert!(!restored.contains(&[15, 22]));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn restore_crossings(&self) -> Graph<'t> {
        self.step(Step::RestoreCrossings).0
    }

    /// Repairs sharp tips ([`Params::tips`](crate::Params::tips)): an edge pairing two samples of
    /// degree two gives way to edges to the loose ends beside it, or to a point without edges
    /// beside it that continues both sides evenly; an edge that is a loose end's only one gives
    /// way to the tip's sample and the loose end that end's side runs straight on to (its rule:
    /// `src/stages/tips.rs`). As in the default pipeline, a tip of two to five samples without
    /// edges is left to [`Graph::repair_spikes`], to be called next.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // Two lines 0.8 apart, unit-spaced: 0..=7 at (-k, 0), 8..=15 at (1 + k, 0), 16..=23 at
    /// // (0.8 + k, 0.8), 24..=31 at (-0.2 - k, 0.8). The graph follows each piece and pairs 0 with
    /// // 16 across the lines (a chord), leaving 8 and 24 as loose ends beside its two ends.
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
    /// let tips = tri.graph_from_edges(edges).repair_tips().edges();
    /// assert!(tips.contains(&[0, 8]) && tips.contains(&[16, 24]) && !tips.contains(&[0, 16]));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn repair_tips(&self) -> Graph<'t> {
        self.step(Step::RepairTips {
            spikes_follow: true,
        })
        .0
    }

    /// Puts back tips of several samples ([`Params::spikes`](crate::Params::spikes)): an edge
    /// across a sharp tip whose two to five samples have no edges gives way to the shortest path
    /// through them, when it is evenly spaced, smooth but at its apex, and one tip on one side of
    /// the edge; two loose ends with such samples between them are joined the same way (its
    /// rule: `src/stages/spikes.rs`).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // A star's spike: 0..=3 run up to the tip's base at (0, 0), its samples 4, 5 (the apex)
    /// // and 6 rise to (1, 3) and fall to 7 at (2, 0), and 8..=10 run down. The graph pairs 3
    /// // with 7 across the base and leaves the tip's samples without edges.
    /// let diagonal = |k: usize| Point::new(k as f64 - 3.0, k as f64 - 3.0);
    /// let mut pts: Vec<Point> = (0..4).map(diagonal).collect();
    /// pts.extend([(0.5, 1.5), (1.0, 3.0), (1.5, 1.5)].map(|(x, y)| Point::new(x, y)));
    /// pts.extend((0..4).map(|k| Point::new(2.0 + k as f64, -(k as f64))));
    /// let tri = triangulate(&pts)?;
    /// let edges = vec![[0, 1], [1, 2], [2, 3], [3, 7], [7, 8], [8, 9], [9, 10]];
    /// let spiked = tri.graph_from_edges(edges).repair_spikes().edges();
    /// assert!([[3, 4], [4, 5], [5, 6], [6, 7]].iter().all(|e| spiked.contains(e)));
    /// assert!(!spiked.contains(&[3, 7]));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn repair_spikes(&self) -> Graph<'t> {
        self.step(Step::RepairSpikes).0
    }

    /// Puts hooked loose ends back in line ([`Params::hooks`](crate::Params::hooks)): where a loose
    /// end `c` hangs from `b`, which the curve reached from `a` first, and `b` has a loose end or
    /// a point without edges beside it to run on to, `a b` gives way to `a c` and `b x` when no
    /// passage it makes is as sharp as the hook `a b c` (its rule: `src/stages/hooks.rs`).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // A curve along y = 0 (0..=5) steps up to y = 0.5 (6..=10), but its edges run from 4 to 6
    /// // and back to 5, a loose end; 7 starts the rest of the curve.
    /// let mut pts: Vec<Point> = (0..6).map(|k| Point::new(k as f64, 0.0)).collect();
    /// pts.extend((0..5).map(|k| Point::new(5.6 + k as f64, 0.5)));
    /// let tri = triangulate(&pts)?;
    /// let edges = vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 6], [5, 6], [7, 8], [8, 9], [9, 10]];
    /// let unhooked = tri.graph_from_edges(edges).unhook().edges();
    /// assert!(unhooked.contains(&[4, 5]) && unhooked.contains(&[6, 7]));
    /// assert!(!unhooked.contains(&[4, 6]));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn unhook(&self) -> Graph<'t> {
        self.step(Step::Unhook).0
    }

    /// Cuts outlier tails ([`Params::tails`](crate::Params::tails)): a chain of at most four
    /// points at a loose end whose joint is longer than 1.5 times the edge it joins and bends more
    /// than twice as sharply as the even run of five edges it hangs from (its rule:
    /// `src/stages/tails.rs`).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // Eight unit-spaced samples of a straight line (1..=8) and point 0, two spacings beyond
    /// // sample 1 and turned 60° off the line's way: an outlier hung on its end.
    /// let mut pts = vec![Point::new(-1.0, 1.732)];
    /// pts.extend((0..8).map(|k| Point::new(k as f64, 0.0)));
    /// let tri = triangulate(&pts)?;
    /// let edges: Vec<[usize; 2]> = (0..8).map(|i| [i, i + 1]).collect();
    /// let cut = tri.graph_from_edges(edges).cut_tails().edges();
    /// assert_eq!(cut, (1..8).map(|i| [i, i + 1]).collect::<Vec<_>>());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn cut_tails(&self) -> Graph<'t> {
        self.step(Step::CutTails).0
    }

    /// Cuts detours ([`Params::detours`](crate::Params::detours)): where two routes of at most
    /// four points between them join the same two points of three edges each, the route the curve
    /// runs into less straightly at both of those points goes, unless they disagree; and a loop of
    /// at most five points hung on a curve is opened at the edge the curve turns into more
    /// sharply (its rules: `src/stages/detours.rs`).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // Six unit-spaced samples of a line (0..=5) and point 6, two spacings off it above samples
    /// // 2 and 3 and joined to both: an outlier hung on the line (an ear).
    /// let mut pts: Vec<Point> = (0..6).map(|k| Point::new(k as f64, 0.0)).collect();
    /// pts.push(Point::new(2.5, 2.0));
    /// let tri = triangulate(&pts)?;
    /// let mut edges: Vec<[usize; 2]> = (0..5).map(|i| [i, i + 1]).collect();
    /// edges.extend([[2, 6], [3, 6]]);
    /// let cut = tri.graph_from_edges(edges).cut_detours().edges();
    /// assert_eq!(cut, (0..5).map(|i| [i, i + 1]).collect::<Vec<_>>());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn cut_detours(&self) -> Graph<'t> {
        self.step(Step::CutDetours).0
    }

    /// The curves through the graph in input positions, ordered as [`crate::curves_from_edges`]'s.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (3.0, 0.0)].map(Point::from))?;
    /// let curves = tri.graph_from_edges([[0, 1], [1, 2], [2, 0]]).curves();
    /// assert!(curves.len() == 1 && curves[0].is_closed() && curves[0].len() == 3);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn curves(&self) -> Vec<Curve> {
        let tri = self.tri;
        let graph = CurveGraph::new(tri.num_points(), &self.edges);
        curves_in_input_positions(tri, &graph)
    }

    /// Panics with "`which` live on different triangulations" unless `others` live on this one's.
    pub(crate) fn assert_beside(&self, others: &[&Graph<'t>], which: &str) {
        let beside = others.iter().all(|g| core::ptr::eq(self.tri, g.tri));
        assert!(beside, "{which} live on different triangulations");
    }

    /// Runs `step` (its parameter checked) and reports whether its rule applied.
    fn step(&self, step: Step) -> (Graph<'t>, bool) {
        self.step_with(step, [&self.edges; 3])
    }

    /// [`Graph::step`] reading the graphs before the IQR stage, the local outlier removal and the
    /// repair, in this order, where a step reads them (see `Step::run`).
    fn step_with(&self, step: Step, [outliers, local, repair]: [&[Edge]; 3]) -> (Graph<'t>, bool) {
        let earlier = Earlier {
            before_outliers: Cow::Borrowed(outliers),
            cut_by_outliers: None,
            before_local: Cow::Borrowed(local),
            before_repair: Cow::Borrowed(repair),
        };
        let parallel = crate::stages::worth_threads(self.tri.num_points());
        let edges = step
            .run(self.tri, &self.edges, earlier, None, parallel)
            .edges;
        let applied = edges.is_some();
        (self.changed_to(edges), applied)
    }

    /// The graph a stage's output `edges` make on this one's triangulation, or this graph when
    /// the stage changed nothing (`None`).
    pub(crate) fn changed_to(&self, edges: Option<Vec<Edge>>) -> Graph<'t> {
        edges.map_or_else(
            || self.clone(),
            |edges| Graph::new(self.tri, Cow::Owned(edges)),
        )
    }
}

/// The graph-level entry points, kept here so the kernel does not depend on the stages.
impl Triangulation {
    /// Algorithm 1: each point's shortest Delaunay edge, its second if the uniformity test passes.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] named `u` for a fixed `u` that is NaN, infinite or not positive.
    ///
    /// ```
    /// use condt::{triangulate, Point, Uniformity};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from))?;
    /// let graph = tri.proximity_graph(Uniformity::Fixed(2.75))?;
    /// assert_eq!(graph.edges(), vec![[0, 1], [0, 3], [1, 2], [2, 3]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn proximity_graph(&self, uniformity: Uniformity) -> Result<Graph<'_>, Error> {
        uniformity.check()?;
        let parallel = crate::stages::worth_threads(self.num_points());
        let edges = proximity::proximity_graph(self, uniformity, parallel);
        Ok(Graph::new(self, Cow::Owned(edges)))
    }

    /// A graph of your own on this triangulation, to run a stage on: `edges` are input positions,
    /// either way round, Delaunay or not; repeats, loops and positions out of range are ignored.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let graph = tri.graph_from_edges([[1, 0], [0, 1], [2, 2], [2, 7], [1, 2]]);
    /// assert_eq!(graph.edges(), vec![[0, 1], [1, 2]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn graph_from_edges(&self, edges: impl IntoIterator<Item = [usize; 2]>) -> Graph<'_> {
        let n = self.num_points();
        let listed: Vec<Edge> = edges
            .into_iter()
            .filter(|&[a, b]| a < n && b < n)
            .map(|[a, b]| ordered(self.vertex(a), self.vertex(b)))
            .filter(|&[a, b]| a != b)
            .collect();
        // A counting sort by the first end (a tile of a split run builds a graph of its 100,000s
        // of edges every round, where a comparison sort was a tenth of the tiles' work).
        let sorted = sort_pairs(n, listed.iter().copied(), listed.len(), |v| v.index());
        Graph::new(self, Cow::Owned(sorted))
    }
}

#[cfg(test)]
mod tests {
    use crate::{triangulate, Point};

    #[test]
    fn a_graph_of_your_own_lists_each_edge_once_where_points_repeat() {
        // Repeated points leave vertex ids past the count of distinct points: the sort of the
        // edges must be bounded by the points.
        let spiral = |t: f64| Point::new(t.cos() * (1.0 + 0.1 * t), t.sin() * (1.0 + 0.1 * t));
        let mut pts: Vec<Point> = (0..40).map(|k| spiral(0.7 * k as f64)).collect();
        for k in 0..20 {
            pts.push(pts[(7 * k) % 40]);
        }
        let tri = triangulate(&pts).unwrap();
        let n = pts.len();
        let other = |a: usize| (13 * a + 5) % n;
        let edges: Vec<[usize; 2]> = (0..n)
            .flat_map(|a| [[a, other(a)], [other(a), a]])
            .collect();
        let graph = tri.graph_from_edges(edges.iter().copied());
        let mut expected: Vec<[usize; 2]> = edges
            .iter()
            .map(|&[a, b]| [tri.vertex(a).index(), tri.vertex(b).index()])
            .filter(|[a, b]| a != b)
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        expected.sort_unstable();
        expected.dedup();
        let listed: Vec<[usize; 2]> = graph
            .listed()
            .iter()
            .map(|&[a, b]| [a.index(), b.index()])
            .collect();
        assert_eq!(listed, expected);
        assert!(listed.iter().flatten().any(|&v| v >= tri.num_vertices()));
    }
}
