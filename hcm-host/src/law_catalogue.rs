//! The normal laws by name, for users: the core's one list of laws ([`LawKind`]),
//! looked up by a name a person typed, and a law built from `key = value` pairs with
//! errors that name the law, the parameter and the parameters it has.
//!
//! Nothing here serialises a law: the parameters are read and written through the
//! core's typed access ([`AnyNormalLaw::get`], [`AnyNormalLaw::map_named`], …).

use hcm_core::law::{AnyNormalLaw, LawKind, NormalLaw, ParameterInfo, MAX_PARAMETERS};
use hcm_core::LawError;

/// One parameter of a law: its field name, unit and meaning.
pub type Parameter = ParameterInfo;

/// One normal law as described to users (the core's description of a [`LawKind`]).
#[derive(Clone, Copy, Debug)]
pub struct LawEntry {
    /// Which law.
    pub(crate) kind: LawKind,
    /// Name used in files and on the command line.
    pub name: &'static str,
    /// Where the formula comes from.
    pub source: &'static str,
    /// The formula, f_n for δ > 0.
    pub formula: &'static str,
    /// Its parameters, in field order.
    pub parameters: &'static [Parameter],
}

const fn describe(kind: LawKind) -> LawEntry {
    LawEntry {
        kind,
        name: kind.name(),
        source: kind.source(),
        formula: kind.formula(),
        parameters: kind.parameters(),
    }
}

/// Every normal law of the core, in the core's order ([`LawKind::ALL`]).
pub const LAWS: &[LawEntry] = &{
    let mut laws = [describe(LawKind::Hertz); LawKind::ALL.len()];
    let mut i = 0;
    while i < laws.len() {
        laws[i] = describe(LawKind::ALL[i]);
        i += 1;
    }
    laws
};

/// Why a law could not be built from user input.
#[derive(Debug, thiserror::Error)]
pub enum LawInputError {
    /// No law has that name.
    #[error("unknown law `{0}`; the laws are: {1}")]
    UnknownLaw(String, String),
    /// A parameter the law does not have.
    #[error("law `{law}`: no parameter `{parameter}`; its parameters are: {expected}")]
    UnknownParameter {
        /// The law's name.
        law: String,
        /// The parameter given.
        parameter: String,
        /// The law's parameters, comma-separated.
        expected: String,
    },
    /// A parameter of the law that was not given.
    #[error("law `{law}`: missing parameter `{parameter}`; its parameters are: {expected}")]
    MissingParameter {
        /// The law's name.
        law: String,
        /// The parameter not given.
        parameter: String,
        /// The law's parameters, comma-separated.
        expected: String,
    },
    /// A parameter given as something other than a number.
    #[error("law `{law}`: `{parameter}` must be a number, found {found}; its parameters are: {expected}")]
    NotANumber {
        /// The law's name.
        law: String,
        /// The parameter.
        parameter: String,
        /// What was given instead, with its type (`string "stiff"`).
        found: String,
        /// The law's parameters, comma-separated.
        expected: String,
    },
    /// The parameters parse but are outside their physical domain.
    #[error("law `{0}`: {1}")]
    Domain(String, LawError),
}

/// Looks a law up by name.
pub fn entry(name: &str) -> Result<&'static LawEntry, LawInputError> {
    LAWS.iter().find(|law| law.name == name).ok_or_else(|| {
        let names: Vec<_> = LAWS.iter().map(|law| law.name).collect();
        LawInputError::UnknownLaw(name.to_owned(), names.join(", "))
    })
}

/// The law called `name`.
pub fn kind(name: &str) -> Result<LawKind, LawInputError> {
    entry(name).map(|law| law.kind)
}

/// `stiffness, exponent, …`: the names of `parameters`.
pub fn names(parameters: &[Parameter]) -> String {
    let names: Vec<_> = parameters.iter().map(|p| p.name).collect();
    names.join(", ")
}

/// Builds and validates a law from its name and `(parameter, value)` pairs (a
/// parameter given twice takes its last value).
pub fn build(name: &str, values: &[(String, f64)]) -> Result<AnyNormalLaw<f64>, LawInputError> {
    build_named(
        name,
        values.iter().map(|(key, value)| (key.as_str(), Ok(*value))),
    )
}

/// Builds and validates a law from its name and a TOML table of its parameters
/// (floats or integers).
pub(crate) fn build_from_table(
    name: &str,
    parameters: &toml::Table,
) -> Result<AnyNormalLaw<f64>, LawInputError> {
    let number = |value: &toml::Value| match value {
        toml::Value::Float(x) => Ok(*x),
        toml::Value::Integer(i) => Ok(*i as f64),
        other => Err(format!("{} {other}", other.type_str())),
    };
    build_named(
        name,
        parameters.iter().map(|(k, v)| (k.as_str(), number(v))),
    )
}

