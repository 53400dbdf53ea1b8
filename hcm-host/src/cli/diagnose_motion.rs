//! `hcm diagnose-motion`: what a tossed or sliding body's simulation gets wrong, from
//! filmed motion alone.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::diagnose::{
    diagnose_motion_with, MotionBase, MotionDiagnosis, GAIN_T, MIN_GAIN, RIVAL_T,
};
use hcm_host::output::write_bytes;
use std::path::PathBuf;

/// Name what a tossed body's simulation misses, from filmed motion alone (no force).
///
/// Example: `hcm diagnose-motion --scenario scenarios/cube_toss.toml --data data/contactnets-cube/tosses.csv --out diagnosis.json`
///
/// Splits the runs of --data by toss number (even numbers train, odd ones are held
/// out), and tries every candidate change of the model: the friction's coefficient,
/// Coulomb's law for its shape (when μ_s ≠ μ_d), viscous friction, torsional and
/// rolling resistance, the table's height and tilt, the tracker's length scale, the
/// body's inertia. Each is
/// fitted on the training tosses with the rest of the model fixed (replaying them as
/// `hcm predict` does) and judged on the held-out tosses, toss by toss, by how much it
/// lowers their score. A candidate helps when its mean held-out gain is at least 3
/// standard errors above zero and at least 1 % of the model's held-out score; the best
/// is named only if it beats every other helping candidate by 2 standard errors on the
/// same tosses, otherwise the answer is "ambiguous" and names none. A named cause is
/// added and the search repeats once on what is left. Writes the whole diagnosis as
/// JSON to --out and prints each candidate's gain.
///
/// Terms:
///   score          per toss: mean position error (% of the body's width) + mean
///                  rotation error (°) over its window's frames, as `hcm predict`
///   held-out gain  the model's score minus the candidate's, per held-out toss; its
///                  mean, standard error and 95 % interval over the tosses
///   physics file   `--physics`: a law with its parameters and friction, as `hcm
///                  identify-motion` writes it; without it, the scenario's own
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    tosses: super::tosses::TossArgs,
    /// Where to write the diagnosis (JSON).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let (model, _, data) = args.tosses.load()?;
    diagnose_into(
        &model,
        &data,
        MotionBase::Given,
        &args.tosses.data,
        &args.out,
    )
}

/// Diagnoses `model` on `data` (read from `path`), writes the diagnosis as JSON to
/// `json` (creating the directory it is in, once there is something to write)
/// and prints it. `hcm diagnose` on a camera's poses comes here too, with a `base`
/// fitted when its physics file says so.
pub fn diagnose_into(
    model: &hcm_host::scenario::Model,
    data: &hcm_host::dataset::Dataset,
    base: MotionBase,
    path: &std::path::Path,
    json: &std::path::Path,
) -> anyhow::Result<()> {
    let bars = Bars::with_status(|_| "candidates");
    let diagnosis = diagnose_motion_with(model, data, base, &bars)
        .with_context(|| format!("diagnosing the runs of {} from their poses", path.display()))?;
    let text = serde_json::to_string_pretty(&diagnosis)?;
    if let Some(dir) = json.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    write_bytes(json, text.as_bytes()).with_context(|| format!("writing {}", json.display()))?;
    print_diagnosis(&diagnosis);
    Ok(())
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
            let values: Vec<String> = (c.parameters.iter())
                .map(|(n, v)| format!("{n} = {v:.4e}"))
                .collect();
            println!(
                "  {:<27} {:>10.4} {:>10.4} {:>8.1}  {:<6} {}",
                c.name,
                c.gain.mean,
                c.gain.standard_error,
                c.gain.t(),
                if c.helps { "helps" } else { "" },
                values.join(", ")
            );
        }
    }
    println!("answer: {}", d.answer);
}
