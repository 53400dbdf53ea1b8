//! The frozen-pose baseline: a "prediction" that holds the body at its recorded pose at
//! the window start for the whole window. Scored like a simulation, it says how much the
//! body moves in the window at all — what a prediction must beat by a wide margin to
//! have learned anything of the contact.

use super::Window;
use crate::dataset::{BodyTrack, Sample};

/// The window's frames of `track` with every pose replaced by the one at the window
/// start, at rest (zero velocities, no force); times kept.
pub fn frozen_pose(track: &BodyTrack, window: &Window) -> Vec<Sample> {
    let start = &track.samples[window.start];
    track.samples[window.start..]
        .iter()
        .map(|frame| Sample {
            time: frame.time,
            position: start.position,
            orientation: start.orientation,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            force: [0.0; 3],
            torque: [0.0; 3],
        })
        .collect()
}