/// Builds and validates law `name` from `(parameter, value or what was found
/// instead)` pairs: every parameter exactly once, no other.
fn build_named<'a>(
    name: &str,
    pairs: impl IntoIterator<Item = (&'a str, Result<f64, String>)>,
) -> Result<AnyNormalLaw<f64>, LawInputError> {
    let law = entry(name)?;
    let expected = || names(law.parameters);
    let mut given = [None; MAX_PARAMETERS];
    for (parameter, value) in pairs {
        let slot = law
            .kind
            .parameter_index(parameter)
            .and_then(|index| given.get_mut(index))
            .ok_or_else(|| LawInputError::UnknownParameter {
                law: name.to_owned(),
                parameter: parameter.to_owned(),
                expected: expected(),
            })?;
        *slot = Some(value.map_err(|found| LawInputError::NotANumber {
            law: name.to_owned(),
            parameter: parameter.to_owned(),
            found,
            expected: expected(),
        })?);
    }
    let values = law
        .parameters
        .iter()
        .zip(given)
        .map(|(parameter, value)| {
            value.ok_or_else(|| LawInputError::MissingParameter {
                law: name.to_owned(),
                parameter: parameter.name.to_owned(),
                expected: expected(),
            })
        })
        .collect::<Result<Vec<f64>, _>>()?;
    let domain = |e| LawInputError::Domain(name.to_owned(), e);
    let built = AnyNormalLaw::from_values(law.kind, &values).map_err(domain)?;
    built.validate().map_err(domain)?;
    Ok(built)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_round_trip_through_map() {
        let law = build(
            "lankarani_nikravesh",
            &[
                ("stiffness".into(), 6.86e9),
                ("exponent".into(), 1.489),
                ("restitution".into(), 0.929),
            ],
        )
        .unwrap();
        let doubled = law.map_named(|name, v| if name == "stiffness" { 2.0 * v } else { v });
        assert_eq!(
            doubled.named().collect::<Vec<_>>(),
            vec![
                ("stiffness", 13.72e9),
                ("exponent", 1.489),
                ("restitution", 0.929)
            ]
        );
    }

    #[test]
    fn every_catalogued_law_builds_from_its_parameters() {
        for law in LAWS {
            let values: Vec<_> = law
                .parameters
                .iter()
                .map(|p| (p.name.to_owned(), 0.5))
                .collect();
            let built = build(law.name, &values).expect(law.name);
            assert_eq!(built.name(), law.name);
        }
        let names: Vec<_> = LAWS.iter().map(|law| law.kind).collect();
        assert_eq!(names, LawKind::ALL);
    }

    #[test]
    fn a_table_builds_the_law_serde_decodes() {
        for law in LAWS {
            let mut table = toml::Table::new();
            for (i, p) in law.parameters.iter().enumerate() {
                table.insert(
                    p.name.to_owned(),
                    toml::Value::Float(0.25 + 0.125 * i as f64),
                );
            }
            let built = build_from_table(law.name, &table).expect(law.name);
            let mut tagged = toml::Table::new();
            tagged.insert(law.name.to_owned(), toml::Value::Table(table));
            let decoded: AnyNormalLaw<f64> = toml::Value::Table(tagged).try_into().unwrap();
            assert_eq!(built, decoded, "{}", law.name);
        }
    }

    #[test]
    fn integers_are_numbers() {
        let table: toml::Table = toml::from_str("stiffness = 3\nexponent = 1.5").unwrap();
        let law = build_from_table("hertz", &table).unwrap();
        assert_eq!(law.get("stiffness"), Ok(3.0));
    }

    #[test]
    fn a_missing_parameter_is_named() {
        let err = build("lankarani_nikravesh", &[("stiffness".into(), 1e9)]).unwrap_err();
        assert!(err.to_string().contains("exponent"), "{err}");
    }

    #[test]
    fn a_parameter_the_law_does_not_have_is_an_error() {
        let values = [
            ("stifness".into(), 1e9),
            ("stiffness".into(), 1e9),
            ("exponent".into(), 1.5),
        ];
        let err = build("hertz", &values).unwrap_err().to_string();
        assert_eq!(
            err,
            "law `hertz`: no parameter `stifness`; its parameters are: stiffness, exponent"
        );
    }

    #[test]
    fn a_parameter_that_is_not_a_number_is_an_error() {
        let table: toml::Table = toml::from_str("stiffness = \"big\"\nexponent = 1.5").unwrap();
        let err = build_from_table("hertz", &table).unwrap_err().to_string();
        assert!(
            err.contains("`stiffness` must be a number")
                && err.contains("\"big\"")
                && err.contains("stiffness, exponent"),
            "{err}"
        );
    }

    #[test]
    fn an_unknown_law_lists_the_laws() {
        let err = build("hertzian", &[]).unwrap_err().to_string();
        assert!(
            err.contains("`hertzian`") && err.contains("lankarani_nikravesh"),
            "{err}"
        );
    }

    #[test]
    fn out_of_domain_is_rejected() {
        let values = [
            ("stiffness".into(), 1e9),
            ("exponent".into(), 1.5),
            ("restitution".into(), 1.5),
        ];
        let err = build("flores", &values).unwrap_err();
        assert!(err.to_string().contains("restitution"), "{err}");
    }
}
