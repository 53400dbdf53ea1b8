//! The contact-frame residual's training rows from motion alone (the
//! residual learned from motion): no sensor measured a force, so the target is what
//! the recorded poses imply against the physics' own prediction over a few frames.
//!
//! For every window frame k of a toss (its window as `hcm predict` finds it) the
//! physics is started at the recorded state of frame k and simulated over `horizon`
//! frames to T = t_{k+h}, sampled densely ([`SUBSTEPS`] samples per frame). The row's
//! target is the pose the physics misses at T, as the wrench-impulse moment that would
//! move the free body there: (m·(p − p̂), I_w·θ), θ the rotation vector of q·q̂⁻¹ and I_w
//! the body's inertia in the world frame at the predicted pose (N·s², N·m·s²). A
//! wrench w(τ) acting on a free body over dτ at τ < T moves its pose at T by
//! (T − τ)·dτ·(w_F/m, I_w⁻¹·w_τ), so each dense sample's touching points enter the row
//! with their levers ([`super::point_samples`]) times (T − τ)·dτ: the network's outputs
//! along the physics' own path add up to the pose it misses (first order: the
//! correction is taken along the uncorrected path, and the law does not react to it).
//!
//! The state at frame k is the recorded pose with the recorded velocities; a camera's
//! data without them take the backward difference from frame k − 1 (a first frame
//! without velocities gives no row). A frame whose start already touches gives no row:
//! a tracker's resting pose lies a millimetre into the table, and the law's push out of
//! it would be the whole target. Where the physics' own replay of the toss has touched
//! for a frame period or longer (resting, sliding, rolling), rows of zero target say
//! that the residual adds nothing there.

use super::point_samples::{touching_points, RowTimes};
use super::summed::SummedRow;
use crate::dataset::{Channel, Dataset, Run, Sample};
use crate::identify::RecordedContact;
use crate::replay::orientation;
use crate::replay::prepare;
use crate::replay::{TossError, TossSetup};
use crate::scenario::Model;
use crate::simulate::simulate;
use nalgebra::{UnitQuaternion, Vector3};
use rayon::prelude::*;

/// Dense samples per frame of the physics' path (–).
pub const SUBSTEPS: usize = 16;

/// How far a frame's time may lie off the grid of frame periods (as a fraction of one):
/// a row needs its end frame exactly `horizon` periods on.
pub(super) const CLOCK_TOLERANCE: f64 = 1e-3;

/// The rows of contact `c` of `physics` (its residual, if any, left out) from the
/// recorded poses of every toss of `data`, over `horizon` frames each, with each row's
/// run (index in the data) and start time (s). In parallel over the tosses, in the
/// data's order: the same rows whatever the thread count.
pub fn motion_rows(
    physics: &Model,
    data: &Dataset,
    c: usize,
    horizon: usize,
) -> Result<(Vec<SummedRow>, RowTimes), TossError> {
    let mut model = physics.clone();
    let Some(contact) = model.contacts.get_mut(c) else {
        return Err(TossError::Setup {
            scenario: physics.scenario.name.clone(),
            problem: format!(
                "it has {} contact(s), and contact {c} was asked for",
                physics.contacts.len()
            ),
        });
    };
    contact.model.residual = None;
    if let Some(joint) = physics.joints.first() {
        // Its dense samples move the primary body alone: a link would leave its joint.
        return Err(TossError::Setup {
            scenario: physics.scenario.name.clone(),
            problem: format!(
                "joint `{}`: a contact's residual is not trained from the poses of a mechanism \
                 yet (its samples move one body); the joint's own torque residual is (`hcm \
                 train` on the mechanism's poses), and `hcm predict` replays it",
                joint.name
            ),
        });
    }
    let setup = TossSetup::new(&model)?;
    rows_of_runs(data, |run| {
        toss_rows(&model, &setup, run, c, horizon.max(1))
    })
}

/// Every run's rows from `of_run` (each row with its start time, s), in parallel over the
/// runs and gathered in the data's order with each row's run: the same rows whatever the
/// thread count. The first run that fails stops it.
pub(super) fn rows_of_runs(
    data: &Dataset,
    of_run: impl Fn(&Run) -> Result<Vec<(SummedRow, f64)>, TossError> + Sync + Send,
) -> Result<(Vec<SummedRow>, RowTimes), TossError> {
    let per_run: Vec<Result<Vec<(SummedRow, f64)>, TossError>> =
        data.runs.par_iter().map(&of_run).collect();
    let (mut rows, mut at) = (Vec::new(), Vec::new());
    for (index, result) in per_run.into_iter().enumerate() {
        for (row, time) in result? {
            rows.push(row);
            at.push((index, time));
        }
    }
    Ok((rows, at))
}

