//! A `Pipeline` stepped to its end gives exactly what `reconstruct` gives, and its reports are
//! the stages as they ran: on the shipped data and on sampled curves with noise and outliers
//! (where the smoothing passes run), for every preset and method.

use condt::{reconstruct, Method, Params, Pipeline, Point, Reconstruction, Stage, StepReport};
use condt_eval::sample::{sample, Sampling, Shape};

fn shipped() -> Vec<Point> {
    condt_io::read_points(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/shapes.txt"
    ))
    .unwrap()
}

fn noisy_curves(seed: u64) -> Vec<Point> {
    let shapes = [
        Shape::FigureEight {
            center: Point::new(0.0, 0.0),
            size: 2.0,
        },
        Shape::Arc {
            center: Point::new(0.0, 5.0),
            radius: 1.5,
            start: 0.0,
            sweep: 4.0,
        },
    ];
    let sampling = Sampling {
        noise: 0.02,
        outlier_fraction: 0.03,
        seed,
        ..Sampling::new(0.08)
    };
    sample(&shapes, &sampling).unwrap().points
}

/// What a test compares of two results: everything public that does not depend on the clock.
fn same(a: &Reconstruction, b: &Reconstruction, what: &str) {
    assert!(a.edges().eq(b.edges()), "{what}: edges");
    assert_eq!(a.curves(), b.curves(), "{what}: curves");
    assert_eq!(a.unused(), b.unused(), "{what}: unused");
    let passes = |r: &Reconstruction| r.smoothing().map(|s| (s.passes, s.moved));
    assert_eq!(passes(a), passes(b), "{what}: smoothing");
    assert_eq!(a.stages().len(), b.stages().len(), "{what}: stages");
    for (x, y) in a.stages().zip(b.stages()) {
        assert_eq!(x.stage, y.stage, "{what}");
        assert_eq!(x.applied, y.applied, "{what}: {} applied", x.stage);
        assert_eq!(x.graph.edges(), y.graph.edges(), "{what}: {}", x.stage);
    }
    for i in 0..a.num_points() {
        assert_eq!(a.stage_point(i), b.stage_point(i), "{what}: point {i}");
        assert_eq!(a.degree(i), b.degree(i), "{what}: degree {i}");
    }
}

#[test]
fn stepping_to_the_end_equals_reconstruct() {
    let presets = [
        ("default", Params::default()),
        ("paper", Params::paper()),
        ("no smoothing", Params::default().with_smooth(false)),
        (
            "outliers first",
            Params::default().with_outliers_first(true),
        ),
        ("nn-crust", Params::default().with_method(Method::NnCrust)),
        ("crust", Params::default().with_method(Method::Crust)),
    ];
    let sets = [
        ("shapes.txt", shipped()),
        ("noisy 1", noisy_curves(1)),
        ("noisy 2", noisy_curves(2)),
    ];
    let mut passes_seen = 0;
    for (set, points) in &sets {
        for (name, params) in &presets {
            let what = format!("{set}, {name}");
            let whole = reconstruct(points, params).unwrap();
            let mut pipeline = Pipeline::new(points, params).unwrap();
            // The stages of each run, in the order they ran, and the graph each step reported.
            let mut runs: Vec<Vec<(Stage, Vec<[usize; 2]>)>> = vec![Vec::new()];
            while let Some(step) = pipeline.step().unwrap() {
                match step {
                    StepReport::Stage(report) => runs
                        .last_mut()
                        .unwrap()
                        .push((report.stage, report.graph.edges())),
                    StepReport::SmoothingPass { pass, moved, .. } => {
                        assert_eq!(pass, runs.len(), "{what}: passes are numbered from 1");
                        assert!(moved > 0, "{what}: a pass moves points");
                        runs.push(Vec::new());
                    }
                    _ => unreachable!("no other report exists yet"),
                }
            }
            assert!(pipeline.is_done());
            assert!(
                pipeline.step().unwrap().is_none(),
                "{what}: done stays done"
            );
            let stepped = pipeline.finish().unwrap();
            same(&stepped, &whole, &what);
            passes_seen += runs.len() - 1;
            assert_eq!(
                whole.smoothing().map_or(0, |s| s.passes),
                runs.len() - 1,
                "{what}: one pass report per pass"
            );
            // Every run ran the stages the parameters choose, in their order, and the last
            // run's reports are the result's stage graphs.
            for run in &runs {
                let stages: Vec<Stage> = run.iter().map(|(stage, _)| *stage).collect();
                assert_eq!(stages, params.stages(), "{what}");
            }
            let last = runs.last().unwrap();
            for ((stage, edges), report) in last.iter().zip(whole.stages()) {
                assert_eq!(*stage, report.stage);
                assert_eq!(*edges, report.graph.edges(), "{what}: {stage}");
            }
        }
    }
    assert!(
        passes_seen > 0,
        "some smoothing pass ran, so the pass steps were tested"
    );
}

#[test]
fn a_pipeline_refuses_what_reconstruct_refuses() {
    let bad = Params::paper().with_outlier_factor(Some(f64::NAN));
    let points = shipped();
    // Compared as text: the refused value is NaN, which equals nothing.
    assert_eq!(
        format!("{:?}", Pipeline::new(&points, &bad).unwrap_err()),
        format!("{:?}", reconstruct(&points, &bad).unwrap_err())
    );
    let nan = [Point::new(0.0, 0.0), Point::new(f64::NAN, 1.0)];
    assert_eq!(
        Pipeline::new(&nan, &Params::default()).unwrap_err(),
        reconstruct(&nan, &Params::default()).unwrap_err()
    );
}

#[test]
fn an_empty_or_tiny_input_steps_to_an_empty_result() {
    for n in 0..3 {
        let points: Vec<Point> = (0..n).map(|k| Point::new(k as f64, 0.0)).collect();
        let mut pipeline = Pipeline::new(&points, &Params::default()).unwrap();
        let mut stage_steps = 0;
        while let Some(step) = pipeline.step().unwrap() {
            stage_steps += usize::from(matches!(step, StepReport::Stage(_)));
        }
        let result = pipeline.finish().unwrap();
        assert_eq!(result.num_points(), n);
        // Two points are an open curve, whose loose ends start the smoothing passes: each pass
        // runs every stage again.
        let runs = 1 + result.smoothing().map_or(0, |s| s.passes);
        assert_eq!(
            stage_steps,
            runs * Params::default().stages().len(),
            "{n} points"
        );
    }
}
