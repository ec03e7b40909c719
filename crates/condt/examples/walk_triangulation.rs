//! (b) Triangulate a point file and walk every point's Delaunay neighbours and the hull.
//!
//! `cargo run --example walk_triangulation -- [POINT_FILE]` (default: the shipped
//! `data/shapes.txt`)

use condt::triangulate;
use condt_io::read_points;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "data/shapes.txt".into());
    let points = read_points(&path)?;
    let tri = triangulate(&points)?;
    tri.validate()?;
    println!(
        "{} points, {} distinct, {} triangles, {} edges",
        tri.num_points(),
        tri.num_vertices(),
        tri.triangles().count(),
        tri.edges().count()
    );

    // Every distinct point with its neighbours, counter-clockwise, and its shortest edge.
    for i in tri.distinct_points() {
        let ring: Vec<usize> = tri.neighbors(i).collect();
        let shortest = ring
            .iter()
            .map(|&j| tri.point(i).dist2(tri.point(j)).sqrt())
            .fold(f64::INFINITY, f64::min);
        println!("{i}: {ring:?}, shortest edge {shortest:.4}");
    }

    let hull: Vec<usize> = tri.hull().collect();
    println!("hull, counter-clockwise: {hull:?}");
    Ok(())
}
