//! Each toss's scores as a CSV file (`hcm predict --scores`, and the inputs of
//! `benches/peers/` that `hcm reproduce cube-toss --peers` writes): the window, how the
//! initial state was found, the prediction's and the frozen pose's errors, and the
//! initial state itself, so that another simulator starts from the very same state.

use super::{InitialState, PathForecast, StateSource, TossEvaluation};
use crate::output::write_atomically;
use anyhow::Context;
use std::path::Path;

/// The initial state's columns of the scores CSV: the primary body's state at the
/// window start the replay started from — centre of mass (m), orientation quaternion
/// (body → world), velocity (m/s) and angular velocity (rad/s), world frame — so that
/// another simulator can start from the very same state (`benches/peers/`).
const INITIAL_STATE_COLUMNS: [&str; 13] = [
    "p0x", "p0y", "p0z", "q0w", "q0x", "q0y", "q0z", "v0x", "v0y", "v0z", "w0x", "w0y", "w0z",
];

/// The forecast's columns of the scores CSV, when an ensemble was scored
/// ([`PathForecast`]): energy scores (% of the width, °), the CRPS of x, y, z (% of the
/// width), the shares of the recorded coordinates inside the 50 % and 90 % bands, and
/// the members that ran and failed.
const FORECAST_COLUMNS: [&str; 9] = [
    "energy_position",
    "energy_rotation",
    "crps_x",
    "crps_y",
    "crps_z",
    "inside_50",
    "inside_90",
    "members",
    "failed",
];

/// Writes each toss's scores as CSV, atomically: run, frames, window start (s), initial
/// state source, position (%) and rotation (°) errors of the prediction and of the
/// frozen pose, then the initial state columns, then (given `forecasts`, one per toss)
/// the forecast's columns. With several moving bodies (a mechanism's links) a `body`
/// column follows `run`: per toss one row per body (its own scores, in % of its own
/// width, and its own initial state), then a row `all` with the toss's scores (their
/// means), no initial state, and the forecast's columns.
pub fn write_scores(
    path: &Path,
    evaluations: &[TossEvaluation],
    forecasts: Option<&[PathForecast]>,
) -> anyhow::Result<()> {
    let several = evaluations.iter().any(|e| !e.score.bodies.is_empty());
    write_atomically(path, |out| -> anyhow::Result<()> {
        let mut csv = csv::Writer::from_writer(out);
        let forecast_columns = forecasts.map_or(&[][..], |_| &FORECAST_COLUMNS[..]);
        csv.write_record(
            std::iter::once("run")
                .chain(several.then_some("body"))
                .chain(SCORE_COLUMNS)
                .chain(INITIAL_STATE_COLUMNS)
                .chain(forecast_columns.iter().copied()),
        )?;
        for (i, e) in evaluations.iter().enumerate() {
            let forecast: Vec<String> = forecasts.and_then(|f| f.get(i)).map_or(Vec::new(), |f| {
                let shares = super::band_shares(&f.coverage);
                [
                    f.position, f.rotation, f.crps[0], f.crps[1], f.crps[2], shares[0], shares[1],
                ]
                .map(|v| v.to_string())
                .into_iter()
                .chain([f.members.to_string(), f.failed.to_string()])
                .collect()
            });
            for row in toss_rows(e, several, forecast) {
                csv.write_record(row)?;
            }
        }
        csv.flush()?;
        Ok(())
    })
    .with_context(|| format!("writing {}", path.display()))
}

/// The rows of one toss: one without `several` bodies; else one per body and `all`.
fn toss_rows(e: &TossEvaluation, several: bool, forecast: Vec<String>) -> Vec<Vec<String>> {
    let run = e.score.run.clone();
    let start = |i: &InitialState| [i.time.to_string(), source(i)];
    let totals = errors(
        (e.score.position_error, e.score.rotation_error),
        (e.baseline.position_error, e.baseline.rotation_error),
    );
    let frames = e.score.frames.to_string();
    if !several {
        let initial = &e.prediction.initial;
        let row = [run, frames]
            .into_iter()
            .chain(start(initial))
            .chain(totals);
        return vec![row.chain(state(initial)).chain(forecast).collect()];
    }
    let initials = std::iter::once(&e.prediction.initial)
        .chain(e.prediction.companions.iter().map(|c| &c.initial));
    let mut rows: Vec<Vec<String>> = (e.score.bodies.iter().zip(&e.baseline.bodies).zip(initials))
        .map(|((body, frozen), initial)| {
            let head = [run.clone(), body.body.clone(), body.frames.to_string()];
            (head.into_iter())
                .chain(start(initial))
                .chain(errors(
                    (body.position_error, body.rotation_error),
                    (frozen.position_error, frozen.rotation_error),
                ))
                .chain(state(initial))
                .chain(forecast.iter().map(|_| String::new()))
                .collect()
        })
        .collect();
    let head = [run, "all".to_owned(), frames, String::new(), String::new()];
    rows.push(
        (head.into_iter())
            .chain(totals)
            .chain(INITIAL_STATE_COLUMNS.iter().map(|_| String::new()))
            .chain(forecast)
            .collect(),
    );
    rows
}

/// The error columns: the model's position (%) and rotation (°) errors, then the frozen
/// pose's.
fn errors(model: (f64, f64), frozen: (f64, f64)) -> [String; 4] {
    [model.0, model.1, frozen.0, frozen.1].map(|v| v.to_string())
}

/// The columns between `run` (and `body`) and the initial state.
const SCORE_COLUMNS: [&str; 7] = [
    "frames",
    "window_start",
    "initial_state",
    "position_error",
    "rotation_error",
    "frozen_position_error",
    "frozen_rotation_error",
];

/// How a start state was found, as the `initial_state` column says it.
fn source(initial: &InitialState) -> String {
    match initial.source {
        StateSource::FreeFlightFit { frames } => format!("fit {frames} frames"),
        StateSource::Recorded => "recorded".to_owned(),
    }
}

/// The [`INITIAL_STATE_COLUMNS`] of `initial`.
fn state(initial: &InitialState) -> impl Iterator<Item = String> {
    let q = initial.orientation.quaternion();
    let quaternion = [q.w, q.i, q.j, q.k];
    let values: Vec<f64> = (initial.position.iter())
        .chain(&quaternion)
        .chain(initial.velocity.iter())
        .chain(initial.angular_velocity.iter())
        .copied()
        .collect();
    values.into_iter().map(|v| v.to_string())
}
