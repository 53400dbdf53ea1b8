//! Sampling a run into the measured-data format while it is integrated: the
//! contact rate inside contact events (and a margin around them), the flight rate
//! elsewhere, on one grid of integer ticks.

use super::event::EventTracker;
use super::layout::StateVector;
use super::stepper::RigidStepper;
use super::system::RigidSystem;
use crate::dataset::{BodyTrack, Run, Sample};
use crate::scenario::Model;
use hcm_core::integrate::DenseOutput;
use nalgebra::Vector3;
use std::collections::{BTreeMap, VecDeque};

/// Collects the samples of a run.
pub struct Recorder {
    /// Contact sample period (s): one tick.
    tick: f64,
    /// Ticks between flight samples.
    stride: u64,
    /// Time sampled at the contact rate around each event (s).
    margin: f64,
    /// The bodies recorded (indices).
    recorded: Vec<usize>,
    /// Samples by tick, one per recorded body.
    samples: BTreeMap<u64, Vec<Sample>>,
    /// Copies of the earlier steps that end within `margin` of the current one's
    /// start, oldest first (none when the margin is 0), for the margin before a
    /// touch-down found later: a copy costs less than the dense outputs at every tick
    /// that might be wanted.
    recent: VecDeque<RigidStepper>,
    /// Copies of `recent` no longer needed, reused.
    spare: Vec<RigidStepper>,
    /// The working state.
    working: Option<StateVector>,
    /// The loads on every body at a sample, reused.
    loads: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// The ticks a step may sample, reused.
    ticks: Vec<u64>,
}

impl Recorder {
    /// A recorder for `model`'s `record` settings.
    pub fn new(model: &Model) -> Self {
        let record = &model.scenario.record;
        let wanted = &record.bodies;
        Recorder {
            tick: record.contact_sample_period,
            stride: (record.flight_sample_period / record.contact_sample_period)
                .round()
                .max(1.0) as u64,
            margin: record.contact_margin,
            recorded: (0..model.bodies.len())
                .filter(|&b| wanted.is_empty() || wanted.contains(&model.bodies[b].name))
                .collect(),
            samples: BTreeMap::new(),
            recent: VecDeque::new(),
            spare: Vec::new(),
            working: None,
            loads: Vec::new(),
            ticks: Vec::new(),
        }
    }

    /// Samples the step just taken: the ticks in (start, end], at the contact rate
    /// where `events` say a contact (or its margin) is, and — for a touch-down found
    /// in this step — the margin before it, from the recent steps.
    pub fn record_step<const JOINT_PATH: bool>(
        &mut self,
        system: &RigidSystem<'_, JOINT_PATH>,
        stepper: &RigidStepper,
        events: &EventTracker,
        first: bool,
    ) {
        let (start, end) = (stepper.previous_time(), stepper.time());
        while self
            .recent
            .front()
            .is_some_and(|kept| kept.time() < start - self.margin)
        {
            self.spare.extend(self.recent.pop_front());
        }
        let mut y = self
            .working
            .take()
            .unwrap_or_else(|| stepper.state().clone());
        let from = if first {
            0
        } else {
            (start / self.tick).floor() as u64 + 1
        };
        let lookback = (start - self.margin).max(0.0);
        let lookback_from = (lookback / self.tick).ceil() as u64;
        let mut ticks = std::mem::take(&mut self.ticks);
        self.candidates(events, (lookback_from.min(from), from), end, &mut ticks);
        for &k in &ticks {
            let t = k as f64 * self.tick;
            let dense = in_window(events, t, self.margin);
            if self.samples.contains_key(&k) || !(dense || (k >= from && k % self.stride == 0)) {
                continue;
            }
            // This step's own ticks from its dense output; earlier ones (the margin
            // before a touch-down) from the oldest kept step that covers them.
            let covering = if t >= start {
                Some(stepper)
            } else {
                self.recent
                    .iter()
                    .find(|s| s.previous_time() <= t && t <= s.time())
            };
            if let Some(step) = covering {
                step.dense_output(t, &mut y);
                let samples = sample_at(system, &y.0, t, &self.recorded, &mut self.loads);
                self.samples.insert(k, samples);
            }
        }
        self.ticks = ticks;
        self.working = Some(y);
        self.keep(stepper);
    }

