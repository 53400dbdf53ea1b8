//! `hcm diagnose` on a rigid (3D) contact: the force diagnosis of
//! `hcm_host::diagnose::rigid` — the catalogue judged on held-out runs, the causes
//! named with their parameters, the model extended — written as report.md,
//! diagnosis.json and extended.toml.

use super::progress::Bars;
use hcm_host::dataset::Dataset;
use hcm_host::diagnose::{diagnose_rigid, RigidDiagnoseSettings, RigidDiagnosis};
use hcm_host::identify::{FitRecord, Physics};
use hcm_host::output::write_bytes;
use hcm_host::scenario::{Model, Scenario};
use std::fmt::Write as _;
use std::path::Path;

/// What the rigid path reads of `hcm diagnose`'s options.
pub struct RigidArgs<'a> {
    pub data: &'a Path,
    pub out: &'a Path,
    pub contact: usize,
    pub fitted: bool,
}

pub fn run(
    args: &RigidArgs<'_>,
    scenario: &Scenario,
    base: &Model,
    data: &Dataset,
) -> anyhow::Result<()> {
    let settings = RigidDiagnoseSettings {
        contact: args.contact,
        fitted_base: args.fitted,
        overrides: scenario.identify.bounds.clone(),
        catalogue: Default::default(),
    };
    let bars = Bars::with_status(|_| "candidates fitted");
    let diagnosis = diagnose_rigid(base, data, &settings, &bars)?;
    // Created once there is something to write: an error leaves no empty directory.
    std::fs::create_dir_all(args.out)?;
    let extended = extended_physics(&diagnosis, args);
    extended.write(
        &args.out.join("extended.toml"),
        &format!("extended model of `{}` from hcm diagnose", scenario.name),
    )?;
    let json = serde_json::json!({
        "diagnosis": diagnosis,
        "parameters": diagnosis.fit.parameters,
        "standard_errors": diagnosis.fit.standard_errors,
    });
    write_bytes(
        &args.out.join("diagnosis.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    let report = markdown(&diagnosis, &scenario.name);
    write_bytes(&args.out.join("report.md"), report.as_bytes())?;
    print!("{report}");
    Ok(())
}

/// The extended model as a physics file: the re-fitted law with the normal effects
/// named, its friction and tangential effects (a measurement cause is reported, not
/// added to the physics).
fn extended_physics(d: &RigidDiagnosis, args: &RigidArgs<'_>) -> Physics {
    let fit = FitRecord {
        method: "diagnose (rigid, force samples)".into(),
        data: args.data.display().to_string(),
        runs: d.runs,
        samples: d.rows,
        force_rms: d.fit.force_rms,
        notes: vec![d.answer.clone()],
        ..FitRecord::default()
    };
    Physics::of_contact(&d.fit.model, args.contact, fit)
}

/// report.md: the answer, each round's candidates with their held-out gain, and the
/// extended model's parameters with standard errors.
fn markdown(d: &RigidDiagnosis, name: &str) -> String {
    let mut out = format!("# Diagnosis of `{name}` (rigid contact, force samples)\n\n");
    let _ = writeln!(out, "**Answer.** {}\n", d.answer);
    let _ = writeln!(
        out,
        "{} runs, {} rows (samples with a measured force, in contact and in flight). Each \
         candidate fitted with the model's own parameters on one half of the runs (even or \
         odd) and scored on the other; gain = the model's held-out score minus the \
         candidate's (mean squared weighted residual per row), ± its standard error over \
         the runs. A cause is named at ≥ 3 standard errors that beats every rival by 3.\n",
        d.runs, d.rows
    );
    for (k, round) in d.rounds.iter().enumerate() {
        let _ = writeln!(
            out,
            "## Round {} (model's score {:.4e})\n",
            k + 1,
            round.score
        );
        let _ = writeln!(out, "| candidate | family | gain | ± | t | helps |");
        let _ = writeln!(out, "|---|---|---|---|---|---|");
        for c in &round.candidates {
            let _ = writeln!(
                out,
                "| {} | {:?} | {:+.3e} | {:.2e} | {:.1} | {} |",
                c.name,
                c.family,
                c.gain.mean,
                c.gain.standard_error,
                c.gain.t(),
                if c.helps { "yes" } else { "" }
            );
        }
        let verdict = match (&round.named, round.ambiguous.is_empty()) {
            (Some(n), _) if !round.same_as.is_empty() => format!(
                "named: {n} (the same model as {}: one is the other written another way)",
                round.same_as.join(", ")
            ),
            (Some(n), _) => format!("named: {n}"),
            (None, false) => format!("ambiguous: {}", round.ambiguous.join(", ")),
            (None, true) => "nothing helps".to_owned(),
        };
        let _ = writeln!(out, "\n{verdict}\n");
    }
    let _ = writeln!(out, "## The extended model (fitted on every run)\n");
    let _ = writeln!(out, "| parameter | value | ± (1 SE) |");
    let _ = writeln!(out, "|---|---|---|");
    for ((n, v), se) in d.fit.parameters.iter().zip(&d.fit.standard_errors) {
        let _ = writeln!(out, "| {n} | {v:.5e} | {se:.2e} |");
    }
    if let Some(g) = &d.total_gain {
        let _ = writeln!(
            out,
            "\nHeld-out gain of the extended model over the given one: {:+.3e} ± {:.2e}.",
            g.mean, g.standard_error
        );
    }
    for w in &d.fit.warnings {
        let _ = writeln!(out, "\nwarning: {w}");
    }
    out
}
