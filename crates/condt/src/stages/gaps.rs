//! Closing gaps at loose ends (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: adding edges at loose ends (degree one) of the graph the earlier stages left. It reads
//! positions, the graph and the Delaunay rings; it may not touch the triangulation, never removes
//! an edge, and does not decide when it runs ([`Params::stages`](crate::Params::stages)). Why: with
//! at most two edges per point, the edge between two samples at a tight bend or in noise can be
//! nobody's choice, a sharp corner's sample can lose both edges, and at a sampled crossing the
//! repair drops two arms.
//!
//! A loose end `a` (one edge, to `a'`) *faces* a Delaunay neighbour `w` **ahead** (the angle at `a`
//! between `a'` and `w` above 90°, [`AHEAD`]: a half-plane, since at noisy ends and sharp corners
//! the last edge is a poor guide; where that edge is *crowded*, under `1 / GAP_RATIO` of the edge
//! before it, noise pushed `a` beside `a'` and every angle at `a` is read from the sample before
//! `a'` instead, as on a straight walk (4)) within a **short** gap (`|aw| <= GAP_RATIO · |aa'|`,
//! the paper's `u`: Algorithm 1's bound for one sampling; a longer gap is a real end).
//!
//! Candidates: (1) another loose end `b` facing `a`, or facing `a` while the join runs within 60°
//! of `a`'s edge ([`TIP`]: a sharp tip's apex left with one side, unless `a`'s side turns back at
//! once, under 90° at `a`'s neighbour: a hook, which the hooks step puts back in line and which
//! stays open with that step off); across a straight join ([`STRAIGHT`] at both ends, from the
//! end's edge or the chord over its last two edges, which noise moving the end sample bends
//! less), or a smooth one ([`SMOOTH_COS`] at both ends) that
//! bends no more than the curve's sharpest passage near either end ([`NEAR_END`]: noise bends both
//! alike), or a tip's join with a curve of [`MIN_SAMPLES`] behind both ends (a sharp tip's apex
//! often lies nearer its neighbour), a gap is measured against the longer of the end's last two
//! edges (noise crowding a sample shortens the last); (2) a point `c` of degree zero with a loose
//! end `d` across it facing `c`, the angle `a c d` above [`STRAIGHT`] (a stranded sample; one of
//! the two may instead be a tip's apex that sees `c` within [`TIP`] of its edge, if the other runs
//! on straight into `c`, the first sample of the tip's other side); (3) a crossing `c` of degree
//! two where `a` lines up (above [`STRAIGHT`]) with one of `c`'s neighbours while `c`'s passage is
//! bent (the repair paired an arm of each curve), or with a loose end facing `c` across `c`'s
//! passage (the repair kept one curve whole); never a `c` on `a`'s own curve within
//! [`MIN_SAMPLES`] points of it (a loop that short is no sampled crossing).
//!
//! (4) Last, for the ends that agreed on none of these: each walks straight on (above
//! [`STRAIGHT`], each step within [`GAP_RATIO`] of the longer of the two before, up to
//! [`MIN_SAMPLES`] points) through unused points, where a step crowded under `1 / GAP_RATIO` of
//! the one before (two samples noise pushed together) need only run ahead; two walks that reach
//! each other's ends or end at the same point join along them (a run of samples the earlier
//! stages dropped; a sharp tip's apex with its nearest samples, which lay nearer the other side
//! than their own).
//!
//! Each end takes its nearest candidate (distances whose squares round alike compared exactly, as
//! ids follow the orientation of the input; only an exact tie by id). Joins need evidence from
//! both sides, which keeps a genuinely open end open: two ends must choose each other, or the same
//! point with each other as partner; at a crossing both dropped arms must come back (one arm alone
//! is a T); a lone edge (two nearby outliers) joins only if both its ends do, along chains of
//! them to a fixed point (an end whose agreed join is so undone does not walk either, (4)). All
//! choices are made at once on the graph as it came in: the result does not depend on the order
//! of the ends, nor on `parallel`.

use super::found_at_vertices;
use super::local_outliers::{MIN_SAMPLES, SMOOTH_COS};
use super::Replaced;
use crate::adjacency::{ordered, CurveGraph, Edge};
use crate::geometry::Point;
use crate::mesh::VertexId;
use crate::predicates::{distance_order, orient2d, Orientation};
use crate::triangulate::Triangulation;
use alloc::borrow::Cow;
use alloc::vec::Vec;

/// Cosine of the smallest angle at a loose end between its edge and a join (90°: a half-plane).
const AHEAD: f64 = 0.0;
/// Cosine of the largest angle at a sharp tip's apex between its one edge and the join to the
/// other side (60°: the tip `Repair::Needs` reads). Two curve ends side by side make about 90°.
const TIP: f64 = 0.5;
/// Cosine of the smallest angle for two arms to form a straight passage (150°, as `CrossingAware`).
pub(super) const STRAIGHT: f64 = -0.866_025_403_784_438_6;
/// Passages read from a loose end to see how much its curve bends (noise included) near it.
const NEAR_END: usize = 3;
/// Longest gap, as a multiple of the loose end's own edge: the paper's `u = 2.75`.
pub(super) const GAP_RATIO: f64 = super::proximity::PAPER_U;

/// The cosine of the angle at `p` between `a` and `b` (`1` if either is at `p`: it passes no test).
pub(super) fn cos_at(p: Point, a: Point, b: Point) -> f64 {
    let (ux, uy, wx, wy) = (a.x - p.x, a.y - p.y, b.x - p.x, b.y - p.y);
    let norms = libm::sqrt((ux * ux + uy * uy) * (wx * wx + wy * wy));
    if norms > 0.0 {
        (ux * wx + uy * wy) / norms
    } else {
        1.0
    }
}

/// What a loose end chose.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Target {
    None,
    /// Another loose end (rule 1).
    End(VertexId),
    /// A point of degree zero or two (rules 2 and 3), with the arm the end lines up with there.
    Through(VertexId, Partner),
}

/// The arm a loose end lines up with at a stranded point or a crossing.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Partner {
    /// One of the crossing's two neighbours.
    Neighbor(VertexId),
    /// Another loose end across the point.
    End(VertexId),
}

/// A straight walk's points ([`Ends::straight_walk`]): at most [`MIN_SAMPLES`], held inline (no
/// allocation per loose end).
#[derive(Copy, Clone, Debug)]
pub(crate) struct Walk {
    len: usize,
    points: [VertexId; MIN_SAMPLES],
}

impl Walk {
    pub(crate) const EMPTY: Walk = Walk {
        len: 0,
        points: [VertexId::INFINITE; MIN_SAMPLES],
    };

    pub(crate) fn push(&mut self, v: VertexId) {
        self.points[self.len] = v;
        self.len += 1;
    }
}

impl core::ops::Deref for Walk {
    type Target = [VertexId];

    fn deref(&self) -> &[VertexId] {
        &self.points[..self.len]
    }
}

