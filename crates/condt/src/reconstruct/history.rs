//! A run's stage history: the [`StageRecord`]s, the [`Undo`] deltas that keep each stage's input
//! in a few bytes (memory) and the walk back. It may not run a stage or choose one.

use super::result::StageReport;
use crate::adjacency::Edge;
use crate::graph::Graph;
use crate::stages::Stage;
use alloc::borrow::Cow;
use alloc::vec;
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

    /// The edges the last record's stage removed, when it is `stage` and its output is its input
    /// without them (the latest output is then `stage`'s): with that output, its input's edges in
    /// another order, for what depends only on the multiset (memory: not rebuilt).
    pub(super) fn removed_by_last(&self, stage: Stage) -> Option<&[(u32, Edge)]> {
        match self.records.last()? {
            StageRecord {
                stage: last,
                undo:
                    Undo::Delta {
                        appended: 0,
                        inserted,
                        removed,
                    },
                ..
            } if *last == stage && inserted.is_empty() => Some(removed),
            _ => None,
        }
    }

    /// The first graph a record holds ([`Undo::Held`]), handed over: the record becomes `First`.
    pub(super) fn take_held(&mut self) -> Option<Vec<Edge>> {
        let record = self
            .records
            .iter_mut()
            .find(|r| matches!(r.undo, Undo::Held(_)))?;
        match core::mem::replace(&mut record.undo, Undo::First) {
            Undo::Held(first) => Some(first),
            _ => None,
        }
    }

    /// Stage `k`'s output, walked back from `last` (the last output); `first` serves `Undo::First`.
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
    /// The output is the input without the edges at `removed`, plus `appended` edges at the end
    /// and the edges at `inserted` (output positions, ascending) before them.
    Delta {
        appended: usize,
        inserted: Vec<u32>,
        /// `(position in the input, edge)`, positions ascending.
        removed: Vec<(u32, Edge)>,
    },
    /// The input itself, when the output is not of that form or the delta would not be smaller.
    Input(Vec<Edge>),
    /// The input is the first graph, computed again when a report asks ([`FIRST_KEPT_UP_TO`]).
    First,
    /// [`Undo::First`] held until repairing again reads it ([`History::take_held`]): computed
    /// again there, it would add the proximity stage's peak to the graphs that step holds.
    Held(Vec<Edge>),
}

/// The repair's record keeps a delta of the first graph only up to one removal (12 bytes) per this
/// many edges, under a byte per edge; past it, [`Undo::First`] (memory against a report's time).
/// Only the repair's: the local outlier removal reads the IQR stage's input (with
/// `outliers_first`, the proximity graph) and must not recompute it.
pub(super) const FIRST_KEPT_UP_TO: usize = 12;

/// A greedy delta lists at most one removal (12 bytes) per this many input edges before the
/// aligned match takes over ([`Undo::of`]).
const ALIGNED_PAST: usize = 8;

impl Undo {
    /// How to get `input` back from `output` (the input itself when no delta is smaller). Matched
    /// greedily: an input edge equal to the next unmatched output edge is kept, others removed,
    /// the output's unmatched tail appended. Edges are distinct, so undoing is exact; a stage that
    /// keeps its order and appends its additions (most do) gets the smallest delta, its change;
    /// one that lists its additions among the rest (repairing again) gets [`Undo::aligned`].
    pub(super) fn of(input: Vec<Edge>, output: &[Edge]) -> Undo {
        // Past this many removals the aligned delta, no larger, takes over: the list grown so far
        // is spare, and counting first would cost every stage one more read of both lists.
        let most = input.len() / ALIGNED_PAST;
        let mut removed = Vec::new();
        let mut kept = 0;
        for (position, &edge) in input.iter().enumerate() {
            if output.get(kept) == Some(&edge) {
                kept += 1;
            } else if removed.len() < most {
                removed.push((position as u32, edge));
            } else {
                drop(removed);
                return Undo::aligned(input, output);
            }
        }
        removed.shrink_to_fit();
        Undo::Delta {
            appended: output.len() - kept,
            inserted: Vec::new(),
            removed,
        }
    }

