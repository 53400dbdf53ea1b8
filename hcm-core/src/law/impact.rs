//! MSC ADAMS IMPACT: Hertz-type stiffness with damping ramped in by a STEP, Eq 8–9.

use super::{step, touching, Hertz, Indentation, NormalLaw};
use crate::error::{require_non_negative, require_positive};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// IMPACT law, Eq 8: f_n = max(0, k·δ^e + step(δ, 0, 0, δ_max, d_max)·δ̇).
///
/// The damping coefficient rises from 0 at touch-down to `max_damping` at
/// `full_damping_depth` along the cubic STEP of Eq 9; the force never pulls.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Impact<T> {
    /// Contact stiffness k (N/m^e).
    pub stiffness: T,
    /// Force exponent e (dimensionless).
    pub exponent: T,
    /// Maximum damping coefficient d_max (N·s/m).
    pub max_damping: T,
    /// Indentation δ_max at which the damping reaches d_max (m).
    pub full_damping_depth: T,
}

super::law_parameters!(Impact {
    stiffness: "N/m^e", "k, contact stiffness";
    exponent: "-", "e, force exponent";
    max_damping: "N·s/m", "d_max, maximum damping";
    full_damping_depth: "m", "δ_max, depth of full damping";
});

impl<T: Real> Impact<T> {
    /// Elastic (non-dissipative) part k·δ^e (N) of the force; 0 for δ ≤ 0.
    #[inline]
    pub fn elastic_force(&self, depth: T) -> T {
        Hertz::elastic_force(self.stiffness, self.exponent, depth)
    }

    /// Damping coefficient step(δ, 0, 0, δ_max, d_max) (N·s/m), Eq 9.
    #[inline]
    pub fn damping_at(&self, depth: T) -> T {
        step(
            depth,
            T::zero(),
            T::zero(),
            self.full_damping_depth,
            self.max_damping,
        )
    }
}

impl<T: Real> NormalLaw<T> for Impact<T> {
    #[inline]
    fn normal_force(&self, contact: &Indentation<T>) -> T {
        if !touching(contact.depth) {
            return T::zero();
        }
        let elastic = Hertz::elastic_force(self.stiffness, self.exponent, contact.depth);
        let force = (elastic + self.damping_at(contact.depth) * contact.rate).saturate();
        // `max` written out so that NaN propagates rather than becoming 0.
        if force < T::zero() {
            T::zero()
        } else {
            force
        }
    }

    fn validate(&self) -> Result<(), LawError> {
        Hertz::validate_elastic(self.stiffness, self.exponent)?;
        require_non_negative(self.max_damping, "max_damping")?;
        require_positive(self.full_damping_depth, "full_damping_depth")
    }
}
