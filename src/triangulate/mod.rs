//! Delaunay triangulation of a planar point set.
//!
//! Owns: turning points into a [`Triangulation`] (a [`Mesh`] plus the points and the map from
//! input positions to vertices) and checking one. It decides signs only through
//! [`crate::predicates`] and edits topology only through the mesh arrays.
//!
//! The method is incremental insertion (Lawson's flips after each split, which yields the same
//! triangulation as Bowyer–Watson's cavity retriangulation) in a biased randomized insertion order
//! with Hilbert order inside each round, locating each point by a visibility walk from the
//! previous one; `docs/triangulation.md` explains the choice and gives the measurements.
//! See also: Amenta, Choi, Rote, "Incremental constructions con BRIO", SoCG 2003, and
//! Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric predicates",
//! Discrete Comput. Geom. 18 (1997).

mod check;
mod collinear;
mod insert;
mod order;
mod scale;

use crate::error::Error;
use crate::geometry::Point;
use crate::mesh::{HalfEdgeId, Hull, Mesh, VertexId};
use crate::predicates::{orient2d, Orientation};
use alloc::vec::Vec;
use insert::Builder;
use scale::Scale;

/// The largest number of input points: 6(2n - 2) half-edges must fit a `u32` index.
pub const MAX_POINTS: usize = 350_000_000;

/// A Delaunay triangulation of a point set, in the caller's indices.
///
/// Vertex ids are input positions: the vertex of input point `i` is `VertexId::new(i)`, except
/// for exact duplicates, which are merged into the smallest input position holding the same
/// point ([`Triangulation::vertex_of_input`]).
///
/// ```
/// use condt::{triangulate, Point};
/// let pts = [(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0), (1.0, 1.0)].map(Point::from);
/// let tri = triangulate(&pts)?;
/// assert_eq!(tri.triangles().count(), 4);
/// assert_eq!(tri.edges().count(), 8);
/// assert_eq!(tri.hull().count(), 4);
/// tri.validate().expect("a valid Delaunay triangulation");
/// # Ok::<(), condt::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Triangulation {
    points: Vec<Point>,
    scale: Scale,
    mesh: Mesh,
    vertex_of_input: Vec<VertexId>,
    num_vertices: usize,
}

/// Triangulates `points`.
///
/// Every finite input is accepted: fewer than three points, collinear points (the mesh then holds
/// the chain of segments between consecutive points, and no triangle), exact duplicates (merged,
/// see [`Triangulation::vertex_of_input`]) and cocircular sets. The result is deterministic and
/// depends only on the set of points, not on their order.
///
/// # Errors
/// [`Error::NonFinite`] for a NaN or infinite coordinate, [`Error::RangeTooWide`] when the set
/// spans more than 2^200 in magnitude, [`Error::TooManyPoints`] beyond [`MAX_POINTS`]; each names
/// the first offending input index.
///
/// ```
/// use condt::{triangulate, Point};
/// let line: Vec<Point> = (0..5).map(|i| Point::new(i as f64, 2.0 * i as f64)).collect();
/// let tri = triangulate(&line)?;
/// assert_eq!(tri.triangles().count(), 0);
/// assert_eq!(tri.edges().count(), 4); // the chain 0 - 1 - 2 - 3 - 4
/// # Ok::<(), condt::Error>(())
/// ```
pub fn triangulate(points: &[Point]) -> Result<Triangulation, Error> {
    if points.len() > MAX_POINTS {
        return Err(Error::TooManyPoints {
            count: points.len(),
            limit: MAX_POINTS,
        });
    }
    let scale = scale::choose_scale(points)?;
    let order = order::insertion_order(points);
    let sorted: Vec<Point> = order
        .iter()
        .map(|&i| scale.apply(points[i as usize]))
        .collect();

    let (mesh, vertex_of_input) = match first_triangle(&sorted) {
        None => collinear::chain(points),
        Some(start) => {
            let mut builder = Builder::new(&sorted, start);
            for v in 0..sorted.len() as u32 {
                if !start.contains(&v) {
                    builder.insert(v);
                }
            }
            let (mesh, merged) = builder.finish();
            drop(sorted);
            into_input_indices(mesh, &merged, &order)
        }
    };
    let num_vertices = vertex_of_input
        .iter()
        .enumerate()
        .filter(|&(i, v)| v.index() == i)
        .count();
    Ok(Triangulation {
        points: points.to_vec(),
        scale,
        mesh,
        vertex_of_input,
        num_vertices,
    })
}

