//! The paper's method as a library: the stages `hcm reproduce` strings together, each
//! a function from one typed value to the next, in this order:
//!
//! 1. [`generate_split`] — PM1's noisy runs of every condition (Eq 18–19), split into the
//!    training set S1 and the validation set S2 ([`Split`]).
//! 2. [`identify_pm2`] — PM2: Lankarani–Nikravesh identified on S1 ([`Pm2`]).
//! 3. [`train_residual`] — the residual network on S1's measured − PM2 force, and its
//!    quantisation-aware int8 twin ([`Trained`]).
//! 4. [`crate::export::export_blobs`] — both networks as the core's weights blobs,
//!    decoded back by the core ([`Blobs`]).
//! 5. [`evaluate_on_s2`] — PM2, HCM and HCM int8 replayed on S2: the paper's table and
//!    its figures ([`Evaluation`]).
//!
//! [`reproduce`] runs them in that order, timing each, and gathers the
//! [`ReproduceResults`], which render to the report's markdown
//! ([`ReproduceResults::markdown`]) and serialise to `results.json`. Nothing here
//! prints or writes a file: progress goes to the caller's [`Progress`], and the
//! intermediate values come back in the [`Reproduction`] for the caller to write.

mod artifacts;
mod cube;
mod evaluate;
mod example;
mod identify;
mod peg;
mod preset;
mod quantity;
mod report;
mod results;
mod setup;
mod train;
pub use cube::{
    chance_forecast, reproduce_cube, CubeReproduction, CubeSettings, ForecastResults, Peers,
};
pub use peg::PegReproduction;
pub use peg::PegSettings;
pub use peg::{evaluate_peg, reproduce_peg, CONTACT as PEG_CONTACT};

pub use crate::figure::NamedFigure;
pub use crate::progress::{Fold, Progress, Silent, Stage};
pub use crate::train::Trained;
pub use artifacts::{write_figures, write_reproduction, Artifact, Reproduced};
pub use evaluate::{evaluate_on_s2, Evaluation};
pub use example::{Example, Pm2Method, ReproduceSettings};
pub use identify::{identify_pm2, Pm2};
pub use preset::{Preset, ScenarioChoice, Shipped};
pub use results::{
    BlobSummary, NamedValue, PaperErrors, Pm2Summary, ReproduceResults, ResidualSummary,
    StageClock, StageTiming,
};
pub use setup::Setup;
pub use train::train_residual;

use crate::experiment::{generate_split, ExperimentError, Split};
use crate::export::{export_blobs, Blobs, ExportError};
use crate::identify::IdentifyError;
use crate::identify::PhysicsError;
use crate::scenario::{Scenario, ScenarioError};
use std::borrow::Cow;

/// The contact of the paper's examples that PM2 and the residual model: they have one.
pub const CONTACT: usize = 0;

