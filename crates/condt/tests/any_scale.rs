//! Coordinates at any scale and with any spread of magnitudes (issue 11, items 2 and 8): the
//! triangulation accepts every finite input, and the reconstruction of a set does not change
//! when the set is multiplied by a power of two.

mod common;

use common::{edge_set, Rng};
use condt::{reconstruct, triangulate, Params, Point, Reconstruction};
use condt_eval::sample::{sample, Sampling, Shape};

fn scaled(points: &[Point], factor: f64) -> Vec<Point> {
    let out: Vec<Point> = points
        .iter()
        .map(|p| Point::new(p.x * factor, p.y * factor))
        .collect();
    // The factor is a power of two and nothing leaves the normal range: exact, and reversible.
    for (p, q) in points.iter().zip(&out) {
        assert_eq!(Point::new(q.x / factor, q.y / factor), *p);
    }
    out
}

fn shapes_txt() -> Vec<Point> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/shapes.txt");
    condt_io::read_points(path).unwrap()
}

/// Everything a reconstruction reports, in input positions.
fn summary(r: &Reconstruction) -> (Vec<[usize; 2]>, Vec<Vec<usize>>, Vec<usize>) {
    let curves = r.curves().iter().map(|c| c.points().collect()).collect();
    (r.edges().collect(), curves, r.unused().to_vec())
}

/// Issue 11, item 2: `shapes.txt` times 2^600 gave 49 curves and 106 unused points instead of 4
/// and 7, because the stages squared unscaled coordinates (overflow above about 1e154); times
/// 2^-600 their squares underflowed to zero.
#[test]
fn shapes_txt_times_2_pow_600_and_2_pow_minus_600_reconstruct_as_unscaled() {
    let points = shapes_txt();
    for params in [Params::default(), Params::paper()] {
        let unscaled = reconstruct(&points, &params).unwrap();
        for factor in [2f64.powi(600), 2f64.powi(-600), 2f64.powi(-1000)] {
            let r = reconstruct(&scaled(&points, factor), &params).unwrap();
            assert_eq!(summary(&r), summary(&unscaled), "factor {factor:e}");
        }
    }
    let r = reconstruct(&scaled(&points, 2f64.powi(600)), &Params::default()).unwrap();
    assert_eq!((r.curves().len(), r.unused().len()), (4, 7));
}

/// The same for sampled shapes with outliers, at scales from 2^-1000 to 2^1000, and with the
/// local outlier stage, whose rules multiply squared lengths together.
#[test]
fn sampled_shapes_reconstruct_the_same_at_every_power_of_two_scale() {
    let shapes = [
        Shape::circle(Point::new(0.0, 0.0), 3.0),
        Shape::Ellipse {
            center: Point::new(9.0, 1.0),
            radii: (4.0, 1.5),
            rotation: 0.4,
        },
        Shape::FigureEight {
            center: Point::new(0.0, 9.0),
            size: 4.0,
        },
    ];
    let mut sampling = Sampling::new(0.3);
    sampling.outlier_fraction = 0.05;
    sampling.noise = 0.01;
    let points = sample(&shapes, &sampling).unwrap().points;
    let local = Params::default().with_local_outliers(true);
    for params in [Params::default(), local] {
        let unscaled = reconstruct(&points, &params).unwrap();
        assert!(unscaled.curves().len() >= 3);
        for k in [-1000, -700, -400, -100, 100, 400, 700, 1000] {
            let r = reconstruct(&scaled(&points, 2f64.powi(k)), &params).unwrap();
            assert_eq!(summary(&r), summary(&unscaled), "scaled by 2^{k}");
        }
    }
}

/// Issue 11, item 8: a unit triangle and a point 1e-61 right of its left side spans more than
/// 2^200 in magnitude and was refused (`RangeTooWide`). The point is strictly inside the
/// triangle, so the triangulation is the fan of three triangles around it.
#[test]
fn a_point_1e_minus_61_from_a_side_is_triangulated() {
    let points = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1e-61, 0.5)].map(Point::from);
    let tri = triangulate(&points).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.triangles().count(), 3);
    let mut around: Vec<usize> = tri.neighbors(3).collect();
    around.sort_unstable();
    assert_eq!(around, vec![0, 1, 2]);
    let mut hull: Vec<usize> = tri.hull().collect();
    hull.sort_unstable();
    assert_eq!(hull, vec![0, 1, 2]);
    // Moved onto the side, it splits that edge instead: two triangles, still valid.
    let on_side = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, 0.5)].map(Point::from);
    assert_eq!(triangulate(&on_side).unwrap().triangles().count(), 2);
}

