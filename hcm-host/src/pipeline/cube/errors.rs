//! Where in a toss the prediction goes wrong: each window frame's position and rotation
//! error (the terms of `hcm predict`'s scores, before their mean over the frames),
//! averaged over tosses per frame index since the window start (the error over time),
//! and over the frames of each [`Phase`].

use super::phases::{phases, Phase};
use crate::dataset::{Dataset, Sample};
use crate::replay::rotation_angle;
use crate::replay::{orientation, TossError, TossEvaluation, TossSetup};
use nalgebra::Vector3;
use serde::Serialize;

/// One toss's errors, frame by frame over its window.
#[derive(Clone, Debug)]
pub struct FrameErrors {
    /// Time since the window start (s), per frame.
    pub(crate) time: Vec<f64>,
    /// |p_pred − p| in % of the body's width, per frame.
    pub(crate) position: Vec<f64>,
    /// Angle of R_predᵀ·R (°), per frame.
    pub(crate) rotation: Vec<f64>,
    /// The frame's phase (from the recorded poses).
    pub(crate) phase: Vec<Phase>,
}

/// The window's recorded frames of `evaluation`'s toss in `data`.
pub fn recorded<'a>(
    setup: &TossSetup,
    data: &'a Dataset,
    evaluation: &TossEvaluation,
) -> Result<&'a [Sample], TossError> {
    let run = &evaluation.prediction.run;
    let track = (data.runs.iter())
        .find(|r| &r.id == run)
        .and_then(|r| r.body(&setup.name))
        .ok_or_else(|| TossError::MissingBody {
            run: run.clone(),
            body: setup.name.clone(),
        })?;
    Ok(&track.samples[evaluation.prediction.window.start..])
}

/// The frame errors of every toss of `evaluations` (predictions of `data`'s runs).
pub(crate) fn frame_errors(
    setup: &TossSetup,
    data: &Dataset,
    evaluations: &[TossEvaluation],
) -> Result<Vec<FrameErrors>, TossError> {
    evaluations
        .iter()
        .map(|e| {
            let run = &e.prediction.run;
            let measured = recorded(setup, data, e)?;
            let start = measured.first().map_or(0.0, |s| s.time);
            let mut errors = FrameErrors {
                time: Vec::new(),
                position: Vec::new(),
                rotation: Vec::new(),
                phase: phases(setup, run, &e.prediction.window, measured)?,
            };
            for (real, model) in measured.iter().zip(&e.prediction.samples) {
                let miss = Vector3::from(model.position) - Vector3::from(real.position);
                let turn = rotation_angle(
                    &orientation(&setup.name, run, model)?,
                    &orientation(&setup.name, run, real)?,
                );
                errors.time.push(real.time - start);
                errors.position.push(100.0 * miss.norm() / setup.width);
                errors.rotation.push(turn.to_degrees());
            }
            errors.phase.truncate(errors.time.len());
            Ok(errors)
        })
        .collect()
}

/// The mean errors over tosses at one frame index since the window start.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimePoint {
    /// Frame index since the window start (–).
    pub(crate) frame: usize,
    /// Mean time since the window start over the tosses (s).
    pub(crate) time: f64,
    /// Tosses whose window reaches this frame (–).
    pub(crate) tosses: usize,
    /// Mean position error (% of the body's width).
    pub(crate) position: f64,
    /// Mean rotation error (°).
    pub(crate) rotation: f64,
}

/// The error over time: per frame index, the means over the tosses that reach it.
pub(crate) fn over_time(tosses: &[FrameErrors]) -> Vec<TimePoint> {
    let longest = tosses.iter().map(|t| t.time.len()).max().unwrap_or(0);
    (0..longest)
        .map(|frame| {
            let at: Vec<&FrameErrors> = tosses.iter().filter(|t| frame < t.time.len()).collect();
            let n = at.len() as f64;
            let mean = |f: &dyn Fn(&FrameErrors) -> f64| at.iter().map(|t| f(t)).sum::<f64>() / n;
            TimePoint {
                frame,
                time: mean(&|t| t.time[frame]),
                tosses: at.len(),
                position: mean(&|t| t.position[frame]),
                rotation: mean(&|t| t.rotation[frame]),
            }
        })
        .collect()
}

/// The errors of one phase, over every frame of every toss in it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PhaseErrors {
    /// The phase.
    pub(crate) phase: Phase,
    /// Tosses with at least one frame in it (–).
    pub(crate) tosses: usize,
    /// Frames in it, over the tosses (–).
    pub(crate) frames: usize,
    /// Mean position error over those frames (% of the body's width).
    pub(crate) position: f64,
    /// Mean rotation error over those frames (°).
    pub(crate) rotation: f64,
    /// The phase's share of the summed position error over all frames (–).
    pub(crate) position_share: f64,
    /// The phase's share of the summed rotation error over all frames (–).
    pub(crate) rotation_share: f64,
}

/// Each phase's errors (in [`Phase::ALL`] order).
pub(crate) fn per_phase(tosses: &[FrameErrors]) -> Vec<PhaseErrors> {
    let total = |f: &dyn Fn(&FrameErrors) -> &Vec<f64>| -> f64 {
        tosses.iter().map(|t| f(t).iter().sum::<f64>()).sum()
    };
    let (all_position, all_rotation) = (total(&|t| &t.position), total(&|t| &t.rotation));
    Phase::ALL
        .iter()
        .map(|&phase| {
            let (mut frames, mut with, mut position, mut rotation) = (0, 0, 0.0, 0.0);
            for t in tosses {
                let before = frames;
                for k in (0..t.phase.len()).filter(|&k| t.phase[k] == phase) {
                    frames += 1;
                    position += t.position[k];
                    rotation += t.rotation[k];
                }
                with += usize::from(frames > before);
            }
            let n = frames as f64;
            PhaseErrors {
                phase,
                tosses: with,
                frames,
                position: position / n,
                rotation: rotation / n,
                position_share: position / all_position,
                rotation_share: rotation / all_rotation,
            }
        })
        .collect()
}
