//! Incremental Delaunay construction: walk to the new point, split, restore the empty-circle
//! property by edge flips (`docs/triangulation.md`, step 4).
//!
//! Owns: the construction state; orientations and in-circle tests only by `predicates` (the walk's
//! slide along an edge reads a float only as a guide), edits only by [`MeshBuilder`].

use crate::geometry::Point;
use crate::mesh::{wrap3, HalfEdgeId, MeshBuilder, VertexId};
use crate::predicates::{self, Orientation};
use alloc::vec::Vec;
use core::marker::PhantomData;
use core::sync::atomic::AtomicUsize;

/// The predicates a construction decides with, chosen once per point set.
pub(crate) trait Kernel {
    fn orient2d(a: Point, b: Point, c: Point) -> Orientation;
    /// A number with the sign of [`Kernel::orient2d`], for the walk to branch on (speed).
    fn orient2d_sign(a: Point, b: Point, c: Point) -> f64 {
        match Self::orient2d(a, b, c) {
            Orientation::Ccw => 1.0,
            Orientation::Cw => -1.0,
            Orientation::Collinear => 0.0,
        }
    }
    fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool;
    /// [`Kernel::in_circle`]`(u, w, v, q)`, `v` the new point every test of an insertion shares.
    #[inline(always)]
    fn in_circle_around(v: Point, u: Point, w: Point, q: Point) -> bool {
        Self::in_circle(u, w, v, q)
    }
    /// For `p` on the inner side of the hull edge `a → b`: past `b` (`Forward`), before `a`
    /// (`Backward`) or between (`Done`) along it; only a guide for [`Builder::ghost_step`].
    fn slide(a: Point, b: Point, p: Point) -> Slide {
        use core::cmp::Ordering::{Greater, Less};
        if predicates::dot_sign(p, b, b, a) == Greater {
            Slide::Forward
        } else if predicates::dot_sign(p, a, b, a) == Less {
            Slide::Backward
        } else {
            Slide::Done
        }
    }
}

/// Shewchuk's predicates alone, for coordinates in their exact range (`scale` checks it).
pub(crate) struct Fast;

impl Kernel for Fast {
    #[inline(always)]
    fn orient2d(a: Point, b: Point, c: Point) -> Orientation {
        predicates::fast_orient2d(a, b, c)
    }
    #[inline(always)]
    fn orient2d_sign(a: Point, b: Point, c: Point) -> f64 {
        predicates::fast_orient2d_det(a, b, c)
    }
    #[inline(always)]
    fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
        predicates::fast_in_circle(a, b, c, d)
    }
    #[inline(always)]
    fn in_circle_around(v: Point, u: Point, w: Point, q: Point) -> bool {
        predicates::fast_in_circle_around(v, u, w, q)
    }
    /// In floating point: coordinates below 2 cannot overflow, and a rounding error only makes
    /// one slide more or less, which the one-way rule keeps finite.
    #[inline(always)]
    fn slide(pa: Point, pb: Point, p: Point) -> Slide {
        let (dx, dy) = (pb.x - pa.x, pb.y - pa.y);
        let along = (p.x - pa.x) * dx + (p.y - pa.y) * dy;
        if along > dx * dx + dy * dy {
            Slide::Forward
        } else if along < 0.0 {
            Slide::Backward
        } else {
            Slide::Done
        }
    }
}

/// The public predicates, exact for every finite input (sets beyond the fast range).
pub(crate) struct Exact;

impl Kernel for Exact {
    #[inline(always)]
    fn orient2d(a: Point, b: Point, c: Point) -> Orientation {
        predicates::orient2d(a, b, c)
    }
    #[inline(always)]
    fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
        predicates::in_circle(a, b, c, d)
    }
}

/// Where [`Builder::locate`] found a point.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Location {
    /// Strictly inside this half-edge's triangle; for a ghost, strictly outside its hull edge.
    Face(HalfEdgeId),
    /// In the relative interior of this finite edge.
    Edge(HalfEdgeId),
    /// Exactly on this vertex.
    Vertex(VertexId),
}

