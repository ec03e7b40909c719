//! Divide and conquer, one level: a large set is cut by a vertical line into two halves, each
//! half is built by incremental insertion (at the same time on two threads with `parallel`), and
//! the two meshes are stitched into the Delaunay triangulation of the whole set.
//!
//! Owns: the cut and the stitch. It decides signs only through the
//! construction's [`Kernel`] and writes topology only through [`MeshBuilder`]; each half is an
//! ordinary [`insert::Builder`] run, in its own range of one [`MeshArrays`].
//!
//! The cut depends only on the set of points (never on their order or on the number of threads),
//! so the triangulation stays a function of the set, and a sequential run builds exactly the mesh a
//! parallel one does. Any step that cannot go as planned (a half with no triangle; a stitch
//! whose bookkeeping does not add up, which exact predicates rule out but the code does not
//! assume) returns `None`, and the caller builds the whole set in one piece instead.
//!
//! The stitch is Guibas and Stolfi's merge ("Primitives for the manipulation of general
//! subdivisions and the computation of Voronoi diagrams", ACM TOG 4(2), 1985) on this crate's
//! triangles: the two hulls are strictly apart, so their lower common tangent exists; from it a
//! base edge climbs, at each step joining the candidate of either half that the empty-circle
//! test picks, after deleting that half's triangles the new triangle's circle would contain. It
//! ends at the upper tangent. Deleted triangles and the ghosts of the hull edges facing the
//! other half free exactly as many slots as the merge makes triangles; the two new ghosts on
//! the tangents take two slots reserved for them. Only triangles near the seam change
//! (`docs/triangulation.md`).

use super::insert::{self, Kernel};
use crate::geometry::Point;
use crate::mesh::{wrap3, HalfEdgeId, Mesh, MeshArrays, MeshBuilder, VertexId};
use crate::predicates::Orientation;
use alloc::vec::Vec;

/// Sets with fewer points are built in one piece. Below it the second thread gains little (the
/// whole construction takes under 20 ms); the same bound decides sequential and parallel runs.
pub(crate) const SPLIT_MIN: usize = 1 << 16;

/// Buckets of x the cut is chosen among: it falls between two of them, so it is set within
/// 1/1024 of the span of the median.
const BUCKETS: usize = 1024;

/// The input positions of the two halves, left and right of a vertical line, each in input
/// order; `None` when the set has fewer than `min` points or no such line leaves at least a
/// quarter of them on each side (most points sharing a few x).
///
/// The line lies between two of [`BUCKETS`] equal buckets of the x span; a bucket's index is
/// monotone in x, so every point of the left half lies strictly left of every point of the
/// right one, and points with the same x (duplicates among them) fall on the same side.
pub(crate) fn split(points: &[Point], min: usize) -> Option<(Vec<u32>, Vec<u32>)> {
    let n = points.len();
    if n < min.max(4) {
        return None;
    }
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        low = if p.x < low { p.x } else { low };
        high = if p.x > high { p.x } else { high };
    }
    let span = high - low;
    if span <= 0.0 || !span.is_finite() {
        return None;
    }
    let per_unit = BUCKETS as f64 / span;
    let bucket = |x: f64| (((x - low) * per_unit) as usize).min(BUCKETS - 1);
    let mut counts = [0usize; BUCKETS];
    for p in points {
        counts[bucket(p.x)] += 1;
    }
    // The boundary `k` (left half: buckets below `k`) whose left count is nearest n / 2.
    let (mut best, mut best_count, mut below) = (0usize, 0usize, 0usize);
    for (k, &count) in counts.iter().enumerate() {
        if below.abs_diff(n / 2) < best_count.abs_diff(n / 2) {
            (best, best_count) = (k, below);
        }
        below += count;
    }
    if best_count < n / 4 || n - best_count < n / 4 {
        return None;
    }
    let mut left = Vec::with_capacity(best_count);
    let mut right = Vec::with_capacity(n - best_count);
    for (i, p) in points.iter().enumerate() {
        if bucket(p.x) < best {
            left.push(i as u32);
        } else {
            right.push(i as u32);
        }
    }
    Some((left, right))
}

