//! Diagnosis: where a physics model departs from measured data, which physical effect
//! is missing, the model extended with it, and what the extension gains.
//!
//! The data path: [`ContactSamples`] (the measured contact, sample by sample) → noise floor
//! and residual structure (what is wrong) → catalogue of candidate effects → sparse
//! selection → joint re-fit (the extended model) → gain on held-out runs.

pub use crate::identify::{contact_samples, ContactSamples};
mod catalogue;
mod diagnosis;
mod family;
mod force_chance;
pub use force_chance::{ChanceRound, ChanceTrial, ForceChance, NamedChance};
mod gain;
mod held_out;
mod naming;
mod noise;
mod nonlinearity;
mod paired;
pub mod power;
pub use paired::Paired;
mod quality;
mod report;
mod rounds;
mod select;
mod sensor;
mod structure;
mod verdict;
pub use diagnosis::{diagnose, DiagnoseSettings, Diagnosis};
mod drag;
mod effects;
mod extended;
pub use extended::extended_physics;
mod json;
pub use json::diagnosis_json;
mod written;
pub use effects::{apply_at, Catalogue, Effect, Scales, Site, CATALOGUE, CHANCES};
pub use written::{write_diagnosis, DiagnosisOf};
mod momentum;
mod motion;
mod rigid;
pub use catalogue::{line_candidates, Candidate};
pub use drag::fit_drag;
pub use family::Family;
pub use gain::{GainRow, GainTable};
pub use momentum::sensor_gain;
pub use momentum::SensorGain;
pub use motion::diagnose_motion;
pub use motion::{
    diagnose_motion_split, MotionDiagnoseError, MotionDiagnosis, GAIN_T, MIN_GAIN, MIN_HELD_OUT,
    RIVAL_T,
};
pub use motion::{diagnose_motion_with, CandidateResult, MotionBase};
pub use naming::{name_causes_beside_momentum, Naming};
pub use noise::noise_floor;
pub use report::answer_line;
pub use report::{answer, diagnosis_markdown};
pub use rigid::{diagnose_rigid, RigidDiagnoseSettings, RigidDiagnosis};
pub use select::BaseFreedom;
pub use select::{refit, Cause};
pub use select::{select, Refit, Selection};
pub use structure::structure_figures;
