//! Reconstruction metrics: how an edge set compares with a ground truth.
//!
//! Owns: [`score`] and the values it returns ([`Score`], [`EdgeProblem`], [`ScoreError`]), and
//! the nearest-segment search the distances need. It reads points and edge lists given in input
//! positions; it may not triangulate or reconstruct (it judges any program's output, not only
//! condt's), and it decides no geometric sign.
//!
//! The metrics are those of the evaluation suite the project measures itself with, so that a
//! score computed here and one computed there can be compared number for number:
//! - **exact**: the output edge set equals the truth's;
//! - **precision, recall, F1** on the two edge sets (edges are undirected);
//! - **outlier edges**: output edges with an end the truth leaves without an edge;
//! - **maximum and RMS distance** of the output to the truth: each output edge is sampled at 0,
//!   1/4, 1/2, 3/4 and 1 of its length, each sample's distance to the nearest truth segment is
//!   divided by the diagonal of the points' bounding box. An output edge that is a truth edge
//!   contributes five zeros; an end that has a truth edge is at distance zero. They are
//!   computed on the points scaled by a power of two, so they are the same at every such scale,
//!   up to ±`f64::MAX` and down to the smallest normal numbers.
//!
//! The distances are exact nearest-segment distances, for every output edge however many are
//! wrong; the suite's scorer samples at most 10,000 wrong edges and stops a query within 1 % of
//! the answer, so on outputs with more wrong edges than that its RMS is an estimate of this one.
//! A bounding-volume hierarchy holds the short truth segments, and strips the long ones, with
//! classes of slope in each strip (`LongStrips`, on rayon's threads with the feature `parallel`,
//! the same numbers as on one). Their cost on a truth of `n` long segments that cross one
//! another, as a chain through random points does, grows as `n^(4/3)`: exact answers for `n`
//! points among `n` lines in less would decide Hopcroft's problem (does a point lie on a line)
//! faster than its best known bound. What the strips win is the constant: scored against another
//! chain, a chain of 2M edges through random points takes about 12 s on two busy cores, where
//! cells of direction classes took 60 s on a quiet machine.

use crate::geometry::Point;
use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec;
use alloc::vec::Vec;
use condt::geometry::{binary_exponent, Scale};
use core::fmt;

/// The fractions of its length at which an output edge is sampled for the distances.
const SAMPLES: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// What is wrong with an edge list, by the position of the first offending edge in it.
///
/// ```
/// use condt_eval::score::{score, EdgeProblem};
/// use condt::Point;
/// let points = [(0.0, 0.0), (1.0, 0.0)].map(Point::from);
/// let result = score(&points, &[[0, 1], [1, 0]], &[[0, 1]]).unwrap();
/// assert_eq!(result.malformed, Some(EdgeProblem::Repeated { position: 1, edge: [0, 1] }));
/// assert_eq!(result.f1, 0.0); // a malformed output scores nothing
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum EdgeProblem {
    /// An end is not a position in the points.
    OutOfRange {
        /// Position of the edge in the list.
        position: usize,
        /// The end that is out of range.
        index: usize,
    },
    /// Both ends are the same point.
    SelfLoop {
        /// Position of the edge in the list.
        position: usize,
        /// The point.
        index: usize,
    },
    /// The edge (in either direction) came earlier in the list.
    Repeated {
        /// Position of the second occurrence in the list.
        position: usize,
        /// The edge, smaller end first.
        edge: [usize; 2],
    },
}

impl EdgeProblem {
    /// Position in the list of the edge the problem is about.
    ///
    /// ```
    /// use condt_eval::score::EdgeProblem;
    /// assert_eq!(EdgeProblem::SelfLoop { position: 4, index: 2 }.position(), 4);
    /// ```
    pub fn position(&self) -> usize {
        match *self {
            EdgeProblem::OutOfRange { position, .. }
            | EdgeProblem::SelfLoop { position, .. }
            | EdgeProblem::Repeated { position, .. } => position,
        }
    }
}

impl fmt::Display for EdgeProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            EdgeProblem::OutOfRange { index, .. } => write!(f, "point {index} does not exist"),
            EdgeProblem::SelfLoop { index, .. } => write!(f, "self-loop at point {index}"),
            EdgeProblem::Repeated { edge: [a, b], .. } => write!(f, "edge {a} {b} repeated"),
        }
    }
}

/// Why [`score`] cannot compare at all.
///
/// ```
/// use condt_eval::score::{score, EdgeProblem, ScoreError};
/// use condt::Point;
/// let points = [(0.0, 0.0), (1.0, 0.0)].map(Point::from);
/// let err = score(&points, &[], &[[0, 2]]).unwrap_err();
/// assert_eq!(err, ScoreError::Truth(EdgeProblem::OutOfRange { position: 0, index: 2 }));
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum ScoreError {
    /// The point at this input position has a NaN or infinite coordinate.
    NonFinite {
        /// Input position of the point.
        index: usize,
    },
    /// The ground truth is not a valid edge list; a malformed *output* is not an error but a
    /// failed score ([`Score::malformed`]).
    Truth(EdgeProblem),
}

impl fmt::Display for ScoreError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScoreError::NonFinite { index } => {
                write!(f, "point {index} has a NaN or infinite coordinate")
            }
            ScoreError::Truth(problem) => write!(f, "ground truth: {problem}"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ScoreError {}

/// How an output edge set compares with the ground truth; see the [module](self) for each
/// metric.
///
/// ```
/// use condt_eval::score::score;
/// use condt::Point;
/// // A unit square; the output has three of its sides and a diagonal.
/// let points = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// let truth = [[0, 1], [1, 2], [2, 3], [3, 0]];
/// let s = score(&points, &[[0, 1], [1, 2], [2, 3], [0, 2]], &truth).unwrap();
/// assert!(!s.exact);
/// assert_eq!((s.true_positives, s.false_positives, s.false_negatives), (3, 1, 1));
/// assert_eq!(s.f1, 0.75);
/// // The diagonal's midpoint is half a side from the nearest side; the diagonal of the box is √2.
/// assert!((s.max_distance.unwrap() - 0.5 / 2f64.sqrt()).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Score {
    /// The output edge set equals the truth's (never, when the output is malformed).
    pub exact: bool,
    /// Output edges that are truth edges, over output edges (1 when both are empty, 0 when
    /// only the output is); 0 when the output is malformed.
    pub precision: f64,
    /// Truth edges found, over truth edges (1 when the truth has none); 0 when the output is
    /// malformed.
    pub recall: f64,
    /// Harmonic mean of precision and recall (0 when both are 0).
    pub f1: f64,
    /// Output edges that are truth edges.
    pub true_positives: usize,
    /// Output edges that are not.
    pub false_positives: usize,
    /// Truth edges the output lacks.
    pub false_negatives: usize,
    /// Output edges with an end that has no truth edge.
    pub outlier_edges: usize,
    /// Largest sample distance to the truth over the bounding-box diagonal; `None` without
    /// output edges; infinite when the output has edges and the truth none.
    pub max_distance: Option<f64>,
    /// Root mean square of the sample distances, likewise.
    pub rms_distance: Option<f64>,
    /// The output's first problem, if it is not a valid edge list. The counts and distances are
    /// then those of its valid edges, each counted once; precision, recall and F1 are 0.
    pub malformed: Option<EdgeProblem>,
}

/// Scores `output` against `truth`, both edge lists in positions of `points` (either direction,
/// any order).
///
/// Edges are compared by position, as the evaluation suite's scorer compares them: where
/// `points` holds exact duplicates, an edge to one copy is not an edge to another. condt's
/// reconstruction gives a duplicate's edges to its first copy
/// ([`Triangulation::first_at`](condt::Triangulation::first_at)), so a truth written on a later
/// copy (a closed ring exported with its first point again at the end) needs its ends mapped to
/// first copies before it is compared.
///
/// # Errors
/// [`ScoreError::NonFinite`] for a point with a NaN or infinite coordinate;
/// [`ScoreError::Truth`] when the truth has an end out of range, a self-loop or a repeated
/// edge.
///
/// ```
/// use condt_eval::sample::{sample, Sampling, Shape};
/// use condt_eval::score::score;
/// use condt::{reconstruct, Params, Point};
/// let circle = sample(&[Shape::circle(Point::new(0.0, 0.0), 1.0)], &Sampling::new(0.3)).unwrap();
/// let result = reconstruct(&circle.points, &Params::default())?;
/// let edges: Vec<[usize; 2]> = result.edges().collect();
/// let s = score(&circle.points, &edges, &circle.edges).unwrap();
/// assert!(s.exact && s.f1 == 1.0 && s.max_distance == Some(0.0));
/// # Ok::<(), condt::Error>(())
/// ```
pub fn score(
    points: &[Point],
    output: &[[usize; 2]],
    truth: &[[usize; 2]],
) -> Result<Score, ScoreError> {
    score_with::<Index>(points, output, truth)
}

