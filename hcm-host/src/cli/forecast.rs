//! `hcm predict --members`: each toss forecast by an ensemble drawn from the model's
//! variation (`hcm_host::replay::forecast_tosses`): every member's path written in the
//! measured-data format with a `member` column, and the forecast scored by proper
//! scores beside the single replay, toss by toss.

use super::progress_bar;
use anyhow::Context;
use hcm_host::dataset::{Dataset, RunWriter};
use hcm_host::identify::split_tosses;
use hcm_host::numerics::scores::calibrated_coverage;
use hcm_host::output::write_atomically;
use hcm_host::replay::{
    band_shares, calibrate_scatter, forecast_tosses, summarize_paths, PathForecast, Spread,
    Summary, TossForecast, BAND_LEVELS, SCATTERS,
};
use hcm_host::scenario::Model;
use std::path::Path;

/// The ensemble's options.
#[derive(clap::Args)]
pub struct EnsembleArgs {
    /// Forecast each toss by an ensemble of N members drawn from the model's variation
    /// (its contacts' `noise`, its `[variation]`, as `hcm diagnose-motion` names them;
    /// or --scatter and --start-spread): --out then holds every member's predicted
    /// path, and the forecast's scores are printed beside the single replay's. A model
    /// without variation gives N copies of the replay.
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub members: Option<u16>,
    /// Relative σ of every contact's stiffness, damping and friction coefficient that
    /// each member draws (e.g. 0.3), in place of the contacts' own `noise`. With
    /// --faces and a model without variation: the one of 0, 0.1, 0.2, 0.3, 0.5 whose
    /// ensembles score best (Brier) on the training tosses (even toss numbers).
    #[arg(long, value_name = "SIGMA")]
    pub scatter: Option<f64>,
    /// Factor on the σ of each toss's start state that each member draws (the
    /// covariance of its free-flight fit; 1: as uncertain as the tracker's noise left
    /// it), in place of the model's `variation.start_state`. With --faces and a model
    /// without variation: 1.
    #[arg(long, value_name = "FACTOR")]
    pub start_spread: Option<f64>,
    /// Seed of the members' draws: the same seed gives the same members on any number
    /// of threads.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Members of the final faces' ensembles when --faces is given without --members.
const FACE_MEMBERS: usize = 16;

/// The ensemble forecast of every toss, and the single replays scored the same way.
pub struct Ensemble {
    /// How the members were drawn.
    pub spread: Spread,
    /// That, in words.
    pub described: String,
    /// Each toss's forecast.
    pub forecasts: Vec<TossForecast>,
    /// Each toss's single replay, scored as a one-member forecast.
    pub replays: Vec<PathForecast>,
}

/// The ensemble forecast of `data` when --members or --faces (`faces`) asks for one.
pub fn forecast(
    args: &EnsembleArgs,
    faces: bool,
    model: &Model,
    data: &Dataset,
) -> anyhow::Result<Option<Ensemble>> {
    if args.members.is_none() && !faces {
        for (given, option) in [
            (args.scatter.is_some(), "--scatter"),
            (args.start_spread.is_some(), "--start-spread"),
        ] {
            anyhow::ensure!(
                !given,
                "{option} sets how an ensemble's members are drawn: give --members N (or \
                 --faces FILE) with it"
            );
        }
        return Ok(None);
    }
    if let Some(s) = args.scatter {
        anyhow::ensure!(
            (0.0..=2.0).contains(&s),
            "--scatter {s}: give a relative σ from 0 to 2, e.g. 0.3"
        );
    }
    if let Some(k) = args.start_spread {
        anyhow::ensure!(
            k >= 0.0 && k.is_finite(),
            "--start-spread {k}: give a factor ≥ 0 on the start state's σ, e.g. 1"
        );
    }
    let members = args.members.map_or(FACE_MEMBERS, usize::from);
    let mut spread = Spread {
        members,
        inflation: args.start_spread,
        scatter: args.scatter,
        seed: args.seed,
    };
    // A model without variation, the faces asked for and nothing given: the faces'
    // ensemble as before the model could carry its scatter (start state as fitted,
    // contact scatter chosen on the training tosses).
    if faces && !model.varies() && args.scatter.is_none() && args.start_spread.is_none() {
        spread.inflation = Some(1.0);
        spread.scatter = Some(calibrated(model, data, spread)?);
    }
    let described = describe(model, spread);
    let bar = progress_bar(data.runs.len() as u64, "ensembles");
    let forecasts = forecast_tosses(model, data, spread, faces, || bar.inc(1))
        .context("forecasting the tosses by ensembles")?;
    bar.finish_and_clear();
    let replay = model.without_variation();
    let replays = forecast_tosses(&replay, data, Spread::replay(), false, || {})
        .context("scoring the single replays")?
        .into_iter()
        .map(|f| f.paths)
        .collect();
    Ok(Some(Ensemble {
        spread,
        described,
        forecasts,
        replays,
    }))
}

/// The ensemble's draws in words.
fn describe(model: &Model, spread: Spread) -> String {
    let (drawn, inflation) = spread.applied(model);
    let mut parts = Vec::new();
    for (c, contact) in drawn.contacts.iter().enumerate() {
        if contact.noise.is_empty() {
            continue;
        }
        let noise: Vec<String> = (contact.noise.iter())
            .map(|(name, b)| format!("{name} {b}"))
            .collect();
        let pair = [contact.body_1, contact.body_2].map(|b| drawn.bodies[b].name.as_str());
        parts.push(format!(
            "contact {c} ({}–{}) scattered by relative σ: {}",
            pair[0],
            pair[1],
            noise.join(", ")
        ));
    }
    if inflation > 0.0 {
        parts.push(format!(
            "start states drawn with their free-flight fits' covariance, σ × {inflation}"
        ));
    }
    let v = &drawn.scenario.variation;
    if v.fixed_height > 0.0 || v.fixed_tilt > 0.0 {
        parts.push(format!(
            "fixed bodies' height σ {} m and tilt σ {} rad per run",
            v.fixed_height, v.fixed_tilt
        ));
    }
    if v.tails > 0.0 && !parts.is_empty() {
        parts.push(format!("run-to-run draws Student-t with ν = {}", v.tails));
    }
    if parts.is_empty() {
        parts.push("no variation (every member is the single replay)".into());
    }
    format!("{} (seed {})", parts.join("; "), spread.seed)
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

/// Writes every member's predicted path to `path`, atomically: the measured-data format
/// with the column `member` last, toss by toss in the data's order, member by member
/// (a failed member has no rows), each body's window frames at their recorded times.
pub fn write_members(path: &Path, forecasts: &[TossForecast], primary: &str) -> anyhow::Result<()> {
    let name = path.display().to_string();
    write_atomically(path, |out| -> anyhow::Result<()> {
        let mut writer = RunWriter::with_members(out, &name)?;
        for forecast in forecasts {
            for (member, prediction) in forecast.members.iter().enumerate() {
                if let Some(prediction) = prediction {
                    writer.write_member(&prediction.to_run(primary), member)?;
                }
            }
        }
        writer.finish()?;
        Ok(())
    })
    .with_context(|| format!("writing {name}"))
}

/// Prints the forecast's scores beside the single replay's: per toss (up to
/// `PER_TOSS` tosses) and over tosses, with the paired gain.
pub fn print_scores(ensemble: &Ensemble, width: f64) {
    const PER_TOSS: usize = 20;
    let members = ensemble.spread.members;
    let paths: Vec<PathForecast> = (ensemble.forecasts.iter())
        .map(|f| f.paths.clone())
        .collect();
    println!();
    println!(
        "forecast: ensembles of {members} members, {}",
        ensemble.described
    );
    let unit = format!("% of {:.1} mm", 1e3 * width);
    if paths.len() <= PER_TOSS {
        println!(
            "| toss | energy score: position ({unit}) | rotation (°) | CRPS x | y | z ({unit}) | inside 50 % band | inside 90 % band | face Brier | face log score |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|");
        for (forecast, toss) in ensemble.forecasts.iter().zip(&paths) {
            let shares = band_shares(&toss.coverage);
            let (brier, log) = forecast
                .face
                .as_ref()
                .map_or((f64::NAN, f64::NAN), |f| (f.brier(), -f.log_likelihood()));
            println!(
                "| {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.3} | {:.3} | {brier:.3} | {log:.3} |",
                toss.run,
                toss.position,
                toss.rotation,
                toss.crps[0],
                toss.crps[1],
                toss.crps[2],
                shares[0],
                shares[1]
            );
        }
        println!();
    }
    println!(
        "| over {} tosses | energy score: position ({unit}) | rotation (°) | CRPS x | y | z ({unit}) | inside 50 % band | inside 90 % band |",
        paths.len()
    );
    println!("|---|---|---|---|---|---|---|---|");
    let row = |label: &str, forecasts: &[PathForecast]| {
        let s = summarize_paths(forecasts);
        let shares = band_shares(&s.coverage);
        println!(
            "| {label} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.3} | {:.3} |",
            s.position.mean, s.rotation.mean, s.crps[0], s.crps[1], s.crps[2], shares[0], shares[1]
        );
    };
    row("single replay", &ensemble.replays);
    row(&format!("ensemble of {members}"), &paths);
    let calibrated: Vec<String> = (BAND_LEVELS.iter())
        .map(|&level| format!("{:.3}", calibrated_coverage(members, level)))
        .collect();
    let gains: Vec<f64> = (ensemble.replays.iter().zip(&paths))
        .map(|(one, many)| one.score() - many.score())
        .collect();
    let gain = Summary::of(&gains);
    let half = 1.96 * gain.std / (gain.count.max(1) as f64).sqrt();
    println!(
        "energy score gain over the single replay (position + rotation, paired per toss): \
         {:.2} ± {half:.2} (95 % interval); bands of {members} members drawn like the \
         outcome hold {} of it",
        gain.mean,
        calibrated.join(" and ")
    );
    let failed: usize = paths.iter().map(|p| p.failed).sum();
    if failed > 0 {
        println!("{failed} members' replays failed and were left out of their tosses' scores");
    }
}
