//! Stiffness exponent: the elastic force grows with another power of δ than the base law's.

use super::while_touching;
use crate::error::require_positive;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// A change Δ of the elastic exponent: the term f_el(δ)·((δ/δ_ref)^Δ − 1) (N) while
/// δ > 0, with f_el the base law's elastic force.
///
/// Added to the base, the elastic part becomes f_el(δ)·(δ/δ_ref)^Δ — for a Hertz base
/// k·δ^(n+Δ)·δ_ref^(−Δ). At δ = δ_ref the force is unchanged, so an identified Δ
/// tilts the force curve about the reference depth instead of trading off against
/// the stiffness k; pick δ_ref near the typical maximum indentation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StiffnessExponent<T> {
    /// Exponent change Δ (dimensionless), any finite value.
    pub exponent_change: T,
    /// Reference depth δ_ref (m), > 0, where the force is left unchanged.
    pub reference_depth: T,
}

crate::law::law_parameters!(StiffnessExponent {
    exponent_change: "-", "Δ, change of the elastic exponent";
    reference_depth: "m", "δ_ref, depth where the force is unchanged";
});

impl<T: Real> StiffnessExponent<T> {
    /// Catalogue name, as a diagnosis spells it.
    pub fn name(&self) -> &'static str {
        "stiffness_exponent"
    }

    /// The additive term f_el·((δ/δ_ref)^Δ − 1) (N) at indentation δ (m), given the
    /// base law's elastic force f_el (N) at the same δ
    /// ([`crate::law::AnyNormalLaw::elastic_force`]). Exactly 0 for δ ≤ 0, NaN for a
    /// NaN δ, saturated at ±[`Real::MAX`].
    #[inline]
    pub fn force(&self, depth: T, elastic_force: T) -> T {
        while_touching(depth, || {
            let ratio = (depth / self.reference_depth).pow(self.exponent_change);
            elastic_force * (ratio.saturate() - T::one())
        })
    }

    /// Checks that Δ is finite and δ_ref > 0 (finite).
    pub fn validate(&self) -> Result<(), LawError> {
        if self.exponent_change.abs() > T::MAX || self.exponent_change.is_nan() {
            return Err(LawError::OutOfRange {
                parameter: "stiffness_exponent.exponent_change",
                allowed: "(−∞, ∞)",
            });
        }
        require_positive(self.reference_depth, "stiffness_exponent.reference_depth")
    }
}
