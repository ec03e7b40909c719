//! The insertion order: biased randomized insertion order (BRIO) rounds, Hilbert order inside each.
//!
//! Rounds keep insertion near O(n log n) even on curves; the Hilbert order keeps walks short
//! (`docs/triangulation.md`). A point's round is a hash of its quantized bounding-box-relative
//! position, so the order depends only on the set of points.
//!
//! Owns: the order in which points are inserted, and its scratch buffers. It may not read or
//! build a mesh; the order changes only the time the insertion takes and, among cocircular
//! points, which diagonal is kept (`docs/triangulation.md`).

use crate::geometry::Point;
use alloc::vec::Vec;

/// Most bits per axis of the quantized grid (a 48-bit Hilbert index at most).
const GRID_BITS: u32 = 24;

/// Each BRIO round holds about `2^ROUND_GROWTH_BITS` times as many points as the one before.
const ROUND_GROWTH_BITS: u32 = 2;

/// One level of the Hilbert curve, branch-free: from a cell's bits `bx`, `by` at this level and
/// the orientation (`swap` exchanges the axes, `flip` mirrors both), the quadrant's rank (0 to 3:
/// lower-left, upper-left, upper-right, lower-right, unrotated) and the next level's orientation.
const fn hilbert_step(bx: u32, by: u32, swap: u32, flip: u32) -> (u32, u32, u32) {
    let exchanged = swap & (bx ^ by);
    let right = bx ^ exchanged ^ flip;
    let up = by ^ exchanged ^ flip;
    let low = up ^ 1;
    ((3 * right) ^ up, swap ^ low, flip ^ (low & right))
}

/// Four levels at once: entry `state << 8 | x_nibble << 4 | y_nibble` holds the eight index bits
/// and, above them, the orientation after them (`swap | flip << 1`).
const HILBERT_NIBBLES: [u16; 1024] = {
    let mut table = [0u16; 1024];
    let mut entry = 0;
    while entry < 1024 {
        let (x, y) = ((entry as u32 >> 4) & 15, entry as u32 & 15);
        let (mut swap, mut flip) = ((entry as u32 >> 8) & 1, (entry as u32 >> 9) & 1);
        let mut index = 0;
        let mut level = 4;
        while level > 0 {
            level -= 1;
            let (rank, next_swap, next_flip) =
                hilbert_step((x >> level) & 1, (y >> level) & 1, swap, flip);
            index = (index << 2) | rank;
            swap = next_swap;
            flip = next_flip;
        }
        table[entry] = (index | ((swap | (flip << 1)) << 8)) as u16;
        entry += 1;
    }
    table
};

/// Position of `(x, y)` on the Hilbert curve of its top `levels` bits (a multiple of four), in a
/// fixed number of table steps so that the loop unrolls.
fn hilbert_index(x: u32, y: u32, levels: u32) -> u64 {
    debug_assert!(levels % 4 == 0 && levels <= GRID_BITS);
    match levels {
        4 => hilbert_steps::<1>(x, y),
        8 => hilbert_steps::<2>(x, y),
        12 => hilbert_steps::<3>(x, y),
        16 => hilbert_steps::<4>(x, y),
        20 => hilbert_steps::<5>(x, y),
        _ => hilbert_steps::<6>(x, y),
    }
}

/// [`hilbert_index`] at `4 * STEPS` levels.
#[inline(always)]
fn hilbert_steps<const STEPS: u32>(x: u32, y: u32) -> u64 {
    let mut index = 0u64;
    let mut state = 0usize;
    let mut level = GRID_BITS;
    for _ in 0..STEPS {
        level -= 4;
        let nibbles = (((x >> level) & 15) << 4 | ((y >> level) & 15)) as usize;
        let entry = HILBERT_NIBBLES[state << 8 | nibbles];
        index = (index << 8) | u64::from(entry & 0xff);
        state = usize::from(entry >> 8);
    }
    index
}