/// The points `truth` names that repeat an earlier point of `points` exactly, each as `[later,
/// first]`, by increasing `later`: [`score`] compares edges by position, and condt's
/// reconstruction gives a duplicate's edges to its first copy, so a truth edge at a later copy
/// is never matched (a ring exported with its first point again at its end scores a false
/// positive and a false negative). For a caller to tell; ends past the points are left out
/// (`score` refuses them). `-0.0` is `0.0`, as for the triangulation. Only the truth's ends are
/// sorted: `O(n log m)` for `m` ends.
///
/// ```
/// use condt::Point;
/// use condt_eval::score::later_copies;
/// let ring = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (1.0, 0.0)].map(Point::from);
/// assert_eq!(later_copies(&ring, &[[0, 1], [1, 2], [2, 3]]), vec![[3, 0]]);
/// ```
pub fn later_copies(points: &[Point], truth: &[[usize; 2]]) -> Vec<[usize; 2]> {
    let key = |p: Point| ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
    let mut ends: Vec<usize> = truth
        .iter()
        .flatten()
        .copied()
        .filter(|&i| i < points.len())
        .collect();
    ends.sort_unstable();
    ends.dedup();
    // Each end's key with the first position holding it, found in one pass over the points.
    let mut firsts: Vec<((u64, u64), usize)> =
        ends.iter().map(|&i| (key(points[i]), usize::MAX)).collect();
    firsts.sort_unstable();
    firsts.dedup();
    for (i, &p) in points.iter().enumerate() {
        if let Ok(at) = firsts.binary_search_by(|(k, _)| k.cmp(&key(p))) {
            firsts[at].1 = firsts[at].1.min(i);
        }
    }
    let first_of = |i: usize| {
        let at = firsts.binary_search_by(|(k, _)| k.cmp(&key(points[i])));
        at.map_or(i, |at| firsts[at].1)
    };
    ends.into_iter()
        .map(|i| [i, first_of(i)])
        .filter(|&[i, first]| first != i)
        .collect()
}

/// The words `condt score` and Python's `condt.score` say of [`later_copies`]' pairs
/// `[i, first]` (at most three named): `None` for none.
///
/// ```
/// use condt_eval::score::later_copies_named;
/// assert_eq!(
///     later_copies_named(&[[3, 0]]).unwrap(),
///     "1 point that repeats an earlier point exactly (3 = 0)"
/// );
/// assert!(later_copies_named(&[]).is_none());
/// ```
pub fn later_copies_named(named: &[[usize; 2]]) -> Option<String> {
    let shown: Vec<String> = named
        .iter()
        .take(3)
        .map(|[i, first]| format!("{i} = {first}"))
        .collect();
    let more = if named.len() > 3 { ", ..." } else { "" };
    let count = match named.len() {
        0 => return None,
        1 => "1 point that repeats".to_string(),
        n => format!("{n} points that repeat"),
    };
    Some(format!(
        "{count} an earlier point exactly ({}{more})",
        shown.join(", ")
    ))
}

/// A nearest-segment search over the truth, on the scaled points.
trait Nearest {
    /// The search over `segments` of `points`, whose coordinates lie in `[0, size]`.
    fn build(points: &[Point], segments: &[[usize; 2]], size: f64) -> Self;
    /// Squared distance from `p` to the nearest segment; infinite without segments.
    fn nearest_squared(&self, p: Point) -> f64;
    /// [`Nearest::nearest_squared`] of each query, found in any order.
    fn nearest_squared_all(&self, queries: &[Point]) -> Vec<f64> {
        queries.iter().map(|&p| self.nearest_squared(p)).collect()
    }
}

impl Nearest for Index {
    fn build(points: &[Point], segments: &[[usize; 2]], size: f64) -> Self {
        Index::new(points, segments, size)
    }
    fn nearest_squared(&self, p: Point) -> f64 {
        Index::nearest_squared(self, p)
    }
    fn nearest_squared_all(&self, queries: &[Point]) -> Vec<f64> {
        Index::nearest_squared_all(self, queries)
    }
}

/// [`score`] with the nearest-segment search `N`.
fn score_with<N: Nearest>(
    points: &[Point],
    output: &[[usize; 2]],
    truth: &[[usize; 2]],
) -> Result<Score, ScoreError> {
    if let Some(index) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(ScoreError::NonFinite { index });
    }
    let (truth, problem) = edge_set(truth, points.len());
    if let Some(problem) = problem {
        return Err(ScoreError::Truth(problem));
    }
    let (output, malformed) = edge_set(output, points.len());

    let true_positives = count_common(&output, &truth);
    let false_positives = output.len() - true_positives;
    let false_negatives = truth.len() - true_positives;
    let precision = match (output.is_empty(), truth.is_empty()) {
        (true, true) => 1.0,
        (true, false) => 0.0,
        _ => true_positives as f64 / output.len() as f64,
    };
    let recall = if truth.is_empty() {
        1.0
    } else {
        true_positives as f64 / truth.len() as f64
    };
    let f1 = if precision + recall > 0.0 {
        2.0 * precision * recall / (precision + recall)
    } else {
        0.0
    };

    let mut has_truth_edge = vec![false; points.len()];
    for &[a, b] in &truth {
        has_truth_edge[a] = true;
        has_truth_edge[b] = true;
    }
    let outlier_edges = output
        .iter()
        .filter(|&&[a, b]| !has_truth_edge[a] || !has_truth_edge[b])
        .count();
    let (max_distance, rms_distance) = distances::<N>(points, &output, &truth, &has_truth_edge);

    let (precision, recall, f1) = if malformed.is_some() {
        (0.0, 0.0, 0.0)
    } else {
        (precision, recall, f1)
    };
    Ok(Score {
        exact: malformed.is_none() && output == truth,
        precision,
        recall,
        f1,
        true_positives,
        false_positives,
        false_negatives,
        outlier_edges,
        max_distance,
        rms_distance,
        malformed,
    })
}

/// The valid edges of `list`, smaller end first, sorted and each once, and the first problem
/// (by position) if there is one.
fn edge_set(list: &[[usize; 2]], num_points: usize) -> (Vec<[usize; 2]>, Option<EdgeProblem>) {
    let mut problem: Option<EdgeProblem> = None;
    let mut note = |found: EdgeProblem| {
        if problem.is_none_or(|p| found.position() < p.position()) {
            problem = Some(found);
        }
    };
    let mut keyed: Vec<([usize; 2], usize)> = Vec::with_capacity(list.len());
    for (position, &[a, b]) in list.iter().enumerate() {
        if let Some(&index) = [a, b].iter().find(|&&i| i >= num_points) {
            note(EdgeProblem::OutOfRange { position, index });
        } else if a == b {
            note(EdgeProblem::SelfLoop { position, index: a });
        } else {
            keyed.push(([a.min(b), a.max(b)], position));
        }
    }
    keyed.sort_unstable();
    let mut edges: Vec<[usize; 2]> = Vec::with_capacity(keyed.len());
    for (edge, position) in keyed {
        if edges.last() == Some(&edge) {
            note(EdgeProblem::Repeated { position, edge });
        } else {
            edges.push(edge);
        }
    }
    (edges, problem)
}

/// Number of edges in both sorted lists.
fn count_common(a: &[[usize; 2]], b: &[[usize; 2]]) -> usize {
    let (mut i, mut j, mut common) = (0, 0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            core::cmp::Ordering::Less => i += 1,
            core::cmp::Ordering::Greater => j += 1,
            core::cmp::Ordering::Equal => {
                common += 1;
                i += 1;
                j += 1;
            }
        }
    }
    common
}

/// Maximum and RMS sample distance of `output` to `truth` (both sorted edge sets), over the
/// bounding-box diagonal of `points`.
fn distances<N: Nearest>(
    points: &[Point],
    output: &[[usize; 2]],
    truth: &[[usize; 2]],
    has_truth_edge: &[bool],
) -> (Option<f64>, Option<f64>) {
    if output.is_empty() {
        return (None, None);
    }
    // First scaled by the power of two that brings the largest coordinate into [1, 2), as the
    // stages scale their input: exact, and it changes no ratio, so the distances (ratios to the
    // diagonal) are the same at every power-of-two scale. Unscaled, the squares overflow beyond
    // about 1e154 and vanish below about 1e-162, and the box of ±f64::MAX is infinite.
    let largest = points
        .iter()
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(0.0f64, f64::max);
    let scale = if largest > 0.0 {
        Scale::power_of_two(-binary_exponent(largest))
    } else {
        Scale::IDENTITY
    };
    let mut local: Vec<Point> = points.iter().map(|&p| scale.apply(p)).collect();
    let max = to_corner(&mut local);
    let diagonal = match libm::hypot(max.x, max.y) {
        d if d > 0.0 => d,
        _ => 1.0,
    };
    let segments = N::build(&local, truth, max.x.max(max.y));
    // The samples that need a search, in order: the search answers them all at once, in an
    // order of its own, and the distances are summed in this order.
    let on_truth = |a: usize, b: usize, t: f64| {
        (t == 0.0 && has_truth_edge[a]) || (t == 1.0 && has_truth_edge[b])
    };
    let mut queries = Vec::new();
    for &[a, b] in output {
        if truth.binary_search(&[a, b]).is_ok() {
            continue; // five zeros
        }
        let (p, q) = (local[a], local[b]);
        for t in SAMPLES.into_iter().filter(|&t| !on_truth(a, b, t)) {
            queries.push(Point::new(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)));
        }
    }
    let mut nearest = segments.nearest_squared_all(&queries).into_iter();
    let (mut largest, mut sum_of_squares) = (0.0f64, 0.0f64);
    for &[a, b] in output {
        if truth.binary_search(&[a, b]).is_ok() {
            continue; // five zeros
        }
        for t in SAMPLES {
            let d = if on_truth(a, b, t) {
                0.0
            } else {
                let squared = nearest
                    .next()
                    .expect("a distance for each sample off the truth");
                libm::sqrt(squared) / diagonal
            };
            largest = largest.max(d);
            sum_of_squares += d * d;
        }
    }
    let samples = (SAMPLES.len() * output.len()) as f64;
    (Some(largest), Some(libm::sqrt(sum_of_squares / samples)))
}

