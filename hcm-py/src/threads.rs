//! How many threads hcm's parallel work uses in this process (the CLI's `--threads`,
//! `HCM_THREADS`): rayon's global pool, fixed at its first use.

use crate::errors::{message, option_as};
use hcm_host::input::numbers;
use pyo3::prelude::*;

/// Sets the worker threads of hcm's parallel work to `threads`; only before the first
/// parallel call of the process (the pool is built once). The results are the same
/// bits on any count.
#[pyfunction]
pub fn set_threads(threads: i64) -> PyResult<()> {
    let threads = option_as("threads", "N", threads, numbers::threads)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global()
        .map_err(|e| {
            message(format!(
                "threads {threads}: {e} (set it before any parallel work, or with \
                 HCM_THREADS before the process starts)"
            ))
        })
}