    /// The delta that keeps the most edges: the longest run of edges common to both lists in the
    /// same order (the longest increasing run of their output positions, in O(n log n)); the
    /// input itself when that delta is larger.
    fn aligned(input: Vec<Edge>, output: &[Edge]) -> Undo {
        let at = positions_in(output, &input);
        // `tails[l]`: the input position ending the best run of length `l + 1` so far.
        let mut tails: Vec<u32> = Vec::new();
        let mut before = vec![u32::MAX; input.len()];
        for (i, &p) in at.iter().enumerate().filter(|&(_, &p)| p != u32::MAX) {
            let ends_below = |&t: &u32| at[t as usize] < p;
            let l = match tails.last() {
                Some(last) if !ends_below(last) => tails.partition_point(ends_below),
                _ => tails.len(),
            };
            if l > 0 {
                before[i] = tails[l - 1];
            }
            if l == tails.len() {
                tails.push(i as u32);
            } else {
                tails[l] = i as u32;
            }
        }
        let mut in_run = vec![false; input.len()];
        let mut i = tails.last().copied().unwrap_or(u32::MAX);
        while i != u32::MAX {
            in_run[i as usize] = true;
            i = before[i as usize];
        }
        drop((tails, before));
        let (mut inserted, mut removed, mut next) = (Vec::new(), Vec::new(), 0);
        for (i, &edge) in input.iter().enumerate() {
            if in_run[i] {
                inserted.extend(next..at[i]);
                next = at[i] + 1;
            } else {
                removed.push((i as u32, edge));
            }
        }
        if 12 * removed.len() + 4 * inserted.len() > 8 * input.len() {
            return Undo::Input(input);
        }
        inserted.shrink_to_fit();
        removed.shrink_to_fit();
        Undo::Delta {
            appended: output.len() - next as usize,
            inserted,
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
            Undo::Input(input) | Undo::Held(input) => Cow::Borrowed(input),
            Undo::Delta {
                appended,
                inserted,
                removed,
            } => {
                // Copied a run at a time (speed: a later stage reads its input back this way).
                let end = output.len() - appended;
                let kept: Cow<'_, [Edge]> = if inserted.is_empty() {
                    Cow::Borrowed(&output[..end])
                } else {
                    let mut kept = Vec::with_capacity(end - inserted.len());
                    let mut from = 0;
                    for &p in inserted {
                        kept.extend_from_slice(&output[from..p as usize]);
                        from = p as usize + 1;
                    }
                    kept.extend_from_slice(&output[from..end]);
                    Cow::Owned(kept)
                };
                let mut input = Vec::with_capacity(kept.len() + removed.len());
                let mut from = 0;
                for &(position, edge) in removed {
                    let to =
                        (from + (position as usize).saturating_sub(input.len())).min(kept.len());
                    input.extend_from_slice(&kept[from..to]);
                    input.push(edge);
                    from = to;
                }
                input.extend_from_slice(&kept[from..]);
                Cow::Owned(input)
            }
        }
    }
}

/// Each edge of `edges`' position in `output` (`u32::MAX` when absent), found among the output
/// positions bucketed by their edge's first end.
fn positions_in(output: &[Edge], edges: &[Edge]) -> Vec<u32> {
    let bound = output.iter().map(|e| e[0].index() + 1).max().unwrap_or(0);
    // Counted at `a + 2`, summed: `starts[a + 1]` is where bucket `a` begins, then, filled, ends.
    let mut starts = vec![0u32; bound + 2];
    for edge in output {
        starts[edge[0].index() + 2] += 1;
    }
    for a in 1..=bound {
        starts[a + 1] += starts[a];
    }
    let mut by_first = vec![0u32; output.len()];
    for (p, edge) in output.iter().enumerate() {
        let slot = &mut starts[edge[0].index() + 1];
        by_first[*slot as usize] = p as u32;
        *slot += 1;
    }
    let find = |&edge: &Edge| {
        let a = edge[0].index().min(bound);
        let bucket = &by_first[starts[a] as usize..starts[a + 1] as usize];
        bucket.iter().copied().find(|&p| output[p as usize] == edge)
    };
    edges.iter().map(|e| find(e).unwrap_or(u32::MAX)).collect()
}
