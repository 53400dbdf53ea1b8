//! Viscous joint damping.

use crate::error::require_non_negative;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Viscous damping in a revolute joint: τ = −c·θ̇ (the damping term of MSC ADAMS's
/// rotational SPRINGDAMPER, CT; the rotational twin of [`crate::friction::ViscousFriction`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointViscous<T> {
    /// Damping coefficient c ≥ 0 (N·m·s/rad).
    pub damping: T,
}

crate::law::map_fields!(JointViscous { damping });

impl<T: Real> JointViscous<T> {
    /// The name of this term in a [`super::JointLaw`].
    pub const NAME: &'static str = "viscous";

    /// Torque on the child (N·m) at joint rate θ̇ `rate` (rad/s); saturates at
    /// ±[`Real::MAX`], NaN propagates.
    #[inline]
    pub fn torque(&self, rate: T) -> T {
        (-self.damping * rate).saturate()
    }

    /// Checks c ≥ 0 and finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.damping, "viscous.damping")
    }
}
