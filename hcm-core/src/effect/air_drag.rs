//! Air drag: quadratic drag on a body in flight.

use crate::error::require_non_negative;
use crate::{LawError, Real};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Quadratic air drag f = −c·|v|·v (N) on a body moving at velocity v (m/s).
///
/// A body effect, not a contact term: it acts between contacts, whatever the
/// normal law, so it is not a [`super::ContactEffect`]. For a body of frontal area A
/// and drag coefficient C_d in air of density ρ_air, c = ½·ρ_air·C_d·A.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AirDrag<T> {
    /// Drag coefficient c (kg/m), ≥ 0.
    pub coefficient: T,
}

crate::law::law_parameters!(AirDrag {
    coefficient: "kg/m", "c = ½·ρ_air·C_d·A, drag coefficient";
});

impl<T: Real> AirDrag<T> {
    /// Catalogue name, as a diagnosis spells it.
    pub fn name(&self) -> &'static str {
        "air_drag"
    }

    /// Drag force −c·|v|·v (N) for the body's velocity v (m/s), in v's frame.
    ///
    /// Opposes v; zero at rest. NaN in v or c gives NaN components; each component
    /// saturates at ±[`Real::MAX`].
    pub fn force(&self, velocity: &Vector3<T>) -> Vector3<T> {
        // Saturating |v| first keeps 0·∞ (c = 0 at an overflowing |v|) from giving NaN.
        let scale =
            (self.coefficient * velocity.norm_squared().square_root().saturate()).saturate();
        velocity.map(|component| (-scale * component).saturate())
    }

    /// Checks c ≥ 0 (finite).
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.coefficient, "air_drag.coefficient")
    }
}
