//! Evaluates ConDT on the ground-truth point sets of `../shared/data` (not shipped with the
//! crate: its terms forbid copying). Prints, per shape family, how many sets were reconstructed
//! exactly (edge set equal to the ground truth) and the mean edge F1; then, for the real sets
//! (no ground truth), how many of their points end in no curve, which is where a rule that
//! removes too much shows (look at the pictures of the sets it names).
//!
//! `cargo run --release --example evaluate -- [DATA_DIR] [--repair off|paper|mutual|crossing|needs]
//!  [--adaptive] [--u X] [--iqr K] [--no-outlier-filter] [--[no-]local-outliers]
//!  [--[no-]confirm-given-back] [--[no-]close-gaps] [--[no-]smooth] [--paper] [--sets]`
//! With `--compare`, runs every repair variant and uniformity mode and prints one table each.

use condt::{reconstruct, Params, Repair, Stage, Uniformity};
use condt_io::read_points;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn family(name: &str) -> &'static str {
    if name.contains("_noise") {
        "noisy (uniform noise)"
    } else if name.contains("_outliers") {
        "outliers (5-20 %)"
    } else if name.contains("dense") {
        "dense closed (10k-12k)"
    } else if name.starts_with("s2d_spiral") {
        "spiral (thin features)"
    } else if ["s2d_blob2_eps", "s2d_simple_eps", "s2d_complex_eps"]
        .iter()
        .any(|p| name.starts_with(p))
    {
        "closed, eps 0.2-0.7"
    } else {
        "drawings: open, multi, junctions"
    }
}

struct Outcome {
    exact: bool,
    f1: f64,
}

fn evaluate_set(
    dir: &Path,
    name: &str,
    params: &Params,
) -> Result<Outcome, Box<dyn std::error::Error>> {
    let points = read_points(dir.join(format!("{name}.pts")))?;
    let truth_text = std::fs::read_to_string(dir.join(format!("{name}.gt")))?;
    let truth: BTreeSet<(usize, usize)> = truth_text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut it = l.split_whitespace().map(|t| t.parse::<usize>().unwrap());
            (it.next().unwrap(), it.next().unwrap())
        })
        .collect();
    let result = reconstruct(&points, params)?;
    let ours: BTreeSet<(usize, usize)> = result.edges().map(|[a, b]| (a, b)).collect();
    let hits = ours.intersection(&truth).count() as f64;
    let (precision, recall) = (
        hits / ours.len().max(1) as f64,
        hits / truth.len().max(1) as f64,
    );
    let f1 = if hits == 0.0 {
        0.0
    } else {
        2.0 * precision * recall / (precision + recall)
    };
    Ok(Outcome {
        exact: ours == truth,
        f1,
    })
}

fn run(dir: &Path, sets: &[String], params: &Params, label: &str, per_set: bool) {
    let mut table: BTreeMap<&str, (usize, usize, f64)> = BTreeMap::new();
    for name in sets {
        match evaluate_set(dir, name, params) {
            Ok(o) => {
                let row = table.entry(family(name)).or_default();
                row.0 += 1;
                row.1 += o.exact as usize;
                row.2 += o.f1;
                if per_set {
                    println!("  {name:<34} exact={} f1={:.4}", o.exact, o.f1);
                }
            }
            Err(e) => println!("  {name}: {e}"),
        }
    }
    println!("\n{label}\n\n| family | sets | exact | mean edge F1 |\n|---|---|---|---|");
    let (mut sets_total, mut exact_total, mut f1_total) = (0, 0, 0.0);
    for (family, (n, exact, f1)) in &table {
        println!("| {family} | {n} | {exact} | {:.4} |", f1 / *n as f64);
        sets_total += n;
        exact_total += exact;
        f1_total += f1;
    }
    println!(
        "| all | {sets_total} | {exact_total} | {:.4} |",
        f1_total / sets_total.max(1) as f64
    );
}

