//! The paper's evaluation tables (Tables 5 and 10): for each condition of the
//! validation data S2, the measured mean indicators beside those of a physics model
//! replayed from the same pre-contact state, and the Eq 20 error of each — as a
//! [`ModelRow`], the shape every judged model takes (`evaluate --json`,
//! `results.json`, `diagnosis.json`).

mod ensemble;
mod motion;
mod rigid;

pub use ensemble::{evaluate_members, members_markdown, IndicatorForecast};
pub use motion::{evaluate_motion, motion_markdown, MotionEvaluation};
pub use rigid::{evaluate_rigid, rigid_markdown, RigidEvaluation};

use crate::dataset::Dataset;
use crate::identify::IdentifyError;
use crate::identify::{simulate_target_with, targets};
use crate::indicators::Indicators;
use crate::scenario::Model;
use serde::Serialize;

/// The Eq 20 errors of a model's four indicators against the measured means (–, a
/// fraction: 0.01 = 1 %).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct IndicatorErrors {
    /// Of the maximum normal contact force.
    pub(crate) max_force: f64,
    /// Of the normal contact impulse.
    pub(crate) impulse: f64,
    /// Of the contact energy loss.
    pub(crate) energy_loss: f64,
    /// Of the contact duration.
    pub(crate) duration: f64,
}

impl IndicatorErrors {
    /// The Eq 20 errors of `model`'s indicators against the `measured` ones.
    pub fn between(model: &Indicators, measured: &Indicators) -> Self {
        Self::from_values(model.relative_error(measured))
    }

    /// The errors given in [`Indicators::NAMES`] order.
    pub fn from_values([max_force, impulse, energy_loss, duration]: [f64; 4]) -> Self {
        Self {
            max_force,
            impulse,
            energy_loss,
            duration,
        }
    }

    /// The four errors in [`Indicators::NAMES`] order.
    pub fn values(&self) -> [f64; 4] {
        [
            self.max_force,
            self.impulse,
            self.energy_loss,
            self.duration,
        ]
    }
}

/// One model judged against measured means: its indicators and their errors. The row
/// `hcm evaluate --json`, `results.json` and `diagnosis.json` share (README, "Model
/// rows").
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelRow {
    /// Model label (`PM2`, `HCM`, `HCM int8`; `base`, `extended`, `HCM` in a diagnosis).
    pub model: String,
    /// The model's indicators (N, N·s, N·m, s); None (JSON `null`) where its
    /// simulation failed.
    pub(crate) indicators: Option<Indicators>,
    /// Their Eq 20 errors against the measured means; None where its simulation failed.
    pub errors: Option<IndicatorErrors>,
}

impl ModelRow {
    /// The row of `model` whose replay gave `simulated` (None if it failed), judged
    /// against the `measured` indicators.
    pub fn judged(model: &str, simulated: Option<Indicators>, measured: &Indicators) -> Self {
        ModelRow {
            model: model.to_owned(),
            indicators: simulated,
            errors: simulated.map(|i| IndicatorErrors::between(&i, measured)),
        }
    }
}

/// The table of one condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConditionTable {
    /// Condition name ("" without conditions).
    pub condition: String,
    /// Runs in S2 for it.
    pub runs: usize,
    /// S2 mean indicators.
    pub(crate) measured: Indicators,
    /// Standard error of each S2 mean (s/√n, same units): errors below about twice
    /// this, relative to the mean, are within the sampling noise of S2. None (JSON
    /// `null`) with a single run, whose spread is unknown.
    pub(crate) standard_error: Option<Indicators>,
    /// The models compared, one row each.
    pub models: Vec<ModelRow>,
}

/// Evaluates the models (`(label, model)`, each a scenario with its physics applied)
/// on contact `c` of the validation data.
pub fn evaluate(
    models: &[(&str, &Model)],
    data: &Dataset,
    c: usize,
) -> Result<Vec<ConditionTable>, IdentifyError> {
    let Some((_, reference)) = models.first() else {
        return Ok(Vec::new());
    };
    let targets = targets(reference, data, c)?;
    Ok(targets
        .iter()
        .map(|target| ConditionTable {
            condition: target.condition.clone(),
            runs: target.runs,
            measured: target.indicators,
            standard_error: target.standard_error,
            models: models
                .iter()
                .map(|(label, model)| {
                    let simulated =
                        simulate_target_with(target, c, &model.contacts[c]).map(|(_, i)| i);
                    ModelRow::judged(label, simulated, &target.indicators)
                })
                .collect(),
        })
        .collect())
}

/// The table as markdown, in the paper's layout.
pub fn markdown(table: &ConditionTable) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let mut header = String::from("| indicator | S2 (mean) | S2 standard error |");
    let mut rule = String::from("|---|---|---|");
    for m in &table.models {
        let _ = write!(header, " {} |", m.model);
        rule.push_str("---|");
    }
    for m in &table.models {
        let _ = write!(header, " error of {} |", m.model);
        rule.push_str("---|");
    }
    let _ = writeln!(out, "{header}\n{rule}");
    let labels = [
        "maximum contact force (N)",
        "contact impulse (N·s)",
        "contact energy loss (N·m)",
        "contact duration (s)",
    ];
    for (i, label) in labels.iter().enumerate() {
        let mean = table.measured.values()[i];
        let _ = match table.standard_error {
            Some(error) => write!(
                out,
                "| {label} | {mean:.5e} | {:.2} % |",
                100.0 * (error.values()[i] / mean).abs()
            ),
            None => write!(out, "| {label} | {mean:.5e} | n/a ({} run) |", table.runs),
        };
        for m in &table.models {
            match m.indicators {
                Some(v) => {
                    let _ = write!(out, " {:.5e} |", v.values()[i]);
                }
                None => out.push_str(" (failed) |"),
            }
        }
        for m in &table.models {
            match m.errors {
                Some(e) => {
                    let _ = write!(out, " {:.2} % |", 100.0 * e.values()[i]);
                }
                None => out.push_str(" – |"),
            }
        }
        out.push('\n');
    }
    out
}
