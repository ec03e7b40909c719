//! (c) Run the ConDT stages one by one and look at the proximity graph before the repair.
//!
//! `cargo run --example stage_by_stage -- [POINT_FILE]` (default: the shipped
//! `data/shapes.txt`)

use condt::{reconstruct, triangulate, Params, Repair, Uniformity};
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

    // Every stage of `Params::default()`, one at a time and in its order (`Params::stages`):
    // `Repair::Needs` (`Repair::Paper` would be Algorithm 2), the IQR rule with k = 1.7 and the
    // spacing floor, the repair run again without the cut edges, the local outlier removal,
    // clumps, the check of the components it gave back, gap closing, junctions, crossings, tips,
    // spikes, hooks, outlier tails and detours. Not
    // run here: the default's smoothing passes, which only `reconstruct` and `Pipeline` run (so
    // on noisy input the default's result can differ from this one; the check below is
    // against the default without them).
    let repaired = proximity.repair(Repair::Needs);
    println!("after the repair: {} edges", repaired.num_edges());

    let outliers = repaired.remove_outliers_floored(1.7)?;
    println!(
        "after outlier removal: {} edges (the rule fired: {})",
        outliers.graph.num_edges(),
        outliers.fired
    );
    let again = outliers.repair_again(&repaired, &proximity, Repair::Needs);
    let local = again.remove_local_outliers(&repaired);
    let clumps = local.remove_clumps();
    let confirmed = clumps.confirm_given_back(&again);
    let joined = confirmed.close_gaps().join_junctions().restore_crossings();
    let closed = joined
        .repair_tips()
        .repair_spikes()
        .unhook()
        .cut_tails()
        .cut_detours();
    println!(
        "repaired again: {} edges; after local outlier removal: {}; after clumps: {}; after \
         confirming given-back components: {}; after gaps, junctions and crossings: {}; after \
         tips, spikes, hooks, tails and detours: {}",
        again.num_edges(),
        local.num_edges(),
        clumps.num_edges(),
        confirmed.num_edges(),
        joined.num_edges(),
        closed.num_edges()
    );
    let pipeline = reconstruct(&points, &Params::default().with_smooth(false))?;
    assert_eq!(closed.edges(), pipeline.edges().collect::<Vec<_>>());

    for curve in closed.curves() {
        let kind = if curve.is_closed() { "closed" } else { "open" };
        println!("{kind} curve through {} points", curve.len());
    }
    Ok(())
}