/// Squared distance from `p` to the segment `a`–`b`.
/// Moves `points` so that their box's lower left corner is the origin, and returns the box's
/// upper right corner. Reason: offsets of 1e6 then cost no precision in the differences the
/// distances are made of.
fn to_corner(points: &mut [Point]) -> Point {
    let min = points
        .iter()
        .fold(Point::new(f64::INFINITY, f64::INFINITY), |m, p| {
            Point::new(m.x.min(p.x), m.y.min(p.y))
        });
    let mut max = Point::new(0.0, 0.0);
    for p in points {
        *p = Point::new(p.x - min.x, p.y - min.y);
        max = Point::new(max.x.max(p.x), max.y.max(p.y));
    }
    max
}

fn segment_distance_squared(p: Point, a: Point, b: Point) -> f64 {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let (wx, wy) = (p.x - a.x, p.y - a.y);
    let length_squared = dx * dx + dy * dy;
    let t = if length_squared > 0.0 {
        ((wx * dx + wy * dy) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (wx - t * dx, wy - t * dy);
    ex * ex + ey * ey
}

/// Relative slack of every pruning test, far above the rounding of the distances (a few units
/// in the last place of coordinates below 4).
const RELATIVE_SLACK: f64 = 1e-9;

/// The squared distance beyond which a lower bound computed in floating point proves that a
/// segment's rounded [`segment_distance_squared`] is not below `best`: `best`'s root widened by
/// [`RELATIVE_SLACK`] and by `margin`, an absolute slack of `RELATIVE_SLACK` times the size of the
/// box the coordinates lie in (plus 1e-150, which covers the underflow of squares), squared.
///
/// The rounded distance of a segment whose exact distance is `D` is at least `(D - e)^2` up to a
/// relative `2^-51`, where `e`, a few units in the last place of the box's size, is much less
/// than `margin`; so a segment whose exact distance exceeds `widened`'s root has a rounded
/// distance above `best`, and skipping it cannot change the minimum.
fn widened(best: f64, margin: f64) -> f64 {
    let reach = libm::sqrt(best) * (1.0 + RELATIVE_SLACK) + margin;
    reach * reach * (1.0 + RELATIVE_SLACK)
}

/// The nearest-segment search of the distances: short segments in a [`SegmentTree`], whose
/// boxes are small, long ones in [`LongSegments`] and [`LongStrips`], where boxes would overlap
/// everywhere (a chain through random points in a random order made every query visit most of
/// the tree). Every part skips only what is provably not nearer (see [`widened`]), so the answer
/// is the minimum of [`segment_distance_squared`] over all segments, whatever the split.
struct Index {
    short: SegmentTree,
    long: LongSegments,
    strips: LongStrips,
    margin: f64,
    /// Whether [`LongStrips`] searches on rayon's threads.
    parallel: bool,
}

impl Index {
    /// The index over `segments` of `points`, whose coordinates lie in `[0, size]`.
    fn new(points: &[Point], segments: &[[usize; 2]], size: f64) -> Index {
        // Segments longer than this go to the long search: a uniform set of segments of this
        // length puts about 64 boxes over each point.
        let threshold = 8.0 * size / libm::sqrt(segments.len().max(1) as f64);
        let (mut short, mut long) = (Vec::new(), Vec::new());
        for &[a, b] in segments {
            let (p, q) = (points[a], points[b]);
            if libm::hypot(q.x - p.x, q.y - p.y) > threshold {
                long.push([p, q]);
            } else {
                short.push([p, q]);
            }
        }
        Index {
            short: SegmentTree::from_ends(short),
            strips: LongStrips::new(&long, size),
            long: LongSegments::new(long, Point::new(size / 2.0, size / 2.0)),
            margin: RELATIVE_SLACK * size + 1e-150,
            parallel: cfg!(feature = "parallel"),
        }
    }

    /// Squared distance from `p` to the nearest segment; infinite without segments.
    fn nearest_squared(&self, p: Point) -> f64 {
        let best = self
            .short
            .nearest_squared(p, f64::INFINITY, Some(self.margin));
        self.long.nearest_squared(p, best, self.margin)
    }

    /// [`Index::nearest_squared`] of every query, found in an order of the index's choosing.
    fn nearest_squared_all(&self, queries: &[Point]) -> Vec<f64> {
        let short = |&p: &Point| {
            self.short
                .nearest_squared(p, f64::INFINITY, Some(self.margin))
        };
        #[cfg(feature = "parallel")]
        let mut best: Vec<f64> = if self.parallel {
            use rayon::prelude::*;
            queries.par_iter().map(short).collect()
        } else {
            queries.iter().map(short).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let mut best: Vec<f64> = queries.iter().map(short).collect();
        self.strips
            .nearest_squared_all(queries, &mut best, &self.long, self.margin, self.parallel);
        best
    }
}

/// The most direction classes of [`Classes`].
const MAX_CLASSES: usize = 1024;

/// The direction of the segment `a`–`b` as the classes of [`Classes`] sort it: the angle of its
/// line in `[0, pi]` as a fraction of `pi`, and the unit normal of that direction. A segment of
/// length zero is given the direction of the x axis: its distance to a point is at least the
/// distance to any line through it.
fn direction(a: Point, b: Point) -> (f64, Point) {
    let pi = core::f64::consts::PI;
    let (mut dx, mut dy) = (b.x - a.x, b.y - a.y);
    let length = libm::hypot(dx, dy);
    if length == 0.0 {
        return (0.0, Point::new(0.0, 1.0));
    }
    let mut angle = libm::atan2(dy, dx);
    if angle < 0.0 {
        angle += pi;
        (dx, dy) = (-dx, -dy);
    }
    (angle / pi, Point::new(-dy / length, dx / length))
}

/// The class of a segment whose direction is `turn` (see [`direction`]), of `classes`.
fn class_of(turn: f64, classes: usize) -> usize {
    ((turn * classes as f64) as usize).min(classes - 1)
}

/// Unit normals of the middle directions of `classes` classes of equal angle, and a bound on
/// the distance between a segment's unit normal and its class's: half a class's angle (a chord
/// is shorter than its arc), widened for the rounding of the angles, of the normals and of the
/// class boundaries.
fn class_normals(classes: usize, normals: &mut Vec<Point>) -> f64 {
    let pi = core::f64::consts::PI;
    normals.clear();
    normals.extend((0..classes).map(|c| {
        let middle = (c as f64 + 0.5) / classes as f64 * pi;
        Point::new(-libm::sin(middle), libm::cos(middle))
    }));
    pi / (2 * classes) as f64 * (1.0 + RELATIVE_SLACK) + 1e-12
}

/// Long segments by direction around a centre: classes of equal angle, and in each the
/// segments sorted by the signed distance of their line from the centre (their key). A query's
/// distance to a segment is at least its distance to the segment's line, and within a class
/// that is, up to the class's angle times the query's distance from the centre, the difference
/// between the query's offset along the class's normal and the segment's key: each class is
/// searched from the query's offset outwards until that bound exceeds the best distance found.
#[derive(Copy, Clone)]
struct Classes<'a> {
    centre: Point,
    /// Bound on the distance between a segment's unit normal and its class's.
    width: f64,
    /// Unit normal of each class's middle direction.
    normals: &'a [Point],
    /// Class `c` holds `keys[starts[c]..starts[c + 1]]`, ascending, and `ends` alike.
    starts: &'a [usize],
    keys: &'a [f64],
    ends: &'a [[Point; 2]],
}

impl Classes<'_> {
    /// Squared distance from `p` to the nearest segment, or `best` if none is nearer.
    /// `scratch` is any buffer, to save an allocation per query.
    fn nearest_squared(
        &self,
        p: Point,
        mut best: f64,
        margin: f64,
        scratch: &mut Vec<(f64, usize, f64)>,
    ) -> f64 {
        let classes = self.normals.len();
        if self.starts[0] == self.starts[classes] {
            return best;
        }
        let (vx, vy) = (p.x - self.centre.x, p.y - self.centre.y);
        // A segment's normal is the class's turned by at most `width`, so the offset of `p`
        // along it differs from the offset along the class's, `u`, by at most `width` times
        // the component of `p` along the class's direction, `t`, plus `width^2 / 2` times `u`
        // (and the rounding of the normals): how far its line may be nearer than its key says.
        let (w, w2) = (self.width, self.width * self.width / 2.0);
        let slack = |u: f64, t: f64| {
            let (u, t) = (u.abs(), t.abs());
            (w * t + w2 * u + 1e-12 * (u + t)) * (1.0 + RELATIVE_SLACK) + margin
        };
        let reach = |best: f64| libm::sqrt(widened(best, margin));
        // First the segment nearest by key in each class, for a good `best` to prune with.
        scratch.clear();
        for (c, n) in self.normals.iter().enumerate() {
            let (first, end) = (self.starts[c], self.starts[c + 1]);
            let (u, t) = (n.x * vx + n.y * vy, n.y * vx - n.x * vy);
            let offset = -u;
            let position = first + self.keys[first..end].partition_point(|&k| k < offset);
            scratch.push((offset, position, slack(u, t)));
            let nearer_below = position > first
                && (position == end
                    || offset - self.keys[position - 1] < self.keys[position] - offset);
            let i = if nearer_below { position - 1 } else { position };
            if i < end {
                let [a, b] = self.ends[i];
                best = best.min(segment_distance_squared(p, a, b));
            }
        }
        let mut nearest = (best, reach(best));
        for (c, &(offset, position, slack)) in scratch.iter().enumerate() {
            let (first, end) = (self.starts[c], self.starts[c + 1]);
            let keyed =
                |from: usize, to: usize| self.keys[from..to].iter().zip(&self.ends[from..to]);
            let above = keyed(position, end).map(|(&key, ends)| (key - offset, ends));
            walk_away(p, above, slack, &mut nearest, &reach);
            let below = keyed(first, position)
                .rev()
                .map(|(&key, ends)| (offset - key, ends));
            walk_away(p, below, slack, &mut nearest, &reach);
        }
        nearest.0
    }
}

/// Walks `run`, segments ordered by their key's distance from the query's (`gap`), until a gap
/// exceeds the reach of the nearest so far plus `slack`; `nearest` is the squared distance and
/// its reach, updated.
fn walk_away<'a>(
    p: Point,
    run: impl Iterator<Item = (f64, &'a [Point; 2])>,
    slack: f64,
    nearest: &mut (f64, f64),
    reach: &impl Fn(f64) -> f64,
) {
    for (gap, &[a, b]) in run {
        if gap > nearest.1 + slack {
            break;
        }
        let d = segment_distance_squared(p, a, b);
        if d < nearest.0 {
            *nearest = (d, reach(d));
        }
    }
}

/// All the long segments in [`Classes`] around one centre, `n^(1/3)` classes for `n` segments:
/// the search of a single query, and of the queries [`LongStrips`] leaves.
struct LongSegments {
    centre: Point,
    width: f64,
    normals: Vec<Point>,
    starts: Vec<usize>,
    keys: Vec<f64>,
    ends: Vec<[Point; 2]>,
}

impl LongSegments {
    /// The search over `segments`.
    fn new(segments: Vec<[Point; 2]>, centre: Point) -> LongSegments {
        let classes = (libm::cbrt(segments.len() as f64) as usize).clamp(1, MAX_CLASSES);
        let mut normals = Vec::new();
        let width = class_normals(classes, &mut normals);
        let mut entries: Vec<(usize, f64, [Point; 2])> = segments
            .into_iter()
            .map(|[a, b]| {
                let (turn, normal) = direction(a, b);
                let key = normal.x * (centre.x - a.x) + normal.y * (centre.y - a.y);
                (class_of(turn, classes), key, [a, b])
            })
            .collect();
        entries.sort_unstable_by(|s, t| s.0.cmp(&t.0).then(s.1.total_cmp(&t.1)));
        let mut starts = vec![0; classes + 1];
        for &(class, _, _) in &entries {
            starts[class + 1] += 1;
        }
        for c in 0..classes {
            starts[c + 1] += starts[c];
        }
        LongSegments {
            centre,
            width,
            normals,
            starts,
            keys: entries.iter().map(|e| e.1).collect(),
            ends: entries.iter().map(|e| e.2).collect(),
        }
    }

    fn classes(&self) -> Classes<'_> {
        Classes {
            centre: self.centre,
            width: self.width,
            normals: &self.normals,
            starts: &self.starts,
            keys: &self.keys,
            ends: &self.ends,
        }
    }

    /// Squared distance from `p` to the nearest long segment, or `best` if none is nearer.
    fn nearest_squared(&self, p: Point, best: f64, margin: f64) -> f64 {
        let mut scratch = Vec::with_capacity(self.normals.len());
        self.classes()
            .nearest_squared(p, best, margin, &mut scratch)
    }
}

