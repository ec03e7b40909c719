//! Construction of a [`Mesh`]: the one place outside `mesh/mod.rs` that writes its arrays.
//!
//! Owns: the half-edge arrays while a mesh is built, in [`MeshArrays`] (sized once); a
//! [`MeshBuilder`] lent a range (two may fill disjoint ones at once) offers the triangulator its
//! edits and reads; [`MeshArrays::seal`] derives `vertex_edges`. It may not look at a coordinate,
//! and checks nothing while building (between edits the arrays may describe no sphere).

use super::{HalfEdgeId, Mesh, TriangleId, VertexId};
use crate::threads::filled;
use alloc::vec::Vec;

impl Mesh {
    /// The arrays [`MeshArrays::reusing`] refills, the vertex edges (derived last) freed now.
    pub(crate) fn into_storage(self) -> Mesh {
        Mesh {
            vertex_edges: Vec::new(),
            ..self
        }
    }
}

/// The storage of a mesh under construction: `half_edges` slots, filled by [`MeshBuilder`]s.
pub(crate) struct MeshArrays {
    origins: Vec<VertexId>,
    twins: Vec<HalfEdgeId>,
}

impl MeshArrays {
    /// Room for `half_edges` half-edges (a multiple of three), filled as [`filled`] does.
    pub(crate) fn new(half_edges: usize, parallel: bool) -> Self {
        MeshArrays::reusing(Mesh::default(), half_edges, parallel)
    }

    /// [`MeshArrays::new`] in the arrays of `storage`, a mesh no longer needed, where they are
    /// large enough (memory: a smoothing pass replaces a mesh by one as large; `docs/perf-log.md`).
    pub(crate) fn reusing(storage: Mesh, half_edges: usize, parallel: bool) -> Self {
        MeshArrays {
            origins: filled(storage.origins, VertexId::INFINITE, half_edges, parallel),
            twins: filled(storage.twins, HalfEdgeId::NONE, half_edges, parallel),
        }
    }

    /// A builder over the whole storage, its first `filled` half-edges already written.
    pub(crate) fn builder(&mut self, filled: usize) -> MeshBuilder<'_> {
        MeshBuilder {
            origins: &mut self.origins,
            twins: &mut self.twins,
            len: filled,
        }
    }

    /// Empty builders over `0..split` and `split..`, each from 0 ([`MeshBuilder::renumber`]).
    pub(crate) fn halves(&mut self, split: usize) -> (MeshBuilder<'_>, MeshBuilder<'_>) {
        let (origins_low, origins_high) = self.origins.split_at_mut(split);
        let (twins_low, twins_high) = self.twins.split_at_mut(split);
        let builder = |origins, twins| MeshBuilder {
            origins,
            twins,
            len: 0,
        };
        (
            builder(origins_low, twins_low),
            builder(origins_high, twins_high),
        )
    }

    /// Moves the `len` half-edges at `from` down to `to`, keeping their links: a twin inside the
    /// moved range moves with it (the caller moves only ranges whose links stay inside).
    pub(crate) fn close_gap(&mut self, from: usize, len: usize, to: usize) {
        debug_assert!(to <= from);
        self.origins.copy_within(from..from + len, to);
        self.twins.copy_within(from..from + len, to);
        let gap = (from - to) as u32;
        for e in &mut self.twins[to..to + len] {
            *e = HalfEdgeId::new(e.index() as u32 - gap);
        }
    }

    /// Keeps the first `len` half-edges and seals the mesh over vertex ids `0..vertex_count`,
    /// deriving each vertex's edge (on two threads when `parallel`). Read-only from now on.
    pub(crate) fn seal(mut self, len: usize, vertex_count: usize, parallel: bool) -> Mesh {
        self.origins.truncate(len);
        self.twins.truncate(len);
        let mut mesh = Mesh {
            origins: self.origins,
            twins: self.twins,
            vertex_edges: Vec::new(),
        };
        mesh.rebuild_vertex_edges(vertex_count, parallel);
        mesh
    }
}

/// A mesh under construction in a range of [`MeshArrays`]; see the module documentation.
pub(crate) struct MeshBuilder<'m> {
    origins: &'m mut [VertexId],
    twins: &'m mut [HalfEdgeId],
    /// Half-edges written so far, from the start of the range.
    len: usize,
}

impl MeshBuilder<'_> {
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }
    /// Appends the triangle `corners` (counter-clockwise) with no twins yet, and returns it
    /// (panics if the range is full: the caller sized it).
    #[inline]
    pub(crate) fn push_triangle(&mut self, corners: [VertexId; 3]) -> TriangleId {
        let base = self.len;
        let t = TriangleId::new((base / 3) as u32);
        self.origins[base..base + 3].copy_from_slice(&corners);
        self.twins[base..base + 3].copy_from_slice(&[HalfEdgeId::NONE; 3]);
        self.len += 3;
        t
    }

    /// Overwrites the corners of `t` (its twins are left as they are).
    #[inline]
    pub(crate) fn set_corners(&mut self, t: TriangleId, corners: [VertexId; 3]) {
        self.set_corners_at(t.index() * 3, corners);
    }
    /// Overwrites the corners of the triangle at `base`.
    #[inline]
    pub(crate) fn set_corners_at(&mut self, base: usize, corners: [VertexId; 3]) {
        self.origins[base..base + 3].copy_from_slice(&corners);
    }
    /// Corners of the triangle at `base`, corner `k` the origin of `base + k` (one bounds check).
    #[inline]
    pub(crate) fn corners_at(&self, base: usize) -> [VertexId; 3] {
        let c = &self.origins[base..base + 3];
        [c[0], c[1], c[2]]
    }

    /// The twins of the triangle at `base` (one bounds check for the three, as above).
    #[inline]
    pub(crate) fn twins_at(&self, base: usize) -> [HalfEdgeId; 3] {
        let t = &self.twins[base..base + 3];
        [t[0], t[1], t[2]]
    }

    /// Overwrites the twins of the triangle at `base` (the caller links the other sides).
    #[inline]
    pub(crate) fn set_twins_at(&mut self, base: usize, twins: [HalfEdgeId; 3]) {
        self.twins[base..base + 3].copy_from_slice(&twins);
    }
    /// Makes `b` the twin of `a`, one way only.
    #[inline]
    pub(crate) fn set_twin(&mut self, a: HalfEdgeId, b: HalfEdgeId) {
        self.twins[a.index()] = b;
    }
    #[inline]
    pub(crate) fn origin(&self, e: HalfEdgeId) -> VertexId {
        self.origins[e.index()]
    }
    /// The half-edge across from `e` (or [`HalfEdgeId::NONE`] if not linked yet).
    #[inline]
    pub(crate) fn twin(&self, e: HalfEdgeId) -> HalfEdgeId {
        self.twins[e.index()]
    }
    /// Makes `a` and `b` each other's twin.
    #[inline]
    pub(crate) fn link(&mut self, a: HalfEdgeId, b: HalfEdgeId) {
        self.twins[a.index()] = b;
        self.twins[b.index()] = a;
    }

    /// Shifts the written ids by `edge_offset` half-edges and `vertex_offset` finite vertices: a
    /// mesh built on its own, placed after another.
    pub(crate) fn renumber(&mut self, vertex_offset: u32, edge_offset: u32) {
        for v in &mut self.origins[..self.len] {
            if !v.is_infinite() {
                *v = VertexId::new(v.index() as u32 + vertex_offset);
            }
        }
        for e in &mut self.twins[..self.len] {
            *e = HalfEdgeId::new(e.index() as u32 + edge_offset);
        }
    }
}
