//! The diagnosis's power study (`hcm power`): a study built once (its strengths scaled),
//! its data sets made and diagnosed by ranges — all of them in one call, or chunks that
//! Ray or Dask map over machines — and rows joined into the table, as the command writes
//! them.

use crate::errors::{hcm_error, message, option};
use crate::progress::run_stage;
use crate::scenario::Scenario;
use hcm_host::diagnose::power::{
    line_effect, read_rows, summary_markdown, write_rows, PowerBase, PowerSettings,
};
use hcm_host::diagnose::{line_candidates, DiagnoseSettings};
use hcm_host::input::numbers;
use pyo3::prelude::*;

/// A power study of one scenario.
#[pyclass(module = "hcm._hcm", frozen)]
pub struct PowerStudy {
    study: hcm_host::diagnose::power::PowerStudy,
}

#[pymethods]
impl PowerStudy {
    /// The study `hcm power` makes with the same options (`effects` empty: every effect
    /// the 1D diagnosis names).
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        scenario: &Scenario,
        runs: i64,
        seeds: i64,
        seed: i128,
        levels: Vec<f64>,
        effects: Vec<String>,
        base: &str,
        contact: i64,
        holdout: f64,
    ) -> PyResult<Self> {
        let runs = option("runs", runs, numbers::runs)?;
        let seeds = option("seeds", seeds, numbers::seeds)?;
        let seed = option("seed", seed, numbers::seed)?;
        let levels = (levels.iter())
            .map(|x| option("levels", x, numbers::number))
            .collect::<PyResult<Vec<f64>>>()?;
        let effects = match effects.is_empty() {
            true => line_candidates().collect(),
            false => (effects.iter())
                .map(|e| option("effects", e, line_effect))
                .collect::<PyResult<Vec<_>>>()?,
        };
        let base = match base {
            "scenario" => PowerBase::Scenario,
            "fitted" => PowerBase::Fitted,
            other => return Err(unknown_base(other)),
        };
        let contact = option("contact", contact, numbers::contact)?;
        let holdout = option("holdout", holdout, numbers::share)?;
        let settings = PowerSettings {
            runs,
            seeds,
            first_seed: seed,
            levels,
            effects,
            base,
            diagnose: DiagnoseSettings {
                contact,
                holdout_fraction: holdout,
                ..DiagnoseSettings::default()
            },
        };
        let study = py
            .detach(|| hcm_host::diagnose::power::PowerStudy::new(&scenario.scenario, settings))
            .map_err(hcm_error)?;
        Ok(PowerStudy { study })
    }

    /// Data sets in the study.
    fn __len__(&self) -> usize {
        self.study.len()
    }

    /// The line that names the study in its files.
    #[getter]
    fn key(&self) -> String {
        self.study.key().to_owned()
    }

    /// Data sets `start` to `stop` (exclusive) made and diagnosed, as the file `hcm power
    /// --shard` writes for them: the study's line, the header, a row per data set.
    #[pyo3(signature = (start, stop, progress=None))]
    fn rows(
        &self,
        py: Python<'_>,
        start: usize,
        stop: usize,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<String> {
        let total = self.study.len();
        if start > stop || stop > total {
            return Err(message(format!(
                "rows {start}..{stop}: the study has data sets 0..{total}"
            )));
        }
        run_stage(py, progress, |progress| {
            let rows = self.study.rows(start..stop, progress)?;
            let mut text = Vec::new();
            write_rows(&mut text, self.study.key(), &rows)?;
            Ok(String::from_utf8(text)?)
        })
    }

    /// The rows of `parts` (texts of [`Self::rows`] or `hcm power --shard` files, in
    /// order, covering every data set once) as one file, and the study's table:
    /// `(rows, table)`, the bytes `hcm power` writes to OUT and OUT.md.
    fn join(&self, parts: Vec<String>) -> PyResult<(String, String)> {
        let read = (parts.iter().enumerate())
            .map(|(k, part)| {
                let name = format!("part {k}");
                let rows = read_rows(&name, part.as_bytes(), self.study.key())?;
                Ok((name, rows))
            })
            .collect::<Result<Vec<_>, hcm_host::diagnose::power::PowerError>>()
            .map_err(hcm_error)?;
        let rows = self.study.join(read).map_err(hcm_error)?;
        let mut text = Vec::new();
        write_rows(&mut text, self.study.key(), &rows).map_err(hcm_error)?;
        let text = String::from_utf8(text).map_err(hcm_error)?;
        Ok((text, summary_markdown(&self.study, &rows)))
    }
}

/// `--base`'s refusal of `value`, in clap's words.
fn unknown_base(value: &str) -> PyErr {
    message(format!(
        "invalid value '{value}' for '--base <BASE>'\n  [possible values: scenario, fitted]"
    ))
}
