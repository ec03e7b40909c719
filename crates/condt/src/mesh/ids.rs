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
    pub const INFINITE: VertexId = VertexId(u32::MAX);

    /// The vertex with this index.
    #[inline]
    pub const fn new(index: u32) -> Self {
        VertexId(index)
    }
    /// Position in the arrays indexed by vertex (not an input position in general).
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
    /// `true` for [`VertexId::INFINITE`].
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
    pub const NONE: HalfEdgeId = HalfEdgeId(u32::MAX);

    /// The half-edge with this index.
    #[inline]
    pub const fn new(index: u32) -> Self {
        HalfEdgeId(index)
    }
    /// Position in the mesh arrays.
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
    /// The next half-edge counter-clockwise in the same triangle. [`HalfEdgeId::NONE`] has none
    /// (unchecked on this hot path: a debug build panics, a release build gives a meaningless id).
    #[inline]
    pub const fn next(self) -> Self {
        HalfEdgeId(if self.0 % 3 == 2 {
            self.0 - 2
        } else {
            self.0 + 1
        })
    }

    /// The previous half-edge in the same triangle (unchecked, as [`HalfEdgeId::next`]).
    #[inline]
    pub const fn prev(self) -> Self {
        HalfEdgeId(if self.0 % 3 == 0 {
            self.0 + 2
        } else {
            self.0 - 1
        })
    }

    /// The triangle that owns this half-edge.
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
    #[inline]
    pub const fn new(index: u32) -> Self {
        TriangleId(index)
    }
    /// Position among the mesh's triangles.
    #[inline]
    pub const fn index(self) -> usize {
        self.0 as usize
    }
    /// Its `corner`-th half-edge (`corner` in `0..3`; for a triangle of a mesh, whose ids are
    /// below `u32::MAX / 3`: a larger one overflows as [`HalfEdgeId::next`] says).
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
