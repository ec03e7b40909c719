//! SVG drawings hold finite numbers only, whatever the coordinates (issue 11, item 7).

use condt::{reconstruct, Params, Point, Reconstruction};
use condt_io::{write_svg, write_svg_stages};

/// Every number in `svg` (colours `#rrggbb` aside): maximal runs of digits, signs, points and
/// exponents, parsed.
fn numbers(svg: &str) -> Vec<f64> {
    let is_part = |c: char| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E');
    let mut text = String::new();
    let mut rest = svg;
    while let Some(at) = rest.find('#') {
        text.push_str(&rest[..at]);
        rest = &rest[(at + 7).min(rest.len())..];
    }
    text.push_str(rest);
    text.split(|c: char| !is_part(c))
        .filter(|t| t.chars().any(|c| c.is_ascii_digit()))
        .map(|t| {
            t.parse::<f64>()
                .unwrap_or_else(|_| panic!("not a number: {t:?}"))
        })
        .collect()
}

fn svg_of(points: &[Point], stages: bool) -> String {
    drawing(
        &reconstruct(points, &Params::default()).unwrap(),
        points,
        stages,
    )
}

/// The stage panels of `r` with `stages`, else its result drawn on `input`.
fn drawing(r: &Reconstruction, input: &[Point], stages: bool) -> String {
    let mut out = Vec::new();
    if stages {
        write_svg_stages(&mut out, r).unwrap();
    } else {
        write_svg(&mut out, r, input).unwrap();
    }
    String::from_utf8(out).unwrap()
}

/// `printf -- '-1e308 0\n1e308 0\n0 1e308\n' | condt reconstruct - --format svg` wrote `inf`
/// and `NaN` coordinates (the span of the x coordinates overflowed).
#[test]
fn coordinates_near_the_largest_double_draw_finite_numbers() {
    let sets = [
        vec![(-1e308, 0.0), (1e308, 0.0), (0.0, 1e308)],
        vec![
            (-f64::MAX, -f64::MAX),
            (f64::MAX, f64::MAX),
            (f64::MAX, -f64::MAX),
        ],
        vec![(1e-320, 0.0), (0.0, 5e-324), (-1e-320, 1e-320)],
        vec![
            (1.0, 1.0),
            (1.0, 1.0 + f64::EPSILON),
            (1.0 + f64::EPSILON, 1.0),
        ],
        vec![(3.0, 4.0)],
        vec![(0.0, 0.0), (0.0, 0.0)],
    ];
    for set in sets {
        let points: Vec<Point> = set.iter().map(|&c| Point::from(c)).collect();
        for stages in [false, true] {
            let svg = svg_of(&points, stages);
            assert!(!svg.contains("inf") && !svg.contains("NaN"), "{svg}");
            let numbers = numbers(&svg);
            assert!(numbers.len() > 5, "{svg}");
            for x in numbers {
                assert!(x.is_finite() && x.abs() <= 1e4, "{x} in {svg}");
            }
        }
    }
}

/// The picture does not depend on the scale of the input: a set and its multiples by powers
/// of two draw the same SVG, byte for byte.
#[test]
fn a_set_and_its_power_of_two_multiples_draw_the_same_svg() {
    let points: Vec<Point> = (0..40)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 40.0;
            Point::new(3.0 * t.cos() + 10.0, 2.0 * t.sin() - 5.0)
        })
        .collect();
    let reference = svg_of(&points, true);
    for k in [-1000, -600, 600, 1000] {
        let f = 2f64.powi(k);
        let scaled: Vec<Point> = points
            .iter()
            .map(|p| Point::new(p.x * f, p.y * f))
            .collect();
        assert_eq!(svg_of(&scaled, true), reference, "2^{k}");
    }
}

/// A noisy open arc runs smoothing passes: the stage drawing says its points are where the stages
/// saw them, and the result-only drawing places the points at their input positions (its
/// circles' centres are the input coordinates mapped by one frame, so the drawing of the input
/// and of the smoothed result alone are identical, and the stage drawing differs).
#[test]
fn drawings_say_when_points_are_at_smoothed_positions() {
    let arc: Vec<Point> = (0..30)
        .map(|k| {
            let t = k as f64 * 1.5 * std::f64::consts::PI / 29.0;
            let r = if k % 2 == 0 { 1.04 } else { 1.0 };
            Point::new(r * t.cos(), r * t.sin())
        })
        .collect();
    let smoothed = reconstruct(&arc, &Params::default()).unwrap();
    assert!(smoothed.smoothing().is_some());
    let plain = reconstruct(&arc, &Params::default().with_smooth(false)).unwrap();
    assert_eq!(
        plain.edges().collect::<Vec<_>>(),
        smoothed.edges().collect::<Vec<_>>()
    );
    let draw = |r: &Reconstruction, stages: bool| drawing(r, &arc, stages);
    let stage_drawing = draw(&smoothed, true);
    assert!(stage_drawing.contains("smoothing pass"));
    assert!(!draw(&plain, true).contains("smoothing pass"));
    assert_eq!(draw(&smoothed, false), draw(&plain, false));
    // Without the legend's note, the stage drawings still differ: the points moved.
    let without_note: String = stage_drawing
        .lines()
        .filter(|line| !line.contains("smoothing pass"))
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(numbers(&without_note), numbers(&draw(&plain, true)));
}

/// The drawings that take the input coordinates from the caller refuse a list of another
/// length with an `InvalidInput` error, and write nothing; the right list is accepted.
#[test]
fn writers_refuse_a_point_list_of_another_length() {
    let points = [(0.0, 0.0), (1.0, 0.0), (0.5, 2.0)].map(Point::from);
    let r = reconstruct(&points, &Params::default()).unwrap();
    for wrong in [&points[..2], &[points[0]; 4][..], &[]] {
        let mut out = Vec::new();
        let err = write_svg(&mut out, &r, wrong).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
        let err = condt_io::write_geojson(&mut out, &r, wrong).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
        assert!(err.to_string().contains("of 3"), "{err}");
        assert!(out.is_empty());
    }
    let mut out = Vec::new();
    write_svg(&mut out, &r, &points).unwrap();
    condt_io::write_geojson(&mut out, &r, &points).unwrap();
    assert!(!out.is_empty());
}
