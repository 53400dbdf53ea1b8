//! The cube pipeline's stages between reading the tosses and the diagnosis: the fit,
//! the predictions of both parts with both models, and the held-out errors over time
//! and per phase.

use super::errors::{frame_errors, over_time, per_phase, PhaseErrors, TimePoint};
use super::{CubeError, CubeSettings};
use crate::dataset::Dataset;
use crate::identify::{beside_physics, identify_motion, MotionFit, MotionParameters, MotionTarget};
use crate::numerics::optimize::genetic::GeneticSettings;
use crate::pipeline::{Fold, Progress, Stage};
use crate::progress::in_stage;
use crate::replay::{evaluate_tosses, TossEvaluation, TossSetup};
use crate::scenario::{Assignment, Model};
use std::sync::atomic::{AtomicU64, Ordering};

/// The fit on the `training` tosses of `fold`, with a progress stage for the GA and
/// one for the polish.
pub fn fit(
    settings: &CubeSettings,
    model: &Model,
    setup: &TossSetup,
    training: &Dataset,
    fold: Fold,
    progress: &dyn Progress,
) -> Result<(MotionFit, MotionParameters), CubeError> {
    let training = super::strided(training, settings.fit_stride);
    let target = MotionTarget::new(model, &training)?;
    let parameters = MotionParameters::new(model, setup)?;
    let genetic = GeneticSettings {
        seed: settings.seed,
        population: settings.population,
        generations: settings.generations,
        ..GeneticSettings::default()
    };
    let fit = identify_motion(
        model,
        &target,
        &parameters,
        &genetic,
        settings.polish,
        fold,
        progress,
    )?;
    Ok((fit, parameters))
}

/// The fitted table offset and inertia as the `--set`s that apply them (a physics file
/// holds the law and the friction, not the bodies).
pub fn sets(model: &Model, parameters: &MotionParameters, fit: &MotionFit) -> Vec<Assignment> {
    beside_physics(model, parameters, &fit.parameters)
}

/// The split's second fold: the same fit on the held-out tosses (odd numbers), judged
/// on the training ones (even), which it never saw — so that every toss is predicted
/// once by a fit that did not see it (two-fold cross-validation).
pub struct SecondFold {
    /// The fit on the held-out part.
    pub(crate) fit: MotionFit,
    /// The training tosses predicted with it, in the data's order.
    pub(crate) predicted: Vec<TossEvaluation>,
}

/// The second fold: `settings`' fit on `odd`, its predictions of `even`.
pub(crate) fn second_fold(
    settings: &CubeSettings,
    model: &Model,
    setup: &TossSetup,
    odd: &Dataset,
    even: &Dataset,
    progress: &dyn Progress,
) -> Result<SecondFold, CubeError> {
    let (fit, _) = self::fit(settings, model, setup, odd, Fold::Second, progress)?;
    let steps = even.runs.len() as u64;
    let done = AtomicU64::new(0);
    let predicted = in_stage(progress, Stage::Predict(Fold::Second), steps, || {
        evaluate_tosses(&fit.model, even, || {
            progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps)
        })
    })?;
    Ok(SecondFold { fit, predicted })
}

/// Both parts predicted with both models (each in the data's order).
pub struct Predictions {
    /// Held-out tosses, the fitted model.
    pub(crate) held_out_fitted: Vec<TossEvaluation>,
    /// Held-out tosses, the scenario's parameters.
    pub(crate) held_out_scenario: Vec<TossEvaluation>,
    /// Training tosses, the fitted model.
    pub(crate) training_fitted: Vec<TossEvaluation>,
    /// Training tosses, the scenario's parameters.
    pub(crate) training_scenario: Vec<TossEvaluation>,
}

/// Every toss of both parts predicted and scored with `scenario`'s and `fitted`'s
/// parameters, the frozen pose beside each.
pub fn predict(
    scenario: &Model,
    fitted: &Model,
    training: &Dataset,
    held_out: &Dataset,
    progress: &dyn Progress,
) -> Result<Predictions, CubeError> {
    let steps = 2 * (training.runs.len() + held_out.runs.len()) as u64;
    let done = AtomicU64::new(0);
    let tick = || {
        let now = done.fetch_add(1, Ordering::Relaxed) + 1;
        progress.advance(now, steps);
    };
    in_stage(progress, Stage::Predict(Fold::First), steps, || {
        Ok(Predictions {
            held_out_fitted: evaluate_tosses(fitted, held_out, tick)?,
            held_out_scenario: evaluate_tosses(scenario, held_out, tick)?,
            training_fitted: evaluate_tosses(fitted, training, tick)?,
            training_scenario: evaluate_tosses(scenario, training, tick)?,
        })
    })
}

/// The held-out errors over time and per phase, of one model.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ErrorProfile {
    /// Per frame index since the window start.
    pub(crate) over_time: Vec<TimePoint>,
    /// Per phase.
    pub(crate) phases: Vec<PhaseErrors>,
}

/// The held-out profiles of the fitted model and of the scenario's parameters.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Timeline {
    /// The fitted model.
    pub(crate) fitted: ErrorProfile,
    /// The scenario's parameters.
    pub(crate) scenario: ErrorProfile,
}

/// The held-out tosses' error profiles.
pub fn timeline(
    setup: &TossSetup,
    held_out: &Dataset,
    predicted: &Predictions,
) -> Result<Timeline, CubeError> {
    let profile = |evaluations: &[TossEvaluation]| -> Result<ErrorProfile, CubeError> {
        let frames = frame_errors(setup, held_out, evaluations)?;
        Ok(ErrorProfile {
            over_time: over_time(&frames),
            phases: per_phase(&frames),
        })
    };
    Ok(Timeline {
        fitted: profile(&predicted.held_out_fitted)?,
        scenario: profile(&predicted.held_out_scenario)?,
    })
}
