//! The physics file: what `identify` writes and `simulate`, `evaluate` and later
//! stages read — the identified law of each contact, and how it was fitted.

use crate::output::write_atomically;
use crate::scenario::{Model, Scenario, ScenarioError};
use hcm_core::effect::{AirDrag, ContactEffect};
use hcm_core::law::AnyNormalLaw;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One contact's law, as identified.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhysicsContact {
    /// The pair, as in the scenario's `[[contact]] bodies`.
    pub bodies: [String; 2],
    /// Law name.
    pub law: String,
    /// Every parameter of the law (SI).
    pub parameters: toml::Table,
    /// Physical effects added to the law (as `hcm diagnose` writes them in
    /// `extended.toml`); none for a plain identified law.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub effects: Vec<ContactEffect<f64>>,
}

/// How a physics file was obtained (for people; not read back into the model).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
pub struct FitRecord {
    /// `lsq` or `ga` (with its fitness).
    pub method: String,
    /// The data file fitted.
    pub data: String,
    /// Runs and contact events used.
    pub runs: usize,
    /// Contact events used.
    pub events: usize,
    /// Force samples used.
    pub samples: usize,
    /// RMS of measured − modelled force over those samples (N).
    pub force_rms: f64,
    /// RMS difference between the replayed simulation's and the mean measured force
    /// curves, over all conditions (N): the GA's default fitness.
    #[serde(default)]
    pub curve_rms: f64,
    /// Wall-clock time of the fit (s).
    pub seconds: f64,
    /// Remarks (e.g. which combination of parameters the data fixes).
    #[serde(default)]
    pub notes: Vec<String>,
}

/// A body effect found from the motion (as `hcm diagnose` writes it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhysicsBody {
    /// Body name, as in the scenario.
    pub name: String,
    /// Quadratic air drag on it.
    pub air_drag: AirDrag<f64>,
}

/// A physics file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Physics {
    /// Identified contacts.
    #[serde(rename = "contact")]
    pub contacts: Vec<PhysicsContact>,
    /// Body effects (air drag); none for a plain identified law.
    #[serde(default, rename = "body", skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<PhysicsBody>,
    /// How the fit went.
    #[serde(default)]
    pub fit: FitRecord,
}

/// Why a physics file could not be used.
#[derive(Debug, thiserror::Error)]
pub enum PhysicsError {
    /// Unreadable or malformed file.
    #[error("physics file {path}: {message}")]
    File { path: String, message: String },
    /// A contact pair the scenario does not have.
    #[error("physics file {path}: the scenario has no contact between `{}` and `{}`", bodies[0], bodies[1])]
    UnknownContact { path: String, bodies: [String; 2] },
    /// The scenario with the physics applied is invalid.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
}

impl Physics {
    /// The physics of `law` identified for contact `c` of `model`.
    pub fn for_contact(
        model: &Model,
        c: usize,
        law: &AnyNormalLaw<f64>,
        fit: FitRecord,
    ) -> Physics {
        let contact = &model.contacts[c];
        let parameters = law
            .named()
            .map(|(name, value)| (name.to_owned(), toml::Value::Float(value)))
            .collect();
        Physics {
            contacts: vec![PhysicsContact {
                bodies: [
                    model.bodies[contact.body_1].name.clone(),
                    model.bodies[contact.body_2].name.clone(),
                ],
                law: law.name().to_owned(),
                parameters,
                effects: Vec::new(),
            }],
            bodies: Vec::new(),
            fit,
        }
    }

    /// Reads a physics file.
    pub fn read(path: &Path) -> Result<Physics, PhysicsError> {
        let file = |message: String| PhysicsError::File {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| file(e.to_string()))?;
        toml::from_str(&text).map_err(|e| file(e.to_string()))
    }

    /// Writes it (atomically), with a comment line on top.
    pub fn write(&self, path: &Path, comment: &str) -> anyhow::Result<()> {
        let text = toml::to_string(self)?;
        write_atomically(path, |w: &mut dyn std::io::Write| -> anyhow::Result<()> {
            writeln!(w, "# {comment}")?;
            w.write_all(text.as_bytes())?;
            Ok(())
        })
    }

    /// `scenario` with each contact's law and parameters replaced by this file's
    /// (and its parameter noise removed: a physics model is deterministic).
    pub fn apply(&self, scenario: &Scenario, path: &Path) -> Result<Scenario, PhysicsError> {
        let mut assignments = Vec::new();
        for contact in &self.contacts {
            let index = scenario
                .contacts
                .iter()
                .position(|c| c.bodies == contact.bodies)
                .ok_or_else(|| PhysicsError::UnknownContact {
                    path: path.display().to_string(),
                    bodies: contact.bodies.clone(),
                })?;
            assignments.push(format!("contact.{index}.law=\"{}\"", contact.law));
            assignments.push(format!(
                "contact.{index}.parameters={}",
                inline_table(&contact.parameters)
            ));
            assignments.push(format!("contact.{index}.noise={{}}"));
            // The physics file is the whole model of the contact: its effects replace
            // the scenario's (none clears them).
            let effects =
                toml::Value::try_from(&contact.effects).map_err(|e| PhysicsError::File {
                    path: path.display().to_string(),
                    message: format!("effects: {e}"),
                })?;
            assignments.push(format!("contact.{index}.effects={effects}"));
        }
        for body in &self.bodies {
            assignments.push(format!(
                "body.{}.air_drag={{ coefficient = {:?} }}",
                body.name, body.air_drag.coefficient
            ));
        }
        Ok(scenario.with(&assignments)?)
    }
}

/// `{ a = 1.0, b = 2.0 }` with round-trip float formatting.
fn inline_table(table: &toml::Table) -> String {
    let items: Vec<String> = table
        .iter()
        .map(|(k, v)| match v.as_float() {
            Some(x) => format!("{k} = {x:?}"),
            None => format!("{k} = {v}"),
        })
        .collect();
    format!("{{ {} }}", items.join(", "))
}
