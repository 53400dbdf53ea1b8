//! The wrench over time of the peg's contacts: S2's mean (runs aligned at their first
//! touch-down) and each model's replay from S2's mean pre-contact state, and the path
//! of the peg's centre of mass — the data of the figures (the paper's Fig 9 analog).

use crate::dataset::{Dataset, Sample};
use crate::indicators::pair_events_from_run;
use crate::scenario::Model;
use crate::simulate::simulate;
use nalgebra::Vector3;

/// ‖F‖ (N) and ‖T‖ (N·m) at times τ (s) after the first touch-down, and the centre of
/// mass's x and z (m) at the same times.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WrenchCurve {
    /// τ (s), increasing.
    pub(crate) time: Vec<f64>,
    /// ‖F‖ on the peg (N).
    pub(crate) force: Vec<f64>,
    /// ‖T‖ on the peg about its centre of mass (N·m).
    pub(crate) torque: Vec<f64>,
    /// Centre of mass, world x (m).
    pub(crate) x: Vec<f64>,
    /// Centre of mass, world z (m).
    pub(crate) z: Vec<f64>,
}

/// The mover's samples of a run, read at `time` (s) by linear interpolation (None
/// outside the samples).
fn at(samples: &[Sample], time: f64) -> Option<(f64, f64, f64, f64)> {
    let i = samples.partition_point(|s| s.time < time);
    let (a, b) = (samples.get(i.checked_sub(1)?)?, samples.get(i)?);
    let w = if b.time > a.time {
        (time - a.time) / (b.time - a.time)
    } else {
        0.0
    };
    let mix = |p: f64, q: f64| p + w * (q - p);
    let norm = |v: [f64; 3]| Vector3::from(v).norm();
    Some((
        mix(norm(a.force), norm(b.force)),
        mix(norm(a.torque), norm(b.torque)),
        mix(a.position[0], b.position[0]),
        mix(a.position[2], b.position[2]),
    ))
}

/// The grid τ_j = start + j·period up to `end` (s).
fn grid(start: f64, end: f64, period: f64) -> Vec<f64> {
    let n = ((end - start) / period).floor().max(0.0) as usize + 1;
    (0..n).map(|j| start + j as f64 * period).collect()
}

/// S2's mean curve of `mover` over τ ∈ [start, end], every run aligned at its first
/// touch-down of contact `c` (runs without one left out), sampled every `period` s.
pub fn mean_curve(
    model: &Model,
    data: &Dataset,
    mover: &str,
    (start, end, period): (f64, f64, f64),
) -> WrenchCurve {
    let time = grid(start, end, period);
    let mut sums = vec![[0.0; 4]; time.len()];
    let mut counts = vec![0usize; time.len()];
    for run in &data.runs {
        let first = pair_events_from_run(model, run)
            .ok()
            .and_then(|events| events.iter().map(|e| e.touch_down()).reduce(f64::min));
        let (Some(first), Some(track)) = (first, run.body(mover)) else {
            continue;
        };
        for (j, tau) in time.iter().enumerate() {
            if let Some((f, t, x, z)) = at(&track.samples, first + tau) {
                sums[j] = [
                    sums[j][0] + f,
                    sums[j][1] + t,
                    sums[j][2] + x,
                    sums[j][3] + z,
                ];
                counts[j] += 1;
            }
        }
    }
    let mean = |k: usize| -> Vec<f64> {
        sums.iter()
            .zip(&counts)
            .map(|(s, &n)| if n > 0 { s[k] / n as f64 } else { f64::NAN })
            .collect()
    };
    WrenchCurve {
        force: mean(0),
        torque: mean(1),
        x: mean(2),
        z: mean(3),
        time,
    }
}

/// `model`'s own curve: simulated, aligned at its first touch-down of contact `c`
/// (empty if it fails or never touches), on the same grid as [`mean_curve`].
pub fn replay_curve(
    model: &Model,
    c: usize,
    mover: &str,
    (start, end, period): (f64, f64, f64),
) -> WrenchCurve {
    let Ok(simulation) = simulate(model) else {
        return WrenchCurve::default();
    };
    let first = simulation
        .events
        .iter()
        .filter(|e| e.contact == c)
        .map(|e| e.touch_down)
        .reduce(f64::min);
    let (Some(first), Some(track)) = (first, simulation.run.body(mover)) else {
        return WrenchCurve::default();
    };
    let time = grid(start, end, period);
    let values: Vec<_> = time
        .iter()
        .map(|tau| {
            at(&track.samples, first + tau).unwrap_or((f64::NAN, f64::NAN, f64::NAN, f64::NAN))
        })
        .collect();
    WrenchCurve {
        force: values.iter().map(|v| v.0).collect(),
        torque: values.iter().map(|v| v.1).collect(),
        x: values.iter().map(|v| v.2).collect(),
        z: values.iter().map(|v| v.3).collect(),
        time,
    }
}
