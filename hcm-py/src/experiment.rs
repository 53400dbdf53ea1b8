//! PM1 (paper Section 4): a scenario's noisy runs and their S1/S2 split, as `hcm
//! generate` makes them, in memory.

use crate::dataset::Dataset;
use crate::errors::option;
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_host::experiment::{check_split, generate as generate_runs, split, Generation};
use hcm_host::input::numbers;
use pyo3::prelude::*;

/// `runs` noisy runs of every condition of `scenario` drawn with `seed` (Eq 18–19),
/// and their split: `(all runs, S1, S2)`, the three files `hcm generate` writes.
#[pyfunction]
#[pyo3(signature = (scenario, runs, seed, progress=None))]
pub fn generate(
    py: Python<'_>,
    scenario: &Scenario,
    runs: i64,
    seed: i128,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Dataset, Dataset, Dataset)> {
    let runs = option("runs", runs, numbers::runs)?;
    let seed = option("seed", seed, numbers::seed)?;
    let scenario = &scenario.scenario;
    let (all, split) = run_stage(py, progress, |progress| {
        // In `hcm generate`'s order: the runs, then the split they allow.
        Generation::new(scenario, runs, seed)?;
        check_split(scenario, runs)?;
        let all = generate_runs(scenario, runs, seed, progress)?;
        let split = split(scenario, all.clone(), seed);
        Ok((all, split))
    })?;
    Ok((
        Dataset::named(all, "<generated>"),
        Dataset::named(split.training, "<S1>"),
        Dataset::named(split.validation, "<S2>"),
    ))
}
