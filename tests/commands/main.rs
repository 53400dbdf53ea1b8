//! The `hcm` binary as a user meets it: every command end to end, help, bad input, outputs, the data format, reproduce, and fuzzed readers.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test commands <module>::`.

mod bad_input;
mod broken_pipe;
mod cli;
mod cube_reproduce;
mod dataset_format;
mod diagnose_force_chance;
mod diagnose_given;
mod diagnose_poses_outputs;
mod elbow_reproduce;
mod fuzz;
mod help;
mod joint_residual;
mod members;
mod outputs;
mod peg_reproduce;
mod predict_mechanism;
mod results_json;
mod rigid_bad_data;
mod rigid_pipeline;
mod rigid_scenario_errors;
mod shards;
mod simulate_members;
