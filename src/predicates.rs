//! Exact geometric predicates.
//!
//! Owns: every decision about a geometric sign. It wraps Shewchuk's adaptive-precision
//! `orient2d` and `incircle` (the `robust` crate), which return the exact sign of their
//! determinant for any finite inputs whose products neither overflow nor underflow. `in_circle`
//! first tries Shewchuk's static error bound inline, which settles most calls without the
//! function call, and hands every call it cannot settle to `robust`. Nothing else in
//! the crate may compute a sign with plain floating point, and this module may not depend on the
//! mesh or the triangulator.
//!
//! Sign conventions (y axis pointing up):
//! - [`orient2d`]`(a, b, c)` is [`Orientation::Ccw`] when `c` lies strictly left of the directed
//!   line `a → b`, that is when `a, b, c` turn counter-clockwise.
//! - [`in_circle`]`(a, b, c, d)` is `true` when `d` lies strictly inside the circle through the
//!   counter-clockwise triangle `a, b, c`.
//!
//! The triangulator rescales its input by a power of two (an exact operation) so that coordinates
//! never approach the underflow range; `docs/predicates.md` derives the range where exactness holds.

use crate::geometry::Point;
use robust::Coord;

/// The turn made by three points.
///
/// ```
/// use condt::predicates::{orient2d, Orientation};
/// use condt::Point;
/// let (a, b) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0));
/// assert_eq!(orient2d(a, b, Point::new(0.5, 1.0)), Orientation::Ccw);
/// assert_eq!(orient2d(a, b, Point::new(0.5, -1.0)), Orientation::Cw);
/// assert_eq!(orient2d(a, b, Point::new(7.0, 0.0)), Orientation::Collinear);
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Counter-clockwise: the third point is strictly left of the line through the first two.
    Ccw,
    /// Clockwise: the third point is strictly right of the line through the first two.
    Cw,
    /// The three points lie on one line (or two of them coincide).
    Collinear,
}

#[inline(always)]
fn coord(p: Point) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// Exact orientation of the triangle `a, b, c`.
///
/// ```
/// use condt::predicates::{orient2d, Orientation};
/// use condt::Point;
/// let (a, b) = (Point::new(0.0, 0.0), Point::new(1.0, 1.0));
/// // One unit in the last place above the diagonal, 10^15 away from the origin:
/// let just_above = Point::new(1e15, f64::from_bits(1e15f64.to_bits() + 1));
/// assert_eq!(orient2d(a, b, just_above), Orientation::Ccw);
/// assert_eq!(orient2d(a, b, Point::new(1e15, 1e15)), Orientation::Collinear);
/// ```
#[inline]
pub fn orient2d(a: Point, b: Point, c: Point) -> Orientation {
    let det = robust::orient2d(coord(a), coord(b), coord(c));
    if det > 0.0 {
        Orientation::Ccw
    } else if det < 0.0 {
        Orientation::Cw
    } else {
        Orientation::Collinear
    }
}

/// `true` when `d` lies strictly inside the circle through `a, b, c`, which must be
/// counter-clockwise (the sign flips for a clockwise triangle). Cocircular points give `false`.
///
/// ```
/// use condt::predicates::in_circle;
/// use condt::Point;
/// let (a, b, c) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0));
/// assert!(in_circle(a, b, c, Point::new(0.5, 0.5)));
/// assert!(!in_circle(a, b, c, Point::new(0.0, 1.0))); // cocircular
/// assert!(!in_circle(a, b, c, Point::new(3.0, 3.0)));
/// ```
#[inline]
pub fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
    // Most calls are far from cocircular: decide those inline with Shewchuk's first-stage bound
    // (Shewchuk 1997, `incircle`, error bound A), and let `robust` settle the rest exactly.
    let (adx, ady) = (a.x - d.x, a.y - d.y);
    let (bdx, bdy) = (b.x - d.x, b.y - d.y);
    let (cdx, cdy) = (c.x - d.x, c.y - d.y);
    let (bc, cb) = (bdx * cdy, cdx * bdy);
    let (ca, ac) = (cdx * ady, adx * cdy);
    let (ab, ba) = (adx * bdy, bdx * ady);
    let (alift, blift, clift) = (
        adx * adx + ady * ady,
        bdx * bdx + bdy * bdy,
        cdx * cdx + cdy * cdy,
    );
    let det = alift * (bc - cb) + blift * (ca - ac) + clift * (ab - ba);
    let permanent = (bc.abs() + cb.abs()) * alift
        + (ca.abs() + ac.abs()) * blift
        + (ab.abs() + ba.abs()) * clift;
    let bound = IN_CIRCLE_FILTER * permanent;
    if det > bound {
        true
    } else if -det > bound {
        false
    } else {
        robust::incircle(coord(a), coord(b), coord(c), coord(d)) > 0.0
    }
}

