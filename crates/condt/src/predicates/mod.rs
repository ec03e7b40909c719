//! Exact geometric predicates (y axis up: counter-clockwise is a left turn).
//!
//! Owns: every orientation, in-circle and exact distance comparison. Nothing else in the crate may
//! decide one in plain floating point (a walk's guide or a stage's angle threshold may compare
//! floats: neither is a predicate whose error would break the mesh), and this module may not
//! depend on the mesh or the triangulator.
//!
//! In the fast range, where no product overflows or underflows (`docs/predicates.md`): Shewchuk's
//! static filter inline, then machine integers on a common binary grid (`small.rs`), then his
//! adaptive stages (`robust`). A call outside it is rescaled by a power of two when that brings it
//! in, else goes to big integers (`exact.rs`: exact for any finite input, far slower).
//!
//! ```
//! use condt::predicates::{in_circle, orient2d, Orientation};
//! use condt::Point;
//! let [a, b, c] = [0.1, 0.2, 0.3].map(|t| Point::new(t, t)); // on the diagonal, exactly
//! assert_eq!(orient2d(a, b, c), Orientation::Collinear);
//! assert!(in_circle(Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0), b));
//! ```

mod exact;
mod small;

use crate::geometry::{binary_exponent, Point, Scale};
use core::cmp::Ordering;
use robust::Coord;

/// The turn made by three points.
///
/// ```
/// use condt::{predicates::{orient2d, Orientation}, Point};
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

/// Exact orientation of the triangle `a, b, c`, for any finite coordinates (with a NaN or an
/// infinity the answer is unspecified, though never a panic: check the points first, as
/// [`triangulate`](crate::triangulate()) does).
///
/// ```
/// use condt::{predicates::{orient2d, Orientation}, Point};
/// let (a, b) = (Point::new(0.0, 0.0), Point::new(1.0, 1.0));
/// // One unit in the last place above the diagonal, 10^15 away from the origin:
/// let just_above = Point::new(1e15, f64::from_bits(1e15f64.to_bits() + 1));
/// assert_eq!(orient2d(a, b, just_above), Orientation::Ccw);
/// assert_eq!(orient2d(a, b, Point::new(1e15, 1e15)), Orientation::Collinear);
/// // Magnitudes 10^600 apart, where the products of floating-point arithmetic underflow:
/// let (p, q) = (Point::new(1e300, 0.0), Point::new(0.0, 1e300));
/// assert_eq!(orient2d(p, q, Point::new(1e-300, 1e-300)), Orientation::Ccw);
/// ```
#[inline]
pub fn orient2d(a: Point, b: Point, c: Point) -> Orientation {
    match reach(&[a, b, c]) {
        Reach::Fast => fast_orient2d(a, b, c),
        Reach::Rescaled(s) => fast_orient2d(s.apply(a), s.apply(b), s.apply(c)),
        Reach::Integers => integers::orient2d(a, b, c),
    }
}

/// `true` when `d` lies strictly inside the circle through `a, b, c`, which must be
/// counter-clockwise (the sign flips for a clockwise triangle). Cocircular points give `false`.
/// Exact for any finite coordinates; unspecified, never a panic, with a NaN or an infinity.
///
/// ```
/// use condt::{predicates::in_circle, Point};
/// let (a, b, c) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0));
/// assert!(in_circle(a, b, c, Point::new(0.5, 0.5)));
/// assert!(!in_circle(a, b, c, Point::new(0.0, 1.0))); // cocircular
/// assert!(!in_circle(a, b, c, Point::new(3.0, 3.0)));
/// // The same square scaled by 2^-1000, with a point 2^-1060 inside its corner:
/// let tiny = |x: f64, y: f64| Point::new(x * 2f64.powi(-1000), y * 2f64.powi(-1000));
/// let just_inside = Point::new(f64::from_bits(1 << 14), 2f64.powi(-1000)); // x = 2^-1060
/// assert!(in_circle(tiny(0.0, 0.0), tiny(1.0, 0.0), tiny(1.0, 1.0), just_inside));
/// ```
#[inline]
pub fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
    match reach(&[a, b, c, d]) {
        Reach::Fast => fast_in_circle(a, b, c, d),
        Reach::Rescaled(s) => fast_in_circle(s.apply(a), s.apply(b), s.apply(c), s.apply(d)),
        Reach::Integers => integers::in_circle(a, b, c, d),
    }
}

