//! `hcm diagnose` from poses (the data hold no force, or `--from-poses`, which
//! `hcm diagnose-motion` implies): what a tossed or sliding body's simulation gets
//! wrong, from filmed motion alone.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::diagnose::{
    diagnose_motion_with, Catalogue, MotionBase, MotionDiagnosis, GAIN_T, MIN_GAIN, RIVAL_T,
};
use hcm_host::identify::{FitRecord, Physics};
use hcm_host::output::{write_bytes, StagedDirectory};
use hcm_host::pipeline::{chance_forecast, write_figures};
use hcm_host::scenario::Model;
use std::fmt::Write;
use std::path::Path;

/// What a diagnosis from poses reads: the model and its physics file (if one was
/// given), the data and the file they came from, and where the answer goes.
pub struct PosesInputs<'a> {
    /// The model diagnosed (the scenario with the physics file applied).
    pub model: &'a Model,
    /// `--physics`, where given: the extended model's file is this one with the chance.
    pub physics: Option<Physics>,
    /// The scenario's name, for the files' comments.
    pub scenario: &'a str,
    /// The contact diagnosed.
    pub contact: usize,
    /// The tosses and their file.
    pub data: (&'a hcm_host::dataset::Dataset, &'a Path),
    /// `--out`: a directory (report.md, diagnosis.json, extended.toml, figures) or a
    /// `.json` file (the diagnosis alone).
    pub out: &'a Path,
}

/// Diagnoses the model on the data, writes the diagnosis and prints it. `--out` a
/// `.json` file: the diagnosis alone, there. A directory (staged, renamed into place
/// when complete): `diagnosis.json`, `report.md`, and where a chance is named the
/// held-out tosses' forecast by the extended model (its section of the report and its
/// figures, `forecast_calibration` and `forecast_bands`) and, where only chances are
/// named, `extended.toml` (the physics with the chance: what `--members` draws).
/// `hcm diagnose` on a camera's poses comes here too, with a `base` fitted when its
/// physics file says so, and the catalogue to try (chance when asked).
pub fn diagnose_into(
    inputs: PosesInputs<'_>,
    base: (MotionBase, &Catalogue),
) -> anyhow::Result<()> {
    let (data, path) = inputs.data;
    let bars = Bars::with_status(|_| "candidates");
    let diagnosis = diagnose_motion_with(inputs.model, data, base, &bars)
        .with_context(|| format!("diagnosing the runs of {} from their poses", path.display()))?;
    let text = serde_json::to_string_pretty(&diagnosis)?;
    if inputs.out.extension().is_some_and(|e| e == "json") {
        if let Some(dir) = inputs.out.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        write_bytes(inputs.out, text.as_bytes())
            .with_context(|| format!("writing {}", inputs.out.display()))?;
        print_diagnosis(&diagnosis);
        return Ok(());
    }
    let staged = StagedDirectory::create(inputs.out, "diagnosis.json")?;
    let dir = staged.path().to_owned();
    write_bytes(&dir.join("diagnosis.json"), text.as_bytes())?;
    let mut report = markdown(&diagnosis, inputs.scenario);
    if diagnosis.extended.varies() {
        let (forecast, figures) = chance_forecast(inputs.model, &diagnosis.extended, data, &bars)
            .context("forecasting the held-out tosses by the named chance")?;
        forecast.write_markdown(&mut report)?;
        write_figures(&figures, &dir)?;
    }
    if diagnosis.extended.varies() && diagnosis.only_chance_named() {
        extended_physics(&inputs, &diagnosis).write(
            &dir.join("extended.toml"),
            &format!(
                "extended model of `{}` from hcm diagnose (poses): the chance it named",
                inputs.scenario
            ),
        )?;
    } else if !diagnosis.named.is_empty() {
        report.push_str(
            "No `extended.toml`: a physics file carries a named chance (a contact's `noise`, \
             a `[variation]`); the named deterministic causes are in `diagnosis.json`.\n",
        );
    }
    write_bytes(&dir.join("report.md"), report.as_bytes())?;
    staged.commit()?;
    print_diagnosis(&diagnosis);
    Ok(())
}

