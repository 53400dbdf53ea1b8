//! Diagnosis: where a physics model departs from measured data, which physical effect
//! is missing, the model extended with it, and what the extension gains.
//!
//! The data path: [`samples`] (the measured contact, sample by sample) → noise floor
//! and residual structure (what is wrong) → catalogue of candidate effects → sparse
//! selection → joint re-fit (the extended model) → gain on held-out runs.

pub mod samples;

pub use samples::{contact_samples, ContactSamples};
pub mod catalogue;
pub mod diagnosis;
pub mod gain;
pub mod held_out;
pub mod naming;
pub mod noise;
pub mod nonlinearity;
pub mod paired;
pub mod quality;
pub mod report;
pub mod select;
pub mod sensor;
pub mod structure;
pub mod verdict;
pub use diagnosis::{diagnose, DiagnoseSettings, Diagnosis};
pub mod drag;
pub mod momentum;
pub mod motion;
pub mod rigid;
