//! Training and int8 fine-tuning as progress stages, the same for every residual
//! ([`super::train_force_residual`], [`super::train_wrench_residual`]): the epochs as
//! steps and the error so far as the stage's status.

use super::{
    quantisation_aware, train, Network, QuantiseReport, TrainError, TrainReport, TrainSettings,
};
use crate::progress::{in_stage, Progress, Stage};

/// [`train`] as [`Stage::Train`]: the epochs as steps, the validation RMS (in `unit`,
/// the outputs' unit) as status.
pub(super) fn train_in_stage(
    inputs: &[Vec<f64>],
    targets: &[Vec<f64>],
    settings: &TrainSettings,
    unit: &str,
    progress: &dyn Progress,
) -> Result<(Network, TrainReport), TrainError> {
    let steps = settings.max_epochs as u64;
    in_stage(progress, Stage::Train, steps, || {
        train(inputs, targets, settings, |epoch, _, validation| {
            progress.advance(epoch as u64, steps);
            progress.status(&format!("val RMS {:.2} {unit}", validation.sqrt()));
        })
    })
}

/// [`quantisation_aware`] fine-tuning of `network`'s int8 twin for `epochs` epochs as
/// [`Stage::Int8Twin`]: the epochs as steps, the RMS against the f32 network (in
/// `unit`) as status.
pub(super) fn int8_twin_in_stage(
    network: &Network,
    inputs: &[Vec<f64>],
    epochs: usize,
    seed: u64,
    unit: &str,
    progress: &dyn Progress,
) -> Result<(Network, QuantiseReport), TrainError> {
    let steps = epochs as u64;
    in_stage(progress, Stage::Int8Twin, steps, || {
        quantisation_aware(network, inputs, epochs, seed, |epoch, rms| {
            progress.advance(epoch as u64, steps);
            progress.status(&format!("RMS to f32 {rms:.3} {unit}"));
        })
    })
}
