//! The whole ConDT pipeline: [`reconstruct`], its [`Params`] and the [`Reconstruction`] that keeps
//! every stage.
//!
//! Reference: J. Antony, M. Reghunath, S. B. Thayyil, R. Muthuganapathy, "ConDT: A 2D curve
//! reconstruction algorithm based on a constrained-neighbor proximity graph" (sections 3 to 5);
//! `docs/condt.md` maps every line of its algorithms to this code and records each reading of an
//! ambiguity.
//!
//! Owns: the order in which the stages run ([`Params::stages`], the one place it is decided), the
//! parameter check, timing, and the final tally in input positions. It may not implement a stage
//! (that is [`crate::stages`]) nor modify the triangulation.
//!
//! ```
//! use condt::{reconstruct, Params, Point};
//! // Twelve points on a circle: one closed curve through all of them.
//! let circle: Vec<Point> = (0..12)
//!     .map(|k| {
//!         let t = k as f64 * std::f64::consts::TAU / 12.0;
//!         Point::new(t.cos(), t.sin())
//!     })
//!     .collect();
//! let result = reconstruct(&circle, &Params::default())?;
//! assert_eq!(result.curves().len(), 1);
//! assert!(result.curves()[0].is_closed());
//! assert_eq!(result.edges().len(), 12);
//! assert!(result.unused().is_empty());
//! # Ok::<(), condt::Error>(())
//! ```

use crate::adjacency::{CurveGraph, Edge};
use crate::curve::{curves_in_input_positions, Curve};
use crate::error::Error;
use crate::geometry::Point;
use crate::graph::Graph;
use crate::mesh::VertexId;
use crate::prefetch::PREFETCH_FROM;
use crate::smooth::{shows_noise, smoothed_positions, MAX_PASSES};
use crate::stages::{proximity, Earlier, Repair, Stage, Step, Uniformity, PARALLEL_FROM};
use crate::threads::both;
#[cfg(test)]
use crate::triangulate::triangulate;
use crate::triangulate::{triangulate_with, Triangulation};
use alloc::borrow::Cow;
use alloc::vec::Vec;
use core::time::Duration;

/// Which reconstruction runs on the Delaunay triangulation: ConDT (the stages [`Params`]
/// chooses), or one of two classical baselines, for comparing methods on the identical
/// triangulation.
///
/// ```
/// use condt::{reconstruct, Method, Params, Point, Stage};
/// let points: Vec<Point> = (0..10)
///     .map(|k| {
///         let t = k as f64 * std::f64::consts::TAU / 10.0;
///         Point::new(t.cos(), t.sin())
///     })
///     .collect();
/// let params = Params { method: Method::NnCrust, ..Params::default() };
/// let result = reconstruct(&points, &params)?;
/// assert_eq!(params.stages(), vec![Stage::NnCrust]);
/// assert_eq!(result.edges().len(), 10);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// ConDT: the proximity graph and the stages after it.
    #[default]
    ConDT,
    /// NN-Crust (Dey and Kumar), [`Triangulation::nn_crust`]; the ConDT parameters are unused.
    NnCrust,
    /// The Crust (Amenta, Bern and Eppstein), [`Triangulation::crust`]; the ConDT parameters are
    /// unused.
    Crust,
}

/// Parameters of a reconstruction.
///
/// ```
/// use condt::{Params, Repair, Uniformity};
/// let p = Params::default();
/// assert_eq!(p.uniformity, Uniformity::Fixed(2.75));
/// assert_eq!(p.outlier_factor, Some(1.7));
/// assert_eq!(p.repair, Repair::Needs);
/// assert!(p.check().is_ok());
/// let bad = Params { outlier_factor: Some(f64::NAN), ..p };
/// assert!(bad.check().is_err());
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Params {
    /// ConDT (the default) or a baseline; with a baseline, the fields below are not used.
    pub method: Method,
    /// Stage 1: the uniformity test (a fixed `u` must be finite and positive).
    pub uniformity: Uniformity,
    /// The non-manifold repair; [`Repair::Off`] skips the stage.
    pub repair: Repair,
    /// The IQR factor `k` of the outlier removal (finite, `>= 0`), or `None` to skip the stage.
    pub outlier_factor: Option<f64>,
    /// Remove outliers before the non-manifold repair instead of after it (the paper's order).
    /// Outlier edges can make a curve vertex non-manifold, and the repair then cuts a sharp
    /// corner there; `docs/condt.md` (note 8) measures both orders.
    pub outliers_first: bool,
    /// Run the local outlier removal after the IQR stage and the repair, whichever order they ran
    /// in (not in the paper; on by default, off in [`Params::paper`]): give back the edges the
    /// global rule cut along smooth, regularly spaced passages; drop edges far longer than the
    /// others at a branch or at both ends, branches of fewer than five points, and components
    /// that look like outliers: fewer than five points clearly apart from everything else,
    /// unless they close a regular cycle or are densely sampled (three or more points, every
    /// edge at most the median edge); nothing is dropped as a component when that would drop a
    /// quarter of the points. A sparsely sampled curve or branch of three or four points is lost
    /// with it on; the rules and the reason for each constant are in
    /// `src/stages/local_outliers.rs`.
    pub local_outliers: bool,
    /// Right after the local outlier removal (and only when it runs), drop every component
    /// made only of edges its first rule gave back unless every vertex of it with two edges is
    /// apart from everything else by more than twice its longest edge (not in the paper; on by default,
    /// off in [`Params::paper`]): a chance chain of smooth passages in a large scatter of
    /// outliers is given back whole, a sparse curve beside a dense one is apart everywhere.
    /// The rule and its reason are in `src/stages/given_back.rs`.
    pub confirm_given_back: bool,
    /// Close gaps at loose ends after the other stages (not in the paper): join two loose ends
    /// that face each other across a short gap, two loose ends to the stranded sample they line
    /// up through, and the two dropped arms of a crossing to the crossing. On by default, off
    /// in [`Params::paper`]; the rules and the reason for each constant are in
    /// `src/stages/gaps.rs`.
    pub close_gaps: bool,
    /// Smoothing passes (not in the paper; on by default, off in [`Params::paper`]): when at
    /// least one point in a hundred ends the first reconstruction's curves or branches them (a
    /// vertex with one edge, or with three or more), a point with two edges meeting at a wide
    /// angle moves halfway to its neighbours' midpoint, and the stages run again on the
    /// Delaunay triangulation of the moved points, up to three times. A reconstruction made
    /// only of cycles, or a large one with few ends and branches, is final at once and pays
    /// nothing; a small clean open curve pays one pass. The result's
    /// edges are between input positions as always; its
    /// [`triangulation`](Reconstruction::triangulation) and drawings show the moved points.
    /// Noise can push a sample into the empty circle of two true neighbours, so that their edge
    /// is not a Delaunay edge of the noisy points; the moved points can have it again. The rule
    /// and its reasons are in `src/smooth.rs`. Only [`reconstruct`] runs the passes:
    /// [`reconstruct_triangulation`] takes its triangulation as given. It lifts the evaluation
    /// suite's noise cases from 40.3 % to 50.0 % exact and lowers its outlier cases from 92.0 %
    /// to 89.3 %; `docs/condt.md`, "Smoothing passes".
    pub smooth: bool,
    /// Run the per-vertex stages on rayon (only with the `parallel` feature, and only from
    /// 65,536 points, below which waking the workers costs more than they save; same result).
    pub parallel: bool,
}