/// The mesh of `points` (in insertion order: the left half's `left` points first, then the right
/// half's) and the `(duplicate, kept)` pairs merged on the way, or `None` when a half has no
/// triangle or the stitch fails.
pub(crate) fn build<K: Kernel>(
    points: &[Point],
    left: usize,
    parallel: bool,
) -> Option<(Mesh, Vec<(u32, u32)>)> {
    let (left_points, right_points) = points.split_at(left);
    let left_room = insert::half_edges(left_points.len());
    let right_room = insert::half_edges(right_points.len());
    // The stitch adds two ghosts: 2(n_l + n_r) - 2 triangles in all.
    let mut arrays = MeshArrays::new(left_room + right_room + 6, parallel);
    let (low, high) = arrays.halves(left_room);
    let (left_built, right_built) = super::both(
        parallel,
        move || {
            insert::build_into::<K>(left_points, low).map(|(mesh, merged)| (mesh.len(), merged))
        },
        move || {
            let (mut mesh, merged) = insert::build_into::<K>(right_points, high)?;
            mesh.renumber(left as u32, left_room as u32);
            Some((mesh.len(), merged))
        },
    );
    let ((left_len, mut merged), (right_len, right_merged)) = (left_built?, right_built?);
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
    stitch::<K>(&mut mesh, points, left_len, right_len)?;
    let len = mesh.len();
    Some((arrays.seal(len, points.len()), merged))
}

/// One half's hull, counter-clockwise: `vertices[i] → vertices[i + 1]` (cyclically) is a hull
/// edge, and `ghosts[i]` the first half-edge of its ghost triangle.
struct Hull {
    vertices: Vec<VertexId>,
    ghosts: Vec<usize>,
}

impl Hull {
    /// Walks the hull of the mesh in the half-edges `range` (a closed sphere), from any ghost.
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
        if i + 1 == self.len() {
            0
        } else {
            i + 1
        }
    }

    fn cw(&self, i: usize) -> usize {
        if i == 0 {
            self.len() - 1
        } else {
            i - 1
        }
    }
}

/// The corner of the ghost triangle at `base` that is the vertex at infinity.
fn infinite_corner(mesh: &MeshBuilder<'_>, base: usize) -> usize {
    let corners = mesh.corners_at(base);
    corners.iter().position(|v| v.is_infinite()).unwrap_or(0)
}

