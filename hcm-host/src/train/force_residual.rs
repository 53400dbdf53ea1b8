//! The 1D contacts' residual as one stage, the same for `hcm train`, `hcm reproduce`
//! and the diagnosis's HCM: the training rows of a contact (measured − PM2 normal force
//! at the data's force samples inside the contact), the shipped architecture
//! ([`HIDDEN`] × [`WIDTH`]) trained on them, and its quantisation-aware int8 twin.

use super::reported::{int8_twin_in_stage, train_in_stage};
use super::{
    residual_pairs, Network, TrainError, TrainReport, TrainSettings, Trained, TrainedResidual,
};
use crate::dataset::Dataset;
use crate::identify::force_samples;
use crate::identify::IdentifyError;
use crate::progress::Progress;
use crate::residual::{HIDDEN, WIDTH};
use crate::scenario::Model;

/// How long and from which seed the stage trains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResidualSettings {
    /// Most training epochs of the f32 network (early stopping may end sooner).
    pub epochs: usize,
    /// Quantisation-aware fine-tuning epochs of the int8 twin.
    pub int8_epochs: usize,
    /// Seed of the initial weights, the shuffles and the validation split.
    pub seed: u64,
}

/// Why the stage failed, whatever residual it trains.
#[derive(Debug, thiserror::Error)]
pub enum ResidualError {
    /// The data's force samples of the contact could not be read against the model
    /// (a residual of the line force).
    #[error(transparent)]
    Samples(#[from] IdentifyError),
    /// The training rows at the recorded poses could not be built.
    #[error(transparent)]
    Rows(#[from] super::wrench_samples::WrenchSampleError),
    /// A run's contact events could not be located.
    #[error(transparent)]
    Events(#[from] crate::indicators::IndicatorError),
    /// The network or its twin could not be trained.
    #[error(transparent)]
    Train(#[from] TrainError),
    /// The tosses could not be replayed frame by frame (a residual from motion).
    #[error(transparent)]
    Toss(#[from] crate::replay::TossError),
}

/// The shipped architecture trained on contact `c`'s measured − `pm2` force in `data`,
/// reporting [`Stage::Train`] to `progress` (the validation RMS, N, as its status).
/// Returns the network, its training and the training rows' inputs.
///
/// [`Stage::Train`]: crate::progress::Stage::Train
pub fn train_force_network(
    pm2: &Model,
    data: &Dataset,
    c: usize,
    epochs: usize,
    seed: u64,
    progress: &dyn Progress,
) -> Result<(Network, TrainReport, Vec<Vec<f64>>), ResidualError> {
    let (samples, _) = force_samples(pm2, data, c)?;
    let (inputs, targets) = residual_pairs(&samples, &pm2.contacts[c].model);
    let settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: WIDTH,
        max_epochs: epochs,
        seed,
        ..TrainSettings::default()
    };
    let (network, report) = train_in_stage(&inputs, &targets, &settings, "N", progress)?;
    Ok((network, report, inputs))
}

/// [`train_force_network`], then its int8 twin fine-tuned over the same inputs
/// ([`Stage::Int8Twin`], the RMS against the f32 network, N, as its status).
///
/// [`Stage::Int8Twin`]: crate::progress::Stage::Int8Twin
pub fn train_force_residual(
    pm2: &Model,
    data: &Dataset,
    c: usize,
    settings: &ResidualSettings,
    progress: &dyn Progress,
) -> Result<Trained, ResidualError> {
    let (network, report, inputs) =
        train_force_network(pm2, data, c, settings.epochs, settings.seed, progress)?;
    let (int8, tuned) = int8_twin_in_stage(
        &network,
        &inputs,
        settings.int8_epochs,
        settings.seed,
        "N",
        progress,
    )?;
    Ok(Trained {
        residual: TrainedResidual::new(c, network, int8),
        rows: inputs.len(),
        report,
        int8: tuned,
        explained: Vec::new(),
        silenced: Vec::new(),
    })
}