/// Where a walk stands between two steps.
#[derive(Copy, Clone, Debug)]
struct Walk {
    at: HalfEdgeId,
    /// Whether the walk entered across `at`: the point is strictly left of it, no test needed.
    entered: bool,
    slide: Slide,
}

impl Walk {
    /// Moves to `e`: across it if `entered`, else sliding along the hull; the walk goes on.
    #[inline(always)]
    fn to(&mut self, e: HalfEdgeId, entered: bool) -> Option<Location> {
        (self.at, self.entered) = (e, entered);
        None
    }
}

/// The hull slides the walk may still take: `Either` way (none yet), only `Forward` (to the
/// ghost after the current hull edge), only `Backward`, or none (`Done`: a plain visibility walk).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Slide {
    Either,
    Forward,
    Backward,
    Done,
}

/// The construction state. Vertex ids are positions in `points` (the insertion order).
pub(crate) struct Builder<'a, 'm, K: Kernel> {
    kernel: PhantomData<K>,
    points: &'a [Point],
    mesh: MeshBuilder<'m>,
    flips: Vec<HalfEdgeId>,
    hint: HalfEdgeId,
    /// `(duplicate, vertex it was merged into)`, in insertion-order ids.
    merged: Vec<(u32, u32)>,
}

/// The half-edges of `n` points: a sphere with `n + 1` vertices has `2n - 2` triangles.
pub(crate) fn half_edges(n: usize) -> usize {
    6 * n.max(3) - 6
}

/// The insertions between two reports to a progress counter ([`build_into`]).
pub(crate) const REPORT_EVERY: usize = 1 << 16;

/// Builds the mesh of `points` (in insertion order) in `mesh`, empty and holding [`half_edges`];
/// returns it with the `(duplicate, kept)` pairs merged, or `None` without a triangle. `progress`
/// gets the vertices inserted every [`REPORT_EVERY`] points: all of them, or none on `None`.
pub(crate) fn build_into<'m, K: Kernel>(
    points: &[Point],
    mesh: MeshBuilder<'m>,
    progress: Option<&AtomicUsize>,
) -> Option<(MeshBuilder<'m>, Vec<(u32, u32)>)> {
    let start = first_triangle::<K>(points)?;
    let mut builder = Builder::<K>::new(points, start, mesh);
    let n = points.len();
    let (mut from, mut reported) = (0, 0);
    while from < n {
        let to = n.min(from + REPORT_EVERY);
        for v in from as u32..to as u32 {
            if !start.contains(&v) {
                builder.insert(v);
            }
        }
        if let Some(counter) = progress {
            let inserted = to - builder.merged.len();
            crate::threads::count(counter, inserted - reported, true);
            reported = inserted;
        }
        from = to;
    }
    Some((builder.mesh, builder.merged))
}

/// The first three points, in insertion order, that make a proper triangle, counter-clockwise.
pub(crate) fn first_triangle<K: Kernel>(points: &[Point]) -> Option<[u32; 3]> {
    let a = 0;
    let b = points.iter().position(|&p| p != points[a])?;
    let (pa, pb) = (points[a], points[b]);
    points[b + 1..].iter().enumerate().find_map(|(k, &pc)| {
        let c = (b + 1 + k) as u32;
        match K::orient2d(pa, pb, pc) {
            Orientation::Ccw => Some([a as u32, b as u32, c]),
            Orientation::Cw => Some([b as u32, a as u32, c]),
            Orientation::Collinear => None,
        }
    })
}

