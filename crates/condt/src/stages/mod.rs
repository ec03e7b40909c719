//! The ConDT stages that run on the finished triangulation, one submodule each: [`proximity`]
//! (Algorithm 1), [`repair`] (Algorithm 2), [`outliers`] (Algorithm 3) and, not in the paper,
//! [`repair_again`], [`local_outliers`], [`given_back`], [`clumps`], [`gaps`], [`junctions`],
//! [`crossings`], [`tips`], [`spikes`], [`hooks`], [`tails`] and [`detours`].
//!
//! Owns: the stage table (`ROWS`, [`Stage`] and its [`Switch`]: every name of a stage), each
//! stage's rule, its parameter check, and [`Step::run`], through which the pipeline and
//! the public `Graph` methods run every stage after the first graph. A run split in tiles
//! ([`crate::tiled`]) reads the rules through crate-private functions of the stage modules instead
//! (`outliers::iqr_cut`, `local_outliers::remove_local_outliers_with` and `last_edges`,
//! `clumps::clumps_of` and `unless_joined`, `gaps::settle_joins`, `tips::candidates` and
//! `settle_candidates`, `given_back::missing_from`, ...), the code the stages themselves run, so
//! each rule is still one piece of code. Stages read the triangulation and may not modify it,
//! nor decide when they run (`Params::steps`). What calls what, and adding a stage:
//! `docs/architecture.md`.

pub(crate) mod clumps;
pub(crate) mod crossings;
pub(crate) mod detours;
pub(crate) mod gaps;
pub(crate) mod given_back;
pub(crate) mod hooks;
pub(crate) mod junctions;
pub(crate) mod local_outliers;
pub(crate) mod outliers;
pub(crate) mod proximity;
pub(crate) mod repair;
pub(crate) mod repair_again;
pub(crate) mod spikes;
pub(crate) mod tails;
pub(crate) mod tips;

pub use proximity::Uniformity;
pub use repair::Repair;

use crate::adjacency::{CurveGraph, Edge};
use crate::bits::IdBits;
use crate::error::Error;
use crate::mesh::VertexId;
use crate::triangulate::Triangulation;
use alloc::borrow::Cow;
use alloc::vec;
use alloc::vec::Vec;

/// A reconstruction stage, as [`Reconstruction::stages`](crate::Reconstruction::stages) reports it.
///
/// ```
/// use condt::{Params, Stage};
/// assert_eq!(Params::paper().stages(), vec![Stage::Proximity, Stage::Repair, Stage::Outliers]);
/// assert_eq!(Stage::Repair.to_string(), "after non-manifold repair");
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Stage {
    /// Stage 1: the ConDT proximity graph (Algorithm 1), chosen on the Delaunay triangulation.
    Proximity,
    /// The non-manifold repair (Algorithm 2).
    Repair,
    /// The IQR outlier removal (Algorithm 3).
    Outliers,
    /// Repairing again without cut edges ([`Params::repair_again`](crate::Params::repair_again)).
    RepairAgain,
    /// The local outlier removal ([`Params::local_outliers`](crate::Params::local_outliers)).
    LocalOutliers,
    /// Confirming the components the local outlier removal rebuilt from edges the IQR stage cut
    /// (not in the paper; see [`Params::confirm_given_back`](crate::Params::confirm_given_back)).
    GivenBack,
    /// Removing components that are not curves ([`Params::clumps`](crate::Params::clumps)).
    Clumps,
    /// Closing gaps at loose ends ([`Params::close_gaps`](crate::Params::close_gaps)).
    Gaps,
    /// Joining loose ends at junctions ([`Params::junctions`](crate::Params::junctions)).
    Junctions,
    /// Restoring crossings read as two bends ([`Params::crossings`](crate::Params::crossings)).
    Crossings,
    /// Re-pairing loose ends across a chord at a tip ([`Params::tips`](crate::Params::tips)).
    Tips,
    /// Putting tips of several unused samples back in place of their chord
    /// ([`Params::spikes`](crate::Params::spikes)).
    Spikes,
    /// Putting loose ends that hook back beside their curve in line
    /// ([`Params::hooks`](crate::Params::hooks)).
    Hooks,
    /// Cutting outlier tails at open ends ([`Params::tails`](crate::Params::tails)).
    Tails,
    /// Cutting short detours beside curves ([`Params::detours`](crate::Params::detours)).
    Detours,
    /// The NN-Crust baseline, the whole method ([`Method::NnCrust`](crate::Method::NnCrust)).
    NnCrust,
    /// The Crust baseline, the whole method ([`Method::Crust`](crate::Method::Crust)).
    Crust,
}

