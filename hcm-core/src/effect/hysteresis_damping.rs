//! Hysteresis damping: damping that grows with the indentation (Hunt–Crossley family).

use super::while_touching;
use crate::error::require_non_negative;
use crate::law::Indentation;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Hysteresis damping: the term c·δ^p·δ̇ (N) while δ > 0.
///
/// With p = n and c = k·χ it is the damping of Hunt–Crossley; as a separate term it
/// lets the damping's depth dependence differ from the base law's elastic exponent.
/// For p > 0 it vanishes at touch-down, so the force stays continuous there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HysteresisDamping<T> {
    /// Damping coefficient c (N·s/m^(1+p)), ≥ 0.
    pub coefficient: T,
    /// Depth exponent p (dimensionless), ≥ 0; p = 0 is viscous damping.
    pub exponent: T,
}

crate::law::law_parameters!(HysteresisDamping {
    coefficient: "N·s/m^(1+p)", "c, damping coefficient";
    exponent: "-", "p, depth exponent";
});

impl<T: Real> HysteresisDamping<T> {
    /// Catalogue name, as a diagnosis spells it.
    pub fn name(&self) -> &'static str {
        "hysteresis_damping"
    }

    /// The additive term c·δ^p·δ̇ (N); exactly 0 for δ ≤ 0, NaN for a NaN δ,
    /// saturated at ±[`Real::MAX`].
    #[inline]
    pub fn force(&self, contact: &Indentation<T>) -> T {
        while_touching(contact.depth, || {
            // Saturating c·δ^p first keeps ∞·0 (a huge c·δ^p at δ̇ = 0) from giving NaN.
            let coefficient = (self.coefficient * contact.depth.pow(self.exponent)).saturate();
            coefficient * contact.rate
        })
    }

    /// Checks c ≥ 0 and p ≥ 0 (both finite).
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.coefficient, "hysteresis_damping.coefficient")?;
        require_non_negative(self.exponent, "hysteresis_damping.exponent")
    }
}