/// Strips of [`Strips`] per cube root of the number of long segments, slope classes per square
/// root of the segments a query would otherwise look at, and entries per bucket of a class:
/// measured on the chain through random points at 100k, 1M and 2M edges.
const STRIPS_PER_CUBE_ROOT: f64 = 2.5;
const CLASSES_PER_SQUARE_ROOT: f64 = 1.0;
const ENTRIES_PER_BUCKET: f64 = 1.0;

/// The fewest entries a window of [`Strips`] looks at.
const SCANNED: usize = 4;

/// The first reach of a query's windows in [`Strips`], in mean spacings of a strip's lines.
const GUESS_PER_SPACING: f64 = 4.0;

/// The most strips of [`Strips`], and the most buckets of one of its classes.
const MAX_STRIPS: usize = 4096;
const MAX_BUCKETS: usize = 1 << 16;

/// How far beyond its strip a strip's segments reach at least, in strip heights.
const REACH_PER_STRIP: f64 = 1.0 / 16.0;

/// Bins of the queries along a strip: a strip's queries are answered bin by bin, so that the
/// windows they look at in each class move along the class's entries.
const QUERY_BINS: usize = 256;

/// The long segments in two [`Strips`]: the steep ones (`|dy| >= |dx|`) in horizontal strips,
/// the others in vertical ones (the same search with `x` and `y` exchanged).
///
/// Why: [`LongSegments`] alone prunes by the class's angle times the query's distance from its
/// centre, so on `n` segments through random points a query looks at `n^(2/3)` of them. In a
/// strip of height `h` that distance is at most `h / 2` across the strip: a strip holds about
/// `m = n / 3` pieces of segments, of which a query with `k` classes of slope looks at about
/// `k + m h / k`, `sqrt(m h)` at best; the strips hold `n / h` pieces in all. `h ~ n^(-1/3)`
/// balances the two, for `n^(4/3)` in all. No algorithm is known that does better on `n` lines
/// and `n` points: distance zero would decide Hopcroft's problem (does a point lie on a line),
/// whose best known bound is `n^(4/3)`. On random input the constant is what can be won, and the
/// strips keep it small (about 4 times below cells of [`Classes`] around their centres, each with
/// a sorted list per class, on one thread): each segment is stored once per strip it crosses, not once per cell;
/// a class is rebuilt from the last strip's (nearly in order) by counting into buckets of its
/// key, with no sort, and a window is found in the buckets, with no binary search; a class is
/// searched by all the strip's queries while it is in the cache; and an entry is tested by the
/// offset of its line before its ends are read.
///
/// A query whose best distance might be beaten by a segment that misses its strip's margin (near
/// an empty part of the box) is finished by [`LongSegments`], so the answer is exact whatever the
/// layout.
struct LongStrips {
    steep: Strips,
    flat: Strips,
}

impl LongStrips {
    /// The strips over `segments`, whose coordinates lie in `[0, size]`.
    fn new(segments: &[[Point; 2]], size: f64) -> LongStrips {
        let (steep, flat): (Vec<[Point; 2]>, Vec<[Point; 2]>) = segments
            .iter()
            .partition(|[a, b]| (b.y - a.y).abs() >= (b.x - a.x).abs());
        let count = ((libm::cbrt(segments.len() as f64) * STRIPS_PER_CUBE_ROOT) as usize)
            .clamp(1, MAX_STRIPS);
        LongStrips {
            steep: Strips::new(&steep, size, count, false),
            flat: Strips::new(&flat, size, count, true),
        }
    }

    /// Lowers each `best[i]` to the squared distance from `queries[i]` to the nearest segment
    /// if one is nearer, finishing with `all` (the same segments) where the strips cannot tell;
    /// on rayon's threads with `parallel`, with the same answers.
    fn nearest_squared_all(
        &self,
        queries: &[Point],
        best: &mut [f64],
        all: &LongSegments,
        margin: f64,
        parallel: bool,
    ) {
        let mut unsure = vec![false; queries.len()];
        self.steep
            .search(queries, best, &mut unsure, margin, parallel);
        self.flat
            .search(queries, best, &mut unsure, margin, parallel);
        let finish = |((&p, d), &unsure): ((&Point, &mut f64), &bool)| {
            if unsure {
                *d = all.nearest_squared(p, *d, margin);
            }
        };
        #[cfg(feature = "parallel")]
        if parallel {
            use rayon::prelude::*;
            let queries = queries.par_iter().zip(best.par_iter_mut());
            queries.zip(unsure.par_iter()).for_each(finish);
            return;
        }
        let queries = queries.iter().zip(best.iter_mut());
        queries.zip(&unsure).for_each(finish);
    }
}

/// Segments whose direction is nearer the `y` axis than the `x` axis (in their frame: given, or
/// with `x` and `y` exchanged), in horizontal strips: in each strip, classes of equal range of
/// slope `dx / dy`, and in each class the segments by the `x` of their line at the strip's
/// middle (their key), in buckets of equal width. A query's distance to a segment is at least
/// the horizontal offset of the segment's line over `sqrt(1 + slope^2)` (at most `sqrt(2)`), and
/// within a class that offset
/// is, up to the class's range of slope times the query's height over the middle, the
/// difference between the query's `x` moved along the class's middle slope and the key: each
/// class is searched in the buckets of that window.
struct Strips {
    transposed: bool,
    count: usize,
    height: f64,
    /// How far beyond its strip a strip's segments reach at least.
    reach: f64,
    classes: usize,
    /// Bound on the difference between a segment's slope and its class's middle slope.
    width: f64,
    /// Buckets of a class, and the inverse of their width (the first starts at 0).
    buckets: usize,
    inverse: f64,
    /// The last bucket, as a float.
    last: f64,
    /// The reach of a line's offset a query's windows are first searched with: a few times the
    /// mean offset of the nearest line.
    guess: f64,
    /// The segments by first strip.
    segments: Vec<Slanted>,
}

/// The entries of a strip of [`Strips`]: the key (the `x` of its line at the strip's middle, in
/// the frame) and slope of each, its ends and its last strip.
#[derive(Default)]
struct Table {
    keys: Vec<[f64; 2]>,
    ends: Vec<[Point; 2]>,
    lasts: Vec<u32>,
}

impl Table {
    fn clear(&mut self) {
        self.keys.clear();
        self.ends.clear();
        self.lasts.clear();
    }

    fn resize(&mut self, len: usize) {
        self.keys.resize(len, [0.0; 2]);
        self.ends.resize(len, [Point::new(0.0, 0.0); 2]);
        self.lasts.resize(len, 0);
    }
}

/// A segment of [`Strips`], as it moves from strip to strip.
#[derive(Copy, Clone)]
struct Slanted {
    /// `dx / dy` in the frame, in `[-1, 1]` (0 for a segment of length zero).
    slope: f64,
    /// The ends as given, for the distance.
    ends: [Point; 2],
    class: u32,
    /// First and last strips it is in.
    strips: [u32; 2],
}

