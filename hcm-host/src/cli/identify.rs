//! `hcm identify`: fit a normal law (PM2) to measured data.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::dataset::{inventory_summary, DataUse, Dataset, Evidence};
use hcm_host::identify::Fitness;
use hcm_host::identify::{identify, FitRecord, Identification, Method, Physics};
use hcm_host::numerics::optimize::GeneticSettings;
use hcm_host::progress::{Progress, Silent};
use hcm_host::scenario::{Model, Scenario};
use std::path::PathBuf;

/// Identify a physics model (PM2) from data.
///
/// Example: `hcm identify --scenario scenarios/bouncing_ball.toml --data data.s1.csv --law lankarani_nikravesh --out pm2.toml`
///
/// Fits the chosen law's free parameters to the data's contacts, prints them with
/// their uncertainty and the fit's force error, and writes a physics file that
/// `hcm simulate --physics`, `hcm train` and `hcm evaluate` read.
///
/// Terms:
///   PM2           physics model 2: a contact law with parameters identified on data
///   S1            the training set written by `hcm generate` (OUT.s1.csv)
///   physics file  TOML naming each contact's law and parameters, plus a fit record
///   GA            the paper's genetic algorithm (`--method ga`): it simulates candidate
///                 parameters and compares them with the data
///   indicators    of one contact: maximum force, impulse, energy loss and duration
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Training data (measured-data CSV), e.g. the S1 file of `hcm generate`.
    #[arg(long)]
    data: PathBuf,
    /// Law to identify (see `hcm laws`).
    #[arg(long)]
    law: String,
    /// `lsq`: least squares on the force samples (fast; 1D: separable + Levenberg–
    /// Marquardt; 3D: Levenberg–Marquardt on the wrench at the recorded poses, from
    /// several starts). `ga`: the paper's genetic algorithm on simulated vs measured
    /// data (3D: replayed contact events).
    /// `both` (rigid, force and poses): the fit from motion (`hcm identify-motion`'s
    /// replays) with the force at the recorded poses in the same objective.
    #[arg(long, value_parser = ["lsq", "ga", "both"], default_value = "lsq")]
    method: String,
    /// GA fitness: `curve` (force curves, default) or `indicators`.
    #[arg(long, value_parser = ["curve", "indicators"], default_value = "curve")]
    fitness: String,
    /// Which contact of the scenario (index of its `[[contact]]`).
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Seed of the genetic algorithm.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// GA population size.
    #[arg(long, default_value_t = 60)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::population)]
    population: usize,
    /// GA generations (it stops earlier when the best has stalled for 30).
    #[arg(long, default_value_t = 150)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::generations)]
    generations: usize,
    /// Rigid contacts: fix the law's exponent at this value (PM2's; default: the
    /// scenario's) and identify the rest. With `--method lsq` and without it, the
    /// exponent is fitted too.
    #[arg(long)]
    exponent: Option<f64>,
    /// Rigid contacts: how many contact events to fit, from the first (default: as
    /// many as the runs usually make).
    #[arg(long)]
    events: Option<usize>,
    /// Physics file to write (TOML), read by `simulate --physics` and `evaluate`.
    #[arg(long)]
    out: PathBuf,
}

