//! The simulator's tracking of contact events ([`ContactEvent`]): touch-down and
//! lift-off located where the pair's signed separation crosses zero on the solver's
//! dense output, the peaks, impulses and work accumulated step by step.

use super::layout::StateVector;
use super::stepper::RigidStepper;
use super::system::RigidSystem;
use crate::indicators::ContactEvent;
use crate::scenario::{pair_rate, pair_separation, Pose};
use crate::scenario::{Contact, Model};
use hcm_core::integrate::{locate_crossing, DenseOutput};
use nalgebra::Vector3;

/// Event times are located to this accuracy (s).
const EVENT_TOLERANCE: f64 = 1e-13;
/// Points inside each solver step (besides its end) at which a contact's force and
/// torque are evaluated for their maxima: the peaks are read off a grid of a quarter
/// step, an error of ~(h/8)²·|F''|/2 — 3e-5 relative for a contact resolved by 50
/// steps (the shipped ball, ~100 steps: 1e-6).
const PEAK_SUBSTEPS: usize = 3;
/// Boole's rule on the step's start and the peak grid (weights × 90/h): the contact's
/// work per step, exact for a power polynomial of degree 5 in time.
const BOOLE: [f64; PEAK_SUBSTEPS + 2] = [7.0, 32.0, 12.0, 32.0, 7.0];

/// The events found so far and which are open.
#[derive(Clone, Debug, Default)]
pub struct EventTracker {
    /// Every event, in order of touch-down.
    pub(crate) events: Vec<ContactEvent>,
    /// Per contact, the index of its open event.
    open: Vec<Option<usize>>,
    /// Per event, the impulse integrals (N·s, N·m·s) at its touch-down.
    start_impulse: Vec<[f64; 6]>,
    /// Per event, the end (s) of the last step it was tracked in and the contact's
    /// power there (W): the next step's first Boole point.
    end_power: Vec<(f64, f64)>,
    /// Lift-offs so far.
    pub(crate) lift_offs: usize,
}

impl EventTracker {
    /// A tracker of `contacts` contacts with the pairs already touching in `y`
    /// opened at `time` (s): overlapping, or touching (separation 0) and approaching.
    pub fn new<const JOINT_PATH: bool>(
        system: &RigidSystem<'_, JOINT_PATH>,
        time: f64,
        y: &[f64],
    ) -> Self {
        let contacts = system.model.contacts.len();
        let mut tracker = EventTracker {
            open: vec![None; contacts],
            ..EventTracker::default()
        };
        for c in 0..contacts {
            let gap = separation(system, y, c);
            if gap < 0.0 || (gap == 0.0 && rate(system, y, c) > 0.0) {
                tracker.touch_down(system, c, time, y);
            }
        }
        tracker
    }

    /// Whether contact `c` is in an open event.
    pub fn is_open(&self, c: usize) -> bool {
        self.open[c].is_some()
    }

