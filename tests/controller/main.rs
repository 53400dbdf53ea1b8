//! The controller side: the firmware on an emulated Cortex-M4F and the C API's examples, against the host.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test controller <module>::`.

mod ffi_c_example;
mod firmware;
