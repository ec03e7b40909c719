//! Half-edge topology of a triangulated sphere, closed by ghost triangles at
//! [`VertexId::INFINITE`] (`docs/half_edge.md` draws the layout and lists the walks).
//!
//! Owns: connectivity only, in three flat arrays indexed by typed ids, private to this module
//! (`build.rs` writes them while a mesh is built; others read a finished [`Mesh`] through its
//! accessors). It may not look at a coordinate and knows nothing of why a triangle was made.
//!
//! ```
//! use condt::{triangulate, Point};
//! let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
//! let mesh = tri.mesh();
//! let e = mesh.triangles().next().unwrap().edge(0);
//! assert_eq!(mesh.dest(e), mesh.origin(e.next()));
//! assert!(mesh.is_ghost(mesh.twin(e).triangle())); // a lone triangle: every edge on the hull
//! # Ok::<(), condt::Error>(())
//! ```

mod build;
mod check;
mod ids;

pub(crate) use build::{MeshArrays, MeshBuilder};
pub(crate) use check::fail;
pub use check::{Element, Rule, Violation};
pub(crate) use ids::wrap3;
pub use ids::{HalfEdgeId, TriangleId, VertexId};

use crate::threads::both;
use alloc::vec::Vec;

/// The topology of a Delaunay triangulation, closed into a sphere by ghost triangles.
///
/// Every method that takes a vertex, half-edge or triangle id reads the mesh's arrays at it:
/// an id that is not this mesh's (out of range, or a `NONE`) panics as slice indexing does,
/// unless the method says otherwise.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0)])?;
/// let mesh = tri.mesh();
/// assert_eq!(mesh.triangles().count(), 1); // one real triangle...
/// assert_eq!(mesh.num_triangles_with_ghosts(), 4); // ...and three ghosts, one per hull edge
/// assert_eq!(mesh.edges().count(), 3);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// `origins[e]`: where half-edge `e` starts; triangle `t` holds `3t .. 3t + 3`.
    origins: Vec<VertexId>,
    /// `twins[e]`: the half-edge across from `e`.
    twins: Vec<HalfEdgeId>,
    /// A half-edge leaving each vertex (to infinity on the hull), or [`HalfEdgeId::NONE`].
    vertex_edges: Vec<HalfEdgeId>,
}

