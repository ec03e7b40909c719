//! Delaunay triangulation of a planar point set.
//!
//! Owns: building a [`Triangulation`] ([`Mesh`], points, input/vertex maps), possibly in a spent
//! one's arrays, and checking one. It decides signs only by [`crate::predicates`], writes
//! topology only through the mesh's builder, and knows nothing of the ConDT stages.
//!
//! Incremental insertion with Lawson's flips in BRIO order, each point located by a visibility
//! walk (`docs/triangulation.md`). The reference is `build`, the set in one piece; `halves`, a
//! speed-up for large sets, builds the same triangles in general position and falls back to
//! `build` when it cannot finish: it changes the speed, never the result.

mod check;
mod collinear;
mod halves;
mod insert;
mod order;
mod scale;

use crate::error::Error;
use crate::geometry::{Point, Scale};
use crate::mesh::{Mesh, MeshArrays, VertexId};
use crate::threads::{both, count, filled};
use alloc::borrow::Cow;
use alloc::vec::Vec;
use core::sync::atomic::{AtomicUsize, Ordering};
use insert::{Exact, Fast, Kernel};
pub(crate) use order::mix as splitmix64_finalizer;
pub(crate) use scale::choose_frames;

/// The largest number of input points: half of what `u32` half-edge ids allow; beyond it
/// [`triangulate`] returns [`Error::TooManyPoints`] before allocating (`docs/triangulation.md`).
///
/// ```
/// use condt::MAX_POINTS;
/// // Two triangles a point, ghosts included, of three half-edges: every id fits in a `u32`.
/// assert!(2 * 3 * MAX_POINTS < u32::MAX as usize);
/// ```
pub const MAX_POINTS: usize = 350_000_000;

/// A Delaunay triangulation of a point set.
///
/// Everything here speaks in input positions (indices into the slice given to [`triangulate`]);
/// exact duplicates are one point, under their smallest input position. [`Triangulation::mesh`]
/// is in [`VertexId`]s, numbered in the (spatial) insertion order; [`Triangulation::vertex`] and
/// [`Triangulation::input_of`] convert.
///
/// ```
/// use condt::{triangulate, Point};
/// let pts = [(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0), (1.0, 1.0)].map(Point::from);
/// let tri = triangulate(&pts)?;
/// assert_eq!(tri.triangles().count(), 4);
/// assert_eq!(tri.edges().count(), 8);
/// let mut hull: Vec<usize> = tri.hull().collect(); // counter-clockwise, from some hull point
/// hull.sort_unstable();
/// assert_eq!(hull, vec![0, 1, 2, 3]);
/// assert_eq!(tri.neighbors(4).count(), 4);
/// assert_eq!(tri.point(4), Point::new(1.0, 1.0));
/// tri.validate()?;
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone)]
pub struct Triangulation {
    /// Positions as the stages measure them ([`Triangulation::vertex_point`]), by vertex id.
    points: Vec<Point>,
    /// The input coordinates by vertex id, when `points` cannot hold them exactly (a wide set).
    inputs: Option<Vec<Point>>,
    /// Input coordinates to the exactly rescaled frame the predicates decide in.
    scale: Scale,
    /// `points` to the predicates' frame (exact when `inputs` is `None`).
    stage_to_predicates: Scale,
    /// `points` to the input coordinates (exact when `inputs` is `None`).
    stage_to_input: Scale,
    /// The caller's coordinates of the input frame's zero, if not zero: smoothing triangulates
    /// positions relative to the set's corner (so that exact translations give the same edges).
    offset: Option<Point>,
    mesh: Mesh,
    /// Whether the set spans more than the fast predicates take: only such a set can hold two
    /// points too close for the stages to measure ([`Triangulation::too_close_to_measure`]).
    wide: bool,
    /// Vertex id -> input position; for a kept vertex, the smallest position of its duplicates.
    input_of_vertex: Vec<u32>,
    /// Input position -> the vertex that stands for it.
    vertex_of_input: Vec<VertexId>,
    num_vertices: usize,
}

/// Counts, not the arrays: the stored coordinates are in the predicates' rescaled frame
/// (`(1, 0)` may be kept as `1.6e60`), which a log would mistake for the input's.
///
/// ```
/// use condt::{triangulate, Point};
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// let tri = triangulate(&square)?;
/// assert_eq!(format!("{tri:?}"), "Triangulation { points: 4, vertices: 4, triangles: 2, .. }");
/// # Ok::<(), condt::Error>(())
/// ```
impl core::fmt::Debug for Triangulation {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Triangulation")
            .field("points", &self.num_points())
            .field("vertices", &self.num_vertices())
            .field("triangles", &self.triangles().count())
            .finish_non_exhaustive()
    }
}

/// Triangulates `points`.
///
/// Every finite input is accepted at any scale: fewer than three points, collinear points (a
/// chain of segments, no triangle), exact duplicates (merged, see [`Triangulation::vertex`]),
/// cocircular sets, and sets spanning more than 2^200 in magnitude (slower exact integer
/// arithmetic, `docs/predicates.md`). The result depends only on the points, not on their order
/// nor on the number of threads: 65,536 distinct points or more are built in two halves, at once
/// with `parallel` (`docs/triangulation.md`); for one thread, use a one-thread rayon pool. Where
/// the Delaunay triangulation is not unique (four or more points on a circle, as in a grid),
/// which diagonal is chosen can depend, in such large sets, on how often points repeat: the cut
/// between the halves falls near the median counted with repeats.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coordinate, naming the first such input index;
/// [`Error::TooManyPoints`] beyond [`MAX_POINTS`].
///
/// ```
/// use condt::{triangulate, Point};
/// let line: Vec<Point> = (0..5).map(|i| Point::new(i as f64, 2.0 * i as f64)).collect();
/// let tri = triangulate(&line)?;
/// assert_eq!(tri.triangles().count(), 0);
/// assert_eq!(tri.edges().collect::<Vec<_>>(), vec![[0, 1], [1, 2], [2, 3], [3, 4]]);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn triangulate(points: &[Point]) -> Result<Triangulation, Error> {
    triangulate_with(points, cfg!(feature = "parallel"), None, None)
}

/// [`triangulate`] on points handed over: the same triangulation, with a lower peak. A set of
/// 65,536 points or more that is cut in two (each side holding a triangle) is freed once its
/// halves are ordered, before the mesh is allocated (16 bytes a point less at the peak), unless
/// it spans more than 2^200 (its inputs are kept then); other sets are freed when it returns.
/// The peak is the allocator's: in a WebAssembly module, whose memory only grows, the freed
/// input leaves a hole the mesh's larger arrays do not fit, and the module grows as much as with
/// [`triangulate`] (README, *Features*).
///
/// # Errors
/// As [`triangulate`].
///
/// ```
/// use condt::{triangulate, triangulate_owned, Point};
/// let points = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.5, 1.0)];
/// let borrowed = triangulate(&points)?;
/// let owned = triangulate_owned(points)?;
/// assert!(owned.triangles().eq(borrowed.triangles()));
/// # Ok::<(), condt::Error>(())
/// ```
pub fn triangulate_owned(points: Vec<Point>) -> Result<Triangulation, Error> {
    triangulate_with(points, cfg!(feature = "parallel"), None, None)
}

/// [`triangulate`], on one thread unless `parallel` (the same result), counting into `inserted`,
/// in the arrays of `spent` (a triangulation no longer needed) as [`MeshArrays::reusing`] does.
/// Points handed over are freed as [`triangulate_owned`] says.
pub(crate) fn triangulate_with<'a>(
    points: impl Into<Cow<'a, [Point]>>,
    parallel: bool,
    inserted: Option<&AtomicUsize>,
    spent: Option<Triangulation>,
) -> Result<Triangulation, Error> {
    let points = points.into();
    // Smaller sets use no thread either way: the pool is not started for them.
    let large = points.len() >= halves::SPLIT_MIN.min(PARALLEL_MIN);
    let parallel = parallel && large && crate::threads::parallel_available();
    triangulate_in(points, parallel, halves::SPLIT_MIN, inserted, spent, None)
}

