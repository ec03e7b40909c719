//! Stage 1, the ConDT proximity graph (Algorithm 1, lines 2–8).
//!
//! Owns: each vertex's choice of its two shortest Delaunay edges and the uniformity test; it reads
//! the finished triangulation and may not change it. Fixed `u` sweeps the triangles in memory order
//! ([`sweep`]: no chain of dependent loads); adaptive `u` walks each ring, adding its lengths from
//! the neighbour with the smallest id, as its floating-point mean depends on the sum's order
//! (docs/condt.md, *Why adaptive `u` walks rings*). Both rank with `TwoBest` (a total order) and
//! decide with [`keep`]; tests compare them.

use super::PARALLEL_FROM;
use crate::adjacency::{ordered, Edge};
use crate::error::Error;
use crate::mesh::VertexId;
use crate::prefetch::{prefetch, PREFETCH_FROM};
use crate::threads::workers;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;
use core::cmp::Ordering;

/// The local uniformity test of Algorithm 1, line 6: when a point keeps its second shortest edge.
///
/// ```
/// use condt::Uniformity;
/// assert_eq!(Uniformity::default(), Uniformity::Fixed(2.75));
/// assert!(Uniformity::Fixed(2.0).check().is_ok() && Uniformity::Adaptive.check().is_ok());
/// let err = Uniformity::Fixed(f64::NAN).check().unwrap_err();
/// let words = "parameter u = NaN is not accepted (u is a finite number greater than 0)";
/// assert_eq!(err.to_string(), words);
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Uniformity {
    /// Keep `e2` when `|e2| < u |e1|` (the paper: `u = 2.75`); `u` must be finite and positive.
    Fixed(f64),
    /// Section 4.1: keep `e2` when shorter than the mean length of the point's Delaunay edges.
    Adaptive,
}

/// The paper's uniformity bound `u`: Algorithm 1's default, and the ratio of lengths the later
/// stages read as one sampling ([`LONG`](super::local_outliers::LONG),
/// [`GAP_RATIO`](super::gaps::GAP_RATIO)), fixed there whatever `u` the caller gives.
pub(crate) const PAPER_U: f64 = 2.75;

impl Default for Uniformity {
    fn default() -> Self {
        Uniformity::Fixed(PAPER_U)
    }
}

impl Uniformity {
    /// `Ok` when the test is well defined: a fixed `u` must be finite and positive.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] named `u` otherwise.
    ///
    /// ```
    /// use condt::{Error, Uniformity};
    /// assert!(Uniformity::Fixed(2.75).check().is_ok());
    /// let zero = Uniformity::Fixed(0.0).check();
    /// assert!(matches!(zero, Err(Error::InvalidParameter { name: "u", .. })));
    /// ```
    pub fn check(self) -> Result<(), Error> {
        match self {
            Uniformity::Fixed(u) if !(u.is_finite() && u > 0.0) => Err(Error::invalid("u", u)),
            _ => Ok(()),
        }
    }
}

/// The (at most two) neighbours vertex `v` keeps, from a walk of its ring. No allocation.
fn kept_neighbors(tri: &Triangulation, v: VertexId, uniformity: Uniformity) -> [VertexId; 2] {
    let mut best = TwoBest::EMPTY;
    // The ring's lengths, which a fixed `u` does not read, come with the walk.
    let ring = offer_ring(tri, v, &mut best);
    keep(tri, v, uniformity, &best, ring)
}

/// Offers `v`'s ring to `best` and returns [`ring_lengths`] from the same walk: the lengths as
/// walked and where the smallest id is are kept (rings longer than the buffer, rare, are walked
/// again).
fn offer_ring(tri: &Triangulation, v: VertexId, best: &mut TwoBest) -> (f64, u32) {
    let p = tri.vertex_point(v);
    let mut walked = [0.0; RING_BUFFER];
    let (mut degree, mut first, mut smallest) = (0, 0, VertexId::INFINITE);
    for w in tri.mesh().neighbors(v) {
        let length2 = p.dist2(tri.vertex_point(w));
        if let Some(slot) = walked.get_mut(degree) {
            *slot = libm::sqrt(length2);
        }
        if w < smallest {
            (first, smallest) = (degree, w);
        }
        degree += 1;
        best.offer(length2, w, |x, y| closer(tri, v, x, y));
    }
    if degree <= RING_BUFFER {
        (sum_turned(&walked[..degree], first), degree as u32)
    } else {
        ring_lengths(tri, v)
    }
}

/// The sum of `lengths` added from `lengths[first]` on, round to `lengths[first - 1]`.
fn sum_turned(lengths: &[f64], first: usize) -> f64 {
    let (before, from) = lengths.split_at(first);
    from.iter().chain(before).fold(0.0, |sum, &l| sum + l)
}

/// Ring lengths [`kept_neighbors`] keeps as it walks (a Delaunay vertex has six neighbours on
/// average; more than this many is rare).
const RING_BUFFER: usize = 16;

/// The sum of `v`'s Delaunay edge lengths and their count, for adaptive `u`. The floating-point
/// sum depends on the order of its terms, so they are added counter-clockwise from the neighbour
/// with the smallest id: an order fixed by `v`'s star and the order of the ids alone, whatever
/// half-edge the mesh stores first (a tile of `condt.dask` that holds the same star, with ids in
/// the same order, adds them alike). Three walks of the ring, no allocation.
fn ring_lengths(tri: &Triangulation, v: VertexId) -> (f64, u32) {
    let p = tri.vertex_point(v);
    let ring = || tri.mesh().neighbors(v);
    let Some((first, _)) = ring().enumerate().min_by_key(|&(_, w)| w) else {
        return (0.0, 0);
    };
    ring()
        .skip(first)
        .chain(ring().take(first))
        .fold((0.0, 0), |(sum, count), w| {
            (sum + libm::sqrt(p.dist2(tri.vertex_point(w))), count + 1)
        })
}

