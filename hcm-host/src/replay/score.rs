//! How far a predicted toss is from the recorded one, as the published simulator
//! comparisons on these tosses report it:
//!
//! - position error: the mean over the window's frames of |p_pred − p| divided by the
//!   body's width (the cube's side, 0.1048 m), in per cent;
//! - rotation error: the mean over the window's frames of the angle of R_predᵀ·R, in
//!   degrees;
//!
//! for several moving bodies, each body's means averaged over the bodies; and over
//! tosses, the mean, the standard deviation and the median of each.

use super::initial_state::orientation;
use super::{TossError, TossSetup};
use crate::dataset::Sample;
use crate::numerics::median;
use nalgebra::{UnitQuaternion, Vector3};
use serde::Serialize;

/// The scores of one toss.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TossScore {
    /// Run id.
    pub run: String,
    /// Frames scored (the window's) (–).
    pub frames: usize,
    /// Mean |p_pred − p| over the frames, in % of the body's width.
    pub position_error: f64,
    /// Mean angle of R_predᵀ·R over the frames (degrees).
    pub rotation_error: f64,
    /// With several moving bodies, each one's own scores (the toss's are their means);
    /// empty with one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<BodyScore>,
}

/// One moving body's scores in a toss of several.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BodyScore {
    /// The body's name.
    pub body: String,
    /// Its frames scored (–).
    pub frames: usize,
    /// Mean |p_pred − p| over its frames, in % of its own width.
    pub position_error: f64,
    /// Mean angle of R_predᵀ·R over its frames (degrees).
    pub rotation_error: f64,
}

/// The angle (rad, in [0, π]) of the rotation taking `predicted` to `measured`: the
/// angle of R_predᵀ·R. As 2·atan2(|v|, |w|) of the quaternion q_pred⁻¹·q, which keeps
/// its precision at small angles (an arccosine of w loses half the digits there) and
/// reads q and −q alike.
pub fn rotation_angle(predicted: &UnitQuaternion<f64>, measured: &UnitQuaternion<f64>) -> f64 {
    let difference = predicted.inverse() * measured;
    let q = difference.quaternion();
    2.0 * q.imag().norm().atan2(q.w.abs())
}

/// Scores `predicted` against `measured` of the primary body, frame by frame (the same
/// frames, in order).
pub fn score_toss(
    setup: &TossSetup,
    run: &str,
    measured: &[Sample],
    predicted: &[Sample],
) -> Result<TossScore, TossError> {
    score_movers(setup, run, &[measured], &[predicted])
}

/// Scores a toss of every moving body: `measured[m]` and `predicted[m]` are the
/// window's frames of `setup.movers[m]` (a mover past the end of either is left out).
/// Each body's errors are its means over its frames, the position error in % of its
/// own width; the toss's are their means over the bodies (one body: its own).
pub fn score_movers(
    setup: &TossSetup,
    run: &str,
    measured: &[&[Sample]],
    predicted: &[&[Sample]],
) -> Result<TossScore, TossError> {
    let (mut position, mut rotation, mut frames) = (0.0, 0.0, 0);
    let bodies = measured.len().min(predicted.len()).min(setup.movers.len());
    let mut rows = Vec::new();
    for m in 0..bodies {
        let mover = &setup.movers[m];
        let (mut p, mut r) = (0.0, 0.0);
        for (recorded, model) in measured[m].iter().zip(predicted[m]) {
            let miss = Vector3::from(model.position) - Vector3::from(recorded.position);
            p += miss.norm();
            r += rotation_angle(
                &orientation(&mover.name, run, model)?,
                &orientation(&mover.name, run, recorded)?,
            );
        }
        let n = measured[m].len().min(predicted[m].len());
        frames += n;
        let (p, r) = (
            100.0 * p / n.max(1) as f64 / mover.width,
            r.to_degrees() / n.max(1) as f64,
        );
        position += p;
        rotation += r;
        rows.push(BodyScore {
            body: mover.name.clone(),
            frames: n,
            position_error: p,
            rotation_error: r,
        });
    }
    let count = bodies.max(1) as f64;
    if bodies < 2 {
        rows.clear();
    }
    Ok(TossScore {
        run: run.to_owned(),
        frames,
        position_error: position / count,
        rotation_error: rotation / count,
        bodies: rows,
    })
}

/// One score over tosses: mean, sample standard deviation and median.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Tosses (–).
    pub count: usize,
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation (n − 1); 0 for one toss.
    pub std: f64,
    /// Median (the mean of the middle two for an even count).
    pub median: f64,
}

impl Summary {
    /// The summary of `values`, summed in their order (so the same values give the
    /// same bits); NaN for an empty list.
    pub fn of(values: &[f64]) -> Summary {
        let n = values.len();
        let mean = values.iter().sum::<f64>() / n as f64;
        let squares: f64 = values.iter().map(|v| (v - mean) * (v - mean)).sum();
        let std = if n > 1 {
            (squares / (n - 1) as f64).sqrt()
        } else {
            0.0
        };
        let median = median(&mut values.to_vec());
        Summary {
            count: n,
            mean,
            std,
            median,
        }
    }

    /// The position and rotation summaries of `scores`.
    pub(crate) fn of_scores(scores: &[TossScore]) -> (Summary, Summary) {
        let position: Vec<f64> = scores.iter().map(|s| s.position_error).collect();
        let rotation: Vec<f64> = scores.iter().map(|s| s.rotation_error).collect();
        (Summary::of(&position), Summary::of(&rotation))
    }
}
