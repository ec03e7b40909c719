//! Sampling curves with known connectivity, for tests, examples and users.
//!
//! Owns: placing points along simple parametric shapes and reporting the ground-truth edges
//! between consecutive samples. It may not triangulate or reconstruct.
//!
//! Spacing is set by `epsilon` against a local feature size (lfs) per shape, taken at its
//! smallest: radius for circles and arcs, the smallest radius of curvature for ellipses, the gap
//! between turns for spirals, the shortest side for polygons, a quarter of the size for the figure
//! eight. Consecutive samples are at most `epsilon · lfs` apart along the curve, an
//! `epsilon`-sampling in the sense of Amenta et al. as long as separate shapes are farther apart
//! than their own lfs (the caller's responsibility).
//!
//! Beyond even sampling, [`Sampling`] can make the conditions real inputs have: density that
//! varies along a curve (or from side to side of a polygon), uniform or Gaussian noise, and
//! outliers alone or in clumps.
//!
//! ```
//! use condt_eval::sample::{sample, Sampling, Shape};
//! use condt::Point;
//! let s = sample(&[Shape::circle(Point::new(0.0, 0.0), 1.0)], &Sampling::new(0.2)).unwrap();
//! assert_eq!(s.points.len(), s.edges.len()); // closed: as many edges as points
//! assert!(s.outliers.is_empty());
//! ```

use crate::geometry::Point;
use crate::MAX_POINTS;
use alloc::vec::Vec;
use core::f64::consts::{PI, TAU};
use core::fmt;

/// A curve to sample.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A closed ellipse with semi-axes `radii`, turned by `rotation` radians.
    Ellipse {
        /// Centre.
        center: Point,
        /// Semi-axes along its own x and y.
        radii: (f64, f64),
        /// Rotation, radians counter-clockwise.
        rotation: f64,
    },
    /// An open circular arc from angle `start` sweeping `sweep` radians (less than a full turn).
    Arc {
        /// Centre.
        center: Point,
        /// Radius.
        radius: f64,
        /// Start angle, radians.
        start: f64,
        /// Swept angle, radians, with sign.
        sweep: f64,
    },
    /// An open Archimedean spiral `r = inner + gap · θ / 2π` over `turns` turns.
    Spiral {
        /// Centre.
        center: Point,
        /// Radius at the start.
        inner: f64,
        /// Distance between successive turns.
        gap: f64,
        /// Number of turns.
        turns: f64,
    },
    /// A closed polygon with sharp corners, each corner a sample. A corner equal to the one
    /// before it (or the last equal to the first, a polygon closed by repeating its first corner)
    /// is the same corner and counted once.
    Polygon(Vec<Point>),
    /// Gerono's lemniscate `(s sin t, s sin t cos t)`: a figure eight whose crossing at the
    /// centre is a sample shared by both lobes (degree four in the ground truth).
    FigureEight {
        /// Centre (the crossing).
        center: Point,
        /// Half-width `s`.
        size: f64,
    },
}

impl Shape {
    /// A circle.
    pub fn circle(center: Point, radius: f64) -> Shape {
        Shape::Ellipse {
            center,
            radii: (radius, radius),
            rotation: 0.0,
        }
    }
}

/// How to sample.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Sampling {
    /// Spacing against the local feature size (see the module documentation).
    pub epsilon: f64,
    /// Uniform outliers in the bounding box, as a fraction of the curve samples.
    pub outlier_fraction: f64,
    /// Outliers are redrawn while closer than this to any earlier point, curve sample or outlier:
    /// an "outlier" within the sample spacing of the curve is indistinguishable from a noisy
    /// sample, and two outliers close together are each other's nearest neighbours, a two-point
    /// curve. 0 keeps every draw (plain uniform outliers).
    pub outlier_clearance: f64,
    /// Each curve sample is moved by up to `noise` in x and y: uniformly within ±`noise`, or
    /// with `noise` as the standard deviation when [`Sampling::gaussian_noise`] is set.
    pub noise: f64,
    /// Gaussian noise (standard deviation `noise` per coordinate) instead of uniform.
    pub gaussian_noise: bool,
    /// How unevenly each curve is sampled: the largest spacing over the smallest, at least 1.
    /// Along a smooth curve the spacing swings smoothly from `1 / density_variation` of the
    /// bound at the start to the bound (`epsilon · lfs`) halfway round; the sides of a polygon
    /// get spacings spread over the same range. The bound is never exceeded, so the sample stays
    /// an `epsilon`-sampling. 1 samples evenly.
    pub density_variation: f64,
    /// Outliers in clumps instead of one by one; `None` draws single outliers.
    pub outlier_clumps: Option<Clumps>,
    /// Seed of the outliers and the noise.
    pub seed: u64,
}

