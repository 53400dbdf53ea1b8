//! Each toss's scores as a CSV file (`hcm predict --scores`, and the inputs of
//! `benches/peers/` that `hcm reproduce cube-toss --peers` writes): the window, how the
//! initial state was found, the prediction's and the frozen pose's errors, and the
//! initial state itself, so that another simulator starts from the very same state.

use super::{StateSource, TossEvaluation};
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

/// Writes each toss's scores as CSV, atomically: run, frames, window start (s), initial
/// state source, position (%) and rotation (°) errors of the prediction and of the
/// frozen pose, then the initial state columns.
pub fn write_scores(path: &Path, evaluations: &[TossEvaluation]) -> anyhow::Result<()> {
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
            .chain(INITIAL_STATE_COLUMNS),
        )?;
        for e in evaluations {
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
                .chain(state),
            )?;
        }
        csv.flush()?;
        Ok(())
    })
    .with_context(|| format!("writing {}", path.display()))
}
