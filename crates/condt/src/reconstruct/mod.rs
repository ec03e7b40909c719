//! The whole ConDT pipeline (paper sections 3 to 5; `docs/condt.md` maps each line of its
//! algorithms to the code), split along its seams: [`params`] (what runs and in which order),
//! [`pipeline`] (running it step by step, with the smoothing passes), [`history`] (what each
//! stage changed, to give its graph back) and [`result`] (the [`Reconstruction`]). None of them
//! implements a stage ([`crate::stages`]) or edits a triangulation's mesh: a smoothing pass
//! builds a new triangulation of the moved points (reusing the old one's storage).

mod history;
mod params;
mod pipeline;
mod result;

pub use params::{Method, Params};
pub use pipeline::{
    reconstruct, reconstruct_owned, reconstruct_triangulation, Pipeline, StepReport, Upcoming,
};
pub use result::{Reconstruction, Smoothing, StageReport};

#[cfg(test)]
mod tests {
    use super::history::Undo;
    use super::pipeline::EdgesFingerprint;
    use super::result::{degrees_of, edges_in_input_positions, Degrees};
    use super::*;
    use crate::adjacency::{ordered, CurveGraph, Edge};
    use crate::mesh::VertexId;
    use crate::sample::{sample, Clumps, Sampling, Shape};
    use crate::stages::{proximity, Earlier, Stage, Step};
    use crate::test_rng::Xorshift;
    use crate::triangulate::triangulate;
    use crate::Point;
    use alloc::borrow::Cow;
    use alloc::vec::Vec;

    /// Every stage with a switch can be turned on and off through `Params::set_stage`, and
    /// doing so adds it to or takes it from the stages that run; no other stage can.
    #[test]
    fn the_stage_switches_and_the_parameters_agree() {
        for stage in Stage::ALL {
            let mut on = Params::default();
            let mut off = Params::default();
            let switchable = on.set_stage(stage, true);
            assert_eq!(off.set_stage(stage, false), switchable, "{stage:?}");
            assert_eq!(switchable, stage.switch().is_some(), "{stage:?}");
            if switchable {
                assert!(on.stages().contains(&stage), "{stage:?}");
                assert!(!off.stages().contains(&stage), "{stage:?}");
            }
        }
    }

    fn edge(a: u32, b: u32) -> Edge {
        [VertexId::new(a), VertexId::new(b)]
    }

    /// Whatever a stage makes of its input (edges removed, edges appended or inserted, the order
    /// changed), the record gives the input back exactly, in its order; the input is stored whole
    /// only when the delta would be larger.
    #[test]
    fn an_undo_gives_the_stage_input_back_exactly() {
        let mut rng = Xorshift::new(12);
        for round in 0..400 {
            let len = rng.below(40) as u32;
            let input: Vec<Edge> = (0..len).map(|k| edge(k, k + 1 + round)).collect();
            let (mut output, mut removals, mut inserted) = (Vec::new(), 0, 0);
            for (k, &e) in input.iter().enumerate() {
                // Every third round, new edges among the kept ones (as repairing again lists them).
                if round % 3 == 1 && rng.below(8) == 0 {
                    output.push(edge(500 + k as u32, 600 + k as u32));
                    inserted += 1;
                }
                if rng.below(4) != 0 {
                    output.push(e);
                } else {
                    removals += 1;
                }
            }
            output.extend((0..rng.below(5) as u32).map(|k| edge(1000 + k, 2000 + k)));
            let reordered = round % 5 == 0 && output.len() > 2;
            if reordered {
                output.swap(0, 1);
            }
            let undo = Undo::of(input.clone(), &output);
            // The delta (12 bytes a removal, 4 an insertion) is kept while the input is no smaller.
            if !reordered && 12 * removals + 4 * inserted <= 8 * input.len() {
                assert!(matches!(undo, Undo::Delta { .. }), "{undo:?}");
            }
            assert_eq!(
                &*undo.input(Cow::Borrowed(&output), &|| unreachable!()),
                input.as_slice()
            );
        }
    }