/// Outliers that come in small groups: each clump has between `min` and `max` points (drawn
/// uniformly) within `radius` of a uniform centre. Clumped outliers are each other's nearest
/// neighbours, the hardest kind for a proximity graph.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Clumps {
    /// Fewest points in a clump (at least 1).
    pub min: usize,
    /// Most points in a clump.
    pub max: usize,
    /// Largest distance of a clump's points from its centre.
    pub radius: f64,
}

impl Sampling {
    /// Clean sampling at `epsilon`: no outliers, no noise.
    pub fn new(epsilon: f64) -> Sampling {
        Sampling {
            epsilon,
            outlier_fraction: 0.0,
            outlier_clearance: 0.0,
            noise: 0.0,
            gaussian_noise: false,
            density_variation: 1.0,
            outlier_clumps: None,
            seed: 1,
        }
    }
}

/// Sampled points with their ground truth.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sample {
    /// Curve samples first, then outliers.
    pub points: Vec<Point>,
    /// Ground-truth edges `[i, j]`, `i < j`, sorted.
    pub edges: Vec<[usize; 2]>,
    /// Positions of the outliers (no ground-truth edge), ascending.
    pub outliers: Vec<usize>,
}

/// Why [`sample`] refuses.
///
/// ```
/// use condt_eval::sample::{sample, SampleError, Sampling, Shape};
/// use condt::Point;
/// let circle = [Shape::circle(Point::new(0.0, 0.0), 1.0)];
/// assert_eq!(sample(&circle, &Sampling::new(0.0)), Err(SampleError::Epsilon(0.0)));
/// assert!(matches!(sample(&circle, &Sampling::new(1e-12)), Err(SampleError::TooManyPoints { .. })));
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum SampleError {
    /// `epsilon` is zero, negative or NaN: no spacing.
    Epsilon(f64),
    /// The sample would have more points than the triangulation takes
    /// ([`condt::MAX_POINTS`]).
    TooManyPoints {
        /// The limit.
        limit: usize,
    },
}