/// A nondecreasing map of the finite doubles of one set (zero, and magnitudes from `smallest`
/// up; strictly increasing up to 2^53 bit patterns above `smallest`, the rest rounded, whose
/// ties [`order_warped_ties`] settles), growing like the log of the magnitude (the ordered bit
/// pattern): a grid on it
/// has as many cells in [1e-300, 1e-299] as in [1, 10]. Counting from `smallest`, the bit pattern
/// of the set's smallest nonzero magnitude, the set times a power of two gets the same order.
pub(crate) fn logarithmic(x: f64, smallest: u64) -> f64 {
    let bits = x.to_bits() & !(1 << 63);
    debug_assert!(
        bits == 0 || bits >= smallest,
        "a magnitude below the set's smallest"
    );
    let magnitude = if bits == 0 {
        0.0
    } else {
        (bits - smallest + 1) as f64
    };
    if x < 0.0 {
        -magnitude
    } else {
        magnitude
    }
}

/// Orders by their own coordinates the points of `order` (an [`insertion_order_into`] of
/// `warped`, the [`logarithmic`] map of `points`) that share a warped place. The map rounds where
/// a magnitude's bit pattern lies more than 2^53 above the set's smallest (one unit in the last
/// place beside 1, when the set reaches down to 1e-70), and the grid sort leaves points of one
/// place in input order: cocircular ones then met the triangulation in an order that the input
/// decided, and so did its diagonal (a review's repro, test
/// `wide_ties_do_not_follow_the_input_order`). Such points are adjacent in `order`, as the cell
/// sort compares their equal places.
pub(crate) fn order_warped_ties(points: &[Point], warped: &[Point], order: &mut [u32]) {
    let own = |i: &u32| points[*i as usize];
    for run in order.chunk_by_mut(|&i, &j| warped[i as usize] == warped[j as usize]) {
        run.sort_unstable_by(|i, j| own(i).lexicographic_cmp(own(j)));
    }
}

/// The bit pattern of the smallest nonzero coordinate magnitude (for [`logarithmic`]), 1 if none.
pub(crate) fn smallest_magnitude(points: &[Point]) -> u64 {
    points
        .iter()
        .flat_map(|p| [p.x, p.y])
        .map(|c| c.to_bits() & !(1 << 63))
        .filter(|&bits| bits != 0)
        .min()
        .unwrap_or(1)
}

/// The output function of SplitMix64 (Steele, Lea and Flood 2014), a bijection of `u64`.
pub(crate) fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The sort keys of [`insertion_order_into`] and the radix sort's second array, lent by the
/// caller (allocated on the caller's thread: see `cut_order`).
#[derive(Default)]
pub(crate) struct Scratch {
    keys: Vec<u64>,
    buffer: Vec<u64>,
}

impl Scratch {
    /// Room for ordering `n` points, allocated by the calling thread.
    pub(crate) fn with_capacity(n: usize) -> Scratch {
        Scratch {
            keys: Vec::with_capacity(n),
            buffer: Vec::with_capacity(n),
        }
    }
}

