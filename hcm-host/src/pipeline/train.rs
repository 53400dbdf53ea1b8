//! Stage 3: the residual network that learns what PM2 misses, and its int8 twin — the
//! train stage ([`crate::train::train_force_residual`]) on the example's contact.

use super::{PipelineError, Progress, CONTACT};
use crate::dataset::Dataset;
use crate::scenario::Model;
use crate::train::{train_force_residual, ResidualSettings, TrainSettings, Trained};

/// Epochs of quantisation-aware fine-tuning of the int8 twin.
pub(crate) const INT8_EPOCHS: usize = 20;

/// Trains the shipped residual architecture on the measured − PM2 force of the
/// `training` set's contact samples (`pm2` is the scenario with PM2 in place), then
/// its int8 twin; both seeded with `seed`.
pub fn train_residual(
    pm2: &Model,
    training: &Dataset,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Trained, PipelineError> {
    let settings = ResidualSettings {
        epochs: TrainSettings::default().max_epochs,
        int8_epochs: INT8_EPOCHS,
        seed,
    };
    Ok(train_force_residual(
        pm2, training, CONTACT, &settings, progress,
    )?)
}
