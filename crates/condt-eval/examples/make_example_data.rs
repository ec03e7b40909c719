//! Writes `data/shapes.txt`, the point file the README's first command runs on: an
//! ellipse, a square with sharp corners, an open arc and an open spiral, sampled by
//! `condt_eval::sample`, plus a few isolated outliers and one exact duplicate, in shuffled order.
//! Run: `cargo run --example make_example_data`.

use condt::Point;
use condt_eval::sample::{sample, Sampling, Shape};
use std::fmt::Write as _;

fn main() -> std::io::Result<()> {
    // Spacings: 0.42 on the ellipse, 0.5 on the square and the arc, 0.1 on the spiral. Algorithm
    // 3's threshold is global: a component sampled far more sparsely than the rest can lose its
    // edges with the outliers (docs/condt.md), so none here is sparser than the others by much.
    let shapes = [
        Shape::Ellipse {
            center: Point::new(0.0, 0.0),
            radii: (3.0, 2.5),
            rotation: 0.3,
        },
        Shape::Polygon(vec![
            Point::new(5.0, -1.5),
            Point::new(7.5, -1.5),
            Point::new(7.5, 1.0),
            Point::new(5.0, 1.0),
        ]),
        Shape::Arc {
            center: Point::new(0.5, 6.5),
            radius: 2.5,
            start: 0.2,
            sweep: 2.4,
        },
        Shape::Spiral {
            center: Point::new(7.0, 6.5),
            inner: 1.0,
            gap: 1.0,
            turns: 1.4,
        },
    ];
    let sampling = Sampling {
        outlier_fraction: 0.03,
        outlier_clearance: 2.0,
        seed: 7,
        ..Sampling::new(0.2)
    };
    let mut points = sample(&shapes, &sampling).unwrap().points;
    points.push(points[10]);
    // A fixed shuffle (multiplication by a number coprime with the count), so the file order
    // carries no curve order.
    let n = points.len();
    let step = (n / 2..n).find(|s| gcd(*s, n) == 1).unwrap_or(1);
    let mut text = String::from("# four curves, made by `cargo run --example make_example_data`\n");
    for i in 0..n {
        let p = points[(i * step) % n];
        writeln!(text, "{:.6} {:.6}", p.x, p.y).unwrap();
    }
    std::fs::write("data/shapes.txt", text)
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}