/// `true` when `d` lies exactly on the circle through `a, b, c` (any orientation): the in-circle
/// determinant is zero. Where `a, b, c` make no circle the determinant still decides: `true`
/// for `d` on their common line, and for any `d` when two of them coincide. Exact for any
/// finite coordinates; unspecified, never a panic, with a NaN or an infinity.
///
/// ```
/// use condt::{predicates::is_cocircular, Point};
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// assert!(is_cocircular(square[0], square[1], square[2], square[3]));
/// let line = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)].map(Point::from);
/// assert!(is_cocircular(line[0], line[1], line[2], Point::new(7.0, 0.0)));
/// assert!(!is_cocircular(line[0], line[1], line[2], Point::new(7.0, 3.0)));
/// assert!(is_cocircular(line[0], line[0], line[1], Point::new(7.0, 3.0)));
/// ```
#[inline]
pub fn is_cocircular(a: Point, b: Point, c: Point, d: Point) -> bool {
    let fast =
        |[a, b, c, d]: [Point; 4]| robust::incircle(coord(a), coord(b), coord(c), coord(d)) == 0.0;
    match reach(&[a, b, c, d]) {
        Reach::Fast => fast([a, b, c, d]),
        Reach::Rescaled(s) => fast([a, b, c, d].map(|p| s.apply(p))),
        Reach::Integers => {
            exact::in_circle_sign(a.into(), b.into(), c.into(), d.into()) == Ordering::Equal
        }
    }
}

/// The big-integer predicates alone (beyond the fast range, and for tests).
pub(crate) mod integers {
    use super::{exact, Ordering, Orientation, Point};

    pub(crate) fn orient2d(a: Point, b: Point, c: Point) -> Orientation {
        match exact::orient2d_sign(a.into(), b.into(), c.into()) {
            Ordering::Greater => Orientation::Ccw,
            Ordering::Less => Orientation::Cw,
            Ordering::Equal => Orientation::Collinear,
        }
    }

    pub(crate) fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
        exact::in_circle_sign(a.into(), b.into(), c.into(), d.into()) == Ordering::Greater
    }
}

/// The exact sign of `(a - b) · (c - d)`, for the hull walk of sets beyond the fast range and
/// NN-Crust's right angle where the rounded product cannot tell.
pub(crate) fn dot_sign(a: Point, b: Point, c: Point, d: Point) -> Ordering {
    exact::dot_sign(a.into(), b.into(), c.into(), d.into())
}

/// The relative gap between two rounded squared distances beyond which their order is the
/// exact one. In [`Point::dist2`] each term carries the rounding of its difference (doubled by
/// the square), of its square and of the sum, each at most 2^-53 of its value: the result is
/// within about 4 x 2^-53 of the exact square, and two that differ by more than 2^-49 of the
/// larger (twice what both errors can span) are in their exact order. The squares lie far
/// above the subnormal range in the stages' frame ([`crate::Error::TooCloseToMeasure`]), where
/// every error is relative.
const ROUNDING_GAP: f64 = 1.0 / (1u64 << 49) as f64;

/// Which of `a` and `b` is nearer to `p`, exactly, given their rounded squared distances `da`
/// and `db` ([`Point::dist2`]): those decide where they differ by more than their rounding can
/// ([`ROUNDING_GAP`]); closer than that (a paper reviewer's points whose squares differ by
/// 6e-18 came out one ulp apart in the wrong order), the two are equal when both squares are
/// known exact ([`exactly_squared`]) and equal, or the two offsets from `p` are the same up to
/// signs and the order of the axes ([`same_legs`]), else big integers decide (slow). Why: a
/// rounded order is not the paper's "shortest edge", and a rounded tie broken by vertex id
/// would depend on the input's orientation (ids follow the insertion order); only an exact tie
/// is left to the caller's id.
pub(crate) fn distance_order(p: Point, (a, da): (Point, f64), (b, db): (Point, f64)) -> Ordering {
    if (da - db).abs() > ROUNDING_GAP * da.max(db)
        || (exactly_squared(p, a) && exactly_squared(p, b))
    {
        return da.total_cmp(&db);
    }
    if same_legs(p, a, b) {
        return Ordering::Equal;
    }
    exact::compare_distances(p.into(), a.into(), b.into())
}

/// [`distance_order`], the squared distances measured here.
pub(crate) fn compare_distances(p: Point, a: Point, b: Point) -> Ordering {
    distance_order(p, (a, p.dist2(a)), (b, p.dist2(b)))
}

