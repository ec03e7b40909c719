//! The library's one `unsafe` block is the cache hint in `crates/condt/src/prefetch.rs`; the
//! binary's allocator (Linux with glibc only) is `crates/condt-alloc/src/lib.rs`, where every
//! `unsafe` block must say why it is sound in a `// SAFETY:` comment right above it; the Python
//! package's native module (`python/src`) has one, viewing a NumPy array's rows as points, in
//! `python/src/convert.rs`, with its `// SAFETY:` comment. `lib.rs` denies unsafe code, but a
//! module could still allow it; this test reads every source file and fails on an `unsafe`
//! keyword or an `allow(unsafe_code)` anywhere else.

use std::fs;
use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("src/ is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Whether `line` uses `unsafe` as a word (an `unsafe` block, fn, impl or trait) or allows
/// unsafe code, outside a `//` comment.
fn uses_unsafe(line: &str) -> bool {
    let code = line.split("//").next().unwrap_or("");
    let as_word = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .any(|word| word == "unsafe");
    as_word || code.contains("allow(unsafe_code)")
}

#[test]
fn unsafe_code_appears_only_in_the_prefetch_module_and_the_allocator() {
    // Every crate of the workspace: the sources of each `crates/*/src`.
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for entry in fs::read_dir(&crates).expect("the crates directory") {
        let src = entry.expect("a directory entry").path().join("src");
        if src.is_dir() {
            rust_files(&src, &mut files);
        }
    }
    // And the Python package's native module.
    let python = crates.join("../python/src");
    rust_files(&python, &mut files);
    let prefetch_path = crates.join("condt/src/prefetch.rs");
    let allocator_path = crates.join("condt-alloc/src/lib.rs");
    let binding_path = python.join("convert.rs");
    assert!(
        files.len() > 20,
        "found the sources ({} files)",
        files.len()
    );
    let mut found = Vec::new();
    for file in &files {
        if file.ends_with("condt/src/prefetch.rs")
            || file.ends_with("condt-alloc/src/lib.rs")
            || file.ends_with("python/src/convert.rs")
        {
            continue;
        }
        let text = fs::read_to_string(file).expect("a source file is UTF-8");
        for (k, line) in text.lines().enumerate() {
            if uses_unsafe(line) {
                found.push(format!("{}:{}: {}", file.display(), k + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "unsafe code outside condt/src/prefetch.rs, condt-alloc/src/lib.rs and \
         python/src/convert.rs:\n{}",
        found.join("\n")
    );
    let prefetch = fs::read_to_string(prefetch_path).expect("condt/src/prefetch.rs");
    assert_eq!(
        prefetch.lines().filter(|l| uses_unsafe(l)).count(),
        2,
        "condt/src/prefetch.rs holds one allow and one unsafe block"
    );
    let allocator = fs::read_to_string(allocator_path).expect("condt-alloc/src/lib.rs");
    let unjustified = unsafe_without_safety_comment(&allocator);
    assert!(
        unjustified.is_empty(),
        "condt-alloc/src/lib.rs: unsafe code without a `// SAFETY:` comment right above it \
         (lines {unjustified:?})"
    );
    assert!(
        allocator.lines().filter(|l| uses_unsafe(l)).count() > 5,
        "the scan sees the allocator's unsafe blocks"
    );
    let binding = fs::read_to_string(binding_path).expect("python/src/convert.rs");
    assert!(
        unsafe_without_safety_comment(&binding).is_empty(),
        "python/src/convert.rs: unsafe code without a `// SAFETY:` comment right above it"
    );
    assert_eq!(
        binding.lines().filter(|l| uses_unsafe(l)).count(),
        1,
        "python/src/convert.rs holds one unsafe block"
    );
}

/// The lines (1-based) of `text` that use `unsafe` without a `// SAFETY:` line in the comment
/// block directly above them; `unsafe fn` signatures are exempt (the `GlobalAlloc` trait or the
/// function's `# Safety` section states the contract, which their callers carry).
fn unsafe_without_safety_comment(text: &str) -> Vec<usize> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        if !uses_unsafe(line) || line.trim_start().starts_with("unsafe fn ") {
            continue;
        }
        let comments_above = lines[..k]
            .iter()
            .rev()
            .take_while(|l| l.trim_start().starts_with("//"));
        if !comments_above
            .clone()
            .any(|l| l.trim_start().starts_with("// SAFETY:"))
        {
            found.push(k + 1);
        }
    }
    found
}

#[test]
fn unsafe_lines_need_a_safety_comment_right_above_them() {
    let justified = "// SAFETY: the reason.\n// More of it.\nlet x = unsafe { f() };\n";
    assert!(unsafe_without_safety_comment(justified).is_empty());
    let bare = "// Not a reason.\nlet x = unsafe { f() };\n";
    assert_eq!(unsafe_without_safety_comment(bare), vec![2]);
    let separated = "// SAFETY: a reason for something else.\nlet y = 1;\nunsafe { f() }\n";
    assert_eq!(unsafe_without_safety_comment(separated), vec![3]);
    assert!(unsafe_without_safety_comment("    unsafe fn alloc(&self) {}\n").is_empty());
}

#[test]
fn the_scan_sees_unsafe_blocks_and_allows_but_not_comments_or_names() {
    assert!(uses_unsafe("    unsafe { f() }"));
    assert!(uses_unsafe("#[allow(unsafe_code)]"));
    assert!(uses_unsafe("pub unsafe fn g() {}"));
    assert!(!uses_unsafe("// an unsafe word in a comment"));
    assert!(!uses_unsafe("let unsafe_count = 0;"));
    assert!(!uses_unsafe("#![deny(unsafe_code)]"));
}
