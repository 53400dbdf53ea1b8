//! The normal contact laws by name (hcm-host's `law_catalogue`), evaluated over arrays
//! through the core's contact model, as `hcm force` evaluates one state.

use crate::errors::hcm_error;
use hcm_core::effect::ContactMemory;
use hcm_core::law::{AnyNormalLaw, Indentation};
use hcm_core::model::ContactModel;
use hcm_host::law_catalogue::{build, LAWS};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

/// One law of the catalogue: `(name, source, formula, [(parameter, unit, meaning)])`.
pub type Description = (
    &'static str,
    &'static str,
    &'static str,
    Vec<(&'static str, &'static str, &'static str)>,
);

/// Every normal law of the core, in the core's order (`hcm laws`).
#[pyfunction]
#[pyo3(name = "law_catalogue")]
pub fn catalogue() -> Vec<Description> {
    LAWS.iter()
        .map(|law| {
            let parameters = law
                .parameters
                .iter()
                .map(|p| (p.name, p.unit, p.meaning))
                .collect();
            (law.name, law.source, law.formula, parameters)
        })
        .collect()
}

/// A normal law with its parameters set and checked (hcm-host's `law_catalogue::build`).
#[pyclass(module = "hcm._hcm", frozen)]
pub struct Law {
    law: AnyNormalLaw<f64>,
}

#[pymethods]
impl Law {
    /// Builds law `name` from `(parameter, value)` pairs: every parameter once, in SI
    /// units (`hcm laws` lists them).
    #[new]
    fn new(name: &str, parameters: Vec<(String, f64)>) -> PyResult<Self> {
        let law = build(name, &parameters).map_err(hcm_error)?;
        Ok(Law { law })
    }

    /// The law's name.
    #[getter]
    fn name(&self) -> &'static str {
        self.law.name()
    }

    /// The parameters as `(name, value)` pairs, in field order (SI units).
    #[getter]
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        self.law.named().collect()
    }

    /// Normal force f_n (N) at indentations `depth` δ (m), rates `rate` δ̇ (m/s) and
    /// approach speeds δ̇0 (m/s), element-wise (equal lengths), through the core's
    /// contact model at touch-down, in f64 — or in the controller's f32 with `f32`.
    fn force<'py>(
        &self,
        py: Python<'py>,
        depth: PyReadonlyArray1<'py, f64>,
        rate: PyReadonlyArray1<'py, f64>,
        approach_speed: PyReadonlyArray1<'py, f64>,
        f32: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (depth, rate, approach) = (
            depth.as_slice()?,
            rate.as_slice()?,
            approach_speed.as_slice()?,
        );
        let n = equal_lengths(&[depth.len(), rate.len(), approach.len()])?;
        let model = ContactModel::physics(self.law);
        let model_32 = model.cast::<f32>();
        let forces: Vec<f64> = py.detach(|| {
            (0..n)
                .map(|i| {
                    if f32 {
                        let state = Indentation {
                            depth: depth[i] as f32,
                            rate: rate[i] as f32,
                            approach_speed: approach[i] as f32,
                        };
                        f64::from(
                            model_32.physics_normal_force(&state, &ContactMemory::touch_down()),
                        )
                    } else {
                        let state = Indentation {
                            depth: depth[i],
                            rate: rate[i],
                            approach_speed: approach[i],
                        };
                        model.physics_normal_force(&state, &ContactMemory::touch_down())
                    }
                })
                .collect()
        });
        Ok(PyArray1::from_vec(py, forces))
    }
}

/// The common length of arrays that must be equally long.
pub fn equal_lengths(lengths: &[usize]) -> PyResult<usize> {
    let n = lengths.first().copied().unwrap_or(0);
    if lengths.iter().any(|&l| l != n) {
        return Err(crate::errors::message(format!(
            "the arrays must be equally long after broadcasting; found lengths {lengths:?}"
        )));
    }
    Ok(n)
}
