//! Linear torsional spring.

use crate::error::require_non_negative;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// A linear torsional spring in a revolute joint: τ = −k·(θ − θ₀) (the stiffness
/// term of MSC ADAMS's rotational SPRINGDAMPER, KT and ANGLE). Conservative: it stores
/// ½k·(θ − θ₀)² (J).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpring<T> {
    /// Torsional stiffness k ≥ 0 (N·m/rad).
    pub stiffness: T,
    /// Rest angle θ₀ (rad), where the spring gives no torque.
    pub rest_angle: T,
}

crate::law::map_fields!(JointSpring {
    stiffness,
    rest_angle
});

impl<T: Real> JointSpring<T> {
    /// The name of this term in a [`super::JointLaw`].
    pub const NAME: &'static str = "spring";

    /// Torque on the child (N·m) at joint angle θ `angle` (rad); saturates at
    /// ±[`Real::MAX`], NaN propagates.
    #[inline]
    pub fn torque(&self, angle: T) -> T {
        (-self.stiffness * (angle - self.rest_angle)).saturate()
    }

    /// Checks k ≥ 0 and finite, θ₀ finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.stiffness, "spring.stiffness")?;
        if self.rest_angle >= -T::MAX && self.rest_angle <= T::MAX {
            Ok(())
        } else {
            Err(LawError::OutOfRange {
                parameter: "spring.rest_angle",
                allowed: "(−∞, ∞)",
            })
        }
    }
}
