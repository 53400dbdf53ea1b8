//! Stage 5: PM2, the HCM and the HCM with int8 weights replayed on S2 — the paper's
//! table (Tables 5 and 10) and its figures (Fig 9/12 and 10/13).

use super::{Blobs, PipelineError, Progress, Stage, CONTACT};
use crate::dataset::Dataset;
use crate::evaluate::{evaluate, ConditionTable};
use crate::figure::{Colour, Figure, Series};
use crate::identify::replay::{simulate_target_with, targets, Target};
use crate::scenario::Model;

/// The column labels of the models compared, in the table's order.
pub const MODELS: [&str; 3] = ["PM2", "HCM", "HCM int8"];

/// A figure and the file stem it is written under (`STEM.svg`, `STEM.png`).
pub struct NamedFigure {
    /// File stem, e.g. `contact_force`.
    pub stem: &'static str,
    /// The figure.
    pub figure: Figure<'static>,
}

/// What stage 5 finds.
pub struct Evaluation {
    /// The table of S2's first condition (the only one of the paper's examples).
    pub table: ConditionTable,
    /// Fig 9/12 (`contact_force`) and Fig 10/13 (`force_error`).
    pub figures: Vec<NamedFigure>,
}

/// Replays PM2 (`pm2`, the scenario with PM2 in place) and PM2 + each blob's residual
/// on the `validation` set (S2) and draws the figures.
pub fn evaluate_on_s2(
    pm2: &Model,
    blobs: &Blobs,
    validation: &Dataset,
    progress: &dyn Progress,
) -> Result<Evaluation, PipelineError> {
    progress.begin(Stage::Evaluate, 1);
    let with_residual = |blob: &super::Blob| {
        let mut hcm = pm2.clone();
        hcm.contacts[CONTACT].model.residual = Some(blob.residual.clone());
        hcm
    };
    let (hcm, hcm_int8) = (with_residual(&blobs.f32), with_residual(&blobs.int8));
    let columns = [(MODELS[0], pm2), (MODELS[1], &hcm), (MODELS[2], &hcm_int8)];
    let table = evaluate(&columns, validation, CONTACT)?
        .into_iter()
        .next()
        .ok_or(PipelineError::NoValidation)?;
    let target = targets(pm2, validation, CONTACT)?
        .into_iter()
        .next()
        .ok_or(PipelineError::NoValidation)?;
    let figures = figures(&target, pm2, &hcm);
    progress.end(Stage::Evaluate);
    Ok(Evaluation { table, figures })
}

/// The S2 mean force curve of `target` beside PM2's and the HCM's replays of it, and
/// the error of each.
fn figures(target: &Target, pm2: &Model, hcm: &Model) -> Vec<NamedFigure> {
    let replay = |model: &Model| {
        simulate_target_with(target, CONTACT, &model.contacts[CONTACT])
            .map(|(curve, _)| curve)
            .unwrap_or_default()
    };
    let (pm2_curve, hcm_curve) = (replay(pm2), replay(hcm));
    // Samples j of the curves lie j periods after touch-down; plotted in µs.
    let time = |j: usize| 1e6 * j as f64 * target.period;
    let points = |v: &[f64]| {
        v.iter()
            .enumerate()
            .map(|(j, f)| (time(j), *f))
            .collect::<Vec<_>>()
    };
    let errors = |v: &[f64]| {
        target
            .curve
            .iter()
            .zip(v)
            .enumerate()
            .map(|(j, (m, s))| (time(j), m - s))
            .collect::<Vec<_>>()
    };
    let series = |label, colour, points| Series {
        label,
        colour: Colour::hex(colour),
        points,
    };
    let force = Figure::new(
        "Contact force over the contact (S2)",
        "time since touch-down (µs)",
        "normal force (N)",
        vec![
            series("S2 mean", 0x333333, points(&target.curve)),
            series("PM2", 0xd62728, points(&pm2_curve)),
            series("HCM", 0x1f77b4, points(&hcm_curve)),
        ],
    );
    let error = Figure::new(
        "Force error: S2 mean − model",
        "time since touch-down (µs)",
        "force error (N)",
        vec![
            series("PM2", 0xd62728, errors(&pm2_curve)),
            series("HCM", 0x1f77b4, errors(&hcm_curve)),
        ],
    );
    vec![
        NamedFigure {
            stem: "contact_force",
            figure: force,
        },
        NamedFigure {
            stem: "force_error",
            figure: error,
        },
    ]
}
