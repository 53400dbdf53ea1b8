//! Plasticity: part of the deepest indentation stays when the bodies unload.

use super::ContactMemory;
use crate::law::{touching, Indentation};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Permanent indentation δ_p = ρ·δ_max: a transform of the base law, not a term.
///
/// While loading (δ̇ ≥ 0) or at and beyond the deepest indentation δ_max of this
/// contact nothing changes. While unloading below δ_max the base law is evaluated at
///
/// δ_eff = δ_max·(δ − δ_p)/(δ_max − δ_p) = (δ − ρ·δ_max)/(1 − ρ),
///
/// which equals δ_max at δ = δ_max (the unloading curve meets the loading one) and 0
/// at δ = δ_p > 0: the contact force ends before δ = 0, and since every law gives
/// exactly 0 for δ ≤ 0 it stays 0 below δ_p. The area between the two curves is the
/// energy the plastic deformation absorbs. δ_max comes from [`ContactMemory`], which
/// the caller keeps.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plasticity<T> {
    /// Permanent share ρ = δ_p/δ_max (dimensionless), 0 ≤ ρ < 1.
    pub permanent_ratio: T,
}

crate::law::law_parameters!(Plasticity {
    permanent_ratio: "-", "ρ = δ_p/δ_max, permanent share of the deepest indentation";
});

impl<T: Real> Plasticity<T> {
    /// Catalogue name, as a diagnosis spells it.
    pub fn name(&self) -> &'static str {
        "plasticity"
    }

    /// Permanent indentation δ_p = ρ·δ_max (m) left by the deepest indentation so far.
    #[inline]
    pub fn permanent_depth(&self, memory: &ContactMemory<T>) -> T {
        (self.permanent_ratio * memory.max_depth).saturate()
    }

    /// Indentation δ_eff (m) at which to evaluate the base law.
    ///
    /// δ itself while loading, at or beyond δ_max, and for δ ≤ 0 (apart stays apart);
    /// the unloading map otherwise. NaN in δ, δ̇, δ_max or ρ gives NaN while δ is
    /// not ≤ 0, because whether the contact unloads cannot be decided.
    #[inline]
    pub fn effective_depth(&self, contact: &Indentation<T>, memory: &ContactMemory<T>) -> T {
        let (depth, max_depth, ratio) = (contact.depth, memory.max_depth, self.permanent_ratio);
        if !touching(depth) {
            return depth;
        }
        if let Some(nan) = [contact.rate, max_depth, ratio]
            .into_iter()
            .find(|x| x.is_nan())
        {
            return nan;
        }
        if contact.rate < T::zero() && depth < max_depth {
            ((depth - self.permanent_depth(memory)) / (T::one() - ratio)).saturate()
        } else {
            depth
        }
    }

    /// Checks 0 ≤ ρ < 1.
    pub fn validate(&self) -> Result<(), LawError> {
        if self.permanent_ratio >= T::zero() && self.permanent_ratio < T::one() {
            Ok(())
        } else {
            Err(LawError::OutOfRange {
                parameter: "plasticity.permanent_ratio",
                allowed: "[0, 1)",
            })
        }
    }
}
