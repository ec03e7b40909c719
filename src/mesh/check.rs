//! Topological invariants of a [`Mesh`], checked without looking at coordinates.

use super::{HalfEdgeId, Mesh, TriangleId, VertexId};
use alloc::vec;
use core::fmt;

/// A broken invariant found by [`Mesh::check_topology`] or
/// [`Triangulation::validate`](crate::Triangulation::validate): what is wrong and the index of
/// the element (half-edge, triangle or vertex, as the reason says) where it was seen.
///
/// ```
/// use condt::{triangulate, Point};
/// let tri = triangulate(&[Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0)])?;
/// assert!(tri.validate().is_ok());
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct InvalidMesh {
    /// The invariant that does not hold.
    pub reason: &'static str,
    /// Index of the element where it fails.
    pub element: usize,
}

impl fmt::Display for InvalidMesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid mesh: {} (at {})", self.reason, self.element)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for InvalidMesh {}

pub(crate) fn fail(reason: &'static str, element: usize) -> Result<(), InvalidMesh> {
    Err(InvalidMesh { reason, element })
}

impl Mesh {
    /// Checks that the arrays describe a triangulated sphere: twins are mutual and run the other
    /// way, no triangle repeats a corner or has two infinite ones, every vertex's ring closes and
    /// holds all its edges, the vertex edge of a hull vertex points to infinity, and Euler's
    /// formula holds.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (1.0, 3.0)].map(Point::from))?;
    /// assert!(tri.mesh().check_topology().is_ok());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn check_topology(&self) -> Result<(), InvalidMesh> {
        let n_half = self.origins.len();
        if self.twins.len() != n_half || n_half % 3 != 0 {
            return fail("array lengths disagree", n_half);
        }
        for t in 0..n_half / 3 {
            let [a, b, c] = self.triangle_vertices(TriangleId::new(t as u32));
            if a == b || b == c || c == a {
                return fail("triangle repeats a corner", t);
            }
            for v in [a, b, c] {
                if !v.is_infinite() && v.index() >= self.vertex_edges.len() {
                    return fail("triangle corner out of range", t);
                }
            }
        }
        for i in 0..n_half {
            let e = HalfEdgeId::new(i as u32);
            let t = self.twin(e);
            if t.index() >= n_half || t == e {
                return fail("twin out of range or itself", i);
            }
            if self.twin(t) != e {
                return fail("twin of twin is not the half-edge", i);
            }
            if self.origin(t) != self.dest(e) || self.dest(t) != self.origin(e) {
                return fail("twin does not run the other way", i);
            }
        }

        let mut out_degree = vec![0u32; self.vertex_edges.len()];
        let mut to_infinity = vec![false; self.vertex_edges.len()];
        let mut infinite_used = false;
        for i in 0..n_half {
            let e = HalfEdgeId::new(i as u32);
            let v = self.origin(e);
            if v.is_infinite() {
                infinite_used = true;
                continue;
            }
            out_degree[v.index()] += 1;
            to_infinity[v.index()] |= self.dest(e).is_infinite();
        }
        let mut vertices = usize::from(infinite_used);
        for (v, &degree) in out_degree.iter().enumerate() {
            let start = self.vertex_edges[v];
            if degree == 0 {
                if !start.is_none() {
                    return fail("vertex without edges has a vertex edge", v);
                }
                continue;
            }
            vertices += 1;
            if start.is_none() || start.index() >= n_half {
                return fail("vertex with edges has no vertex edge", v);
            }
            if self.origin(start) != VertexId::new(v as u32) {
                return fail("vertex edge does not leave its vertex", v);
            }
            if to_infinity[v] && !self.dest(start).is_infinite() {
                return fail("vertex edge of a hull vertex does not point to infinity", v);
            }
            let mut e = start;
            let mut steps = 0u32;
            loop {
                steps += 1;
                if steps > degree {
                    return fail("ring does not close within the vertex's degree", v);
                }
                e = self.twin(e.prev());
                if e == start {
                    break;
                }
            }
            if steps != degree {
                return fail("ring misses some edges of its vertex", v);
            }
        }
        if n_half > 0 {
            // A triangulated sphere: V - E + F = 2.
            let (edges, faces) = (n_half / 2, n_half / 3);
            if vertices + faces != edges + 2 {
                return fail("Euler's formula fails: not a sphere", vertices);
            }
        }
        Ok(())
    }
}
