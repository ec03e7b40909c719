//! The deterministic generator the unit tests draw their inputs from (test builds only).
//!
//! Owns: reproducible pseudo-random numbers for tests, in one definition. Nothing in the library
//! may use it; integration tests and benches have their own inputs (`tests/common`).

use crate::geometry::Point;
use alloc::vec::Vec;

/// Marsaglia's xorshift64 (shifts 13, 7, 17): fast and reproducible, which is all a test input
/// needs; not a statistical generator.
pub(crate) struct Xorshift(u64);

impl Xorshift {
    /// A generator from a nonzero seed (zero would stay zero).
    pub(crate) fn new(seed: u64) -> Self {
        debug_assert_ne!(seed, 0);
        Xorshift(seed)
    }

    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number in `0..bound` (slightly biased; fine for test inputs).
    pub(crate) fn below(&mut self, bound: u64) -> u64 {
        self.next_u64() % bound
    }

    /// A number in `[0, 1)` with 53 random bits.
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// `n` points uniform in the unit square, each drawn as `x` then `y`.
    pub(crate) fn unit_points(&mut self, n: usize) -> Vec<Point> {
        (0..n)
            .map(|_| Point::new(self.unit(), self.unit()))
            .collect()
    }
}
