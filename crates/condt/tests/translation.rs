//! Exact translations do not change the Crust (issue 29, defect 8): its circumcentres are
//! computed relative to the corner of the samples' box, so a translation that is exact on the
//! input moves every centre exactly with the samples. The sets were found by a search over small
//! sets on non-dyadic grids (where circumcentres round), translated by powers of two; before
//! the fix each gave other edges once translated.

use condt::{triangulate, Point};

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
        for k in [1.0, 2.0, 4.0] {
            let offset = Point::new(offset.x * k, offset.y * k);
            if points
                .iter()
                .all(|p| exact_sum(p.x, offset.x) && exact_sum(p.y, offset.y))
            {
                assert_eq!(
                    crust(&translated(&points, offset)),
                    expected,
                    "{points:?} + {offset:?}"
                );
            }
        }
        // The search's offset is exact (checked by `translated`).
        assert_eq!(
            crust(&translated(&points, offset)),
            expected,
            "{points:?} + {offset:?}"
        );
    }
}
