//! The repository itself: the documentation's commands and results, the host's layers and function lengths, the Python build's features.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test repository <module>::`.

mod docs_results;
mod features;
mod function_length;
mod layers;
mod readme;
