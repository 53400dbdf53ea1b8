//! The normal laws by name: what each one is, its parameters with units, and how
//! to build one from `key=value` pairs.

use hcm_core::law::{AnyNormalLaw, NormalLaw};
use hcm_core::LawError;

/// One parameter of a law: its field name, unit and meaning.
#[derive(Clone, Copy, Debug)]
pub struct Parameter {
    /// Field name, as in scenario files and `--set`.
    pub name: &'static str,
    /// SI unit.
    pub unit: &'static str,
    /// Symbol and meaning.
    pub meaning: &'static str,
}

/// One normal law as described to users.
#[derive(Clone, Copy, Debug)]
pub struct LawEntry {
    /// Name used in files and on the command line.
    pub name: &'static str,
    /// Where the formula comes from.
    pub source: &'static str,
    /// The formula, f_n for δ > 0.
    pub formula: &'static str,
    /// Its parameters.
    pub parameters: &'static [Parameter],
}

const fn p(name: &'static str, unit: &'static str, meaning: &'static str) -> Parameter {
    Parameter {
        name,
        unit,
        meaning,
    }
}

const STIFFNESS: Parameter = p("stiffness", "N/m^n", "k, contact stiffness");
const EXPONENT: Parameter = p("exponent", "-", "n, force exponent");
const RESTITUTION: Parameter = p("restitution", "-", "ce, coefficient of restitution");

/// Every normal law of the core.
pub const LAWS: &[LawEntry] = &[
    LawEntry {
        name: "hertz",
        source: "Eq 2 (k from Eq 3)",
        formula: "k·δ^n",
        parameters: &[STIFFNESS, EXPONENT],
    },
    LawEntry {
        name: "lankarani_nikravesh",
        source: "Eq 4–5",
        formula: "k·δ^n + 3k(1−ce²)δ^n/(4δ̇0)·δ̇",
        parameters: &[STIFFNESS, EXPONENT, RESTITUTION],
    },
    LawEntry {
        name: "variable_stiffness",
        source: "Eq 6–7 (as printed)",
        formula: "k(δ)·δ + 2λ·√(k(δ)·m_e)·δ·δ̇, k(δ) = c·E*·√(2rδ−δ²)",
        parameters: &[
            p(
                "surface_loading",
                "-",
                "c, surface loading coefficient (4/3…2π)",
            ),
            p("effective_modulus", "Pa", "E*, effective modulus"),
            p("radius", "m", "r, sphere radius"),
            p("damping", "1/m", "λ, damping (literal Eq 6)"),
            p("effective_mass", "kg", "m_e, effective mass"),
        ],
    },
    LawEntry {
        name: "impact",
        source: "Eq 8–9 (MSC ADAMS)",
        formula: "max(0, k·δ^e + step(δ, 0, 0, δ_max, d_max)·δ̇)",
        parameters: &[
            STIFFNESS,
            p("exponent", "-", "e, force exponent"),
            p("max_damping", "N·s/m", "d_max, maximum damping"),
            p("full_damping_depth", "m", "δ_max, depth of full damping"),
        ],
    },
    LawEntry {
        name: "hunt_crossley",
        source: "Hunt & Crossley 1975",
        formula: "k·δ^n·(1 + χ·δ̇)",
        parameters: &[
            STIFFNESS,
            EXPONENT,
            p("damping", "s/m", "χ, damping factor"),
        ],
    },
    LawEntry {
        name: "flores",
        source: "Flores et al. 2011",
        formula: "k·δ^n·(1 + 8(1−ce)/(5·ce·δ̇0)·δ̇)",
        parameters: &[STIFFNESS, EXPONENT, RESTITUTION],
    },
];

/// Why a law could not be built from user input.
#[derive(Debug, thiserror::Error)]
pub enum LawInputError {
    /// No law has that name.
    #[error("unknown law `{0}`; the laws are: {1}")]
    UnknownLaw(String, String),
    /// A parameter is missing or has the wrong type.
    #[error("law `{law}`: {message}; its parameters are: {expected}")]
    Parameters {
        law: String,
        message: String,
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

/// Builds and validates a law from its name and `(parameter, value)` pairs.
pub fn build(name: &str, values: &[(String, f64)]) -> Result<AnyNormalLaw<f64>, LawInputError> {
    let table = values
        .iter()
        .map(|(key, value)| (key.clone(), toml::Value::Float(*value)))
        .collect();
    build_from_table(name, &table)
}

/// Builds and validates a law from its name and a TOML table of its parameters.
pub fn build_from_table(
    name: &str,
    parameters: &toml::Table,
) -> Result<AnyNormalLaw<f64>, LawInputError> {
    let law = entry(name)?;
    let mut outer = toml::Table::new();
    outer.insert(name.to_owned(), toml::Value::Table(parameters.clone()));
    let built: AnyNormalLaw<f64> =
        toml::Value::Table(outer)
            .try_into()
            .map_err(|e: toml::de::Error| LawInputError::Parameters {
                law: name.to_owned(),
                message: e.message().trim().to_owned(),
                expected: law
                    .parameters
                    .iter()
                    .map(|p| p.name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
    built
        .validate()
        .map_err(|e| LawInputError::Domain(name.to_owned(), e))?;
    Ok(built)
}

/// A law's parameters by name, in catalogue order, with their values.
pub fn parameters(law: &AnyNormalLaw<f64>) -> Vec<(&'static str, f64)> {
    let table = parameter_table(law);
    entry(law.name())
        .map(|e| e.parameters)
        .unwrap_or(&[])
        .iter()
        .filter_map(|p| {
            table
                .get(p.name)
                .and_then(toml::Value::as_float)
                .map(|v| (p.name, v))
        })
        .collect()
}

/// The same law with every parameter passed through `f(name, value)`.
pub fn map_parameters(
    law: &AnyNormalLaw<f64>,
    mut f: impl FnMut(&str, f64) -> f64,
) -> AnyNormalLaw<f64> {
    let mut table = parameter_table(law);
    for (name, value) in table.iter_mut() {
        if let Some(v) = value.as_float() {
            *value = toml::Value::Float(f(name, v));
        }
    }
    let mut outer = toml::Table::new();
    outer.insert(law.name().to_owned(), toml::Value::Table(table));
    toml::Value::Table(outer).try_into().unwrap_or(*law)
}

/// The law's fields as a TOML table (the externally tagged serde form, unwrapped).
pub fn parameter_table(law: &AnyNormalLaw<f64>) -> toml::Table {
    match toml::Value::try_from(law) {
        Ok(toml::Value::Table(mut outer)) => match outer.remove(law.name()) {
            Some(toml::Value::Table(inner)) => inner,
            _ => toml::Table::new(),
        },
        _ => toml::Table::new(),
    }
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
        let doubled = map_parameters(
            &law,
            |name, v| if name == "stiffness" { 2.0 * v } else { v },
        );
        assert_eq!(
            parameters(&doubled),
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
    }

    #[test]
    fn a_missing_parameter_is_named() {
        let err = build("lankarani_nikravesh", &[("stiffness".into(), 1e9)]).unwrap_err();
        assert!(err.to_string().contains("exponent"), "{err}");
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
