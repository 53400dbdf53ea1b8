//! Simulation of a scenario: integrate the equations of motion with the core's
//! adaptive Dormand–Prince solver, locate every touch-down and lift-off (δ = 0) to
//! 1e-13 s, and collect each contact event's indicators and a sampled trajectory.

mod peak;
mod record;
pub mod rigid;
mod state;
mod system;

pub use state::{Layout, StateVector};
pub use system::{ContactModes, ContactSystem, Loads};

use crate::dataset::Run;
use crate::indicators::Indicators;
use crate::scenario::{Model, SimulationSpec};
use hcm_core::integrate::{locate_crossing, Dopri5, IntegrationError, OdeState, Settings};

/// Event times are located to this accuracy (s).
const EVENT_TOLERANCE: f64 = 1e-13;

/// One contact event: from touch-down to lift-off of one contact pair.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactEvent {
    /// Index of the contact in the model.
    pub contact: usize,
    /// Touch-down time (s), located at δ = 0.
    pub touch_down: f64,
    /// Lift-off time (s), located at δ = 0; `None` if the run ended in contact.
    pub lift_off: Option<f64>,
    /// Indentation rate at touch-down, δ̇_in (m/s).
    pub approach_speed: f64,
    /// −δ̇ at lift-off, δ̇_out (m/s).
    pub separation_speed: f64,
    /// Maximum normal force over the contact (N), from the dense output.
    pub max_force: f64,
    /// Normal impulse ∫f_n dt (N·s), integrated with the motion.
    pub impulse: f64,
    /// Work absorbed by the contact ∫f_n·δ̇ dt (J): the energy it dissipated.
    pub work: f64,
    /// Kinetic energy of the pair's moving bodies at touch-down (J).
    pub kinetic_energy_in: f64,
    /// Kinetic energy of the pair's moving bodies at lift-off (J).
    pub kinetic_energy_out: f64,
    /// Effective mass of the pair (kg).
    pub effective_mass: f64,
}

impl ContactEvent {
    /// The paper's four indicators of this event (energy loss as the relative-motion
    /// energy ½·m_e·(δ̇_in² − δ̇_out²)); `None` if the contact never ended.
    pub fn indicators(&self) -> Option<Indicators> {
        let lift_off = self.lift_off?;
        Some(Indicators {
            max_force: self.max_force,
            impulse: self.impulse,
            energy_loss: 0.5
                * self.effective_mass
                * (self.approach_speed.powi(2) - self.separation_speed.powi(2)),
            duration: lift_off - self.touch_down,
        })
    }
}

/// A simulated run.
#[derive(Clone, Debug)]
pub struct Simulation {
    /// Contact events in order of touch-down (1D scenarios).
    pub events: Vec<ContactEvent>,
    /// Contact events of body pairs in 3D scenarios ([`Model::is_rigid`]), in order
    /// of touch-down.
    pub pair_events: Vec<rigid::PairEvent>,
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
        scenario: String,
        cause: IntegrationError,
        /// What else to check for this model (e.g. a friction transition speed).
        hint: String,
    },
    /// A contact's parameter noise names a parameter its law does not have.
    #[error("contact {contact}: parameter noise: {source}")]
    Noise {
        contact: usize,
        source: hcm_core::LawError,
    },
}

/// The solver settings a scenario's `[simulation]` table asks for.
fn solver_settings(spec: &SimulationSpec) -> Settings<f64> {
    Settings {
        max_step: spec.max_step,
        max_steps: spec.max_steps,
        ..Settings::new(spec.relative_tolerance, spec.absolute_tolerance)
    }
}

/// One stretch of solver output with constant contact modes.
#[derive(Clone)]
pub(crate) struct Segment {
    pub start: f64,
    pub end: f64,
    pub stepper: Dopri5<f64, StateVector>,
    pub modes: ContactModes,
}

