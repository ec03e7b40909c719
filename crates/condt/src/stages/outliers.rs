//! Stage 3, outlier removal (Algorithm 3).
//!
//! Owns: the interquartile-range rule on squared edge lengths, and its spacing floor (beyond the
//! paper); it may not touch the triangulation.
//!
//! With the sorted squared lengths `s` of the `n` edges, `T = Q3 + k (Q3 - Q1)`, `Q1 = s[n/4]`,
//! `Q3 = s[3n/4]` (`k = 1.7` by default). The filter applies only when some vertex has every edge
//! longer than twice the threshold taken as a length, `|e| > 2 √T`; it then keeps the edges of
//! squared length not above `T`. The paper compares plain lengths with `2 T`, mixing units:
//! `docs/condt.md`, notes 5 and 6.
//!
//! **Spacing floor** ([`Params::iqr_floor`](crate::Params::iqr_floor), on by default): the cut
//! keeps every edge up to [`FLOOR_RATIO`] times the median edge; whether the rule fires is still
//! decided on `T`. Why: `T` scales with the spread of the lengths, which evenly spaced samples
//! (fonts, maps, resampled outlines) hardly have, so it cuts straight stretches spaced a few per
//! cent wider than the rest (docs/condt.md, *The spacing floor*).

use super::Outcome;
use crate::adjacency::{collect_exact, Edge};
use crate::triangulate::Triangulation;
use alloc::vec;
use alloc::vec::Vec;

/// The floor's ratio to the median edge. Reason: a tool spacing points evenly at `h` splits each
/// segment into a whole number of pieces, rounded, so they reach `3h/2`; the median edge is about
/// `h`, and a curve edge even with a quarter of the edges outliers' (the quartiles' premise).
pub(crate) const FLOOR_RATIO: f64 = 1.5;

/// Algorithm 3's parameters: the factor `k` (checked by the caller: finite, `>= 0`) and whether
/// the cut has the spacing floor.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct IqrRule {
    pub(crate) factor: f64,
    pub(crate) floor: bool,
}

/// The rule's two thresholds on squared lengths.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Thresholds {
    /// Algorithm 3's `T`: the rule fires when some vertex has every edge above `4 T`.
    pub(crate) fire: f64,
    /// Edges above it are cut when the rule fires: `T`, or with the floor the larger of `T` and
    /// `FLOOR_RATIO²` times the median squared length.
    pub(crate) cut: f64,
}

/// The thresholds on the squared lengths `lengths2` (not empty), `Q3 = s[min(3n/4, n - 1)]`, the
/// median `s[n/2]`: the one place they are computed (for repairing again and explanations too);
/// the list, no longer needed, is the scratch space.
pub(crate) fn iqr_thresholds_of(lengths2: Vec<f64>, rule: IqrRule) -> Thresholds {
    let n = lengths2.len();
    let upper = (3 * n / 4).min(n - 1);
    // The quartiles of the sorted list, without sorting it: selections, each among the values the
    // one before put below it. They select integer keys in `f64::total_cmp`'s order (the same
    // values, compared faster), in the lengths' own list.
    let mut keys: Vec<i64> = lengths2.into_iter().map(total_order_key).collect();
    let q3 = total_order_key_value(*keys.select_nth_unstable(upper).1);
    let (q1, median) = if n / 4 < upper {
        let below_q3 = &mut keys[..upper];
        let median = if n / 2 < upper {
            total_order_key_value(*below_q3.select_nth_unstable(n / 2).1)
        } else {
            q3
        };
        // n / 4 < n / 2 here (n >= 2), and n / 4 < upper.
        let below_median = &mut below_q3[..(n / 2).min(upper)];
        let q1 = total_order_key_value(*below_median.select_nth_unstable(n / 4).1);
        (q1, median)
    } else {
        (q3, q3) // a single edge
    };
    let fire = q3 + rule.factor * (q3 - q1);
    let cut = if rule.floor {
        fire.max(FLOOR_RATIO * FLOOR_RATIO * median)
    } else {
        fire
    };
    Thresholds { fire, cut }
}

/// An integer that orders as `x` does under `f64::total_cmp` (which compares these keys).
#[inline]
fn total_order_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

/// The `f64` of a [`total_order_key`] (the map is its own inverse).
#[inline]
fn total_order_key_value(key: i64) -> f64 {
    f64::from_bits((key ^ (((key >> 63) as u64) >> 1) as i64) as u64)
}