impl<'a, 'm, K: Kernel> Builder<'a, 'm, K> {
    /// Starts from the counter-clockwise triangle `a, b, c` and its ghosts, in `mesh`.
    fn new(points: &'a [Point], [a, b, c]: [u32; 3], mut mesh: MeshBuilder<'m>) -> Self {
        debug_assert_eq!(
            K::orient2d(points[a as usize], points[b as usize], points[c as usize]),
            Orientation::Ccw
        );
        debug_assert_eq!(mesh.len(), 0);
        let inf = VertexId::INFINITE;
        let [a, b, c] = [a, b, c].map(VertexId::new);
        // Triangle 0 = (a, b, c); ghosts 1 = (b, a, ∞), 2 = (c, b, ∞), 3 = (a, c, ∞).
        for corners in [[a, b, c], [b, a, inf], [c, b, inf], [a, c, inf]] {
            mesh.push_triangle(corners);
        }
        let h = HalfEdgeId::new;
        for (x, y) in [(0, 3), (1, 6), (2, 9), (4, 11), (7, 5), (10, 8)] {
            mesh.link(h(x), h(y));
        }
        Builder {
            kernel: PhantomData,
            points,
            mesh,
            flips: Vec::new(),
            hint: h(0),
            merged: Vec::new(),
        }
    }
    #[inline]
    fn point(&self, v: VertexId) -> Point {
        self.points[v.index()]
    }
    #[inline]
    fn origin(&self, e: HalfEdgeId) -> VertexId {
        self.mesh.origin(e)
    }
    #[inline]
    fn twin(&self, e: HalfEdgeId) -> HalfEdgeId {
        self.mesh.twin(e)
    }
    pub(crate) fn insert(&mut self, v: u32) {
        let p = self.points[v as usize];
        let v = VertexId::new(v);
        let mut outside_hull = false;
        match self.locate(p) {
            Location::Face(e) => {
                outside_hull = self.origin(e.prev()).is_infinite();
                self.split_triangle(e, v)
            }
            Location::Edge(e) => self.split_edge(e, v),
            Location::Vertex(w) => {
                self.merged.push((v.index() as u32, w.index() as u32));
                return;
            }
        }
        self.restore_delaunay(v);
        if outside_hull {
            self.hint = self.ghost_at(v);
        }
    }

    /// A ghost's half-edge at hull vertex `v`, turning around `v` from the hint (at `v`): the next
    /// point usually lies outside the hull near `v`, reached along the hull, not across its fan.
    fn ghost_at(&self, v: VertexId) -> HalfEdgeId {
        let (base, _) = self.hint.base_and_corner();
        let Some(k) = self.mesh.corners_at(base).iter().position(|&c| c == v) else {
            return self.hint;
        };
        let start = HalfEdgeId::at(base, k);
        let mut e = start;
        loop {
            // `e` leaves `v`; the triangle's next corner is its destination.
            let (base, corner) = e.base_and_corner();
            if self
                .origin(HalfEdgeId::at(base, wrap3(corner + 1)))
                .is_infinite()
            {
                return e;
            }
            e = self.twin(HalfEdgeId::at(base, wrap3(corner + 2)));
            if e == start {
                return self.hint;
            }
        }
    }

    /// Visibility walk from the hint; it terminates because, seen from any point, "lies in front
    /// of" has no cycle among the triangles of a Delaunay triangulation.
    fn locate(&self, p: Point) -> Location {
        let mut walk = Walk {
            at: self.hint,
            entered: false,
            slide: Slide::Either,
        };
        loop {
            let (base, corner) = walk.at.base_and_corner();
            let corners = self.mesh.corners_at(base);
            let found = match corners.iter().position(|v| v.is_infinite()) {
                Some(infinite) => self.ghost_step(p, base, corners, infinite, &mut walk),
                None => {
                    walk.slide = Slide::Done;
                    self.triangle_step(p, base, corner, corners, &mut walk)
                }
            };
            if let Some(location) = found {
                return location;
            }
        }
    }

