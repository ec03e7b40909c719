//! Spikes: a chord across a sharp tip whose samples have no edges given up for a path through
//! them (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: replacing one edge `a b` (the chord) by a path `a s1 … sk b` through two to
//! [`MOST`] points without edges, and joining two loose ends `a`, `b` by such a path. It reads positions, the graph and the Delaunay rings; it may
//! not touch the triangulation, and does not decide when it runs
//! ([`Params::stages`](crate::Params::stages): after the tips, before the hooks).
//!
//! Why: at a sharp, thin tip the samples of its two sides lie nearer each other across the tip
//! than along it, so Algorithm 1 pairs them across, the repair and the outlier rules drop those
//! pairs, and what is left is the chord across the tip's base with the tip's samples unused. The
//! tips step puts back a tip of one sample (its apex form); this step puts back a tip of several.
//!
//! Rule (each test with its reason: docs/condt.md, *Spikes*): for an edge `a b` whose ends have
//! two edges each (`a'` and `b'` the others), the points without edges that are Delaunay
//! neighbours of `a` or `b`, and those joined to them through Delaunay edges between points
//! without edges, each step within [`GAP_RATIO`] of the longer of `a a'` and `b b'`, must number
//! two to [`MOST`] (more is a scatter, not a tip). Of the paths from
//! `a` to `b` through all of them along Delaunay edges, the shortest (the first in the order of
//! the points' ids on a tie) replaces `a b` when, along `a' a s1 … sk b b'`:
//! - each edge is within [`GAP_RATIO`] of the one before it and the one after it (even sampling,
//!   Algorithm 1's bound);
//! - every passage is smooth ([`SMOOTH_COS`]) but one, at an `si`: the tip's apex;
//! - the path's points lie on the apex's side of the chord, each farther from its line than the
//!   one before up to the apex and nearer after it (one tip, not a zig-zag or a box);
//! - the chord is straight ([`STRAIGHT`]) at neither end: a chord across a tip's base turns at
//!   both, while the curve's own edge runs straight on beside stray points.
//!
//! The same path joins two loose ends `a` and `b` (`a'`, `b'` their neighbours) when both end
//! curves of [`MIN_SAMPLES`] points (as the tips step asks of the loose ends it joins) and the
//! tests above but the chord's pass, the line `a b` in the chord's place: a tip whose samples and
//! the edges to them the earlier stages all dropped.
//!
//! A point in two moves takes part in none: the result depends neither on the order nor on
//! `parallel`.

use super::found_at_vertices;
use super::gaps::{Ends, GAP_RATIO, STRAIGHT};
use super::local_outliers::{MIN_SAMPLES, SMOOTH_COS};
use super::{alone, Replaced};
use crate::adjacency::{ordered, path_edges, Edge};
use crate::bits::IdBits;
use crate::mesh::VertexId;
use crate::predicates::{orient2d, Orientation};
use alloc::vec::Vec;

/// Most samples of a tip the step puts back: as many as make a curve of its own
/// ([`MIN_SAMPLES`]); more points without edges gathered beside a chord or between two loose
/// ends are a scatter, not a tip's samples.
const MOST: usize = MIN_SAMPLES;

/// A move: the path `a run[0] … run[len - 1] b` joined, in place of the chord `a b` when
/// `chord` (else `a` and `b` are loose ends).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Spike {
    a: VertexId,
    b: VertexId,
    run: [VertexId; MOST],
    len: usize,
    chord: bool,
}

impl Spike {
    /// The points of the move, each once (owned, as the settling reads them).
    fn points(&self) -> impl Iterator<Item = VertexId> + use<> {
        let mut points = [self.a; MOST + 2];
        points[1] = self.b;
        points[2..2 + self.len].copy_from_slice(&self.run[..self.len]);
        points.into_iter().take(self.len + 2)
    }

    /// The edges the move adds, along the path from `a` to `b`.
    fn joins(&self) -> impl Iterator<Item = Edge> + '_ {
        path_edges(self.a, &self.run[..self.len], self.b)
    }
}