/// Algorithm 3 on `edges`; unchanged unless fired.
pub(crate) fn remove_outliers(tri: &Triangulation, edges: &[Edge], rule: IqrRule) -> Outcome {
    let length2 = |k: usize| {
        let [a, b] = edges[k];
        tri.vertex_point(a).dist2(tri.vertex_point(b))
    };
    let lengths: Vec<f64> = (0..edges.len()).map(length2).collect();
    let ends = |[a, b]: Edge| [a.index(), b.index()];
    // The lengths are the thresholds' scratch space, then measured again as read (memory: one
    // list of lengths beside the stage's input and output, not two).
    Outcome::from(iqr_cut_of(
        edges,
        ends,
        lengths,
        length2,
        tri.num_points(),
        rule,
    ))
}

/// The edges Algorithm 3 keeps of `edges` (ends by `ends`, below `vertex_count`; squared lengths
/// `lengths`), `None` unless it fires: the one implementation of the rule, for the stage and for
/// edges gathered from tiles ([`crate::remove_gathered_outliers`]).
pub(crate) fn iqr_cut<E: Copy>(
    edges: &[E],
    ends: impl Fn(E) -> [usize; 2],
    lengths: &[f64],
    vertex_count: usize,
    rule: IqrRule,
) -> Option<Vec<E>> {
    let length2 = |k: usize| lengths[k];
    iqr_cut_of(edges, ends, lengths.to_vec(), length2, vertex_count, rule)
}

