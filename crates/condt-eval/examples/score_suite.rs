//! Scores reconstructions of a suite of point sets with ground truth, per category: exact %,
//! mean edge F1 and the number of output edges that touch a point the truth leaves unused
//! (outlier edges). A measuring tool for quality decisions; the suite itself is not part of the
//! crate (`../shared/eval` generates one per seed).
//!
//! ```text
//! cargo run --release --example score_suite -- SUITE_DIR [--paper] [--outputs DIR]
//! ```
//!
//! SUITE_DIR holds `cases.tsv` (a header, then `name`, `category`, `n_points`, tab-separated)
//! and `NAME.pts` / `NAME.gt` per case. Without `--outputs` every case is reconstructed here
//! with the default parameters (with `--paper`, `Params::paper()`); with `--outputs DIR` the
//! edges are read from `DIR/NAME/output.edges` instead (any program's output, in the layout
//! `run.py --keep-outputs` writes).

use condt::{reconstruct, Params};
use condt_eval::score::score;
use condt_io::read_points;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// An edge list as written, repeats and all, so that the scorer can refuse a malformed one.
type Edges = Vec<[usize; 2]>;

fn read_edges(path: &Path) -> Result<Edges, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(path)?;
    let mut edges = Edges::new();
    for line in text
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
    {
        let mut ends = line.split_whitespace().map(str::parse::<usize>);
        let (Some(Ok(a)), Some(Ok(b))) = (ends.next(), ends.next()) else {
            return Err(format!("{}: malformed line {line:?}", path.display()).into());
        };
        edges.push([a, b]);
    }
    Ok(edges)
}

#[derive(Default)]
struct Tally {
    cases: usize,
    exact: usize,
    f1_sum: f64,
    outlier_edges: usize,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let suite = PathBuf::from(
        args.first()
            .ok_or("usage: score_suite SUITE_DIR [--paper] [--outputs DIR]")?,
    );
    let params = if args.iter().any(|a| a == "--paper") {
        Params::paper()
    } else {
        Params::default()
    };
    let outputs = args
        .iter()
        .position(|a| a == "--outputs")
        .and_then(|k| args.get(k + 1))
        .map(PathBuf::from);
    let listing = std::fs::read_to_string(suite.join("cases.tsv"))?;
    let mut by_category: BTreeMap<String, Tally> = BTreeMap::new();
    for row in listing.lines().skip(1).filter(|l| !l.is_empty()) {
        let fields: Vec<&str> = row.split('\t').collect();
        let (name, category) = (fields[0], fields[1].to_string());
        let points = read_points(suite.join(format!("{name}.pts")))?;
        let truth = read_edges(&suite.join(format!("{name}.gt")))?;
        let ours: Edges = match &outputs {
            Some(dir) => read_edges(&dir.join(name).join("output.edges"))?,
            None => reconstruct(&points, &params)?.edges().collect(),
        };
        let s = score(&points, &ours, &truth)?;
        let tally = by_category.entry(category).or_default();
        tally.cases += 1;
        tally.exact += usize::from(s.exact);
        tally.f1_sum += s.f1;
        tally.outlier_edges += s.outlier_edges;
    }
    let mut all = Tally::default();
    println!("| category | cases | exact % | mean F1 | outlier edges |");
    println!("|---|---|---|---|---|");
    for (category, t) in &by_category {
        print_row(category, t);
        all.cases += t.cases;
        all.exact += t.exact;
        all.f1_sum += t.f1_sum;
        all.outlier_edges += t.outlier_edges;
    }
    print_row("all", &all);
    Ok(())
}

fn print_row(label: &str, t: &Tally) {
    println!(
        "| {label} | {} | {:.1} | {:.4} | {} |",
        t.cases,
        100.0 * t.exact as f64 / t.cases.max(1) as f64,
        t.f1_sum / t.cases.max(1) as f64,
        t.outlier_edges
    );
}
