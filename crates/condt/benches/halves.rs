//! The construction in two halves (`src/triangulate/halves.rs`), timed through the public
//! `triangulate`, which cuts a set of 65,536 points or more by a vertical line, builds the halves
//! (at once on rayon's threads with the `parallel` feature) and stitches them.
//!
//! - `halves_1M/*`: the sets the stitch was reviewed on (uniform, 200 ellipses, a 1000 x 1000
//!   grid), on one thread (the halves one after the other: the cost of the cut and the stitch
//!   against the one-piece construction the crate's docs measure) and on rayon's pool (the
//!   speed-up the halves are for).
//! - `threshold/*`: uniform sets one point below the cut (built in one piece by the sequential
//!   insertion, the reference the halves must equal) and at it (built in two halves), on one
//!   thread and on rayon's pool.
//!
//! Whether a set was stitched or fell back to one piece is not visible here (the result is the
//! same); the unit tests of `halves.rs` assert that these kinds of sets stitch.
//!
//! `cargo bench -p condt --bench halves`

use condt::{triangulate, Point};
use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use std::hint::black_box;
use std::time::Duration;

/// The size from which `triangulate` builds a set in two halves.
const SPLIT_MIN: usize = 1 << 16;

/// A xorshift generator: the inputs are the same on every run.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn uniform(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = Rng(seed);
    (0..n).map(|_| Point::new(rng.unit(), rng.unit())).collect()
}

/// `n` points on 200 ellipses in a 20 x 10 array, in no order.
fn ellipses(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|k| {
            let e = (k % 200) as f64;
            let (cx, cy) = ((e % 20.0) * 3.0, (e / 20.0).floor() * 2.0);
            let t = rng.unit() * std::f64::consts::TAU;
            Point::new(cx + 1.2 * t.cos(), cy + 0.7 * t.sin())
        })
        .collect()
}

fn grid(side: usize) -> Vec<Point> {
    (0..side * side)
        .map(|i| Point::new((i % side) as f64, (i / side) as f64))
        .collect()
}

fn bench_pair(
    c: &mut Criterion,
    group: &str,
    inputs: &[(String, Vec<Point>)],
    one_thread: &rayon::ThreadPool,
) {
    let mut group = c.benchmark_group(group);
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .sampling_mode(SamplingMode::Flat);
    for (name, points) in inputs {
        // Checked once before it is timed: a fast wrong mesh is no result.
        let tri = triangulate(points).unwrap();
        if let Err(violation) = tri.validate() {
            panic!("{name}: the triangulation is not valid: {violation:?}");
        }
        drop(tri);
        group.bench_function(format!("{name}/one_thread"), |b| {
            one_thread
                .install(|| b.iter_with_large_drop(|| triangulate(black_box(points)).unwrap()))
        });
        group.bench_function(format!("{name}/parallel"), |b| {
            b.iter_with_large_drop(|| triangulate(black_box(points)).unwrap())
        });
    }
    group.finish();
}

fn halves(c: &mut Criterion) {
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let large = [
        ("uniform".to_string(), uniform(1_000_000, 5)),
        ("ellipses".to_string(), ellipses(1_000_000, 6)),
        ("grid".to_string(), grid(1000)),
    ];
    bench_pair(c, "halves_1M", &large, &one_thread);
    let around = [
        (
            format!("one_piece_{}", SPLIT_MIN - 1),
            uniform(SPLIT_MIN - 1, 7),
        ),
        (format!("halves_{SPLIT_MIN}"), uniform(SPLIT_MIN, 7)),
    ];
    bench_pair(c, "threshold", &around, &one_thread);
}

criterion_group!(benches, halves);
criterion_main!(benches);
