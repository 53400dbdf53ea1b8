//! `hcm evaluate`: the paper's table for a physics model on validation data.

use anyhow::Context;
use hcm_host::dataset::{complete, inventory_summary, DataUse, Dataset, Evidence};
use hcm_host::evaluate::{
    evaluate, evaluate_members, evaluate_motion, evaluate_rigid, markdown, members_markdown,
    motion_markdown, rigid_markdown,
};
use hcm_host::identify::Physics;
use hcm_host::residual::ContactResidual;
use std::path::PathBuf;

/// The paper's table for a physics model (and the HCM) on validation data (S2).
///
/// Example: `hcm evaluate --scenario scenarios/bouncing_ball.toml --data data.s2.csv --physics pm2.toml`
///
/// For each condition of the data: the mean indicators of its runs beside those of each
/// model, simulated from the runs' mean state just before touch-down, and each model's
/// error. On a 3D (rigid) scenario: every contact event of every run replayed from the
/// recorded state before it (maximum force and torque, linear and angular impulse,
/// duration), the moving body's path from the run's start, and HCM − PM2 run by run;
/// on a camera's data (poses, no force), every run replayed from its window start as
/// `hcm predict` does, its position and rotation errors beside the frozen pose's.
///
/// Terms:
///   S2          the validation set written by `hcm generate` (OUT.s2.csv)
///   PM2         the physics law identified by `hcm identify` (`--physics`)
///   HCM         hybrid contact model: PM2 plus the residual network (`--residual`)
///   residual    the network trained by `hcm train` to predict the force PM2 gets wrong
///   blob        the residual network as `hcm export` writes it
///   indicators  of one contact: maximum force (N), impulse (N·s), energy loss (N·m)
///               and duration (s)
///   error       the paper's Eq 20: |measured mean − model| / measured mean
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Validation data (measured-data CSV), e.g. the S2 file of `hcm generate`.
    #[arg(long)]
    data: PathBuf,
    /// Physics file written by `hcm identify`.
    #[arg(long)]
    physics: PathBuf,
    /// Residual network blob written by `hcm export` (from the network `hcm train`
    /// wrote): adds the HCM column (PM2 + residual, simulated with the residual inside
    /// the integrator's force).
    #[arg(long)]
    residual: Option<PathBuf>,
    /// Which contact of the scenario.
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Also forecast by an ensemble of N runs drawn from the model's variation and score
    /// it beside the single replay by proper scores: on force data each condition's
    /// indicators from members whose contact parameters are drawn from the physics
    /// file's `noise` (Eq 18), the fair CRPS of each indicator per run (% of the measured
    /// mean) and the share of the runs' indicators inside the members' 50 % and 90 %
    /// bands (with --json: `{"conditions": [...], "forecast": [...]}`); on a camera's
    /// data as `hcm predict --members` scores its tosses.
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u16).range(1..=1000))]
    members: Option<u16>,
    /// Seed of the members' draws: the same seed gives the same members on any number
    /// of threads.
    #[arg(long, default_value_t = 1)]
    seed: u64,
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
    let evidence = Evidence::of(&pm2, &data, args.contact);
    if evidence != Evidence::LineForce && !args.json {
        println!("{}", inventory_summary(&data, &pm2, args.contact));
    }
    if evidence == Evidence::Poses {
        return run_motion(&args, &pm2, &data);
    }
    let file = args.data.display().to_string();
    data.require_for(&file, &pm2, args.contact, evidence, DataUse::Evaluate)?;
    if evidence == Evidence::Wrench {
        return run_rigid(&args, &pm2, &data);
    }
    // Camera frames and force rows on their own clocks: the motion at the force samples.
    let completed = complete(&pm2, &data)?;
    let data = completed.data.as_ref();
    let models = with_hcm(&args, &pm2)?;
    let columns: Vec<(&str, &hcm_host::scenario::Model)> =
        models.iter().map(|(l, m)| (*l, m)).collect();
    let tables = evaluate(&columns, data, args.contact)?;
    let forecast = match args.members {
        Some(n) => Some(evaluate_members(
            &pm2,
            data,
            args.contact,
            n.into(),
            args.seed,
        )?),
        None => None,
    };
    if args.json {
        let json = match &forecast {
            Some(f) => serde_json::json!({ "conditions": tables, "forecast": f }),
            None => serde_json::to_value(&tables)?,
        };
        println!("{}", serde_json::to_string_pretty(&json)?);
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
    if let Some(forecast) = &forecast {
        if !pm2.varies() {
            println!(
                "note: {} carries no `noise` (Eq 18) for its members to draw: every member is \
                 the replay. A physics file with the named scatter (`hcm diagnose --chance`'s \
                 extended.toml) or a `noise` table on the contact makes them differ.\n",
                args.physics.display()
            );
        }
        println!(
            "Forecast by ensembles of {} runs drawn from the contacts' noise (seed {}), each \
             replayed from its condition's mean pre-contact state:\n",
            args.members.unwrap_or(0),
            args.seed
        );
        print!("{}", members_markdown(forecast));
    }
    Ok(())
}

