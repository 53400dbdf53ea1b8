//! What the physics gets wrong, and why (`hcm diagnose` on 1D force data): the answer,
//! the named causes with their intervals, the gain held out, the extended model and
//! the report — written to a directory as the command writes it, when one is given.

use crate::dataset::Dataset;
use crate::errors::{message, option};
use crate::identify::Physics;
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_host::dataset::{DataUse, Evidence};
use hcm_host::diagnose::{
    diagnose as diagnose_data, diagnosis_json, diagnosis_markdown, extended_physics,
    write_diagnosis, BaseFreedom, DiagnoseSettings, DiagnosisOf,
};
use hcm_host::input::numbers;
use hcm_host::output::StagedDirectory;
use pyo3::prelude::*;
use std::path::PathBuf;

/// A finished diagnosis: diagnosis.json's contents (JSON text), the report (Markdown)
/// and the extended model.
#[pyclass(module = "hcm._hcm", frozen)]
pub struct Diagnosis {
    #[pyo3(get)]
    json: String,
    #[pyo3(get)]
    report: String,
    extended: hcm_host::identify::Physics,
}

#[pymethods]
impl Diagnosis {
    /// The extended model as a physics file (extended.toml).
    fn extended(&self) -> Physics {
        Physics::made(self.extended.clone(), Vec::new())
    }
}

/// The diagnosis's options, as `hcm diagnose` takes them.
pub struct DiagnoseOptions {
    pub contact: usize,
    pub seed: u64,
    pub holdout: f64,
    pub chance: bool,
    pub first: Option<usize>,
    pub out: Option<PathBuf>,
}

/// Diagnoses contact `contact` of `scenario` under `physics` (the base model) on
/// `data`, as `hcm diagnose --physics` on 1D force data.
#[pyfunction]
#[pyo3(signature = (scenario, physics, data, contact, seed, holdout, chance, first=None, out=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn diagnose(
    py: Python<'_>,
    scenario: &Scenario,
    physics: &Physics,
    data: &Dataset,
    contact: i64,
    seed: i128,
    holdout: f64,
    chance: bool,
    first: Option<usize>,
    out: Option<PathBuf>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Diagnosis> {
    let contact = option("contact", contact, numbers::contact)?;
    let seed = option("seed", seed, numbers::seed)?;
    let holdout = option("holdout", holdout, numbers::share)?;
    if let Some(out) = &out {
        hcm_host::output::check_kind("--out", out, true).map_err(message)?;
    }
    let options = DiagnoseOptions {
        contact,
        seed,
        holdout,
        chance,
        first,
        out,
    };
    let scenario_name = scenario.scenario.name.clone();
    let base = physics.apply(&scenario.scenario)?;
    let fitted = physics.physics.fitted();
    run_stage(py, progress, |_| {
        let base = base.model()?;
        let c = options.contact;
        base.check_contact(c).map_err(anyhow::Error::msg)?;
        let mut runs = data.dataset.clone();
        if let Some(first) = options.first {
            anyhow::ensure!(first > 0, "--first 0: give at least one run");
            runs.runs.truncate(first);
        }
        let evidence = Evidence::of(&base, &runs, c);
        anyhow::ensure!(
            evidence == Evidence::LineForce,
            "{}: from Python, diagnose reads a 1D contact's force samples; this scenario and \
             data need `hcm diagnose`",
            data.name
        );
        runs.require_for(&data.name, &base, c, evidence, DataUse::Diagnose)?;
        let staged = match &options.out {
            Some(out) => Some(StagedDirectory::create(out, "diagnosis.json")?),
            None => None,
        };
        let settings = DiagnoseSettings {
            contact: c,
            seed: options.seed,
            holdout_fraction: options.holdout,
            base_freedom: if fitted {
                BaseFreedom::Fitted
            } else {
                BaseFreedom::Given
            },
            chance: options.chance,
            ..DiagnoseSettings::default()
        };
        let diagnosis = diagnose_data(&base, &runs, &settings)?;
        let of = DiagnosisOf {
            base: &base,
            contact: c,
            data: &data.name,
            scenario: &scenario_name,
        };
        let report = match staged {
            Some(staged) => {
                let report = write_diagnosis(staged.path(), &of, &diagnosis)?;
                staged.commit()?;
                report
            }
            None => diagnosis_markdown(&diagnosis, &[]),
        };
        Ok(Diagnosis {
            json: serde_json::to_string_pretty(&diagnosis_json(&diagnosis))?,
            report,
            extended: extended_physics(&base, c, &data.name, &diagnosis),
        })
    })
}