/// A double with a random sign, a random exponent in `exponents` and a random mantissa.
fn random_double(rng: &mut Rng, exponents: core::ops::Range<i32>) -> f64 {
    let span = (exponents.end - exponents.start) as usize;
    let e = exponents.start + rng.below(span) as i32;
    let magnitude = (1.0 + rng.unit()) * 2f64.powi(e.max(-1022)) * 2f64.powi((e + 1022).min(0));
    if rng.below(2) == 0 {
        magnitude
    } else {
        -magnitude
    }
}

/// Random sets whose coordinates span the whole double range, from subnormals to 2^1023, and
/// mixes of an ordinary cloud with a few points at extreme magnitudes: every one triangulates,
/// passes `validate()` (with the exact predicates) and has the triangle count its hull implies.
#[test]
fn sets_spanning_the_whole_double_range_triangulate_validly() {
    let mut rng = Rng::new(11);
    for round in 0..6 {
        let mut points: Vec<Point> = if round % 2 == 0 {
            (0..60)
                .map(|_| {
                    let x = random_double(&mut rng, -1074..1023);
                    Point::new(x, random_double(&mut rng, -1074..1023))
                })
                .collect()
        } else {
            (0..600)
                .map(|_| Point::new(rng.unit(), rng.unit()))
                .collect()
        };
        for _ in 0..8 {
            let p = Point::new(
                random_double(&mut rng, -1074..1023),
                random_double(&mut rng, -1074..1023),
            );
            // Some extreme points, some with one extreme and one ordinary coordinate.
            if rng.below(2) == 0 {
                points.push(p);
            } else {
                let q = points[rng.below(points.len())];
                points.push(Point::new(p.x, q.y));
            }
        }
        let tri = triangulate(&points).unwrap();
        tri.validate().unwrap();
        let (n, h) = (tri.num_vertices(), tri.hull().count());
        assert!(!tri.is_degenerate());
        assert_eq!(tri.triangles().count(), 2 * n - 2 - h, "round {round}");
    }
}

/// A set just beyond the fast range triangulates like the same set with the tiny coordinate
/// set to zero, where the fast predicates apply, when the move crosses no predicate: here the
/// point sits alone in the middle of an empty square either way.
#[test]
fn a_tiny_coordinate_changes_nothing_it_should_not() {
    let mut rng = Rng::new(5);
    let mut points: Vec<Point> = (0..2000)
        .map(|_| {
            let p = Point::new(2.0 * rng.unit() - 1.0, rng.unit());
            // Keep a square hole around (0, 0.5).
            if p.x.abs() < 0.1 && (p.y - 0.5).abs() < 0.1 {
                Point::new(p.x + 0.5, p.y)
            } else {
                p
            }
        })
        .collect();
    points.push(Point::new(0.0, 0.5));
    let reference = triangulate(&points).unwrap();
    let last = points.len() - 1;
    for tiny in [1e-70, -1e-200, 1e-320] {
        points[last] = Point::new(tiny, 0.5);
        let exact = triangulate(&points).unwrap();
        exact.validate().unwrap();
        assert_eq!(edge_set(&exact), edge_set(&reference), "{tiny:e}");
    }
}

/// The stages' positions of a set spanning the whole range lose the smallest coordinates' bits;
/// the triangulation still answers every input point exactly as given, and validates.
#[test]
fn input_points_come_back_exactly_from_the_widest_sets() {
    let points = [
        (f64::MAX, 0.0),
        (5e-324, 1e-300),
        (0.0, -f64::MAX),
        (-1e-310, 3.0),
        (-f64::MAX, f64::MAX),
        (1.0, 1e-320),
    ]
    .map(Point::from);
    let tri = triangulate(&points).unwrap();
    tri.validate().unwrap();
    for (i, &p) in points.iter().enumerate() {
        assert_eq!(tri.point(i), p, "point {i}");
    }
}

