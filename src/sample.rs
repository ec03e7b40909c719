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
//! ```
//! use condt::sample::{sample, Sampling, Shape};
//! use condt::Point;
//! let s = sample(&[Shape::circle(Point::new(0.0, 0.0), 1.0)], &Sampling::new(0.2));
//! assert_eq!(s.points.len(), s.edges.len()); // closed: as many edges as points
//! assert!(s.outliers.is_empty());
//! ```

use crate::geometry::Point;
use alloc::vec::Vec;
use core::f64::consts::{PI, TAU};

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
    /// A closed polygon with sharp corners, each corner a sample.
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
    /// Each curve sample is moved uniformly within ±`noise` in x and y.
    pub noise: f64,
    /// Seed of the outliers and the noise.
    pub seed: u64,
}

impl Sampling {
    /// Clean sampling at `epsilon`: no outliers, no noise.
    pub fn new(epsilon: f64) -> Sampling {
        Sampling {
            epsilon,
            outlier_fraction: 0.0,
            outlier_clearance: 0.0,
            noise: 0.0,
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

/// Samples of `curve(t)`, `t` in `[0, 1]`, evenly spaced in arc length at most `spacing` apart.
/// For a closed curve `curve(1) == curve(0)` and the last sample is not repeated.
fn along(curve: impl Fn(f64) -> Point, closed: bool, spacing: f64) -> Vec<Point> {
    const FINE: usize = 8192;
    let dense: Vec<Point> = (0..=FINE).map(|k| curve(k as f64 / FINE as f64)).collect();
    let mut cumulative = Vec::with_capacity(dense.len());
    let mut total = 0.0;
    cumulative.push(0.0);
    for w in dense.windows(2) {
        total += libm::sqrt(w[0].dist2(w[1]));
        cumulative.push(total);
    }
    let pieces = libm::ceil(total / spacing).max(if closed { 3.0 } else { 1.0 }) as usize;
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
    samples
}

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
/// ```
/// use condt::sample::{sample, Sampling, Shape};
/// use condt::Point;
/// let eight = sample(&[Shape::FigureEight { center: Point::new(0.0, 0.0), size: 1.0 }], &Sampling::new(0.1));
/// let crossing_degree = eight.edges.iter().filter(|e| e.contains(&0)).count();
/// assert_eq!(crossing_degree, 4);
/// ```
pub fn sample(shapes: &[Shape], sampling: &Sampling) -> Sample {
    let mut out = Sample::default();
    for shape in shapes {
        push_shape(&mut out, shape, sampling.epsilon);
    }
    // One stream for both steps: the outliers draw where the noise stopped.
    let mut random = Random(sampling.seed);
    add_noise(&mut out.points, sampling.noise, &mut random);
    add_outliers(&mut out, sampling, &mut random);
    sort_edges(&mut out.edges);
    out
}

/// Appends the samples and ground-truth edges of one shape to `out`.
fn push_shape(out: &mut Sample, shape: &Shape, eps: f64) {
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
fn push_ellipse(out: &mut Sample, center: Point, (a, b): (f64, f64), rotation: f64, eps: f64) {
    let (big, small) = (a.max(b), a.min(b));
    let (c, s) = (libm::cos(rotation), libm::sin(rotation));
    let at = |t: f64| {
        let (x, y) = (a * libm::cos(TAU * t), b * libm::sin(TAU * t));
        Point::new(center.x + c * x - s * y, center.y + s * x + c * y)
    };
    push_chain(out, &along(at, true, eps * small * small / big), true);
}

/// An open circular arc; its lfs is the radius.
fn push_arc(out: &mut Sample, center: Point, radius: f64, start: f64, sweep: f64, eps: f64) {
    let at = |t: f64| {
        let angle = start + sweep * t;
        Point::new(
            center.x + radius * libm::cos(angle),
            center.y + radius * libm::sin(angle),
        )
    };
    push_chain(out, &along(at, false, eps * radius), false);
}

/// An open Archimedean spiral; its lfs is the smaller of the start radius and half the gap.
fn push_spiral(out: &mut Sample, center: Point, inner: f64, gap: f64, turns: f64, eps: f64) {
    let at = |t: f64| {
        let angle = TAU * turns * t;
        let r = inner + gap * angle / TAU;
        Point::new(
            center.x + r * libm::cos(angle),
            center.y + r * libm::sin(angle),
        )
    };
    push_chain(out, &along(at, false, eps * inner.min(gap / 2.0)), false);
}

/// A closed polygon: every corner is a sample, and each side is cut evenly into pieces at most
/// `eps` times the shortest side long.
fn push_polygon(out: &mut Sample, corners: &[Point], eps: f64) {
    let n = corners.len();
    let side = |k: usize| libm::sqrt(corners[k].dist2(corners[(k + 1) % n]));
    let shortest = (0..n).map(side).fold(f64::INFINITY, f64::min);
    let mut chain = Vec::new();
    for k in 0..n {
        let (p, q) = (corners[k], corners[(k + 1) % n]);
        let pieces = libm::ceil(side(k) / (eps * shortest)).max(1.0) as usize;
        for j in 0..pieces {
            let f = j as f64 / pieces as f64;
            chain.push(Point::new(p.x + f * (q.x - p.x), p.y + f * (q.y - p.y)));
        }
    }
    push_chain(out, &chain, true);
}

/// Gerono's lemniscate as two lobes, `t` in `[0, π]` and `t` in `[π, 2π]`. Both start and end
/// at the crossing, which is sampled once and shared, so it gets four edges.
fn push_figure_eight(out: &mut Sample, center: Point, size: f64, eps: f64) {
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
        let chain = along(at, false, eps * size / 4.0);
        let inner = &chain[1..chain.len() - 1];
        let base = out.points.len();
        out.points.extend_from_slice(inner);
        out.edges.push([crossing, base]);
        for k in 1..inner.len() {
            out.edges.push([base + k - 1, base + k]);
        }
        out.edges.push([crossing, base + inner.len() - 1]);
    }
}

/// Moves each point uniformly within `±noise` in x and y (x drawn before y); draws nothing when
/// `noise` is not positive.
fn add_noise(points: &mut [Point], noise: f64, random: &mut Random) {
    if noise > 0.0 {
        for p in points.iter_mut() {
            p.x += (2.0 * random.unit() - 1.0) * noise;
            p.y += (2.0 * random.unit() - 1.0) * noise;
        }
    }
}

/// Appends `outlier_fraction` times as many uniform points in the bounding box as there are
/// curve samples, redrawing any closer than `outlier_clearance` to an earlier point. Gives up
/// after a thousand draws per wanted outlier, so a clearance too large for the box ends with
/// fewer outliers rather than never.
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
    let mut attempts = 0;
    while out.outliers.len() < extra && attempts < 1000 * extra {
        attempts += 1;
        let p = Point::new(
            lo.x + random.unit() * (hi.x - lo.x),
            lo.y + random.unit() * (hi.y - lo.y),
        );
        if clearance2 > 0.0 && out.points.iter().any(|q| q.dist2(p) < clearance2) {
            continue;
        }
        out.outliers.push(out.points.len());
        out.points.push(p);
    }
}

/// Puts every edge as `[low, high]` and the list in ascending order.
fn sort_edges(edges: &mut [[usize; 2]]) {
    for e in edges.iter_mut() {
        e.sort_unstable();
    }
    edges.sort_unstable();
}