/// The loose ends of a graph and the tests on them (shared with the later steps: junctions,
/// crossings, tips, spikes, hooks, tails and detours read them too).
pub(crate) struct Ends<'a> {
    pub(super) tri: &'a Triangulation,
    /// Borrowed from a caller that goes on using it (rule 4), else owned and handed on.
    pub(super) graph: Cow<'a, CurveGraph>,
}

/// Whether a step of squared length `step` is *crowded* after one of squared length `before`:
/// under `1 / GAP_RATIO` of it, two samples noise pushed together, whose direction is the noise's.
/// The one test of a crowded loose end ([`Ends::heading_from`]) and a straight walk's crowded step.
pub(super) fn crowded(step: f64, before: f64) -> bool {
    GAP_RATIO * GAP_RATIO * step < before
}

/// Whether squared lengths are one sampling (the longest within [`GAP_RATIO`] of the shortest;
/// no lengths are): the crossings' four arms, a junction's edges around a chord past it.
pub(super) fn one_sampling(lengths2: &[f64]) -> bool {
    let longest = lengths2.iter().copied().fold(0.0, f64::max);
    let shortest = lengths2.iter().copied().fold(f64::INFINITY, f64::min);
    longest <= GAP_RATIO * GAP_RATIO * shortest
}

impl<'a> Ends<'a> {
    /// The loose ends of `edges`, with the previous stage's curve `graph` if any.
    pub(crate) fn new(tri: &'a Triangulation, edges: &[Edge], graph: Option<CurveGraph>) -> Self {
        let graph = graph.unwrap_or_else(|| CurveGraph::new(tri.num_points(), edges));
        Ends {
            tri,
            graph: Cow::Owned(graph),
        }
    }

    /// The curve graph, to hand on to the next stage, if it is this stage's own.
    pub(super) fn into_graph(self) -> Option<CurveGraph> {
        match self.graph {
            Cow::Owned(graph) => Some(graph),
            Cow::Borrowed(_) => None,
        }
    }

    /// The values `find` gives for the loose ends, by increasing id (on threads if `parallel`).
    pub(super) fn each_loose<T: Send>(
        &self,
        parallel: bool,
        find: impl Fn(VertexId) -> Option<T> + Sync + Send,
    ) -> Vec<T> {
        // Clean curves have none: the stages that start from loose ends then cost one scan.
        if !self.graph.has_loose_end() {
            return Vec::new();
        }
        found_at_vertices(self.tri.num_points(), parallel, |a| {
            self.is_loose(a).then(|| find(a)).flatten()
        })
    }

    pub(super) fn point(&self, v: VertexId) -> Point {
        self.tri.vertex_point(v)
    }

    pub(crate) fn is_loose(&self, v: VertexId) -> bool {
        self.graph.degree(v) == 1
    }

    /// The one neighbour of the loose end `a`.
    pub(super) fn along(&self, a: VertexId) -> VertexId {
        self.graph.first_two(a)[0]
    }

    /// The sample beyond the loose end `a`'s neighbour, where that neighbour has two edges.
    pub(super) fn beyond(&self, a: VertexId) -> Option<VertexId> {
        let next = self.along(a);
        (self.graph.degree(next) == 2).then(|| self.graph.onward(next, a))
    }

    /// Whether the chain from `next` away from `from` runs through at least [`MIN_SAMPLES`]
    /// points of degree two, none of them in `avoid`.
    pub(super) fn branch(&self, from: VertexId, next: VertexId, avoid: &[VertexId]) -> bool {
        let clear = self
            .graph
            .passages(from, next)
            .take_while(|p| !avoid.contains(&p[1]));
        clear.take(MIN_SAMPLES).count() == MIN_SAMPLES
    }

    /// Whether `w` is ahead of the loose end `a` and the gap is short (the module's two tests).
    pub(super) fn faces(&self, a: VertexId, w: VertexId) -> bool {
        w != self.along(a) && self.turn(a, w) < AHEAD && self.short(a, w, false)
    }

    /// The cosine of the angle at `at` between `u` and `w`.
    pub(super) fn cos_of(&self, at: VertexId, u: VertexId, w: VertexId) -> f64 {
        cos_at(self.point(at), self.point(u), self.point(w))
    }

    /// The cosine of the angle at the loose end `a` between its edge and `w`; where that edge
    /// is crowded (under `1 / GAP_RATIO` of the edge before it: noise pushed the end beside its
    /// neighbour, as in a straight walk), between the sample before it and `w`.
    pub(super) fn turn(&self, a: VertexId, w: VertexId) -> f64 {
        self.cos_of(a, self.heading_from(a), w)
    }

    /// The sample a loose end's direction is read from: its neighbour, or where the edge to it
    /// is crowded ([`Ends::turn`]), the sample before that.
    pub(super) fn heading_from(&self, a: VertexId) -> VertexId {
        let next = self.along(a);
        let (pa, pn) = (self.point(a), self.point(next));
        match self.beyond(a) {
            Some(beyond) if crowded(pa.dist2(pn), pn.dist2(self.point(beyond))) => beyond,
            _ => next,
        }
    }

    /// The cosine of the angle at the loose end `a` between the point two edges back and `w` (`1`
    /// where the curve ends sooner): the chord of the module's rule (1).
    fn chord_turn(&self, a: VertexId, w: VertexId) -> f64 {
        self.beyond(a)
            .map_or(1.0, |beyond| self.cos_of(a, beyond, w))
    }

    /// Whether the gap from the loose end `a` to `w` is within [`GAP_RATIO`] of `a`'s edge, or with
    /// `two_edges` of the longer of its last two edges.
    pub(super) fn short(&self, a: VertexId, w: VertexId, two_edges: bool) -> bool {
        self.point(a).dist2(self.point(w)) <= self.longest_gap2(a, two_edges)
    }

    /// The squared length of the longest short gap from the loose end `a` ([`Ends::short`]).
    fn longest_gap2(&self, a: VertexId, two_edges: bool) -> f64 {
        let next = self.along(a);
        let (p, back) = (self.point(a), self.point(next));
        let mut spacing = p.dist2(back);
        if two_edges && self.graph.degree(next) == 2 {
            let beyond = self.point(self.graph.onward(next, a));
            spacing = spacing.max(back.dist2(beyond));
        }
        GAP_RATIO * GAP_RATIO * spacing
    }

    /// The cosine of the sharpest of the first [`NEAR_END`] passages from the loose end `a`, or -1.
    pub(super) fn sharpest_passage(&self, a: VertexId) -> f64 {
        let passages = self.graph.passages(a, self.along(a)).take(NEAR_END);
        passages
            .map(|[prev, here, next]| self.cos_of(here, prev, next))
            .fold(-1.0, f64::max)
    }

    /// Whether the loose end `a`'s curve turns back at once: its first passage under 90°. A
    /// crowded end ([`Ends::heading_from`]) is not: its edge points where noise put it.
    fn hooked(&self, a: VertexId) -> bool {
        let next = self.along(a);
        self.heading_from(a) == next
            && self
                .beyond(a)
                .is_some_and(|beyond| self.cos_of(next, a, beyond) > AHEAD)
    }

