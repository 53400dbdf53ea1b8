//! Every toss of a data file predicted and scored, beside the frozen-pose baseline: what
//! `hcm predict` prints and writes, and what the identification from motion minimises.

use super::{frozen_pose, predict_tosses, score_toss, TossError, TossPrediction, TossScore};
use super::{Summary, TossSetup};
use crate::dataset::{BodyTrack, Dataset, Run};
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
            let track = run
                .body(&setup.name)
                .ok_or_else(|| TossError::MissingBody {
                    run: run.id.clone(),
                    body: setup.name.clone(),
                })?;
            let measured = &track.samples[prediction.window.start..];
            let score = score_toss(&setup, &run.id, measured, &prediction.samples)?;
            let frozen = frozen_pose(track, &prediction.window);
            let baseline = score_toss(&setup, &run.id, measured, &frozen)?;
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

/// The predicted trajectories as a data file: one run per toss, its id and body kept,
/// the window's frames at their recorded times.
pub fn predicted_dataset(evaluations: &[TossEvaluation], body: &str) -> Dataset {
    Dataset {
        runs: evaluations
            .iter()
            .map(|e| Run {
                id: e.prediction.run.clone(),
                bodies: vec![BodyTrack {
                    body: body.to_owned(),
                    samples: e.prediction.samples.clone(),
                }],
            })
            .collect(),
    }
}
