//! The options every command shares that replays filmed tosses with a scenario's
//! physics (`hcm predict`, `hcm diagnose-motion`), and their reading.

use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::identify::Physics;
use hcm_host::replay::TossSetup;
use hcm_host::scenario::Model;
use std::path::PathBuf;

/// Scenario, optional physics file, the tosses and how many of them.
#[derive(clap::Args)]
pub struct TossArgs {
    #[command(flatten)]
    pub scenario: super::ScenarioArgs,
    /// Physics file from `hcm identify` or `hcm identify-motion`: replaces the scenario's
    /// contact law and friction.
    #[arg(long)]
    pub physics: Option<PathBuf>,
    /// Filmed tosses (measured-data CSV): position and orientation in every frame.
    #[arg(long)]
    pub data: PathBuf,
    /// Use only the first N runs of --data.
    #[arg(long, value_name = "N")]
    pub first: Option<usize>,
}

impl TossArgs {
    /// The model (the scenario with the physics file), the tosses' setup, and the data,
    /// checked against them.
    pub fn load(&self) -> anyhow::Result<(Model, TossSetup, Dataset)> {
        let mut scenario = self.scenario.load()?;
        if let Some(path) = &self.physics {
            scenario = Physics::read(path)?.apply(&scenario, path)?;
        }
        let model = scenario.model()?;
        let setup = TossSetup::new(&model)?;
        let mut data = Dataset::read(&self.data)
            .with_context(|| format!("reading the tosses of {}", self.data.display()))?;
        if let Some(first) = self.first {
            anyhow::ensure!(first > 0, "--first 0: give at least one run");
            data.runs.truncate(first);
        }
        setup.check_data(&self.data.display().to_string(), &model, &data)?;
        Ok((model, setup, data))
    }
}
