//! The paper's table (`hcm evaluate` on 1D force data): PM2, and the HCM when a blob is
//! given, against held-out runs by the four indicators and their Eq 20 errors.

use crate::dataset::Dataset;
use crate::errors::hcm_error;
use crate::identify::Physics;
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_host::dataset::{complete, DataUse, Evidence};
use hcm_host::evaluate::evaluate as tables;
use hcm_host::residual::ContactResidual;
use pyo3::prelude::*;

/// The tables of `hcm evaluate --json`, one per condition, as JSON text.
#[pyfunction]
#[pyo3(signature = (scenario, physics, data, residual=None, contact=0, progress=None))]
pub fn evaluate(
    py: Python<'_>,
    scenario: &Scenario,
    physics: &Physics,
    data: &Dataset,
    residual: Option<Vec<u8>>,
    contact: usize,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let pm2 = physics
        .apply(&scenario.scenario)?
        .model()
        .map_err(hcm_error)?;
    let json = run_stage(py, progress, |_| {
        pm2.check_contact(contact).map_err(anyhow::Error::msg)?;
        let evidence = Evidence::of(&pm2, &data.dataset, contact);
        data.dataset
            .require_for(&data.name, &pm2, contact, evidence, DataUse::Evaluate)?;
        anyhow::ensure!(
            evidence == Evidence::LineForce,
            "{}: from Python, evaluate judges a 1D contact on force data; this scenario and \
             data need `hcm evaluate`",
            data.name
        );
        let completed = complete(&pm2, &data.dataset)?;
        let mut models = vec![("PM2", pm2.clone())];
        if let Some(bytes) = &residual {
            let decoded =
                ContactResidual::decode(bytes).map_err(|e| anyhow::anyhow!("<blob>: {e}"))?;
            let hcm = pm2
                .with_residual(contact, decoded, "<blob>")
                .map_err(anyhow::Error::msg)?;
            models.push(("HCM", hcm));
        }
        let columns: Vec<(&str, &hcm_host::scenario::Model)> =
            models.iter().map(|(l, m)| (*l, m)).collect();
        let tables = tables(&columns, completed.data.as_ref(), contact)?;
        Ok(serde_json::to_string_pretty(&tables)?)
    })?;
    Ok(json)
}
