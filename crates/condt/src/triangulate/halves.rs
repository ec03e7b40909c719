//! One level of divide and conquer: a vertical cut, each half built by [`insert::Builder`] in its
//! own range of one [`MeshArrays`] (at once with `parallel`), then Guibas and Stolfi's merge done
//! by flips, the mesh a sphere throughout (`docs/triangulation.md`, "Two halves").
//!
//! Owns: the cut and the stitch; signs only by the [`Kernel`], topology only through
//! [`MeshBuilder`]. A half with no triangle, or a stitch that does not add up (exact predicates
//! rule it out; the code does not assume it), returns `None`: the caller builds in one piece.

use super::insert::{self, Kernel};
use crate::geometry::Point;
use crate::mesh::{wrap3, HalfEdgeId, Mesh, MeshArrays, MeshBuilder, VertexId};
use crate::predicates::Orientation;
use crate::threads::both;
use alloc::vec::Vec;
use core::sync::atomic::AtomicUsize;

/// Smaller sets are built in one piece (a second thread gains little); the same bound on one
/// thread or two, so both give one result.
pub(crate) const SPLIT_MIN: usize = 1 << 16;

/// Buckets of x the cut falls between: within 1/1024 of the span of the median.
const BUCKETS: usize = 1024;

/// Where a set is cut ([`cut`]): the left half is the points in buckets below `boundary`.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Cut {
    low: f64,
    per_unit: f64,
    boundary: usize,
    left: usize,
}

impl Cut {
    #[inline]
    pub(crate) fn is_left(&self, p: Point) -> bool {
        bucket(p.x, self.low, self.per_unit) < self.boundary
    }
    pub(crate) fn left_len(&self) -> usize {
        self.left
    }
}

/// The bucket of `x` among [`BUCKETS`] equal ones from `low`: monotone in `x`.
#[inline]
fn bucket(x: f64, low: f64, per_unit: f64) -> usize {
    (((x - low) * per_unit) as usize).min(BUCKETS - 1)
}

/// Where to cut `points` by a vertical line between two of [`BUCKETS`] x buckets, nearest the
/// median; `None` below `min` points or when no line leaves a quarter of them on each side.
pub(crate) fn cut(points: &[Point], min: usize, parallel: bool) -> Option<Cut> {
    let n = points.len();
    if n < min.max(4) {
        return None;
    }
    let (first, second) = points.split_at(n / 2);
    let range = |part: &[Point]| {
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in part {
            low = if p.x < low { p.x } else { low };
            high = if p.x > high { p.x } else { high };
        }
        (low, high)
    };
    let ((low_a, high_a), (low_b, high_b)) = both(parallel, || range(first), || range(second));
    let (low, high) = (low_a.min(low_b), high_a.max(high_b));
    let span = high - low;
    if span <= 0.0 || !span.is_finite() {
        return None;
    }
    let per_unit = BUCKETS as f64 / span;
    let histogram = |part: &[Point]| {
        let mut counts = alloc::vec![0u32; BUCKETS];
        for p in part {
            counts[bucket(p.x, low, per_unit)] += 1;
        }
        counts
    };
    let (counts, more) = both(parallel, || histogram(first), || histogram(second));
    // The boundary `k` (left half: buckets below `k`) whose left count is nearest n / 2.
    let (mut best, mut best_count, mut below) = (0usize, 0usize, 0usize);
    for (k, (&count, &more)) in counts.iter().zip(&more).enumerate() {
        if below.abs_diff(n / 2) < best_count.abs_diff(n / 2) {
            (best, best_count) = (k, below);
        }
        below += count as usize + more as usize;
    }
    if best_count < n / 4 || n - best_count < n / 4 {
        return None;
    }
    Some(Cut {
        low,
        per_unit,
        boundary: best,
        left: best_count,
    })
}

/// The mesh of `points` (in insertion order: the left half's `left` points first), in `storage`'s
/// arrays if large enough, or `None` (module doc) after taking back what the halves counted.
pub(crate) fn build<K: Kernel>(
    points: &[Point],
    left: usize,
    parallel: bool,
    progress: Option<&AtomicUsize>,
    storage: Mesh,
) -> super::Built {
    let (left_points, right_points) = points.split_at(left);
    let left_room = insert::half_edges(left_points.len());
    let right_room = insert::half_edges(right_points.len());
    // The stitch adds two ghosts: 2(n_l + n_r) - 2 triangles in all.
    let mut arrays = MeshArrays::reusing(storage, left_room + right_room + 6, parallel);
    let (low, high) = arrays.halves(left_room);
    let (left_built, right_built) = both(
        parallel,
        move || {
            insert::build_into::<K>(left_points, low, progress)
                .map(|(mesh, merged)| (mesh.len(), merged))
        },
        move || {
            let (mut mesh, merged) = insert::build_into::<K>(right_points, high, progress)?;
            mesh.renumber(left as u32, left_room as u32);
            Some((mesh.len(), merged))
        },
    );
    let added = |built: &Option<(usize, Vec<(u32, u32)>)>, len: usize| {
        built.as_ref().map_or(0, |(_, merged)| len - merged.len())
    };
    let take_back = |count: usize| {
        if let Some(counter) = progress {
            crate::threads::count(counter, count, false);
        }
    };
    let ((left_len, mut merged), (right_len, right_merged)) = match (left_built, right_built) {
        (Some(left_built), Some(right_built)) => (left_built, right_built),
        (left_built, right_built) => {
            take_back(added(&left_built, left) + added(&right_built, points.len() - left));
            return None;
        }
    };
    if left_len < left_room {
        // Duplicates merged on the left left its range short: close the gap.
        arrays.close_gap(left_room, right_len, left_len);
    }
    merged.extend(
        right_merged
            .into_iter()
            .map(|(duplicate, kept)| (duplicate + left as u32, kept + left as u32)),
    );
    let mut mesh = arrays.builder(left_len + right_len);
    if stitch::<K>(&mut mesh, points, left_len, right_len).is_none() {
        take_back(points.len() - merged.len());
        return None;
    }
    let len = mesh.len();
    Some((arrays.seal(len, points.len(), parallel), merged))
}

