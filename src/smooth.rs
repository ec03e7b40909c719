//! Smoothing noisy positions before the reconstruction (not in the paper; off by default;
//! [`Params::smooth`](crate::Params::smooth)).
//!
//! Owns: one rule that moves points to smoothed positions read off a first reconstruction. It
//! reads the first pass's triangulation and final graph; it returns new positions, one per input
//! position, and touches neither.
//!
//! Why: at 1-3 % noise some true edges of a curve are not Delaunay edges of the noisy points (a
//! sample pushed off the curve lies in every empty circle through the two neighbours it sits
//! between), so no stage that chooses among Delaunay edges can keep them. Moved back towards the
//! curve, the samples have a Delaunay triangulation that holds those edges again; the stages then
//! run on it, and the edges they choose are still between input positions.
//!
//! Rule. A point with exactly two edges in the first pass's final graph, whose two edges meet at
//! an angle of at least [`SMOOTH_ANGLE`], moves to `(a + 2p + b) / 4` (`a`, `b` its neighbours):
//! one step of the umbrella (Laplacian) operator with weight one half, which halves the distance
//! of `p` to its neighbours' chord and moves it along the curve towards the middle of them.
//! Every other point stays where it is: a point with one, three or more edges (an end, a
//! crossing, a branch) or none (an outlier) has no consistent curve neighbourhood, and a point
//! at a sharp corner (angle below [`SMOOTH_ANGLE`]) would be rounded off.

use crate::adjacency::{CurveGraph, Edge};
use crate::geometry::Point;
use crate::triangulate::Triangulation;
use alloc::vec::Vec;

/// The smallest angle, at a point, between its two edges for the point to move: 90°. Reason: a
/// sharp corner of the suite is under 60° and noise of a few per cent of the spacing tilts each
/// edge by a few degrees, so nothing near a corner reaches a right angle, while a smooth curve
/// sampled densely enough for the proximity graph (at least about five samples per quarter turn)
/// bends by under 20° per sample.
pub(crate) const SMOOTH_ANGLE_COS: f64 = 0.0;

fn env_f64(name: &str, default: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        if let Ok(v) = std::env::var(name) {
            if let Ok(x) = v.parse() {
                return x;
            }
        }
    }
    let _ = name;
    default
}

/// The smoothed position of every input position (see the module comment), and how many moved.
pub(crate) fn smoothed_positions(tri: &Triangulation, edges: &[Edge]) -> (Vec<Point>, usize) {
    let n = tri.num_points();
    let graph = CurveGraph::new(n, edges);
    let cos_limit = env_f64("CONDT_SMOOTH_COS", SMOOTH_ANGLE_COS);
    let weight = env_f64("CONDT_SMOOTH_W", 0.5);
    let iterations = env_f64("CONDT_SMOOTH_ITER", 1.0) as usize;
    let mu = env_f64("CONDT_SMOOTH_MU", 0.0);
    let mut now: Vec<Point> = (0..n).map(|i| tri.point(i)).collect();
    let mut moved = 0;
    let sweeps = iterations.max(1) * if mu != 0.0 { 2 } else { 1 };
    for sweep in 0..sweeps {
        let weight = if mu != 0.0 && sweep % 2 == 1 { mu } else { weight };
        let before = now.clone();
        moved = 0;
        for i in 0..n {
            let v = tri.vertex(i);
            if graph.degree(v) != 2 {
                continue;
            }
            let [x, y] = graph.first_two(v);
            if env_f64("CONDT_SMOOTH_INNER", 0.0) > 0.0 && (graph.degree(x) != 2 || graph.degree(y) != 2) {
                continue;
            }
            let p = before[i];
            let a = before[tri.input_of(x)];
            let b = before[tri.input_of(y)];
            let (ux, uy) = (a.x - p.x, a.y - p.y);
            let (wx, wy) = (b.x - p.x, b.y - p.y);
            let la = (ux * ux + uy * uy).sqrt();
            let lb = (wx * wx + wy * wy).sqrt();
            if !(la > 0.0 && lb > 0.0) {
                continue;
            }
            let cos = (ux * wx + uy * wy) / (la * lb);
            // The angle at p is at least the limit when its cosine is at most the limit's.
            if cos > cos_limit {
                continue;
            }
            let mid = Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
            now[i] = Point::new(
                p.x + weight * (mid.x - p.x),
                p.y + weight * (mid.y - p.y),
            );
            moved += 1;
        }
    }
    (now, moved)
}
