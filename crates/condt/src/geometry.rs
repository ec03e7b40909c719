//! Points and plain floating-point helpers.
//!
//! Owns: the [`Point`] type, arithmetic that measures (distances, bounding boxes) and exact
//! rescaling by powers of two ([`Scale`], [`binary_exponent`]), shared with `condt-io`'s drawings.
//! It may not decide an orientation or in-circle sign: that is [`crate::predicates`]'s alone.
//!
//! ```
//! use condt::geometry::{binary_exponent, Scale};
//! use condt::Point;
//! let p = Point::new(6.0, -1.0);
//! assert_eq!(Scale::power_of_two(-binary_exponent(p.x)).apply(p), Point::new(1.5, -0.25));
//! ```

/// A point of the plane, in double precision.
///
/// Its layout is fixed (`#[repr(C)]`): `x` then `y`, the size and alignment of `[f64; 2]`, so
/// that a binding can view the rows of an `(n, 2)` float64 array (NumPy's, in the Python
/// package) as `&[Point]` without copying them.
///
/// ```
/// use condt::Point;
/// let p = Point::new(3.0, 4.0);
/// assert_eq!(p.dist2(Point::new(0.0, 0.0)), 25.0);
/// assert_eq!(Point::from([3.0, 4.0]), p);
/// assert_eq!(core::mem::size_of::<Point>(), core::mem::size_of::<[f64; 2]>());
/// assert_eq!(core::mem::align_of::<Point>(), core::mem::align_of::<[f64; 2]>());
/// assert_eq!(core::mem::offset_of!(Point, y), core::mem::size_of::<f64>());
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq)]
#[repr(C)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
}

impl Point {
    /// A point from its coordinates.
    ///
    /// ```
    /// use condt::Point;
    /// let p = Point::new(1.5, -2.0);
    /// assert_eq!((p.x, p.y), (1.5, -2.0));
    /// ```
    #[inline]
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }
    /// Squared Euclidean distance to `other`.
    ///
    /// ```
    /// use condt::Point;
    /// assert_eq!(Point::new(1.0, 1.0).dist2(Point::new(4.0, 5.0)), 25.0);
    /// ```
    #[inline]
    pub fn dist2(self, other: Point) -> f64 {
        let dx = self.x - other.x;
        let dy = self.y - other.y;
        dx * dx + dy * dy
    }

    /// `true` when both coordinates are finite (neither NaN nor infinite).
    ///
    /// ```
    /// use condt::Point;
    /// assert!(Point::new(1.0, 2.0).is_finite());
    /// assert!(!Point::new(f64::NAN, 0.0).is_finite());
    /// assert!(!Point::new(0.0, f64::INFINITY).is_finite());
    /// ```
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
    #[inline]
    pub(crate) fn scaled(self, factor: f64) -> Point {
        Point::new(self.x * factor, self.y * factor)
    }
    /// Lexicographic order, x first, by value (so -0.0 equals 0.0). Any exact translation keeps
    /// it; along a line it is the order of the points on that line.
    ///
    /// ```
    /// use condt::Point;
    /// use std::cmp::Ordering;
    /// assert_eq!(Point::new(-1.0, 5.0).lexicographic_cmp(Point::new(0.0, 0.0)), Ordering::Less);
    /// assert_eq!(Point::new(-0.0, 1.0).lexicographic_cmp(Point::new(0.0, 1.0)), Ordering::Equal);
    /// ```
    #[inline]
    pub fn lexicographic_cmp(self, other: Point) -> core::cmp::Ordering {
        let by = |a: f64, b: f64| a.partial_cmp(&b).unwrap_or(core::cmp::Ordering::Equal);
        by(self.x, other.x).then(by(self.y, other.y))
    }
}

/// The lower left corner of the bounding box of `points`, `None` for no point.
pub(crate) fn lower_left(points: impl Iterator<Item = Point>) -> Option<Point> {
    points.reduce(|c, p| Point::new(c.x.min(p.x), c.y.min(p.y)))
}

