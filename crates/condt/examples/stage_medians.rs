//! (d) Time each stage of one reconstruction run: the medians over several runs of stepping a
//! `Pipeline` (the default parameters without smoothing passes, so that every stage runs once;
//! with `smooth`, with them: each pass's triangulation and stages in their own rows).
//!
//! `cargo run --release --example stage_medians -- POINT_FILE [RUNS] [seq] [smooth]` (default 9
//! runs, on rayon's threads; `seq` runs on one)

use condt::{Params, Pipeline, StepReport};
use condt_io::read_points;
use std::time::{Duration, Instant};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().unwrap_or_else(|| "data/shapes.txt".into());
    let runs: usize = args.next().map_or(Ok(9), |s| s.parse())?;
    let flags: Vec<String> = args.collect();
    let parallel = !flags.iter().any(|f| f == "seq");
    let smooth = flags.iter().any(|f| f == "smooth");
    let points = read_points(&path)?;
    let params = Params::default()
        .with_smooth(smooth)
        .with_parallel(parallel);
    // One row per step, in order: its name and its time in every run.
    let mut rows: Vec<(String, Vec<Duration>)> = Vec::new();
    for _ in 0..runs.max(1) {
        let mut times = Vec::new();
        let clock = Instant::now();
        let mut pipeline = Pipeline::new(&points, &params)?;
        times.push(("triangulation".to_string(), clock.elapsed()));
        let mut clock = Instant::now();
        let mut pass = 0;
        while let Some(step) = pipeline.step()? {
            let name = match step {
                StepReport::Stage(report) => report.stage.to_string(),
                StepReport::SmoothingPass { pass: k, .. } => {
                    pass = k;
                    "moving points, triangulating them".to_string()
                }
                _ => "another step".to_string(),
            };
            let name = if pass > 0 {
                format!("pass {pass}: {name}")
            } else {
                name
            };
            times.push((name, clock.elapsed()));
            clock = Instant::now();
        }
        pipeline.finish()?;
        times.push(("curves and tally".to_string(), clock.elapsed()));
        for (k, (name, time)) in times.into_iter().enumerate() {
            if rows.len() <= k {
                rows.push((name, Vec::new()));
            }
            rows[k].1.push(time);
        }
    }
    let mut total = 0.0;
    for (name, mut times) in rows {
        times.sort_unstable();
        let median = times[times.len() / 2].as_secs_f64() * 1e3;
        total += median;
        println!("{name:>45} {median:9.1} ms");
    }
    println!("{:>45} {total:9.1} ms", "sum of the medians");
    Ok(())
}
