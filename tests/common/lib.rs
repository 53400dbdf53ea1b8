//! What the workspace's integration tests (`tests/*.rs`) and benchmarks (`benches/*.rs`)
//! share: the reference setup of the paper's examples, the hidden-effect data sets of the
//! diagnosis tests, and a fixture that runs the `hcm` binary (`cli`).
//!
//! This is the library of the root package `hcm-tests`, so that Cargo finds every file in
//! `tests/` and `benches/` by itself; `tests/common/` holds no tests of its own.

pub mod cli;
pub mod hidden;
pub mod reference;
pub mod rigid_reference;

use std::path::{Path, PathBuf};

/// The path of a scenario file in the workspace's `scenarios/`.
pub fn scenario(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name)
}
