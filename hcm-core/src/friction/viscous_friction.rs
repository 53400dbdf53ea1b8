//! Viscous (speed-proportional) friction added to the dry friction law.

use crate::error::require_non_negative;
use crate::{LawError, Real};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Viscous friction at a touching point: **f_v** = −c_v·**v_t**, with **v_t** the slip
/// velocity (m/s, the relative velocity's part perpendicular to the normal).
///
/// A lubricated or soft contact resists sliding more the faster it slides; a dry STEP
/// or Coulomb law (Eq 10–11) alone holds μ constant above v_d.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViscousFriction<T> {
    /// Viscous coefficient c_v per contact point (N·s/m).
    pub coefficient: T,
}

crate::law::map_fields!(ViscousFriction { coefficient });

impl<T: Real> ViscousFriction<T> {
    /// The catalogue name.
    pub const NAME: &'static str = "viscous_friction";

    /// Force on body 1 (N) for slip velocity `slip` (m/s, already perpendicular to
    /// the normal); saturates at ±[`Real::MAX`], NaN propagates.
    #[inline]
    pub fn force(&self, slip: &Vector3<T>) -> Vector3<T> {
        slip.map(|v| (-self.coefficient * v).saturate())
    }

    /// Checks c_v ≥ 0 and finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.coefficient, "viscous_friction.coefficient")
    }
}