/// Whether `|b - p| < scale · |a - p|`, exactly (`scale` positive and finite): Algorithm 1's
/// uniformity test, `|e2| < u |e1|`. The rounded lengths decide where they differ by more than
/// [`SCALED_GAP`] of their size; a ratio that close to `scale` (exactly `u` on a grid: the
/// paper drops the edge there, rounding could keep it) is decided in integers.
pub(crate) fn shorter_than_scaled(p: Point, a: Point, scale: f64, b: Point) -> bool {
    let (near2, far2) = (p.dist2(a), p.dist2(b));
    let near = scale * libm::sqrt(near2);
    let far = libm::sqrt(far2);
    // Squares near the subnormal range have lost digits the bound counts on (a diff review:
    // squares of 1.2 and 1.4 units of 2^-1074 rounded to 1 and 2): decided exactly.
    let tiny = near2.min(far2) < TINY_SQUARE;
    if !tiny && (near - far).abs() > SCALED_GAP * near.max(far) {
        return far < near;
    }
    exact::compare_scaled_distances(p.into(), a.into(), scale, b.into()) == Ordering::Greater
}

/// Relative error bound of [`shorter_than_scaled`]'s rounded lengths: a squared length within
/// 4 units in the last place of its value (two differences, two squares and a sum, each rounded
/// to half a unit), its square root and the product by `scale` within 3, so well under 2^-48.
const SCALED_GAP: f64 = 1.0 / (1u64 << 48) as f64;

/// Squared lengths below `2^-960` may sum squares that underflowed; above it, what underflowed is
/// at most `2^-1073`, far below [`SCALED_GAP`] of the sum. The stages' frame keeps every nonzero
/// square far above it; below, the test is decided in integers, so it is exact for any points.
const TINY_SQUARE: f64 = f64::from_bits((1023 - 960) << 52); // 2^-960

/// Whether `a + b` is computed without rounding (Knuth's two-sum leaves no error). False on an
/// overflow (the error reads NaN).
fn exact_sum(a: f64, b: f64) -> bool {
    let s = a + b;
    let b_part = s - a;
    (a - (s - b_part)) + (b - b_part) == 0.0
}

/// Whether `a - p` and `b - p` are computed exactly and have the same legs (absolute offsets
/// along x and y, in either order): then `|a - p| = |b - p|` exactly. Evenly spaced samples
/// whose coordinates are not dyadic (0.1 apart, a zigzag) tie like this at almost every point,
/// and would each pay the big-integer comparison.
fn same_legs(p: Point, a: Point, b: Point) -> bool {
    let legs = |q: Point| {
        let exact = exact_sum(q.x, -p.x) && exact_sum(q.y, -p.y);
        exact.then(|| ((q.x - p.x).abs(), (q.y - p.y).abs()))
    };
    match (legs(a), legs(b)) {
        (Some((ax, ay)), Some((bx, by))) => (ax == bx && ay == by) || (ax == by && ay == bx),
        _ => false,
    }
}

/// Whether `p.dist2(q)` is known to be the exact squared distance: each difference and the sum
/// checked by Knuth's two-sum, each square by its mantissa (26 significant bits or fewer, far
/// above the subnormal range: exact). A square it cannot vouch for goes to the exact comparison.
fn exactly_squared(p: Point, q: Point) -> bool {
    let exact_square = |d: f64| {
        let bits = d.to_bits();
        d == 0.0 || ((bits >> 52) & 0x7ff > 600 && bits & ((1 << 27) - 1) == 0)
    };
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    exact_sum(q.x, -p.x)
        && exact_sum(q.y, -p.y)
        && exact_square(dx)
        && exact_square(dy)
        && exact_sum(dx * dx, dy * dy)
}

/// How a call's coordinates can be decided.
enum Reach {
    /// Already in the fast range: every nonzero magnitude in `[2^-200, 2)`.
    Fast,
    /// In the fast range once multiplied by this power of two.
    Rescaled(Scale),
    /// Spanning more than the fast range holds.
    Integers,
}

/// The magnitudes, as bit patterns, that bound the fast range: `[2^-200, 2)`.
const FAST_LOW: u64 = (1023 - MAX_SPREAD_BITS as u64) << 52;
const FAST_HIGH: u64 = 1024 << 52;

