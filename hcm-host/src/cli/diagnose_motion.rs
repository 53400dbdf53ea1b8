//! `hcm diagnose` from poses (the data hold no force, or `--from-poses`, which
//! `hcm diagnose-motion` implies): what a tossed or sliding body's simulation gets
//! wrong, from filmed motion alone.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::diagnose::{
    diagnose_motion_with, Catalogue, MotionBase, MotionDiagnosis, GAIN_T, MIN_GAIN, RIVAL_T,
};
use hcm_host::output::write_bytes;

/// Diagnoses `model` on `data` (read from `path`), writes the diagnosis as JSON to
/// `json` (creating the directory it is in, once there is something to write)
/// and prints it. `hcm diagnose` on a camera's poses comes here too, with a `base`
/// fitted when its physics file says so, and the catalogue to try (chance when asked).
pub fn diagnose_into(
    model: &hcm_host::scenario::Model,
    data: &hcm_host::dataset::Dataset,
    base: (MotionBase, &Catalogue),
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
