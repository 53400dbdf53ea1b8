//! Hunt–Crossley: Hertz with damping proportional to the elastic force.

use super::{Hertz, Indentation, NormalLaw};
use crate::error::require_non_negative;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Hunt–Crossley law f_n = k·δ^n·(1 + χ·δ̇) for δ > 0 (Hunt & Crossley 1975).
///
/// The damping k·χ·δ^n·δ̇ vanishes with δ, so the force is continuous at touch-down.
/// Lankarani–Nikravesh and Flores are this law with χ set from the restitution and
/// the approach speed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HuntCrossley<T> {
    /// Contact stiffness k (N/m^n).
    pub stiffness: T,
    /// Exponent n (dimensionless).
    pub exponent: T,
    /// Damping factor χ (s/m).
    pub damping: T,
}

super::law_parameters!(HuntCrossley {
    stiffness: "N/m^n", "k, contact stiffness";
    exponent: "-", "n, force exponent";
    damping: "s/m", "χ, damping factor";
});

impl<T: Real> HuntCrossley<T> {
    /// Elastic (non-dissipative) part k·δ^n (N) of the force; 0 for δ ≤ 0.
    #[inline]
    pub fn elastic_force(&self, depth: T) -> T {
        Hertz::elastic_force(self.stiffness, self.exponent, depth)
    }

    /// k·δ^n·(1 + χ·δ̇) (N), 0 for δ ≤ 0: the force of every law of this family.
    #[inline]
    pub fn family_force(stiffness: T, exponent: T, damping: T, contact: &Indentation<T>) -> T {
        let elastic = Hertz::elastic_force(stiffness, exponent, contact.depth);
        (elastic + elastic * damping * contact.rate).saturate()
    }
}

impl<T: Real> NormalLaw<T> for HuntCrossley<T> {
    #[inline]
    fn normal_force(&self, contact: &Indentation<T>) -> T {
        Self::family_force(self.stiffness, self.exponent, self.damping, contact)
    }

    fn validate(&self) -> Result<(), LawError> {
        Hertz::validate_elastic(self.stiffness, self.exponent)?;
        require_non_negative(self.damping, "damping")
    }
}