/// Points left unused on every real set, summed, and the sets that lose the most.
fn unused_on_real_sets(dir: &Path, real: &[String], params: &Params) {
    let mut per_set: Vec<(usize, &str, usize)> = Vec::new();
    for name in real {
        let path = dir.join(format!("{name}.pts"));
        let points = match read_points(&path) {
            Ok(points) => points,
            Err(e) => {
                println!("  {name}: {e}");
                continue;
            }
        };
        match reconstruct(&points, params) {
            Ok(result) => per_set.push((result.unused().len(), name, points.len())),
            Err(e) => println!("  {name}: {e}"),
        }
    }
    let unused: usize = per_set.iter().map(|s| s.0).sum();
    let points: usize = per_set.iter().map(|s| s.2).sum();
    per_set.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(b.1)));
    let most: Vec<String> = per_set
        .iter()
        .take(5)
        .map(|(u, name, n)| format!("{name} {u}/{n}"))
        .collect();
    println!(
        "\nreal sets (no ground truth): {} sets, {points} points, {unused} unused; most: {}",
        per_set.len(),
        most.join(", ")
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = args
        .iter()
        .find(|a| !a.starts_with("--") && Path::new(a).is_dir())
        .cloned()
        .unwrap_or_else(|| "../shared/data".into());
    let dir = Path::new(&dir);
    let Ok(index) = std::fs::read_to_string(dir.join("index.tsv")) else {
        eprintln!(
            "no data at {} (index.tsv missing): name the data directory, \
             `cargo run --release -p condt-eval --example evaluate -- DIR [--paper]`",
            dir.display()
        );
        std::process::exit(1);
    };
    let column = |at: usize, value: &str| -> Vec<String> {
        index
            .lines()
            .skip(1)
            .filter_map(|l| {
                let cols: Vec<&str> = l.split('\t').collect();
                (cols.get(at) == Some(&value)).then(|| cols[0].to_string())
            })
            .collect()
    };
    let sets = column(3, "True");
    let real = column(1, "real");
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let mut params = if args.iter().any(|a| a == "--paper") {
        Params::paper()
    } else {
        Params::default()
    };
    // Every stage switch of the stage table (`--[no-]local-outliers`, `--[no-]clumps`, ...), as
    // the command line reads them, and the smoothing passes.
    for stage in Stage::ALL {
        if let Some(switch) = stage.switch() {
            for (flag, on) in [
                (format!("--{}", switch.flag), true),
                (format!("--no-{}", switch.flag), false),
            ] {
                if args.contains(&flag) {
                    params.set_stage(stage, on);
                }
            }
        }
    }
    for (flag, on) in [("--smooth", true), ("--no-smooth", false)] {
        if args.iter().any(|a| a == flag) {
            params.smooth = on;
        }
    }
    if let Some(r) = value("--repair") {
        params.repair = match r.as_str() {
            "off" => Repair::Off,
            "mutual" => Repair::Mutual,
            "crossing" => Repair::CrossingAware,
            "needs" => Repair::Needs,
            "paper" => Repair::Paper,
            other => {
                // A typo was read as `paper` and the table headed so: a wrong figure, unsaid.
                eprintln!(
                    "--repair {other}: unknown; the modes are paper, mutual, crossing, needs, off"
                );
                std::process::exit(2);
            }
        };
    }
    if args.iter().any(|a| a == "--adaptive") {
        params.uniformity = Uniformity::Adaptive;
    }
    if let Some(u) = value("--u") {
        params.uniformity = Uniformity::Fixed(u.parse().expect("--u takes a number"));
    }
    if let Some(k) = value("--iqr") {
        params.outlier_factor = Some(k.parse().expect("--iqr takes a number"));
    }
    if args.iter().any(|a| a == "--outliers-first") {
        params.outliers_first = true;
    }
    if args.iter().any(|a| a == "--no-outlier-filter") {
        params.outlier_factor = None;
    }
    let per_set = args.iter().any(|a| a == "--sets");
    if args.iter().any(|a| a == "--compare") {
        for repair in [
            Repair::Off,
            Repair::Paper,
            Repair::Mutual,
            Repair::CrossingAware,
            Repair::Needs,
        ] {
            for uniformity in [Uniformity::Fixed(2.75), Uniformity::Adaptive] {
                let p = params.with_repair(repair).with_uniformity(uniformity);
                run(
                    dir,
                    &sets,
                    &p,
                    &format!("repair {repair:?}, uniformity {uniformity:?}"),
                    per_set,
                );
            }
        }
    } else {
        run(dir, &sets, &params, &format!("{params:?}"), per_set);
        unused_on_real_sets(dir, &real, &params);
    }
}
