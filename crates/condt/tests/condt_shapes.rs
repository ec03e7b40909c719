//! ConDT on curves the crate samples itself: exact reconstruction, outliers, invariances, and
//! parallel == sequential on sets past the parallel threshold
//! (`parallel_equals_sequential_above_the_parallel_threshold`; below it both take the same code,
//! so `run` reconstructs once). Every test names its shape.

mod common;

use common::{edges, final_edges, run, run_both, stage_edges, truth, Rng, PARALLEL_FROM};
use condt::Point;
use condt::{reconstruct, Params, Reconstruction, Repair, Stage, Uniformity};
use condt_eval::sample::{sample, Sample, Sampling, Shape};
use std::collections::BTreeSet;
use std::f64::consts::PI;

fn assert_exact(shapes: &[Shape], epsilon: f64, params: Params, label: &str) -> Reconstruction {
    let s = sample(shapes, &Sampling::new(epsilon)).unwrap();
    let r = run(&s.points, params);
    let (ours, gt) = (edges(&r), truth(&s));
    let missing: Vec<_> = gt.difference(&ours).collect();
    let extra: Vec<_> = ours.difference(&gt).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "{label}: missing {missing:?}, extra {extra:?}"
    );
    r
}

fn origin() -> Point {
    Point::new(0.0, 0.0)
}

#[test]
fn circle_is_one_closed_curve() {
    for eps in [0.1, 0.3, 0.5] {
        let r = assert_exact(
            &[Shape::circle(origin(), 1.0)],
            eps,
            Params::default(),
            "circle",
        );
        assert_eq!(r.curves().len(), 1);
        assert!(r.curves()[0].is_closed());
        assert!(r.unused().is_empty());
    }
}

#[test]
fn ellipse_turned_and_elongated() {
    let shape = Shape::Ellipse {
        center: Point::new(3.0, -2.0),
        radii: (4.0, 1.5),
        rotation: 0.7,
    };
    assert_exact(&[shape], 0.3, Params::default(), "ellipse");
}

#[test]
fn three_separate_closed_components() {
    let shapes = [
        Shape::circle(origin(), 1.0),
        Shape::circle(Point::new(5.0, 0.0), 1.5),
        Shape::Ellipse {
            center: Point::new(1.0, 6.0),
            radii: (2.0, 1.0),
            rotation: 0.3,
        },
    ];
    let r = assert_exact(&shapes, 0.2, Params::default(), "three components");
    assert_eq!(r.curves().len(), 3);
    assert!(r.curves().iter().all(|c| c.is_closed()));
}

#[test]
fn dense_open_arc_is_one_open_curve() {
    let arc = Shape::Arc {
        center: origin(),
        radius: 2.0,
        start: 0.3,
        sweep: 1.2 * PI,
    };
    let r = assert_exact(&[arc], 0.05, Params::default(), "open arc");
    assert_eq!(r.curves().len(), 1);
    assert!(!r.curves()[0].is_closed());
    assert_eq!(
        (0..r.num_points()).filter(|&i| r.degree(i) == 1).count(),
        2,
        "two ends"
    );
}

#[test]
fn open_spiral() {
    let spiral = Shape::Spiral {
        center: origin(),
        inner: 1.0,
        gap: 1.0,
        turns: 2.5,
    };
    assert_exact(&[spiral], 0.1, Params::default(), "spiral");
}

#[test]
fn square_with_sharp_corners() {
    let square = Shape::Polygon(vec![
        origin(),
        Point::new(4.0, 0.0),
        Point::new(4.0, 4.0),
        Point::new(0.0, 4.0),
    ]);
    let r = assert_exact(&[square], 0.1, Params::default(), "square");
    assert_eq!(r.curves().len(), 1);
}

#[test]
fn figure_eight_keeps_its_crossing_with_repair_off() {
    let eight = Shape::FigureEight {
        center: origin(),
        size: 2.0,
    };
    let params = Params::default().with_repair(Repair::Off);
    let r = assert_exact(&[eight], 0.1, params, "figure eight");
    assert_eq!(r.degree(0), 4, "the crossing sample has degree four");
}

