//! Junctions: where three curves meet (not in the paper; on by default, off in `Params::paper`).
//!
//! Owns: adding edges at a loose end that meets a curve at a junction, and giving a loose end at a
//! junction the place of the chord that runs past it. It reads positions, the graph and the
//! Delaunay rings; it may not touch the triangulation, removes no edge but such a chord, and does
//! not decide when it runs ([`Params::stages`](crate::Params::stages): after gap closing,
//! before the crossings).
//!
//! Why: at a junction of three curves (map borders, a T) the repair keeps two of the sample's three
//! edges, so the third curve ends one sample short; gap closing leaves such ends alone on purpose.
//! Rule (each test with its reason: docs/condt.md, *Junctions*): a loose end `a` joins the
//! Delaunay neighbour `c` with two edges that it faces within 30° ([`STRAIGHT`]; a crowded end's
//! angles read from the sample before its neighbour, as gap closing reads them), within
//! [`GAP_RATIO`] times `c`'s shorter edge (its longer where the two are not one sampling), with
//! three branches (`Ends::branch`), straightest ahead among those that pass (ties by id). A piece
//! of five or six points, too short for a branch, counts as the end's branch where its other end
//! meets a junction too, more than five passages from the first along its curve
//! (`Ends::bridges_to`: a stroke between two curves, not an arch over one). Where
//! the end's curve runs on smoothly ([`SMOOTH_COS`] at its first passages), the end may also
//! reach `c` through one sample without edges that lies straight ahead (a gap closing
//! walk, [`Ends::straight_walk`]) and meets `c` straight on: the repair can strand a branch's last
//! sample that lies as near the junction's neighbours as the junction. Of a direct join and such
//! a walk, the end takes the straighter. A point two ends choose takes both (a junction of four),
//! a point three or more choose takes none, and a stranded sample two walks pass goes to
//! neither. An end that joins nothing may instead be the junction's own sample, cut short by a
//! chord `c d` between two of its Delaunay neighbours whose curves both run straight on into it
//! ([`Ends::chord_past`]): `c d` gives way to the end's edges to `c` and `d`, unless `c` or `d`
//! takes part in another choice. All choices are made on the graph as it came in: the result
//! depends neither on the order of the ends nor on `parallel`. Rule 4 of the local outlier
//! removal and the clump stage ask earlier which pieces the joins would tie to a kept curve
//! ([`junction_joins`]), and keep them.

use super::gaps::{cos_at, crowded, one_sampling, Ends, Walk, GAP_RATIO, STRAIGHT};
use super::local_outliers::{MIN_SAMPLES, SMOOTH_COS};
use super::{uses, Replaced};
use crate::adjacency::{ordered, path_edges, Edge};
use crate::mesh::VertexId;
use alloc::vec::Vec;