/// One half's hull, counter-clockwise: `vertices[i] → vertices[i + 1]` (cyclically) is a hull
/// edge, and `ghosts[i]` the first half-edge of its ghost triangle.
struct Hull {
    vertices: Vec<VertexId>,
    ghosts: Vec<usize>,
}

impl Hull {
    /// Walks the hull of the closed mesh in the half-edges `range`, from any ghost.
    fn of(mesh: &MeshBuilder<'_>, range: core::ops::Range<usize>) -> Option<Hull> {
        let start = range
            .step_by(3)
            .find(|&base| mesh.corners_at(base).iter().any(|v| v.is_infinite()))?;
        let (mut vertices, mut ghosts) = (Vec::new(), Vec::new());
        let mut base = start;
        loop {
            let infinite = infinite_corner(mesh, base);
            // The ghost of hull edge `a → b` is `(b, a, ∞)` in some rotation.
            vertices.push(mesh.corners_at(base)[wrap3(infinite + 2)]);
            ghosts.push(base);
            // Across `∞ → b` lies the ghost of the hull edge leaving `b`.
            let (next, _) = mesh.twin(HalfEdgeId::at(base, infinite)).base_and_corner();
            if next == start {
                return Some(Hull { vertices, ghosts });
            }
            if ghosts.len() > mesh.len() {
                return None;
            }
            base = next;
        }
    }
    fn len(&self) -> usize {
        self.vertices.len()
    }
    fn ccw(&self, i: usize) -> usize {
        (i + 1) % self.len()
    }
    fn cw(&self, i: usize) -> usize {
        (i + self.len() - 1) % self.len()
    }
}

/// The corner of the ghost triangle at `base` that is the vertex at infinity.
fn infinite_corner(mesh: &MeshBuilder<'_>, base: usize) -> usize {
    let corners = mesh.corners_at(base);
    corners.iter().position(|v| v.is_infinite()).unwrap_or(0)
}

