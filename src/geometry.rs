//! Points and plain floating-point helpers.
//!
//! Owns: the [`Point`] type and arithmetic that measures (distances, bounding boxes). It may not
//! decide an orientation or an in-circle sign: that belongs to [`crate::predicates`] alone.

/// A point of the plane, in double precision.
///
/// ```
/// use condt::Point;
/// let p = Point::new(3.0, 4.0);
/// assert_eq!(p.dist2(Point::new(0.0, 0.0)), 25.0);
/// assert_eq!(Point::from([3.0, 4.0]), p);
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
}

impl Point {
    /// A point from its coordinates.
    #[inline]
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }

    /// Squared Euclidean distance to `other`.
    #[inline]
    pub fn dist2(self, other: Point) -> f64 {
        let dx = self.x - other.x;
        let dy = self.y - other.y;
        dx * dx + dy * dy
    }

    /// `true` when both coordinates are finite (neither NaN nor infinite).
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }

    /// The point with both coordinates multiplied by `factor`.
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

impl From<Point> for [f64; 2] {
    #[inline]
    fn from(p: Point) -> Self {
        [p.x, p.y]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