/// The widest ratio, in binary orders of magnitude, between the largest coordinate magnitude and
/// a nonzero one that the fast predicates decide exactly once the largest is in `[1, 2)`.
pub(crate) const MAX_SPREAD_BITS: i32 = 200;

#[inline(always)]
fn reach(points: &[Point]) -> Reach {
    const MAGNITUDE: u64 = !(1 << 63);
    let in_range = |c: f64| {
        let bits = c.to_bits() & MAGNITUDE;
        bits == 0 || (FAST_LOW..FAST_HIGH).contains(&bits)
    };
    if points.iter().all(|p| in_range(p.x) && in_range(p.y)) {
        return Reach::Fast;
    }
    rescale_or_integers(points)
}

#[cold]
fn rescale_or_integers(points: &[Point]) -> Reach {
    if !points.iter().all(|p| p.is_finite()) {
        // Not a question with an answer; robust gives some sign without panicking.
        return Reach::Fast;
    }
    let magnitudes = points.iter().flat_map(|p| [p.x.abs(), p.y.abs()]);
    let nonzero = magnitudes.filter(|&m| m != 0.0);
    let (top, bottom) = nonzero.fold((i32::MIN, i32::MAX), |(top, bottom), m| {
        let e = binary_exponent(m);
        (top.max(e), bottom.min(e))
    });
    if top == i32::MIN {
        return Reach::Fast; // all zero
    }
    if top - bottom <= MAX_SPREAD_BITS {
        Reach::Rescaled(Scale::power_of_two(-top))
    } else {
        Reach::Integers
    }
}

/// [`orient2d`] for coordinates whose products neither overflow nor underflow (the fast range).
#[inline(always)]
pub(crate) fn fast_orient2d(a: Point, b: Point, c: Point) -> Orientation {
    let det = fast_orient2d_det(a, b, c);
    if det > 0.0 {
        Orientation::Ccw
    } else if det < 0.0 {
        Orientation::Cw
    } else {
        Orientation::Collinear
    }
}

/// [`fast_orient2d`]'s determinant, a number whose sign is exact, for a hot loop to branch on.
#[inline(always)]
pub(crate) fn fast_orient2d_det(a: Point, b: Point, c: Point) -> f64 {
    // Shewchuk's first-stage bound, as `robust::orient2d` has it, inline so that a call it cannot
    // settle tries the small integers before the adaptive stages.
    let left = (a.x - c.x) * (b.y - c.y);
    let right = (a.y - c.y) * (b.x - c.x);
    let det = left - right;
    let bound = ORIENT2D_FILTER * (left + right).abs();
    if det >= bound || -det >= bound {
        det
    } else {
        undecided_orient2d(a, b, c)
    }
}

/// [`fast_orient2d_det`] past its filter: collinear or nearly so.
#[inline(never)]
fn undecided_orient2d(a: Point, b: Point, c: Point) -> f64 {
    match small::orient2d_sign(a.into(), b.into(), c.into()) {
        Some(sign) => sign as i8 as f64,
        None => robust::orient2d(coord(a), coord(b), coord(c)),
    }
}

/// The first-stage error bound of the orientation determinant relative to `|left + right|`
/// (`robust`'s constant, from Ozaki, Ogita, Rump and Oishi, BIT 2016).
const ORIENT2D_FILTER: f64 = 3.3306690621773722e-16;

/// [`in_circle`] for coordinates in the fast range (see [`fast_orient2d`]).
#[inline]
pub(crate) fn fast_in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
    // Shewchuk's first-stage bound (1997, `incircle`, bound A) settles most calls inline.
    let (det, bound) = in_circle_det(a, b, c, d);
    if det > bound {
        true
    } else if -det > bound {
        false
    } else {
        undecided_in_circle(a, b, c, d)
    }
}

/// [`fast_in_circle`]`(u, w, v, q)` with the differences taken from `v`, the new point every test
/// of one insertion shares: the same answers (`docs/triangulation.md`, step 4).
#[inline(always)]
pub(crate) fn fast_in_circle_around(v: Point, u: Point, w: Point, q: Point) -> bool {
    let (det, bound) = in_circle_det(u, w, q, v);
    if -det > bound {
        true
    } else if det > bound {
        false
    } else {
        undecided_in_circle(u, w, v, q)
    }
}

/// The in-circle determinant in floating point, differences from `d` (positive: `d` inside the
/// circle of the counter-clockwise `a, b, c`), and the bound past which its sign is exact.
#[inline(always)]
fn in_circle_det(a: Point, b: Point, c: Point, d: Point) -> (f64, f64) {
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
    (det, IN_CIRCLE_FILTER * permanent)
}

