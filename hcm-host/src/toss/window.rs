//! A toss's window: the frames a prediction is judged on. Issue 17 defines it to start
//! [`LEAD_FRAMES`] frames before the body's centre first comes within its circumscribed
//! radius of the plane (0.0524·√3 m for the ContactNets cube) — before that frame no
//! corner can touch, so the motion is free flight, which the simulator predicts exactly
//! and which would flatter any score — and to run to the toss's last frame. The height
//! is measured from the plane body's reference point (the table of the data's frame,
//! z = 0 for the tosses), not from its contact surface, which a fitted offset moves: the
//! frames scored are the data's, whatever the model.

use super::{TossError, TossSetup};
use crate::dataset::{BodyTrack, Channel};
use nalgebra::Vector3;

/// Frames the window starts before the first frame within reach of the plane (–).
pub const LEAD_FRAMES: usize = 3;

/// One toss's window, as indices into its body track's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// First frame of the window: [`LEAD_FRAMES`] before `near`, or the toss's first
    /// frame if it has fewer before `near`.
    pub start: usize,
    /// First frame whose centre lies within the circumscribed radius of the plane.
    pub near: usize,
    /// Frames in the toss (the window runs from `start` to the last).
    pub frames: usize,
}

impl Window {
    /// Frames in the window (–).
    pub fn len(&self) -> usize {
        self.frames - self.start
    }

    /// Whether the window holds no frame (never, for a window [`find_window`] made).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The window of `run`'s track of the tossed body. Every frame must hold a position
/// (the camera's); a toss whose centre never comes within reach of the plane has no
/// window and is an error naming the run and its lowest height.
pub fn find_window(setup: &TossSetup, run: &str, track: &BodyTrack) -> Result<Window, TossError> {
    let mut lowest = (f64::INFINITY, f64::NAN);
    for (index, sample) in track.samples.iter().enumerate() {
        if !sample.has(Channel::Position) {
            return Err(TossError::Frame {
                run: run.to_owned(),
                time: sample.time,
                problem: format!(
                    "body `{}` has no position (px, py, pz empty): a toss needs the camera's \
                     pose in every frame",
                    setup.name
                ),
            });
        }
        let height = setup.height(&Vector3::from(sample.position));
        if height < setup.radius {
            return Ok(Window {
                start: index.saturating_sub(LEAD_FRAMES),
                near: index,
                frames: track.samples.len(),
            });
        }
        if height < lowest.0 {
            lowest = (height, sample.time);
        }
    }
    Err(TossError::NoContact {
        run: run.to_owned(),
        body: setup.name.clone(),
        threshold: setup.radius,
        lowest: lowest.0,
        lowest_time: lowest.1,
    })
}
