//! The residual network (paper Section 3.2): trained on the force PM2 gets wrong
//! (`hcm train` on 1D force data), and exported as the blobs a controller embeds
//! (`hcm export`).

use crate::dataset::Dataset;
use crate::errors::{hcm_error, message, option};
use crate::identify::Physics;
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_core::residual::Quantisation;
use hcm_host::dataset::{DataUse, Evidence};
use hcm_host::input::numbers;
use hcm_host::train::{ResidualKind, ResidualSettings, Trained};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;

/// A trained residual: the f32 network and its int8 twin, with how training went.
#[pyclass(module = "hcm._hcm", frozen)]
pub struct Residual {
    trained: Trained,
}

#[pymethods]
impl Residual {
    /// The blob `hcm export` writes: `"f32"` or `"int8"` weights.
    fn blob<'py>(&self, py: Python<'py>, weights: &str) -> PyResult<Bound<'py, PyBytes>> {
        let quantisation = match weights {
            "f32" => Quantisation::F32,
            "int8" => Quantisation::Int8,
            other => {
                return Err(message(format!(
                    "invalid value '{other}' for weights [possible values: f32, int8]"
                )))
            }
        };
        let blob =
            hcm_host::export::blob(&self.trained.residual, quantisation).map_err(hcm_error)?;
        Ok(PyBytes::new(py, &blob.bytes))
    }

    /// The file `hcm train` writes (`residual.json`), as text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.trained.residual).map_err(|e| message(e.to_string()))
    }

    /// Writes `residual.json` (atomically).
    fn write(&self, path: PathBuf) -> PyResult<()> {
        self.trained.residual.write(&path).map_err(hcm_error)
    }

    /// How training went: rows, epochs, best epoch, train and validation RMS (N),
    /// seconds; the int8 twin's RMS against the f32 network rounded and tuned (N).
    fn report(&self) -> Vec<(&'static str, f64)> {
        let (r, q) = (&self.trained.report, &self.trained.int8);
        vec![
            ("rows", self.trained.rows as f64),
            ("epochs", r.epochs as f64),
            ("best_epoch", r.best_epoch as f64),
            ("train_rms", r.train_loss.sqrt()),
            ("validation_rms", r.validation_loss.sqrt()),
            ("seconds", r.seconds),
            ("int8_rounded_rms", q.rounded_rms),
            ("int8_tuned_rms", q.tuned_rms),
            ("int8_tuned_max", q.tuned_max),
            ("int8_epochs", q.epochs as f64),
        ]
    }
}

/// Trains the residual of contact `contact` of `scenario` under `physics` (PM2) on
/// `data` (S1), as `hcm train` does on force data.
#[pyfunction]
#[pyo3(signature = (scenario, physics, data, contact, epochs, int8_epochs, seed, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn train(
    py: Python<'_>,
    scenario: &Scenario,
    physics: &Physics,
    data: &Dataset,
    contact: i64,
    epochs: i64,
    int8_epochs: i64,
    seed: i128,
    progress: Option<Py<PyAny>>,
) -> PyResult<Residual> {
    let contact = option("contact", contact, numbers::contact)?;
    let epochs = option("epochs", epochs, numbers::epochs)?;
    let int8_epochs = option("int8-epochs", int8_epochs, numbers::fine_tuning_epochs)?;
    let seed = option("seed", seed, numbers::seed)?;
    let pm2 = physics.apply(&scenario.scenario)?;
    let trained = run_stage(py, progress, |progress| {
        let pm2 = pm2.model()?;
        pm2.check_contact(contact).map_err(anyhow::Error::msg)?;
        let evidence = Evidence::of(&pm2, &data.dataset, contact);
        data.dataset
            .require_for(&data.name, &pm2, contact, evidence, DataUse::Train)?;
        let kind = ResidualKind::of(evidence, false, !pm2.joints.is_empty());
        anyhow::ensure!(
            kind == ResidualKind::Force,
            "{}: from Python, train learns a 1D contact's force residual; this scenario and \
             data need `hcm train`",
            data.name
        );
        let settings = ResidualSettings {
            epochs,
            int8_epochs,
            seed,
        };
        Ok(kind.train(
            (&pm2, &data.dataset, contact),
            usize::MAX,
            &settings,
            progress,
        )?)
    })?;
    Ok(Residual { trained })
}