    /// Keeps a copy of the step just taken for a touch-down found in a later step;
    /// with no margin, none.
    fn keep(&mut self, stepper: &RigidStepper) {
        if self.margin <= 0.0 {
            return;
        }
        let copy = match self.spare.pop() {
            Some(mut copy) => {
                copy.clone_from(stepper);
                copy
            }
            None => stepper.clone(),
        };
        self.recent.push_back(copy);
    }

    /// Writes into `ticks` those from `low` to `end` (s) that may be sampled, in order:
    /// the flight ticks from `from` on and the ticks near an event (a superset of
    /// [`in_window`]'s: the caller decides). Walking every tick of a long flight step
    /// (1000 per ms at 1 µs) cost more than the rest of the ball's simulation.
    fn candidates(
        &self,
        events: &EventTracker,
        (low, from): (u64, u64),
        end: f64,
        ticks: &mut Vec<u64>,
    ) {
        let high = (end / self.tick).floor() as u64;
        let first_flight = from.div_ceil(self.stride) * self.stride;
        ticks.clear();
        ticks.extend((first_flight..=high).step_by(self.stride as usize));
        let low_time = low as f64 * self.tick;
        for e in &events.events {
            let until = e.lift_off.map_or(f64::INFINITY, |off| off + self.margin);
            if until < low_time || e.touch_down - self.margin > end {
                continue;
            }
            // One tick of slack either side: `in_window` decides.
            let a = ((e.touch_down - self.margin) / self.tick).floor().max(0.0) as u64;
            let b = (until / self.tick).ceil().min(high as f64) as u64;
            ticks.extend(a.saturating_sub(1).max(low)..=(b + 1).min(high));
        }
        ticks.sort_unstable();
        ticks.dedup();
    }

    /// The run sampled so far (id `"0"`).
    pub fn finish(self, model: &Model) -> Run {
        let mut tracks: Vec<BodyTrack> = self
            .recorded
            .iter()
            .map(|&b| BodyTrack {
                body: model.bodies[b].name.clone(),
                samples: Vec::new(),
            })
            .collect();
        for samples in self.samples.into_values() {
            for (track, sample) in tracks.iter_mut().zip(samples) {
                track.samples.push(sample);
            }
        }
        Run {
            id: "0".into(),
            bodies: tracks,
        }
    }
}

/// Whether `t` (s) lies in an event or within `margin` (s) of one.
fn in_window(events: &EventTracker, t: f64, margin: f64) -> bool {
    events
        .events
        .iter()
        .any(|e| e.touch_down - margin <= t && e.lift_off.is_none_or(|off| t <= off + margin))
}

/// Every recorded body at time `t` (s), in state `y`; `loads` is working space.
fn sample_at<const JOINT_PATH: bool>(
    system: &RigidSystem<'_, JOINT_PATH>,
    y: &[f64],
    t: f64,
    recorded: &[usize],
    loads: &mut Vec<(Vector3<f64>, Vector3<f64>)>,
) -> Vec<Sample> {
    system.body_loads(y, loads);
    recorded
        .iter()
        .map(|&b| {
            let pose = system.layout.pose(system.model, y, b);
            let q = pose.orientation.quaternion();
            Sample {
                time: t,
                position: pose.position.into(),
                orientation: [q.w, q.i, q.j, q.k],
                velocity: pose.velocity.into(),
                angular_velocity: pose.angular_velocity.into(),
                force: loads[b].0.into(),
                torque: loads[b].1.into(),
            }
        })
        .collect()
}