/// [`triangulate_with`] cutting sets of `split_min` points and more in two, or inserting them in
/// the `given` order (a permutation of the input positions) on one thread.
fn triangulate_in(
    mut points: Cow<'_, [Point]>,
    parallel: bool,
    split_min: usize,
    progress: Option<&AtomicUsize>,
    spent: Option<Triangulation>,
    given: Option<Vec<u32>>,
) -> Result<Triangulation, Error> {
    let frames = scale::choose_frames(&points)?;
    let scale = frames.predicates;
    // The rest of `spent` is freed before the cut's scratch is allocated (memory: 8 bytes a point).
    let spare = match spent {
        Some(t) => (t.input_of_vertex, t.points, t.mesh.into_storage()),
        None => Default::default(),
    };
    let (order, mut sorted, built) = match given {
        Some(order) => construct_in_order(&points, &frames, order, progress),
        None => construct(&mut points, &frames, parallel, split_min, progress, spare),
    };
    // Read below only without a triangle or for a wide set, neither of which `construct` frees.
    let points = &*points;
    let (mesh, merged, order) = match built {
        None => {
            // No triangle: the chain in line order is the vertex order instead.
            let (mesh, merged, line_order) = collinear::chain(points);
            if let Some(counter) = progress {
                crate::threads::count(counter, points.len() - merged.len(), true);
            }
            for (slot, &i) in sorted.iter_mut().zip(&line_order) {
                *slot = scale.apply(points[i as usize]);
            }
            (mesh, merged, line_order)
        }
        Some((mesh, merged)) => (mesh, merged, order),
    };
    // The stored coordinates are the stages' positions: exact in the fast range (every nonzero
    // coordinate ends at least 1); a wide set may lose low bits there, so it keeps its inputs too.
    let (predicates_exponent, stages_exponent) = frames.exponents;
    let stage_to_input = frames.stages.inverse();
    let mut inputs = None;
    if frames.wide {
        let stage = frames.stages;
        let exact = points
            .iter()
            .all(|&p| stage_to_input.apply(stage.apply(p)) == p);
        if !exact {
            inputs = Some(order.iter().map(|&i| points[i as usize]).collect());
        }
        for (slot, &i) in sorted.iter_mut().zip(&order) {
            *slot = stage.apply(points[i as usize]);
        }
    } else {
        let to_stages = Scale::power_of_two(stages_exponent - predicates_exponent);
        let rescale =
            |points: &mut [Point]| points.iter_mut().for_each(|p| *p = to_stages.apply(*p));
        let middle = sorted.len() / 2;
        let (low, high) = sorted.split_at_mut(middle);
        let split = parallel && low.len() >= PARALLEL_MIN / 2;
        both(split, || rescale(low), || rescale(high));
    }
    let (input_of_vertex, vertex_of_input) = vertex_maps(order, &merged, parallel);
    let num_vertices = vertex_of_input.len() - merged.len();
    Ok(Triangulation {
        points: sorted,
        inputs,
        scale,
        stage_to_predicates: Scale::power_of_two(predicates_exponent - stages_exponent),
        stage_to_input,
        offset: None,
        mesh,
        wide: frames.wide,
        input_of_vertex,
        vertex_of_input,
        num_vertices,
    })
}

/// A mesh and the `(duplicate, kept)` pairs merged into it, or `None` without a triangle.
type Built = Option<(Mesh, Vec<(u32, u32)>)>;

/// The insertion order (input positions), its points in the predicates' frame, and their mesh,
/// in the `spare` arrays for these three if large enough.
fn construct(
    input: &mut Cow<'_, [Point]>,
    frames: &scale::Frames,
    parallel: bool,
    split_min: usize,
    progress: Option<&AtomicUsize>,
    (spare_order, spare_points, mesh): (Vec<u32>, Vec<Point>, Mesh),
) -> (Vec<u32>, Vec<Point>, Built) {
    if let Some(cut) = cut_in_two(input, frames, split_min, parallel) {
        let buffers = (spare_order, spare_points);
        let (order, sorted) = cut_order(input, frames, &cut, parallel, true, buffers);
        // The halves read only `sorted`, which holds an unwide input exactly (a power-of-two
        // scaling within the normal range): points handed over are freed before the mesh is
        // allocated, and read back from `sorted` in the rare case they are needed again.
        let freed = matches!(input, Cow::Owned(_)) && !frames.wide;
        if freed {
            *input = Cow::Owned(Vec::new());
        }
        let counted = progress.map(|inserted| inserted.load(Ordering::Relaxed));
        let built = if frames.wide {
            halves::build::<Exact>(&sorted, cut.left_len(), parallel, progress, mesh)
        } else {
            halves::build::<Fast>(&sorted, cut.left_len(), parallel, progress, mesh)
        };
        match &built {
            // Fewer distinct points than the bound are built in one piece, as they would be
            // without their repeats: on a cocircular set the two constructions may choose
            // other diagonals, and the triangulation would change with how often a point
            // repeats (an embedded developer's review: a grid given 4,097 times over).
            Some((_, merged)) if order.len() - merged.len() < split_min => {}
            Some(_) => return (order, sorted, built),
            None => {}
        }
        if let (Some(inserted), Some(counted)) = (progress, counted) {
            // The halves' count taken back (`threads::count`: Cortex-M0 has no `fetch_sub`).
            let now = inserted.load(Ordering::Relaxed);
            count(inserted, now.saturating_sub(counted), false);
        }
        if freed {
            drop(built);
            let to_input = frames.predicates.inverse();
            let mut points = alloc::vec![Point::default(); order.len()];
            for (&i, &p) in order.iter().zip(&sorted) {
                points[i as usize] = to_input.apply(p);
            }
            *input = Cow::Owned(points);
        }
    }
    let order = spatial_order(input, frames);
    construct_in_order(input, frames, order, progress)
}

/// The insertion order of a set cut in two (left half first) and, with `with_points`, its points in
/// the predicates' frame, in `buffers` if large enough; each half on its own thread if `parallel`.
fn cut_order(
    points: &[Point],
    frames: &scale::Frames,
    cut: &halves::Cut,
    parallel: bool,
    with_points: bool,
    buffers: (Vec<u32>, Vec<Point>),
) -> (Vec<u32>, Vec<Point>) {
    let n = points.len();
    let mut order = filled(buffers.0, 0u32, n, parallel);
    let mut sorted = if with_points {
        filled(buffers.1, Point::default(), n, parallel)
    } else {
        Vec::new()
    };
    let left = cut.left_len();
    let (order_left, order_right) = order.split_at_mut(left);
    let (sorted_left, sorted_right) = sorted.split_at_mut(if with_points { left } else { 0 });
    // Both halves' scratch is allocated on this thread, not the second half's (memory: another
    // thread's malloc arena would keep it once freed; `docs/perf-log.md`).
    let scratch = |len: usize| {
        (
            alloc::vec![0u32; len + 1],
            order::Scratch::with_capacity(len),
        )
    };
    let (scratch_left, scratch_right) = (scratch(left), scratch(n - left));
    let half = |is_left: bool,
                order: &mut [u32],
                sorted: &mut [Point],
                (mut members, mut scratch): (Vec<u32>, order::Scratch)| {
        // Branch-free (the side is a coin toss on unorganized input): every position is written
        // to the next free slot, which only a member keeps; the spare slot absorbs the tail.
        let len = order.len();
        let mut next = 0;
        for (i, &p) in points.iter().enumerate() {
            members[next] = i as u32;
            next = (next + usize::from(cut.is_left(p) == is_left)).min(len);
        }
        debug_assert_eq!(next, len);
        members.truncate(len);
        // The half's points in input order, for its spatial order, gathered in `sorted` itself
        // (memory: a list of its own raised the smoothing passes' peak).
        let mut spare = Vec::new();
        let gathered = if sorted.len() == len {
            sorted
        } else {
            spare.resize(len, Point::default());
            &mut spare[..]
        };
        for (slot, &i) in gathered.iter_mut().zip(&members) {
            *slot = points[i as usize];
        }
        spatial_order_into(gathered, frames, order, &mut scratch);
        for slot in order.iter_mut() {
            *slot = members[*slot as usize];
        }
        for (slot, &i) in gathered.iter_mut().zip(order.iter()) {
            *slot = frames.predicates.apply(points[i as usize]);
        }
    };
    both(
        parallel,
        || half(true, order_left, sorted_left, scratch_left),
        || half(false, order_right, sorted_right, scratch_right),
    );
    (order, sorted)
}

