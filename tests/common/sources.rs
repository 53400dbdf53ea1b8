//! The Rust sources and the Markdown pages of a tree, for the tests that read the code
//! itself (tests/repository/layers.rs, tests/repository/function_length.rs) and the documentation
//! (tests/repository/readme.rs, tests/repository/docs_results.rs).

use std::fs;
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, unit-test files (`tests.rs`, a `tests/` folder)
/// excluded, sorted.
pub fn rust_sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    collect(dir, &mut out);
    out.sort();
    out
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() && name != "tests" {
            collect(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") && name != "tests.rs" {
            out.push(path);
        }
    }
}

/// The documentation's pages: `README.md`, then every `.md` file under `docs/` (sorted,
/// subdirectories included), each as a path relative to `root`.
pub fn markdown_pages(root: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    collect_markdown(&root.join("docs"), &mut found);
    found.sort();
    found.insert(0, root.join("README.md"));
    found
        .into_iter()
        .map(|path| path.strip_prefix(root).unwrap().to_path_buf())
        .collect()
}

fn collect_markdown(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            collect_markdown(&path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
}