impl Strips {
    /// The steep `segments` (in the frame), whose coordinates lie in `[0, size]`, in `count`
    /// strips.
    fn new(segments: &[[Point; 2]], size: f64, count: usize, transposed: bool) -> Strips {
        // Entries are counted in `u32`: 2^32 segments would take 64 GiB of ends.
        assert!(segments.len() < u32::MAX as usize, "too many segments");
        let size = if size > 0.0 { size } else { 1.0 };
        let height = size / count as f64;
        let mut strips = Strips {
            transposed,
            count,
            height,
            reach: height * REACH_PER_STRIP,
            classes: 1,
            width: 0.0,
            buckets: 1,
            inverse: 0.0,
            last: 0.0,
            guess: 0.0,
            segments: Vec::with_capacity(segments.len()),
        };
        let mut pieces = 0;
        for &ends in segments {
            let [a, b] = ends.map(|p| strips.frame(p));
            let dy = b.y - a.y;
            let slope = if dy == 0.0 { 0.0 } else { (b.x - a.x) / dy };
            let reach = 2.0 * strips.reach;
            let (first, last) = (
                strips.strip_of(a.y.min(b.y) - reach),
                strips.strip_of(a.y.max(b.y) + reach),
            );
            pieces += last - first + 1;
            strips.segments.push(Slanted {
                slope,
                ends,
                class: 0,
                strips: [first as u32, last as u32],
            });
        }
        // A query looks at `k` windows, with `m h / (2 k)` entries in all on average: `m` the
        // pieces in a strip, spread over `size`, and a window of `2 |dy| / k` at a height `dy`
        // of `h / 4` on average.
        let per_strip = pieces as f64 / count as f64;
        let examined = per_strip * height / (2.0 * size);
        strips.classes =
            ((libm::sqrt(examined) * CLASSES_PER_SQUARE_ROOT) as usize).clamp(1, MAX_CLASSES);
        let k = strips.classes;
        strips.width = (1.0 + RELATIVE_SLACK) / k as f64 + 1e-12;
        for s in &mut strips.segments {
            s.class = class_of((s.slope + 1.0) / 2.0, k) as u32;
        }
        strips.segments.sort_by_key(|s| s.strips[0]);
        let per_class = (per_strip / k as f64).max(1.0);
        strips.buckets = ((per_class / ENTRIES_PER_BUCKET) as usize).clamp(1, MAX_BUCKETS);
        strips.inverse = strips.buckets as f64 / size;
        strips.last = (strips.buckets - 1) as f64;
        strips.guess = GUESS_PER_SPACING * size / per_strip.max(1.0);
        strips
    }

    /// `p` in the frame of the strips.
    fn frame(&self, p: Point) -> Point {
        if self.transposed {
            Point::new(p.y, p.x)
        } else {
            p
        }
    }

    /// The strip of the coordinate `v`, clamped to the strips.
    fn strip_of(&self, v: f64) -> usize {
        ((v / self.height).max(0.0) as usize).min(self.count - 1)
    }

    /// The bucket of the key `x`, clamped to the buckets: non-decreasing in `x`.
    fn bucket(&self, x: f64) -> usize {
        // Clamped as a float, the conversion needs no saturation of its own.
        (x * self.inverse).max(0.0).min(self.last) as usize
    }

    /// Middle slope of class `c`.
    fn middle(&self, c: usize) -> f64 {
        (2 * c + 1) as f64 / self.classes as f64 - 1.0
    }

    /// Lowers `best` as [`LongStrips::nearest_squared_all`] does, over these segments, and marks
    /// as `unsure` the queries a segment outside the strips might be nearer to.
    fn search(
        &self,
        queries: &[Point],
        best: &mut [f64],
        unsure: &mut [bool],
        margin: f64,
        parallel: bool,
    ) {
        if self.segments.is_empty() {
            return;
        }
        // The queries by strip, and in a strip by bin along it.
        let bins = QUERY_BINS;
        let key = |p: Point| {
            let p = self.frame(p);
            let bin = ((p.x * self.inverse / self.buckets as f64 * bins as f64).max(0.0) as usize)
                .min(bins - 1);
            self.strip_of(p.y) * bins + bin
        };
        let mut starts = vec![0usize; self.count * bins + 1];
        for &p in queries {
            starts[key(p) + 1] += 1;
        }
        for i in 0..self.count * bins {
            starts[i + 1] += starts[i];
        }
        let mut order = vec![0usize; queries.len()];
        {
            let mut next = starts.clone();
            for (i, &p) in queries.iter().enumerate() {
                let slot = &mut next[key(p)];
                order[*slot] = i;
                *slot += 1;
            }
        }
        let sorted: Vec<Point> = order.iter().map(|&i| queries[i]).collect();
        let mut found: Vec<(f64, bool)> = order.iter().map(|&i| (best[i], false)).collect();
        let row_starts: Vec<usize> = (0..=self.count).map(|r| starts[r * bins]).collect();
        // Runs of strips with about the same number of queries, each searched on its own.
        let runs = if parallel { 16 } else { 1 };
        let mut pieces = Vec::with_capacity(runs);
        let mut rest: &mut [(f64, bool)] = &mut found;
        let mut first = 0;
        for run in 1..=runs {
            let target = queries.len() * run / runs;
            let mut last = first;
            while last < self.count && (row_starts[last] < target || run == runs) {
                last += 1;
            }
            let (piece, tail) = rest.split_at_mut(row_starts[last] - row_starts[first]);
            pieces.push((first..last, piece));
            rest = tail;
            first = last;
        }
        let search = |(rows, found): (core::ops::Range<usize>, &mut [(f64, bool)])| {
            let from = row_starts[rows.start];
            self.search_rows(
                rows,
                &row_starts,
                &sorted[from..from + found.len()],
                found,
                margin,
            );
        };
        #[cfg(feature = "parallel")]
        if parallel {
            use rayon::prelude::*;
            pieces.into_par_iter().for_each(search);
        } else {
            pieces.into_iter().for_each(search);
        }
        #[cfg(not(feature = "parallel"))]
        pieces.into_iter().for_each(search);
        for (&i, &(d, u)) in order.iter().zip(&found) {
            best[i] = d;
            unsure[i] |= u;
        }
    }

    /// [`Strips::search`] of the strips `rows`, whose queries (`queries[row_starts[r] - from..]`
    /// for `from = row_starts[rows.start]`) have the best distances and marks `found`.
    fn search_rows(
        &self,
        rows: core::ops::Range<usize>,
        row_starts: &[usize],
        queries: &[Point],
        found: &mut [(f64, bool)],
        margin: f64,
    ) {
        let (k, nb) = (self.classes, self.buckets);
        let from = row_starts[rows.start];
        // The entries of the current strip, class by class and in a class bucket by bucket:
        // class `c`'s bucket `b` is entries `starts[c * nb + b]..starts[c * nb + b + 1]` of
        // `table` (whose keys are apart from the rest, for the queries to read them alone).
        let (mut table, mut next) = (Table::default(), Table::default());
        let (mut starts, mut next_starts) = (vec![0u32; k * nb + 1], vec![0u32; k * nb + 1]);
        let mut counts = vec![0u32; nb + 1];
        let mut incoming: Vec<Slanted> = Vec::new();
        let mut added = 0;
        let mut pending: Vec<Pending> = Vec::new();
        let mut placed: Vec<(u32, f64)> = Vec::new();
        for r in rows {
            if row_starts[r] == row_starts[r + 1] {
                continue; // the segments that entered meanwhile enter at the next strip built
            }
            // The segments that enter, by class.
            incoming.clear();
            while added < self.segments.len() && self.segments[added].strips[0] as usize <= r {
                if self.segments[added].strips[1] as usize >= r {
                    incoming.push(self.segments[added]);
                }
                added += 1;
            }
            incoming.sort_unstable_by_key(|s| s.class);
            let y = (r as f64 + 0.5) * self.height;
            let (y0, y1) = (r as f64 * self.height, (r + 1) as f64 * self.height);
            let span = row_starts[r] - from..row_starts[r + 1] - from;
            pending.clear();
            pending.extend(queries[span.clone()].iter().zip(&found[span.clone()]).map(
                |(&q, &(best, _))| {
                    let p = self.frame(q);
                    let mut query = Pending {
                        p,
                        dy: p.y - y,
                        best,
                        limit: 0.0,
                        within: 0.0,
                    };
                    query.lower(best, margin);
                    query
                },
            ));
            // How far a segment outside the strip is at least, and `within` for a best distance
            // that far.
            let beyond = |query: &Pending| self.reach + (query.p.y - y0).min(y1 - query.p.y);
            let cap = |query: &Pending| {
                core::f64::consts::SQRT_2
                    * beyond(query)
                    * (1.0 + RELATIVE_SLACK)
                    * (1.0 + RELATIVE_SLACK)
                    + margin
            };
            // Class by class: the class is rebuilt from the last strip's entries of the class
            // (nearly in order already), keyed at this strip's middle, and searched by the
            // strip's queries while it is in the cache, each in the window of its best
            // distance's reach up to `guess`; ...
            next.clear();
            let mut entering = 0;
            for c in 0..k {
                let old = starts[c * nb] as usize..starts[(c + 1) * nb] as usize;
                let new_from = entering;
                while entering < incoming.len() && incoming[entering].class as usize == c {
                    entering += 1;
                }
                let new = &incoming[new_from..entering];
                let live = || {
                    old.clone()
                        .map(|i| (table.keys[i][1], table.ends[i], table.lasts[i]))
                        .chain(new.iter().map(|s| (s.slope, s.ends, s.strips[1])))
                        .filter(|&(_, _, last)| last as usize >= r)
                };
                // Counted into buckets of the key, then placed.
                placed.clear();
                counts.iter_mut().for_each(|n| *n = 0);
                for (slope, ends, _) in live() {
                    let a = self.frame(ends[0]);
                    let key = a.x + (y - a.y) * slope;
                    let b = self.bucket(key);
                    counts[b + 1] += 1;
                    placed.push((b as u32, key));
                }
                let base = next.keys.len();
                for b in 0..nb {
                    counts[b + 1] += counts[b];
                    next_starts[c * nb + b] = (base + counts[b] as usize) as u32;
                }
                next.resize(base + counts[nb] as usize);
                for ((slope, ends, last), &(b, key)) in live().zip(&placed) {
                    let i = base + counts[b as usize] as usize;
                    (next.keys[i], next.ends[i], next.lasts[i]) = ([key, slope], ends, last);
                    counts[b as usize] += 1;
                }
                next_starts[(c + 1) * nb] = next.keys.len() as u32;
                let class = Class {
                    strips: self,
                    middle: self.middle(c),
                    starts: &next_starts[c * nb..=(c + 1) * nb],
                    table: &next,
                };
                for query in &mut pending {
                    class.look(query, query.within.min(self.guess), margin);
                }
            }
            core::mem::swap(&mut table, &mut next);
            core::mem::swap(&mut starts, &mut next_starts);
            // ... then, for the queries whose best distance reaches farther, again with all of
            // it, as far as a segment outside the strip might be nearer (a query far from every
            // segment of a sparse strip is left unsure).
            for c in 0..k {
                let class = Class {
                    strips: self,
                    middle: self.middle(c),
                    starts: &starts[c * nb..=(c + 1) * nb],
                    table: &table,
                };
                for query in pending.iter_mut().filter(|q| q.within > self.guess) {
                    class.look(query, query.within.min(cap(query)), margin);
                }
            }
            for (query, found) in pending.iter().zip(&mut found[span]) {
                let unsure = libm::sqrt(widened(query.best, margin)) + margin > beyond(query)
                    || query.within > cap(query);
                *found = (query.best, unsure);
            }
        }
    }
}