/// [`construct`] in one piece, in the insertion order given.
fn construct_in_order(
    points: &[Point],
    frames: &scale::Frames,
    order: Vec<u32>,
    progress: Option<&AtomicUsize>,
) -> (Vec<u32>, Vec<Point>, Built) {
    let sorted: Vec<Point> = order
        .iter()
        .map(|&i| frames.predicates.apply(points[i as usize]))
        .collect();
    let built = if frames.wide {
        build::<Exact>(&sorted, progress)
    } else {
        build::<Fast>(&sorted, progress)
    };
    (order, sorted, built)
}

/// The insertion order of `points` and, for a set cut in two ([`halves::cut`]), the left size.
fn insertion_order(
    points: &[Point],
    frames: &scale::Frames,
    parallel: bool,
    split_min: usize,
) -> (Vec<u32>, Option<usize>) {
    // The decision `construct` builds by, so the ids (and the stages' ties) follow this order:
    // a set cut in two whose distinct points are fewer than the bound is built again in one
    // piece, in that order (a review: with repeats past the bound, this order was the halves'
    // while the ids followed the one piece's).
    match cut_in_two(points, frames, split_min, parallel) {
        Some(cut) if distinct_count(points) >= split_min => (
            cut_order(points, frames, &cut, parallel, false, Default::default()).0,
            Some(cut.left_len()),
        ),
        _ => (spatial_order(points, frames), None),
    }
}

/// Where a set is built in two halves: [`halves::cut`], when each side holds a triangle (a half
/// without one cannot be built; the set is then built in one piece, in the one-piece order).
fn cut_in_two(
    points: &[Point],
    frames: &scale::Frames,
    split_min: usize,
    parallel: bool,
) -> Option<halves::Cut> {
    halves::cut(points, split_min, parallel)
        .filter(|cut| halves_have_triangles(points, frames, cut))
}

/// Whether each side of `cut` holds three points not on one line (in the predicates' frame, as
/// the halves' builders see them): exactly when neither half's build returns `None` for want of a
/// triangle ([`halves::build`]).
fn halves_have_triangles(points: &[Point], frames: &scale::Frames, cut: &halves::Cut) -> bool {
    // Per side: its first point, then a second distinct one, then whether a third leaves their line.
    let mut sides: [(Option<Point>, Option<Point>, bool); 2] = [(None, None, false); 2];
    for &p in points {
        let q = frames.predicates.apply(p);
        let side = &mut sides[usize::from(cut.is_left(p))];
        match *side {
            (_, _, true) => {}
            (None, _, _) => side.0 = Some(q),
            (Some(a), None, _) => side.1 = (q != a).then_some(q),
            (Some(a), Some(b), _) => {
                side.2 = crate::predicates::orient2d(a, b, q)
                    != crate::predicates::Orientation::Collinear
            }
        }
        if sides[0].2 && sides[1].2 {
            return true;
        }
    }
    false
}

/// How many distinct points `points` holds (`-0.0` and `0.0` one), by a sort of a copy.
fn distinct_count(points: &[Point]) -> usize {
    let mut sorted = points.to_vec();
    sorted.sort_unstable_by(|p, q| p.lexicographic_cmp(*q));
    sorted.dedup_by(|p, q| p == q);
    sorted.len()
}

/// The spatial insertion order of `points` built in one piece, decided by its distinct points
/// alone, each followed by its repeats. The order's grid and its crowded cells count points, so
/// an order of every copy changed with how often a point repeats, and on a cocircular set so did
/// the diagonals (a triangulator tester's review: a 16 x 16 grid and two far points, given six
/// times over, took other diagonals in 196 of its 496 triangles). Repeats end up side by side in
/// the order (equal points share every cell and sort together), so one scan finds them; a set
/// without repeats keeps its order.
fn spatial_order(points: &[Point], frames: &scale::Frames) -> Vec<u32> {
    let mut scratch = order::Scratch::default();
    let mut order = alloc::vec![0; points.len()];
    spatial_order_into(points, frames, &mut order, &mut scratch);
    let same = |i: u32, j: u32| points[i as usize] == points[j as usize];
    if !order.windows(2).any(|pair| same(pair[0], pair[1])) {
        return order;
    }
    // Each group of equal points by its smallest position, as the triangulation keeps it
    // (keyed once: a key read at every comparison costs a group's length each time).
    let mut groups: Vec<(u32, &[u32])> = order
        .chunk_by(|&i, &j| same(i, j))
        .map(|group| (group.iter().copied().min().unwrap_or_default(), group))
        .collect();
    groups.sort_unstable_by_key(|&(first, _)| first);
    let distinct: Vec<Point> = groups.iter().map(|&(i, _)| points[i as usize]).collect();
    let mut distinct_order = alloc::vec![0; distinct.len()];
    spatial_order_into(&distinct, frames, &mut distinct_order, &mut scratch);
    let mut repeated = Vec::with_capacity(points.len());
    for k in distinct_order {
        let (first, group) = groups[k as usize];
        repeated.push(first);
        repeated.extend(group.iter().copied().filter(|&i| i != first));
    }
    repeated
}

/// [`spatial_order`] written into `order`, sorting in `scratch`.
fn spatial_order_into(
    points: &[Point],
    frames: &scale::Frames,
    order: &mut [u32],
    scratch: &mut order::Scratch,
) {
    if frames.wide {
        // Wide sets: a logarithmic grid (on a linear one, most points share one cell).
        let smallest = order::smallest_magnitude(points);
        let warped: Vec<Point> = points
            .iter()
            .map(|p| {
                Point::new(
                    order::logarithmic(p.x, smallest),
                    order::logarithmic(p.y, smallest),
                )
            })
            .collect();
        order::insertion_order_into(&warped, order, scratch);
        order::order_warped_ties(points, &warped, order);
    } else {
        order::insertion_order_into(points, order, scratch);
    }
}

/// The mesh of `points` (in insertion order) in one piece: the reference for [`halves`]. Reports
/// like [`insert::build_into`].
fn build<K: Kernel>(points: &[Point], progress: Option<&AtomicUsize>) -> Built {
    insert::first_triangle::<K>(points)?;
    let mut arrays = MeshArrays::new(insert::half_edges(points.len()), false);
    let (mesh, merged) = insert::build_into::<K>(points, arrays.builder(0), progress)?;
    let len = mesh.len();
    Some((arrays.seal(len, points.len(), false), merged))
}

/// Below this many points, the passes after the construction run on one thread.
const PARALLEL_MIN: usize = 1 << 16;

/// The maps between vertex ids (positions in `order`) and input positions (a merged group
/// reports its smallest). With `parallel`, two threads each read the whole order and write only
/// their half; a write outside it rewrites the half's first slot, not branching.
fn vertex_maps(
    mut input_of_vertex: Vec<u32>,
    merged: &[(u32, u32)],
    parallel: bool,
) -> (Vec<u32>, Vec<VertexId>) {
    let n = input_of_vertex.len();
    let mut vertex_of_input = filled(Vec::new(), VertexId::INFINITE, n, parallel);
    let order = &input_of_vertex;
    let place = |slots: &mut [VertexId], first: usize| {
        if slots.is_empty() {
            return;
        }
        for (v, &i) in order.iter().enumerate() {
            let slot = (i as usize).wrapping_sub(first);
            let mine = slot < slots.len();
            let slot = if mine { slot } else { 0 };
            let kept = slots[slot];
            slots[slot] = if mine { VertexId::new(v as u32) } else { kept };
        }
    };
    if parallel && n >= PARALLEL_MIN {
        let middle = n / 2;
        let (low, high) = vertex_of_input.split_at_mut(middle);
        both(true, || place(low, 0), || place(high, middle));
    } else {
        for (v, &i) in input_of_vertex.iter().enumerate() {
            vertex_of_input[i as usize] = VertexId::new(v as u32);
        }
    }
    // A kept id is a vertex, never a duplicate: each pair reads what no other pair writes.
    for &(duplicate, kept) in merged {
        let (duplicate, kept_at) = (duplicate as usize, kept as usize);
        vertex_of_input[input_of_vertex[duplicate] as usize] = VertexId::new(kept);
        input_of_vertex[kept_at] = input_of_vertex[kept_at].min(input_of_vertex[duplicate]);
    }
    (input_of_vertex, vertex_of_input)
}

