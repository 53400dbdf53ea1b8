//! Hertz: elastic contact without dissipation, Eq 2.

use super::{touching, Indentation, NormalLaw};
use crate::error::require_positive;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Hertz law f_n = k·δ^n for δ > 0, Eq 2.
///
/// Conserves energy: the restitution of a Hertz impact is exactly 1.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hertz<T> {
    /// Contact stiffness k (N/m^n); Eq 3 gives it for spheres and planes
    /// ([`crate::geometry`]).
    pub stiffness: T,
    /// Exponent n (dimensionless), 3/2 for the parabolic pressure of two spheres.
    pub exponent: T,
}

super::law_parameters!(Hertz {
    stiffness: "N/m^n", "k, contact stiffness";
    exponent: "-", "n, force exponent";
});

impl<T: Real> Hertz<T> {
    /// Elastic force k·δ^n (N), shared by every law built on Hertz; 0 for δ ≤ 0.
    #[inline]
    pub fn elastic_force(stiffness: T, exponent: T, depth: T) -> T {
        if touching(depth) {
            (stiffness * depth.pow(exponent)).saturate()
        } else {
            T::zero()
        }
    }

    /// Checks k > 0 and n > 0 (both finite).
    pub fn validate_elastic(stiffness: T, exponent: T) -> Result<(), LawError> {
        require_positive(stiffness, "stiffness")?;
        require_positive(exponent, "exponent")
    }
}

impl<T: Real> NormalLaw<T> for Hertz<T> {
    #[inline]
    fn normal_force(&self, contact: &Indentation<T>) -> T {
        Self::elastic_force(self.stiffness, self.exponent, contact.depth)
    }

    fn validate(&self) -> Result<(), LawError> {
        Self::validate_elastic(self.stiffness, self.exponent)
    }
}
