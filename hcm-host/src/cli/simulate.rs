//! `hcm simulate`: run a scenario and write its trajectory in the measured-data format.

use super::report;
use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::identify::Physics;
use hcm_host::simulate::simulate;
use std::path::PathBuf;

/// Simulate a scenario and write its trajectory.
///
/// Example: `hcm simulate --scenario scenarios/bouncing_ball.toml --out traj.csv`
///
/// Writes every body's sampled motion and contact force to OUT (measured-data CSV, one
/// row per sample per body; the README's "Measured-data format") and prints the
/// indicators of each contact.
///
/// Terms:
///   scenario    a TOML file of bodies, materials, contact laws and solver settings
///   indicators  of one contact: maximum force (N), impulse ∫f dt (N·s), energy lost
///               (N·m = J) and duration (s)
///   PM2         a physics law identified on data by `hcm identify` (`--physics`)
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Physics file from `hcm identify`: replaces the scenario's contact laws.
    #[arg(long)]
    physics: Option<PathBuf>,
    /// Where to write the trajectory (CSV, measured-data format).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let mut scenario = args.scenario.load()?;
    if let Some(path) = &args.physics {
        scenario = Physics::read(path)?.apply(&scenario, path)?;
    }
    let model = scenario.model()?;
    let simulation = simulate(&model)?;
    let dataset = Dataset {
        runs: vec![simulation.run.clone()],
    };
    dataset
        .write(&args.out)
        .with_context(|| format!("writing {}", args.out.display()))?;
    let samples: usize = simulation.run.bodies.iter().map(|b| b.samples.len()).sum();
    println!(
        "{}: simulated to t = {:.6} s in {} steps ({} rejected); wrote {} rows to {}",
        model.scenario.name,
        simulation.end_time,
        simulation.steps.0,
        simulation.steps.1,
        samples,
        args.out.display()
    );
    let label = |c: usize| {
        let c = &model.contacts[c];
        format!(
            "{}–{}",
            model.bodies[c.body_1].name, model.bodies[c.body_2].name
        )
    };
    if model.is_rigid() {
        let rows: Vec<_> = simulation
            .pair_events
            .iter()
            .map(|e| {
                let indicators = e.indicators_until(e.lift_off.unwrap_or(simulation.end_time));
                (
                    label(e.contact),
                    e.touch_down,
                    indicators,
                    e.lift_off.is_none(),
                )
            })
            .collect();
        print!("{}", report::pair_event_table(&rows));
        return Ok(());
    }
    let rows: Vec<_> = simulation
        .events
        .iter()
        .map(|e| {
            let c = &model.contacts[e.contact];
            let label = format!(
                "{}–{}",
                model.bodies[c.body_1].name, model.bodies[c.body_2].name
            );
            (label, e.touch_down, e.indicators())
        })
        .collect();
    print!("{}", report::event_table(&rows));
    Ok(())
}
