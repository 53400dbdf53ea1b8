//! The residual network and the hybrid contact model: training, inputs, motion residual, the peg's HCM, ensembles' final faces, and the pipeline as a library.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test train <module>::`.

mod faces;
mod hybrid_model;
mod joint_residual;
mod motion_residual;
mod paths;
mod peg_hcm;
mod peg_oracle;
mod pipeline;
mod residual_inputs;
mod summed;
mod training;