/// The corner of the bounding box of `points` nearest to one of them (rounded squared distances),
/// `None` for no point. Corners tied at that (two corners on points, say) go by the sum of the
/// squared distances to every point (each over the box's squared diagonal, in units of 2^-60,
/// summed exactly: no order of the points can change it), then lower left, lower right, upper
/// right and upper left. Why: differences from a corner do not change when the set moves by an
/// exact translation, as the corner moves with it; from this corner they do not change either
/// when the set is turned by 90 degrees or mirrored, as the box, the corners and every distance
/// turn with it (each is the same two squares), where the lower left corner would be another
/// corner of the set, whose differences round otherwise. Only a set that turning or mirroring
/// maps onto itself, or nearly, can tie to the end.
pub(crate) fn nearest_corner(points: impl Iterator<Item = Point> + Clone) -> Option<Point> {
    let [lower, upper] = points.clone().fold(None, |box_, p: Point| {
        let [lower, upper] = box_.unwrap_or([p, p]);
        Some([
            Point::new(lower.x.min(p.x), lower.y.min(p.y)),
            Point::new(upper.x.max(p.x), upper.y.max(p.y)),
        ])
    })?;
    let corners = [
        lower,
        Point::new(upper.x, lower.y),
        upper,
        Point::new(lower.x, upper.y),
    ];
    let mut nearest = [f64::INFINITY; 4];
    for p in points.clone() {
        for (corner, best) in corners.iter().zip(&mut nearest) {
            *best = best.min(corner.dist2(p));
        }
    }
    let least = nearest.iter().copied().fold(f64::INFINITY, f64::min);
    let tied = nearest.map(|d| d == least);
    let diagonal2 = lower.dist2(upper);
    if tied.iter().filter(|&&t| t).count() == 1 || diagonal2 <= 0.0 {
        return tied.iter().position(|&t| t).map(|k| corners[k]);
    }
    let unit = (1u64 << 60) as f64;
    let sums = core::array::from_fn::<u128, 4, _>(|k| match tied[k] {
        true => points
            .clone()
            .map(|p| ((corners[k].dist2(p) / diagonal2).min(1.0) * unit) as u128)
            .sum(),
        false => u128::MAX,
    });
    let first_least = (0..4).fold(0, |k, j| if sums[j] < sums[k] { j } else { k });
    Some(corners[first_least])
}

impl From<[f64; 2]> for Point {
    #[inline]
    fn from([x, y]: [f64; 2]) -> Self {
        Point::new(x, y)
    }
}

impl From<(f64, f64)> for Point {
    #[inline]
    fn from((x, y): (f64, f64)) -> Self {
        Point::new(x, y)
    }
}

/// Widens `f32` coordinates (a renderer's or a game engine's) to a [`Point`]: exact, as every
/// `f32` is an `f64`, so the result is the one the same values given as `f64` have.
///
/// ```
/// use condt::Point;
/// let p = Point::from([0.1f32, -3.5]);
/// assert_eq!(p, Point::new(f64::from(0.1f32), -3.5));
/// assert_eq!(p.x as f32, 0.1f32); // and back without loss
/// // Untyped literals still read as `f64`.
/// assert_eq!(Point::from([0.1, 2.0]).x, 0.1f64);
/// ```
impl From<[f32; 2]> for Point {
    #[inline]
    fn from([x, y]: [f32; 2]) -> Self {
        Point::new(f64::from(x), f64::from(y))
    }
}

/// Widens `f32` coordinates to a [`Point`], exactly, as `From<[f32; 2]>` does.
///
/// ```
/// use condt::Point;
/// let points: Vec<Point> = [(1.5f32, 0.25f32), (0.1, 2.0)].map(Point::from).to_vec();
/// assert_eq!(points[1], Point::new(f64::from(0.1f32), 2.0));
/// // Untyped literals still read as `f64`.
/// assert_eq!([(0.1, 2.0)].map(Point::from)[0].x, 0.1f64);
/// ```
impl From<(f32, f32)> for Point {
    #[inline]
    fn from((x, y): (f32, f32)) -> Self {
        Point::new(f64::from(x), f64::from(y))
    }
}

