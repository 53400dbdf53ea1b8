//! A toss's window: the frames a prediction is judged on. Issue 17 defines it to start
//! [`LEAD_FRAMES`] frames before the body's centre first comes within its circumscribed
//! radius of a fixed body it can touch (0.0524·√3 m of the table for the ContactNets
//! cube) — before that frame no corner can touch, so the motion is free flight, which
//! the simulator predicts exactly and which would flatter any score — and to run to the
//! toss's last frame. A plane's clearance is measured from its reference point (the
//! table of the data's frame, z = 0 for the tosses), not from its contact surface, which
//! a fitted offset moves: the frames scored are the data's, whatever the model
//! ([`super::partner`]).

use super::{TossError, TossSetup};
use crate::dataset::{BodyTrack, Channel};
use nalgebra::Vector3;

/// Frames the window starts before the first frame within reach of a fixed body (–).
pub const LEAD_FRAMES: usize = 3;

/// One toss's window, as indices into its body track's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// First frame of the window: [`LEAD_FRAMES`] before `near`, or the toss's first
    /// frame if it has fewer before `near`.
    pub start: usize,
    /// First frame whose centre lies within the circumscribed radius of a fixed body.
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
/// (the camera's). The window's `near` frame is the first within the circumscribed
/// radius of a partner, or the first where the body turned away from one within a
/// frame's travel of touching it (a bounce between two frames); a toss with neither
/// has no window and is an error naming the run and its lowest clearance.
pub fn find_window(setup: &TossSetup, run: &str, track: &BodyTrack) -> Result<Window, TossError> {
    let mut lowest = (f64::INFINITY, f64::NAN);
    let mut clearances = Vec::with_capacity(track.samples.len());
    for sample in &track.samples {
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
        let height = setup.clearance(&Vector3::from(sample.position));
        if height < lowest.0 {
            lowest = (height, sample.time);
        }
        clearances.push(height);
    }
    let position = |k: usize| Vector3::from(track.samples[k].position);
    let near = (0..clearances.len()).find(|&k| {
        let c = clearances[k];
        // A contact shorter than a frame (a ball's bounce) may fall between two frames
        // that both lie beyond reach: the frame where the body turned away from its
        // partner within one frame's travel of touching it counts too.
        let turned = k > 0
            && k + 1 < clearances.len()
            && clearances[k - 1] >= c
            && c < clearances[k + 1]
            && c < setup.radius + (position(k + 1) - position(k)).norm();
        c < setup.radius || turned
    });
    match near {
        Some(index) => Ok(Window {
            start: index.saturating_sub(LEAD_FRAMES),
            near: index,
            frames: track.samples.len(),
        }),
        None => Err(TossError::NoContact {
            run: run.to_owned(),
            body: setup.name.clone(),
            threshold: setup.radius,
            lowest: lowest.0,
            lowest_time: lowest.1,
        }),
    }
}