impl Default for Params {
    /// The best pipeline measured (`docs/condt.md`, "Beyond the paper"): the paper's proximity
    /// graph and outlier rule with [`Repair::Needs`], then the local outlier removal and gap
    /// closing, and smoothing passes where the result shows noise. Its cost: a sparsely sampled curve of three or four points, isolated, counts as
    /// outliers (`local_outliers: false` keeps it). [`Params::paper`] turns every step beyond
    /// the paper off.
    ///
    /// ```
    /// use condt::{Params, Repair, Stage};
    /// let p = Params::default();
    /// assert_eq!(p.repair, Repair::Needs);
    /// assert!(p.close_gaps && p.local_outliers && p.smooth);
    /// assert_eq!(
    ///     p.stages(),
    ///     vec![
    ///         Stage::Proximity,
    ///         Stage::Repair,
    ///         Stage::Outliers,
    ///         Stage::LocalOutliers,
    ///         Stage::GivenBack,
    ///         Stage::Gaps
    ///     ]
    /// );
    /// ```
    fn default() -> Self {
        Params {
            repair: Repair::Needs,
            local_outliers: true,
            confirm_given_back: true,
            close_gaps: true,
            smooth: true,
            ..Params::paper()
        }
    }
}

impl Params {
    /// The paper's pipeline as we read it, for studying and reproducing it: Algorithm 1 with
    /// `u = 2.75`, Algorithm 2 as printed ([`Repair::Paper`]), then Algorithm 3 with `k = 1.7`,
    /// and no stage beyond the paper. `docs/condt.md` lists every reading of an ambiguity.
    ///
    /// ```
    /// use condt::{Params, Repair, Stage, Uniformity};
    /// let paper = Params::paper();
    /// assert_eq!(paper.uniformity, Uniformity::Fixed(2.75));
    /// assert_eq!(paper.repair, Repair::Paper);
    /// assert_eq!(paper.stages(), vec![Stage::Proximity, Stage::Repair, Stage::Outliers]);
    /// ```
    pub fn paper() -> Params {
        Params {
            method: Method::ConDT,
            uniformity: Uniformity::Fixed(2.75),
            repair: Repair::Paper,
            outlier_factor: Some(1.7),
            outliers_first: false,
            local_outliers: false,
            confirm_given_back: false,
            close_gaps: false,
            smooth: false,
            parallel: cfg!(feature = "parallel"),
        }
    }

    /// `Ok` when every parameter is one its stage accepts.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first parameter that is NaN, infinite or out of
    /// range.
    pub fn check(&self) -> Result<(), Error> {
        if self.method != Method::ConDT {
            return Ok(());
        }
        self.uniformity.check()?;
        self.steps().try_for_each(|step| step.check())
    }

    /// The stages these parameters run, in the order they run: the proximity graph, then the
    /// repair and the outlier removal in the order [`Params::outliers_first`] chooses, then the
    /// local outlier removal, then closing gaps, each only when it is on.
    ///
    /// ```
    /// use condt::{Params, Repair, Stage};
    /// let p = Params { outliers_first: true, repair: Repair::Off, ..Params::paper() };
    /// assert_eq!(p.stages(), vec![Stage::Proximity, Stage::Outliers]);
    /// let local = Params { outliers_first: true, local_outliers: true, ..Params::paper() };
    /// assert_eq!(
    ///     local.stages(),
    ///     vec![Stage::Proximity, Stage::Outliers, Stage::Repair, Stage::LocalOutliers]
    /// );
    /// let q = Params { close_gaps: true, ..Params::paper() };
    /// assert_eq!(q.stages().last(), Some(&Stage::Gaps));
    /// ```
    pub fn stages(&self) -> Vec<Stage> {
        core::iter::once(self.first_stage())
            .chain(self.steps().map(Step::stage))
            .collect()
    }

    /// The graph built on the triangulation: ConDT's proximity graph or a baseline.
    fn first_stage(&self) -> Stage {
        match self.method {
            Method::ConDT => Stage::Proximity,
            Method::NnCrust => Stage::NnCrust,
            Method::Crust => Stage::Crust,
        }
    }

    /// The steps after the proximity graph, in order: the one place the order is decided.
    fn steps(&self) -> impl Iterator<Item = Step> {
        let repair = (self.repair != Repair::Off).then_some(Step::Repair(self.repair));
        let outliers = self.outlier_factor.map(|factor| Step::Outliers { factor });
        let (first, second) = if self.outliers_first {
            (outliers, repair)
        } else {
            (repair, outliers)
        };
        // The local outlier removal comes after both: its rules read vertices with three or more
        // edges as branches, which only a repaired graph makes true. Closing gaps runs last: it
        // joins loose ends, which the earlier stages create.
        // Confirming given-back components reads what the local outlier removal added, so it
        // comes right after it, and only with it.
        let local = self.local_outliers.then_some(Step::LocalOutliers);
        let confirm =
            (self.local_outliers && self.confirm_given_back).then_some(Step::ConfirmGivenBack);
        let gaps = self.close_gaps.then_some(Step::CloseGaps);
        // A baseline is the whole method: no ConDT stage follows it.
        let condt = self.method == Method::ConDT;
        first
            .into_iter()
            .chain(second)
            .chain(local)
            .chain(confirm)
            .chain(gaps)
            .filter(move |_| condt)
    }
}

/// One stage as it ran.
#[derive(Clone, Debug)]
struct StageRecord {
    stage: Stage,
    /// How to get its input back from its output.
    undo: Undo,
    time: Duration,
}

/// How a stage's input is recovered from its output: the stage graphs are stored as the final
/// graph and one of these per stage, walked back from the last stage. Reason: memory. A full
/// copy per stage that changed its graph took 8 bytes per point and stage (26.5 at the
/// reconstruction's peak on curves), while a stage changes a few edges in a hundred.
#[derive(Clone, Debug)]
enum Undo {
    /// The rule did not apply: the output is the input (the proximity graph, which has no input,
    /// is recorded so too).
    Unchanged,
    /// The output is the input with the edges at the positions `removed` lists taken out (the
    /// others in their order) and `appended` edges added at the end: the input is the output's
    /// first `len - appended` edges with each removed edge put back at its position.
    Delta {
        appended: usize,
        /// `(position in the input, edge)`, positions ascending.
        removed: Vec<(u32, Edge)>,
    },
    /// The input itself, when the output is not of that form or the delta would not be smaller.
    Input(Vec<Edge>),
    /// The input is the first stage's graph, which is computed again from the triangulation
    /// when a report asks for it (see [`FIRST_KEPT_UP_TO`]).
    First,
}

/// The record of the step that reads the first stage's graph (the proximity graph) keeps a
/// delta only while it holds at most one removal per this many edges of that graph, under a
/// byte per edge (12 bytes a removal); past it, the graph is computed again when a report asks
/// for it ([`Undo::First`]). Reason: memory against the time of a report. On uniform points the
/// repair keeps the edges of few vertices as they were (200k points: 146,489 removals of
/// 233,262 edges, or the whole graph, 9.3 bytes per point through every later stage and pass);
/// along curves it changes a few edges in a hundred (1,299 of 201,159), and the reports there
/// cost nothing more. Only the repair's record is replaced so: the local outlier removal reads
/// the IQR stage's input, which with `outliers_first` is the proximity graph, and must not
/// recompute it.
const FIRST_KEPT_UP_TO: usize = 12;

