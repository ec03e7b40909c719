//! Topological invariants of a [`Mesh`], checked without looking at coordinates.
//!
//! Owns: the rules a mesh's arrays must obey and the [`Violation`] naming a broken one. It may
//! not read coordinates (geometry is `triangulate::check`'s) nor change the mesh.

use super::{HalfEdgeId, Mesh, TriangleId, VertexId};
use alloc::vec;
use core::fmt;

/// A broken invariant found by [`Mesh::check_topology`] or
/// [`Triangulation::validate`](crate::Triangulation::validate): the rule, and where it fails.
///
/// ```
/// use condt::mesh::{Element, Rule, TriangleId, Violation};
/// let broken = Violation { rule: Rule::TriangleNotCcw, element: Element::Triangle(TriangleId::new(3)) };
/// assert_eq!(broken.to_string(), "invalid mesh: triangle is not counter-clockwise (at triangle 3)");
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Violation {
    /// The invariant that does not hold.
    pub rule: Rule,
    /// Where it fails.
    pub element: Element,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid mesh: {} (at {})", self.rule, self.element)
    }
}

impl core::error::Error for Violation {}

/// Declares [`Rule`] and its [`Rule::description`], each variant's words beside its documentation.
macro_rules! rules {
    ($($(#[$doc:meta])* $rule:ident => $words:literal,)*) => {
        /// One invariant of a mesh or a triangulation: topology, checked by
        /// [`Mesh::check_topology`], or maps and exact geometry, by
        /// [`Triangulation::validate`](crate::Triangulation::validate). Each names the kind of
        /// [`Element`] it reports.
        ///
        /// ```
        /// use condt::mesh::Rule;
        /// assert_eq!(Rule::RepeatedCorner.to_string(), "triangle repeats a corner");
        /// ```
        #[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
        #[non_exhaustive]
        pub enum Rule {
            $($(#[$doc])* $rule,)*
        }

        impl Rule {
            /// The invariant, in words.
            ///
            /// ```
            /// use condt::mesh::Rule;
            /// assert_eq!(Rule::HullNotConvex.description(), "hull is not convex");
            /// ```
            pub fn description(&self) -> &'static str {
                match self {
                    $(Rule::$rule => $words,)*
                }
            }
        }
    };
}

rules! {
    // Topology: `Mesh::check_topology`.
    /// The half-edge arrays have different lengths, or not a multiple of three. [`Element::Whole`].
    ArrayLengths => "array lengths disagree",
    /// A triangle has the same vertex at two corners. [`Element::Triangle`].
    RepeatedCorner => "triangle repeats a corner",
    /// A triangle corner is a finite vertex outside the vertex id space. [`Element::Triangle`].
    CornerOutOfRange => "triangle corner out of range",
    /// A half-edge's twin is out of range, or is the half-edge itself. [`Element::HalfEdge`].
    TwinOutOfRange => "twin out of range or itself",
    /// The twin of a half-edge's twin is not the half-edge. [`Element::HalfEdge`].
    TwinNotMutual => "twin of twin is not the half-edge",
    /// A half-edge's twin does not join the same two vertices the other way. [`Element::HalfEdge`].
    TwinNotReversed => "twin does not run the other way",
    /// A vertex that no half-edge leaves has a vertex edge. [`Element::Vertex`].
    StrayVertexEdge => "vertex without edges has a vertex edge",
    /// A vertex that half-edges leave has no (or an out-of-range) vertex edge. [`Element::Vertex`].
    MissingVertexEdge => "vertex with edges has no vertex edge",
    /// A vertex edge does not leave its vertex. [`Element::Vertex`].
    VertexEdgeNotLeaving => "vertex edge does not leave its vertex",
    /// The vertex edge of a hull vertex does not point to infinity. [`Element::Vertex`].
    HullVertexEdgeNotToInfinity => "vertex edge of a hull vertex does not point to infinity",
    /// The ring of a vertex does not close within its degree. [`Element::Vertex`].
    RingNotClosed => "ring does not close within the vertex's degree",
    /// The ring of a vertex closes before meeting every half-edge leaving it. [`Element::Vertex`].
    RingIncomplete => "ring misses some edges of its vertex",
    /// `V - E + F` is not 2: the triangles do not form a sphere. [`Element::Whole`].
    EulerCharacteristic => "Euler's formula fails: not a sphere",

    // Maps: `Triangulation::validate`.
    /// The vertex id space, the coordinates and the two maps differ in length. [`Element::Whole`].
    VertexArrayLengths => "vertex arrays do not match the number of points",
    /// An input maps to no vertex, or one not naming its smallest copy. [`Element::InputPoint`].
    InputNotMapped => "input point maps to no vertex, or not to its smallest duplicate",
    /// A merged duplicate's id holds a point other than its vertex's. [`Element::Vertex`].
    DuplicateMisplaced => "duplicate merged into a vertex elsewhere",
    /// A vertex edge on a non-vertex id, or none on a vertex (of two or more). [`Element::Vertex`].
    VertexEdgePresence => "vertex edge present where no vertex is, or missing",
    /// The stored number of vertices disagrees with the maps. [`Element::Whole`].
    VertexCount => "vertex count disagrees with the maps",

    // Geometry: `Triangulation::validate`, exact predicates.
    /// A real triangle is not strictly counter-clockwise. [`Element::Triangle`].
    TriangleNotCcw => "triangle is not counter-clockwise",
    /// An edge between two real triangles fails the strict in-circle test: it is not locally
    /// Delaunay. [`Element::HalfEdge`] (the one of the pair with the smaller id).
    NotLocallyDelaunay => "edge is not locally Delaunay",
    /// Consecutive hull edges turn counter-clockwise seen from the ghosts: the hull is not convex.
    /// [`Element::HalfEdge`] (the first hull edge, clockwise).
    HullNotConvex => "hull is not convex",

    // Collinear input (no real triangle): `Triangulation::validate`.
    /// At least two distinct points, but no edge. [`Element::Whole`].
    ChainMissing => "distinct points but no edge",
    /// There is no real triangle, yet a vertex is off the line of the chain. [`Element::Vertex`].
    ChainNotCollinear => "no triangle, yet the points are not collinear",
    /// A chain vertex has more than two neighbours. [`Element::Vertex`].
    ChainBranches => "chain vertex with more than two neighbours",
    /// A chain vertex does not lie between its two neighbours. [`Element::Vertex`].
    ChainDoublesBack => "chain vertex is not between its neighbours",
    /// The chain's edges do not join every vertex. [`Element::Whole`].
    ChainDisconnected => "chain does not join every vertex",
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.description())
    }
}

/// The element at which a [`Rule`] fails.
///
/// ```
/// use condt::mesh::{Element, VertexId};
/// assert_eq!(Element::Vertex(VertexId::new(4)).to_string(), "vertex 4");
/// assert_eq!(Element::InputPoint(7).to_string(), "input point 7");
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Element {
    /// A half-edge.
    HalfEdge(HalfEdgeId),
    /// A triangle (real or ghost).
    Triangle(TriangleId),
    /// A vertex id.
    Vertex(VertexId),
    /// An input position.
    InputPoint(usize),
    /// No one element: an array length or a global count.
    Whole,
}

impl fmt::Display for Element {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Element::HalfEdge(e) => write!(f, "half-edge {}", e.index()),
            Element::Triangle(t) => write!(f, "triangle {}", t.index()),
            Element::Vertex(v) => write!(f, "vertex {}", v.index()),
            Element::InputPoint(i) => write!(f, "input point {i}"),
            Element::Whole => f.write_str("the whole mesh"),
        }
    }
}

