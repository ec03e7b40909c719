//! Triangulation benchmarks: condt against spade's `bulk_load` and delaunator on the same inputs,
//! so that ratios come from one run, and against condt's own spatial sort of the same points
//! (`hilbert_sort`), the cost floor any insertion-order triangulator pays. Single-threaded
//! throughout (condt and its sort run inside a one-thread rayon pool), except `condt_parallel`:
//! condt on rayon's global pool, which builds a set of 65,536 points or more in two halves at
//! once (the same triangulation).
//!
//! Run all: `cargo bench --bench triangulate`; one group: `cargo bench --bench triangulate -- uniform_1M`.

#[path = "../../condt/tests/common/mod.rs"]
mod common;

use condt::Point;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, SamplingMode};
use spade::Triangulation as _;
use std::hint::black_box;
use std::time::Duration;

fn inputs() -> Vec<(&'static str, Vec<Point>)> {
    let offset = |p: Point| Point::new(p.x + 1e6, p.y + 1e6);
    vec![
        ("uniform_10k", common::uniform(10_000, 1)),
        ("uniform_100k", common::uniform(100_000, 2)),
        ("uniform_1M", common::uniform(1_000_000, 3)),
        // The input of curve reconstruction: 200 random ellipses, 5,000 points each, jitter 1e-6.
        ("ellipses_1M", common::on_ellipses(1_000_000, 200, 1e-6, 4)),
        ("clustered_1M", common::clustered(1_000_000, 7)),
        ("grid_1M", common::grid(1000, 5)),
        (
            "uniform_offset_1e6_1M",
            common::uniform(1_000_000, 6)
                .into_iter()
                .map(offset)
                .collect(),
        ),
    ]
}

fn triangulators(c: &mut Criterion) {
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for (name, points) in inputs() {
        // Every input is checked once before it is timed: a fast wrong mesh is no result.
        let tri = condt::triangulate(&points).unwrap();
        if let Err(violation) = tri.validate() {
            panic!("{name}: the triangulation is not valid: {violation:?}");
        }
        drop(tri);
        let mut group = c.benchmark_group(name);
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .sampling_mode(SamplingMode::Flat);
        // Every routine is timed without freeing its result: iter_batched (spade) never times the
        // drop, so the others use iter_with_large_drop.
        group.bench_function("condt", |b| {
            one_thread.install(|| {
                b.iter_with_large_drop(|| condt::triangulate(black_box(&points)).unwrap())
            })
        });
        group.bench_function("condt_parallel", |b| {
            b.iter_with_large_drop(|| condt::triangulate(black_box(&points)).unwrap())
        });

        let spade_points: Vec<spade::Point2<f64>> = points
            .iter()
            .map(|p| spade::Point2::new(p.x, p.y))
            .collect();
        group.bench_function("spade_bulk_load", |b| {
            b.iter_batched(
                || spade_points.clone(),
                |pts| spade::DelaunayTriangulation::<spade::Point2<f64>>::bulk_load(pts).unwrap(),
                BatchSize::LargeInput,
            )
        });

        let delaunator_points: Vec<delaunator::Point> = points
            .iter()
            .map(|p| delaunator::Point { x: p.x, y: p.y })
            .collect();
        group.bench_function("delaunator", |b| {
            b.iter_with_large_drop(|| delaunator::triangulate(black_box(&delaunator_points)))
        });

        // The yardstick: condt's spatial sort alone (input check, BRIO rounds, Hilbert order).
        group.bench_function("hilbert_sort", |b| {
            one_thread.install(|| {
                b.iter_with_large_drop(|| {
                    condt::Triangulation::insertion_order(black_box(&points)).unwrap()
                })
            })
        });
        group.finish();
    }
}

criterion_group!(benches, triangulators);
criterion_main!(benches);