impl Undo {
    /// How to get `input` back from `output`. The input is moved into the record only when no
    /// delta is smaller than it.
    ///
    /// The delta matches the two lists greedily: an input edge equal to the next unmatched
    /// output edge is kept, any other is removed, and the output's unmatched tail is appended.
    /// Edges are distinct within a list, so undoing it gives the input back exactly, whatever
    /// the stage did; a stage that keeps its edges in order and appends the ones it adds (all of
    /// them do) gives the smallest delta, its actual change.
    fn of(input: Vec<Edge>, output: &[Edge]) -> Undo {
        // Past this many removals the delta (12 bytes each) outweighs the input (8 per edge).
        let most = 2 * input.len() / 3;
        let mut removed = Vec::new();
        let mut kept = 0;
        for (position, &edge) in input.iter().enumerate() {
            if output.get(kept) == Some(&edge) {
                kept += 1;
            } else if removed.len() < most {
                removed.push((position as u32, edge));
            } else {
                return Undo::Input(input);
            }
        }
        removed.shrink_to_fit();
        Undo::Delta {
            appended: output.len() - kept,
            removed,
        }
    }

    /// How many edges of `input` the delta of [`Undo::of`] would list as removed.
    fn removals(input: &[Edge], output: &[Edge]) -> usize {
        let mut kept = 0;
        for &edge in input {
            kept += usize::from(output.get(kept) == Some(&edge));
        }
        input.len() - kept
    }

    /// The stage's input, given its `output`; `first` computes the first stage's graph.
    fn input<'e>(
        &'e self,
        output: Cow<'e, [Edge]>,
        first: &dyn Fn() -> Vec<Edge>,
    ) -> Cow<'e, [Edge]> {
        match self {
            Undo::Unchanged => output,
            Undo::First => Cow::Owned(first()),
            Undo::Input(input) => Cow::Borrowed(input),
            Undo::Delta { appended, removed } => {
                let kept = &output[..output.len() - appended];
                let mut input = Vec::with_capacity(kept.len() + removed.len());
                let mut rest = kept.iter().copied();
                for &(position, edge) in removed {
                    // The kept edges before this position, in their order.
                    let gap = (position as usize).saturating_sub(input.len());
                    input.extend(rest.by_ref().take(gap));
                    input.push(edge);
                }
                input.extend(rest);
                Cow::Owned(input)
            }
        }
    }
}

/// The output of stage `k` of `records`, walking back from `last`, the last stage's output;
/// `first` computes the first stage's graph when a record says to ([`Undo::First`]).
fn output_of<'e>(
    records: &'e [StageRecord],
    last: &'e [Edge],
    k: usize,
    first: &dyn Fn() -> Vec<Edge>,
) -> Cow<'e, [Edge]> {
    // The next stage's input is the first stage's graph itself: nothing to walk back through.
    if matches!(records.get(k + 1).map(|r| &r.undo), Some(Undo::First)) {
        return Cow::Owned(first());
    }
    records[k + 1..]
        .iter()
        .rev()
        .fold(Cow::Borrowed(last), |output, record| {
            record.undo.input(output, first)
        })
}

/// The first stage's graph of a reconstruction on `tri` with `params`, as [`run_stages`]
/// computed it.
fn first_graph(tri: &Triangulation, params: &Params) -> Vec<Edge> {
    match params.method {
        Method::ConDT => proximity::proximity_graph(tri, params.uniformity, params.parallel),
        Method::NnCrust => crate::baselines::nn_crust_edges(tri),
        // `reconstruct_triangulation` checked that it fits (`crust_fits`), the one way it fails.
        Method::Crust => crate::baselines::crust_edges(tri).unwrap_or_default(),
    }
}

/// Everything a reconstruction computed, stage by stage, in input positions. Exact duplicates
/// are one point, reported under the smallest input position holding it (see
/// [`Triangulation::vertex`]).
///
/// ```
/// use condt::{reconstruct, Params, Point, Stage};
/// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.1)].map(Point::from);
/// let result = reconstruct(&pts, &Params::default())?;
/// for report in result.stages() {
///     println!("{}: {} edges, rule applied: {}", report.stage, report.graph.num_edges(), report.applied);
/// }
/// assert_eq!(result.stages().next().unwrap().stage, Stage::Proximity);
/// assert_eq!(result.stages().count(), Params::default().stages().len());
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Reconstruction {
    params: Params,
    triangulation: Triangulation,
    /// The stages in the order they ran, the proximity graph first.
    records: Vec<StageRecord>,
    /// The last stage's output, from which the records give back every earlier stage's.
    final_edges: Vec<Edge>,
    /// The final edges, sorted, in input positions (32-bit, as the kernel stores indices).
    edges: Vec<[u32; 2]>,
    /// Final degree of every input point.
    degrees: Degrees,
    curves: Vec<Curve>,
    unused: Vec<usize>,
    triangulation_time: Duration,
    curves_time: Duration,
    smoothing: Option<Smoothing>,
}

/// What the smoothing passes ([`Params::smooth`]) did, as [`Reconstruction::smoothing`]
/// reports them.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// // A noisy open arc: 30 samples over three quarters of a circle, every other one pushed out
/// // by 4 % of the radius. Its two ends are loose ends, so the passes run.
/// let pts: Vec<Point> = (0..30)
///     .map(|k| {
///         let t = k as f64 * 1.5 * std::f64::consts::PI / 29.0;
///         let r = if k % 2 == 0 { 1.04 } else { 1.0 };
///         Point::new(r * t.cos(), r * t.sin())
///     })
///     .collect();
/// let result = reconstruct(&pts, &Params::default())?;
/// let smoothing = result.smoothing().expect("it ran");
/// assert!(smoothing.passes >= 1 && smoothing.moved > 0);
/// // The stages saw the moved points; the edges are between input positions.
/// assert_ne!(result.stage_point(2), pts[2]);
/// assert_eq!(result.curves().len(), 1);
/// assert!(reconstruct(&pts, &Params::paper())?.smoothing().is_none());
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Smoothing {
    /// How many smoothing passes ran, each a reconstruction of moved points (at least one):
    /// the result is the last one's.
    pub passes: usize,
    /// How many points the last pass moved (from the positions the pass before it saw).
    pub moved: usize,
    /// The wall-clock time of the first reconstruction, every pass but the last, and every
    /// smoothing (zero without `std`); the result's stage and triangulation times are the last
    /// pass's.
    pub earlier_passes: Duration,
}

/// One stage of a [`Reconstruction`], as [`Reconstruction::stages`] reports it.
#[derive(Clone, Debug)]
pub struct StageReport<'r> {
    /// Which stage.
    pub stage: Stage,
    /// The graph it left.
    pub graph: Graph<'r>,
    /// Whether its rule applied (a vertex needed repair; the outlier rule fired). The proximity
    /// graph always applies.
    pub applied: bool,
    /// Its wall-clock time (zero without the `std` feature, which has no clock).
    pub time: Duration,
}

impl Reconstruction {
    /// The parameters it ran with.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// What the smoothing pass did, or `None` when it did not run ([`Params::smooth`]).
    pub fn smoothing(&self) -> Option<Smoothing> {
        self.smoothing
    }

    /// The Delaunay triangulation the stages walked (of the smoothed positions when
    /// [`Params::smooth`] is on).
    pub fn triangulation(&self) -> &Triangulation {
        &self.triangulation
    }

    /// The stages in the order they ran, the proximity graph first; see [`Params::stages`].
    ///
    /// Each stage's graph is rebuilt from the final one when its report is made (the
    /// reconstruction keeps only what each stage changed), in O(edges) per stage after it; the
    /// proximity graph may be computed again from the triangulation (when the repair changed
    /// more than one of its edges in twelve, its record does not keep it).
    pub fn stages(&self) -> impl ExactSizeIterator<Item = StageReport<'_>> + '_ {
        (0..self.records.len()).map(move |k| self.report(k))
    }

