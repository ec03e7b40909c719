//! The default pipeline on conditions real inputs have and the evaluation suite does not cover
//! (issue 10, item 3): density that varies along a curve or from side to side of a polygon,
//! outliers in clumps, Gaussian as well as uniform noise, curves close to each other, and open
//! ends that point at each other. Every condition runs over seeds 1 to 5 (the seed moves the
//! noise and the outliers), so one lucky draw cannot pass a test.
//!
//! Where the default is exact the test says so; where it is not, the test asserts the weaker
//! property it does keep, and the comment says what fails and by how much. Conditions where the
//! default does something wrong (two parallel arcs 2 to 2.5 spacings apart joined at their ends)
//! have no test pinning the wrong output; the tests there are on the neighbouring cases that
//! work. Tests of outlier clumps turn the local outlier removal on (`--local-outliers`), which
//! the default leaves off.

mod common;

use common::{edges, run, truth};
use condt::Point;
use condt::{Params, Reconstruction};
use condt_eval::sample::{sample, Clumps, Sample, Sampling, Shape};
use std::collections::BTreeSet;
use std::f64::consts::PI;

const SEEDS: std::ops::RangeInclusive<u64> = 1..=5;

/// The true edges the result lacks and the edges it has that are not true.
fn diff(s: &Sample, r: &Reconstruction) -> (Vec<[usize; 2]>, Vec<[usize; 2]>) {
    let (ours, gt) = (edges(r), truth(s));
    (
        gt.difference(&ours).copied().collect(),
        ours.difference(&gt).copied().collect(),
    )
}

fn assert_exact(s: &Sample, params: Params, label: &str) -> Reconstruction {
    let r = run(&s.points, params);
    let (missing, extra) = diff(s, &r);
    assert!(
        missing.is_empty() && extra.is_empty(),
        "{label}: missing {missing:?}, extra {extra:?}"
    );
    r
}

/// `r` is one curve, closed or open as `closed` says.
fn assert_one_curve(r: &Reconstruction, closed: bool, label: &str) {
    assert_eq!(r.curves().len(), 1, "{label}");
    assert_eq!(r.curves()[0].is_closed(), closed, "{label}");
}

/// Shortest and longest ground-truth edge.
fn spacings(s: &Sample) -> (f64, f64) {
    s.edges
        .iter()
        .map(|&[a, b]| s.points[a].dist2(s.points[b]).sqrt())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        })
}

/// `shapes` sampled with `sampling`, then again with uniform noise of `jitter` times the
/// shortest true spacing of the clean sample (the same points before the noise).
fn jittered(shapes: &[Shape], sampling: Sampling, jitter: f64) -> Sample {
    let (shortest, _) = spacings(&sample(shapes, &sampling).unwrap());
    sample(
        shapes,
        &Sampling {
            noise: jitter * shortest,
            ..sampling
        },
    )
    .unwrap()
}

fn origin() -> Point {
    Point::new(0.0, 0.0)
}

/// Number of points with exactly one edge.
fn ends(r: &Reconstruction) -> usize {
    (0..r.num_points()).filter(|&i| r.degree(i) == 1).count()
}

// 1. Density that varies 4x along one curve.

/// Closed curves whose spacing swings smoothly from a quarter of the bound to the bound: exact
/// with the default and with the paper on every seed (measured: 45 of 45 inputs each, also
/// without jitter).
#[test]
fn closed_curves_with_density_varying_4x_are_exact() {
    let shapes = [
        Shape::Ellipse {
            center: Point::new(1.0, 2.0),
            radii: (2.0, 1.0),
            rotation: 0.4,
        },
        Shape::Ellipse {
            center: Point::new(1.0, 2.0),
            radii: (3.0, 1.0),
            rotation: 1.1,
        },
        Shape::circle(origin(), 1.0),
    ];
    for shape in &shapes {
        for eps in [0.1, 0.3] {
            for seed in SEEDS {
                let sampling = Sampling {
                    density_variation: 4.0,
                    seed,
                    ..Sampling::new(eps)
                };
                let s = jittered(std::slice::from_ref(shape), sampling, 0.03);
                let (lo, hi) = spacings(&s);
                assert!(hi / lo > 3.0, "the density does vary: {}", hi / lo);
                let label = format!("{shape:?} eps {eps} seed {seed}");
                let r = assert_exact(&s, Params::default(), &label);
                assert_one_curve(&r, true, &label);
            }
        }
    }
}