    /// An input handed over gives the result a borrowed one gives, the stage points it reports
    /// included bit for bit: with and without smoothing passes, with signed zeros and
    /// duplicates, and across a range of magnitudes the stages' frame does not hold exactly.
    #[test]
    fn an_owned_input_gives_the_same_result() {
        let mut rng = Xorshift::new(3);
        let noisy: Vec<Point> = (0..300)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 300.0;
                let r = 1.0 + 0.05 * (rng.unit() - 0.5);
                Point::new(r * libm::cos(t), r * libm::sin(t))
            })
            .collect();
        let mut zeros = noisy.clone();
        zeros.extend([Point::new(-0.0, 0.0), Point::new(0.0, 0.0), noisy[7]]);
        // A set spanning more than the stages' frame holds exactly (a curve near 1e300, a point
        // near 1e-300, which becomes subnormal there): the triangulation keeps its inputs, and
        // every input position must still come back bit for bit. (Two such points would be too
        // close to measure beside 1e300: `Error::TooCloseToMeasure`.)
        let mut wide: Vec<Point> = noisy
            .iter()
            .map(|p| Point::new(p.x * 1e300, p.y * 1e300))
            .collect();
        wide.push(Point::new(1e-300, 3e-301));
        for points in [noisy, zeros, wide] {
            let tri = triangulate(&points).unwrap();
            tri.validate().unwrap();
            for smooth in [false, true] {
                let params = Params::default().with_smooth(smooth);
                let borrowed = reconstruct(&points, &params).unwrap();
                let owned = reconstruct_owned(points.clone(), &params).unwrap();
                assert_eq!(owned.edges, borrowed.edges);
                assert_eq!(owned.curves, borrowed.curves);
                assert_eq!(owned.smoothing.is_some(), borrowed.smoothing.is_some());
                // The curves were assembled, whichever way the passes ended: every final edge
                // lies on one of them.
                let segments: usize = borrowed
                    .curves()
                    .iter()
                    .map(|c| c.len() - usize::from(!c.is_closed()))
                    .sum();
                assert!(!borrowed.edges.is_empty());
                assert_eq!(segments, borrowed.edges.len());
                for (i, &input) in points.iter().enumerate() {
                    let (p, q) = (borrowed.stage_point(i), owned.stage_point(i));
                    assert_eq!(
                        (q.x.to_bits(), q.y.to_bits()),
                        (p.x.to_bits(), p.y.to_bits())
                    );
                    // Without the passes, the stages saw the input points (a merged duplicate
                    // keeps the bits of its first position: equal, perhaps not in a zero's sign).
                    if !smooth {
                        assert_eq!(p, input, "point {i}");
                    }
                }
            }
            let smoothed = reconstruct(&points, &Params::default()).unwrap();
            assert!(smoothed.smoothing.is_some(), "the passes ran");
        }
    }

    /// Degrees of 255 and more go to the side list and come back exactly, in order, beside
    /// the small ones around them.
    #[test]
    fn degrees_keep_large_values_exactly() {
        let values = [0, 2, 254, 255, 300, 1, 70_000, 254, u32::MAX as usize, 3];
        let mut degrees = Degrees::default();
        for &d in &values {
            degrees.push(d);
        }
        assert_eq!(degrees.len(), values.len());
        assert_eq!(degrees.large.len(), 4);
        for (i, &d) in values.iter().enumerate() {
            assert_eq!(degrees.get(i), d, "position {i}");
        }
        assert!(degrees.iter().eq(values.iter().copied()));
        assert_eq!(
            alloc::format!("{degrees:?}"),
            alloc::format!("{values:?}"),
            "Debug shows the degrees as a list"
        );
    }

    /// The final tally gives every input position its vertex's degree (one of 300 and one of
    /// exactly 255 too, past the byte), copies of a point share it, the points without edges are
    /// the unused ones, and the edges, read from the list, are each listed once under the smaller
    /// position, in order.
    #[test]
    fn the_final_tally_reads_degrees_and_edges_in_input_positions() {
        let mut points: Vec<Point> = (0..400)
            .map(|k| Point::new(f64::from(k), f64::from((k * k) % 101)))
            .collect();
        points.extend([points[0], points[7], points[399]]);
        let tri = triangulate(&points).unwrap();
        let v = |i: usize| tri.vertex(i);
        let mut last: Vec<Edge> = (1..301).map(|i| ordered(v(0), v(i))).collect();
        last.extend((301..=350).map(|i| ordered(v(i), v(i + 1))));
        last.extend((1..256).map(|i| ordered(v(360), v(i))));
        last.sort_unstable();
        let graph = CurveGraph::new(points.len(), &last);
        let (degrees, unused) = degrees_of(&tri, &graph, Degrees::with_room(points.len()));
        let degree = |i| degrees.get(i);
        assert_eq!((degree(0), degree(360), degree(400)), (300, 255, 300));
        assert_eq!(
            (degree(7), degree(401), degree(351), degree(399)),
            (2, 2, 1, 0)
        );
        let expected: Vec<usize> = (0..points.len()).filter(|&i| degree(i) == 0).collect();
        assert_eq!(unused, expected);
        let mut edges: Vec<[u32; 2]> = Vec::new();
        for i in 0..points.len() {
            for k in 0..graph.degree(v(i)) {
                let j = tri.input_of(graph.neighbor(v(i), k)) as u32;
                if j > i as u32 && tri.input_of(v(i)) == i {
                    edges.push([i as u32, j]);
                }
            }
        }
        edges.sort_unstable();
        assert_eq!(edges.len(), last.len());
        for parallel in [false, true] {
            assert_eq!(edges_in_input_positions(&tri, &last, parallel), edges);
        }
    }

    /// Every stage's graph as `stages()` rebuilds it is the graph the stage left: running the
    /// steps one by one through the public `Graph` methods gives the same edges in the same
    /// order.
    #[test]
    fn the_stage_graphs_are_rebuilt_as_the_stages_left_them() {
        let mut rng = Xorshift::new(7);
        let mut points: Vec<Point> = (0..400)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 400.0;
                let r = 1.0 + 0.02 * (rng.unit() - 0.5);
                Point::new(r * libm::cos(t), r * libm::sin(t))
            })
            .collect();
        points.extend((0..60).map(|_| Point::new(3.0 * rng.unit() - 1.5, 3.0 * rng.unit() - 1.5)));
        let params = Params::default().with_smooth(false);
        let result = reconstruct(&points, &params).unwrap();
        let tri = result.triangulation();
        let reports: Vec<StageReport<'_>> = result.stages().collect();
        let proximity = tri.proximity_graph(params.uniformity).unwrap();
        assert_eq!(reports[0].graph.listed(), proximity.listed());
        let repaired = proximity.repair(params.repair);
        assert_eq!(reports[1].graph.listed(), repaired.listed());
        let filtered = repaired.remove_outliers_floored(1.7).unwrap();
        assert_eq!(reports[2].graph.listed(), filtered.graph.listed());
        assert_eq!(reports[2].applied, filtered.fired);
        let again = filtered.repair_again(&repaired, &proximity, params.repair);
        assert_eq!(reports[3].graph.listed(), again.listed());
        let local = again.remove_local_outliers(&repaired);
        assert_eq!(reports[4].graph.listed(), local.listed());
        let unclumped = local.remove_clumps();
        assert_eq!(reports[5].graph.listed(), unclumped.listed());
        let confirmed = unclumped.confirm_given_back(&again);
        assert_eq!(reports[6].graph.listed(), confirmed.listed());
        let closed = confirmed.close_gaps();
        assert_eq!(reports[7].graph.listed(), closed.listed());
        let joined = closed.join_junctions();
        assert_eq!(reports[8].graph.listed(), joined.listed());
        assert_eq!(result.graph().listed(), joined.listed());
        assert!(
            reports.iter().skip(1).any(|r| r.applied),
            "some stage changed the graph"
        );
    }

    /// On uniform points the repair changes most of the proximity graph, so its record does not
    /// keep it ([`Undo::First`]): the reports still give every stage's graph as it was, the
    /// proximity graph computed again; along a curve the repair's record stays a delta.
    #[test]
    fn a_repair_record_that_would_hold_the_proximity_graph_recomputes_it() {
        let mut rng = Xorshift::new(21);
        let uniform = rng.unit_points(3000);
        let curve: Vec<Point> = (0..3000)
            .map(|k| {
                let t = k as f64 * core::f64::consts::TAU / 3000.0;
                Point::new(libm::cos(t), 0.5 * libm::sin(t))
            })
            .collect();
        let params = Params::default().with_smooth(false);
        for (points, recomputed) in [(uniform, true), (curve, false)] {
            let result = reconstruct(&points, &params).unwrap();
            let repair = &result.history.records[1];
            assert_eq!(repair.stage, Stage::Repair);
            assert_eq!(matches!(repair.undo, Undo::First), recomputed);
            let tri = result.triangulation();
            let proximity = tri.proximity_graph(params.uniformity).unwrap();
            let reports: Vec<StageReport<'_>> = result.stages().collect();
            assert_eq!(reports[0].graph.listed(), proximity.listed());
            let repaired = proximity.repair(params.repair);
            assert_eq!(reports[1].graph.listed(), repaired.listed());
            let filtered = repaired.remove_outliers_floored(1.7).unwrap();
            assert_eq!(reports[2].graph.listed(), filtered.graph.listed());
            assert_eq!(
                result.stage(Stage::Proximity).unwrap().graph.listed(),
                proximity.listed()
            );
        }
    }

    /// The fixed-point test's fingerprint is that of the same list made again, and tells apart
    /// every other list tried: each single edge changed in either end, dropped or added, two
    /// edges swapped, and the empty list.
    #[test]
    fn edge_fingerprints_tell_lists_apart() {
        let mut rng = Xorshift::new(5);
        let mut seen = alloc::collections::BTreeMap::new();
        for round in 0..200 {
            let n = 2 + rng.below(1 << (round % 30)) as u32;
            let mut edges: Vec<[u32; 2]> = (0..1 + rng.below(40))
                .map(|_| {
                    let (a, b) = (rng.below(n.into()) as u32, rng.below(n.into()) as u32);
                    [a.min(b), a.max(b) + u32::from(a == b)]
                })
                .collect();
            if round == 0 {
                edges.push([u32::MAX - 1, u32::MAX]);
            }
            edges.sort_unstable();
            edges.dedup();
            let print = EdgesFingerprint::of(&edges);
            assert_eq!(print, EdgesFingerprint::of(&edges.clone()));
            let mut others = alloc::vec![Vec::new()];
            for k in 0..edges.len() {
                for end in 0..2 {
                    let mut changed = edges.clone();
                    changed[k][end] ^= 1 << rng.below(32);
                    others.push(changed);
                }
                let mut dropped = edges.clone();
                dropped.remove(k);
                others.push(dropped);
                if k > 0 {
                    let mut swapped = edges.clone();
                    swapped.swap(k - 1, k);
                    others.push(swapped);
                }
            }
            let mut added = edges.clone();
            added.push([0, 1]);
            others.push(added);
            for other in others {
                assert_eq!(other == edges, EdgesFingerprint::of(&other) == print);
            }
            // Across rounds, different lists have different hashes (lists met again agree).
            if let Some(earlier) = seen.insert(print.hashes, edges.clone()) {
                assert_eq!(earlier, edges);
            }
        }
        assert!(seen.len() > 150);
    }

    /// A stage given the curve graph of its input decides exactly as one that builds its own,
    /// and the graph it hands on is the curve graph of its output: on noisy, crossing curves
    /// with outliers and clumps, where every stage changes something, and on a clean circle,
    /// where none does.
    #[test]
    fn a_handed_on_curve_graph_is_that_of_the_stage_output_and_changes_nothing() {
        let shapes = [
            Shape::FigureEight {
                center: Point::new(0.0, 0.0),
                size: 2.0,
            },
            Shape::circle(Point::new(5.0, 0.0), 1.0),
            Shape::Arc {
                center: Point::new(0.0, 5.0),
                radius: 1.5,
                start: 0.0,
                sweep: 4.0,
            },
        ];
        let (mut clean_seeds, mut clean_reaching_the_end) = (0, 0);
        for seed in 0..12u64 {
            let sampling = Sampling {
                noise: if seed % 3 == 0 { 0.0 } else { 0.02 },
                outlier_fraction: if seed % 2 == 0 { 0.0 } else { 0.05 },
                outlier_clumps: (seed % 4 == 1).then_some(Clumps {
                    min: 3,
                    max: 7,
                    radius: 0.1,
                }),
                seed,
                ..Sampling::new(0.08)
            };
            let points = sample(&shapes, &sampling).unwrap().points;
            let tri = triangulate(&points).unwrap();
            let n = tri.num_points();
            let params = Params::default();
            let mut current = proximity::proximity_graph(&tri, params.uniformity, params.parallel);
            let mut graph: Option<CurveGraph> = None;
            let (mut before_outliers, mut before_local) = (current.clone(), current.clone());
            let before_repair = current.clone();
            for step in params.steps() {
                if matches!(step, Step::Outliers(_)) {
                    before_outliers = current.clone();
                }
                if step == Step::LocalOutliers {
                    before_local = current.clone();
                }
                let earlier = Earlier {
                    before_outliers: Cow::Borrowed(&before_outliers),
                    cut_by_outliers: None,
                    before_local: Cow::Borrowed(
                        if step == Step::ConfirmGivenBack && before_local == current {
                            &current
                        } else {
                            &before_local
                        },
                    ),
                    before_repair: Cow::Borrowed(&before_repair),
                };
                let given = graph.is_some();
                let with = step.run(&tri, &current, earlier.clone(), graph.take(), false);
                let without = step.run(&tri, &current, earlier, None, false);
                assert_eq!(
                    with.edges, without.edges,
                    "seed {seed}, {step:?}, given {given}"
                );
                let output = with.edges.unwrap_or_else(|| current.clone());
                if let Some(g) = &with.graph {
                    assert_eq!(*g, CurveGraph::new(n, &output), "seed {seed}, {step:?}");
                }
                graph = with.graph;
                current = output;
            }
            // Where no stage changes anything (no noise, no outliers), the local outlier
            // removal's graph reaches the curves.
            let clean = sampling.noise == 0.0 && sampling.outlier_fraction == 0.0;
            clean_reaching_the_end += usize::from(clean && graph.is_some());
            clean_seeds += usize::from(clean);
        }
        assert_eq!(clean_reaching_the_end, clean_seeds);
    }

    /// Every field of `Params` has its chainable setter (a field added without one would leave
    /// callers of the builder style nothing to set it with, and no other test notices).
    #[test]
    fn every_parameter_has_its_setter() {
        let source = include_str!("params.rs");
        let body = source
            .split("pub struct Params {")
            .nth(1)
            .expect("the struct");
        let body = body.split("\n}").next().expect("its end");
        let fields: Vec<&str> = body
            .lines()
            .filter_map(|line| line.trim().strip_prefix("pub "))
            .filter_map(|field| field.split(':').next())
            .collect();
        assert!(fields.len() >= 20, "the fields were not found: {fields:?}");
        let setters = source
            .split("setters! {")
            .nth(1)
            .expect("the setters' list");
        for field in fields {
            let setter = alloc::format!("with_{field}({field}:");
            assert!(
                setters.contains(&setter),
                "Params::{field} has no `{setter}` setter"
            );
        }
    }
}
