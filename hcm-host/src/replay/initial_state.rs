//! The state a toss's replay starts from, re-estimated from the free-flight frames up
//! to its window start. A tracker's velocities are differences of noisy poses (the
//! ContactNets ones jump by 0.1 m/s from frame to frame); before the window no corner
//! can touch, so the motion there is known in form and a fit over several frames
//! averages the noise out:
//!
//! - position: p(τ) = p₀ + v·τ + ½·g·τ², least squares per axis with g the scenario's
//!   gravity (a parabola in z with g = 9.81 m/s² and straight lines in x and y for the
//!   tosses), τ the time from the window start;
//! - orientation: R(τ) = exp([a + ω·τ]ₓ)·R_w with R_w the recorded orientation at the
//!   window start, the rotation vectors log(R_i·R_wᵀ) fitted by a straight line per
//!   component: constant angular velocity ω (world frame), exact in free flight for a
//!   body of isotropic inertia such as the cube (8.1e-4 kg·m² about every axis); the
//!   start orientation is exp(aₓ)·R_w.
//!
//! The fit uses the last `FIT_FRAMES` frames up to and including the window start.
//! With fewer than `MIN_FIT_FRAMES` (a toss filmed from just before its landing) the
//! recorded pose, velocity and angular velocity at the window start are used as they
//! are, and [`StateSource::Recorded`] says so.

use super::{TossError, TossSetup, Window};
use crate::dataset::{BodyTrack, Channel, FlightFit, Sample};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Frames fitted up to the window start (–): 8 frames are 47 ms at 148 Hz, enough to
/// average the tracker's noise while the cube is surely in free flight.
pub(crate) const FIT_FRAMES: usize = 8;

/// Fewest frames fitted (–): two unknowns per axis, and two more frames to average.
pub(crate) const MIN_FIT_FRAMES: usize = 4;

/// How far a recorded quaternion's norm may lie from 1 (–) before it is refused.
const UNIT_TOLERANCE: f64 = 1e-6;

/// Where the initial state came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StateSource {
    /// Fitted to this many free-flight frames ending at the window start.
    FreeFlightFit {
        /// Frames fitted (–).
        frames: usize,
    },
    /// The recorded state at the window start, too few frames before it to fit.
    Recorded,
}

/// The body's state at the window start.
#[derive(Clone, Debug, PartialEq)]
pub struct InitialState {
    /// Time of the window start in the data (s).
    pub time: f64,
    /// Centre-of-mass position (m, world frame).
    pub position: Vector3<f64>,
    /// Orientation, body → world.
    pub orientation: UnitQuaternion<f64>,
    /// Centre-of-mass velocity (m/s, world frame).
    pub velocity: Vector3<f64>,
    /// Angular velocity ω (rad/s, world frame).
    pub angular_velocity: Vector3<f64>,
    /// How it was obtained.
    pub source: StateSource,
    /// The free-flight fits it came from — of the position, and of the rotation vector
    /// relative to the recorded window-start orientation — with their covariances: how
    /// far the tracker's noise leaves the state uncertain (`super::ensemble`). None
    /// for a recorded state.
    pub(crate) fits: Option<[FlightFit; 2]>,
}

/// The initial state of `run`'s toss of the primary body at `window.start` (see the
/// module documentation).
pub fn estimate_initial_state(
    setup: &TossSetup,
    run: &str,
    track: &BodyTrack,
    window: &Window,
) -> Result<InitialState, TossError> {
    estimate_state(&setup.name, setup.gravity, run, track, window)
}