#[test]
fn figure_eight_gets_its_crossing_back_when_gaps_are_closed() {
    // The paper's repair keeps two of the crossing's four edges; closing gaps restores the other
    // two, the arms that point straight through the crossing.
    let eight = Shape::FigureEight {
        center: origin(),
        size: 2.0,
    };
    let s = sample(&[eight], &Sampling::new(0.1)).unwrap();
    let repaired = run(&s.points, Params::paper());
    assert_eq!(repaired.degree(0), 2, "the repair cut the crossing");
    let params = Params::paper().with_close_gaps(true);
    let r = assert_exact(
        &[Shape::FigureEight {
            center: origin(),
            size: 2.0,
        }],
        0.1,
        params,
        "figure eight, gaps closed",
    );
    assert_eq!(r.degree(0), 4);
    assert!(r.stage(Stage::Gaps).unwrap().applied);
}

#[test]
fn a_gap_in_a_noisy_circle_is_closed() {
    // Noise of a third of the spacing: one pair of consecutive samples is nobody's choice and the
    // circle falls open there; the two ends face each other across one spacing.
    let s = sample(
        &[Shape::circle(origin(), 1.0)],
        &Sampling {
            noise: 0.03,
            seed: 14,
            ..Sampling::new(0.1)
        },
    )
    .unwrap();
    let gt = truth(&s);
    let plain = run(&s.points, Params::paper());
    let found = edges(&plain);
    assert_eq!(
        gt.difference(&found).count(),
        1,
        "the pipeline leaves one gap"
    );
    assert!(found.is_subset(&gt));
    let closed = run(&s.points, Params::paper().with_close_gaps(true));
    assert_eq!(edges(&closed), gt);
    assert_eq!(closed.curves().len(), 1);
    assert!(closed.curves()[0].is_closed());
}

#[test]
fn closing_gaps_leaves_open_arcs_and_clean_shapes_alone() {
    let params = Params::default().with_close_gaps(true);
    let arc = Shape::Arc {
        center: origin(),
        radius: 1.0,
        start: 0.0,
        sweep: 1.5 * PI,
    };
    for eps in [0.1, 0.3, 0.5] {
        let r = assert_exact(
            std::slice::from_ref(&arc),
            eps,
            params,
            "open arc, gaps closed",
        );
        assert!(!r.stage(Stage::Gaps).unwrap().applied, "eps {eps}");
        assert_exact(
            &[Shape::circle(origin(), 1.0)],
            eps,
            params,
            "circle, gaps closed",
        );
    }
}

#[test]
fn adaptive_uniformity_on_a_circle_and_an_arc() {
    let params = Params::default().with_uniformity(Uniformity::Adaptive);
    assert_exact(
        &[Shape::circle(origin(), 1.0)],
        0.2,
        params,
        "circle, adaptive",
    );
}

/// Two circles sampled every 0.3 to 0.45, with uniform outliers at least 1.0 (over twice the
/// spacing) from every other point. Nearer the curve than the spacing, an outlier is
/// indistinguishable from a noisy sample (the paper's Fig. 4b shows the same); two outliers near
/// each other are mutual nearest neighbours, a two-point curve by ConDT's own definition. Neither
/// can be removed by a rule on edge lengths; `docs/condt.md` measures plain uniform outliers.
/// Reconstructed with the paper's pipeline, whose global rule these tests are about.
fn with_outliers(fraction: f64, seed: u64) -> (Sample, Reconstruction) {
    let shapes = [
        Shape::circle(origin(), 3.0),
        Shape::circle(Point::new(8.0, 1.0), 2.0),
    ];
    let sampling = Sampling {
        outlier_fraction: fraction,
        outlier_clearance: 1.0,
        seed,
        ..Sampling::new(0.15)
    };
    let s = sample(&shapes, &sampling).unwrap();
    let r = run(&s.points, Params::paper());
    (s, r)
}

#[test]
fn five_percent_outliers_get_no_edge() {
    for seed in 1..=5 {
        let (s, r) = with_outliers(0.05, seed);
        assert!(!s.outliers.is_empty());
        for &o in &s.outliers {
            assert_eq!(
                r.degree(o),
                0,
                "two circles, 5 % outliers, seed {seed}: outlier {o} has an edge"
            );
        }
    }
}