    /// One step in the ghost at `base` (its corner `infinite` at infinity): `p` is outside its
    /// hull edge (found), on its line (found, or slide), or inside (slide, or enter across it).
    #[inline(always)]
    fn ghost_step(
        &self,
        p: Point,
        base: usize,
        corners: [VertexId; 3],
        infinite: usize,
        walk: &mut Walk,
    ) -> Option<Location> {
        let half_edge = |k: usize| HalfEdgeId::at(base, k);
        // The ghost's finite edge `a → b` starts after the infinite corner; the ghost before it
        // along the hull lies across `∞ → a`, the one after it across `b → ∞`.
        let (h, after) = (wrap3(infinite + 1), wrap3(infinite + 2));
        let hull = half_edge(h);
        let (a, b) = (corners[h], corners[after]);
        let (pa, pb) = (self.point(a), self.point(b));
        let to_ghost_after = || self.twin(half_edge(after));
        let to_ghost_before = || self.twin(half_edge(infinite));
        match K::orient2d(pa, pb, p) {
            Orientation::Ccw => Some(Location::Face(hull)),
            Orientation::Cw => {
                // `p` is inside this hull edge's line; past one end it is likely outside further
                // along, so slide to the next ghost that way. Slides go one way only, before the
                // walk enters a real triangle: past the far end of `a → b`, `p` is nearer `b`
                // than `a`, so the distance to the slide's vertex shrinks.
                let way = K::slide(pa, pb, p);
                if way != Slide::Done && (walk.slide == Slide::Either || walk.slide == way) {
                    walk.slide = way;
                    let next = if way == Slide::Forward {
                        to_ghost_after()
                    } else {
                        to_ghost_before()
                    };
                    walk.to(next, false)
                } else {
                    walk.slide = Slide::Done;
                    walk.to(self.twin(hull), true)
                }
            }
            Orientation::Collinear => {
                // Sliding back and forth between this and a Cw slide could cycle at a sharp hull
                // corner: no more Cw slides after a collinear one.
                walk.slide = Slide::Done;
                match position_on_segment(pa, pb, p) {
                    Segment::AtStart => Some(Location::Vertex(a)),
                    Segment::AtEnd => Some(Location::Vertex(b)),
                    Segment::Inside => Some(Location::Edge(hull)),
                    Segment::BeyondEnd => walk.to(to_ghost_after(), false),
                    Segment::BeforeStart => walk.to(to_ghost_before(), false),
                }
            }
        }
    }

    /// One step in the real triangle at `base`, entered at `corner`: leave through any edge with
    /// `p` strictly on its right; with none, `p` is inside, on one edge, or on a corner.
    #[inline(always)]
    fn triangle_step(
        &self,
        p: Point,
        base: usize,
        corner: usize,
        corners: [VertexId; 3],
        walk: &mut Walk,
    ) -> Option<Location> {
        let half_edge = |k: usize| HalfEdgeId::at(base, k);
        let points = corners.map(|v| self.point(v));
        let first = if walk.entered { corner } else { 0 };
        let mut collinear = [0usize; 2];
        let mut n_collinear = 0;
        for step in usize::from(walk.entered)..3 {
            let k = wrap3(first + step);
            let sign = K::orient2d_sign(points[k], points[wrap3(k + 1)], p);
            // Counter-clockwise, the common case, is tested first: one comparison per step.
            if sign > 0.0 {
                continue;
            }
            if sign < 0.0 {
                return walk.to(self.twin(half_edge(k)), true);
            }
            collinear[n_collinear.min(1)] = k;
            n_collinear += 1;
        }
        Some(match n_collinear {
            0 => Location::Face(half_edge(0)),
            1 => Location::Edge(half_edge(collinear[0])),
            _ => {
                // On two edge lines of a proper triangle: at their shared corner, where the first
                // of the two edges (in triangle order) ends.
                let (x, y) = (collinear[0], collinear[1]);
                Location::Vertex(if wrap3(x + 1) == y {
                    corners[y]
                } else {
                    corners[x]
                })
            }
        })
    }

