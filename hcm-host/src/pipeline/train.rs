//! Stage 3: the residual network that learns what PM2 misses, and its int8 twin.

use super::{PipelineError, Progress, Stage, CONTACT};
use crate::dataset::Dataset;
use crate::identify::samples::force_samples;
use crate::residual::{HIDDEN, WIDTH};
use crate::scenario::Model;
use crate::train::{
    quantisation_aware, residual_pairs, train, QuantiseReport, TrainReport, TrainSettings,
    TrainedResidual,
};

/// Epochs of quantisation-aware fine-tuning of the int8 twin.
pub const INT8_EPOCHS: usize = 20;

/// The trained residual and how its training went.
#[derive(Clone, Debug)]
pub struct Trained {
    /// The network and its int8 twin (`residual.json`).
    pub residual: TrainedResidual,
    /// Training rows: S1's force samples inside the contact.
    pub samples: usize,
    /// The f32 network's training.
    pub report: TrainReport,
    /// The int8 twin's fine-tuning.
    pub int8: QuantiseReport,
}

/// Trains the shipped residual architecture on the measured − PM2 force of the
/// `training` set's contact samples (`pm2` is the scenario with PM2 in place), then
/// its int8 twin; both seeded with `seed`.
pub fn train_residual(
    pm2: &Model,
    training: &Dataset,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Trained, PipelineError> {
    let (samples, _) = force_samples(pm2, training, CONTACT)?;
    let (inputs, outputs) = residual_pairs(&samples, &pm2.contacts[CONTACT].model);
    let settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: WIDTH,
        seed,
        ..TrainSettings::default()
    };
    let epochs = settings.max_epochs as u64;
    progress.begin(Stage::Train, epochs);
    let (network, report) = train(&inputs, &outputs, &settings, |epoch, _, _| {
        progress.advance(epoch as u64, epochs)
    })?;
    progress.end(Stage::Train);
    let twin_epochs = INT8_EPOCHS as u64;
    progress.begin(Stage::Int8Twin, twin_epochs);
    let (int8, tuned) = quantisation_aware(&network, &inputs, INT8_EPOCHS, seed, |epoch, _| {
        progress.advance(epoch as u64, twin_epochs)
    })?;
    progress.end(Stage::Int8Twin);
    Ok(Trained {
        residual: TrainedResidual::new(CONTACT, network, int8),
        samples: inputs.len(),
        report,
        int8: tuned,
    })
}
