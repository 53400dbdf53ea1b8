//! Flores et al.: hysteresis damping valid over the whole restitution range.

use super::lankarani_nikravesh::restitution_in_unit_interval;
use super::{per_approach_speed, Hertz, HuntCrossley, Indentation, NormalLaw};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Flores law f_n = k·δ^n·(1 + χ·δ̇) with χ = 8·(1 − ce)/(5·ce·δ̇0) (s/m)
/// (Flores, Machado, Silva & Martins 2011).
///
/// Unlike Lankarani–Nikravesh it stays accurate for low restitution. δ̇0 ≤ 0 drops
/// the damping; ce = 0 gives unbounded damping, saturated at [`Real::MAX`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Flores<T> {
    /// Contact stiffness k (N/m^n).
    pub stiffness: T,
    /// Exponent n (dimensionless).
    pub exponent: T,
    /// Coefficient of restitution ce (dimensionless, 0 < ce ≤ 1).
    pub restitution: T,
}

super::law_parameters!(Flores {
    stiffness: "N/m^n", "k, contact stiffness";
    exponent: "-", "n, force exponent";
    restitution: "-", "ce, coefficient of restitution";
});

impl<T: Real> Flores<T> {
    /// Elastic (non-dissipative) part k·δ^n (N) of the force; 0 for δ ≤ 0.
    #[inline]
    pub fn elastic_force(&self, depth: T) -> T {
        Hertz::elastic_force(self.stiffness, self.exponent, depth)
    }

    /// The Hunt–Crossley damping factor χ = 8·(1 − ce)/(5·ce·δ̇0) (s/m).
    #[inline]
    pub fn damping_factor(&self, approach_speed: T) -> T {
        let ce = self.restitution;
        let coefficient = (T::of(8.0) * (T::one() - ce) / (T::of(5.0) * ce)).saturate();
        per_approach_speed(coefficient, approach_speed)
    }
}

impl<T: Real> NormalLaw<T> for Flores<T> {
    #[inline]
    fn normal_force(&self, contact: &Indentation<T>) -> T {
        let damping = self.damping_factor(contact.approach_speed);
        HuntCrossley::family_force(self.stiffness, self.exponent, damping, contact)
    }

    fn validate(&self) -> Result<(), LawError> {
        Hertz::validate_elastic(self.stiffness, self.exponent)?;
        restitution_in_unit_interval(self.restitution)
    }
}