impl From<Point> for [f64; 2] {
    #[inline]
    fn from(p: Point) -> Self {
        [p.x, p.y]
    }
}

/// The exponent `e` with `2^e <= x < 2^(e+1)`, for finite `x > 0` (subnormals included).
///
/// ```
/// use condt::geometry::binary_exponent;
/// assert_eq!(binary_exponent(1.0), 0);
/// assert_eq!(binary_exponent(0.75), -1);
/// assert_eq!(binary_exponent(f64::MIN_POSITIVE / 4.0), -1024);
/// ```
pub fn binary_exponent(x: f64) -> i32 {
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
pub(crate) fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// Multiplication by a power of two, kept as two factors so each stays a normal double (`2^k` for
/// `k` from -2044 to 2046): exact, changing no sign or ratio, while no coordinate leaves the
/// normal range. The stages work on the input scaled so; the drawings use it to zoom exactly.
///
/// ```
/// use condt::{geometry::Scale, Point};
/// let big = Point::new(3.0 * 2f64.powi(1000), -2f64.powi(1001));
/// let scale = Scale::power_of_two(-1000);
/// assert_eq!(scale.apply(big), Point::new(3.0, -2.0));
/// assert_eq!(scale.inverse().apply(scale.apply(big)), big);
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Scale {
    first: f64,
    second: f64,
}

impl Scale {
    /// Multiplication by one.
    ///
    /// ```
    /// use condt::{geometry::Scale, Point};
    /// let p = Point::new(0.1, -3.0e300);
    /// assert_eq!(Scale::IDENTITY.apply(p), p);
    /// ```
    pub const IDENTITY: Scale = Scale {
        first: 1.0,
        second: 1.0,
    };

    /// Multiplication by `2^k`.
    ///
    /// # Panics
    /// If `k` is outside `-2044..=2046`, where the two factors would leave the normal range.
    ///
    /// ```
    /// use condt::{geometry::Scale, Point};
    /// assert_eq!(Scale::power_of_two(3).apply(Point::new(1.0, -0.5)), Point::new(8.0, -4.0));
    /// // Beyond one double's exponent range, in two exact steps:
    /// let tiny = Point::new(2f64.powi(-1000), 0.0);
    /// assert_eq!(Scale::power_of_two(2000).apply(tiny), Point::new(2f64.powi(1000), 0.0));
    /// ```
    pub fn power_of_two(k: i32) -> Scale {
        assert!(
            (-2044..=2046).contains(&k),
            "Scale::power_of_two: 2^{k} is outside 2^-2044 to 2^2046"
        );
        let half = k / 2;
        Scale {
            first: pow2(half),
            second: pow2(k - half),
        }
    }

    /// `p` multiplied by the scale (exact while `p` stays in the normal range).
    ///
    /// ```
    /// use condt::{geometry::Scale, Point};
    /// assert_eq!(Scale::power_of_two(-2).apply(Point::new(1.0, 3.0)), Point::new(0.25, 0.75));
    /// ```
    #[inline]
    pub fn apply(self, p: Point) -> Point {
        p.scaled(self.first).scaled(self.second)
    }
    /// The scale that undoes this one, exactly (its factors are powers of two).
    ///
    /// ```
    /// use condt::{geometry::Scale, Point};
    /// let undo = Scale::power_of_two(11).inverse();
    /// assert_eq!(undo.apply(Point::new(2048.0, -6144.0)), Point::new(1.0, -3.0));
    /// ```
    pub fn inverse(self) -> Scale {
        Scale {
            first: 1.0 / self.second,
            second: 1.0 / self.first,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corner a smoothing pass measures from turns with the set: for turned, mirrored and
    /// permuted copies of random sets (with a far point, as wide sets have; and with points on
    /// two corners, told apart by the sums), the corner chosen is the image of the one chosen.
    #[test]
    fn the_nearest_corner_turns_with_the_set_and_ignores_the_order() {
        let mut rng = crate::test_rng::Xorshift::new(99);
        let maps: [fn(Point) -> Point; 4] = [
            |p| Point::new(-p.y, p.x),
            |p| Point::new(-p.x, -p.y),
            |p| Point::new(-p.x, p.y),
            |p| Point::new(p.y, p.x),
        ];
        for case in 0..200 {
            let mut points: Vec<Point> = (0..20)
                .map(|_| Point::new(rng.unit() * 3.0 - 1.0, rng.unit() - 0.5))
                .collect();
            if case % 2 == 0 {
                // Off the box's corners: a wide set whose nearest distances do not tie.
                points.push(Point::new(1e9 * rng.unit(), 0.3 * rng.unit()));
            }
            if case % 3 == 0 {
                // Two points on corners of the box: the nearest distance ties at zero.
                let lower = lower_left(points.iter().copied()).unwrap();
                let right = points.iter().map(|p| p.x).fold(f64::MIN, f64::max);
                points.push(lower);
                points.push(Point::new(right, lower.y));
            }
            let corner = nearest_corner(points.iter().copied()).unwrap();
            for map in maps {
                let turned: Vec<Point> = points.iter().map(|&p| map(p)).collect();
                assert_eq!(nearest_corner(turned.iter().copied()), Some(map(corner)));
            }
            points.reverse();
            points.swap(0, 7);
            assert_eq!(nearest_corner(points.iter().copied()), Some(corner));
        }
        assert_eq!(nearest_corner(core::iter::empty()), None);
        let one = Point::new(2.0, -3.0);
        assert_eq!(nearest_corner(core::iter::once(one)), Some(one));
    }

    /// The ends of the range scale exactly; one step beyond is refused, not a wrong factor
    /// (found by a stress run: `2^-2045` gave 0 in a release build).
    #[test]
    fn a_power_of_two_scale_is_exact_to_its_range_and_refused_beyond() {
        let tiny = f64::from_bits(1); // 2^-1074
        let up = Scale::power_of_two(2046).apply(Point::new(tiny, 1.0));
        assert_eq!(up.x, 2f64.powi(972));
        let down = Scale::power_of_two(-2044).apply(Point::new(f64::MAX, 2f64.powi(1000)));
        // Not `2f64.powi(-1044)`: unless the compiler folds it, that is 1 / 2^1044, which
        // overflows first, so 0 (at opt-level 0, and under Miri).
        assert_eq!(down.y, f64::from_bits(1 << 30)); // 2^-1044
        for k in [-2045, 2047, i32::MIN, i32::MAX] {
            assert!(
                std::panic::catch_unwind(|| Scale::power_of_two(k)).is_err(),
                "{k}"
            );
        }
    }

    #[test]
    fn lexicographic_order_is_numeric_for_negative_coordinates() {
        use core::cmp::Ordering::Less;
        assert_eq!(
            Point::new(-2.0, 0.0).lexicographic_cmp(Point::new(-1.0, 0.0)),
            Less
        );
        assert_eq!(
            Point::new(1.0, -2.0).lexicographic_cmp(Point::new(1.0, -1.0)),
            Less
        );
    }

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
    fn power_of_two_scales_reach_both_ends_of_the_range() {
        let s = Scale::power_of_two(2046);
        assert_eq!(
            s.apply(Point::new(f64::from_bits(1 << 51), 0.0)).x, // 2^-1023, subnormal
            2f64.powi(1023)
        );
        let s = Scale::power_of_two(-2044);
        // 2^-1044 is subnormal: bit 30 of the pattern.
        assert_eq!(
            s.apply(Point::new(2f64.powi(1000), 0.0)).x,
            f64::from_bits(1 << 30)
        );
        assert_eq!(
            Scale::power_of_two(-10)
                .inverse()
                .apply(Point::new(3.0, 0.0))
                .x,
            3072.0
        );
    }
}
