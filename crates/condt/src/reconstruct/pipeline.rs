//! The [`Pipeline`] runs a reconstruction step by step ([`reconstruct`] to the end): the first
//! graph, each of [`Params::stages`], the last graph's tally; with smoothing on, a noisy run is
//! followed by a smoothing pass and a new run until two agree or [`MAX_PASSES`] ran. It owns runs,
//! passes, clocks and their thread ([`on_worker`]); it may not implement nor order stages.

use super::history::{History, StageRecord, Undo, FIRST_KEPT_UP_TO};
use super::params::{Method, Params};
use super::result::{
    degrees_of, edges_in_input_positions, Degrees, Reconstruction, Smoothing, StageReport,
};
use crate::adjacency::{CurveGraph, Edge};
use crate::curve::curves_in_input_positions;
use crate::error::Error;
use crate::geometry::Point;
use crate::graph::Graph;
use crate::mesh::VertexId;
use crate::smooth::{
    keep_apart, repeats, shows_noise, smoothed_positions, unmoved, PassInput, MAX_PASSES,
};
use crate::stages::{proximity, Earlier, Stage, Step, PARALLEL_FROM};
use crate::threads::both;
use crate::triangulate::{choose_frames, splitmix64_finalizer, triangulate_with, Triangulation};
use alloc::borrow::Cow;
use alloc::vec::Vec;
use core::sync::atomic::AtomicUsize;
use core::time::Duration;

/// A reconstruction run one step at a time: [`step`](Pipeline::step) runs and reports the next
/// stage or smoothing pass, [`finish`](Pipeline::finish) the rest; [`reconstruct`] is this loop.
///
/// ```
/// use condt::{Params, Pipeline, Point, StepReport};
/// let angles = (0..24).map(|k| k as f64 * std::f64::consts::TAU / 24.0);
/// let points: Vec<Point> = angles.map(|t| Point::new(2.0 * t.cos(), t.sin())).collect();
/// let mut pipeline = Pipeline::new(&points, &Params::default())?;
/// while let Some(step) = pipeline.step()? {
///     if let StepReport::Stage(r) = step {
///         println!("{}: {} edges", r.stage, r.graph.num_edges());
///     }
/// }
/// assert_eq!(pipeline.finish()?.curves().len(), 1);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Debug)]
pub struct Pipeline {
    params: Params,
    state: State,
    /// What the passes did so far, their time included (`None` until one ran).
    smoothing: Option<Smoothing>,
    /// Laps at the ends of triangulations and smoothings: what lies between is a run's cost.
    pass_clock: Stopwatch,
}

/// What one [`Pipeline::step`] did.
///
/// ```
/// use condt::{Params, Pipeline, Point, Stage, StepReport};
/// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
/// let mut pipeline = Pipeline::new(&points, &Params::paper())?;
/// let Some(StepReport::Stage(first)) = pipeline.step()? else { panic!("a stage is first") };
/// assert_eq!((first.stage, first.graph.num_edges()), (Stage::Proximity, 3));
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum StepReport<'p> {
    /// A stage ran: its report, with the graph it left.
    Stage(StageReport<'p>),
    /// A smoothing pass ([`Params::smooth`]): points moved and triangulated again for a new run.
    SmoothingPass {
        /// Which pass (the first is 1).
        pass: usize,
        /// How many points it moved.
        moved: usize,
        /// The wall-clock time of the triangulation of the moved points (zero without `std` and
        /// on `wasm32-unknown-unknown`).
        time: Duration,
    },
}

/// What [`Pipeline::step`] runs next ([`Pipeline::upcoming`]).
///
/// ```
/// use condt::{Params, Pipeline, Point, Upcoming};
/// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
/// let mut pipeline = Pipeline::new(&points, &Params::paper())?;
/// let mut seen = Vec::new();
/// while let Some(next) = pipeline.upcoming() {
///     seen.push(next);
///     pipeline.step()?;
/// }
/// assert!(seen.into_iter().eq(Params::paper().stages().into_iter().map(Upcoming::Stage)));
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Upcoming {
    /// A stage.
    Stage(Stage),
    /// A smoothing pass: the points move and are triangulated again.
    SmoothingPass,
}