    /// The report of `stage`, or `None` when it did not run. Only its graph is rebuilt.
    pub fn stage(&self, stage: Stage) -> Option<StageReport<'_>> {
        let k = self
            .records
            .iter()
            .position(|record| record.stage == stage)?;
        Some(self.report(k))
    }

    /// Every stage that ran with its wall-clock time, in order: what [`stages`](Self::stages)
    /// reports of them, without rebuilding their graphs (zero times without `std`).
    ///
    /// ```
    /// use condt::{reconstruct, Params, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
    /// let result = reconstruct(&pts, &Params::default())?;
    /// let names: Vec<_> = result.stage_times().map(|(stage, _)| stage).collect();
    /// assert_eq!(names, Params::default().stages());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn stage_times(&self) -> impl ExactSizeIterator<Item = (Stage, Duration)> + '_ {
        self.records
            .iter()
            .map(|record| (record.stage, record.time))
    }

    /// The report of the `k`-th stage that ran, its graph rebuilt from the final one.
    fn report(&self, k: usize) -> StageReport<'_> {
        let record = &self.records[k];
        StageReport {
            stage: record.stage,
            graph: Graph::new(
                &self.triangulation,
                output_of(&self.records, &self.final_edges, k, &|| {
                    first_graph(&self.triangulation, &self.params)
                }),
            ),
            // The first graph has no input to leave as it was.
            applied: k == 0 || !matches!(record.undo, Undo::Unchanged),
            time: record.time,
        }
    }

    /// The final graph, as the last stage left it.
    pub fn graph(&self) -> Graph<'_> {
        Graph::new(&self.triangulation, Cow::Borrowed(&self.final_edges))
    }

    /// The final edges as input positions `[a, b]`, `a < b`, sorted.
    pub fn edges(&self) -> impl ExactSizeIterator<Item = [usize; 2]> + Clone + '_ {
        self.edges.iter().map(|&[a, b]| [a as usize, b as usize])
    }

    /// The final edges as [`Reconstruction::edges`] gives them, as the slice they are kept in,
    /// so that a writer can cut it into pieces.
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

    /// The curves, in input positions, sorted; see [`Graph::curves`].
    pub fn curves(&self) -> &[Curve] {
        &self.curves
    }

    /// Input positions whose point ended with no edge (outliers), ascending.
    pub fn unused(&self) -> &[usize] {
        &self.unused
    }

    /// The final degree of input point `index` (duplicates share their point's degree).
    ///
    /// # Panics
    /// If `index` is not an input position.
    pub fn degree(&self, index: usize) -> usize {
        self.degrees.get(index)
    }

    /// The coordinates of input point `index` as the stages saw them: the input point, or the
    /// smoothed position when the smoothing passes ([`Params::smooth`]) moved it. The stage
    /// drawings show these, because the rings and lengths the stages tested are theirs.
    ///
    /// The result keeps no copy of the input: the input coordinates are the caller's (the
    /// slice given to [`reconstruct`]; [`reconstruct_owned`] hands them over for good).
    /// Reason: a copy of the points the passes moved cost 10 to 16 bytes a point through every
    /// pass and in the result, a tenth of the peak (`docs/performance.md`, "Where the bytes per
    /// point go").
    ///
    /// # Panics
    /// If `index` is not an input position.
    pub fn stage_point(&self, index: usize) -> Point {
        self.triangulation.point(index)
    }

    /// Number of input points.
    pub fn num_points(&self) -> usize {
        self.degrees.len()
    }

    /// Wall-clock time of the triangulation (zero without `std`).
    pub fn triangulation_time(&self) -> Duration {
        self.triangulation_time
    }

    /// Wall-clock time of the curve assembly and final tally (zero without `std`).
    pub fn curves_time(&self) -> Duration {
        self.curves_time
    }
}

/// A clock that reads zero without `std`.
struct Stopwatch {
    #[cfg(feature = "std")]
    start: std::time::Instant,
}

impl Stopwatch {
    fn start() -> Self {
        Stopwatch {
            #[cfg(feature = "std")]
            start: std::time::Instant::now(),
        }
    }

    /// Time since the start or the previous lap.
    fn lap(&mut self) -> Duration {
        #[cfg(feature = "std")]
        {
            let now = std::time::Instant::now();
            let elapsed = now - self.start;
            self.start = now;
            elapsed
        }
        #[cfg(not(feature = "std"))]
        Duration::ZERO
    }
}

/// Triangulates `points` and reconstructs the curves through them.
///
/// # Errors
/// As [`triangulate`](crate::triangulate()): non-finite coordinates, an over-wide dynamic range, too many points; and
/// [`Error::InvalidParameter`] when [`Params::check`] refuses `params` (checked first).
pub fn reconstruct(points: &[Point], params: &Params) -> Result<Reconstruction, Error> {
    reconstruct_input(Cow::Borrowed(points), params)
}

/// [`reconstruct`] of points the caller hands over: the same result, but the points are freed
/// as soon as they are triangulated (the triangulation keeps them in its own frame), so the
/// stages run without them (16 bytes per point less at the peak; the command line reads its
/// points into memory only to reconstruct them). The result speaks in input positions; for
/// the input coordinates afterwards (where the smoothing passes moved points, the result has
/// only the moved positions, [`Reconstruction::stage_point`]), keep the points and call
/// [`reconstruct`].
///
/// # Errors
/// As [`reconstruct`].
///
/// ```
/// use condt::{reconstruct, reconstruct_owned, Params, Point};
/// let points: Vec<Point> = (0..40)
///     .map(|k| {
///         let t = k as f64 * std::f64::consts::TAU / 40.0;
///         Point::new(t.cos(), (2.0 * t).sin())
///     })
///     .collect();
/// let borrowed = reconstruct(&points, &Params::default())?;
/// let owned = reconstruct_owned(points, &Params::default())?;
/// assert_eq!(owned.edges().collect::<Vec<_>>(), borrowed.edges().collect::<Vec<_>>());
/// assert_eq!(owned.curves(), borrowed.curves());
/// # Ok::<(), condt::Error>(())
/// ```
pub fn reconstruct_owned(points: Vec<Point>, params: &Params) -> Result<Reconstruction, Error> {
    reconstruct_input(Cow::Owned(points), params)
}

