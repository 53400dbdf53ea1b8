//! Noise-added experiments (PM1, paper Section 4): many runs of a scenario with
//! noise on the contact parameters (Eq 18) and on the sampled outputs (Eq 19),
//! split into a training set S1 and a validation set S2.
//!
//! Every run draws from its own random stream, derived from the seed and the run's
//! index, so the data are bit-identical for a seed whatever the number of threads.

mod split;

pub use split::{condition_of, split, Split};

use crate::dataset::{Dataset, Run};
use crate::scenario::{Model, Scenario, ScenarioError};
use crate::simulate::{simulate, SimulationError};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

/// Why an experiment could not be generated.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    /// A condition's overrides do not make a valid scenario.
    #[error("condition `{condition}`: {source}")]
    Condition {
        condition: String,
        source: ScenarioError,
    },
    /// A run's simulation failed.
    #[error("run `{run}`: {source}")]
    Simulation {
        run: String,
        source: SimulationError,
    },
    /// Nothing to generate.
    #[error("--runs must be at least 1")]
    NoRuns,
}

/// The conditions of an experiment: (name, model). A scenario without conditions
/// has one, named "".
pub fn conditions(scenario: &Scenario) -> Result<Vec<(String, Model)>, ExperimentError> {
    let specs = &scenario.experiment.conditions;
    if specs.is_empty() {
        let model = scenario
            .model()
            .map_err(|source| ExperimentError::Condition {
                condition: String::new(),
                source,
            })?;
        return Ok(vec![(String::new(), model)]);
    }
    specs
        .iter()
        .map(|c| {
            let fail = |source| ExperimentError::Condition {
                condition: c.name.clone(),
                source,
            };
            let model = scenario.with(&c.set).map_err(fail)?.model().map_err(fail)?;
            Ok((c.name.clone(), model))
        })
        .collect()
}

/// Run id of run `k` of `condition` (`0007`, or `v0.95/007` with conditions).
fn run_id(condition: &str, k: usize, runs: usize) -> String {
    let width = (runs.max(2) - 1).to_string().len();
    if condition.is_empty() {
        format!("{k:0width$}")
    } else {
        format!("{condition}/{k:0width$}")
    }
}

/// A random stream for run `index` of an experiment seeded with `seed`: SplitMix64
/// of the pair, so neighbouring runs get unrelated streams.
fn run_rng(seed: u64, index: u64) -> ChaCha8Rng {
    let mut z = seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ChaCha8Rng::seed_from_u64(z ^ (z >> 31))
}

/// Generates `runs_per_condition` noisy runs of every condition of `scenario`.
/// `progress` is called once per finished run (from worker threads).
pub fn generate(
    scenario: &Scenario,
    runs_per_condition: usize,
    seed: u64,
    progress: impl Fn() + Sync,
) -> Result<Dataset, ExperimentError> {
    if runs_per_condition == 0 {
        return Err(ExperimentError::NoRuns);
    }
    let conditions = conditions(scenario)?;
    let jobs: Vec<(usize, usize)> = (0..conditions.len())
        .flat_map(|c| (0..runs_per_condition).map(move |k| (c, k)))
        .collect();
    let runs: Result<Vec<Run>, ExperimentError> = jobs
        .par_iter()
        .enumerate()
        .map(|(index, &(c, k))| {
            let (name, model) = &conditions[c];
            let id = run_id(name, k, runs_per_condition);
            let mut rng = run_rng(seed, index as u64);
            let run = noisy_run(model, &mut rng).map_err(|source| ExperimentError::Simulation {
                run: id.clone(),
                source,
            })?;
            progress();
            Ok(Run { id, ..run })
        })
        .collect();
    Ok(Dataset { runs: runs? })
}

/// One run of PM1: contact parameters η = a + a·b·ζ (Eq 18), then output noise
/// γ = γ0 + σ·ζ on every recorded sample (Eq 19).
pub fn noisy_run(model: &Model, rng: &mut ChaCha8Rng) -> Result<Run, SimulationError> {
    let mut model = model.clone();
    for (index, contact) in model.contacts.iter_mut().enumerate() {
        // Drawn in the order of `noise` (by name, as the scenario's table is sorted),
        // one draw per noisy parameter.
        for (name, b) in &contact.noise {
            let noisy = |source| SimulationError::Noise {
                contact: index,
                source,
            };
            let law = &mut contact.model.normal.base;
            let a = law.get(name).map_err(noisy)?;
            law.set(name, a + a * b * normal(rng)).map_err(noisy)?;
        }
    }
    let mut run = simulate(&model)?.run;
    let e = &model.scenario.experiment;
    for track in &mut run.bodies {
        if e.sensor_delay > 0.0 {
            delay_forces(&mut track.samples, e.sensor_delay);
        }
        for sample in &mut track.samples {
            for (f, b) in sample.force.iter_mut().zip(e.force_offset) {
                *f += b;
            }
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
    Ok(run)
}

/// Replaces each sample's force by the force τ (s) earlier, linearly interpolated
/// between the samples (held at the first sample's value before it): a lagging sensor.
fn delay_forces(samples: &mut [crate::dataset::Sample], delay: f64) {
    let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let forces: Vec<[f64; 3]> = samples.iter().map(|s| s.force).collect();
    let mut j = 0;
    for sample in samples.iter_mut() {
        let t = sample.time - delay;
        while j + 1 < times.len() && times[j + 1] <= t {
            j += 1;
        }
        sample.force = if t <= times[0] {
            forces[0]
        } else if j + 1 >= times.len() {
            forces[j]
        } else {
            let s = (t - times[j]) / (times[j + 1] - times[j]);
            std::array::from_fn(|k| forces[j][k] + s * (forces[j + 1][k] - forces[j][k]))
        };
    }
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}
