//! Replays every saved fuzz input (`fuzz/corpus/TARGET/*` and `fuzz/artifacts/TARGET/*`) through
//! the same checks the fuzz targets run, so that a normal `cargo test` on stable keeps covering
//! them: each found crash stays fixed, and the corpus keeps exercising the paths the fuzzer
//! reached. The checks live in `fuzz/src/lib.rs`, included here as a module.

#[path = "../../../fuzz/src/lib.rs"]
#[allow(dead_code)]
mod checks;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// The saved inputs of `target`, sorted, from both directories (either may be missing).
fn inputs(target: &str) -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let mut files: Vec<PathBuf> = ["corpus", "artifacts"]
        .iter()
        .filter_map(|dir| std::fs::read_dir(root.join(dir).join(target)).ok())
        .flatten()
        .map(|entry| entry.expect("readable fuzz directory").path())
        .filter(|path| path.is_file())
        .collect();
    files.sort();
    files
}

/// Runs `check` on every saved input of `target` and names every one that fails.
fn replay(target: &str, check: fn(&[u8])) {
    let files = inputs(target);
    // An empty corpus would make this test pass without checking anything.
    assert!(
        files.len() >= 10,
        "only {} saved inputs for fuzz target {target}",
        files.len()
    );
    let failures: Vec<String> = files
        .iter()
        .filter_map(|path| {
            let data = std::fs::read(path).expect("readable fuzz input");
            catch_unwind(AssertUnwindSafe(|| check(&data)))
                .err()
                .map(|_| path.display().to_string())
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} inputs fail (messages above): {failures:#?}",
        failures.len(),
        files.len()
    );
}

#[test]
fn triangulate_corpus_replays_cleanly() {
    replay("triangulate", checks::triangulate);
}

#[test]
fn reconstruct_corpus_replays_cleanly() {
    replay("reconstruct", checks::reconstruct);
}

#[test]
fn parse_points_corpus_replays_cleanly() {
    replay("parse_points", checks::parse_points);
}

#[test]
fn parse_formats_corpus_replays_cleanly() {
    replay("parse_formats", checks::parse_formats);
}