/// Joins the two meshes in `mesh` (the left one in half-edges `0..left_len`, the right one after
/// it; vertex ids of the left half below those of the right) and flips until Delaunay.
fn stitch<K: Kernel>(
    mesh: &mut MeshBuilder<'_>,
    points: &[Point],
    left_len: usize,
    right_len: usize,
) -> Option<()> {
    let left = Hull::of(mesh, 0..left_len)?;
    let right = Hull::of(mesh, left_len..left_len + right_len)?;
    let at = |v: VertexId| points[v.index()];
    let (l_at, r_at) = (
        |i: usize| at(left.vertices[i]),
        |j: usize| at(right.vertices[j]),
    );
    let orient = |a: Point, b: Point, c: Point| K::orient2d(a, b, c);
    let extreme = |hull: &Hull, rightmost: bool| {
        (0..hull.len()).max_by(|&i, &j| {
            let (p, q) = (at(hull.vertices[i]), at(hull.vertices[j]));
            let order = p.lexicographic_cmp(q);
            if rightmost {
                order
            } else {
                order.reverse()
            }
        })
    };
    let (start_l, start_r) = (extreme(&left, true)?, extreme(&right, false)?);
    // The tangent's walk moves each pivot at most once round its hull.
    let budget = 2 * (left.len() + right.len()) + 4;

    // Lower tangent: every point on or above the line from left pivot to right pivot; among
    // points on it, the pivots are the two nearest each other.
    let (mut i0, mut j0) = (start_l, start_r);
    let mut steps = 0;
    loop {
        steps += 1;
        if steps > budget {
            return None;
        }
        let (l, r) = (l_at(i0), r_at(j0));
        let down_l = left.cw(i0);
        match orient(l, r, l_at(down_l)) {
            Orientation::Cw => {
                i0 = down_l;
                continue;
            }
            Orientation::Collinear if l_at(down_l).x > l.x => {
                i0 = down_l;
                continue;
            }
            _ => {}
        }
        let down_r = right.ccw(j0);
        match orient(l, r, r_at(down_r)) {
            Orientation::Cw => j0 = down_r,
            Orientation::Collinear if r_at(down_r).x < r.x => j0 = down_r,
            _ => break,
        }
    }
    // Upper tangent, the mirror image.
    let (mut i1, mut j1) = (start_l, start_r);
    steps = 0;
    loop {
        steps += 1;
        if steps > budget {
            return None;
        }
        let (l, r) = (l_at(i1), r_at(j1));
        let up_l = left.ccw(i1);
        match orient(l, r, l_at(up_l)) {
            Orientation::Ccw => {
                i1 = up_l;
                continue;
            }
            Orientation::Collinear if l_at(up_l).x > l.x => {
                i1 = up_l;
                continue;
            }
            _ => {}
        }
        let up_r = right.cw(j1);
        match orient(l, r, r_at(up_r)) {
            Orientation::Ccw => j1 = up_r,
            Orientation::Collinear if r_at(up_r).x < r.x => j1 = up_r,
            _ => break,
        }
    }

    // The ghosts beside the tangents stay: before `l0` and after `r0` below, before `r1` and
    // after `l1` above. Read before anything changes.
    let from_infinity = |ghost: usize| HalfEdgeId::at(ghost, infinite_corner(mesh, ghost));
    let to_infinity = |ghost: usize| HalfEdgeId::at(ghost, wrap3(infinite_corner(mesh, ghost) + 2));
    let hull_edge = |ghost: usize| HalfEdgeId::at(ghost, wrap3(infinite_corner(mesh, ghost) + 1));
    let into_l0 = from_infinity(left.ghosts[left.cw(i0)]);
    let out_of_r0 = to_infinity(right.ghosts[j0]);
    let into_r1 = from_infinity(right.ghosts[right.cw(j1)]);
    let out_of_l1 = to_infinity(left.ghosts[i1]);
    let mut e_l = mesh.twin(hull_edge(left.ghosts[i0]));
    let mut f_r = mesh.twin(hull_edge(right.ghosts[right.cw(j0)]));

    // The ghosts of the hull edges facing the other half (left: from `i0` counter-clockwise to
    // `i1`; right: from `j1` counter-clockwise to `j0`) go: their slots take the new triangles.
    let mut free = Vec::new();
    let mut i = i0;
    while i != i1 {
        free.push(left.ghosts[i]);
        i = left.ccw(i);
    }
    let mut j = j1;
    while j != j0 {
        free.push(right.ghosts[j]);
        j = right.ccw(j);
    }
    for &slot in &free {
        detach(mesh, slot);
    }
    let inf = VertexId::INFINITE;
    let (l0, r0, l1, r1) = (
        left.vertices[i0],
        right.vertices[j0],
        left.vertices[i1],
        right.vertices[j1],
    );
    let below = mesh.push_triangle([r0, l0, inf]);
    mesh.link(below.edge(1), into_l0);
    mesh.link(below.edge(2), out_of_r0);

    // Guibas and Stolfi's merge, from the lower tangent up, writing each new triangle at once.
    // Across an edge whose twin is `NONE` lies the region still to fill. `e_l` is the left
    // candidate edge `l → x`, in the left triangle (or ghost) on its counter-clockwise side;
    // `f_r` the right one, `x → r`, in the right triangle (or ghost) `(x, r, y)`. A candidate whose triangle's
    // third corner lies above the base and in the circle through the base and the candidate is
    // deleted (its slot detached and freed); then the base climbs to the candidate the
    // empty-circle test picks, until neither lies above it: the base is the upper tangent.
    // A slot freed and not yet reused: all three corners at infinity.
    let detached = |mesh: &MeshBuilder<'_>, e: HalfEdgeId| {
        e.is_none() || mesh.corners_at(e.base_and_corner().0) == [VertexId::INFINITE; 3]
    };
    let (mut l, mut r) = (l0, r0);
    let mut base_twin = below.edge(0);
    let mut made = 0;
    loop {
        made += 1;
        if made > mesh.len() {
            return None;
        }
        let above =
            |x: VertexId| !x.is_infinite() && orient(at(l), at(r), at(x)) == Orientation::Ccw;
        let mut cand_l = mesh.origin(e_l.next());
        if above(cand_l) {
            loop {
                let next = mesh.origin(e_l.prev());
                if !(above(next) && K::in_circle(at(l), at(r), at(cand_l), at(next))) {
                    break;
                }
                let (base, _) = e_l.base_and_corner();
                e_l = mesh.twin(e_l.prev());
                if e_l.is_none() {
                    return None;
                }
                detach(mesh, base);
                free.push(base);
                cand_l = next;
            }
        }
        let mut cand_r = mesh.origin(f_r);
        if above(cand_r) {
            loop {
                let next = mesh.origin(f_r.prev());
                if !(above(next) && K::in_circle(at(l), at(r), at(cand_r), at(next))) {
                    break;
                }
                let (base, _) = f_r.base_and_corner();
                f_r = mesh.twin(f_r.next());
                if f_r.is_none() {
                    return None;
                }
                detach(mesh, base);
                free.push(base);
                cand_r = next;
            }
        }
        let (left_ok, right_ok) = (above(cand_l), above(cand_r));
        if !left_ok && !right_ok {
            break;
        }
        let take_right =
            !left_ok || (right_ok && K::in_circle(at(cand_l), at(l), at(r), at(cand_r)));
        let (apex, across) = if take_right {
            (cand_r, f_r)
        } else {
            (cand_l, e_l)
        };
        if detached(mesh, across) {
            return None;
        }
        let slot = free.pop()?;
        mesh.set_corners_at(slot, [l, r, apex]);
        let edge = |k: usize| HalfEdgeId::at(slot, k);
        // Edge 0 is the base, `l → r`; an apex from the left half: edge 2 runs along the left
        // candidate and edge 1 is the next base; from the right half, the other way round.
        let (along, next_base) = if take_right { (1, 2) } else { (2, 1) };
        mesh.link(edge(0), base_twin);
        mesh.link(edge(along), across);
        mesh.unlink(edge(next_base));
        base_twin = edge(next_base);
        if take_right {
            // The next right candidate: round `apex` counter-clockwise, through the right
            // half's triangles and ghosts, to the last edge before the region still to fill.
            let mut h = f_r;
            let mut turns = 0;
            loop {
                let turned = mesh.twin(h.prev());
                if turned.is_none() {
                    f_r = h.prev();
                    break;
                }
                h = turned;
                turns += 1;
                if turns > mesh.len() {
                    return None;
                }
            }
            r = apex;
        } else {
            // The next left candidate: round `apex` clockwise, through the left half's
            // triangles and ghosts, to the last edge before the region still to fill.
            let mut h = e_l.next();
            let mut turns = 0;
            loop {
                let turned = mesh.twin(h);
                if turned.is_none() {
                    e_l = h;
                    break;
                }
                h = turned.next();
                turns += 1;
                if turns > mesh.len() {
                    return None;
                }
            }
            l = apex;
        }
    }
    if (l, r) != (l1, r1) || !free.is_empty() {
        return None;
    }
    let above = mesh.push_triangle([l1, r1, inf]);
    mesh.link(above.edge(0), base_twin);
    mesh.link(above.edge(1), into_r1);
    mesh.link(above.edge(2), out_of_l1);
    Some(())
}

