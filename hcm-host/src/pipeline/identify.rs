//! Stage 2: PM2, the physics law identified on S1.

use super::{PipelineError, Pm2Method, Progress, CONTACT};
use crate::dataset::Dataset;
use crate::identify::{identify, Identification, Physics};
use crate::scenario::{Model, Scenario};
use std::path::Path;

/// The law PM2 uses, as in the paper.
pub(crate) const PM2_LAW: &str = "lankarani_nikravesh";

/// PM2 in its three forms.
#[derive(Clone, Debug)]
pub struct Pm2 {
    /// The identified law and how the fit went.
    pub(crate) identification: Identification,
    /// The physics file's content (`pm2.toml`).
    pub(crate) physics: Physics,
    /// The scenario with PM2 in place of its contact law: the model every later
    /// stage simulates.
    pub(crate) model: Model,
}

/// Identifies `PM2_LAW` on the training set of `scenario` (read from `path`) by
/// `method` (seeded with `seed`).
pub fn identify_pm2(
    scenario: &Scenario,
    path: &Path,
    training: &Dataset,
    method: Pm2Method,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Pm2, PipelineError> {
    let model = scenario.model()?;
    let identification = identify(
        scenario,
        &model,
        training,
        CONTACT,
        PM2_LAW,
        method.method(seed),
        progress,
    )?;
    let physics = Physics::for_contact(
        &model,
        CONTACT,
        &identification.law,
        identification.fit.clone(),
    );
    let model = physics.apply(scenario, path)?.model()?;
    Ok(Pm2 {
        identification,
        physics,
        model,
    })
}
