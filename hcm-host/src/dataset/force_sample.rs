//! One in-contact sample of a recorded contact on its line of centres: the state a
//! normal law reads and the force the data measured there.

use hcm_core::effect::ContactMemory;
use hcm_core::law::Indentation;

/// One in-contact sample: the state a normal law reads and the force it should give.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceSample {
    /// Indentation δ (m).
    pub depth: f64,
    /// Indentation rate δ̇ (m/s).
    pub rate: f64,
    /// Approach speed δ̇0 of the sample's impact (m/s).
    pub approach_speed: f64,
    /// Deepest indentation δ_max (m) of the sample's impact so far.
    pub max_depth: f64,
    /// Measured normal force f_n (N).
    pub force: f64,
}

impl ForceSample {
    /// The sample's state as the contact model reads it: (δ, δ̇, δ̇0) and δ_max.
    pub fn state(&self) -> (Indentation<f64>, ContactMemory<f64>) {
        (
            Indentation {
                depth: self.depth,
                rate: self.rate,
                approach_speed: self.approach_speed,
            },
            ContactMemory {
                max_depth: self.max_depth,
            },
        )
    }
}