#[derive(Debug)]
enum State {
    Stages(Run),
    /// A run ended showing noise (or differing from the run before): a smoothing pass is next.
    Smooth(Reconstruction, PassInput),
    Done(Reconstruction),
    /// A step failed (its error was returned), leaving nothing to go on with.
    Failed(Error),
    /// Only while a step moves the state from one variant to the next, and after a step that
    /// panicked (a caller that caught the panic gets a second one, saying so, at the next step).
    Moving,
}

#[derive(Debug)]
struct Run {
    tri: Triangulation,
    triangulation_time: Duration,
    history: History,
    /// The latest stage's output; each stage's record keeps only how to get its input back.
    current: Vec<Edge>,
    /// The curve graph of `current` when the last stage handed one on (`Outcome::graph`).
    current_graph: Option<CurveGraph>,
    assembly: CurveAssembly,
    /// The previous run's final edges, for the fixed-point test of a pass another may follow.
    previous: Option<EdgesFingerprint>,
}

/// When a run's curves are assembled: only the final run's are read (others are dead memory).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum CurveAssembly {
    /// The final one: the curves are assembled beside the final degrees.
    Now,
    /// The first run when passes may follow: no curves if its degrees show noise ([`shows_noise`]).
    UnlessNoisy,
    /// A pass that another may follow: the curves wait until the fixed-point test says.
    Later,
}

