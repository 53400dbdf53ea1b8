//! A 1D diagnosis written out whole: what `hcm diagnose --out DIR` holds.

use super::{diagnosis_json, diagnosis_markdown, extended_physics, structure_figures, Diagnosis};
use crate::output::write_bytes;
use crate::scenario::Model;
use std::path::Path;

/// What a diagnosis was made of, for its files: the base model, the contact diagnosed,
/// the data file's name and the scenario's.
pub struct DiagnosisOf<'a> {
    /// The base model (the scenario with the base physics file applied).
    pub base: &'a Model,
    /// The contact diagnosed.
    pub contact: usize,
    /// The data, as their file is named.
    pub data: &'a str,
    /// The scenario's name.
    pub scenario: &'a str,
}

/// Writes `diagnosis` into the directory `out` — extended.toml (the extended model as a
/// physics file), diagnosis.json, the residual figures (SVG and PNG) and report.md —
/// and returns the report's text.
pub fn write_diagnosis(
    out: &Path,
    of: &DiagnosisOf<'_>,
    diagnosis: &Diagnosis,
) -> anyhow::Result<String> {
    extended_physics(of.base, of.contact, of.data, diagnosis).write(
        &out.join("extended.toml"),
        &format!("extended model of `{}` from hcm diagnose", of.scenario),
    )?;
    write_bytes(
        &out.join("diagnosis.json"),
        serde_json::to_string_pretty(&diagnosis_json(diagnosis))?.as_bytes(),
    )?;
    let figures = write_figures(out, diagnosis)?;
    let report = diagnosis_markdown(diagnosis, &figures);
    write_bytes(&out.join("report.md"), report.as_bytes())?;
    Ok(report)
}

/// Writes the residual figures (base vs extended) to `out` as SVG and PNG; their names.
fn write_figures(out: &Path, diagnosis: &Diagnosis) -> anyhow::Result<Vec<&'static str>> {
    let mut figures = Vec::new();
    for (name, figure) in structure_figures(
        &diagnosis.before,
        Some(&diagnosis.after),
        ("base", "extended"),
    ) {
        write_bytes(&out.join(format!("{name}.svg")), figure.svg().as_bytes())?;
        write_bytes(&out.join(format!("{name}.png")), &figure.png()?)?;
        figures.push(name);
    }
    Ok(figures)
}
