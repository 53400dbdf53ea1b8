//! PM2: a law fitted to force data (`hcm identify` on 1D data), and the physics file it
//! makes — the law's values, standard errors, the fit's record, the file's text.

use crate::dataset::Dataset;
use crate::errors::{hcm_error, message, option};
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_host::dataset::{DataUse, Evidence};
use hcm_host::identify::{identify as fit, Fitness, Method};
use hcm_host::input::numbers;
use hcm_host::numerics::optimize::GeneticSettings;
use pyo3::prelude::*;
use std::path::PathBuf;

/// What a physics file's errors call one that was made in Python.
const MADE_HERE: &str = "<identified>";

/// A physics file: each contact's law and parameters (SI), effects, scatter, and how the
/// fit went.
#[pyclass(module = "hcm._hcm", frozen)]
pub struct Physics {
    pub physics: hcm_host::identify::Physics,
    /// The file it was read from, or `<identified>`: what its errors name.
    pub path: PathBuf,
    /// One-σ standard errors of the fitted parameters (least squares), by name.
    standard_errors: Vec<(String, f64)>,
}

#[pymethods]
impl Physics {
    /// Reads a physics file (`hcm identify`'s `--out`, `hcm diagnose`'s extended.toml).
    #[staticmethod]
    fn read(path: PathBuf) -> PyResult<Self> {
        let physics = hcm_host::identify::Physics::read(&path).map_err(hcm_error)?;
        Ok(Physics {
            physics,
            path,
            standard_errors: Vec::new(),
        })
    }

    /// The file's contents as JSON (contacts, bodies, sets, fit).
    fn to_json(&self) -> PyResult<String> {
        serde_json_text(&self.physics)
    }

    /// The file's text: `# comment` then the TOML `write` writes.
    fn to_toml(&self, comment: &str) -> PyResult<String> {
        let text = toml_text(&self.physics)?;
        Ok(format!("# {comment}\n{text}"))
    }

    /// Writes the file (atomically) with `comment` on its first line.
    fn write(&self, path: PathBuf, comment: &str) -> PyResult<()> {
        self.physics.write(&path, comment).map_err(hcm_error)
    }

    /// One-σ standard errors of the fitted parameters (least squares; empty otherwise).
    #[getter]
    fn standard_errors(&self) -> Vec<(String, f64)> {
        self.standard_errors.clone()
    }
}

impl Physics {
    /// A physics file made here (not read from a file), with its standard errors.
    pub fn made(physics: hcm_host::identify::Physics, standard_errors: Vec<(String, f64)>) -> Self {
        Physics {
            physics,
            path: PathBuf::from(MADE_HERE),
            standard_errors,
        }
    }

    /// `scenario` with this file's laws.
    pub fn apply(
        &self,
        scenario: &hcm_host::scenario::Scenario,
    ) -> PyResult<hcm_host::scenario::Scenario> {
        self.physics.apply(scenario, &self.path).map_err(hcm_error)
    }
}

fn serde_json_text(physics: &hcm_host::identify::Physics) -> PyResult<String> {
    serde_json::to_string(physics).map_err(|e| message(e.to_string()))
}

/// The TOML `Physics::write` writes below its comment line.
fn toml_text(physics: &hcm_host::identify::Physics) -> PyResult<String> {
    toml::to_string(physics).map_err(|e| message(e.to_string()))
}

/// The fitting options of `hcm identify`, as they arrive from Python.
#[derive(Clone)]
pub struct FitOptions {
    pub law: Option<String>,
    pub method: String,
    pub fitness: String,
    pub seed: u64,
    pub population: usize,
    pub generations: usize,
    pub contact: usize,
}

/// Fits a law to contact `contact`'s force samples in `data` (1D data: `hcm identify`'s
/// force path), least squares or the genetic algorithm.
#[pyfunction]
#[pyo3(signature = (scenario, data, law, method, fitness, seed, population, generations, contact, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn identify(
    py: Python<'_>,
    scenario: &Scenario,
    data: &Dataset,
    law: Option<String>,
    method: String,
    fitness: String,
    seed: i128,
    population: i64,
    generations: i64,
    contact: i64,
    progress: Option<Py<PyAny>>,
) -> PyResult<Physics> {
    let seed = option("seed", seed, numbers::seed)?;
    let population = option("population", population, numbers::population)?;
    let generations = option("generations", generations, numbers::generations)?;
    let contact = option("contact", contact, numbers::contact)?;
    let options = FitOptions {
        law,
        method,
        fitness,
        seed,
        population,
        generations,
        contact,
    };
    let scenario = &scenario.scenario;
    let (physics, standard_errors) = run_stage(py, progress, |progress| {
        fit_force(scenario, data, &options, progress)
    })?;
    Ok(Physics::made(physics, standard_errors))
}

/// `hcm identify`'s checks and fit on 1D force data, in its order.
fn fit_force(
    scenario: &hcm_host::scenario::Scenario,
    data: &Dataset,
    options: &FitOptions,
    progress: &dyn hcm_host::progress::Progress,
) -> anyhow::Result<(hcm_host::identify::Physics, Vec<(String, f64)>)> {
    let model = scenario.model()?;
    let c = options.contact;
    model.check_contact(c).map_err(anyhow::Error::msg)?;
    let evidence = Evidence::of(&model, &data.dataset, c);
    anyhow::ensure!(
        evidence == Evidence::LineForce,
        "{}: from Python, identify fits a 1D contact's force samples; scenario `{}` is 3D \
         or the data hold poses — run `hcm identify` on the file",
        data.name,
        scenario.name
    );
    let method = match options.method.as_str() {
        "lsq" | "ga" => options.method.as_str(),
        other => anyhow::bail!(
            "invalid value '{other}' for method: a 1D contact is fitted by `lsq` or `ga`"
        ),
    };
    let law = options.law.clone().ok_or_else(|| {
        anyhow::anyhow!(
            "{}: name the law to fit with --law (see `hcm laws`), e.g. --law hertz; only a \
             fit from poses defaults to the scenario's own law",
            data.name
        )
    })?;
    let what = if method == "ga" {
        DataUse::IdentifyEvents
    } else {
        DataUse::Identify
    };
    data.dataset
        .require_for(&data.name, &model, c, evidence, what)?;
    let settings = GeneticSettings {
        seed: options.seed,
        population: options.population,
        generations: options.generations,
        ..GeneticSettings::default()
    };
    let method = match (method, options.fitness.as_str()) {
        ("lsq", _) => Method::Lsq,
        (_, "indicators") => Method::Ga(Fitness::Indicators, settings),
        (_, "curve") => Method::Ga(Fitness::Curve, settings),
        (_, other) => anyhow::bail!(
            "invalid value '{other}' for fitness: the genetic algorithm's fitness is `curve` or \
             `indicators`"
        ),
    };
    let result = fit(scenario, &model, &data.dataset, c, &law, method, progress)?;
    let mut record = result.fit.clone();
    record.data = data.name.clone();
    let physics = hcm_host::identify::Physics::for_contact(&model, c, &result.law, record);
    Ok((physics, result.standard_errors))
}
