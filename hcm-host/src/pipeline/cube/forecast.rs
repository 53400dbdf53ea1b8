//! The held-out tosses forecast by the chance the diagnosis named: the extended model's
//! ensembles beside the fitted model's single replays, both scored by the same proper
//! scores, toss by toss (`crate::replay::forecast_tosses`).

use crate::dataset::Dataset;
use crate::diagnose::Paired;
use crate::numerics::scores::{calibrated_coverage, central_band};
use crate::progress::{in_stage, Progress, Stage};
use crate::replay::{
    band_shares, forecast_tosses, summarize_faces, summarize_paths, FaceSummary, PathForecast,
    Spread, TossError, TossForecast, TossSetup, BAND_LEVELS, CALIBRATION_LEVELS,
};
use crate::scenario::Model;
use serde::Serialize;
use std::fmt::Write;
use std::sync::atomic::{AtomicU64, Ordering};

/// Members of the held-out ensembles: enough for the 90 % band to be calibrated
/// (type-6 quantiles need 19).
pub(crate) const MEMBERS: usize = 32;
/// Seed of their draws.
const SEED: u64 = 1;

/// One model's path scores over the held-out tosses.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathScores {
    /// Mean energy score of the centre (% of the width).
    pub(crate) position: f64,
    /// Mean energy score of the orientation (°).
    pub(crate) rotation: f64,
    /// Mean CRPS of x, y and z (% of the width).
    pub(crate) crps: [f64; 3],
    /// Share of the recorded coordinates inside the 50 % and 90 % bands.
    pub(crate) coverage: Vec<f64>,
    /// The calibration curve: (nominal level, share inside) at every level of
    /// [`CALIBRATION_LEVELS`].
    pub(crate) calibration: Vec<(f64, f64)>,
}

impl PathScores {
    fn of(forecasts: &[PathForecast]) -> PathScores {
        let s = summarize_paths(forecasts);
        PathScores {
            position: s.position.mean,
            rotation: s.rotation.mean,
            crps: s.crps,
            coverage: band_shares(&s.coverage).to_vec(),
            calibration: (CALIBRATION_LEVELS.iter())
                .map(|&level| (level, s.coverage.share_at(level)))
                .collect(),
        }
    }
}

/// One held-out toss's recorded centre beside its forecast's bands, for the report's
/// figure.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ShownToss {
    /// Run id.
    pub(crate) run: String,
    /// Each window frame's time since the window start (s).
    pub(crate) time: Vec<f64>,
    /// The recorded centre at each frame (m).
    pub(crate) recorded: Vec<[f64; 3]>,
    /// Per frame and axis: the members' central 50 % and 90 % bands (m).
    pub(crate) bands: Vec<[[(f64, f64); 2]; 3]>,
}

impl ShownToss {
    /// The toss of `forecast` (of `data`'s runs, `setup`'s primary body) with its bands;
    /// None where a member failed or the recording is missing.
    fn of(setup: &TossSetup, data: &Dataset, forecast: &TossForecast) -> Option<ShownToss> {
        let members: Vec<_> = (forecast.members.iter())
            .map(Option::as_ref)
            .collect::<Option<_>>()?;
        let first = members.first()?;
        let run = (data.runs.iter()).find(|r| r.id == forecast.paths.run)?;
        let recorded = run.body(&setup.name)?.samples.get(first.window.start..)?;
        let t0 = recorded.first()?.time;
        let bands = (0..recorded.len())
            .map(|i| {
                std::array::from_fn(|axis| {
                    let values: Vec<f64> = members
                        .iter()
                        .filter_map(|m| m.samples.get(i).map(|s| s.position[axis]))
                        .collect();
                    BAND_LEVELS.map(|level| central_band(&values, level))
                })
            })
            .collect();
        Some(ShownToss {
            run: forecast.paths.run.clone(),
            time: recorded.iter().map(|s| s.time - t0).collect(),
            recorded: recorded.iter().map(|s| s.position).collect(),
            bands,
        })
    }
}

