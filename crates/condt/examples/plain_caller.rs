//! (f) A plain library caller: `reconstruct` with the points borrowed and the system allocator
//! (glibc's malloc on Linux: no global allocator is declared), for the peak resident set such a
//! program reaches (`docs/performance.md`, *Library callers with glibc's own malloc*).
//!
//! `cargo build --release -p condt --example plain_caller`, then
//! `/usr/bin/time -f %M target/release/examples/plain_caller POINT_FILE [owned] [seq]` (default
//! parameters; `owned` hands the points over as `reconstruct_owned` does, `seq` runs on one
//! thread). `step_memory` says which step holds what.

use condt::{reconstruct, reconstruct_owned, Params};
use condt_io::read_points;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().map_or("data/shapes.txt", String::as_str);
    let flag = |word: &str| args.iter().skip(1).any(|a| a == word);
    let params = Params::default().with_parallel(!flag("seq"));
    let points = read_points(path)?;
    let result = if flag("owned") {
        reconstruct_owned(points, &params)?
    } else {
        reconstruct(&points, &params)?
    };
    println!(
        "{} edges, {} curves, {} unused",
        result.edges().len(),
        result.curves().len(),
        result.unused().len()
    );
    Ok(())
}
