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

    /// The coordinates as bit patterns, with -0.0 folded onto 0.0, so that equal points compare
    /// equal and the order is total.
    #[inline]
    pub(crate) fn key_bits(self) -> (u64, u64) {
        ((self.x + 0.0).to_bits(), (self.y + 0.0).to_bits())
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
    fn negative_zero_has_the_key_of_zero() {
        assert_eq!(Point::new(-0.0, -0.0).key_bits(), Point::new(0.0, 0.0).key_bits());
    }
}