/// The forecast of the toss whose ensemble score is the median of `forecasts`.
fn median_toss(setup: &TossSetup, data: &Dataset, forecasts: &[TossForecast]) -> Option<ShownToss> {
    let mut order: Vec<usize> = (0..forecasts.len()).collect();
    order.sort_by(|&a, &b| {
        forecasts[a]
            .paths
            .score()
            .total_cmp(&forecasts[b].paths.score())
    });
    let median = *order.get(order.len() / 2)?;
    ShownToss::of(setup, data, &forecasts[median])
}

/// What the forecast stage found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ForecastResults {
    /// Members per toss (–).
    pub(crate) members: usize,
    /// The named chance's variation, as the extended physics file carries it.
    pub(crate) variation: Vec<String>,
    /// The fitted model's single replays.
    pub(crate) replay: PathScores,
    /// The extended model's ensembles.
    pub(crate) ensemble: PathScores,
    /// The bands' levels and what a calibrated ensemble of `members` holds (–).
    pub(crate) calibrated: Vec<(f64, f64)>,
    /// The energy score's gain (position + rotation, % + °), replay − ensemble, paired
    /// per toss.
    pub(crate) gain: Paired,
    /// The final faces from the same members (the primary body a box).
    pub(crate) faces: Option<FaceSummary>,
    /// The held-out toss of median ensemble score with its bands (the figure's).
    #[serde(skip)]
    pub(crate) shown: Option<ShownToss>,
}

impl ForecastResults {
    /// Its report section (`## Forecast by the named chance`): the table, the gain,
    /// the calibration curve's numbers and the faces, in markdown.
    pub fn write_markdown(&self, out: &mut String) -> std::fmt::Result {
        let f = self;
        writeln!(
            out,
            "## Forecast by the named chance\n\nThe held-out tosses forecast by ensembles of {} \
             members of the extended model (the fitted model with {}; `extended.toml`), beside \
             the fitted model's single replays, scored alike: the energy score of the centre \
             (% of the width) and of the orientation (°), the CRPS of each coordinate, and the \
             share of the recorded coordinates inside the members' central bands.\n",
            f.members,
            f.variation.join(", ")
        )?;
        let calibrated: Vec<String> = (f.calibrated.iter())
            .map(|(level, share)| format!("{:.0} %: {share:.3}", 100.0 * level))
            .collect();
        writeln!(
            out,
            "| held out | energy score: position (%) | rotation (°) | CRPS x | y | z (%) | inside 50 % band | inside 90 % band |\n|---|---|---|---|---|---|---|---|"
        )?;
        for (label, s) in [("single replay", &f.replay), ("ensemble", &f.ensemble)] {
            writeln!(
                out,
                "| {label} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.3} | {:.3} |",
                s.position,
                s.rotation,
                s.crps[0],
                s.crps[1],
                s.crps[2],
                s.coverage[0],
                s.coverage[1]
            )?;
        }
        writeln!(
            out,
            "\nEnergy score gain (position + rotation, replay − ensemble, paired per toss): \
             {:.2} (95 % {:.2} to {:.2}) over {} tosses; a calibrated ensemble's bands hold \
             {}.",
            f.gain.mean,
            f.gain.interval[0],
            f.gain.interval[1],
            f.gain.units,
            calibrated.join(", ")
        )?;
        let curve: Vec<String> = (f.ensemble.calibration.iter())
            .map(|(level, share)| format!("{:.0} %: {share:.3}", 100.0 * level))
            .collect();
        writeln!(
            out,
            "The calibration curve (`forecast_calibration.svg`), each central band's share of the held-out coordinates: {}. `forecast_bands.svg`: the held-out toss of median score, its recorded centre over the members' 50 % and 90 % bands.",
            curve.join(", ")
        )?;
        if let Some(s) = &f.faces {
            writeln!(
                out,
                "Final faces from the same members: Brier {:.4} (replay {:.4}), log-likelihood \
                 {:.4} (replay {:.4}), most probable face right on {} of {} (replay {}).",
                s.brier.1,
                s.brier.0,
                s.log_likelihood.1,
                s.log_likelihood.0,
                s.ensemble_right,
                s.tosses,
                s.replay_right
            )?;
        }
        writeln!(out)
    }
}

