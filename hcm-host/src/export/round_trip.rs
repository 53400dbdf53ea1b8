//! How faithfully the core's decoded network reproduces the host network it was
//! exported from, over the points where the core runs it (its training envelope).

use crate::residual::ContactResidual;
use crate::train::Network;
use hcm_core::model::{Correction, Residual};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Grid steps per input for networks of at most [`GRID_INPUTS`] inputs.
const GRID_STEPS: usize = 9;
/// Up to this many inputs the envelope is walked on a full grid (9³ = 729 points).
const GRID_INPUTS: usize = 3;
/// Random points drawn inside the envelope of a wider network (fixed seed).
const RANDOM_POINTS: usize = 4096;
/// Seed of those points: the same points every time.
const RANDOM_SEED: u64 = 0x5eed;

/// Worst |core − host| of `decoded` against the host `network` it was exported from,
/// relative to the largest |host output| of the same quantity — the force (N) or
/// the torque (N·m) of a wrench residual, its three components together, since a
/// component the motion leaves near zero (F_y of a peg moving in a plane) is no scale
/// of its own — worst over the quantities. Points: a 9 × 9 × 9
/// grid spanning the training envelope for up to three inputs; otherwise 4096 points
/// drawn uniformly in the envelope's box with a fixed seed (13 inputs do not make a
/// grid). See [`round_trip_error_over`] for chosen points (the training inputs).
pub fn round_trip_error(network: &Network, decoded: &ContactResidual) -> f64 {
    let points = if network.inputs <= GRID_INPUTS {
        grid(network)
    } else {
        random_points(network)
    };
    round_trip_error_over(network, decoded, &points)
}

/// [`round_trip_error`] over the given `points` (raw input units); points where the
/// core switches the residual off (outside the envelope) count only towards the
/// largest host output.
pub fn round_trip_error_over(
    network: &Network,
    decoded: &ContactResidual,
    points: &[Vec<f64>],
) -> f64 {
    let mut worst = vec![0.0_f64; network.outputs];
    let mut largest = vec![0.0_f64; network.outputs];
    for x in points {
        let host = network.evaluate(x);
        for (l, h) in largest.iter_mut().zip(&host) {
            *l = l.max(h.abs());
        }
        if let Some(core) = core_outputs(decoded, x) {
            for ((w, h), c) in worst.iter_mut().zip(&host).zip(&core) {
                *w = w.max((c - h).abs());
            }
        }
    }
    // One output, or vectors of three (force, torque, …).
    let group = if network.outputs.is_multiple_of(3) {
        3
    } else {
        1
    };
    let most = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    worst
        .chunks(group)
        .zip(largest.chunks(group))
        .map(|(w, l)| most(w) / most(l).max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max)
}

/// The decoded network's outputs at `x` as the core evaluates them (a contact-frame
/// network's raw four, every other's correction), or `None` where it is switched off.
fn core_outputs(decoded: &ContactResidual, x: &[f64]) -> Option<Vec<f64>> {
    match decoded {
        ContactResidual::Point(stored) => {
            let features: &[f64; hcm_core::model::POINT_INPUTS] = x.try_into().ok()?;
            stored.outputs(features).map(|o| o.to_vec())
        }
        ContactResidual::JointTorque(joint) => Residual::<f64>::correction(joint, x).map(outputs),
        _ => Residual::<f64>::correction(decoded, x).map(outputs),
    }
}

/// A correction's values in the network's output order.
fn outputs(correction: Correction<f64>) -> Vec<f64> {
    match correction {
        Correction::NormalForce(force) => vec![force],
        Correction::Wrench { force, torque } => force.iter().chain(&torque).copied().collect(),
        Correction::PairWrench {
            force_1,
            torque_1,
            force_2,
            torque_2,
        } => [force_1, torque_1, force_2, torque_2]
            .iter()
            .flat_map(|v| v.iter().copied())
            .collect(),
    }
}

/// The 9ⁿ grid over the envelope's box (n ≤ 3 inputs).
fn grid(network: &Network) -> Vec<Vec<f64>> {
    let axis = |i: usize, k: usize| {
        let (lo, hi) = (network.envelope_min[i], network.envelope_max[i]);
        lo + (hi - lo) * k as f64 / (GRID_STEPS - 1) as f64
    };
    let mut points = vec![Vec::new()];
    for i in 0..network.inputs {
        points = points
            .into_iter()
            .flat_map(|p| {
                (0..GRID_STEPS).map(move |k| {
                    let mut p = p.clone();
                    p.push(axis(i, k));
                    p
                })
            })
            .collect();
    }
    points
}

/// [`RANDOM_POINTS`] points uniform in the envelope's box, seeded.
fn random_points(network: &Network) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(RANDOM_SEED);
    (0..RANDOM_POINTS)
        .map(|_| {
            (network.envelope_min.iter().zip(&network.envelope_max))
                .map(|(lo, hi)| lo + (hi - lo) * rng.random::<f64>())
                .collect()
        })
        .collect()
}
