//! `hcm predict --faces`: each toss's final face forecast by an ensemble of replays
//! (`hcm_host::replay::ensemble`), the contact's scatter chosen on the training tosses
//! unless given, scored per part.

use super::progress_bar;
use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::identify::{part_of, split_tosses, Part};
use hcm_host::output::write_atomically;
use hcm_host::replay::{
    calibrate_scatter, forecast_faces, summarize_faces, FaceForecast, Spread, FACES, SCATTERS,
};
use hcm_host::scenario::Model;
use std::path::{Path, PathBuf};

/// The final-face forecast's options.
#[derive(clap::Args)]
pub struct FaceArgs {
    /// Also forecast each toss's final face (the primary body must be a box) by an
    /// ensemble of replays, and write each toss's face probabilities to FILE (CSV).
    #[arg(long, value_name = "FILE")]
    pub faces: Option<PathBuf>,
    /// Replays per toss in the ensemble.
    #[arg(long, value_name = "N", default_value_t = 16,
          value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub members: u16,
    /// Relative σ of the contact's stiffness, damping and friction each member draws
    /// (e.g. 0.3); without it, the one of 0, 0.1, 0.2, 0.3, 0.5 whose ensembles score
    /// best (Brier) on the training tosses (even toss numbers).
    #[arg(long, value_name = "SIGMA")]
    pub scatter: Option<f64>,
    /// Seed of the ensemble's draws.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// The forecasts of `--faces`, made before anything is written.
pub struct Forecasts {
    path: PathBuf,
    spread: Spread,
    forecasts: Vec<FaceForecast>,
}

impl Forecasts {
    /// Writes the CSV and prints the table.
    pub fn write(&self, data: &Dataset) -> anyhow::Result<()> {
        write_faces(&self.path, &self.forecasts, data)?;
        print_faces(&self.forecasts, data, self.spread);
        println!(
            "wrote each toss's face probabilities to {}",
            self.path.display()
        );
        Ok(())
    }
}

/// The final faces of `data`'s tosses under `model` when `--faces` is given (the
/// scatter chosen on the training part unless given).
pub fn forecast(
    args: &FaceArgs,
    model: &Model,
    data: &Dataset,
) -> anyhow::Result<Option<Forecasts>> {
    let Some(path) = &args.faces else {
        return Ok(None);
    };
    let mut spread = Spread {
        members: usize::from(args.members),
        inflation: 1.0,
        scatter: args.scatter.unwrap_or(0.0),
        seed: args.seed,
    };
    match args.scatter {
        Some(s) if !(0.0..=2.0).contains(&s) => {
            anyhow::bail!("--scatter {s}: give a relative σ from 0 to 2, e.g. 0.3")
        }
        Some(_) => {}
        None => spread.scatter = calibrated(model, data, spread)?,
    }
    let bar = progress_bar(data.runs.len() as u64, "final faces");
    let forecasts = forecast_faces(model, data, spread, || bar.inc(1))
        .context("forecasting the final faces")?;
    bar.finish_and_clear();
    Ok(Some(Forecasts {
        path: path.clone(),
        spread,
        forecasts,
    }))
}

/// The scatter chosen on the training part of `data`, its search printed.
fn calibrated(model: &Model, data: &Dataset, spread: Spread) -> anyhow::Result<f64> {
    let (training, _) = split_tosses(data);
    anyhow::ensure!(
        !training.runs.is_empty(),
        "--faces without --scatter chooses the scatter on the training tosses (even toss \
         numbers), and --data has none: give --scatter"
    );
    let total = (training.runs.len() * SCATTERS.len()) as u64;
    let bar = progress_bar(total, "choosing scatter");
    let (best, scores) = calibrate_scatter(model, &training, spread, &SCATTERS, || bar.inc(1))
        .context("choosing the contact's scatter on the training tosses")?;
    bar.finish_and_clear();
    let tried: Vec<String> = (scores.iter())
        .map(|(s, brier)| format!("{s}: {brier:.4}"))
        .collect();
    println!(
        "scatter chosen on the {} training tosses (mean Brier score per scatter: {}): {best}",
        training.runs.len(),
        tried.join(", ")
    );
    Ok(best)
}

/// Prints the face scores of the training and held-out parts (and all tosses).
fn print_faces(forecasts: &[FaceForecast], data: &Dataset, spread: Spread) {
    println!();
    println!(
        "final faces: ensembles of {} replays from start states drawn with their free-flight \
         fits' covariance, contact parameters scattered by σ = {} (seed {})",
        spread.members, spread.scatter, spread.seed
    );
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
        let s = summarize_faces(&chosen, spread.members);
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
