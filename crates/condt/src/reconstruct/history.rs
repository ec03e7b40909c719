//! The stage history of a run: which stages ran, in order, and how to get each one's graph back
//! from the last one's.
//!
//! Owns: [`StageRecord`], the [`Undo`] deltas that keep a stage's input in a few bytes, and the
//! walk back from the last graph ([`output_of`], [`History::input_of`]). It may not run a stage
//! or decide which runs: it only remembers. Reason for the deltas: memory.

use crate::adjacency::Edge;
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
    /// The graph `stage` started from when it ran, walked back from `current` (the latest
    /// output); `current` itself when `stage` has not run (or is the first). `first` computes the
    /// first stage's graph when a record says to.
    pub(super) fn input_of<'e>(
        &'e self,
        stage: Stage,
        current: &'e [Edge],
        first: &dyn Fn() -> Vec<Edge>,
    ) -> Cow<'e, [Edge]> {
        match self.records.iter().position(|r| r.stage == stage) {
            Some(k) if k > 0 => output_of(&self.records, current, k - 1, first),
            _ => Cow::Borrowed(current),
        }
    }

    /// The output of the `k`-th stage, walked back from `last`, the latest stage's output.
    pub(super) fn output_of<'e>(
        &'e self,
        last: &'e [Edge],
        k: usize,
        first: &dyn Fn() -> Vec<Edge>,
    ) -> Cow<'e, [Edge]> {
        output_of(&self.records, last, k, first)
    }
}

/// One stage as it ran.
#[derive(Clone, Debug)]
pub(super) struct StageRecord {
    pub(super) stage: Stage,
    /// How to get its input back from its output.
    pub(super) undo: Undo,
    pub(super) time: Duration,
}

/// How a stage's input is recovered from its output: the stage graphs are stored as the final
/// graph and one of these per stage, walked back from the last stage. Reason: memory (a stage
/// changes a few edges in a hundred; a full copy costs 8 bytes per point).
#[derive(Clone, Debug)]
pub(super) enum Undo {
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
/// for it ([`Undo::First`]). Reason: memory against the time of a report. Only the repair's
/// record is replaced so: the local outlier removal reads the IQR stage's input, which with
/// `outliers_first` is the proximity graph, and must not recompute it.
pub(super) const FIRST_KEPT_UP_TO: usize = 12;

impl Undo {
    /// How to get `input` back from `output`. The input is moved into the record only when no
    /// delta is smaller than it.
    ///
    /// The delta matches the two lists greedily: an input edge equal to the next unmatched
    /// output edge is kept, any other is removed, and the output's unmatched tail is appended.
    /// Edges are distinct within a list, so undoing it gives the input back exactly, whatever
    /// the stage did; a stage that keeps its edges in order and appends the ones it adds (all of
    /// them do) gives the smallest delta, its actual change.
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

    /// How many edges of `input` the delta of [`Undo::of`] would list as removed.
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
pub(super) fn output_of<'e>(
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