/// The rows of one toss: one per window frame with a frame `horizon` periods on and a
/// touching point on the physics' path between them.
fn toss_rows(
    model: &Model,
    setup: &TossSetup,
    run: &Run,
    c: usize,
    horizon: usize,
) -> Result<Vec<(SummedRow, f64)>, TossError> {
    let toss = prepare(setup, run)?;
    let body = toss.primary();
    let frames = &body.track.samples;
    let period = toss.frame_period;
    let mut rows = Vec::new();
    for k in body.window.start..frames.len().saturating_sub(horizon) {
        let (start, end) = (&frames[k], &frames[k + horizon]);
        let periods = (end.time - start.time) / period;
        if (periods - horizon as f64).abs() > CLOCK_TOLERANCE * horizon as f64 {
            continue;
        }
        let Some(state) = frame_state(&setup.name, &run.id, frames, k)? else {
            continue;
        };
        let measured = (
            Vector3::from(end.position),
            orientation(&setup.name, &run.id, end)?,
        );
        let span = (end.time - start.time, period / SUBSTEPS as f64);
        if let Some(row) = frame_row((model, setup, c), &run.id, &state, measured, span)? {
            rows.push((row, start.time));
        }
    }
    rows.extend(sustained_rows((model, setup, c), &toss, horizon)?);
    Ok(rows)
}

/// Rows of zero target where the physics' own replay of the toss has been in contact
/// for a whole frame period or longer (resting, sliding, rolling): there the tracker's
/// poses say nothing the physics can be started from (a millimetre of noise against a
/// law's micrometres), and the residual learns to add nothing. Each row holds
/// `horizon` frame periods of such samples, weighted as the frame rows are.
fn sustained_rows(
    (model, setup, c): (&Model, &TossSetup, usize),
    toss: &crate::replay::PreparedToss<'_>,
    horizon: usize,
) -> Result<Vec<(SummedRow, f64)>, TossError> {
    let step = toss.frame_period / SUBSTEPS as f64;
    let mut replay = crate::replay::replay_model(model, setup, toss);
    replay.scenario.record.contact_sample_period = step;
    replay.scenario.record.flight_sample_period = step;
    let simulation = simulate(&replay).map_err(|error| TossError::Simulation {
        run: toss.run.to_owned(),
        error,
    })?;
    let single = Dataset {
        runs: vec![simulation.run],
    };
    // As in `frame_row`: refused only when the replay never touches.
    let Ok(recorded) = RecordedContact::from_data(&replay, &single, c) else {
        return Ok(Vec::new());
    };
    let contact = &replay.contacts[c].model;
    let (span, start) = (
        horizon as f64 * toss.frame_period,
        toss.primary().initial.time,
    );
    let (mut rows, mut run_start, mut row_start): (Vec<(SummedRow, f64)>, f64, f64) =
        (Vec::new(), f64::NAN, f64::NAN);
    let mut last = f64::NEG_INFINITY;
    for sample in &recorded.samples {
        if sample.time - last > 1.5 * step {
            run_start = sample.time;
        }
        last = sample.time;
        if sample.time - run_start < toss.frame_period {
            continue;
        }
        if rows.is_empty() || sample.time >= row_start + span {
            row_start = sample.time;
            let target = vec![0.0; 6];
            rows.push((
                SummedRow {
                    points: Vec::new(),
                    target,
                },
                start + row_start,
            ));
        }
        let weight = (row_start + span - sample.time) * step;
        let row = &mut rows.last_mut().expect("a row was pushed").0;
        row.points
            .extend(weighted_points(contact, &recorded, sample, weight));
    }
    Ok(rows)
}

/// A body's state: position (m), orientation, velocity (m/s), angular velocity (rad/s),
/// world frame.
pub(super) type State = (
    Vector3<f64>,
    UnitQuaternion<f64>,
    Vector3<f64>,
    Vector3<f64>,
);

/// The recorded state of body `body` at frame `k`: its pose, and its recorded velocities or else the
/// backward difference from frame k − 1 (`None` at a first frame without them).
pub(super) fn frame_state(
    body: &str,
    run: &str,
    frames: &[Sample],
    k: usize,
) -> Result<Option<State>, TossError> {
    let frame = &frames[k];
    let q = orientation(body, run, frame)?;
    let p = Vector3::from(frame.position);
    if frame.has(Channel::Velocity) && frame.has(Channel::AngularVelocity) {
        let (v, w) = (frame.velocity, frame.angular_velocity);
        return Ok(Some((p, q, Vector3::from(v), Vector3::from(w))));
    }
    let Some(before) = k.checked_sub(1).map(|j| &frames[j]) else {
        return Ok(None);
    };
    let dt = frame.time - before.time;
    let turn = (q * orientation(body, run, before)?.inverse()).scaled_axis();
    let v = (p - Vector3::from(before.position)) / dt;
    Ok(Some((p, q, v, turn / dt)))
}

