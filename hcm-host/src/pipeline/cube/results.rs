//! What `results.json` holds: every figure of the report, unrounded.

use super::cross_validated::CrossValidated;
use super::faces::FaceResults;
use super::forecast::ForecastResults;
use super::stages::{Predictions, SecondFold, Timeline};
use super::CubeSettings;
use crate::diagnose::MotionDiagnosis;
use crate::identify::MotionFit;
use crate::pipeline::StageTiming;
use crate::replay::{summarize, Summary, TossEvaluation};
use crate::scenario::Assignment;
use serde::Serialize;

/// A simulator's published scores on this data set (fitted and scored on all 550
/// tosses, as quoted second-hand; not confirmed from the paper).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Published {
    /// The simulator.
    pub(crate) simulator: &'static str,
    /// Position error, mean and standard deviation over tosses (% of the width).
    pub(crate) position: [f64; 2],
    /// Rotation error, mean and standard deviation over tosses (°).
    pub(crate) rotation: [f64; 2],
}

/// The published figures, as quoted second-hand.
pub const PUBLISHED: [Published; 3] = [
    Published {
        simulator: "Drake",
        position: [13.5, 8.2],
        rotation: [16.5, 20.0],
    },
    Published {
        simulator: "Bullet",
        position: [14.9, 8.9],
        rotation: [16.5, 20.2],
    },
    Published {
        simulator: "MuJoCo",
        position: [25.1, 10.8],
        rotation: [21.7, 21.4],
    },
];

/// One row of the score table: a model on one part of the split.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelScores {
    /// `held out`, `cross-validated` (every toss, each predicted by the fold that did
    /// not fit on it) or `training`.
    pub(crate) part: &'static str,
    /// `fitted`, `scenario's parameters` or `frozen pose`.
    pub(crate) model: &'static str,
    /// Position error over tosses (% of the width).
    pub(crate) position: Summary,
    /// Rotation error over tosses (°).
    pub(crate) rotation: Summary,
}

/// One held-out toss's scores under each model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TossRow {
    /// Run id.
    pub(crate) run: String,
    /// Frames of its window (–).
    pub(crate) frames: usize,
    /// Fitted model: position (%) and rotation (°) errors.
    pub(crate) fitted: [f64; 2],
    /// The scenario's parameters: the same.
    pub(crate) scenario: [f64; 2],
    /// The frozen pose: the same.
    pub(crate) frozen: [f64; 2],
}

/// The fit, without its wall-clock time (which is in the timings).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FitSummary {
    /// Fitted values (SI units).
    pub(crate) parameters: Vec<(String, f64)>,
    /// Training fitness (% + °): the scenario's parameters, after the GA, after the
    /// polish.
    pub(crate) start_fitness: f64,
    pub(crate) genetic_fitness: f64,
    pub(crate) fitness: f64,
    /// Replays of the training set (–).
    pub(crate) evaluations: usize,
}

impl FitSummary {
    /// `fit` without its time.
    pub fn of(fit: &MotionFit) -> FitSummary {
        FitSummary {
            parameters: fit.parameters.clone(),
            start_fitness: fit.start_fitness,
            genetic_fitness: fit.genetic_fitness,
            fitness: fit.fitness,
            evaluations: fit.evaluations,
        }
    }
}

/// Everything the report states.
#[derive(Clone, Debug, Serialize)]
pub struct CubeResults {
    /// The example (`cube-toss`, `elbow-toss`).
    pub(crate) name: &'static str,
    /// The fits saw every `fit_stride`th toss of their part (–).
    pub(crate) fit_stride: usize,
    /// The scenario and the data as given.
    pub(crate) scenario: String,
    pub(crate) data: String,
    /// The settings.
    pub(crate) first: Option<usize>,
    pub(crate) seed: u64,
    pub(crate) population: usize,
    pub(crate) generations: usize,
    pub(crate) polish: usize,
    /// Tosses in each part (–).
    pub(crate) training_tosses: usize,
    pub(crate) held_out_tosses: usize,
    /// The fit.
    pub(crate) fit: FitSummary,
    /// The second fold's fit (on the held-out part).
    pub(crate) second_fit: FitSummary,
    /// The `--set`s the fitted table offset and inertia need beside physics.toml.
    pub(crate) sets: Vec<String>,
    /// The score table.
    pub(crate) scores: Vec<ModelScores>,
    /// The published figures, for comparison.
    pub(crate) published: Vec<Published>,
    /// Every held-out toss's scores.
    pub(crate) held_out: Vec<TossRow>,
    /// Held-out errors over time and per phase.
    pub(crate) timeline: Timeline,
    /// The diagnosis of the fitted model (`null`: skipped).
    pub(crate) diagnosis: Option<MotionDiagnosis>,
    /// The held-out tosses' final faces by ensembles (`null`: skipped).
    pub(crate) faces: Option<FaceResults>,
    /// The held-out tosses forecast by the chance the diagnosis named (`null`: none
    /// named, or no diagnosis).
    pub(crate) forecast: Option<ForecastResults>,
    /// The named chance cross-validated: the second fold's (`null`: none named, or no
    /// diagnosis).
    pub(crate) cross_validated: Option<CrossValidated>,
    /// Wall clock per stage (s); the only part that differs between runs.
    pub(crate) timings: Vec<StageTiming>,
}

