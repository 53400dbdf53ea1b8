//! Simulation of a scenario, one engine for every example: rigid bodies with mass,
//! inertia tensor, position, orientation quaternion, velocity and angular velocity
//! (Eq 22), touching at up to eight points per body pair (sphere–plane, sphere–sphere,
//! box–plane, box–box, box–compound, sphere–box…), the contact's core model evaluated
//! at every point (normal law, STEP friction on the slip ω × r included, Eq 1 with the
//! arms, residual). The 1D examples (Eq 17, Eq 21) are the special case of spheres and
//! planes moving along a line of centres: their bodies are rigid bodies that happen
//! not to turn (no torque reaches them), and a moving plane given no inertia tensor is
//! held from turning.
//!
//! It integrates with the core's adaptive Dormand–Prince solver, switching to the
//! linearly implicit RODAS where stiction makes the run stiff ([`RigidStepper`]),
//! renormalising each quaternion before a step when it has drifted by more than a
//! few ulps (as [`hcm_core::rigid::step_unit`] does for one body). Contact forces are
//! continuous at every touch-down (each law gives 0 at δ = 0), so a new point needs no
//! restart; contact events (an interval in which any point of a pair touches) are
//! located where the pair's separation crosses zero, for the indicators and the
//! sampling only.

mod event;
mod footprint;
mod jacobian;
mod joints;
mod layout;
mod memory;
mod record;
mod stepper;
mod system;
pub use footprint::{memory_budget, record_bytes, shown_bytes};
pub(crate) use joints::joint_compliance;

pub use crate::indicators::ContactEvent;
pub use event::EventTracker;
pub use layout::{RigidLayout, StateVector};
pub use stepper::RigidStepper;
pub use system::{ContactLoad, PairManifold, RigidSystem};

use crate::dataset::Run;
use crate::scenario::{Model, SimulationSpec};
use hcm_core::integrate::{DenseOutput, IntegrationError, Settings};
use record::Recorder;

/// Renormalise a quaternion when |‖q‖ − 1| exceeds this (–): a few f64 ulps.
const DRIFT: f64 = 4.0 * f64::EPSILON;

/// Below this stiction transition speed v_s (m/s) the STEP's slope μ_s·f_n/v_s is
/// steep enough to make a run stiff (time constant m·v_s/(μ_s·f_n)); the stiff steps
/// ([`RigidStepper`]) keep a cube resting on a 10° incline at ~1.6 steps per ms down to
/// v_s = 0.01 mm/s (README), so a failure below it is worth naming the cause.
const SLOW_STICTION_SPEED: f64 = 1e-4;

/// A simulated run.
#[derive(Clone, Debug)]
pub struct Simulation {
    /// Contact events of every pair, in order of touch-down.
    pub events: Vec<ContactEvent>,
    /// Time the run stopped (s).
    pub end_time: f64,
    /// Accepted and rejected solver steps.
    pub steps: (u64, u64),
    /// The sampled trajectory (run id `"0"`; callers may rename it).
    pub run: Run,
}

/// Why a simulation failed.
#[derive(Debug, thiserror::Error)]
pub enum SimulationError {
    /// The solver gave up (stiff, diverging or too long a run).
    /// (The integrator's error is shown in the message, not chained as a source, so
    /// that it is printed once.)
    #[error("scenario `{scenario}`: {cause} (check the law parameters, or loosen simulation.relative_tolerance / raise simulation.max_steps{hint})")]
    Solver {
        /// The scenario's name.
        scenario: String,
        /// Why the integrator stopped.
        cause: IntegrationError,
        /// What else to check for this model (e.g. a friction transition speed).
        hint: String,
    },
    /// The record would not fit in memory.
    #[error(
        "scenario `{scenario}`: its record would take up to {} ({samples:.3e} samples: \
         simulation.end_time {end_time} s at a record period of {period} s), more than the \
         {} of memory available; raise record.contact_sample_period and \
         record.flight_sample_period or shorten simulation.end_time",
        footprint::shown_bytes(*bytes),
        footprint::shown_bytes(*budget)
    )]
    TooLarge {
        /// The scenario's name.
        scenario: String,
        /// Memory the record would take at most (bytes).
        bytes: f64,
        /// Memory available (bytes).
        budget: f64,
        /// Samples the record would hold at most: `end_time / period`.
        samples: f64,
        /// The simulated duration, `simulation.end_time` (s).
        end_time: f64,
        /// The shorter of the contact and flight record periods (s).
        period: f64,
    },
    /// A contact's parameter noise names a parameter its law does not have.
    #[error("contact {contact}: parameter noise: {source}")]
    Noise {
        /// The contact's index in the scenario (from 0).
        contact: usize,
        /// The law's refusal of the parameter's name.
        source: hcm_core::LawError,
    },
}

