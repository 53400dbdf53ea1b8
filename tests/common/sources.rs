//! The Rust sources of a tree, for the tests that read the code itself
//! (tests/layers.rs, tests/function_length.rs).

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
