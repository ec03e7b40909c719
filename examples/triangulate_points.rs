//! Triangulates a point file and walks the mesh: counts, the hull, and one vertex's ring.
//! Run: `cargo run --example triangulate_points -- examples/data/shapes.txt`.

use condt::io::read_points;
use condt::triangulate;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "examples/data/shapes.txt".into());
    let points = read_points(&path)?;
    let tri = triangulate(&points)?;
    tri.validate()?;
    println!(
        "{} points, {} distinct, {} triangles, {} edges, {} on the hull",
        points.len(),
        tri.num_vertices(),
        tri.triangles().count(),
        tri.edges().count(),
        tri.hull().count()
    );
    // Vertex ids follow the triangulator's spatial order; translate from and to input positions.
    let v = tri.vertex_of_input(0);
    let ring: Vec<usize> = tri.neighbors(v).map(|w| tri.input_index(w)).collect();
    println!("neighbours of point 0, counter-clockwise: {ring:?}");
    let shortest = tri
        .neighbors(v)
        .map(|w| tri.point(v).dist2(tri.point(w)).sqrt())
        .fold(f64::INFINITY, f64::min);
    println!("its shortest Delaunay edge is {shortest:.4} long");
    Ok(())
}