/// Which of `x` and `y` is nearer to `v`, exactly; `Equal` when they are (the caller then goes
/// by id). Rounded squared lengths decide only where they differ by more than their rounding
/// ([`crate::predicates::distance_order`]).
fn closer(tri: &Triangulation, v: VertexId, x: VertexId, y: VertexId) -> Ordering {
    let [p, px, py] = [v, x, y].map(|u| tri.vertex_point(u));
    crate::predicates::compare_distances(p, px, py)
}

/// Algorithm 1, line 6: the shortest edge always, the second when it passes the uniformity test
/// (the one place it is written; `ring`: the sum of its lengths, their count). `best` holds `v`'s
/// offers; their lengths are measured again (the record keeps only a key).
fn keep(
    tri: &Triangulation,
    v: VertexId,
    uniformity: Uniformity,
    best: &TwoBest,
    ring: (f64, u32),
) -> [VertexId; 2] {
    let [w1, w2] = best.kept();
    let length = |w: VertexId| libm::sqrt(tri.vertex_point(v).dist2(tri.vertex_point(w)));
    let point = |w: VertexId| tri.vertex_point(w);
    // Fixed `u`: exactly, as the paper states it (a ratio of exactly `u` drops the edge). The
    // adaptive bound is a mean of square roots, which no integer holds: rounded.
    let keep_second = !w2.is_infinite()
        && match (uniformity, ring) {
            (Uniformity::Fixed(u), _) => {
                crate::predicates::shorter_than_scaled(point(v), point(w1), u, point(w2))
            }
            (Uniformity::Adaptive, (sum, count)) => length(w2) < sum / count as f64,
        };
    [w1, if keep_second { w2 } else { VertexId::INFINITE }]
}

/// How vertex `v` saw its edge to each of `others` in Algorithm 1, read off its ring as
/// [`kept_neighbors`] reads it (evidence for [`crate::Reconstruction::provenance`]). The ring is
/// sorted once for all of `others`, into `ring` (the caller's buffer, kept from vertex to
/// vertex), and each edge's rank found there by a binary search: O((d + k) log d) for `k` edges
/// at a vertex of degree `d`, where a walk of the ring per edge was quadratic at the hub of a
/// fan (a point beside a long line of samples: docs/perf-log.md).
pub(crate) fn end_choices<'a>(
    tri: &'a Triangulation,
    v: VertexId,
    others: impl IntoIterator<Item = VertexId> + 'a,
    uniformity: Uniformity,
    ring: &'a mut Vec<(f64, VertexId)>,
) -> impl Iterator<Item = EndChoice> + 'a {
    let p = tri.vertex_point(v);
    let key = move |u: VertexId| (p.dist2(tri.vertex_point(u)), u);
    ring.clear();
    ring.extend(tri.mesh().neighbors(v).map(key));
    // The stage's order ([`TwoBest::offer`]): exact length, then id; the stage compares a
    // 32-bit key first, so the two can differ where two squares within the rounding gap fall on
    // either side of a key's step (docs/condt.md, *Readings*, item 1).
    // A vertex is itself first: the search below meets its own entry, whose tie the exact
    // comparison would otherwise settle at length (big integers, where the square rounds).
    let order = move |a: &(f64, VertexId), b: &(f64, VertexId)| {
        if a.1 == b.1 {
            return Ordering::Equal;
        }
        let at = |&(length2, w): &(f64, VertexId)| (tri.vertex_point(w), length2);
        crate::predicates::distance_order(p, at(a), at(b)).then(a.1.cmp(&b.1))
    };
    ring.sort_unstable_by(order);
    let ring = &*ring;
    let second = ring.get(1).map(|&(length2, w)| {
        let (l1, l2) = (libm::sqrt(ring[0].0), libm::sqrt(length2));
        let bound = match uniformity {
            Uniformity::Fixed(u) => u,
            Uniformity::Adaptive => {
                let (sum, count) = ring_lengths(tri, v);
                sum / f64::from(count) / l1
            }
        };
        let kept = kept_neighbors(tri, v, uniformity)[1] == w;
        // The test compares `l2` with `u l1` (or the ring's mean), not the quotient: where the
        // two round to opposite sides of the bound, the true ratio is the bound to within
        // rounding, and it is read on the side the test took.
        let ratio = match (l2 / l1, kept) {
            (ratio, true) if ratio >= bound => bound.next_down(),
            (ratio, false) if ratio < bound => bound,
            (ratio, _) => ratio,
        };
        EndChoice::Second { ratio, bound, kept }
    });
    // The order is total (ids differ), so only `w` itself matches its key.
    others.into_iter().map(
        move |w| match ring.binary_search_by(|probe| order(probe, &key(w))) {
            Err(_) => EndChoice::NotDelaunay,
            Ok(at) => match (at + 1, second) {
                (1, _) => EndChoice::Shortest,
                (2, Some(second)) => second,
                (rank, _) => EndChoice::Later { rank },
            },
        },
    )
}

