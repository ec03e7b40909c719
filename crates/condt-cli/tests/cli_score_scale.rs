//! `condt score` at extreme scales: the distances are those of the same points at unit scale.

use std::path::Path;
use std::process::Command;

/// `condt score --json` on a square's truth and an output with a diagonal and an edge off the
/// truth, its corners multiplied by `scale` (a power of two, or `f64::MAX`).
fn score_json(dir: &Path, scale: f64) -> String {
    let corners = [
        (-1.0, -1.0),
        (1.0, -1.0),
        (1.0, 1.0),
        (-1.0, 1.0),
        (0.25, 0.5),
    ];
    let points: String = corners
        .iter()
        .map(|&(x, y)| format!("{:?} {:?}\n", x * scale, y * scale))
        .collect();
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let points = write("square.pts", &points);
    let output = write("square.edges", "0 1\n0 2\n1 3\n2 4\n");
    let truth = write("square.gt", "0 1\n1 2\n2 3\n0 3\n");
    let run = Command::new(env!("CARGO_BIN_EXE_condt"))
        .arg("score")
        .args([&points, &output, &truth])
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).unwrap()
}

#[test]
fn distances_do_not_depend_on_a_power_of_two_scale() {
    let dir = tempfile::tempdir().unwrap();
    let unit = score_json(dir.path(), 1.0);
    assert!(unit.contains("\"max_dist\": 0.35355339059327373"), "{unit}");
    // 2^600 squared overflows, 2^-600 squared vanishes.
    for scale in [2f64.powi(600), 2f64.powi(-600)] {
        assert_eq!(score_json(dir.path(), scale), unit, "{scale:e}");
    }
    // Corners at ±f64::MAX (the box's sides overflow), against the same points 2^1023 smaller.
    let below_two = 2.0 - f64::EPSILON;
    assert_eq!(below_two * 2f64.powi(1023), f64::MAX);
    assert_eq!(
        score_json(dir.path(), f64::MAX),
        score_json(dir.path(), below_two)
    );
}
