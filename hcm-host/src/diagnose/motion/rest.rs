//! What the recordings that end at rest show of a fixed body that varies from run to
//! run, beyond the tracker's noise: how tilted a box lies, and how high the body's
//! centre rests (`Scales::rest_tilt`, `Scales::rest_height`, the bounds of the
//! `fixed_tilt` and `fixed_height` chances). A table tilted or moved by σ·ζ per run
//! leaves it there; what the rest does not show is not the table's.

use crate::dataset::{Dataset, FlightFit};
use crate::replay::{orientation, prepare, TossSetup};
use crate::scenario::{Model, Shape};
use nalgebra::{UnitQuaternion, Vector3};

/// Frames a recording's end must be still over to count as at rest (–): 7 frames,
/// 47 ms at the cube's 148 Hz.
const STILL_FRAMES: usize = 7;
/// Most the centre may move over those frames, as a share of the body's width (–).
const STILL_SHARE: f64 = 0.02;
/// Most the body may turn over those frames (rad): 2°.
const STILL_TURN: f64 = 0.035;

/// The largest per-run spreads of the fixed body the resting poses of `data` leave:
/// `(tilt (rad), height (m))`, each NaN where unknown (tilt: the body is not a box;
/// both: no recording ends at rest, or too few for a height's spread).
///
/// - Tilt: the mean square angle θ² between the up direction and the box's axis
///   nearest it in the last frame, at its upper 2-standard-error bound (× (1 + 2/√n):
///   θ² of a tilt drawn per run scatters like its mean), less the tracker's own tilt
///   noise (the free-flight fits' orientation residual variance across the up
///   direction, averaged over the recordings); its square root, 0 if negative.
/// - Height: the sample variance of the resting centre's height along up over the
///   recordings, at its upper bound (× (1 + 2·√(2/(n − 1)))), less the tracker's
///   position noise along up likewise; its square root.
pub(crate) fn rest_spreads(model: &Model, setup: &TossSetup, data: &Dataset) -> (f64, f64) {
    let up = -setup.gravity.normalize();
    let (mut tilts, mut heights) = (Vec::new(), Vec::new());
    for run in &data.runs {
        let Some(track) = run.body(&setup.name) else {
            continue;
        };
        let Some(end) = track.samples.len().checked_sub(STILL_FRAMES) else {
            continue;
        };
        let frames = &track.samples[end..];
        let turns: Option<Vec<_>> = (frames.iter())
            .map(|s| orientation(&setup.name, &run.id, s).ok())
            .collect();
        let Some(turns) = turns else {
            continue;
        };
        let last = &frames[STILL_FRAMES - 1];
        let moved = (frames.iter())
            .map(|s| (Vector3::from(s.position) - Vector3::from(last.position)).norm())
            .fold(0.0, f64::max);
        let turned = (turns.iter())
            .map(|q| q.angle_to(&turns[STILL_FRAMES - 1]))
            .fold(0.0, f64::max);
        if moved <= STILL_SHARE * setup.width && turned <= STILL_TURN {
            tilts.push(tilt(&turns[STILL_FRAMES - 1], &up));
            heights.push(Vector3::from(last.position).dot(&up));
        }
    }
    let noise = tracker_noise(setup, data, &up);
    let beyond = |upper: f64, tracker: f64| (upper - tracker).max(0.0).sqrt();
    let boxed = matches!(model.bodies[setup.body].shape, Shape::Box { .. });
    let tilt = match tilts.len() {
        0 => f64::NAN,
        _ if !boxed => f64::NAN,
        n => {
            let mean = tilts.iter().map(|t| t * t).sum::<f64>() / n as f64;
            beyond(mean * (1.0 + 2.0 / (n as f64).sqrt()), noise.0)
        }
    };
    let height = match heights.len() {
        0..=2 => f64::NAN,
        n => {
            let mean = heights.iter().sum::<f64>() / n as f64;
            let variance = heights.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            let upper = variance * (1.0 + 2.0 * (2.0 / (n - 1) as f64).sqrt());
            beyond(upper, noise.1)
        }
    };
    (tilt, height)
}

/// The angle (rad) between `up` and the axis of `q`'s box nearest it.
fn tilt(q: &UnitQuaternion<f64>, up: &Vector3<f64>) -> f64 {
    let nearest = (0..3)
        .map(|k| (q * Vector3::ith(k, 1.0)).dot(up).abs())
        .fold(0.0, f64::max);
    nearest.min(1.0).acos()
}

/// The tracker's noise the free-flight fits of `data`'s recordings found at their
/// window starts, averaged over the recordings: the orientation noise across `up`
/// (rad², Σ_k σ_k²·(1 − up_k²) of the rotation fit) and the position noise along it
/// (m², Σ_k σ_k²·up_k² of the position fit); 0 without fits.
fn tracker_noise(setup: &TossSetup, data: &Dataset, up: &Vector3<f64>) -> (f64, f64) {
    let (mut tilt, mut height, mut count) = (0.0, 0.0, 0);
    let along = |fit: &FlightFit, across: bool| {
        (0..3)
            .map(|k| {
                fit.noise[k]
                    * if across {
                        1.0 - up[k] * up[k]
                    } else {
                        up[k] * up[k]
                    }
            })
            .sum::<f64>()
    };
    for run in &data.runs {
        let Ok(toss) = prepare(setup, run) else {
            continue;
        };
        if let Some([flight, turning]) = &toss.primary().initial.fits {
            tilt += along(turning, true);
            height += along(flight, false);
            count += 1;
        }
    }
    let n = count.max(1) as f64;
    (tilt / n, height / n)
}