#[test]
fn ten_percent_outliers_get_no_edge() {
    for seed in 1..=5 {
        let (s, r) = with_outliers(0.10, seed);
        for &o in &s.outliers {
            assert_eq!(
                r.degree(o),
                0,
                "two circles, 10 % outliers, seed {seed}: outlier {o} has an edge"
            );
        }
        assert_eq!(s.outliers.len(), 8, "all outliers placed");
        assert!(r.stage(Stage::Outliers).unwrap().applied);
        assert_eq!(r.unused().len(), s.outliers.len());
    }
}

fn test_shapes() -> Vec<(&'static str, Sample)> {
    vec![
        (
            "circle",
            sample(&[Shape::circle(origin(), 1.0)], &Sampling::new(0.2)).unwrap(),
        ),
        (
            "spiral",
            sample(
                &[Shape::Spiral {
                    center: origin(),
                    inner: 1.0,
                    gap: 1.0,
                    turns: 2.0,
                }],
                &Sampling::new(0.1),
            )
            .unwrap(),
        ),
        ("two circles with outliers", with_outliers(0.1, 3).0),
        (
            "figure eight",
            sample(
                &[Shape::FigureEight {
                    center: origin(),
                    size: 2.0,
                }],
                &Sampling::new(0.1),
            )
            .unwrap(),
        ),
    ]
}

#[test]
fn rotating_by_90_degrees_keeps_the_edges() {
    for (label, s) in test_shapes() {
        let turned: Vec<Point> = s.points.iter().map(|p| Point::new(-p.y, p.x)).collect();
        assert_eq!(
            edges(&run(&s.points, Params::default())),
            edges(&run(&turned, Params::default())),
            "{label}"
        );
    }
}

#[test]
fn translating_by_a_power_of_two_keeps_the_edges() {
    for (label, s) in test_shapes() {
        // Coordinates below 2^5 in magnitude, moved by 2^6: every sum is exact only if the
        // low bits survive, so round the sample to a dyadic grid first.
        let snapped: Vec<Point> = s
            .points
            .iter()
            .map(|p| {
                Point::new(
                    (p.x * 1024.0).round() / 1024.0,
                    (p.y * 1024.0).round() / 1024.0,
                )
            })
            .collect();
        let moved: Vec<Point> = snapped
            .iter()
            .map(|p| Point::new(p.x + 64.0, p.y - 128.0))
            .collect();
        assert_eq!(
            edges(&run(&snapped, Params::default())),
            edges(&run(&moved, Params::default())),
            "{label}"
        );
    }
}

#[test]
fn permuting_the_input_permutes_the_edges() {
    for (label, s) in test_shapes() {
        let mut order: Vec<usize> = (0..s.points.len()).collect();
        Rng::new(17).shuffle(&mut order);
        let shuffled: Vec<Point> = order.iter().map(|&i| s.points[i]).collect();
        let back: BTreeSet<[usize; 2]> = edges(&run(&shuffled, Params::default()))
            .into_iter()
            .map(|[a, b]| {
                let (a, b) = (order[a], order[b]);
                [a.min(b), a.max(b)]
            })
            .collect();
        assert_eq!(back, edges(&run(&s.points, Params::default())), "{label}");
    }
}

#[test]
fn duplicates_map_back_to_their_vertex() {
    let mut s = sample(&[Shape::circle(origin(), 1.0)], &Sampling::new(0.3)).unwrap();
    let copy = s.points[3];
    s.points.push(copy);
    let r = run(&s.points, Params::default());
    let last = s.points.len() - 1;
    let tri = r.triangulation();
    assert_eq!(tri.vertex(last), tri.vertex(3));
    assert_eq!(
        tri.input_of(tri.vertex(last)),
        3,
        "reported under the smaller position"
    );
    assert_eq!(r.degree(last), r.degree(3));
    assert!(
        !r.unused().contains(&last),
        "a duplicate of a used point is not an outlier"
    );
    // The edges and curves are those of the set without the copy, under the first position.
    let without = run(&s.points[..last], Params::default());
    assert_eq!(final_edges(&r), final_edges(&without));
    assert_eq!(r.curves(), without.curves());
}