impl Pipeline {
    /// Triangulates `points` and readies the stages; nothing else runs until `step` or `finish`.
    ///
    /// # Errors
    /// [`Params::check`]'s error (checked first); as [`triangulate`](crate::triangulate());
    /// [`Error::TooCloseToMeasure`] when two points are too close for the stages to measure
    /// beside the largest coordinate; for the Crust, [`Error::TooManyPoints`] when its second
    /// triangulation would be too large.
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let pipeline = Pipeline::new(&points, &Params::paper())?;
    /// assert_eq!(pipeline.triangulation().map(|t| t.num_points()), Some(3));
    /// assert!(Pipeline::new(&[Point::new(f64::NAN, 0.0)], &Params::paper()).is_err());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn new(points: &[Point], params: &Params) -> Result<Pipeline, Error> {
        Pipeline::of_input(Cow::Borrowed(points), params, None)
    }

    /// [`Pipeline::new`] on points handed over, freed once triangulated (the stages do without).
    ///
    /// # Errors
    /// As [`Pipeline::new`].
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// let points = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.5, 1.0)];
    /// assert_eq!(Pipeline::new_owned(points, &Params::paper())?.finish()?.edges().len(), 3);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn new_owned(points: Vec<Point>, params: &Params) -> Result<Pipeline, Error> {
        Pipeline::of_input(Cow::Owned(points), params, None)
    }

    /// [`Pipeline::new_owned`], adding to `inserted` as points are inserted (about every 65,536,
    /// from any thread, up to the number of distinct points) so another thread shows progress.
    ///
    /// # Errors
    /// As [`Pipeline::new`].
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// use std::sync::atomic::{AtomicUsize, Ordering};
    /// let points = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.5, 1.0)];
    /// let inserted = AtomicUsize::new(0);
    /// Pipeline::new_owned_observed(points, &Params::paper(), &inserted)?;
    /// assert_eq!(inserted.load(Ordering::Relaxed), 3);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn new_owned_observed(
        points: Vec<Point>,
        params: &Params,
        inserted: &AtomicUsize,
    ) -> Result<Pipeline, Error> {
        Pipeline::of_input(Cow::Owned(points), params, Some(inserted))
    }

    /// The stages on a triangulation already built, which the result keeps (no smoothing passes).
    ///
    /// # Errors
    /// [`Params::check`]'s error; [`Error::TooCloseToMeasure`] and, for the Crust,
    /// [`Error::TooManyPoints`] (as [`Pipeline::new`]).
    ///
    /// ```
    /// use condt::{triangulate, Params, Pipeline, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from))?;
    /// let result = Pipeline::on_triangulation(tri, &Params::paper())?.finish()?;
    /// assert_eq!(result.edges().collect::<Vec<_>>(), vec![[0, 1], [0, 2], [1, 2]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn on_triangulation(tri: Triangulation, params: &Params) -> Result<Pipeline, Error> {
        Pipeline::start(tri, Duration::ZERO, params, false, Stopwatch::start())
    }

    fn of_input(
        points: Cow<'_, [Point]>,
        params: &Params,
        inserted: Option<&AtomicUsize>,
    ) -> Result<Pipeline, Error> {
        params.check()?;
        let params = &params.on_available_threads(points.len());
        let mut clock = Stopwatch::start();
        // On the stages' worker: their allocations reuse what it freed (`on_worker`).
        // Points handed over are freed by the triangulator once it no longer reads them.
        let tri = on_worker(params.parallel, points.len(), || {
            triangulate_with(points, params.parallel, inserted, None)
        })?;
        let triangulation_time = clock.lap();
        let may_smooth = params.smooth && params.method == Method::ConDT;
        Pipeline::start(tri, triangulation_time, params, may_smooth, clock)
    }

    fn start(
        tri: Triangulation,
        triangulation_time: Duration,
        params: &Params,
        may_smooth: bool,
        pass_clock: Stopwatch,
    ) -> Result<Pipeline, Error> {
        params.check()?;
        // The parameters it runs with: smoothing off where no pass can run (a triangulation
        // given, a baseline method), as `parallel` is off where no thread can start (asked only
        // of sets large enough to use threads).
        let params = &params
            .on_available_threads(tri.num_points())
            .with_smooth(params.smooth && may_smooth);
        if let Some((first, second)) = tri.too_close_to_measure() {
            let largest = tri.input_of_largest();
            return Err(Error::TooCloseToMeasure {
                first,
                second,
                largest,
            });
        }
        if params.method == Method::Crust {
            crate::baselines::crust_fits(&tri)?;
        }
        Ok(Pipeline {
            params: *params,
            state: State::Stages(Run::new(tri, triangulation_time, may_smooth, None)),
            smoothing: None,
            pass_clock,
        })
    }

    /// The parameters it runs with.
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let pipeline = Pipeline::new(&points, &Params::paper())?;
    /// assert_eq!(pipeline.params().stages(), Params::paper().stages());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The triangulation the stages walk now (of the moved points after a pass); `None` on failure.
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let pipeline = Pipeline::new(&points, &Params::paper())?;
    /// assert_eq!(pipeline.triangulation().map(|t| t.triangles().count()), Some(1));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangulation(&self) -> Option<&Triangulation> {
        match &self.state {
            State::Stages(run) => Some(&run.tri),
            State::Smooth(result, _) | State::Done(result) => Some(result.triangulation()),
            State::Failed(_) | State::Moving => None,
        }
    }

    /// What the next [`step`](Pipeline::step) runs; `None` once every step has run or one failed.
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point, Stage, Upcoming};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let mut pipeline = Pipeline::new(&points, &Params::paper())?;
    /// assert_eq!(pipeline.upcoming(), Some(Upcoming::Stage(Stage::Proximity)));
    /// while pipeline.step()?.is_some() {}
    /// assert_eq!(pipeline.upcoming(), None);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn upcoming(&self) -> Option<Upcoming> {
        match &self.state {
            State::Stages(run) => {
                let next = self.params.stages().get(run.history.records.len()).copied();
                next.map(Upcoming::Stage)
            }
            State::Smooth(..) => Some(Upcoming::SmoothingPass),
            State::Done(_) | State::Failed(_) | State::Moving => None,
        }
    }

    /// Whether every step has run: [`finish`](Pipeline::finish) returns at once.
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let mut pipeline = Pipeline::new(&points, &Params::paper())?;
    /// assert!(!pipeline.is_done());
    /// while pipeline.step()?.is_some() {}
    /// assert!(pipeline.is_done());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn is_done(&self) -> bool {
        matches!(self.state, State::Done(_) | State::Failed(_))
    }

    /// Runs the next stage or smoothing pass and reports it; `None` once every step has run.
    ///
    /// # Errors
    /// As [`triangulate`](crate::triangulate()) when a pass triangulates the moved points (never
    /// in practice: they lie between input points); later steps and `finish` repeat the error.
    ///
    /// # Panics
    /// Only when a step panicked before (a bug) and the caller caught it: the pipeline's state
    /// went with the unwinding, and this says so instead of running on half a state.
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point, Stage, StepReport};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let mut pipeline = Pipeline::new(&points, &Params::paper())?;
    /// pipeline.step()?; // the proximity graph
    /// let Some(StepReport::Stage(repair)) = pipeline.step()? else { panic!("a stage is next") };
    /// assert!(repair.stage == Stage::Repair && !repair.applied); // no point has three edges
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn step(&mut self) -> Result<Option<StepReport<'_>>, Error> {
        match core::mem::replace(&mut self.state, State::Moving) {
            State::Stages(mut run) => {
                let k = run.history.records.len();
                let n = run.tri.num_points();
                on_worker(self.params.parallel, n, || run.run_stage(&self.params));
                self.state = if run.history.records.len() > self.params.steps().count() {
                    self.end_of_run(run)
                } else {
                    State::Stages(run)
                };
                Ok(Some(StepReport::Stage(self.report(k))))
            }
            State::Smooth(result, input) => {
                let n = result.triangulation().num_points();
                let pass = on_worker(self.params.parallel, n, || {
                    self.smoothing_pass(result, input)
                });
                Ok(Some(pass.inspect_err(|&e| self.state = State::Failed(e))?))
            }
            State::Done(result) => {
                self.state = State::Done(result);
                Ok(None)
            }
            State::Failed(error) => {
                self.state = State::Failed(error);
                Err(error)
            }
            State::Moving => {
                panic!("a step of this Pipeline panicked earlier, leaving nothing to go on with")
            }
        }
    }

    /// Runs every step left and gives the result.
    ///
    /// # Errors
    /// As [`step`](Pipeline::step).
    ///
    /// ```
    /// use condt::{Params, Pipeline, Point};
    /// let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    /// let result = Pipeline::new(&points, &Params::paper())?.finish()?;
    /// assert!(result.curves().len() == 1 && result.curves()[0].is_closed());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn finish(mut self) -> Result<Reconstruction, Error> {
        while self.step()?.is_some() {}
        match self.state {
            State::Done(result) => Ok(result),
            // A failed step returned its error above.
            _ => unreachable!("the steps ran to the end"),
        }
    }

    /// The report of the `k`-th stage of the current run, which has just run.
    fn report(&self, k: usize) -> StageReport<'_> {
        match &self.state {
            State::Stages(run) => {
                let graph = Graph::new(&run.tri, Cow::Borrowed(&run.current));
                run.history.records[k].report(k, graph)
            }
            State::Smooth(result, _) | State::Done(result) => result.report(k),
            State::Failed(_) | State::Moving => unreachable!("a stage that ran leaves a state"),
        }
    }

    /// What follows a run's last stage: its tally, then a smoothing pass or the result.
    fn end_of_run(&mut self, run: Run) -> State {
        let previous = run.previous;
        let (mut result, waiting) = run.finish(&self.params);
        // Curves wait after a noisy first run (no `previous`) and after a pass another may follow,
        // which is final at a fixed point: the same final edges as the pass before.
        if let Some(pass) = waiting {
            if previous.is_none_or(|edges| edges != EdgesFingerprint::of(&result.edges)) {
                return State::Smooth(result, pass);
            }
            result.assemble_curves(pass.into_graph());
        }
        result.smoothing = self.smoothing;
        State::Done(result)
    }

    /// Moves `result`'s points along its curves and triangulates them again for the next run.
    fn smoothing_pass(
        &mut self,
        mut result: Reconstruction,
        pass: PassInput,
    ) -> Result<StepReport<'static>, Error> {
        let mut smoothing = self.smoothing.unwrap_or_default();
        // Memory: of the previous run only its edge fingerprint (none for a last pass),
        // triangulation (whose arrays hold the next) and final curve graph are kept, each freed
        // once read.
        let last_pass = smoothing.passes + 1 >= MAX_PASSES;
        let previous = (!last_pass).then(|| EdgesFingerprint::of(&result.edges));
        drop(core::mem::take(&mut result.edges));
        let (triangulation, triangulation_time) = result.into_last_triangulation();
        let mut smoothed = smoothed_positions(&triangulation, &pass, false);
        let merged_before = triangulation.num_points() - triangulation.num_vertices();
        // Relative to the corner (or `smooth::PassFrame`'s own frame); where that merges distinct
        // points, those stay where they were, and where even that merges, the pass is made in the
        // run's own input frame, computed only then (docs/condt.md, *Smoothing passes*). `repeats`
        // counts what the triangulation merges; a wide set is given both at once, and its next
        // triangulation tells whether points merged.
        let relative_merges = repeats(&smoothed.positions) > merged_before
            || choose_frames(&smoothed.positions).is_ok_and(|frames| frames.wide);
        let (mut back, mut back_in_run_frame) = (0, 0);
        if relative_merges {
            smoothed = smoothed_positions(&triangulation, &pass, true);
            back = keep_apart(
                &mut smoothed.positions,
                unmoved(&triangulation, smoothed.own_frame),
            );
            let original = |i: usize| triangulation.frame_point(triangulation.vertex(i));
            back_in_run_frame = keep_apart(&mut smoothed.in_run_frame, original);
        }
        drop(pass);
        // The replaced run's triangulation is an earlier pass's cost too.
        smoothing.earlier_passes += triangulation_time;
        smoothing.earlier_passes += self.pass_clock.lap();
        let parallel = self.params.parallel;
        let run_offset = triangulation.frame_offset();
        let relative = triangulate_with(&smoothed.positions, parallel, None, Some(triangulation))?;
        let merges_more = relative.num_points() - relative.num_vertices() > merged_before;
        debug_assert!(
            relative_merges || !merges_more,
            "`repeats` counts what the triangulation merges"
        );
        let (tri, moved) = if merges_more && relative_merges {
            let framed = triangulate_with(&smoothed.in_run_frame, parallel, None, Some(relative))?;
            // `keep_apart` puts back only points that moved, counted in the same frame.
            let moved = smoothed.moved_in_run_frame - back_in_run_frame;
            (framed.with_frame_offset(run_offset), moved)
        } else {
            (relative.with_offset(smoothed.corner), smoothed.moved - back)
        };
        drop(smoothed);
        let triangulation_time = self.pass_clock.lap();
        smoothing.passes += 1;
        smoothing.moved = moved;
        self.smoothing = Some(smoothing);
        self.state = State::Stages(Run::new(tri, triangulation_time, false, previous));
        Ok(StepReport::SmoothingPass {
            pass: smoothing.passes,
            moved,
            time: triangulation_time,
        })
    }
}

