//! Scenario files (hcm-host's `Scenario`): read from a path or a TOML string, with
//! `key=value` overrides and a physics file applied, as the CLI's `--scenario`,
//! `--set` and `--physics` do.

use crate::errors::hcm_error;
use hcm_host::identify::Physics;
use pyo3::prelude::*;
use std::path::PathBuf;

/// A scenario: bodies, materials, contact laws and solver settings.
#[pyclass(module = "hcm._hcm", frozen, skip_from_py_object)]
#[derive(Clone)]
pub struct Scenario {
    pub scenario: hcm_host::scenario::Scenario,
}

#[pymethods]
impl Scenario {
    /// Reads the scenario file at `path` with `key=value` overrides (TOML values, as
    /// `hcm … --set`).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf, overrides: Vec<String>) -> PyResult<Self> {
        let scenario = py
            .detach(|| hcm_host::scenario::Scenario::load(&path, &overrides))
            .map_err(hcm_error)?;
        Ok(Scenario { scenario })
    }

    /// Parses scenario text; `name` stands for its path in messages (and relative paths
    /// in it, such as a mesh, resolve against its folder).
    #[staticmethod]
    fn from_toml(text: &str, name: PathBuf, overrides: Vec<String>) -> PyResult<Self> {
        let scenario =
            hcm_host::scenario::Scenario::parse(&name, text, &overrides).map_err(hcm_error)?;
        Ok(Scenario { scenario })
    }

    /// This scenario with more `key=value` overrides applied.
    fn with_set(&self, overrides: Vec<String>) -> PyResult<Self> {
        let scenario = self.scenario.with(&overrides).map_err(hcm_error)?;
        Ok(Scenario { scenario })
    }

    /// This scenario with the physics file at `path` (from `hcm identify`) in place of
    /// its contact laws, as `--physics`.
    fn with_physics(&self, path: PathBuf) -> PyResult<Self> {
        let physics = Physics::read(&path).map_err(hcm_error)?;
        let scenario = physics.apply(&self.scenario, &path).map_err(hcm_error)?;
        Ok(Scenario { scenario })
    }

    /// This scenario with a physics file made in Python (`identify`, a diagnosis's
    /// extended model) in place of its contact laws.
    fn with_physics_object(&self, physics: &crate::identify::Physics) -> PyResult<Self> {
        let scenario = physics.apply(&self.scenario)?;
        Ok(Scenario { scenario })
    }

    /// The scenario as TOML text, every override applied (`from_toml` of it with `path`
    /// gives it back).
    fn to_toml(&self) -> String {
        self.scenario.to_toml()
    }

    /// The scenario file's path (or the name its text was given).
    #[getter]
    fn path(&self) -> PathBuf {
        self.scenario.path().to_owned()
    }

    /// The scenario's name.
    #[getter]
    fn name(&self) -> String {
        self.scenario.name.clone()
    }

    /// The bodies' names, in file order (resolving the scenario checks it).
    #[getter]
    fn bodies(&self) -> PyResult<Vec<String>> {
        let model = self.model()?;
        Ok(model.bodies.into_iter().map(|b| b.name).collect())
    }

    /// The contacts as `(body 1, body 2, law name)`, in file order.
    #[getter]
    fn contacts(&self) -> PyResult<Vec<(String, String, &'static str)>> {
        let model = self.model()?;
        Ok(model
            .contacts
            .iter()
            .map(|c| {
                (
                    model.bodies[c.body_1].name.clone(),
                    model.bodies[c.body_2].name.clone(),
                    c.law().name(),
                )
            })
            .collect())
    }
}

impl Scenario {
    /// The resolved model the simulator runs.
    pub fn model(&self) -> PyResult<hcm_host::scenario::Model> {
        self.scenario.model().map_err(hcm_error)
    }
}