impl Args {
    /// What the rigid path needs.
    fn into_rigid(self) -> super::identify_rigid::RigidArgs {
        super::identify_rigid::RigidArgs {
            data: self.data,
            law: self.law,
            method: self.method,
            contact: self.contact,
            exponent: self.exponent,
            events: self.events,
            out: self.out,
        }
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let model = scenario.model()?;
    super::check_contact(args.contact, &model)?;
    let data = Dataset::read(&args.data)?;
    let evidence = Evidence::of(&model, &data, args.contact);
    if evidence != Evidence::LineForce {
        println!("{}", inventory_summary(&data, &model, args.contact));
    }
    anyhow::ensure!(
        !(evidence == Evidence::Poses && args.method == "both"),
        "{}: --method both fits the force with the motion, and the data hold no force \
         (fx, fy, fz); drop --method to fit from the poses alone",
        args.data.display()
    );
    if evidence == Evidence::Poses || (evidence == Evidence::Wrench && args.method == "both") {
        println!(
            "fitting from the poses{}, as `hcm identify-motion` does (GA 20 × 10, polish 40)",
            if evidence == Evidence::Poses {
                ""
            } else {
                " and the force at them"
            }
        );
        let with_force = args.method == "both";
        let motion = super::identify_motion::Args::from_identify(
            args.scenario,
            args.data,
            args.out,
            args.seed,
            args.law,
            args.contact,
            with_force,
        );
        return super::identify_motion::run(motion);
    }
    let by_events = args.method == "ga";
    let needs = evidence.requirement(if by_events {
        DataUse::IdentifyEvents
    } else {
        DataUse::Identify
    });
    if let Some(needs) = needs {
        data.require(
            &args.data.display().to_string(),
            &model,
            &[args.contact],
            needs,
        )?;
    }
    let settings = GeneticSettings {
        seed: args.seed,
        population: args.population,
        generations: args.generations,
        ..GeneticSettings::default()
    };
    if evidence == Evidence::Wrench {
        return super::identify_rigid::run(&args.into_rigid(), &scenario, &model, &data, settings);
    }
    anyhow::ensure!(
        args.exponent.is_none() && args.events.is_none(),
        "--exponent and --events are for rigid (3D) contacts; scenario `{}` is 1D: bound the \
         exponent with [identify.bounds.<law>] exponent = [lo, hi] instead",
        scenario.name
    );
    identify_one_dimensional(&args, &scenario, &model, &data, settings)
}

/// The 1D path: fits `--law` to the force samples by the method asked for, prints the
/// result and writes the physics file.
fn identify_one_dimensional(
    args: &Args,
    scenario: &Scenario,
    model: &Model,
    data: &Dataset,
    settings: GeneticSettings,
) -> anyhow::Result<()> {
    let method = match (args.method.as_str(), args.fitness.as_str()) {
        ("lsq", _) => Method::Lsq,
        (_, "indicators") => Method::Ga(Fitness::Indicators, settings),
        _ => Method::Ga(Fitness::Curve, settings),
    };
    // Least squares takes a moment: no bar.
    let bars = Bars::with_status(|_| "GA generations");
    let progress: &dyn Progress = match method {
        Method::Lsq => &Silent,
        Method::Ga(..) => &bars,
    };
    let result = identify(
        scenario,
        model,
        data,
        args.contact,
        &args.law,
        method,
        progress,
    )?;
    let mut fit = result.fit.clone();
    fit.data = args.data.display().to_string();
    print_identification(&args.law, &result, &fit);
    let physics = Physics::for_contact(model, args.contact, &result.law, fit);
    write_physics(&physics, &scenario.name, &args.out)
}

/// Prints the fit of `law`: runs, events and samples used, time (s), each parameter
/// with its standard error, the force RMS errors (N) and the notes.
fn print_identification(law: &str, result: &Identification, fit: &FitRecord) {
    println!(
        "{} by {} on {} runs ({} events, {} force samples) in {:.3} s",
        law, fit.method, fit.runs, fit.events, fit.samples, fit.seconds
    );
    for (name, value) in result.law.named() {
        let error = result
            .standard_errors
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, e)| format!("  ± {e:.3e} (1σ)"))
            .unwrap_or_default();
        println!("  {name:<20} {value:.6e}{error}");
    }
    println!(
        "  force residual RMS   {:.4} N over the force samples",
        fit.force_rms
    );
    println!(
        "  force curve RMS      {:.4} N between replayed and mean measured curves",
        fit.curve_rms
    );
    for note in &fit.notes {
        println!("  note: {note}");
    }
}

/// Writes `physics` (PM2 of scenario `name`) to `out` and says so.
pub(super) fn write_physics(
    physics: &Physics,
    name: &str,
    out: &std::path::Path,
) -> anyhow::Result<()> {
    physics
        .write(
            out,
            &format!("PM2 of scenario `{name}` identified by hcm identify"),
        )
        .with_context(|| format!("writing {}", out.display()))?;
    println!("wrote {}", out.display());
    Ok(())
}