/// `rule` broken at `element`, as an error.
pub(crate) fn fail(rule: Rule, element: Element) -> Result<(), Violation> {
    Err(Violation { rule, element })
}

impl Mesh {
    /// Checks that the arrays describe a triangulated sphere: every topological [`Rule`].
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let tri = triangulate(&[(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (1.0, 3.0)].map(Point::from))?;
    /// assert!(tri.mesh().check_topology().is_ok());
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn check_topology(&self) -> Result<(), Violation> {
        let n_half = self.origins.len();
        if self.twins.len() != n_half || n_half % 3 != 0 {
            return fail(Rule::ArrayLengths, Element::Whole);
        }
        for t in (0..(n_half / 3) as u32).map(TriangleId::new) {
            let [a, b, c] = self.triangle_vertices(t);
            if a == b || b == c || c == a {
                return fail(Rule::RepeatedCorner, Element::Triangle(t));
            }
            for v in [a, b, c] {
                if !v.is_infinite() && v.index() >= self.vertex_edges.len() {
                    return fail(Rule::CornerOutOfRange, Element::Triangle(t));
                }
            }
        }
        let mut out_degree = vec![0u32; self.vertex_edges.len()];
        let mut to_infinity = vec![false; self.vertex_edges.len()];
        let mut infinite_used = false;
        for e in (0..n_half as u32).map(HalfEdgeId::new) {
            let t = self.twin(e);
            if t.index() >= n_half || t == e {
                return fail(Rule::TwinOutOfRange, Element::HalfEdge(e));
            }
            if self.twin(t) != e {
                return fail(Rule::TwinNotMutual, Element::HalfEdge(e));
            }
            if self.origin(t) != self.dest(e) || self.dest(t) != self.origin(e) {
                return fail(Rule::TwinNotReversed, Element::HalfEdge(e));
            }
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
            let vertex = VertexId::new(v as u32);
            let start = self.vertex_edges[v];
            if degree == 0 {
                if !start.is_none() {
                    return fail(Rule::StrayVertexEdge, Element::Vertex(vertex));
                }
                continue;
            }
            vertices += 1;
            if start.is_none() || start.index() >= n_half {
                return fail(Rule::MissingVertexEdge, Element::Vertex(vertex));
            }
            if self.origin(start) != vertex {
                return fail(Rule::VertexEdgeNotLeaving, Element::Vertex(vertex));
            }
            if to_infinity[v] && !self.dest(start).is_infinite() {
                return fail(Rule::HullVertexEdgeNotToInfinity, Element::Vertex(vertex));
            }
            // The ring must come back to `start` in exactly `degree` steps.
            let mut e = start;
            let back_after = (1..=degree).find(|_| {
                e = self.twin(e.prev());
                e == start
            });
            match back_after {
                None => return fail(Rule::RingNotClosed, Element::Vertex(vertex)),
                Some(steps) if steps != degree => {
                    return fail(Rule::RingIncomplete, Element::Vertex(vertex))
                }
                Some(_) => {}
            }
        }
        if n_half > 0 {
            // A triangulated sphere: V - E + F = 2.
            let (edges, faces) = (n_half / 2, n_half / 3);
            if vertices + faces != edges + 2 {
                return fail(Rule::EulerCharacteristic, Element::Whole);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::triangulate;
    use alloc::string::ToString;

    /// A square with its centre: four hull vertices and one inner vertex of degree four.
    fn mesh() -> Mesh {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)].map(Point::from);
        let mesh = triangulate(&square).unwrap().mesh().clone();
        assert_eq!(mesh.check_topology(), Ok(()));
        mesh
    }

    fn violation(mesh: &Mesh) -> (Rule, Element) {
        let v = mesh.check_topology().unwrap_err();
        (v.rule, v.element)
    }

    #[test]
    fn a_shortened_array_is_reported_for_the_whole_mesh() {
        let mut m = mesh();
        m.twins.pop();
        assert_eq!(violation(&m), (Rule::ArrayLengths, Element::Whole));
    }

    #[test]
    fn a_repeated_corner_is_reported_at_its_triangle() {
        let mut m = mesh();
        m.origins[3 * 2 + 1] = m.origins[3 * 2];
        let t = Element::Triangle(TriangleId::new(2));
        assert_eq!(violation(&m), (Rule::RepeatedCorner, t));
    }

    #[test]
    fn broken_twins_are_reported_at_the_first_half_edge_involved() {
        let mut m = mesh();
        m.twins[4] = HalfEdgeId::new(4);
        let at = Element::HalfEdge(HalfEdgeId::new(4));
        assert_eq!(violation(&m), (Rule::TwinOutOfRange, at));

        // Half-edge 0 now points at a half-edge that does not point back; its old twin still
        // points at 0, but 0 comes first.
        let mut m = mesh();
        let other = (1..m.num_half_edges() as u32)
            .map(HalfEdgeId::new)
            .find(|&e| e != m.twin(HalfEdgeId::new(0)) && m.twin(e) != HalfEdgeId::new(0))
            .unwrap();
        m.twins[0] = other;
        let at = Element::HalfEdge(HalfEdgeId::new(0));
        assert_eq!(violation(&m), (Rule::TwinNotMutual, at));
    }

    #[test]
    fn wrong_vertex_edges_are_reported_at_their_vertex() {
        let m = mesh();
        // The centre is the one vertex whose ring has no ghost.
        let centre = (0..m.num_vertex_ids() as u32)
            .map(VertexId::new)
            .find(|&v| m.ring(v).count() == 4)
            .unwrap();
        let corner = (0..m.num_vertex_ids() as u32)
            .map(VertexId::new)
            .find(|&v| v != centre)
            .unwrap();

        let mut broken = m.clone();
        broken.vertex_edges[centre.index()] = m.vertex_edges[centre.index()].next();
        let at = Element::Vertex(centre);
        assert_eq!(violation(&broken), (Rule::VertexEdgeNotLeaving, at));

        // A hull vertex whose edge leaves it, but towards a finite neighbour.
        let mut broken = m.clone();
        broken.vertex_edges[corner.index()] = m.ring(corner).next().unwrap();
        let at = Element::Vertex(corner);
        assert_eq!(violation(&broken), (Rule::HullVertexEdgeNotToInfinity, at));

        let mut broken = m.clone();
        broken.vertex_edges[corner.index()] = HalfEdgeId::NONE;
        assert_eq!(violation(&broken), (Rule::MissingVertexEdge, at));
    }

    #[test]
    fn a_violation_prints_its_rule_and_element() {
        let mut m = mesh();
        m.twins.pop();
        let text = m.check_topology().unwrap_err().to_string();
        assert_eq!(
            text,
            "invalid mesh: array lengths disagree (at the whole mesh)"
        );
    }
}