/// The physics file of the diagnosed model with the named chance: `--physics`' file
/// where given, else the scenario's contact as it stands, with the extended model's
/// scatter and `[variation]`.
fn extended_physics(inputs: &PosesInputs<'_>, d: &MotionDiagnosis) -> Physics {
    let physics = inputs.physics.clone().unwrap_or_else(|| {
        let fit = FitRecord {
            data: inputs.data.1.display().to_string(),
            notes: vec![d.answer.clone()],
            ..FitRecord::default()
        };
        Physics::of_contact(inputs.model, inputs.contact, fit)
    });
    physics.with_variation(&d.extended)
}

/// report.md: the rounds as `print_diagnosis` prints them, in markdown.
fn markdown(d: &MotionDiagnosis, scenario: &str) -> String {
    let mut out = format!(
        "# Diagnosis of `{scenario}` from poses\n\n**Answer.** {}\n\n",
        d.answer
    );
    let _ = writeln!(
        out,
        "{} training tosses (even toss numbers), {} held out (odd). Every candidate is \
         fitted on the training tosses and judged on the held-out ones: gain = the model's \
         held-out score minus the candidate's (% of the width + °, per toss; for chance the \
         ensembles' energy score), paired per toss; it helps at t ≥ {GAIN_T} and a gain \
         ≥ {:.0} % of the model's score, and is named if it beats every other by t ≥ {RIVAL_T}.\n",
        d.training_tosses,
        d.held_out_tosses,
        100.0 * MIN_GAIN
    );
    for (k, round) in d.rounds.iter().enumerate() {
        let _ = writeln!(
            out,
            "## Round {}\n\nThe model scores {:.3} (training) and {:.3} (held out).\n\n\
             | candidate | gain | ± se | t | helps | parameters | interval |\n|---|---|---|---|---|---|---|",
            k + 1,
            round.training,
            round.held_out
        );
        for c in &round.candidates {
            let [name, gain, se, t, helps, values] = cells(c);
            let interval = c
                .interval
                .map_or(String::new(), |[lo, hi]| format!("{lo:.4e} to {hi:.4e}"));
            let helps = if helps.is_empty() { "" } else { "yes" };
            let _ = writeln!(
                out,
                "| {name} | {gain} | {se} | {t} | {helps} | {values} | {interval} |"
            );
        }
        let _ = writeln!(out);
    }
    out
}

fn print_diagnosis(d: &MotionDiagnosis) {
    println!(
        "{} training and {} held-out tosses; a candidate helps at t ≥ {GAIN_T} and a gain \
         ≥ {:.0} % of the model's held-out score, and is named if it beats the others by \
         t ≥ {RIVAL_T}",
        d.training_tosses,
        d.held_out_tosses,
        100.0 * MIN_GAIN
    );
    for (k, round) in d.rounds.iter().enumerate() {
        println!(
            "round {}: the model scores {:.3} (training) and {:.3} (held out), % + ° per toss",
            k + 1,
            round.training,
            round.held_out
        );
        println!(
            "  {:<27} {:>10} {:>10} {:>8}  {:<6} parameters",
            "candidate", "gain", "± se", "t", ""
        );
        for c in &round.candidates {
            let [name, gain, se, t, helps, values] = cells(c);
            println!("  {name:<27} {gain:>10} {se:>10} {t:>8}  {helps:<6} {values}");
        }
    }
    println!("answer: {}", d.answer);
    if d.chance_seconds > 0.0 {
        println!("the chance phase took {:.0} s", d.chance_seconds);
    }
}

/// A candidate's row: its name, gain, standard error, t, `helps` or nothing, and its
/// fitted values — as printed and as the report's table has them.
fn cells(c: &hcm_host::diagnose::CandidateResult) -> [String; 6] {
    let values: Vec<String> = (c.parameters.iter())
        .map(|(n, v)| format!("{n} = {v:.4e}"))
        .collect();
    [
        c.name.to_owned(),
        format!("{:.4}", c.gain.mean),
        format!("{:.4}", c.gain.standard_error),
        format!("{:.1}", c.gain.t()),
        if c.helps { "helps" } else { "" }.to_owned(),
        values.join(", "),
    ]
}
