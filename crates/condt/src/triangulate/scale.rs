//! Input checks and the exact power-of-two rescalings: into the frame the predicates decide in
//! (largest magnitude in [1, 2)) and into the stages' positions (in [2^200, 2^201)).
//! `docs/predicates.md` derives both ranges and when a set is *wide*, needing exact predicates.
//!
//! Owns: refusing input no frame can take, and choosing the two frames. It may not change a point
//! other than by an exact power-of-two scaling (no rounding, no translation).

use crate::error::Error;
use crate::geometry::{binary_exponent, Point, Scale};
use crate::predicates::MAX_SPREAD_BITS;
use crate::triangulate::MAX_POINTS;

/// The binary exponent the stages' positions give the largest coordinate magnitude.
pub(crate) const STAGE_EXPONENT: i32 = 200;

/// The frames a point set is worked in.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Frames {
    /// Input to the frame the triangulator decides signs in (exact).
    pub(crate) predicates: Scale,
    /// Whether the set spans more than the fast predicates take, so the exact ones must decide.
    pub(crate) wide: bool,
    /// Input to the positions the stages measure.
    pub(crate) stages: Scale,
    /// The binary exponents of `predicates` and `stages`.
    pub(crate) exponents: (i32, i32),
}

/// Checks the size ([`MAX_POINTS`]) and that every point is finite, and picks the frames.
pub(crate) fn choose_frames(points: &[Point]) -> Result<Frames, Error> {
    let (count, limit) = (points.len(), MAX_POINTS);
    if count > limit {
        return Err(Error::TooManyPoints { count, limit });
    }
    // One pass, in integers (speed): magnitudes compare as bit patterns (NaN above infinity above
    // every finite value); zero, one below, wraps to the top when seeking the smallest nonzero.
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
        return Ok(Frames {
            predicates: Scale::IDENTITY,
            wide: false,
            stages: Scale::IDENTITY,
            exponents: (0, 0),
        });
    }
    let top = binary_exponent(largest);
    let bottom = binary_exponent(smallest);
    let wide = bottom < top - MAX_SPREAD_BITS;
    // A wide set is still brought to [1, 2) when that is exact (no coordinate becomes
    // subnormal): most of its predicate calls then stay in the fast range.
    let predicates = if !wide || bottom - top >= -1022 {
        -top
    } else {
        0
    };
    let stages = STAGE_EXPONENT - top;
    Ok(Frames {
        predicates: Scale::power_of_two(predicates),
        wide,
        stages: Scale::power_of_two(stages),
        exponents: (predicates, stages),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_brings_the_largest_magnitude_into_one_to_two() {
        for largest in [f64::from_bits(3), 1e-200, 3.0e-5, 1.0, 1e15, f64::MAX] {
            let pts = [Point::new(largest, 0.0), Point::new(0.0, -largest / 2.0)];
            let frames = choose_frames(&pts).unwrap();
            assert!(!frames.wide);
            let q = frames.predicates.apply(pts[0]);
            assert!((1.0..2.0).contains(&q.x), "{largest} scaled to {}", q.x);
            let s = frames.stages.apply(pts[0]);
            assert_eq!(
                binary_exponent(s.x),
                STAGE_EXPONENT,
                "{largest} for the stages"
            );
        }
    }

    #[test]
    fn a_set_beyond_the_fast_range_is_wide_and_scaled_only_when_exact() {
        let pts = [
            Point::new(1.0, 0.0),
            Point::new(0.5, 1e-50),
            Point::new(1e-300, 0.0),
        ];
        let frames = choose_frames(&pts).unwrap();
        assert!(frames.wide);
        assert_eq!(frames.predicates.apply(pts[2]), pts[2]);
        let pts = [Point::new(4.0, 0.0), Point::new(1e-70, 0.0)];
        let frames = choose_frames(&pts).unwrap();
        assert!(frames.wide);
        assert_eq!(frames.predicates.apply(pts[0]).x, 1.0);
    }

    /// The bit-pattern extremes: signed zeros count as zero, subnormals as tiny magnitudes, and
    /// the sign never makes a magnitude large.
    #[test]
    fn zeros_signs_and_subnormals_are_read_as_magnitudes() {
        let zeros = [Point::new(-0.0, 0.0), Point::new(0.0, -0.0)];
        let frames = choose_frames(&zeros).unwrap();
        assert_eq!(frames.predicates, Scale::IDENTITY);
        assert!(!frames.wide);
        let negative = [Point::new(-0.0, -3.0), Point::new(0.0, 1.0)];
        let q = choose_frames(&negative)
            .unwrap()
            .predicates
            .apply(negative[0]);
        assert_eq!(q.y, -1.5, "largest magnitude 3, negative");
        assert!(choose_frames(&[Point::new(1.0, -5e-324)]).unwrap().wide);
        let subnormal = [Point::new(1e-310, -2e-310)];
        let frames = choose_frames(&subnormal).unwrap();
        assert!(!frames.wide);
        let q = frames.predicates.apply(subnormal[0]);
        assert!((0.5..1.0).contains(&q.x), "{}", q.x);
        for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
            let pts = [Point::new(1.0, 2.0), Point::new(-0.0, bad)];
            assert_eq!(choose_frames(&pts), Err(Error::NonFinite { index: 1 }));
        }
    }
}
