//! Typed 32-bit handles for vertices, half-edges and triangles.
//!
//! Owns: the handle types and the index arithmetic of a triangle's three half-edges. It may not
//! read a mesh: a handle says nothing of whether its element exists.

/// A vertex, numbered in the (spatial) insertion order;
/// [`Triangulation::input_of`](crate::Triangulation::input_of) gives its input position.
/// [`VertexId::INFINITE`] closes the mesh into a sphere.
///
/// ```
/// use condt::mesh::VertexId;
/// assert_eq!(VertexId::new(7).index(), 7);
/// assert!(VertexId::INFINITE.is_infinite());
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct VertexId(u32);

impl VertexId {
    /// The vertex at infinity, apex of every ghost triangle.
    ///
    /// ```
    /// use condt::mesh::{TriangleId, VertexId};
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let corners = (0..4).map(|t| tri.mesh().triangle_vertices(TriangleId::new(t)));
    /// assert_eq!(corners.filter(|c| c.contains(&VertexId::INFINITE)).count(), 3); // the ghosts
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub const INFINITE: VertexId = VertexId(u32::MAX);

    /// The vertex with this index.
    ///
    /// ```
    /// use condt::mesh::VertexId;
    /// assert!(VertexId::new(0) < VertexId::new(1) && !VertexId::new(0).is_infinite());
    /// ```
    #[inline]
    pub const fn new(index: u32) -> Self {
        VertexId(index)
    }
    /// Position in the arrays indexed by vertex (not an input position in general).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// assert!((0..3).all(|i| tri.vertex(i).index() < tri.mesh().num_vertex_ids()));
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
    /// `true` for [`VertexId::INFINITE`].
    ///
    /// ```
    /// use condt::mesh::HalfEdgeId;
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from))?;
    /// let origins = (0..12).map(|e| tri.mesh().origin(HalfEdgeId::new(e)));
    /// let from_infinity = origins.filter(|v| v.is_infinite());
    /// assert_eq!(from_infinity.count(), 3); // one in each ghost
    /// # Ok::<(), condt::Error>(())
    /// ```
    #[inline]
    pub const fn is_infinite(self) -> bool {
        self.0 == u32::MAX
    }
}

/// A directed edge. Triangle `t` owns half-edges `3t`, `3t + 1`, `3t + 2` counter-clockwise, so
/// [`next`](HalfEdgeId::next), [`prev`](HalfEdgeId::prev) and [`triangle`](HalfEdgeId::triangle)
/// are arithmetic; the twin is stored in the [`Mesh`](crate::mesh::Mesh).
///
/// ```
/// use condt::mesh::{HalfEdgeId, TriangleId};
/// let e = HalfEdgeId::new(5);
/// assert_eq!(e.next(), HalfEdgeId::new(3));
/// assert_eq!(e.prev(), HalfEdgeId::new(4));
/// assert_eq!(e.triangle(), TriangleId::new(1));
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct HalfEdgeId(u32);

impl HalfEdgeId {
    /// "No half-edge", used where a vertex has no incident edge.
    ///
    /// ```
    /// use condt::mesh::HalfEdgeId;
    /// assert!(HalfEdgeId::NONE.is_none());
    /// assert_ne!(HalfEdgeId::NONE, HalfEdgeId::new(0));
    /// ```
    pub const NONE: HalfEdgeId = HalfEdgeId(u32::MAX);

    /// The half-edge with this index.
    ///
    /// ```
    /// use condt::mesh::{HalfEdgeId, TriangleId};
    /// assert_eq!(HalfEdgeId::new(4).triangle(), TriangleId::new(1));
    /// ```
    #[inline]
    pub const fn new(index: u32) -> Self {
        HalfEdgeId(index)
    }
    /// Position in the mesh arrays.
    ///
    /// ```
    /// use condt::mesh::TriangleId;
    /// assert_eq!(TriangleId::new(2).edge(2).index(), 8);
    /// ```
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
    /// The next half-edge counter-clockwise in the same triangle. [`HalfEdgeId::NONE`] has none
    /// (unchecked on this hot path: a debug build panics, a release build gives a meaningless id).
    ///
    /// ```
    /// use condt::mesh::HalfEdgeId;
    /// let e = HalfEdgeId::new(7);
    /// assert_eq!(e.next(), HalfEdgeId::new(8));
    /// assert_eq!(e.next().next().next(), e);
    /// ```
    #[inline]
    pub const fn next(self) -> Self {
        HalfEdgeId(if self.0 % 3 == 2 {
            self.0 - 2
        } else {
            self.0 + 1
        })
    }

