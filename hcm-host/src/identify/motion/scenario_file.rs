//! The fitted model as a scenario file: the scenario as read (its `--set` overrides
//! applied) with the fitted law parameters, friction coefficients and table offset
//! written in, so that `hcm predict --scenario FILE` replays the fit with nothing else
//! to give. A physics file carries the law and the friction but has no place for the
//! table's height; this file carries all three (the original's comments are not kept).

use super::MotionParameters;
use crate::scenario::{Model, Scenario, ScenarioError};

/// The `--set` assignments that turn `model`'s scenario into the fitted one, from the
/// fit's [`MotionParameters::named`] values: the law's two parameters, `mu_static`,
/// `mu_dynamic` and `table_offset` (m).
pub fn fitted_assignments(
    model: &Model,
    parameters: &MotionParameters,
    named: &[(String, f64)],
) -> Vec<String> {
    let contact = parameters.contact;
    named
        .iter()
        .map(|(name, value)| match name.as_str() {
            "table_offset" => table_assignment(model, parameters, *value),
            "mu_static" | "mu_dynamic" => format!("contact.{contact}.friction.{name}={value:e}"),
            _ => format!("contact.{contact}.parameters.{name}={value:e}"),
        })
        .collect()
}

/// The `--set` that puts the table's surface at `offset` (m) — what a physics file,
/// which holds the law and the friction but not the plane, needs beside it.
pub fn table_assignment(model: &Model, parameters: &MotionParameters, offset: f64) -> String {
    let table = &model.bodies[parameters.plane].name;
    format!("body.{table}.shape.plane.offset={offset:e}")
}

/// The fit's table offset (m) among its [`MotionParameters::named`] values (0 if none).
pub fn fitted_offset(named: &[(String, f64)]) -> f64 {
    (named.iter())
        .find(|(name, _)| name == "table_offset")
        .map_or(0.0, |p| p.1)
}

/// The text of the fitted scenario file: `scenario` with `assignments` applied, checked
/// by reading it back, under a header saying where it came from.
pub fn fitted_scenario_text(
    scenario: &Scenario,
    assignments: &[String],
    header: &str,
) -> Result<String, ScenarioError> {
    let fitted = scenario.with(assignments)?;
    fitted.model()?;
    let body = toml::to_string(&fitted.source.document).map_err(|e| ScenarioError::Syntax {
        path: fitted.source.path.clone(),
        message: format!("cannot write the fitted scenario as TOML: {e}"),
    })?;
    let comment: String = header.lines().map(|l| format!("# {l}\n")).collect();
    Ok(comment + &body)
}