/// PM2, and the HCM (PM2 with `--residual`'s blob on the contact) when given.
fn with_hcm(
    args: &Args,
    pm2: &hcm_host::scenario::Model,
) -> anyhow::Result<Vec<(&'static str, hcm_host::scenario::Model)>> {
    let mut models = vec![("PM2", pm2.clone())];
    if let Some(path) = &args.residual {
        let bytes = hcm_host::input::read_bytes(path, hcm_host::input::TEXT_LIMIT, "a blob")
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        let residual = ContactResidual::decode(&bytes)
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        let hcm = (pm2.with_residual(args.contact, residual, &path.display().to_string()))
            .map_err(anyhow::Error::msg)?;
        models.push(("HCM", hcm));
    }
    Ok(models)
}

/// The rigid path: every run replayed from its own pre-contact state by PM2 (and the
/// HCM), its events' indicators and the moving body's path against the data.
fn run_rigid(args: &Args, pm2: &hcm_host::scenario::Model, data: &Dataset) -> anyhow::Result<()> {
    anyhow::ensure!(
        args.members.is_none(),
        "--members: a wrench's events are not forecast by ensembles yet; on force along a \
         line (`hcm evaluate --members` on S2 data) and on a camera's poses they are"
    );
    let models = with_hcm(args, pm2)?;
    let columns: Vec<(&str, &hcm_host::scenario::Model)> =
        models.iter().map(|(l, m)| (*l, m)).collect();
    let evaluation = evaluate_rigid(&columns, data, args.contact)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&evaluation)?);
        return Ok(());
    }
    println!(
        "{} — {} held-out runs, each contact event replayed from the recorded state before \
         it, the path from the run's pre-contact state; PM2 = {}\n",
        pm2.scenario.name,
        evaluation.runs,
        pm2.contacts[args.contact].law().name()
    );
    print!("{}", rigid_markdown(&evaluation));
    for why in &evaluation.left_out {
        eprintln!("warning: left out: {why}");
    }
    Ok(())
}

/// A camera's data: every run replayed from its window start by PM2 (and the HCM) and
/// scored against the recorded poses, beside the frozen pose.
fn run_motion(args: &Args, pm2: &hcm_host::scenario::Model, data: &Dataset) -> anyhow::Result<()> {
    let models = with_hcm(args, pm2)?;
    let columns: Vec<(&str, &hcm_host::scenario::Model)> =
        models.iter().map(|(l, m)| (*l, m)).collect();
    let evaluation = evaluate_motion(&columns, data)
        .with_context(|| format!("replaying the runs of {}", args.data.display()))?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&evaluation)?);
        return Ok(());
    }
    println!(
        "{} — {} runs replayed from their window starts (as `hcm predict`), scored on the \
         recorded poses; PM2 = {}\n",
        pm2.scenario.name,
        evaluation.runs,
        pm2.contacts[args.contact].law().name()
    );
    print!("{}", motion_markdown(&evaluation));
    if args.members.is_some() {
        let ensemble = super::forecast::EnsembleArgs {
            members: args.members,
            scatter: None,
            start_spread: None,
            seed: args.seed,
        };
        if let Some(e) = super::forecast::forecast(&ensemble, false, pm2, data)? {
            let setup = hcm_host::replay::TossSetup::new(pm2)?;
            println!();
            super::forecast::print_scores(&e, setup.width);
        }
    }
    Ok(())
}
