//! Sampling a 3D run into the measured-data format while it is integrated: the
//! contact rate inside contact events (and a margin around them), the flight rate
//! elsewhere, on one grid of integer ticks.

use super::event::EventTracker;
use super::stepper::RigidStepper;
use super::system::RigidSystem;
use crate::dataset::{BodyTrack, Run, Sample};
use crate::scenario::Model;
use hcm_core::integrate::DenseOutput;
use nalgebra::Vector3;
use std::collections::{BTreeMap, VecDeque};

/// One accepted step kept for sampling: (start (s), end (s), its dense output).
type Step = (f64, f64, RigidStepper);

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
    /// Earlier steps covering `margin` before the current one (none when the margin
    /// is 0).
    recent: VecDeque<Step>,
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
        }
    }

    /// Samples the step just taken: the ticks in (start, end], at the contact rate
    /// where `events` say a contact (or its margin) is, and — for a touch-down found
    /// in this step — the margin before it, from the recent steps.
    pub fn record_step(
        &mut self,
        system: &RigidSystem<'_>,
        stepper: &RigidStepper,
        events: &EventTracker,
        first: bool,
    ) {
        let (start, end) = (stepper.previous_time(), stepper.time());
        while self
            .recent
            .front()
            .is_some_and(|s| s.1 < start - self.margin)
        {
            self.recent.pop_front();
        }
        let from = if first {
            0
        } else {
            (start / self.tick).floor() as u64 + 1
        };
        let lookback = (start - self.margin).max(0.0);
        let lookback_from = (lookback / self.tick).ceil() as u64;
        let ticks = self.candidates(events, (lookback_from.min(from), from), end);
        for k in ticks {
            let t = k as f64 * self.tick;
            let dense = in_window(events, t, self.margin);
            if self.samples.contains_key(&k) || !(dense || (k >= from && k % self.stride == 0)) {
                continue;
            }
            // This step's own ticks from its dense output; earlier ones (the margin
            // before a touch-down) from the steps kept for it.
            let step = if t >= start {
                Some(stepper)
            } else {
                self.recent
                    .iter()
                    .find(|s| s.0 <= t && t <= s.1)
                    .map(|s| &s.2)
            };
            if let Some(step) = step {
                let samples = sample_at(system, step, t, &self.recorded);
                self.samples.insert(k, samples);
            }
        }
        // Kept only when a later touch-down may need samples before its step; with no
        // margin, no step is copied.
        if self.margin > 0.0 {
            self.recent.push_back((start, end, stepper.clone()));
        }
    }

    /// The ticks from `low` to `end` (s) that may be sampled, in order: the flight
    /// ticks from `from` on and the ticks near an event (a superset of [`in_window`]'s:
    /// the caller decides). Walking every tick of a long flight step (1000 per ms at
    /// 1 µs) cost more than the rest of the ball's simulation.
    fn candidates(&self, events: &EventTracker, (low, from): (u64, u64), end: f64) -> Vec<u64> {
        let high = (end / self.tick).floor() as u64;
        let first_flight = from.div_ceil(self.stride) * self.stride;
        let mut ticks: Vec<u64> = (first_flight..=high)
            .step_by(self.stride as usize)
            .collect();
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
        ticks
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

/// Every recorded body at time `t` (s) of `step`'s dense output.
fn sample_at(
    system: &RigidSystem<'_>,
    step: &RigidStepper,
    t: f64,
    recorded: &[usize],
) -> Vec<Sample> {
    let mut y = step.state().clone();
    step.dense_output(t, &mut y);
    let mut loads: Vec<(Vector3<f64>, Vector3<f64>)> = Vec::new();
    system.body_loads(&y.0, &mut loads);
    recorded
        .iter()
        .map(|&b| {
            let pose = system.layout.pose(system.model, &y.0, b);
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
