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
use crate::replay::{shift_surface, tilt_surface};
use crate::scenario::{Contact, ExperimentSpec, FrictionSpec, Model};
use crate::simulate::{simulate, SimulationError};
use hcm_core::LawError;
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
    scattered(model, rng, Draw::Exact)
}

/// `model` with every contact's noise drawn by `draw`, in contact order, then every
/// fixed body's height and tilt (`[variation]`), in body order.
fn scattered(model: &Model, rng: &mut ChaCha8Rng, draw: Draw) -> Result<Model, SimulationError> {
    let mut model = model.clone();
    for (index, contact) in model.contacts.iter_mut().enumerate() {
        scatter_parameters(contact, rng, draw).map_err(|source| SimulationError::Noise {
            contact: index,
            source,
        })?;
    }
    let variation = &model.scenario.variation;
    let (height, tilt) = (variation.fixed_height, variation.fixed_tilt);
    if height > 0.0 || tilt > 0.0 {
        let fixed: Vec<usize> = (0..model.bodies.len())
            .filter(|&b| model.bodies[b].fixed)
            .collect();
        for body in fixed {
            if height > 0.0 {
                let shift = draw.offset(height, normal(rng));
                shift_surface(&mut model, body, shift);
            }
            if tilt > 0.0 {
                let [x, y] = [0; 2].map(|_| draw.offset(tilt, normal(rng)));
                tilt_surface(&mut model, body, x, y);
            }
        }
    }
    Ok(model)
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

/// How Eq 18's ζ becomes a parameter's new value a′ from its value a and relative σ b.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Draw {
    /// The paper's: a′ = a + a·b·ζ, ζ ~ N(0, 1) as drawn (a generated experiment).
    Exact,
    /// A forecast member's: ζ truncated to ±2.5 (offsets too) and the factor 1 + b·ζ held ≥ 0.05, so
    /// a positive parameter stays positive; a value the law still refuses (a
    /// restitution above 1) has its offset from a halved until the law takes it. A
    /// member is a plausible run, never a run the model cannot simulate.
    Member,
}

impl Draw {
    /// a′ for ζ (the new value before any halving).
    fn value(self, a: f64, b: f64, zeta: f64) -> f64 {
        match self {
            Draw::Exact => a + a * b * zeta,
            Draw::Member => a * (1.0 + b * zeta.clamp(-2.5, 2.5)).max(0.05),
        }
    }

    /// An offset of standard deviation σ for ζ: σ·ζ, ζ truncated as the draw truncates.
    fn offset(self, sigma: f64, zeta: f64) -> f64 {
        match self {
            Draw::Exact => sigma * zeta,
            Draw::Member => sigma * zeta.clamp(-2.5, 2.5),
        }
    }
}

/// The name in a contact's `noise` table that scatters μ_s and μ_d by one ζ (both ×
/// the same factor, so μ_d ≤ μ_s holds): the friction coefficient of a surface that is
/// not the same at every spot.
pub const FRICTION_COEFFICIENT: &str = "mu";

/// A forecast member's model: every contact's parameters of its `noise` table drawn
/// as [`Draw::Member`] does, in the order [`noisy_model`] draws them. A member whose
/// friction leaves its domain (v_d below v_s) is an error, like a generated run.
pub fn member_model(model: &Model, rng: &mut ChaCha8Rng) -> Result<Model, SimulationError> {
    scattered(model, rng, Draw::Member)
}

/// Eq 18 on one contact: each parameter of its `noise` table (sorted by name, one draw
/// each, so a scenario's runs draw alike whatever else changes) drawn by `draw`. A
/// friction name acts on the contact's friction when it has one ([`FRICTION_COEFFICIENT`]
/// on both coefficients); any other name on the normal law, which refuses names it does
/// not have. Friction scattered out of its domain (v_d below v_s, say) is refused
/// rather than simulated.
fn scatter_parameters(
    contact: &mut Contact,
    rng: &mut ChaCha8Rng,
    draw: Draw,
) -> Result<(), LawError> {
    for (name, b) in &contact.noise {
        let zeta = normal(rng);
        let friction = contact.model.friction.as_mut();
        if let Some(f) = friction {
            if name == FRICTION_COEFFICIENT {
                let factor = draw.value(1.0, *b, zeta);
                f.static_coefficient *= factor;
                f.dynamic_coefficient *= factor;
                continue;
            }
            if let Some(a) = FrictionSpec::parameter(f, name) {
                *a = draw.value(*a, *b, zeta);
                continue;
            }
        }
        let law = &mut contact.model.normal.base;
        let a = law.get(name)?;
        let mut value = draw.value(a, *b, zeta);
        let mut tries = 0;
        while let Err(error) = law.set(name, value) {
            tries += 1;
            if draw == Draw::Exact || tries > 30 {
                return Err(error);
            }
            value = a + 0.5 * (value - a);
        }
    }
    match &contact.model.friction {
        Some(friction) => friction.validate(),
        None => Ok(()),
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
