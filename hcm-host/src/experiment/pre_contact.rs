//! A 3D run's recorded state just before its first contact, and the model that replays
//! the run from there — how identification and evaluation replay each run of a
//! generated (or measured) experiment.
//!
//! The data carry it: every recorded sample holds the moving body's 13 state components
//! (position, orientation quaternion, velocity, angular velocity; world frame), and the
//! recorder samples at the contact rate from `record.contact_margin` before each
//! touch-down. The pre-contact state is the last sample at or before the first
//! touch-down of any contact of the run (located from the recorded poses, as
//! `hcm indicators` does); every law gives zero force there, so replaying from it
//! changes nothing but the start time.

use crate::dataset::{Run, Sample};
use crate::indicators::{pair_events_from_run, IndicatorError};
use crate::scenario::Model;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// How far a recorded quaternion's norm may lie from 1 (–): far above the simulator's
/// drift (4 ulps) and a round trip through the data file (exact), far below what would
/// change a replay.
const UNIT_TOLERANCE: f64 = 1e-6;

/// The recorded state of every moving body of a run just before its first contact.
#[derive(Clone, Debug, PartialEq)]
pub struct PreContact {
    /// Run id.
    pub run: String,
    /// Time of the samples (s); a replay's t = 0 is this time.
    pub time: f64,
    /// The first touch-down located in the data (s).
    pub touch_down: f64,
    /// (index of the body in the model, its sample at `time`) for every moving body.
    pub states: Vec<(usize, Sample)>,
}

/// Why a run has no usable pre-contact state.
#[derive(Debug, thiserror::Error)]
pub enum PreContactError {
    /// The run's contacts could not be located.
    #[error(transparent)]
    Indicators(#[from] IndicatorError),
    /// The run never completes a contact.
    #[error("run `{run}` has no completed contact, so no pre-contact state to replay from")]
    NoContact {
        /// The run's id.
        run: String,
    },
    /// A moving body has no sample before the first touch-down.
    #[error(
        "run `{run}`, body `{body}`: no sample at or before the first touch-down at \
         t = {touch_down} s; record from before the contact (record.contact_margin)"
    )]
    NoSampleBefore {
        /// The run's id.
        run: String,
        /// The moving body's name.
        body: String,
        /// Time of the run's first touch-down (s).
        touch_down: f64,
    },
    /// Two moving bodies' last samples before the contact are at different times.
    #[error(
        "run `{run}`: bodies `{first}` and `{second}` have their last samples before the \
         first contact at different times ({first_time} s, {second_time} s); record them \
         on one clock"
    )]
    DifferentClocks {
        /// The run's id.
        run: String,
        /// The first moving body's name.
        first: String,
        /// The second moving body's name.
        second: String,
        /// Time of the first body's last sample before the contact (s).
        first_time: f64,
        /// Time of the second body's last sample before the contact (s).
        second_time: f64,
    },
    /// The recorded orientation is not a unit quaternion.
    #[error(
        "run `{run}`, body `{body}`, t = {time} s: columns `qw`, `qx`, `qy`, `qz` hold a \
         quaternion of norm {norm}; a replay needs a unit quaternion (within {UNIT_TOLERANCE})"
    )]
    NotUnit {
        /// The run's id.
        run: String,
        /// The body's name.
        body: String,
        /// Time of the sample (s).
        time: f64,
        /// Euclidean norm of the recorded quaternion (qw, qx, qy, qz) (–).
        norm: f64,
    },
}

/// The pre-contact state of every run of `runs`, in order (see the module
/// documentation); the first run without one is an error naming it.
pub fn pre_contact_states(model: &Model, runs: &[Run]) -> Result<Vec<PreContact>, PreContactError> {
    runs.iter().map(|run| pre_contact(model, run)).collect()
}

/// The pre-contact state of one run.
fn pre_contact(model: &Model, run: &Run) -> Result<PreContact, PreContactError> {
    let events = pair_events_from_run(model, run)?;
    let touch_down = (events.iter().map(|e| e.event.touch_down))
        .min_by(f64::total_cmp)
        .ok_or_else(|| PreContactError::NoContact {
            run: run.id.clone(),
        })?;
    state_before(model, run, touch_down)
}

/// The recorded state of every moving body of `run` at its last sample at or before
/// `touch_down` (s): where a replay of the contact event that starts then begins (the
/// first event's is the run's [`PreContact`]).
pub fn state_before(
    model: &Model,
    run: &Run,
    touch_down: f64,
) -> Result<PreContact, PreContactError> {
    let mut states: Vec<(usize, Sample)> = Vec::new();
    for (index, body) in model.bodies.iter().enumerate().filter(|(_, b)| !b.fixed) {
        let track = run
            .body(&body.name)
            .ok_or_else(|| IndicatorError::MissingBody {
                run: run.id.clone(),
                body: body.name.clone(),
            })?;
        let sample = (track.samples.iter())
            .take_while(|s| s.time <= touch_down)
            .last()
            .ok_or_else(|| PreContactError::NoSampleBefore {
                run: run.id.clone(),
                body: body.name.clone(),
                touch_down,
            })?;
        let norm = quaternion(sample).norm();
        // NaN components give a NaN norm, refused too.
        let unit = (norm - 1.0).abs() <= UNIT_TOLERANCE;
        if !unit {
            return Err(PreContactError::NotUnit {
                run: run.id.clone(),
                body: body.name.clone(),
                time: sample.time,
                norm,
            });
        }
        if let Some((first, earlier)) = states.first() {
            if earlier.time != sample.time {
                return Err(PreContactError::DifferentClocks {
                    run: run.id.clone(),
                    first: model.bodies[*first].name.clone(),
                    second: body.name.clone(),
                    first_time: earlier.time,
                    second_time: sample.time,
                });
            }
        }
        states.push((index, sample.clone()));
    }
    let time = states.first().map_or(0.0, |(_, s)| s.time);
    Ok(PreContact {
        run: run.id.clone(),
        time,
        touch_down,
        states,
    })
}

/// `model` started from `pre`: each moving body's position, orientation (normalised),
/// velocity and angular velocity set to its recorded sample, and the end time moved
/// back by the samples' time, so the replay ends where the run did. The replay's
/// times are the run's minus [`PreContact::time`].
pub fn replay_model(model: &Model, pre: &PreContact) -> Model {
    let mut replay = model.clone();
    for (index, sample) in &pre.states {
        let body = &mut replay.bodies[*index];
        body.position = Vector3::from(sample.position);
        body.orientation = UnitQuaternion::from_quaternion(quaternion(sample));
        body.velocity = Vector3::from(sample.velocity);
        body.angular_velocity = Vector3::from(sample.angular_velocity);
    }
    replay.scenario.simulation.end_time -= pre.time;
    replay
}

/// A sample's orientation `[w, x, y, z]` as a quaternion (not normalised).
fn quaternion(sample: &Sample) -> Quaternion<f64> {
    let [w, x, y, z] = sample.orientation;
    Quaternion::new(w, x, y, z)
}
