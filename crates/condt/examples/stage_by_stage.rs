//! (c) Run the ConDT stages one by one and look at the proximity graph before the repair.
//!
//! `cargo run --example stage_by_stage -- [POINT_FILE]` (default: the shipped
//! `data/shapes.txt`)

use condt::{triangulate, Repair, Uniformity};
use condt_io::read_points;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "data/shapes.txt".into());
    let points = read_points(&path)?;
    let tri = triangulate(&points)?;

    let proximity = tri.proximity_graph(Uniformity::Fixed(2.75))?;
    let degrees = proximity.degrees();
    let crowded: Vec<usize> = (0..degrees.len()).filter(|&i| degrees[i] > 2).collect();
    println!(
        "proximity graph: {} edges; points with more than two: {crowded:?}",
        proximity.num_edges()
    );
    let edges = proximity.edges();
    for &i in &crowded {
        let around: Vec<&[usize; 2]> = edges.iter().filter(|e| e.contains(&i)).collect();
        println!("  {i}: {around:?}");
    }

    // Every stage of `Params::default()`, one at a time and in its order: `Repair::Needs`
    // (`Repair::Paper` would be Algorithm 2), the IQR rule with k = 1.7, the local outlier
    // removal, the check of the components it gave back, gap closing. Not run here: the
    // default's smoothing passes, which only `reconstruct` and `Pipeline` run (so on noisy
    // input the default's result can differ from this one).
    let repaired = proximity.repair(Repair::Needs);
    println!("after the repair: {} edges", repaired.num_edges());

    let outliers = repaired.remove_outliers(1.7)?;
    println!(
        "after outlier removal: {} edges (the rule fired: {})",
        outliers.graph.num_edges(),
        outliers.fired
    );
    let local = outliers.graph.remove_local_outliers(&repaired);
    let confirmed = local.confirm_given_back(&outliers.graph);
    let closed = confirmed.close_gaps();
    println!(
        "after local outlier removal: {} edges; after confirming given-back components: {}; \
         after closing gaps: {}",
        local.num_edges(),
        confirmed.num_edges(),
        closed.num_edges()
    );

    for curve in closed.curves() {
        let kind = if curve.is_closed() { "closed" } else { "open" };
        println!("{kind} curve through {} points", curve.len());
    }
    Ok(())
}