/// The row of contact `c` of `model` from one start `state` of run `run` over
/// `span.0` seconds to the `measured` pose at its end, the path sampled every `span.1`
/// seconds: `None` when nothing touches on the physics' path.
fn frame_row(
    (model, setup, c): (&Model, &TossSetup, usize),
    run: &str,
    state: &State,
    measured: (Vector3<f64>, UnitQuaternion<f64>),
    (span, step): (f64, f64),
) -> Result<Option<SummedRow>, TossError> {
    let path_model = dense_model(model, setup, state, span, step);
    let simulation = simulate(&path_model).map_err(|error| TossError::Simulation {
        run: run.to_owned(),
        error,
    })?;
    let path = simulation.run;
    let Some(last) = (path.body(&setup.name)).and_then(|t| t.samples.last().cloned()) else {
        return Ok(None);
    };
    let predicted = (
        Vector3::from(last.position),
        orientation(&setup.name, run, &last)?,
    );
    let single = Dataset { runs: vec![path] };
    // The path's samples hold the simulator's own force, and the bodies are the
    // scenario's: the only refusal left is a path that never touches — no row.
    let Ok(recorded) = RecordedContact::from_data(&path_model, &single, c) else {
        return Ok(None);
    };
    // A start already touching is a recorded pose the physics does not hold at rest
    // (the tracker's millimetre against the law's micrometres): the law's push out of
    // it would be the row's whole target.
    if recorded
        .samples
        .first()
        .is_some_and(|s| s.time < 0.5 * step)
    {
        return Ok(None);
    }
    let contact = &path_model.contacts[c].model;
    let mut points = Vec::new();
    for sample in &recorded.samples {
        let weight = (last.time - sample.time) * step;
        points.extend(weighted_points(contact, &recorded, sample, weight));
    }
    if points.is_empty() {
        return Ok(None);
    }
    let target = missed_moment(model, setup, predicted, measured);
    Ok(Some(SummedRow { points, target }))
}

/// `sample`'s touching points with their levers times `weight` (s²): (T − τ)·dτ, what
/// a wrench at τ moves the free body's pose at T by.
fn weighted_points(
    contact: &crate::residual::HostContactModel,
    recorded: &RecordedContact,
    sample: &crate::identify::RecordedSample,
    weight: f64,
) -> Vec<(Vec<f64>, Vec<f64>)> {
    let mut points = touching_points(contact, recorded, sample);
    for (_, lever) in &mut points {
        lever.iter_mut().for_each(|l| *l *= weight);
    }
    points
}

/// `model` started at `state`, run for `span` (s) and recording the body every `step`
/// (s), in contact or not.
fn dense_model(model: &Model, setup: &TossSetup, state: &State, span: f64, step: f64) -> Model {
    let mut out = model.clone();
    let body = &mut out.bodies[setup.body];
    (body.position, body.orientation) = (state.0, state.1);
    (body.velocity, body.angular_velocity) = (state.2, state.3);
    let scenario = &mut out.scenario;
    scenario.simulation.end_time = span * (1.0 + 1e-9);
    scenario.simulation.stop_after_contacts = 0;
    scenario.record.contact_sample_period = step;
    scenario.record.flight_sample_period = step;
    scenario.record.contact_margin = 0.0;
    scenario.record.bodies = vec![setup.name.clone()];
    out
}

/// The pose `predicted` misses against `measured`, as the wrench-impulse moment on the
/// free body that moves it there: (m·Δp, I_w·θ) (N·s², N·m·s²).
fn missed_moment(
    model: &Model,
    setup: &TossSetup,
    predicted: (Vector3<f64>, UnitQuaternion<f64>),
    measured: (Vector3<f64>, UnitQuaternion<f64>),
) -> Vec<f64> {
    let body = &model.bodies[setup.body];
    let shift = body.mass * (measured.0 - predicted.0);
    let turn = (measured.1 * predicted.1.inverse()).scaled_axis();
    let rotation = predicted.1.to_rotation_matrix();
    let inertia = rotation.matrix() * body.inertia * rotation.matrix().transpose();
    let moment = inertia * turn;
    vec![shift.x, shift.y, shift.z, moment.x, moment.y, moment.z]
}
