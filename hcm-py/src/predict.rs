//! Recorded tosses replayed from their window start and scored against the recorded
//! poses (`hcm predict`): the predicted trajectories, each toss's scores, and their
//! summary, beside the frozen pose's.

use crate::dataset::Dataset;
use crate::errors::hcm_error;
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_host::progress::{Fold, Stage};
use hcm_host::replay::{
    evaluate_tosses, predicted_dataset, summarize, write_scores, Summary, TossEvaluation, TossSetup,
};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

/// The tosses predicted: one evaluation per toss, and the predicted body's name.
#[pyclass(module = "hcm._hcm", frozen)]
pub struct Prediction {
    evaluations: Vec<TossEvaluation>,
    body: String,
}

/// `(mean, std, median)` of one score over the tosses.
fn triple(s: &Summary) -> (f64, f64, f64) {
    (s.mean, s.std, s.median)
}

#[pymethods]
impl Prediction {
    /// The predicted trajectories (`hcm predict --out`'s file).
    fn dataset(&self) -> Dataset {
        Dataset::named(
            predicted_dataset(&self.evaluations, &self.body),
            "<predicted>",
        )
    }

    /// Per toss: `(run, frames, position error (% of the width), rotation error (°),
    /// frozen pose's position error, frozen pose's rotation error)`.
    fn scores(&self) -> Vec<(String, usize, f64, f64, f64, f64)> {
        self.evaluations
            .iter()
            .map(|e| {
                let (s, b) = (&e.score, &e.baseline);
                (
                    s.run.clone(),
                    s.frames,
                    s.position_error,
                    s.rotation_error,
                    b.position_error,
                    b.rotation_error,
                )
            })
            .collect()
    }

    /// `(mean, std, median)` over the tosses of the position and rotation errors, the
    /// prediction's then the frozen pose's (the table `hcm predict` prints).
    fn summary(&self) -> [(f64, f64, f64); 4] {
        let s = summarize(&self.evaluations);
        [
            triple(&s.position),
            triple(&s.rotation),
            triple(&s.baseline_position),
            triple(&s.baseline_rotation),
        ]
    }

    /// Writes each toss's scores as `hcm predict --scores` does.
    fn write_scores(&self, path: PathBuf) -> PyResult<()> {
        write_scores(&path, &self.evaluations, None).map_err(hcm_error)
    }
}

/// Replays the tosses of `data` (their first `first`) with `scenario`'s physics, as
/// `hcm predict` does.
#[pyfunction]
#[pyo3(signature = (scenario, data, first=None, progress=None))]
pub fn predict(
    py: Python<'_>,
    scenario: &Scenario,
    data: &Dataset,
    first: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Prediction> {
    run_stage(py, progress, |progress| {
        let model = scenario.scenario.model()?;
        let setup = TossSetup::new(&model)?;
        let mut tosses = data.dataset.clone();
        if let Some(first) = first {
            anyhow::ensure!(first > 0, "--first 0: give at least one run");
            tosses.runs.truncate(first);
        }
        setup.check_data(&data.name, &model, &tosses)?;
        let total = tosses.runs.len() as u64;
        let done = AtomicU64::new(0);
        progress.begin(Stage::Predict(Fold::First), total);
        let evaluations = evaluate_tosses(&model, &tosses, || {
            progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, total)
        })
        .map_err(|e| {
            anyhow::Error::from(e).context(format!("predicting the tosses of {}", data.name))
        })?;
        progress.end(Stage::Predict(Fold::First));
        Ok(Prediction {
            evaluations,
            body: setup.name.clone(),
        })
    })
}