impl Run {
    /// A run on `tri`: with `previous`, a pass another may follow; else with `may_smooth`, a first
    /// run that passes may follow; else a final run (the last pass, or a run without passes).
    fn new(
        tri: Triangulation,
        triangulation_time: Duration,
        may_smooth: bool,
        previous: Option<EdgesFingerprint>,
    ) -> Run {
        let assembly = match previous {
            Some(_) => CurveAssembly::Later,
            None if may_smooth => CurveAssembly::UnlessNoisy,
            None => CurveAssembly::Now,
        };
        Run {
            tri,
            triangulation_time,
            history: History {
                records: Vec::with_capacity(6),
            },
            current: Vec::new(),
            current_graph: None,
            assembly,
            previous,
        }
    }

    /// Runs the next stage: the first graph, then each step in order.
    fn run_stage(&mut self, params: &Params) {
        let mut clock = Stopwatch::start();
        let k = self.history.records.len();
        if k == 0 {
            self.current = first_graph(&self.tri, params);
            self.history.records.push(StageRecord {
                stage: params.first_stage(),
                undo: Undo::Unchanged,
                time: clock.lap(),
            });
            return;
        }
        let Some(step) = params.steps().nth(k - 1) else {
            return;
        };
        let held = match step {
            Step::RepairAgain { .. } => self.history.take_held(),
            _ => None,
        };
        let (tri, history, current) = (&self.tri, &self.history, &self.current);
        // An earlier stage's input, rebuilt only for the step that reads it, only while it runs.
        let first = || first_graph(tri, params);
        let input_of = |stage: Stage, read: bool| {
            if read {
                history.input_of(stage, current, &first)
            } else {
                Cow::Borrowed(current.as_slice())
            }
        };
        // Repairing again reads the proximity graph only when the IQR stage cut an edge: the one
        // the repair's record held, else walked back (a delta) or rebuilt (`Undo::First`).
        let cut = history
            .records
            .iter()
            .any(|r| r.stage == Stage::Outliers && !matches!(r.undo, Undo::Unchanged));
        let reads = step.reads();
        let reads_first = reads.before_repair && cut;
        let before_repair = held
            .filter(|_| reads_first)
            .map_or_else(|| input_of(Stage::Repair, reads_first), Cow::Owned);
        // Repairing again reads the lengths of the IQR stage's input: its output and cut edges.
        let cut_by_outliers = match step {
            Step::RepairAgain { .. } => history.removed_by_last(Stage::Outliers),
            _ => None,
        };
        let earlier = Earlier {
            before_outliers: input_of(
                Stage::Outliers,
                reads.before_outliers && cut_by_outliers.is_none(),
            ),
            cut_by_outliers,
            before_local: input_of(Stage::LocalOutliers, reads.before_local),
            before_repair,
        };
        let graph = self.current_graph.take();
        let outcome = step.run(tri, current, earlier, graph, params.parallel);
        self.current_graph = outcome.graph;
        let undo = match outcome.edges {
            None => Undo::Unchanged,
            Some(output) => {
                let input = core::mem::replace(&mut self.current, output);
                // Only the repair's record may stand for the first graph (see FIRST_KEPT_UP_TO).
                let reads_first = k == 1 && matches!(step, Step::Repair(_));
                // `r * K > len` as `r > len / K` (the same for integers), which cannot overflow.
                if reads_first
                    && Undo::removals(&input, &self.current) > input.len() / FIRST_KEPT_UP_TO
                {
                    let repairs_again = params
                        .steps()
                        .any(|s| matches!(s, Step::RepairAgain { .. }));
                    if repairs_again {
                        Undo::Held(input)
                    } else {
                        Undo::First
                    }
                } else {
                    Undo::of(input, &self.current)
                }
            }
        };
        // A handed-on graph must be the curve graph of exactly the list the next stage reads.
        debug_assert!(self
            .current_graph
            .as_ref()
            .is_none_or(|graph| *graph == CurveGraph::new(self.tri.num_points(), &self.current)));
        self.history.records.push(StageRecord {
            stage: step.stage(),
            undo,
            time: clock.lap(),
        });
    }