/// Writes into `order` (as long as `points`) the order in which to insert `points`, as indices
/// into it, sorting in `scratch`; a grid cell of [`CROWDED_CELL`] points or more gets an order of
/// its own (see there).
pub(crate) fn insertion_order_into(points: &[Point], order: &mut [u32], scratch: &mut Scratch) {
    let n = points.len();
    debug_assert_eq!(order.len(), n);
    let (mut min_x, mut min_y) = (f64::INFINITY, f64::INFINITY);
    let (mut max_x, mut max_y) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    // Finite points: plain comparisons, cheaper than `f64::min`'s NaN rule.
    for p in points {
        min_x = if p.x < min_x { p.x } else { min_x };
        min_y = if p.y < min_y { p.y } else { min_y };
        max_x = if p.x > max_x { p.x } else { max_x };
        max_y = if p.y > max_y { p.y } else { max_y };
    }
    let span = (max_x - min_x).max(max_y - min_y);
    if n < 2 || span <= 0.0 {
        for (slot, i) in order.iter_mut().zip(0..) {
            *slot = i;
        }
        return;
    }
    let cells = ((1u64 << GRID_BITS) - 1) as f64;
    let to_grid = cells / span;
    if !to_grid.is_normal() {
        // The width overflows (`span` infinite, `to_grid` 0) or is so small that `to_grid` does:
        // every point would land in one cell, and a crowded cell would be ordered again, the same
        // way, without end. The same grid on a copy brought into range by a power of two.
        let copy = within_range(points, span, (min_x, min_y));
        return insertion_order_into(&copy, order, scratch);
    }
    let size_bits = usize::BITS - n.leading_zeros();
    // Round r (0 = first) holds about n / g^(rounds - r) points, g = 2^ROUND_GROWTH_BITS: a point
    // lands in the last round with probability 1 - 1/g, in the one before with (1 - 1/g) / g, ...
    let rounds = size_bits / ROUND_GROWTH_BITS;
    // At least 2^8 cells per point on average (in whole table steps of four levels): finer cells
    // would not improve locality, and points sharing a cell are ordered by their coordinates.
    let levels = ((size_bits / 2 + 4).next_multiple_of(4)).min(GRID_BITS);
    let key_of = |p: &Point| {
        let qx = (((p.x - min_x) * to_grid) as u32).min(cells as u32);
        let qy = (((p.y - min_y) * to_grid) as u32).min(cells as u32);
        let level =
            (mix(((qx as u64) << 32) | qy as u64).trailing_zeros() / ROUND_GROWTH_BITS).min(rounds);
        let round = (rounds - level) as u64;
        (round << (2 * levels)) | hilbert_index(qx, qy, levels)
    };
    let key_bits = 2 * levels + (u32::BITS - rounds.leading_zeros());
    let index_bits = usize::BITS - (n - 1).leading_zeros();
    if key_bits + index_bits <= u64::BITS {
        // Key and input position packed in one word, radix-sorted on the key bits only.
        let packed = &mut scratch.keys;
        packed.clear();
        packed.extend(
            points
                .iter()
                .enumerate()
                .map(|(i, p)| (key_of(p) << index_bits) | i as u64),
        );
        radix_sort(packed, &mut scratch.buffer, index_bits, key_bits);
        let index_mask = (1u64 << index_bits) - 1;
        for (slot, &w) in order.iter_mut().zip(packed.iter()) {
            *slot = (w & index_mask) as u32;
        }
        for_each_run(
            packed,
            |w| w >> index_bits,
            |run| order_cell(points, &mut order[run]),
        );
    } else {
        let mut keyed: Vec<(u64, u32)> = points
            .iter()
            .enumerate()
            .map(|(i, p)| (key_of(p), i as u32))
            .collect();
        keyed.sort_unstable_by_key(|&(key, _)| key);
        for (slot, &(_, i)) in order.iter_mut().zip(&keyed) {
            *slot = i;
        }
        for_each_run(
            &keyed,
            |&(key, _)| key,
            |run| order_cell(points, &mut order[run]),
        );
    }
}

/// `points` with a width whose grid step is a normal number, each in the cell the ideal grid
/// would give it: halved when the width overflows (exact for every normal coordinate), or shifted
/// to the lower-left corner `min` (rounding as the ideal grid's differences do) and scaled up by
/// 2^600 when it is below about 2^-1000.
fn within_range(points: &[Point], span: f64, min: (f64, f64)) -> Vec<Point> {
    if span.is_infinite() {
        points
            .iter()
            .map(|p| Point::new(p.x / 2.0, p.y / 2.0))
            .collect()
    } else {
        let up = libm::ldexp(1.0, 600);
        let (min_x, min_y) = min;
        points
            .iter()
            .map(|p| Point::new((p.x - min_x) * up, (p.y - min_y) * up))
            .collect()
    }
}

/// A grid cell this full (a dense cluster, far points having stretched the box) is ordered like a
/// set of its own instead of by coordinates, which would make each walk cross much of it
/// (`docs/triangulation.md`, "Crowded cells"): a circle of 64,000 points and one point at 1e4
/// took 2.0 s to triangulate that way, against 0.05 s; 1,000 rings of 1,000 points far apart,
/// 7.4 s with cells ordered from 1,024 points, against 0.49 s from 64.
const CROWDED_CELL: usize = 1 << 6;