    /// Whether the loose ends `a` and `b` may join (the module's rule (1)).
    fn ends_meet(&self, a: VertexId, b: VertexId) -> bool {
        let (at_a, at_b) = (self.turn(a, b), self.turn(b, a));
        let line_a = self.chord_turn(a, b).min(at_a);
        let line_b = self.chord_turn(b, a).min(at_b);
        let straight = (line_a < STRAIGHT && line_b < STRAIGHT)
            || (line_a < SMOOTH_COS
                && line_b < SMOOTH_COS
                && line_a.max(line_b) <= self.sharpest_passage(a).max(self.sharpest_passage(b)));
        // A tip's apex whose side turns back at once (under 90°) is a hook, not a tip: the
        // hooks step puts such an end back in line (with that step off, it stays open).
        let ahead = |c: f64| c < AHEAD;
        let (tip_a, tip_b) = (at_a > TIP && !self.hooked(a), at_b > TIP && !self.hooked(b));
        let ahead_or_tip =
            |here: f64, there: f64, tip_there: bool| ahead(here) && (ahead(there) || tip_there);
        // A tip's join between two curves (branches of MIN_SAMPLES behind both ends) is measured
        // as a straight one is: a sharp tip's apex often lies nearer its neighbour than the
        // spacing, and an outlier pair at a sharp angle has no such branches. The longer measure
        // passes whatever the shorter does, so the walks along the branches come last (speed).
        let sided = |e: VertexId| self.branch(e, self.along(e), &[]);
        let short = |two_edges: bool| self.short(a, b, two_edges) && self.short(b, a, two_edges);
        b != self.along(a)
            && a != self.along(b)
            && (ahead_or_tip(at_a, at_b, tip_b) || ahead_or_tip(at_b, at_a, tip_a))
            && (short(straight)
                || (!straight && (tip_a || tip_b) && short(true) && sided(a) && sided(b)))
    }

    /// Whether `w` is within [`TIP`] of the loose end `a`'s edge at a short gap (a tip's apex).
    fn tip_toward(&self, a: VertexId, w: VertexId) -> bool {
        w != self.along(a) && self.turn(a, w) > TIP && self.short(a, w, false)
    }

    /// Whether the loose end `a` reaches the point `c` for rule (2): faces it, or is a tip's apex
    /// toward it; `other_faces` says whether the end across, `other`, does.
    fn reaches(&self, a: VertexId, c: VertexId, other_faces: bool, other: VertexId) -> bool {
        let straight_on = |e: VertexId| self.turn(e, c) < STRAIGHT;
        if self.faces(a, c) {
            other_faces || straight_on(a)
        } else {
            other_faces && straight_on(other) && self.tip_toward(a, c)
        }
    }

    /// The loose end across `c` from `a` that `reaches` accepts and lines up with `a` best, among
    /// those `across` accepts.
    fn end_across(
        &self,
        a: VertexId,
        c: VertexId,
        reaches: impl Fn(VertexId) -> bool,
        across: impl Fn(Point) -> bool,
    ) -> Option<VertexId> {
        let (pa, pc) = (self.point(a), self.point(c));
        self.tri
            .mesh()
            .neighbors(c)
            .filter(|&d| d != a && self.is_loose(d) && reaches(d))
            .map(|d| (d, cos_at(pc, pa, self.point(d))))
            .filter(|&(d, cos)| cos < STRAIGHT && across(self.point(d)))
            .min_by(|x, y| x.1.total_cmp(&y.1).then(x.0.cmp(&y.0)))
            .map(|(d, _)| d)
    }

    /// Rule 3: the arm `a`, facing the degree-two point `c`, lines up with something there.
    fn crossing_partner(&self, a: VertexId, c: VertexId) -> Option<Partner> {
        let (pa, pc) = (self.point(a), self.point(c));
        let [x, y] = self.graph.first_two(c);
        let (px, py) = (self.point(x), self.point(y));
        if cos_at(pc, px, py) >= STRAIGHT {
            // A bent passage: an arm of each curve.
            let (cx, cy) = (cos_at(pc, pa, px), cos_at(pc, pa, py));
            if cx.min(cy) < STRAIGHT {
                // An exact tie goes to the smaller id, not to the neighbour listed first: the
                // order of `c`'s edges follows the edge list, which the result may not depend on.
                let second = cy < cx || (cy == cx && y < x);
                return Some(Partner::Neighbor(if second { y } else { x }));
            }
        }
        // A loose end across `c`, the pair crossing `c`'s passage.
        self.end_across(
            a,
            c,
            |d| self.faces(d, c),
            |pd| {
                let (sx, sy) = (orient2d(pa, pd, px), orient2d(pa, pd, py));
                sx != Orientation::Collinear && sy != Orientation::Collinear && sx != sy
            },
        )
        .map(Partner::End)
    }

    /// Whether `c` is one of the [`MIN_SAMPLES`] points of degree two behind the loose end `a` on
    /// its own curve. Such a point is no crossing `a` was dropped at: the curve would cross itself
    /// there in a loop of at most `MIN_SAMPLES + 1` samples (`a` and those behind it up to `c`),
    /// which is no sampled crossing. A noisy tip bends its own passages that far back below
    /// [`STRAIGHT`], and such a point may lie as near as the end across the gap.
    fn close_behind(&self, a: VertexId, c: VertexId) -> bool {
        let mut behind = self.graph.passages(a, self.along(a)).take(MIN_SAMPLES);
        behind.any(|[_, here, _]| here == c)
    }

    /// The nearest candidate of the loose end `a` (ties as the module says).
    pub(crate) fn target(&self, a: VertexId) -> Target {
        let pa = self.point(a);
        let mut best = Target::None;
        let mut best_key = (f64::INFINITY, VertexId::INFINITE);
        // Every candidate is within a short gap, at most the longer of `a`'s last two edges
        // ([`Ends::short`]): a farther neighbour is passed over untested (speed).
        let longest_gap2 = self.longest_gap2(a, true);
        for w in self.tri.mesh().neighbors(a) {
            let key = (pa.dist2(self.point(w)), w);
            if key.0 > longest_gap2 {
                continue;
            }
            // The first candidate is the nearest yet; then exact lengths, then ids.
            let at = |(length2, u): (f64, VertexId)| (self.point(u), length2);
            let order = || distance_order(pa, at(key), at(best_key)).then(key.1.cmp(&best_key.1));
            if !best_key.1.is_infinite() && order().is_ge() {
                continue;
            }
            // Facing is read for points of degree zero and two alone (speed: it measures an angle).
            let degree = self.graph.degree(w);
            let facing = matches!(degree, 0 | 2) && self.faces(a, w);
            let candidate = match degree {
                0 if facing || self.tip_toward(a, w) => self
                    .end_across(a, w, |d| self.reaches(d, w, facing, a), |_| true)
                    .map(|d| Target::Through(w, Partner::End(d))),
                1 if self.ends_meet(a, w) => Some(Target::End(w)),
                2 if facing && !self.close_behind(a, w) => self
                    .crossing_partner(a, w)
                    .map(|partner| Target::Through(w, partner)),
                _ => None,
            };
            if let Some(candidate) = candidate {
                (best, best_key) = (candidate, key);
            }
        }
        best
    }

