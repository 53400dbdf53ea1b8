//! The physics file: what `identify` writes and `simulate`, `evaluate` and later
//! stages read — the identified law of each contact, and how it was fitted.

use crate::input;
use crate::law_catalogue::{self, LawInputError};
use crate::output::write_atomically;

use crate::scenario::{Assignment, FrictionSpec, Model, Scenario, ScenarioError};
use hcm_core::effect::{AirDrag, ContactEffect};
use hcm_core::law::AnyNormalLaw;
use hcm_core::LawError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One contact's law, as identified.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhysicsContact {
    /// The pair, as in the scenario's `[[contact]] bodies`.
    pub(crate) bodies: [String; 2],
    /// Law name.
    pub(crate) law: String,
    /// Every parameter of the law (SI).
    pub parameters: toml::Table,
    /// The contact's parameter scatter from run to run (relative σ per parameter, –;
    /// the scenario's `noise`, Eq 18), as `hcm diagnose` names it: what a forecast's
    /// members draw. None: the contact is the same in every run.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub noise: std::collections::BTreeMap<String, f64>,
    /// Physical effects added to the law (as `hcm diagnose` writes them in
    /// `extended.toml`); none for a plain identified law.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub effects: Vec<ContactEffect<f64>>,
    /// STEP friction (Eq 10–11), identified with the law on a rigid contact; absent:
    /// the scenario's stays.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionSpec>,
    /// Tangential effects at every point (viscous friction, torsional and rolling
    /// resistance), as `hcm diagnose` names them on a rigid contact; absent: the
    /// scenario's stay.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential: Option<hcm_core::friction::TangentialEffects<f64>>,
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
    /// What the fit found beside the contacts, as scenario assignments applied with the
    /// file (written `key=value`, as `--set` takes them): the shift of the fixed body a
    /// thrown one lands on, the thrown body's inertia (the fit from motion). None
    /// otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sets: Vec<Assignment>,
    /// How the fit went.
    #[serde(default)]
    pub(crate) fit: FitRecord,
}

/// Why a physics file could not be used. Every variant but `Scenario` names the
/// physics file: an error in it is never reported against the scenario.
#[derive(Debug, thiserror::Error)]
pub enum PhysicsError {
    /// Unreadable or malformed file.
    #[error("physics file {path}: {}", input::bounded(message))]
    File {
        /// The physics file's path.
        path: String,
        /// Why it could not be read or parsed.
        message: String,
    },
    /// A contact pair the scenario does not have.
    #[error("physics file {path}: the scenario has no contact between `{}` and `{}`", input::excerpt(&bodies[0]), input::excerpt(&bodies[1]))]
    UnknownContact {
        /// The physics file's path.
        path: String,
        /// The two bodies the file's contact names.
        bodies: [String; 2],
    },
    /// A key of the physics file (`contact.0.law`, `contact.0.parameters.restitution`)
    /// holds what its law or the scenario cannot take.
    #[error(
        "physics file {path}: {}: {}",
        input::shorten(key),
        input::shorten(message)
    )]
    Key {
        /// The physics file's path.
        path: String,
        /// The key, dotted (`contact.0.parameters.restitution`).
        key: String,
        /// What is wrong with its value.
        message: String,
    },
    /// The physics file's laws are valid, but the scenario they make is not, while the
    /// scenario alone is (e.g. a derived parameter out of its domain).
    /// (The scenario's error is part of the message, not a `source`, so that a chain
    /// printed with `{:#}` does not repeat it.)
    #[error("physics file {path} does not fit the scenario: {scenario_error}")]
    Misfit {
        /// The physics file's path.
        path: String,
        /// What is wrong with the scenario the file's laws make.
        scenario_error: ScenarioError,
    },
    /// The scenario is invalid, with or without the physics applied.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
}