/// Orders the points `run` sharing one grid cell: a crowded one by [`insertion_order_into`] on
/// them alone, any other by coordinates, never by input position.
fn order_cell(points: &[Point], run: &mut [u32]) {
    let position = |i: &u32| points[*i as usize];
    if run.len() >= CROWDED_CELL {
        let cell: Vec<Point> = run.iter().map(position).collect();
        // Each call's grid spans its own points, whose extremes along the wider axis land in
        // different cells: every level of this recursion splits its set.
        if cell.iter().any(|p| p.lexicographic_cmp(cell[0]).is_ne()) {
            let mut local = alloc::vec![0; cell.len()];
            insertion_order_into(&cell, &mut local, &mut Scratch::default());
            let ordered: Vec<u32> = local.iter().map(|&k| run[k as usize]).collect();
            run.copy_from_slice(&ordered);
            return;
        }
    }
    run.sort_unstable_by(|i, j| position(i).lexicographic_cmp(position(j)));
}

/// Calls `sort` on every range of two or more consecutive items with equal `key`.
fn for_each_run<T, K: PartialEq>(
    items: &[T],
    key: impl Fn(&T) -> K,
    mut sort: impl FnMut(core::ops::Range<usize>),
) {
    let mut start = 0;
    for run in items.chunk_by(|a, b| key(a) == key(b)) {
        if run.len() > 1 {
            sort(start..start + run.len());
        }
        start += run.len();
    }
}

