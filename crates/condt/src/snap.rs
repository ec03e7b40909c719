//! Near-duplicate points made exact duplicates, before a run: [`snap`].
//!
//! Owns: moving a point onto an earlier one within a distance the caller gives. It may not touch
//! a triangulation or a stage; the points it moves become exact duplicates, which
//! [`triangulate`](crate::triangulate()) merges into the first of them as it merges any other.
//! Why: data exported piece by piece (GIS parcels ring by ring, a font's contours, tiles of a
//! scan) repeats a shared border's samples with rounding differences (1e-9 m after a
//! reprojection); the Delaunay triangulation keeps both copies, and a curve cannot run along
//! two samples a nanometre apart (the proximity graph pairs each with its twin). Only the caller
//! knows how far apart two samples may be and still be one: there is no default.

use crate::error::Error;
use crate::geometry::Point;
use alloc::vec;
use alloc::vec::Vec;
use core::cmp::Ordering;

/// Moves every point of `points` that lies within `distance` of an earlier point that stays
/// onto the nearest such point (the earliest of equally near ones), and exact duplicates with
/// the first of them; returns how many points changed. Points are taken in order, so a point
/// moves at most `distance`, and two that stay are more than `distance` apart (both up to the
/// rounding below): a chain of
/// samples each `distance` from the next is thinned, not collapsed into one. Non-finite points
/// are left as they are (the triangulation refuses them).
///
/// "Within" allows for decimal input: points whose decimals lie `distance` apart can be read a
/// few units in the last place farther apart (`500000.001` and `500000.002` at `distance`
/// 0.001), so the test allows twice the machine epsilon times the larger coordinate and
/// `distance` each (two to four units in their last place, at most a quarter of `distance`),
/// on any input: `1e15` and `1e15 + 2` are within `1.7`.
///
/// `distance` 0 changes nothing (exact duplicates are merged by the triangulation anyway).
/// O(n log n) time; at its peak about 50 bytes a point besides `points` (where every point
/// is a cell of its own), 32 once the grid is built.
///
/// # Errors
/// [`Error::InvalidParameter`] named `distance` when it is NaN, negative or infinite;
/// [`Error::TooManyPoints`] beyond [`MAX_POINTS`](crate::MAX_POINTS).
///
/// ```
/// use condt::{snap, Point};
/// // A shared border's sample exported twice, the second time after a reprojection.
/// let mut points = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0 + 1e-9, 0.0)];
/// assert_eq!(snap(&mut points, 1e-6)?, 1);
/// assert_eq!(points[2], points[1]); // now an exact duplicate: the triangulation merges it
/// assert!(snap(&mut points, f64::NAN).is_err());
/// // The slack for rounding: 2 apart is within 1.7 at 1e15 (a unit in the last place is 0.125
/// // there), not at the origin.
/// let mut far = vec![Point::new(1e15, 0.0), Point::new(1e15 + 2.0, 0.0)];
/// assert_eq!(snap(&mut far, 1.7)?, 1);
/// let mut near = vec![Point::new(0.0, 0.0), Point::new(2.0, 0.0)];
/// assert_eq!(snap(&mut near, 1.7)?, 0);
/// # Ok::<(), condt::Error>(())
/// ```
pub fn snap(points: &mut [Point], distance: f64) -> Result<usize, Error> {
    if !(distance.is_finite() && distance >= 0.0) {
        return Err(Error::invalid("distance", distance));
    }
    let (count, limit) = (points.len(), crate::triangulate::MAX_POINTS);
    if count > limit {
        return Err(Error::TooManyPoints { count, limit });
    }
    if distance == 0.0 {
        return Ok(0);
    }
    let grid = Grid::of(points, distance);
    // The points that stay, by cell: a list through `next`, the latest first.
    let mut head = vec![NONE; grid.crowded.len()];
    let mut next = vec![NONE; points.len()];
    let mut moved = 0;
    for i in 0..points.len() {
        let cell = grid.cell_of[i];
        if cell == NONE || grid.first[i] != i as u32 || !grid.crowded[cell as usize] {
            continue;
        }
        let p = points[i];
        let mut nearest: Option<(f64, u32)> = None;
        for neighbour in grid.around(cell as usize) {
            let mut j = head[neighbour];
            while j != NONE {
                let q = points[j as usize];
                let gap = apart(p, q);
                let nearer = nearest.is_none_or(|(best, k)| gap < best || (gap == best && j < k));
                if within(gap, distance, rounding(p, q, distance)) && nearer {
                    nearest = Some((gap, j));
                }
                j = next[j as usize];
            }
        }
        match nearest {
            Some((_, j)) => {
                points[i] = points[j as usize];
                moved += 1;
            }
            None => {
                next[i] = head[cell as usize];
                head[cell as usize] = i as u32;
            }
        }
    }
    for i in 0..points.len() {
        let j = grid.first[i] as usize;
        if j != i && points[i] != points[j] {
            points[i] = points[j];
            moved += 1;
        }
    }
    Ok(moved)
}