/// A smoothing pass hands on positions relative to a corner of the set's box, and the stages'
/// positions add the corner back: next to `f64::MAX` that sum rounded past the largest double,
/// and `stage_point` of a curve's end, which no pass moves, read as infinite. (Found by a
/// fuzzer.)
#[test]
fn stage_points_next_to_the_largest_double_stay_finite() {
    let points = [
        (8.988465674311579e307, 1.7976931348623157e308),
        (4.332386899878474e307, 1.1263929698464622e308),
        (1.7976931348623157e308, 8.089602798306176e307),
        (8.988465674311579e307, 8.988465674311579e307),
    ]
    .map(Point::from);
    let result = reconstruct(&points, &Params::default()).unwrap();
    assert!(result.smoothing().is_some(), "a pass ran");
    let slack = 1e-12 * f64::MAX;
    let within = |v: f64, of: fn(&Point) -> f64| {
        let lowest = points.iter().map(of).fold(f64::INFINITY, f64::min);
        let highest = points.iter().map(of).fold(f64::NEG_INFINITY, f64::max);
        v >= lowest - slack && v <= highest
    };
    for (i, given) in points.iter().enumerate() {
        let p = result.stage_point(i);
        assert!(
            within(p.x, |p| p.x) && within(p.y, |p| p.y),
            "point {i}: {p:?}"
        );
        if result.degree(i) == 1 {
            // A curve's end does not move: within rounding of where it was.
            assert!((p.x - given.x).abs() <= slack, "point {i}: {p:?}");
            assert!((p.y - given.y).abs() <= slack, "point {i}: {p:?}");
        }
    }
}

/// Crowded grid cells (1,024 points or more; until 2026-12-06 only in sets of 65,536 points or
/// more) are ordered again, each on a grid of its own. A set
/// narrower than about 2^-1000 made the grid's step overflow (and a set wider than `f64::MAX`
/// made it zero): every point fell in one cell, which was ordered again the same way until the
/// stack overflowed (an abort, not a panic). Such sets now reconstruct, as their rescaled copies.
#[test]
fn sets_of_65536_points_narrower_than_2_pow_minus_1000_or_wider_than_f64_max_reconstruct() {
    let n = 1 << 16;
    let mut rng = Rng::new(65_536);
    let narrow: Vec<Point> = (0..n)
        .map(|_| Point::new(rng.unit() * 1e-303, rng.unit() * 1e-303))
        .collect();
    let wide_points: Vec<Point> = (0..n)
        .map(|_| {
            Point::new(
                (2.0 * rng.unit() - 1.0) * 1.7e308,
                (2.0 * rng.unit() - 1.0) * 1.7e308,
            )
        })
        .collect();
    assert!(
        wide_points.iter().map(|p| p.x).fold(0.0, f64::max)
            - wide_points.iter().map(|p| p.x).fold(0.0, f64::min)
            == f64::INFINITY
    );
    let params = Params::default();
    let narrow_result = summary(&reconstruct(&narrow, &params).unwrap());
    let narrow_scaled = summary(&reconstruct(&scaled(&narrow, 2f64.powi(600)), &params).unwrap());
    assert_eq!(narrow_result, narrow_scaled);
    let wide = reconstruct(&wide_points, &params).unwrap();
    let wide_halved = reconstruct(&scaled(&wide_points, 0.5), &params).unwrap();
    assert_eq!(summary(&wide), summary(&wide_halved));
    assert!(wide.smoothing().is_some() && !wide.edges().collect::<Vec<_>>().is_empty());
    // The smoothed positions the stages measured, in the caller's frame: within the input's box
    // and, up to rounding, twice those of the halved set (the passes moved its points alike; it
    // is smoothed relative to its corner, this one in place).
    for i in 0..n {
        let (p, q) = (wide.stage_point(i), wide_halved.stage_point(i));
        assert!(p.x.abs() <= 1.7e308 && p.y.abs() <= 1.7e308, "{i}: {p:?}");
        let off = (p.x - 2.0 * q.x).abs().max((p.y - 2.0 * q.y).abs());
        assert!(off <= 1e-12 * 1.7e308, "{i}: {p:?} against twice {q:?}");
    }
}