/// A command-line switch that turns a stage on or off (`--NAME` and `--no-NAME`), with its
/// help; [`Params::set_stage`](crate::Params::set_stage) does what it says.
///
/// ```
/// use condt::{Params, Stage};
/// let switch = Stage::Tails.switch().unwrap();
/// assert_eq!(switch.flag, "tails"); // `--tails` and `--no-tails`
/// let mut p = Params::paper();
/// assert!(p.set_stage(Stage::Tails, true) && p.tails);
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Switch {
    /// The flag without its dashes.
    pub flag: &'static str,
    /// What the stage does, for a command line's help (lines of at most 70 columns).
    pub help: &'static str,
}

/// Everything that names a stage, one row per stage in [`Stage`]'s order; the command line's
/// switches and `--timings` lines, the drawings' titles and the viewer's layers all read it.
struct Row {
    /// The stage the row is for (a test checks that [`Stage::row`] finds each stage's own row).
    stage: Stage,
    name: &'static str,
    title: &'static str,
    key: &'static str,
    switch: Option<Switch>,
}

/// The rows in order: `Variant: name, title, key` and, for a stage with a switch, its
/// `flag => help`.
macro_rules! rows {
    ($($stage:ident: $name:literal, $title:literal, $key:literal
        $(, $flag:literal => $help:literal)?;)*) => {
        [$(Row {
            stage: Stage::$stage,
            name: $name,
            title: $title,
            key: $key,
            switch: rows!(@switch $($flag, $help)?),
        },)*]
    };
    (@switch) => { None };
    (@switch $flag:literal, $help:literal) => { Some(Switch { flag: $flag, help: $help }) };
}

