//! Each toss's scores as a CSV file (`hcm predict --scores`, and the inputs of
//! `benches/peers/` that `hcm reproduce cube-toss --peers` writes): the window, how the
//! initial state was found, the prediction's and the frozen pose's errors, and the
//! initial state itself, so that another simulator starts from the very same state.

use super::{PathForecast, StateSource, TossEvaluation};
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
/// the forecast's columns.
pub fn write_scores(
    path: &Path,
    evaluations: &[TossEvaluation],
    forecasts: Option<&[PathForecast]>,
) -> anyhow::Result<()> {
    write_atomically(path, |out| -> anyhow::Result<()> {
        let mut csv = csv::Writer::from_writer(out);
        csv.write_record(
            [
                "run",
                "frames",
                "window_start",
                "initial_state",
                "position_error",
                "rotation_error",
                "frozen_position_error",
                "frozen_rotation_error",
            ]
            .into_iter()
            .chain(INITIAL_STATE_COLUMNS)
            .chain(
                forecasts
                    .map_or(&[][..], |_| &FORECAST_COLUMNS[..])
                    .iter()
                    .copied(),
            ),
        )?;
        for (i, e) in evaluations.iter().enumerate() {
            let forecast = forecasts.and_then(|f| f.get(i)).map(|f| {
                let shares = super::band_shares(&f.coverage);
                [
                    f.position, f.rotation, f.crps[0], f.crps[1], f.crps[2], shares[0], shares[1],
                ]
                .map(|v| v.to_string())
                .into_iter()
                .chain([f.members.to_string(), f.failed.to_string()])
            });
            let source = match e.prediction.initial.source {
                StateSource::FreeFlightFit { frames } => format!("fit {frames} frames"),
                StateSource::Recorded => "recorded".to_owned(),
            };
            let initial = &e.prediction.initial;
            let q = initial.orientation.quaternion();
            let quaternion = [q.w, q.i, q.j, q.k];
            let state = (initial.position.iter())
                .chain(&quaternion)
                .chain(initial.velocity.iter())
                .chain(initial.angular_velocity.iter())
                .map(f64::to_string);
            csv.write_record(
                [
                    e.score.run.clone(),
                    e.score.frames.to_string(),
                    initial.time.to_string(),
                    source,
                    e.score.position_error.to_string(),
                    e.score.rotation_error.to_string(),
                    e.baseline.position_error.to_string(),
                    e.baseline.rotation_error.to_string(),
                ]
                .into_iter()
                .chain(state)
                .chain(forecast.into_iter().flatten()),
            )?;
        }
        csv.flush()?;
        Ok(())
    })
    .with_context(|| format!("writing {}", path.display()))
}
