//! The insertion order: biased randomized insertion order (BRIO) rounds, Hilbert order inside each.
//!
//! Rounds keep the expected cost of incremental insertion near O(n log n) even on points along
//! curves, where a purely spatial order can degrade; the Hilbert order inside a round keeps every
//! walk short and the memory access local. The "random" round of each point is a hash of its
//! bounding-box-relative quantized position, so the order depends only on the set of points: the
//! same set in any input order, or translated by a power of two, is inserted in the same sequence.

use crate::geometry::Point;
use alloc::vec::Vec;

/// Most bits per axis of the quantized grid; two axes make at most a 48-bit Hilbert index.
const GRID_BITS: u32 = 24;

/// Each BRIO round holds about `2^ROUND_GROWTH_BITS` times as many points as the one before.
const ROUND_GROWTH_BITS: u32 = 2;

/// Position of `(x, y)` along the Hilbert curve filling the grid, using its top `levels` bits.
///
/// Branch-free on purpose: the bits of scattered points are random, and a branch per level
/// mispredicted half the time costs more than all the arithmetic. The curve's orientation at the
/// current level is kept as two flags, `swap` (exchange the axes) and `flip` (mirror both).
fn hilbert_index(x: u32, y: u32, levels: u32) -> u64 {
    let mut index = 0u64;
    let (mut swap, mut flip) = (0u32, 0u32);
    for level in (GRID_BITS - levels..GRID_BITS).rev() {
        let (bx, by) = ((x >> level) & 1, (y >> level) & 1);
        let exchanged = swap & (bx ^ by);
        let right = bx ^ exchanged ^ flip;
        let up = by ^ exchanged ^ flip;
        // Quadrants in curve order: lower-left 0, upper-left 1, upper-right 2, lower-right 3.
        index = (index << 2) | u64::from((3 * right) ^ up);
        let low = up ^ 1;
        swap ^= low;
        flip ^= low & right;
    }
    index
}

/// SplitMix64 finalizer: a cheap, well-mixed hash of a 64-bit word.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The order in which to insert `points`, as indices into it.
pub(crate) fn insertion_order(points: &[Point]) -> Vec<u32> {
    let n = points.len();
    let (mut min_x, mut min_y) = (f64::INFINITY, f64::INFINITY);
    let (mut max_x, mut max_y) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for p in points {
        min_x = min_x.min(p.x);
        min_y = min_y.min(p.y);
        max_x = max_x.max(p.x);
        max_y = max_y.max(p.y);
    }
    let span = (max_x - min_x).max(max_y - min_y);
    if n < 2 || span <= 0.0 {
        return (0..n as u32).collect();
    }
    let cells = ((1u64 << GRID_BITS) - 1) as f64;
    let to_grid = cells / span;
    let size_bits = usize::BITS - n.leading_zeros();
    // Round r (0 = first) holds about n / g^(rounds - r) points, g = 2^ROUND_GROWTH_BITS: a point
    // lands in the last round with probability 1 - 1/g, in the one before with (1 - 1/g) / g, ...
    let rounds = size_bits / ROUND_GROWTH_BITS;
    // About 2^8 cells per point on average: finer cells would not improve locality, and points
    // sharing a cell are ordered by their coordinates anyway.
    let levels = (size_bits / 2 + 4).min(GRID_BITS);
    let mut keyed: Vec<(u64, u32)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let qx = (((p.x - min_x) * to_grid) as u32).min(cells as u32);
            let qy = (((p.y - min_y) * to_grid) as u32).min(cells as u32);
            let level = (mix(((qx as u64) << 32) | qy as u64).trailing_zeros() / ROUND_GROWTH_BITS)
                .min(rounds);
            let round = (rounds - level) as u64;
            (
                (round << (2 * GRID_BITS)) | hilbert_index(qx, qy, levels),
                i as u32,
            )
        })
        .collect();
    keyed.sort_unstable_by_key(|&(key, _)| key);
    // Points sharing a grid cell are ordered by their coordinates, never by input position.
    let mut start = 0;
    while start < n {
        let mut end = start + 1;
        while end < n && keyed[end].0 == keyed[start].0 {
            end += 1;
        }
        if end - start > 1 {
            keyed[start..end].sort_unstable_by(|&(_, i), &(_, j)| {
                points[i as usize].lexicographic_cmp(points[j as usize])
            });
        }
        start = end;
    }
    keyed.into_iter().map(|(_, i)| i).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert_index_visits_neighbouring_cells_consecutively() {
        // On a small corner of the grid, consecutive indices are adjacent cells.
        let mut cells: Vec<(u64, u32, u32)> = Vec::new();
        for x in 0..8u32 {
            for y in 0..8u32 {
                cells.push((hilbert_index(x, y, GRID_BITS), x, y));
            }
        }
        cells.sort_unstable();
        for w in cells.windows(2) {
            let (dx, dy) = (w[0].1.abs_diff(w[1].1), w[0].2.abs_diff(w[1].2));
            assert_eq!(dx + dy, 1, "{:?} -> {:?}", w[0], w[1]);
            assert_eq!(w[0].0 + 1, w[1].0);
        }
    }

    #[test]
    fn order_is_a_permutation_independent_of_input_order() {
        let pts: Vec<Point> = (0..200)
            .map(|i| Point::new((i * 37 % 101) as f64, (i * 53 % 97) as f64))
            .collect();
        let order = insertion_order(&pts);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert!(seen.iter().enumerate().all(|(i, &j)| i as u32 == j));
        let reversed: Vec<Point> = pts.iter().rev().copied().collect();
        let order_rev = insertion_order(&reversed);
        let a: Vec<Point> = order.iter().map(|&i| pts[i as usize]).collect();
        let b: Vec<Point> = order_rev.iter().map(|&i| reversed[i as usize]).collect();
        assert_eq!(a, b);
    }
}
