//! A fit's objective for optimisers outside hcm: `fitness(params[m, p]) -> [m]`, the
//! value `hcm identify --method ga` minimises, for m candidates in one call (in
//! parallel, Python's lock released), so DEAP, nevergrad, Ray or Dask can map it.

use crate::dataset::Dataset;
use crate::errors::{hcm_error, message};
use crate::scenario::Scenario;
use hcm_host::identify::Fitness;
use numpy::{PyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

/// The fitness of contact `contact`'s law `law` on `data`, over its free parameters.
#[pyclass(module = "hcm._hcm", frozen)]
pub struct Objective {
    objective: hcm_host::identify::Objective,
}

#[pymethods]
impl Objective {
    #[new]
    fn new(
        py: Python<'_>,
        scenario: &Scenario,
        data: &Dataset,
        law: &str,
        fitness: &str,
        contact: usize,
    ) -> PyResult<Self> {
        let kind = match fitness {
            "curve" => Fitness::Curve,
            "indicators" => Fitness::Indicators,
            other => {
                return Err(message(format!(
                    "invalid value '{other}' for fitness [possible values: curve, indicators]"
                )))
            }
        };
        let model = scenario.model()?;
        model.check_contact(contact).map_err(message)?;
        let objective = py
            .detach(|| {
                hcm_host::identify::Objective::new(
                    &scenario.scenario,
                    &model,
                    &data.dataset,
                    contact,
                    law,
                    kind,
                )
            })
            .map_err(hcm_error)?;
        Ok(Objective { objective })
    }

    /// The free parameters' names, in a candidate's column order.
    #[getter]
    fn parameters(&self) -> Vec<String> {
        self.objective
            .parameters()
            .into_iter()
            .map(str::to_owned)
            .collect()
    }

    /// Each free parameter's interval `(low, high)` (SI units).
    #[getter]
    fn bounds(&self) -> Vec<(f64, f64)> {
        self.objective.bounds()
    }

    /// The fitness of each row of `candidates` (`[m, p]`, the free parameters' values).
    fn values<'py>(
        &self,
        py: Python<'py>,
        candidates: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let array = candidates.as_array();
        let p = self.objective.parameters().len();
        if array.ncols() != p {
            return Err(message(format!(
                "candidates have {} columns; the law's free parameters are {p}: {}",
                array.ncols(),
                self.objective.parameters().join(", ")
            )));
        }
        let rows: Vec<Vec<f64>> = array.rows().into_iter().map(|r| r.to_vec()).collect();
        let values = py.detach(|| self.objective.values(&rows));
        Ok(PyArray1::from_vec(py, values))
    }
}
