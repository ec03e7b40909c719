//! What a reconstruction runs: the [`Method`], the checked [`Params`] and the stage order, decided
//! only in `Params::steps` ([`Params::stages`]). It may not run nor implement a stage.

use crate::error::Error;
use crate::stages::outliers::IqrRule;
use crate::stages::{Repair, Stage, Step, Uniformity};
#[cfg(doc)]
use crate::{reconstruct, reconstruct_triangulation, Reconstruction, Triangulation};
use alloc::vec::Vec;

/// ConDT (the stages [`Params`] chooses) or a classical baseline, compared on one triangulation.
///
/// ```
/// use condt::{reconstruct, Method, Params, Point, Stage};
/// let angles = (0..10).map(|k| k as f64 * std::f64::consts::TAU / 10.0);
/// let points: Vec<Point> = angles.map(|t| Point::new(t.cos(), t.sin())).collect();
/// let params = Params::default().with_method(Method::NnCrust);
/// assert_eq!(params.stages(), vec![Stage::NnCrust]);
/// assert_eq!(reconstruct(&points, &params)?.edges().len(), 10);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// ConDT: the proximity graph and the stages after it.
    #[default]
    ConDT,
    /// NN-Crust (Dey and Kumar), [`Triangulation::nn_crust`]; the ConDT parameters are unused.
    NnCrust,
    /// The Crust (Amenta, Bern and Eppstein), [`Triangulation::crust`]; ConDT parameters unused.
    Crust,
}

/// Parameters of a reconstruction; the stages *beyond the paper* are off in [`Params::paper`].
///
/// ```
/// use condt::{Params, Uniformity};
/// let p = Params::default();
/// assert_eq!((p.uniformity, p.outlier_factor), (Uniformity::Fixed(2.75), Some(1.7)));
/// assert!(p.check().is_ok());
/// assert!(p.with_outlier_factor(Some(f64::NAN)).check().is_err());
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
    /// Remove outliers before the repair, not after it as the paper orders them: outlier edges
    /// can make a curve vertex non-manifold, and the repair cuts a corner there
    /// (`docs/condt.md`, note 8).
    pub outliers_first: bool,
    /// The IQR stage cuts no edge up to 1.5 times the median edge (beyond the paper; why:
    /// `src/stages/outliers.rs`).
    pub iqr_floor: bool,
    /// If the IQR stage cut edges, repair again without all above its threshold (beyond the paper;
    /// repair first only): curve edges an outlier cost come back (`src/stages/repair_again.rs`).
    pub repair_again: bool,
    /// The local outlier removal, after the IQR stage and the repair (beyond the paper; its four
    /// rules: `src/stages/local_outliers.rs`).
    pub local_outliers: bool,
    /// After the local outlier removal (only with it; beyond the paper), drop each component of
    /// edges it gave back unless it lies clearly apart (`src/stages/given_back.rs`).
    pub confirm_given_back: bool,
    /// Close gaps at loose ends (beyond the paper; the joins it makes: `src/stages/gaps.rs`).
    pub close_gaps: bool,
    /// Remove components fewer than half of whose points a curve passes smoothly and evenly, or
    /// half and every point apart: clumps of outliers; not one that gap closing, the tips, the
    /// hooks or the junctions would join to a component that stays, whether those steps run or
    /// not (beyond the
    /// paper; `src/stages/clumps.rs`).
    pub clumps: bool,
    /// Join a loose end to the curve it meets where three curves of five points or more, sampled
    /// alike, meet, as on map borders or a T, or four where two ends meet one point; join a
    /// stroke of five or six points so where both its ends meet curves; or put a loose end at a
    /// junction in place of the chord that runs past it (beyond the paper;
    /// `src/stages/junctions.rs`).
    pub junctions: bool,
    /// Restore a crossing that Algorithm 1 read as two bends (beyond the paper;
    /// `src/stages/crossings.rs`).
    pub crossings: bool,
    /// Where an edge pairs the samples on either side of a sharp tip, join each to a loose end
    /// beside it, or both to the tip's sample if it has no edge (and, where one of the two is a
    /// loose end, that end on to the loose end its side runs straight to), instead (beyond the
    /// paper; `src/stages/tips.rs`).
    pub tips: bool,
    /// Where an edge pairs the samples on either side of a sharp tip whose two to five samples
    /// have no edges, join the two through them instead, along the shortest path, when that path
    /// is evenly spaced, smooth but at its apex, and one tip on one side of the edge; likewise two
    /// loose ends with such a tip's samples between them (beyond the paper;
    /// `src/stages/spikes.rs`).
    pub spikes: bool,
    /// Where a loose end hangs from a sample the curve reached first (noise swapped the two) and
    /// the curve runs on from that sample to a loose end or a point without edges, put the loose
    /// end back between the sample and the one before it and join the sample onward, when that
    /// makes no passage as sharp as the hook, or none sharp but at the loose end, which becomes a
    /// tip's apex (beyond the paper; `src/stages/hooks.rs`).
    pub hooks: bool,
    /// After the hooks, cut a tail of at most four points at a loose end whose joint is long and
    /// bends sharply against the even run it hangs from: outliers beyond an open end (beyond the
    /// paper; `src/stages/tails.rs`).
    pub tails: bool,
    /// Last, where two routes of at most four points between them join the same two points of
    /// three edges each (one or two outliers hung on a curve's samples, a chord past a sample),
    /// remove the route the curve runs into less straightly at both ends, none where the ends
    /// disagree or share their third neighbour; and open a loop of at most five points hung on a
    /// curve (a stroke's end folded back) at its sharper edge (beyond the paper;
    /// `src/stages/detours.rs`).
    pub detours: bool,
    /// Smoothing passes (beyond the paper; `smooth.rs`): where the curves show noise, points move
    /// towards their neighbours and the stages run again, up to three times. Edges stay between
    /// input positions, the [`triangulation`](Reconstruction::triangulation) is of the moved
    /// points; [`reconstruct`] runs passes, [`reconstruct_triangulation`] none.
    pub smooth: bool,
    /// Use rayon's threads (only with the `parallel` feature; the same result) on large sets (below
    /// 65,536 points, waking the workers costs more than they save).
    pub parallel: bool,
}

