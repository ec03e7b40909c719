//! Timing harness for `score` on the adversarial truth of issue 29, defect 6: a chain through
//! uniform random points in a random order, so that its segments are long and cross one another.
//!
//! `cargo bench -p condt-eval --bench score_chain -- [EDGES...]` (default 100000) prints, for
//! each size, the time of one `score` call against two outputs: another random chain through
//! the same points (long edges, samples anywhere in the square) and a boustrophedon path
//! (short edges, the shape of a reconstruction's output). No timing is asserted anywhere.

use condt::Point;
use condt_eval::score::score;
use std::time::Instant;

/// Marsaglia's xorshift64, as the unit tests use.
struct Xorshift(u64);

impl Xorshift {
    fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn shuffle(&mut self, v: &mut [usize]) {
        for i in (1..v.len()).rev() {
            let j = (self.next_u64() % (i as u64 + 1)) as usize;
            v.swap(i, j);
        }
    }
}

fn chain(order: &[usize]) -> Vec<[usize; 2]> {
    order.windows(2).map(|w| [w[0], w[1]]).collect()
}

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![100_000]
    } else {
        sizes
    };
    for edges in sizes {
        let mut rng = Xorshift(0x9e37_79b9_7f4a_7c15);
        let n = edges + 1;
        let points: Vec<Point> = (0..n).map(|_| Point::new(rng.unit(), rng.unit())).collect();
        let mut order: Vec<usize> = (0..n).collect();
        rng.shuffle(&mut order);
        let truth = chain(&order);
        rng.shuffle(&mut order);
        let random_output = chain(&order);
        // Boustrophedon: horizontal strips of about two points per strip height.
        let strips = ((n as f64 / 2.0).sqrt().ceil() as usize).max(1);
        let mut by_strip: Vec<usize> = (0..n).collect();
        let key = |i: usize| {
            let s = ((points[i].y * strips as f64) as usize).min(strips - 1);
            let x = if s % 2 == 0 {
                points[i].x
            } else {
                -points[i].x
            };
            (s, x)
        };
        by_strip.sort_by(|&a, &b| key(a).partial_cmp(&key(b)).unwrap());
        let short_output = chain(&by_strip);
        for (name, output) in [
            ("random chain", &random_output),
            ("short path", &short_output),
        ] {
            let start = Instant::now();
            let s = score(&points, output, &truth).expect("a valid truth");
            let seconds = start.elapsed().as_secs_f64();
            println!(
                "{edges} edges, output {name}: {seconds:.3} s (max {:?}, rms {:?}, tp {})",
                s.max_distance, s.rms_distance, s.true_positives
            );
        }
    }
}
