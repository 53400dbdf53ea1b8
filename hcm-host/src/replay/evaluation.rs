//! Every toss of a data file predicted and scored, beside the frozen-pose baseline: what
//! `hcm predict` prints and writes, and what the identification from motion minimises.

use super::score::score_movers;
use super::{frozen_pose, predict_tosses, TossError, TossPrediction, TossScore};
use super::{Summary, TossSetup};
use crate::dataset::{Dataset, Sample};
use crate::scenario::Model;

/// One toss predicted and scored.
#[derive(Clone, Debug)]
pub struct TossEvaluation {
    /// The prediction.
    pub prediction: TossPrediction,
    /// Its scores.
    pub score: TossScore,
    /// The frozen-pose baseline's scores on the same frames.
    pub baseline: TossScore,
}

/// The summaries over tosses: (position, rotation) of the model, then of the baseline.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct EvaluationSummary {
    /// Position error of the model (% of the body's width).
    pub position: Summary,
    /// Rotation error of the model (degrees).
    pub rotation: Summary,
    /// Position error of the frozen pose (% of the body's width).
    pub baseline_position: Summary,
    /// Rotation error of the frozen pose (degrees).
    pub baseline_rotation: Summary,
}

/// Predicts and scores every run of `data` with `model` (in parallel; `done` is called
/// as each toss's simulation ends), in the data's order.
pub fn evaluate_tosses(
    model: &Model,
    data: &Dataset,
    done: impl Fn() + Sync,
) -> Result<Vec<TossEvaluation>, TossError> {
    let setup = TossSetup::new(model)?;
    let predictions = predict_tosses(model, data, done)?;
    predictions
        .into_iter()
        .zip(&data.runs)
        .map(|(prediction, run)| {
            let mut measured = Vec::with_capacity(setup.movers.len());
            let mut frozen = Vec::with_capacity(setup.movers.len());
            for (mover, window) in setup.movers.iter().zip(prediction.windows()) {
                let track = run
                    .body(&mover.name)
                    .ok_or_else(|| TossError::MissingBody {
                        run: run.id.clone(),
                        body: mover.name.clone(),
                    })?;
                measured.push(&track.samples[window.start..]);
                frozen.push(frozen_pose(track, &window));
            }
            let score = score_movers(&setup, &run.id, &measured, &prediction.tracks())?;
            let frozen: Vec<&[Sample]> = frozen.iter().map(Vec::as_slice).collect();
            let baseline = score_movers(&setup, &run.id, &measured, &frozen)?;
            Ok(TossEvaluation {
                prediction,
                score,
                baseline,
            })
        })
        .collect()
}

/// The summaries of `evaluations`.
pub fn summarize(evaluations: &[TossEvaluation]) -> EvaluationSummary {
    let scores: Vec<TossScore> = evaluations.iter().map(|e| e.score.clone()).collect();
    let baselines: Vec<TossScore> = evaluations.iter().map(|e| e.baseline.clone()).collect();
    let (position, rotation) = Summary::of_scores(&scores);
    let (baseline_position, baseline_rotation) = Summary::of_scores(&baselines);
    EvaluationSummary {
        position,
        rotation,
        baseline_position,
        baseline_rotation,
    }
}

/// With several moving bodies, each one's summaries over tosses: its name, then its
/// position and rotation errors and the frozen pose's, as [`EvaluationSummary`] (each
/// body's position in % of its own width); empty with one body.
pub fn summarize_bodies(evaluations: &[TossEvaluation]) -> Vec<(String, EvaluationSummary)> {
    let Some(first) = evaluations.first() else {
        return Vec::new();
    };
    // Body m's position (or rotation) errors over the tosses, of the model or of the
    // frozen pose.
    let column = |m: usize, frozen: bool, rotation: bool| {
        let values: Vec<f64> = (evaluations.iter())
            .filter_map(|e| {
                let body = (if frozen { &e.baseline } else { &e.score })
                    .bodies
                    .get(m)?;
                Some(if rotation {
                    body.rotation_error
                } else {
                    body.position_error
                })
            })
            .collect();
        Summary::of(&values)
    };
    (first.score.bodies.iter().enumerate())
        .map(|(m, body)| {
            let summary = EvaluationSummary {
                position: column(m, false, false),
                rotation: column(m, false, true),
                baseline_position: column(m, true, false),
                baseline_rotation: column(m, true, true),
            };
            (body.body.clone(), summary)
        })
        .collect()
}

/// The predicted trajectories as a data file: one run per toss, its id and bodies kept
/// (`body` the primary's name), the window's frames at their recorded times.
pub fn predicted_dataset(evaluations: &[TossEvaluation], body: &str) -> Dataset {
    Dataset {
        runs: (evaluations.iter())
            .map(|e| e.prediction.to_run(body))
            .collect(),
    }
}
