//! One run of PM1 (paper Section 4): the contact's parameters scattered (Eq 18), the
//! scenario simulated, and noise added to what is recorded (Eq 19).
//!
//! Eq 18 draws η = a + a·b·ζ, ζ ~ N(0, 1), once per run for every parameter named in
//! the contact's `noise` table: the normal law's (IMPACT's stiffness, damping, …) and,
//! for a contact with friction, the STEP friction's (μ_s, μ_d, v_s, v_d). Eq 19 adds
//! σ·ζ to every recorded force component (and, where asked, torque, position and
//! velocity components), a fresh ζ per component and sample.

use crate::dataset::{Run, Sample};
use crate::numerics::sampled::{delayed, low_pass};
use crate::scenario::{drawn_run, Draw, ExperimentSpec, Model};
use crate::simulate::{simulate, SimulationError};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// One run of PM1: contact parameters η = a + a·b·ζ (Eq 18), then output noise
/// γ = γ0 + σ·ζ on every recorded sample (Eq 19).
pub fn noisy_run(model: &Model, rng: &mut ChaCha8Rng) -> Result<Run, SimulationError> {
    let model = noisy_model(model, rng)?;
    let mut run = simulate(&model)?.run;
    add_output_noise(&model.scenario.experiment, &mut run, rng);
    Ok(run)
}

/// The model of one run of PM1: every contact's noisy parameters drawn (Eq 18), in
/// contact order; the first draws of the run's stream.
pub fn noisy_model(model: &Model, rng: &mut ChaCha8Rng) -> Result<Model, SimulationError> {
    drawn_run(model, rng, Draw::Exact)
        .map_err(|(contact, source)| SimulationError::Noise { contact, source })
}

/// Eq 19 and the sensor effects on a simulated run: a force sensor's nonlinearity,
/// lag, low-pass filter, gain and offset ([`read_by_sensor`]), then σ·ζ on every
/// force, torque, position and velocity component whose σ is set, sample by sample in
/// time order.
fn add_output_noise(e: &ExperimentSpec, run: &mut Run, rng: &mut ChaCha8Rng) {
    for track in &mut run.bodies {
        read_by_sensor(e, &mut track.samples);
        for sample in &mut track.samples {
            for (values, sigma) in [
                (&mut sample.force[..], e.force_noise),
                (&mut sample.torque[..], e.torque_noise),
                (&mut sample.position[..], e.position_noise),
                (&mut sample.velocity[..], e.velocity_noise),
            ] {
                if sigma > 0.0 {
                    values.iter_mut().for_each(|v| *v += sigma * normal(rng));
                }
            }
        }
    }
}

/// Whether the scenario's sensor reads the wrench as it is: no nonlinearity, lag or
/// filter, gain 1, offset 0.
pub fn sensor_is_exact(e: &ExperimentSpec) -> bool {
    e.force_nonlinearity == 0.0
        && e.sensor_delay == 0.0
        && e.sensor_filter == 0.0
        && e.force_gain == 1.0
        && e.force_offset == [0.0; 3]
}

/// The reading of `samples` (one body's track, time ascending) by the scenario's force
/// sensor, in place: the force through its nonlinearity, read `sensor_delay` late,
/// through its low-pass filter, then force and torque times `force_gain`, plus
/// `force_offset` on the force. What `hcm generate` records, and what a model that
/// names a sensor effect compares with the data.
pub fn read_by_sensor(e: &ExperimentSpec, samples: &mut [Sample]) {
    if e.force_nonlinearity != 0.0 {
        for sample in samples.iter_mut() {
            let magnitude = sample.force.iter().map(|f| f * f).sum::<f64>().sqrt();
            let scale = 1.0 + e.force_nonlinearity * magnitude;
            sample.force.iter_mut().for_each(|f| *f *= scale);
        }
    }
    if e.sensor_delay > 0.0 {
        delay_forces(samples, e.sensor_delay);
    }
    if e.sensor_filter > 0.0 {
        filter_forces(samples, e.sensor_filter);
    }
    for sample in samples.iter_mut() {
        for (f, b) in sample.force.iter_mut().zip(e.force_offset) {
            *f = e.force_gain * *f + b;
        }
        sample.torque.iter_mut().for_each(|t| *t *= e.force_gain);
    }
}

/// Replaces each force component's series along `samples` by `through(times, series)`.
fn map_force_components(samples: &mut [Sample], through: impl Fn(&[f64], &[f64]) -> Vec<f64>) {
    let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let mapped: Vec<Vec<f64>> = (0..3)
        .map(|k| {
            let f: Vec<f64> = samples.iter().map(|s| s.force[k]).collect();
            through(&times, &f)
        })
        .collect();
    for (i, sample) in samples.iter_mut().enumerate() {
        sample.force = std::array::from_fn(|k| mapped[k][i]);
    }
}

/// Replaces each sample's force by the force τ (s) earlier: a lagging sensor, read
/// between the samples on the cubic Hermite curve through them (`numerics::sampled::
/// delayed`, as the diagnosis' sensor model reads; a straight line between samples would
/// average two of them, a low-pass filter of its own at a coarse rate), held at the
/// first sample's value before it.
fn delay_forces(samples: &mut [Sample], delay: f64) {
    map_force_components(samples, |t, f| delayed(t, f, delay));
}

/// Passes each sample's force through a first-order low-pass filter of time constant
/// τ (s), T·ẏ + y = f, at rest on the first sample's force (`numerics::sampled::
/// low_pass`: exact for a force linear between the samples).
fn filter_forces(samples: &mut [Sample], tau: f64) {
    map_force_components(samples, |t, f| low_pass(t, f, tau));
}

/// ζ ~ N(0, 1).
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}