/// Joins the left mesh (half-edges `0..left_len`, the lower vertex ids) and the right one after it.
fn stitch<K: Kernel>(
    mesh: &mut MeshBuilder<'_>,
    points: &[Point],
    left_len: usize,
    right_len: usize,
) -> Option<()> {
    let left = Hull::of(mesh, 0..left_len)?;
    let right = Hull::of(mesh, left_len..left_len + right_len)?;
    let at = |v: VertexId| points[v.index()];
    let l_at = |i: usize| at(left.vertices[i]);
    let r_at = |j: usize| at(right.vertices[j]);
    // The left hull's rightmost vertex and the right hull's leftmost (all distinct points).
    let start_l = (0..left.len()).max_by(|&i, &j| l_at(i).lexicographic_cmp(l_at(j)))?;
    let start_r = (0..right.len()).min_by(|&i, &j| r_at(i).lexicographic_cmp(r_at(j)))?;
    // The tangent's walk moves each pivot at most once round its hull.
    let budget = 2 * (left.len() + right.len()) + 4;
    // A common tangent from the extreme points: each pivot steps round its hull while its next
    // vertex lies on the `away` side of the line between the pivots, or on it nearer the other
    // half, so of the points on the tangent the pivots are the two nearest each other.
    let tangent = |away: Orientation,
                   left_step: fn(&Hull, usize) -> usize,
                   right_step: fn(&Hull, usize) -> usize| {
        let (mut i, mut j) = (start_l, start_r);
        for _ in 0..budget {
            let (l, r) = (l_at(i), r_at(j));
            let next_l = left_step(&left, i);
            let side = K::orient2d(l, r, l_at(next_l));
            if side == away || (side == Orientation::Collinear && l_at(next_l).x > l.x) {
                i = next_l;
                continue;
            }
            let next_r = right_step(&right, j);
            let side = K::orient2d(l, r, r_at(next_r));
            if side == away || (side == Orientation::Collinear && r_at(next_r).x < r.x) {
                j = next_r;
                continue;
            }
            return Some((i, j));
        }
        None
    };
    // Lower tangent: every point on or above the line; upper: on or below it.
    let (i0, j0) = tangent(Orientation::Cw, Hull::cw, Hull::ccw)?;
    let (i1, j1) = tangent(Orientation::Ccw, Hull::ccw, Hull::cw)?;
    // Two new ghosts join the spheres (docs/triangulation.md, "The merge"): `below`, `(r0, l0, ∞)`,
    // between the ghosts before `l0` and after `r0`; `top`, `(l0, r0, ∞)`, between those of the
    // hull edges facing the other half (left `i0` to `i1`, right `j1` to `j0`, counter-clockwise).
    let from_infinity = |ghost: usize| HalfEdgeId::at(ghost, infinite_corner(mesh, ghost));
    let to_infinity = |ghost: usize| HalfEdgeId::at(ghost, wrap3(infinite_corner(mesh, ghost) + 2));
    let into_l0 = from_infinity(left.ghosts[left.cw(i0)]);
    let out_of_l0 = to_infinity(left.ghosts[i0]);
    let out_of_r0 = to_infinity(right.ghosts[j0]);
    let into_r0 = from_infinity(right.ghosts[right.cw(j0)]);
    let inf = VertexId::INFINITE;
    let (l0, r0) = (left.vertices[i0], right.vertices[j0]);
    let (l1, r1) = (left.vertices[i1], right.vertices[j1]);
    let below = mesh.push_triangle([r0, l0, inf]);
    let top = mesh.push_triangle([l0, r0, inf]);
    mesh.link(below.edge(0), top.edge(0));
    mesh.link(below.edge(1), into_l0);
    mesh.link(below.edge(2), out_of_r0);
    mesh.link(top.edge(1), into_r0);
    mesh.link(top.edge(2), out_of_l0);
    let top = top.edge(0).base_and_corner().0;
    // `top` is `[l, r, ∞]`: edge 0 the base `l → r`, edge 1 `r → ∞`, edge 2 `∞ → l`.
    let [t_base, t_right, t_left] = [0, 1, 2].map(|k| HalfEdgeId::at(top, k));
    let write = |mesh: &mut MeshBuilder<'_>,
                 slot: usize,
                 corners: [VertexId; 3],
                 twins: [HalfEdgeId; 3]| {
        mesh.set_corners_at(slot, corners);
        for (k, twin) in twins.into_iter().enumerate() {
            mesh.link(HalfEdgeId::at(slot, k), twin);
        }
    };
    let (mut l, mut r) = (l0, r0);
    let mut steps = 0;
    let limit = 4 * mesh.len();
    loop {
        let above =
            |x: VertexId| !x.is_infinite() && K::orient2d(at(l), at(r), at(x)) == Orientation::Ccw;
        // The left candidate `l → x`: across `∞ → l` of `top` lies the ghost `(x, l, ∞)`, and
        // across its `x → l` the triangle `(l, x, n)` (`n` is `∞` if it is a ghost too). The right
        // one mirrors it (every triangle reversed: `next` for `prev`, corners 1 and 2 exchanged):
        // `r → y`, across `r → ∞` the ghost `(r, y, ∞)`, across its `r → y` `(y, r, m)`.
        let mut candidate = |mesh: &mut MeshBuilder<'_>, left: bool| loop {
            steps += 1;
            if steps > limit {
                return None;
            }
            let fwd = |e: HalfEdgeId| if left { e.prev() } else { e.next() };
            let bwd = |e: HalfEdgeId| if left { e.next() } else { e.prev() };
            let (near, t_side) = if left { (l, t_left) } else { (r, t_right) };
            let ghost_in = mesh.twin(t_side); // l → ∞ (∞ → r)
            let e = mesh.twin(fwd(ghost_in)); // l → x (y → r)
            let far = mesh.origin(if left { e.next() } else { e });
            let apex = mesh.origin(e.prev());
            if !(above(far) && above(apex) && K::in_circle(at(l), at(r), at(far), at(apex))) {
                return Some(far);
            }
            // Flip `l – x`: `(l, x, n)` and ghost `(x, l, ∞)` turn into `(n, l, ∞)`, `(x, n, ∞)`.
            let (ghost, _) = ghost_in.base_and_corner();
            let (inner, _) = e.base_and_corner();
            let (w_far_apex, w_apex_near) = (mesh.twin(bwd(e)), mesh.twin(fwd(e)));
            let w_far = mesh.twin(bwd(ghost_in));
            let corner = |k: usize| if left { k } else { 3 - k }; // 1 or 2
            let to_inner = HalfEdgeId::at(inner, corner(1));
            let to_ghost = HalfEdgeId::at(ghost, corner(2));
            let mirrored = |[a, b, c]: [VertexId; 3], [t0, t1, t2]: [HalfEdgeId; 3]| {
                if left {
                    ([a, b, c], [t0, t1, t2])
                } else {
                    ([b, a, c], [t0, t2, t1])
                }
            };
            let (corners, twins) = mirrored([apex, near, inf], [w_apex_near, t_side, to_inner]);
            write(mesh, ghost, corners, twins);
            let (corners, twins) = mirrored([far, apex, inf], [w_far_apex, to_ghost, w_far]);
            write(mesh, inner, corners, twins);
        };
        let cand_l = candidate(mesh, true)?;
        let cand_r = candidate(mesh, false)?;
        let (left_ok, right_ok) = (above(cand_l), above(cand_r));
        if !left_ok && !right_ok {
            break;
        }
        let take_right =
            !left_ok || (right_ok && K::in_circle(at(cand_l), at(l), at(r), at(cand_r)));
        let w_base = mesh.twin(t_base);
        if take_right {
            // Flip `top`'s `r – ∞` with ghost `(r, y, ∞)`: `(l, r, y)` there, `top` is `(l, y, ∞)`.
            let ghost_in = mesh.twin(t_right);
            let (ghost, _) = ghost_in.base_and_corner();
            let (w_ry, w_y) = (mesh.twin(ghost_in.next()), mesh.twin(ghost_in.prev()));
            let w_left = mesh.twin(t_left);
            write(mesh, ghost, [l, r, cand_r], [w_base, w_ry, t_base]);
            mesh.set_corners_at(top, [l, cand_r, inf]);
            mesh.link(t_right, w_y);
            mesh.link(t_left, w_left);
            r = cand_r;
        } else {
            // Flip `top`'s `∞ – l` with ghost `(x, l, ∞)`: `(l, r, x)` there, `top` is `(x, r, ∞)`.
            let ghost_in = mesh.twin(t_left);
            let (ghost, _) = ghost_in.base_and_corner();
            let (w_xl, w_x) = (mesh.twin(ghost_in.prev()), mesh.twin(ghost_in.next()));
            let w_right = mesh.twin(t_right);
            write(mesh, ghost, [l, r, cand_l], [w_base, t_base, w_xl]);
            mesh.set_corners_at(top, [cand_l, r, inf]);
            mesh.link(t_right, w_right);
            mesh.link(t_left, w_x);
            l = cand_l;
        }
    }
    if (l, r) != (l1, r1) {
        return None;
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::super::scale;
    use super::super::tests::{split, triangulate_split};
    use super::*;
    use crate::test_rng::Xorshift;
    use alloc::format;

    /// Builds `points` cut in two, without falling back to one piece: `None` if a step failed.
    fn built_in_halves(points: &[Point]) -> Option<(Mesh, Vec<(u32, u32)>)> {
        let frames = scale::choose_frames(points).unwrap();
        let (order, left) = super::super::insertion_order(points, &frames, false, 0);
        let sorted: Vec<Point> = order
            .iter()
            .map(|&i| frames.predicates.apply(points[i as usize]))
            .collect();
        build::<super::super::insert::Fast>(&sorted, left?, false, None, Mesh::default())
    }

    /// The triangles of a triangulation in input positions, each from its smallest, sorted.
    fn triangles(tri: &super::super::Triangulation) -> Vec<[usize; 3]> {
        let mut all: Vec<[usize; 3]> = tri
            .triangles()
            .map(super::super::tests::smallest_first)
            .collect();
        all.sort_unstable();
        all
    }

    /// Sets that exercise the cut: general position, cocircular grids, duplicates on both
    /// sides, every point on the hull, a cut through clusters, and halves that meet at a
    /// collinear seam.
    fn sets() -> Vec<(&'static str, Vec<Point>)> {
        let mut rng = Xorshift::new(0x5eed_cafe);
        let mut sets = Vec::new();
        for n in [4, 5, 10, 100, 2000] {
            let uniform = rng.unit_points(n);
            sets.push(("uniform", uniform));
        }
        let grid: Vec<Point> = (0..900)
            .map(|i| Point::new((i % 30) as f64, (i / 30) as f64))
            .collect();
        sets.push(("grid", grid.clone()));
        let mut repeated: Vec<Point> = (0..600)
            .map(|_| Point::new(rng.below(25) as f64, rng.below(25) as f64))
            .collect();
        repeated.extend_from_slice(&repeated.clone()[..200]);
        sets.push(("repeated", repeated));
        let circle = (0..500)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 500.0;
                Point::new(libm::cos(t), libm::sin(t))
            })
            .collect();
        sets.push(("circle", circle));
        let clusters = (0..1500)
            .map(|k| {
                let centre = [(0.0, 0.0), (5.0, 1.0), (5.0, -3.0)][k % 3];
                let (dx, dy) = (rng.unit() - 0.5, rng.unit() - 0.5);
                Point::new(centre.0 + dx * dx * dx, centre.1 + dy * dy * dy)
            })
            .collect();
        sets.push(("clusters", clusters));
        // A vertical line of points on each side of a gap: each half is collinear.
        let columns = (0..400)
            .map(|k| Point::new(if k % 2 == 0 { 0.0 } else { 1.0 }, (k / 2) as f64))
            .collect();
        sets.push(("columns", columns));
        // Two columns per side: every hull edge facing the gap is long and collinear.
        let ladders = (0..800)
            .map(|k| Point::new((k % 4) as f64, (k / 4) as f64))
            .collect();
        sets.push(("ladders", ladders));
        // Points on a parabola opening to each side: deep, curved facing chains.
        let arcs = (0..1000)
            .map(|k| {
                let t = (k / 2) as f64 / 250.0 - 1.0;
                if k % 2 == 0 {
                    Point::new(-t * t, t)
                } else {
                    Point::new(0.01 + t * t, t + 0.001)
                }
            })
            .collect();
        sets.push(("arcs", arcs));
        sets
    }

    #[test]
    fn cut_sets_are_delaunay_and_one_thread_builds_what_two_do() {
        for (name, points) in sets() {
            let one = triangulate_split(&points, false, 0, None).unwrap();
            one.validate()
                .unwrap_or_else(|e| panic!("{name} ({} points): {e}", points.len()));
            let two = triangulate_split(&points, true, 0, None).unwrap();
            assert_eq!(triangles(&one), triangles(&two), "{name}");
            assert_eq!(
                one.mesh().num_half_edges(),
                two.mesh().num_half_edges(),
                "{name}"
            );
            for e in 0..one.mesh().num_half_edges() as u32 {
                let e = HalfEdgeId::new(e);
                assert_eq!(one.mesh().origin(e), two.mesh().origin(e), "{name}");
                assert_eq!(one.mesh().twin(e), two.mesh().twin(e), "{name}");
            }
        }
    }

    /// Every set with a triangle on each side is stitched (no fall back to one piece), and in
    /// general position the result is the one Delaunay triangulation.
    #[test]
    fn halves_stitch_without_falling_back() {
        for (name, points) in sets() {
            let Some((left, right)) = split(&points, 0) else {
                continue;
            };
            assert!(left.len() >= points.len() / 4 && right.len() >= points.len() / 4);
            let max_left = left
                .iter()
                .map(|&i| points[i as usize].x)
                .fold(f64::MIN, f64::max);
            let min_right = right
                .iter()
                .map(|&i| points[i as usize].x)
                .fold(f64::MAX, f64::min);
            assert!(max_left < min_right, "{name}");
            if name == "columns" || left.len() < 3 || right.len() < 3 {
                assert!(built_in_halves(&points).is_none(), "{name}");
                continue;
            }
            assert!(
                built_in_halves(&points).is_some(),
                "{name} {} {}",
                left.len(),
                right.len()
            );
            if name == "uniform" {
                let whole = triangulate_split(&points, false, usize::MAX, None).unwrap();
                let cut = triangulate_split(&points, false, 0, None).unwrap();
                assert_eq!(triangles(&whole), triangles(&cut), "{name}");
            }
        }
    }

    /// Many small random sets, cut at any size: integer coordinates from a small range (full of
    /// cocircular quadruples, collinear runs and duplicates) and points in general position,
    /// where the cut must give the one Delaunay triangulation that the whole construction gives.
    #[test]
    fn random_sets_cut_in_two_are_delaunay() {
        let mut rng = Xorshift::new(0x0dd_ba11);
        for round in 0..300 {
            let n = 3 + rng.below(300) as usize;
            let range = 2 + rng.below(40);
            let integers = round % 2 == 0;
            let points: Vec<Point> = (0..n)
                .map(|_| {
                    if integers {
                        Point::new(rng.below(range) as f64, rng.below(range) as f64)
                    } else {
                        Point::new(rng.unit(), rng.unit() * 0.1)
                    }
                })
                .collect();
            let cut = triangulate_split(&points, false, 0, None).unwrap();
            cut.validate()
                .unwrap_or_else(|e| panic!("round {round}, {n} points: {e}"));
            if !integers {
                let whole = triangulate_split(&points, false, usize::MAX, None).unwrap();
                assert_eq!(triangles(&whole), triangles(&cut), "round {round}");
            }
        }
    }

    #[test]
    fn uniform_points_stitch() {
        let mut rng = Xorshift::new(7);
        for n in [10, 100, 1000, 5000, 300_000] {
            let points = rng.unit_points(n);
            assert!(built_in_halves(&points).is_some(), "{n}");
            let tri = triangulate_split(&points, false, 0, None).unwrap();
            tri.validate().unwrap();
        }
    }

    /// Uniform sets and points on overlapping ellipses (tiny clusters of curves, as curve
    /// reconstruction gives) are stitched at every size, none built in one piece (what a
    /// by-hand harness once counted at these sizes; the timing is `benches/halves.rs`).
    #[test]
    fn uniform_and_ellipse_sets_stitch_at_every_size() {
        let mut rng = Xorshift::new(77);
        for (n, sets) in [(100usize, 40), (1000, 20), (10_000, 4), (100_000, 1)] {
            for round in 0..sets {
                let uniform = rng.unit_points(n);
                assert!(
                    built_in_halves_any(&uniform).is_some(),
                    "uniform {n} {round}"
                );
                let ellipses: Vec<Point> = (0..n)
                    .map(|k| {
                        let e = (k % 10) as f64;
                        let t = rng.unit() * core::f64::consts::TAU;
                        Point::new(e * 0.7 + 1.2 * libm::cos(t), (e % 3.0) + 0.7 * libm::sin(t))
                    })
                    .collect();
                assert!(
                    built_in_halves_any(&ellipses).is_some(),
                    "ellipses {n} {round}"
                );
            }
        }
    }

    // ---- Degenerate and adversarial inputs: each set through `check` ----

    /// Whether the points make a proper triangle (exact).
    fn has_triangle(points: &[Point]) -> bool {
        super::super::insert::first_triangle::<super::super::insert::Exact>(points).is_some()
    }

    /// [`built_in_halves`] with the kernel the construction would choose.
    fn built_in_halves_any(points: &[Point]) -> Option<(Mesh, Vec<(u32, u32)>)> {
        let frames = scale::choose_frames(points).unwrap();
        let (order, left) = super::super::insertion_order(points, &frames, false, 0);
        let sorted: Vec<Point> = order
            .iter()
            .map(|&i| frames.predicates.apply(points[i as usize]))
            .collect();
        if frames.wide {
            build::<super::super::insert::Exact>(&sorted, left?, false, None, Mesh::default())
        } else {
            build::<super::super::insert::Fast>(&sorted, left?, false, None, Mesh::default())
        }
    }

    /// Whether `points` is cut in two halves that each have a triangle and yet the stitch
    /// fails (the construction then builds the set in one piece: correct but slower).
    fn falls_back(points: &[Point]) -> bool {
        let Some((left, right)) = split(points, 0) else {
            return false;
        };
        let gather = |ids: &[u32]| ids.iter().map(|&i| points[i as usize]).collect::<Vec<_>>();
        has_triangle(&gather(&left))
            && has_triangle(&gather(&right))
            && built_in_halves_any(points).is_none()
    }

    /// The smallest subset of `points` (removing one point at a time) that still falls back to
    /// one piece: printed when a set does, for a test case small enough to read.
    fn shrunk(points: &[Point]) -> Vec<(f64, f64)> {
        let mut pts = points.to_vec();
        let mut k = 0;
        while k < pts.len() {
            let mut fewer = pts.clone();
            fewer.remove(k);
            if falls_back(&fewer) {
                pts = fewer;
            } else {
                k += 1;
            }
        }
        pts.iter().map(|p| (p.x, p.y)).collect()
    }

    /// Everything checked on one set: `validate()` on the cut, the same mesh on one thread and
    /// two (the halves built at once: `triangulate_split` with a cut at any size), (in general
    /// position) the triangles of the one-piece construction, and no fall back to one piece
    /// when each half has a triangle (else the smallest such subset is printed).
    fn check(name: &str, points: &[Point], general: bool) {
        let one = triangulate_split(points, false, 0, None).unwrap();
        one.validate()
            .unwrap_or_else(|e| panic!("{name} ({} points): {e}", points.len()));
        let two = triangulate_split(points, true, 0, None).unwrap();
        assert_eq!(triangles(&one), triangles(&two), "{name}: threads");
        for e in 0..one.mesh().num_half_edges() as u32 {
            let e = HalfEdgeId::new(e);
            assert_eq!(one.mesh().origin(e), two.mesh().origin(e), "{name}");
            assert_eq!(one.mesh().twin(e), two.mesh().twin(e), "{name}");
        }
        if general {
            let whole = triangulate_split(points, false, usize::MAX, None).unwrap();
            assert_eq!(
                triangles(&whole),
                triangles(&one),
                "{name}: against one piece"
            );
        }
        if falls_back(points) {
            panic!(
                "{name}: built in one piece; smallest such subset: {:?}",
                shrunk(points)
            );
        }
    }

    fn shuffle(rng: &mut Xorshift, points: &mut [Point]) {
        for i in (1..points.len()).rev() {
            let j = rng.below(i as u64 + 1) as usize;
            points.swap(i, j);
        }
    }

    /// Lattice points on the circle of radius `r` centred at `(cx, cy)`.
    fn lattice_circle(r: i64, cx: f64, cy: f64) -> Vec<Point> {
        let mut out = Vec::new();
        for x in -r..=r {
            let y2 = r * r - x * x;
            let y = libm::sqrt(y2 as f64) as i64;
            for y in [y - 1, y, y + 1] {
                if y >= 0 && y * y == y2 {
                    out.push(Point::new(cx + x as f64, cy + y as f64));
                    if y != 0 {
                        out.push(Point::new(cx + x as f64, cy - y as f64));
                    }
                }
            }
        }
        out
    }

    /// Sets the first version of the stitch could not join (it built them in one piece), each
    /// with a triangle on both sides. It kept the region still to fill as triangles cut out of
    /// the mesh, which cannot hold an edge Guibas and Stolfi keep with that region on both
    /// sides, nor a region that touches a vertex twice.
    #[test]
    fn stitch_joins_what_a_cut_out_region_could_not() {
        let sets: [&[(f64, f64)]; 7] = [
            // The right hull's only corner on the merged hull is its rightmost point: both
            // tangents end there and every right hull edge faces the left half.
            &[
                (3.0, 6.0),
                (4.0, 3.0),
                (0.0, 7.0),
                (2.0, 0.0),
                (6.0, 0.0),
                (4.0, 2.0),
            ],
            // The left half's one triangle fails the circle test: its two facing hull edges
            // stay, with the region to fill on both sides.
            &[
                (1.0, 2.0),
                (2.0, 3.0),
                (3.0, 5.0),
                (2.0, 0.0),
                (5.0, 0.0),
                (3.0, 2.0),
            ],
            &[
                (4.0, 4.0),
                (1.0, 2.0),
                (6.0, 4.0),
                (5.0, 1.0),
                (3.0, 4.0),
                (6.0, 6.0),
            ],
            &[
                (8.0, -2.0),
                (10.0, 2.0),
                (7.0, 2.0),
                (9.0, -2.0),
                (0.0, 1.0),
                (3.0, 2.5),
            ],
            &[
                (3.0, 0.8999046728845453),
                (4.0, 0.32050799204832137),
                (2.0, 0.924499420195516),
                (6.0, 0.8963817388261929),
                (1.0, 0.767425441880306),
                (5.0, 0.8038272623815764),
            ],
            // Collinear runs on both tangents.
            &[
                (2.0, 0.0),
                (2.0, 3.0),
                (1.0, 0.0),
                (1.0, 3.0),
                (1.0, 4.0),
                (1.0, 6.0),
                (1.0, 0.0),
                (3.0, 7.0),
                (2.0, 7.0),
                (3.0, -2.0),
                (0.0, 6.0),
                (1.0, 9.0),
            ],
            // General position: deletions on the right reach the upper tangent's right end,
            // whose uncovered side then touches the region to fill twice.
            &[
                (0.9562619857374105, 0.3882328043931498),
                (0.6957032236326658, 0.24352622521143175),
                (0.6408025313235827, 0.28372443267246494),
                (0.012449053719118086, 0.37587507343186255),
                (0.2843238959621691, 0.7192283999303851),
                (0.5211621814574898, 0.8442664460402897),
                (0.13060461660859535, 0.26497211557375966),
                (0.2771024889425152, 0.18178433545134542),
                (0.6077626588306797, 0.7956436344761829),
                (0.8663812949151619, 0.18401490289780176),
                (0.5958966797714078, 0.11171079229191738),
                (0.6000071891035085, 0.1607483001891319),
                (0.5207561906462116, 0.8103598262020495),
                (0.026597939553836936, 0.46682751685387625),
                (0.2569153635894307, 0.7512601199539931),
                (0.1664619743217245, 0.6519467920089129),
                (0.9984257671487117, 0.08742068104347556),
                (0.5162301402012168, 0.6292081185331877),
                (0.5965778176167712, 0.5497231006839393),
                (0.2127684723307146, 0.20364523584194194),
                (0.22350374581004673, 0.9997473434668604),
                (0.7604333254886454, 0.45295180107068833),
                (0.4492010488257123, 0.9896286187509409),
                (0.6734624958837111, 0.2775927226145576),
                (0.4120707635206924, 0.8960974831930111),
                (0.4410855999043356, 0.8513696484986122),
                (0.745799134291924, 0.6535728245748861),
                (0.07212801869908181, 0.06794866424416268),
                (0.08743851173525485, 0.10886835429111485),
                (0.5728754473128364, 0.16786415667969445),
                (0.9853396175274628, 0.42077785022959313),
                (0.6820595015499685, 0.7669083171530872),
            ],
        ];
        for (k, set) in sets.iter().enumerate() {
            let points: Vec<Point> = set.iter().map(|&(x, y)| Point::new(x, y)).collect();
            assert!(built_in_halves_any(&points).is_some(), "set {k}");
            check(&format!("set {k}"), &points, k == 6);
        }
    }

    #[test]
    fn cocircular_sets_across_the_seam() {
        for r in [5, 25, 65, 85, 325, 1105] {
            let mut pts = lattice_circle(r, 0.0, 0.0);
            check(&format!("circle {r}"), &pts, false);
            pts.push(Point::new(0.0, 0.0));
            check(&format!("circle {r} + centre"), &pts, false);
            // Two concentric cocircular rings.
            let mut rings = lattice_circle(r, 0.0, 0.0);
            rings.extend(lattice_circle(5 * r, 0.0, 0.0));
            check(&format!("rings {r}"), &rings, false);
        }
        // Random subsets of a big lattice circle.
        let all = lattice_circle(5525, 0.0, 0.0);
        let mut rng = Xorshift::new(99);
        for round in 0..200 {
            let keep = 4 + rng.below(all.len() as u64 - 4) as usize;
            let mut pts = all.clone();
            shuffle(&mut rng, &mut pts);
            pts.truncate(keep);
            check(&format!("subset {round}"), &pts, false);
        }
    }

    #[test]
    fn small_random_sets() {
        let mut rng = Xorshift::new(0xfeed_beef);
        for round in 0..4000 {
            let n = 4 + rng.below(40) as usize;
            let kind = round % 5;
            let range = 2 + rng.below(8);
            let points: Vec<Point> = (0..n)
                .map(|_| match kind {
                    0 => Point::new(rng.below(range) as f64, rng.below(range) as f64),
                    1 => Point::new(rng.unit(), rng.unit()),
                    2 => Point::new(rng.below(range) as f64, rng.unit()),
                    3 => Point::new(rng.unit(), rng.below(range) as f64),
                    _ => {
                        let t = rng.below(range) as f64;
                        Point::new(t, 2.0 * t + rng.below(2) as f64)
                    }
                })
                .collect();
            check(&format!("round {round} kind {kind}"), &points, kind == 1);
        }
    }

    #[test]
    fn facing_arcs() {
        // Two facing arcs of circles, deep merges: left arc bulging right, right arc bulging
        // left, and the mirror (bulging away).
        for n in [10usize, 50, 300, 2000] {
            for (bulge, gap) in [(1.0, 0.01), (-1.0, 0.01), (1.0, 2.0), (1.0, 1e-9)] {
                let mut pts = Vec::new();
                for k in 0..n {
                    let t = (k as f64 / (n - 1) as f64 - 0.5) * 2.0;
                    let dx = bulge * (1.0 - t * t);
                    pts.push(Point::new(-gap + dx, t));
                    pts.push(Point::new(gap - dx + 3.0 * bulge.max(0.0), t + 1e-3));
                }
                check(&format!("arcs {n} {bulge} {gap}"), &pts, false);
            }
        }
        // Two facing lattice half circles from the same circle: every point cocircular.
        let pts: Vec<Point> = lattice_circle(1105, 0.0, 0.0);
        check("one lattice circle", &pts, false);
    }

    #[test]
    fn collinear_tangents() {
        let mut rng = Xorshift::new(3);
        for round in 0..500 {
            let n = 8 + rng.below(60) as usize;
            let w = 4 + rng.below(20);
            let mut pts = Vec::new();
            // Bottom and top lines across both halves, and random lattice points between.
            let slope = rng.below(3) as f64 - 1.0;
            for x in 0..w {
                if rng.below(3) > 0 {
                    pts.push(Point::new(x as f64, slope * x as f64));
                }
                if rng.below(3) > 0 {
                    pts.push(Point::new(x as f64, slope * x as f64 + 10.0));
                }
            }
            for _ in 0..n {
                let x = rng.below(w);
                pts.push(Point::new(
                    x as f64,
                    slope * x as f64 + 1.0 + rng.below(9) as f64,
                ));
            }
            shuffle(&mut rng, &mut pts);
            check(&format!("tangent lines {round}"), &pts, false);
        }
    }

    #[test]
    fn one_half_tiny_or_collinear() {
        let mut rng = Xorshift::new(11);
        for round in 0..2000 {
            let n_left = 3 + rng.below(6) as usize;
            let n_right = n_left + rng.below(3) as usize;
            let mut pts = Vec::new();
            let collinear_left = round % 3 == 0;
            for _ in 0..n_left {
                if collinear_left {
                    let t = rng.below(5) as f64;
                    pts.push(Point::new(t, t * 0.5 + 1.0));
                } else {
                    pts.push(Point::new(rng.below(5) as f64, rng.below(5) as f64));
                }
            }
            for _ in 0..n_right {
                pts.push(Point::new(
                    6.0 + rng.below(5) as f64,
                    rng.below(5) as f64 - 2.0,
                ));
            }
            shuffle(&mut rng, &mut pts);
            check(&format!("tiny {round}"), &pts, false);
        }
    }

    #[test]
    fn wide_sets() {
        let mut rng = Xorshift::new(17);
        for round in 0..300 {
            let n = 8 + rng.below(200) as usize;
            let tiny = [1e-70, 1e-200, 1e-300, 5e-324][round % 4];
            let pts: Vec<Point> = (0..n)
                .map(|k| {
                    if k % 2 == 0 {
                        Point::new(rng.unit() * tiny, rng.unit() * tiny)
                    } else {
                        Point::new(0.5 + rng.unit(), rng.unit() - 0.5)
                    }
                })
                .collect();
            check(&format!("wide {round}"), &pts, false);
            // Integers times a tiny and a huge factor: cocircular and collinear runs.
            let pts: Vec<Point> = (0..n)
                .map(|k| {
                    let f = if k % 3 == 0 { tiny } else { 1.0 };
                    Point::new(
                        (rng.below(6) as f64 + if k % 3 == 0 { 0.0 } else { 7.0 }) * f,
                        rng.below(6) as f64 * f,
                    )
                })
                .collect();
            check(&format!("wide lattice {round}"), &pts, false);
        }
    }

    #[test]
    fn scales_and_slivers() {
        let mut rng = Xorshift::new(23);
        for round in 0..600 {
            let n = 6 + rng.below(150) as usize;
            let scale = [1e-300, 1e-160, 1.0, 1e160, 1e300, 4e-320][round % 6];
            let thin = [1e-3, 1e-9, 1e-15, 0.0][(round / 6) % 4];
            let pts: Vec<Point> = (0..n)
                .map(|k| {
                    let x = rng.unit();
                    let y = if k % 7 == 0 {
                        rng.unit() * 1e-3
                    } else {
                        (x - 0.5) * thin
                    };
                    Point::new(x * scale, y * scale)
                })
                .collect();
            check(&format!("sliver {round}"), &pts, false);
        }
    }

    #[test]
    fn grids_with_holes_and_duplicates() {
        let mut rng = Xorshift::new(31);
        for round in 0..300 {
            let w = 3 + rng.below(25);
            let h = 2 + rng.below(25);
            let mut pts = Vec::new();
            for i in 0..w * h {
                let (x, y) = ((i % w) as f64, (i / w) as f64);
                let hole = (x - w as f64 / 2.0).abs() < 2.0 && (y - h as f64 / 2.0).abs() < 2.0;
                if !hole && rng.below(10) > 0 {
                    pts.push(Point::new(x, y));
                    if rng.below(5) == 0 {
                        pts.push(Point::new(x, y));
                    }
                }
            }
            shuffle(&mut rng, &mut pts);
            check(&format!("grid {round} {w}x{h}"), &pts, false);
        }
    }

    /// A longer sweep of random sets (a correctness check too slow for every run: by hand,
    /// `cargo test -p condt --lib long_fuzz -- --ignored`).
    #[test]
    #[ignore]
    #[cfg(feature = "std")]
    fn long_fuzz() {
        let mut rng = Xorshift::new(0xabad_1dea);
        for round in 0..20000 {
            let n = 4 + rng.below(if round % 10 == 0 { 3000 } else { 120 }) as usize;
            let kind = round % 6;
            let range = 2 + rng.below(30);
            let points: Vec<Point> = (0..n)
                .map(|_| match kind {
                    0 => Point::new(rng.below(range) as f64, rng.below(range) as f64),
                    1 => Point::new(rng.unit(), rng.unit()),
                    2 => {
                        let t = rng.unit() * core::f64::consts::TAU;
                        let r = 1.0 + rng.below(3) as f64;
                        Point::new(r * libm::cos(t), r * libm::sin(t) * 0.3)
                    }
                    3 => Point::new(rng.unit(), rng.unit() * 1e-6),
                    4 => {
                        let k = rng.below(range) as f64;
                        let side = if rng.below(2) == 0 { -1.0 } else { 1.0 };
                        Point::new(side * (1.0 + k * k * 0.01), k)
                    }
                    _ => {
                        let f = if rng.below(2) == 0 { 1e-100 } else { 1.0 };
                        Point::new(rng.below(range) as f64 * f, rng.below(range) as f64 * f)
                    }
                })
                .collect();
            check(&format!("long {round} kind {kind}"), &points, kind == 1);
        }
    }
}
