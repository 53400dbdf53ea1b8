//! `hcm predict`: replay measured tosses from their window start and score the
//! prediction against the recorded poses.

use super::progress_bar;
use anyhow::Context;
use hcm_host::replay::{
    evaluate_tosses, predicted_dataset, summarize, summarize_bodies, write_scores, StateSource,
    Summary, TossEvaluation, TossSetup,
};
use std::path::PathBuf;
use std::time::Instant;

/// Predict measured tosses from their window start and score the prediction.
///
/// Example: `hcm predict --scenario scenarios/cube_toss.toml --data data/contactnets-cube/tosses.csv --out predicted.csv`
///
/// For each run of --data (a toss: the scenario's one moving body, a box, filmed while
/// it lands on the scenario's fixed plane): finds the window, estimates the initial
/// state there, simulates from it with the scenario's physics (or --physics), and
/// writes the predicted trajectory to OUT in the measured-data format, at the run's own
/// frame times from the window start on. Prints the scores over tosses beside the
/// frozen-pose baseline's. Tosses run in parallel (RAYON_NUM_THREADS threads; the
/// results do not depend on it).
///
/// Terms:
///   window         a toss's frames from 3 frames before the body's centre first comes
///                  within its circumscribed radius of a fixed body it can touch (the
///                  ContactNets cube: 0.0524·√3 m of the table; nearer, a corner can
///                  touch), or bounces off it between two frames, to its last frame
///   initial state  the body's state at the window start: position and velocity fitted
///                  to the last 8 frames up to it (a parabola under the scenario's
///                  gravity, a straight line across), orientation and angular velocity
///                  likewise (constant angular velocity); with fewer than 4 such frames,
///                  the recorded state at the window start (the summary counts these)
///   position error mean over the window's frames of |p_pred − p| / the body's width
///                  (the cube's side, 0.1048 m), in %
///   rotation error mean over the window's frames of the angle of R_predᵀ·R, in degrees
///   frozen pose    the baseline: the body held at its recorded window-start pose
///   physics file   a contact law with its parameters and friction, as `hcm identify`
///                  or `hcm identify-motion` writes it (`--physics`); without it, the
///                  scenario's own. The table offset and inertia `hcm identify-motion`
///                  found are given as the `--set`s it prints
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    tosses: super::tosses::TossArgs,
    /// Where to write the predicted trajectories (measured-data CSV, one run per toss;
    /// with --members, every member's: the same columns and `member` last).
    #[arg(long)]
    out: PathBuf,
    /// Also write each toss's scores (CSV: run, frames, window start, how the initial
    /// state was found, position and rotation error of the prediction and of the frozen
    /// pose, then the initial state itself: p0x…p0z (m), q0w…q0z, v0x…v0z (m/s),
    /// w0x…w0z (rad/s), world frame; with --members, then the forecast's scores:
    /// energy_position (%), energy_rotation (°), crps_x…crps_z (%), inside_50 and
    /// inside_90 (shares of the recorded coordinates), members, failed). With several
    /// moving bodies (a mechanism's links) a `body` column after `run`: per toss a row
    /// per body (its scores in % of its own width, its own initial state), then a row
    /// `all` (their means, no initial state, the forecast's scores).
    #[arg(long, value_name = "FILE")]
    scores: Option<PathBuf>,
    /// Also forecast each toss's final face (the primary body must be a box) by the
    /// ensemble (16 members without --members), and write each toss's face
    /// probabilities to FILE (CSV).
    #[arg(long, value_name = "FILE")]
    faces: Option<PathBuf>,
    #[command(flatten)]
    ensemble: super::forecast::EnsembleArgs,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let (model, setup, data) = args.tosses.load()?;
    let bar = progress_bar(data.runs.len() as u64, "tosses");
    let started = Instant::now();
    let evaluations = evaluate_tosses(&model, &data, || bar.inc(1))
        .with_context(|| format!("predicting the tosses of {}", args.tosses.data.display()))?;
    bar.finish_and_clear();
    let seconds = started.elapsed().as_secs_f64();
    // Every forecast made before anything is written: a failure leaves no output.
    let faces = args.faces.is_some();
    let ensemble = super::forecast::forecast(&args.ensemble, faces, &model, &data)?;
    let members = ensemble
        .as_ref()
        .filter(|_| args.ensemble.members.is_some());
    match members {
        Some(e) => super::forecast::write_members(&args.out, &e.forecasts, &setup.name)?,
        None => predicted_dataset(&evaluations, &setup.name)
            .write(&args.out)
            .with_context(|| format!("writing {}", args.out.display()))?,
    }
    if let Some(path) = &args.scores {
        let paths: Option<Vec<_>> =
            members.map(|e| e.forecasts.iter().map(|f| f.paths.clone()).collect());
        write_scores(path, &evaluations, paths.as_deref())?;
    }
    print_summary(&model.scenario.name, &setup, &evaluations, seconds);
    if let Some(e) = members {
        super::forecast::print_scores(e, setup.width);
        println!(
            "wrote every member's predicted trajectories to {} (column `member`)",
            args.out.display()
        );
    } else {
        println!("wrote the predicted trajectories to {}", args.out.display());
    }
    if let Some(path) = &args.scores {
        println!("wrote each toss's scores to {}", path.display());
    }
    if let (Some(path), Some(e)) = (&args.faces, &ensemble) {
        let forecasts: Vec<_> = e.forecasts.iter().filter_map(|f| f.face.clone()).collect();
        super::faces::write(path, &forecasts, &data, e.spread.members, &e.described)?;
    }
    Ok(())
}

