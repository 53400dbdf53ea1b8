//! What S1 says about a rigid body's contact events, and where to replay them from
//! (the fitness: each run replayed from its recorded pre-contact state).
//!
//! The events' statistics are the S2 statistics' ([`wrench_statistics`]: events
//! matched by order over the runs with the usual event count, the others left out and
//! listed); to them this adds when each event starts after the first. The replay starts
//! from the mean of the matched runs' pre-contact states ([`pre_contact_states`]).

use super::RigidIdentifyError;
use crate::dataset::{Dataset, Sample};
use crate::experiment::{pre_contact_states, replay_model, PreContact};
use crate::indicators::{
    pair_events_from_run, wrench_statistics, EventCountMismatch, RecordedEvent,
    WrenchEventStatistics,
};
use crate::scenario::Model;
use nalgebra::Vector4;

/// One contact event as S1 measured it.
#[derive(Clone, Debug, PartialEq)]
pub struct EventTarget {
    /// Mean and standard error of each indicator over the matched runs.
    pub(crate) statistics: WrenchEventStatistics,
    /// Mean time from the first event's touch-down to this one's (s); 0 for the first.
    pub delay: f64,
}

/// The measured events of one contact and the state to replay them from.
#[derive(Clone, Debug)]
pub struct WrenchTarget {
    /// Index of the contact in the model.
    pub(crate) contact: usize,
    /// The model started from the matched runs' mean pre-contact state, stopping
    /// after the last target event.
    pub model: Model,
    /// The events, in order of occurrence.
    pub events: Vec<EventTarget>,
    /// Runs in the data.
    pub runs: usize,
    /// Runs left out because their event count is not the usual one.
    pub left_out: Vec<EventCountMismatch>,
}

impl WrenchTarget {
    /// Contact `c`'s events in `data`: all the usual ones, or the first `events` of
    /// them when given.
    pub fn from_data(
        model: &Model,
        data: &Dataset,
        c: usize,
        events: Option<usize>,
    ) -> Result<WrenchTarget, RigidIdentifyError> {
        if c >= model.contacts.len() {
            return Err(RigidIdentifyError::NoSuchContact(c));
        }
        let mut found: Vec<RecordedEvent> = Vec::new();
        for run in &data.runs {
            found.extend(
                pair_events_from_run(model, run)?
                    .into_iter()
                    .filter(|e| e.event.contact == c),
            );
        }
        let ids: Vec<String> = data.runs.iter().map(|r| r.id.clone()).collect();
        let statistics = wrench_statistics(&ids, &found)
            .into_iter()
            .next()
            .filter(|s| s.expected_events > 0)
            .ok_or(RigidIdentifyError::TooFewEvents {
                wanted: events.unwrap_or(1),
                usual: 0,
            })?;
        let wanted = events.unwrap_or(statistics.expected_events);
        if wanted == 0 || wanted > statistics.expected_events {
            return Err(RigidIdentifyError::TooFewEvents {
                wanted,
                usual: statistics.expected_events,
            });
        }
        let left_out = statistics.mismatched_runs.clone();
        let matched: Vec<_> = (data.runs.iter())
            .filter(|r| !left_out.iter().any(|m| m.run == r.id))
            .cloned()
            .collect();
        let delay = |k: usize| {
            let delays: Vec<f64> = matched
                .iter()
                .filter_map(|run| {
                    let own = |n: usize| found.iter().find(|e| e.run == run.id && e.number == n);
                    Some(own(k)?.touch_down() - own(0)?.touch_down())
                })
                .collect();
            delays.iter().sum::<f64>() / delays.len().max(1) as f64
        };
        let targets = (statistics.events.into_iter().take(wanted).enumerate())
            .map(|(k, statistics)| EventTarget {
                statistics,
                delay: delay(k),
            })
            .collect();
        let starts = pre_contact_states(model, &matched)?;
        let mut start = replay_model(model, &mean_pre_contact(&starts));
        start.scenario.simulation.stop_after_contacts = wanted;
        Ok(WrenchTarget {
            contact: c,
            model: start,
            events: targets,
            runs: data.runs.len(),
            left_out,
        })
    }
}

/// The mean of pre-contact states of the same bodies: time, position, velocity and
/// angular velocity componentwise; orientation the normalised sum of the quaternions,
/// each turned to the first one's hemisphere (q and −q are one rotation).
fn mean_pre_contact(starts: &[PreContact]) -> PreContact {
    let n = starts.len().max(1) as f64;
    let mean = |f: &dyn Fn(&PreContact) -> f64| starts.iter().map(f).sum::<f64>() / n;
    let first = starts.first();
    let states = first.map_or_else(Vec::new, |first| {
        (first.states.iter().enumerate())
            .map(|(b, (index, reference))| {
                let sample = |p: &PreContact| p.states.get(b).map(|s| s.1.clone());
                let all: Vec<Sample> = starts.iter().filter_map(sample).collect();
                (*index, mean_sample(reference, &all))
            })
            .collect()
    });
    PreContact {
        run: "mean".to_owned(),
        time: mean(&|p| p.time),
        touch_down: mean(&|p| p.touch_down),
        states,
    }
}

/// The componentwise mean of `samples`, orientation as in [`mean_pre_contact`].
fn mean_sample(reference: &Sample, samples: &[Sample]) -> Sample {
    let n = samples.len().max(1) as f64;
    let mean3 = |f: fn(&Sample) -> [f64; 3]| -> [f64; 3] {
        core::array::from_fn(|i| samples.iter().map(|s| f(s)[i]).sum::<f64>() / n)
    };
    let hemisphere = Vector4::from(reference.orientation);
    let sum: Vector4<f64> = samples
        .iter()
        .map(|s| Vector4::from(s.orientation))
        .map(|q| if q.dot(&hemisphere) < 0.0 { -q } else { q })
        .sum();
    let unit = sum / sum.norm();
    Sample {
        time: samples.iter().map(|s| s.time).sum::<f64>() / n,
        position: mean3(|s| s.position),
        orientation: [unit[0], unit[1], unit[2], unit[3]],
        velocity: mean3(|s| s.velocity),
        angular_velocity: mean3(|s| s.angular_velocity),
        force: mean3(|s| s.force),
        torque: mean3(|s| s.torque),
    }
}