impl Ends<'_> {
    /// The points without edges a tip between the points `from` (a chord's two ends, two loose
    /// ends, or one loose end alone) would run through: those among their Delaunay neighbours,
    /// and those joined to them through points without edges, each step at most `reach2` (a
    /// squared length) long; `None` when there are more than [`MOST`] or fewer than two.
    fn tip_run(&self, from: &[VertexId], reach2: f64) -> Option<([VertexId; MOST], usize)> {
        let mesh = self.tri.mesh();
        let mut run = [VertexId::new(0); MOST];
        let mut len = 0;
        let add = |from: VertexId, w: VertexId, run: &mut [VertexId; MOST], len: &mut usize| {
            let near = self.point(from).dist2(self.point(w)) <= reach2;
            if self.graph.degree(w) != 0 || !near || run[..*len].contains(&w) {
                return true;
            }
            if *len == MOST {
                return false;
            }
            run[*len] = w;
            *len += 1;
            true
        };
        for &end in from {
            if !mesh.neighbors(end).all(|w| add(end, w, &mut run, &mut len)) {
                return None;
            }
        }
        let mut next = 0;
        while next < len {
            let at = run[next];
            if !mesh.neighbors(at).all(|w| add(at, w, &mut run, &mut len)) {
                return None;
            }
            next += 1;
        }
        (len >= 2).then_some((run, len))
    }

    /// Whether the spikes step would put back a tip of two to five samples on the chord `a b`
    /// (the tips step leaves such a chord to it).
    pub(super) fn spike_puts_back(&self, a: VertexId, b: VertexId) -> bool {
        self.spike_at(a, b).is_some()
    }

    /// The move of the chord `a b` (both ends of degree two), if any (the module's rule).
    fn spike_at(&self, a: VertexId, b: VertexId) -> Option<Spike> {
        let before_a = self.graph.onward(a, b);
        let after_b = self.graph.onward(b, a);
        // The chord's own passages first: on curves nearly every edge runs straight on at an end
        // (speed: the ring walks are skipped).
        if before_a == b
            || after_b == a
            || before_a == after_b
            || self.cos_of(a, before_a, b) < STRAIGHT
            || self.cos_of(b, after_b, a) < STRAIGHT
            || !self.leads_off(a, before_a)
            || !self.leads_off(b, after_b)
        {
            return None;
        }
        self.tip_through([before_a, a, b, after_b], true)
    }

    /// The move from `a` to `b` through the run of points without edges between them, given
    /// `[a', a, b, b']` (`chord`: whether `a b` is an edge the move replaces), if the run and its
    /// path pass the module's tests; the checks particular to a chord or to two loose ends
    /// (that a point without edges continues each end's curve, [`Ends::leads_off`]) are the
    /// caller's.
    fn tip_through(&self, [before_a, a, b, after_b]: [VertexId; 4], chord: bool) -> Option<Spike> {
        // A tip's samples lie within the curve's spacing of each other (Algorithm 1's bound on
        // the edges at its ends): points farther off, such as another tip's across the space
        // between two spikes, are not gathered.
        let (pa, pb) = (self.point(a), self.point(b));
        let spacing2 = pa
            .dist2(self.point(before_a))
            .max(pb.dist2(self.point(after_b)));
        let (mut run, len) = self.tip_run(&[a, b], GAP_RATIO * GAP_RATIO * spacing2)?;
        run[..len].sort_unstable();
        let best = self.shortest_path(a, b, run, len)?;
        self.is_tip(before_a, a, &best[..len], b, after_b)
            .then_some(Spike {
                a,
                b,
                run: best,
                len,
                chord,
            })
    }

    /// The loose ends from which a point without edges continues their curve
    /// ([`Ends::leads_off`] from the one neighbour), each asked once: a loose end is paired with
    /// every other beside its tip's run, and each pairing asked it again, walking its whole ring
    /// (a performance review: a point above 200,000 on a line, a loose end beside them all, made
    /// the step 1.7 s instead of milliseconds). Only those `beside` a point without edges can
    /// (speed: the others' rings are not walked); on rayon's threads when `parallel` (the same
    /// set).
    fn loose_ends_leading_off(
        &self,
        beside: impl Fn(VertexId) -> bool + Sync + Send,
        parallel: bool,
    ) -> IdBits {
        let leading = self.each_loose(parallel, |x| {
            (beside(x) && self.leads_off(x, self.along(x))).then_some(x.index())
        });
        IdBits::of(leading.into_iter())
    }

    /// The moves of the loose end `x` through a tip's run to another loose end, each pair of
    /// ends read by [`Ends::spike_between`] (so from either end alike), if any; `leading`:
    /// [`Ends::loose_ends_leading_off`].
    fn loose_spikes_at(&self, x: VertexId, leading: &IdBits) -> Option<Vec<Spike>> {
        if !leading.contains(x.index()) {
            return None;
        }
        let before = self.along(x);
        let reach2 = GAP_RATIO * GAP_RATIO * self.point(x).dist2(self.point(before));
        let (run, len) = self.tip_run(&[x], reach2)?;
        let mesh = self.tri.mesh();
        // Each other loose end once, however many of the run's points it lies beside (the
        // moves are sorted afterwards: the order here is free).
        let mut loose_beside: Vec<VertexId> = run[..len]
            .iter()
            .flat_map(|&s| mesh.neighbors(s))
            .filter(|&y| y != x && self.is_loose(y))
            .collect();
        loose_beside.sort_unstable();
        loose_beside.dedup();
        let found: Vec<Spike> = loose_beside
            .into_iter()
            .filter_map(|y| self.spike_between(x.min(y), x.max(y), leading))
            .collect();
        (!found.is_empty()).then_some(found)
    }

    /// The move joining the loose ends `a` and `b` through the points without edges between
    /// them, if any (the module's rule for two loose ends).
    fn spike_between(&self, a: VertexId, b: VertexId, leading: &IdBits) -> Option<Spike> {
        let (before_a, after_b) = (self.along(a), self.along(b));
        if before_a == b || after_b == a || before_a == after_b {
            return None;
        }
        // Each loose end ends a curve of its own, as the tips step asks of the loose ends it
        // joins: short pieces near crossings and in noise are not a tip's two sides.
        if !self.branch(a, before_a, &[]) || !self.branch(b, after_b, &[]) {
            return None;
        }
        if !leading.contains(a.index()) || !leading.contains(b.index()) {
            return None;
        }
        self.tip_through([before_a, a, b, after_b], false)
    }

    /// Whether a point without edges continues the curve from `before` through `at` smoothly and
    /// evenly: the path's first or last edge would need one (speed: tested before the run is
    /// gathered).
    fn leads_off(&self, at: VertexId, before: VertexId) -> bool {
        let (p, behind) = (self.point(at), self.point(at).dist2(self.point(before)));
        self.tri.mesh().neighbors(at).any(|w| {
            let to_w = p.dist2(self.point(w));
            self.graph.degree(w) == 0
                && to_w.max(behind) <= GAP_RATIO * GAP_RATIO * to_w.min(behind)
                && self.cos_of(at, before, w) < SMOOTH_COS
        })
    }

    /// The shortest path from `a` to `b` through all of `run[..len]` (sorted) along Delaunay
    /// edges: the first in the order of the permutations on a tie.
    fn shortest_path(
        &self,
        a: VertexId,
        b: VertexId,
        mut run: [VertexId; MOST],
        len: usize,
    ) -> Option<[VertexId; MOST]> {
        let mesh = self.tri.mesh();
        let linked = |u: VertexId, w: VertexId| mesh.adjacent(u, w);
        let length = |u: VertexId, w: VertexId| libm::sqrt(self.point(u).dist2(self.point(w)));
        let mut best: Option<(f64, [VertexId; MOST])> = None;
        loop {
            let path = &run[..len];
            let stops = || core::iter::once(a).chain(path.iter().copied()).chain([b]);
            let pairs = stops().zip(stops().skip(1));
            let total: f64 = pairs.clone().map(|(u, w)| length(u, w)).sum();
            if best.is_none_or(|(shortest, _)| total < shortest)
                && pairs.clone().all(|(u, w)| linked(u, w))
            {
                best = Some((total, run));
            }
            if !next_permutation(&mut run[..len]) {
                break;
            }
        }
        best.map(|(_, run)| run)
    }

    /// Whether `before_a a run… b after_b` is a tip in place of the chord `a b` (the module's
    /// tests of lengths, passages and side).
    fn is_tip(
        &self,
        before_a: VertexId,
        a: VertexId,
        run: &[VertexId],
        b: VertexId,
        after_b: VertexId,
    ) -> bool {
        let mut path = [VertexId::new(0); MOST + 4];
        path[0] = before_a;
        path[1] = a;
        path[2..2 + run.len()].copy_from_slice(run);
        path[2 + run.len()] = b;
        path[3 + run.len()] = after_b;
        let path = &path[..run.len() + 4];
        let length2 = |k: usize| self.point(path[k]).dist2(self.point(path[k + 1]));
        let even = (0..path.len() - 2).all(|k| {
            let (l, m) = (length2(k), length2(k + 1));
            l.max(m) <= GAP_RATIO * GAP_RATIO * l.min(m)
        });
        if !even {
            return false;
        }
        // The sharp passages, by their place in `path`: one, at a point of the run.
        let mut apex = None;
        for k in 1..path.len() - 1 {
            if self.cos_of(path[k], path[k - 1], path[k + 1]) >= SMOOTH_COS {
                if apex.is_some() || k < 2 || k > run.len() + 1 {
                    return false;
                }
                apex = Some(k - 2);
            }
        }
        let Some(apex) = apex else {
            return false;
        };
        // Twice the area of `a b s`, of the apex's sign: the distance from the chord's line, times
        // `|a b|`, on the apex's side. Rising from `a` (0) to the apex and falling to `b` (0), so
        // every point lies on that side.
        let (pa, pb) = (self.point(a), self.point(b));
        let cross = |s: VertexId| {
            let p = self.point(s);
            (pb.x - pa.x) * (p.y - pa.y) - (pb.y - pa.y) * (p.x - pa.x)
        };
        // The apex's side of the chord, exactly (an apex on the chord's line is no tip).
        let side = match orient2d(pa, pb, self.point(run[apex])) {
            Orientation::Ccw => 1.0,
            Orientation::Cw => -1.0,
            Orientation::Collinear => return false,
        };
        let height = |k: usize| match k {
            0 => 0.0,
            k if k <= run.len() => side * cross(run[k - 1]),
            _ => 0.0,
        };
        let apex = apex + 1;
        (0..apex).all(|k| height(k) < height(k + 1))
            && (apex..=run.len()).all(|k| height(k) > height(k + 1))
    }
}

