//! A joint's residual's training rows from motion alone: what the recorded poses of a
//! mechanism say its joint's law misses, against the physics' own prediction over a few
//! frames — the joint's counterpart of [`super::motion_samples`].
//!
//! For every window frame k of a toss (its window as `hcm predict` finds it) with a frame
//! `horizon` periods on, the mechanism is started at the recorded states of frame k
//! (every link's pose and velocities — or the backward difference from frame k − 1 —
//! assembled onto the joints as a replay's start is) and simulated over `horizon` frames
//! to T = t_{k+h}, sampled densely (the contact rows' `SUBSTEPS` samples per frame). A torque pair τ(s)
//! on the joint at s < T turns it at T by (T − s)·c(s)·τ(s)·ds, c the joint's compliance
//! at the bodies' poses then (`simulate::joint_compliance`): so the row's points are the
//! dense samples, each with the joint's own state [θ (rad), θ̇ (rad/s)] as the network's
//! input and (T − s)·c·ds as its lever, and the row's target is the joint angle the
//! physics misses at T, θ_recorded − θ̂ (rad, wrapped to (−π, π]). First order, as the
//! contact's motion rows: the correction is taken along the uncorrected path.
//!
//! Only flight: a row whose path touches anything is left out — a contact's stiffness
//! is no part of the compliance, and a tracker's poses through an impact say more of
//! the contact than of the joint. The network so learns the joint's torque where the
//! joint alone moves the links, and acts everywhere inside its envelope.

use super::motion_samples::{frame_state, rows_of_runs, State, CLOCK_TOLERANCE, SUBSTEPS};
use super::point_samples::RowTimes;
use super::summed::SummedRow;
use crate::dataset::{Dataset, Run, Sample};
use crate::replay::{assemble, orientation, prepare, InitialState, StateSource};
use crate::replay::{TossError, TossSetup};
use crate::scenario::{JointKind, Model, Pose};
use crate::simulate::{joint_compliance, simulate};
use std::f64::consts::PI;

/// The rows of joint `j` of `physics` (its residual, if any, left out) from the recorded
/// poses of every toss of `data`, over `horizon` frames each, with each row's run (index
/// in the data) and start time (s). In parallel over the tosses, in the data's order:
/// the same rows whatever the thread count.
pub fn joint_rows(
    physics: &Model,
    data: &Dataset,
    j: usize,
    horizon: usize,
) -> Result<(Vec<SummedRow>, RowTimes), TossError> {
    let mut model = physics.clone();
    let fail = |problem: String| TossError::Setup {
        scenario: physics.scenario.name.clone(),
        problem,
    };
    let Some(joint) = model.joints.get_mut(j) else {
        return Err(fail(format!(
            "it has {} joint(s), and joint {j} was asked for",
            physics.joints.len()
        )));
    };
    if joint.kind != JointKind::Revolute {
        return Err(fail(format!(
            "joint `{}` is {}: a joint's residual is learned for a hinge (revolute) only",
            joint.name,
            joint.kind.name()
        )));
    }
    joint.residual = None;
    let setup = TossSetup::new(&model)?;
    rows_of_runs(data, |run| {
        toss_rows(&model, &setup, run, j, horizon.max(1))
    })
}

/// The rows of one toss: one per window frame with a frame `horizon` periods on, of
/// every link, and a path in flight between them.
fn toss_rows(
    model: &Model,
    setup: &TossSetup,
    run: &Run,
    j: usize,
    horizon: usize,
) -> Result<Vec<(SummedRow, f64)>, TossError> {
    let toss = prepare(setup, run)?;
    let tracks: Vec<&[Sample]> = toss.bodies.iter().map(|b| &b.track.samples[..]).collect();
    let period = toss.frame_period;
    let mut rows = Vec::new();
    for k in toss.primary().window.start..tracks[0].len().saturating_sub(horizon) {
        let (start, end) = (tracks[0][k].time, tracks[0][k + horizon].time);
        let on_grid =
            ((end - start) / period - horizon as f64).abs() <= CLOCK_TOLERANCE * horizon as f64;
        // Every link's frames k and k + h at the same instants as the primary's.
        let same = |t: &&[Sample]| {
            t.len() > k + horizon
                && (t[k].time - start).abs() <= CLOCK_TOLERANCE * period
                && (t[k + horizon].time - end).abs() <= CLOCK_TOLERANCE * period
        };
        if !on_grid || !tracks.iter().all(same) {
            continue;
        }
        let Some(states) = link_states(setup, &run.id, &tracks, k)? else {
            continue;
        };
        let recorded = recorded_angle(model, setup, &run.id, &tracks, k + horizon, j)?;
        if let Some(row) = frame_row(
            (model, setup, j),
            &run.id,
            &states,
            recorded,
            (end - start, period),
        )? {
            rows.push((row, start));
        }
    }
    Ok(rows)
}

/// Every link's recorded state at frame `k`, assembled onto the joints; `None` where a
/// link's first frame has no velocities.
fn link_states(
    setup: &TossSetup,
    run: &str,
    tracks: &[&[Sample]],
    k: usize,
) -> Result<Option<Vec<State>>, TossError> {
    let mut states = Vec::with_capacity(tracks.len());
    for (mover, track) in setup.movers.iter().zip(tracks) {
        let Some((position, orientation, velocity, angular_velocity)) =
            frame_state(&mover.name, run, track, k)?
        else {
            return Ok(None);
        };
        states.push(InitialState {
            time: track[k].time,
            position,
            orientation,
            velocity,
            angular_velocity,
            source: StateSource::Recorded,
            fits: None,
        });
    }
    assemble(setup, &mut states);
    Ok(Some(
        (states.into_iter())
            .map(|s| (s.position, s.orientation, s.velocity, s.angular_velocity))
            .collect(),
    ))
}