/// [`reconstruct`] and [`reconstruct_owned`]: an owned input is freed once triangulated.
fn reconstruct_input(points: Cow<'_, [Point]>, params: &Params) -> Result<Reconstruction, Error> {
    params.check()?;
    let mut clock = Stopwatch::start();
    let tri = triangulate_with(&points, params.parallel)?;
    let triangulation_time = clock.lap();
    drop(points);
    let may_smooth = params.smooth && params.method == Method::ConDT;
    let first_run = if may_smooth {
        CurveAssembly::UnlessNoisy
    } else {
        CurveAssembly::Now
    };
    let (mut result, _) = stages_on(tri, params, first_run)?;
    result.triangulation_time = triangulation_time;
    if may_smooth && shows_noise(result.degrees.iter()) {
        // Each pass smooths along the previous pass's final graph and reconstructs the moved
        // points; the passes stop at a fixed point (the same final edges) or after
        // `MAX_PASSES` (src/smooth.rs gives the reasons).
        let mut earlier_passes = Duration::ZERO;
        let mut smoothing = Smoothing::default();
        loop {
            // Of the previous pass only its final edges are read again (the fixed-point test,
            // by their fingerprint), and its triangulation and final graph to smooth along: the
            // rest (stage records, degrees) is freed before the positions are computed (26 bytes
            // per point of uniform points at the passes' peak), those two once they are, and the
            // moved positions once they are triangulated. The last pass allowed stops whatever
            // its edges, so they are not kept for it.
            let last_pass = smoothing.passes + 1 >= MAX_PASSES;
            let previous_edges = (!last_pass).then(|| EdgesFingerprint::of(&result.edges));
            drop(core::mem::take(&mut result.edges));
            let (triangulation, final_edges, triangulation_time) = result.into_last_graph();
            let (positions, moved) = smoothed_positions(&triangulation, &final_edges);
            drop((triangulation, final_edges));
            // The replaced pass's triangulation is an earlier pass's cost too.
            earlier_passes += triangulation_time;
            earlier_passes += clock.lap();
            let tri = triangulate_with(&positions, params.parallel)?;
            drop(positions);
            let triangulation_time = clock.lap();
            let run = if last_pass {
                CurveAssembly::Now
            } else {
                CurveAssembly::Later
            };
            let (pass, graph) = stages_on(tri, params, run)?;
            result = pass;
            result.triangulation_time = triangulation_time;
            smoothing.passes += 1;
            smoothing.moved = moved;
            // A pass that may be followed (`CurveAssembly::Later`) keeps its edges and returns its
            // curve graph; the last allowed returns neither and has its curves.
            debug_assert_eq!(graph.is_some(), previous_edges.is_some());
            if let (Some(graph), Some(previous)) = (graph, previous_edges) {
                // A fixed point is final: its curves are assembled. Otherwise another pass
                // replaces it, curves unassembled.
                if previous == EdgesFingerprint::of(&result.edges) {
                    result.assemble_curves(graph);
                    break;
                }
            } else {
                break;
            }
        }
        smoothing.earlier_passes = earlier_passes;
        result.smoothing = Some(smoothing);
    }
    Ok(result)
}

/// The fixed-point test's record of a pass's final edges (input positions `[i, j]`, sorted, as
/// the tally makes them): their count and two 64-bit hashes of the list, each chained over the
/// edges through a different bijective mixer (the finalizers of SplitMix64 and of MurmurHash3).
/// Reason: the list itself was held through the whole next pass, every phase of which it raised
/// (3.2 bytes per point of uniform points packed, 6.5 unpacked), for one comparison at its end.
/// Two different lists of the same length give the same record with a chance of about 2^-128;
/// the passes would then stop one pass early, with a result that is still the reconstruction of
/// the last pass's positions.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
struct EdgesFingerprint {
    len: usize,
    hashes: [u64; 2],
}

impl EdgesFingerprint {
    fn of(edges: &[[u32; 2]]) -> EdgesFingerprint {
        let mut hashes = [0x243f_6a88_85a3_08d3_u64, 0x1319_8a2e_0370_7344];
        for &[i, j] in edges {
            let word = (u64::from(i) << 32) | u64::from(j);
            hashes = [
                splitmix64_finalizer(hashes[0] ^ word),
                murmur3_finalizer(hashes[1].wrapping_add(word).rotate_left(29)),
            ];
        }
        EdgesFingerprint {
            len: edges.len(),
            hashes,
        }
    }
}

/// The output function of SplitMix64 (Steele, Lea and Flood 2014), a bijection of `u64`.
fn splitmix64_finalizer(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The 64-bit finalizer of MurmurHash3 (Appleby), a bijection of `u64`.
fn murmur3_finalizer(mut z: u64) -> u64 {
    z = (z ^ (z >> 33)).wrapping_mul(0xff51_afd7_ed55_8ccd);
    z = (z ^ (z >> 33)).wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    z ^ (z >> 33)
}

impl Reconstruction {
    /// Assembles the curves of a reconstruction that ran without them ([`CurveAssembly::Later`]),
    /// `graph` the curve graph of its final edges; the time is added to the curves' time.
    fn assemble_curves(&mut self, graph: CurveGraph) {
        debug_assert!(graph == CurveGraph::new(self.triangulation.num_points(), &self.final_edges));
        let mut clock = Stopwatch::start();
        let tri = &self.triangulation;
        let in_parallel = self.params.parallel && tri.num_points() >= PARALLEL_FROM;
        self.curves = on_worker(in_parallel, || curves_in_input_positions(tri, &graph));
        drop(graph);
        self.curves_time += clock.lap();
    }

    /// The triangulation, the final edges and the triangulation's time; everything else is
    /// freed here (a partial move out of a variable would keep the rest until it is assigned
    /// again, after the next pass).
    fn into_last_graph(self) -> (Triangulation, Vec<Edge>, Duration) {
        (
            self.triangulation,
            self.final_edges,
            self.triangulation_time,
        )
    }
}

/// Runs the ConDT stages on a triangulation already built, which the result keeps.
///
/// # Errors
/// [`Error::InvalidParameter`] when [`Params::check`] refuses `params`.
///
/// ```
/// use condt::{reconstruct_triangulation, triangulate, Params, Point};
/// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from))?;
/// // The paper's pipeline: the default's local outlier removal drops curves under five points.
/// let result = reconstruct_triangulation(tri, &Params::paper())?;
/// assert_eq!(result.edges().collect::<Vec<_>>(), vec![[0, 1], [0, 2], [1, 2]]);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn reconstruct_triangulation(
    tri: Triangulation,
    params: &Params,
) -> Result<Reconstruction, Error> {
    // `stages_on` checks the parameters and the Crust's fit.
    stages_on(tri, params, CurveAssembly::Now).map(|(result, _)| result)
}

/// When a reconstruction's curves are assembled, which depends on whether it is the final one of
/// [`reconstruct`]: a reconstruction that a smoothing pass replaces is read only for its final
/// edges, degrees and graph, so its curves would be dead (10.6 bytes per point of uniform points
/// beside the final tally).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum CurveAssembly {
    /// The final one: the curves are assembled beside the final tally.
    Now,
    /// The first reconstruction when smoothing passes may run: final unless its degrees show
    /// noise ([`shows_noise`], read off the curve graph before the tally), and then no curves.
    UnlessNoisy,
    /// A pass that another may follow: the curves wait until the caller knows
    /// ([`Reconstruction::assemble_curves`] with the curve graph returned).
    Later,
}

/// [`reconstruct_triangulation`], returning the final curve graph when the curves wait
/// ([`CurveAssembly::Later`]).
fn stages_on(
    tri: Triangulation,
    params: &Params,
    assembly: CurveAssembly,
) -> Result<(Reconstruction, Option<CurveGraph>), Error> {
    params.check()?;
    if params.method == Method::Crust {
        crate::baselines::crust_fits(&tri)?;
    }
    let in_parallel = params.parallel && tri.num_points() >= PARALLEL_FROM;
    Ok(on_worker(in_parallel, move || {
        run_stages(tri, params, assembly)
    }))
}

