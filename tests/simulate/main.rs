//! The simulator and the replay of recorded motion: independent references, shipped scenes, figures.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test simulate <module>::`.

mod cube_drop;
mod cube_drop_reference;
mod cube_toss;
mod figures_readable;
mod joints;
mod peg_in_hole;
mod peg_speed;
mod simulate_figures;
mod simulation;
mod variation_tails;