const ROWS: [Row; 17] = rows! {
    Proximity: "proximity", "ConDT proximity graph", "proximity";
    Repair: "repair", "after non-manifold repair", "repair";
    Outliers: "IQR outliers", "after outlier removal", "iqr-outliers";
    RepairAgain: "repair again", "after repairing again without the cut edges", "repair-again",
        "repair-again" => "(default on; off with --paper) when the outlier filter cut
edges, repair again without them: a curve edge the repair
dropped for an outlier's pair comes back";
    LocalOutliers: "local outliers", "after local outlier removal", "local-outliers",
        "local-outliers" => "(default on; off with --paper) after the outlier filter and the
repair, remove outliers locally: give back edges the filter cut
along regular passages; drop edges far longer than their
neighbours, branches of fewer than 5 points and components of
fewer than 5 points clearly apart from the rest, unless dense
or gap closing, the tips, the hooks or the junctions would join
them to a curve that stays, whether those steps run or not, and
unless they hold a quarter of the points with edges (so beside
other curves a sparsely sampled curve of 3 or 4 points, or a
closed one of 5 or 6, is lost; alone it stays)";
    GivenBack: "given-back check", "after confirming given-back components", "given-back",
        "confirm-given-back" => "(default on; off with --paper; needs the local outlier removal)
after it and the clumps, drop a component rebuilt only from edges
the outlier filter cut unless every point of it with two edges or
more is apart from every unused point or other such component by
twice its longest edge
(a chance chain of outliers in a large scatter; a sparse curve
the filter cut that passes near an unused point stays cut)";
    Clumps: "clumps", "after removing clumps", "clumps",
        "clumps" => "(default on; off with --paper) after the local outlier removal,
remove components fewer than half of whose points a curve passes
smoothly and evenly, or half and every point apart (clumps of
outliers), unless that would remove a quarter of the points with
edges; a component gap closing, the tips, the hooks or the
junctions would join to one that stays, stays";
    Gaps: "gaps", "after closing gaps", "gaps",
        "close-gaps" => "(default on; off with --paper) after the removals, join loose
ends that face each other across a short gap or line up through a
stranded point, two that walk straight on through unused points
and meet, and a crossing's dropped arms";
    Junctions: "junctions", "after joining junctions", "junctions",
        "junctions" => "(default on; off with --paper) after gap closing, join a loose
end to the curve it meets where three (or four) curves meet (map
borders, a T), or put it in place of the edge that runs past it
there: each branch runs on evenly through 5 samples of degree two
(one that ends free: 7 samples besides the junction's); a stroke
of 5 or 6 points is joined where both its ends meet curves";
    Crossings: "crossings", "after restoring crossings", "crossings",
        "crossings" => "(default on; off with --paper) after the junctions, where two
curves cross at a sample at a narrow angle and the sample kept
an arm of each (two V shapes), give it all four arms in place of
the edge that paired its neighbours";
    Tips: "tips", "after re-pairing loose ends at tips", "tips",
        "tips" => "(default on; off with --paper) after the crossings, where an edge
pairs the samples on either side of a sharp tip, join each of the
two to a loose end beside it, or both to the tip's sample if it
has no edge and continues both sides evenly (a loose end among
the two also to the loose end its side runs straight on to), in
place of that edge, when the new passages are smooth (straight
beside a loose end) and no curve is split";
    Spikes: "spikes", "after putting back thin tips", "spikes",
        "spikes" => "(default on; off with --paper) after the tips, where an edge
pairs the samples on either side of a sharp tip whose 2 to 5
samples have no edges, join the two through them instead, along
the shortest path, when it is evenly spaced, smooth but at its
apex, and rises to the apex and falls on one side of the edge;
likewise two loose ends ending curves of 5 points";
    Hooks: "hooks", "after unhooking loose ends", "hooks",
        "hooks" => "(default on; off with --paper) after the spikes, where a loose
end hangs from a sample that the curve reached first (the two
samples' order swapped by noise) and the curve runs on from that
sample to a loose end or a point without edges, put the loose
end between the sample and the one before, and join the sample
onward, when that leaves no passage as sharp as the hook, or none
sharp but at the loose end (a tip's apex)";
    Tails: "outlier tails", "after cutting outlier tails", "tails",
        "tails" => "(default on; off with --paper) after the hooks, cut a tail of at
most 4 points at a loose end whose joint is longer than 1.5 times
the edge it joins and bends more than twice as sharply as the even
run of 5 edges it hangs from (outliers beyond an open end)";
    Detours: "detours", "after cutting detours", "detours",
        "detours" => "(default on; off with --paper) last, where two routes of at most
4 points between them join the same two points of three edges
each (an outlier hung on two samples, a chord past one), remove
the route the curve runs into less straightly at both ends
(none where the two ends disagree); and open a loop of at most 5
points hung on a curve at the edge the curve turns into sharper";
    NnCrust: "NN-Crust", "NN-Crust (baseline)", "nn-crust";
    Crust: "Crust", "Crust (baseline)", "crust";
};

impl Stage {
    /// Every stage, in the order of the table that names them.
    ///
    /// ```
    /// assert_eq!(condt::Stage::ALL[0], condt::Stage::Proximity);
    /// assert!(condt::Stage::ALL.iter().all(|s| !s.key().contains(' ')));
    /// ```
    pub const ALL: [Stage; ROWS.len()] = {
        let mut all = [Stage::Proximity; ROWS.len()];
        let mut k = 0;
        while k < all.len() {
            all[k] = ROWS[k].stage;
            k += 1;
        }
        all
    };

    fn row(self) -> &'static Row {
        &ROWS[self as usize]
    }

    /// A short name for the stage itself, as explanations and the viewer's panel use it.
    ///
    /// ```
    /// assert_eq!(condt::Stage::Outliers.name(), "IQR outliers");
    /// ```
    pub fn name(self) -> &'static str {
        self.row().name
    }

    /// A title for the graph this stage leaves, as drawings label it.
    ///
    /// ```
    /// assert_eq!(condt::Stage::Gaps.title(), "after closing gaps");
    /// ```
    pub fn title(self) -> &'static str {
        self.row().title
    }

    /// One word for the stage, as the command line's `--timings` lines name it.
    ///
    /// ```
    /// assert_eq!(condt::Stage::Outliers.key(), "iqr-outliers");
    /// ```
    pub fn key(self) -> &'static str {
        self.row().key
    }

    /// The switch that turns the stage on or off, if it has one (the others are set by their
    /// parameters: the repair's mode, the IQR factor, the method).
    ///
    /// ```
    /// assert_eq!(condt::Stage::Gaps.switch().unwrap().flag, "close-gaps");
    /// assert!(condt::Stage::Proximity.switch().is_none());
    /// ```
    pub fn switch(self) -> Option<&'static Switch> {
        self.row().switch.as_ref()
    }
}

