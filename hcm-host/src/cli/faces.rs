//! `hcm predict --faces`: each toss's final face forecast by the ensemble
//! (`hcm_host::replay::ensemble`), scored per part and written as CSV.

use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::identify::{part_of, Part};
use hcm_host::output::write_atomically;
use hcm_host::replay::{summarize_faces, FaceForecast, FACES};
use std::path::Path;

/// Writes each toss's face probabilities to `path` and prints the table (`members`
/// per ensemble, `described` the ensemble's draws in words).
pub fn write(
    path: &Path,
    forecasts: &[FaceForecast],
    data: &Dataset,
    members: usize,
    described: &str,
) -> anyhow::Result<()> {
    write_faces(path, forecasts, data)?;
    print_faces(forecasts, data, members, described);
    println!("wrote each toss's face probabilities to {}", path.display());
    Ok(())
}

/// Prints the face scores of the training and held-out parts (and all tosses).
fn print_faces(forecasts: &[FaceForecast], data: &Dataset, members: usize, described: &str) {
    println!();
    println!("final faces: ensembles of {members} replays, {described}");
    println!(
        "| tosses | right face: replay | ensemble | Brier: replay | ensemble | log-likelihood: replay | ensemble |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (label, part) in [
        ("training", Some(Part::Training)),
        ("held out", Some(Part::HeldOut)),
        ("all", None),
    ] {
        let chosen: Vec<FaceForecast> = (forecasts.iter().zip(&data.runs).enumerate())
            .filter(|(i, (_, run))| part.is_none_or(|p| part_of(&run.id, *i) == p))
            .map(|(_, (f, _))| f.clone())
            .collect();
        if chosen.is_empty() {
            continue;
        }
        let s = summarize_faces(&chosen, members);
        println!(
            "| {label} ({}) | {} | {} | {:.4} | {:.4} | {:.4} | {:.4} |",
            s.tosses,
            s.replay_right,
            s.ensemble_right,
            s.brier.0,
            s.brier.1,
            s.log_likelihood.0,
            s.log_likelihood.1
        );
    }
    let failed: usize = forecasts.iter().map(|f| f.failed).sum();
    if failed > 0 {
        println!("{failed} members' replays failed and were left out of their tosses' counts");
    }
}

/// Writes each toss's faces as CSV, atomically.
fn write_faces(path: &Path, forecasts: &[FaceForecast], data: &Dataset) -> anyhow::Result<()> {
    write_atomically(path, |out| -> anyhow::Result<()> {
        let mut csv = csv::Writer::from_writer(out);
        let probabilities = (0..FACES).map(|f| format!("p{}", hcm_host::replay::Face(f).name()));
        let header = [
            "run",
            "part",
            "measured",
            "replay",
            "most_probable",
            "members",
            "failed",
        ]
        .map(str::to_owned)
        .into_iter()
        .chain(probabilities)
        .chain(["brier", "replay_brier"].map(str::to_owned));
        csv.write_record(header)?;
        for (i, (f, run)) in forecasts.iter().zip(&data.runs).enumerate() {
            let part = match part_of(&run.id, i) {
                Part::Training => "training",
                Part::HeldOut => "held out",
            };
            let fixed = [
                f.run.clone(),
                part.to_owned(),
                f.measured.name().to_owned(),
                f.replay.name().to_owned(),
                f.most_probable().name().to_owned(),
                f.members().to_string(),
                f.failed.to_string(),
            ];
            let p = f.probabilities().map(|p| p.to_string());
            let scores = [f.brier().to_string(), f.replay_brier().to_string()];
            csv.write_record(fixed.into_iter().chain(p).chain(scores))?;
        }
        csv.flush()?;
        Ok(())
    })
    .with_context(|| format!("writing {}", path.display()))
}