impl Default for Params {
    /// The best pipeline measured (`docs/condt.md`): the paper's, [`Repair::Needs`], all beyond it;
    /// beside other curves it loses a curve of three or four sparse points (`local_outliers:
    /// false` keeps it; alone, it stays).
    ///
    /// ```
    /// use condt::{Params, Stage::*};
    /// let p = Params::default();
    /// assert!(p.repair == condt::Repair::Needs && p.smooth);
    /// let all = [Proximity, Repair, Outliers, RepairAgain, LocalOutliers, Clumps, GivenBack];
    /// let later = [Gaps, Junctions, Crossings, Tips, Spikes, Hooks, Tails, Detours];
    /// assert_eq!(p.stages(), [&all[..], &later[..]].concat());
    /// ```
    fn default() -> Self {
        let mut params = Params::paper()
            .with_repair(Repair::Needs)
            .with_iqr_floor(true)
            .with_smooth(true);
        for stage in Stage::ALL {
            params.set_stage(stage, true); // every stage with a switch
        }
        params
    }
}

impl Params {
    /// The paper's pipeline as we read it (`docs/condt.md`): Algorithm 1 with `u = 2.75`,
    /// Algorithm 2 as printed ([`Repair::Paper`]), Algorithm 3 with `k = 1.7`, nothing beyond.
    ///
    /// ```
    /// use condt::{Params, Repair, Stage, Uniformity};
    /// let paper = Params::paper();
    /// assert_eq!((paper.uniformity, paper.repair), (Uniformity::Fixed(2.75), Repair::Paper));
    /// assert_eq!(paper.stages(), vec![Stage::Proximity, Stage::Repair, Stage::Outliers]);
    /// ```
    pub fn paper() -> Params {
        Params {
            method: Method::ConDT,
            uniformity: Uniformity::Fixed(2.75),
            repair: Repair::Paper,
            outlier_factor: Some(1.7),
            outliers_first: false,
            iqr_floor: false,
            repair_again: false,
            local_outliers: false,
            confirm_given_back: false,
            close_gaps: false,
            clumps: false,
            junctions: false,
            crossings: false,
            tips: false,
            spikes: false,
            hooks: false,
            tails: false,
            detours: false,
            smooth: false,
            parallel: cfg!(feature = "parallel"),
        }
    }

