//! Construction of a [`Mesh`]: the one place outside `mesh/mod.rs` that writes its arrays.
//!
//! Owns: the half-edge arrays (`origins`, `twins`) while a mesh is being built, and the step that
//! seals them ([`MeshBuilder::finish`], which derives `vertex_edges`). It offers the triangulator
//! exactly the edits it makes: append a triangle, overwrite a triangle's corners, link two twins,
//! and the reads it needs between edits.
//!
//! It may not look at a coordinate or decide a sign (that is the caller's business), and it does
//! not check invariants while the mesh is under construction: between two edits the arrays may
//! describe no sphere at all (unlinked twins, stale corners). [`Mesh::check_topology`] checks the
//! finished mesh. Once [`MeshBuilder::finish`] has run, nothing outside `mesh` can change it.
//!
//! Triangles are addressed either by [`TriangleId`] or, in the hot loops, by `base`, the index of
//! the triangle's first half-edge as [`HalfEdgeId::base_and_corner`] returns it, so that a caller
//! holding a half-edge reads its triangle after one division and no multiplication.

use super::{HalfEdgeId, Mesh, TriangleId, VertexId};
use alloc::vec::Vec;

/// A mesh under construction; see the module documentation.
pub(crate) struct MeshBuilder {
    /// The arrays being filled; `vertex_edges` stays empty until [`MeshBuilder::finish`].
    mesh: Mesh,
}

impl MeshBuilder {
    /// An empty mesh with room for `half_edges` half-edges.
    pub(crate) fn with_capacity(half_edges: usize) -> Self {
        MeshBuilder {
            mesh: Mesh {
                origins: Vec::with_capacity(half_edges),
                twins: Vec::with_capacity(half_edges),
                vertex_edges: Vec::new(),
            },
        }
    }

    /// Appends the triangle `corners` (counter-clockwise) with no twins yet, and returns it.
    #[inline]
    pub(crate) fn push_triangle(&mut self, corners: [VertexId; 3]) -> TriangleId {
        let t = TriangleId::new((self.mesh.origins.len() / 3) as u32);
        self.mesh.origins.extend_from_slice(&corners);
        self.mesh.twins.extend_from_slice(&[HalfEdgeId::NONE; 3]);
        t
    }

    /// Overwrites the corners of `t` (its twins are left as they are).
    #[inline]
    pub(crate) fn set_corners(&mut self, t: TriangleId, corners: [VertexId; 3]) {
        self.set_corners_at(t.index() * 3, corners);
    }

    /// Overwrites the corners of the triangle whose first half-edge is at `base`.
    #[inline]
    pub(crate) fn set_corners_at(&mut self, base: usize, corners: [VertexId; 3]) {
        self.mesh.origins[base..base + 3].copy_from_slice(&corners);
    }

    /// The corners of the triangle whose first half-edge is at `base`, corner `k` being the
    /// origin of half-edge `base + k`. One bounds check for the three.
    #[inline]
    pub(crate) fn corners_at(&self, base: usize) -> [VertexId; 3] {
        let c = &self.mesh.origins[base..base + 3];
        [c[0], c[1], c[2]]
    }

    /// Where `e` starts.
    #[inline]
    pub(crate) fn origin(&self, e: HalfEdgeId) -> VertexId {
        self.mesh.origin(e)
    }

    /// The half-edge across from `e` (or [`HalfEdgeId::NONE`] if not linked yet).
    #[inline]
    pub(crate) fn twin(&self, e: HalfEdgeId) -> HalfEdgeId {
        self.mesh.twin(e)
    }

    /// Makes `a` and `b` each other's twin.
    #[inline]
    pub(crate) fn link(&mut self, a: HalfEdgeId, b: HalfEdgeId) {
        self.mesh.link(a, b);
    }

    /// Seals the mesh over vertex ids `0..vertex_count`: derives each vertex's edge (for a hull
    /// vertex, the one pointing to infinity) and hands the arrays over, read-only from now on.
    pub(crate) fn finish(mut self, vertex_count: usize) -> Mesh {
        self.mesh.rebuild_vertex_edges(vertex_count);
        self.mesh
    }
}
