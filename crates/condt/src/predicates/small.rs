//! Exact signs in machine integers for the calls the floating-point filters cannot settle whose
//! coordinates are small integers on a common binary grid (integer grids, pixel contours, where
//! nearly every in-circle test is exactly cocircular): multiples of `2^-49` in `[-4, 4)`, whose
//! differences over the grid's unit are below `2^30` (`docs/predicates.md`, item 4).
//!
//! Owns: the fixed-point reading of a call's coordinates and the two determinants on it. A call
//! it refuses (`None`) goes on to Shewchuk's adaptive stages: a wrong refusal costs time only.
//! It may not answer a call outside its grid: a sign it gives must be exact.

use core::cmp::Ordering;

/// The doubles in `[8, 16)` are the multiples of `2^-49` there, counted by their bit patterns: a
/// multiple `x` of `2^-49` in `[-4, 4)` lands exactly on `x + 12`, and `(x + 12).to_bits() -
/// 12.to_bits()` is the integer `x · 2^49`.
const ANCHOR: f64 = 12.0;

/// `x · 2^49` while exact and within range (the integer in `[-2^51, 2^51)`, nothing rounded off
/// `x + 12`); the checks collect in a flag so that a call reads its coordinates without a branch.
#[inline(always)]
fn fixed(x: f64, exact: &mut bool) -> i64 {
    let shifted = x + ANCHOR;
    // Wrapping: a negative `shifted` may wrap below i64::MIN, landing outside [-2^51, 2^51).
    let integer = (shifted.to_bits() as i64).wrapping_sub(ANCHOR.to_bits() as i64);
    // Outside [8, 16) (or negative: the sign bit makes the pattern negative) the integer leaves
    // [-2^51, 2^51); inside, `shifted - 12` is exact and equals `x` only if nothing was rounded.
    let in_range = (integer.wrapping_add(1 << 51) as u64) < 1 << 52;
    *exact &= in_range & (shifted - ANCHOR == x);
    integer
}

/// Differences, in units of their common power of two, at or above this are refused (module doc).
const SMALL_LIMIT: u64 = 1 << 30;

/// The differences `p - origin`, exactly, divided by their largest common power of two, when all
/// then lie below `SMALL_LIMIT` in magnitude (all zero allowed: every point the same).
#[inline(always)]
fn small_differences<const N: usize>(
    points: [[f64; 2]; N],
    origin: [f64; 2],
) -> Option<[[i64; 2]; N]> {
    let mut exact = true;
    let (ox, oy) = (fixed(origin[0], &mut exact), fixed(origin[1], &mut exact));
    let mut out = [[0i64; 2]; N];
    let mut bits = 0i64;
    for (slot, p) in out.iter_mut().zip(points) {
        // Only exact (in-range) readings are kept, and their differences are below 2^52; the
        // others may wrap, and are thrown away below.
        *slot = [
            fixed(p[0], &mut exact).wrapping_sub(ox),
            fixed(p[1], &mut exact).wrapping_sub(oy),
        ];
        bits |= slot[0] | slot[1];
    }
    if !exact {
        return None;
    }
    // All zero (one point repeated) gives a unit of 64: the shifts below would overflow, and
    // every difference is zero anyway.
    let unit = bits.trailing_zeros().min(63);
    let mut largest = 0u64;
    for slot in out.iter_mut() {
        for v in slot.iter_mut() {
            *v >>= unit; // exact: every difference is a multiple of 2^unit
            largest |= v.unsigned_abs();
        }
    }
    (largest < SMALL_LIMIT).then_some(out)
}

/// The in-circle sign (positive: `d` strictly inside the circle of the counter-clockwise
/// `a, b, c`), or `None` when the coordinates are not small integers on a common grid.
// Inlined into its one caller, itself out of line (the filter's slow branch); so is the next.
#[inline(always)]
pub(super) fn in_circle_sign(
    a: [f64; 2],
    b: [f64; 2],
    c: [f64; 2],
    d: [f64; 2],
) -> Option<Ordering> {
    let [[adx, ady], [bdx, bdy], [cdx, cdy]] = small_differences([a, b, c], d)?;
    // Each difference is below 2^30: the lifts below 2^61, the 2x2 minors below 2^61, so both
    // fit an i64; their products below 2^122, and the sum of three below 2^124.
    let lift = |x: i64, y: i64| x * x + y * y;
    let minor = |x0: i64, y0: i64, x1: i64, y1: i64| x0 * y1 - x1 * y0;
    let det = lift(adx, ady) as i128 * minor(bdx, bdy, cdx, cdy) as i128
        + lift(bdx, bdy) as i128 * minor(cdx, cdy, adx, ady) as i128
        + lift(cdx, cdy) as i128 * minor(adx, ady, bdx, bdy) as i128;
    Some(det.cmp(&0))
}