    /// The tally and the curves, or the pass that follows when they wait (not
    /// [`CurveAssembly::Now`]).
    fn finish(self, params: &Params) -> (Reconstruction, Option<PassInput>) {
        let mut clock = Stopwatch::start();
        let tri = &self.tri;
        let n = tri.num_points();
        let in_parallel = params.parallel && n >= PARALLEL_FROM;
        let (waiting, curves, degrees, unused, edges) = on_worker(in_parallel, n, || {
            let last = self.current.as_slice();
            let graph = self
                .current_graph
                .unwrap_or_else(|| CurveGraph::new(n, last));
            let pass = match self.assembly {
                CurveAssembly::Now => Err(graph),
                // Without duplicates the input positions name the ids one to one, so the count
                // reads the records in memory order instead of the input's (speed).
                CurveAssembly::UnlessNoisy => {
                    let noisy = if tri.num_vertices() == n {
                        shows_noise((0..n as u32).map(|v| graph.degree(VertexId::new(v))))
                    } else {
                        shows_noise(tri.input_to_vertex().iter().map(|&v| graph.degree(v)))
                    };
                    if noisy {
                        PassInput::moving(tri, graph)
                    } else {
                        Err(graph)
                    }
                }
                // A pass that would move no point would give this result again.
                CurveAssembly::Later => PassInput::moving(tri, graph),
            };
            let room = Degrees::with_room(n);
            let (waiting, curves, (degrees, unused)) = match pass {
                Ok(pass) => {
                    let degrees = degrees_of(tri, pass.graph(), room);
                    (Some(pass), Vec::new(), degrees)
                }
                Err(graph) => {
                    let (curves, degrees) = both(
                        in_parallel,
                        || curves_in_input_positions(tri, &graph),
                        || degrees_of(tri, &graph, room),
                    );
                    (None, curves, degrees)
                }
            };
            // After a final run's graph is freed (memory: it is not alive beside these nor
            // beside the curves' scratch); a run a pass follows keeps it in the pass's input.
            let edges = edges_in_input_positions(tri, last, in_parallel);
            (waiting, curves, degrees, unused, edges)
        });
        let curves_time = clock.lap();
        let result = Reconstruction {
            params: *params,
            triangulation: self.tri,
            history: self.history,
            final_edges: self.current,
            edges,
            degrees,
            curves,
            unused,
            triangulation_time: self.triangulation_time,
            curves_time,
            smoothing: None,
        };
        (result, waiting)
    }
}