/// The stages of [`reconstruct_triangulation`], its parameters checked; the curve graph is
/// returned when the curves wait ([`CurveAssembly::Later`]).
fn run_stages(
    tri: Triangulation,
    params: &Params,
    assembly: CurveAssembly,
) -> (Reconstruction, Option<CurveGraph>) {
    let mut clock = Stopwatch::start();
    let first = first_graph(&tri, params);
    let mut records = Vec::with_capacity(6);
    records.push(StageRecord {
        stage: params.first_stage(),
        undo: Undo::Unchanged,
        time: clock.lap(),
    });
    // The latest stage's output; each stage's record keeps only how to get its input back.
    let mut current = first;
    // The curve graph of `current` when the last stage handed one on (`Outcome::graph`).
    let mut current_graph = None;
    for step in params.steps() {
        // The input of an earlier stage, rebuilt only for the step that reads it (`Step::run`
        // says which reads which), and only while it runs.
        let input_of =
            |stage: Stage, read: bool| match records.iter().position(|r| r.stage == stage) {
                Some(k) if read && k > 0 => {
                    output_of(&records, &current, k - 1, &|| first_graph(&tri, params))
                }
                _ => Cow::Borrowed(current.as_slice()),
            };
        let before_outliers = input_of(Stage::Outliers, step == Step::LocalOutliers);
        let before_local = input_of(Stage::LocalOutliers, step == Step::ConfirmGivenBack);
        let earlier = Earlier {
            before_outliers,
            before_local,
        };
        let outcome = step.run(&tri, &current, earlier, current_graph.take());
        current_graph = outcome.graph;
        let undo = match outcome.edges {
            None => Undo::Unchanged,
            Some(output) => {
                let input = core::mem::replace(&mut current, output);
                // Only the repair's record may stand for the first graph (see FIRST_KEPT_UP_TO).
                let reads_first = records.len() == 1 && matches!(step, Step::Repair(_));
                // `r * K > len` as `r > len / K` (the same for integers), which cannot overflow.
                if reads_first && Undo::removals(&input, &current) > input.len() / FIRST_KEPT_UP_TO
                {
                    Undo::First
                } else {
                    Undo::of(input, &current)
                }
            }
        };
        // A handed-on graph must be the curve graph of exactly the list the next stage reads
        // (checked in debug builds, so every test of the pipeline checks it).
        debug_assert!(current_graph
            .as_ref()
            .is_none_or(|graph| *graph == CurveGraph::new(tri.num_points(), &current)));
        records.push(StageRecord {
            stage: step.stage(),
            undo,
            time: clock.lap(),
        });
    }
    let last = current.as_slice();
    let n = tri.num_points();
    let graph = current_graph.unwrap_or_else(|| CurveGraph::new(n, last));
    let in_parallel = params.parallel && n >= PARALLEL_FROM;
    let curves_now = match assembly {
        CurveAssembly::Now => true,
        CurveAssembly::UnlessNoisy => {
            !shows_noise(tri.input_to_vertex().iter().map(|&v| graph.degree(v)))
        }
        CurveAssembly::Later => false,
    };
    let (curves, tally) = if curves_now {
        both(
            in_parallel,
            || curves_in_input_positions(&tri, &graph),
            || tally(&tri, &graph, last.len()),
        )
    } else {
        (Vec::new(), tally(&tri, &graph, last.len()))
    };
    let curves_time = clock.lap();
    // The curve graph's degrees are the tally's.
    debug_assert!(
        assembly != CurveAssembly::UnlessNoisy || curves_now != shows_noise(tally.degrees.iter())
    );
    let result = Reconstruction {
        params: *params,
        triangulation: tri,
        records,
        final_edges: current,
        edges: tally.edges,
        degrees: tally.degrees,
        curves,
        unused: tally.unused,
        triangulation_time: Duration::ZERO,
        curves_time,
        smoothing: None,
    };
    let waiting = (assembly == CurveAssembly::Later).then_some(graph);
    (result, waiting)
}

/// Runs `work` on one of rayon's worker threads when `parallel`. Called from outside the pool,
/// rayon's parallel loops leave the caller blocked and, once done, their workers spinning for a
/// while: with as many workers as cores, the sequential stages that follow then share a core with
/// a spinning worker (gap closing measured 22 to 29 ms after the parallel proximity pass instead
/// of 9 to 10 ms at 1M points, 2 cores). From inside the pool the caller's own thread is one of
/// the workers, so nothing spins beside it but the others.
#[cfg(feature = "parallel")]
fn on_worker<R: Send>(parallel: bool, work: impl FnOnce() -> R + Send) -> R {
    if parallel {
        rayon::scope(|_| work())
    } else {
        work()
    }
}

#[cfg(not(feature = "parallel"))]
fn on_worker<R>(_parallel: bool, work: impl FnOnce() -> R) -> R {
    work()
}

/// The degree of every input point in a byte, the rare degree above 254 in a sorted side list.
/// Reason: the list is kept in the result and is alive at the last step's peak, where four
/// bytes a point were 3 more than any graph of the stages needs.
#[derive(Clone, Default)]
struct Degrees {
    /// The degree, or [`Degrees::LARGE`] when it is in `large`.
    small: Vec<u8>,
    /// `(input position, degree)` of every degree from [`Degrees::LARGE`] up, by position.
    large: Vec<(u32, u32)>,
}

impl Degrees {
    const LARGE: u8 = u8::MAX;

    fn with_capacity(n: usize) -> Degrees {
        Degrees {
            small: Vec::with_capacity(n),
            large: Vec::new(),
        }
    }

    /// Appends the degree of the next input position.
    fn push(&mut self, degree: usize) {
        match u8::try_from(degree) {
            Ok(small) if small < Self::LARGE => self.small.push(small),
            _ => {
                let position = self.small.len() as u32;
                self.large.push((position, degree as u32));
                self.small.push(Self::LARGE);
            }
        }
    }

    fn get(&self, index: usize) -> usize {
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

    fn len(&self) -> usize {
        self.small.len()
    }

    fn iter(&self) -> impl ExactSizeIterator<Item = usize> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }
}

