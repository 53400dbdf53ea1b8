//! `hcm identify` on a rigid (3D) contact: by least squares on the wrench at the
//! recorded poses (`--method lsq`), or as the peg-in-hole defines PM2 — the law with
//! its exponent fixed and the rest, friction included, found by the genetic algorithm
//! replaying S1's contact events from their mean pre-contact state (`--method ga`).

use super::progress::Bars;
use hcm_host::dataset::Dataset;
use hcm_host::identify::{
    identify_events, identify_from_samples, with_law, ContactScales, RigidIdentification,
    SampleFit, WrenchTarget,
};
use hcm_host::identify::{FitRecord, Physics};
use hcm_host::numerics::optimize::GeneticSettings;
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
    let start = start_model(args, model)?;
    if args.method == "lsq" {
        return run_samples(args, scenario, &start, data);
    }
    let law = start.contacts[c].law().name();
    let bars = Bars::with_status(|_| "GA generations");
    let fit = identify_events(&start, data, c, args.events, &settings, &bars)?;
    if let Some(scales) = &fit.scales {
        let exponent = start.contacts[c].law().get("exponent").unwrap_or(1.5);
        print_scaled(scales, exponent, &fit.scaled);
    }
    let (target, found) = (fit.target, fit.found);
    print_found(law, &start.contacts[c], &target, &found);
    let fit = fit_record(args, &target, &found);
    let physics = Physics::for_contact(&found.model, c, found.model.contacts[c].law(), fit);
    super::identify::write_physics(&physics, &scenario.name, &args.out)
}

/// Says which bounds were scaled from the data, and from what.
fn print_scaled(scales: &ContactScales, exponent: f64, changed: &[String]) {
    if !changed.is_empty() {
        println!(
            "search box scaled from the data (peak normal force {:.3e} N, deepest point \
             {:.3e} m, fastest approach {:.3e} m/s, elastic level {:.3e} N/m^{exponent}): {}",
            scales.peak_force,
            scales.peak_depth,
            scales.peak_rate,
            scales.stiffness,
            changed.join(", ")
        );
    }
}

/// `--method lsq`: the law (and friction) fitted to the wrench at the recorded poses.
fn run_samples(
    args: &RigidArgs,
    scenario: &Scenario,
    start: &Model,
    data: &Dataset,
) -> anyhow::Result<()> {
    let c = args.contact;
    anyhow::ensure!(
        args.events.is_none(),
        "--events: the least-squares fit uses every touching sample; --events is for \
         --method ga, which replays the first contact events"
    );
    let bars = Bars::with_status(|_| "least-squares starts");
    let bounds = &scenario.identify.bounds;
    let found = identify_from_samples(start, data, c, bounds, args.exponent.is_none(), &bars)?;
    let exponent = start.contacts[c].law().get("exponent").unwrap_or(1.5);
    println!(
        "{} touching samples with a measured force ({} with torque) in {} runs",
        found.fit.rows, found.torque_rows, found.fit.runs
    );
    print_scaled(&found.scales, exponent, &found.scaled);
    let found = found.fit;
    print_samples_fit(start.contacts[c].law().name(), &found);
    let fit = FitRecord {
        method: "lsq (wrench at the recorded poses)".into(),
        data: args.data.display().to_string(),
        runs: found.runs,
        events: 0,
        samples: found.rows,
        force_rms: found.force_rms,
        curve_rms: f64::NAN,
        seconds: found.seconds,
        notes: (found.parameters.iter().zip(&found.standard_errors))
            .map(|((n, v), e)| format!("{n} = {v:.6e} ± {e:.3e} (1σ)"))
            .chain(found.warnings.iter().map(|w| format!("warning: {w}")))
            .collect(),
    };
    let physics = Physics::for_contact(&found.model, c, found.model.contacts[c].law(), fit);
    super::identify::write_physics(&physics, &scenario.name, &args.out)
}

/// Prints the least-squares fit: parameters with standard errors, residual RMS, time,
/// and its warnings on standard error.
fn print_samples_fit(law: &str, found: &SampleFit) {
    println!(
        "{law} and STEP friction by least squares on {} samples of {} runs in {:.1} s \
         ({} wrench evaluations of every sample)",
        found.rows, found.runs, found.seconds, found.evaluations
    );
    for ((name, value), se) in found.parameters.iter().zip(&found.standard_errors) {
        println!("  {name:<20} {value:.6e}  ± {se:.3e} (1σ)");
    }
    println!("  force residual RMS   {:.4e} N", found.force_rms);
    if found.torque_rms.is_finite() {
        println!("  torque residual RMS  {:.4e} N·m", found.torque_rms);
    }
    let (fixed, loose): (Vec<&str>, Vec<&str>) = (found.parameters.iter())
        .map(|(name, _)| name.as_str())
        .partition(|name| {
            !(found.warnings.iter()).any(|w| w.starts_with(&format!("`{name}` is not fixed")))
        });
    println!(
        "  fixed by the data: {}; not fixed by them (see the warnings): {}",
        if fixed.is_empty() {
            "none".to_owned()
        } else {
            fixed.join(", ")
        },
        if loose.is_empty() {
            "none".to_owned()
        } else {
            loose.join(", ")
        }
    );
    for w in &found.warnings {
        eprintln!("warning: {w}");
    }
}

/// The model the search starts from ([`with_law`]).
fn start_model(args: &RigidArgs, model: &Model) -> anyhow::Result<Model> {
    Ok(with_law(model, args.contact, &args.law, args.exponent)?)
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
