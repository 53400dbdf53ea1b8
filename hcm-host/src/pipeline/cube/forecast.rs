//! The held-out tosses forecast by the chance the diagnosis named: the extended model's
//! ensembles beside the fitted model's single replays, both scored by the same proper
//! scores, toss by toss (`crate::replay::forecast_tosses`).

use crate::dataset::Dataset;
use crate::diagnose::Paired;
use crate::numerics::scores::calibrated_coverage;
use crate::progress::{in_stage, Progress, Stage};
use crate::replay::{
    forecast_tosses, summarize_faces, summarize_paths, FaceSummary, PathForecast, Spread,
    TossError, BAND_LEVELS,
};
use crate::scenario::Model;
use serde::Serialize;
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
}

impl PathScores {
    fn of(forecasts: &[PathForecast]) -> PathScores {
        let s = summarize_paths(forecasts);
        PathScores {
            position: s.position.mean,
            rotation: s.rotation.mean,
            crps: s.crps,
            coverage: s.coverage.shares(),
        }
    }
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
}

/// The held-out tosses forecast by `extended` (a model that varies) beside `fitted`'s
/// replays; reports [`Stage::Forecast`].
pub(crate) fn forecast(
    fitted: &Model,
    extended: &Model,
    variation: Vec<String>,
    held_out: &Dataset,
    progress: &dyn Progress,
) -> Result<ForecastResults, TossError> {
    let steps = 2 * held_out.runs.len() as u64;
    let done = AtomicU64::new(0);
    let tick = || progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps);
    in_stage(progress, Stage::Forecast, steps, || {
        let spread = Spread::of_model(MEMBERS, SEED);
        let boxed = crate::replay::TossSetup::new(extended).is_ok_and(|s| {
            matches!(
                extended.bodies[s.body].shape,
                crate::scenario::Shape::Box { .. }
            )
        });
        let ensembles = forecast_tosses(extended, held_out, spread, boxed, tick)?;
        let replays = forecast_tosses(fitted, held_out, Spread::replay(), false, tick)?;
        let paths: Vec<PathForecast> = ensembles.iter().map(|f| f.paths.clone()).collect();
        let single: Vec<PathForecast> = replays.into_iter().map(|f| f.paths).collect();
        let scores = |f: &[PathForecast]| f.iter().map(PathForecast::score).collect::<Vec<_>>();
        let faces: Vec<_> = ensembles.iter().filter_map(|f| f.face.clone()).collect();
        Ok(ForecastResults {
            members: MEMBERS,
            variation,
            replay: PathScores::of(&single),
            ensemble: PathScores::of(&paths),
            calibrated: (BAND_LEVELS.iter())
                .map(|&l| (l, calibrated_coverage(MEMBERS, l)))
                .collect(),
            gain: Paired::of(&scores(&single), &scores(&paths)),
            faces: boxed.then(|| summarize_faces(&faces, MEMBERS)),
        })
    })
}