/// Simulates `model` from t = 0 and samples its trajectory: in 3D
/// ([`rigid::simulate_rigid`]) when [`Model::is_rigid`], else along the line of
/// centres with events located per contact.
pub fn simulate(model: &Model) -> Result<Simulation, SimulationError> {
    if model.is_rigid() {
        return rigid::simulate_rigid(model);
    }
    let spec = &model.scenario.simulation;
    let layout = Layout::new(model);
    let mut y0 = layout.initial_state(model);
    let modes = ContactModes {
        touching: vec![false; model.contacts.len()],
        approach_speed: vec![0.0; model.contacts.len()],
    };
    let mut system = ContactSystem::new(model, &layout, modes);
    let mut events: Vec<ContactEvent> = Vec::new();
    let mut open: Vec<Option<usize>> = vec![None; model.contacts.len()];
    for (c, slot) in open.iter_mut().enumerate() {
        let k = system.kinematics(&y0.0, c);
        if k.depth > 0.0 || (k.depth == 0.0 && k.rate > 0.0) {
            *slot = Some(events.len());
            y0.0[layout.deepest_index(c)] = k.depth.max(0.0);
            events.push(touch_down(
                model,
                &layout,
                &mut system.modes,
                c,
                0.0,
                &y0.0,
                k.rate,
            ));
        }
    }
    let solver_error = |cause| SimulationError::Solver {
        scenario: model.scenario.name.clone(),
        cause,
        hint: String::new(),
    };
    let mut stepper = Dopri5::new(&mut system, 0.0, y0.clone(), solver_settings(spec));
    let mut scratch = y0;
    let mut segments: Vec<Segment> = Vec::new();
    // Best grid point of each event's force, refined once the event ends.
    let mut peaks: Vec<Option<peak::PeakCandidate>> = vec![None; events.len()];
    let mut end = spec.end_time;
    let mut lift_offs = 0;
    while stepper.time() < end {
        stepper.step(&mut system, end).map_err(solver_error)?;
        let event = earliest_crossing(&system, &stepper, &mut scratch);
        let segment_end = event.map_or(stepper.time(), |(t, _)| t);
        for (c, index) in open.iter().enumerate() {
            if let Some(e) = *index {
                let span = (stepper.previous_time(), segment_end);
                let candidate = peak::grid_max(&system, &stepper, c, span, segments.len());
                if peaks[e].is_none_or(|best| candidate.force > best.force) {
                    peaks[e] = Some(candidate);
                }
            }
        }
        segments.push(Segment {
            start: stepper.previous_time(),
            end: segment_end,
            stepper: stepper.clone(),
            modes: system.modes.clone(),
        });
        let Some((time, c)) = event else { continue };
        stepper.dense_output(time, &mut scratch);
        let mut y = scratch.clone();
        let rate = system.kinematics(&y.0, c).rate;
        match open[c].take() {
            Some(e) => {
                events[e].max_force = refined_peak(model, &layout, &segments, c, peaks[e]);
                lift_off(
                    model,
                    &layout,
                    &mut system.modes,
                    &mut events[e],
                    time,
                    &y.0,
                    rate,
                );
                lift_offs += 1;
                if spec.stop_after_contacts > 0 && lift_offs >= spec.stop_after_contacts {
                    end = end.min(time + model.scenario.record.contact_margin);
                }
            }
            None => {
                open[c] = Some(events.len());
                peaks.push(None);
                y.0[layout.deepest_index(c)] = 0.0;
                events.push(touch_down(
                    model,
                    &layout,
                    &mut system.modes,
                    c,
                    time,
                    &y.0,
                    rate,
                ));
            }
        }
        stepper.restart(&mut system, time, y);
    }
    // Contacts still open at the end keep their running totals.
    for (c, index) in open.iter().enumerate() {
        if let Some(e) = *index {
            events[e].max_force = refined_peak(model, &layout, &segments, c, peaks[e]);
            let i = layout.impulse_index(c);
            let y = stepper.state().components();
            events[e].impulse = y[i] - events[e].impulse;
            events[e].work = y[i + 1] - events[e].work;
        }
    }
    let end_time = stepper.time();
    let run = record::sample(model, &layout, &segments, &events, end_time);
    Ok(Simulation {
        events,
        pair_events: Vec::new(),
        end_time,
        steps: (stepper.accepted_steps(), stepper.rejected_steps()),
        run,
    })
}