/// Triangulates `points` and reconstructs the curves through them ([`Pipeline::new`] to the end).
///
/// # Errors
/// As [`Pipeline::new`] and [`Pipeline::step`].
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let angles = (0..12).map(|k| k as f64 * std::f64::consts::TAU / 12.0);
/// let circle: Vec<Point> = angles.map(|t| Point::new(t.cos(), t.sin())).collect();
/// let result = reconstruct(&circle, &Params::default())?;
/// assert!(result.curves().len() == 1 && result.curves()[0].is_closed());
/// assert!(result.edges().len() == 12 && result.unused().is_empty());
/// # Ok::<(), condt::Error>(())
/// ```
pub fn reconstruct(points: &[Point], params: &Params) -> Result<Reconstruction, Error> {
    Pipeline::new(points, params)?.finish()
}

/// [`reconstruct`] of points handed over, freed once triangulated (16 bytes per point less at the
/// peak); the result keeps only the positions the stages saw ([`Reconstruction::stage_point`]).
///
/// # Errors
/// As [`reconstruct`].
///
/// ```
/// use condt::{reconstruct, reconstruct_owned, Params, Point};
/// let angles = (0..40).map(|k| k as f64 * std::f64::consts::TAU / 40.0);
/// let points: Vec<Point> = angles.map(|t| Point::new(t.cos(), (2.0 * t).sin())).collect();
/// let borrowed = reconstruct(&points, &Params::default())?;
/// let owned = reconstruct_owned(points, &Params::default())?;
/// assert_eq!(owned.edges().collect::<Vec<_>>(), borrowed.edges().collect::<Vec<_>>());
/// assert_eq!(owned.curves(), borrowed.curves());
/// # Ok::<(), condt::Error>(())
/// ```
pub fn reconstruct_owned(points: Vec<Point>, params: &Params) -> Result<Reconstruction, Error> {
    Pipeline::new_owned(points, params)?.finish()
}

