//! The one classification of every catalogue's candidates: what part of the model (or
//! of the measurement) a candidate changes.

use serde::Serialize;

/// What kind of cause a candidate is. Two candidates of different families that
/// explain the data equally well make an answer ambiguous rather than pick one; a
/// measurement cause is reported, not added to the physics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Family {
    /// The friction law's coefficients or shape.
    Friction,
    /// Couples against the bodies' relative rotation (torsional, rolling).
    Resistance,
    /// The normal law: its damping (the impact's dissipation), adhesion, plasticity,
    /// stiffness, or another law in its place.
    Normal,
    /// How the data were measured (the sensor, the tracker, the table's calibration),
    /// not the physics.
    Measurement,
    /// The body's own properties (inertia, shape, drag through the air).
    Body,
    /// A mechanism's joints: their own friction, stiffness, placement.
    Joint,
    /// Chance: how a run varies from the next (the contact's parameters, the start
    /// state, the fixed body's place), a spread the model carries and forecasts draw.
    Chance,
}

impl Family {
    /// The family's name in a report (`friction`, `resistance`, `normal`,
    /// `measurement`, `body`, `joint`, `chance`), as serialised.
    pub fn name(self) -> &'static str {
        match self {
            Family::Friction => "friction",
            Family::Resistance => "resistance",
            Family::Normal => "normal",
            Family::Measurement => "measurement",
            Family::Body => "body",
            Family::Joint => "joint",
            Family::Chance => "chance",
        }
    }

    /// `physical` (a term the extended model carries), `measurement` (a correction of
    /// the data) or `chance` (a spread the extended model carries): the kind the force
    /// diagnosis reports for each cause.
    pub fn kind(self) -> &'static str {
        match self {
            Family::Measurement => "measurement",
            Family::Chance => "chance",
            _ => "physical",
        }
    }
}

/// Serialises a family as its [`Family::kind`].
pub(crate) fn serialize_kind<S: serde::Serializer>(
    family: &Family,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(family.kind())
}
