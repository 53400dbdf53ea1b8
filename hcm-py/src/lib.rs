//! `hcm._hcm`: the compiled half of the `hcm` Python package. The Python half
//! (`python/hcm/`) turns Python values into the contiguous arrays these functions take
//! and wraps what they return; everything computed here is hcm-host's and hcm-core's
//! own code, so Python and the `hcm` command print the same figures.
//!
//! One file per concept: the laws, scenarios, data sets, the simulator, the hybrid
//! model through the core, and how hcm's errors become Python exceptions.

mod dataset;
mod errors;
mod hybrid;
mod laws;
mod scenario;
mod simulate;

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
    Ok(())
}
