//! Coulomb (dry) joint friction, smoothed by the STEP of Eq 11.

use crate::error::{require_non_negative, require_positive};
use crate::law::step;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Coulomb friction in a revolute joint, smoothed through zero rate:
///
/// τ = −sign(θ̇)·step(|θ̇|, 0, 0, ω_s, τ_c),
///
/// with the cubic STEP of Eq 9/11 ([`crate::law::step`]), as the velocity-step
/// friction of Eq 10–11 ([`crate::friction::VelocityStepFriction`]) smooths μ from 0
/// at zero slip to μ_s at v_s. Odd in θ̇, 0 at θ̇ = 0, equal to τ_c in magnitude for
/// |θ̇| ≥ ω_s and never above it; |τ| is non-decreasing in |θ̇| up to rounding (in
/// `f32` it dips up to 2 ulps of τ_c below its running maximum inside the band).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointCoulomb<T> {
    /// Friction torque τ_c ≥ 0 (N·m), reached for |θ̇| ≥ ω_s.
    pub torque: T,
    /// Smoothing rate ω_s > 0 (rad/s): the STEP's width.
    pub smoothing_rate: T,
}

crate::law::map_fields!(JointCoulomb {
    torque,
    smoothing_rate
});

impl<T: Real> JointCoulomb<T> {
    /// The name of this term in a [`super::JointLaw`].
    pub const NAME: &'static str = "coulomb";

    /// Torque on the child (N·m) at joint rate θ̇ `rate` (rad/s). ±∞ gives ∓τ_c;
    /// NaN gives NaN. With ω_s ≤ 0 (rejected by `validate`) it is the unsmoothed jump.
    #[inline]
    pub fn torque(&self, rate: T) -> T {
        let full = self.torque;
        let magnitude = step(rate.abs(), T::zero(), T::zero(), self.smoothing_rate, full);
        // Rounding in the cubic may land an ulp above τ_c; a NaN stays NaN.
        let magnitude = if magnitude > full { full } else { magnitude }.saturate();
        if rate < T::zero() {
            magnitude
        } else {
            -magnitude
        }
    }

    /// Checks τ_c ≥ 0 and ω_s > 0, both finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.torque, "coulomb.torque")?;
        require_positive(self.smoothing_rate, "coulomb.smoothing_rate")
    }
}