/// How one end of an edge saw it in Algorithm 1 ([`crate::EdgeStory::ends`]).
///
/// ```
/// use condt::{reconstruct, EndChoice, Params, Point};
/// let pts = [(0.0, 0.0), (1.0, 0.0), (3.0, 0.0)].map(Point::from);
/// let stories = reconstruct(&pts, &Params::paper())?.provenance();
/// assert_eq!(stories[0].ends, [EndChoice::Shortest, EndChoice::Shortest]); // [0, 1]
/// let second = EndChoice::Second { ratio: 2.0, bound: 2.75, kept: true };
/// assert_eq!(stories[1].ends, [second, EndChoice::Shortest]); // [1, 2], at 1 then at 2
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum EndChoice {
    /// The end's shortest Delaunay edge: always kept.
    Shortest,
    /// The end's second shortest edge, kept when `ratio < bound`.
    Second {
        /// `|e2| / |e1|` at this end. The test compares `|e2|` with `bound · |e1|`; where the
        /// rounded quotient falls on the other side of `bound`, it reads `bound` (not kept) or the
        /// double just below it (kept), so `ratio < bound` always equals `kept`.
        ratio: f64,
        /// The uniformity bound: `u`, or with the adaptive test the ring's mean length over `|e1|`.
        bound: f64,
        /// Whether the test passed.
        kept: bool,
    },
    /// Neither: the edge is the end's `rank`-th shortest (3 or more).
    Later {
        /// Rank in the ring, 1 for the shortest.
        rank: usize,
    },
    /// The edge is not a Delaunay edge at this end (a stage added it).
    NotDelaunay,
}

impl EndChoice {
    /// Whether this end keeps the edge in the proximity graph.
    ///
    /// ```
    /// assert!(condt::EndChoice::Shortest.keeps());
    /// assert!(!condt::EndChoice::Second { ratio: 3.0, bound: 2.75, kept: false }.keeps());
    /// ```
    pub fn keeps(&self) -> bool {
        matches!(
            self,
            EndChoice::Shortest | EndChoice::Second { kept: true, .. }
        )
    }
}

/// Most vertex ranges swept at once. Each sweep reads every triangle's corners to find its own
/// vertices, so more ranges cost memory traffic that more threads do not repay.
const MAX_SWEEP_RANGES: usize = 4;

/// The proximity graph, each edge once, listed by the vertex that kept it, whatever `parallel`.
pub(crate) fn proximity_graph(
    tri: &Triangulation,
    uniformity: Uniformity,
    parallel: bool,
) -> Vec<Edge> {
    let parallel = parallel && tri.num_points() >= PARALLEL_FROM;
    match uniformity {
        Uniformity::Fixed(_) => {
            let best = two_best_offers(tri, workers(parallel).min(MAX_SWEEP_RANGES));
            // Each vertex's choice replaces its offers in place (the ids of its record): memory.
            let decide =
                |i: usize, b: &TwoBest| keep(tri, VertexId::new(i as u32), uniformity, b, (0.0, 0));
            list_kept(best, parallel, &decide, TwoBest::keep_only, TwoBest::kept)
        }
        Uniformity::Adaptive => {
            let kept = alloc::vec![[VertexId::INFINITE; 2]; tri.num_points()];
            let decide = ring_choice(tri, uniformity);
            list_kept(kept, parallel, &decide, |k, pair| *k = pair, |k| *k)
        }
    }
}

/// What vertex `i` keeps, from a walk of its ring (none for an id left by a merged duplicate).
fn ring_choice(
    tri: &Triangulation,
    uniformity: Uniformity,
) -> impl Fn(usize, &[VertexId; 2]) -> [VertexId; 2] + Sync + '_ {
    move |i, _| {
        let v = VertexId::new(i as u32);
        if tri.is_vertex(v) {
            kept_neighbors(tri, v, uniformity)
        } else {
            [VertexId::INFINITE; 2]
        }
    }
}

/// Every kept edge once, from one record per vertex (`read` gives its choice): each vertex
/// decides with `decide` and `store` records it, in the listing pass, or when `parallel` all on
/// rayon first, then listed in ranges of ids, one per thread, joined in order (the same list).
/// The records are freed before the pieces are joined (memory: the peak of the stage).
fn list_kept<T: Send + Sync>(
    mut records: Vec<T>,
    parallel: bool,
    decide: &(impl Fn(usize, &T) -> [VertexId; 2] + Sync),
    store: impl Fn(&mut T, [VertexId; 2]) + Sync,
    read: impl Fn(&T) -> [VertexId; 2] + Sync,
) -> Vec<Edge> {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        decide_all(&mut records, decide, &store);
        let decided = &*records;
        let size = decided.len().div_ceil(workers(true)).max(1);
        let pieces: Vec<Vec<Edge>> = (0..decided.len())
            .into_par_iter()
            .step_by(size)
            .map(|first| list_decided(decided, first..(first + size).min(decided.len()), &read))
            .collect();
        drop(records);
        let total: usize = pieces.iter().map(Vec::len).sum();
        let mut pieces = pieces.into_iter();
        let mut edges = pieces.next().unwrap_or_default();
        edges.reserve_exact(total - edges.len());
        for piece in pieces {
            edges.extend_from_slice(&piece);
        }
        return edges;
    }
    let _ = parallel;
    let mut listing = Listing::new(records.len());
    for i in 0..records.len() {
        let pair = decide(i, &records[i]);
        store(&mut records[i], pair);
        listing.add(&records, i, pair, &read);
    }
    listing.done()
}