/// Why a stage of the pipeline failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// The scenario does not resolve to a model.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// Stage 1: a run could not be generated.
    #[error(transparent)]
    Experiment(#[from] ExperimentError),
    /// Stage 2: PM2 could not be identified.
    #[error(transparent)]
    Identify(#[from] IdentifyError),
    /// Stage 2: the identified law does not fit back into the scenario.
    #[error(transparent)]
    Physics(#[from] PhysicsError),
    /// Stage 3: the residual's rows, events or training failed.
    #[error(transparent)]
    Residual(#[from] crate::train::ResidualError),
    /// Stage 4: a network could not be encoded as a blob, or its blob does not decode.
    #[error(transparent)]
    Export(#[from] ExportError),
    /// The rigid-body stages (peg-in-hole): PM2 or the S2 comparison failed.
    #[error(transparent)]
    Rigid(#[from] crate::identify::RigidIdentifyError),
    /// The cube tosses' stages (boxed: the other stages' results stay small).
    #[error(transparent)]
    Cube(Box<cube::CubeError>),
    /// Stage 5: S2 holds no condition to evaluate.
    #[error("the validation data hold no condition")]
    NoValidation,
}

impl From<cube::CubeError> for PipelineError {
    fn from(error: cube::CubeError) -> Self {
        PipelineError::Cube(Box::new(error))
    }
}

/// Everything [`reproduce`] made: each stage's value, for the caller to write, and
/// the results.
pub struct Reproduction {
    /// The scenario as read, overrides applied.
    pub(crate) scenario: Scenario,
    /// S1 and S2.
    pub(crate) sets: Split,
    /// PM2.
    pub(crate) pm2: Pm2,
    /// The residual network and its int8 twin.
    pub(crate) trained: Trained,
    /// Their blobs.
    pub(crate) blobs: Blobs,
    /// Fig 9/12 and 10/13.
    pub(crate) figures: Vec<NamedFigure>,
    /// Every table of the report.
    pub(crate) results: ReproduceResults,
}

/// The ball's and the flat shot's files: S1 and S2, PM2, the trained network, its
/// blobs and the figures (SVG and PNG).
impl Reproduced for Reproduction {
    fn artifacts(&self) -> anyhow::Result<Vec<Artifact<'_>>> {
        let comment = format!("PM2 of `{}` from hcm reproduce", self.scenario.name);
        Ok(vec![
            Artifact::Data("s1.csv", Cow::Borrowed(&self.sets.training)),
            Artifact::Data("s2.csv", Cow::Borrowed(&self.sets.validation)),
            Artifact::Physics("pm2.toml", self.pm2.physics.clone(), comment),
            Artifact::Residual("residual.json", &self.trained.residual),
            Artifact::Bytes("residual.bin", &self.blobs.f32.bytes),
            Artifact::Bytes("residual.int8.bin", &self.blobs.int8.bytes),
            Artifact::Figures(&self.figures),
        ])
    }

    fn record(&mut self, timing: StageTiming) {
        self.results.timings.push(timing);
    }

    fn results_json(&self) -> anyhow::Result<String> {
        Ok(self.results.json()?)
    }

    fn report(&self) -> String {
        self.results.markdown()
    }
}

/// Reads the scenario of `settings` and runs stages 1–5 on it, timing each (wall
/// clock, s). Bit-identical results (but for the timings) for the same settings.
pub fn reproduce(
    settings: &ReproduceSettings,
    progress: &dyn Progress,
) -> Result<Reproduction, PipelineError> {
    let scenario = settings.scenario.load()?;
    let label = settings.scenario.label();
    let path = label.as_path();
    // A scenario that does not resolve, or a run count too small to split into S1 and
    // S2, fails here, before minutes of generation.
    scenario.model()?;
    crate::experiment::check_split(&scenario, settings.runs)?;
    let mut clock = StageClock::default();
    let seed = settings.seed;
    let sets = clock.time("generate + split", || {
        generate_split(&scenario, settings.runs, seed, progress)
    })?;
    let pm2 = clock.time("identify PM2", || {
        identify_pm2(
            &scenario,
            path,
            &sets.training,
            settings.method,
            seed,
            progress,
        )
    })?;
    let trained = clock.time("train (+ int8 twin)", || {
        train_residual(&pm2.model, &sets.training, seed, progress)
    })?;
    let blobs = clock.time("export", || export_blobs(&trained.residual))?;
    let evaluation = clock.time("evaluate + figures", || {
        evaluate_on_s2(&pm2.model, &blobs, &sets.validation, progress)
    })?;
    let timings = clock.0;

    let setup = Setup::describe(&scenario, &sets, &evaluation.table.condition);
    let results = ReproduceResults::gather(
        settings,
        setup,
        &pm2,
        &trained,
        &blobs,
        &evaluation,
        timings,
    );
    Ok(Reproduction {
        scenario,
        sets,
        pm2,
        trained,
        blobs,
        figures: evaluation.figures,
        results,
    })
}
