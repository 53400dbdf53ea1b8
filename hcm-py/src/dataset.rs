//! Measured data (hcm-host's `Dataset`, the measured-data CSV format) to and from
//! arrays: `run` and `body` as text, the 20 numeric columns (`time`, `px` … `tz`, SI
//! units) as one row-major `[rows, 20]` array, one row per sample per body, in the
//! file's order.

use crate::errors::{hcm_error, message};
use hcm_host::dataset::{csv_header, sample_values};
use numpy::{PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Numeric columns of the format: every column after `run` and `body`.
const NUMERIC: usize = 20;

/// The columns as [`Dataset::arrays`] returns them: run ids, body names, the numeric
/// columns `[rows, 20]`.
type Columns<'py> = (Vec<String>, Vec<String>, Bound<'py, PyArray2<f64>>);

/// A measured-data set: runs of bodies' sampled motion and contact loads.
#[pyclass(module = "hcm._hcm", frozen, skip_from_py_object)]
#[derive(Clone)]
pub struct Dataset {
    pub dataset: hcm_host::dataset::Dataset,
    /// What the data are called in messages and fit records: the file's path as given,
    /// or `<arrays>`, `<simulated>`, `<S1>`, ….
    pub name: String,
}

impl Dataset {
    /// `dataset`, called `name`.
    pub fn named(dataset: hcm_host::dataset::Dataset, name: &str) -> Self {
        Dataset {
            dataset,
            name: name.to_owned(),
        }
    }
}

#[pymethods]
impl Dataset {
    /// Reads a measured-data CSV file (the `hcm` commands' `--data`).
    #[staticmethod]
    fn read_csv(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let dataset = py
            .detach(|| hcm_host::dataset::Dataset::read(&path))
            .map_err(hcm_error)?;
        Ok(Dataset::named(dataset, &path.display().to_string()))
    }

    /// Reads measured-data CSV text; `name` names it in messages.
    #[staticmethod]
    fn from_csv_text(py: Python<'_>, text: &str, name: &str) -> PyResult<Self> {
        let dataset = py
            .detach(|| hcm_host::dataset::Dataset::from_reader(name, text.as_bytes()))
            .map_err(hcm_error)?;
        Ok(Dataset::named(dataset, name))
    }

    /// A data set from its columns: `run` and `body` (text, one per row) and the
    /// numeric columns as `[rows, 20]` (NaN for a channel not sampled). Checked as a
    /// CSV file is: errors name `<arrays>` and line r + 2 for row r (line 1 being the
    /// header).
    #[staticmethod]
    fn from_arrays(
        py: Python<'_>,
        run: Vec<String>,
        body: Vec<String>,
        numeric: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Self> {
        let values = numeric.as_array().to_owned();
        let shape = values.shape().to_vec();
        if shape[1] != NUMERIC || shape[0] != run.len() || shape[0] != body.len() {
            return Err(message(format!(
                "from_arrays: {} run ids, {} body names and numeric columns of shape {:?}; \
                 expected one run id and one body name per row and {NUMERIC} numeric columns \
                 ({})",
                run.len(),
                body.len(),
                shape,
                column_names()[2..].join(", ")
            )));
        }
        let text = py.detach(|| {
            let mut text = csv_header();
            text.push('\n');
            for (r, row) in values.rows().into_iter().enumerate() {
                text.push_str(&quoted(&run[r]));
                text.push(',');
                text.push_str(&quoted(&body[r]));
                for value in row {
                    text.push(',');
                    // Rust prints the shortest text that reads back to the same f64.
                    if !value.is_nan() {
                        let _ = write!(text, "{value}");
                    }
                }
                text.push('\n');
            }
            text
        });
        let dataset = py
            .detach(|| hcm_host::dataset::Dataset::from_reader("<arrays>", text.as_bytes()))
            .map_err(hcm_error)?;
        Ok(Dataset::named(dataset, "<arrays>"))
    }

    /// Writes the data set as a measured-data CSV file, atomically.
    fn write_csv(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| self.dataset.write(&path)).map_err(hcm_error)
    }

    /// The CSV text of the data set (what `write_csv` writes).
    fn to_csv_text(&self, py: Python<'_>) -> PyResult<String> {
        let mut bytes = Vec::new();
        py.detach(|| self.dataset.to_writer(&mut bytes))
            .map_err(hcm_error)?;
        String::from_utf8(bytes).map_err(|e| message(e.to_string()))
    }

    /// The columns: `(run ids, body names, numeric [rows, 20])`, one row per sample
    /// per body, runs and bodies in the file's order.
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Columns<'py>> {
        let (mut runs, mut bodies, mut rows) = (Vec::new(), Vec::new(), Vec::new());
        for run in &self.dataset.runs {
            for track in &run.bodies {
                for sample in &track.samples {
                    runs.push(run.id.clone());
                    bodies.push(track.body.clone());
                    rows.push(sample_values(sample).to_vec());
                }
            }
        }
        let numeric = PyArray2::from_vec2(py, &rows).map_err(|e| message(e.to_string()))?;
        Ok((runs, bodies, numeric))
    }

    /// What the data are called in messages: the file's path, or `<arrays>`, ….
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// The run ids, in the file's order.
    #[getter]
    fn runs(&self) -> Vec<String> {
        self.dataset.runs.iter().map(|r| r.id.clone()).collect()
    }

    /// The column names of the format, in order (`run`, `body`, `time`, `px` … `tz`).
    #[staticmethod]
    fn columns() -> Vec<String> {
        column_names()
    }
}

/// The format's column names.
fn column_names() -> Vec<String> {
    csv_header().split(',').map(str::to_owned).collect()
}

/// A text cell as CSV writes it: quoted when it holds a comma, quote or line break.
fn quoted(cell: &str) -> String {
    if cell.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", cell.replace('"', "\"\""))
    } else {
        cell.to_owned()
    }
}