/// Joint `j`'s recorded angle at frame `k` (rad).
fn recorded_angle(
    model: &Model,
    setup: &TossSetup,
    run: &str,
    tracks: &[&[Sample]],
    k: usize,
    j: usize,
) -> Result<f64, TossError> {
    let joint = &model.joints[j];
    let turned = |body: usize| -> Result<_, TossError> {
        let m = mover_of(setup, body);
        orientation(&setup.movers[m].name, run, &tracks[m][k])
    };
    Ok(joint.angle(&turned(joint.bodies[0])?, &turned(joint.bodies[1])?))
}

/// The mover (index into the setup's movers) that is model body `body`.
fn mover_of(setup: &TossSetup, body: usize) -> usize {
    (setup.movers.iter())
        .position(|m| m.body == body)
        .unwrap_or(0)
}

/// The row of joint `j` from the links' start `states` of run `run` over `span.0`
/// seconds to the `recorded` angle at its end (rad), the path sampled every
/// `span.1 / SUBSTEPS` seconds: `None` when the path touches anything.
fn frame_row(
    (model, setup, j): (&Model, &TossSetup, usize),
    run: &str,
    states: &[State],
    recorded: f64,
    (span, period): (f64, f64),
) -> Result<Option<SummedRow>, TossError> {
    let step = period / SUBSTEPS as f64;
    let path_model = dense_model(model, setup, states, span, step);
    let simulation = simulate(&path_model).map_err(|error| TossError::Simulation {
        run: run.to_owned(),
        error,
    })?;
    if !simulation.events.is_empty() {
        return Ok(None);
    }
    let tracks: Vec<&[Sample]> = (setup.movers.iter())
        .map(|m| {
            simulation
                .run
                .body(&m.name)
                .map_or(&[][..], |t| &t.samples[..])
        })
        .collect();
    let samples = tracks.iter().map(|t| t.len()).min().unwrap_or(0);
    let Some(end) = tracks[0].get(samples.wrapping_sub(1)).map(|s| s.time) else {
        return Ok(None);
    };
    let joint = &model.joints[j];
    let mut points = Vec::with_capacity(samples);
    let mut predicted = f64::NAN;
    for i in 0..samples {
        let poses = path_poses(model, setup, run, &tracks, i)?;
        let (p1, p2) = (&poses[joint.bodies[0]], &poses[joint.bodies[1]]);
        let axis = p1.orientation * joint.axis.into_inner();
        let angle = joint.angle(&p1.orientation, &p2.orientation);
        let rate = (p2.angular_velocity - p1.angular_velocity).dot(&axis);
        let lever = (end - tracks[0][i].time) * step * joint_compliance(model, j, &poses);
        points.push((vec![angle, rate], vec![lever]));
        predicted = angle;
    }
    let missed = wrapped(recorded - predicted);
    Ok(missed.is_finite().then(|| SummedRow {
        points,
        target: vec![missed],
    }))
}

/// Every body's pose at dense sample `i` of the path (`tracks`, one per mover); the
/// fixed bodies where the model places them.
fn path_poses(
    model: &Model,
    setup: &TossSetup,
    run: &str,
    tracks: &[&[Sample]],
    i: usize,
) -> Result<Vec<Pose>, TossError> {
    let mut poses: Vec<Pose> = (model.bodies.iter())
        .map(|b| Pose {
            position: b.position,
            orientation: b.orientation,
            velocity: b.velocity,
            angular_velocity: b.angular_velocity,
        })
        .collect();
    for (mover, track) in setup.movers.iter().zip(tracks) {
        let sample = &track[i];
        poses[mover.body] = Pose {
            position: sample.position.into(),
            orientation: orientation(&mover.name, run, sample)?,
            velocity: sample.velocity.into(),
            angular_velocity: sample.angular_velocity.into(),
        };
    }
    Ok(poses)
}

/// `model` started with its movers at `states`, run for `span` (s) and recording them
/// every `step` (s).
fn dense_model(model: &Model, setup: &TossSetup, states: &[State], span: f64, step: f64) -> Model {
    let mut out = model.clone();
    for (mover, state) in setup.movers.iter().zip(states) {
        let body = &mut out.bodies[mover.body];
        (body.position, body.orientation) = (state.0, state.1);
        (body.velocity, body.angular_velocity) = (state.2, state.3);
    }
    let scenario = &mut out.scenario;
    scenario.simulation.end_time = span * (1.0 + 1e-9);
    scenario.simulation.stop_after_contacts = 0;
    scenario.record.contact_sample_period = step;
    scenario.record.flight_sample_period = step;
    scenario.record.contact_margin = 0.0;
    scenario.record.bodies = setup.movers.iter().map(|m| m.name.clone()).collect();
    out
}

/// `angle` (rad) wrapped to (−π, π].
fn wrapped(angle: f64) -> f64 {
    let a = angle.rem_euclid(2.0 * PI);
    if a > PI {
        a - 2.0 * PI
    } else {
        a
    }
}