    /// The unused points a straight walk from the loose end `a` passes, then the end it meets.
    ///
    /// Each step is within [`GAP_RATIO`] of the longer of the two before it (the end's last two
    /// edges at the start), as noise crowding a sample shortens one of them. A step under
    /// `1 / GAP_RATIO` of the one before is *crowded* (two samples noise pushed together): its
    /// direction is the noise's, so it need only run ahead ([`AHEAD`]), and the straightness of
    /// the step after it is read from the point before it.
    pub(crate) fn straight_walk(&self, a: VertexId) -> Walk {
        let mut path = Walk::EMPTY;
        let along = self.along(a);
        let (mut from, mut here) = (along, a);
        let mut last = self.point(along).dist2(self.point(a));
        let mut before = self
            .beyond(a)
            .map_or(0.0, |beyond| self.point(along).dist2(self.point(beyond)));
        for _ in 0..MIN_SAMPLES {
            let (pf, ph) = (self.point(from), self.point(here));
            let span = last.max(before);
            let next = self
                .tri
                .mesh()
                .neighbors(here)
                .filter(|&w| w != a && !path.contains(&w))
                .filter(|&w| matches!(self.graph.degree(w), 0 | 1))
                .map(|w| (ph.dist2(self.point(w)), w))
                .filter(|&(d, w)| {
                    let cos = cos_at(ph, pf, self.point(w));
                    d <= GAP_RATIO * GAP_RATIO * span
                        && (cos < STRAIGHT || (crowded(d, last) && cos < AHEAD))
                })
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let Some((d, w)) = next else { break };
            path.push(w);
            if self.graph.degree(w) == 1 {
                break;
            }
            if !crowded(d, last) {
                from = here;
            }
            (before, last, here) = (last, d, w);
        }
        path
    }

    /// The straight walks ([`Ends::straight_walk`]) of the loose ends other than the `joined`
    /// ones, by increasing end, those that pass a point. The walks run in ranges on several
    /// threads when `parallel` (each alone, the same list).
    fn walks(&self, joined: &[VertexId], parallel: bool) -> Vec<(VertexId, Walk)> {
        self.each_loose(parallel, |a| {
            if joined.binary_search(&a).is_ok() {
                return None;
            }
            let walk = self.straight_walk(a);
            (!walk.is_empty()).then_some((a, walk))
        })
    }
}

/// Rule (4) of the module: runs of unused points between two loose ends of `graph` (over `n`
/// points) along their `walks` (by increasing end, as [`Ends::walks`] lists them), unless a point
/// is in one of the `joins` made. Reads the graph alone.
fn stranded_runs(
    n: usize,
    graph: &CurveGraph,
    walks: Vec<(VertexId, Walk)>,
    joins: &[Edge],
) -> Vec<Edge> {
    if walks.is_empty() {
        return Vec::new();
    }
    let walk_of = |v: VertexId| {
        walks
            .binary_search_by_key(&v, |(a, _)| *a)
            .ok()
            .map(|k| &walks[k].1)
    };
    // Walks by the point they end at, to find two that meet.
    let mut by_last: Vec<(VertexId, usize)> = walks
        .iter()
        .enumerate()
        .map(|(k, (_, walk))| (*walk.last().expect("non-empty"), k))
        .collect();
    by_last.sort_unstable();
    let mut chains: Vec<Vec<VertexId>> = Vec::new();
    for (a, walk) in &walks {
        let last = *walk.last().expect("non-empty");
        let chain: Vec<VertexId> = if graph.degree(last) == 1 {
            // Reached a loose end: it must reach `a` back, through the same points.
            let inner = &walk[..walk.len() - 1];
            match walk_of(last) {
                Some(back)
                    if last > *a
                        && back.last() == Some(a)
                        && back[..back.len() - 1].iter().rev().eq(inner) =>
                {
                    core::iter::once(*a).chain(walk.iter().copied()).collect()
                }
                _ => continue,
            }
        } else {
            // Ended at an unused point: exactly one other walk must end there, from
            // elsewhere (of three or more, which two meet would be a guess).
            let mut others = listed_under(&by_last, last)
                .map(|k| &walks[k])
                .filter(|(b, _)| b != a);
            match (others.next(), others.next()) {
                (Some((b, w)), None)
                    if b > a && w.iter().all(|v| *v == last || !walk.contains(v)) =>
                {
                    core::iter::once(*a)
                        .chain(walk.iter().copied())
                        .chain(w.iter().rev().skip(1).copied())
                        .chain(core::iter::once(*b))
                        .collect()
                }
                _ => continue,
            }
        };
        chains.push(chain);
    }
    // Two runs through one point, or a run through a point a join took: neither is made
    // (which would win depends on the ids, that is on the input's orientation).
    let claimed: Vec<VertexId> = joins.iter().flatten().copied().collect();
    super::alone(n, &mut chains, &claimed, Vec::clone);
    let edges = chains.iter().flat_map(|chain| chain.windows(2));
    edges.map(|p| ordered(p[0], p[1])).collect()
}

/// The indices listed under `v` in `sorted`, a list of (point, index) pairs sorted by point.
fn listed_under(sorted: &[(VertexId, usize)], v: VertexId) -> impl Iterator<Item = usize> + '_ {
    let from = sorted.partition_point(|&(w, _)| w < v);
    let run = sorted[from..].iter().take_while(move |&&(w, _)| w == v);
    run.map(|&(_, k)| k)
}

/// Closes gaps in the graph of `ends` ([`super::with_ends`]): no edge removed, the joins added.
pub(crate) fn close_gaps(ends: &Ends<'_>, parallel: bool) -> Replaced {
    (Vec::new(), gap_joins(ends, parallel))
}

/// The joins [`close_gaps`] adds to the graph of `ends`, by increasing loose end.
pub(super) fn gap_joins(ends: &Ends<'_>, parallel: bool) -> Vec<Edge> {
    // Only loose ends choose (few): a list by increasing id, searched by id (memory). Each end
    // chooses alone (the stage's cost), in ranges on several threads when `parallel`.
    let targets: Vec<(VertexId, Target)> = ends.each_loose(parallel, |a| {
        Some((a, ends.target(a))).filter(|&(_, target)| target != Target::None)
    });
    let walks = |joined: &[VertexId]| ends.walks(joined, parallel);
    settle_joins(ends.tri.num_points(), &ends.graph, &targets, walks)
}

