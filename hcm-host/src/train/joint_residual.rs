//! A joint's residual learned from a mechanism's poses: the rows of
//! [`super::joint_samples`] — the joint angle the physics misses a few frames after each
//! recorded state, against the joint's compliance along its own path — trained as the
//! contact-frame residual's rows are ([`super::summed::train_summed`], one output: the
//! torque on the child, N·m), then its int8 twin. `hcm train` runs it on a mechanism's
//! camera data (poses, no force).

use super::joint_samples::joint_rows;
use super::point_residual::summed_explained;
use super::reported::int8_twin_in_stage;
use super::summed::{point_inputs, train_summed};
use super::{ResidualError, ResidualSettings, TrainSettings, Trained, TrainedResidual};
use crate::dataset::Dataset;
use crate::progress::{in_stage, Progress, Stage};
use crate::residual::{HIDDEN, JOINT_WIDTH};
use crate::scenario::Model;

/// The unit of the rows' targets: the joint angle missed.
pub const JOINT_UNITS: &str = "rad";

/// Epochs without a better validation loss before training stops (–).
const PATIENCE: usize = 40;

/// Adam's learning rate (–).
const LEARNING_RATE: f64 = 3e-3;

/// The torque residual of joint `j` of `physics` (the fitted physics, its residual left
/// out) learned from the recorded poses of `training` over `horizon` frames, then its
/// int8 twin, seeded with `settings.seed`. The trained file names the joint where a
/// contact's names its contact.
pub fn train_joint_residual(
    physics: &Model,
    training: &Dataset,
    j: usize,
    horizon: usize,
    settings: &ResidualSettings,
    progress: &dyn Progress,
) -> Result<Trained, ResidualError> {
    let (rows, _) = joint_rows(physics, training, j, horizon)?;
    let train_settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: JOINT_WIDTH,
        max_epochs: settings.epochs,
        patience: PATIENCE,
        learning_rate: LEARNING_RATE,
        seed: settings.seed,
        ..TrainSettings::default()
    };
    let steps = settings.epochs as u64;
    let (network, report, silenced) = in_stage(progress, Stage::Train, steps, || {
        train_summed(&rows, 1, &train_settings, |epoch, _, validation| {
            progress.advance(epoch as u64, steps);
            progress.status(&format!("val RMS {:.3e} {JOINT_UNITS}", validation.sqrt()));
        })
    })?;
    let inputs = point_inputs(&rows);
    let (int8, tuned) = int8_twin_in_stage(
        &network,
        &inputs,
        settings.int8_epochs,
        settings.seed,
        JOINT_UNITS,
        progress,
    )?;
    let explained = summed_explained(&network, &rows);
    Ok(Trained {
        residual: TrainedResidual::new(j, network, int8),
        rows: rows.len(),
        report,
        int8: tuned,
        explained,
        silenced,
    })
}
