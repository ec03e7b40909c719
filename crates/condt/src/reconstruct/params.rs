//! What a reconstruction runs: the [`Method`] and its [`Params`], and the order of the stages.
//!
//! Owns: the parameters, their check, and [`Params::stages`], the one place where the order of
//! the stages is decided. It may not run a stage (that is the pipeline) nor implement one (that
//! is [`crate::stages`]).

use crate::error::Error;
use crate::stages::{Repair, Stage, Step, Uniformity};
#[cfg(doc)]
use crate::{reconstruct, reconstruct_triangulation, Reconstruction, Triangulation};
use alloc::vec::Vec;

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
/// let params = Params::default().with_method(Method::NnCrust);
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
/// let bad = p.with_outlier_factor(Some(f64::NAN));
/// assert!(bad.check().is_err());
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
#[non_exhaustive]
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
    /// Remove components fewer than half of whose points a curve passes smoothly and evenly
    /// (not in the paper): clumps of outliers, which the local outlier removal keeps because
    /// they lie apart from everything else. Runs after the local outlier removal and its
    /// given-back check; removes nothing when that would remove a quarter of the points with
    /// edges. On by default, off in [`Params::paper`]; the rule and its reasons are in
    /// `src/stages/clumps.rs`.
    pub clumps: bool,
    /// Join a loose end to the curve it meets where three curves meet (not in the paper): map
    /// borders, a T in a drawing. Runs last, after closing gaps; the junction needs three
    /// branches of at least five points each, sampled alike. On by default, off in
    /// [`Params::paper`]; the rule and its reasons are in `src/stages/junctions.rs`.
    pub junctions: bool,
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
    ///         Stage::Clumps,
    ///         Stage::GivenBack,
    ///         Stage::Gaps,
    ///         Stage::Junctions
    ///     ]
    /// );
    /// ```
    fn default() -> Self {
        Params::paper()
            .with_repair(Repair::Needs)
            .with_local_outliers(true)
            .with_confirm_given_back(true)
            .with_clumps(true)
            .with_close_gaps(true)
            .with_junctions(true)
            .with_smooth(true)
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
            clumps: false,
            junctions: false,
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
    /// let p = Params::paper().with_outliers_first(true).with_repair(Repair::Off);
    /// assert_eq!(p.stages(), vec![Stage::Proximity, Stage::Outliers]);
    /// let local = Params::paper().with_outliers_first(true).with_local_outliers(true);
    /// assert_eq!(
    ///     local.stages(),
    ///     vec![Stage::Proximity, Stage::Outliers, Stage::Repair, Stage::LocalOutliers]
    /// );
    /// let q = Params::paper().with_close_gaps(true);
    /// assert_eq!(q.stages().last(), Some(&Stage::Gaps));
    /// ```
    pub fn stages(&self) -> Vec<Stage> {
        core::iter::once(self.first_stage())
            .chain(self.steps().map(Step::stage))
            .collect()
    }

    /// The graph built on the triangulation: ConDT's proximity graph or a baseline.
    pub(super) fn first_stage(&self) -> Stage {
        match self.method {
            Method::ConDT => Stage::Proximity,
            Method::NnCrust => Stage::NnCrust,
            Method::Crust => Stage::Crust,
        }
    }

    /// The steps after the proximity graph, in order: the one place the order is decided.
    pub(crate) fn steps(&self) -> impl Iterator<Item = Step> {
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
        // Clumps are whole components; they go before the joins so that no join reaches one.
        let clumps = self.clumps.then_some(Step::RemoveClumps);
        let gaps = self.close_gaps.then_some(Step::CloseGaps);
        // Junctions come after the gaps: an end that a gap join or a crossing claims is not a
        // junction's.
        let junctions = self.junctions.then_some(Step::JoinJunctions);
        // A baseline is the whole method: no ConDT stage follows it.
        let condt = self.method == Method::ConDT;
        first
            .into_iter()
            .chain(second)
            .chain(local)
            .chain(clumps)
            .chain(confirm)
            .chain(gaps)
            .chain(junctions)
            .filter(move |_| condt)
    }
}

