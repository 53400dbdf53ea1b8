//! `hcm._hcm`: the compiled half of the `hcm` Python package. The Python half
//! (`python/hcm/`) turns Python values into the contiguous arrays these functions take
//! and wraps what they return; everything computed here is hcm-host's and hcm-core's
//! own code, so Python and the `hcm` command print the same figures.
//!
//! One file per concept: the laws, scenarios, data sets, the simulator, the hybrid
//! model through the core, and how hcm's errors become Python exceptions.

mod dataset;
mod diagnose;
mod errors;
mod evaluate;
mod experiment;
mod hybrid;
mod identify;
mod laws;
mod objective;
mod power;
mod predict;
mod progress;
mod scenario;
mod simulate;
mod threads;
mod train;

use pyo3::prelude::*;

/// The module `hcm._hcm`.
#[pymodule]
fn _hcm(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("HcmError", m.py().get_type::<errors::HcmError>())?;
    m.add_function(wrap_pyfunction!(laws::catalogue, m)?)?;
    m.add_class::<laws::Law>()?;
    m.add_class::<scenario::Scenario>()?;
    m.add_class::<dataset::Dataset>()?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_class::<hybrid::HybridModel>()?;
    m.add_function(wrap_pyfunction!(experiment::generate, m)?)?;
    m.add_class::<identify::Physics>()?;
    m.add_function(wrap_pyfunction!(identify::identify, m)?)?;
    m.add_class::<train::Residual>()?;
    m.add_function(wrap_pyfunction!(train::train, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::evaluate, m)?)?;
    m.add_class::<objective::Objective>()?;
    m.add_class::<predict::Prediction>()?;
    m.add_function(wrap_pyfunction!(predict::predict, m)?)?;
    m.add_function(wrap_pyfunction!(threads::set_threads, m)?)?;
    m.add_class::<diagnose::Diagnosis>()?;
    m.add_function(wrap_pyfunction!(diagnose::diagnose, m)?)?;
    m.add_class::<power::PowerStudy>()?;
    Ok(())
}