/// [`list_kept`]'s first half on rayon: every record decided and stored.
#[cfg(feature = "parallel")]
fn decide_all<T: Send + Sync>(
    records: &mut [T],
    decide: &(impl Fn(usize, &T) -> [VertexId; 2] + Sync),
    store: &(impl Fn(&mut T, [VertexId; 2]) + Sync),
) {
    use rayon::prelude::*;
    records
        .par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(i, r)| store(r, decide(i, r)));
}

/// [`list_kept`] of the decided records of the ids in `range`, prefetching partners' records.
#[cfg(feature = "parallel")]
fn list_decided<T>(
    records: &[T],
    range: core::ops::Range<usize>,
    read: &impl Fn(&T) -> [VertexId; 2],
) -> Vec<Edge> {
    let prefetching = records.len() >= PREFETCH_FROM;
    let mut listing = Listing::new(range.len());
    for i in range.clone() {
        if prefetching {
            // Decided records name their partners ahead of the listing (most reads would miss).
            if let Some(ahead) = records[..range.end].get(i + PARTNERS_AHEAD) {
                for w in read(ahead) {
                    // Only a smaller partner's record is read.
                    if w.index() < i + PARTNERS_AHEAD {
                        prefetch(records, w.index());
                    }
                }
            }
        }
        listing.add(records, i, read(&records[i]), read);
    }
    listing.done()
}

/// The edges listed so far, in a buffer grown by an eighth as needed.
struct Listing {
    edges: Vec<Edge>,
    count: usize,
}

impl Listing {
    /// Room for `vertices` edges, about what curves keep (memory: `docs/perf-log.md`).
    fn new(vertices: usize) -> Listing {
        Listing {
            edges: alloc::vec![[VertexId::INFINITE; 2]; vertices + 2],
            count: 0,
        }
    }

    /// Lists the edges vertex `i` keeps (`pair`) that a smaller partner has not listed already.
    #[inline]
    fn add<T>(
        &mut self,
        records: &[T],
        i: usize,
        pair: [VertexId; 2],
        read: &impl Fn(&T) -> [VertexId; 2],
    ) {
        let edges = &mut self.edges;
        if self.count + 2 > edges.len() {
            // `resize` alone would double the capacity.
            let more = (edges.len() / 8).max(2);
            edges.reserve_exact(more);
            edges.resize(edges.len() + more, [VertexId::INFINITE; 2]);
        }
        let v = VertexId::new(i as u32);
        for w in pair {
            // Only a smaller `w` can have listed the edge already (and it has decided). For the
            // others `v`'s own record, at hand, is read instead: no miss and no branch.
            let earlier = w < v;
            let partner = read(&records[if earlier { w.index() } else { i }]);
            let listed_by_w = earlier & ((partner[0] == v) | (partner[1] == v));
            edges[self.count] = ordered(v, w);
            self.count += usize::from(!w.is_infinite() & !listed_by_w);
        }
    }

    fn done(mut self) -> Vec<Edge> {
        self.edges.truncate(self.count);
        self.edges.shrink_to_fit();
        self.edges
    }
}

/// How many vertices ahead [`list_decided`] prefetches the records of a vertex's partners.
#[cfg(feature = "parallel")]
const PARTNERS_AHEAD: usize = 16;

/// The two best offers a vertex has had, best first: `(squared length as bits, neighbour)`. A
/// non-negative `f64` orders like its bits, so offers compare as integers, without branches.
#[derive(Copy, Clone)]
struct TwoBest {
    /// [`TwoBest::key`]s of the two offers: 16 bytes a record, not 24 (memory: the stage's peak).
    keys: [u32; 2],
    ids: [u32; 2],
}

impl TwoBest {
    const EMPTY: TwoBest = TwoBest {
        keys: [u32::MAX; 2],
        ids: [u32::MAX; 2],
    };

    /// A squared length's upper 32 bits (sign, exponent and 20 bits of mantissa): for the
    /// non-negative lengths this keeps their order (it never swaps two) over the whole range of
    /// `f64`, so unequal keys order their lengths and equal keys go to the exact comparison.
    /// What is left to rounding: two squares within [`crate::predicates::distance_order`]'s
    /// rounding gap (2^-49) of each other that round to either side of a key's step (2^-20),
    /// one such pair in about 10^8 near ties; testing for neighbouring keys in every offer cost
    /// 1.3 % more instructions on 100,000 uniform points.
    #[inline]
    fn key(length2: f64) -> u32 {
        (length2.to_bits() >> 32) as u32
    }

    /// Keeps the two smallest of those held and `(length, id)` (ties: [`TwoBest::offer_tied`]).
    #[inline]
    fn offer(
        &mut self,
        length2: f64,
        w: VertexId,
        closer: impl Fn(VertexId, VertexId) -> Ordering,
    ) {
        let (l, w) = (Self::key(length2), w.index() as u32);
        let [l0, l1] = self.keys;
        let [i0, i1] = self.ids;
        if l == l0 || l == l1 {
            return self.offer_tied(l, w, closer);
        }
        // No tie is left here: a strict comparison decides.
        let (before_first, before_second) = (l < l0, l < l1);
        // All ones when the condition holds: selections by mask compile to no branch.
        let m0 = u32::from(before_first).wrapping_neg();
        let m1 = u32::from(before_second).wrapping_neg();
        let pick = |mask: u32, yes: u32, no: u32| (yes & mask) | (no & !mask);
        let (second_l, second_i) = (pick(m1, l, l1), pick(m1, w, i1));
        self.keys = [pick(m0, l, l0), pick(m0, l0, second_l)];
        self.ids = [pick(m0, w, i0), pick(m0, i0, second_i)];
    }
    /// [`TwoBest::offer`] when the key equals one held: by exact length, then id.
    #[cold]
    fn offer_tied(&mut self, l: u32, w: u32, closer: impl Fn(VertexId, VertexId) -> Ordering) {
        let [l0, l1] = self.keys;
        let [i0, i1] = self.ids;
        let before = |li: u32, ii: u32| {
            l < li
                || (l == li
                    && closer(VertexId::new(w), VertexId::new(ii)).then(w.cmp(&ii))
                        == Ordering::Less)
        };
        if before(l0, i0) {
            self.keys = [l, l0];
            self.ids = [w, i0];
        } else if before(l1, i1) {
            self.keys = [l0, l];
            self.ids = [i0, w];
        }
    }
    /// Replaces the offers by the kept neighbours ([`TwoBest::kept`]); lengths are not read again.
    #[inline]
    fn keep_only(&mut self, pair: [VertexId; 2]) {
        self.ids = pair.map(|w| w.index() as u32);
    }
    #[inline]
    fn kept(&self) -> [VertexId; 2] {
        self.ids.map(VertexId::new)
    }
}