impl Mesh {
    /// Number of half-edges, ghosts included.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.mesh().num_half_edges(), 12); // one triangle and three ghosts
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn num_half_edges(&self) -> usize {
        self.origins.len()
    }
    /// Number of triangles, ghosts included.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from))?;
    /// assert_eq!(tri.mesh().num_triangles_with_ghosts(), 2 + 4); // one ghost per hull edge
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn num_triangles_with_ghosts(&self) -> usize {
        self.origins.len() / 3
    }
    /// Size of the vertex id space (for a [`Triangulation`](crate::Triangulation), the number of
    /// input points, duplicates included): not a count of vertices with edges.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (0.0, 0.0)].map(Point::from))?;
    /// assert_eq!((tri.mesh().num_vertex_ids(), tri.num_vertices()), (4, 3));
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn num_vertex_ids(&self) -> usize {
        self.vertex_edges.len()
    }
    /// Where `e` starts.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let v = tri.vertex(2);
    /// assert_eq!(tri.mesh().origin(tri.mesh().vertex_edge(v).unwrap()), v);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn origin(&self, e: HalfEdgeId) -> VertexId {
        self.origins[e.index()]
    }
    /// Where `e` ends.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let mesh = tri.mesh();
    /// let t = mesh.triangles().next().unwrap();
    /// assert_eq!(mesh.dest(t.edge(0)), mesh.triangle_vertices(t)[1]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn dest(&self, e: HalfEdgeId) -> VertexId {
        self.origins[e.next().index()]
    }
    /// The half-edge running the other way along the same edge.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let mesh = tri.mesh();
    /// assert!(mesh.edges().all(|e| mesh.twin(mesh.twin(e)) == e));
    /// assert!(mesh.edges().all(|e| mesh.origin(mesh.twin(e)) == mesh.dest(e)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn twin(&self, e: HalfEdgeId) -> HalfEdgeId {
        self.twins[e.index()]
    }
    /// One half-edge leaving `v` (on the hull: the one pointing to infinity), or `None` when `v`
    /// has no edge: it is a merged duplicate, or the only distinct point.
    ///
    /// ```
    /// use condt::{mesh::VertexId, triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0), (1.0, 0.0)].map(Point::from))?;
    /// let ids = (0..4).map(VertexId::new);
    /// let without = ids.filter(|&v| tri.mesh().vertex_edge(v).is_none());
    /// assert_eq!(without.count(), 1); // the id the duplicate left unused
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn vertex_edge(&self, v: VertexId) -> Option<HalfEdgeId> {
        let e = *self.vertex_edges.get(v.index())?;
        (!e.is_none()).then_some(e)
    }

    /// The three corners of `t`, counter-clockwise.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let t = tri.mesh().triangles().next().unwrap();
    /// let mut corners = tri.mesh().triangle_vertices(t).map(|v| tri.input_of(v));
    /// corners.sort_unstable();
    /// assert_eq!(corners, [0, 1, 2]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn triangle_vertices(&self, t: TriangleId) -> [VertexId; 3] {
        let i = t.index() * 3;
        [self.origins[i], self.origins[i + 1], self.origins[i + 2]]
    }

    /// The corners of `triangles` as one slice, three per triangle ([`Mesh::triangle_corners`]).
    ///
    /// # Panics
    /// If the range goes past [`Mesh::num_triangles_with_ghosts`] or ends before it starts.
    ///
    /// ```
    /// use condt::{mesh::TriangleId, triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let mesh = tri.mesh();
    /// assert_eq!(mesh.corner_slice(0..4).len(), 12);
    /// assert_eq!(mesh.corner_slice(1..2), mesh.triangle_vertices(TriangleId::new(1)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn corner_slice(&self, triangles: core::ops::Range<usize>) -> &[VertexId] {
        // Saturating: a start near `usize::MAX / 3` wrapped round to the first triangles in release.
        let corner = |t: usize| t.saturating_mul(3);
        &self.origins[corner(triangles.start)..corner(triangles.end)]
    }
    /// [`Mesh::triangle_vertices`] of every triangle in `triangles` (ghosts included), in one pass.
    ///
    /// # Panics
    /// As [`Mesh::corner_slice`].
    ///
    /// ```
    /// use condt::{mesh::TriangleId, triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let mesh = tri.mesh();
    /// let each = (0..4).map(|t| mesh.triangle_vertices(TriangleId::new(t)));
    /// assert!(mesh.triangle_corners(0..4).eq(each));
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn triangle_corners(
        &self,
        triangles: core::ops::Range<usize>,
    ) -> impl Iterator<Item = [VertexId; 3]> + '_ {
        let corners = self.corner_slice(triangles).chunks_exact(3);
        corners.map(|c| [c[0], c[1], c[2]])
    }
    /// `true` when `t` is a ghost triangle (one corner is [`VertexId::INFINITE`]).
    ///
    /// ```
    /// use condt::{mesh::TriangleId, triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let ghosts = (0..4).filter(|&t| tri.mesh().is_ghost(TriangleId::new(t)));
    /// assert_eq!(ghosts.count(), 3);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn is_ghost(&self, t: TriangleId) -> bool {
        self.triangle_vertices(t).iter().any(|v| v.is_infinite())
    }
    /// `true` when both ends of `e` are finite vertices.
    ///
    /// ```
    /// use condt::{mesh::HalfEdgeId, triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let finite = (0..12).filter(|&e| tri.mesh().is_finite_edge(HalfEdgeId::new(e)));
    /// assert_eq!(finite.count(), 6); // three edges, each both ways
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn is_finite_edge(&self, e: HalfEdgeId) -> bool {
        !self.origin(e).is_infinite() && !self.dest(e).is_infinite()
    }
    /// `true` when `e` is finite with a ghost on one side: on the hull (or the collinear chain).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// let mesh = tri.mesh();
    /// assert_eq!(mesh.edges().filter(|&e| mesh.is_hull_edge(e)).count(), 4);
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub fn is_hull_edge(&self, e: HalfEdgeId) -> bool {
        self.is_finite_edge(e)
            && (self.is_ghost(e.triangle()) || self.is_ghost(self.twin(e).triangle()))
    }
    /// The real (non-ghost) triangles.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// assert_eq!(tri.mesh().triangles().count(), 4);
    /// assert!(tri.mesh().triangles().all(|t| !tri.mesh().is_ghost(t)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn triangles(&self) -> impl Iterator<Item = TriangleId> + '_ {
        (0..self.num_triangles_with_ghosts() as u32)
            .map(TriangleId::new)
            .filter(move |&t| !self.is_ghost(t))
    }
    /// Every finite undirected edge once, as the half-edge of the pair with the smaller id.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// let mesh = tri.mesh();
    /// assert_eq!(mesh.edges().count(), 8);
    /// assert!(mesh.edges().all(|e| e < mesh.twin(e) && mesh.is_finite_edge(e)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn edges(&self) -> impl Iterator<Item = HalfEdgeId> + '_ {
        (0..self.num_half_edges() as u32)
            .map(HalfEdgeId::new)
            .filter(move |&e| e < self.twin(e) && self.is_finite_edge(e))
    }

    /// The half-edges leaving `v` towards finite vertices, counter-clockwise (for a hull vertex,
    /// from one hull neighbour through the interior to the other). O(degree), no allocation.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&square)?;
    /// let mesh = tri.mesh();
    /// let around: Vec<_> = mesh.ring(tri.vertex(4)).map(|e| tri.input_of(mesh.dest(e))).collect();
    /// assert_eq!(around.len(), 4);
    /// // Counter-clockwise: each neighbour is the next corner of the square after the previous one.
    /// assert!(around.windows(2).all(|w| w[1] == (w[0] + 1) % 4));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn ring(&self, v: VertexId) -> Ring<'_> {
        let start = self.vertex_edge(v).unwrap_or(HalfEdgeId::NONE);
        Ring {
            mesh: self,
            start,
            current: start,
        }
    }
    /// The finite neighbours of `v`, counter-clockwise (the destinations of [`Mesh::ring`]).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// let around = tri.mesh().neighbors(tri.vertex(4));
    /// let mut around: Vec<usize> = around.map(|v| tri.input_of(v)).collect();
    /// around.sort_unstable();
    /// assert_eq!(around, vec![0, 1, 2, 3]);
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn neighbors(&self, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        self.ring(v).map(move |e| self.dest(e))
    }
    /// Whether an edge joins the finite vertices `a` and `b`. The two rings are walked in turn,
    /// so the answer costs at most twice the smaller degree: a point beside thousands of samples
    /// (a fan's hub) answers for each of them at the cost of theirs, where a walk of its own ring
    /// for each made the stages asking quadratic there. `false`, not a panic, for the infinite
    /// vertex or an id beyond the mesh, as [`Mesh::neighbors`] has no neighbour for them.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// let [a, c, e] = [0, 2, 4].map(|i| tri.vertex(i));
    /// assert!(tri.mesh().adjacent(a, e) && tri.mesh().adjacent(e, a));
    /// assert!(!tri.mesh().adjacent(a, c)); // the square's diagonal runs through 4
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn adjacent(&self, a: VertexId, b: VertexId) -> bool {
        let (mut around_a, mut around_b) = (self.neighbors(a), self.neighbors(b));
        loop {
            match around_a.next() {
                Some(w) if w == b => return true,
                None => return false,
                _ => {}
            }
            match around_b.next() {
                Some(w) if w == a => return true,
                None => return false,
                _ => {}
            }
        }
    }
    /// The vertices of the convex hull, counter-clockwise, each hull edge once (points on a hull
    /// edge included). On a collinear chain the walk goes out and back: inner vertices twice.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
    /// let tri = triangulate(&pts)?;
    /// assert_eq!(tri.mesh().hull().count(), 4);
    /// assert!(tri.mesh().hull().all(|v| v != tri.vertex(4)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn hull(&self) -> Hull<'_> {
        // The finite half-edge of some ghost triangle, if there is one.
        let start = (0..self.num_half_edges() as u32)
            .map(HalfEdgeId::new)
            .find(|&e| self.origin(e.prev()).is_infinite())
            .unwrap_or(HalfEdgeId::NONE);
        Hull {
            mesh: self,
            start,
            current: start,
        }
    }

    /// Fills `vertex_edges`: the last edge leaving each vertex (with `parallel`, two threads each
    /// scan every origin for their half of the ids), then each hull vertex's edge to infinity.
    fn rebuild_vertex_edges(&mut self, vertex_count: usize, parallel: bool) {
        // Slot `vertex_count` absorbs the half-edges leaving the vertex at infinity.
        let sink = vertex_count;
        let origins = &self.origins;
        let record = |edges: &mut [HalfEdgeId], first: usize| {
            for (i, &v) in origins.iter().enumerate() {
                // Below `first` the subtraction wraps to a huge slot: not this thread's.
                let slot = v.index().min(sink).wrapping_sub(first);
                if let Some(edge) = edges.get_mut(slot) {
                    *edge = HalfEdgeId::new(i as u32);
                }
            }
        };
        let mut edges = core::mem::take(&mut self.vertex_edges);
        edges.clear();
        edges.resize(vertex_count + 1, HalfEdgeId::NONE);
        if parallel {
            let middle = vertex_count / 2;
            let (low, high) = edges.split_at_mut(middle);
            both(true, || record(low, 0), || record(high, middle));
        } else {
            record(&mut edges, 0);
        }
        let from_infinity = edges[sink];
        edges.truncate(vertex_count);
        self.vertex_edges = edges;
        if from_infinity.is_none() {
            return;
        }
        // `∞ → a` is followed in its ghost by `a → b`, then `b → ∞`; across `∞ → a` lies the
        // previous ghost's `a → ∞`, followed by `∞ → c`. Walked back, one division per ghost.
        let start = from_infinity;
        let mut entry = start;
        loop {
            let (base, corner) = entry.base_and_corner();
            let to_infinity = HalfEdgeId::at(base, wrap3(corner + 2));
            let b = self.origin(to_infinity);
            self.vertex_edges[b.index()] = to_infinity;
            let across = self.twins[entry.index()];
            let (base, corner) = across.base_and_corner();
            entry = HalfEdgeId::at(base, wrap3(corner + 1));
            if entry == start {
                break;
            }
        }
    }
}

