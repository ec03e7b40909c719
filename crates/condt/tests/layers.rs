//! `docs/architecture.md` draws the core's modules in layers, each beside the modules it may use,
//! and says that every arrow points down. This test holds the code to that picture: it reads the
//! picture, checks that each module's list names only modules drawn below it, and reads every
//! source file of the module for `crate::` paths outside comments and `#[cfg(test)]` items,
//! which must lead to the module itself or to one on its list. A path through a root re-export
//! (`crate::Point`) counts as the module that defines it (`lib.rs`'s `pub use`). The reading is
//! plain text, with limits: a nested group (`crate::{a::{b}, c}`) is read up to its first `}`,
//! `super::super::` paths and items under `#[cfg(any(test, ..))]` are not told apart; none is in
//! the code today.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The column at which the picture's "uses" lists begin, in characters.
const USES_COLUMN: usize = 55;

/// A module of the picture, top to bottom, with the modules it may use.
struct Layer {
    module: String,
    uses: BTreeSet<String>,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The layer picture of `docs/architecture.md`: the text block after "Layers, from the top down".
fn layers() -> (Vec<Layer>, BTreeSet<String>) {
    let doc = fs::read_to_string(root().join("../../docs/architecture.md")).expect("the doc");
    let start = doc
        .find("Layers, from the top down")
        .expect("architecture.md draws the layers");
    let block = doc[start..]
        .split("```")
        .nth(1)
        .expect("the layers are a code block");
    let mut layers: Vec<Layer> = Vec::new();
    let mut leaves = BTreeSet::new();
    for line in block.lines() {
        if let Some(rest) = line.strip_prefix("  ") {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_lowercase() || *c == '_' || *c == ',' || *c == ' ')
                .collect();
            if let Some(names) = rest.split_once(": leaves").map(|(names, _)| names) {
                // "prefetch, threads: leaves (...)": modules that use none of the others.
                leaves.extend(names.split(',').map(|n| n.trim().to_string()));
                break;
            }
            let first = name.split_whitespace().next().unwrap_or("");
            if !first.is_empty() && rest.starts_with(first) {
                layers.push(Layer {
                    module: first.to_string(),
                    uses: BTreeSet::new(),
                });
            }
        }
        // A word of the middle column that runs into the uses column would be read as a module
        // used (a contributor's stage name gave "stages lists es"): said as what it is.
        let before: Vec<char> = line.chars().take(USES_COLUMN).collect();
        assert!(
            before.len() < USES_COLUMN || before[USES_COLUMN - 2..] == [' ', ' '],
            "architecture.md's layer picture: the middle column reaches column {USES_COLUMN}, \
             where the uses list starts (wrap it): {line:?}"
        );
        let uses: String = line.chars().skip(USES_COLUMN).collect();
        if let Some(layer) = layers.last_mut() {
            for used in uses.split(',') {
                let used = used.split_whitespace().next().unwrap_or("");
                if !used.is_empty() && used != "(nothing)" {
                    layer.uses.insert(used.to_string());
                }
            }
        }
    }
    (layers, leaves)
}

fn rust_files(path: &Path, out: &mut Vec<PathBuf>) {
    if path.is_dir() {
        for entry in fs::read_dir(path).expect("a readable directory") {
            rust_files(&entry.expect("a directory entry").path(), out);
        }
    } else if path.extension().is_some_and(|e| e == "rs") {
        out.push(path.to_path_buf());
    }
}

/// The source files of module `name`: `src/name.rs` and everything under `src/name/`.
fn module_files(name: &str) -> Vec<PathBuf> {
    let src = root().join("src");
    let mut files = Vec::new();
    let file = src.join(format!("{name}.rs"));
    if file.exists() {
        files.push(file);
    }
    rust_files(&src.join(name), &mut files);
    files
}

/// `text` without `//` comments and without the items under a `#[cfg(test)]` line (a block's
/// braces counted to its end, or a one-line item to its `;`).
fn library_code(text: &str) -> String {
    let mut code = String::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if line.trim() == "#[cfg(test)]" {
            let mut depth = 0i64;
            let mut opened = false;
            for item in lines.by_ref() {
                let item = item.split("//").next().unwrap_or("");
                depth += item.matches('{').count() as i64 - item.matches('}').count() as i64;
                opened |= item.contains('{');
                if (opened && depth <= 0) || (!opened && item.trim_end().ends_with(';')) {
                    break;
                }
            }
            continue;
        }
        code.push_str(line.split("//").next().unwrap_or(""));
        code.push('\n');
    }
    code
}