impl core::fmt::Display for Stage {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.title())
    }
}

/// A stage that runs on a graph, with its parameter.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Step {
    Repair(Repair),
    Outliers(outliers::IqrRule),
    RepairAgain {
        rule: outliers::IqrRule,
        mode: Repair,
    },
    LocalOutliers,
    ConfirmGivenBack,
    RemoveClumps,
    CloseGaps,
    JoinJunctions,
    RestoreCrossings,
    /// The tips step; `spikes_follow` when the spikes step runs after it (the apex form leaves
    /// it the tips of two to five samples).
    RepairTips {
        spikes_follow: bool,
    },
    RepairSpikes,
    Unhook,
    CutTails,
    CutDetours,
}

/// The graphs of earlier stages a step may read ([`Step::run`]), handed over so it can free them.
#[derive(Clone)]
pub(crate) struct Earlier<'a> {
    /// The IQR stage's input ([`Step::Outliers`]), or the step's input when it has not run.
    pub(crate) before_outliers: Cow<'a, [Edge]>,
    /// For repairing again, the edges the IQR stage cut (with their input positions) when it is
    /// the stage before and its output is its input without them: `before_outliers` is then not
    /// rebuilt, only the lengths of its edges are read ([`repair_again::repair_again`]).
    pub(crate) cut_by_outliers: Option<&'a [(u32, Edge)]>,
    /// The local outlier removal's input ([`Step::LocalOutliers`]), or the step's input likewise.
    pub(crate) before_local: Cow<'a, [Edge]>,
    /// The repair's input, the proximity graph ([`Step::Repair`]), or the step's input likewise.
    pub(crate) before_repair: Cow<'a, [Edge]>,
}

/// Which of the graphs in [`Earlier`] a step reads ([`Step::reads`]): the pipeline rebuilds only
/// those, and hands the step its own input in the others' place.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct Reads {
    pub(crate) before_outliers: bool,
    pub(crate) before_local: bool,
    pub(crate) before_repair: bool,
}

impl Step {
    /// The earlier graphs [`Step::run`] reads for this step: a new stage that reads one says so
    /// here, beside the arm of `run` that reads it.
    pub(crate) fn reads(self) -> Reads {
        Reads {
            before_outliers: matches!(self, Step::RepairAgain { .. } | Step::LocalOutliers),
            before_local: matches!(self, Step::ConfirmGivenBack),
            before_repair: matches!(self, Step::RepairAgain { .. }),
        }
    }

    pub(crate) fn stage(self) -> Stage {
        match self {
            Step::Repair(_) => Stage::Repair,
            Step::Outliers(_) => Stage::Outliers,
            Step::RepairAgain { .. } => Stage::RepairAgain,
            Step::LocalOutliers => Stage::LocalOutliers,
            Step::ConfirmGivenBack => Stage::GivenBack,
            Step::RemoveClumps => Stage::Clumps,
            Step::CloseGaps => Stage::Gaps,
            Step::JoinJunctions => Stage::Junctions,
            Step::RestoreCrossings => Stage::Crossings,
            Step::RepairTips { .. } => Stage::Tips,
            Step::RepairSpikes => Stage::Spikes,
            Step::Unhook => Stage::Hooks,
            Step::CutTails => Stage::Tails,
            Step::CutDetours => Stage::Detours,
        }
    }

    /// `Ok` when the parameter is one the stage accepts.
    pub(crate) fn check(self) -> Result<(), Error> {
        match self {
            Step::Outliers(rule) | Step::RepairAgain { rule, .. }
                if !(rule.factor.is_finite() && rule.factor >= 0.0) =>
            {
                Err(Error::invalid("k", rule.factor))
            }
            _ => Ok(()),
        }
    }