/// What the two folds made: the fit on the training part with its `--set`s, both parts
/// predicted, and the second fold.
pub struct Folds<'a> {
    pub(crate) fit: &'a MotionFit,
    pub(crate) sets: &'a [Assignment],
    pub(crate) predicted: &'a Predictions,
    pub(crate) second: &'a SecondFold,
}

impl CubeResults {
    /// The results of one run.
    pub(crate) fn gather(
        settings: &CubeSettings,
        folds: Folds<'_>,
        timeline: Timeline,
        diagnosis: Option<&MotionDiagnosis>,
        timings: Vec<StageTiming>,
    ) -> CubeResults {
        CubeResults {
            name: settings.name,
            fit_stride: settings.fit_stride,
            scenario: settings.scenario.label().display().to_string(),
            data: settings.data.display().to_string(),
            first: settings.first,
            seed: settings.seed,
            population: settings.population,
            generations: settings.generations,
            polish: settings.polish,
            training_tosses: folds.predicted.training_fitted.len(),
            held_out_tosses: folds.predicted.held_out_fitted.len(),
            fit: FitSummary::of(folds.fit),
            second_fit: FitSummary::of(&folds.second.fit),
            sets: folds.sets.iter().map(Assignment::to_string).collect(),
            scores: score_rows(folds.predicted, folds.second),
            // The published figures are the cube's data set's.
            published: match settings.name {
                "cube-toss" => PUBLISHED.to_vec(),
                _ => Vec::new(),
            },
            held_out: toss_rows(
                &folds.predicted.held_out_fitted,
                &folds.predicted.held_out_scenario,
            ),
            timeline,
            diagnosis: diagnosis.cloned(),
            faces: None,
            forecast: None,
            cross_validated: None,
            timings,
        }
    }

    /// With the forecast by the named chance.
    pub(crate) fn with_forecast(self, forecast: Option<ForecastResults>) -> CubeResults {
        CubeResults { forecast, ..self }
    }

    /// With the named chance cross-validated.
    pub(crate) fn with_cross_validated(self, cross_validated: Option<CrossValidated>) -> Self {
        CubeResults {
            cross_validated,
            ..self
        }
    }

    /// With the final faces' results.
    pub(crate) fn with_faces(self, faces: Option<FaceResults>) -> CubeResults {
        CubeResults { faces, ..self }
    }

    /// The row of `model` on `part`.
    pub fn row(&self, part: &str, model: &str) -> Option<&ModelScores> {
        (self.scores.iter()).find(|r| r.part == part && r.model == model)
    }
}

/// The score table: held out first, then both folds (every toss, each by the fit that
/// did not see it), then training; fitted, scenario's, frozen pose.
fn score_rows(p: &Predictions, second: &SecondFold) -> Vec<ModelScores> {
    let mut rows = Vec::new();
    let both = |a: &[TossEvaluation], b: &[TossEvaluation]| [a, b].concat();
    let cross_fitted = both(&p.held_out_fitted, &second.predicted);
    let cross_scenario = both(&p.held_out_scenario, &p.training_scenario);
    let parts = [
        ("held out", &p.held_out_fitted, &p.held_out_scenario),
        ("cross-validated", &cross_fitted, &cross_scenario),
        ("training", &p.training_fitted, &p.training_scenario),
    ];
    for (part, fitted, scenario) in parts {
        let (fitted, scenario) = (summarize(fitted), summarize(scenario));
        let models = [
            ("fitted", fitted.position, fitted.rotation),
            (
                "scenario's parameters",
                scenario.position,
                scenario.rotation,
            ),
            (
                "frozen pose",
                fitted.baseline_position,
                fitted.baseline_rotation,
            ),
        ];
        for (model, position, rotation) in models {
            rows.push(ModelScores {
                part,
                model,
                position,
                rotation,
            });
        }
    }
    rows
}

fn toss_rows(fitted: &[TossEvaluation], scenario: &[TossEvaluation]) -> Vec<TossRow> {
    fitted
        .iter()
        .zip(scenario)
        .map(|(f, s)| TossRow {
            run: f.score.run.clone(),
            frames: f.score.frames,
            fitted: [f.score.position_error, f.score.rotation_error],
            scenario: [s.score.position_error, s.score.rotation_error],
            frozen: [f.baseline.position_error, f.baseline.rotation_error],
        })
        .collect()
}
