//! Reading the plain point format on one thread: 1M points as `x y` lines held in memory, parsed
//! by `condt_io::parse_points` inside a one-thread rayon pool (so the parallel reader stays
//! sequential and the figure is one core's). Two texts: 17-digit coordinates in [0, 1) as
//! `scripts/scale.py` writes them (shortest round-trip form), and the same points with six
//! decimals.
//!
//! Run: `cargo bench --bench parse`.

#[path = "../../condt/tests/common/mod.rs"]
mod common;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Duration;

fn text(points: &[condt::Point], decimals: Option<usize>) -> String {
    let mut text = String::with_capacity(points.len() * 40);
    for p in points {
        match decimals {
            None => writeln!(text, "{} {}", p.x, p.y),
            Some(d) => writeln!(text, "{:.d$} {:.d$}", p.x, p.y),
        }
        .unwrap();
    }
    text
}

fn parse(c: &mut Criterion) {
    let points = common::uniform(1_000_000, 3);
    // One thread: `parse_points` asks rayon how many threads it has and parses sequentially
    // below two.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut group = c.benchmark_group("parse_1M");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .sampling_mode(SamplingMode::Flat);
    for (name, decimals) in [("digits_17", None), ("decimals_6", Some(6))] {
        let text = text(&points, decimals);
        // A parse that reads other numbers is no result.
        let parsed = condt_io::parse_points(&text, "bench").unwrap();
        assert_eq!(parsed.len(), points.len());
        if decimals.is_none() {
            assert_eq!(parsed, points);
        }
        group.bench_function(name, |b| {
            b.iter_with_large_drop(|| {
                pool.install(|| condt_io::parse_points(black_box(&text), "bench").unwrap())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, parse);
criterion_main!(benches);