/// Cuts the triangle at `base` out of the mesh: the half-edges across its sides no longer have
/// a twin, and its corners read as outside.
fn detach(mesh: &mut MeshBuilder<'_>, base: usize) {
    for k in 0..3 {
        let across = mesh.twin(HalfEdgeId::at(base, k));
        if !across.is_none() {
            mesh.unlink(across);
        }
        mesh.unlink(HalfEdgeId::at(base, k));
    }
    mesh.set_corners_at(base, [VertexId::INFINITE; 3]);
}

#[cfg(test)]
mod tests {
    use super::super::{scale, triangulate_split};
    use super::*;
    use crate::test_rng::Xorshift;

    /// Builds `points` cut in two, without falling back to one piece: `None` if a step failed.
    fn built_in_halves(points: &[Point]) -> Option<(Mesh, Vec<(u32, u32)>)> {
        let frames = scale::choose_frames(points).unwrap();
        let (order, left) = super::super::insertion_order(points, &frames, false, 0);
        let sorted: Vec<Point> = order
            .iter()
            .map(|&i| frames.predicates.apply(points[i as usize]))
            .collect();
        build::<super::super::insert::Fast>(&sorted, left?, false)
    }

    /// The triangles of a triangulation in input positions, each from its smallest, sorted.
    fn triangles(tri: &super::super::Triangulation) -> Vec<[usize; 3]> {
        let mut all: Vec<[usize; 3]> = tri
            .triangles()
            .map(|[a, b, c]| {
                let first = a.min(b).min(c);
                if first == a {
                    [a, b, c]
                } else if first == b {
                    [b, c, a]
                } else {
                    [c, a, b]
                }
            })
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
            let uniform = (0..n).map(|_| Point::new(rng.unit(), rng.unit())).collect();
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
            let one = triangulate_split(&points, false, 0).unwrap();
            one.validate()
                .unwrap_or_else(|e| panic!("{name} ({} points): {e}", points.len()));
            let two = triangulate_split(&points, true, 0).unwrap();
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
                let whole = triangulate_split(&points, false, usize::MAX).unwrap();
                let cut = triangulate_split(&points, false, 0).unwrap();
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
            let cut = triangulate_split(&points, false, 0).unwrap();
            cut.validate()
                .unwrap_or_else(|e| panic!("round {round}, {n} points: {e}"));
            if !integers {
                let whole = triangulate_split(&points, false, usize::MAX).unwrap();
                assert_eq!(triangles(&whole), triangles(&cut), "round {round}");
            }
        }
    }

    #[test]
    fn uniform_points_stitch() {
        let mut rng = Xorshift::new(7);
        for n in [10, 100, 1000, 5000, 300_000] {
            let points: Vec<Point> = (0..n).map(|_| Point::new(rng.unit(), rng.unit())).collect();
            assert!(built_in_halves(&points).is_some(), "{n}");
            let tri = triangulate_split(&points, false, 0).unwrap();
            tri.validate().unwrap();
        }
    }
}
