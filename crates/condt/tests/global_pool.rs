//! The library starts rayon's global pool only for work that uses it: a run on fewer than
//! 65,536 points, or one inside the caller's own pool, leaves the caller free to build the
//! global pool as it wishes (an embedded review: a 12-point `triangulate` started one thread a
//! core, and the caller's `build_global` then failed). One test in its own file: the global pool
//! is the process's.
#![cfg(feature = "parallel")]

use condt::{reconstruct, triangulate, Method, Params, Point, Triangulation};

fn circle(n: usize) -> Vec<Point> {
    (0..n)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / n as f64;
            Point::new(t.cos(), t.sin())
        })
        .collect()
}

#[test]
fn small_runs_and_runs_in_the_callers_pool_start_no_global_pool() {
    // Scattered points too, so that smoothing passes and every stage run.
    let mut points = circle(200);
    points.extend((0..50).map(|k| Point::new((k % 7) as f64 * 0.3, (k / 7) as f64 * 0.3)));
    let tri = triangulate(&points).unwrap();
    let _ = Triangulation::insertion_order(&points).unwrap();
    let _ = tri.proximity_graph(Default::default()).unwrap();
    for method in [Method::ConDT, Method::NnCrust, Method::Crust] {
        let result = reconstruct(&points, &Params::default().with_method(method)).unwrap();
        let _ = result.provenance();
    }
    let _ = tri.crust().unwrap();
    // A large set inside a pool of the caller's own runs there.
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let large = circle(70_000);
    one.install(|| {
        let _ = reconstruct(&large, &Params::default()).unwrap();
    });
    assert!(
        rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build_global()
            .is_ok(),
        "the library started rayon's global pool"
    );
    assert!(condt::parallel_available());
}