/// Rearranges `items` into the next permutation in lexicographic order; `false` (and the first
/// order) after the last.
fn next_permutation(items: &mut [VertexId]) -> bool {
    let Some(i) = (1..items.len()).rev().find(|&i| items[i - 1] < items[i]) else {
        items.reverse();
        return false;
    };
    let j = (i..items.len())
        .rev()
        .find(|&j| items[j] > items[i - 1])
        .expect("items[i] is larger");
    items.swap(i - 1, j);
    items[i..].reverse();
    true
}

/// Puts tips of several unused samples back in the graph of `ends` ([`super::with_ends`]): the
/// chords, and each move's path from `a` to `b` by increasing `a`.
pub(crate) fn repair_spikes(ends: &Ends<'_>, parallel: bool) -> Replaced {
    let moves = settled(ends, parallel);
    let chords = moves
        .iter()
        .filter(|m| m.chord)
        .map(|m| ordered(m.a, m.b))
        .collect();
    let joins = moves.iter().flat_map(|m| m.joins()).collect();
    (chords, joins)
}

/// Every move of the rule on the graph of `ends`, settled: a point in two moves takes part in
/// none.
fn settled(ends: &Ends, parallel: bool) -> Vec<Spike> {
    let graph = &ends.graph;
    // Along clean curves no point is left without edges: one tight scan (speed).
    if !graph.has_unused() {
        return Vec::new();
    }
    // Each end of a move leads off to a point without edges beside it (`Ends::leads_off`): the
    // chords and loose ends are sought among the points beside one (speed: on scattered points
    // the others' ring walks are skipped), each chord once, from its smaller end.
    let marks = beside_unused(ends, parallel);
    let beside = |v: VertexId| marks.contains(v.index());
    let found = found_at_vertices(ends.tri.num_points(), parallel, |a| {
        if graph.degree(a) != 2 || !beside(a) {
            return None;
        }
        let found: Vec<Spike> = graph
            .first_two(a)
            .into_iter()
            .filter(|&b| a < b && graph.degree(b) == 2 && beside(b))
            .filter_map(|b| ends.spike_at(a, b))
            .collect();
        (!found.is_empty()).then_some(found)
    });
    let mut moves: Vec<Spike> = found.into_iter().flatten().collect();
    // Two loose ends with a tip's run between them (a tip whose samples and the edges to them
    // the earlier stages all dropped); only ends `beside` a point without edges lead off.
    let leading = ends.loose_ends_leading_off(beside, parallel);
    let loose = ends.each_loose(parallel, |x| ends.loose_spikes_at(x, &leading));
    moves.extend(loose.into_iter().flatten());
    if moves.is_empty() {
        return moves;
    }
    moves.sort_unstable();
    moves.dedup();
    // A chord with two moves cannot be: its run is found from its ends alone.
    alone(ends.tri.num_points(), &mut moves, &[], Spike::points);
    moves
}