impl Triangulation {
    /// The order in which [`triangulate`] inserts `points`, as input positions (for a set cut in
    /// two, the left half's, then the right half's); unless all are collinear, vertex ids follow
    /// it (where exact duplicates share a vertex, [`Triangulation::input_of`] names the group's
    /// smallest position, which need not be the one inserted). The spatial sort alone: the
    /// benchmarks' yardstick for the whole build.
    ///
    /// # Errors
    /// Those of [`triangulate`]: [`Error::NonFinite`] and [`Error::TooManyPoints`].
    ///
    /// ```
    /// use condt::{mesh::VertexId, triangulate, Point, Triangulation};
    /// let pts: Vec<Point> = (0..100).map(|i| Point::new((i % 10) as f64, (i / 10) as f64)).collect();
    /// let order = Triangulation::insertion_order(&pts)?;
    /// let tri = triangulate(&pts)?;
    /// for (v, &i) in order.iter().enumerate() {
    ///     assert_eq!(tri.input_of(VertexId::new(v as u32)), i as usize);
    /// }
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn insertion_order(points: &[Point]) -> Result<Vec<u32>, Error> {
        let frames = scale::choose_frames(points)?;
        let parallel = points.len() >= PARALLEL_MIN && crate::threads::parallel_available();
        Ok(insertion_order(points, &frames, parallel, halves::SPLIT_MIN).0)
    }