/// An open arc, dense at both ends and four times sparser in the middle: one open curve, exact.
#[test]
fn open_arc_with_density_varying_4x_is_exact() {
    for sweep in [1.2 * PI, 1.7 * PI] {
        let arc = Shape::Arc {
            center: origin(),
            radius: 2.0,
            start: 0.3,
            sweep,
        };
        for eps in [0.1, 0.3] {
            for seed in SEEDS {
                let sampling = Sampling {
                    density_variation: 4.0,
                    seed,
                    ..Sampling::new(eps)
                };
                let s = jittered(std::slice::from_ref(&arc), sampling, 0.03);
                let label = format!("arc sweep {sweep} eps {eps} seed {seed}");
                let r = assert_exact(&s, Params::default(), &label);
                assert_one_curve(&r, false, &label);
                assert_eq!(ends(&r), 2, "{label}");
            }
        }
    }
}

// 2. Polygons whose sides are sampled at different spacings, with small jitter.

fn polygons() -> Vec<(&'static str, Vec<Point>)> {
    let hexagon = (0..6)
        .map(|k| {
            let t = k as f64 * PI / 3.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    vec![
        (
            "square",
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
            ],
        ),
        (
            "3:1 rectangle",
            vec![
                Point::new(0.0, 0.0),
                Point::new(3.0, 0.0),
                Point::new(3.0, 1.0),
                Point::new(0.0, 1.0),
            ],
        ),
        ("hexagon", hexagon),
        (
            "L",
            vec![
                Point::new(0.0, 0.0),
                Point::new(2.0, 0.0),
                Point::new(2.0, 1.0),
                Point::new(1.0, 1.0),
                Point::new(1.0, 2.0),
                Point::new(0.0, 2.0),
            ],
        ),
    ]
}

/// Corners of 90° and more (square, rectangle, hexagon, the L with its reflex corner) with sides
/// sampled up to 4x apart (spacing 2.5x from one side to the next at most) and jitter of 3 % of
/// the smallest spacing: the default is exact on every seed. The paper is not: at variation 4
/// and eps 0.1 it is exact on 2 of 5 seeds on the square and 1 of 5 on the rectangle, with one
/// or two edges cut at a corner where a dense side meets a sparse one.
#[test]
fn polygons_with_sides_at_different_spacings_are_exact() {
    for (name, corners) in polygons() {
        for eps in [0.1, 0.2] {
            for variation in [2.0, 4.0] {
                for seed in SEEDS {
                    let sampling = Sampling {
                        density_variation: variation,
                        seed,
                        ..Sampling::new(eps)
                    };
                    let s = jittered(&[Shape::Polygon(corners.clone())], sampling, 0.03);
                    let label = format!("{name} eps {eps} variation {variation} seed {seed}");
                    let r = assert_exact(&s, Params::default(), &label);
                    assert_one_curve(&r, true, &label);
                }
            }
        }
    }
}

/// A triangle with corners of 65°, 49° and 66°. With spacings up to 2x apart it is exact. With
/// 3x or 4x, the first sample of a sparse side lies nearer the last-but-one sample of the dense
/// side than the corner does, and the edge between the corner and it is nobody's choice: the
/// default loses the edge at one or both corners where a dense side meets a sparse one (exact on
/// 3 of 10 inputs at variation 3, none at 4; the paper on none, with two wrong edges each). What
/// the default keeps: it never adds a wrong edge, and every edge it loses has a corner at one
/// end.
#[test]
fn acute_triangle_with_sides_at_different_spacings_loses_edges_only_at_corners() {
    let corners = vec![
        Point::new(0.0, 0.0),
        Point::new(2.0, 0.0),
        Point::new(0.7, 1.5),
    ];
    for eps in [0.1, 0.2] {
        for seed in SEEDS {
            let sampling = Sampling {
                density_variation: 2.0,
                seed,
                ..Sampling::new(eps)
            };
            let s = jittered(&[Shape::Polygon(corners.clone())], sampling, 0.03);
            assert_exact(
                &s,
                Params::default(),
                &format!("triangle eps {eps} variation 2 seed {seed}"),
            );
        }
    }
    let mut lost = 0;
    for eps in [0.1, 0.2] {
        for variation in [3.0, 4.0] {
            for seed in SEEDS {
                let sampling = Sampling {
                    density_variation: variation,
                    seed,
                    ..Sampling::new(eps)
                };
                let clean = sample(&[Shape::Polygon(corners.clone())], &sampling).unwrap();
                let s = jittered(&[Shape::Polygon(corners.clone())], sampling, 0.03);
                let label = format!("triangle eps {eps} variation {variation} seed {seed}");
                let r = run(&s.points, Params::default());
                let (missing, extra) = diff(&s, &r);
                assert!(extra.is_empty(), "{label}: wrong edges {extra:?}");
                let is_corner = |i: usize| corners.contains(&clean.points[i]);
                for e in &missing {
                    assert!(
                        is_corner(e[0]) || is_corner(e[1]),
                        "{label}: lost {e:?} away from the corners"
                    );
                }
                lost += missing.len();
            }
        }
    }
    // Not a wish that it fails: the count shows these inputs exercise the weakness.
    assert!(lost > 0);
}

/// The outline of the right triangle with legs `a` and `b` (integers), each side split into
/// pieces of length 1 (the hypotenuse into the whole number of pieces nearest), as a CAD tool
/// resamples a polygon: long runs of exactly collinear, exactly evenly spaced samples.
fn resampled_right_triangle(a: u32, b: u32) -> Vec<Point> {
    let corners = [
        (0.0, 0.0),
        (f64::from(a), 0.0),
        (f64::from(a), f64::from(b)),
    ];
    let mut points = Vec::new();
    for k in 0..3 {
        let (p, q) = (corners[k], corners[(k + 1) % 3]);
        let pieces = (q.0 - p.0).hypot(q.1 - p.1).round() as u32;
        for j in 0..pieces {
            let t = f64::from(j) / f64::from(pieces);
            points.push(Point::new(p.0 + (q.0 - p.0) * t, p.1 + (q.1 - p.1) * t));
        }
    }
    points
}

/// Resampled polygons with sharp corners (a CAD user's review: 24 of 528 such triangles lost
/// their sharpest corner, the tips step taking one of the corner's three samples and leaving
/// the other two without edges, which the spikes step would have put back whole). Every
/// right triangle with integer legs up to 24, the short one at least 3 and the sharp corner at
/// least 15 degrees, is one closed curve through its samples in their order. Sharper corners
/// are out of scope: below 15 degrees the first four samples of each side lie within one
/// spacing of the other side.
#[test]
fn resampled_triangles_keep_their_sharp_corners() {
    for a in 6..=24u32 {
        for b in 3..=a {
            if f64::from(b).atan2(f64::from(a)) < 15f64.to_radians() {
                continue;
            }
            let points = resampled_right_triangle(a, b);
            let n = points.len();
            let truth: BTreeSet<[usize; 2]> = (0..n)
                .map(|i| {
                    let j = (i + 1) % n;
                    [i.min(j), i.max(j)]
                })
                .collect();
            let r = run(&points, Params::default());
            assert_eq!(edges(&r), truth, "right triangle {a} x {b}");
        }
    }
}

// 3. Outliers in clumps, kept clear of the curves.

/// Two circles sampled at eps 0.1 (spacing 0.3 and 0.2) with clumps of outliers, each clump at
/// least `clearance` spacings of the larger circle from every curve sample.
fn clumped(fraction: f64, (min, max): (usize, usize), radius: f64, seed: u64) -> Sample {
    let shapes = [
        Shape::circle(origin(), 3.0),
        Shape::circle(Point::new(8.0, 1.0), 2.0),
    ];
    sample(
        &shapes,
        &Sampling {
            outlier_fraction: fraction,
            outlier_clearance: 2.0 * 0.3,
            outlier_clumps: Some(Clumps { min, max, radius }),
            seed,
            ..Sampling::new(0.1)
        },
    )
    .unwrap()
}

/// The default pipeline with the local outlier removal on.
fn with_local_outliers() -> Params {
    Params::default().with_local_outliers(true)
}

/// With the local outlier removal on (`--local-outliers`: off by default), clumps of three or
/// four outliers (radius a third of, or equal to, the spacing; 5 and 10 % outliers) get no
/// edge: exact on every seed. The paper keeps 2 to 12 outlier
/// edges on every one of these inputs. (At 20 % outliers with clumps as wide as the spacing,
/// two clumps side by side on seed 5 make a component of more than four points that keeps
/// five edges.)
#[test]
fn clumps_of_three_or_four_outliers_get_no_edge() {
    for fraction in [0.05, 0.1] {
        for radius in [0.1, 0.3] {
            for seed in SEEDS {
                let s = clumped(fraction, (3, 4), radius, seed);
                assert!(s.outliers.len() >= 6);
                let label =
                    format!("{fraction} outliers in clumps of 3-4, r {radius}, seed {seed}");
                let r = assert_exact(&s, with_local_outliers(), &label);
                assert_eq!(r.unused(), &s.outliers[..], "{label}");
            }
        }
    }
}

/// Clumps of three to seven, with the local outlier removal on. A clump of five or more points
/// is a small curve by every local measure (`docs/condt.md`, "Still wrong"), and the stage
/// keeps its edges on some seeds
/// (exact on 4 of 5 seeds at 5 % and 10 %, 3 of 5 at 20 %; the paper on none). What it keeps on every
/// seed: both circles exact, no edge between an outlier and a curve sample, and outlier edges
/// only within groups of at least five outliers.
#[test]
fn clumps_of_up_to_seven_outliers_never_touch_the_curves() {
    for fraction in [0.05, 0.1, 0.2] {
        for seed in SEEDS {
            let s = clumped(fraction, (3, 7), 0.1, seed);
            let label = format!("{fraction} outliers in clumps of 3-7, seed {seed}");
            let r = run(&s.points, with_local_outliers());
            let (missing, extra) = diff(&s, &r);
            assert!(missing.is_empty(), "{label}: lost curve edges {missing:?}");
            let outlier: BTreeSet<usize> = s.outliers.iter().copied().collect();
            for e in &extra {
                assert!(
                    outlier.contains(&e[0]) && outlier.contains(&e[1]),
                    "{label}: {e:?} joins an outlier to a curve"
                );
            }
            for curve in r.curves() {
                let points: Vec<usize> = curve.points().collect();
                if points.iter().any(|i| outlier.contains(i)) {
                    assert!(
                        points.iter().all(|i| outlier.contains(i)),
                        "{label}: {points:?}"
                    );
                    assert!(points.len() >= 5, "{label}: a group of {}", points.len());
                }
            }
        }
    }
}

// 4. Gaussian as well as uniform noise.

/// Noise of 2 and 5 % of the spacing, uniform or Gaussian (standard deviation), on closed, open
/// and two-component inputs: the default and the paper are exact on every seed. (At 10 %
/// Gaussian noise one seed of the two circles loses an edge with both.)
#[test]
fn small_uniform_and_gaussian_noise_is_exact() {
    let cases: [(&str, Vec<Shape>, f64); 4] = [
        ("circle", vec![Shape::circle(origin(), 1.0)], 0.1),
        (
            "ellipse",
            vec![Shape::Ellipse {
                center: origin(),
                radii: (2.0, 1.0),
                rotation: 0.3,
            }],
            0.05,
        ),
        (
            "arc",
            vec![Shape::Arc {
                center: origin(),
                radius: 2.0,
                start: 0.3,
                sweep: 1.2 * PI,
            }],
            0.2,
        ),
        (
            "two circles",
            vec![
                Shape::circle(origin(), 3.0),
                Shape::circle(Point::new(8.0, 1.0), 2.0),
            ],
            0.3,
        ),
    ];
    for (name, shapes, spacing) in &cases {
        for fraction in [0.02, 0.05] {
            for gaussian_noise in [false, true] {
                for seed in SEEDS {
                    let s = sample(
                        shapes,
                        &Sampling {
                            noise: fraction * spacing,
                            gaussian_noise,
                            seed,
                            ..Sampling::new(0.1)
                        },
                    )
                    .unwrap();
                    let label = format!("{name} noise {fraction} gaussian {gaussian_noise} {seed}");
                    assert_exact(&s, Params::default(), &label);
                    assert_exact(&s, Params::paper(), &format!("paper, {label}"));
                }
            }
        }
    }
}

// 5. Two curves whose gap is 2 to 3 times their spacing.

/// Concentric circles of radius 1 and 1 + gap, sampled at `eps` (spacing `eps` on the inner one,
/// a little more on the outer), with jitter of 2 % of the spacing.
fn concentric(eps: f64, gap_in_spacings: f64, seed: u64) -> Sample {
    let gap = gap_in_spacings * eps;
    sample(
        &[
            Shape::circle(origin(), 1.0),
            Shape::circle(origin(), 1.0 + gap),
        ],
        &Sampling {
            noise: 0.02 * eps,
            seed,
            ..Sampling::new(eps)
        },
    )
    .unwrap()
}

/// A gap of 2.5 or 3 inner spacings (2.2 to 2.8 times the outer circle's spacing): exact, two
/// closed curves; the next test goes down to 2 spacings.
#[test]
fn concentric_circles_two_and_a_half_spacings_apart_are_exact() {
    for eps in [0.03, 0.05] {
        for gap in [2.5, 3.0] {
            for seed in SEEDS {
                let s = concentric(eps, gap, seed);
                let label = format!("concentric eps {eps} gap {gap} seed {seed}");
                let r = assert_exact(&s, Params::default(), &label);
                assert_eq!(r.curves().len(), 2, "{label}");
                assert!(r.curves().iter().all(|c| c.is_closed()), "{label}");
            }
        }
    }
}

/// At two inner spacings (1.8 to 1.9 times the outer spacing) ConDT itself is exact: every
/// sample's two nearest neighbours are on its own circle. The default's local outlier removal
/// used to delete a whole circle here (no sample of it is twice its edge length from the other
/// circle); it now keeps any cycle of seven or more points of which three quarters pass smoothly
/// and evenly, so both pipelines are exact.
#[test]
fn both_pipelines_keep_concentric_circles_two_spacings_apart() {
    for eps in [0.03, 0.05] {
        for seed in SEEDS {
            let s = concentric(eps, 2.0, seed);
            for (name, params) in [("paper", Params::paper()), ("default", Params::default())] {
                let label = format!("{name}, concentric eps {eps} gap 2 seed {seed}");
                let r = assert_exact(&s, params, &label);
                assert_eq!(r.curves().len(), 2, "{label}");
            }
        }
    }
}

/// Two parallel arcs (radius 2 and 2 + gap, the same angles). Their ends sit side by side, and
/// an end whose next sample along its own arc is `d` away keeps a second edge up to `2.75 d`
/// long (Algorithm 1's `u`): a gap under 2.75 times the outer arc's spacing joins the arcs at
/// their ends (default: one or two wrong edges on every seed at 2 and 2.5 inner spacings; the
/// paper none to two). With the gap at 3 times the outer spacing, both are exact.
#[test]
fn parallel_arcs_three_spacings_apart_stay_two_open_curves() {
    for eps in [0.03, 0.05] {
        for seed in SEEDS {
            // The outer arc's spacing is eps times its radius; solve gap = 3 eps (2 + gap).
            let gap = 3.0 * eps * 2.0 / (1.0 - 3.0 * eps);
            let arcs = [
                Shape::Arc {
                    center: origin(),
                    radius: 2.0,
                    start: 0.2,
                    sweep: 1.5,
                },
                Shape::Arc {
                    center: origin(),
                    radius: 2.0 + gap,
                    start: 0.2,
                    sweep: 1.5,
                },
            ];
            let s = sample(
                &arcs,
                &Sampling {
                    noise: 0.02 * eps * 2.0,
                    seed,
                    ..Sampling::new(eps)
                },
            )
            .unwrap();
            let (_, hi) = spacings(&s);
            assert!(gap >= 2.8 * hi, "gap {gap} against spacing {hi}");
            let label = format!("parallel arcs eps {eps} seed {seed}");
            for params in [Params::default(), Params::paper()] {
                let r = assert_exact(&s, params, &label);
                assert_eq!(r.curves().len(), 2, "{label}");
                assert_eq!(ends(&r), 4, "{label}");
            }
        }
    }
}

// 6. Open ends that point at each other.

/// Two arcs on one unit circle, each a little less than half of it, with a gap of
/// `gap_in_spacings · eps` (as an angle, so about that many spacings as a chord) between the
/// end of one and the start of the other at both sides.
fn facing_arcs(eps: f64, gap_in_spacings: f64, seed: u64) -> Sample {
    let gap = gap_in_spacings * eps;
    sample(
        &[
            Shape::Arc {
                center: origin(),
                radius: 1.0,
                start: gap / 2.0,
                sweep: PI - gap,
            },
            Shape::Arc {
                center: origin(),
                radius: 1.0,
                start: PI + gap / 2.0,
                sweep: PI - gap,
            },
        ],
        &Sampling {
            noise: 0.02 * eps,
            seed,
            ..Sampling::new(eps)
        },
    )
    .unwrap()
}

/// Ends 3 to 4 spacings apart stay apart: two open curves, exact, with the default and the
/// paper. Below 2.75 spacings both join them (2 and 2.5 spacings: the two gaps closed on every
/// seed by the default; the paper closes one or both): an end keeps a second edge up to 2.75
/// times its first (Algorithm 1's `u`), and the default's gap closing uses the same ratio.
#[test]
fn ends_three_to_four_spacings_apart_stay_open() {
    for eps in [0.05, 0.1] {
        for gap in [3.0, 3.5, 4.0] {
            for seed in SEEDS {
                let s = facing_arcs(eps, gap, seed);
                let label = format!("facing arcs eps {eps} gap {gap} seed {seed}");
                for params in [Params::default(), Params::paper()] {
                    let r = assert_exact(&s, params, &label);
                    assert_eq!(r.curves().len(), 2, "{label}");
                    assert!(r.curves().iter().all(|c| !c.is_closed()), "{label}");
                    assert_eq!(ends(&r), 4, "{label}");
                }
            }
        }
    }
}

/// Ends less than one spacing apart: the right answer is one closed curve through both gaps.
/// The points are then a sample of the whole circle at least as fine as the arcs' own (every
/// gap is shorter than the spacing), so no method can tell them from a closed circle sampled a
/// little unevenly; joining the ends is the reconstruction the sampling supports, and reporting
/// four loose ends would invent a boundary the data does not show. Both pipelines give the true
/// edges plus the two across the gaps, on every seed.
#[test]
fn ends_under_one_spacing_apart_close_into_one_circle() {
    for eps in [0.05, 0.1] {
        for gap in [0.5, 0.8] {
            for seed in SEEDS {
                let s = facing_arcs(eps, gap, seed);
                let label = format!("facing arcs eps {eps} gap {gap} seed {seed}");
                // The two gaps: the last sample of each arc to the first of the other.
                let first_len = s.points.len() / 2;
                let last = s.points.len() - 1;
                let mut expected = truth(&s);
                expected.insert([first_len - 1, first_len]);
                expected.insert([0, last]);
                let (_, spacing) = spacings(&s);
                assert!(s.points[first_len - 1].dist2(s.points[first_len]).sqrt() < spacing);
                for params in [Params::default(), Params::paper()] {
                    let r = run(&s.points, params);
                    assert_eq!(edges(&r), expected, "{label}");
                    assert_one_curve(&r, true, &label);
                }
            }
        }
    }
}
