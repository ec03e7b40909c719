//! Parses a plain point file `TIMES` times on one thread and prints the number of points: the
//! single-core parse figures of docs/performance.md ("Parsing alone, one thread") come from it,
//! by instruction counts or by processor time less that of `TIMES` = 0 (which only reads the
//! file).
//!
//! `cargo run --release --example parse_text -- uniform-1M.txt 10`, or under
//! `valgrind --tool=callgrind target/release/examples/parse_text uniform-1M.txt 1`. A third
//! argument `keep` keeps every result until the end, so that each parse writes its points into
//! fresh pages, as in `cargo bench --bench parse` (criterion drops the results after timing
//! them); without it each result is freed before the next parse, whose points reuse its memory.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(path), Some(Ok(times))) = (args.first(), args.get(1).map(|t| t.parse::<usize>()))
    else {
        eprintln!("usage: parse_text FILE TIMES [keep]");
        return ExitCode::from(2);
    };
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(err) => {
            eprintln!("{path}: {err}");
            return ExitCode::FAILURE;
        }
    };
    // One thread: `parse_points` parses sequentially when rayon has fewer than two.
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
        Ok(pool) => pool,
        Err(err) => {
            eprintln!("no thread pool: {err}");
            return ExitCode::FAILURE;
        }
    };
    let keep = args.get(2).is_some_and(|a| a == "keep");
    let mut kept = Vec::new();
    let mut count = 0;
    for _ in 0..times {
        match pool.install(|| condt_io::parse_points(&text, path)) {
            Ok(points) => {
                count = points.len();
                if keep {
                    kept.push(points);
                }
            }
            Err(err) => {
                eprintln!("{err}");
                return ExitCode::FAILURE;
            }
        }
    }
    println!("{count}");
    ExitCode::SUCCESS
}