/// [`iqr_cut`] of squared lengths the caller no longer needs (their list is the thresholds'
/// scratch space, in any order after), reading the `k`-th edge's again as `length2(k)`.
fn iqr_cut_of<E: Copy>(
    edges: &[E],
    ends: impl Fn(E) -> [usize; 2],
    lengths: Vec<f64>,
    length2: impl Fn(usize) -> f64,
    vertex_count: usize,
    rule: IqrRule,
) -> Option<Vec<E>> {
    if lengths.is_empty() {
        return None;
    }
    let n = lengths.len();
    let upper = (3 * n / 4).min(n - 1);
    // With `factor >= 0`, T >= Q3: no edge exceeds 4T when at most `upper` lengths lie below a
    // quarter of the longest (the longest is then within 4 Q3). A count, not a selection.
    let longest = lengths.iter().copied().fold(0.0, f64::max);
    let below = lengths.iter().filter(|&&l| 4.0 * l < longest).count();
    if below <= upper {
        return None;
    }
    let Thresholds { fire, cut } = iqr_thresholds_of(lengths, rule);
    // A vertex all of whose edges exceed the bound, |e| > 2 √T: a point tied in only by long
    // edges. Per vertex, bit 0 records an edge and bit 1 an edge within the bound.
    let mut seen = vec![0u8; vertex_count];
    for (k, &edge) in edges.iter().enumerate() {
        let mark = 1 | (u8::from(length2(k) <= 4.0 * fire) << 1);
        let [a, b] = ends(edge);
        seen[a] |= mark;
        seen[b] |= mark;
    }
    if !seen.contains(&1) {
        return None;
    }
    drop(seen);
    // Not above T: with a perfectly uniform sample IQR = 0 and every edge equals T exactly.
    Some(collect_exact(
        edges.len(),
        edges
            .iter()
            .enumerate()
            .filter(|&(k, _)| length2(k) <= cut)
            .map(|(_, &edge)| edge),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::ordered;
    use crate::mesh::VertexId;
    use crate::{triangulate, Point};

    /// Ten unit edges along a line (so IQR = 0 and T = 1), plus a vertex at `(5, gap)` tied to
    /// the line by two edges of length about `gap`.
    fn line_and_lone_point(gap: f64) -> (Triangulation, Vec<Edge>) {
        let mut pts: Vec<Point> = (0..11).map(|i| Point::new(i as f64, 0.0)).collect();
        pts.push(Point::new(5.0, gap));
        pts.push(Point::new(5.0 + 1e-9, 0.0)); // so the lone point has two nearest line points
        let tri = triangulate(&pts).unwrap();
        let v = |i: u32| tri.vertex(i as usize);
        let mut edges: Vec<Edge> = (0..10).map(|i| ordered(v(i), v(i + 1))).collect();
        edges.push(ordered(v(5), v(11)));
        edges.push(ordered(v(11), v(12)));
        (tri, edges)
    }

    /// The rule as the module comment states it, by sorting: the reference for the selections
    /// and the counting shortcut.
    fn by_sorting(tri: &Triangulation, edges: &[Edge], rule: IqrRule) -> (bool, Vec<Edge>) {
        let length2 = |&[a, b]: &Edge| tri.vertex_point(a).dist2(tri.vertex_point(b));
        let mut sorted: Vec<f64> = edges.iter().map(length2).collect();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let (q1, q3) = (sorted[n / 4], sorted[(3 * n / 4).min(n - 1)]);
        let threshold = q3 + rule.factor * (q3 - q1);
        let floor = FLOOR_RATIO * FLOOR_RATIO * sorted[n / 2];
        let cut = if rule.floor {
            threshold.max(floor)
        } else {
            threshold
        };
        let lone = tri.vertices().any(|v| {
            let mut incident = edges.iter().filter(|e| e.contains(&v)).peekable();
            incident.peek().is_some() && incident.all(|e| length2(e) > 4.0 * threshold)
        });
        let kept = edges
            .iter()
            .filter(|e| !lone || length2(e) <= cut)
            .copied()
            .collect();
        (lone, kept)
    }

    #[test]
    fn agrees_with_sorting_on_random_graphs() {
        let mut rng = crate::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let mut random = |bound: u64| rng.below(bound);
        let (mut applied, mut not_applied) = (0, 0);
        for round in 0..400 {
            // A unit-spaced cluster and, in some rounds, a few points far out.
            let far = if round % 2 == 0 { random(4) } else { 0 };
            let mut pts: Vec<Point> = (0..30)
                .map(|_| Point::new(random(40) as f64 / 8.0, random(40) as f64 / 8.0))
                .collect();
            pts.extend((0..far).map(|k| Point::new(20.0 + 7.0 * k as f64, -9.0)));
            let tri = triangulate(&pts).unwrap();
            let v = |i: u64| tri.vertex(i as usize);
            let mut edges: Vec<Edge> = Vec::new();
            for _ in 0..1 + random(40) {
                let (a, b) = (v(random(pts.len() as u64)), v(random(pts.len() as u64)));
                if a != b && !edges.contains(&ordered(a, b)) {
                    edges.push(ordered(a, b));
                }
            }
            if edges.is_empty() {
                continue;
            }
            let factor = [0.0, 0.5, 1.7, 3.0][round % 4];
            let rule = IqrRule {
                factor,
                floor: round % 8 >= 4,
            };
            let (lone, kept) = by_sorting(&tri, &edges, rule);
            let filtered = remove_outliers(&tri, &edges, rule);
            assert_eq!(filtered.edges.is_some(), lone, "{edges:?}, {rule:?}");
            // The same rule on edges given as index pairs with their squared lengths, as tiles
            // gather them.
            let length2 = |&[a, b]: &Edge| tri.vertex_point(a).dist2(tri.vertex_point(b));
            let lengths: Vec<f64> = edges.iter().map(length2).collect();
            let pairs: Vec<[usize; 2]> = edges.iter().map(|e| e.map(VertexId::index)).collect();
            let gathered = iqr_cut(&pairs, |e| e, &lengths, tri.num_points(), rule);
            let kept_pairs: Vec<[usize; 2]> = kept.iter().map(|e| e.map(VertexId::index)).collect();
            assert_eq!(gathered, lone.then_some(kept_pairs), "{edges:?}, {rule:?}");
            assert_eq!(filtered.edges.unwrap_or(edges), kept);
            applied += usize::from(lone);
            not_applied += usize::from(!lone);
        }
        assert!(applied > 40 && not_applied > 40, "{applied} {not_applied}");
    }

    const PAPER: IqrRule = IqrRule {
        factor: 1.7,
        floor: false,
    };

    #[test]
    fn triggers_only_when_every_edge_of_a_vertex_exceeds_twice_the_threshold_length() {
        // T = 1 (IQR 0): the bound is |e| > 2.
        let (tri, edges) = line_and_lone_point(1.9);
        assert!(
            remove_outliers(&tri, &edges, PAPER).edges.is_none(),
            "|e| = 1.9 <= 2: no outlier"
        );
        let (tri, edges) = line_and_lone_point(2.1);
        let filtered = remove_outliers(&tri, &edges, PAPER);
        assert!(filtered.edges.is_some(), "|e| = 2.1 > 2: an outlier");
        // Every unit edge survives (it equals T), the two long ones go.
        let kept = filtered.edges.expect("applied");
        assert_eq!(kept.len(), 10);
        assert!(kept.iter().all(|e| !e.contains(&tri.vertex(11))));
    }

    /// An evenly spaced line (unit edges, IQR 0, so T = 1) with three edges 4 % longer,
    /// and a point 3 away tied to it: the rule fires on the far point either way; without the
    /// floor it also cuts the stretch, with it only the far point's edges.
    #[test]
    fn the_floor_keeps_a_slightly_wider_stretch_and_still_cuts_an_outlier() {
        let mut pts: Vec<Point> = (0..=20).map(|i| Point::new(i as f64, 0.0)).collect();
        for p in &mut pts[18..] {
            p.x = 17.0 + (p.x - 17.0) * 1.04;
        }
        pts.push(Point::new(7.0, 3.0));
        let tri = triangulate(&pts).unwrap();
        let v = |i: usize| tri.vertex(i);
        let mut edges: Vec<Edge> = (0..20).map(|i| ordered(v(i), v(i + 1))).collect();
        edges.extend([ordered(v(7), v(21)), ordered(v(6), v(21))]);
        let x = |w: VertexId| tri.vertex_point(w).x;
        let wide = |e: &Edge| !e.contains(&v(21)) && x(e[0]).min(x(e[1])) > 16.9;
        let cut = |floor| {
            let rule = IqrRule { floor, ..PAPER };
            let kept = remove_outliers(&tri, &edges, rule).edges.expect("fires");
            let lost: Vec<Edge> = edges
                .iter()
                .filter(|e| !kept.contains(e))
                .copied()
                .collect();
            lost
        };
        let (paper, floored) = (cut(false), cut(true));
        assert_eq!(paper.iter().filter(|e| wide(e)).count(), 3, "{paper:?}");
        assert_eq!(floored, [ordered(v(7), v(21)), ordered(v(6), v(21))]);
    }

    /// The thresholds by the module comment's definition, computed by sorting, for every count
    /// from a single edge up: the stage's counting shortcut returns before the quartiles under
    /// five edges, but repairing again, the explanations and the tiles take them of any list.
    #[test]
    fn the_rule_on_gathered_edges_does_not_depend_on_the_scale() {
        // A chain of nine equal edges and a tenth, ten times as long, to a point it alone ties
        // in: every other length is Q1 = Q3, so the IQR is 0, the long edge alone exceeds the
        // threshold and its far end has no edge within the bound: the rule fires and cuts it.
        // The same at every scale (its quick count of short edges once compared with a constant
        // where it means a ratio: mutation testing's survivors `4.0 + l` and `4.0 / l`).
        let edges: Vec<[usize; 2]> = (0..10).map(|i| [i, i + 1]).collect();
        for scale in [1e-6, 1e-2, 1.0, 1e2, 1e6] {
            let mut lengths2 = vec![0.01 * scale; 9];
            lengths2.push(scale);
            let kept = iqr_cut(&edges, |e| e, &lengths2, 11, PAPER);
            assert_eq!(kept.as_deref(), Some(&edges[..9]), "scale {scale}");
        }
    }

    #[test]
    fn thresholds_agree_with_sorting_for_every_count() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let rules = [0.0, 1.7].map(|factor| [false, true].map(|floor| IqrRule { factor, floor }));
        for n in 1..=24 {
            for round in 0..20 {
                // Ties in some rounds (four values), all distinct in the others.
                let lengths2: Vec<f64> = (0..n)
                    .map(|_| match round % 2 {
                        0 => rng.below(4) as f64,
                        _ => 10.0 * rng.unit(),
                    })
                    .collect();
                let mut sorted = lengths2.clone();
                sorted.sort_by(f64::total_cmp);
                let (q1, median, q3) = (sorted[n / 4], sorted[n / 2], sorted[3 * n / 4]);
                for rule in rules.into_iter().flatten() {
                    let fire = q3 + rule.factor * (q3 - q1);
                    let cut = match rule.floor {
                        true => fire.max(1.5 * 1.5 * median),
                        false => fire,
                    };
                    let got = iqr_thresholds_of(lengths2.clone(), rule);
                    assert_eq!(got, Thresholds { fire, cut }, "{lengths2:?}, {rule:?}");
                }
            }
        }
    }

    /// The selection keys order as `f64::total_cmp` does and give the same bits back, for
    /// negative values, zeros of both signs, infinities and NaNs too: squared lengths are never
    /// negative, so the stage alone cannot tell a key that is wrong on the sign bit.
    #[test]
    fn order_keys_order_as_total_cmp_and_give_the_value_back() {
        let values = [
            f64::NEG_INFINITY,
            -f64::MAX,
            -1.0 - f64::EPSILON,
            -1.0,
            -f64::MIN_POSITIVE,
            -1e-310,
            -0.0,
            0.0,
            1e-310,
            f64::MIN_POSITIVE,
            1.0 / 3.0,
            1.0 + f64::EPSILON,
            3.0,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for x in values {
            let back = total_order_key_value(total_order_key(x));
            assert_eq!(back.to_bits(), x.to_bits(), "{x}");
            for y in values {
                let keys = total_order_key(x).cmp(&total_order_key(y));
                assert_eq!(keys, x.total_cmp(&y), "{x} {y}");
            }
        }
    }
}