/// The degrees as a list, as `Reconstruction`'s `Debug` showed them before they were packed.
impl core::fmt::Debug for Degrees {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// The final graph seen from the input positions.
struct Tally {
    degrees: Degrees,
    unused: Vec<usize>,
    edges: Vec<[u32; 2]>,
}

/// How many input positions ahead [`tally`] asks for the neighbours' positions (and twice as
/// many for the records).
const TALLY_PREFETCH: usize = 16;

/// One pass over the input positions gives the degrees, the unused points and the final edges
/// already sorted: an edge is listed by its smaller input position. For the common vertex of
/// degree <= 2 both candidates are written and the count advances only past those that belong
/// (whether they do is a coin toss, so it is not branched on). A vertex's degree and neighbours
/// are one record of the curve graph; the neighbours' input positions come from the
/// triangulation's dense map, which packs sixteen to a cache line where the records pack four.
/// (Gathering each vertex's contribution in vertex order first, or scattering it to its input
/// position, was tried: fewer cache misses on shuffled input, more on input in curve order.)
fn tally(tri: &Triangulation, graph: &CurveGraph, edge_count: usize) -> Tally {
    let n = tri.num_points();
    // Without duplicates every input position stands for its own vertex: no need to look.
    let has_duplicates = tri.num_vertices() < n;
    let mut degrees = Degrees::with_capacity(n);
    let mut unused = Vec::new();
    // Room for the two candidates a vertex writes past the last edge it lists.
    let mut edges: Vec<[u32; 2]> = alloc::vec![[0, 0]; edge_count + 2];
    let mut count = 0;
    let input_of = |w: VertexId| {
        if w.is_infinite() {
            0
        } else {
            tri.input_of(w) as u32
        }
    };
    let order = tri.input_to_vertex();
    let prefetching = n >= PREFETCH_FROM;
    for (i, &v) in order.iter().enumerate() {
        if prefetching {
            // On shuffled input every record and neighbour position is a miss: the record is
            // asked for two distances ahead, the positions of its neighbours one distance ahead,
            // once the record has arrived.
            if let Some(&later) = order.get(i + 2 * TALLY_PREFETCH) {
                graph.prefetch(later);
            }
            if let Some(&soon) = order.get(i + TALLY_PREFETCH) {
                for w in graph.first_two(soon) {
                    tri.prefetch_input_of(w);
                }
            }
        }
        let degree = graph.degree(v);
        degrees.push(degree);
        let i = i as u32;
        if degree == 0 {
            unused.push(i as usize);
        } else if degree <= 2 {
            let [x, y] = graph.first_two(v).map(input_of);
            // A duplicate input point lists nothing: its edges are under the first copy.
            let listing = !has_duplicates || tri.input_of(v) as u32 == i;
            for j in [x.min(y), x.max(y)] {
                edges[count] = [i, j];
                count += usize::from(listing & (j > i));
            }
        } else if !has_duplicates || tri.input_of(v) as u32 == i {
            let first = count;
            for k in 0..degree {
                let j = input_of(graph.neighbor(v, k));
                if j > i {
                    edges[count] = [i, j];
                    count += 1;
                }
            }
            edges[first..count].sort_unstable();
        }
    }
    edges.truncate(count);
    Tally {
        degrees,
        unused,
        edges,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sample::{sample, Clumps, Sampling, Shape};
    use crate::test_rng::Xorshift;

    fn edge(a: u32, b: u32) -> Edge {
        [VertexId::new(a), VertexId::new(b)]
    }

    /// Whatever a stage makes of its input (edges removed, edges appended, the order changed),
    /// the record gives the input back exactly, in its order; the input is stored whole only
    /// when the change is not of the usual form.
    #[test]
    fn an_undo_gives_the_stage_input_back_exactly() {
        let mut rng = Xorshift::new(12);
        for round in 0..200 {
            let len = rng.below(40) as u32;
            let input: Vec<Edge> = (0..len).map(|k| edge(k, k + 1 + round)).collect();
            let mut output: Vec<Edge> = input
                .iter()
                .copied()
                .filter(|_| rng.below(4) != 0)
                .collect();
            let removals = input.len() - output.len();
            output.extend((0..rng.below(5) as u32).map(|k| edge(1000 + k, 2000 + k)));
            let reordered = round % 5 == 0 && output.len() > 2;
            if reordered {
                output.swap(0, 1);
            }
            let undo = Undo::of(input.clone(), &output);
            // The delta (12 bytes a removal) is kept while it is smaller than the input.
            if !reordered && removals < 2 * input.len() / 3 {
                assert!(matches!(undo, Undo::Delta { .. }), "{undo:?}");
            }
            assert_eq!(
                &*undo.input(Cow::Borrowed(&output), &|| unreachable!()),
                input.as_slice()
            );
        }
    }

    /// An input handed over gives the result a borrowed one gives, the stage points it reports
    /// included bit for bit: with and without smoothing passes, with signed zeros and
    /// duplicates, and across a range of magnitudes the stages' frame does not hold exactly.
    #[test]
    fn an_owned_input_gives_the_same_result() {
        let mut rng = Xorshift::new(3);
        let noisy: Vec<Point> = (0..300)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 300.0;
                let r = 1.0 + 0.05 * (rng.unit() - 0.5);
                Point::new(r * libm::cos(t), r * libm::sin(t))
            })
            .collect();
        let mut zeros = noisy.clone();
        zeros.extend([Point::new(-0.0, 0.0), Point::new(0.0, 0.0), noisy[7]]);
        // A set spanning more than the stages' frame holds exactly (a curve near 1e300, points
        // near 1e-300, which become subnormal there): the triangulation keeps its inputs, and
        // every input position must still come back bit for bit.
        let mut wide: Vec<Point> = noisy
            .iter()
            .map(|p| Point::new(p.x * 1e300, p.y * 1e300))
            .collect();
        wide.extend([Point::new(1e-300, 3e-301), Point::new(-2e-290, 7e-295)]);
        for points in [noisy, zeros, wide] {
            let tri = triangulate(&points).unwrap();
            tri.validate().unwrap();
            for smooth in [false, true] {
                let params = Params {
                    smooth,
                    ..Params::default()
                };
                let borrowed = reconstruct(&points, &params).unwrap();
                let owned = reconstruct_owned(points.clone(), &params).unwrap();
                assert_eq!(owned.edges, borrowed.edges);
                assert_eq!(owned.curves, borrowed.curves);
                assert_eq!(owned.smoothing.is_some(), borrowed.smoothing.is_some());
                // The curves were assembled, whichever way the passes ended: every final edge
                // lies on one of them.
                let segments: usize = borrowed
                    .curves()
                    .iter()
                    .map(|c| c.len() - usize::from(!c.is_closed()))
                    .sum();
                assert!(!borrowed.edges.is_empty());
                assert_eq!(segments, borrowed.edges.len());
                for (i, &input) in points.iter().enumerate() {
                    let (p, q) = (borrowed.stage_point(i), owned.stage_point(i));
                    assert_eq!(
                        (q.x.to_bits(), q.y.to_bits()),
                        (p.x.to_bits(), p.y.to_bits())
                    );
                    // Without the passes, the stages saw the input points (a merged duplicate
                    // keeps the bits of its first position: equal, perhaps not in a zero's sign).
                    if !smooth {
                        assert_eq!(p, input, "point {i}");
                    }
                }
            }
            let smoothed = reconstruct(&points, &Params::default()).unwrap();
            assert!(smoothed.smoothing.is_some(), "the passes ran");
        }
    }

    /// Degrees of 255 and more go to the side list and come back exactly, in order, beside
    /// the small ones around them.
    #[test]
    fn degrees_keep_large_values_exactly() {
        let values = [0, 2, 254, 255, 300, 1, 70_000, 254, u32::MAX as usize, 3];
        let mut degrees = Degrees::with_capacity(values.len());
        for &d in &values {
            degrees.push(d);
        }
        assert_eq!(degrees.len(), values.len());
        assert_eq!(degrees.large.len(), 4);
        for (i, &d) in values.iter().enumerate() {
            assert_eq!(degrees.get(i), d, "position {i}");
        }
        assert!(degrees.iter().eq(values.iter().copied()));
        assert_eq!(
            alloc::format!("{degrees:?}"),
            alloc::format!("{values:?}"),
            "Debug shows the degrees as a list"
        );
    }