/// Refuses a run whose record would not fit in memory ([`footprint`]).
fn fits_in_memory(model: &Model) -> Result<(), SimulationError> {
    let (bytes, budget) = (footprint::run_bytes(model), footprint::memory_budget());
    if bytes <= budget {
        return Ok(());
    }
    let record = &model.scenario.record;
    let period = record
        .contact_sample_period
        .min(record.flight_sample_period);
    let end_time = model.scenario.simulation.end_time;
    Err(SimulationError::TooLarge {
        scenario: model.scenario.name.clone(),
        bytes,
        budget,
        samples: end_time / period,
        end_time,
        period,
    })
}

/// The solver settings a scenario's `[simulation]` table asks for.
fn solver_settings(spec: &SimulationSpec) -> Settings<f64> {
    Settings {
        max_step: spec.max_step,
        max_steps: spec.max_steps,
        ..Settings::new(spec.relative_tolerance, spec.absolute_tolerance)
    }
}

/// A hint for a solver failure: the friction transition speeds below
/// [`SLOW_STICTION_SPEED`], if any.
fn stiction_hint(model: &Model) -> String {
    let slow: Vec<String> = model
        .contacts
        .iter()
        .enumerate()
        .filter_map(|(i, c)| {
            let v = c.model.friction?.stiction_speed;
            (v < SLOW_STICTION_SPEED).then(|| format!("contact.{i}.friction.v_static = {v} m/s"))
        })
        .collect();
    if slow.is_empty() {
        return String::new();
    }
    format!(
        "; stiction makes the run stiff: {} is below {SLOW_STICTION_SPEED} m/s, where the \
         STEP law's slope at rest is steepest",
        slow.join(", ")
    )
}

/// What a simulation keeps besides its sampled trajectory. Crate-private: the samples
/// of [`Observed::Trajectory`] are [`Observed::Events`]' only under the conditions it
/// states, which the toss replay sets up (`replay::replay_model`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Observed {
    /// The contact events with their indicators (`Simulation::events`).
    Events,
    /// The samples alone: no event is located or tracked, `Simulation::events` stays
    /// empty. Events only observe the motion, so the samples are bit for bit those of
    /// [`Observed::Events`] when the run does not stop on contacts
    /// (`stop_after_contacts` = 0) and every tick is sampled (one record period, no
    /// margin): a toss's replay, which scores its frames alone and so skips the
    /// quarter of its work the events' peaks and work took.
    Trajectory,
}

/// Simulates `model` from t = 0 and samples its trajectory.
pub fn simulate(model: &Model) -> Result<Simulation, SimulationError> {
    simulate_observing(model, Observed::Events)
}

/// [`simulate`], keeping what `observed` says.
pub(crate) fn simulate_observing(
    model: &Model,
    observed: Observed,
) -> Result<Simulation, SimulationError> {
    run_on_path::<true>(model, observed)
}

/// [`simulate`] with the joints' loads compiled in (`JOINT_PATH` true, what [`simulate`]
/// runs) or out (false: the derivative as it was before joints). A scene with joints
/// always takes the joint path. For measuring what the joint path costs a scene without
/// joints, both in one benchmark run (`benches/ball_simulation.rs`); generic, so that
/// only a caller asking for `false` compiles that twin.
#[doc(hidden)]
pub fn simulate_on_path<const JOINT_PATH: bool>(
    model: &Model,
) -> Result<Simulation, SimulationError> {
    if !JOINT_PATH && !model.joints.is_empty() {
        return run_on_path::<true>(model, Observed::Events);
    }
    run_on_path::<JOINT_PATH>(model, Observed::Events)
}