/// Wide sets (magnitudes spread beyond 2^200) are ordered for insertion on a logarithmic grid.
/// It read the coordinates' bit patterns as they are, which a power of two shifts up for the
/// positive ones and down for the negative ones: another order, and with it other ties between
/// equal lengths. It now starts from the set's smallest magnitude (normal coordinates here, whose
/// scaling is exact).
#[test]
fn wide_sets_reconstruct_the_same_times_a_power_of_two() {
    let mut rng = Rng::new(8);
    for (round, n) in [5, 8, 60, 400].into_iter().enumerate() {
        let points: Vec<Point> = (0..n)
            .map(|_| {
                let x = random_double(&mut rng, -900..900);
                Point::new(x, random_double(&mut rng, -900..900))
            })
            .collect();
        for params in [Params::default(), Params::default().with_smooth(false)] {
            // Such sets have points too close to measure beside their largest coordinate: the
            // same refusal, naming the same two points, at every scale.
            let result = reconstruct(&points, &params).map(|r| summary(&r));
            for factor in [8.0, 2f64.powi(-5)] {
                let again = reconstruct(&scaled(&points, factor), &params).map(|r| summary(&r));
                assert_eq!(result, again, "round {round}, {n} points, factor {factor}");
            }
        }
    }
}

/// The stages measure lengths down to 2^-450 times the largest coordinate (`docs/predicates.md`).
/// A circle of radius 1 beside a point at 1e230 came out as 14 open pieces, silently: its edges'
/// squares underflowed to zero in the stages' frame. Such a set is now refused, naming two points
/// too close to measure (the same two at every power-of-two scale); at 1e130 it is still
/// measured, and the circle comes out whole.
#[test]
fn points_too_close_to_measure_beside_the_largest_coordinate_are_refused_by_name() {
    let circle: Vec<Point> = (0..40)
        .map(|k| {
            let t = core::f64::consts::TAU * k as f64 / 40.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    let with = |points: &[Point], far: Point| {
        let mut points = points.to_vec();
        points.push(far);
        points
    };
    for far in [1e230, -1e300, 1e140] {
        let points = with(&circle, Point::new(far, 0.0));
        for params in [Params::default(), Params::paper()] {
            let err = reconstruct(&points, &params).map(|_| ()).unwrap_err();
            let condt::Error::TooCloseToMeasure {
                first,
                second,
                largest,
            } = err
            else {
                panic!("{far:e}: {err}");
            };
            // Two distinct circle points, nearer than 2^-450 times |far| (no underflow here),
            // and the far point that sets the scale.
            assert!(first < second && second < 40, "{far:e}: {first} {second}");
            assert_eq!(largest, 40, "{far:e}");
            let (p, q) = (points[first], points[second]);
            let length = (p.x - q.x).hypot(p.y - q.y);
            assert!(
                length > 0.0 && length < 2f64.powi(-450) * far.abs(),
                "{far:e}"
            );
            assert!(err
                .to_string()
                .contains(&format!("points {first} and {second} ")));
            assert!(err.to_string().contains("(point 40's)"), "{err}");
            let halved = reconstruct(&scaled(&points, 0.5), &params).map(|_| ());
            assert_eq!(halved, Err(err), "{far:e}");
        }
        triangulate(&points).unwrap().validate().unwrap();
    }
    for far in [1e130, 1e100] {
        let result = reconstruct(&with(&circle, Point::new(far, 0.0)), &Params::default()).unwrap();
        assert_eq!(result.curves().len(), 1, "{far:e}");
        assert!(result.curves()[0].is_closed());
        assert_eq!(result.edges().count(), 40);
        assert_eq!(result.unused(), &[40]);
    }
    // A circle of radius 1e-300 beside (1, 1): refused alike.
    let tiny: Vec<Point> = circle
        .iter()
        .map(|p| Point::new(p.x * 1e-300, p.y * 1e-300))
        .collect();
    assert!(matches!(
        reconstruct(&with(&tiny, Point::new(1.0, 1.0)), &Params::default()),
        Err(condt::Error::TooCloseToMeasure { .. })
    ));
}