/// One class of a strip of [`Strips`].
struct Class<'a> {
    strips: &'a Strips,
    middle: f64,
    /// Bucket `b` is entries `starts[b]..starts[b + 1]` of `table`.
    starts: &'a [u32],
    table: &'a Table,
}

impl Class<'_> {
    /// Lowers `query.best` to the distance of every segment of the class whose key is within
    /// the query's window of the class widened by `reach` (none if negative, as it is for a
    /// query outside the strip), if that is nearer.
    fn look(&self, query: &mut Pending, reach: f64, margin: f64) {
        let reach = reach.max(0.0);
        let target = query.p.x - self.middle * query.dy;
        // The class's slopes move the key by up to this much over the query's height.
        let spread = self.strips.width * query.dy.abs() * (1.0 + RELATIVE_SLACK) + margin;
        let bucket = |x: f64| self.strips.bucket(x);
        let lo = bucket(target - spread - reach);
        let hi = bucket(target + spread + reach);
        // At least `SCANNED` entries, so that the loop runs the same number of times for most
        // windows (the branch predicted): the ones after the window are segments too.
        let (first, end) = (self.starts[lo] as usize, self.starts[hi + 1] as usize);
        let range = first..end.max((first + SCANNED).min(self.table.keys.len()));
        let keys = self.table.keys[range.clone()].iter();
        for (&[key, slope], i) in keys.zip(range) {
            let offset = query.p.x - (key + slope * query.dy);
            if offset * offset <= query.limit * (1.0 + slope * slope) {
                let [a, b] = self.table.ends[i];
                let d = segment_distance_squared(self.strips.frame(query.p), a, b);
                if d < query.best {
                    query.lower(d, margin);
                }
            }
        }
    }
}

/// A query of [`Strips::search_rows`] in its strip, with what its windows need and no more
/// (every class reads them all).
struct Pending {
    /// The query in the frame.
    p: Point,
    /// Its height over the strip's middle.
    dy: f64,
    best: f64,
    /// The square of the distance beyond which a line's segment is not nearer than `best`
    /// whatever the rounding: a segment whose line's offset (see [`Strips`]) has a square above
    /// `limit * (1 + slope^2)` is skipped.
    limit: f64,
    /// Bound on the offset of a line that is not skipped.
    within: f64,
}

impl Pending {
    /// Sets the best distance.
    fn lower(&mut self, best: f64, margin: f64) {
        // The rounded distance of a segment farther than `widened`'s root from the query is
        // above `best`, and a segment is at least as far as its line, up to the rounding of
        // the line (a few units in the last place of the box's size, much less than `margin`).
        let reach = libm::sqrt(widened(best, margin)) * (1.0 + RELATIVE_SLACK) + margin;
        self.best = best;
        self.limit = reach * reach;
        self.within = core::f64::consts::SQRT_2 * reach * (1.0 + RELATIVE_SLACK) + margin;
    }
}

/// Axis-aligned box.
#[derive(Copy, Clone)]
struct Bounds {
    min: Point,
    max: Point,
}

impl Bounds {
    fn of_segment(a: Point, b: Point) -> Bounds {
        Bounds {
            min: Point::new(a.x.min(b.x), a.y.min(b.y)),
            max: Point::new(a.x.max(b.x), a.y.max(b.y)),
        }
    }

    fn union(self, other: Bounds) -> Bounds {
        Bounds {
            min: Point::new(self.min.x.min(other.min.x), self.min.y.min(other.min.y)),
            max: Point::new(self.max.x.max(other.max.x), self.max.y.max(other.max.y)),
        }
    }

    fn distance_squared(&self, p: Point) -> f64 {
        let dx = (self.min.x - p.x).max(p.x - self.max.x).max(0.0);
        let dy = (self.min.y - p.y).max(p.y - self.max.y).max(0.0);
        dx * dx + dy * dy
    }
}

/// Segments per leaf of the hierarchy.
const LEAF: usize = 4;

/// Levels of the hierarchy at most: each level halves the segments, and there are fewer than
/// 2^64 of them.
const STACK_LEVELS: usize = 65;

/// A bounding-volume hierarchy over segments, built by median splits along the wider side;
/// a nearest query visits boxes closest first and stops at the first box farther than the best
/// segment found, so it is exact and takes logarithmic time near the segments and far from them.
struct SegmentTree {
    /// Segment ends, in the order the tree's leaves hold them.
    ends: Vec<[Point; 2]>,
    /// Nodes in depth-first order; `nodes[0]` is the root.
    nodes: Vec<Node>,
}

#[derive(Copy, Clone)]
struct Node {
    bounds: Bounds,
    /// A leaf's segments are `ends[first..first + count]`; an inner node has `count == 0`, its
    /// left child right after it and its right child at `first`.
    first: usize,
    count: usize,
}

impl SegmentTree {
    #[cfg(test)]
    fn new(points: &[Point], segments: &[[usize; 2]]) -> SegmentTree {
        SegmentTree::from_ends(
            segments
                .iter()
                .map(|&[a, b]| [points[a], points[b]])
                .collect(),
        )
    }

    fn from_ends(mut ends: Vec<[Point; 2]>) -> SegmentTree {
        let mut nodes = Vec::with_capacity(2 * ends.len() / LEAF + 1);
        if !ends.is_empty() {
            let count = ends.len();
            build(&mut ends, 0, count, &mut nodes);
        }
        SegmentTree { ends, nodes }
    }

    /// Squared distance from `p` to the nearest segment, or `best` if none is nearer; infinite
    /// without segments and an infinite `best`.
    ///
    /// With a `margin` (see [`widened`]), a box is skipped only when it is provably farther than
    /// `best` whatever the rounding, so the answer is the minimum of [`segment_distance_squared`]
    /// over every segment. Without one, a box is skipped when its rounded distance is not below
    /// `best`: the rule of the implementation before issue 29's defect 6, kept for the tests'
    /// reference.
    fn nearest_squared(&self, p: Point, mut best: f64, margin: Option<f64>) -> f64 {
        if self.nodes.is_empty() {
            return best;
        }
        let limit = |best: f64| match margin {
            Some(margin) => widened(best, margin),
            None => best,
        };
        let mut beyond = limit(best);
        // Depth-first, nearer child first. A median split halves every node, so the tree is at
        // most 64 levels deep and the stack, one deferred child per level and the node being
        // looked at, fits a fixed array: no allocation per query.
        let mut stack = [(0.0f64, 0usize); 2 * STACK_LEVELS];
        let mut depth = 1;
        while depth > 0 {
            depth -= 1;
            let (bound, k) = stack[depth];
            let skip = match margin {
                Some(_) => bound > beyond,
                None => bound >= best,
            };
            if skip {
                continue;
            }
            let node = self.nodes[k];
            if node.count > 0 {
                for &[a, b] in &self.ends[node.first..node.first + node.count] {
                    best = best.min(segment_distance_squared(p, a, b));
                }
                beyond = limit(best);
                continue;
            }
            let (left, right) = (k + 1, node.first);
            let dl = self.nodes[left].bounds.distance_squared(p);
            let dr = self.nodes[right].bounds.distance_squared(p);
            let (near, far) = if dl <= dr {
                ((dl, left), (dr, right))
            } else {
                ((dr, right), (dl, left))
            };
            stack[depth] = far;
            stack[depth + 1] = near;
            depth += 2;
        }
        best
    }
}