/// No point, no cell.
const NONE: u32 = u32::MAX;

/// How far the computed distance of `p` and `q` may lie beyond the distance of the decimals
/// they were read from: each coordinate rounds by half a unit in its last place, the
/// difference and `hypot` by one more, and so does `distance` itself. Twins written exactly
/// `distance` apart (`x` and `x + 0.001` at UTM's 500,000 m) computed a hair farther apart in a
/// third of the cases and stayed apart (a GIS user's review). At most a quarter of `distance`,
/// so that the grid still finds every such pair in neighbouring cells.
fn rounding(p: Point, q: Point, distance: f64) -> f64 {
    let largest = p.x.abs().max(p.y.abs()).max(q.x.abs()).max(q.y.abs());
    // Each term alone: their sum could overflow (the diff review: near f64::MAX the slack
    // became a quarter of `distance`).
    (2.0 * f64::EPSILON * largest + 2.0 * f64::EPSILON * distance).min(distance / 4.0)
}

/// Whether `gap` is at most `distance` give or take `slack`; where their sum overflows, at most
/// `distance` (a gap beyond the doubles is never within).
fn within(gap: f64, distance: f64, slack: f64) -> bool {
    let limit = distance + slack;
    gap <= if limit.is_finite() { limit } else { distance }
}

/// The distance from `p` to `q`, without overflow where its square would leave the range.
fn apart(p: Point, q: Point) -> f64 {
    libm::hypot(p.x - q.x, p.y - q.y)
}

/// A grid of square cells twice the snapping distance wide, over the finite points: two points
/// within the distance lie in the same or neighbouring cells, whatever the rounding of the
/// division (their quotients differ by at most a half and a rounding). The cells are numbered in
/// sorted order (x index, then y index); their indices are needed only while it is built.
struct Grid {
    /// Per cell, whether it holds two points or more or a neighbour cell is occupied. The lone
    /// point of an uncrowded cell has no other point within the distance: it neither moves nor
    /// is moved onto, and is passed over (speed: that is most points where the distance is below
    /// the spacing, as it is meant to be).
    crowded: Vec<bool>,
    /// Per cell, its occupied neighbours and itself as three runs of cell numbers, the rows
    /// below, at and above it: where each starts, and ([`Grid::lengths`]) how long it is, so that
    /// no point searches for them.
    starts: Vec<[u32; 3]>,
    /// The runs' lengths, at most 3 each (apart from `starts`: 15 bytes a cell, not 24).
    lengths: Vec<[u8; 3]>,
    /// Each point's cell; [`NONE`] for a point off the grid.
    cell_of: Vec<u32>,
    /// Each point's first equal position (itself when none comes before it; `-0.0` equals
    /// `0.0`, as for the triangulation); a point off the grid is its own.
    first: Vec<u32>,
}