/// The orientation sign (positive: counter-clockwise), or `None` as for [`in_circle_sign`].
#[inline(always)]
pub(super) fn orient2d_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<Ordering> {
    let [[acx, acy], [bcx, bcy]] = small_differences([a, b], c)?;
    // Differences below 2^30: each product below 2^60, their difference below 2^61.
    Some((acx * bcy - acy * bcx).cmp(&0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Xorshift;

    /// The robust crate's determinants, exact for these inputs (well inside its range), as
    /// signs (a zero may come as -0.0).
    fn robust_in_circle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Ordering {
        let p = |q: [f64; 2]| robust::Coord { x: q[0], y: q[1] };
        sign(robust::incircle(p(a), p(b), p(c), p(d)))
    }

    fn robust_orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
        let p = |q: [f64; 2]| robust::Coord { x: q[0], y: q[1] };
        sign(robust::orient2d(p(a), p(b), p(c)))
    }

    fn sign(det: f64) -> Ordering {
        det.partial_cmp(&0.0).expect("a finite determinant")
    }

    /// Random calls on grids of every unit from 2^-49 to 1 and every extent up to the limit,
    /// many of them cocircular or collinear: the integers answer every call inside their
    /// documented range, and agree with Shewchuk's predicates.
    #[test]
    fn integers_agree_with_shewchuk_on_grids() {
        let mut rng = Xorshift::new(0x4528_21e6_38d0_1377);
        let (mut answered, mut degenerate) = (0, 0);
        for round in 0..100_000 {
            let unit_exponent = -49 + (rng.next_u64() % 50) as i32;
            let unit = crate::geometry::Scale::power_of_two(unit_exponent)
                .apply(crate::Point::new(1.0, 0.0))
                .x;
            // A side (in units) that keeps the coordinates in [-4, 4), and mostly small sides,
            // where cocircular and collinear calls are common.
            let largest_side = ((1u64 << 30) - 1).min((2.0 / unit) as u64);
            let side = if round % 2 == 0 {
                largest_side.min(8)
            } else {
                1 + rng.next_u64() % largest_side
            };
            let origin = -2.0 + (rng.next_u64() % (2.0 / unit) as u64) as f64 * unit;
            let mut coordinate = || origin + (rng.next_u64() % side) as f64 * unit;
            let mut point = || [coordinate(), coordinate()];
            let (a, b, c, d) = (point(), point(), point(), point());
            let expected = robust_in_circle(a, b, c, d);
            if let Some(sign) = in_circle_sign(a, b, c, d) {
                answered += 1;
                assert_eq!(sign, expected, "{a:?} {b:?} {c:?} {d:?}");
            }
            degenerate += usize::from(expected == Ordering::Equal);
            if let Some(sign) = orient2d_sign(a, b, c) {
                assert_eq!(sign, robust_orient2d(a, b, c), "{a:?} {b:?} {c:?}");
            }
        }
        assert_eq!(answered, 100_000);
        assert!(degenerate > 5_000, "only {degenerate} cocircular");
    }

    /// The extremes of the range: differences of 2^30 - 1 units are taken (the largest
    /// determinant), 2^30 are refused; coordinates must be multiples of 2^-49 in [-4, 4).
    #[test]
    fn the_range_ends_where_the_module_doc_says() {
        let top = ((1u64 << 30) - 1) as f64;
        // Nearly the largest determinant: the corners of a square of side 2^30 - 1 and a point
        // just inside the circle through three of them.
        let (a, b, c) = ([0.0, 0.0], [top, 0.0], [top, top]);
        let unit = 2f64.powi(-29); // brings 2^30 - 1 below 2
        let s = |p: [f64; 2]| [p[0] * unit, p[1] * unit];
        for d in [[0.0, top], [1.0, top], [0.0, top - 1.0], [top, 1.0]] {
            assert_eq!(
                in_circle_sign(s(a), s(b), s(c), s(d)),
                Some(robust_in_circle(s(a), s(b), s(c), s(d)))
            );
        }
        let beyond = [top + 1.0, 0.0];
        // Differences are taken from the last point.
        assert_eq!(in_circle_sign(s(c), s(beyond), s(b), s(a)), None);
        assert_eq!(orient2d_sign(s(beyond), s(c), s(a)), None);
        assert!(orient2d_sign(s(a), s(beyond), s(c)).is_some());
        // Not a multiple of 2^-49, or out of range.
        let fine = [2f64.powi(-50), 0.0];
        assert_eq!(orient2d_sign([0.0, 0.0], fine, [1.0, 1.0]), None);
        assert_eq!(orient2d_sign([0.0, 0.0], [4.0, 0.0], [1.0, 1.0]), None);
        assert_eq!(orient2d_sign([0.0, 0.0], [-4.5, 0.0], [1.0, 1.0]), None);
        // Nothing out of range is read, and nothing overflows (tests run with overflow checks):
        // negative sums whose bit patterns fall below i64::MIN, infinities, NaN, extremes.
        for bad in [
            -12.0 - 2f64.powi(-40),
            -12.5,
            -1e300,
            -f64::MAX,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ] {
            for p in [[bad, 0.0], [0.5, bad]] {
                assert_eq!(orient2d_sign([0.0, 0.0], p, [1.0, 1.0]), None, "{bad}");
                assert_eq!(orient2d_sign(p, [0.0, 0.0], [1.0, 1.0]), None, "{bad}");
                assert_eq!(orient2d_sign([0.0, 0.0], [1.0, 1.0], p), None, "{bad}");
                assert_eq!(in_circle_sign(p, [0.0, 0.0], [1.0, 1.0], [3.5, -3.5]), None);
                assert_eq!(in_circle_sign([3.5, -3.5], [0.0, 0.0], [1.0, 1.0], p), None);
            }
        }
        assert_eq!(
            orient2d_sign([-0.0, 0.0], [1.0, -0.0], [0.0, 1.0]),
            Some(Ordering::Greater)
        );
        assert_eq!(
            orient2d_sign([-4.0, 0.0], [3.5, 0.0], [1.0, 1.0]),
            Some(Ordering::Greater)
        );
        assert_eq!(orient2d_sign([0.0, 0.0], [f64::NAN, 0.0], [1.0, 1.0]), None);
        // The same point four times: zero.
        let p = [0.5, 0.25];
        assert_eq!(in_circle_sign(p, p, p, p), Some(Ordering::Equal));
    }
}
