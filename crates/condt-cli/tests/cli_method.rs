//! `condt reconstruct --method`: the classical baselines on the same triangulation.

use condt::{triangulate, Point};
use condt_eval::sample::{sample, Sampling, Shape};
use std::process::Command;

fn run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_condt"))
        .args(args)
        .output()
        .expect("the binary runs")
}

#[test]
fn each_method_writes_its_own_edges() {
    let dir = tempfile::Builder::new()
        .prefix("condt-method-")
        .tempdir()
        .unwrap();
    let shape = sample(
        &[Shape::Ellipse {
            center: Point::new(0.0, 0.0),
            radii: (4.0, 1.0),
            rotation: 0.5,
        }],
        &Sampling::new(0.35),
    )
    .unwrap();
    let text: String = shape
        .points
        .iter()
        .map(|p| format!("{:?} {:?}\n", p.x, p.y))
        .collect();
    let input = dir.path().join("ellipse.txt");
    std::fs::write(&input, text).unwrap();
    let tri = triangulate(&shape.points).unwrap();
    for (method, expected) in [
        ("nn-crust", tri.nn_crust().edges()),
        ("crust", tri.crust().unwrap().edges()),
    ] {
        let out = run(&[
            "reconstruct",
            input.to_str().unwrap(),
            "--method",
            method,
            "--format",
            "edges",
        ]);
        assert!(out.status.success(), "{method}");
        let written: Vec<[usize; 2]> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(|l| {
                let mut ends = l.split(' ').map(|t| t.parse().unwrap());
                [ends.next().unwrap(), ends.next().unwrap()]
            })
            .collect();
        assert_eq!(written, expected, "{method}");
        // Well sampled, both baselines find the ellipse.
        assert_eq!(written, shape.edges, "{method}");
    }
}

#[test]
fn a_baseline_refuses_condt_options_and_an_unknown_method_is_named() {
    for args in [
        vec!["reconstruct", "-", "--method", "crust", "--u", "2"],
        vec!["reconstruct", "-", "--paper", "--method", "nn-crust"],
        vec![
            "reconstruct",
            "-",
            "--method",
            "nn-crust",
            "--method",
            "crust",
        ],
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
    let out = run(&["reconstruct", "-", "--method", "alpha"]);
    assert_eq!(out.status.code(), Some(2));
    let said = String::from_utf8(out.stderr).unwrap();
    assert!(said.contains("condt, nn-crust and crust"), "{said}");
}
