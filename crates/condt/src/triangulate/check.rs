//! The full check of a [`Triangulation`]: topology, duplicates map, and exact geometry.
//!
//! Owns: `validate`'s geometric rules (orientation, the empty circle, the hull), decided by the
//! exact predicates only. It may not change the triangulation.

use super::insert::{position_on_segment, Segment};
use super::Triangulation;
use crate::mesh::{fail, Element, HalfEdgeId, Rule, VertexId, Violation};
use crate::predicates::{in_circle, orient2d, Orientation};

impl Triangulation {
    /// Checks everything a Delaunay triangulation promises, with exact predicates:
    ///
    /// The topology ([`Mesh::check_topology`](crate::mesh::Mesh::check_topology)); every input
    /// point maps to a vertex at its position, every vertex to itself, and exactly the vertices
    /// have edges (when there are two or more); every real triangle is counter-clockwise; every
    /// edge between two real triangles is locally Delaunay, which implies the empty-circle
    /// property for every triangle; the hull is convex (it turns only clockwise or straight along
    /// its ghosts); with no triangle, every point is on one line, between its chain neighbours.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let grid: Vec<Point> = (0..100).map(|i| Point::new((i % 10) as f64, (i / 10) as f64)).collect();
    /// // Valid although every grid square is cocircular; a violation converts to `condt::Error`.
    /// triangulate(&grid)?.validate()?;
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn validate(&self) -> Result<(), Violation> {
        let mesh = &self.mesh;
        mesh.check_topology()?;
        let n = self.points.len();
        if mesh.num_vertex_ids() != n
            || self.vertex_of_input.len() != n
            || self.input_of_vertex.len() != n
        {
            return fail(Rule::VertexArrayLengths, Element::Whole);
        }
        for (i, &v) in self.vertex_of_input.iter().enumerate() {
            if v.index() >= n || !self.is_vertex(v) || self.input_of_vertex[v.index()] as usize > i
            {
                return fail(Rule::InputNotMapped, Element::InputPoint(i));
            }
        }
        let mut vertices = 0;
        for u in (0..n as u32).map(VertexId::new) {
            // Every id holds an input point; a merged duplicate's point equals its vertex's.
            let kept = self.vertex_of_input[self.input_of_vertex[u.index()] as usize];
            if self.input_point(u) != self.input_point(kept) {
                return fail(Rule::DuplicateMisplaced, Element::Vertex(u));
            }
            vertices += usize::from(kept == u);
            let has_edge = mesh.vertex_edge(u).is_some();
            if has_edge != (kept == u && self.num_vertices >= 2) {
                return fail(Rule::VertexEdgePresence, Element::Vertex(u));
            }
        }
        if vertices != self.num_vertices {
            return fail(Rule::VertexCount, Element::Whole);
        }
        if self.is_degenerate() {
            return self.check_chain();
        }
        for t in mesh.triangles() {
            let [a, b, c] = mesh.triangle_vertices(t).map(|v| self.scaled_point(v));
            if orient2d(a, b, c) != Orientation::Ccw {
                return fail(Rule::TriangleNotCcw, Element::Triangle(t));
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
                return fail(Rule::NotLocallyDelaunay, Element::HalfEdge(e));
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
                return fail(Rule::HullNotConvex, Element::HalfEdge(e));
            }
        }
        Ok(())
    }

    /// With no real triangle: every vertex on the first edge's line, the chain never doubling back.
    fn check_chain(&self) -> Result<(), Violation> {
        let mesh = &self.mesh;
        let Some(first) = mesh.edges().next() else {
            return if self.num_vertices <= 1 {
                Ok(())
            } else {
                fail(Rule::ChainMissing, Element::Whole)
            };
        };
        let [a, b] = [mesh.origin(first), mesh.dest(first)].map(|v| self.scaled_point(v));
        for v in self.vertices() {
            let p = self.scaled_point(v);
            if orient2d(a, b, p) != Orientation::Collinear {
                return fail(Rule::ChainNotCollinear, Element::Vertex(v));
            }
            let mut around = mesh.neighbors(v);
            let (left, right) = (around.next(), around.next());
            if around.next().is_some() {
                return fail(Rule::ChainBranches, Element::Vertex(v));
            }
            if let (Some(l), Some(r)) = (left, right) {
                let (pl, pr) = (self.scaled_point(l), self.scaled_point(r));
                if position_on_segment(pl, pr, p) != Segment::Inside {
                    return fail(Rule::ChainDoublesBack, Element::Vertex(v));
                }
            }
        }
        if mesh.edges().count() + 1 != self.num_vertices {
            return fail(Rule::ChainDisconnected, Element::Whole);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::triangulate;

    fn violation(tri: &Triangulation) -> (Rule, Element) {
        let v = tri.validate().unwrap_err();
        (v.rule, v.element)
    }

    /// A kite whose short diagonal `a – c` is the Delaunay edge.
    fn kite() -> Triangulation {
        let points = [(-1.0, 0.0), (0.0, -3.0), (1.0, 0.0), (0.0, 3.0)].map(Point::from);
        let tri = triangulate(&points).unwrap();
        assert_eq!(tri.validate(), Ok(()));
        tri
    }

    #[test]
    fn a_mirrored_triangulation_has_a_clockwise_triangle() {
        let mut tri = kite();
        for p in tri.points.iter_mut() {
            p.x = -p.x;
        }
        let first = tri.mesh.triangles().next().unwrap();
        assert_eq!(
            violation(&tri),
            (Rule::TriangleNotCcw, Element::Triangle(first))
        );
    }

    #[test]
    fn a_stretched_diagonal_is_not_locally_delaunay() {
        let mut tri = kite();
        let (a, c) = (tri.vertex(0), tri.vertex(2));
        let diagonal = tri
            .mesh
            .edges()
            .find(|&e| {
                let ends = [tri.mesh.origin(e), tri.mesh.dest(e)];
                ends == [a, c] || ends == [c, a]
            })
            .unwrap();
        // Still convex and counter-clockwise, but now `b – d` is the shorter diagonal.
        // (The stored positions are the stages' ones: the input times 2^199 here.)
        let stage = |x: f64, y: f64| Point::new(x * 2f64.powi(199), y * 2f64.powi(199));
        assert_eq!(tri.points[a.index()], stage(-1.0, 0.0));
        tri.points[a.index()] = stage(-10.0, 0.0);
        tri.points[c.index()] = stage(10.0, 0.0);
        assert_eq!(
            violation(&tri),
            (Rule::NotLocallyDelaunay, Element::HalfEdge(diagonal))
        );
    }

    #[test]
    fn an_unmapped_input_point_is_reported_by_position() {
        let mut tri = kite();
        tri.vertex_of_input[2] = VertexId::INFINITE;
        assert_eq!(
            violation(&tri),
            (Rule::InputNotMapped, Element::InputPoint(2))
        );
    }

    #[test]
    fn a_chain_vertex_moved_off_the_line_is_reported() {
        let line: alloc::vec::Vec<Point> = (0..4).map(|i| Point::new(i as f64, 0.0)).collect();
        let mut tri = triangulate(&line).unwrap();
        assert_eq!(tri.validate(), Ok(()));
        let v = tri.vertex(3);
        tri.points[v.index()].y = tri.points[v.index()].x / 3.0;
        assert_eq!(
            violation(&tri),
            (Rule::ChainNotCollinear, Element::Vertex(v))
        );
    }
}
