//! Adhesion: a constant attraction while the bodies touch (DMT type).

use super::while_touching;
use crate::error::require_non_negative;
use crate::law::Indentation;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// DMT-type adhesion: the term −a (N) while δ > 0.
///
/// Derjaguin–Muller–Toporov adhesion adds a constant attraction, the pull-off force
/// (2π·R·w for a sphere of radius R and work of adhesion w), to the Hertz force for
/// the whole contact. The force therefore steps by −a at touch-down and by +a at
/// separation; the range of the surface forces outside contact is neglected.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Adhesion<T> {
    /// Pull-off force a (N), ≥ 0.
    pub pull_off_force: T,
}

crate::law::law_parameters!(Adhesion {
    pull_off_force: "N", "a, pull-off force";
});

impl<T: Real> Adhesion<T> {
    /// Catalogue name, as a diagnosis spells it.
    pub fn name(&self) -> &'static str {
        "adhesion"
    }

    /// The additive term −a (N); exactly 0 for δ ≤ 0, NaN for a NaN δ.
    #[inline]
    pub fn force(&self, contact: &Indentation<T>) -> T {
        while_touching(contact.depth, || -self.pull_off_force)
    }

    /// Checks a ≥ 0 (finite).
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.pull_off_force, "adhesion.pull_off_force")
    }
}