    /// Every stage's graph as `stages()` rebuilds it is the graph the stage left: running the
    /// steps one by one through the public `Graph` methods gives the same edges in the same
    /// order.
    #[test]
    fn the_stage_graphs_are_rebuilt_as_the_stages_left_them() {
        let mut rng = Xorshift::new(7);
        let mut points: Vec<Point> = (0..400)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 400.0;
                let r = 1.0 + 0.02 * (rng.unit() - 0.5);
                Point::new(r * libm::cos(t), r * libm::sin(t))
            })
            .collect();
        points.extend((0..60).map(|_| Point::new(3.0 * rng.unit() - 1.5, 3.0 * rng.unit() - 1.5)));
        let params = Params {
            smooth: false,
            ..Params::default()
        };
        let result = reconstruct(&points, &params).unwrap();
        let tri = result.triangulation();
        let reports: Vec<StageReport<'_>> = result.stages().collect();
        let proximity = tri.proximity_graph(params.uniformity).unwrap();
        assert_eq!(reports[0].graph.listed(), proximity.listed());
        let repaired = proximity.repair(params.repair);
        assert_eq!(reports[1].graph.listed(), repaired.listed());
        let filtered = repaired.remove_outliers(1.7).unwrap();
        assert_eq!(reports[2].graph.listed(), filtered.graph.listed());
        assert_eq!(reports[2].applied, filtered.fired);
        let local = filtered.graph.remove_local_outliers(&repaired);
        assert_eq!(reports[3].graph.listed(), local.listed());
        let confirmed = local.confirm_given_back(&filtered.graph);
        assert_eq!(reports[4].graph.listed(), confirmed.listed());
        let closed = confirmed.close_gaps();
        assert_eq!(reports[5].graph.listed(), closed.listed());
        assert_eq!(result.graph().listed(), closed.listed());
        assert!(
            reports.iter().skip(1).any(|r| r.applied),
            "some stage changed the graph"
        );
    }

    /// On uniform points the repair changes most of the proximity graph, so its record does not
    /// keep it ([`Undo::First`]): the reports still give every stage's graph as it was, the
    /// proximity graph computed again; along a curve the repair's record stays a delta.
    #[test]
    fn a_repair_record_that_would_hold_the_proximity_graph_recomputes_it() {
        let mut rng = Xorshift::new(21);
        let uniform = rng.unit_points(3000);
        let curve: Vec<Point> = (0..3000)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 3000.0;
                Point::new(libm::cos(t), 0.5 * libm::sin(t))
            })
            .collect();
        let params = Params {
            smooth: false,
            ..Params::default()
        };
        for (points, recomputed) in [(uniform, true), (curve, false)] {
            let result = reconstruct(&points, &params).unwrap();
            let repair = &result.records[1];
            assert_eq!(repair.stage, Stage::Repair);
            assert_eq!(matches!(repair.undo, Undo::First), recomputed);
            let tri = result.triangulation();
            let proximity = tri.proximity_graph(params.uniformity).unwrap();
            let reports: Vec<StageReport<'_>> = result.stages().collect();
            assert_eq!(reports[0].graph.listed(), proximity.listed());
            let repaired = proximity.repair(params.repair);
            assert_eq!(reports[1].graph.listed(), repaired.listed());
            let filtered = repaired.remove_outliers(1.7).unwrap();
            assert_eq!(reports[2].graph.listed(), filtered.graph.listed());
            assert_eq!(
                result.stage(Stage::Proximity).unwrap().graph.listed(),
                proximity.listed()
            );
        }
    }

    /// The fixed-point test's fingerprint is that of the same list made again, and tells apart
    /// every other list tried: each single edge changed in either end, dropped or added, two
    /// edges swapped, and the empty list.
    #[test]
    fn edge_fingerprints_tell_lists_apart() {
        let mut rng = Xorshift::new(5);
        let mut seen = alloc::collections::BTreeMap::new();
        for round in 0..200 {
            let n = 2 + rng.below(1 << (round % 30)) as u32;
            let mut edges: Vec<[u32; 2]> = (0..1 + rng.below(40))
                .map(|_| {
                    let (a, b) = (rng.below(n.into()) as u32, rng.below(n.into()) as u32);
                    [a.min(b), a.max(b) + u32::from(a == b)]
                })
                .collect();
            if round == 0 {
                edges.push([u32::MAX - 1, u32::MAX]);
            }
            edges.sort_unstable();
            edges.dedup();
            let print = EdgesFingerprint::of(&edges);
            assert_eq!(print, EdgesFingerprint::of(&edges.clone()));
            let mut others = alloc::vec![Vec::new()];
            for k in 0..edges.len() {
                for end in 0..2 {
                    let mut changed = edges.clone();
                    changed[k][end] ^= 1 << rng.below(32);
                    others.push(changed);
                }
                let mut dropped = edges.clone();
                dropped.remove(k);
                others.push(dropped);
                if k > 0 {
                    let mut swapped = edges.clone();
                    swapped.swap(k - 1, k);
                    others.push(swapped);
                }
            }
            let mut added = edges.clone();
            added.push([0, 1]);
            others.push(added);
            for other in others {
                assert_eq!(other == edges, EdgesFingerprint::of(&other) == print);
            }
            // Across rounds, different lists have different hashes (lists met again agree).
            if let Some(earlier) = seen.insert(print.hashes, edges.clone()) {
                assert_eq!(earlier, edges);
            }
        }
        assert!(seen.len() > 150);
    }

    /// A stage given the curve graph of its input decides exactly as one that builds its own,
    /// and the graph it hands on is the curve graph of its output: on noisy, crossing curves
    /// with outliers and clumps, where every stage changes something, and on a clean circle,
    /// where none does.
    #[test]
    fn a_handed_on_curve_graph_is_that_of_the_stage_output_and_changes_nothing() {
        let shapes = [
            Shape::FigureEight {
                center: Point::new(0.0, 0.0),
                size: 2.0,
            },
            Shape::circle(Point::new(5.0, 0.0), 1.0),
            Shape::Arc {
                center: Point::new(0.0, 5.0),
                radius: 1.5,
                start: 0.0,
                sweep: 4.0,
            },
        ];
        let (mut clean_seeds, mut clean_reaching_the_end) = (0, 0);
        for seed in 0..12u64 {
            let sampling = Sampling {
                noise: if seed % 3 == 0 { 0.0 } else { 0.02 },
                outlier_fraction: if seed % 2 == 0 { 0.0 } else { 0.05 },
                outlier_clumps: (seed % 4 == 1).then_some(Clumps {
                    min: 3,
                    max: 7,
                    radius: 0.1,
                }),
                seed,
                ..Sampling::new(0.08)
            };
            let points = sample(&shapes, &sampling).points;
            let tri = triangulate(&points).unwrap();
            let n = tri.num_points();
            let params = Params::default();
            let mut current = proximity::proximity_graph(&tri, params.uniformity, params.parallel);
            let mut graph: Option<CurveGraph> = None;
            let (mut before_outliers, mut before_local) = (current.clone(), current.clone());
            for step in params.steps() {
                if matches!(step, Step::Outliers { .. }) {
                    before_outliers = current.clone();
                }
                if step == Step::LocalOutliers {
                    before_local = current.clone();
                }
                let earlier = Earlier {
                    before_outliers: Cow::Borrowed(&before_outliers),
                    before_local: Cow::Borrowed(
                        if step == Step::ConfirmGivenBack && before_local == current {
                            &current
                        } else {
                            &before_local
                        },
                    ),
                };
                let given = graph.is_some();
                let with = step.run(&tri, &current, earlier.clone(), graph.take());
                let without = step.run(&tri, &current, earlier, None);
                assert_eq!(
                    with.edges, without.edges,
                    "seed {seed}, {step:?}, given {given}"
                );
                let output = with.edges.unwrap_or_else(|| current.clone());
                if let Some(g) = &with.graph {
                    assert_eq!(*g, CurveGraph::new(n, &output), "seed {seed}, {step:?}");
                }
                graph = with.graph;
                current = output;
            }
            // Where no stage changes anything (no noise, no outliers), the local outlier
            // removal's graph reaches the curves.
            let clean = sampling.noise == 0.0 && sampling.outlier_fraction == 0.0;
            clean_reaching_the_end += usize::from(clean && graph.is_some());
            clean_seeds += usize::from(clean);
        }
        assert_eq!(clean_reaching_the_end, clean_seeds);
    }
}
