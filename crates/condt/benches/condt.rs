//! ConDT pipeline benchmarks: the triangulation, the stages after it, and the whole, on a
//! 10,000-point closed curve and on about 1M points along 200 closed curves (in curve order and
//! shuffled). Before the criterion
//! groups, a per-step breakdown (the median of 11 runs of `step_times`) is printed for each input.
//!
//! The curves carry noise of 1e-9 (measurement precision). Without it, a centred ellipse sampled
//! uniformly in arc length has its samples at exact antipodes, and every pair of neighbours with
//! their antipodes is nearly cocircular: a degenerate input that sends about 11 % of the
//! in-circle tests to exact arithmetic. `symmetric_ellipse_10k` keeps that worst case.
//!
//! `cargo bench --bench condt`

use condt::{reconstruct, reconstruct_triangulation, triangulate, Params, Point};
use condt_eval::sample::{sample, Sampling, Shape};
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, SamplingMode};
use std::time::Duration;

fn one_ellipse_10k(noise: f64) -> Vec<Point> {
    let ellipse = Shape::Ellipse {
        center: Point::new(0.0, 0.0),
        radii: (3.0, 2.0),
        rotation: 0.3,
    };
    let sampling = Sampling {
        noise,
        ..Sampling::new(0.00119)
    };
    let points = sample(&[ellipse], &sampling).unwrap().points;
    assert_eq!(points.len(), 10_000);
    points
}

fn ellipses_1m() -> Vec<Point> {
    let shapes: Vec<Shape> = (0..200)
        .map(|k| Shape::Ellipse {
            center: Point::new((k % 20) as f64 * 40.0, (k / 20) as f64 * 40.0),
            radii: (10.0 + (k % 7) as f64, 6.0 + (k % 5) as f64),
            rotation: k as f64 * 0.1,
        })
        .collect();
    sample(
        &shapes,
        &Sampling {
            noise: 1e-9,
            ..Sampling::new(0.00295)
        },
    )
    .unwrap()
    .points
}

/// The same points in a fixed pseudo-random order: unorganized input, as files usually are.
fn shuffled(mut points: Vec<Point>) -> Vec<Point> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for i in (1..points.len()).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        points.swap(i, (state % (i as u64 + 1)) as usize);
    }
    points
}

fn median(mut values: Vec<Duration>) -> Duration {
    values.sort();
    values[values.len() / 2]
}

/// Per-step wall-clock times of one run: triangulation, each stage in run order, curves.
fn step_times(points: &[Point], params: &Params) -> Vec<(String, Duration)> {
    let result = reconstruct(points, params).unwrap();
    let mut times = vec![("triangulation".to_string(), result.triangulation_time())];
    times.extend(
        result
            .stage_times()
            .map(|(stage, time)| (stage.key().to_string(), time)),
    );
    times.push(("curves".to_string(), result.curves_time()));
    // With smoothing passes, everything before the last pass (the first reconstruction
    // included) is cost after the result's triangulation too.
    let (passes, earlier) = result
        .smoothing()
        .map_or((0, Duration::ZERO), |s| (s.passes, s.earlier_passes));
    times.push((format!("smoothing passes ({passes})"), earlier));
    times
}

fn breakdown(name: &str, points: &[Point], params: &Params) {
    let runs: Vec<Vec<(String, Duration)>> = (0..11).map(|_| step_times(points, params)).collect();
    let medians: Vec<(String, Duration)> = (0..runs[0].len())
        .map(|k| {
            let label = runs[0][k].0.clone();
            (label, median(runs.iter().map(|run| run[k].1).collect()))
        })
        .collect();
    let tri = medians[0].1;
    let after: Duration = medians[1..].iter().map(|(_, t)| *t).sum();
    let listed: Vec<String> = medians.iter().map(|(l, t)| format!("{l} {t:?}")).collect();
    println!(
        "{name} ({} points, parallel = {}): {}; after/triangulation = {:.2}",
        points.len(),
        params.parallel,
        listed.join(", "),
        after.as_secs_f64() / tri.as_secs_f64()
    );
}

fn pipeline(c: &mut Criterion) {
    let inputs = [
        ("closed_curve_10k", one_ellipse_10k(1e-9)),
        ("symmetric_ellipse_10k", one_ellipse_10k(0.0)),
        ("curves_1M", ellipses_1m()),
        ("curves_1M_shuffled", shuffled(ellipses_1m())),
    ];
    for (name, points) in inputs {
        for parallel in [false, true] {
            breakdown(name, &points, &Params::default().with_parallel(parallel));
        }
        let mut group = c.benchmark_group(format!("condt_{name}"));
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .sampling_mode(SamplingMode::Flat);
        // The stages are measured against the triangulation on one thread; with the `parallel`
        // feature a set of 65,536 points or more is triangulated in two halves at once.
        let one_thread = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        group.bench_function("triangulation", |b| {
            one_thread.install(|| b.iter(|| triangulate(&points).unwrap()))
        });
        group.bench_function("triangulation_parallel", |b| {
            b.iter(|| triangulate(&points).unwrap())
        });
        for parallel in [false, true] {
            let params = Params::default().with_parallel(parallel);
            let label = if parallel { "parallel" } else { "sequential" };
            group.bench_function(format!("stages_after_triangulation_{label}"), |b| {
                b.iter_batched(
                    || triangulate(&points).unwrap(),
                    |tri| reconstruct_triangulation(tri, &params).unwrap(),
                    BatchSize::LargeInput,
                )
            });
            group.bench_function(format!("full_{label}"), |b| {
                b.iter(|| reconstruct(&points, &params).unwrap())
            });
        }
        group.finish();
    }
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
