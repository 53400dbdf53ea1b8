//! Lankarani–Nikravesh: Hertz with hysteresis damping set by the restitution, Eq 4–5.

use super::{per_approach_speed, Hertz, HuntCrossley, Indentation, NormalLaw};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Lankarani–Nikravesh law, Eq 4–5:
/// f_n = k·δ^n + d·δ̇ with d = 3·k·(1 − ce²)·δ^n / (4·δ̇0).
///
/// Derived for restitution close to 1; the caller supplies δ̇0 in
/// [`Indentation::approach_speed`]. δ̇0 ≤ 0 (a contact that began at rest) drops the
/// damping term, leaving Hertz.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LankaraniNikravesh<T> {
    /// Contact stiffness k (N/m^n).
    pub stiffness: T,
    /// Exponent n (dimensionless).
    pub exponent: T,
    /// Coefficient of restitution ce (dimensionless, 0 < ce ≤ 1).
    pub restitution: T,
}

super::law_parameters!(LankaraniNikravesh {
    stiffness: "N/m^n", "k, contact stiffness";
    exponent: "-", "n, force exponent";
    restitution: "-", "ce, coefficient of restitution";
});

impl<T: Real> LankaraniNikravesh<T> {
    /// Elastic (non-dissipative) part k·δ^n (N) of the force; 0 for δ ≤ 0.
    #[inline]
    pub fn elastic_force(&self, depth: T) -> T {
        Hertz::elastic_force(self.stiffness, self.exponent, depth)
    }

    /// The equivalent Hunt–Crossley damping factor χ = 3·(1 − ce²)/(4·δ̇0) (s/m).
    #[inline]
    pub fn damping_factor(&self, approach_speed: T) -> T {
        let ce = self.restitution;
        per_approach_speed(T::of(0.75) * (T::one() - ce * ce), approach_speed)
    }
}

impl<T: Real> NormalLaw<T> for LankaraniNikravesh<T> {
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

/// Checks 0 < ce ≤ 1.
pub(super) fn restitution_in_unit_interval<T: Real>(restitution: T) -> Result<(), LawError> {
    if restitution > T::zero() && restitution <= T::one() {
        Ok(())
    } else {
        Err(LawError::OutOfRange {
            parameter: "restitution",
            allowed: "(0, 1]",
        })
    }
}