    /// Runs the stage on `edges` (each edge once, any order) with a parameter that passed
    /// [`Step::check`], reading from `earlier` what it needs. `graph`, if given, is the curve
    /// graph of `edges` the previous stage handed on ([`Outcome::graph`]): the stages after the
    /// local outlier removal read it, the others drop it first (memory). `parallel`: the stages
    /// that can use threads do from [`PARALLEL_FROM`] points on (the same outcome).
    pub(crate) fn run(
        self,
        tri: &Triangulation,
        edges: &[Edge],
        earlier: Earlier<'_>,
        graph: Option<CurveGraph>,
        parallel: bool,
    ) -> Outcome {
        let parallel = parallel && tri.num_points() >= PARALLEL_FROM;
        let reads_graph = !matches!(
            self,
            Step::Repair(_) | Step::Outliers(_) | Step::RepairAgain { .. } | Step::LocalOutliers
        );
        let graph = graph.filter(|_| reads_graph);
        match self {
            Step::Repair(mode) => Outcome::from(repair::repair(tri, edges, mode, parallel)),
            Step::Outliers(rule) => outliers::remove_outliers(tri, edges, rule),
            Step::RepairAgain { rule, mode } => {
                repair_again::repair_again(tri, edges, earlier, rule, mode, parallel)
            }
            Step::LocalOutliers => local_outliers::remove_local_outliers(
                tri,
                edges,
                earlier.before_outliers,
                &local_outliers::Rules::ALL,
                parallel,
            ),
            Step::ConfirmGivenBack => {
                given_back::confirm_given_back(tri, edges, &earlier.before_local, graph)
            }
            Step::RemoveClumps => clumps::remove_clumps(tri, edges, graph, parallel),
            Step::CloseGaps => with_ends(tri, edges, graph, parallel, gaps::close_gaps),
            Step::JoinJunctions => {
                with_ends(tri, edges, graph, parallel, junctions::join_junctions)
            }
            Step::RestoreCrossings => {
                with_ends(tri, edges, graph, parallel, crossings::restore_crossings)
            }
            Step::RepairTips { spikes_follow } => {
                with_ends(tri, edges, graph, parallel, |ends, parallel| {
                    tips::repair_tips(ends, parallel, spikes_follow)
                })
            }
            Step::RepairSpikes => with_ends(tri, edges, graph, parallel, spikes::repair_spikes),
            Step::Unhook => with_ends(tri, edges, graph, parallel, hooks::unhook),
            Step::CutTails => with_ends(tri, edges, graph, parallel, tails::cut_tails),
            Step::CutDetours => with_ends(tri, edges, graph, parallel, detours::cut_detours),
        }
    }
}

/// What a stage made of its input.
pub(crate) struct Outcome {
    /// The new edge list, or `None` when the rule did not apply and the input stands (stored once).
    pub(crate) edges: Option<Vec<Edge>>,
    /// The output's curve graph (the input's when `edges` is `None`), if the stage had it at hand:
    /// building one costs about as much as a light stage, and later stages and the curves read one.
    pub(crate) graph: Option<CurveGraph>,
}

impl Outcome {
    pub(crate) const UNCHANGED: Outcome = Outcome {
        edges: None,
        graph: None,
    };

    pub(crate) fn unchanged_with(graph: Option<CurveGraph>) -> Outcome {
        Outcome { edges: None, graph }
    }

    /// The outcome `output` of a stage on `input` (the form [`CurveGraph::follow`] reads), with
    /// `graph`, the input's curve graph if the stage had it, made the output's and handed on.
    pub(crate) fn changed(input: &[Edge], output: Vec<Edge>, graph: Option<CurveGraph>) -> Outcome {
        let graph = graph.map(|mut graph| {
            graph.follow(input, &output);
            graph
        });
        Outcome {
            edges: Some(output),
            graph,
        }
    }

    /// The outcome of a stage that replaces edges of `input`: the input in order without
    /// `removed`, then `added` in order, with `graph` (the input's, if the stage had it) made the
    /// output's, or the input unchanged when neither list has an edge. The junctions, crossings,
    /// tips, spikes and hooks steps replace edges this way, the outlier tails and the detours
    /// remove them so, and gap closing adds them so.
    pub(crate) fn replacing(
        input: &[Edge],
        graph: Option<CurveGraph>,
        mut removed: Vec<Edge>,
        added: Vec<Edge>,
    ) -> Outcome {
        if removed.is_empty() && added.is_empty() {
            return Outcome::unchanged_with(graph);
        }
        removed.sort_unstable();
        // A bit per point up to the largest first end removed: an edge whose first end has none
        // (almost every edge: few are replaced) is kept without the search (speed: a search per
        // edge was 4% of a reconstruction's instructions on 1M uniform points, docs/perf-log.md).
        let firsts = IdBits::of(removed.iter().map(|e| e[0].index()));
        let may_be_removed = |e: &Edge| firsts.contains(e[0].index());
        let mut out: Vec<Edge> =
            Vec::with_capacity(input.len().saturating_sub(removed.len()) + added.len());
        out.extend(
            input
                .iter()
                .filter(|e| !may_be_removed(e) || removed.binary_search(e).is_err()),
        );
        out.extend(added);
        Outcome::changed(input, out, graph)
    }
}