/// The points with a point without edges among their Delaunay neighbours (marked from those
/// points' rings: the Delaunay edges join both ways).
fn beside_unused(ends: &Ends, parallel: bool) -> IdBits {
    let (graph, mesh, n) = (&ends.graph, ends.tri.mesh(), ends.tri.num_points());
    let unused = found_at_vertices(n, parallel, |u| (graph.degree(u) == 0).then_some(u));
    let mut marks = IdBits::new(n);
    for w in unused.into_iter().flat_map(|u| mesh.neighbors(u)) {
        marks.insert(w.index());
    }
    marks
}

#[cfg(test)]
mod tests {
    use crate::{triangulate, Point};

    /// A tip between two curves of `arm` points: one runs up the diagonal to `a` (point
    /// `arm - 1`, at (0, 0)), the tip's samples `run` (without edges) lead to `b` (at (2, 0),
    /// `arm + run.len()`), and the other runs down from `b`. Returns the points, the curves'
    /// edges and `b`.
    fn between_arms(arm: usize, run: &[(f64, f64)]) -> (Vec<Point>, Vec<[usize; 2]>, usize) {
        let top = (arm - 1) as f64;
        let mut pts: Vec<Point> = (0..arm)
            .map(|k| Point::new(k as f64 - top, k as f64 - top))
            .collect();
        pts.extend(run.iter().map(|&(x, y)| Point::new(x, y)));
        let b = pts.len();
        pts.extend((0..arm).map(|k| Point::new(2.0 + k as f64, -(k as f64))));
        let mut edges: Vec<[usize; 2]> = (1..arm).map(|i| [i - 1, i]).collect();
        edges.extend((b..b + arm - 1).map(|i| [i, i + 1]));
        (pts, edges, b)
    }

