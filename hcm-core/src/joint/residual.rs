//! A joint's learned torque: a one-output residual network read from the joint's own
//! state [θ (rad), θ̇ (rad/s)] (a slide's [s (m), ṡ (m/s)]), its output the torque on
//! the child about the axis (N·m; a slide's force along it, N) that the joint's law
//! misses — the paper's hybrid model (Section 3.2) applied to a joint instead of a
//! contact: τ = τ_law(θ, θ̇) + r(θ, θ̇).
//!
//! The controller evaluates the same sum as the host's simulator, through the same
//! network ([`crate::residual::Mlp`] as a [`Residual`]): outside the network's training
//! envelope, on a NaN input or without a network, the residual adds nothing and the law
//! stands alone.
//!
//! ```
//! use hcm_core::joint::{hybrid_torque, JointLaw, JointViscous};
//! use hcm_core::model::NoResidual;
//!
//! let law = JointLaw { viscous: Some(JointViscous { damping: 0.02_f32 }), ..JointLaw::ZERO };
//! // Without a network the hybrid torque is the law's (N·m).
//! assert_eq!(hybrid_torque(&law, &NoResidual, 0.3, 2.0), law.torque(0.3, 2.0));
//! ```

use super::JointLaw;
use crate::model::{Correction, Residual};
use crate::Real;

/// Inputs of a joint's residual: θ (rad) and θ̇ (rad/s) — a slide's s (m) and ṡ (m/s).
pub const JOINT_INPUTS: usize = 2;

/// The residual's torque on the child (N·m) at joint angle `angle` (rad) and rate
/// `rate` (rad/s): a one-output network's output; `None` where it is switched off
/// (outside its envelope, NaN in, no network) or where `residual` is not a one-output
/// network.
#[inline]
pub fn residual_torque<T: Real, R: Residual<T>>(residual: &R, angle: T, rate: T) -> Option<T> {
    match residual.correction(&[angle, rate])? {
        Correction::NormalForce(torque) => Some(torque),
        _ => None,
    }
}

/// The hybrid joint torque on the child (N·m): the law's ([`JointLaw::torque`]) plus
/// the residual's where it is on ([`residual_torque`]). NaN in either input gives NaN
/// (the law's), as everywhere in the crate without a panic.
#[inline]
pub fn hybrid_torque<T: Real, R: Residual<T>>(
    law: &JointLaw<T>,
    residual: &R,
    angle: T,
    rate: T,
) -> T {
    let torque = law.torque(angle, rate);
    match residual_torque(residual, angle, rate) {
        Some(correction) => torque + correction,
        None => torque,
    }
}
