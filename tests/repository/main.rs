//! The repository itself: the documentation's commands and results, the host's layers and function lengths.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test repository <module>::`.

mod docs_results;
mod function_length;
mod layers;
mod readme;