#[test]
fn tiny_inputs_do_not_panic() {
    for n in 0..4 {
        let pts: Vec<Point> = (0..n)
            .map(|i| Point::new(i as f64, (i * i) as f64))
            .collect();
        let r = run(&pts, Params::default());
        assert_eq!(r.num_points(), n);
    }
    let line: Vec<Point> = (0..10).map(|i| Point::new(i as f64, 0.0)).collect();
    let r = run(&line, Params::default());
    assert_eq!(r.edges().len(), 9, "a dense line is one open curve");
}

#[cfg(feature = "parallel")]
#[test]
fn parallel_equals_sequential_above_the_parallel_threshold() {
    // Four circles, over 65,536 points in all: the size from which the rayon pass runs.
    let circles: Vec<Shape> = (0..4)
        .map(|k| Shape::circle(Point::new(3.0 * k as f64, 0.0), 1.0))
        .collect();
    let s = sample(&circles, &Sampling::new(3e-4)).unwrap();
    // `run_both` asserts the size too: past it, the stages, the triangulation (cut in two, the
    // halves on two threads) and the curves take their parallel paths.
    assert!(s.points.len() >= PARALLEL_FROM, "{}", s.points.len());
    // `run_both` compares every stage of the two passes.
    let r = run_both(&s.points, Params::default());
    assert_eq!(r.curves().iter().filter(|c| c.is_closed()).count(), 4);
    assert_eq!(edges(&r), truth(&s));
    // Noise and outliers give branch points and unused points; both uniformity tests; the
    // sweep cut into as many triangle ranges as there are workers (two to four).
    let noisy = sample(
        &circles,
        &Sampling {
            noise: 1e-4,
            outlier_fraction: 0.02,
            ..Sampling::new(3e-4)
        },
    )
    .unwrap();
    assert!(
        noisy.points.len() >= PARALLEL_FROM,
        "{}",
        noisy.points.len()
    );
    let mut branch_points = 0;
    for uniformity in [Uniformity::Fixed(2.75), Uniformity::Adaptive] {
        for workers in 2..=4 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(workers)
                .build()
                .unwrap();
            // The paper's pipeline leaves branch points, which the parallel passes must see.
            let params = Params::paper().with_uniformity(uniformity);
            let r = pool.install(|| run_both(&noisy.points, params));
            branch_points += (0..r.num_points()).filter(|&i| r.degree(i) > 2).count();
            assert!(!r.unused().is_empty());
        }
    }
    assert!(branch_points > 0);
    // The default pipeline: gap closing, junctions and crossings search for their candidates in
    // ranges on rayon's threads; `run_both` compares every stage of the two, and each of those
    // stages changes the graph of one of these sets, so their parallel searches found work.
    let mut applied = Vec::new();
    for points in [noisy.points, junctions_and_crossings()] {
        let r = run_both(&points, Params::default());
        applied.extend(r.stages().filter(|s| s.applied).map(|s| s.stage));
    }
    for stage in [
        Stage::LocalOutliers,
        Stage::Gaps,
        Stage::Junctions,
        Stage::Crossings,
    ] {
        assert!(applied.contains(&stage), "{stage}");
    }
}

/// Over 65,536 evenly spaced points: in each cell a T (the stem's end one spacing below the bar's
/// middle) and an X (two strokes crossing at a shared sample at 30 degrees), jittered slightly.
fn junctions_and_crossings() -> Vec<Point> {
    let mut rng = Rng::new(7);
    let mut points = Vec::new();
    for cell in 0..1_700 {
        let (x0, y0) = (f64::from(cell % 50) * 40.0, f64::from(cell / 50) * 40.0);
        let mut add = |x: f64, y: f64| {
            let (dx, dy) = (rng.unit() - 0.5, rng.unit() - 0.5);
            points.push(Point::new(x0 + x + 0.02 * dx, y0 + y + 0.02 * dy));
        };
        for k in -8..=8 {
            add(f64::from(k), 0.0);
        }
        for k in 1..=8 {
            add(0.0, -f64::from(k));
        }
        let (along, across) = (15f64.to_radians().cos(), 15f64.to_radians().sin());
        for k in -6..=6 {
            let k = f64::from(k);
            add(20.0 + k * along, 20.0 + k * across);
            if k != 0.0 {
                add(20.0 + k * along, 20.0 - k * across);
            }
        }
    }
    points
}

