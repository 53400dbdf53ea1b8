//! The diagnosis: hidden effects named, none named where none is hidden, and the naming rule's power.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test diagnose <module>::`.

mod diagnose;
mod diagnose_chance;
mod diagnose_fitted_base;
mod diagnose_force_chance;
mod diagnose_joint;
mod diagnose_motion;
mod diagnose_power;
mod diagnose_power_curve;
mod diagnose_power_table;
mod diagnose_rig;
mod diagnose_rigid;
mod diagnose_scatter;
mod diagnose_sensor_gain;
mod effect_recipe;
