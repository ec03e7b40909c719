//! The full check of a [`Triangulation`]: topology, duplicates map, and exact geometry.

use super::insert::{position_on_segment, Segment};
use super::Triangulation;
use crate::mesh::{HalfEdgeId, InvalidMesh, VertexId};
use crate::predicates::{in_circle, orient2d, Orientation};

fn fail(reason: &'static str, element: usize) -> Result<(), InvalidMesh> {
    Err(InvalidMesh { reason, element })
}

impl Triangulation {
    /// Checks everything a Delaunay triangulation promises, with exact predicates:
    /// - the topology ([`Mesh::check_topology`](crate::Mesh::check_topology));
    /// - every input point maps to a vertex at the same position, every vertex to itself, and
    ///   exactly the vertices have edges (when there are at least two);
    /// - every real triangle is counter-clockwise;
    /// - every edge between two real triangles is locally Delaunay (strict in-circle test fails);
    /// - the hull turns only clockwise-or-straight along its ghosts, i.e. it is convex;
    /// - with no triangle, all points are collinear and each chain vertex lies between its
    ///   two neighbours.
    ///
    /// Local Delaunayhood of every edge of a valid triangulation implies the empty-circle
    /// property for every triangle.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let grid: Vec<Point> = (0..100).map(|i| Point::new((i % 10) as f64, (i / 10) as f64)).collect();
    /// triangulate(&grid)?.validate().expect("valid even though every square is cocircular");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn validate(&self) -> Result<(), InvalidMesh> {
        let mesh = &self.mesh;
        mesh.check_topology()?;
        let n = self.points.len();
        if mesh.num_vertex_ids() != n
            || self.vertex_of_input.len() != n
            || self.input_of_vertex.len() != n
        {
            return fail("vertex arrays do not match the number of points", n);
        }
        for (i, &v) in self.vertex_of_input.iter().enumerate() {
            if v.index() >= n || !self.is_vertex(v) || self.input_of_vertex[v.index()] as usize > i
            {
                return fail(
                    "input point maps to no vertex, or not to its smallest duplicate",
                    i,
                );
            }
        }
        let mut vertices = 0;
        for u in (0..n as u32).map(VertexId::new) {
            // Every id holds an input point; a merged duplicate's point equals its vertex's.
            let kept = self.vertex_of_input[self.input_of_vertex[u.index()] as usize];
            if self.points[u.index()] != self.points[kept.index()] {
                return fail("duplicate merged into a vertex elsewhere", u.index());
            }
            vertices += usize::from(kept == u);
            let has_edge = mesh.vertex_edge(u).is_some();
            if has_edge != (kept == u && self.num_vertices >= 2) {
                return fail(
                    "vertex edge present where no vertex is, or missing",
                    u.index(),
                );
            }
        }
        if vertices != self.num_vertices {
            return fail("vertex count disagrees with the maps", vertices);
        }
        if self.is_degenerate() {
            return self.check_chain();
        }
        for t in mesh.triangles() {
            let [a, b, c] = mesh.triangle_vertices(t).map(|v| self.scaled_point(v));
            if orient2d(a, b, c) != Orientation::Ccw {
                return fail("triangle is not counter-clockwise", t.index());
            }
        }
        for e in mesh.edges() {
            let f = mesh.twin(e);
            let (apex_e, apex_f) = (mesh.origin(e.prev()), mesh.origin(f.prev()));
            if apex_e.is_infinite() || apex_f.is_infinite() {
                continue;
            }
            let [a, b, c, d] =
                [mesh.origin(e), mesh.dest(e), apex_e, apex_f].map(|v| self.scaled_point(v));
            if in_circle(a, b, c, d) {
                return fail("edge is not locally Delaunay", e.index());
            }
        }
        for e in (0..mesh.num_half_edges() as u32).map(HalfEdgeId::new) {
            if !mesh.origin(e.prev()).is_infinite() {
                continue;
            }
            // `e = a → b` is a hull edge, clockwise; the next one clockwise is `b → c`.
            let following = mesh.twin(e.next()).next();
            let [a, b, c] =
                [mesh.origin(e), mesh.dest(e), mesh.dest(following)].map(|v| self.scaled_point(v));
            if orient2d(a, b, c) == Orientation::Ccw {
                return fail("hull is not convex", e.index());
            }
        }
        Ok(())
    }

    /// With no real triangle: every vertex is on the line of the first edge, and the chain
    /// never doubles back.
    fn check_chain(&self) -> Result<(), InvalidMesh> {
        let mesh = &self.mesh;
        let Some(first) = mesh.edges().next() else {
            return if self.num_vertices <= 1 {
                Ok(())
            } else {
                fail("distinct points but no edge", 0)
            };
        };
        let (a, b) = (
            self.scaled_point(mesh.origin(first)),
            self.scaled_point(mesh.dest(first)),
        );
        for v in self.vertices() {
            let p = self.scaled_point(v);
            if orient2d(a, b, p) != Orientation::Collinear {
                return fail("no triangle, yet the points are not collinear", v.index());
            }
            let mut around = mesh.neighbors(v);
            let (left, right) = (around.next(), around.next());
            if around.next().is_some() {
                return fail("chain vertex with more than two neighbours", v.index());
            }
            if let (Some(l), Some(r)) = (left, right) {
                let (pl, pr) = (self.scaled_point(l), self.scaled_point(r));
                if position_on_segment(pl, pr, p) != Segment::Inside {
                    return fail("chain vertex is not between its neighbours", v.index());
                }
            }
        }
        if mesh.edges().count() + 1 != self.num_vertices {
            return fail("chain does not join every vertex", self.num_vertices);
        }
        Ok(())
    }
}