/// [`fast_in_circle`] past its filter (cocircular or nearly so): small integers on a common grid
/// in machine integers, the rest by `robust`'s adaptive stages.
#[inline(never)]
fn undecided_in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
    match small::in_circle_sign(a.into(), b.into(), c.into(), d.into()) {
        Some(sign) => sign == Ordering::Greater,
        None => robust::incircle(coord(a), coord(b), coord(c), coord(d)) > 0.0,
    }
}

/// Relative error bound of the floating-point in-circle determinant: (10 + 96ε)ε, ε = 2^-53.
const IN_CIRCLE_FILTER: f64 = (10.0 + 96.0 * f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact squares are told from rounded ones, a difference absorbed by a large coordinate
    /// included (2^-60 - 1 rounds to -1, which the naive check `d - a == -b` would pass).
    #[test]
    fn squared_lengths_are_known_exact_only_when_no_step_rounds() {
        let origin = Point::new(0.0, 0.0);
        assert!(exactly_squared(origin, Point::new(3.0, 4.0)));
        assert!(exactly_squared(
            Point::new(0.5, -2.0),
            Point::new(-1.25, 8.0)
        ));
        assert!(!exactly_squared(origin, Point::new(0.1, 0.2)));
        assert!(!exactly_squared(
            Point::new(2f64.powi(-60), 0.0),
            Point::new(1.0, 0.0)
        ));
        assert!(!exactly_squared(
            origin,
            Point::new(1.0 + f64::EPSILON, 0.0)
        ));
    }

    /// The same-legs shortcut agrees with the big integers on offsets that are mirrored or
    /// swapped copies (evenly spaced, non-dyadic samples), and stays out of the way when a
    /// difference rounds (a leg absorbed by a large coordinate) or the legs differ by one ulp.
    #[test]
    fn tied_distances_with_the_same_legs_are_equal_and_no_others() {
        let mut rng = crate::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let mut unit = || (rng.next_u64() >> 11) as f64 / 2f64.powi(53);
        let mut shortcut = 0;
        for k in 0..20_000 {
            let p = Point::new(unit() * 100.0 - 50.0, unit() * 1e6);
            let (dx, dy) = (unit() * 0.3, unit() * 0.3);
            let a = Point::new(p.x + dx, p.y - dy);
            // Mirrored and swapped offsets of `a`'s, as rounded; every fourth nudged by an ulp.
            let (ex, ey) = (a.x - p.x, a.y - p.y);
            let mut b = match k % 3 {
                0 => Point::new(p.x - ex, p.y + ey),
                1 => Point::new(p.x + ey, p.y + ex),
                _ => Point::new(p.x - ey, p.y - ex),
            };
            if k % 4 == 0 {
                b.x = libm::nextafter(b.x, f64::INFINITY);
            }
            let exact = exact::compare_distances(p.into(), a.into(), b.into());
            shortcut += usize::from(same_legs(p, a, b));
            assert!(
                !same_legs(p, a, b) || exact == Ordering::Equal,
                "{p:?} {a:?} {b:?}"
            );
            assert_eq!(compare_distances(p, a, b), exact, "{p:?} {a:?} {b:?}");
        }
        // The shortcut does take most mirrored pairs.
        assert!(shortcut > 4_000, "{shortcut}");
        // 2^-60 - 1 rounds to -1: the offsets look alike but are not.
        let p = Point::new(1.0, 0.0);
        let (a, b) = (Point::new(2f64.powi(-60), 0.0), Point::new(2.0, 0.0));
        assert!(!same_legs(p, a, b));
        assert_eq!(compare_distances(p, a, b), Ordering::Less);
    }

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

    /// Random calls, half of them near-degenerate, each also multiplied by a random power of two
    /// (exact): the integers, the public predicates and Shewchuk's (on the unscaled call, in its
    /// exact range) must all agree.
    #[test]
    fn integers_agree_with_shewchuk_where_both_are_exact() {
        let mut rng = crate::test_rng::Xorshift::new(0x1319_8a2e_0370_7344);
        let nudge = |v: f64, k: i64| f64::from_bits((v.to_bits() as i64 + k) as u64);
        let (mut collinear, mut cocircular) = (0, 0);
        for round in 0..20_000 {
            let mut unit = || rng.unit() * 2.0 - 1.0;
            let (a, b) = (Point::new(unit(), unit()), Point::new(unit(), unit()));
            let mut c = Point::new(unit(), unit());
            let mut d = Point::new(unit(), unit());
            if round % 2 == 1 {
                // c near the line a b, d near the circle (a reflected through b c's bisector).
                let t = unit();
                let k = (round % 5) as i64 - 2;
                c = Point::new(nudge(a.x + t * (b.x - a.x), k), a.y + t * (b.y - a.y));
                let (mx, my) = ((b.x + c.x) / 2.0, (b.y + c.y) / 2.0);
                let (ux, uy) = (c.x - b.x, c.y - b.y);
                let s = ((a.x - mx) * ux + (a.y - my) * uy) / (ux * ux + uy * uy);
                d = Point::new(nudge(a.x - 2.0 * s * ux, k), nudge(a.y - 2.0 * s * uy, -k));
            }
            if round % 97 == 0 {
                // Exactly degenerate: a repeated point.
                c = a;
                d = b;
            }
            let orientation = fast_orient2d(a, b, c);
            let inside = fast_in_circle(a, b, c, d);
            let on = robust::incircle(coord(a), coord(b), coord(c), coord(d)) == 0.0;
            collinear += usize::from(orientation == Orientation::Collinear);
            cocircular += usize::from(on);
            assert_eq!(
                integers::orient2d(a, b, c),
                orientation,
                "{a:?} {b:?} {c:?}"
            );
            assert_eq!(
                integers::in_circle(a, b, c, d),
                inside,
                "{a:?} {b:?} {c:?} {d:?}"
            );
            let k = (rng.next_u64() % 1800) as i32 - 900;
            let s = Scale::power_of_two(k);
            let [a, b, c, d] = [a, b, c, d].map(|p| s.apply(p));
            assert_eq!(orient2d(a, b, c), orientation, "scaled by 2^{k}");
            assert_eq!(in_circle(a, b, c, d), inside, "scaled by 2^{k}");
            assert_eq!(is_cocircular(a, b, c, d), on, "scaled by 2^{k}");
            assert_eq!(integers::orient2d(a, b, c), orientation, "scaled by 2^{k}");
            assert_eq!(integers::in_circle(a, b, c, d), inside, "scaled by 2^{k}");
        }
        assert!(
            collinear > 100 && cocircular > 100,
            "{collinear} {cocircular}"
        );
    }

    /// Calls spanning the whole double range, where only the integers can decide: each answer
    /// must be consistent with the determinant's symmetries (a swap flips the orientation,
    /// a cyclic shift keeps it) and with known configurations.
    #[test]
    fn calls_spanning_the_whole_range_are_consistent() {
        let mut rng = crate::test_rng::Xorshift::new(0xa409_3822_299f_31d0);
        let mut coordinate = move || {
            let exponent = (rng.next_u64() % 2097) as i32 - 1074;
            let mantissa = 1.0 + rng.unit();
            let sign = if rng.next_u64() % 2 == 0 { 1.0 } else { -1.0 };
            let magnitude = Scale::power_of_two(exponent)
                .apply(Point::new(mantissa, 0.0))
                .x;
            sign * magnitude.min(f64::MAX)
        };
        let mut point = || Point::new(coordinate(), coordinate());
        for _ in 0..2000 {
            let (a, b, c, d) = (point(), point(), point(), point());
            let o = orient2d(a, b, c);
            assert_eq!(orient2d(b, c, a), o);
            let flipped = match o {
                Orientation::Ccw => Orientation::Cw,
                Orientation::Cw => Orientation::Ccw,
                Orientation::Collinear => Orientation::Collinear,
            };
            assert_eq!(orient2d(b, a, c), flipped);
            if o == Orientation::Ccw {
                assert_eq!(in_circle(a, b, c, d), in_circle(b, c, a, d));
                // With a clockwise triangle the determinant changes sign.
                let (inside, on) = (in_circle(a, b, c, d), is_cocircular(a, b, c, d));
                assert_eq!(in_circle(b, a, c, d), !inside && !on);
                // Each corner lies on its own circle.
                assert!(is_cocircular(a, b, c, a) && !in_circle(a, b, c, c));
            }
        }
        // A point 2^-1074 off a line through points 2^1023 apart.
        let (far, tiny) = (f64::MAX, f64::from_bits(1));
        let (a, b) = (Point::new(-far, 0.0), Point::new(far, 0.0));
        assert_eq!(orient2d(a, b, Point::new(0.0, tiny)), Orientation::Ccw);
        assert_eq!(
            orient2d(a, b, Point::new(tiny, 0.0)),
            Orientation::Collinear
        );
        assert_eq!(orient2d(a, b, Point::new(far, -tiny)), Orientation::Cw);
    }

    /// `|b - p| < scale |a - p|` against integer arithmetic, on points of integer offsets
    /// below 2^10 from a far origin, in a unit of `2^-40` to `2^40` (the exact path's integers
    /// then start at other exponents), and dyadic scales `m / 2^k` (`m` odd below 2^20):
    /// `|b - p|² 4^k < m² |a - p|²` in `u128`. Half of the `b` are placed on the ratio exactly
    /// or one unit off it, where the rounded lengths cannot tell (a paper-fidelity review: a
    /// ratio of exactly 2.75 kept the second edge).
    #[test]
    fn the_scaled_distance_test_is_exact() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut ties = 0;
        for round in 0..20_000 {
            let small = |rng: &mut crate::test_rng::Xorshift| rng.below(1 << 10) as i64 - 512;
            let step = |rng: &mut crate::test_rng::Xorshift| rng.below(3) as i64 - 1;
            let (k, m, (ax, ay), (bx, by));
            if round % 2 == 0 {
                k = rng.below(19) as u32;
                m = 2 * rng.below(1 << 19) + 1;
                (ax, ay) = (small(&mut rng), small(&mut rng));
                (bx, by) = (small(&mut rng), small(&mut rng));
            } else {
                // `a = 2^k a'` and `b = m (a' turned a quarter)`: the ratio is the scale
                // exactly, or `b` one unit off it.
                k = rng.below(4) as u32;
                m = 2 * rng.below(16) + 1;
                let a_ = (rng.below(32) as i64 - 16, rng.below(32) as i64 - 16);
                (ax, ay) = (a_.0 << k, a_.1 << k);
                let m_ = m as i64;
                (bx, by) = (-a_.1 * m_ + step(&mut rng), a_.0 * m_ + step(&mut rng));
            }
            let scale = m as f64 / f64::from(1u32 << k);
            let origin = 1e6;
            let unit = libm::ldexp(1.0, rng.below(81) as i32 - 40);
            let at = |x: i64, y: i64| {
                Point::new((origin + x as f64) * unit, (origin * 0.5 + y as f64) * unit)
            };
            let (p, a, b) = (at(0, 0), at(ax, ay), at(bx, by));
            let squared = |x: i64, y: i64| (x * x + y * y) as u128;
            let left = squared(bx, by) << (2 * k);
            let right = u128::from(m * m) * squared(ax, ay);
            ties += usize::from(left == right);
            assert_eq!(
                shorter_than_scaled(p, a, scale, b),
                left < right,
                "p {p:?} a {a:?} b {b:?} scale {scale}"
            );
        }
        assert!(ties > 20, "only {ties} exact ratios");
        // Squares near the subnormal range (1.2 and 1.4 units of 2^-1074, rounded to 1 and 2):
        // `b` is the farther, though its rounded square says otherwise at a scale of 1.
        let tiny = libm::ldexp(1.0, -537);
        let (p, a) = (
            Point::new(0.0, 0.0),
            Point::new(0.6f64.sqrt() * tiny, 0.6f64.sqrt() * tiny),
        );
        let b = Point::new(1.4f64.sqrt() * tiny, 0.0);
        assert_eq!(
            shorter_than_scaled(p, a, 1.0, b),
            exact::compare_scaled_distances(p.into(), a.into(), 1.0, b.into()) == Ordering::Greater
        );
        assert!(!shorter_than_scaled(p, a, 1.0, b));
        // The paper's u on a grid: |e2| = 2.75 |e1| exactly (11 (a, b) against 4 (a, b)).
        for (x, y) in [(1.0, 1.0), (2.0, 1.0), (3.0, 7.0)] {
            let (p, a) = (Point::new(0.0, 0.0), Point::new(4.0 * x, 4.0 * y));
            assert!(!shorter_than_scaled(
                p,
                a,
                2.75,
                Point::new(-11.0 * y, 11.0 * x)
            ));
            assert!(shorter_than_scaled(
                p,
                a,
                2.75,
                Point::new(-11.0 * y + 1.0, 11.0 * x)
            ));
        }
    }
}