/// The joins from what the loose ends of `graph` (over `n` points) chose: `targets`, by
/// increasing end, those other than [`Target::None`] ([`Ends::target`]), and `walks(joined)`,
/// the straight walks of the ends not `joined` ([`Ends::walks`]). Agreement, the lone-edge fixed
/// point and the stranded runs read the graph alone, so a run split in tiles settles them on the
/// gathered edges ([`crate::tiled`]).
pub(crate) fn settle_joins(
    n: usize,
    graph: &CurveGraph,
    targets: &[(VertexId, Target)],
    walks: impl FnOnce(&[VertexId]) -> Vec<(VertexId, Walk)>,
) -> Vec<Edge> {
    let along = |a: VertexId| graph.first_two(a)[0];
    let slot = |a: VertexId| targets.binary_search_by_key(&a, |&(v, _)| v).ok();
    let target_of = |a: VertexId| slot(a).map_or(Target::None, |k| targets[k].1);
    // The ends lined up at each crossing (few), by crossing.
    let mut at_crossing: Vec<(VertexId, usize)> = targets
        .iter()
        .enumerate()
        .filter_map(|(k, &(_, target))| match target {
            Target::Through(c, Partner::Neighbor(_)) => Some((c, k)),
            _ => None,
        })
        .collect();
    at_crossing.sort_unstable();
    let arms = |c: VertexId| listed_under(&at_crossing, c);
    // Which of its two neighbours the crossing `c` is lined up with by the ends `counted`, one
    // bit per slot.
    let lined_up = |c: VertexId, counted: &dyn Fn(usize) -> bool| {
        arms(c)
            .filter(|&k| counted(k))
            .fold(0u8, |bits, k| match targets[k].1 {
                Target::Through(_, Partner::Neighbor(x)) => {
                    bits | 1 << usize::from(graph.first_two(c)[0] != x)
                }
                _ => bits,
            })
    };
    // Whether the loose end `a` gets the join it chose: the other side agrees.
    let agrees = |a: VertexId| match target_of(a) {
        Target::End(b) => target_of(b) == Target::End(a),
        // Both dropped arms come back, each in line with one of the two kept ones.
        Target::Through(c, Partner::Neighbor(_)) => lined_up(c, &|_| true) == 0b11,
        // Both come back, in line with each other, through a crossing or a stranded point.
        Target::Through(c, Partner::End(d)) => target_of(d) == Target::Through(c, Partner::End(a)),
        Target::None => false,
    };
    let agreed: Vec<bool> = targets.iter().map(|&(a, _)| agrees(a)).collect();
    // A lone edge (both its points loose) is joined only when both its ends are, and a join is
    // made only when every end taking part in it is (its partner; at a crossing, the other arm):
    // undoing one can undo another along a chain of lone edges, so to a fixed point, asking again
    // only the ends an undone one bears on (any order reaches the same point). Rule 4 asks for
    // these joins to keep pieces: a join counted there is one this stage makes.
    let holds = |made: &[bool], k: usize| {
        let (a, target) = targets[k];
        let is_made = |v: VertexId| slot(v).is_some_and(|j| made[j]);
        let next = along(a);
        (graph.degree(next) != 1 || is_made(next))
            && match target {
                Target::End(b) | Target::Through(_, Partner::End(b)) => is_made(b),
                Target::Through(c, Partner::Neighbor(_)) => lined_up(c, &|j| made[j]) == 0b11,
                Target::None => false,
            }
    };
    let mut made = agreed.clone();
    let mut queue: Vec<usize> = (0..targets.len()).filter(|&k| made[k]).collect();
    while let Some(k) = queue.pop() {
        if !made[k] || holds(&made, k) {
            continue;
        }
        made[k] = false;
        let (a, target) = targets[k];
        let next = along(a);
        if graph.degree(next) == 1 {
            queue.extend(slot(next));
        }
        match target {
            Target::End(b) | Target::Through(_, Partner::End(b)) => queue.extend(slot(b)),
            Target::Through(c, Partner::Neighbor(_)) => queue.extend(arms(c)),
            Target::None => {}
        }
    }
    let (mut joins, mut joined_ends) = (Vec::new(), Vec::new());
    for (k, &(a, target)) in targets.iter().enumerate() {
        // An end that found its partner does not walk (form 4), also where the lone-edge rule
        // undid the join: a walk would join what that rule keeps apart.
        if agreed[k] {
            joined_ends.push(a);
        }
        match target {
            _ if !made[k] => {}
            Target::End(b) if a < b => joins.push(ordered(a, b)),
            Target::Through(c, _) => joins.push(ordered(a, c)),
            _ => {}
        }
    }
    let runs = stranded_runs(n, graph, walks(&joined_ends), &joins);
    joins.extend(runs);
    joins
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangulate;
    use core::f64::consts::PI;

    const NONE: Vec<[usize; 2]> = Vec::new();

    /// Runs the stage on `pairs` (input positions) over `pts` and returns the joins it added, as
    /// sorted input positions.
    fn joins(pts: &[Point], pairs: &[[usize; 2]]) -> Vec<[usize; 2]> {
        let tri = triangulate(pts).unwrap();
        let edges: Vec<Edge> = pairs
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let outcome = crate::stages::with_ends(&tri, &edges, None, false, close_gaps);
        let out = outcome.edges.unwrap_or_else(|| edges.clone());
        assert_eq!(&out[..edges.len()], &edges[..], "never removes an edge");
        crate::Graph::new(&tri, alloc::borrow::Cow::Borrowed(&out[edges.len()..])).edges()
    }

    /// Two arms meet at `c = 0` at equal angles to a loose end below: the tie between them is
    /// settled by id, whichever of `c`'s two edges the list holds first.
    #[test]
    fn a_tie_between_the_arms_at_a_crossing_does_not_follow_the_list_order() {
        let mut pts = vec![Point::new(0.0, 0.0)];
        let mut pairs = Vec::new();
        // Four straight arms of six samples from `c`: up-left, up-right, down, down-left.
        for (dx, dy) in [(-1.0, 3.0), (1.0, 3.0), (0.0, -1.2), (-0.4, -1.2)] {
            let first = pts.len();
            pts.extend((1..=6).map(|k| Point::new(dx * k as f64, dy * k as f64)));
            pairs.extend((first..first + 5).map(|i| [i, i + 1]));
        }
        let (up_left, up_right) = (1, 7);
        let listed = |first: usize, second: usize| {
            let mut list = pairs.clone();
            list.extend([[0, first], [0, second]]);
            joins(&pts, &list)
        };
        let left_first = listed(up_left, up_right);
        assert_eq!(left_first, listed(up_right, up_left));
        // The tie is real: the down arm's loose end lines up with both upper arms alike.
        let (pa, pc) = (pts[13], pts[0]);
        let cos = |p: Point| cos_at(pc, pa, p);
        assert_eq!(cos(pts[up_left]), cos(pts[up_right]));
    }

    /// A chain through `0, 1, ..., n - 1`, without the edges listed in `missing` (by their
    /// smaller end).
    fn chain(n: usize, missing: &[usize]) -> Vec<[usize; 2]> {
        (0..n - 1)
            .filter(|i| !missing.contains(i))
            .map(|i| [i, i + 1])
            .collect()
    }

    /// A hairpin: two parallel legs joined by a half circle of radius 1 sampled every 30°,
    /// `(0..n)` in order along it.
    fn hairpin() -> Vec<Point> {
        let mut pts: Vec<Point> = (0..4)
            .map(|k| Point::new(-3.0 + k as f64 * 0.5, 1.0))
            .collect();
        pts.extend((1..6).map(|k| {
            let t = PI / 2.0 - k as f64 * PI / 6.0;
            Point::new(-1.5 + libm::cos(t) + 1.0, libm::sin(t))
        }));
        pts.extend((0..4).map(|k| Point::new(-1.0 - k as f64 * 0.5, -1.0)));
        pts
    }

    #[test]
    fn a_gap_at_a_tight_bend_is_closed() {
        let pts = hairpin();
        // The apex edge (a 30° turn at each end) is missing.
        assert_eq!(joins(&pts, &chain(pts.len(), &[6])), vec![[6, 7]]);
        // The same with a far offset and a tiny scale: only ratios matter.
        let moved: Vec<Point> = pts
            .iter()
            .map(|p| Point::new(1e6 + 1e-5 * p.x, -1e6 + 1e-5 * p.y))
            .collect();
        assert_eq!(joins(&moved, &chain(pts.len(), &[6])), vec![[6, 7]]);
    }

    /// A gap beside a noisy tip: the loose end `a` (2) turned back through the apex 1, and the
    /// sample 4, three edges behind `a`, lies nearer `a` than the straight end `b` (0) across the
    /// gap, its passage bent below [`STRAIGHT`] and lined up with `a` across it (through 5). It is
    /// no crossing `a` was dropped at (that would be a loop of four samples): `a` still chooses
    /// `b`.
    #[test]
    fn a_point_on_the_ends_own_curve_is_no_crossing_it_was_dropped_at() {
        let polar = |from: Point, length: f64, degrees: f64| {
            let t = degrees.to_radians();
            Point::new(
                from.x + length * libm::cos(t),
                from.y + length * libm::sin(t),
            )
        };
        let (b, a) = (Point::new(-0.2, 0.0), Point::new(1.6, 0.0));
        let apex = polar(a, 1.0, -38.4);
        let back = polar(apex, 1.2, 209.6);
        let near = polar(back, 0.88, 180.8);
        let mut pts = vec![b, apex, a, back, near];
        for k in 1..=5 {
            pts.push(polar(near, 1.2 * k as f64, 212.0));
        }
        pts.extend((1..=5).map(|k| Point::new(-0.2 - k as f64, 0.0)));
        assert!(pts[4].dist2(a) < b.dist2(a), "4 is nearer a than b is");
        let mut pairs = vec![[2, 1], [1, 3], [3, 4], [4, 5]];
        pairs.extend((5..9).map(|i| [i, i + 1]));
        pairs.extend([[0, 10], [10, 11], [11, 12], [12, 13], [13, 14]]);
        assert_eq!(joins(&pts, &pairs), vec![[0, 2]]);
    }

    /// [`Ends::close_behind`] covers the [`MIN_SAMPLES`] points behind a loose end, no farther.
    #[test]
    fn the_points_close_behind_a_loose_end_are_the_next_five_along_its_curve() {
        let pts: Vec<Point> = (0..9).map(|k| Point::new(k as f64, 0.0)).collect();
        let tri = triangulate(&pts).unwrap();
        let edges: Vec<Edge> = (0..8)
            .map(|i| ordered(tri.vertex(i), tri.vertex(i + 1)))
            .collect();
        let ends = Ends::new(&tri, &edges, None);
        let end = tri.vertex(0);
        let behind: Vec<usize> = (1..9)
            .filter(|&k| ends.close_behind(end, tri.vertex(k)))
            .collect();
        assert_eq!(behind, vec![1, 2, 3, 4, 5]);
    }

    /// Noise carried the sample 9 past 8 along a curve (the x of each sample falls from left to
    /// right in the list), so 9 hangs from 8, which joined 10: a hook. The loose ends 7 and 9 see
    /// each other as a tip's join would (the join within 60° of 9's edge, 9 the apex), but 9's
    /// side turns back at once, at 8 (36°): gap closing leaves it to the hooks step.
    #[test]
    fn an_end_that_hooks_back_is_no_tips_apex() {
        let pts: Vec<Point> = [
            (8.05, -1.12),
            (6.7, -0.72),
            (5.18, -0.79),
            (4.42, -0.78),
            (2.69, -0.46),
            (1.68, -0.35),
            (0.33, -0.36),
            (0.0, 0.0),
            (-2.27, -0.41),
            (-3.03, 0.04),
            (-4.44, -0.6),
            (-4.97, -0.05),
            (-6.72, 0.08),
            (-8.19, 0.06),
            (-9.59, -0.13),
            (-10.37, 0.4),
            (-11.5, 0.04),
        ]
        .iter()
        .map(|&(x, y)| Point::new(x, y))
        .collect();
        let mut pairs: Vec<[usize; 2]> = (0..7).map(|i| [i, i + 1]).collect();
        pairs.extend([[9, 8], [8, 10]]);
        pairs.extend((10..16).map(|i| [i, i + 1]));
        assert_eq!(joins(&pts, &pairs), NONE);
        // The whole default pipeline puts 9 back between 8 and 10.
        let chain: Vec<[usize; 2]> = (0..16).map(|i| [i, i + 1]).collect();
        let result = crate::reconstruct(&pts, &crate::Params::default()).unwrap();
        assert_eq!(result.edges().collect::<Vec<_>>(), chain);
    }

    #[test]
    fn a_gap_longer_than_u_times_the_end_edge_stays_open() {
        // Two unit-spaced chains along a line; the gap between 3 and 4 is `gap` long.
        let line = |gap: f64| -> Vec<Point> {
            (0..8)
                .map(|i| {
                    let x = i as f64 + if i >= 4 { gap - 1.0 } else { 0.0 };
                    Point::new(x, 0.0)
                })
                .collect()
        };
        // On a line the triangulation is a chain: still a ring around every point.
        let broken = chain(8, &[3]);
        assert_eq!(joins(&line(2.7), &broken), vec![[3, 4]]);
        assert_eq!(joins(&line(2.8), &broken), NONE);
    }

    /// A sharp tip: two arms of unit spacing meeting at 20° at the apex `0`, which kept its edge
    /// up the left arm; the right arm ends one spacing from the apex. The join is ahead of the
    /// right arm's end only (at the apex it runs 20° beside the apex's own edge), which suffices
    /// at a tip.
    #[test]
    fn a_sharp_tips_missing_side_is_joined_from_the_arm_that_sees_it_ahead() {
        let half = 10f64.to_radians();
        let arm = |side: f64, k: usize| {
            let r = k as f64;
            Point::new(side * r * libm::sin(half), r * libm::cos(half))
        };
        let mut pts = vec![Point::new(0.0, 0.0)];
        pts.extend((1..5).map(|k| arm(-1.0, k))); // 1..=4, the left arm
        pts.extend((1..5).map(|k| arm(1.0, k))); // 5..=8, the right arm
        let edges = [[0, 1], [1, 2], [2, 3], [3, 4], [5, 6], [6, 7], [7, 8]];
        assert_eq!(joins(&pts, &edges), vec![[0, 5]]);
        // The right arm's first sample stranded as well: the arm's end runs on straight through
        // it to the apex, which sees it within 20° of its edge (rule 2 with a tip on one side).
        let edges = [[0, 1], [1, 2], [2, 3], [3, 4], [6, 7], [7, 8]];
        assert_eq!(joins(&pts, &edges), vec![[0, 5], [5, 6]]);
        // Two parallel strokes ending side by side, one end a tenth of a spacing higher: the
        // join is ahead of that end (94°) but not a tip at the other (86°): no join.
        let strokes: Vec<Point> = (0..8)
            .map(|k| Point::new(1.5 * (k / 4) as f64, (k % 4) as f64 + 0.1 * (k / 4) as f64))
            .collect();
        assert_eq!(
            joins(&strokes, &[[0, 1], [1, 2], [2, 3], [4, 5], [5, 6], [6, 7]]),
            NONE
        );
    }

    /// A sharp tip (35°) whose apex `0` has lost its edge to the other side's last sample, `8`
    /// (straight on from that side), and lies 0.35 from its own neighbour where the spacing is
    /// 0.7: the gap of 1.3 is within 2.75 of the spacing, not of the apex's last edge. `sides`
    /// samples on each side.
    fn tip_with_a_crowded_apex(sides: usize) -> (Vec<Point>, Vec<[usize; 2]>) {
        let (c, s) = (libm::cos(35f64.to_radians()), libm::sin(35f64.to_radians()));
        let mut pts = vec![Point::new(0.0, 0.0)];
        pts.extend((0..sides - 1).map(|k| {
            let r = 0.35 + 0.7 * k as f64;
            Point::new(r * c, r * s)
        }));
        pts.extend((0..sides).map(|k| Point::new(1.3 + 0.7 * k as f64, 0.0)));
        let mut pairs: Vec<[usize; 2]> = (0..sides - 1).map(|k| [k, k + 1]).collect();
        pairs.extend((sides..2 * sides - 1).map(|k| [k, k + 1]));
        (pts, pairs)
    }

    #[test]
    fn a_tips_gap_between_two_curves_is_measured_against_the_spacing() {
        let (pts, pairs) = tip_with_a_crowded_apex(8);
        assert_eq!(joins(&pts, &pairs), vec![[0, 8]]);
        // With four samples a side there is no curve behind either end: the apex's last edge
        // is the measure, and the gap is too long for it.
        let (pts, pairs) = tip_with_a_crowded_apex(4);
        assert_eq!(joins(&pts, &pairs), NONE);
    }

    /// A crowded sample at the end of a unit-spaced line: its last edge is 0.35, the gap to the
    /// next line's end 1.15 (over 2.75 times 0.35). Straight on, the end's spacing is the
    /// longer of its last two edges and the gap closes; bent by 36° at the end, it stays open.
    #[test]
    fn a_straight_gap_is_measured_against_the_ends_last_two_edges() {
        let mut pts: Vec<Point> = [0.0, 1.0, 2.0, 3.0, 3.35]
            .map(|x| Point::new(x, 0.0))
            .to_vec();
        pts.extend([4.5, 5.5, 6.5, 7.5].map(|x| Point::new(x, 0.0)));
        let edges = chain(9, &[4]);
        assert_eq!(joins(&pts, &edges), vec![[4, 5]]);
        for (k, p) in pts[5..].iter_mut().enumerate() {
            *p = Point::new(4.3 + k as f64, 0.7 * (k + 1) as f64);
        }
        assert_eq!(joins(&pts, &edges), NONE);
    }

    /// A straight line whose end sample 4 noise pushed aside and onto sample 3 (its edge 0.5,
    /// at 37° to the line): the join to 5 bends 45° from that edge, but only 8° from the chord
    /// 2-4, so it is straight and closes (read along the edge alone, it stays open: the gap is four
    /// times that edge).
    #[test]
    fn a_straight_gap_is_read_along_the_chord_over_the_last_two_edges() {
        let mut pts: Vec<Point> = [0.0, 1.0, 2.0, 3.0].map(|x| Point::new(x, 0.0)).to_vec();
        pts.push(Point::new(3.4, -0.3));
        pts.extend([5.5, 6.5, 7.5, 8.5].map(|x| Point::new(x, 0.0)));
        assert_eq!(joins(&pts, &chain(9, &[4])), vec![[4, 5]]);
    }

    /// A 40° tip whose apex and the four samples before it on each side are unused (the sides'
    /// ends are too far apart to face each other across the tip): the two sides walk straight on
    /// through them and meet at the apex. A row of unused points that meets no walk stays.
    #[test]
    fn straight_walks_that_meet_at_a_tips_apex_join() {
        let side = |degrees: f64| -> Vec<Point> {
            let (c, s) = (
                libm::cos(degrees.to_radians()),
                libm::sin(degrees.to_radians()),
            );
            (1..=7)
                .map(|k| Point::new(k as f64 * c, k as f64 * s))
                .collect()
        };
        // 0-6 one side (0 nearest the apex), 7-13 the other, 14 the apex.
        let mut pts = side(160.0);
        pts.extend(side(200.0));
        pts.push(Point::new(0.0, 0.0));
        let sides = [[4, 5], [5, 6], [11, 12], [12, 13]];
        let mut expected: Vec<[usize; 2]> =
            (0..4).flat_map(|k| [[k, k + 1], [k + 7, k + 8]]).collect();
        expected.extend([[0, 14], [7, 14]]);
        expected.sort_unstable();
        assert_eq!(joins(&pts, &sides), expected);
        pts.extend((0..4).map(|k| Point::new(-2.0 - k as f64, 5.0)));
        assert_eq!(joins(&pts, &sides), expected);
    }

    /// Two samples that noise pushed together between two loose ends: the short step between
    /// them turns 41° off the line, and each end's nearest sample is another one of the two (no
    /// agreement on a stranded point). The walks read the step after the crowded one from the
    /// sample before it, pass both and meet.
    #[test]
    fn straight_walks_pass_two_crowded_samples() {
        let mut pts: Vec<Point> = (0..=5).map(|k| Point::new(k as f64, 0.0)).collect();
        pts.extend((8..=13).map(|k| Point::new(k as f64, 0.0)));
        pts.extend([Point::new(6.4, 0.1), Point::new(6.65, -0.12)]);
        let pieces: Vec<[usize; 2]> = (0..5).chain(6..11).map(|i| [i, i + 1]).collect();
        assert_eq!(joins(&pts, &pieces), vec![[5, 12], [6, 13], [12, 13]]);
    }

    /// A loose end that noise pushed beside its neighbour (the edge to it a third of the
    /// spacing, turned 100° off the curve, a little backwards): its edge points away from the
    /// gap, so only the sample before it tells that the other curve's end lies ahead.
    #[test]
    fn a_crowded_loose_end_faces_the_gap_from_the_sample_before() {
        let angle = 100f64.to_radians();
        let mut pts: Vec<Point> = (0..4).map(|k| Point::new(k as f64, 0.0)).collect();
        pts.push(Point::new(
            3.0 + 0.35 * libm::cos(angle),
            0.35 * libm::sin(angle),
        ));
        pts.extend((0..5).map(|k| Point::new(3.6 + k as f64, 0.35)));
        let pieces: Vec<[usize; 2]> = (0..4).chain(5..9).map(|i| [i, i + 1]).collect();
        assert_eq!(joins(&pts, &pieces), vec![[4, 5]]);
    }

    /// A turtle walk from the origin: each step turns by the given degrees, then goes the
    /// given length.
    fn walk(steps: &[(f64, f64)]) -> Vec<Point> {
        let (mut p, mut heading) = (Point::new(0.0, 0.0), 0.0f64);
        let mut pts = vec![p];
        for &(turn, length) in steps {
            heading += turn.to_radians();
            p = Point::new(
                p.x + length * libm::cos(heading),
                p.y + length * libm::sin(heading),
            );
            pts.push(p);
        }
        pts
    }

    /// A zig-zag (passages of 140°, as noise bends a curve) whose point 4 was crowded onto point
    /// 3 (its edge 0.35): the gap 4-5 (1.05, bent 35° at both ends) is three times that edge.
    /// The join bends no more than the curve does, so the gap is measured against the longer of
    /// the end's last two edges and closes; along a straight curve the same bent join stays open.
    #[test]
    fn a_gap_that_bends_like_its_curve_is_measured_against_the_last_two_edges() {
        let zigzag = |bend: f64| -> Vec<(f64, f64)> {
            let turns = [0.0, bend, -bend, bend, -35.0, 35.0, -bend, bend, -bend];
            let lengths = [1.0, 1.0, 1.0, 0.35, 1.05, 1.0, 1.0, 1.0, 1.0];
            turns.into_iter().zip(lengths).collect()
        };
        let edges = chain(10, &[4]);
        assert_eq!(joins(&walk(&zigzag(40.0)), &edges), vec![[4, 5]]);
        assert_eq!(joins(&walk(&zigzag(0.0)), &edges), NONE);
    }

    #[test]
    fn an_open_arc_stays_open() {
        // 270° of the unit circle, 30 samples: the ends are 1.41 apart, nine times the spacing.
        let pts: Vec<Point> = (0..30)
            .map(|k| {
                let t = k as f64 * 1.5 * PI / 29.0;
                Point::new(libm::cos(t), libm::sin(t))
            })
            .collect();
        assert_eq!(joins(&pts, &chain(30, &[])), NONE);
        // Two arcs back to back, `)(`, each end near the other's but not facing it.
        let mut parens: Vec<Point> = (0..9)
            .map(|k| {
                let t = PI * (0.75 + k as f64 * 0.5 / 8.0);
                Point::new(1.05 + libm::cos(t), libm::sin(t))
            })
            .collect();
        parens.extend(
            (0..9)
                .map(|k| Point::new(-parens[k].x, parens[k].y))
                .collect::<Vec<_>>(),
        );
        let mut pairs = chain(9, &[]);
        pairs.extend(chain(9, &[]).iter().map(|&[a, b]| [a + 9, b + 9]));
        assert_eq!(joins(&parens, &pairs), NONE);
    }

    /// Nine samples along a gentle arc, `0..9` in order.
    fn arc() -> Vec<Point> {
        (0..9)
            .map(|i| {
                let t = (i as f64 - 4.0) * 0.1;
                Point::new(10.0 * libm::sin(t), 10.0 * libm::cos(t))
            })
            .collect()
    }

    #[test]
    fn a_stranded_sample_is_joined_from_both_sides() {
        // Sample 4 lost both its edges; its neighbours are loose and line up through it.
        let pts = arc();
        assert_eq!(joins(&pts, &chain(9, &[3, 4])), vec![[3, 4], [4, 5]]);
        // Moved off the curve (the angle 3-4-5 below 150°) it is an outlier: the two ends join
        // each other across it instead.
        let mut off = pts.clone();
        off[4] = Point::new(off[4].x, off[4].y + 0.5);
        assert_eq!(joins(&off, &chain(9, &[3, 4])), vec![[3, 5]]);
    }

    #[test]
    fn a_lone_edge_joins_only_when_both_its_ends_do() {
        // 0-1-2, then 3-4 alone, then 5-6-7-8: a piece of curve between two gaps.
        let pts = arc();
        assert_eq!(joins(&pts, &chain(9, &[2, 4])), vec![[2, 3], [4, 5]]);
        // The same pair past the end of a curve (nothing beyond 4): two outliers, left alone.
        let short = &pts[..5];
        assert_eq!(joins(short, &chain(5, &[2])), NONE);
        // Two such pairs in a row: the far one is left alone, so the near one joins on one side
        // only and is left alone too (not joined to the curve at 2-3).
        let shorter = &pts[..7];
        assert_eq!(joins(shorter, &chain(7, &[2, 4])), NONE);
    }

    /// A plus sign: a horizontal chain `0..7` and a vertical chain `7..14`, both through the
    /// crossing, which is point 3 of the first (the vertical chain's middle, position 10, is a
    /// copy of it: the triangulation merges the two).
    fn plus() -> Vec<Point> {
        let mut pts: Vec<Point> = (0..7).map(|i| Point::new(i as f64 - 3.0, 0.0)).collect();
        pts.extend((0..7).map(|i| Point::new(0.0, (i as f64 - 3.0) * 1.1)));
        pts
    }

    #[test]
    fn a_crossings_dropped_passage_is_restored() {
        let pts = plus();
        // The repair kept the horizontal passage and dropped both vertical arms (9-3, 3-11).
        let mut pairs = chain(7, &[]);
        pairs.extend([[7, 8], [8, 9], [11, 12], [12, 13]]);
        assert_eq!(joins(&pts, &pairs), vec![[3, 9], [3, 11]]);
    }

    #[test]
    fn a_crossings_dropped_arms_are_restored_after_a_bent_passage() {
        let pts = plus();
        // The repair kept a bend, left arm to upper arm (2-3-11), and dropped the right arm
        // (3-4) and the lower arm (9-3).
        let mut pairs = chain(3, &[]);
        pairs.extend([
            [2, 3],
            [4, 5],
            [5, 6],
            [7, 8],
            [8, 9],
            [3, 11],
            [11, 12],
            [12, 13],
        ]);
        assert_eq!(joins(&pts, &pairs), vec![[3, 4], [3, 9]]);
    }

    #[test]
    fn an_end_pointing_at_a_straight_passage_without_a_partner_stays_loose() {
        // A T whose stem stops one spacing short of the bar: nothing continues across the bar,
        // so the stem is an open end, not a crossing arm.
        let mut pts: Vec<Point> = (0..7).map(|i| Point::new(i as f64 - 3.0, 0.0)).collect();
        pts.extend((1..4).map(|i| Point::new(0.0, i as f64)));
        let mut pairs = chain(7, &[]);
        pairs.extend([[7, 8], [8, 9]]);
        assert_eq!(joins(&pts, &pairs), NONE);
    }
}