/// Stable LSD radix sort of `values` on bits `low .. low + bits`, in nine-bit digits, all counts
/// in one read, alternating with `buffer`.
fn radix_sort(values: &mut Vec<u64>, buffer: &mut Vec<u64>, low: u32, bits: u32) {
    const DIGIT_BITS: u32 = 9;
    const DIGITS: usize = 1 << DIGIT_BITS;
    const MAX_PASSES: usize = 64usize.div_ceil(DIGIT_BITS as usize);
    let passes = (bits.div_ceil(DIGIT_BITS) as usize).min(MAX_PASSES);
    let digit =
        |v: u64, pass: usize| ((v >> (low + pass as u32 * DIGIT_BITS)) as usize) & (DIGITS - 1);
    // On the heap, and only the passes used: 16 KB of stack at every level of a crowded cell's
    // recursion was too much for an embedded caller's stack.
    let mut counts = alloc::vec![[0u32; DIGITS]; passes];
    for &v in values.iter() {
        for (pass, count) in counts.iter_mut().enumerate().take(passes) {
            count[digit(v, pass)] += 1;
        }
    }
    buffer.clear();
    buffer.resize(values.len(), 0);
    for (pass, offsets) in counts.iter_mut().enumerate().take(passes) {
        // A digit shared by every value would not move anything.
        if offsets.contains(&(values.len() as u32)) {
            continue;
        }
        let mut total = 0;
        for slot in offsets.iter_mut() {
            let count = *slot;
            *slot = total;
            total += count;
        }
        for &v in values.iter() {
            let d = digit(v, pass);
            buffer[offsets[d] as usize] = v;
            offsets[d] += 1;
        }
        core::mem::swap(values, buffer);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`insertion_order_into`] into a new list.
    fn insertion_order(points: &[Point]) -> Vec<u32> {
        let mut order = alloc::vec![0; points.len()];
        insertion_order_into(points, &mut order, &mut Scratch::default());
        order
    }

    /// The same curve one level at a time, without the table.
    fn hilbert_index_by_levels(x: u32, y: u32) -> u64 {
        let (mut index, mut swap, mut flip) = (0u64, 0, 0);
        for level in (0..GRID_BITS).rev() {
            let (rank, s, f) = hilbert_step((x >> level) & 1, (y >> level) & 1, swap, flip);
            index = (index << 2) | u64::from(rank);
            (swap, flip) = (s, f);
        }
        index
    }

    #[test]
    fn table_steps_agree_with_single_levels() {
        for k in 0..20_000u64 {
            let (x, y) = ((mix(k) as u32) >> 8, (mix(k + 1_000_003) as u32) >> 8);
            let full = hilbert_index(x, y, GRID_BITS);
            assert_eq!(full, hilbert_index_by_levels(x, y));
            // Fewer levels: the curve at a coarser grid, the leading digits of the full index.
            for levels in (4..GRID_BITS).step_by(4) {
                let coarse = full >> (2 * (GRID_BITS - levels));
                assert_eq!(hilbert_index(x, y, levels), coarse, "{levels} levels");
            }
        }
    }

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
        // The whole grid at the coarsest table step: a 16 x 16 curve through every cell.
        let mut coarse: Vec<(u64, u32, u32)> = Vec::new();
        for x in 0..16u32 {
            for y in 0..16u32 {
                coarse.push((
                    hilbert_index(x << (GRID_BITS - 4), y << (GRID_BITS - 4), 4),
                    x,
                    y,
                ));
            }
        }
        coarse.sort_unstable();
        assert_eq!(coarse[0].0, 0);
        for w in coarse.windows(2) {
            assert_eq!(
                w[0].1.abs_diff(w[1].1) + w[0].2.abs_diff(w[1].2),
                1,
                "{:?} -> {:?}",
                w[0],
                w[1]
            );
            assert_eq!(w[0].0 + 1, w[1].0);
        }
    }

    #[test]
    fn radix_sort_orders_by_the_selected_bits_and_is_stable() {
        let mut values: Vec<u64> = (0..5000u64)
            .map(|i| (mix(i) & 0xffff_ff00) | (i & 0xff))
            .collect();
        let mut expected = values.clone();
        expected.sort_by_key(|v| v >> 8);
        radix_sort(&mut values, &mut Vec::new(), 8, 24);
        assert_eq!(values, expected);
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

    /// Points `i` and `i + 1` of `order`, summed over the order: how far the walks of an
    /// insertion in that order travel, roughly.
    fn path_length(points: &[Point], order: &[u32]) -> f64 {
        order
            .windows(2)
            .map(|w| libm::sqrt(points[w[0] as usize].dist2(points[w[1] as usize])))
            .sum()
    }

    /// A set whose box one far point stretches: its cluster shares one grid cell, and is ordered
    /// as a set of its own (a short path through it), not by coordinates (where every step jumps
    /// across the cluster in y). Sets of any size: a small one paid the coordinate order too.
    #[test]
    fn a_crowded_cell_gets_a_spatial_order() {
        // 500 points: below 1,024, the bound until a triangulator tester's review found rings of
        // a few hundred points far apart ten to twenty-five times slower than of 1,024.
        for n in [CROWDED_CELL, 500, 4 * CROWDED_CELL] {
            crowded_cell_order(n);
        }
    }

    fn crowded_cell_order(n: usize) {
        let mut points: Vec<Point> = (0..n as u64)
            .map(|k| {
                let (a, b) = (mix(2 * k), mix(2 * k + 1));
                Point::new(
                    (a >> 11) as f64 / 2f64.powi(53),
                    (b >> 11) as f64 / 2f64.powi(53),
                )
            })
            .collect();
        points.push(Point::new(1e7, 1e7));
        let order = insertion_order(&points);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert!(seen.iter().enumerate().all(|(i, &j)| i as u32 == j));
        let cluster: Vec<u32> = order
            .iter()
            .copied()
            .filter(|&i| (i as usize) < n)
            .collect();
        // A Hilbert order through n uniform points is about 0.7 sqrt(n) long (with the BRIO
        // rounds a little more); the coordinate order about n / 3.
        let length = path_length(&points, &cluster);
        assert!(length < 4.0 * libm::sqrt(n as f64), "path {length}");
        // Input order does not matter.
        let reversed: Vec<Point> = points.iter().rev().copied().collect();
        let order_rev = insertion_order(&reversed);
        let a: Vec<Point> = order.iter().map(|&i| points[i as usize]).collect();
        let b: Vec<Point> = order_rev.iter().map(|&i| reversed[i as usize]).collect();
        assert_eq!(a, b);
    }
}