    /// The previous half-edge in the same triangle (unchecked, as [`HalfEdgeId::next`]).
    ///
    /// ```
    /// use condt::mesh::HalfEdgeId;
    /// let e = HalfEdgeId::new(6);
    /// assert_eq!(e.prev(), HalfEdgeId::new(8));
    /// assert_eq!(e.next().prev(), e);
    /// ```
    #[inline]
    pub const fn prev(self) -> Self {
        HalfEdgeId(if self.0 % 3 == 0 {
            self.0 + 2
        } else {
            self.0 - 1
        })
    }

    /// The triangle that owns this half-edge.
    ///
    /// ```
    /// use condt::mesh::{HalfEdgeId, TriangleId};
    /// assert_eq!(HalfEdgeId::new(8).triangle(), TriangleId::new(2));
    /// ```
    #[inline]
    pub const fn triangle(self) -> TriangleId {
        TriangleId(self.0 / 3)
    }
    /// The position of its triangle's first half-edge and its own corner (`0..3`) in it: one
    /// division, after which the triangle's other half-edges are corner steps ([`wrap3`]).
    #[inline]
    pub(crate) const fn base_and_corner(self) -> (usize, usize) {
        let corner = self.0 as usize % 3;
        (self.0 as usize - corner, corner)
    }

    /// The half-edge at `corner` of the triangle whose first half-edge is at `base` (the
    /// inverse of [`HalfEdgeId::base_and_corner`]).
    #[inline]
    pub(crate) const fn at(base: usize, corner: usize) -> Self {
        HalfEdgeId((base + corner) as u32)
    }
    /// `true` for [`HalfEdgeId::NONE`].
    ///
    /// ```
    /// use condt::mesh::HalfEdgeId;
    /// assert!(HalfEdgeId::NONE.is_none() && !HalfEdgeId::new(0).is_none());
    /// ```
    #[inline]
    pub const fn is_none(self) -> bool {
        self.0 == u32::MAX
    }
}

/// A triangle, real or ghost.
///
/// ```
/// use condt::mesh::{HalfEdgeId, TriangleId};
/// assert_eq!(TriangleId::new(2).edge(1), HalfEdgeId::new(7));
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct TriangleId(u32);

impl TriangleId {
    /// The triangle with this index.
    ///
    /// ```
    /// use condt::mesh::{HalfEdgeId, TriangleId};
    /// assert_eq!(TriangleId::new(1).edge(0), HalfEdgeId::new(3));
    /// ```
    #[inline]
    pub const fn new(index: u32) -> Self {
        TriangleId(index)
    }
    /// Position among the mesh's triangles.
    ///
    /// ```
    /// use condt::mesh::HalfEdgeId;
    /// assert_eq!(HalfEdgeId::new(7).triangle().index(), 2);
    /// ```
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
    /// Its `corner`-th half-edge (`corner` in `0..3`; for a triangle of a mesh, whose ids are
    /// below `u32::MAX / 3`: a larger one overflows as [`HalfEdgeId::next`] says).
    ///
    /// ```
    /// use condt::mesh::{HalfEdgeId, TriangleId};
    /// let t = TriangleId::new(2);
    /// assert_eq!(t.edge(0), HalfEdgeId::new(6));
    /// assert!((0..3).all(|corner| t.edge(corner).triangle() == t));
    /// ```
    #[inline]
    pub const fn edge(self, corner: u32) -> HalfEdgeId {
        HalfEdgeId(self.0 * 3 + corner)
    }
}

/// `k mod 3` for `k < 6`: a corner index stepped forward, without a division.
#[inline]
pub(crate) const fn wrap3(k: usize) -> usize {
    if k >= 3 {
        k - 3
    } else {
        k
    }
}