/// Prints what was predicted, how long it took and the scores over tosses.
fn print_summary(name: &str, setup: &TossSetup, evaluations: &[TossEvaluation], seconds: f64) {
    let frames: usize = evaluations.iter().map(|e| e.score.frames).sum();
    let recorded = (evaluations.iter())
        .filter(|e| e.prediction.initial.source == StateSource::Recorded)
        .count();
    let mut times: Vec<f64> = evaluations.iter().map(|e| e.prediction.seconds).collect();
    let steps: u64 = evaluations.iter().map(|e| e.prediction.steps).sum();
    times.sort_by(f64::total_cmp);
    let median_ms = 1e3 * times.get(times.len() / 2).copied().unwrap_or(f64::NAN);
    println!(
        "{name}: {} tosses, {frames} frames in their windows, predicted in {seconds:.2} s \
         ({} threads; one toss's simulation: median {median_ms:.1} ms, {} solver steps on \
         average)",
        evaluations.len(),
        rayon::current_num_threads(),
        steps / evaluations.len().max(1) as u64
    );
    println!(
        "initial states: {} fitted to the free-flight frames up to the window start, \
         {recorded} recorded (too few frames before the window)",
        evaluations.len() - recorded
    );
    let summary = summarize(evaluations);
    // Several moving bodies (a mechanism's links): each one's rows, then their mean.
    let bodies = summarize_bodies(evaluations);
    let unit = match bodies.is_empty() {
        true => format!("{:.1} mm", 1e3 * setup.width),
        false => "each body's width".to_owned(),
    };
    println!();
    println!(
        "| model | position error (% of {unit}): mean ± std | median | rotation error (°): mean ± std | median |"
    );
    println!("|---|---|---|---|---|");
    let row = |label: &str, position: &Summary, rotation: &Summary| {
        println!(
            "| {label} | {:.2} ± {:.2} | {:.2} | {:.2} ± {:.2} | {:.2} |",
            position.mean,
            position.std,
            position.median,
            rotation.mean,
            rotation.std,
            rotation.median
        );
    };
    for (name, s) in &bodies {
        row(&format!("simulation: `{name}`"), &s.position, &s.rotation);
    }
    let label = |what: &str| match bodies.is_empty() {
        true => what.to_owned(),
        false => format!("{what} (mean over the bodies)"),
    };
    row(&label("simulation"), &summary.position, &summary.rotation);
    for (name, s) in &bodies {
        let (p, r) = (&s.baseline_position, &s.baseline_rotation);
        row(&format!("frozen pose: `{name}`"), p, r);
    }
    row(
        &label("frozen pose"),
        &summary.baseline_position,
        &summary.baseline_rotation,
    );
}