impl Ends<'_> {
    /// Whether the degree-two point `c` has a junction's two branches and `|sc|` is within
    /// [`GAP_RATIO`] of its sampling (its shorter edge, or its longer where the two are not one
    /// sampling), for a join from `s`.
    fn junction_at(&self, s: VertexId, c: VertexId, avoid: VertexId) -> bool {
        if self.graph.degree(c) != 2 {
            return false;
        }
        let [x, y] = self.graph.first_two(c);
        let pc = self.point(c);
        let (e1, e2) = (pc.dist2(self.point(x)), pc.dist2(self.point(y)));
        // Where `c`'s edges are no one sampling by Algorithm 1's own ratio, the shorter measures
        // none: a second sample right beside the junction, as where outlines digitised apart
        // meet (a Natural Earth junction has one 1/2000 of a spacing away).
        let spacing = if one_sampling(&[e1, e2]) {
            e1.min(e2)
        } else {
            e1.max(e2)
        };
        self.point(s).dist2(pc) <= GAP_RATIO * GAP_RATIO * spacing
            && self.branch(c, x, &[avoid, y])
            && self.branch(c, y, &[avoid, x])
    }

    /// Whether the loose end `a` meets the degree-two point `c` at a junction (the module's rule).
    fn meets_at_junction(&self, a: VertexId, c: VertexId) -> bool {
        self.meets_directly(a, c) && {
            let [x, y] = self.graph.first_two(c);
            self.branch(a, self.along(a), &[c, x, y]) || self.bridges_to(a, c)
        }
    }

    /// Whether the loose end `a` faces the point `c` of degree two straight on, near enough,
    /// with `c`'s two branches: the module's rule but for the end's own branch.
    fn meets_directly(&self, a: VertexId, c: VertexId) -> bool {
        self.graph.degree(c) == 2
            && self.faces(a, c)
            && self.turn(a, c) < STRAIGHT
            && self.junction_at(a, c, a)
    }

    /// The other end of the piece the loose end `a` ends, where the piece is a path of
    /// [`MIN_SAMPLES`] points or one more, ending at a loose end: enough samples to show a curve,
    /// too few for a branch.
    fn short_piece_end(&self, a: VertexId) -> Option<VertexId> {
        let mut points = 2;
        let mut last = self.along(a);
        for [_, _, next] in self.graph.passages(a, last) {
            points += 1;
            last = next;
            if points > MIN_SAMPLES + 1 {
                return None;
            }
        }
        (points >= MIN_SAMPLES && self.graph.degree(last) == 1).then_some(last)
    }

    /// Whether the loose end `a`, meeting `c`, ends a short piece ([`Ends::short_piece_end`])
    /// whose other end meets a junction directly at a point other than `c` and more than
    /// [`MIN_SAMPLES`] passages from it along `c`'s curve: a stroke too short for a branch counts
    /// as one where its two ends meet curves at two junctions, not where it would close a small
    /// loop with one curve.
    fn bridges_to(&self, a: VertexId, c: VertexId) -> bool {
        let Some(other) = self.short_piece_end(a) else {
            return false;
        };
        self.tri
            .mesh()
            .neighbors(other)
            .any(|w| !self.near_along(c, w) && self.meets_directly(other, w))
    }

    /// Whether `w` is `c` (of degree two) or lies within [`MIN_SAMPLES`] passages of it along
    /// its curve, either way.
    fn near_along(&self, c: VertexId, w: VertexId) -> bool {
        w == c
            || self.graph.first_two(c).into_iter().any(|x| {
                x == w
                    || self
                        .graph
                        .passages(c, x)
                        .take(MIN_SAMPLES)
                        .any(|[_, _, next]| next == w)
            })
    }

    /// What the loose end `a` chooses, if anything: its junction, or else the chord past it.
    fn choice_of(&self, a: VertexId) -> Option<Choice> {
        // Both need the end's own branch, or a short piece that may bridge two junctions: without
        // either (most ends on scattered points) the rings are skipped (speed).
        if !self.branch(a, self.along(a), &[]) && self.short_piece_end(a).is_none() {
            return None;
        }
        match self.junction_of(a) {
            Some(junction) => Some(Choice::Join(junction)),
            None => self.chord_past(a).map(Choice::Chord),
        }
    }

    /// The junction the loose end `a` chooses, if any: the straightest ahead of the direct joins
    /// that pass and the join through a stranded sample, if any (a tie to the direct one).
    fn junction_of(&self, a: VertexId) -> Option<Junction> {
        let direct = self
            .tri
            .mesh()
            .neighbors(a)
            .filter(|&c| self.meets_at_junction(a, c))
            .map(|c| (self.turn(a, c), c))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        // A direct join beside the junction must not hide a walk through the branch's stranded
        // last sample that runs straighter (the junction's neighbours can lie within the turn
        // and the gap a direct join allows).
        let straighter = |&(turn, _): &(f64, Junction)| direct.is_none_or(|(d, _)| turn < d);
        match self.junction_beyond(a).filter(straighter) {
            Some((_, walked)) => Some(walked),
            None => direct.map(|(_, c)| Junction {
                end: a,
                walk: Walk::EMPTY,
                at: c,
            }),
        }
    }

    /// The chord that runs past the loose end `a` where it is a junction's sample, if exactly one
    /// does: an edge `c d` of two Delaunay neighbours of `a` of degree two whose curves each run
    /// straight on into `a` ([`STRAIGHT`]) and straighter through `a` than along the chord, every
    /// edge there within [`GAP_RATIO`] of the others, each of the three curves a branch. Evenly
    /// spaced borders meeting at a narrow angle put the branches' first samples nearer each other
    /// than the junction's sample: Algorithm 1 pairs them and the repair leaves the junction's
    /// sample a loose end. The end's curve must run on smoothly, as for a walk.
    fn chord_past(&self, a: VertexId) -> Option<ChordPast> {
        if self.sharpest_passage(a) >= SMOOTH_COS {
            return None;
        }
        let along = self.along(a);
        let mut found: Option<ChordPast> = None;
        for c in self.tri.mesh().neighbors(a) {
            if c == along || self.graph.degree(c) != 2 {
                continue;
            }
            for d in self.graph.first_two(c) {
                // Each chord is met from both its ends: tested from the smaller.
                if d <= c || d == a || d == along || self.graph.degree(d) != 2 {
                    continue;
                }
                let (c_on, d_on) = (self.graph.onward(c, d), self.graph.onward(d, c));
                let sampling = [(a, along), (a, c), (a, d), (c, c_on), (d, d_on)]
                    .map(|(u, w)| self.point(u).dist2(self.point(w)));
                let passes = self.cos_of(c, c_on, a) < STRAIGHT
                    && self.cos_of(d, d_on, a) < STRAIGHT
                    && self.straighter(c, d, a)
                    && self.straighter(d, c, a)
                    && one_sampling(&sampling)
                    && self.tri.mesh().adjacent(a, d)
                    && self.branch(c, c_on, &[a, d])
                    && self.branch(d, d_on, &[a, c])
                    && self.branch(a, along, &[c, d]);
                if !passes {
                    continue;
                }
                if found.is_some() {
                    // Two chords pass: which the junction cut short would be a guess.
                    return None;
                }
                found = Some(ChordPast { end: a, c, d });
            }
        }
        found
    }

    /// The junction a straight walk from the loose end `a` through samples without edges
    /// ([`Ends::straight_walk`]) reaches, with the cosine of the end's turn toward the walk: the
    /// repair can leave the branch's last sample without edges where it lies as near the
    /// junction's neighbours as the junction (evenly spaced borders). The end's curve must run
    /// on smoothly, the walk pass exactly one sample `s`, and `s` meet `c` straight on (read from
    /// the point before it, as the walk reads a step after a crowded one), within [`GAP_RATIO`]
    /// of the walk's last two steps, `c` being a junction as above whose branches do not run
    /// into the end's own curve.
    fn junction_beyond(&self, a: VertexId) -> Option<(f64, Junction)> {
        if self.sharpest_passage(a) >= SMOOTH_COS {
            return None;
        }
        let walk = self.straight_walk(a);
        let [s] = *walk else { return None };
        if self.graph.degree(s) != 0 {
            return None;
        }
        let along = self.along(a);
        let (ps, pa, p_along) = (self.point(s), self.point(a), self.point(along));
        let (step, last) = (ps.dist2(pa), pa.dist2(p_along));
        let from = if crowded(step, last) { p_along } else { pa };
        let span = step.max(last);
        self.tri
            .mesh()
            .neighbors(s)
            .filter(|&c| self.graph.degree(c) == 2)
            .map(|c| (cos_at(ps, from, self.point(c)), c))
            .filter(|&(cos, c)| {
                let [x, y] = self.graph.first_two(c);
                cos < STRAIGHT
                    && ps.dist2(self.point(c)) <= GAP_RATIO * GAP_RATIO * span
                    && self.junction_at(s, c, a)
                    && self.branch(a, along, &[c, x, y])
            })
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .map(|(_, c)| {
                let junction = Junction {
                    end: a,
                    walk,
                    at: c,
                };
                (self.turn(a, s), junction)
            })
    }
}