    /// Every touch-down and lift-off inside the last step, in time order: (time (s),
    /// contact). A pair that touches and lets go within one step is not seen (the
    /// scenario's `max_step` bounds how short a missed contact can be).
    pub fn crossings<const JOINT_PATH: bool>(
        &self,
        system: &RigidSystem<'_, JOINT_PATH>,
        stepper: &RigidStepper,
        scratch: &mut StateVector,
    ) -> Vec<(f64, usize)> {
        let mut found = Vec::new();
        for c in 0..self.open.len() {
            let after = separation(system, &stepper.state().0, c);
            let changed = if self.is_open(c) {
                after >= 0.0
            } else {
                after < 0.0
            };
            if !changed {
                continue;
            }
            let gap = |_t: f64, y: &StateVector| separation(system, &y.0, c);
            let time = locate_crossing(stepper, gap, EVENT_TOLERANCE, scratch)
                .unwrap_or_else(|| stepper.time());
            found.push((time, c));
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        found
    }

    /// Switches contact `c` at `time` (s), `y` the state there: opens or closes its
    /// event.
    pub fn switch<const JOINT_PATH: bool>(
        &mut self,
        system: &RigidSystem<'_, JOINT_PATH>,
        c: usize,
        time: f64,
        y: &[f64],
    ) {
        match self.open[c].take() {
            Some(e) => {
                self.close(system, e, y);
                let event = &mut self.events[e];
                event.lift_off = Some(time);
                event.separation_speed = -rate(system, y, c);
                event.kinetic_energy_out = kinetic_energy(system, y, c);
                self.lift_offs += 1;
            }
            None => self.touch_down(system, c, time, y),
        }
    }

    /// Event `e`'s impulses: the integrals in `y` less those at its touch-down.
    fn close<const JOINT_PATH: bool>(
        &mut self,
        system: &RigidSystem<'_, JOINT_PATH>,
        e: usize,
        y: &[f64],
    ) {
        let start = self.start_impulse[e];
        let event = &mut self.events[e];
        let i = system.layout.impulse_index(event.contact);
        event.linear_impulse = Vector3::from_fn(|k, _| y[i + k] - start[k]);
        event.angular_impulse = Vector3::from_fn(|k, _| y[i + 3 + k] - start[3 + k]);
        if !event.approach_speed.is_nan() {
            event.normal_impulse = event.linear_impulse.norm();
        }
    }

    fn touch_down<const JOINT_PATH: bool>(
        &mut self,
        system: &RigidSystem<'_, JOINT_PATH>,
        c: usize,
        time: f64,
        y: &[f64],
    ) {
        let i = system.layout.impulse_index(c);
        self.open[c] = Some(self.events.len());
        self.start_impulse.push(std::array::from_fn(|k| y[i + k]));
        self.end_power.push((f64::NAN, 0.0));
        self.events.push(ContactEvent {
            approach_speed: rate(system, y, c),
            work: 0.0,
            kinetic_energy_in: kinetic_energy(system, y, c),
            effective_mass: system.model.contacts[c].effective_mass,
            ..ContactEvent::starting(c, time)
        });
    }

    /// Updates every event that was open during the last step: its maxima on a grid
    /// of `PEAK_SUBSTEPS` inner points and the step's end, and its work by Boole's
    /// rule on that grid and the step's start.
    pub fn track_step<const JOINT_PATH: bool>(
        &mut self,
        system: &RigidSystem<'_, JOINT_PATH>,
        stepper: &RigidStepper,
        scratch: &mut StateVector,
        step_start: f64,
    ) {
        let end = stepper.time();
        let intervals = (PEAK_SUBSTEPS + 1) as f64;
        for (event, last) in self.events.iter_mut().zip(&mut self.end_power) {
            if event.lift_off.is_some_and(|t| t < step_start) {
                continue;
            }
            let from = event.touch_down.max(step_start);
            let until = event.lift_off.unwrap_or(end).min(end);
            let mut work = 0.0;
            for (k, weight) in BOOLE.iter().enumerate() {
                let t = step_start + (end - step_start) * k as f64 / intervals;
                if t < from || t > until {
                    continue;
                }
                if k == 0 {
                    // The last step's end: the same state (renormalised at most), and
                    // the same force (a latch keeps it continuous); else evaluated.
                    let power = if last.0 == step_start {
                        last.1
                    } else {
                        let start = &stepper.previous_state().0;
                        system.contact_load(start, event.contact).dissipation
                    };
                    work += weight * power;
                    continue;
                }
                stepper.dense_output(t, scratch);
                let load = system.contact_load(&scratch.0, event.contact);
                event.max_force = event.max_force.max(load.on_mover.0.norm());
                event.max_torque = event.max_torque.max(load.on_mover.1.norm());
                event.max_points = event.max_points.max(load.points);
                work += weight * load.dissipation;
                if k == PEAK_SUBSTEPS + 1 {
                    *last = (end, load.dissipation);
                }
            }
            event.work += work * (end - step_start) / 90.0;
        }
    }

    /// Closes the events still open at the end `time` (s) of the run, state `y`:
    /// their impulses so far, lift-off left `None`.
    pub fn finish<const JOINT_PATH: bool>(
        &mut self,
        system: &RigidSystem<'_, JOINT_PATH>,
        y: &[f64],
    ) {
        for c in 0..self.open.len() {
            if let Some(e) = self.open[c].take() {
                self.close(system, e, y);
            }
        }
    }
}

/// Contact `c`'s signed separation (m) in state `y`.
fn separation<const JOINT_PATH: bool>(
    system: &RigidSystem<'_, JOINT_PATH>,
    y: &[f64],
    c: usize,
) -> f64 {
    at_poses(system, y, c, pair_separation)
}

/// Contact `c`'s indentation rate δ̇ (m/s) in state `y` (see [`pair_rate`]).
fn rate<const JOINT_PATH: bool>(system: &RigidSystem<'_, JOINT_PATH>, y: &[f64], c: usize) -> f64 {
    at_poses(system, y, c, pair_rate)
}

/// `of` (a pair quantity of the contact geometry) for contact `c` at its two bodies'
/// poses in state `y`.
fn at_poses<const JOINT_PATH: bool>(
    system: &RigidSystem<'_, JOINT_PATH>,
    y: &[f64],
    c: usize,
    of: impl Fn(&Model, &Contact, &Pose, &Pose) -> f64,
) -> f64 {
    let contact = &system.model.contacts[c];
    let pose = |b| system.layout.pose(system.model, y, b);
    of(
        system.model,
        contact,
        &pose(contact.body_1),
        &pose(contact.body_2),
    )
}

/// Kinetic energy (J) of contact `c`'s moving bodies in state `y`.
fn kinetic_energy<const JOINT_PATH: bool>(
    system: &RigidSystem<'_, JOINT_PATH>,
    y: &[f64],
    c: usize,
) -> f64 {
    let contact = &system.model.contacts[c];
    system.kinetic_energy(y, contact.body_1) + system.kinetic_energy(y, contact.body_2)
}
