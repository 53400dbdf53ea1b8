//! A joint's travel limits.

use crate::error::require_non_negative;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Travel limits as stops: past `upper` (or below `lower`) a stiff one-sided spring and
/// damper pushes the joint back, τ = min(0, −k·(θ − θ_max) − c·θ̇) above and max(0,
/// −k·(θ − θ_min) − c·θ̇) below (the damper never pulls the joint into its stop, as the
/// contact laws' damping never pulls two bodies together); nothing between them. For a
/// slide the same in m, N/m, N·s/m.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointLimit<T> {
    /// Lowest angle θ_min (rad) before the stop pushes.
    pub lower: T,
    /// Highest angle θ_max ≥ θ_min (rad).
    pub upper: T,
    /// The stop's stiffness k ≥ 0 (N·m/rad).
    pub stiffness: T,
    /// The stop's damping c ≥ 0 (N·m·s/rad).
    pub damping: T,
}

crate::law::map_fields!(JointLimit {
    lower,
    upper,
    stiffness,
    damping
});

impl<T: Real> JointLimit<T> {
    /// The name of this term in a [`super::JointLaw`].
    pub const NAME: &'static str = "limit";

    /// Torque on the child (N·m) at angle θ `angle` (rad) and rate θ̇ `rate` (rad/s):
    /// 0 between the limits; saturates at ±[`Real::MAX`]; NaN in either gives NaN.
    #[inline]
    pub fn torque(&self, angle: T, rate: T) -> T {
        if angle.is_nan() || rate.is_nan() {
            return angle + rate;
        }
        let push = |beyond: T| -self.stiffness * beyond - self.damping * rate;
        if angle > self.upper {
            push(angle - self.upper).min(T::zero()).saturate()
        } else if angle < self.lower {
            push(angle - self.lower).max(T::zero()).saturate()
        } else {
            T::zero()
        }
    }

    /// Checks θ_min ≤ θ_max, both finite, and k, c ≥ 0 and finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.stiffness, "limit.stiffness")?;
        require_non_negative(self.damping, "limit.damping")?;
        let finite = |x: T| x >= -T::MAX && x <= T::MAX;
        if finite(self.lower) && finite(self.upper) && self.lower <= self.upper {
            Ok(())
        } else {
            Err(LawError::OutOfRange {
                parameter: "limit.upper",
                allowed: "[limit.lower, ∞), both finite",
            })
        }
    }
}
