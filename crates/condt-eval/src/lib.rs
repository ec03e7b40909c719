//! # condt-eval
//!
//! What a curve reconstruction is measured against: [`sample`] places points along shapes with
//! known connectivity (and, on request, density changes, noise and outliers) and reports the
//! ground-truth edges; [`score`] compares any program's edge list with such a ground truth.
//! Neither triangulates nor reconstructs, so they judge condt and its competitors alike.
//!
//! ```
//! use condt::{reconstruct, Params, Point};
//! use condt_eval::sample::{sample, Sampling, Shape};
//! use condt_eval::score::score;
//!
//! let truth = sample(&[Shape::circle(Point::new(0.0, 0.0), 1.0)], &Sampling::new(0.2))?;
//! let result = reconstruct(&truth.points, &Params::default())?;
//! let edges: Vec<[usize; 2]> = result.edges().collect();
//! let s = score(&truth.points, &edges, &truth.edges)?;
//! assert!(s.exact);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![cfg_attr(not(feature = "std"), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]

extern crate alloc;

pub mod sample;

/// The most points a sample may have: as many as the triangulation takes.
use condt::MAX_POINTS;
pub mod score;

/// The one geometric type both modules speak, under the path they use inside `condt` too (the
/// core's unit tests include `sample.rs` as a module of their own).
mod geometry {
    pub use condt::Point;
}

#[cfg(test)]
#[path = "../../condt/src/test_rng.rs"]
#[allow(dead_code)] // each crate uses part of the shared generator
mod test_rng;