/// The first three points, in insertion order, that make a proper triangle, counter-clockwise.
fn first_triangle(points: &[Point]) -> Option<[u32; 3]> {
    let a = 0;
    let b = points.iter().position(|&p| p != points[a])?;
    let (pa, pb) = (points[a], points[b]);
    points[b + 1..].iter().enumerate().find_map(|(k, &pc)| {
        let c = (b + 1 + k) as u32;
        match orient2d(pa, pb, pc) {
            Orientation::Ccw => Some([a as u32, b as u32, c]),
            Orientation::Cw => Some([b as u32, a as u32, c]),
            Orientation::Collinear => None,
        }
    })
}

/// Renames the builder's insertion-order vertices to input positions, merging duplicates into
/// their smallest input position.
fn into_input_indices(
    mut mesh: Mesh,
    merged: &[(u32, u32)],
    order: &[u32],
) -> (Mesh, Vec<VertexId>) {
    // Vertex edges first, while ids still follow the spatial order and the writes stay local.
    mesh.rebuild_vertex_edges(order.len());
    let mut name: Vec<u32> = order.to_vec();
    for &(dup, kept) in merged {
        name[kept as usize] = name[kept as usize].min(order[dup as usize]);
    }
    for v in mesh.origins.iter_mut() {
        if !v.is_infinite() {
            *v = VertexId::new(name[v.index()]);
        }
    }
    let mut vertex_edges = alloc::vec![HalfEdgeId::NONE; order.len()];
    for (v, &e) in mesh.vertex_edges.iter().enumerate() {
        if !e.is_none() {
            vertex_edges[name[v] as usize] = e;
        }
    }
    mesh.vertex_edges = vertex_edges;
    let mut vertex_of_input: Vec<VertexId> = (0..order.len() as u32).map(VertexId::new).collect();
    for &(dup, kept) in merged {
        let kept_name = VertexId::new(name[kept as usize]);
        vertex_of_input[order[dup as usize] as usize] = kept_name;
        // The position that gave up its name to a smaller duplicate points to the winner too.
        vertex_of_input[order[kept as usize] as usize] = kept_name;
    }
    (mesh, vertex_of_input)
}

impl Triangulation {
    /// The topology.
    #[inline]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The input points, in input order (duplicates included).
    #[inline]
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// The position of vertex `v`.
    #[inline]
    pub fn point(&self, v: VertexId) -> Point {
        self.points[v.index()]
    }

    /// Number of distinct points, that is of vertices.
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.num_vertices
    }

    /// The vertices, in increasing input position.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        self.vertex_of_input
            .iter()
            .enumerate()
            .filter(|&(i, v)| v.index() == i)
            .map(|(_, &v)| v)
    }

    /// The vertex that input point `index` became: itself, or for an exact duplicate the smallest
    /// input position with the same coordinates.
    ///
    /// # Panics
    /// If `index` is not an input position.
    #[inline]
    pub fn vertex_of_input(&self, index: usize) -> VertexId {
        self.vertex_of_input[index]
    }

    /// [`Triangulation::vertex_of_input`] for every input position at once.
    #[inline]
    pub fn input_to_vertex(&self) -> &[VertexId] {
        &self.vertex_of_input
    }

    /// The real triangles as their corners, counter-clockwise.
    pub fn triangles(&self) -> impl Iterator<Item = [VertexId; 3]> + '_ {
        self.mesh
            .triangles()
            .map(|t| self.mesh.triangle_vertices(t))
    }

    /// Every edge once, as `[a, b]` with `a < b`.
    pub fn edges(&self) -> impl Iterator<Item = [VertexId; 2]> + '_ {
        self.mesh.edges().map(|e| {
            let (a, b) = (self.mesh.origin(e), self.mesh.dest(e));
            if a < b {
                [a, b]
            } else {
                [b, a]
            }
        })
    }

    /// The neighbours of `v`, counter-clockwise; see [`Mesh::ring`].
    pub fn neighbors(&self, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        self.mesh.neighbors(v)
    }

    /// The convex hull, counter-clockwise; see [`Mesh::hull`].
    pub fn hull(&self) -> Hull<'_> {
        self.mesh.hull()
    }

    /// `true` when there is no triangle: all points are collinear or fewer than three are distinct.
    pub fn is_degenerate(&self) -> bool {
        self.mesh.triangles().next().is_none()
    }

    /// Vertex position in the exactly rescaled frame the predicates work in.
    #[inline]
    pub(crate) fn scaled_point(&self, v: VertexId) -> Point {
        self.scale.apply(self.points[v.index()])
    }
}
