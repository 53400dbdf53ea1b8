//! `hcm simulate`: run a scenario and write its trajectory in the measured-data format.

use super::report;
use anyhow::Context;
use hcm_host::dataset::RunWriter;
use hcm_host::dataset::{Dataset, Evidence};
use hcm_host::experiment::simulate_members;
use hcm_host::figure::rigid_figures;
use hcm_host::identify::Physics;
use hcm_host::output::{commit, write_atomically, StagedFile};
use hcm_host::pipeline::NamedFigure;
use hcm_host::scenario::Model;
use hcm_host::simulate::simulate;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Simulate a scenario and write its trajectory.
///
/// Example: `hcm simulate --scenario scenarios/bouncing_ball.toml --out traj.csv`
///
/// Writes every body's sampled motion and contact force to OUT (measured-data CSV, one
/// row per sample per body; the README's "Measured-data format") and prints the
/// indicators of each contact.
///
/// With --figures DIR (3D scenarios only: a box, compound, friction or rotation; a 1D
/// scenario is refused) also writes into DIR, as SVG and PNG:
///   trajectory      side view (x–z, mm, equal scales): the centre-of-mass path, the
///                   body's outline at the start, its first touch-downs and the end,
///                   and the fixed bodies' outlines (a plane's trace at the body's y)
///   contact_force   ‖F‖ on the moving body over time (N), touch-downs marked
///   contact_torque  ‖T‖ about its centre of mass over time (N·m), touch-downs marked
///   contact_events  ‖F‖ and ‖T‖ of each of the first 6 contact events, one panel per
///                   event on its own time scale (a millisecond's contact is a spike
///                   on the run's axis)
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
    /// Directory (created if missing) for the figures of a 3D scenario: trajectory,
    /// contact_force, contact_torque, contact_events (.svg and .png).
    #[arg(long, value_name = "DIR", value_hint = clap::ValueHint::DirPath)]
    figures: Option<PathBuf>,
    /// Simulate N members drawn from the scenario's variation (each contact's `noise`,
    /// its `[variation]`'s fixed height and tilt) as a forecast draws them, member m
    /// from stream m of --seed: OUT holds them all, the measured-data format with the
    /// column `member` (0 … N−1) last, the same bytes on any thread count.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    members: Option<u32>,
    /// Seed of the members' draws.
    #[arg(long, default_value_t = 1, requires = "members")]
    seed: u64,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let mut scenario = args.scenario.load()?;
    if let Some(path) = &args.physics {
        scenario = Physics::read(path)?.apply(&scenario, path)?;
    }
    let model = scenario.model()?;
    let evidence = Evidence::simulated(&model);
    if args.figures.is_some() && evidence == Evidence::LineForce {
        anyhow::bail!(
            "--figures: scenario `{}` is 1D (no box, compound, friction or rotation); \
             the figures show 3D motion — plot OUT's force column instead",
            model.scenario.name
        );
    }
    if let Some(members) = args.members {
        return write_members(&model, members as usize, &args);
    }
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
    if evidence == Evidence::Wrench {
        let rows: Vec<_> = simulation
            .events
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
        if let Some(dir) = &args.figures {
            write_figures(dir, &rigid_figures(&model, &simulation))?;
            println!("wrote the figures to {}", dir.display());
        }
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
            (label, e.touch_down, e.normal_indicators())
        })
        .collect();
    print!("{}", report::event_table(&rows));
    Ok(())
}

/// Simulates `members` members of `model` from `--seed` and writes them all to `--out`
/// (atomically), member by member, with the `member` column; prints what they drew
/// and each member's contact events.
fn write_members(model: &Model, members: usize, args: &Args) -> anyhow::Result<()> {
    anyhow::ensure!(
        args.figures.is_none(),
        "--figures draws one run: drop --members, or drop --figures to simulate the members"
    );
    let (seed, out) = (args.seed, &args.out);
    if !model.varies() {
        eprintln!(
            "note: scenario `{}` has no variation (no contact `noise`, no fixed height or \
             tilt): every member is the same run",
            model.scenario.name
        );
    }
    let simulations = simulate_members(model, members, seed)?;
    let name = out.display().to_string();
    write_atomically(out, |file| -> anyhow::Result<()> {
        let mut writer = RunWriter::with_members(file, &name)?;
        for (member, simulation) in simulations.iter().enumerate() {
            writer.write_member(&simulation.run, member)?;
        }
        writer.finish()?;
        Ok(())
    })
    .with_context(|| format!("writing {name}"))?;
    let events: Vec<usize> = simulations.iter().map(|s| s.events.len()).collect();
    let rows: usize = (simulations.iter())
        .flat_map(|s| &s.run.bodies)
        .map(|b| b.samples.len())
        .sum();
    println!(
        "{}: {members} members (seed {seed}), contact events per member {}–{}; wrote {rows} \
         rows to {name} (column `member`)",
        model.scenario.name,
        events.iter().min().unwrap_or(&0),
        events.iter().max().unwrap_or(&0),
    );
    Ok(())
}

/// Writes each figure as `<stem>.svg` and `<stem>.png` into `dir` (created if missing),
/// all moved into place together: the set appears whole or not at all.
fn write_figures(dir: &Path, figures: &[NamedFigure]) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut finished = Vec::new();
    for named in figures {
        let png = named
            .figure
            .png()
            .with_context(|| format!("drawing {}.png", named.stem))?;
        for (extension, bytes) in [("svg", named.figure.svg().into_bytes()), ("png", png)] {
            let path = dir.join(format!("{}.{extension}", named.stem));
            let mut file = StagedFile::create(&path)?;
            file.write_all(&bytes)
                .with_context(|| format!("writing {}", path.display()))?;
            finished.push(file.finish()?);
        }
    }
    commit(finished)?;
    Ok(())
}
