//! Viscous damping: a dashpot in parallel with the base law (Kelvin–Voigt).

use super::while_touching;
use crate::error::require_non_negative;
use crate::law::Indentation;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Kelvin–Voigt viscous damping: the term c·δ̇ (N) while δ > 0.
///
/// Unlike the Hunt–Crossley family the term does not vanish with δ, so the force
/// jumps by c·δ̇0 at touch-down and pulls (c·δ̇ < 0) just before separation: the
/// force–indentation loop is open at δ = 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViscousDamping<T> {
    /// Damping coefficient c (N·s/m), ≥ 0.
    pub coefficient: T,
}

crate::law::law_parameters!(ViscousDamping {
    coefficient: "N·s/m", "c, damping coefficient";
});

impl<T: Real> ViscousDamping<T> {
    /// Catalogue name, as a diagnosis spells it.
    pub fn name(&self) -> &'static str {
        "viscous_damping"
    }

    /// The additive term c·δ̇ (N); exactly 0 for δ ≤ 0, NaN for a NaN δ, saturated
    /// at ±[`Real::MAX`].
    #[inline]
    pub fn force(&self, contact: &Indentation<T>) -> T {
        while_touching(contact.depth, || self.coefficient * contact.rate)
    }

    /// Checks c ≥ 0 (finite).
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.coefficient, "viscous_damping.coefficient")
    }
}
