//! Identification: PM1 generation, PM2 by least squares and the genetic algorithm, from force, from motion, from other solvers' and rigs' data.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test identify <module>::`.

mod cube_toss_identify;
mod evaluate_members;
mod identification;
mod independent_solver;
mod motion_scenes;
mod peg_generate;
mod peg_identify;
mod peg_s2;
mod rig_data;
mod rigid_identify_samples;
mod two_bodies;
