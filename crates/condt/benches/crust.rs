//! A timing harness (no criterion: single runs of seconds): the Crust against NN-Crust on the
//! inputs where the Crust's second triangulation used to degrade (issue 29, defect 5): uniform
//! points, whose hull slivers have circumcentres far outside the set, and nearly collinear
//! points, whose circumcentres spread over many orders of magnitude. Prints, per input, the
//! best of three runs of `reconstruct` with each method and their ratio (target: below 5).
//!
//! `cargo bench -p condt --bench crust` (a size as argument, e.g. `-- 200000`, replaces the 1M
//! uniform points)

use condt::{reconstruct, Method, Params, Point};
use std::time::{Duration, Instant};

/// xorshift64*: reproducible coordinates in [0, 1).
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn uniform(n: usize) -> Vec<Point> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    (0..n).map(|_| Point::new(rng.unit(), rng.unit())).collect()
}

/// Points along the x axis, 1e-15 off it at most.
fn nearly_collinear(n: usize) -> Vec<Point> {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    (0..n)
        .map(|_| Point::new(rng.unit(), 1e-15 * rng.unit()))
        .collect()
}

fn best_of_three(points: &[Point], method: Method) -> (Duration, usize) {
    let params = Params::default().with_method(method);
    (0..3)
        .map(|_| {
            let start = Instant::now();
            let result = reconstruct(points, &params).unwrap();
            (start.elapsed(), result.edges().count())
        })
        .min()
        .unwrap()
}

fn main() {
    let size = std::env::args()
        .skip(1)
        .find_map(|a| a.parse::<usize>().ok())
        .unwrap_or(1_000_000);
    for (name, points) in [
        (format!("uniform {size}"), uniform(size)),
        (
            "nearly collinear 100000".to_string(),
            nearly_collinear(100_000),
        ),
    ] {
        let (nn, nn_edges) = best_of_three(&points, Method::NnCrust);
        let (crust, crust_edges) = best_of_three(&points, Method::Crust);
        println!(
            "{name}: NN-Crust {nn:.2?} ({nn_edges} edges), Crust {crust:.2?} ({crust_edges} edges), \
             Crust / NN-Crust {:.2}",
            crust.as_secs_f64() / nn.as_secs_f64()
        );
    }
}