/// Appends the subtree over `ends[first..first + count]` to `nodes`, returning its index.
fn build(ends: &mut [[Point; 2]], first: usize, count: usize, nodes: &mut Vec<Node>) -> usize {
    let slice = &mut ends[first..first + count];
    let bounds = slice
        .iter()
        .map(|&[a, b]| Bounds::of_segment(a, b))
        .reduce(Bounds::union)
        .expect("a node holds at least one segment");
    let index = nodes.len();
    if count <= LEAF {
        nodes.push(Node {
            bounds,
            first,
            count,
        });
        return index;
    }
    let along_x = bounds.max.x - bounds.min.x >= bounds.max.y - bounds.min.y;
    let centre = |s: &[Point; 2]| {
        if along_x {
            s[0].x + s[1].x
        } else {
            s[0].y + s[1].y
        }
    };
    let half = count / 2;
    slice.select_nth_unstable_by(half, |s, t| centre(s).total_cmp(&centre(t)));
    nodes.push(Node {
        bounds,
        first: 0,
        count: 0,
    });
    build(ends, first, half, nodes);
    let right = build(ends, first + half, count - half, nodes);
    nodes[index].first = right;
    index
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Xorshift;

    fn brute_nearest(points: &[Point], truth: &[[usize; 2]], p: Point) -> f64 {
        truth
            .iter()
            .map(|&[a, b]| segment_distance_squared(p, points[a], points[b]))
            .fold(f64::INFINITY, f64::min)
    }

    /// The search of the implementation before issue 29's defect 6: one tree over all the
    /// segments, skipping a box whose rounded distance is not below the best found.
    struct Reference(SegmentTree);

    impl Nearest for Reference {
        fn build(points: &[Point], segments: &[[usize; 2]], _size: f64) -> Self {
            Reference(SegmentTree::new(points, segments))
        }
        fn nearest_squared(&self, p: Point) -> f64 {
            self.0.nearest_squared(p, f64::INFINITY, None)
        }
    }

    /// The minimum over all segments, one by one.
    struct Brute(Vec<[Point; 2]>);

    impl Nearest for Brute {
        fn build(points: &[Point], segments: &[[usize; 2]], _size: f64) -> Self {
            Brute(
                segments
                    .iter()
                    .map(|&[a, b]| [points[a], points[b]])
                    .collect(),
            )
        }
        fn nearest_squared(&self, p: Point) -> f64 {
            self.0
                .iter()
                .map(|&[a, b]| segment_distance_squared(p, a, b))
                .fold(f64::INFINITY, f64::min)
        }
    }

    /// A chain through `order`.
    fn chain(order: &[usize]) -> Vec<[usize; 2]> {
        order.windows(2).map(|w| [w[0], w[1]]).collect()
    }

    fn shuffled(rng: &mut Xorshift, n: usize) -> Vec<usize> {
        let mut order: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            order.swap(i, rng.below(i as u64 + 1) as usize);
        }
        order
    }

    /// Random edges: each joins a random point to one of the next `reach` (in input order), a
    /// random reach, so that some sets have short edges only and others long ones too.
    fn random_edges(rng: &mut Xorshift, n: usize, count: usize) -> Vec<[usize; 2]> {
        let reach = 1 + rng.below(n as u64);
        (0..count)
            .map(|_| {
                let a = rng.below(n as u64) as usize;
                let b = (a + 1 + rng.below(reach) as usize) % n;
                [a.min(b), a.max(b)]
            })
            .filter(|&[a, b]| a != b)
            .collect::<alloc::collections::BTreeSet<[usize; 2]>>()
            .into_iter()
            .collect()
    }

    /// Points of several kinds: uniform, on a coarse grid (exact ties, axis-parallel
    /// segments), clustered with a far outlier, and with repeated points.
    fn random_points(rng: &mut Xorshift, n: usize, kind: u64) -> Vec<Point> {
        (0..n)
            .map(|i| match kind {
                0 => Point::new(rng.unit(), rng.unit()),
                1 => Point::new(rng.below(12) as f64, rng.below(9) as f64 * 0.5),
                2 if i == 0 => Point::new(1e3, -2e3),
                2 => Point::new(1.0 + rng.unit() * 1e-3, rng.unit() * 1e-3),
                _ => Point::new(rng.below(40) as f64 * 0.1, rng.unit().sqrt()),
            })
            .collect()
    }

    /// Every distance of the fast search against the reference and against the minimum over
    /// all segments, bit for bit, on random sets where segments are short, long and mixed,
    /// including the adversarial chain through random points in a random order.
    #[test]
    fn the_fast_search_scores_exactly_as_the_reference_does() {
        let mut rng = Xorshift::new(0x5eed_2906);
        let (mut compared, mut reference_off) = (0, Vec::new());
        for case in 0..240 {
            let n = 2 + rng.below(if case % 8 == 0 { 3000 } else { 200 }) as usize;
            let points = random_points(&mut rng, n, case % 4);
            let (truth, output) = match case % 3 {
                // The adversarial chain, scored against another chain.
                0 => (chain(&shuffled(&mut rng, n)), chain(&shuffled(&mut rng, n))),
                // Mixed lengths.
                1 => (
                    random_edges(&mut rng, n, n),
                    random_edges(&mut rng, n, 2 * n),
                ),
                // Short truth (a chain in input order), output of any length.
                _ => (
                    chain(&(0..n).collect::<Vec<_>>()),
                    random_edges(&mut rng, n, n),
                ),
            };
            let fast = score_with::<Index>(&points, &output, &truth);
            let brute = score_with::<Brute>(&points, &output, &truth);
            assert_eq!(fast, brute, "case {case}: {n} points, against brute");
            let reference = score_with::<Reference>(&points, &output, &truth);
            let (fast, brute) = (fast.unwrap(), brute.unwrap());
            assert_eq!(
                (
                    fast.max_distance.map(f64::to_bits),
                    fast.rms_distance.map(f64::to_bits)
                ),
                (
                    brute.max_distance.map(f64::to_bits),
                    brute.rms_distance.map(f64::to_bits)
                ),
                "case {case}"
            );
            // The reference skips a box when its rounded distance is not below the best found,
            // which can skip a segment whose rounded distance is a unit in the last place below
            // its box's (case 223: the RMS differs in its last bit). Everywhere else the
            // reference is the minimum too, and the fast search gives its numbers.
            if reference.as_ref().unwrap() != &brute {
                reference_off.push(case);
                continue;
            }
            compared += output.len();
        }
        assert!(compared > 50_000, "{compared}");
        assert!(reference_off.len() <= 2, "{reference_off:?}");
    }

    /// Query by query, inside and outside the box, the index against the minimum over all
    /// segments, with the long search holding every segment, some or none.
    #[test]
    fn the_index_returns_the_minimum_over_all_segments() {
        let mut rng = Xorshift::new(29);
        for case in 0..40 {
            let n = 2 + rng.below(1500) as usize;
            let points = random_points(&mut rng, n, case % 4);
            let truth = match case % 2 {
                0 => chain(&shuffled(&mut rng, n)),
                _ => random_edges(&mut rng, n, n),
            };
            // In the frame `distances` uses: corner at the origin.
            let mut local = points.clone();
            let corner = to_corner(&mut local);
            let size = corner.x.max(corner.y);
            let index = Index::new(&local, &truth, size);
            if case % 4 == 0 {
                assert!(!index.long.keys.is_empty(), "case {case}");
            }
            for _ in 0..200 {
                let s = Point::new(
                    (rng.unit() * 1.4 - 0.2) * size,
                    (rng.unit() * 1.4 - 0.2) * size,
                );
                let brute = brute_nearest(&local, &truth, s);
                assert_eq!(
                    index.nearest_squared(s).to_bits(),
                    brute.to_bits(),
                    "case {case}"
                );
            }
        }
    }

    /// The strips (once a grid of cells), given the segments directly (so that they also hold
    /// segments of length zero, which the index leaves to the tree), against the minimum over
    /// all segments, query by query, on one thread and in runs of strips on rayon's: long
    /// crossing segments, collinear and axis-parallel ones, a cluster with a far outlier,
    /// queries inside, on and outside the box. Then whole scores against the brute search at
    /// scales from 2^-1000 to 2^1000.
    #[test]
    fn the_grid_returns_the_minimum_over_all_segments() {
        let mut rng = Xorshift::new(0x6d_2906);
        for case in 0..48 {
            let n = 2 + rng.below(if case % 6 == 0 { 4000 } else { 300 }) as usize;
            let points = random_points(&mut rng, n, case % 4);
            let mut truth = match case % 3 {
                0 => chain(&shuffled(&mut rng, n)),
                1 => random_edges(&mut rng, n, n),
                _ => chain(&(0..n).collect::<Vec<_>>()),
            };
            let mut local = points.clone();
            let corner = to_corner(&mut local);
            let size = corner.x.max(corner.y);
            if size == 0.0 {
                continue;
            }
            // Segments of length zero, and queries on the points, at the segments' middles
            // and anywhere around the box.
            truth.extend((0..1 + n / 8).map(|_| [rng.below(n as u64) as usize; 2]));
            let ends: Vec<[Point; 2]> = truth.iter().map(|&[a, b]| [local[a], local[b]]).collect();
            let mut queries: Vec<Point> = local.clone();
            queries.extend(
                ends.iter()
                    .map(|[a, b]| Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0)),
            );
            queries.extend((0..300).map(|_| {
                Point::new(
                    (rng.unit() * 1.4 - 0.2) * size,
                    (rng.unit() * 1.4 - 0.2) * size,
                )
            }));
            let margin = RELATIVE_SLACK * size + 1e-150;
            let strips = LongStrips::new(&ends, size);
            let all = LongSegments::new(ends.clone(), Point::new(size / 2.0, size / 2.0));
            for parallel in [false, true] {
                let mut found = vec![f64::INFINITY; queries.len()];
                strips.nearest_squared_all(&queries, &mut found, &all, margin, parallel);
                for (&s, d) in queries.iter().zip(found) {
                    let brute = brute_nearest(&local, &truth, s);
                    assert_eq!(d.to_bits(), brute.to_bits(), "case {case}: {s:?}");
                }
            }
            if case % 4 == 0 {
                truth.retain(|&[a, b]| a != b);
                let output = chain(&shuffled(&mut rng, n));
                for k in [-1000, -600, 0, 600, 1000] {
                    let scale = Scale::power_of_two(k);
                    let scaled: Vec<Point> = points.iter().map(|&p| scale.apply(p)).collect();
                    assert_eq!(
                        score_with::<Index>(&scaled, &output, &truth),
                        score_with::<Brute>(&scaled, &output, &truth),
                        "case {case}: 2^{k}"
                    );
                }
            }
        }
    }

    /// On rayon's threads (in runs of strips, each building its first strip from nothing) and
    /// on one, the same distances bit for bit, on chains long enough for many strips, with
    /// queries on another chain and all over the box.
    #[test]
    fn the_parallel_search_finds_what_one_thread_does() {
        let mut rng = Xorshift::new(0x9a7a_2906);
        for (n, kind) in [(30_000, 0), (6_000, 1), (6_000, 3)] {
            let points = random_points(&mut rng, n, kind);
            let truth = chain(&shuffled(&mut rng, n));
            let size = points.iter().fold(0.0f64, |m, p| m.max(p.x).max(p.y));
            let mut index = Index::new(&points, &truth, size);
            assert!(index.strips.steep.count > 16, "{n} points");
            let order = shuffled(&mut rng, n);
            let mut queries: Vec<Point> = order
                .windows(2)
                .map(|w| {
                    let (a, b) = (points[w[0]], points[w[1]]);
                    Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0)
                })
                .collect();
            queries.extend((0..n).map(|_| Point::new(rng.unit() * size, rng.unit() * size)));
            index.parallel = false;
            let one = index.nearest_squared_all(&queries);
            index.parallel = true;
            let many = index.nearest_squared_all(&queries);
            for (i, (a, b)) in one.iter().zip(&many).enumerate() {
                assert_eq!(a.to_bits(), b.to_bits(), "{n} points, query {i}");
            }
            for (&s, d) in queries.iter().zip(&one).step_by(97) {
                assert_eq!(d.to_bits(), brute_nearest(&points, &truth, s).to_bits());
            }
        }
    }

    #[test]
    fn the_tree_finds_the_nearest_segment_near_and_far() {
        let mut rng = Xorshift::new(7);
        let points = rng.unit_points(500);
        let truth: Vec<[usize; 2]> = (0..499).step_by(2).map(|i| [i, i + 1]).collect();
        let tree = SegmentTree::new(&points, &truth);
        for _ in 0..300 {
            // Queries inside the box and up to 100 boxes away.
            let p = Point::new((rng.unit() - 0.5) * 200.0, (rng.unit() - 0.5) * 200.0);
            let q = Point::new(rng.unit(), rng.unit());
            for s in [p, q] {
                let brute = brute_nearest(&points, &truth, s);
                assert_eq!(tree.nearest_squared(s, f64::INFINITY, None), brute);
                assert_eq!(tree.nearest_squared(s, f64::INFINITY, Some(1e-9)), brute);
            }
        }
    }

    #[test]
    fn an_output_identical_to_the_truth_in_any_order_and_direction_is_exact() {
        let points = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)].map(Point::from);
        let s = score(&points, &[[2, 1], [0, 1]], &[[0, 1], [1, 2]]).unwrap();
        assert!(s.exact);
        assert_eq!((s.precision, s.recall, s.f1), (1.0, 1.0, 1.0));
        assert_eq!((s.max_distance, s.rms_distance), (Some(0.0), Some(0.0)));
    }

    #[test]
    fn edges_to_points_without_truth_edges_are_outlier_edges() {
        // Points 0-1-2 form the truth; 3 is an outlier two units above point 1.
        let points = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (1.0, 2.0)].map(Point::from);
        let truth = [[0, 1], [1, 2]];
        let s = score(&points, &[[0, 1], [1, 2], [1, 3]], &truth).unwrap();
        assert_eq!(s.outlier_edges, 1);
        assert_eq!(
            (s.true_positives, s.false_positives, s.false_negatives),
            (2, 1, 0)
        );
        let diagonal = libm::hypot(2.0, 2.0);
        // Samples of 1-3 at t = 0 (on the truth), 0.5, 1, 1.5 and 2 units above it.
        assert_eq!(s.max_distance, Some(2.0 / diagonal));
        let squares: f64 = [0.0, 0.5, 1.0, 1.5, 2.0].iter().map(|d| d * d).sum();
        let rms = libm::sqrt(squares / 15.0) / diagonal;
        assert!((s.rms_distance.unwrap() - rms).abs() < 1e-15);
    }

    #[test]
    fn a_malformed_output_scores_nothing_and_names_its_first_problem() {
        let points = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)].map(Point::from);
        let truth = [[0, 1], [1, 2]];
        for (output, problem) in [
            (
                vec![[0, 1], [1, 2], [2, 1]],
                EdgeProblem::Repeated {
                    position: 2,
                    edge: [1, 2],
                },
            ),
            (
                vec![[0, 1], [1, 1], [1, 9]],
                EdgeProblem::SelfLoop {
                    position: 1,
                    index: 1,
                },
            ),
            (
                vec![[0, 5], [1, 1]],
                EdgeProblem::OutOfRange {
                    position: 0,
                    index: 5,
                },
            ),
        ] {
            let s = score(&points, &output, &truth).unwrap();
            assert_eq!(s.malformed, Some(problem));
            assert!(!s.exact);
            assert_eq!((s.precision, s.recall, s.f1), (0.0, 0.0, 0.0));
        }
    }

    #[test]
    fn empty_sets_follow_the_conventions() {
        let points = [(0.0, 0.0), (1.0, 0.0)].map(Point::from);
        let both_empty = score(&points, &[], &[]).unwrap();
        assert!(both_empty.exact);
        assert_eq!((both_empty.precision, both_empty.recall), (1.0, 1.0));
        assert_eq!(both_empty.max_distance, None);
        let nothing_found = score(&points, &[], &[[0, 1]]).unwrap();
        assert_eq!((nothing_found.precision, nothing_found.f1), (0.0, 0.0));
        let no_truth = score(&points, &[[0, 1]], &[]).unwrap();
        assert_eq!(no_truth.recall, 1.0);
        assert_eq!(no_truth.max_distance, Some(f64::INFINITY));
        assert_eq!(no_truth.outlier_edges, 1);
    }

    #[test]
    fn distances_do_not_depend_on_an_offset() {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let near: Vec<Point> = square.iter().map(|&p| Point::from(p)).collect();
        let far: Vec<Point> = square
            .iter()
            .map(|&(x, y)| Point::new(x + 1e6, y + 1e6))
            .collect();
        let truth = [[0, 1], [1, 2], [2, 3], [0, 3]];
        let output = [[0, 1], [1, 2], [0, 2]];
        assert_eq!(
            score(&near, &output, &truth).unwrap(),
            score(&far, &output, &truth).unwrap()
        );
    }

    /// A set whose distances are all non-trivial: a square's truth and an output with a diagonal,
    /// a side off the truth and an outlier edge.
    fn square_case(scale: Scale) -> (Vec<Point>, Vec<[usize; 2]>, Vec<[usize; 2]>) {
        let corners = [
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
            (0.25, 0.5),
        ];
        let points = corners.map(|p| scale.apply(Point::from(p))).to_vec();
        let truth = vec![[0, 1], [1, 2], [2, 3], [0, 3]];
        let output = vec![[0, 1], [0, 2], [1, 3], [2, 4]];
        (points, output, truth)
    }

    #[test]
    fn distances_are_the_same_at_every_power_of_two_scale() {
        let (points, output, truth) = square_case(Scale::IDENTITY);
        let unit = score(&points, &output, &truth).unwrap();
        let max = unit.max_distance.unwrap();
        assert!(max > 0.0 && max < 1.0, "{max}");
        assert!(unit.rms_distance.unwrap() > 0.0);
        // 2^±600 (beyond 1e154 squares overflow, below 1e-162 they vanish) and the extremes
        // of the range, where the corners are ±f64::MAX and the box's sides overflow.
        for k in [600, -600, 1000, -1000, 1023] {
            let (points, output, truth) = square_case(Scale::power_of_two(k));
            assert_eq!(score(&points, &output, &truth).unwrap(), unit, "2^{k}");
        }
        let widest = Scale::power_of_two(1023)
            .apply(Point::new(2.0 - f64::EPSILON, 0.0))
            .x;
        assert_eq!(widest, f64::MAX);
        let at_max: Vec<Point> = points
            .iter()
            .map(|p| Point::new(p.x * widest, p.y * widest))
            .collect();
        let unit_max: Vec<Point> = points
            .iter()
            .map(|p| Point::new(p.x * (2.0 - f64::EPSILON), p.y * (2.0 - f64::EPSILON)))
            .collect();
        assert_eq!(
            score(&at_max, &output, &truth).unwrap(),
            score(&unit_max, &output, &truth).unwrap()
        );
    }

    #[test]
    fn a_non_finite_point_or_a_bad_truth_is_an_error() {
        let points = [Point::new(0.0, 0.0), Point::new(f64::NAN, 0.0)];
        assert_eq!(
            score(&points, &[], &[]),
            Err(ScoreError::NonFinite { index: 1 })
        );
        let points = [(0.0, 0.0), (1.0, 0.0)].map(Point::from);
        assert_eq!(
            score(&points, &[], &[[0, 1], [1, 0]]),
            Err(ScoreError::Truth(EdgeProblem::Repeated {
                position: 1,
                edge: [0, 1]
            }))
        );
    }
}