impl fmt::Display for SampleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SampleError::Epsilon(epsilon) => {
                write!(f, "epsilon must be a positive number, not {epsilon}")
            }
            SampleError::TooManyPoints { limit } => {
                write!(f, "the sample would have more than {limit} points")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for SampleError {}

/// Room for `count` more points (a float, so that an infinite or huge count is refused before
/// anything is allocated) after `used`.
fn check_room(used: usize, count: f64) -> Result<usize, SampleError> {
    if count <= (MAX_POINTS.saturating_sub(used)) as f64 {
        // NaN (a shape of zero size: 0 / 0) counts as nothing.
        Ok(if count >= 0.0 { count as usize } else { 0 })
    } else {
        Err(SampleError::TooManyPoints { limit: MAX_POINTS })
    }
}

/// SplitMix64: small, seedable, good enough for test data.
struct Random(u64);

impl Random {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The local spacing of a curve sampled with `variation` (see [`Sampling::density_variation`]),
/// as a fraction of the bound, at `fraction` of its length: `1 / variation` at the start, 1
/// halfway, smooth and periodic so a closed curve has no seam.
fn spacing_factor(variation: f64, fraction: f64) -> f64 {
    let low = 1.0 / variation.max(1.0);
    low + (1.0 - low) * (0.5 - 0.5 * libm::cos(TAU * fraction))
}

/// Samples of `curve(t)`, `t` in `[0, 1]`, at most `spacing` apart in arc length: evenly spaced
/// when `variation` is 1, otherwise with the local spacing `spacing · spacing_factor`; at least
/// `min_pieces` pieces. For a closed curve `curve(1) == curve(0)` and the last sample is not
/// repeated. Refused when there would be more samples than fit after `used` points.
fn along(
    curve: impl Fn(f64) -> Point,
    (closed, min_pieces): (bool, f64),
    spacing: f64,
    variation: f64,
    used: usize,
) -> Result<Vec<Point>, SampleError> {
    const FINE: usize = 8192;
    let dense: Vec<Point> = (0..=FINE).map(|k| curve(k as f64 / FINE as f64)).collect();
    let mut cumulative = Vec::with_capacity(dense.len());
    let mut total = 0.0;
    cumulative.push(0.0);
    for w in dense.windows(2) {
        total += libm::sqrt(w[0].dist2(w[1]));
        cumulative.push(total);
    }
    if variation > 1.0 {
        // Measure the curve in units of the local spacing: evenly spaced targets on that
        // measure are samples whose spacing follows the factor.
        let mut stretched = 0.0;
        let lengths = cumulative.clone();
        for j in 1..cumulative.len() {
            let middle = 0.5 * (lengths[j - 1] + lengths[j]) / total;
            stretched += (lengths[j] - lengths[j - 1]) / spacing_factor(variation, middle);
            cumulative[j] = stretched;
        }
        total = stretched;
    }
    let pieces = libm::ceil(total / spacing).max(min_pieces);
    check_room(used, if closed { pieces } else { pieces + 1.0 })?;
    let pieces = pieces as usize;
    let count = if closed { pieces } else { pieces + 1 };
    let mut samples = Vec::with_capacity(count);
    let mut j = 0;
    for k in 0..count {
        let target = total * k as f64 / pieces as f64;
        while j + 1 < cumulative.len() - 1 && cumulative[j + 1] < target {
            j += 1;
        }
        let span = cumulative[j + 1] - cumulative[j];
        let f = if span > 0.0 {
            ((target - cumulative[j]) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        // On the curve itself, not on the polyline used to measure it: samples on one straight
        // piece would be collinear, which no curve is.
        samples.push(curve((j as f64 + f) / FINE as f64));
    }
    Ok(samples)
}

/// Fewest pieces of a closed curve (a triangle) and of an open one (a segment).
const CLOSED: (bool, f64) = (true, 3.0);
const OPEN: (bool, f64) = (false, 1.0);

/// Appends a chain of samples to `out`, joining consecutive ones (and the ends, if closed).
fn push_chain(out: &mut Sample, chain: &[Point], closed: bool) {
    let base = out.points.len();
    out.points.extend_from_slice(chain);
    for k in 1..chain.len() {
        out.edges.push([base + k - 1, base + k]);
    }
    if closed && chain.len() > 2 {
        out.edges.push([base, base + chain.len() - 1]);
    }
}

/// Samples `shapes` as `sampling` says.
///
/// # Errors
/// [`SampleError::Epsilon`] when `epsilon` is not positive (or NaN);
/// [`SampleError::TooManyPoints`] when the samples and outliers would be more than
/// [`condt::MAX_POINTS`] (refused before they are allocated).
///
/// ```
/// use condt_eval::sample::{sample, Sampling, Shape};
/// use condt::Point;
/// let eight = sample(&[Shape::FigureEight { center: Point::new(0.0, 0.0), size: 1.0 }], &Sampling::new(0.1)).unwrap();
/// let crossing_degree = eight.edges.iter().filter(|e| e.contains(&0)).count();
/// assert_eq!(crossing_degree, 4);
/// ```
pub fn sample(shapes: &[Shape], sampling: &Sampling) -> Result<Sample, SampleError> {
    if sampling.epsilon.is_nan() || sampling.epsilon <= 0.0 {
        return Err(SampleError::Epsilon(sampling.epsilon));
    }
    let mut out = Sample::default();
    for shape in shapes {
        push_shape(
            &mut out,
            shape,
            sampling.epsilon,
            sampling.density_variation,
        )?;
    }
    check_room(
        out.points.len(),
        libm::round(sampling.outlier_fraction * out.points.len() as f64),
    )?;
    // One stream for both steps: the outliers draw where the noise stopped.
    let mut random = Random(sampling.seed);
    add_noise(&mut out.points, sampling, &mut random);
    add_outliers(&mut out, sampling, &mut random);
    sort_edges(&mut out.edges);
    Ok(out)
}

/// Appends the samples and ground-truth edges of one shape to `out`.
fn push_shape(
    out: &mut Sample,
    shape: &Shape,
    eps: f64,
    variation: f64,
) -> Result<(), SampleError> {
    let eps = (eps, variation);
    match *shape {
        Shape::Ellipse {
            center,
            radii,
            rotation,
        } => push_ellipse(out, center, radii, rotation, eps),
        Shape::Arc {
            center,
            radius,
            start,
            sweep,
        } => push_arc(out, center, radius, start, sweep, eps),
        Shape::Spiral {
            center,
            inner,
            gap,
            turns,
        } => push_spiral(out, center, inner, gap, turns, eps),
        Shape::Polygon(ref corners) => push_polygon(out, corners, eps),
        Shape::FigureEight { center, size } => push_figure_eight(out, center, size, eps),
    }
}

/// A closed ellipse; its lfs is the smallest radius of curvature, `small² / big`.
fn push_ellipse(
    out: &mut Sample,
    center: Point,
    (a, b): (f64, f64),
    rotation: f64,
    (eps, variation): (f64, f64),
) -> Result<(), SampleError> {
    let (big, small) = (a.max(b), a.min(b));
    let (c, s) = (libm::cos(rotation), libm::sin(rotation));
    let at = |t: f64| {
        let (x, y) = (a * libm::cos(TAU * t), b * libm::sin(TAU * t));
        Point::new(center.x + c * x - s * y, center.y + s * x + c * y)
    };
    let used = out.points.len();
    let chain = along(at, CLOSED, eps * small * small / big, variation, used)?;
    push_chain(out, &chain, true);
    Ok(())
}

/// An open circular arc; its lfs is the radius.
fn push_arc(
    out: &mut Sample,
    center: Point,
    radius: f64,
    start: f64,
    sweep: f64,
    (eps, variation): (f64, f64),
) -> Result<(), SampleError> {
    let at = |t: f64| {
        let angle = start + sweep * t;
        Point::new(
            center.x + radius * libm::cos(angle),
            center.y + radius * libm::sin(angle),
        )
    };
    let chain = along(at, OPEN, eps * radius, variation, out.points.len())?;
    push_chain(out, &chain, false);
    Ok(())
}

/// An open Archimedean spiral; its lfs is the smaller of the start radius and half the gap.
fn push_spiral(
    out: &mut Sample,
    center: Point,
    inner: f64,
    gap: f64,
    turns: f64,
    (eps, variation): (f64, f64),
) -> Result<(), SampleError> {
    let at = |t: f64| {
        let angle = TAU * turns * t;
        let r = inner + gap * angle / TAU;
        Point::new(
            center.x + r * libm::cos(angle),
            center.y + r * libm::sin(angle),
        )
    };
    let spacing = eps * inner.min(gap / 2.0);
    let chain = along(at, OPEN, spacing, variation, out.points.len())?;
    push_chain(out, &chain, false);
    Ok(())
}

/// A closed polygon: every corner is a sample, and each side is cut evenly into pieces at most
/// `eps` times the shortest side long (side `k` of `n` at `spacing_factor(variation, k / n)` of
/// that bound). A corner equal to the one before it (cyclically) is dropped: it would make the
/// shortest side, and so the spacing, zero.
fn push_polygon(
    out: &mut Sample,
    corners: &[Point],
    (eps, variation): (f64, f64),
) -> Result<(), SampleError> {
    let mut corners: Vec<Point> = corners.to_vec();
    corners.dedup();
    while corners.len() > 1 && corners.first() == corners.last() {
        corners.pop();
    }
    let n = corners.len();
    let side = |k: usize| libm::sqrt(corners[k].dist2(corners[(k + 1) % n]));
    let shortest = (0..n).map(side).fold(f64::INFINITY, f64::min);
    let bound = |k: usize| {
        if variation > 1.0 {
            eps * shortest * spacing_factor(variation, k as f64 / n as f64)
        } else {
            eps * shortest
        }
    };
    let pieces = |k: usize| libm::ceil(side(k) / bound(k)).max(1.0);
    check_room(out.points.len(), (0..n).map(pieces).sum())?;
    let mut chain = Vec::new();
    for k in 0..n {
        let (p, q) = (corners[k], corners[(k + 1) % n]);
        let pieces = pieces(k) as usize;
        for j in 0..pieces {
            let f = j as f64 / pieces as f64;
            chain.push(Point::new(p.x + f * (q.x - p.x), p.y + f * (q.y - p.y)));
        }
    }
    push_chain(out, &chain, true);
    Ok(())
}

/// Gerono's lemniscate as two lobes, `t` in `[0, π]` and `t` in `[π, 2π]`. Both start and end
/// at the crossing, which is sampled once and shared, so it gets four edges. Each lobe has at
/// least two samples besides the crossing (three pieces, a triangle), however large `eps`: with
/// fewer its edges would be a self-loop or the same edge twice.
fn push_figure_eight(
    out: &mut Sample,
    center: Point,
    size: f64,
    (eps, variation): (f64, f64),
) -> Result<(), SampleError> {
    check_room(out.points.len(), 1.0)?;
    let crossing = out.points.len();
    out.points.push(center);
    for lobe in 0..2 {
        let offset = lobe as f64 * PI;
        let at = |t: f64| {
            let u = offset + PI * t;
            Point::new(
                center.x + size * libm::sin(u),
                center.y + size * libm::sin(u) * libm::cos(u),
            )
        };
        let used = out.points.len();
        let chain = along(at, (false, 3.0), eps * size / 4.0, variation, used)?;
        let inner = &chain[1..chain.len() - 1];
        let base = out.points.len();
        out.points.extend_from_slice(inner);
        out.edges.push([crossing, base]);
        for k in 1..inner.len() {
            out.edges.push([base + k - 1, base + k]);
        }
        out.edges.push([crossing, base + inner.len() - 1]);
    }
    Ok(())
}

/// Moves each point by the sampling's noise, uniform within `±noise` in x and y (x drawn before
/// y) or Gaussian with standard deviation `noise` (Box–Muller, two draws per point); draws
/// nothing when `noise` is not positive.
fn add_noise(points: &mut [Point], sampling: &Sampling, random: &mut Random) {
    let noise = sampling.noise;
    if noise <= 0.0 {
        return;
    }
    for p in points.iter_mut() {
        let (u, v) = (random.unit(), random.unit());
        let (dx, dy) = if sampling.gaussian_noise {
            // 1 - u lies in (0, 1], so the logarithm is finite.
            let r = libm::sqrt(-2.0 * libm::log(1.0 - u));
            (r * libm::cos(TAU * v), r * libm::sin(TAU * v))
        } else {
            (2.0 * u - 1.0, 2.0 * v - 1.0)
        };
        p.x += dx * noise;
        p.y += dy * noise;
    }
}

/// Appends `outlier_fraction` times as many uniform points in the bounding box as there are
/// curve samples, redrawing any closer than `outlier_clearance` to an earlier point (for a
/// clump, to any point before the clump); with `outlier_clumps`, each draw is the centre of a
/// clump. Gives up after a thousand draws per wanted outlier, so a clearance too large for the
/// box ends with fewer outliers rather than never.
fn add_outliers(out: &mut Sample, sampling: &Sampling, random: &mut Random) {
    let curve_points = out.points.len();
    let extra = libm::round(sampling.outlier_fraction * curve_points as f64) as usize;
    if extra == 0 {
        return;
    }
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for p in &out.points {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let clearance2 = sampling.outlier_clearance * sampling.outlier_clearance;
    // A point is clear when no point before `from` lies within the clearance.
    let clear = |points: &[Point], from: usize, p: Point| {
        clearance2 <= 0.0 || points[..from].iter().all(|q| q.dist2(p) >= clearance2)
    };
    let mut attempts = 0;
    while out.outliers.len() < extra && attempts < 1000 * extra {
        attempts += 1;
        let p = Point::new(
            lo.x + random.unit() * (hi.x - lo.x),
            lo.y + random.unit() * (hi.y - lo.y),
        );
        let Some(clumps) = sampling.outlier_clumps else {
            if clear(&out.points, out.points.len(), p) {
                out.outliers.push(out.points.len());
                out.points.push(p);
            }
            continue;
        };
        // A clump: its centre and members must be clear of everything before the clump.
        let before = out.points.len();
        if !clear(&out.points, before, p) {
            continue;
        }
        let (min, max) = (clumps.min.max(1), clumps.max.max(clumps.min.max(1)));
        let size = min + (random.unit() * (max - min + 1) as f64) as usize;
        let size = size.min(max).min(extra - out.outliers.len());
        for _ in 0..size {
            let (r, angle) = (
                clumps.radius * libm::sqrt(random.unit()),
                TAU * random.unit(),
            );
            let q = Point::new(p.x + r * libm::cos(angle), p.y + r * libm::sin(angle));
            if clear(&out.points, before, q) {
                out.outliers.push(out.points.len());
                out.points.push(q);
            }
        }
    }
}

/// Puts every edge as `[low, high]` and the list in ascending order.
fn sort_edges(edges: &mut [[usize; 2]]) {
    for e in edges.iter_mut() {
        e.sort_unstable();
    }
    edges.sort_unstable();
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    fn spacings(s: &Sample) -> Vec<f64> {
        s.edges
            .iter()
            .map(|&[a, b]| libm::sqrt(s.points[a].dist2(s.points[b])))
            .collect()
    }

    #[test]
    fn density_varies_by_the_ratio_asked_and_never_beyond_the_bound() {
        let circle = [Shape::circle(Point::new(0.0, 0.0), 1.0)];
        for variation in [2.0, 4.0] {
            let s = sample(
                &circle,
                &Sampling {
                    density_variation: variation,
                    ..Sampling::new(0.1)
                },
            )
            .unwrap();
            let d = spacings(&s);
            let (short, long) = d.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            });
            // Chords of a unit circle: the bound 0.1 in arc length is a little more as a chord.
            assert!(long <= 0.1 + 1e-12, "{long}");
            let ratio = long / short;
            assert!(
                (ratio - variation).abs() < 0.15 * variation,
                "{variation}: {ratio}"
            );
        }
        let even = spacings(&sample(&circle, &Sampling::new(0.1)).unwrap());
        let (lo, hi) = even.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        assert!(hi / lo < 1.01, "even sampling stays even: {}", hi / lo);
    }

    /// A sample's edges are within its points, none a self-loop and none twice.
    fn assert_well_formed(s: &Sample) {
        for &[a, b] in &s.edges {
            assert!(
                a < b && b < s.points.len(),
                "edge {a} {b} of {}",
                s.points.len()
            );
        }
        assert!(s.edges.windows(2).all(|w| w[0] != w[1]), "{:?}", s.edges);
    }

    #[test]
    fn repeated_polygon_corners_are_one_corner() {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
        let plain = sample(&[Shape::Polygon(square.to_vec())], &Sampling::new(0.25)).unwrap();
        assert_eq!(plain.points.len(), 16);
        // Closed by repeating the first corner, and with a corner given twice in a row.
        let closed = [&square[..], &square[..1]].concat();
        let doubled = [&square[..2], &square[1..]].concat();
        for corners in [closed, doubled] {
            let s = sample(&[Shape::Polygon(corners)], &Sampling::new(0.25)).unwrap();
            assert_eq!(s, plain);
        }
    }

    #[test]
    fn a_spacing_that_is_not_positive_is_refused() {
        let circle = [Shape::circle(Point::new(0.0, 0.0), 1.0)];
        for epsilon in [0.0, -0.1, f64::NEG_INFINITY] {
            assert_eq!(
                sample(&circle, &Sampling::new(epsilon)),
                Err(SampleError::Epsilon(epsilon))
            );
        }
        let nan = sample(&circle, &Sampling::new(f64::NAN)).unwrap_err();
        assert!(matches!(nan, SampleError::Epsilon(e) if e.is_nan()));
    }

    #[test]
    fn more_points_than_the_triangulation_takes_are_refused_before_allocating() {
        let too_many = Err(SampleError::TooManyPoints { limit: MAX_POINTS });
        let circle = Shape::circle(Point::new(0.0, 0.0), 1.0);
        let square = Shape::Polygon(
            [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]
                .map(Point::from)
                .to_vec(),
        );
        let eight = Shape::FigureEight {
            center: Point::new(0.0, 0.0),
            size: 1.0,
        };
        let arc = Shape::Arc {
            center: Point::new(0.0, 0.0),
            radius: 1.0,
            start: 0.0,
            sweep: 1.0,
        };
        for shape in [circle.clone(), square, eight, arc] {
            // 1e-12 asked for a 100 TB allocation; the smallest positive number, infinitely many.
            for epsilon in [1e-12, f64::from_bits(1)] {
                assert_eq!(
                    sample(core::slice::from_ref(&shape), &Sampling::new(epsilon)),
                    too_many
                );
            }
        }
        // The limit counts the whole sample, outliers too.
        let outliers = Sampling {
            outlier_fraction: 1e12,
            ..Sampling::new(0.1)
        };
        assert_eq!(sample(&[circle], &outliers), too_many);
    }

    #[test]
    fn a_coarse_figure_eight_keeps_a_sample_per_lobe_and_no_bad_edge() {
        for epsilon in [1.0, 4.0, 100.0, f64::INFINITY] {
            let s = sample(
                &[Shape::FigureEight {
                    center: Point::new(0.0, 0.0),
                    size: 1.0,
                }],
                &Sampling::new(epsilon),
            )
            .unwrap();
            assert_well_formed(&s);
            // The crossing and two samples on each side of it: two triangles sharing a corner.
            assert!(s.points[1..].iter().any(|p| p.x > 0.0), "{epsilon}");
            assert!(s.points[1..].iter().any(|p| p.x < 0.0), "{epsilon}");
            assert_eq!(s.edges.iter().filter(|e| e.contains(&0)).count(), 4);
        }
    }

    #[test]
    fn polygon_sides_get_different_spacings() {
        let square = [Shape::Polygon(vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ])];
        let s = sample(
            &square,
            &Sampling {
                density_variation: 4.0,
                ..Sampling::new(0.1)
            },
        )
        .unwrap();
        // Side 0 at a quarter of the bound, side 2 at the bound: 40 and 10 pieces.
        let per_side = |k: usize| {
            let on_side = |p: &Point| match k {
                0 => p.y == 0.0,
                _ => p.y == 1.0,
            };
            s.points.iter().filter(|p| on_side(p)).count()
        };
        assert_eq!(per_side(0), 41);
        assert_eq!(per_side(2), 11);
    }

    #[test]
    fn gaussian_noise_has_the_asked_deviation_and_uniform_noise_stays_in_its_box() {
        let shapes = [Shape::circle(Point::new(0.0, 0.0), 10.0)];
        let clean = sample(&shapes, &Sampling::new(0.001)).unwrap();
        assert!(clean.points.len() > 5000);
        let moved = |gaussian_noise: bool| {
            let noisy = sample(
                &shapes,
                &Sampling {
                    noise: 0.01,
                    gaussian_noise,
                    ..Sampling::new(0.001)
                },
            )
            .unwrap();
            clean
                .points
                .iter()
                .zip(&noisy.points)
                .map(|(a, b)| (b.x - a.x, b.y - a.y))
                .collect::<Vec<_>>()
        };
        let gaussian = moved(true);
        let variance =
            gaussian.iter().map(|&(x, y)| x * x + y * y).sum::<f64>() / (2 * gaussian.len()) as f64;
        assert!((libm::sqrt(variance) - 0.01).abs() < 0.0005, "{variance}");
        assert!(
            gaussian.iter().any(|&(x, _)| x.abs() > 0.01),
            "tails beyond one sigma"
        );
        let uniform = moved(false);
        assert!(uniform
            .iter()
            .all(|&(x, y)| x.abs() <= 0.01 && y.abs() <= 0.01));
    }

    #[test]
    fn clumped_outliers_come_in_groups_of_the_asked_sizes() {
        let radius = 0.05;
        let s = sample(
            &[Shape::circle(Point::new(0.0, 0.0), 1.0)],
            &Sampling {
                outlier_fraction: 0.3,
                outlier_clearance: 0.2,
                outlier_clumps: Some(Clumps {
                    min: 3,
                    max: 7,
                    radius,
                }),
                ..Sampling::new(0.05)
            },
        )
        .unwrap();
        let curve_points = s.points.len() - s.outliers.len();
        assert_eq!(
            s.outliers.len(),
            libm::round(0.3 * curve_points as f64) as usize
        );
        // Every outlier has a clump mate within the clump's diameter, and none is near the curve.
        for &i in &s.outliers {
            let p = s.points[i];
            let mates = s
                .outliers
                .iter()
                .filter(|&&j| j != i && s.points[j].dist2(p) <= 4.0 * radius * radius)
                .count();
            assert!(mates >= 1, "outlier {i} is alone");
            assert!(s.points[..curve_points]
                .iter()
                .all(|q| q.dist2(p) >= 0.2 * 0.2));
        }
    }
}