impl Physics {
    /// Whether a fit wrote it (`hcm identify` records its method), rather than a
    /// person: what a diagnosis may re-tune of its law depends on it.
    pub fn fitted(&self) -> bool {
        !self.fit.method.is_empty()
    }

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
                noise: Default::default(),
                effects: Vec::new(),
                friction: contact.model.friction.as_ref().map(FrictionSpec::of),
                tangential: None,
            }],
            bodies: Vec::new(),
            sets: Vec::new(),
            fit,
        }
    }

    /// Contact `c` of `model` as it stands: its base law, its effects, its friction and,
    /// where any is set, its tangential effects — a diagnosis' extended model (the
    /// fitted law of `hcm identify` goes through [`Physics::for_contact`]).
    pub fn of_contact(model: &Model, c: usize, fit: FitRecord) -> Physics {
        let contact = &model.contacts[c].model;
        let mut physics = Physics::for_contact(model, c, &contact.normal.base, fit);
        physics.contacts[0].effects = contact.normal.effects.iter().copied().collect();
        let t = contact.tangential;
        let any = t.viscous_friction.is_some()
            || t.torsional_resistance.is_some()
            || t.rolling_resistance.is_some();
        physics.contacts[0].tangential = any.then_some(t);
        physics
    }

    /// This file with `model`'s variation: each of its contacts' parameter scatter
    /// (`noise`) from the model's contact between the same bodies, and the model's
    /// `[variation]` as `sets` (those not 0) — the extended model of a diagnosis that
    /// named a chance.
    pub fn with_variation(mut self, model: &Model) -> Physics {
        for contact in &mut self.contacts {
            let same = (model.contacts.iter()).find(|c| {
                [c.body_1, c.body_2].map(|b| model.bodies[b].name.as_str())
                    == [contact.bodies[0].as_str(), contact.bodies[1].as_str()]
            });
            if let Some(c) = same {
                contact.noise = c.noise.iter().cloned().collect();
            }
        }
        self.sets.extend(variation_sets(model));
        self
    }

    /// Reads a physics file.
    pub fn read(path: &Path) -> Result<Physics, PhysicsError> {
        let file = |message: String| PhysicsError::File {
            path: path.display().to_string(),
            message,
        };
        let text = input::read_text(path, input::TEXT_LIMIT, "a physics file").map_err(file)?;
        toml::from_str(&text).map_err(|e| file(input::toml_error(&text, &e)))
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

    /// `scenario` with each contact's law, parameters and parameter scatter replaced by
    /// this file's (a contact without `noise` in the file has none: the scenario's
    /// experiment noise is not part of a model).
    ///
    /// Errors name the physics file and its key (`contact.0.law`,
    /// `contact.0.parameters.restitution`), not the scenario it is applied to.
    pub fn apply(&self, scenario: &Scenario, path: &Path) -> Result<Scenario, PhysicsError> {
        self.check(scenario, path)?;
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
            let set = |key: &str, value: toml::Value| Assignment::contact(index, &[key], value);
            assignments.push(set("law", contact.law.clone().into()));
            assignments.push(set("parameters", contact.parameters.clone().into()));
            let noise: toml::Table = (contact.noise.iter())
                .map(|(name, b)| (name.clone(), toml::Value::Float(*b)))
                .collect();
            assignments.push(set("noise", noise.into()));
            // The physics file is the whole model of the contact: its effects replace
            // the scenario's (none clears them).
            let effects =
                toml::Value::try_from(&contact.effects).map_err(|e| PhysicsError::File {
                    path: path.display().to_string(),
                    message: format!("effects: {e}"),
                })?;
            assignments.push(set("effects", effects));
            if let Some(f) = &contact.friction {
                let friction = [
                    ("mu_static", f.mu_static),
                    ("mu_dynamic", f.mu_dynamic),
                    ("v_static", f.v_static),
                    ("v_dynamic", f.v_dynamic),
                ];
                assignments.push(set("friction", float_table(&friction)));
            }
            if let Some(t) = &contact.tangential {
                let table = toml::Value::try_from(t).map_err(|e| PhysicsError::File {
                    path: path.display().to_string(),
                    message: format!("tangential: {e}"),
                })?;
                assignments.push(set("tangential", table));
            }
        }
        for body in &self.bodies {
            let drag = float_table(&[("coefficient", body.air_drag.coefficient)]);
            assignments.push(Assignment::body(&body.name, &["air_drag"], drag));
        }
        assignments.extend(self.sets.iter().cloned());
        let misfit = |scenario_error| PhysicsError::Misfit {
            path: path.display().to_string(),
            scenario_error,
        };
        let applied = scenario.with_assignments(&assignments).map_err(misfit)?;
        // What `check` cannot see alone (parameters derived from the bodies): the
        // scenario resolves without the physics but not with it.
        match applied.model() {
            Err(error) if scenario.model().is_ok() => Err(misfit(error)),
            _ => Ok(applied),
        }
    }

    /// Checks each key of the file that the scenario does not decide: law names,
    /// parameter names, types and domains, body names and their air drag.
    fn check(&self, scenario: &Scenario, path: &Path) -> Result<(), PhysicsError> {
        let key_error = |key: String, message: String| PhysicsError::Key {
            path: path.display().to_string(),
            key,
            message,
        };
        for (i, contact) in self.contacts.iter().enumerate() {
            if let Err(error) = law_catalogue::build_from_table(&contact.law, &contact.parameters) {
                let parameter = |name: &str| format!("contact.{i}.parameters.{name}");
                let (key, message) = match &error {
                    LawInputError::UnknownLaw(..) => {
                        (format!("contact.{i}.law"), error.to_string())
                    }
                    LawInputError::UnknownParameter {
                        parameter: name, ..
                    }
                    | LawInputError::NotANumber {
                        parameter: name, ..
                    } => (parameter(name), error.to_string()),
                    // A parameter the scenario may derive from its bodies: checked once
                    // applied.
                    LawInputError::MissingParameter { .. } => continue,
                    LawInputError::Domain(_, domain) => match domain_parameter(domain) {
                        Some(name) => {
                            let found = contact
                                .parameters
                                .get(name)
                                .map_or(String::new(), |v| format!(", found {v}"));
                            (parameter(name), format!("{error}{found}"))
                        }
                        None => (format!("contact.{i}.parameters"), error.to_string()),
                    },
                };
                return Err(key_error(key, message));
            }
        }
        for (i, body) in self.bodies.iter().enumerate() {
            if !scenario.bodies.iter().any(|b| b.name == body.name) {
                let names: Vec<_> = scenario.bodies.iter().map(|b| b.name.as_str()).collect();
                let message = format!(
                    "the scenario has no body `{}` (its bodies: {})",
                    body.name,
                    names.join(", ")
                );
                return Err(key_error(format!("body.{i}.name"), message));
            }
            if let Err(error) = body.air_drag.validate() {
                return Err(key_error(format!("body.{i}.air_drag"), error.to_string()));
            }
        }
        Ok(())
    }
}

/// `model`'s `[variation]` as the assignments that set it, those not 0.
pub fn variation_sets(model: &Model) -> Vec<Assignment> {
    let v = &model.scenario.variation;
    let entries = [
        ("start_state", v.start_state),
        ("fixed_height", v.fixed_height),
        ("fixed_tilt", v.fixed_tilt),
        ("tails", v.tails),
        ("tracker", v.tracker),
    ];
    (entries.into_iter())
        .filter(|(_, value)| *value != 0.0)
        .filter_map(|(name, value)| Assignment::parse(&format!("variation.{name}={value:?}")).ok())
        .collect()
}

/// The parameter a domain error is about, if it names one.
fn domain_parameter(error: &LawError) -> Option<&'static str> {
    match error {
        LawError::NotPositive { parameter }
        | LawError::Negative { parameter }
        | LawError::OutOfRange { parameter, .. } => Some(parameter),
        _ => None,
    }
}

/// The TOML table `{ name = value, … }` of `entries`.
pub(crate) fn float_table(entries: &[(&str, f64)]) -> toml::Value {
    let table: toml::Table = (entries.iter())
        .map(|&(name, value)| (name.to_owned(), value.into()))
        .collect();
    table.into()
}
