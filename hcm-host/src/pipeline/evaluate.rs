//! Stage 5: PM2, the HCM and the HCM with int8 weights replayed on S2 — the paper's
//! table (Tables 5 and 10) and its figures (Fig 9/12 and 10/13).

use super::{PipelineError, Progress, Stage, CONTACT};
use crate::dataset::Dataset;
use crate::evaluate::{evaluate, ConditionTable};
use crate::export::Blobs;
use crate::figure::{Band, Colour, Figure, NamedFigure, Series, Stroke};
use crate::identify::{curve, simulate_target_with, targets, Target};
use crate::progress::in_stage;
use crate::scenario::Model;

/// The column labels of the models compared, in the table's order.
pub(crate) const MODELS: [&str; 3] = ["PM2", "HCM", "HCM int8"];

/// What stage 5 finds.
pub struct Evaluation {
    /// The table of S2's first condition (the only one of the paper's examples).
    pub(crate) table: ConditionTable,
    /// Fig 9/12 (`contact_force`) and Fig 10/13 (`force_error`).
    pub(crate) figures: Vec<NamedFigure>,
}

/// Replays PM2 (`pm2`, the scenario with PM2 in place) and PM2 + each blob's residual
/// on the `validation` set (S2) and draws the figures.
pub fn evaluate_on_s2(
    pm2: &Model,
    blobs: &Blobs,
    validation: &Dataset,
    progress: &dyn Progress,
) -> Result<Evaluation, PipelineError> {
    in_stage(progress, Stage::Evaluate, 1, || {
        let (hcm, hcm_int8) = blobs.hybrid_models(pm2, CONTACT);
        let columns = [(MODELS[0], pm2), (MODELS[1], &hcm), (MODELS[2], &hcm_int8)];
        let table = evaluate(&columns, validation, CONTACT)?
            .into_iter()
            .next()
            .ok_or(PipelineError::NoValidation)?;
        let target = targets(pm2, validation, CONTACT)?
            .into_iter()
            .next()
            .ok_or(PipelineError::NoValidation)?;
        let figures = figures(&target, pm2, &hcm, validation);
        Ok(Evaluation { table, figures })
    })
}

/// The S2 mean force curve of `target` beside PM2's and the HCM's replays of it (with a
/// zoom on the peak, where the curves overlap), and the error of each (with the zero line
/// and ±2 standard errors of the S2 mean).
fn figures(target: &Target, pm2: &Model, hcm: &Model, validation: &Dataset) -> Vec<NamedFigure> {
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
        // The measured mean last and dotted: over the models' lines, never under them.
        vec![
            series("PM2", 0xd62728, points(&pm2_curve)),
            series("HCM", 0x1f77b4, points(&hcm_curve)),
            series("S2 mean", 0x000000, points(&target.curve)),
        ],
    )
    .with_stroke("S2 mean", Stroke::MEASURED)
    .with_peak_inset();
    let standard_error = mean_standard_error(pm2, validation, target);
    let band = Band {
        label: "±2 standard errors of the S2 mean",
        colour: Colour::hex(0xd9d9d9),
        points: standard_error
            .iter()
            .enumerate()
            .map(|(j, e)| (time(j), -2.0 * e, 2.0 * e))
            .collect(),
    };
    let error = Figure::new(
        "Force error: S2 mean − model",
        "time since touch-down (µs)",
        "force error (N)",
        vec![
            series("PM2", 0xd62728, errors(&pm2_curve)),
            series("HCM", 0x1f77b4, errors(&hcm_curve)),
        ],
    )
    .with_band(band)
    .with_zero_line();
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

/// Standard error s/√n (N) of the S2 mean force curve of `target`, sample by sample,
/// over the condition's runs (NaN with fewer than two runs: no band is drawn).
fn mean_standard_error(model: &Model, data: &Dataset, target: &Target) -> Vec<f64> {
    let len = target.curve.len();
    let curves: Vec<Vec<f64>> = data
        .runs
        .iter()
        .filter(|run| crate::experiment::condition_of(&run.id) == target.condition)
        .filter_map(|run| {
            curve(model, run, CONTACT, target.period, len)
                .ok()
                .flatten()
        })
        .map(|(c, _)| c)
        .collect();
    let n = curves.len() as f64;
    (0..len)
        .map(|j| {
            if n < 2.0 {
                return f64::NAN;
            }
            let squares: f64 = curves
                .iter()
                .map(|c| (c.get(j).copied().unwrap_or(f64::NAN) - target.curve[j]).powi(2))
                .sum();
            (squares / (n - 1.0)).sqrt() / n.sqrt()
        })
        .collect()
}