/// The edges the junctions stage would join at the loose ends of `ends` that `at` selects (each
/// end's own choice, before the ends that share a point are settled): rule 4 of the local outlier
/// removal and the clump stage keep the pieces they join to a component that stays
/// (`local_outliers::would_join`), as they keep those gap closing joins.
pub(crate) fn junction_joins(
    ends: &Ends<'_>,
    parallel: bool,
    at: impl Fn(VertexId) -> bool + Sync + Send,
) -> Vec<Edge> {
    // An end `at` does not select is not asked (a tile's ends it does not own).
    let found = ends.each_loose(parallel, |a| {
        match at(a).then(|| ends.choice_of(a)).flatten() {
            Some(Choice::Join(junction)) => Some(junction),
            _ => None,
        }
    });
    found.iter().flat_map(Junction::edges).collect()
}

/// A loose end's junction: the end, the samples without edges a walk passed on the way (none for
/// a direct join) and the junction's point.
#[derive(Copy, Clone, Debug)]
struct Junction {
    end: VertexId,
    walk: Walk,
    at: VertexId,
}

impl Junction {
    /// The edges that join the end to the junction, in order.
    fn edges(&self) -> impl Iterator<Item = Edge> + '_ {
        path_edges(self.end, &self.walk, self.at)
    }
}

