//! Variable stiffness: stiffness grows with the contact radius, Eq 6–7.

use super::{touching, Indentation, NormalLaw};
use crate::error::{require_non_negative, require_positive};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Variable-stiffness law of a sphere on a flat body, Eq 6–7, **as printed**:
///
/// k(δ) = c·E*·a(δ), a(δ) = √(2rδ − δ²),
/// f_n = k(δ)·δ + 2λ·√(k(δ)·m_e)·δ·δ̇.
///
/// The extra δ in the damping term makes λ carry units of 1/m; this literal form
/// is the one that reproduces the paper's tables. Only the product c·E* enters the
/// force. For δ > 2r the radicand is clamped at 0 (no contact area, no force).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VariableStiffness<T> {
    /// Surface loading coefficient c (dimensionless, 4/3 ≤ c ≤ 2π).
    pub surface_loading: T,
    /// Effective modulus E* (Pa), [`crate::geometry::effective_modulus`].
    pub effective_modulus: T,
    /// Sphere radius r (m).
    pub radius: T,
    /// Damping λ (1/m), Eq 6 literal.
    pub damping: T,
    /// Effective mass m_e = m1·m2/(m1 + m2) (kg); the ball's mass on fixed ground.
    pub effective_mass: T,
}

super::law_parameters!(VariableStiffness {
    surface_loading: "-", "c, surface loading coefficient (4/3…2π)";
    effective_modulus: "Pa", "E*, effective modulus";
    radius: "m", "r, sphere radius";
    damping: "1/m", "λ, damping (literal Eq 6)";
    effective_mass: "kg", "m_e, effective mass";
});

impl<T: Real> VariableStiffness<T> {
    /// Elastic (non-dissipative) part k(δ)·δ (N) of Eq 6; 0 for δ ≤ 0.
    #[inline]
    pub fn elastic_force(&self, depth: T) -> T {
        if touching(depth) {
            (self.stiffness_at(depth) * depth).saturate()
        } else {
            T::zero()
        }
    }

    /// Effective contact stiffness k(δ) = c·E*·√(2rδ − δ²) (N/m), Eq 7.
    #[inline]
    pub fn stiffness_at(&self, depth: T) -> T {
        let radicand = T::of(2.0) * self.radius * depth - depth * depth;
        let area_radius = if radicand > T::zero() {
            radicand.square_root()
        } else if radicand.is_nan() {
            radicand
        } else {
            T::zero()
        };
        (self.surface_loading * self.effective_modulus * area_radius).saturate()
    }
}

impl<T: Real> NormalLaw<T> for VariableStiffness<T> {
    #[inline]
    fn normal_force(&self, contact: &Indentation<T>) -> T {
        let depth = contact.depth;
        if !touching(depth) {
            return T::zero();
        }
        let k = self.stiffness_at(depth);
        let damping = T::of(2.0) * self.damping * (k * self.effective_mass).square_root() * depth;
        (k * depth + damping * contact.rate).saturate()
    }

    fn validate(&self) -> Result<(), LawError> {
        require_positive(self.surface_loading, "surface_loading")?;
        require_positive(self.effective_modulus, "effective_modulus")?;
        require_positive(self.radius, "radius")?;
        require_non_negative(self.damping, "damping")?;
        require_positive(self.effective_mass, "effective_mass")
    }
}
