//! Why a set of law parameters is rejected.

use core::fmt;

/// A law parameter outside its physical domain, reported by each law's `validate`.
///
/// Evaluating a law never fails; this error exists so that a controller can refuse
/// bad parameters once, at configuration time, rather than produce odd forces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum LawError {
    /// A parameter must be finite and strictly positive.
    NotPositive {
        /// Name of the parameter, as spelled in the law's fields.
        parameter: &'static str,
    },
    /// A parameter must be finite and not negative.
    Negative {
        /// Name of the parameter, as spelled in the law's fields.
        parameter: &'static str,
    },
    /// A parameter must lie in a closed or half-open range.
    OutOfRange {
        /// Name of the parameter, as spelled in the law's fields.
        parameter: &'static str,
        /// The allowed range, in words (e.g. `"(0, 1]"`).
        allowed: &'static str,
    },
}

impl fmt::Display for LawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LawError::NotPositive { parameter } => {
                write!(f, "`{parameter}` must be a finite number greater than zero")
            }
            LawError::Negative { parameter } => {
                write!(f, "`{parameter}` must be a finite number, zero or greater")
            }
            LawError::OutOfRange { parameter, allowed } => {
                write!(f, "`{parameter}` must lie in {allowed}")
            }
        }
    }
}

impl core::error::Error for LawError {}

/// Checks that `value` is finite and > 0.
pub(crate) fn require_positive<T: crate::Real>(
    value: T,
    parameter: &'static str,
) -> Result<(), LawError> {
    value
        .positive()
        .map(|_| ())
        .ok_or(LawError::NotPositive { parameter })
}

/// Checks that `value` is finite and ≥ 0.
pub(crate) fn require_non_negative<T: crate::Real>(
    value: T,
    parameter: &'static str,
) -> Result<(), LawError> {
    if value >= T::zero() && value <= T::MAX {
        Ok(())
    } else {
        Err(LawError::Negative { parameter })
    }
}