/// Relative error bound of the floating-point in-circle determinant: (10 + 96ε)ε, ε = 2^-53.
const IN_CIRCLE_FILTER: f64 = (10.0 + 96.0 * f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);

/// `true` when `d` lies exactly on the circle through `a, b, c` (any orientation).
///
/// ```
/// use condt::predicates::is_cocircular;
/// use condt::Point;
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// assert!(is_cocircular(square[0], square[1], square[2], square[3]));
/// ```
#[inline]
pub fn is_cocircular(a: Point, b: Point, c: Point, d: Point) -> bool {
    robust::incircle(coord(a), coord(b), coord(c), coord(d)) == 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_is_antisymmetric_under_swap() {
        let (a, b, c) = (
            Point::new(0.0, 0.0),
            Point::new(2.0, 1.0),
            Point::new(-1.0, 3.0),
        );
        assert_eq!(orient2d(a, b, c), Orientation::Ccw);
        assert_eq!(orient2d(b, a, c), Orientation::Cw);
        assert_eq!(orient2d(b, c, a), Orientation::Ccw);
    }

    #[test]
    fn nearly_collinear_points_are_decided_exactly() {
        // c is one ulp above the line y = x at x = 1e15: naive arithmetic says collinear.
        let a = Point::new(0.0, 0.0);
        let b = Point::new(1.0, 1.0);
        let y = 1e15f64;
        let c = Point::new(y, f64::from_bits(y.to_bits() + 1));
        assert_eq!(orient2d(a, b, c), Orientation::Ccw);
        assert_eq!(orient2d(a, b, Point::new(y, y)), Orientation::Collinear);
    }

    #[test]
    fn inline_filter_agrees_with_robust_everywhere() {
        let mut rng = crate::test_rng::Xorshift::new(0x243f_6a88_85a3_08d3);
        let mut unit = move || rng.unit();
        let nudge = |v: f64, k: i64| f64::from_bits((v.to_bits() as i64 + k) as u64);
        let mut near = 0;
        for round in 0..200_000 {
            let (a, b, c) = (
                Point::new(unit(), unit()),
                Point::new(unit(), unit()),
                Point::new(unit(), unit()),
            );
            let d = if round % 2 == 0 {
                Point::new(unit(), unit())
            } else {
                // Near-cocircular: the reflection of `a` through the bisector of `b c` lies on the
                // circle in exact arithmetic; nudging it by a few ulps lands on either side.
                let (mx, my) = ((b.x + c.x) / 2.0, (b.y + c.y) / 2.0);
                let (ux, uy) = (c.x - b.x, c.y - b.y);
                let t = ((a.x - mx) * ux + (a.y - my) * uy) / (ux * ux + uy * uy);
                let k = (round % 7) as i64 - 3;
                Point::new(nudge(a.x - 2.0 * t * ux, k), nudge(a.y - 2.0 * t * uy, -k))
            };
            let det = robust::incircle(coord(a), coord(b), coord(c), coord(d));
            near += usize::from(det.abs() < 1e-15);
            assert_eq!(in_circle(a, b, c, d), det > 0.0, "{a:?} {b:?} {c:?} {d:?}");
        }
        // The nudged half must really probe the zone the inline bound cannot settle.
        assert!(near > 20_000, "only {near} near-cocircular cases");
    }

    #[test]
    fn in_circle_detects_a_point_one_ulp_inside() {
        let (a, b, c) = (
            Point::new(-1.0, 0.0),
            Point::new(0.0, -1.0),
            Point::new(1.0, 0.0),
        );
        let on = Point::new(0.0, 1.0);
        let inside = Point::new(0.0, f64::from_bits(1.0f64.to_bits() - 1));
        assert!(is_cocircular(a, b, c, on));
        assert!(!in_circle(a, b, c, on));
        assert!(in_circle(a, b, c, inside));
    }
}