    /// `Ok` when every parameter is one its stage accepts.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first parameter NaN, infinite or out of range.
    ///
    /// ```
    /// use condt::{Error, Params};
    /// assert!(Params::default().check().is_ok());
    /// let bad = Params::paper().with_outlier_factor(Some(-1.0));
    /// assert!(matches!(bad.check(), Err(Error::InvalidParameter { name: "k", .. })));
    /// ```
    pub fn check(&self) -> Result<(), Error> {
        if self.method != Method::ConDT {
            return Ok(());
        }
        self.uniformity.check()?;
        self.steps().try_for_each(|step| step.check())
    }

    /// The stages these parameters run, in order: the first graph, then each stage that is on,
    /// the repair and the IQR stage in the order [`Params::outliers_first`] chooses.
    ///
    /// ```
    /// use condt::{Params, Repair, Stage as S};
    /// let p = Params::paper().with_outliers_first(true).with_repair(Repair::Off);
    /// assert_eq!(p.stages(), vec![S::Proximity, S::Outliers]);
    /// let local = Params::paper().with_outliers_first(true).with_local_outliers(true);
    /// assert_eq!(local.stages(), [S::Proximity, S::Outliers, S::Repair, S::LocalOutliers]);
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

    /// Algorithm 3's rule as these parameters set it: `None` when it is off.
    pub(crate) fn iqr_rule(&self) -> Option<IqrRule> {
        let floor = self.iqr_floor;
        self.outlier_factor.map(|factor| IqrRule { factor, floor })
    }

    /// The steps after the proximity graph, in order: the one place the order is decided.
    pub(crate) fn steps(&self) -> impl Iterator<Item = Step> + use<> {
        let repair = (self.repair != Repair::Off).then_some(Step::Repair(self.repair));
        let outliers = self.iqr_rule().map(Step::Outliers);
        let (first, second) = if self.outliers_first {
            (outliers, repair)
        } else {
            (repair, outliers)
        };
        // Only a repair that ran before the cut can be run again without the cut edges.
        let again = match (self.repair_again && !self.outliers_first, repair, outliers) {
            (true, Some(_), Some(Step::Outliers(rule))) => Some(Step::RepairAgain {
                rule,
                mode: self.repair,
            }),
            _ => None,
        };
        // The local outlier removal reads three or more edges as a branch, which only a repaired
        // graph makes true; the given-back check reads what it added. Clumps go before a join can
        // reach one; a junction takes only an end no gap join or crossing claimed; tips re-pair
        // the loose ends every join before left, spikes put back the tips of several samples
        // they cannot, hooks put back the loose ends still hanging; a tail and a detour are
        // judged on the finished curves.
        let steps = [
            first,
            second,
            again,
            self.local_outliers.then_some(Step::LocalOutliers),
            self.clumps.then_some(Step::RemoveClumps),
            (self.local_outliers && self.confirm_given_back).then_some(Step::ConfirmGivenBack),
            self.close_gaps.then_some(Step::CloseGaps),
            self.junctions.then_some(Step::JoinJunctions),
            self.crossings.then_some(Step::RestoreCrossings),
            self.tips.then_some(Step::RepairTips {
                spikes_follow: self.spikes,
            }),
            self.spikes.then_some(Step::RepairSpikes),
            self.hooks.then_some(Step::Unhook),
            self.tails.then_some(Step::CutTails),
            self.detours.then_some(Step::CutDetours),
        ];
        // A baseline is the whole method: no ConDT stage follows it.
        let condt = self.method == Method::ConDT;
        steps.into_iter().flatten().filter(move |_| condt)
    }

    /// These parameters with `parallel` off when rayon's threads cannot run
    /// ([`parallel_available`](crate::parallel_available)): what a run on `n` points uses and its
    /// result reports. Below [`PARALLEL_FROM`](crate::stages::PARALLEL_FROM) points no step uses
    /// threads, and the pool is not asked (asking starts it).
    pub(crate) fn on_available_threads(self, n: usize) -> Params {
        let available = n < crate::stages::PARALLEL_FROM || crate::threads::parallel_available();
        self.with_parallel(self.parallel && available)
    }