    /// [`triangulate`], adding to `inserted` (`Relaxed`) every 65,536 points or so the points
    /// inserted, for a progress bar on another thread. It adds [`Triangulation::num_vertices`] in
    /// all, nothing on an error; halves rebuilt in one piece take back their count first.
    ///
    /// # Errors
    /// Those of [`triangulate`]: [`Error::NonFinite`] and [`Error::TooManyPoints`].
    ///
    /// ```
    /// use condt::{triangulate, Point, Triangulation};
    /// use core::sync::atomic::{AtomicUsize, Ordering};
    /// let mut pts: Vec<Point> = (0..3000)
    ///     .map(|i| Point::new((i * 37 % 1009) as f64, (i * 101 % 1013) as f64))
    ///     .collect();
    /// pts.push(pts[0]); // a duplicate: one vertex for two points
    /// let inserted = AtomicUsize::new(0);
    /// let tri = Triangulation::triangulate_observed(&pts, &inserted)?;
    /// assert_eq!(inserted.load(Ordering::Relaxed), tri.num_vertices());
    /// assert_eq!(tri.num_vertices(), pts.len() - 1);
    /// assert!(tri.triangles().eq(triangulate(&pts)?.triangles()));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangulate_observed(
        points: &[Point],
        inserted: &AtomicUsize,
    ) -> Result<Triangulation, Error> {
        let parallel = cfg!(feature = "parallel");
        triangulate_with(points, parallel, Some(inserted), None)
    }

    /// [`triangulate`] inserting the points in `order`, which names every input position once,
    /// on one thread: vertex ids follow `order` (unless all points are collinear), and so do
    /// the stages' ties, which go to the smaller id. A tile of a larger set, inserted in that
    /// set's [`insertion_order`](Triangulation::insertion_order) restricted to the tile, orders
    /// its vertices as the whole set does: what `condt.dask` in Python builds on.
    ///
    /// The cost is the order's: each point is found by a walk from the one inserted before, so
    /// a spatial order ([`insertion_order`](Triangulation::insertion_order)) keeps it near
    /// `triangulate`'s, while an order that jumps about can make it quadratic (a triangulator
    /// tester's review: points on a circle in a random order, where each walk crosses a fan).
    ///
    /// # Errors
    /// Those of [`triangulate`]; [`Error::InvalidParameter`] named `order` when `order` is not a
    /// permutation of `0..points.len()`: its value is `order`'s length if that differs from the
    /// number of points, else the first position repeated or out of range.
    ///
    /// ```
    /// use condt::{mesh::VertexId, triangulate, Point, Triangulation};
    /// let pts: Vec<Point> = (0..50).map(|i| Point::new(i as f64, (i as f64).sin())).collect();
    /// let order: Vec<u32> = (0..50).rev().collect();
    /// let tri = Triangulation::triangulate_in_order(&pts, &order)?;
    /// assert_eq!(tri.input_of(VertexId::new(0)), 49); // the first inserted is vertex 0
    /// let sorted = |t: &Triangulation| {
    ///     let mut all: Vec<[usize; 3]> = t.triangles().map(|mut v| { v.sort(); v }).collect();
    ///     all.sort();
    ///     all
    /// };
    /// assert_eq!(sorted(&tri), sorted(&triangulate(&pts)?)); // in general position, one answer
    /// assert!(Triangulation::triangulate_in_order(&pts, &[0, 0]).is_err());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangulate_in_order(points: &[Point], order: &[u32]) -> Result<Triangulation, Error> {
        let mut seen = alloc::vec![false; points.len()];
        let mut misfit = (order.len() != points.len()).then_some(order.len());
        for &i in order {
            match seen.get_mut(i as usize) {
                Some(slot) if !*slot => *slot = true,
                _ => {
                    misfit = misfit.or(Some(i as usize));
                    break;
                }
            }
        }
        if let Some(position) = misfit {
            return Err(Error::invalid("order", position as f64));
        }
        triangulate_in(
            points.into(),
            false,
            usize::MAX,
            None,
            None,
            Some(order.to_vec()),
        )
    }

    /// The half-edge topology, in vertex ids.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.mesh().triangles().count(), 1);
    /// assert_eq!(tri.mesh().num_vertex_ids(), 3);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }
    /// The coordinates of input point `index`: those of its vertex, so of the first of its
    /// duplicates, which are equal by value (`-0.0` and `0.0` are one point, given back as the
    /// first of them wrote it).
    ///
    /// # Panics
    /// If `index` is not an input position.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (0.0, 0.0)].map(Point::from))?;
    /// assert_eq!(tri.point(2), Point::new(0.5, 1.0));
    /// assert_eq!(tri.point(3), Point::new(0.0, 0.0)); // a merged duplicate: the same coordinates
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn point(&self, index: usize) -> Point {
        self.input_point(self.vertex(index))
    }
    /// The input coordinates of vertex `v`.
    #[inline]
    pub(crate) fn input_point(&self, v: VertexId) -> Point {
        let p = self.frame_point(v);
        // A position a smoothing pass moved, relative to the set's corner, lies within rounding
        // of the input's range: where adding the corner back rounds past the largest double, it
        // is the largest double (an infinite coordinate would be no position at all).
        let shifted = |a: f64, b: f64| {
            let sum = a + b;
            if sum.is_finite() {
                sum
            } else {
                f64::MAX.copysign(sum)
            }
        };
        match self.offset {
            Some(offset) => Point::new(shifted(p.x, offset.x), shifted(p.y, offset.y)),
            None => p,
        }
    }
    /// Vertex `v` in the frame its points were given in: [`Triangulation::input_point`] less the
    /// offset (exact, where adding the offset may round).
    #[inline]
    pub(crate) fn frame_point(&self, v: VertexId) -> Point {
        match &self.inputs {
            Some(inputs) => inputs[v.index()],
            None => self.stage_to_input.apply(self.points[v.index()]),
        }
    }
    /// This triangulation, its points given relative to `offset` (see the `offset` field).
    pub(crate) fn with_offset(self, offset: Point) -> Triangulation {
        self.with_frame_offset(Some(offset))
    }
    /// Where the input frame's zero lies in the caller's coordinates, `None` when it is theirs.
    pub(crate) fn frame_offset(&self) -> Option<Point> {
        self.offset
    }
    /// [`Triangulation::with_offset`], or in the caller's own frame for `None`.
    pub(crate) fn with_frame_offset(mut self, offset: Option<Point>) -> Triangulation {
        self.offset = offset;
        self
    }
    /// Where the input frame's zero lies in the caller's coordinates (see the `offset` field).
    pub(crate) fn offset(&self) -> Point {
        self.offset.unwrap_or(Point::new(0.0, 0.0))
    }
    /// A position in the stages' frame ([`Triangulation::vertex_point`]) in input coordinates.
    #[inline]
    pub(crate) fn stage_to_input(&self, p: Point) -> Point {
        self.stage_to_input.apply(p)
    }
    /// The vertex that input point `index` became (exact duplicates share one).
    ///
    /// # Panics
    /// If `index` is not an input position.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, 0.0)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// assert_eq!(tri.vertex(3), tri.vertex(0)); // a duplicate is merged...
    /// assert_eq!(tri.input_of(tri.vertex(3)), 0); // ...into its first position
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn vertex(&self, index: usize) -> VertexId {
        self.vertex_of_input[index]
    }
    /// The input position vertex `v` stands for (for merged duplicates, the smallest one). An
    /// id a merged duplicate left unused (no vertex has it) gives that duplicate's own position,
    /// whose [`Triangulation::vertex`] is its group's.
    ///
    /// # Panics
    /// If `v` is not a vertex id of this triangulation (for example [`VertexId::INFINITE`]).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (0.5, 0.3)].map(Point::from))?;
    /// let mut hull: Vec<usize> = tri.mesh().hull().map(|v| tri.input_of(v)).collect();
    /// hull.sort_unstable();
    /// assert_eq!(hull, vec![0, 1, 2]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn input_of(&self, v: VertexId) -> usize {
        self.input_of_vertex[v.index()] as usize
    }
    /// Number of input points, duplicates included.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (1.0, 0.0)].map(Point::from))?;
    /// assert_eq!(tri.num_points(), 4);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn num_points(&self) -> usize {
        self.vertex_of_input.len()
    }
    /// Number of distinct points, that is of mesh vertices.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (1.0, 0.0)].map(Point::from))?;
    /// assert_eq!(tri.num_vertices(), 3); // point 3 repeats point 1
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.num_vertices
    }
    /// The input position of every distinct point (the smallest of its duplicates), ascending.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.distinct_points().collect::<Vec<_>>(), vec![0, 2, 3]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn distinct_points(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.num_points()).filter(move |&i| self.first_at(i) == i)
    }
    /// The first input position at the same point as `index`: `index` itself unless it repeats
    /// an earlier point. Edges and curves name a merged duplicate by this position.
    ///
    /// # Panics
    /// If `index` is not an input position.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (1.0, 0.0)].map(Point::from))?;
    /// assert_eq!((tri.first_at(1), tri.first_at(3)), (1, 1));
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn first_at(&self, index: usize) -> usize {
        self.input_of(self.vertex(index))
    }
    /// Every exact duplicate as `[duplicate, first]`, its position and the first position at its
    /// point ([`Triangulation::first_at`]), by increasing duplicate.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (0.0, 0.0), (0.5, 1.0), (1.0, 0.0)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// assert_eq!(tri.merged().collect::<Vec<_>>(), vec![[2, 0], [4, 1]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn merged(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        (0..self.num_points())
            .map(move |i| [i, self.first_at(i)])
            .filter(|&[i, first]| first != i)
    }
    /// The real triangles as the input positions of their corners, counter-clockwise.
    ///
    /// ```
    /// use condt::predicates::{orient2d, Orientation};
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.triangles().count(), 2);
    /// let ccw = |[a, b, c]: [usize; 3]| orient2d(tri.point(a), tri.point(b), tri.point(c));
    /// assert!(tri.triangles().all(|t| ccw(t) == Orientation::Ccw));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangles(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        self.mesh
            .triangles()
            .map(|t| self.mesh.triangle_vertices(t).map(|v| self.input_of(v)))
    }
    /// Every edge once, as input positions `[a, b]` with `a < b`.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let mut edges: Vec<[usize; 2]> = tri.edges().collect();
    /// edges.sort_unstable();
    /// assert_eq!(edges, vec![[0, 1], [0, 2], [1, 2]]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn edges(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        let mesh = &self.mesh;
        mesh.edges()
            .map(|e| self.input_edge([mesh.origin(e), mesh.dest(e)]))
    }

    /// The edge `[v, w]` as input positions, smaller first.
    pub(crate) fn input_edge(&self, [v, w]: [VertexId; 2]) -> [usize; 2] {
        let (a, b) = (self.input_of(v), self.input_of(w));
        [a.min(b), a.max(b)]
    }
    /// The Delaunay neighbours of input point `index`, counter-clockwise ([`Mesh::ring`]).
    ///
    /// # Panics
    /// If `index` is not an input position.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// let mut around: Vec<usize> = tri.neighbors(0).collect();
    /// around.sort_unstable();
    /// assert_eq!(around, vec![1, 3, 4]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn neighbors(&self, index: usize) -> impl Iterator<Item = usize> + '_ {
        self.mesh
            .neighbors(self.vertex(index))
            .map(|w| self.input_of(w))
    }
    /// The convex hull as input positions, counter-clockwise from some hull point ([`Mesh::hull`]),
    /// each hull edge once (points on a hull edge included). On a collinear set the walk goes out
    /// and back along the line, so its inner points come twice; a set of one distinct point has
    /// no hull edge, and the walk is empty.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (2.0, 0.0), (1.0, 2.0), (1.0, 0.5)].map(Point::from))?;
    /// let mut hull: Vec<usize> = tri.hull().collect();
    /// hull.sort_unstable();
    /// assert_eq!(hull, vec![0, 1, 2]); // not the inner point 3
    /// let line = triangulate(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)].map(Point::from))?;
    /// let mut walked: Vec<usize> = line.hull().collect();
    /// walked.sort_unstable();
    /// assert_eq!(walked, vec![0, 1, 1, 2]); // out and back: the middle point twice
    /// let lone = triangulate(&[(1.0, 1.0), (1.0, 1.0)].map(Point::from))?;
    /// assert_eq!(lone.hull().count(), 0);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn hull(&self) -> impl Iterator<Item = usize> + '_ {
        self.mesh.hull().map(|v| self.input_of(v))
    }
    /// `true` when there is no triangle: all points are collinear or fewer than three are distinct.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let line = triangulate(&[(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)].map(Point::from))?;
    /// let bent = triangulate(&[(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)].map(Point::from))?;
    /// assert!(line.is_degenerate() && !bent.is_degenerate());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn is_degenerate(&self) -> bool {
        self.mesh.triangles().next().is_none()
    }
    /// Vertex `v` as the stages measure it: scaled by a power of two into [2^200, 2^201), so
    /// squared lengths and their products never overflow nor underflow (`docs/predicates.md`).
    #[inline]
    pub(crate) fn vertex_point(&self, v: VertexId) -> Point {
        self.points[v.index()]
    }
    /// Two points nearer than the stages measure, as input positions `(smaller, larger)`: 2^-450
    /// times the largest coordinate magnitude, below which squared lengths (and their products)
    /// leave the normal doubles (`docs/predicates.md`). Of such pairs joined by a Delaunay edge
    /// (the closest two points of a set are), the first by input positions: their lengths may
    /// all read 0 here, so the closest cannot be told. A set that is not wide has its distinct
    /// points at least 2^-252 of that magnitude apart, so only a wide one is searched.
    pub(crate) fn too_close_to_measure(&self) -> Option<(usize, usize)> {
        // In the stages' frame the largest magnitude is in [2^200, 2^201).
        const LEAST_LENGTH_EXPONENT: i32 = scale::STAGE_EXPONENT - 450;
        let least_squared = crate::geometry::pow2(2 * LEAST_LENGTH_EXPONENT);
        if !self.wide {
            return None;
        }
        let mesh = &self.mesh;
        // A collinear set's chain of segments is its edges too (`collinear.rs`).
        mesh.edges()
            .map(|e| (mesh.origin(e), mesh.dest(e)))
            .filter(|&(a, b)| self.vertex_point(a).dist2(self.vertex_point(b)) < least_squared)
            .map(|(a, b)| self.input_edge([a, b]).into())
            // By input positions: the same answer whatever the mesh's numbering (`parallel`).
            .min()
    }
    /// The input position of the first point (by input position) whose larger coordinate
    /// magnitude is the set's largest: the point that sets the scale (an error names it).
    pub(crate) fn input_of_largest(&self) -> usize {
        let magnitude = |v: VertexId| {
            let p = self.vertex_point(v);
            p.x.abs().max(p.y.abs())
        };
        let largest = self.vertices().map(magnitude).fold(0.0, f64::max);
        self.vertices()
            .filter(|&v| magnitude(v) == largest)
            .map(|v| self.input_of(v))
            .min()
            .unwrap_or(0)
    }
    /// Every [`Triangulation::vertex_point`], by vertex id (for a loop that prefetches them).
    #[inline]
    pub(crate) fn vertex_points(&self) -> &[Point] {
        &self.points
    }
    /// `true` when `v` is a mesh vertex: not a merged duplicate's id, infinite or out of range.
    #[inline]
    pub(crate) fn is_vertex(&self, v: VertexId) -> bool {
        self.input_of_vertex
            .get(v.index())
            .is_some_and(|&i| self.vertex_of_input[i as usize] == v)
    }
    /// The vertices, in id (spatial) order.
    pub(crate) fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.points.len() as u32)
            .map(VertexId::new)
            .filter(move |&v| self.is_vertex(v))
    }
    /// [`Triangulation::vertex`] for every input position at once.
    #[inline]
    pub(crate) fn input_to_vertex(&self) -> &[VertexId] {
        &self.vertex_of_input
    }
    /// Vertex position in the exactly rescaled frame the predicates work in.
    #[inline]
    pub(crate) fn scaled_point(&self, v: VertexId) -> Point {
        match &self.inputs {
            Some(inputs) => self.scale.apply(inputs[v.index()]),
            None => self.stage_to_predicates.apply(self.points[v.index()]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`triangulate_in`] afresh.
    pub(super) fn triangulate_split(
        points: &[Point],
        parallel: bool,
        split_min: usize,
        progress: Option<&AtomicUsize>,
    ) -> Result<Triangulation, Error> {
        triangulate_in(points.into(), parallel, split_min, progress, None, None)
    }

    /// The input positions of the two halves of [`halves::cut`], each in input order.
    pub(super) fn split(points: &[Point], min: usize) -> Option<(Vec<u32>, Vec<u32>)> {
        let cut = halves::cut(points, min, false)?;
        let (left, right): (Vec<u32>, Vec<u32>) =
            (0..points.len() as u32).partition(|&i| cut.is_left(points[i as usize]));
        Some((left, right))
    }

    /// The integer predicates alone, to check constructions against.
    struct Integers;

    impl Kernel for Integers {
        fn orient2d(a: Point, b: Point, c: Point) -> Orientation {
            crate::predicates::integers::orient2d(a, b, c)
        }
        fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
            crate::predicates::integers::in_circle(a, b, c, d)
        }
    }
    use crate::predicates::Orientation;
    use crate::test_rng::Xorshift;
    use alloc::vec;

    /// A review's repro: four cocircular points one unit in the last place apart and one at
    /// 1e-70 (a wide set, ordered on the logarithmic grid, which puts the four in one place).
    /// Every order of the five gives one diagonal; before, half of the 120 gave the other.
    #[test]
    fn wide_ties_do_not_follow_the_input_order() {
        let u = f64::from_bits(1f64.to_bits() + 1);
        let set = [(1.0, 1.0), (u, 1.0), (1.0, u), (u, u), (1e-70, 0.0)].map(Point::from);
        let edges_of = |points: &[Point]| {
            let tri = triangulate(points).unwrap();
            let mut edges: Vec<[(u64, u64); 2]> = tri
                .edges()
                .map(|[a, b]| {
                    let bits = |i: usize| (points[i].x.to_bits(), points[i].y.to_bits());
                    let (p, q) = (bits(a), bits(b));
                    [p.min(q), p.max(q)]
                })
                .collect();
            edges.sort_unstable();
            edges
        };
        let expected = edges_of(&set);
        let mut order = [0, 1, 2, 3, 4];
        // Every permutation, by Heap's algorithm.
        let mut counters = [0usize; 5];
        let mut k = 1;
        while k < 5 {
            if counters[k] < k {
                order.swap(if k % 2 == 0 { 0 } else { counters[k] }, k);
                let permuted = order.map(|i| set[i]);
                assert_eq!(edges_of(&permuted), expected, "{order:?}");
                counters[k] += 1;
                k = 1;
            } else {
                counters[k] = 0;
                k += 1;
            }
        }
    }

    /// A triangle's corners in the same cyclic order, starting from the smallest.
    pub(super) fn smallest_first<T: Ord + Copy>([a, b, c]: [T; 3]) -> [T; 3] {
        let first = a.min(b).min(c);
        if first == a {
            [a, b, c]
        } else if first == b {
            [b, c, a]
        } else {
            [c, a, b]
        }
    }

    /// The triangles of the mesh `build` makes, as vertex ids from the smallest, sorted; and the
    /// merged duplicates.
    fn triangles<K: Kernel>(points: &[Point]) -> (Vec<[u32; 3]>, Vec<(u32, u32)>) {
        let (mesh, merged) = build::<K>(points, None).expect("a triangle");
        let mut triangles: Vec<[u32; 3]> = mesh
            .triangles()
            .map(|t| smallest_first(mesh.triangle_vertices(t).map(|v| v.index() as u32)))
            .collect();
        triangles.sort_unstable();
        (triangles, merged)
    }

    /// The three kernels build the same triangulation on sets in the fast range: random points,
    /// a grid (cocircular everywhere) and duplicates. The same insertion order gives the same
    /// splits and flips whatever path the walk takes (only the slots triangles land in may
    /// differ, when a point on an edge is reached from the other side), so any difference is a
    /// sign the kernels disagree on.
    #[test]
    fn fast_exact_and_integer_kernels_build_the_same_mesh() {
        let mut rng = Xorshift::new(0x082e_fa98_ec4e_6c89);
        let mut sets: Vec<Vec<Point>> = Vec::new();
        sets.push(rng.unit_points(400));
        sets.push(
            (0..225)
                .map(|i| Point::new((i % 15) as f64 / 8.0, (i / 15) as f64 / 8.0))
                .collect(),
        );
        let mut repeated: Vec<Point> = (0..150)
            .map(|_| Point::new((rng.below(20) as f64) / 16.0, (rng.below(20) as f64) / 16.0))
            .collect();
        repeated.extend_from_slice(&repeated.clone()[..50]);
        sets.push(repeated);
        // Grids the small-integer path takes (integers, an offset of 10^6, binary fixed point)
        // and ones it refuses (decimal steps), in the predicates' frame, with holes.
        let power = |k: i32| Scale::power_of_two(k).apply(Point::new(1.0, 0.0)).x;
        let frame = |p: Point, scale: f64| Point::new(p.x * scale, p.y * scale);
        let holey: Vec<Point> = shuffled_grid(24, &mut rng)
            .into_iter()
            .filter(|p| (p.x as i32 * 7 + p.y as i32 * 3) % 5 != 0)
            .collect();
        for (points, scale) in [
            (holey.clone(), power(-5)),
            (moved(&holey, |p| frame(p, 0.001)), power(5)),
            (moved(&holey, |p| frame(p, 1.0 / 1024.0)), power(5)),
        ] {
            sets.push(moved(&points, |p| frame(p, scale)));
        }
        sets.push(moved(&holey, |p| {
            frame(Point::new(p.x + 1e6, p.y - 1e6), power(-20))
        }));
        for points in &sets {
            let fast = triangles::<Fast>(points);
            assert!(fast.0.len() > 100);
            assert_eq!(fast, triangles::<Exact>(points));
            assert_eq!(fast, triangles::<Integers>(points));
        }
    }

    /// The `side` x `side` integer grid, shuffled.
    fn shuffled_grid(side: usize, rng: &mut Xorshift) -> Vec<Point> {
        let mut points: Vec<Point> = (0..side * side)
            .map(|i| Point::new((i % side) as f64, (i / side) as f64))
            .collect();
        for i in (1..points.len()).rev() {
            points.swap(i, rng.below(i as u64 + 1) as usize);
        }
        points
    }

    fn moved(points: &[Point], f: impl Fn(Point) -> Point) -> Vec<Point> {
        points.iter().map(|&p| f(p)).collect()
    }

    /// Grids in every form the small-integer path takes or refuses: integers, binary fixed point,
    /// decimal steps (0.001, 0.01) that are not exact binary fractions, offsets of 10^6 exact and
    /// not, steps of 2^-30 next to 1, huge integers; whole, with holes, and with a block cut out.
    /// Each triangulates validly; a whole grid into its `2 (side - 1)^2` unit cells, any set into
    /// `2n - h - 2` triangles (h hull vertices).
    #[test]
    fn grids_triangulate_validly_in_every_form() {
        let mut rng = Xorshift::new(0x3f84_d5b5_b547_0917);
        let side = 40;
        let whole = shuffled_grid(side, &mut rng);
        let holey: Vec<Point> = whole
            .iter()
            .copied()
            .filter(|_| rng.below(10) != 0)
            .collect();
        let cut: Vec<Point> = whole
            .iter()
            .copied()
            .filter(|p| !(10.0..25.0).contains(&p.x) || !(5.0..30.0).contains(&p.y))
            .collect();
        let forms: [fn(Point) -> Point; 9] = [
            |p| p,
            |p| Point::new(p.x - 20.0, p.y - 20.0),
            |p| Point::new(p.x / 1024.0, p.y / 1024.0),
            |p| Point::new(p.x * 0.001, p.y * 0.001),
            |p| Point::new(p.x * 0.01 - 0.3, p.y * 0.01 + 7.0),
            |p| Point::new(p.x + 1e6, p.y - 1e6),
            |p| Point::new(p.x * 0.001 + 1e6, p.y * 0.001 + 1e6),
            |p| Point::new(1.0 + p.x * 2f64.powi(-30), 1.0 + p.y * 2f64.powi(-30)),
            |p| Point::new(p.x * 2f64.powi(40), p.y * -2f64.powi(40)),
        ];
        for (k, form) in forms.iter().enumerate() {
            for (set, points) in [("whole", &whole), ("holes", &holey), ("cut", &cut)] {
                let points = moved(points, form);
                let tri = triangulate(&points).unwrap();
                tri.validate()
                    .unwrap_or_else(|v| panic!("form {k}, {set}: {v:?}"));
                let (n, h) = (tri.num_vertices(), tri.hull().count());
                assert_eq!(tri.triangles().count(), 2 * n - h - 2, "form {k}, {set}");
                if set == "whole" {
                    assert_eq!(tri.triangles().count(), 2 * (side - 1) * (side - 1));
                }
            }
        }
    }

    /// The same mesh, half-edge for half-edge, and the same maps.
    fn assert_same(one: &Triangulation, two: &Triangulation, name: &str) {
        let (a, b) = (one.mesh(), two.mesh());
        assert_eq!(a.num_half_edges(), b.num_half_edges(), "{name}");
        for e in 0..a.num_half_edges() as u32 {
            let e = crate::mesh::HalfEdgeId::new(e);
            assert_eq!(a.origin(e), b.origin(e), "{name}");
            assert_eq!(a.twin(e), b.twin(e), "{name}");
        }
        assert_eq!(one.num_vertices(), two.num_vertices(), "{name}");
        for i in 0..one.num_points() {
            assert_eq!(one.vertex(i), two.vertex(i), "{name}");
        }
    }

    /// A triangulation built in the arrays of another (as the smoothing passes do)
    /// is the one built afresh, whether those arrays are larger, smaller or of a set as large,
    /// on the cut and the one-piece paths, with duplicates.
    #[test]
    fn built_in_another_triangulations_arrays_is_the_same() {
        let mut rng = Xorshift::new(0x5707_a9e5);
        let mut set = rng.unit_points(2000);
        set.extend_from_within(..300);
        let grid: Vec<Point> = (0..900)
            .map(|k| Point::new((k % 30) as f64, (k / 30) as f64))
            .collect();
        for points in [&set, &grid] {
            for split_min in [0, usize::MAX] {
                let expected = triangulate_split(points, false, split_min, None).unwrap();
                for other in [rng.unit_points(5000), rng.unit_points(50), points.clone()] {
                    let spent = triangulate(&other).unwrap();
                    for parallel in [false, true] {
                        let tri = triangulate_in(
                            points.into(),
                            parallel,
                            split_min,
                            None,
                            Some(spent.clone()),
                            None,
                        );
                        let tri = tri.unwrap();
                        assert_same(&tri, &expected, "reused");
                        assert_eq!(tri.vertex_points(), expected.vertex_points());
                        for v in 0..tri.num_points() {
                            let v = VertexId::new(v as u32);
                            assert_eq!(tri.input_of(v), expected.input_of(v));
                        }
                    }
                }
            }
        }
    }

    /// [`Triangulation::triangulate_observed`] builds what [`triangulate`] builds and its counter
    /// ends at the number of distinct points on every path: one piece, two halves (on one
    /// thread and on two, past several reports each), halves that fall back to one piece (what
    /// they counted taken back), sets without a triangle, wide sets, and no points at all.
    #[test]
    fn observed_counts_the_vertices_and_builds_what_triangulate_builds() {
        let mut rng = Xorshift::new(0x0b5e_55ed);
        let with_copies = |mut points: Vec<Point>, copies: usize| {
            for k in 0..copies {
                let copy = points[(k * 7919) % points.len()];
                points.push(copy);
            }
            points
        };
        let mut sets: Vec<(&str, Vec<Point>)> = vec![
            ("none", Vec::new()),
            ("one", vec![Point::new(1.0, 2.0)]),
            ("random", with_copies(rng.unit_points(5000), 300)),
            (
                "line",
                with_copies((0..1000).map(|i| Point::new(i as f64, 0.5)).collect(), 50),
            ),
            (
                "wide",
                (0..500)
                    .map(|k| {
                        let f = if k % 2 == 0 { 1e-200 } else { 1.0 };
                        Point::new(rng.unit() * f, rng.unit() * f)
                    })
                    .collect(),
            ),
        ];
        // Above the size the set is cut in two, with over two reports per half.
        let large = with_copies(rng.unit_points(halves::SPLIT_MIN * 5), 1000);
        assert!(halves::cut(&large, halves::SPLIT_MIN, true).is_some());
        sets.push(("halves", large));
        for (name, points) in &sets {
            let expected = triangulate(points).unwrap();
            for parallel in [false, true] {
                let inserted = AtomicUsize::new(0);
                let tri = triangulate_with(points, parallel, Some(&inserted), None).unwrap();
                assert_eq!(inserted.into_inner(), expected.num_vertices(), "{name}");
                assert_same(&tri, &expected, name);
            }
            let inserted = AtomicUsize::new(5);
            let tri = Triangulation::triangulate_observed(points, &inserted).unwrap();
            assert_eq!(inserted.into_inner(), 5 + expected.num_vertices(), "{name}");
            assert_same(&tri, &expected, name);
        }
        // Cut at any size: a column on the left and scattered points on the right (the left half
        // has no triangle, so the set is built in one piece after the right half has counted),
        // and a set whose halves stitch.
        let column: Vec<Point> = (0..400)
            .map(|k| {
                if k % 2 == 0 {
                    Point::new(0.0, k as f64)
                } else {
                    Point::new(1.0 + rng.unit(), rng.unit() * 400.0)
                }
            })
            .collect();
        let (left, right) = split(&column, 0).unwrap();
        assert_eq!((left.len(), right.len()), (200, 200));
        let inserted = AtomicUsize::new(0);
        let tri = triangulate_split(&column, true, 0, Some(&inserted)).unwrap();
        assert_eq!(inserted.into_inner(), 400);
        assert_same(&tri, &triangulate(&column).unwrap(), "column");
        let small = with_copies(rng.unit_points(3000), 100);
        let inserted = AtomicUsize::new(0);
        let tri = triangulate_split(&small, true, 0, Some(&inserted)).unwrap();
        assert!(halves::cut(&small, 0, true).is_some());
        assert_eq!(inserted.into_inner(), tri.num_vertices());
        assert_eq!(tri.num_vertices(), 3000);
        let inserted = AtomicUsize::new(0);
        let nan = [Point::new(0.0, 0.0), Point::new(f64::NAN, 0.0)];
        assert!(Triangulation::triangulate_observed(&nan, &inserted).is_err());
        assert_eq!(inserted.into_inner(), 0);
    }

    /// Points handed over ([`triangulate_owned`]) give what borrowed points give on every path:
    /// freed after the halves' order, freed and read back for halves that fall back to one piece
    /// (repeats), kept for a wide set, and the one-piece path (a line, a small set).
    #[test]
    fn owned_points_build_what_borrowed_points_build() {
        let mut rng = Xorshift::new(0x0a4e_d5e7);
        let random = rng.unit_points(halves::SPLIT_MIN + 3000);
        // Every fifth point repeated four more times: cut in two, too few distinct to stay so.
        let repeated: Vec<Point> = (0..halves::SPLIT_MIN + 5).map(|k| random[k / 5]).collect();
        let wide: Vec<Point> = random
            .iter()
            .enumerate()
            .map(|(k, &p)| if k % 2 == 0 { p.scaled(1e-210) } else { p })
            .collect();
        let line: Vec<Point> = (0..halves::SPLIT_MIN + 7)
            .map(|k| Point::new(k as f64 * 0.75, 3.0))
            .collect();
        let small = rng.unit_points(500);
        let cases = [
            ("random", &random, true),
            ("repeated", &repeated, true),
            ("wide", &wide, true),
            ("line", &line, false),
            ("small", &small, false),
        ];
        for (name, points, cut) in cases {
            let frames = choose_frames(points).unwrap();
            let halves = cut_in_two(points, &frames, halves::SPLIT_MIN, false);
            assert_eq!(halves.is_some(), cut, "{name}");
            let borrowed = triangulate(points).unwrap();
            for parallel in [false, true] {
                let owned = triangulate_with(points.clone(), parallel, None, None).unwrap();
                assert_same(&owned, &borrowed, name);
                for (i, &p) in points.iter().enumerate() {
                    assert_eq!(owned.point(i), p, "{name}");
                }
            }
        }
        assert!(distinct_count(&repeated) < halves::SPLIT_MIN);
        assert!(choose_frames(&wide).unwrap().wide);
    }

    /// The triangles in input positions, each from its smallest corner, sorted.
    fn input_triangles(tri: &Triangulation) -> Vec<[usize; 3]> {
        let mut all: Vec<[usize; 3]> = tri.triangles().map(smallest_first).collect();
        all.sort_unstable();
        all
    }

    /// The reference test of the construction in two halves ([`halves`]): above the size where
    /// [`triangulate`] cuts a set in two (the halves built at once on two threads), it builds
    /// what the sequential insertion of the whole set builds. On points in general position the
    /// Delaunay triangulation is unique: the same triangles exactly. On a grid (cocircular
    /// everywhere, so many triangulations are Delaunay) both are valid with the same count.
    #[test]
    fn halves_build_what_the_sequential_insertion_builds() {
        let mut rng = Xorshift::new(0x4a1f_5eed);
        let random = rng.unit_points(halves::SPLIT_MIN + 5000);
        let side = 260;
        let grid = shuffled_grid(side, &mut rng);
        for (name, points, general) in [("random", &random, true), ("grid", &grid, false)] {
            assert!(points.len() >= halves::SPLIT_MIN, "{name}");
            assert!(
                halves::cut(points, halves::SPLIT_MIN, true).is_some(),
                "{name}"
            );
            // The real path: built in two halves, and nothing fell back to one piece.
            assert!(built_in_two(points).is_some(), "{name}");
            let halves = triangulate_with(points, true, None, None).unwrap();
            let whole = triangulate_split(points, false, usize::MAX, None).unwrap();
            halves.validate().unwrap();
            whole.validate().unwrap();
            if general {
                assert_eq!(input_triangles(&halves), input_triangles(&whole), "{name}");
            } else {
                let count = 2 * (side - 1) * (side - 1);
                assert_eq!(halves.triangles().count(), count);
                assert_eq!(whole.triangles().count(), count);
            }
        }
    }

    /// `Triangulation::insertion_order` names the order the triangulation inserts in, so a
    /// set triangulated in it gets the same vertex ids (what `condt.dask`'s tiles build on), also
    /// where the set is cut in two but a half has no triangle and the build falls back to one
    /// piece: a line of 65,528 samples with a short curve rising from between two of them (the
    /// order of the halves was given, and the stages' ties went the other way).
    #[test]
    fn the_insertion_order_is_the_one_the_triangulation_uses() {
        let h = libm::ldexp(1.0, -15);
        let mut line: Vec<Point> = (0..65_528).map(|k| Point::new(k as f64 * h, 0.0)).collect();
        let x = (60_485.0 + 0.5) * h;
        line.extend((0..8).map(|k| Point::new(x, h + k as f64 * h * 1.01)));
        let mut rng = Xorshift::new(0x0de5);
        let scattered = rng.unit_points(halves::SPLIT_MIN + 100);
        // Past the bound only with its repeats: built again in one piece (a review found the
        // order then the halves', 0 of 80,000 ids as built).
        let mut twice: Vec<Point> = rng
            .unit_points(40_000)
            .iter()
            .map(|p| Point::new((p.x * 1e6).floor(), (p.y * 1e6).floor()))
            .collect();
        twice.extend_from_slice(&twice.clone());
        for points in [line, scattered, twice] {
            assert!(halves::cut(&points, halves::SPLIT_MIN, false).is_some());
            let order = Triangulation::insertion_order(&points).unwrap();
            let whole = triangulate(&points).unwrap();
            let in_order = Triangulation::triangulate_in_order(&points, &order).unwrap();
            assert!((0..points.len()).all(|i| whole.vertex(i) == in_order.vertex(i)));
        }
    }

    /// The mesh of `points` cut in two as [`triangulate`] cuts it, or `None` where the
    /// construction would fall back to one piece.
    fn built_in_two(points: &[Point]) -> Option<(Mesh, Vec<(u32, u32)>)> {
        let frames = scale::choose_frames(points).unwrap();
        let (order, left) = insertion_order(points, &frames, false, halves::SPLIT_MIN);
        let sorted: Vec<Point> = order
            .iter()
            .map(|&i| frames.predicates.apply(points[i as usize]))
            .collect();
        halves::build::<Fast>(&sorted, left?, false, None, Mesh::default())
    }

    /// Above the size where sealing, rescaling and the vertex maps take two threads, they give
    /// what one thread gives: the same vertex edges, stored points and maps both ways, on
    /// points in a shuffled input order with duplicates (merged into their first copy).
    #[test]
    fn passes_after_the_construction_match_on_two_threads() {
        let mut rng = Xorshift::new(0x5ea1);
        let mut points = rng.unit_points(PARALLEL_MIN + 4321);
        for k in 0..500 {
            let copy = points[(k * 131) % points.len()];
            points.push(copy);
        }
        let n = points.len();
        for k in (1..n).rev() {
            points.swap(k, rng.below(k as u64 + 1) as usize);
        }
        // The parallel passes run: the set is past their threshold and cut in two.
        assert!(n >= PARALLEL_MIN && n >= halves::SPLIT_MIN);
        assert!(halves::cut(&points, halves::SPLIT_MIN, true).is_some());
        let one = triangulate_with(&points, false, None, None).unwrap();
        let two = triangulate_with(&points, true, None, None).unwrap();
        one.validate().unwrap();
        let mesh = one.mesh();
        assert_eq!(mesh.num_half_edges(), two.mesh().num_half_edges());
        assert_eq!(mesh.num_vertex_ids(), n);
        for v in 0..n as u32 {
            let v = VertexId::new(v);
            assert_eq!(mesh.vertex_edge(v), two.mesh().vertex_edge(v));
            assert_eq!(one.input_of(v), two.input_of(v));
        }
        for i in 0..n {
            assert_eq!(one.vertex(i), two.vertex(i));
            assert_eq!(one.point(i).x.to_bits(), two.point(i).x.to_bits());
            assert_eq!(one.point(i).y.to_bits(), two.point(i).y.to_bits());
            assert_eq!(one.point(i), points[i]);
            // Every input maps to a vertex that maps back to it or to the first copy of it.
            let back = one.first_at(i);
            assert!(back <= i && points[back] == points[i]);
        }
    }
}