/// Two noisy circles with 10 % outliers kept clear of them: the repair changes the proximity
/// graph and the outlier rule fires, in either stage order.
fn noisy_circles_with_outliers() -> Sample {
    let shapes = [
        Shape::circle(origin(), 3.0),
        Shape::circle(Point::new(8.0, 1.0), 2.0),
    ];
    let sampling = Sampling {
        outlier_fraction: 0.1,
        outlier_clearance: 1.0,
        noise: 0.02,
        seed: 1,
        ..Sampling::new(0.15)
    };
    sample(&shapes, &sampling).unwrap()
}

/// Noisy circles with outliers, repaired by the paper's rule, in both stage orders: each stage's
/// graph is a subset of its input's, the final edges are the last stage's, and a stage that
/// changes nothing reports its input unchanged.
#[test]
fn stage_graphs_chain_in_either_order_on_noisy_circles_with_outliers() {
    let s = noisy_circles_with_outliers();
    let subset = |small: &[[usize; 2]], big: &[[usize; 2]]| small.iter().all(|e| big.contains(e));
    for outliers_first in [false, true] {
        let r = run(
            &s.points,
            Params::paper().with_outliers_first(outliers_first),
        );
        let order: Vec<Stage> = r.stages().map(|report| report.stage).collect();
        let expected = if outliers_first {
            [Stage::Proximity, Stage::Outliers, Stage::Repair]
        } else {
            [Stage::Proximity, Stage::Repair, Stage::Outliers]
        };
        assert_eq!(order, expected);
        let of = |stage| stage_edges(&r, stage).expect("the stage ran");
        let (proximity, repaired, filtered) =
            (of(Stage::Proximity), of(Stage::Repair), of(Stage::Outliers));
        assert!(
            r.stage(Stage::Outliers).unwrap().applied,
            "outliers_first = {outliers_first}"
        );
        if outliers_first {
            assert!(subset(&filtered, &proximity) && filtered.len() < proximity.len());
            assert!(subset(&repaired, &filtered));
            assert_eq!(final_edges(&r), repaired);
        } else {
            assert!(subset(&repaired, &proximity) && repaired.len() < proximity.len());
            assert!(subset(&filtered, &repaired) && filtered.len() < repaired.len());
            assert_eq!(final_edges(&r), filtered);
        }
    }
    // Stages that are off do not run, and the final graph is the proximity graph.
    let unrepaired = run(
        &s.points,
        Params::paper()
            .with_repair(Repair::Off)
            .with_outlier_factor(None),
    );
    assert_eq!(unrepaired.stages().count(), 1);
    assert!(stage_edges(&unrepaired, Stage::Repair).is_none());
    assert_eq!(
        Some(final_edges(&unrepaired)),
        stage_edges(&unrepaired, Stage::Proximity)
    );
}