    /// A star's spike: [`between_arms`] of four points each, the graph pairing `a` (point 3) with
    /// `b`; `unused` are further points without edges.
    fn spike(run: &[(f64, f64)], unused: &[(f64, f64)]) -> (Vec<Point>, Vec<[usize; 2]>, usize) {
        let (mut pts, mut edges, b) = between_arms(4, run);
        edges.insert(3, [3, b]);
        pts.extend(unused.iter().map(|&(x, y)| Point::new(x, y)));
        (pts, edges, b)
    }

    fn spiked(pts: &[Point], edges: Vec<[usize; 2]>) -> Vec<[usize; 2]> {
        let tri = triangulate(pts).unwrap();
        tri.graph_from_edges(edges).repair_spikes().edges()
    }

    const TIP: [(f64, f64); 3] = [(0.5, 1.5), (1.0, 3.0), (1.5, 1.5)];

    #[test]
    fn a_tip_of_three_unused_samples_replaces_its_chord() {
        let (pts, edges, b) = spike(&TIP, &[]);
        let out = spiked(&pts, edges);
        assert!(!out.contains(&[3, b]));
        for e in [[3, 4], [4, 5], [5, 6], [6, b]] {
            assert!(out.contains(&e), "{e:?} missing from {out:?}");
        }
    }

