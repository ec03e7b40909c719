//! Exact translations do not change the Crust or the default pipeline's smoothing passes
//! (issue 29, defect 8): the Crust's circumcentres and the smoothed positions are computed
//! relative to the corner of the set's box, so a translation that is exact on the input moves
//! every centre and every smoothed position exactly with the samples. The sets were found by a
//! search over small sets on non-dyadic grids (where circumcentres and averages round),
//! translated by powers of two or by one half; before the fix each gave other edges once
//! translated.

use condt::{reconstruct, triangulate, Params, Point};

/// Whether `a + b` is a double (Knuth's two-sum has no error).
fn exact_sum(a: f64, b: f64) -> bool {
    let s = a + b;
    let bb = s - a;
    (a - (s - bb)) + (b - bb) == 0.0
}

fn translated(points: &[Point], offset: Point) -> Vec<Point> {
    assert!(
        points
            .iter()
            .all(|p| exact_sum(p.x, offset.x) && exact_sum(p.y, offset.y)),
        "the translation must be exact"
    );
    points
        .iter()
        .map(|p| Point::new(p.x + offset.x, p.y + offset.y))
        .collect()
}

fn crust(points: &[Point]) -> Vec<[usize; 2]> {
    triangulate(points).unwrap().crust().unwrap().edges()
}

#[test]
fn an_exact_translation_keeps_the_crust_of_four_points() {
    let sets: [([Point; 4], Point); 3] = [
        (
            [
                Point::new(0.8818181818181818, 0.425),
                Point::new(0.7909090909090909, 0.8),
                Point::new(0.8818181818181818, 0.55),
                Point::new(0.7909090909090909, 0.55),
            ],
            Point::new(-1.0, 0.0),
        ),
        (
            [
                Point::new(0.7526315789473683, 0.5857142857142856),
                Point::new(0.8578947368421053, 0.8714285714285714),
                Point::new(0.8578947368421053, 0.5857142857142856),
                Point::new(0.7526315789473683, 0.3),
            ],
            Point::new(1.0, 0.0),
        ),
        (
            [
                Point::new(0.8764705882352941, 0.44285714285714284),
                Point::new(0.8764705882352941, 0.3),
                Point::new(0.7, 0.44285714285714284),
                Point::new(0.8764705882352941, 0.5857142857142856),
            ],
            Point::new(1.0, 0.0),
        ),
    ];
    for (points, offset) in sets {
        let expected = crust(&points);
        // The search's offset, and others exact for every set (`translated` checks; a guard
        // that skipped inexact ones had left only the search's own).
        for (k, dy) in [(1.0, 0.0), (0.25, 0.0), (0.5, -0.5), (0.75, -0.5)] {
            let offset = Point::new(offset.x * k, offset.y * k + dy);
            assert_eq!(
                crust(&translated(&points, offset)),
                expected,
                "{points:?} + {offset:?}"
            );
        }
        // With each point given again first (vertex ids then skip the merged copies' slots).
        for repeated in 0..points.len() {
            let mut with_copy = vec![points[repeated]];
            with_copy.extend_from_slice(&points);
            assert_eq!(
                crust(&translated(&with_copy, offset)),
                crust(&with_copy),
                "{with_copy:?} + {offset:?}"
            );
        }
    }
}

/// Noisy arcs of 14 points on grids of 1/5, 1/7 and 1/6 (the last with a repeated point): the
/// smoothing passes run (the arcs have two ends in 14 points), and before the fix the moved
/// positions rounded by where the set lay, so the set shifted by -1/2 got other edges.
#[test]
fn an_exact_translation_keeps_the_default_reconstruction_through_the_smoothing_passes() {
    let arcs: [&[(f64, f64)]; 3] = [
        &[
            (2.5, 0.4),
            (2.7, 0.8),
            (2.3, 1.2),
            (2.2, 1.7),
            (1.9, 1.8),
            (1.8, 2.0),
            (1.5, 2.3),
            (0.9, 2.5),
            (0.8, 2.6),
            (0.4, 2.3),
            (0.0, 2.5),
            (-0.4, 2.3),
            (-0.4, 2.2),
            (-0.8, 1.9),
        ],
        &[
            (2.4285714285714284, 0.42857142857142855),
            (2.5714285714285716, 1.0),
            (2.2857142857142856, 1.2857142857142858),
            (2.142857142857143, 1.2857142857142858),
            (2.142857142857143, 1.7142857142857142),
            (1.5714285714285714, 2.142857142857143),
            (1.2857142857142858, 2.142857142857143),
            (1.1428571428571428, 2.5714285714285716),
            (0.8571428571428571, 2.4285714285714284),
            (0.2857142857142857, 2.7142857142857144),
            (0.14285714285714285, 2.5714285714285716),
            (-0.2857142857142857, 2.2857142857142856),
            (-0.5714285714285714, 2.142857142857143),
            (-1.0, 2.0),
        ],
        &[
            (2.6666666666666665, 0.3333333333333333),
            (2.3333333333333335, 1.0),
            (2.3333333333333335, 1.1666666666666667),
            (2.0, 1.3333333333333333),
            (1.8333333333333333, 1.8333333333333333),
            (2.0, 2.1666666666666665),
            (1.6666666666666667, 2.3333333333333335),
            (1.1666666666666667, 2.5),
            (0.6666666666666666, 2.5),
            (0.5, 2.3333333333333335),
            (0.0, 2.6666666666666665),
            (-0.5, 2.3333333333333335),
            (-0.5, 2.3333333333333335),
            (-1.0, 2.0),
        ],
    ];
    let params = Params::default();
    for arc in arcs {
        let points: Vec<Point> = arc.iter().map(|&p| Point::from(p)).collect();
        let result = reconstruct(&points, &params).unwrap();
        assert!(
            result.smoothing().is_some_and(|s| s.passes >= 1),
            "the smoothing passes run"
        );
        let expected: Vec<[usize; 2]> = result.edges().collect();
        // Offsets exact on all three grids (`translated` checks; a guard that skipped inexact
        // ones had left only -1/2).
        for offset in [-0.5, -0.25, -0.375, 0.0625, -1.0 / 1024.0] {
            let offset = Point::new(offset, offset);
            let moved = reconstruct(&translated(&points, offset), &params).unwrap();
            assert_eq!(
                moved.edges().collect::<Vec<_>>(),
                expected,
                "{points:?} + {offset:?}"
            );
        }
    }
}