    /// Splits the triangle `(a, b, c)` of `e = a → b` into `(a, b, v)`, `(b, c, v)`, `(c, a, v)`.
    ///
    /// ```text
    ///          c                    c
    ///         / \                  /|\
    ///        /   \                / | \
    ///       /  v  \      =>      /  v  \
    ///      /       \            / /   \ \
    ///     a ------- b          a ------- b
    /// ```
    fn split_triangle(&mut self, e: HalfEdgeId, v: VertexId) {
        let (a, b, c) = (self.origin(e), self.origin(e.next()), self.origin(e.prev()));
        let (out_ab, out_bc, out_ca) = (self.twin(e), self.twin(e.next()), self.twin(e.prev()));
        let m = &mut self.mesh;
        let t0 = e.triangle();
        let t1 = m.push_triangle([b, c, v]);
        let t2 = m.push_triangle([c, a, v]);
        m.set_corners(t0, [a, b, v]);
        m.link(t0.edge(0), out_ab);
        m.link(t1.edge(0), out_bc);
        m.link(t2.edge(0), out_ca);
        m.link(t0.edge(1), t1.edge(2));
        m.link(t1.edge(1), t2.edge(2));
        m.link(t2.edge(1), t0.edge(2));
        self.flips
            .extend_from_slice(&[t0.edge(0), t1.edge(0), t2.edge(0)]);
        self.hint = t0.edge(0);
    }

    /// Splits the finite edge `e = a → b`, between `(a, b, c)` and `(b, a, d)`, at `v` into the
    /// four triangles `(v, b, c)`, `(v, c, a)`, `(v, a, d)`, `(v, d, b)`.
    ///
    /// ```text
    ///          c                    c
    ///        /   \                / | \
    ///     a ---v--- b    =>    a ---v--- b
    ///        \   /                \ | /
    ///          d                    d
    /// ```
    fn split_edge(&mut self, e: HalfEdgeId, v: VertexId) {
        let f = self.twin(e);
        let (a, b) = (self.origin(e), self.origin(f));
        let (c, d) = (self.origin(e.prev()), self.origin(f.prev()));
        let (out_bc, out_ca) = (self.twin(e.next()), self.twin(e.prev()));
        let (out_ad, out_db) = (self.twin(f.next()), self.twin(f.prev()));
        let m = &mut self.mesh;
        let t_bc = e.triangle();
        let t_ad = f.triangle();
        let t_ca = m.push_triangle([v, c, a]);
        let t_db = m.push_triangle([v, d, b]);
        m.set_corners(t_bc, [v, b, c]);
        m.set_corners(t_ad, [v, a, d]);
        m.link(t_bc.edge(1), out_bc);
        m.link(t_ca.edge(1), out_ca);
        m.link(t_ad.edge(1), out_ad);
        m.link(t_db.edge(1), out_db);
        m.link(t_bc.edge(2), t_ca.edge(0));
        m.link(t_ca.edge(2), t_ad.edge(0));
        m.link(t_ad.edge(2), t_db.edge(0));
        m.link(t_db.edge(2), t_bc.edge(0));
        self.flips
            .extend_from_slice(&[t_bc.edge(1), t_ca.edge(1), t_ad.edge(1), t_db.edge(1)]);
        self.hint = t_bc.edge(0);
    }

    /// Flips illegal edges opposite the new vertex `v` until none is left. A flip hands over the
    /// next edge to test directly, not through the stack (the same order of tests).
    fn restore_delaunay(&mut self, v: VertexId) {
        let pv = self.point(v);
        let mut next = self.flips.pop().map(|e| self.to_test(e));
        while let Some(Opposite { e, f, u, w }) = next {
            // `e = u → w` lies in the triangle (u, w, v); across it, `f` in (w, u, q).
            let (f_base, f_corner) = f.base_and_corner();
            let q = self.origin(HalfEdgeId::at(f_base, wrap3(f_corner + 2)));
            next = if self.is_illegal(u, w, pv, q) {
                Some(self.flip(e, (f_base, f_corner), [u, w, q], v))
            } else {
                self.flips.pop().map(|e| self.to_test(e))
            };
        }
    }

    #[inline(always)]
    fn to_test(&self, e: HalfEdgeId) -> Opposite {
        let f = self.twin(e);
        Opposite {
            e,
            f,
            u: self.origin(e),
            w: self.origin(f),
        }
    }

