//! Input checks and the exact power-of-two rescaling that keeps the predicates out of underflow.
//!
//! Multiplying by a power of two changes no predicate sign and loses no bit as long as no result
//! leaves the normal range, so the triangulator works on a copy scaled to make the largest
//! coordinate magnitude fall in [1, 2). With every nonzero coordinate at least 2^-200 after
//! scaling, every coordinate is a multiple of 2^-252, every degree-4 product inside `incircle`
//! a multiple of 2^-1008, and all of them stay normal doubles: the predicates are exact.

use crate::error::Error;
use crate::geometry::Point;

/// How many binary orders of magnitude below the largest coordinate a nonzero coordinate may lie.
pub(crate) const MAX_DYNAMIC_RANGE_BITS: i32 = 200;

/// The exponent `e` with `2^e <= x < 2^(e+1)`, for finite `x > 0` (subnormals included).
fn binary_exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if biased == 0 {
        let mantissa = bits & ((1u64 << 52) - 1);
        63 - mantissa.leading_zeros() as i32 - 1074
    } else {
        biased - 1023
    }
}

/// `2^k` for `k` in the normal exponent range.
fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// A power-of-two scale, kept as two factors so that each stays a normal double.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Scale {
    first: f64,
    second: f64,
}

impl Scale {
    pub(crate) const IDENTITY: Scale = Scale {
        first: 1.0,
        second: 1.0,
    };

    #[inline]
    pub(crate) fn apply(self, p: Point) -> Point {
        p.scaled(self.first).scaled(self.second)
    }

    /// The scale that undoes this one, exactly (its factors are powers of two).
    pub(crate) fn inverse(self) -> Scale {
        Scale {
            first: 1.0 / self.second,
            second: 1.0 / self.first,
        }
    }
}

/// Checks every point and picks the scale: the first non-finite point, or the first with a
/// coordinate too small for the set's dynamic range, is an error naming its index.
pub(crate) fn choose_scale(points: &[Point]) -> Result<Scale, Error> {
    // One pass for the common case: all finite, and the smallest nonzero magnitude within range.
    // Magnitudes compare as their bit patterns (NaN above infinity above every finite value),
    // and zero, one below, wraps to the top when looking for the smallest nonzero one: integer
    // minima and maxima, one chain per axis, where float ones with NaN rules chain far slower.
    const MAGNITUDE: u64 = !(1 << 63);
    let (mut largest, mut smallest) = ([0u64; 2], [u64::MAX; 2]);
    for p in points {
        for (axis, c) in [p.x, p.y].into_iter().enumerate() {
            let bits = c.to_bits() & MAGNITUDE;
            largest[axis] = largest[axis].max(bits);
            smallest[axis] = smallest[axis].min(bits.wrapping_sub(1));
        }
    }
    let largest = f64::from_bits(largest[0].max(largest[1]));
    let smallest = f64::from_bits(smallest[0].min(smallest[1]).wrapping_add(1));
    if !largest.is_finite() {
        let index = points.iter().position(|p| !p.is_finite()).unwrap_or(0);
        return Err(Error::NonFinite { index });
    }
    if largest == 0.0 {
        return Ok(Scale::IDENTITY);
    }
    let top = binary_exponent(largest);
    let floor = top - MAX_DYNAMIC_RANGE_BITS;
    if binary_exponent(smallest) < floor {
        let too_small = |c: f64| c != 0.0 && binary_exponent(c.abs()) < floor;
        let index = points
            .iter()
            .position(|p| too_small(p.x) || too_small(p.y))
            .unwrap_or(0);
        return Err(Error::RangeTooWide { index });
    }
    let half = -top / 2;
    Ok(Scale {
        first: pow2(half),
        second: pow2(-top - half),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_exponent_covers_normal_and_subnormal_numbers() {
        assert_eq!(binary_exponent(1.0), 0);
        assert_eq!(binary_exponent(1.5), 0);
        assert_eq!(binary_exponent(0.75), -1);
        assert_eq!(binary_exponent(1e15), 49);
        assert_eq!(binary_exponent(f64::MIN_POSITIVE), -1022);
        assert_eq!(binary_exponent(f64::from_bits(1)), -1074);
        assert_eq!(binary_exponent(f64::MAX), 1023);
    }

    #[test]
    fn scaling_brings_the_largest_magnitude_into_one_to_two() {
        for largest in [f64::from_bits(3), 1e-200, 3.0e-5, 1.0, 1e15, f64::MAX] {
            let pts = [Point::new(largest, 0.0), Point::new(0.0, -largest / 2.0)];
            let s = choose_scale(&pts).unwrap();
            let q = s.apply(pts[0]);
            assert!((1.0..2.0).contains(&q.x), "{largest} scaled to {}", q.x);
        }
    }

    #[test]
    fn a_coordinate_beyond_the_dynamic_range_is_refused_by_index() {
        let pts = [
            Point::new(1.0, 0.0),
            Point::new(0.5, 1e-50),
            Point::new(1e-300, 0.0),
        ];
        assert_eq!(choose_scale(&pts), Err(Error::RangeTooWide { index: 2 }));
    }

    /// The bit-pattern extremes: signed zeros count as zero, subnormals as tiny magnitudes, and
    /// the sign never makes a magnitude large.
    #[test]
    fn zeros_signs_and_subnormals_are_read_as_magnitudes() {
        let zeros = [Point::new(-0.0, 0.0), Point::new(0.0, -0.0)];
        assert_eq!(choose_scale(&zeros), Ok(Scale::IDENTITY));
        let negative = [Point::new(-0.0, -3.0), Point::new(0.0, 1.0)];
        let q = choose_scale(&negative).unwrap().apply(negative[0]);
        assert_eq!(q.y, -1.5, "largest magnitude 3, negative");
        assert_eq!(
            choose_scale(&[Point::new(1.0, -5e-324)]),
            Err(Error::RangeTooWide { index: 0 })
        );
        let subnormal = [Point::new(1e-310, -2e-310)];
        let q = choose_scale(&subnormal).unwrap().apply(subnormal[0]);
        assert!((0.5..1.0).contains(&q.x), "{}", q.x);
        for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
            let pts = [Point::new(1.0, 2.0), Point::new(-0.0, bad)];
            assert_eq!(choose_scale(&pts), Err(Error::NonFinite { index: 1 }));
        }
    }
}
