//! `hcm evaluate`: the paper's table for a physics model on validation data.

use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::evaluate::{evaluate, markdown};
use hcm_host::identify::Physics;
use hcm_host::residual::ContactResidual;
use std::path::PathBuf;

/// Compare a physics model with validation data: S2 mean, PM2 and the Eq 20 error per
/// indicator, per condition. Each condition is replayed from the mean state of its
/// runs just before touch-down.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Validation data (measured-data CSV), e.g. the S2 file of `hcm generate`.
    #[arg(long)]
    data: PathBuf,
    /// Physics file written by `hcm identify`.
    #[arg(long)]
    physics: PathBuf,
    /// Residual network blob from `hcm train`: adds the HCM column (PM2 + residual,
    /// simulated with the residual inside the integrator's force).
    #[arg(long)]
    residual: Option<PathBuf>,
    /// Which contact of the scenario.
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Print JSON instead of markdown.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let physics = Physics::read(&args.physics)?;
    let pm2 = physics.apply(&scenario, &args.physics)?.model()?;
    super::check_contact(args.contact, &pm2)?;
    let data = Dataset::read(&args.data)?;
    let mut models = vec![("PM2", pm2.clone())];
    if let Some(path) = &args.residual {
        let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
        let residual = ContactResidual::decode(&bytes)
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        let mut hcm = pm2.clone();
        hcm.contacts[args.contact].model.residual = Some(residual);
        models.push(("HCM", hcm));
    }
    let columns: Vec<(&str, &hcm_host::scenario::Model)> =
        models.iter().map(|(l, m)| (*l, m)).collect();
    let tables = evaluate(&columns, &data, args.contact)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&tables)?);
        return Ok(());
    }
    for table in &tables {
        let name = if table.condition.is_empty() {
            String::new()
        } else {
            format!(" — condition {}", table.condition)
        };
        println!(
            "{}{} ({} runs), PM2 = {}\n",
            scenario.name,
            name,
            table.runs,
            pm2.contacts[args.contact].law().name()
        );
        print!("{}", markdown(table));
        println!();
    }
    Ok(())
}