/// One fold's held-out tosses forecast: the extended model's ensembles and the fitted
/// model's single replays, toss by toss in the data's order.
pub(crate) struct FoldForecast {
    /// Each toss's ensemble of [`MEMBERS`].
    pub(crate) ensembles: Vec<TossForecast>,
    /// Each toss's replay, scored as a one-member forecast.
    pub(crate) replays: Vec<PathForecast>,
    /// Whether the faces were forecast (the body is a box).
    pub(crate) boxed: bool,
}

/// The held-out tosses forecast by `extended` (a model that varies) beside `fitted`'s
/// replays; reports [`Stage::Forecast`].
pub(crate) fn forecast(
    fitted: &Model,
    extended: &Model,
    variation: Vec<String>,
    held_out: &Dataset,
    progress: &dyn Progress,
) -> Result<(ForecastResults, FoldForecast), TossError> {
    let fold = fold_forecast(fitted, extended, held_out, progress)?;
    let setup = TossSetup::new(extended)?;
    let mut results = results_of(&[&fold], variation);
    results.shown = median_toss(&setup, held_out, &fold.ensembles);
    Ok((results, fold))
}

/// [`FoldForecast`] of `held_out`; reports [`Stage::Forecast`].
pub(crate) fn fold_forecast(
    fitted: &Model,
    extended: &Model,
    held_out: &Dataset,
    progress: &dyn Progress,
) -> Result<FoldForecast, TossError> {
    let steps = 2 * held_out.runs.len() as u64;
    let done = AtomicU64::new(0);
    let tick = || progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps);
    in_stage(progress, Stage::Forecast, steps, || {
        let spread = Spread::of_model(MEMBERS, SEED);
        let setup = TossSetup::new(extended)?;
        let boxed = matches!(
            extended.bodies[setup.body].shape,
            crate::scenario::Shape::Box { .. }
        );
        let ensembles = forecast_tosses(extended, held_out, spread, boxed, tick)?;
        let replays = forecast_tosses(fitted, held_out, Spread::replay(), false, tick)?;
        Ok(FoldForecast {
            ensembles,
            replays: replays.into_iter().map(|f| f.paths).collect(),
            boxed,
        })
    })
}

/// The scores of `folds` together (every toss of each, paired with its own replay),
/// the extended models' `variation` as `--set`s; no toss shown.
pub(crate) fn results_of(folds: &[&FoldForecast], variation: Vec<String>) -> ForecastResults {
    let paths: Vec<PathForecast> = (folds.iter())
        .flat_map(|f| f.ensembles.iter().map(|t| t.paths.clone()))
        .collect();
    let single: Vec<PathForecast> = folds.iter().flat_map(|f| f.replays.clone()).collect();
    let scores = |f: &[PathForecast]| f.iter().map(PathForecast::score).collect::<Vec<_>>();
    let faces: Vec<_> = (folds.iter())
        .flat_map(|f| f.ensembles.iter().filter_map(|t| t.face.clone()))
        .collect();
    let boxed = folds.iter().all(|f| f.boxed);
    ForecastResults {
        members: MEMBERS,
        variation,
        replay: PathScores::of(&single),
        ensemble: PathScores::of(&paths),
        calibrated: (BAND_LEVELS.iter())
            .map(|&l| (l, calibrated_coverage(MEMBERS, l)))
            .collect(),
        gain: Paired::of(&scores(&single), &scores(&paths)),
        faces: boxed.then(|| summarize_faces(&faces, MEMBERS)),
        shown: None,
    }
}

/// The held-out tosses of `data` (its odd toss numbers) forecast by a diagnosis'
/// extended model `extended` (a model that varies) beside `base`'s single replays, and
/// the forecast's figures: what `hcm diagnose` shows of a named chance, as `hcm
/// reproduce cube-toss` shows it.
pub fn chance_forecast(
    base: &Model,
    extended: &Model,
    data: &Dataset,
    progress: &dyn Progress,
) -> Result<(ForecastResults, Vec<crate::figure::NamedFigure>), TossError> {
    let (_, held_out) = crate::identify::split_tosses(data);
    let variation = super::extended_physics_sets(extended);
    let (results, _) = forecast(base, extended, variation, &held_out, progress)?;
    let figures = super::forecast_figures::forecast_figures(&results);
    Ok((results, figures))
}
