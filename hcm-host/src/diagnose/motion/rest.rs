//! How tilted a box lies once at rest at the end of its recordings, beyond what the
//! tracker's noise makes of a flat rest: what a per-run tilt of the fixed body it
//! rests on could be (`Scales::rest_tilt`, the bound of the `fixed_tilt` chance).

use crate::dataset::Dataset;
use crate::replay::{orientation, prepare, TossSetup};
use crate::scenario::{Model, Shape};
use nalgebra::Vector3;

/// Frames a recording's end must be still over to count as at rest (–): 7 frames,
/// 47 ms at the cube's 148 Hz.
const STILL_FRAMES: usize = 7;
/// Most the centre may move over those frames, as a share of the body's width (–).
const STILL_SHARE: f64 = 0.02;
/// Most the body may turn over those frames (rad): 2°.
const STILL_TURN: f64 = 0.035;

/// The largest RMS tilt (rad) per run that the fixed body's tilt could have, as the
/// resting box shows it: the mean square angle θ² between the up direction and the
/// box's axis nearest it in the last frame, over the recordings of `data` that end at
/// rest, at its upper 2-standard-error bound (× (1 + 2/√n): θ² of a tilt drawn per run
/// scatters like its mean), less the tracker's own tilt noise — the orientation
/// residual variance of the free-flight fits, its two components across the up
/// direction, averaged over the recordings. 0 where the rest shows no more than the
/// tracker's noise; NaN when the primary body is not a box or no recording ends at
/// rest.
pub(crate) fn rest_tilt(model: &Model, setup: &TossSetup, data: &Dataset) -> f64 {
    if !matches!(model.bodies[setup.body].shape, Shape::Box { .. }) {
        return f64::NAN;
    }
    let up = -setup.gravity.normalize();
    let (mut sum, mut count) = (0.0, 0);
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
        if !(moved <= STILL_SHARE * setup.width && turned <= STILL_TURN) {
            continue;
        }
        let q = turns[STILL_FRAMES - 1];
        let nearest = (0..3)
            .map(|k| (q * Vector3::ith(k, 1.0)).dot(&up).abs())
            .fold(0.0, f64::max);
        sum += nearest.min(1.0).acos().powi(2);
        count += 1;
    }
    if count == 0 {
        return f64::NAN;
    }
    let upper = sum / count as f64 * (1.0 + 2.0 / (count as f64).sqrt());
    (upper - tracker_tilt(setup, data, &up)).max(0.0).sqrt()
}

/// The mean over the recordings of `data` of the orientation noise across `up` (rad²)
/// their free-flight fits found at the window start: Σ_k σ_k²·(1 − up_k²) of the
/// rotation fit's residual variances; 0 without fits.
fn tracker_tilt(setup: &TossSetup, data: &Dataset, up: &Vector3<f64>) -> f64 {
    let (mut sum, mut count) = (0.0, 0);
    for run in &data.runs {
        let Ok(toss) = prepare(setup, run) else {
            continue;
        };
        if let Some([_, turning]) = &toss.primary().initial.fits {
            sum += (0..3)
                .map(|k| turning.noise[k] * (1.0 - up[k] * up[k]))
                .sum::<f64>();
            count += 1;
        }
    }
    sum / count.max(1) as f64
}