impl Grid {
    fn of(points: &[Point], distance: f64) -> Grid {
        let side = 2.0 * distance;
        // A coordinate 2^62 cells out or more is over 2^10 times the distance from any other
        // double (its spacing there), so only a point with that very coordinate can be within
        // the distance: it gets an index of its own, from its bits, beyond 2^62 (the index would
        // saturate otherwise; within the range a neighbour's index cannot overflow, nor beyond
        // it, below 2^62 + 2^61 + 1).
        const REACH: f64 = 4_611_686_018_427_387_904.0; // 2^62
        let index = |v: f64| -> i64 {
            let cell = libm::floor(v / side);
            if cell.abs() < REACH {
                return cell as i64;
            }
            let own = (1i64 << 62) + (v.abs().to_bits() >> 2) as i64;
            if v < 0.0 {
                -own
            } else {
                own
            }
        };
        // Off the grid: non-finite points, which no distance reaches.
        let key = |p: Point| (p.x.is_finite() && p.y.is_finite()).then(|| (index(p.x), index(p.y)));
        // Sized once (memory: a collected iterator of unknown length grows by doubling).
        let mut entries: Vec<((i64, i64), u32)> = Vec::with_capacity(points.len());
        let indexed = points.iter().enumerate();
        entries.extend(indexed.filter_map(|(i, &p)| key(p).map(|k| (k, i as u32))));
        // By cell, then by coordinates, then by position: equal points in a run, the first
        // leading (coordinates are read only where cells tie).
        entries.sort_unstable_by(|(ka, a), (kb, b)| {
            ka.cmp(kb).then_with(|| {
                let (p, q) = (points[*a as usize], points[*b as usize]);
                let by = |u: f64, v: f64| u.partial_cmp(&v).unwrap_or(Ordering::Equal);
                by(p.x, q.x).then(by(p.y, q.y)).then(a.cmp(b))
            })
        });
        let count = 1 + entries.windows(2).filter(|w| w[0].0 != w[1].0).count();
        let mut cells: Vec<(i64, i64)> = Vec::with_capacity(count);
        let mut crowded: Vec<bool> = Vec::with_capacity(count);
        let mut cell_of = vec![NONE; points.len()];
        let mut first: Vec<u32> = (0..points.len() as u32).collect();
        for (k, &(cell, i)) in entries.iter().enumerate() {
            if cells.last() == Some(&cell) {
                *crowded.last_mut().expect("a cell") = true;
                let before = entries[k - 1].1;
                if points[before as usize] == points[i as usize] {
                    first[i as usize] = first[before as usize];
                }
            } else {
                cells.push(cell);
                crowded.push(false);
            }
            cell_of[i as usize] = (cells.len() - 1) as u32;
        }
        drop(entries);
        // A row's three cells around a cell lie together in the sorted cells, and where they
        // start only grows from one cell to the next: one sweep with a pointer per row.
        let mut row_starts = [0usize; 3];
        let mut starts = Vec::with_capacity(cells.len());
        let mut lengths = Vec::with_capacity(cells.len());
        for c in 0..cells.len() {
            let (x, y) = cells[c];
            let (mut start, mut length) = ([0u32; 3], [0u8; 3]);
            for (k, at) in row_starts.iter_mut().enumerate() {
                let row = x + k as i64 - 1;
                while *at < cells.len() && cells[*at] < (row, y - 1) {
                    *at += 1;
                }
                let run = cells[*at..]
                    .iter()
                    .take(3)
                    .take_while(|&&(r, v)| r == row && v <= y + 1)
                    .count();
                (start[k], length[k]) = (*at as u32, run as u8);
            }
            // Itself counts once; any other cell in the runs is an occupied neighbour.
            crowded[c] |= length.iter().map(|&l| usize::from(l)).sum::<usize>() > 1;
            starts.push(start);
            lengths.push(length);
        }
        Grid {
            crowded,
            starts,
            lengths,
            cell_of,
            first,
        }
    }