/// The library refuses parameters that would silently delete every edge or keep every one:
/// NaN, infinite or non-positive `u`; NaN, infinite or negative `k`; through `reconstruct`, the
/// step methods and `Params::check` alike, naming the parameter.
#[test]
fn invalid_parameters_are_refused_with_their_name() {
    use condt::{triangulate, Error};
    let s = sample(&[Shape::circle(origin(), 1.0)], &Sampling::new(0.3)).unwrap();
    for u in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
        let params = Params::default().with_uniformity(Uniformity::Fixed(u));
        let err = reconstruct(&s.points, &params).unwrap_err();
        assert!(
            matches!(err, Error::InvalidParameter { name: "u", value } if value.to_bits() == u.to_bits()),
            "u = {u}: {err:?}"
        );
        assert!(matches!(
            params.check(),
            Err(Error::InvalidParameter { name: "u", .. })
        ));
    }
    for k in [f64::NAN, f64::NEG_INFINITY, f64::INFINITY, -0.5] {
        let params = Params::default().with_outlier_factor(Some(k));
        let err = reconstruct(&s.points, &params).unwrap_err();
        assert!(
            matches!(err, Error::InvalidParameter { name: "k", .. }),
            "k = {k}: {err:?}"
        );
    }
    // Accepted at the edges of the ranges: the smallest positive u, k = 0.
    let edge_values = Params::default()
        .with_uniformity(Uniformity::Fixed(f64::MIN_POSITIVE))
        .with_outlier_factor(Some(0.0));
    assert!(reconstruct(&s.points, &edge_values).is_ok());
    let tri = triangulate(&s.points).unwrap();
    assert!(tri.proximity_graph(Uniformity::Fixed(f64::NAN)).is_err());
    let graph = tri.proximity_graph(Uniformity::default()).unwrap();
    assert!(graph.remove_outliers(f64::NAN).is_err());
    assert!(graph.remove_outliers(-1.0).is_err());
}

/// Running the stages one by one with the public step methods gives exactly what
/// `reconstruct` keeps, stage for stage, in both orders.
#[test]
fn step_methods_compose_into_the_pipeline() {
    use condt::triangulate;
    // Every stage changes the graph on this input, in both orders.
    let s = noisy_circles_with_outliers();
    let tri = triangulate(&s.points).unwrap();
    for outliers_first in [false, true] {
        let params = Params::default().with_outliers_first(outliers_first);
        let r = reconstruct(&s.points, &params).unwrap();
        let proximity = tri.proximity_graph(params.uniformity).unwrap();
        let (repaired, filtered) = if outliers_first {
            let filtered = proximity.remove_outliers(1.7).unwrap();
            (filtered.graph.repair(params.repair), filtered)
        } else {
            let repaired = proximity.repair(params.repair);
            let filtered = repaired.remove_outliers(1.7).unwrap();
            (repaired, filtered)
        };
        assert!(filtered.fired, "outliers_first = {outliers_first}");
        assert_eq!(
            stage_edges(&r, Stage::Proximity).unwrap(),
            proximity.edges()
        );
        assert_eq!(stage_edges(&r, Stage::Repair).unwrap(), repaired.edges());
        assert_eq!(
            stage_edges(&r, Stage::Outliers).unwrap(),
            filtered.graph.edges()
        );
        let last = if outliers_first {
            &repaired
        } else {
            &filtered.graph
        };
        assert_eq!(final_edges(&r), last.edges());
        assert_eq!(r.curves(), &last.curves()[..]);
        // Degrees agree with the final edges, per input position.
        let degrees = last.degrees();
        assert!((0..r.num_points()).all(|i| r.degree(i) == degrees[i]));
    }
}

