//! Revolute-joint laws: the torque τ (N·m) a joint applies to its child body about
//! the joint axis, from the joint angle θ (rad) and rate θ̇ (rad/s).
//!
//! ## Conventions
//!
//! - θ (rad) is the child's rotation relative to the parent about the joint axis,
//!   positive by the right-hand rule about the axis; θ̇ (rad/s) is its rate.
//! - τ (N·m) acts on the **child** about the axis; the parent receives −τ.
//! - Power τ·θ̇ (W) is the rate at which the joint does work on the relative motion:
//!   ≤ 0 for [`JointViscous`] and [`JointCoulomb`] (they dissipate), −d/dt ½k·(θ − θ₀)²
//!   for [`JointSpring`] (it stores energy).
//!
//! One law per file, each a small `Copy` value with a `validate`; [`JointLaw`] sums
//! the three, each optional. As everywhere in the crate, evaluation never panics.
//!
//! [`JointViscous`]: crate::joint::JointViscous
//! [`JointCoulomb`]: crate::joint::JointCoulomb
//! [`JointSpring`]: crate::joint::JointSpring
//! [`JointLaw`]: crate::joint::JointLaw
//!
//! ```
//! use hcm_core::joint::{JointCoulomb, JointLaw, JointViscous};
//!
//! let law = JointLaw {
//!     viscous: Some(JointViscous { damping: 0.02_f32 }),
//!     coulomb: Some(JointCoulomb { torque: 0.1, smoothing_rate: 0.01 }),
//!     ..JointLaw::ZERO
//! };
//! assert!(law.validate().is_ok());
//! let tau = law.torque(0.3, 2.0); // N·m: −0.02·2 − 0.1
//! assert!((tau + 0.14).abs() < 1e-6);
//! assert!(law.power(0.3, 2.0) <= 0.0); // W
//! ```

mod coulomb;
mod law;
mod limit;
mod residual;
mod spring;
mod viscous;

pub use coulomb::JointCoulomb;
pub use law::JointLaw;
pub use limit::JointLimit;
pub use residual::{hybrid_torque, residual_torque, JOINT_INPUTS};
pub use spring::JointSpring;
pub use viscous::JointViscous;

#[cfg(test)]
mod tests;
