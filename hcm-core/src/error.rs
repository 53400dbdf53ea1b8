//! Why a set of law parameters is rejected.

use crate::law::ParameterInfo;
use core::fmt;

/// A law parameter outside its physical domain, reported by each law's `validate`,
/// or a parameter asked for by a name or a count the law does not have.
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
    /// The law (or effect) has no parameter of that name.
    UnknownParameter {
        /// Name of the law or effect (`"hertz"`, `"adhesion"`).
        law: &'static str,
        /// The name asked for, as the caller spelled it.
        parameter: ParameterName,
        /// The parameters it does have.
        expected: &'static [ParameterInfo],
    },
    /// A list of parameter values longer or shorter than the law's parameters.
    ParameterCount {
        /// Name of the law or effect.
        law: &'static str,
        /// Its parameters, one value each, in this order.
        expected: &'static [ParameterInfo],
        /// How many values were given.
        found: usize,
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
            LawError::UnknownParameter {
                law,
                parameter,
                expected,
            } => {
                write!(
                    f,
                    "`{law}` has no parameter `{parameter}`; its parameters are: "
                )?;
                write_names(f, expected)
            }
            LawError::ParameterCount {
                law,
                expected,
                found,
            } => {
                let count = expected.len();
                write!(f, "`{law}` takes {count} parameter values (")?;
                write_names(f, expected)?;
                write!(f, "), found {found}")
            }
        }
    }
}

/// `a, b, c`: the parameters' names.
fn write_names(f: &mut fmt::Formatter<'_>, parameters: &[ParameterInfo]) -> fmt::Result {
    for (i, parameter) in parameters.iter().enumerate() {
        if i > 0 {
            f.write_str(", ")?;
        }
        f.write_str(parameter.name)?;
    }
    Ok(())
}

impl LawError {
    /// `law` has no parameter `name`; it has `expected`.
    pub(crate) fn unknown_parameter(
        law: &'static str,
        name: &str,
        expected: &'static [ParameterInfo],
    ) -> LawError {
        LawError::UnknownParameter {
            law,
            parameter: ParameterName::new(name),
            expected,
        }
    }
}

/// A parameter name as a caller spelled it, kept without an allocator so that
/// [`LawError`] stays `Copy`: the first [`ParameterName::CAPACITY`] bytes, cut at a
/// character boundary (shown with a trailing `…` when cut).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct ParameterName {
    bytes: [u8; ParameterName::CAPACITY],
    len: u8,
    truncated: bool,
}

impl ParameterName {
    /// Most bytes of the name kept.
    pub const CAPACITY: usize = 48;

    /// Keeps `name`, or its longest prefix of at most [`Self::CAPACITY`] bytes
    /// that ends on a character boundary.
    pub fn new(name: &str) -> ParameterName {
        let mut len = name.len().min(Self::CAPACITY);
        // Terminates: 0 is always a boundary.
        while !name.is_char_boundary(len) {
            len -= 1;
        }
        let mut bytes = [0; Self::CAPACITY];
        for (to, from) in bytes.iter_mut().zip(name.as_bytes().iter().take(len)) {
            *to = *from;
        }
        ParameterName {
            bytes,
            len: len as u8,
            truncated: len < name.len(),
        }
    }

    /// The name kept (all of it unless [`Self::is_truncated`]).
    pub fn as_str(&self) -> &str {
        self.bytes
            .get(..usize::from(self.len))
            .and_then(|bytes| core::str::from_utf8(bytes).ok())
            .unwrap_or("")
    }

    /// True if the name was longer than [`Self::CAPACITY`] bytes.
    pub fn is_truncated(&self) -> bool {
        self.truncated
    }
}

impl fmt::Display for ParameterName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())?;
        if self.truncated {
            f.write_str("…")?;
        }
        Ok(())
    }
}

impl fmt::Debug for ParameterName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_str(), f)?;
        if self.truncated {
            f.write_str("…")?;
        }
        Ok(())
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

#[cfg(test)]
mod tests {
    extern crate std;

    use super::{LawError, ParameterName};
    use crate::law::LawKind;
    use std::{format, string::String};

    #[test]
    fn short_names_are_kept_whole() {
        let name = ParameterName::new("stifness");
        assert_eq!((name.as_str(), name.is_truncated()), ("stifness", false));
        assert_eq!(format!("{name}"), "stifness");
    }

    #[test]
    fn long_names_are_cut_at_a_character_boundary() {
        // 47 ASCII bytes then a 2-byte δ: the 48-byte cut would split δ.
        let long: String = "a".repeat(47) + "δδ";
        let name = ParameterName::new(&long);
        assert_eq!(name.as_str(), "a".repeat(47));
        assert!(name.is_truncated());
        assert_eq!(format!("{name}"), "a".repeat(47) + "…");
        assert_eq!(ParameterName::new("").as_str(), "");
    }

    #[test]
    fn messages_name_the_law_the_parameter_and_what_it_has() {
        let hertz = LawKind::Hertz;
        let unknown = LawError::unknown_parameter("hertz", "stifness", hertz.parameters());
        assert_eq!(
            format!("{unknown}"),
            "`hertz` has no parameter `stifness`; its parameters are: stiffness, exponent"
        );
        let count = LawError::ParameterCount {
            law: "hertz",
            expected: hertz.parameters(),
            found: 3,
        };
        assert_eq!(
            format!("{count}"),
            "`hertz` takes 2 parameter values (stiffness, exponent), found 3"
        );
    }
}
