//! Stage 5 of the peg-in-hole: PM2, the HCM and the HCM int8 replayed from S2's mean
//! pre-contact state, their wall contacts against S2's mean — the paper's Table 15
//! (maximum force and torque, linear and angular impulse of contacts 1 and 2) — and
//! the figures.

use super::curves::{mean_curve, replay_curve, WrenchCurve};
use super::figures::{event_spans, figures};
use crate::dataset::Dataset;
use crate::identify::with_physics;
use crate::identify::{mover_name, replay_events, RigidIdentifyError, WrenchTarget};
use crate::pipeline::NamedFigure;
use crate::scenario::Model;
use serde::Serialize;

/// Table 15's indicators: key, label, unit.
pub const INDICATORS: [(&str, &str, &str); 4] = [
    ("max_force", "maximum force", "N"),
    ("max_torque", "maximum torque", "N·m"),
    ("linear_impulse", "linear impulse", "N·s"),
    ("angular_impulse", "angular impulse", "N·m·s"),
];

/// The paper's Table 15 errors (fractions): (contact, indicator key, PM2, HCM). The
/// paper gives the impulses only.
pub const PAPER: [(usize, &str, f64, f64); 4] = [
    (1, "linear_impulse", 0.0362, 0.0145),
    (1, "angular_impulse", 0.0425, 0.0047),
    (2, "linear_impulse", 0.1667, 0.0052),
    (2, "angular_impulse", 0.0297, 0.0215),
];

/// One cell row of the table: one indicator of one contact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PegRow {
    /// Contact number, 1-based (1 = first wall contact).
    pub contact: usize,
    /// Indicator key (`max_force`, …).
    pub indicator: &'static str,
    /// Its unit.
    pub(crate) unit: &'static str,
    /// S2 mean.
    pub mean: f64,
    /// Standard error of the S2 mean (same unit).
    pub standard_error: f64,
    /// Each model's value, in [`PegEvaluation::models`] order; `None` if its replay
    /// does not make this contact.
    pub values: Vec<Option<f64>>,
    /// Each model's Eq 20 error |mean − value| / mean.
    pub errors: Vec<Option<f64>>,
    /// The paper's (PM2, HCM) errors, where it gives them.
    pub(crate) paper: Option<(f64, f64)>,
}

impl PegRow {
    /// The S2 mean's standard error as a share of it (–).
    pub fn relative_standard_error(&self) -> f64 {
        self.standard_error / self.mean.abs()
    }

    /// Whether model `m`'s error is below model `reference`'s (false if either made
    /// no such contact).
    pub fn beats(&self, m: usize, reference: usize) -> bool {
        match (
            self.errors.get(m).copied().flatten(),
            self.errors.get(reference).copied().flatten(),
        ) {
            (Some(a), Some(b)) => a < b,
            _ => false,
        }
    }

    /// How model `m`'s error compares with the two bounds the HCM is held to (at or
    /// below the paper's HCM error, or within two S2 standard errors): `"≤ paper"`, `"≤ 2 SE"`,
    /// `"neither"`, or `"no contact"`.
    pub fn verdict(&self, m: usize) -> &'static str {
        let Some(error) = self.errors.get(m).copied().flatten() else {
            return "no contact";
        };
        if self.paper.is_some_and(|(_, hcm)| error <= hcm) {
            "≤ paper"
        } else if error <= 2.0 * self.relative_standard_error() {
            "≤ 2 SE"
        } else {
            "neither"
        }
    }
}

/// What stage 5 finds.
pub struct PegEvaluation {
    /// Model labels, in column order.
    pub models: Vec<String>,
    /// S2 runs, and those averaged (the usual event count).
    pub(crate) runs: (usize, usize),
    /// The rows: contacts 1, 2, … × [`INDICATORS`].
    pub rows: Vec<PegRow>,
    /// Each model's and S2's curves (S2 first).
    pub curves: Vec<(&'static str, WrenchCurve)>,
    /// The figures.
    pub(crate) figures: Vec<NamedFigure>,
}

/// Replays `models` (label, model with its physics) from S2's mean pre-contact state
/// and compares their first `events` contacts of contact `c` with S2's.
pub fn evaluate_peg(
    models: &[(&'static str, &Model)],
    validation: &Dataset,
    c: usize,
    events: usize,
) -> Result<PegEvaluation, RigidIdentifyError> {
    let reference = models
        .first()
        .map(|m| m.1)
        .ok_or(RigidIdentifyError::NoSuchContact(c))?;
    let target = WrenchTarget::from_data(reference, validation, c, Some(events))?;
    let replays: Vec<_> = models
        .iter()
        .map(|(_, m)| replay_events(&with_physics(&target.model, m), c).unwrap_or_default())
        .collect();
    let mut rows = Vec::new();
    for (k, event) in target.events.iter().enumerate() {
        let s = &event.statistics;
        let estimates = [
            s.max_force,
            s.max_torque,
            s.linear_impulse,
            s.angular_impulse,
        ];
        for (i, (key, _, unit)) in INDICATORS.iter().enumerate() {
            let values: Vec<Option<f64>> = replays
                .iter()
                .map(|r| r.get(k).map(|(_, got)| got.values()[i]))
                .collect();
            let mean = estimates[i].mean;
            rows.push(PegRow {
                contact: k + 1,
                indicator: key,
                unit,
                mean,
                standard_error: estimates[i].standard_error,
                errors: values
                    .iter()
                    .map(|v| v.map(|v| (mean - v).abs() / mean.abs()))
                    .collect(),
                values,
                paper: PAPER
                    .iter()
                    .find(|p| p.0 == k + 1 && p.1 == *key)
                    .map(|p| (p.2, p.3)),
            });
        }
    }
    let curves = curves(models, &target, validation, c);
    let figures = figures(&curves, &event_spans(&target.events));
    Ok(PegEvaluation {
        models: models.iter().map(|m| m.0.to_owned()).collect(),
        runs: (target.runs, target.runs - target.left_out.len()),
        rows,
        curves,
        figures,
    })
}

/// S2's mean curve and each model's, from 2 ms before the first contact to 2 ms after
/// the last target contact ends, every 20 µs.
fn curves(
    models: &[(&'static str, &Model)],
    target: &WrenchTarget,
    validation: &Dataset,
    c: usize,
) -> Vec<(&'static str, WrenchCurve)> {
    let last = target.events.last();
    let end = last.map_or(0.01, |e| e.delay + e.statistics.duration.mean) + 2e-3;
    let window = (-2e-3, end, 20e-6);
    let mover = mover_name(&target.model, c).unwrap_or_default();
    let mut out = vec![(
        "S2 mean",
        mean_curve(&target.model, validation, &mover, window),
    )];
    for (label, model) in models {
        let replay_model = with_physics(&target.model, model);
        out.push((*label, replay_curve(&replay_model, c, &mover, window)));
    }
    out
}
