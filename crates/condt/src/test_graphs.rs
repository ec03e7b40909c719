//! Points with hand-drawn graphs that the unit tests of more than one module read (test builds
//! only).
//!
//! Owns: such fixtures, in one definition. Nothing in the library may use it.

use crate::geometry::Point;
use alloc::vec::Vec;

/// Two rows 0.8 apart, one apart along each: an open curve along the bottom row from (1, 0) to
/// x = 12, around a half circle below and back along the top row to (-0.2, 0.8), its two loose
/// ends (positions 0 and `curve_len - 1`); then a piece of six from `curve_len` on: the bottom
/// row's three samples left of its end and the top row's three right of its end, joined by a
/// chord across the rows (`curve_len`, `curve_len + 3`), as Algorithm 1 pairs samples at a
/// narrow tip. The points, the edges and `curve_len`; the tips stage's move gives the chord up
/// for the two ends' edges. For rule 4's tests, the stage's and the tiled one.
pub(crate) fn tip_piece_beside_a_curve() -> (Vec<Point>, Vec<[usize; 2]>, usize) {
    let mut pts: Vec<Point> = (0..12).map(|k| Point::new(1.0 + k as f64, 0.0)).collect();
    let (radius, from) = (12.0, libm::atan2(-0.4, 12.0));
    let steps = libm::ceil(core::f64::consts::PI * radius) as usize;
    pts.extend((1..steps).map(|k| {
        let t = from - core::f64::consts::PI * k as f64 / steps as f64;
        Point::new(radius * libm::cos(t), 0.4 + radius * libm::sin(t))
    }));
    pts.extend((0..12).rev().map(|k| Point::new(-0.2 - k as f64, 0.8)));
    let curve_len = pts.len();
    let mut pairs: Vec<[usize; 2]> = (0..curve_len - 1).map(|k| [k, k + 1]).collect();
    pts.extend((0..3).map(|k| Point::new(-(k as f64), 0.0)));
    pts.extend((0..3).map(|k| Point::new(0.8 + k as f64, 0.8)));
    let piece = curve_len;
    pairs.extend([[piece, piece + 1], [piece + 1, piece + 2]]);
    pairs.extend([[piece + 3, piece + 4], [piece + 4, piece + 5]]);
    pairs.push([piece, piece + 3]);
    (pts, pairs, curve_len)
}

/// A straight open curve of twelve unit-spaced samples along `y = 0` (positions 0 to 11), then a
/// hook: the loose end 12 at (12, 0) hangs from 13 at (12.6, 0.5), which 11 reached first; then a
/// piece of four from (13.6, 0.5) on, a spacing apart (positions 14 to 17). The points, the edges
/// and 14 (the curve's points). The hooks stage puts 12 back between 11 and 13 and joins 13 to
/// 14; gap closing joins nothing (12 faces back, 14 sees no loose end ahead), and the piece is
/// under a quarter of the points. For rule 4's tests, the stage's and the tiled one.
pub(crate) fn hooked_piece_beside_a_curve() -> (Vec<Point>, Vec<[usize; 2]>, usize) {
    let mut pts: Vec<Point> = (0..13).map(|k| Point::new(k as f64, 0.0)).collect();
    pts.push(Point::new(12.6, 0.5));
    pts.extend((0..4).map(|k| Point::new(13.6 + k as f64, 0.5)));
    let mut pairs: Vec<[usize; 2]> = (0..11).map(|k| [k, k + 1]).collect();
    pairs.extend([[11, 13], [12, 13], [14, 15], [15, 16], [16, 17]]);
    (pts, pairs, 14)
}

/// A comb: a straight curve of 31 unit-spaced samples along `y = 0` (positions 0 to 30), a short
/// tooth of eight samples at `x = 15` from `y = 1` up (positions 31 to 38) and two long teeth of
/// twenty at `x = 13` and `x = 17` (39 to 58, 59 to 78), each tooth a curve whose loose end lies
/// one spacing above the straight curve, facing it. The points, the edges and 31 (the short tooth's
/// end). The short tooth lies two spacings from the long ones along its whole length, so none of
/// its samples is apart and rule 4 alone would drop it; the junctions stage joins each tooth to the
/// straight curve. For rule 4's tests, the stage's and the tiled one.
pub(crate) fn comb_with_a_short_tooth() -> (Vec<Point>, Vec<[usize; 2]>, usize) {
    let mut pts: Vec<Point> = (0..=30).map(|x| Point::new(x as f64, 0.0)).collect();
    let mut pairs: Vec<[usize; 2]> = (0..30).map(|k| [k, k + 1]).collect();
    for (x, len) in [(15.0, 8), (13.0, 20), (17.0, 20)] {
        let first = pts.len();
        pts.extend((1..=len).map(|y| Point::new(x, y as f64)));
        pairs.extend((first..first + len - 1).map(|k| [k, k + 1]));
    }
    (pts, pairs, 31)
}

/// A circle of radius 10 sampled at 60 angles whose samples 15 to 26 zig-zag across it (0.5 in
/// and out, as noise at half a spacing leaves a stretch), the circle's edges missing at both
/// ends of that stretch: an open curve of the other 48 samples (positions 0 to 47, its loose
/// ends 0 and 47) and the stretch as a piece of its own (positions 48 to 59, in order along the
/// circle). The points, the edges and 48. The piece passes smoothly nowhere and stands apart
/// from the rest at its middle samples; gap closing joins its ends to the curve's. For the clump
/// stage's tests, the stage's and the tiled one.
pub(crate) fn zig_zag_piece_in_a_gap() -> (Vec<Point>, Vec<[usize; 2]>, usize) {
    let at = |k: usize, r: f64| {
        let t = core::f64::consts::TAU * k as f64 / 60.0;
        Point::new(r * libm::cos(t), r * libm::sin(t))
    };
    let mut pts: Vec<Point> = (27..60).chain(0..15).map(|k| at(k, 10.0)).collect();
    let curve_len = pts.len();
    let mut pairs: Vec<[usize; 2]> = (0..curve_len - 1).map(|k| [k, k + 1]).collect();
    pts.extend((15..27).map(|k| at(k, if k % 2 == 0 { 10.5 } else { 9.5 })));
    pairs.extend((curve_len..pts.len() - 1).map(|k| [k, k + 1]));
    (pts, pairs, curve_len)
}
