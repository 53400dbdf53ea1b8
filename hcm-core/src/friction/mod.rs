//! Tangential (friction) laws: the friction force f_f at a contact, perpendicular to
//! the common normal (paper Section 3.1.3).

mod velocity_step;

pub use velocity_step::VelocityStepFriction;