/// [`simulate_observing`] on the derivative `JOINT_PATH` picks ([`RigidSystem`]).
fn run_on_path<const JOINT_PATH: bool>(
    model: &Model,
    observed: Observed,
) -> Result<Simulation, SimulationError> {
    fits_in_memory(model)?;
    let spec = &model.scenario.simulation;
    let record = &model.scenario.record;
    // Without events the run cannot stop on contacts nor sample them at their own rate.
    assert!(
        observed == Observed::Events
            || (spec.stop_after_contacts == 0
                && record.contact_margin == 0.0
                && record.contact_sample_period == record.flight_sample_period),
        "Observed::Trajectory needs no stop on contacts, no margin and one record period"
    );
    let layout = RigidLayout::new(model);
    let y0 = layout.initial_state(model);
    let mut system = RigidSystem::<JOINT_PATH>::on_path(model, &layout);
    system.latch(&y0.0);
    // A tracker of no contact finds no crossing and tracks no event.
    let mut tracker = match observed {
        Observed::Events => EventTracker::new(&system, 0.0, &y0.0),
        Observed::Trajectory => EventTracker::default(),
    };
    let solver_error = |cause| SimulationError::Solver {
        scenario: model.scenario.name.clone(),
        cause,
        hint: stiction_hint(model),
    };
    let mut recorder = Recorder::new(model);
    let mut stepper = RigidStepper::new(&mut system, 0.0, y0.clone(), solver_settings(spec));
    let mut scratch = y0;
    let mut end = spec.end_time;
    let mut first = true;
    while stepper.time() < end {
        if layout.quaternion_drift(&stepper.state().0) > DRIFT {
            let mut unit = stepper.state().clone();
            layout.normalise(&mut unit.0);
            let time = stepper.time();
            stepper.restart(&mut system, time, unit);
        }
        let step_start = stepper.time();
        stepper.step(&mut system, end).map_err(solver_error)?;
        for (time, c) in tracker.crossings(&system, &stepper, &mut scratch) {
            stepper.dense_output(time, &mut scratch);
            tracker.switch(&system, c, time, &scratch.0);
            if !tracker.is_open(c)
                && spec.stop_after_contacts > 0
                && tracker.lift_offs >= spec.stop_after_contacts
            {
                end = end.min(time + model.scenario.record.contact_margin);
            }
        }
        tracker.track_step(&system, &stepper, &mut scratch, step_start);
        recorder.record_step(&system, &stepper, &tracker, first);
        first = false;
        system.latch(&stepper.state().0);
    }
    tracker.finish(&system, &stepper.state().0);
    Ok(Simulation {
        events: tracker.events,
        end_time: stepper.time(),
        steps: stepper.steps(),
        run: recorder.finish(model),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Scenario;
    use std::path::Path;

    /// Every number of every sample, as bits.
    fn bits(run: &Run) -> Vec<u64> {
        (run.bodies.iter().flat_map(|t| &t.samples))
            .flat_map(|s| {
                let vectors = [
                    s.position,
                    s.velocity,
                    s.angular_velocity,
                    s.force,
                    s.torque,
                ];
                let numbers = vectors.into_iter().flatten().chain(s.orientation);
                std::iter::once(s.time).chain(numbers)
            })
            .map(f64::to_bits)
            .collect()
    }

    /// The shipped cube tossed onto its table (a bounce, a tumble, a rest), recorded at
    /// one period without a margin: the trajectory alone is the trajectory the events
    /// were tracked along, bit for bit.
    #[test]
    fn a_run_observing_its_trajectory_alone_samples_the_same_bits() {
        let text = include_str!("../../scenarios/cube_toss.toml");
        let scenario = Scenario::parse(Path::new("cube_toss.toml"), text, &[]).unwrap();
        let mut model = scenario.model().unwrap();
        model.scenario.simulation.stop_after_contacts = 0;
        let with_events = simulate_observing(&model, Observed::Events).unwrap();
        let alone = simulate_observing(&model, Observed::Trajectory).unwrap();
        assert!(!with_events.events.is_empty(), "the cube lands");
        assert!(alone.events.is_empty());
        assert_eq!(with_events.steps, alone.steps);
        assert_eq!(with_events.end_time.to_bits(), alone.end_time.to_bits());
        assert!(with_events.run.bodies[0].samples.len() > 50);
        assert_eq!(bits(&with_events.run), bits(&alone.run));
    }
}
