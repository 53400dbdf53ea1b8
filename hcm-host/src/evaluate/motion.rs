//! `hcm evaluate` on a camera's data (trajectory scores: PM2 beside
//! the HCM beside the data): every run replayed from its window start by each
//! model, as `hcm predict` does, and scored against the recorded poses — position error
//! (% of the body's width) and rotation error (°) — beside the frozen pose, with each
//! model's per-run difference from the first (HCM − PM2).

use super::rigid::{mean_se, verdict};
use crate::dataset::Dataset;
use crate::replay::{evaluate_tosses, summarize, EvaluationSummary, TossError};
use crate::scenario::Model;
use serde::Serialize;

/// One model's scores.
#[derive(Clone, Debug, Serialize)]
pub struct MotionColumn {
    /// Its label.
    pub label: String,
    /// Position and rotation error over the runs, and the frozen pose's.
    pub summary: EvaluationSummary,
    /// Per run: position error (%) + rotation error (°), in the data's order.
    pub scores: Vec<f64>,
    /// Its per-run score minus the first model's: mean and standard error (% + °).
    pub paired: (f64, f64),
}

/// What [`evaluate_motion`] finds.
#[derive(Clone, Debug, Serialize)]
pub struct MotionEvaluation {
    /// Runs scored.
    pub runs: usize,
    /// One column per model, in the order given.
    pub columns: Vec<MotionColumn>,
}

/// Replays every run of `data` with each of `models` (label, model) and scores it.
pub fn evaluate_motion(
    models: &[(&str, &Model)],
    data: &Dataset,
) -> Result<MotionEvaluation, TossError> {
    let mut columns: Vec<MotionColumn> = Vec::with_capacity(models.len());
    for (label, model) in models {
        let evaluations = evaluate_tosses(model, data, || {})?;
        let scores: Vec<f64> = (evaluations.iter())
            .map(|e| e.score.position_error + e.score.rotation_error)
            .collect();
        let paired = match columns.first() {
            Some(first) => mean_se(scores.iter().zip(&first.scores).map(|(s, f)| s - f)),
            None => (0.0, 0.0),
        };
        columns.push(MotionColumn {
            label: (*label).to_owned(),
            summary: summarize(&evaluations),
            scores,
            paired,
        });
    }
    Ok(MotionEvaluation {
        runs: data.runs.len(),
        columns,
    })
}

/// The evaluation as markdown: one row per model and the frozen pose, then each
/// model's per-run difference from the first.
pub fn motion_markdown(e: &MotionEvaluation) -> String {
    use std::fmt::Write as _;
    let mut out = String::from(
        "| model | position error (% of width): mean ± std | median | rotation error (°): mean ± std | median |\n|---|---|---|---|---|\n",
    );
    let row =
        |out: &mut String, label: &str, p: &crate::replay::Summary, r: &crate::replay::Summary| {
            let _ = writeln!(
                out,
                "| {label} | {:.2} ± {:.2} | {:.2} | {:.2} ± {:.2} | {:.2} |",
                p.mean, p.std, p.median, r.mean, r.std, r.median
            );
        };
    for c in &e.columns {
        row(&mut out, &c.label, &c.summary.position, &c.summary.rotation);
    }
    if let Some(first) = e.columns.first() {
        let s = &first.summary;
        row(
            &mut out,
            "frozen pose",
            &s.baseline_position,
            &s.baseline_rotation,
        );
    }
    for c in e.columns.iter().skip(1) {
        let (d, se) = c.paired;
        let verdict = verdict(d, se);
        let _ = writeln!(
            out,
            "\n{} − {}: {d:+.3} ± {se:.3} % + ° per run over {} runs ({verdict})",
            c.label, e.columns[0].label, e.runs
        );
    }
    out
}
