//! # condt
//!
//! Curve reconstruction from unorganized planar points with ConDT (J. Antony, M. Reghunath,
//! S. B. Thayyil, R. Muthuganapathy, "ConDT: A 2D curve reconstruction algorithm based on a
//! constrained-neighbor proximity graph"), on its own exact Delaunay kernel.
//!
//! [`reconstruct`] gives the curves through a point set and keeps every stage for inspection:
//!
//! ```
//! use condt::{reconstruct, Params, Point};
//! let angles = (0..16).map(|k| k as f64 * std::f64::consts::TAU / 16.0);
//! let points: Vec<Point> = angles.map(|t| Point::new(2.0 * t.cos(), t.sin())).collect();
//! let result = reconstruct(&points, &Params::default())?;
//! let curve = &result.curves()[0];
//! assert!(curve.is_closed() && curve.len() == 16);
//! for i in curve.points() {
//!     let _p: Point = points[i]; // every index is a position in `points`
//! }
//! for report in result.stages() {
//!     println!("{}: {} edges", report.stage, report.graph.num_edges());
//! }
//! # Ok::<(), condt::Error>(())
//! ```
//!
//! [`reconstruct`] is a [`Pipeline`] run to its end: [`Pipeline::step`] runs one stage (or
//! smoothing pass) at a time and reports it ([`StepReport`]). [`Params`] start from a preset
//! ([`Params::default`], [`Params::paper`]) and change through their `with_*` setters. The stages
//! can also be run one by one, each a method on the graph the previous one left; the paper's
//! three algorithms are the first three: Algorithm 1 is
//! [`Triangulation::proximity_graph`], Algorithm 2 [`Graph::repair`] with [`Repair::Paper`],
//! Algorithm 3 [`Graph::remove_outliers`] (the repository's `docs/condt.md` maps each line of
//! them to the code, and says where the paper is ambiguous and what was chosen):
//!
//! ```
//! use condt::{triangulate, Point, Repair, Uniformity};
//! let points = [(0.0, 0.0), (1.0, 0.1), (2.0, 0.0), (3.0, 0.2)].map(Point::from);
//! let tri = triangulate(&points)?;
//! let proximity = tri.proximity_graph(Uniformity::default())?;
//! let repaired = proximity.repair(Repair::Paper);
//! let filtered = repaired.remove_outliers(1.7)?;
//! assert!(!filtered.fired);
//! assert_eq!(filtered.graph.edges(), vec![[0, 1], [1, 2], [2, 3]]);
//! # Ok::<(), condt::Error>(())
//! ```
//!
//! Underneath is the kernel, usable on its own: [`triangulate`] builds a [`Triangulation`], read
//! in input positions, with the half-edge level in [`mesh`] and the exact predicates in
//! [`predicates`].
//!
//! ```
//! use condt::{triangulate, Point};
//! let points = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.0, 0.0)].map(Point::from);
//! let tri = triangulate(&points)?;
//! assert_eq!(tri.num_vertices(), 4); // point 4 repeats point 0 and is merged into it
//! assert_eq!(tri.triangles().count(), 2);
//! assert_eq!(tri.hull().count(), 4);
//! tri.validate()?;
//! # Ok::<(), condt::Error>(())
//! ```
//!
//! ## Features
//! `std` (default): stage timings (the error types implement `core::error::Error`, which is
//! `std::error::Error`, in every build). `parallel` (default,
//! implies `std`): multi-threaded stages and the two halves of a large triangulation built at
//! once, on rayon (same results). Without default features the crate is `#![no_std]`, needs only
//! `alloc`, and depends on `robust` and `libm` alone; it builds for Cortex-M0 too (no atomic
//! read-modify-write needed).
//!
//! ## Stack and heap on small targets
//! Measured under QEMU on a Cortex-M4 (`thumbv7em-none-eabihf`, opt-level "z", stack painted):
//! a `reconstruct` call writes up to about 31 KB of stack, 24.7 KB of it `robust`'s adaptive
//! in-circle test when its fast filter cannot decide (near-cocircular doubles such as samples of
//! an ellipse; an integer grid, decided by exact small integers, needs 7.6 KB); a set spanning
//! more than 2^200 takes the big-integer predicates, up to about 57 KB at the widest spread.
//! The heap: 12 KB for 32 points, 830 KB for 4,000 (a bump allocator that never frees). It
//! depends on the points: scattered or noisy ones run smoothing passes, each a reconstruction
//! again. On a 64-bit host (a scratch harness's counting allocator, a realloc counted at its
//! new size, `Params::default()`, no default features, 2026-12-07), 4,000 uniform random points
//! allocate 5.7-5.8 MB in all (two sets) with 0.62 MB live at the peak, 1.48-1.49 MB without the
//! passes and 0.96 MB with `Params::paper()`; 4,000 samples of an ellipse allocate 0.68 MB.
//! Under a bump allocator, turn the passes off (`Params::with_smooth(false)`). A refused
//! allocation ends in the allocation error handler, as everywhere in `alloc`.
//!
//! ## Layout
//! Public as modules: [`mesh`], [`predicates`], [`geometry`] (points, exact power-of-two
//! scaling) and [`tiled`] (the stages' rules on edges gathered from the tiles of a split run, for
//! Python's `condt.dask`); the rest is re-exported here. `docs/architecture.md` draws the
//! modules in layers, each using only those below it, with what each owns and may not touch.
#![cfg_attr(not(feature = "std"), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]

extern crate alloc;

mod adjacency;
mod baselines;
mod bits;
mod curve;
mod error;
pub mod geometry;
mod graph;
pub mod mesh;
pub mod predicates;
mod prefetch;
mod provenance;
mod reconstruct;
mod smooth;
mod snap;
mod stages;
mod threads;
pub mod tiled;
mod triangulate;

#[cfg(test)]
mod test_graphs;
#[cfg(test)]
mod test_rng;

/// The unit tests sample curves with `condt_eval::sample`, compiled into this crate (a
/// dev-dependency on condt-eval would bring a second, incompatible `Point`).
#[cfg(test)]
#[path = "../../condt-eval/src/sample.rs"]
#[allow(dead_code)] // the tests use some of the shapes
mod sample;

pub use curve::{curves_from_edges, Curve};
pub use error::Error;
pub use geometry::Point;
pub use graph::{Graph, OutlierRemoval};
pub use provenance::{Change, EdgeStory, EndChoice, Reason};
pub use reconstruct::{
    reconstruct, reconstruct_owned, reconstruct_triangulation, Method, Params, Pipeline,
    Reconstruction, Smoothing, StageReport, StepReport, Upcoming,
};
pub use smooth::{gathered_smoothing_pass, GatheredPass};
pub use snap::snap;
pub use stages::{Repair, Stage, Switch, Uniformity};
pub use threads::parallel_available;
pub use tiled::{gathered_repair_again_input, remove_gathered_outliers};
pub use triangulate::{triangulate, triangulate_owned, Triangulation, MAX_POINTS};

/// The README's code examples, compiled and run as doctests so they cannot go stale.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
struct ReadmeDoctests;