/// The first name of every `crate::` path in `code`, including each name of a `crate::{..}` group.
fn crate_paths(code: &str) -> BTreeSet<String> {
    let word = |s: &str| -> String {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut names = BTreeSet::new();
    for (at, _) in code.match_indices("crate::") {
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue; // `$crate::` in a macro, or a longer identifier
        }
        let rest = &code[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let group = &group[..group.find('}').unwrap_or(group.len())];
            names.extend(group.split(',').map(word).filter(|n| !n.is_empty()));
        } else {
            names.insert(word(rest));
        }
    }
    names
}

/// Each root re-export's module, from `lib.rs`'s `pub use module::{..}` and `pub use module::Name`.
fn root_exports() -> BTreeMap<String, String> {
    let lib = fs::read_to_string(root().join("src/lib.rs")).expect("lib.rs");
    let mut exports = BTreeMap::new();
    for statement in library_code(&lib).split(';') {
        let Some(path) = statement.trim().strip_prefix("pub use ") else {
            continue;
        };
        let (module, names) = path.split_once("::").expect("pub use module::..");
        let names = names.trim().trim_start_matches('{').trim_end_matches('}');
        for name in names.split(',') {
            let name = name.split("::").last().unwrap_or("").trim();
            if !name.is_empty() {
                exports.insert(name.to_string(), module.trim().to_string());
            }
        }
    }
    exports
}

/// The modules `lib.rs` declares for the library (not those of its unit tests).
fn declared_modules() -> BTreeSet<String> {
    let lib = fs::read_to_string(root().join("src/lib.rs")).expect("lib.rs");
    library_code(&lib)
        .lines()
        .filter_map(|line| {
            let line = line.trim().trim_start_matches("pub ");
            line.strip_prefix("mod ")?
                .strip_suffix(';')
                .map(str::to_string)
        })
        .collect()
}

#[test]
fn every_module_lists_only_modules_drawn_below_it() {
    let (layers, leaves) = layers();
    let drawn: BTreeSet<String> = layers
        .iter()
        .map(|l| l.module.clone())
        .chain(leaves.clone())
        .collect();
    assert_eq!(
        drawn,
        declared_modules(),
        "the picture draws every module of lib.rs"
    );
    for (k, layer) in layers.iter().enumerate() {
        let below: BTreeSet<&str> = layers[k + 1..].iter().map(|l| l.module.as_str()).collect();
        for used in &layer.uses {
            assert!(
                below.contains(used.as_str()) || leaves.contains(used),
                "{} lists {used}, which is not drawn below it",
                layer.module
            );
        }
    }
}

#[test]
fn no_module_uses_one_its_layer_does_not_list() {
    let (layers, leaves) = layers();
    let exports = root_exports();
    let mut modules: Vec<(String, BTreeSet<String>)> = layers
        .into_iter()
        .map(|layer| (layer.module, layer.uses))
        .collect();
    modules.extend(leaves.iter().map(|leaf| (leaf.clone(), BTreeSet::new())));
    let known: BTreeSet<String> = modules.iter().map(|(m, _)| m.clone()).collect();
    let mut crossings = Vec::new();
    for (module, uses) in &modules {
        let files = module_files(module);
        assert!(!files.is_empty(), "module {module} has no source file");
        for file in files {
            let text = fs::read_to_string(&file).expect("a source file");
            let file = file.strip_prefix(root()).unwrap_or(&file).to_path_buf();
            for name in crate_paths(&library_code(&text)) {
                let target = if known.contains(&name) {
                    name.clone()
                } else if let Some(module) = exports.get(&name) {
                    module.clone()
                } else {
                    panic!(
                        "{}: crate::{name} is neither a module nor a root export",
                        file.display()
                    );
                };
                if &target != module && !uses.contains(&target) {
                    crossings.push(format!("{}: crate::{name} ({target})", file.display()));
                }
            }
        }
    }
    assert!(
        crossings.is_empty(),
        "uses that docs/architecture.md's layers do not allow:\n{}",
        crossings.join("\n")
    );
}

#[test]
fn the_reader_sees_cfg_test_items_and_groups() {
    let code = library_code(
        "use crate::mesh::VertexId; // crate::graph in a comment\n\
         #[cfg(test)]\nmod tests {\n    use crate::reconstruct;\n}\n\
         #[cfg(test)]\nuse crate::stages;\nuse crate::{error::Error, Point};\n",
    );
    let names: Vec<String> = crate_paths(&code).into_iter().collect();
    assert_eq!(names, ["Point", "error", "mesh"]);
}