    /// Turns a switchable `stage` ([`Stage::switch`]) on or off: `true` when it has a switch,
    /// which is then set; `false` for any other, left as is. A stage switched on runs only where
    /// what it needs runs too ([`Params::stages`] lists the stages that run): repair again
    /// needs the outlier filter after the repair (not `outliers_first`), the given-back check
    /// needs local outlier removal.
    ///
    /// ```
    /// use condt::{Params, Stage};
    /// let mut p = Params::default();
    /// assert!(p.set_stage(Stage::Gaps, false));
    /// assert!(!p.close_gaps && !p.stages().contains(&Stage::Gaps));
    /// assert!(!p.set_stage(Stage::Proximity, false));
    /// // Switched on, but the paper's pipeline has no local outlier removal to confirm.
    /// let mut paper = Params::paper();
    /// assert!(paper.set_stage(Stage::GivenBack, true) && paper.confirm_given_back);
    /// assert!(!paper.stages().contains(&Stage::GivenBack));
    /// ```
    pub fn set_stage(&mut self, stage: Stage, on: bool) -> bool {
        let field = match stage {
            Stage::RepairAgain => &mut self.repair_again,
            Stage::LocalOutliers => &mut self.local_outliers,
            Stage::GivenBack => &mut self.confirm_given_back,
            Stage::Clumps => &mut self.clumps,
            Stage::Gaps => &mut self.close_gaps,
            Stage::Junctions => &mut self.junctions,
            Stage::Crossings => &mut self.crossings,
            Stage::Tips => &mut self.tips,
            Stage::Spikes => &mut self.spikes,
            Stage::Hooks => &mut self.hooks,
            Stage::Tails => &mut self.tails,
            Stage::Detours => &mut self.detours,
            _ => return false,
        };
        *field = on;
        true
    }
}

/// `with_FIELD(FIELD: TYPE)`: a chainable setter for each field listed.
macro_rules! setters {
    ($($setter:ident($field:ident: $type:ty = $value:expr),)*) => {$(
        #[doc = concat!("Sets [`Params::", stringify!($field), "`].")]
        ///
        /// ```
        /// use condt::{Method, Params, Repair, Uniformity};
        /// let paper = Params::paper();
        #[doc = concat!("let value = ", stringify!($value), ";")]
        #[doc = concat!("let set = paper.", stringify!($setter), "(value);")]
        #[doc = concat!("assert!(set.", stringify!($field), " == value && paper.",
            stringify!($field), " != value);")]
        /// ```
        pub fn $setter(mut self, $field: $type) -> Params {
            self.$field = $field;
            self
        }
    )*};
}

/// Chainable setters, one per field, to spell a pipeline from a preset.
///
/// ```
/// use condt::{Params, Repair};
/// let p = Params::paper().with_repair(Repair::Needs).with_smooth(true);
/// assert!(p.repair == Repair::Needs && p.smooth && !p.close_gaps);
/// ```
impl Params {
    setters! {
        with_method(method: Method = Method::NnCrust),
        with_uniformity(uniformity: Uniformity = Uniformity::Fixed(2.0)),
        with_repair(repair: Repair = Repair::Needs),
        with_outlier_factor(outlier_factor: Option<f64> = Some(3.0)),
        with_outliers_first(outliers_first: bool = !paper.outliers_first),
        with_iqr_floor(iqr_floor: bool = !paper.iqr_floor),
        with_local_outliers(local_outliers: bool = !paper.local_outliers),
        with_confirm_given_back(confirm_given_back: bool = !paper.confirm_given_back),
        with_close_gaps(close_gaps: bool = !paper.close_gaps),
        with_repair_again(repair_again: bool = !paper.repair_again),
        with_clumps(clumps: bool = !paper.clumps),
        with_junctions(junctions: bool = !paper.junctions),
        with_crossings(crossings: bool = !paper.crossings),
        with_tips(tips: bool = !paper.tips),
        with_spikes(spikes: bool = !paper.spikes),
        with_hooks(hooks: bool = !paper.hooks),
        with_tails(tails: bool = !paper.tails),
        with_detours(detours: bool = !paper.detours),
        with_smooth(smooth: bool = !paper.smooth),
        with_parallel(parallel: bool = !paper.parallel),
    }
}
