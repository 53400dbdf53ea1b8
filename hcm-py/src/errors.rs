//! hcm's errors as Python exceptions: one class, `hcm.HcmError`, whose message is the
//! text the `hcm` command prints after `error: ` for the same mistake (the error and
//! its causes, `{:#}`).

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::{PyErr, PyResult};

create_exception!(
    hcm,
    HcmError,
    PyException,
    "An input hcm refuses or a stage that failed; the message is the `hcm` command's."
);

/// `error` as an [`HcmError`] with the CLI's message.
pub fn hcm_error(error: impl Into<anyhow::Error>) -> PyErr {
    // The CLI's line ends the message; a TOML parser's excerpt ends in a newline.
    HcmError::new_err(format!("{:#}", error.into()).trim_end().to_owned())
}

/// A plain message as an [`HcmError`].
pub fn message(text: impl Into<String>) -> PyErr {
    HcmError::new_err(text.into())
}

/// A numeric option checked by the command's own parser (hcm-host's `input::numbers`),
/// refused with the command's words: `invalid value 'V' for '--NAME <NAME>': why`.
pub fn option<T>(
    name: &str,
    value: impl std::fmt::Display,
    parse: fn(&str) -> Result<T, String>,
) -> PyResult<T> {
    let placeholder = name.to_uppercase().replace('-', "_");
    option_as(name, &placeholder, value, parse)
}

/// [`option`] for an option whose value the CLI names `placeholder` (`--threads <N>`).
pub fn option_as<T>(
    name: &str,
    placeholder: &str,
    value: impl std::fmt::Display,
    parse: fn(&str) -> Result<T, String>,
) -> PyResult<T> {
    let text = value.to_string();
    parse(&text).map_err(|reason| {
        message(format!(
            "invalid value '{text}' for '--{name} <{placeholder}>': {reason}"
        ))
    })
}