    /// Whether edge `u – w`, with the new vertex (at `pv`) left of it and `q` right, must flip.
    #[inline]
    fn is_illegal(&self, u: VertexId, w: VertexId, pv: Point, q: VertexId) -> bool {
        // The vertex at infinity has the largest id: one comparison settles the common case.
        if !u.max(w).max(q).is_infinite() {
            K::in_circle_around(pv, self.point(u), self.point(w), self.point(q))
        } else if q.is_infinite() {
            // A hull edge seen from inside: always kept.
            false
        } else if u.is_infinite() {
            // Edge ∞ – w between ghosts (∞, w, v) and (q, w, ∞): flip when v sees hull edge q → w.
            K::orient2d(self.point(q), self.point(w), pv) == Orientation::Ccw
        } else {
            // Edge u – ∞ between ghosts (u, ∞, v) and (u, q, ∞): flip when v sees hull edge u → q.
            K::orient2d(self.point(u), self.point(q), pv) == Orientation::Ccw
        }
    }

    /// Replaces the edge `u – w` (half-edges `e` in `(u, w, v)` and `f` in `(w, u, q)`) by `v – q`,
    /// giving `(v, u, q)` and `(v, q, w)`; queues the edge of the first opposite `v`, returns the
    /// second's. `f` and `[u, w, q]` come as the caller read them, to save dividing and loading.
    ///
    /// ```text
    ///          v                    v
    ///        /   \                / | \
    ///       u --- w      =>      u  |  w
    ///        \   /                \ | /
    ///          q                    q
    /// ```
    fn flip(
        &mut self,
        e: HalfEdgeId,
        f: (usize, usize),
        [u, w, q]: [VertexId; 3],
        v: VertexId,
    ) -> Opposite {
        let (e_base, e_corner) = e.base_and_corner();
        let (f_base, f_corner) = f;
        let at = HalfEdgeId::at;
        let m = &mut self.mesh;
        let e_twins = m.twins_at(e_base);
        let f_twins = m.twins_at(f_base);
        let out_vu = e_twins[wrap3(e_corner + 2)];
        let out_wv = e_twins[wrap3(e_corner + 1)];
        let out_uq = f_twins[wrap3(f_corner + 1)];
        let out_qw = f_twins[wrap3(f_corner + 2)];
        m.set_corners_at(e_base, [v, u, q]);
        m.set_corners_at(f_base, [v, q, w]);
        // Both triangles' twins at once, then the four outer half-edges back.
        m.set_twins_at(e_base, [out_vu, out_uq, at(f_base, 0)]);
        m.set_twins_at(f_base, [at(e_base, 2), out_qw, out_wv]);
        m.set_twin(out_vu, at(e_base, 0));
        m.set_twin(out_uq, at(e_base, 1));
        m.set_twin(out_qw, at(f_base, 1));
        m.set_twin(out_wv, at(f_base, 2));
        self.flips.push(at(e_base, 1));
        self.hint = at(e_base, 0);
        Opposite {
            e: at(f_base, 1),
            f: out_qw,
            u: q,
            w,
        }
    }
}

/// An edge `u → w` to test: `e` in the new vertex's triangle, `f` its twin.
#[derive(Copy, Clone)]
struct Opposite {
    e: HalfEdgeId,
    f: HalfEdgeId,
    u: VertexId,
    w: VertexId,
}

/// Where a point collinear with a segment `a → b` lies along it.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Segment {
    BeforeStart,
    AtStart,
    Inside,
    AtEnd,
    BeyondEnd,
}

/// Classifies `p`, known to be collinear with the distinct points `a` and `b`, along the segment.
/// Compares coordinates only (exact); on a non-vertical line x orders the points, else y does.
pub(crate) fn position_on_segment(a: Point, b: Point, p: Point) -> Segment {
    let (ka, kb, kp) = if a.x != b.x {
        (a.x, b.x, p.x)
    } else {
        (a.y, b.y, p.y)
    };
    // At neither end, a backward segment reverses both strict tests.
    let forward = ka < kb;
    if kp == ka {
        Segment::AtStart
    } else if kp == kb {
        Segment::AtEnd
    } else if (kp < ka) == forward {
        Segment::BeforeStart
    } else if (kp > kb) == forward {
        Segment::BeyondEnd
    } else {
        Segment::Inside
    }
}