/// A chord past a loose end's junction: `end` takes the place of the edge `c d` (`c < d`).
#[derive(Copy, Clone, Debug)]
struct ChordPast {
    end: VertexId,
    c: VertexId,
    d: VertexId,
}

/// What a loose end chooses: a join to the junction it meets, or else a chord it takes over.
#[derive(Copy, Clone, Debug)]
enum Choice {
    Join(Junction),
    Chord(ChordPast),
}

/// Joins loose ends in the graph of `ends` ([`super::with_ends`]) to the junctions they meet, and
/// replaces the chords that run past a loose end at a junction: those chords, and the joins'
/// edges by increasing end, then each chord's two new edges by increasing end.
pub(crate) fn join_junctions(ends: &Ends<'_>, parallel: bool) -> Replaced {
    let found: Vec<Choice> = ends.each_loose(parallel, |a| ends.choice_of(a));
    if found.is_empty() {
        return Replaced::default();
    }
    let mut joins: Vec<Junction> = Vec::with_capacity(found.len());
    let mut chords: Vec<ChordPast> = Vec::new();
    for choice in found {
        match choice {
            Choice::Join(junction) => joins.push(junction),
            Choice::Chord(chord) => chords.push(chord),
        }
    }
    // Two loose ends at one point make a junction of four (each end chooses once, and a point of
    // degree two is no loose end); three or more, none. A sample without edges two walks pass
    // goes to neither.
    let points = |join: &Junction| {
        let Junction { walk, at, .. } = *join;
        (0..=walk.len()).map(move |k| walk.get(k).copied().unwrap_or(at))
    };
    let uses_of_joins = uses(ends.tri.num_points(), &joins, points);
    // A chord's ends take part in nothing else: no other chord, no join chose them (counted before
    // the joins settle, so even a join dropped below keeps the chord out).
    let uses_of_chords = uses(ends.tri.num_points(), &chords, |chord| [chord.c, chord.d]);
    chords.retain(|chord| {
        [chord.c, chord.d]
            .iter()
            .all(|v| uses_of_chords[v.index()] == 1 && uses_of_joins[v.index()] == 0)
    });
    joins.retain(|join| {
        uses_of_joins[join.at.index()] <= 2
            && join.walk.iter().all(|v| uses_of_joins[v.index()] == 1)
    });
    let mut added: Vec<Edge> = joins.iter().flat_map(Junction::edges).collect();
    added.extend(
        chords
            .iter()
            .flat_map(|chord| [ordered(chord.end, chord.c), ordered(chord.end, chord.d)]),
    );
    let removed = chords
        .iter()
        .map(|chord| ordered(chord.c, chord.d))
        .collect();
    (removed, added)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{triangulate, Point};

    /// A straight curve `0..=12` along `y = 0` and, above point 6, a branch of `branch` samples
    /// at `x = 6`, `y = gap, gap + 1, ...`; with `below` samples more below point 6 as well when
    /// `below > 0` (a crossing whose two arms were dropped). Returns the joins the stage adds, in
    /// input positions.
    fn joins(branch: usize, gap: f64, below: usize) -> Vec<[usize; 2]> {
        let arms = [(1.0, branch), (-1.0, below)].map(|(sign, count)| {
            (0..count)
                .map(|k| Point::new(6.0, sign * (gap + k as f64)))
                .collect()
        });
        joins_of(&arms)
    }

    /// [`joins`] with the straight curve `0..=12` along `y = 0` and `arms`, each a curve of its
    /// own whose first point is its loose end.
    fn joins_of(arms: &[Vec<Point>]) -> Vec<[usize; 2]> {
        let line: Vec<Point> = (0..=12).map(|i| Point::new(i as f64, 0.0)).collect();
        joins_along(&line, arms)
    }

    /// [`joins_of`] with the curve through `line`, in order, in place of the straight one.
    fn joins_along(line: &[Point], arms: &[Vec<Point>]) -> Vec<[usize; 2]> {
        let mut pts = line.to_vec();
        let mut edges: Vec<[usize; 2]> = (1..line.len()).map(|i| [i - 1, i]).collect();
        for arm in arms {
            let first = pts.len();
            pts.extend_from_slice(arm);
            edges.extend((first..first + arm.len().saturating_sub(1)).map(|i| [i, i + 1]));
        }
        let [removed, added] = changes(&pts, &edges);
        assert_eq!(
            removed,
            Vec::<[usize; 2]>::new(),
            "no chord passes these ends"
        );
        added
    }

    /// The edges the stage removes from `edges` over `pts` and those it adds, in input positions.
    fn changes(pts: &[Point], edges: &[[usize; 2]]) -> [Vec<[usize; 2]>; 2] {
        let tri = triangulate(pts).unwrap();
        let listed: Vec<Edge> = edges
            .iter()
            .map(|&[a, b]| ordered(tri.vertex(a), tri.vertex(b)))
            .collect();
        let out = crate::stages::with_ends(&tri, &listed, None, false, join_junctions)
            .edges
            .unwrap_or_else(|| listed.clone());
        let positions =
            |list: Vec<Edge>| crate::Graph::new(&tri, alloc::borrow::Cow::Owned(list)).edges();
        let removed = listed
            .iter()
            .filter(|e| !out.contains(e))
            .copied()
            .collect();
        let added = out
            .iter()
            .filter(|e| !listed.contains(e))
            .copied()
            .collect();
        [positions(removed), positions(added)]
    }

    #[test]
    fn a_branch_one_sample_short_of_a_curve_is_joined_at_the_junction() {
        assert_eq!(joins(7, 1.0, 0), vec![[6, 13]]);
        // Sampled alike: a gap of 2.5 spacings is still one sampling, 3 is not.
        assert_eq!(joins(7, 2.5, 0), vec![[6, 13]]);
        assert_eq!(joins(7, 3.0, 0), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn a_junction_continues_its_branch_straight_on() {
        // A branch leaving the curve at 45°: its end runs straight on into point 6.
        let slanted: Vec<Point> = (1..8)
            .map(|k| Point::new(6.0 + k as f64, k as f64))
            .collect();
        assert_eq!(joins_of(&[slanted]), vec![[6, 13]]);
        // A curve alongside, one spacing above, ending over point 7: every point of the line
        // lies 45° or more off its way (point 6 at 135°), so it is no junction.
        let alongside: Vec<Point> = (7..14).map(|x| Point::new(x as f64, 1.0)).collect();
        assert_eq!(joins_of(&[alongside]), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn a_sample_next_to_the_junction_does_not_hide_it() {
        // Two outlines digitised apart meet at (6, 0): the curve has a second sample 1e-4 beside
        // it. The junction's two edges are then no one sampling, and its longer edge measures the
        // gap (by its shorter one, 1e-4, the branch's end one spacing away was too far).
        let branch: Vec<Point> = (1..8).map(|k| Point::new(6.0, k as f64)).collect();
        let mut line: Vec<Point> = (0..=12).map(|i| Point::new(i as f64, 0.0)).collect();
        line.insert(7, Point::new(6.0 + 1e-4, 0.0));
        assert_eq!(
            joins_along(&line, core::slice::from_ref(&branch)),
            vec![[6, 14]]
        );
        // A curve evenly sampled five times as densely: its samples are a sampling, and the
        // branch's end, five of their spacings away, is no junction of it.
        let dense: Vec<Point> = (0..=60).map(|i| Point::new(i as f64 / 5.0, 0.0)).collect();
        assert_eq!(joins_along(&dense, &[branch]), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn a_short_spur_is_not_a_branch() {
        // Five points of degree two past the end are needed: a branch of 6 samples has 4.
        assert_eq!(joins(6, 1.0, 0), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn two_ends_meeting_one_point_make_a_junction_of_four_and_three_none() {
        // Up and down from point 6, straight through it: in the pipeline gap closing takes such
        // a pair first (a crossing); the stage alone joins both.
        assert_eq!(joins(7, 1.0, 7), vec![[6, 13], [6, 20]]);
        // Up, and two arms from below that run straight into point 6 at 27° each side.
        let up: Vec<Point> = (1..8).map(|k| Point::new(6.0, k as f64)).collect();
        let right: Vec<Point> = (1..8)
            .map(|k| Point::new(6.0 + k as f64, -2.0 * k as f64))
            .collect();
        let left: Vec<Point> = (1..8)
            .map(|k| Point::new(6.0 - k as f64, -2.0 * k as f64))
            .collect();
        for pair in [[&up, &right], [&up, &left], [&right, &left]] {
            let arms = pair.map(|arm| arm.clone());
            assert_eq!(joins_of(&arms), vec![[6, 13], [6, 20]]);
        }
        assert_eq!(joins_of(&[up, right, left]), Vec::<[usize; 2]>::new());
    }

    #[test]
    fn a_branch_reaches_the_junction_through_its_stranded_last_sample() {
        // The branch's last sample (6, 1) has no edge (a one-point arm): its end (6, 2) walks
        // straight on through it to point 6.
        let stranded = alloc::vec![Point::new(6.0, 1.0)];
        let branch: Vec<Point> = (2..9).map(|k| Point::new(6.0, k as f64)).collect();
        assert_eq!(
            joins_of(&[stranded.clone(), branch]),
            vec![[6, 13], [13, 14]]
        );
        // A branch that turns sharply one sample before its end is an outlier's tail, not a
        // curve running into the junction: no walk.
        let mut tail = alloc::vec![Point::new(6.0, 2.0), Point::new(6.0, 3.0)];
        tail.extend((0..6).map(|k| Point::new(7.0 + k as f64, 2.2)));
        assert_eq!(joins_of(&[stranded, tail]), Vec::<[usize; 2]>::new());
        // Over the middle of an edge of the curve, the walk's last step would turn 40° to reach
        // either end of it: no sample of the curve lies straight on.
        let line: Vec<Point> = (0..=12).map(|i| Point::new(i as f64 + 0.5, 0.0)).collect();
        let stranded = alloc::vec![Point::new(6.0, 0.6)];
        let branch: Vec<Point> = (2..9).map(|k| Point::new(6.0, k as f64 - 0.4)).collect();
        assert_eq!(
            joins_along(&line, &[stranded, branch]),
            Vec::<[usize; 2]>::new()
        );
    }

    #[test]
    fn a_join_beside_the_junction_does_not_hide_the_stranded_walk() {
        // The end (10, 1.9) sees the junction's neighbours (9, 0) and (11, 0) within 30° and 2.75
        // spacings, a direct join; the walk through the stranded (10, 1) runs straight on.
        let line: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
        let stranded = alloc::vec![Point::new(10.0, 1.0)];
        let branch: Vec<Point> = (0..7).map(|k| Point::new(10.0, 1.9 + k as f64)).collect();
        assert_eq!(
            joins_along(&line, &[stranded, branch]),
            vec![[10, 21], [21, 22]]
        );
    }

    /// Three curves of `arms` samples leaving point 0 at 180°, 235.7° and 129° (a narrow
    /// junction as evenly spaced borders meet), the first two sampled `1.0` apart, the third
    /// `third` apart; point 0 keeps an edge to the third curve only, and the first samples of the
    /// other two are paired (points 1 and `1 + arms[0]`): their distance, 0.93, is under the
    /// junction's spacing. `bend` turns the first curve by that many degrees at its first sample.
    /// Returns the stage's removed and added edges in input positions.
    fn narrow_junction(arms: [usize; 3], third: f64, bend: f64) -> [Vec<[usize; 2]>; 2] {
        let mut pts = alloc::vec![Point::new(0.0, 0.0)];
        let mut edges = alloc::vec![[0, 1 + arms[0] + arms[1]], [1, 1 + arms[0]]];
        for (k, (angle, spacing)) in [(180.0, 1.0), (235.7, 1.0), (129.0, third)]
            .into_iter()
            .enumerate()
        {
            let first = pts.len();
            let direction = |degrees: f64| {
                let t = f64::to_radians(degrees);
                (libm::cos(t), libm::sin(t))
            };
            let (dx, dy) = direction(angle);
            let start = Point::new(dx * spacing, dy * spacing);
            let (bx, by) = direction(if k == 0 { angle + bend } else { angle });
            pts.extend((0..arms[k]).map(|j| {
                let j = j as f64 * spacing;
                Point::new(start.x + bx * j, start.y + by * j)
            }));
            edges.extend((first..first + arms[k] - 1).map(|i| [i, i + 1]));
        }
        changes(&pts, &edges)
    }

    #[test]
    fn a_chord_past_a_junction_sample_gives_way_to_it() {
        let changed = narrow_junction([8; 3], 1.0, 0.0);
        assert_eq!(changed, [vec![[1, 9]], vec![[0, 1], [0, 9]]]);
    }

    #[test]
    fn a_chord_stays_where_a_curve_does_not_run_into_the_loose_end() {
        let nothing: [Vec<[usize; 2]>; 2] = [Vec::new(), Vec::new()];
        // The first curve turns 40° at its first sample: it no longer heads for point 0.
        assert_eq!(narrow_junction([8; 3], 1.0, 40.0), nothing);
        // A third curve sampled three times as sparsely: no one sampling at the junction.
        assert_eq!(narrow_junction([8; 3], 3.0, 0.0), nothing);
        // Curves of four samples: no branches (the end's own curve is read first).
        assert_eq!(narrow_junction([4; 3], 1.0, 0.0), nothing);
        // The first or the second curve alone of four samples: the chord's own curves must be
        // branches too.
        assert_eq!(narrow_junction([4, 8, 8], 1.0, 0.0), nothing);
        assert_eq!(narrow_junction([8, 4, 8], 1.0, 0.0), nothing);
    }

    /// Point 0 and curves of eight samples one spacing apart leaving it at `degrees` (in order:
    /// curve `k` holds points `1 + 8k ..= 8 + 8k`); point 0 keeps an edge to curve `own` only,
    /// and each pair in `chords` joins the first samples of those two curves. Returns the
    /// stage's removed and added edges in input positions.
    fn star(degrees: &[f64], own: usize, chords: &[[usize; 2]]) -> [Vec<[usize; 2]>; 2] {
        changes(
            &star_points(degrees),
            &star_edges(degrees.len(), own, chords),
        )
    }

    /// The points of [`star`].
    fn star_points(degrees: &[f64]) -> Vec<Point> {
        let mut pts = alloc::vec![Point::new(0.0, 0.0)];
        for &angle in degrees {
            let t = f64::to_radians(angle);
            let (dx, dy) = (libm::cos(t), libm::sin(t));
            pts.extend((1..=8).map(|j| Point::new(dx * j as f64, dy * j as f64)));
        }
        pts
    }

    /// The edges of [`star`] with `curves` curves.
    fn star_edges(curves: usize, own: usize, chords: &[[usize; 2]]) -> Vec<[usize; 2]> {
        let first = |k: usize| 1 + 8 * k;
        let mut edges = alloc::vec![[0, first(own)]];
        edges.extend(chords.iter().map(|&[k, l]| [first(k), first(l)]));
        edges.extend((0..curves).flat_map(|k| (first(k)..first(k) + 7).map(|i| [i, i + 1])));
        edges
    }

    #[test]
    fn a_chord_stays_where_its_curve_runs_straighter_along_it() {
        // A right-angled junction: each chord curve runs straight into point 0.
        let replaced = [vec![[1, 9]], vec![[0, 1], [0, 9]]];
        assert_eq!(star(&[180.0, 270.0, 45.0], 2, &[[0, 1]]), replaced);
        // The first curve turned 25° toward the second beyond its first sample: it still
        // heads within 30° of point 0, but runs on straighter along the chord, which it keeps.
        let mut turned = star_points(&[180.0, 270.0, 45.0]);
        for (j, p) in turned[2..9].iter_mut().enumerate() {
            let t = f64::to_radians(155.0);
            let j = (j + 1) as f64;
            *p = Point::new(-1.0 + j * libm::cos(t), j * libm::sin(t));
        }
        let nothing: [Vec<[usize; 2]>; 2] = [Vec::new(), Vec::new()];
        assert_eq!(changes(&turned, &star_edges(3, 2, &[[0, 1]])), nothing);
    }

    #[test]
    fn two_chords_past_one_end_are_a_guess_and_stay() {
        // The narrow junction of `narrow_junction` and its mirror image across the end's own
        // curve (129°): each chord alone gives way to point 0.
        let one = star(&[180.0, 235.7, 129.0], 2, &[[0, 1]]);
        assert_eq!(one, [vec![[1, 9]], vec![[0, 1], [0, 9]]]);
        let mirrored = star(&[129.0, 78.0, 22.3], 0, &[[1, 2]]);
        assert_eq!(mirrored, [vec![[9, 17]], vec![[0, 9], [0, 17]]]);
        // Both chords at once: which one the junction cut short would be a guess.
        let both = star(&[180.0, 235.7, 129.0, 78.0, 22.3], 2, &[[0, 1], [3, 4]]);
        let nothing: [Vec<[usize; 2]>; 2] = [Vec::new(), Vec::new()];
        assert_eq!(both, nothing);
    }

    #[test]
    fn a_chord_whose_end_a_join_takes_stays() {
        // A fourth curve ends one spacing above the chord's first sample (point 1 at (-1, 0))
        // and heads straight down at it: a junction join to point 1, which the chord then
        // gives way to: point 1 would take three edges at once.
        let mut pts = star_points(&[180.0, 235.7, 129.0]);
        pts.extend((0..8).map(|j| Point::new(-1.0, 1.0 + j as f64)));
        let mut edges = star_edges(3, 2, &[[0, 1]]);
        edges.extend((25..32).map(|i| [i, i + 1]));
        let [removed, added] = changes(&pts, &edges);
        assert_eq!(removed, Vec::<[usize; 2]>::new());
        assert_eq!(added, vec![[1, 25]]);
    }

    #[test]
    fn a_chord_stays_where_the_end_s_own_curve_bends_sharply() {
        // The end's own curve (points 17 to 24) turns by 80° at its first sample: the end's
        // passages are not smooth, so nothing says the end continues its curve into a junction.
        let mut pts = star_points(&[180.0, 235.7, 129.0]);
        let start = pts[17];
        let t = f64::to_radians(129.0 - 80.0);
        for (j, p) in pts[18..25].iter_mut().enumerate() {
            let j = (j + 1) as f64;
            *p = Point::new(start.x + j * libm::cos(t), start.y + j * libm::sin(t));
        }
        let nothing: [Vec<[usize; 2]>; 2] = [Vec::new(), Vec::new()];
        assert_eq!(changes(&pts, &star_edges(3, 2, &[[0, 1]])), nothing);
    }

    /// Two straight curves of 13 samples along `y = 0` and `y = top`, and a stroke of `len`
    /// samples at `x = 6` from `y = 1` up; the stage's added edges, in input positions.
    fn rung(len: usize, top: f64) -> Vec<[usize; 2]> {
        let mut pts: Vec<Point> = (0..=12).map(|x| Point::new(x as f64, 0.0)).collect();
        pts.extend((0..=12).map(|x| Point::new(x as f64, top)));
        pts.extend((1..=len).map(|y| Point::new(6.0, y as f64)));
        let mut edges: Vec<[usize; 2]> = (0..12).chain(13..25).map(|i| [i, i + 1]).collect();
        edges.extend((26..25 + len).map(|i| [i, i + 1]));
        let [removed, added] = changes(&pts, &edges);
        assert!(removed.is_empty());
        added
    }

    #[test]
    fn a_stroke_too_short_for_a_branch_joins_where_both_its_ends_meet_curves() {
        // Six samples between two curves, each end one spacing from a curve: both join.
        assert_eq!(rung(6, 7.0), vec![[6, 26], [19, 31]]);
        // Five: still a curve's worth of samples.
        assert_eq!(rung(5, 6.0), vec![[6, 26], [19, 30]]);
        // Four: too few to show a curve.
        assert_eq!(rung(4, 5.0), Vec::<[usize; 2]>::new());
        // Six, the far curve three spacings beyond the stroke's end: that end meets nothing, and
        // neither end joins.
        assert_eq!(rung(6, 9.0), Vec::<[usize; 2]>::new());
    }

    /// A straight curve of 21 samples along `y = 0` and a path through `piece` from position 21
    /// on; the stage's added edges.
    fn over_a_line(piece: &[(f64, f64)]) -> Vec<[usize; 2]> {
        let mut pts: Vec<Point> = (0..=20).map(|x| Point::new(x as f64, 0.0)).collect();
        pts.extend(piece.iter().map(|&(x, y)| Point::new(x, y)));
        let mut edges: Vec<[usize; 2]> = (0..20).map(|i| [i, i + 1]).collect();
        edges.extend((21..20 + piece.len()).map(|i| [i, i + 1]));
        let [removed, added] = changes(&pts, &edges);
        assert!(removed.is_empty());
        added
    }

    #[test]
    fn a_short_arch_over_one_curve_is_no_bridge() {
        // Six samples, both ends one spacing above the line, three samples apart along it:
        // joined at both ends they would close a loop of nine with the line.
        let arch = [
            (8.0, 1.0),
            (8.0, 2.0),
            (9.0, 2.0),
            (10.0, 2.0),
            (11.0, 2.0),
            (11.0, 1.0),
        ];
        assert_eq!(over_a_line(&arch), Vec::<[usize; 2]>::new());
    }
}