/// [`Pipeline::on_triangulation`] run to its end: the stages on a triangulation the result keeps.
///
/// # Errors
/// As [`Pipeline::on_triangulation`].
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
    Pipeline::on_triangulation(tri, params)?.finish()
}

/// The first stage's graph of a reconstruction on `tri` with `params`, as the run computed it.
pub(super) fn first_graph(tri: &Triangulation, params: &Params) -> Vec<Edge> {
    match params.method {
        Method::ConDT => proximity::proximity_graph(tri, params.uniformity, params.parallel),
        Method::NnCrust => crate::baselines::nn_crust_edges(tri),
        // The pipeline checked that it fits (`crust_fits`), the one way it fails.
        Method::Crust => crate::baselines::crust_edges(tri, params.parallel).unwrap_or_default(),
    }
}

/// A pass's final edges as the fixed-point test keeps them (memory): count and two 64-bit hashes.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) struct EdgesFingerprint {
    len: usize,
    pub(super) hashes: [u64; 2],
}

impl EdgesFingerprint {
    pub(super) fn of(edges: &[[u32; 2]]) -> EdgesFingerprint {
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

/// The 64-bit finalizer of MurmurHash3 (Appleby), a bijection of `u64`.
fn murmur3_finalizer(mut z: u64) -> u64 {
    z = (z ^ (z >> 33)).wrapping_mul(0xff51_afd7_ed55_8ccd);
    z = (z ^ (z >> 33)).wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    z ^ (z >> 33)
}

/// A clock that reads zero without `std`, and on WebAssembly without an operating system.
#[derive(Debug)]
pub(super) struct Stopwatch {
    #[cfg(feature = "std")]
    start: Option<std::time::Instant>,
}

/// Now, where `std` has a clock: on `wasm32-unknown-unknown` its `Instant::now` panics, and
/// every `reconstruct` trapped there with the default features (a web developer's check).
#[cfg(feature = "std")]
fn now() -> Option<std::time::Instant> {
    let no_clock = cfg!(all(target_family = "wasm", target_os = "unknown"));
    (!no_clock).then(std::time::Instant::now)
}

impl Stopwatch {
    pub(super) fn start() -> Self {
        Stopwatch {
            #[cfg(feature = "std")]
            start: now(),
        }
    }

    pub(super) fn lap(&mut self) -> Duration {
        #[cfg(feature = "std")]
        if let (Some(now), Some(start)) = (now(), self.start.as_mut()) {
            return now - core::mem::replace(start, now);
        }
        Duration::ZERO
    }
}

/// Runs `work` on rayon's first worker thread when `parallel` and `n` points reach the stages'
/// threshold: called from outside the pool, rayon leaves its workers spinning beside the
/// sequential stages that follow. Always the same worker: glibc's malloc keeps what each thread's
/// arena freed, so stages on whichever worker was free would each grow an arena to their peak.
pub(super) fn on_worker<R: Send>(parallel: bool, n: usize, work: impl FnOnce() -> R + Send) -> R {
    #[cfg(feature = "parallel")]
    if parallel && n >= PARALLEL_FROM && rayon::current_thread_index() != Some(0) {
        let work = std::sync::Mutex::new(Some(work));
        let mut results = rayon::broadcast(|context| match context.index() {
            0 => work.lock().ok()?.take().map(|work| work()),
            _ => None,
        });
        return results
            .swap_remove(0)
            .expect("the first worker ran the work");
    }
    let _ = (parallel, n);
    work()
}

#[cfg(feature = "parallel")]
#[cfg(test)]
mod tests {
    use super::on_worker;
    use crate::stages::PARALLEL_FROM;

    /// Every call runs on the same worker, the pool's first, whichever thread asks.
    #[test]
    fn on_worker_runs_on_the_first_worker() {
        let index = || rayon::current_thread_index();
        assert_eq!(on_worker(true, PARALLEL_FROM, index), Some(0));
        assert_eq!(on_worker(false, PARALLEL_FROM, index), None);
        assert_eq!(on_worker(true, PARALLEL_FROM - 1, index), None);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        let from_workers: Vec<_> = pool.broadcast(|_| on_worker(true, PARALLEL_FROM, index));
        assert_eq!(from_workers, vec![Some(0); 3]);
    }
}
