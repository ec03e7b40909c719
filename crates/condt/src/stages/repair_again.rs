//! Repairing again without the cut edges (not in the paper; on by default, off in
//! `Params::paper`), right after the IQR rule, when it fired.
//!
//! Owns: one rule. It reads the proximity graph and the repair's output through `Step::run` and
//! the IQR stage's cut threshold ([`iqr_thresholds_of`]); it may not touch the triangulation.
//!
//! Why: an outlier near a curve makes two curve points non-manifold, the repair may keep the
//! outlier's pair over the curve edge between them, and the cut then loses that edge. Rule: when
//! the IQR stage removed edges, repair the proximity graph less every edge above its cut
//! threshold, taken from the repaired graph as that stage took it (docs/condt.md, *Repairing
//! again without the cut edges*, says why cutting first is no cure, and what it gains).

use super::outliers::{iqr_thresholds_of, IqrRule};
use super::repair::repair;
use super::{Earlier, Outcome, Repair};
use crate::adjacency::{collect_exact, Edge};
use crate::triangulate::Triangulation;

/// The rule on `edges`, the IQR stage's output, reading from `earlier` that stage's input (the
/// list, or the edges it cut: the same lengths, which is all the thresholds read) and the
/// repair's, the proximity graph. Each is freed once read, before the repair runs (memory: its
/// peak).
pub(crate) fn repair_again(
    tri: &Triangulation,
    edges: &[Edge],
    earlier: Earlier<'_>,
    rule: IqrRule,
    mode: Repair,
    parallel: bool,
) -> Outcome {
    // The IQR stage only removes edges: it cut exactly when the lists differ.
    let unchanged = match earlier.cut_by_outliers {
        Some(cut) => cut.is_empty(),
        None => edges == &*earlier.before_outliers,
    };
    if unchanged {
        return Outcome::UNCHANGED;
    }
    let length2 = |&[a, b]: &Edge| tri.vertex_point(a).dist2(tri.vertex_point(b));
    // The thresholds are order statistics: of the lengths alone, in any order.
    let lengths = match earlier.cut_by_outliers {
        Some(cut) => edges
            .iter()
            .chain(cut.iter().map(|(_, edge)| edge))
            .map(length2)
            .collect(),
        None => earlier.before_outliers.iter().map(length2).collect(),
    };
    drop(earlier.before_outliers);
    let threshold = iqr_thresholds_of(lengths, rule).cut;
    let proximity = earlier.before_repair;
    let short = collect_exact(
        proximity.len(),
        proximity
            .iter()
            .filter(|e| length2(e) <= threshold)
            .copied(),
    );
    drop(proximity);
    Outcome::from(Some(repair(tri, &short, mode, parallel).unwrap_or(short)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::triangulate;
    use crate::Params;
    use alloc::borrow::Cow;

    /// An evenly spaced square outline, 10 points a side, and one outlier just outside a corner,
    /// nearer to the corner's two neighbours than they are to each other across the corner.
    fn square_with_outlier() -> Vec<Point> {
        let mut pts = Vec::new();
        for k in 0..10 {
            let t = k as f64;
            pts.extend([
                Point::new(t, 0.0),
                Point::new(10.0, t),
                Point::new(10.0 - t, 10.0),
                Point::new(0.0, 10.0 - t),
            ]);
        }
        pts.push(Point::new(-0.9, -0.9));
        pts.push(Point::new(30.0, 30.0)); // far away: the IQR rule fires
        pts
    }

    /// Without the spacing floor: the outlier lies 1.27 spacings off the corner, within the floor
    /// (1.5 median edges), which keeps its edge to the corner whichever pair the repair chose.
    #[test]
    fn the_outliers_pair_at_a_corner_gives_way_to_the_curve() {
        let pts = square_with_outlier();
        let params = Params::default().with_smooth(false).with_iqr_floor(false);
        let with = crate::reconstruct(&pts, &params).unwrap();
        let without = crate::reconstruct(&pts, &params.with_repair_again(false)).unwrap();
        let curve = |r: &crate::Reconstruction| {
            let edges: Vec<[usize; 2]> = r.edges().collect();
            (edges.len(), edges.iter().all(|&[a, b]| a < 40 && b < 40))
        };
        assert_eq!(
            curve(&with),
            (40, true),
            "{:?}",
            with.edges().collect::<Vec<_>>()
        );
        assert_ne!(curve(&without), (40, true));
    }

    #[test]
    fn nothing_changes_when_the_rule_did_not_fire() {
        let pts = square_with_outlier();
        let tri = triangulate(&pts).unwrap();
        let edges = [[crate::mesh::VertexId::new(0), crate::mesh::VertexId::new(1)]];
        let rule = IqrRule {
            factor: 1.7,
            floor: true,
        };
        let same = Earlier {
            before_outliers: Cow::Borrowed(&edges[..]),
            cut_by_outliers: None,
            before_local: Cow::Borrowed(&edges[..]),
            before_repair: Cow::Borrowed(&edges[..]),
        };
        let outcome = repair_again(&tri, &edges, same, rule, Repair::Needs, false);
        assert!(outcome.edges.is_none());
    }
}