/// Counter-clockwise walk around one vertex; see [`Mesh::ring`].
///
/// ```
/// use condt::{mesh::Ring, triangulate, Point};
/// let pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
/// let tri = triangulate(&pts)?;
/// let ring: Ring<'_> = tri.mesh().ring(tri.vertex(0));
/// assert_eq!(ring.count(), 3);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Ring<'a> {
    mesh: &'a Mesh,
    start: HalfEdgeId,
    current: HalfEdgeId,
}

impl Iterator for Ring<'_> {
    type Item = HalfEdgeId;

    #[inline]
    fn next(&mut self) -> Option<HalfEdgeId> {
        loop {
            if self.current.is_none() {
                return None;
            }
            let e = self.current;
            let turned = self.mesh.twin(e.prev());
            self.current = if turned == self.start {
                HalfEdgeId::NONE
            } else {
                turned
            };
            if !self.mesh.dest(e).is_infinite() {
                return Some(e);
            }
        }
    }
}

/// Counter-clockwise walk along the convex hull; see [`Mesh::hull`].
///
/// ```
/// use condt::{mesh::Hull, triangulate, Point};
/// let tri = triangulate(&[(0.0, 0.0), (2.0, 0.0), (1.0, 2.0), (1.0, 0.5)].map(Point::from))?;
/// let hull: Hull<'_> = tri.mesh().hull();
/// assert_eq!(hull.count(), 3);
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Hull<'a> {
    mesh: &'a Mesh,
    start: HalfEdgeId,
    current: HalfEdgeId,
}

impl Iterator for Hull<'_> {
    type Item = VertexId;

    fn next(&mut self) -> Option<VertexId> {
        if self.current.is_none() {
            return None;
        }
        // `current` is the finite edge a → b of the ghost (a, b, ∞); ghosts run clockwise around
        // the hull, so the next vertex counter-clockwise is the origin of the ghost before it.
        let e = self.current;
        let next = self.mesh.twin(e.prev()).prev();
        self.current = if next == self.start {
            HalfEdgeId::NONE
        } else {
            next
        };
        Some(self.mesh.origin(e))
    }
}
