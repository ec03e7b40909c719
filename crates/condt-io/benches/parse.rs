//! Reading the plain point format on one thread: 1M points as `x y` lines held in memory, parsed
//! by `condt_io::parse_points` inside a one-thread rayon pool (so the parallel reader stays
//! sequential and the figure is one core's). Two texts: 17-digit coordinates in [0, 1) as
//! `scripts/scale.py` writes them (shortest round-trip form), and the same points with six
//! decimals.
//!
//! `numbers_1M` reads the same texts' 2M numbers alone, the line splitting shared, with each
//! decimal reader in question: the hand-written one of `src/decimal.rs` (included here by
//! path), `fast_float2::parse_partial` and `str::parse`. One run on the shared two-core
//! machine (medians): 17 digits 45.8 ms, 66.7 ms and 140 ms; six decimals 22.4 ms, 34.9 ms and
//! 87 ms. The hand-written reader stays for that margin (`src/decimal.rs` has the end-to-end
//! figure).
//!
//! Run: `cargo bench --bench parse`.

#[path = "../../condt/tests/common/mod.rs"]
mod common;
#[path = "../src/decimal.rs"]
// Its unit tests' imports too: cargo builds benches with `cfg(test)`, without the `#[test]`s.
#[allow(dead_code, unused_imports)]
mod decimal;
// What the unit tests inside `decimal.rs` use.
#[cfg(test)]
extern crate alloc;
#[cfg(test)]
#[path = "../../condt/src/test_rng.rs"]
#[allow(dead_code)]
mod test_rng;
#[cfg(test)]
mod geometry {
    pub use condt::Point;
}

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

/// The sum of the bits of every number of `text` (`x y` lines) read by `read`, which gets each
/// number with the rest of the text after it (as the points reader does), and gives the value
/// and the bytes it consumed.
fn read_numbers(text: &str, read: impl Fn(&[u8]) -> Option<(f64, usize)>) -> u64 {
    let bytes = text.as_bytes();
    let mut sum = 0u64;
    let mut at = 0;
    while at < bytes.len() {
        let (x, used) = read(&bytes[at..]).unwrap();
        at += used + 1;
        let (y, used) = read(&bytes[at..]).unwrap();
        at += used + 1;
        sum = sum.wrapping_add(x.to_bits()).wrapping_add(y.to_bits());
    }
    sum
}

fn hand_written(bytes: &[u8]) -> Option<(f64, usize)> {
    let (value, rest) =
        decimal::parse_prefix_short(bytes).or_else(|| decimal::parse_prefix_outlined(bytes))?;
    Some((value, bytes.len() - rest.len()))
}

fn fast_float2(bytes: &[u8]) -> Option<(f64, usize)> {
    fast_float2::parse_partial::<f64, _>(bytes).ok()
}

fn std_parse(bytes: &[u8]) -> Option<(f64, usize)> {
    let end = bytes
        .iter()
        .position(|&b| b == b' ' || b == b'\n')
        .unwrap_or(bytes.len());
    let token = std::str::from_utf8(&bytes[..end]).ok()?;
    Some((token.parse().ok()?, end))
}

fn parse(c: &mut Criterion) {
    let points = common::uniform(1_000_000, 3);
    // One thread: `parse_points` asks rayon how many threads it has and parses sequentially
    // below two.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let texts = [("digits_17", None), ("decimals_6", Some(6))].map(|(name, decimals)| {
        let text = text(&points, decimals);
        (name, decimals, text)
    });
    let mut group = c.benchmark_group("parse_1M");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .sampling_mode(SamplingMode::Flat);
    for (name, decimals, text) in &texts {
        // A parse that reads other numbers is no result.
        let parsed = condt_io::parse_points(text, "bench").unwrap();
        assert_eq!(parsed.len(), points.len());
        if decimals.is_none() {
            assert_eq!(parsed, points);
        }
        group.bench_function(*name, |b| {
            b.iter_with_large_drop(|| {
                pool.install(|| condt_io::parse_points(black_box(text), "bench").unwrap())
            })
        });
    }
    group.finish();

    let mut group = c.benchmark_group("numbers_1M");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .sampling_mode(SamplingMode::Flat);
    for (name, _, text) in &texts {
        // The three read the same bits.
        let expected = read_numbers(text, std_parse);
        assert_eq!(read_numbers(text, hand_written), expected);
        assert_eq!(read_numbers(text, fast_float2), expected);
        for (reader, read) in [
            (
                "hand_written",
                hand_written as fn(&[u8]) -> Option<(f64, usize)>,
            ),
            ("fast_float2", fast_float2),
            ("str_parse", std_parse),
        ] {
            group.bench_function(format!("{name}/{reader}"), |b| {
                b.iter(|| read_numbers(black_box(text), read))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, parse);
criterion_main!(benches);