    /// The occupied cells among `cell` and its eight neighbours.
    fn around(&self, cell: usize) -> impl Iterator<Item = usize> + '_ {
        let (starts, lengths) = (self.starts[cell], self.lengths[cell]);
        (0..3).flat_map(move |k| {
            let start = starts[k] as usize;
            start..start + usize::from(lengths[k])
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Xorshift;

    /// The rule itself, by brute force: each point in order onto the nearest earlier point that
    /// stayed, within `distance`; exact duplicates with their first.
    fn snapped_by_brute_force(points: &[Point], distance: f64) -> Vec<Point> {
        let mut out = points.to_vec();
        let mut stays: Vec<usize> = Vec::new();
        for i in 0..out.len() {
            if let Some(j) = (0..i).find(|&j| points[j] == points[i]) {
                out[i] = out[j];
                continue;
            }
            let nearest = stays
                .iter()
                .map(|&j| (apart(out[i], out[j]), j, rounding(out[i], out[j], distance)))
                .filter(|&(gap, _, slack)| within(gap, distance, slack))
                .map(|(gap, j, _)| (gap, j))
                .min_by(|a, b| a.partial_cmp(b).expect("finite"));
            match nearest {
                Some((_, j)) => out[i] = out[j],
                None => stays.push(i),
            }
        }
        out
    }

    /// Twins written 0.001 apart at UTM's magnitudes (a GIS user's review: `--snap 0.001`
    /// moved 67 of 100, the parsed doubles of the rest lying a few units in the last place
    /// farther apart), each snapped; twins 0.0011 apart stay apart.
    #[test]
    fn twins_written_the_distance_apart_snap() {
        let mut rng = Xorshift::new(7);
        // A coordinate in ten-thousandths of a metre, written as a decimal and read back.
        let read = |t: u64| {
            format!("{}.{:04}", t / 10_000, t % 10_000)
                .parse::<f64>()
                .unwrap()
        };
        for (gap, snapped) in [(10, 200), (11, 0)] {
            let mut points = Vec::new();
            for _ in 0..200 {
                let x = 4_000_000_000 + rng.below(2_000_000_000);
                let y = 40_000_000_000 + rng.below(20_000_000_000);
                points.push(Point::new(read(x), read(y)));
                points.push(Point::new(read(x + gap), read(y)));
            }
            assert_eq!(snap(&mut points, 0.001).unwrap(), snapped, "gap {gap}");
        }
    }

    #[test]
    fn the_grid_follows_the_rule() {
        let mut rng = Xorshift::new(59);
        for round in 0..200 {
            let n = if round % 25 == 0 {
                600
            } else {
                1 + rng.below(60) as usize
            };
            // Clustered on a coarse lattice, so that near and exact duplicates are common.
            let mut points: Vec<Point> = (0..n)
                .map(|_| {
                    let coarse = |r: &mut Xorshift| r.below(6) as f64 * 0.5;
                    let fine = |r: &mut Xorshift| (r.below(5) as f64 - 2.0) * 0.05;
                    Point::new(
                        coarse(&mut rng) + fine(&mut rng),
                        coarse(&mut rng) + fine(&mut rng),
                    )
                })
                .collect();
            if round % 3 == 0 {
                points.push(Point::new(-0.0, 0.0));
                points.push(Point::new(0.0, -0.0));
            }
            let mut distance = [0.05, 0.1, 0.15, 0.3, 1.0][round % 5];
            if round % 4 == 1 {
                // The distance far below the coordinates' spacing, or far above: the cells'
                // indices beyond 2^62, where a coordinate gets one of its own.
                let scale = [1e-300, 1e-200, 2f64.powi(60), 1e250][round / 4 % 4];
                distance *= scale;
            }
            if round % 4 == 3 {
                for p in &mut points[..n / 2] {
                    p.x += 1e300; // far out in x only (the sum rounds to 1e300): y decides
                }
            }
            let expected = snapped_by_brute_force(&points, distance);
            let mut snapped = points.clone();
            let moved = snap(&mut snapped, distance).expect("valid");
            assert_eq!(snapped, expected, "round {round}, distance {distance}");
            let changed = points.iter().zip(&snapped).filter(|(a, b)| a != b).count();
            assert_eq!(moved, changed);
            for (p, q) in points.iter().zip(&snapped) {
                assert!(
                    within(apart(*p, *q), distance, rounding(*p, *q, distance)),
                    "a point moves at most the distance"
                );
            }
        }
    }

    #[test]
    fn refuses_a_distance_that_is_no_length_and_takes_odd_points() {
        for bad in [f64::NAN, -1.0, f64::INFINITY] {
            let err = snap(&mut [Point::new(0.0, 0.0)], bad).unwrap_err();
            assert!(matches!(
                err,
                Error::InvalidParameter {
                    name: "distance",
                    ..
                }
            ));
        }
        let mut points = [
            Point::new(f64::NAN, 0.0),
            Point::new(f64::MAX, 0.0),
            Point::new(f64::MAX, 1e-300),
            Point::new(0.0, 0.0),
            Point::new(1e-300, 0.0),
        ];
        assert_eq!(snap(&mut points, 1e-200).expect("valid"), 2);
        assert!(points[0].x.is_nan());
        // Far beyond the grid's cells in x, and near in y: the rule holds there too.
        assert_eq!(points[2], Point::new(f64::MAX, 0.0));
        assert_eq!(points[4], Point::new(0.0, 0.0));
        assert_eq!(snap(&mut points, 0.0), Ok(0));
    }

    /// The case this is for: two squares exported ring by ring, whose shared side's samples
    /// differ by a rounding. Without snapping, the twins pair up and the border is lost.
    #[test]
    fn a_shared_border_exported_twice_comes_back() {
        let ring = |x0: f64, wobble: f64| -> Vec<Point> {
            let side = |from: Point, to: Point| {
                (0..10).map(move |i| {
                    let t = i as f64 / 10.0;
                    Point::new(from.x + t * (to.x - from.x), from.y + t * (to.y - from.y))
                })
            };
            let corners = [
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 10.0),
                (0.0, 10.0),
                (0.0, 0.0),
            ]
            .map(|(x, y)| Point::new(x0 + x, y));
            let mut points: Vec<Point> =
                corners.windows(2).flat_map(|c| side(c[0], c[1])).collect();
            for p in &mut points {
                if p.x == 10.0 {
                    p.y += wobble; // the left square's right side is the right one's left side
                }
            }
            points
        };
        let mut points = ring(0.0, 0.0);
        points.extend(ring(10.0, 1e-9));
        let before = crate::reconstruct(&points, &crate::Params::default()).expect("finite");
        assert!(
            !before.unused().is_empty(),
            "the twins should break the border"
        );
        let mut snapped = points.clone();
        assert_eq!(snap(&mut snapped, 1e-6).expect("valid"), 11);
        let after = crate::reconstruct(&snapped, &crate::Params::default()).expect("finite");
        // The twins share their first's edges: nothing is unused, and the border is one curve
        // between the two junctions, beside each square's other three sides.
        assert!(after.unused().is_empty());
        assert_eq!(after.curves().len(), 3);
    }
}
