//! The final faces of the held-out tosses (`crate::replay::ensemble`): the fitted
//! model's ensembles, their contact scatter chosen on the training tosses, scored
//! against the single replays.

use crate::dataset::Dataset;
use crate::progress::{in_stage, Progress, Stage};
use crate::replay::{
    calibrate_scatter, forecast_faces, summarize_faces, FaceSummary, Spread, TossError, SCATTERS,
};
use crate::scenario::Model;
use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};

/// Seed of the ensembles' draws.
const SEED: u64 = 1;

/// What the faces stage found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaceResults {
    /// The contact scatter chosen (relative σ, –).
    pub(crate) scatter: f64,
    /// Each scatter tried with its mean Brier score over the training tosses (–).
    pub(crate) calibration: Vec<(f64, f64)>,
    /// The held-out tosses' scores.
    pub(crate) held_out: FaceSummary,
}

/// The held-out faces of `fitted` by ensembles of `members`, the scatter chosen on
/// `training`; reports [`Stage::Faces`].
pub(crate) fn faces(
    fitted: &Model,
    training: &Dataset,
    held_out: &Dataset,
    members: usize,
    progress: &dyn Progress,
) -> Result<FaceResults, TossError> {
    let steps = (training.runs.len() * SCATTERS.len() + held_out.runs.len()) as u64;
    let done = AtomicU64::new(0);
    let tick = || progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps);
    in_stage(progress, Stage::Faces, steps, || {
        let spread = Spread {
            members,
            inflation: Some(1.0),
            scatter: Some(0.0),
            seed: SEED,
        };
        let (scatter, calibration) = calibrate_scatter(fitted, training, spread, &SCATTERS, tick)?;
        let spread = Spread {
            scatter: Some(scatter),
            ..spread
        };
        let forecasts = forecast_faces(fitted, held_out, spread, tick)?;
        Ok(FaceResults {
            scatter,
            calibration,
            held_out: summarize_faces(&forecasts, members),
        })
    })
}