/// The state of body `name` (its `track` of `run`) at `window.start`, its free-flight
/// fit under the acceleration `gravity` (m/s²): the scenario's for a body in flight,
/// zero for one resting or sliding on another (a supported body).
pub(crate) fn estimate_state(
    name: &str,
    gravity: Vector3<f64>,
    run: &str,
    track: &BodyTrack,
    window: &Window,
) -> Result<InitialState, TossError> {
    let start = &track.samples[window.start];
    let first = (window.start + 1).saturating_sub(FIT_FRAMES);
    let frames = &track.samples[first..=window.start];
    let start_orientation = orientation(name, run, start)?;
    if frames.len() < MIN_FIT_FRAMES {
        return recorded(name, run, start, start_orientation);
    }
    // The data's free-flight fit (`dataset::FlightFit`, the rig reconstruction's),
    // referred to the window start: under gravity for the position, at zero
    // acceleration for the rotation vectors.
    let track_fit = |points: &[(f64, [f64; 3])], gravity: [f64; 3]| {
        FlightFit::fit(points, gravity, start.time).ok_or_else(|| TossError::Frame {
            run: run.to_owned(),
            time: start.time,
            problem: "the frames up to the window start share one time".into(),
        })
    };
    let positions: Vec<(f64, [f64; 3])> = frames.iter().map(|s| (s.time, s.position)).collect();
    let flight = track_fit(&positions, gravity.into())?;
    let inverse = start_orientation.inverse();
    let mut turns = Vec::with_capacity(frames.len());
    for sample in frames {
        let turn = (orientation(name, run, sample)? * inverse).scaled_axis();
        turns.push((sample.time, turn.into()));
    }
    let turning = track_fit(&turns, [0.0; 3])?;
    Ok(InitialState {
        time: start.time,
        position: Vector3::from(flight.position),
        orientation: UnitQuaternion::from_scaled_axis(Vector3::from(turning.position))
            * start_orientation,
        velocity: Vector3::from(flight.velocity),
        angular_velocity: Vector3::from(turning.velocity),
        source: StateSource::FreeFlightFit {
            frames: frames.len(),
        },
        fits: Some([flight, turning]),
    })
}

/// The recorded state at the window start, when too few frames precede it to fit.
fn recorded(
    name: &str,
    run: &str,
    start: &Sample,
    orientation: UnitQuaternion<f64>,
) -> Result<InitialState, TossError> {
    for channel in [Channel::Velocity, Channel::AngularVelocity] {
        if !start.has(channel) {
            return Err(TossError::Frame {
                run: run.to_owned(),
                time: start.time,
                problem: format!(
                    "fewer than {MIN_FIT_FRAMES} frames up to the window start to estimate \
                     the velocity of `{}` from, and its recorded {} ({}) is empty there",
                    name,
                    channel.name(),
                    channel.column_list()
                ),
            });
        }
    }
    Ok(InitialState {
        time: start.time,
        position: Vector3::from(start.position),
        orientation,
        velocity: Vector3::from(start.velocity),
        angular_velocity: Vector3::from(start.angular_velocity),
        source: StateSource::Recorded,
        fits: None,
    })
}

/// A frame's recorded orientation of body `name`, refused when empty or not a unit
/// quaternion.
pub fn orientation(
    name: &str,
    run: &str,
    sample: &Sample,
) -> Result<UnitQuaternion<f64>, TossError> {
    let [w, x, y, z] = sample.orientation;
    let quaternion = Quaternion::new(w, x, y, z);
    let norm = quaternion.norm();
    // An empty channel reads as NaN, whose norm is NaN: refused too.
    if (norm - 1.0).abs() <= UNIT_TOLERANCE {
        return Ok(UnitQuaternion::from_quaternion(quaternion));
    }
    let problem = if sample.lacks(Channel::Orientation) {
        format!(
            "body `{name}` has no orientation (qw, qx, qy, qz empty): a toss needs the camera's \
             pose in every frame"
        )
    } else {
        format!(
            "body `{name}`: columns `qw`, `qx`, `qy`, `qz` hold a quaternion of norm {norm}; \
             a pose needs a unit quaternion (within {UNIT_TOLERANCE})"
        )
    };
    Err(TossError::Frame {
        run: run.to_owned(),
        time: sample.time,
        problem,
    })
}
