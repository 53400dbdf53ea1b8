//! Tangential (friction) laws: the friction force f_f at a contact, perpendicular to
//! the common normal (paper Section 3.1.3), and the tangential effects a contact may
//! add to it (viscous friction, torsional and rolling resistance).

mod spin_resistance;
mod tangential;
mod velocity_step;
mod viscous_friction;

pub use spin_resistance::{RollingResistance, TorsionalResistance};
pub use tangential::TangentialEffects;
pub use velocity_step::VelocityStepFriction;
pub use viscous_friction::ViscousFriction;

#[cfg(test)]
mod tests;
