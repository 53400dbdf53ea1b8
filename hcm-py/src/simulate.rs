//! The simulator (hcm-host's `simulate`), as `hcm simulate` runs it: one run of a
//! scenario, its trajectory as a data set, Python's lock released meanwhile.

use crate::dataset::Dataset;
use crate::errors::hcm_error;
use crate::scenario::Scenario;
use pyo3::prelude::*;

/// Simulates `scenario` once: the trajectory (run `0`), the contact force on each body
/// at every sample, as `hcm simulate --out` writes it.
#[pyfunction]
pub fn simulate(py: Python<'_>, scenario: &Scenario) -> PyResult<Dataset> {
    let model = scenario.model()?;
    let simulation = py
        .detach(|| hcm_host::simulate::simulate(&model))
        .map_err(hcm_error)?;
    let dataset = hcm_host::dataset::Dataset {
        runs: vec![simulation.run],
    };
    Ok(Dataset::named(dataset, "<simulated>"))
}
