//! The joint law: a sum of optional spring, viscous, Coulomb and limit terms.

use super::{JointCoulomb, JointLimit, JointSpring, JointViscous};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// The torque of a revolute joint on its child (N·m): the sum of the terms present,
/// τ = −k·(θ − θ₀) − c·θ̇ − sign(θ̇)·step(|θ̇|, 0, 0, ω_s, τ_c) (the rotational
/// SPRINGDAMPER of MSC ADAMS plus the STEP-smoothed friction of Eq 10–11), plus the
/// stops of a [`JointLimit`] past the ends of its travel. All absent
/// by default ([`JointLaw::ZERO`]); absent terms are omitted when serialised.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointLaw<T> {
    /// Torsional spring −k·(θ − θ₀).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring: Option<JointSpring<T>>,
    /// Viscous damping −c·θ̇.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscous: Option<JointViscous<T>>,
    /// STEP-smoothed Coulomb friction.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coulomb: Option<JointCoulomb<T>>,
    /// Stops at the ends of the joint's travel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limit: Option<JointLimit<T>>,
}

impl<T> JointLaw<T> {
    /// No term: a free joint.
    pub const ZERO: JointLaw<T> = JointLaw {
        spring: None,
        viscous: None,
        coulomb: None,
        limit: None,
    };

    /// True when no term is present (a present term with a zero coefficient counts).
    pub fn is_zero(&self) -> bool {
        self.spring.is_none()
            && self.viscous.is_none()
            && self.coulomb.is_none()
            && self.limit.is_none()
    }
}

impl<T> Default for JointLaw<T> {
    /// No term ([`JointLaw::ZERO`]).
    fn default() -> Self {
        Self::ZERO
    }
}

impl<T: Real> JointLaw<T> {
    /// Torque on the child (N·m) at joint angle θ `angle` (rad) and rate θ̇ `rate`
    /// (rad/s); the parent receives its opposite. Saturates at ±[`Real::MAX`]; NaN in
    /// either input gives NaN, whichever terms are present.
    #[inline]
    pub fn torque(&self, angle: T, rate: T) -> T {
        if angle.is_nan() || rate.is_nan() {
            return angle + rate;
        }
        let mut torque = T::zero();
        if let Some(spring) = &self.spring {
            torque += spring.torque(angle);
        }
        if let Some(viscous) = &self.viscous {
            torque += viscous.torque(rate);
        }
        if let Some(coulomb) = &self.coulomb {
            torque += coulomb.torque(rate);
        }
        if let Some(limit) = &self.limit {
            torque += limit.torque(angle, rate);
        }
        torque.saturate()
    }

    /// Power of the joint torque on the relative motion, τ·θ̇ (W), for θ (rad) and θ̇
    /// (rad/s). The viscous and Coulomb parts are ≤ 0 (dissipation); the spring's is
    /// −d/dt ½k·(θ − θ₀)². Saturates at ±[`Real::MAX`]; NaN propagates.
    #[inline]
    pub fn power(&self, angle: T, rate: T) -> T {
        (self.torque(angle, rate) * rate).saturate()
    }

    /// `Ok` if every present term's parameters are in their domains; otherwise the
    /// error names the first bad field (`"coulomb.smoothing_rate"`).
    pub fn validate(&self) -> Result<(), LawError> {
        self.spring.map_or(Ok(()), |t| t.validate())?;
        self.viscous.map_or(Ok(()), |t| t.validate())?;
        self.coulomb.map_or(Ok(()), |t| t.validate())?;
        self.limit.map_or(Ok(()), |t| t.validate())
    }
}

impl<T: Copy> JointLaw<T> {
    /// The same law with every parameter passed through `f` (e.g. a float cast).
    pub fn map<U>(self, f: impl Fn(T) -> U + Copy) -> JointLaw<U> {
        JointLaw {
            spring: self.spring.map(|t| t.map(f)),
            viscous: self.viscous.map(|t| t.map(f)),
            coulomb: self.coulomb.map(|t| t.map(f)),
            limit: self.limit.map(|t| t.map(f)),
        }
    }
}