/// The event's peak force (N): the golden-section refinement around its best grid
/// point, in the solver step that holds it.
fn refined_peak(
    model: &Model,
    layout: &Layout,
    segments: &[Segment],
    c: usize,
    candidate: Option<peak::PeakCandidate>,
) -> f64 {
    let Some(candidate) = candidate else {
        return 0.0;
    };
    let segment = &segments[candidate.segment];
    let system = ContactSystem::new(model, layout, segment.modes.clone());
    peak::refine(
        &system,
        &segment.stepper,
        c,
        candidate,
        (segment.start, segment.end),
    )
}

/// The first δ = 0 crossing in the last step that changes a contact's mode:
/// (time, contact).
fn earliest_crossing(
    system: &ContactSystem,
    stepper: &Dopri5<f64, StateVector>,
    scratch: &mut StateVector,
) -> Option<(f64, usize)> {
    let mut earliest: Option<(f64, usize)> = None;
    for c in 0..system.model.contacts.len() {
        let before = system.kinematics(&stepper.previous_state().0, c).depth;
        let after = system.kinematics(&stepper.state().0, c).depth;
        let crossing = if system.modes.touching[c] {
            before > 0.0 && after <= 0.0
        } else {
            before <= 0.0 && after > 0.0
        };
        if !crossing {
            continue;
        }
        let depth = |_t: f64, y: &StateVector| system.kinematics(&y.0, c).depth;
        if let Some(t) = locate_crossing(stepper, depth, EVENT_TOLERANCE, scratch) {
            if earliest.is_none_or(|(best, _)| t < best) {
                earliest = Some((t, c));
            }
        }
    }
    earliest
}

/// Kinetic energy (J) of the moving bodies of contact `c` in state `y`.
fn pair_kinetic_energy(model: &Model, layout: &Layout, c: usize, y: &[f64]) -> f64 {
    let contact = &model.contacts[c];
    [contact.body_1, contact.body_2]
        .into_iter()
        .filter(|&b| !model.bodies[b].fixed)
        .map(|b| 0.5 * model.bodies[b].mass * layout.motion(model, y, b).1.norm_squared())
        .sum()
}

fn touch_down(
    model: &Model,
    layout: &Layout,
    modes: &mut ContactModes,
    c: usize,
    time: f64,
    y: &[f64],
    rate: f64,
) -> ContactEvent {
    modes.touching[c] = true;
    modes.approach_speed[c] = rate;
    let i = layout.impulse_index(c);
    ContactEvent {
        contact: c,
        touch_down: time,
        lift_off: None,
        approach_speed: rate,
        separation_speed: f64::NAN,
        max_force: 0.0,
        // Running totals at touch-down; replaced by the increments at lift-off.
        impulse: y[i],
        work: y[i + 1],
        kinetic_energy_in: pair_kinetic_energy(model, layout, c, y),
        kinetic_energy_out: f64::NAN,
        effective_mass: model.contacts[c].effective_mass,
    }
}

fn lift_off(
    model: &Model,
    layout: &Layout,
    modes: &mut ContactModes,
    event: &mut ContactEvent,
    time: f64,
    y: &[f64],
    rate: f64,
) {
    let c = event.contact;
    modes.touching[c] = false;
    let i = layout.impulse_index(c);
    event.lift_off = Some(time);
    event.separation_speed = -rate;
    event.impulse = y[i] - event.impulse;
    event.work = y[i + 1] - event.work;
    event.kinetic_energy_out = pair_kinetic_energy(model, layout, c, y);
}
