//! A run's stage history: the [`StageRecord`]s, the [`Undo`] deltas that keep each stage's input in
//! a few bytes (memory) and the walk back ([`History::output_of`]). It may not run a stage or choose one.

use super::result::StageReport;
use crate::adjacency::Edge;
use crate::graph::Graph;
use crate::stages::Stage;
use alloc::borrow::Cow;
use alloc::vec::Vec;
use core::time::Duration;

/// The stages of one run so far, in the order they ran, the first graph first.
#[derive(Clone, Debug, Default)]
pub(super) struct History {
    pub(super) records: Vec<StageRecord>,
}

impl History {
    /// Where `stage` ran among the records.
    pub(super) fn position(&self, stage: Stage) -> Option<usize> {
        self.records.iter().position(|r| r.stage == stage)
    }

    /// The graph `stage` started from, walked back from `current` (the latest output); `current`
    /// itself when `stage` has not run or is the first. `first` computes the first graph.
    pub(super) fn input_of<'e>(
        &'e self,
        stage: Stage,
        current: &'e [Edge],
        first: &dyn Fn() -> Vec<Edge>,
    ) -> Cow<'e, [Edge]> {
        match self.position(stage) {
            Some(k) if k > 0 => self.output_of(current, k - 1, first),
            _ => Cow::Borrowed(current),
        }
    }

    /// Stage `k`'s output, walked back from `last` (the last output); `first` serves
    /// [`Undo::First`].
    pub(super) fn output_of<'e>(
        &'e self,
        last: &'e [Edge],
        k: usize,
        first: &dyn Fn() -> Vec<Edge>,
    ) -> Cow<'e, [Edge]> {
        let records = &self.records;
        // The next stage's input is the first graph itself: nothing to walk back through.
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
}

#[derive(Clone, Debug)]
pub(super) struct StageRecord {
    pub(super) stage: Stage,
    pub(super) undo: Undo,
    pub(super) time: Duration,
}

impl StageRecord {
    /// The report of the `k`-th stage of a run, `graph` the graph it left.
    pub(super) fn report<'r>(&self, k: usize, graph: Graph<'r>) -> StageReport<'r> {
        StageReport {
            stage: self.stage,
            graph,
            applied: k == 0 || !matches!(self.undo, Undo::Unchanged),
            time: self.time,
        }
    }
}

/// How a stage's input is recovered from its output. Reason: memory (a stage changes a few edges
/// in a hundred; a full copy costs 8 bytes per point).
#[derive(Clone, Debug)]
pub(super) enum Undo {
    /// The output is the input: the rule did not apply, or this is the first graph (no input).
    Unchanged,
    /// The output is the input without the edges at `removed`, plus `appended` edges at the end.
    Delta {
        appended: usize,
        /// `(position in the input, edge)`, positions ascending.
        removed: Vec<(u32, Edge)>,
    },
    /// The input itself, when the output is not of that form or the delta would not be smaller.
    Input(Vec<Edge>),
    /// The input is the first graph, computed again when a report asks ([`FIRST_KEPT_UP_TO`]).
    First,
}

/// The repair's record keeps a delta of the first graph only up to one removal (12 bytes) per this
/// many edges, under a byte per edge; past it, [`Undo::First`] (memory against a report's time).
/// Only the repair's: the local outlier removal reads the IQR stage's input (with
/// `outliers_first`, the proximity graph) and must not recompute it.
pub(super) const FIRST_KEPT_UP_TO: usize = 12;

impl Undo {
    /// How to get `input` back from `output` (the input itself when no delta is smaller). Matched
    /// greedily: an input edge equal to the next unmatched output edge is kept, others removed,
    /// the output's unmatched tail appended. Edges are distinct, so undoing is exact; a stage that
    /// keeps its order and appends its additions (all do) gets the smallest delta, its change.
    pub(super) fn of(input: Vec<Edge>, output: &[Edge]) -> Undo {
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

    /// How many edges of `input` [`Undo::of`] would list as removed.
    pub(super) fn removals(input: &[Edge], output: &[Edge]) -> usize {
        let mut kept = 0;
        for &edge in input {
            kept += usize::from(output.get(kept) == Some(&edge));
        }
        input.len() - kept
    }

    /// The stage's input, given its `output`; `first` computes the first stage's graph.
    pub(super) fn input<'e>(
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