/// Every vertex's two best offers, from `parts` sweeps at once (on rayon), each for its own range
/// of ids into its own part of one shared array (memory).
fn two_best_offers(tri: &Triangulation, parts: usize) -> Vec<TwoBest> {
    let mut best = alloc::vec![TwoBest::EMPTY; tri.num_points()];
    #[cfg(feature = "parallel")]
    if parts > 1 {
        use rayon::prelude::*;
        let size = best.len().div_ceil(parts);
        best.par_chunks_mut(size)
            .enumerate()
            .for_each(|(k, part)| sweep(tri, part, Some(k * size)));
        return best;
    }
    let _ = parts;
    sweep(tri, &mut best, None);
    best
}

/// How many triangles ahead the sweep asks for the points and records it will read: far
/// enough that a miss resolves first, near enough that the lines are still in the L1 cache.
const PREFETCH_TRIANGLES: usize = 32;

/// The offers the half-edges of every triangle make: each finite half-edge offers its destination
/// to its origin. `best` holds every vertex's record (`first` is `None`) or those from `first` on.
fn sweep(tri: &Triangulation, best: &mut [TwoBest], first: Option<usize>) {
    match (tri.num_points() >= PREFETCH_FROM, first) {
        (true, None) => sweep_with::<true, false>(tri, best, 0),
        (false, None) => sweep_with::<false, false>(tri, best, 0),
        (true, Some(first)) => sweep_with::<true, true>(tri, best, first),
        (false, Some(first)) => sweep_with::<false, true>(tri, best, first),
    }
}