impl Params {
    /// These parameters with `parallel` off when rayon's threads cannot run
    /// ([`parallel_available`](crate::parallel_available)): what a reconstruction runs with,
    /// and what its result reports.
    pub(crate) fn on_available_threads(self) -> Params {
        if self.parallel && !crate::threads::parallel_available() {
            self.with_parallel(false)
        } else {
            self
        }
    }

    /// Turns `stage` on or off, for the stages with a [`Switch`](crate::stages::Switch)
    /// ([`Stage::switch`]); `false` for any other stage, which is left as it is.
    ///
    /// ```
    /// use condt::{Params, Stage};
    /// let mut p = Params::default();
    /// assert!(p.set_stage(Stage::Gaps, false));
    /// assert!(!p.close_gaps && !p.stages().contains(&Stage::Gaps));
    /// assert!(!p.set_stage(Stage::Proximity, false));
    /// ```
    pub fn set_stage(&mut self, stage: Stage, on: bool) -> bool {
        let field = match stage {
            Stage::LocalOutliers => &mut self.local_outliers,
            Stage::GivenBack => &mut self.confirm_given_back,
            Stage::Clumps => &mut self.clumps,
            Stage::Gaps => &mut self.close_gaps,
            Stage::Junctions => &mut self.junctions,
            _ => return false,
        };
        *field = on;
        true
    }
}

/// Chainable setters, one per field, so that a pipeline is spelled from a preset:
/// `Params::paper().with_repair(Repair::Needs)`.
///
/// ```
/// use condt::{Params, Repair};
/// let p = Params::paper().with_repair(Repair::Needs).with_smooth(true);
/// assert_eq!(p.repair, Repair::Needs);
/// assert!(p.smooth && !p.close_gaps);
/// ```
impl Params {
    /// Sets [`Params::method`].
    pub fn with_method(mut self, method: Method) -> Params {
        self.method = method;
        self
    }

    /// Sets [`Params::uniformity`].
    pub fn with_uniformity(mut self, uniformity: Uniformity) -> Params {
        self.uniformity = uniformity;
        self
    }

    /// Sets [`Params::repair`].
    pub fn with_repair(mut self, repair: Repair) -> Params {
        self.repair = repair;
        self
    }

    /// Sets [`Params::outlier_factor`].
    pub fn with_outlier_factor(mut self, outlier_factor: Option<f64>) -> Params {
        self.outlier_factor = outlier_factor;
        self
    }

    /// Sets [`Params::outliers_first`].
    pub fn with_outliers_first(mut self, outliers_first: bool) -> Params {
        self.outliers_first = outliers_first;
        self
    }

    /// Sets [`Params::local_outliers`].
    pub fn with_local_outliers(mut self, local_outliers: bool) -> Params {
        self.local_outliers = local_outliers;
        self
    }

    /// Sets [`Params::confirm_given_back`].
    pub fn with_confirm_given_back(mut self, confirm_given_back: bool) -> Params {
        self.confirm_given_back = confirm_given_back;
        self
    }

    /// Sets [`Params::close_gaps`].
    pub fn with_close_gaps(mut self, close_gaps: bool) -> Params {
        self.close_gaps = close_gaps;
        self
    }

    /// Sets [`Params::clumps`].
    pub fn with_clumps(mut self, clumps: bool) -> Params {
        self.clumps = clumps;
        self
    }

    /// Sets [`Params::junctions`].
    pub fn with_junctions(mut self, junctions: bool) -> Params {
        self.junctions = junctions;
        self
    }

    /// Sets [`Params::smooth`].
    pub fn with_smooth(mut self, smooth: bool) -> Params {
        self.smooth = smooth;
        self
    }

    /// Sets [`Params::parallel`].
    pub fn with_parallel(mut self, parallel: bool) -> Params {
        self.parallel = parallel;
        self
    }
}
