//! The contact laws, effects, geometry, rigid-body dynamics, integrator and residual blob of `hcm-core`, against closed forms and independent oracles.
//!
//! One test binary per area: each file below was a test binary of its own;
//! as modules of one crate the host library is linked once for all of them.
//! Run one file's tests with `cargo test -p hcm-tests --test contact <module>::`.

mod analytic_laws;
mod box_box_parry;
mod box_geometry_parry;
mod effects;
mod integrator;
mod law_properties;
mod residual_blob;
mod rigid_body;
mod rigid_contact;
mod rounded_box;
mod tangential_effects;
