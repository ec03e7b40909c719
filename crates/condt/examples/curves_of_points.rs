//! (a) Reconstruct the curves through a list of coordinates and print each curve's points.
//!
//! `cargo run --example curves_of_points`

use condt::{reconstruct, Params, Point};

fn main() -> Result<(), condt::Error> {
    // A square of 12 points and, apart from it, an open arc of 7.
    let mut coordinates: Vec<(f64, f64)> = (0..12)
        .map(|k| {
            let (side, t) = (k / 3, (k % 3) as f64 / 3.0);
            [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][side]
        })
        .collect();
    coordinates.extend((0..7).map(|k| {
        let angle = 0.4 * k as f64;
        (3.0 + angle.cos(), 0.5 + angle.sin())
    }));

    let points: Vec<Point> = coordinates.iter().map(|&p| Point::from(p)).collect();
    let result = reconstruct(&points, &Params::default())?;

    for (n, curve) in result.curves().iter().enumerate() {
        let kind = if curve.is_closed() { "closed" } else { "open" };
        println!("curve {n} ({kind}, {} points):", curve.len());
        for i in curve.points() {
            let (x, y) = coordinates[i];
            println!("  {i:3}: ({x:.3}, {y:.3})");
        }
    }
    println!("unused points: {:?}", result.unused());
    Ok(())
}
