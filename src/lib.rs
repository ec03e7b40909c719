//! # condt
//!
//! Curve reconstruction from unorganized planar points, standing on its own exact Delaunay kernel.
//!
//! [`condt::reconstruct`] returns the curves through a point set, with
//! every intermediate graph kept for inspection. Underneath is the kernel, usable on its own:
//! exact predicates ([`predicates`]), a compact half-edge mesh ([`mesh`]) and an incremental
//! Delaunay triangulator ([`triangulate()`], in the module [`mod@triangulate`]).
//!
//! ```
//! use condt::{triangulate, Point};
//!
//! let points = [
//!     Point::new(0.0, 0.0),
//!     Point::new(1.0, 0.0),
//!     Point::new(0.0, 1.0),
//!     Point::new(1.0, 1.0),
//!     Point::new(0.0, 0.0), // an exact duplicate of point 0
//! ];
//! let tri = triangulate(&points)?;
//! assert_eq!(tri.num_vertices(), 4);
//! assert_eq!(tri.triangles().count(), 2);
//! // Point 4 is merged into point 0, never dropped silently:
//! assert_eq!(tri.vertex_of_input(4), tri.vertex_of_input(0));
//! assert_eq!(tri.input_index(tri.vertex_of_input(4)), 0);
//! tri.validate()?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Features
//! - `std` (default): file I/O helpers ([`io`]) and the `condt` command-line tool.
//! - `parallel` (default, implies `std`): multi-threaded stages, on rayon.
//!
//! With `--no-default-features` the library is `#![no_std]` and needs only `alloc`.
//!
//! ## Layout
//! Each module depends only on the ones listed before it; `docs/architecture.md` draws the graph.
//! - [`error`]: the error type shared by every module.
//! - [`geometry`]: the [`Point`] type and plain-arithmetic helpers that decide no signs.
//! - [`predicates`]: the only place a geometric sign is decided (exact, via `robust`).
//! - [`mesh`]: half-edge topology with typed ids; never sees a coordinate.
//! - [`mod@triangulate`]: builds a Delaunay [`Triangulation`] from points and checks one.
//! - [`graph`]: sorted edge sets and their adjacency.
//! - [`condt`]: the ConDT stages (proximity graph, non-manifold repair, outlier removal).
//! - [`curve`]: ordered polylines from an edge set.
//! - [`sample`]: curves sampled with known connectivity, for tests and examples.
//! - [`io`] (`std`): reading point files and writing results atomically.
//! - [`cli`] (`std`): the command-line front end used by the `condt` binary.
//! - `test_rng` (unit tests only): the reproducible generator the unit tests draw inputs from.
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

extern crate alloc;

#[cfg(feature = "std")]
pub mod cli;
pub mod condt;
pub mod curve;
pub mod error;
pub mod geometry;
pub mod graph;
#[cfg(feature = "std")]
pub mod io;
pub mod mesh;
pub mod predicates;
pub mod sample;
#[cfg(test)]
mod test_rng;
pub mod triangulate;

pub use error::Error;
pub use geometry::Point;
pub use mesh::{Element, HalfEdgeId, Mesh, Rule, TriangleId, VertexId, Violation};
pub use triangulate::{triangulate, Triangulation};

/// The README's code examples, compiled and run as doctests so they cannot go stale.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