    #[test]
    fn a_tip_of_two_samples_is_put_back_along_the_shorter_path() {
        // The apex is the second sample; `3 5 4 b` would be longer.
        let (pts, edges, b) = spike(&[(0.5, 1.5), (1.0, 3.0)], &[]);
        let out = spiked(&pts, edges);
        assert!(out.contains(&[3, 4]) && out.contains(&[4, 5]) && out.contains(&[5, b]));
        assert!(!out.contains(&[3, b]));
    }

    #[test]
    fn a_run_that_is_not_one_tip_or_a_scatter_keeps_the_chord() {
        // A corner at (0, 1), then level to (1, 1): the apex is not the farthest from the chord.
        let level = [(0.0, 1.0), (1.0, 1.0)];
        // Two sharp passages, at (0, 1.5) and (1.5, 2): a box, not a tip.
        let twice = [(0.0, 1.5), (1.5, 2.0), (1.5, 1.0)];
        for run in [&level[..], &twice[..]] {
            let (pts, edges, b) = spike(run, &[]);
            assert!(spiked(&pts, edges).contains(&[3, b]), "{run:?}");
        }
        // Five points without edges beside the chord: a scatter, not a tip's samples.
        let (pts, edges, b) = spike(&TIP, &[(1.0, 4.5), (1.0, 6.0)]);
        assert!(spiked(&pts, edges).contains(&[3, b]));
    }

    #[test]
    fn an_uneven_run_or_a_chord_that_runs_straight_on_stays() {
        // The apex three times as far from the sample before it as the tip's other edges.
        let (pts, edges, b) = spike(&[(0.5, 1.5), (1.0, 6.0), (1.5, 1.5)], &[]);
        assert!(spiked(&pts, edges).contains(&[3, b]));
        // A low tip on a straight line, smooth where it leaves the line: the chord `3 7` is the
        // line's own edge.
        let mut pts: Vec<Point> = (0..4).map(|k| Point::new(k as f64 - 3.0, 0.0)).collect();
        pts.extend([(1.0, 0.6), (2.0, 1.2), (3.0, 0.6)].map(|(x, y)| Point::new(x, y)));
        pts.extend((0..4).map(|k| Point::new(4.0 + k as f64, 0.0)));
        let edges = vec![[0, 1], [1, 2], [2, 3], [3, 7], [7, 8], [8, 9], [9, 10]];
        assert!(spiked(&pts, edges).contains(&[3, 7]));
    }

    /// Two curves of seven points ([`between_arms`]) whose ends `a` (point 6) and `b` are loose.
    fn loose_tip(run: &[(f64, f64)]) -> (Vec<Point>, Vec<[usize; 2]>, usize) {
        between_arms(7, run)
    }

    #[test]
    fn two_loose_ends_are_joined_through_a_tip_s_samples() {
        let (pts, edges, b) = loose_tip(&TIP);
        let out = spiked(&pts, edges);
        for e in [[6, 7], [7, 8], [8, 9], [9, b]] {
            assert!(out.contains(&e), "{e:?} missing from {out:?}");
        }
        // Short pieces (four points each side) are not a tip's two sides.
        let (pts, edges, b) = loose_tip(&TIP);
        let short: Vec<[usize; 2]> = edges
            .into_iter()
            .filter(|&[i, j]| (i >= 2 && j <= 6) || (i >= b && j <= b + 3))
            .collect();
        assert!(!spiked(&pts, short).contains(&[6, 7]));
    }
}