/// FNV-1a over the edges, as the pins below were taken.
fn edge_hash(edges: impl Iterator<Item = [usize; 2]>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for [a, b] in edges {
        for x in [a as u64, b as u64] {
            for byte in x.to_le_bytes() {
                h ^= u64::from(byte);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
    }
    h
}

/// `Params::paper()` reproduces, edge for edge, the default pipeline of commit 029f6cd (the
/// paper's reading before any stage beyond it existed) on five pinned inputs. The pins were
/// taken by running that commit's `reconstruct` on the same inputs (a throwaway program against
/// a checkout of it); the same identity was checked on every file of `../shared/data` in five
/// modes (`docs/condt.md`, "Presets").
#[test]
fn paper_preset_reproduces_the_pinned_outputs() {
    let o = origin();
    let star: Vec<Point> = (0..10)
        .map(|k| {
            let r = if k % 2 == 0 { 1.0 } else { 0.4 };
            let a = std::f64::consts::TAU * k as f64 / 10.0 + 0.1;
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect();
    let cases: Vec<(&str, Vec<Shape>, Sampling, usize, u64)> = vec![
        (
            "noisy circles with outliers",
            vec![
                Shape::circle(o, 3.0),
                Shape::circle(Point::new(8.0, 1.0), 2.0),
            ],
            Sampling {
                outlier_fraction: 0.1,
                outlier_clearance: 1.0,
                noise: 0.02,
                seed: 1,
                ..Sampling::new(0.15)
            },
            84,
            0xe974_997f_9c62_9425,
        ),
        (
            "figure eight, noisy",
            vec![Shape::FigureEight {
                center: o,
                size: 2.0,
            }],
            Sampling {
                noise: 0.01,
                ..Sampling::new(0.05)
            },
            471,
            0x5c8c_4a96_b87c_1053,
        ),
        (
            "five-point star",
            vec![Shape::Polygon(star)],
            Sampling::new(0.3),
            25,
            0x5419_5838_b949_d547,
        ),
        (
            "spiral and arc with outliers",
            vec![
                Shape::Spiral {
                    center: o,
                    inner: 0.5,
                    gap: 0.4,
                    turns: 3.0,
                },
                Shape::Arc {
                    center: Point::new(5.0, 0.0),
                    radius: 1.5,
                    start: 0.0,
                    sweep: 4.0,
                },
            ],
            Sampling {
                outlier_fraction: 0.05,
                seed: 7,
                ..Sampling::new(0.2)
            },
            521,
            0xee8e_2ca2_5346_7aff,
        ),
    ];
    for (label, shapes, sampling, count, hash) in cases {
        let s = sample(&shapes, &sampling).unwrap();
        let r = run(&s.points, Params::paper());
        assert_eq!(r.edges().len(), count, "{label}");
        assert_eq!(edge_hash(r.edges()), hash, "{label}");
    }
    let shipped = condt_io::read_points(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/shapes.txt"
    ))
    .unwrap();
    let r = run(&shipped, Params::paper());
    assert_eq!(r.edges().len(), 225);
    assert_eq!(edge_hash(r.edges()), 0x4a4f_d6f9_473b_811a);
}

/// A comb drawn with evenly spaced samples: a straight line of 31 samples, a short tooth of eight
/// between two long teeth of twenty, two spacings to each side, every tooth meeting the line at a
/// T. No sample of the short tooth lies apart from the long ones, so the local outlier removal
/// would drop it as a noisy piece; the junction its end makes with the line keeps it, and the
/// result is the drawing: the line, the three teeth and their three junction edges.
#[test]
fn a_short_tooth_between_long_ones_keeps_its_junction() {
    let mut points: Vec<Point> = (0..=30).map(|x| Point::new(x as f64, 0.0)).collect();
    let mut drawn: BTreeSet<[usize; 2]> = (0..30).map(|k| [k, k + 1]).collect();
    for (x, len) in [(15, 8), (13, 20), (17, 20)] {
        let first = points.len();
        points.extend((1..=len).map(|y| Point::new(x as f64, y as f64)));
        drawn.extend((first..first + len - 1).map(|k| [k, k + 1]));
        drawn.insert([x, first]);
    }
    let r = run(&points, Params::default());
    assert_eq!(edges(&r), drawn);
    assert!(r.unused().is_empty());
}

/// A ladder's rung drawn with evenly spaced samples: two straight curves seven spacings apart and,
/// between them, a stroke of six samples, each end one spacing from a curve. The stroke is too
/// short for a branch and lies apart from nothing; it meets a curve at both ends, so it is kept
/// and joined at both: the result is the drawing.
#[test]
fn a_short_rung_between_two_curves_is_joined_at_both_ends() {
    let mut points: Vec<Point> = (0..=12).map(|x| Point::new(x as f64, 0.0)).collect();
    points.extend((0..=12).map(|x| Point::new(x as f64, 7.0)));
    points.extend((1..=6).map(|y| Point::new(6.0, y as f64)));
    let mut drawn: BTreeSet<[usize; 2]> = (0..12).chain(13..25).map(|k| [k, k + 1]).collect();
    drawn.extend((26..31).map(|k| [k, k + 1]));
    drawn.extend([[6, 26], [19, 31]]);
    let r = run(&points, Params::default());
    assert_eq!(edges(&r), drawn);
}
