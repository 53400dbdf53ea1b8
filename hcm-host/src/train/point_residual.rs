//! The contact-frame residual as one stage: one network evaluated at every touching
//! point from that point's δ, δ̇, slip speed, spin and rolling rate
//! (`hcm_core::model::point_residual`), trained on the wrench PM2 misses on the
//! moving body ([`super::point_samples`], the sum over the points by
//! [`super::summed`]), and its int8 twin. `hcm train --inputs contact` runs it.
//!
//! Beside the body-state residual of Eq 12 ([`super::wrench_residual`]) it trades the
//! body's pose for the contact's own state: a contact at another place, in another
//! orientation, or at another corner of a face reads the same inputs.

use super::explained::EXPLAINED_MIN;
use super::point_samples::point_rows;
use super::reported::int8_twin_in_stage;
use super::summed::{point_inputs, train_summed, SummedRow};
use super::wrench_residual::event_ends;
use super::ResidualError;
use super::Trained;
use super::{ResidualSettings, TrainSettings, TrainedResidual};
use crate::dataset::Dataset;
use crate::progress::{in_stage, Progress, Stage};
use crate::residual::{HIDDEN, POINT_WIDTH};
use crate::scenario::Model;
use hcm_core::model::{POINT_INPUTS, POINT_OUTPUTS};

/// The units of the rows' targets, as a status names them.
const WRENCH_UNITS: &str = "N, N·m";

/// Epochs without improvement before stopping.
const PATIENCE: usize = 40;

/// The spin and rolling rates (rad/s): one vector's components, normalised and given
/// an envelope tolerance by its larger spread ([`TrainSettings::input_vectors`]).
/// Measured on the peg, whose motion is planar: spin rates of 1e-10 rad/s (rounding)
/// in training set the spin's scale and envelope, and a held-out condition's 1e-9
/// switched the residual off at every point (HCM = PM2 to the last digit).
const ANGULAR_RATES: std::ops::Range<usize> = 3..5;

/// Adam's step size.
const LEARNING_RATE: f64 = 3e-3;

/// The contact-frame residual of contact `c` of `pm2` (the scenario with PM2 in
/// place) on the samples of the first `events` contact events of `training`, then its
/// int8 twin, seeded with `settings.seed`. Reports [`Stage::Train`] and
/// [`Stage::Int8Twin`] to `progress`. The returned [`Trained`]'s `silenced` lists
/// the outputs the fit does not need (k_n, r_f, c_t, c_n, c_r: 0 to 4;
/// [`super::summed::train_summed`]), fixed at 0; its R² is per component of the body's
/// wrench.
pub fn train_point_residual(
    pm2: &Model,
    training: &Dataset,
    c: usize,
    events: usize,
    settings: &ResidualSettings,
    progress: &dyn Progress,
) -> Result<Trained, ResidualError> {
    let (rows, at) = point_rows(pm2, training, c)?;
    let ends = event_ends(pm2, training, events)?;
    let rows: Vec<SummedRow> = (rows.into_iter().zip(&at))
        .filter(|(_, (run, time))| *time < ends[*run])
        .map(|(row, _)| row)
        .collect();
    train_point_rows(&rows, c, settings, WRENCH_UNITS, progress)
}

/// The contact-frame residual of contact `c` trained on `rows` (targets in `units`, as
/// a status names them), then its int8 twin: [`train_point_residual`]'s stages on rows
/// built elsewhere (from motion: [`super::motion_samples`]).
pub fn train_point_rows(
    rows: &[SummedRow],
    c: usize,
    settings: &ResidualSettings,
    units: &str,
    progress: &dyn Progress,
) -> Result<Trained, ResidualError> {
    let train_settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: POINT_WIDTH,
        max_epochs: settings.epochs,
        patience: PATIENCE,
        learning_rate: LEARNING_RATE,
        seed: settings.seed,
        input_vectors: vec![ANGULAR_RATES],
        ..TrainSettings::default()
    };
    let steps = settings.epochs as u64;
    let (network, report, unfelt) = in_stage(progress, Stage::Train, steps, || {
        train_summed(
            rows,
            POINT_OUTPUTS,
            &train_settings,
            |epoch, _, validation| {
                progress.advance(epoch as u64, steps);
                progress.status(&format!("val RMS {:.3} {units}", validation.sqrt()));
            },
        )
    })?;
    let network = from_rest(network);
    let inputs = point_inputs(rows);
    let (int8, tuned) = int8_twin_in_stage(
        &network,
        &inputs,
        settings.int8_epochs,
        settings.seed,
        units,
        progress,
    )?;
    let explained = summed_explained(&network, rows);
    Ok(Trained {
        residual: TrainedResidual::new(c, network, int8),
        rows: rows.len(),
        report,
        int8: tuned,
        explained,
        silenced: unfelt,
    })
}

/// The features that start at zero — δ at touch-down and lift-off, the slip speed,
/// spin and rolling rates of a point that does not move (every one but δ̇) — in
/// [`point_features`](hcm_core::model::point_residual::point_features)' order.
const FROM_ZERO: [bool; POINT_INPUTS] = [true, false, true, true, true];

/// `network` with its envelope reaching down to 0 in the features that start there.
///
/// Every contact passes δ = 0 at touch-down and lift-off, yet a sampled record holds
/// its smallest δ above 0; with the envelope there, the residual switched on and off
/// at that depth, a jump in the force the integrator chased: measured on
/// `examples/rig`, the HCM's simulation stopped at its step limit within the first
/// contact. From 0, the correction meets the contact as it begins.
fn from_rest(mut network: super::Network) -> super::Network {
    for (min, from_zero) in network.envelope_min.iter_mut().zip(FROM_ZERO) {
        if from_zero {
            *min = min.min(0.0);
        }
    }
    network
}

/// R² of each wrench component (force x y z, torque x y z) of the network's summed
/// prediction over `rows`; 0 for a component without variance.
pub(super) fn summed_explained(network: &super::Network, rows: &[SummedRow]) -> Vec<f64> {
    let components = rows.first().map_or(0, |r| r.target.len());
    let n = rows.len().max(1) as f64;
    let mut mean = vec![0.0; components];
    for row in rows {
        for (m, t) in mean.iter_mut().zip(&row.target) {
            *m += t / n;
        }
    }
    let (mut variance, mut error) = (vec![0.0; components], vec![0.0; components]);
    for row in rows {
        let mut prediction = vec![0.0; components];
        for (x, lever) in &row.points {
            let y = network.evaluate(x);
            for (t, value) in prediction.iter_mut().enumerate() {
                *value += (0..y.len())
                    .map(|k| lever[t * y.len() + k] * y[k])
                    .sum::<f64>();
            }
        }
        for t in 0..components {
            variance[t] += (row.target[t] - mean[t]).powi(2);
            error[t] += (row.target[t] - prediction[t]).powi(2);
        }
    }
    (variance.iter().zip(&error))
        .map(|(v, e)| if *v > 0.0 { 1.0 - e / v } else { 0.0 })
        .collect()
}

/// Whether a trained wrench residual explains under [`EXPLAINED_MIN`] of PM2's error
/// in every component: no better than a zero output.
pub fn explains_nothing(trained: &Trained) -> bool {
    trained.explained.iter().all(|r2| *r2 < EXPLAINED_MIN)
}