/// What a stage that reads the graph's loose ends and points ([`gaps::Ends`]) changes: the edges
/// it removes and those it adds, in the order [`Outcome::replacing`] lists them.
pub(crate) type Replaced = (Vec<Edge>, Vec<Edge>);

/// Runs such a stage, `stage(ends, parallel)`, on `edges` (`graph`, their curve graph if at
/// hand): the input edges in order without the removed ones, then the added ones, with the
/// output's curve graph.
pub(crate) fn with_ends(
    tri: &Triangulation,
    edges: &[Edge],
    graph: Option<CurveGraph>,
    parallel: bool,
    stage: impl FnOnce(&gaps::Ends<'_>, bool) -> Replaced,
) -> Outcome {
    let ends = gaps::Ends::new(tri, edges, graph);
    let (removed, added) = stage(&ends, parallel);
    Outcome::replacing(edges, ends.into_graph(), removed, added)
}

impl From<Option<Vec<Edge>>> for Outcome {
    fn from(edges: Option<Vec<Edge>>) -> Outcome {
        Outcome { edges, graph: None }
    }
}

/// [`crate::threads::found_in_order`] over the vertices of ids `0..n`: the values `find` gives
/// them, in increasing id.
pub(crate) fn found_at_vertices<T: Send>(
    n: usize,
    parallel: bool,
    find: impl Fn(VertexId) -> Option<T> + Sync + Send,
) -> Vec<T> {
    crate::threads::found_in_order(n, parallel, |i| find(VertexId::new(i as u32)))
}

/// Keeps the `choices` none of whose points another choice names, or `claimed` holds (points that
/// had two candidates): where two choices meet, either would be a guess, so neither is made, and
/// the outcome depends on no order. `points` lists a choice's points, each once.
pub(crate) fn alone<C, P>(
    n: usize,
    choices: &mut Vec<C>,
    claimed: &[VertexId],
    points: impl Fn(&C) -> P,
) where
    P: IntoIterator<Item = VertexId>,
{
    let mut uses = uses(n, choices, &points);
    for v in claimed {
        uses[v.index()] = uses[v.index()].saturating_add(1);
    }
    choices.retain(|choice| points(choice).into_iter().all(|v| uses[v.index()] == 1));
}

/// How many of `choices` name each of the `n` points (`points` lists a choice's points, each
/// once), saturating: the count [`alone`] and the junctions' settling read.
pub(crate) fn uses<C, P>(n: usize, choices: &[C], points: impl Fn(&C) -> P) -> Vec<u8>
where
    P: IntoIterator<Item = VertexId>,
{
    let mut uses = vec![0u8; n];
    for choice in choices {
        for v in points(choice) {
            uses[v.index()] = uses[v.index()].saturating_add(1);
        }
    }
    uses
}

/// Fewest points for which stages use rayon: below it, waking the workers costs more than it saves.
pub(crate) const PARALLEL_FROM: usize = 1 << 16;

/// Whether a step on `n` points runs on rayon's threads: from [`PARALLEL_FROM`] points on,
/// where rayon can run ([`parallel_available`](crate::parallel_available), asked only then:
/// asking starts the global pool).
pub(crate) fn worth_threads(n: usize) -> bool {
    n >= PARALLEL_FROM && crate::threads::parallel_available()
}

#[cfg(test)]
mod table_tests {
    use super::*;

    #[test]
    fn the_rows_are_in_the_order_of_the_variants_and_their_words_are_distinct() {
        for (k, stage) in Stage::ALL.iter().enumerate() {
            assert_eq!(ROWS[k].stage, *stage);
            assert_eq!(stage.row().stage, *stage);
        }
        let mut keys: Vec<&str> = Stage::ALL.iter().map(|s| s.key()).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), Stage::ALL.len());
    }
}