/// [`sweep`], prefetching corners' points and records [`PREFETCH_TRIANGLES`] triangles ahead when
/// `PREFETCH` ([`crate::prefetch`]); `PART` when `best` holds only the records from `first` on.
fn sweep_with<const PREFETCH: bool, const PART: bool>(
    tri: &Triangulation,
    best: &mut [TwoBest],
    first: usize,
) {
    // Where `u`'s record is, if `best` holds it: an infinite corner's (`u32::MAX`) never is.
    let slot = |u: VertexId| u.index().wrapping_sub(first);
    let offer = |best: &mut [TwoBest], u: VertexId, w: VertexId| {
        if !PART || slot(u) < best.len() {
            best[slot(u)].offer(tri.vertex_point(u).dist2(tri.vertex_point(w)), w, |x, y| {
                closer(tri, u, x, y)
            });
        }
    };
    let triangles = 0..tri.mesh().num_triangles_with_ghosts();
    let ahead = tri.mesh().corner_slice(triangles.clone());
    let points = tri.vertex_points();
    for (k, corners) in tri.mesh().triangle_corners(triangles).enumerate() {
        if PREFETCH {
            // A ghost's infinite corner is out of range: `prefetch` skips it.
            let next = 3 * (k + PREFETCH_TRIANGLES);
            for &v in ahead.get(next..next + 3).unwrap_or(&[]) {
                if !PART || slot(v) < best.len() {
                    prefetch(points, v.index());
                    prefetch(best, slot(v));
                }
            }
        }
        let [a, b, c] = corners;
        if a.is_infinite() || b.is_infinite() || c.is_infinite() {
            // A ghost: only its finite half-edge offers.
            for k in 0..3 {
                let (u, w) = (corners[k], corners[(k + 1) % 3]);
                if !u.is_infinite() && !w.is_infinite() {
                    offer(best, u, w);
                }
            }
        } else {
            offer(best, a, b);
            offer(best, b, c);
            offer(best, c, a);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::sample::{sample, Sampling, Shape};
    use crate::triangulate;
    use alloc::vec;

    /// Algorithm 1 keeps the second edge only when `|e2| < u |e1|`: at a ratio of exactly
    /// `u` it drops it, although rounded square roots can read the ratio as a hair under `u`
    /// (a paper-fidelity review: point 0's edges to 1 and 2 are `sqrt 2` and `2.75 sqrt 2`).
    #[test]
    fn a_second_edge_of_exactly_u_times_the_first_is_dropped() {
        let points = [(0.0, 0.0), (1.0, 1.0), (-2.75, -2.75), (-2.75, -3.75)].map(Point::from);
        let result = crate::reconstruct(&points, &crate::Params::paper()).unwrap();
        assert_eq!(result.edges().collect::<Vec<_>>(), vec![[0, 1], [2, 3]]);
        // A hair under the ratio, the edge stays.
        let mut nearer = points;
        nearer[2] = Point::new(-2.75, -2.75 + 1e-9);
        let result = crate::reconstruct(&nearer, &crate::Params::paper()).unwrap();
        assert!(result.edges().any(|e| e == [0, 2]));
    }

    /// Each end's choice, all edges of a vertex answered together, against one count per edge of
    /// the ring members before it in the stage's order (the reading `end_choices` replaced); on
    /// scattered points, a grid (exact ties, decided by id) and a fan's hub (degree 400).
    #[test]
    fn end_choices_rank_each_edge_as_a_count_of_the_ring_before_it() {
        let mut rng = crate::test_rng::Xorshift::new(17);
        let scattered: Vec<Point> = (0..400)
            .map(|_| Point::new(rng.unit(), rng.unit()))
            .collect();
        let grid: Vec<Point> = (0..400)
            .map(|k| Point::new(f64::from(k % 20), f64::from(k / 20)))
            .collect();
        let mut fan: Vec<Point> = (0..400).map(|k| Point::new(f64::from(k), 0.0)).collect();
        fan.push(Point::new(200.0, 1.0));
        for points in [scattered, grid, fan] {
            let tri = triangulate(&points).unwrap();
            for v in (0..tri.num_vertices()).map(|i| VertexId::new(i as u32)) {
                let ring: Vec<VertexId> = tri.mesh().neighbors(v).collect();
                let before =
                    |a: VertexId, b: VertexId| closer(&tri, v, a, b).then(a.cmp(&b)).is_lt();
                // Every ring member, then a vertex off the ring (none on a full ring of all).
                let off = (0..tri.num_vertices() as u32)
                    .map(VertexId::new)
                    .find(|&u| u != v && !ring.contains(&u));
                let asked: Vec<VertexId> = ring.iter().copied().chain(off).collect();
                let mut buffer = Vec::new();
                let fixed = Uniformity::Fixed(2.75);
                let choices: Vec<EndChoice> =
                    end_choices(&tri, v, asked.iter().copied(), fixed, &mut buffer).collect();
                assert_eq!(choices.len(), asked.len());
                for (&w, choice) in asked.iter().zip(choices) {
                    if !ring.contains(&w) {
                        assert_eq!(choice, EndChoice::NotDelaunay);
                        continue;
                    }
                    let rank = 1 + ring.iter().filter(|&&u| before(u, w)).count();
                    match choice {
                        EndChoice::Shortest => assert_eq!(rank, 1),
                        EndChoice::Second { kept, .. } => {
                            assert_eq!(rank, 2);
                            let pair = kept_neighbors(&tri, v, Uniformity::Fixed(2.75));
                            assert_eq!(kept, pair[1] == w);
                        }
                        EndChoice::Later { rank: told } => assert_eq!(told, rank),
                        EndChoice::NotDelaunay => panic!("a ring member told as not Delaunay"),
                    }
                }
            }
        }
    }

    /// The union, against a set built edge by edge, on scattered points where many vertices keep
    /// two edges their neighbours do not keep back: more edges than vertices, so the buffer grows.
    #[test]
    fn union_lists_every_kept_edge_once_as_its_buffer_grows() {
        let mut rng = crate::test_rng::Xorshift::new(0x5851_f42d_4c95_7f2d);
        let mut unit = move || rng.unit();
        let points: Vec<Point> = (0..3000).map(|_| Point::new(unit(), unit())).collect();
        let tri = triangulate(&points).unwrap();
        let n = tri.num_points();
        for uniformity in [
            Uniformity::Fixed(2.75),
            Uniformity::Fixed(100.0),
            Uniformity::Adaptive,
        ] {
            let kept = ring_walks(&tri, uniformity, false);
            let mut expected = alloc::collections::BTreeSet::new();
            for (v, pair) in kept.iter().enumerate() {
                for &w in pair.iter().filter(|w| !w.is_infinite()) {
                    expected.insert(ordered(VertexId::new(v as u32), w));
                }
            }
            let union = proximity_graph(&tri, uniformity, false);
            let listed: alloc::collections::BTreeSet<Edge> = union.iter().copied().collect();
            assert_eq!(
                listed.len(),
                union.len(),
                "{uniformity:?}: an edge listed twice"
            );
            assert_eq!(listed, expected, "{uniformity:?}");
            if let Uniformity::Fixed(_) = uniformity {
                // As the parallel path lists them: swept in two ranges, decided first, in place.
                let best = two_best_offers(&tri, 2);
                let decide = |i: usize, b: &TwoBest| {
                    keep(&tri, VertexId::new(i as u32), uniformity, b, (0.0, 0))
                };
                let decided = list_kept(best, true, &decide, TwoBest::keep_only, TwoBest::kept);
                assert_eq!(decided, union, "{uniformity:?}");
            }
            if uniformity == Uniformity::Fixed(100.0) {
                assert!(
                    union.len() > n + 2,
                    "{} edges: the buffer never grew",
                    union.len()
                );
            }
        }
    }

    /// Adaptive `u`'s ring sum starts at the neighbour with the smallest id, so where the ring
    /// walk starts does not change a bit of it (a tile of `condt.dask` stores other first
    /// half-edges than the whole set); the walk's buffer and the walk again agree.
    #[test]
    fn a_rings_sum_does_not_depend_on_where_its_walk_starts() {
        // Lengths whose sum rounds differently by the order of the terms.
        let lengths = [1.0, 1e-16, 3.0, 1e-16, 0.1, 7.0, 1e-16, 0.3];
        let ids = [5u32, 9, 2, 7, 4, 8, 3, 6];
        let turned = |start: usize| -> (Vec<u32>, Vec<f64>) {
            let turn = |k: usize| (k + start) % ids.len();
            (0..ids.len())
                .map(|k| (ids[turn(k)], lengths[turn(k)]))
                .unzip()
        };
        let sums: Vec<u64> = (0..ids.len())
            .map(|start| {
                let (ids, lengths) = turned(start);
                let first = (0..ids.len()).min_by_key(|&k| ids[k]).unwrap();
                sum_turned(&lengths, first).to_bits()
            })
            .collect();
        assert!(sums.iter().all(|&s| s == sums[0]), "{sums:?}");
        let plain: Vec<u64> = (0..ids.len())
            .map(|start| sum_turned(&turned(start).1, 0).to_bits())
            .collect();
        assert!(
            plain.iter().any(|&s| s != plain[0]),
            "the lengths must tell the orders apart"
        );
        // A fan of 40 points around a centre: its ring is longer than the buffer.
        let mut points = vec![Point::new(0.0, 0.0)];
        points.extend((0..40).map(|k| {
            let t = k as f64 * core::f64::consts::TAU / 40.0;
            Point::new(libm::cos(t) * (1.0 + 0.01 * k as f64), libm::sin(t))
        }));
        let tri = triangulate(&points).unwrap();
        for v in (0..tri.num_points()).map(|i| tri.vertex(i)) {
            let mut best = TwoBest::EMPTY;
            let sum = offer_ring(&tri, v, &mut best);
            assert_eq!(sum.0.to_bits(), ring_lengths(&tri, v).0.to_bits());
            assert_eq!(sum.1, ring_lengths(&tri, v).1);
        }
        assert!(tri.mesh().neighbors(tri.vertex(0)).count() > RING_BUFFER);
    }

    /// Two neighbours at squared lengths 2^24 and 2^24 + 1, both exact, share a record key (an
    /// `f32`); the nearer still comes first, in the sweep and the ring walk, whichever id it has.
    #[test]
    fn lengths_with_one_key_are_ordered_exactly() {
        let (near, far) = (Point::new(4096.0, 0.0), Point::new(1.0, 4096.0));
        let rest = [(-12e3, 2e3), (800.0, -12e3), (12e3, 12e3)].map(Point::from);
        let origin = Point::new(0.0, 0.0);
        assert_eq!(
            TwoBest::key(origin.dist2(near)),
            TwoBest::key(origin.dist2(far))
        );
        for (points, expected) in [([near, far], [1, 2]), ([far, near], [2, 1])] {
            let mut all = vec![Point::new(0.0, 0.0)];
            all.extend(points.iter().chain(&rest));
            let tri = triangulate(&all).unwrap();
            let (v, input) = (tri.vertex(0), |w: VertexId| tri.input_of(w));
            let fixed = Uniformity::Fixed(2.75);
            let walked = kept_neighbors(&tri, v, fixed).map(input);
            let best = two_best_offers(&tri, 1);
            let swept = keep(&tri, v, fixed, &best[v.index()], (0.0, 0)).map(input);
            assert_eq!((walked, swept), (expected, expected));
        }
    }

    /// Squared lengths that round one ulp apart in the wrong order, under one key (a reviewer of
    /// the paper's preset found them): point 0 is nearer to 1 than to 2 by 6.4e-18 in squared
    /// length, and its two nearest are 3 and then 1, swept and walked, in either input order.
    #[test]
    fn lengths_that_round_in_the_wrong_order_are_ordered_exactly() {
        let coords = [
            (0.9497985626218988, 0.6303992934263946),
            (0.788009549780357, 0.1066306096972589),
            (0.4476113389882713, 0.8502112838881093),
            (1.199019431234693, 0.744488242631751),
            (0.8210256073551059, 0.04410109712742619),
        ];
        let points: Vec<Point> = coords.iter().map(|&c| Point::from(c)).collect();
        assert!(points[0].dist2(points[1]) > points[0].dist2(points[2]));
        for order in [[0, 1, 2, 3, 4], [0, 2, 1, 3, 4], [4, 3, 2, 1, 0]] {
            let shuffled: Vec<Point> = order.iter().map(|&k| points[k]).collect();
            let tri = triangulate(&shuffled).unwrap();
            let at = |k: usize| order.iter().position(|&j| j == k).unwrap();
            let v = tri.vertex(at(0));
            let input = |w: VertexId| order[tri.input_of(w)];
            let fixed = Uniformity::Fixed(2.75);
            let walked = kept_neighbors(&tri, v, fixed).map(input);
            let best = two_best_offers(&tri, 1);
            let swept = keep(&tri, v, fixed, &best[v.index()], (0.0, 0)).map(input);
            assert_eq!((walked, swept), ([3, 1], [3, 1]), "{order:?}");
        }
    }

    /// On a grid of 4096 with every coordinate moved by -1, 0 or 1, many rings hold lengths
    /// whose squares differ by 1 in 2^24 (one key) or not at all: every vertex's two picks, swept
    /// and walked, are its two nearest by exact integer length, then vertex id.
    #[test]
    fn picks_follow_exact_lengths_among_near_ties() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut jitter = move || (rng.next_u64() % 3) as i64 - 1;
        let cells: Vec<[i64; 2]> = (0..400)
            .map(|k| [4096 * (k % 20) + jitter(), 4096 * (k / 20) + jitter()])
            .collect();
        let points: Vec<Point> = cells
            .iter()
            .map(|&[x, y]| Point::new(x as f64, y as f64))
            .collect();
        let tri = triangulate(&points).unwrap();
        let wide = Uniformity::Fixed(100.0);
        let best = two_best_offers(&tri, 1);
        let mut key_ties = 0;
        for v in (0..tri.num_points()).map(|i| tri.vertex(i)) {
            let at = |w: VertexId| cells[tri.input_of(w)];
            let length2 = |w: VertexId| {
                let ([x, y], [a, b]) = (at(v), at(w));
                (x - a).pow(2) + (y - b).pow(2)
            };
            let mut ring: Vec<VertexId> = tri.mesh().neighbors(v).collect();
            ring.sort_by_key(|&w| (length2(w), w));
            let key = |w: VertexId| TwoBest::key(tri.vertex_point(v).dist2(tri.vertex_point(w)));
            key_ties += usize::from(key(ring[0]) == key(ring[1]) || key(ring[1]) == key(ring[2]));
            let expected = [ring[0], ring[1]];
            assert_eq!(
                kept_neighbors(&tri, v, wide),
                expected,
                "walked, vertex {v:?}"
            );
            assert_eq!(
                keep(&tri, v, wide, &best[v.index()], (0.0, 0)),
                expected,
                "swept"
            );
        }
        assert!(key_ties > 50, "only {key_ties} rings with a tie of keys");
    }

    /// The sweep (in one to four vertex ranges) and the ring walks (sequential and on
    /// rayon, run here at any size) choose the same neighbours for every vertex.
    #[test]
    fn sweep_and_ring_walks_agree_on_every_vertex() {
        let centre = Point::new(0.0, 0.0);
        let inputs = [
            ("circle", vec![Shape::circle(centre, 1.0)], 0.05, 0.0),
            (
                "square with outliers",
                vec![Shape::Polygon(vec![
                    Point::new(0.0, 0.0),
                    Point::new(4.0, 0.0),
                    Point::new(4.0, 4.0),
                    Point::new(0.0, 4.0),
                ])],
                0.1,
                0.1,
            ),
            (
                "figure eight, noisy",
                vec![Shape::FigureEight {
                    center: centre,
                    size: 2.0,
                }],
                0.05,
                0.0,
            ),
        ];
        let mut dropped = 0;
        for (label, shapes, epsilon, outliers) in inputs {
            let s = sample(
                &shapes,
                &Sampling {
                    outlier_fraction: outliers,
                    noise: 0.01,
                    ..Sampling::new(epsilon)
                },
            )
            .unwrap();
            let tri = triangulate(&s.points).unwrap();
            let fixed = Uniformity::Fixed(2.75);
            let ring_walks = |uniformity, parallel| ring_walks(&tri, uniformity, parallel);
            let walked = ring_walks(fixed, false);
            for ranges in 1..=4 {
                let best = two_best_offers(&tri, ranges);
                let swept: Vec<_> = (best.iter().enumerate())
                    .map(|(i, b)| keep(&tri, VertexId::new(i as u32), fixed, b, (0.0, 0)))
                    .collect();
                assert_eq!(swept, walked, "{label}, {ranges} ranges");
            }
            let adaptive = Uniformity::Adaptive;
            assert_eq!(
                ring_walks(adaptive, true),
                ring_walks(adaptive, false),
                "{label}"
            );
            for uniformity in [fixed, adaptive] {
                let kept = ring_walks(uniformity, false);
                let seconds = kept.iter().filter(|k| !k[1].is_infinite()).count();
                assert!(seconds > 0, "{label}");
                dropped += kept.len() - seconds;
            }
        }
        // Not vacuous: the uniformity test dropped some second edges, kept others.
        assert!(dropped > 0);
        // The ring walks on rayon split the vertices into jobs of at least 4,096: a set that
        // makes several jobs, so the parallel walks really run apart (the sets above make one).
        let s = sample(
            &[Shape::circle(centre, 1.0)],
            &Sampling {
                outlier_fraction: 0.05,
                noise: 0.01,
                ..Sampling::new(0.0005)
            },
        )
        .unwrap();
        let tri = triangulate(&s.points).unwrap();
        let n = tri.num_points();
        assert!(n >= 3 * 4096, "{n}");
        for uniformity in [Uniformity::Fixed(2.75), Uniformity::Adaptive] {
            assert_eq!(
                ring_walks(&tri, uniformity, true),
                ring_walks(&tri, uniformity, false),
                "{uniformity:?}"
            );
        }
    }

    /// Every vertex's choice from a walk of its ring, as the adaptive test lists them.
    fn ring_walks(
        tri: &Triangulation,
        uniformity: Uniformity,
        parallel: bool,
    ) -> Vec<[VertexId; 2]> {
        let mut kept = vec![[VertexId::INFINITE; 2]; tri.num_points()];
        let decide = ring_choice(tri, uniformity);
        #[cfg(feature = "parallel")]
        if parallel {
            decide_all(&mut kept, &decide, &|k: &mut [VertexId; 2], pair| *k = pair);
            return kept;
        }
        let _ = parallel;
        for (i, k) in kept.iter_mut().enumerate() {
            *k = decide(i, k);
        }
        kept
    }

    /// `tests/common/mod.rs` (the integration tests' `run`) compares sequential and parallel
    /// reconstructions only from this size, below which both take the same sequential code.
    #[test]
    fn the_parallel_threshold_is_the_one_the_integration_tests_assume() {
        assert_eq!(PARALLEL_FROM, 1 << 16);
    }
}
