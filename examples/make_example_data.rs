//! Writes `examples/data/two_ellipses.txt`, the point file the README's first command runs on:
//! two interlocking ellipses sampled at uniform parameter steps, in a shuffled order, with one
//! exact duplicate. Run: `cargo run --example make_example_data`.

use std::fmt::Write as _;

fn main() -> std::io::Result<()> {
    let mut points = Vec::new();
    for (cx, cy, a, b, n) in [(0.0, 0.0, 3.0, 1.5, 90), (2.5, 0.5, 2.0, 2.0, 70)] {
        for k in 0..n {
            let t = k as f64 / n as f64 * std::f64::consts::TAU;
            points.push((cx + a * t.cos(), cy + b * t.sin()));
        }
    }
    points.push(points[7]);
    // A fixed multiplicative shuffle, so the file order carries no curve order.
    let n = points.len();
    let shuffled: Vec<(f64, f64)> = (0..n).map(|i| points[(i * 97) % n]).collect();
    let mut text =
        String::from("# two ellipses, made by `cargo run --example make_example_data`\n");
    for (x, y) in shuffled {
        writeln!(text, "{x:.6} {y:.6}").unwrap();
    }
    std::fs::write("examples/data/two_ellipses.txt", text)
}
