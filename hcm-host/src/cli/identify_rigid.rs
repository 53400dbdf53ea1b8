//! `hcm identify` on a rigid (3D) contact: PM2 as issue 15 defines it — the scenario's
//! law with its exponent fixed and the rest, friction included, found by the genetic
//! algorithm replaying S1's contact events from their mean pre-contact state.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::identify::rigid::{
    identify_rigid, RigidIdentification, RigidParameters, WrenchTarget,
};
use hcm_host::identify::{FitRecord, Physics};
use hcm_host::numerics::optimize::genetic::GeneticSettings;
use hcm_host::scenario::{Contact, Model, Scenario};
use std::path::PathBuf;

/// The options of `hcm identify` the rigid path reads.
pub struct RigidArgs {
    pub data: PathBuf,
    pub law: String,
    pub method: String,
    pub contact: usize,
    pub exponent: Option<f64>,
    pub events: Option<usize>,
    pub out: PathBuf,
}

pub fn run(
    args: &RigidArgs,
    scenario: &Scenario,
    model: &Model,
    data: &Dataset,
    settings: GeneticSettings,
) -> anyhow::Result<()> {
    let c = args.contact;
    let law = model.contacts[c].law().name();
    check_method_and_law(args, scenario, law)?;
    let start = start_model(args, model)?;
    let target = WrenchTarget::from_data(&start, data, c, args.events)?;
    let parameters = RigidParameters::new(&start, c, &scenario.identify.bounds)?;
    let bars = Bars::with_status(|_| "GA generations");
    let found = identify_rigid(&start, &target, &parameters, &settings, &bars)?;
    print_found(law, &start.contacts[c], &target, &found);
    let fit = fit_record(args, &target, &found);
    let physics = Physics::for_contact(&found.model, c, found.model.contacts[c].law(), fit);
    super::identify::write_physics(&physics, &scenario.name, &args.out)
}

/// Refuses a method other than the GA and a law other than the scenario's `law`.
fn check_method_and_law(args: &RigidArgs, scenario: &Scenario, law: &str) -> anyhow::Result<()> {
    let c = args.contact;
    anyhow::ensure!(
        args.method == "ga",
        "--method {}: least squares fits 1D force samples; contact {c} of scenario `{}` is \
         rigid (3D) and is identified by replaying its contact events: use --method ga",
        args.method,
        scenario.name
    );
    anyhow::ensure!(
        args.law == law,
        "--law {}: a rigid contact keeps the scenario's law (`{law}`) and fixes its exponent \
         (--exponent); give --law {law}, or change the law in the scenario",
        args.law
    );
    Ok(())
}

/// The model the search starts from: `model` with the contact's exponent set to
/// `--exponent` if given.
fn start_model(args: &RigidArgs, model: &Model) -> anyhow::Result<Model> {
    let mut start = model.clone();
    if let Some(exponent) = args.exponent {
        start.contacts[args.contact]
            .model
            .normal
            .base
            .set("exponent", exponent)
            .with_context(|| format!("--exponent {exponent}"))?;
    }
    Ok(start)
}

/// Prints what the GA found: the runs and events it used, its time (s) and replays,
/// the parameters and the fitness.
fn print_found(law: &str, start: &Contact, target: &WrenchTarget, found: &RigidIdentification) {
    let used = target.runs - target.left_out.len();
    println!(
        "{law} (exponent fixed at {}) and STEP friction by the genetic algorithm on {used} of {} runs \
         ({} contact events each) in {:.1} s: {} replays",
        start.law().get("exponent").unwrap_or(f64::NAN),
        target.runs,
        target.events.len(),
        found.seconds,
        found.evaluations
    );
    for (name, value) in &found.parameters {
        println!("  {name:<20} {value:.6e}");
    }
    println!(
        "  fitness              {:.4e} (mean squared relative error of the events' indicators)",
        found.fitness
    );
    for w in &found.warnings {
        eprintln!("warning: {w}");
    }
}

/// The physics file's record of the fit: method, data, runs and events used, time (s),
/// and notes on the fitness and the runs left out.
fn fit_record(args: &RigidArgs, target: &WrenchTarget, found: &RigidIdentification) -> FitRecord {
    let used = target.runs - target.left_out.len();
    let mut notes = vec![format!(
        "fitness {:.4e}: mean squared relative error of max force, max torque, linear and \
         angular impulse and delay of the first {} contact events, replayed from S1's mean \
         pre-contact state",
        found.fitness,
        target.events.len()
    )];
    for m in &target.left_out {
        notes.push(format!("run {} left out: {} events", m.run, m.events));
    }
    notes.extend(found.warnings.iter().map(|w| format!("warning: {w}")));
    FitRecord {
        method: "ga (contact events)".into(),
        data: args.data.display().to_string(),
        runs: used,
        events: used * target.events.len(),
        samples: 0,
        force_rms: f64::NAN,
        curve_rms: f64::NAN,
        seconds: found.seconds,
        notes,
    }
}
