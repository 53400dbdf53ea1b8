//! The paper's evaluation tables (Tables 5 and 10): for each condition of the
//! validation data S2, the measured mean indicators beside those of a physics model
//! replayed from the same pre-contact state, and the Eq 20 error of each.

use crate::dataset::Dataset;
use crate::identify::replay::{simulate_target_with, targets};
use crate::identify::IdentifyError;
use crate::indicators::Indicators;
use crate::scenario::Model;
use serde::Serialize;

/// One model's indicators and their errors against the S2 mean.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelColumn {
    /// Column label (`PM2`, `HCM`).
    pub label: String,
    /// The model's indicators (None if its simulation failed).
    pub indicators: Option<Indicators>,
    /// Eq 20 errors, in the order of [`Indicators::NAMES`].
    pub errors: Option<[f64; 4]>,
}

/// The table of one condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConditionTable {
    /// Condition name ("" without conditions).
    pub condition: String,
    /// Runs in S2 for it.
    pub runs: usize,
    /// S2 mean indicators.
    pub measured: Indicators,
    /// Standard error of each S2 mean (s/√n, same units): errors below about twice
    /// this, relative to the mean, are within the sampling noise of S2.
    pub standard_error: Indicators,
    /// The models compared.
    pub models: Vec<ModelColumn>,
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
                    let indicators =
                        simulate_target_with(target, c, &model.contacts[c]).map(|(_, i)| i);
                    ModelColumn {
                        label: label.to_string(),
                        indicators,
                        errors: indicators.map(|i| i.relative_error(&target.indicators)),
                    }
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
        let _ = write!(header, " {} |", m.label);
        rule.push_str("---|");
    }
    for m in &table.models {
        let _ = write!(header, " error of {} |", m.label);
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
        let (mean, error) = (table.measured.values()[i], table.standard_error.values()[i]);
        let _ = write!(
            out,
            "| {label} | {mean:.5e} | {:.2} % |",
            100.0 * (error / mean).abs()
        );
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
                    let _ = write!(out, " {:.2} % |", 100.0 * e[i]);
                }
                None => out.push_str(" – |"),
            }
        }
        out.push('\n');
    }
    out
}
