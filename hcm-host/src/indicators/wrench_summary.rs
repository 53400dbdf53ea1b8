//! The S2 statistics of the 3D indicators (the paper's Table 15 reference values): per
//! contact and per event of it (1st wall contact, 2nd, …), the mean over the runs of a
//! set and its standard error, for the maximum force and torque, the linear and
//! angular impulse, and the duration.
//!
//! Events are matched by their order within a run. Noise can change how many events a
//! run has (a sliding contact that lifts off for a few µs becomes two), and matching
//! such a run by order would set a fragment beside whole contacts. So each contact
//! takes the event count most runs have (the smallest, on a tie) as its expected count;
//! only runs with exactly that count enter its statistics, and every other run is
//! listed with its count — counted and reported, never silently misaligned.

use super::{RecordedEvent, WrenchIndicators};
use serde::Serialize;

/// The mean of a quantity over runs with its standard error (the quantity's unit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Estimate {
    /// Mean over the runs.
    pub mean: f64,
    /// Standard error of the mean, s/√n with s the sample standard deviation (n − 1);
    /// NaN (JSON `null`) for one run, whose spread is unknown.
    pub standard_error: f64,
    /// Sample standard deviation s over the runs; NaN for one run.
    pub(crate) std: f64,
}

impl Estimate {
    /// Of `values`; the mean is NaN for none.
    pub fn of(values: &[f64]) -> Estimate {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        let std = if values.len() > 1 {
            variance.sqrt()
        } else {
            f64::NAN
        };
        Estimate {
            mean,
            standard_error: std / n.sqrt(),
            std,
        }
    }

    /// The standard error as a fraction of the mean's magnitude (0.01 = 1 %).
    pub fn relative_error(&self) -> f64 {
        self.standard_error / self.mean.abs()
    }
}

/// The statistics of the k-th event of a contact over the runs that match.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WrenchEventStatistics {
    /// Event number within the contact, 1-based (1 = first contact).
    pub event: usize,
    /// Runs averaged.
    pub runs: usize,
    /// Maximum ‖F‖ (N).
    pub(crate) max_force: Estimate,
    /// Maximum ‖T‖ about the moving body's centre of mass (N·m).
    pub(crate) max_torque: Estimate,
    /// ‖∫F dt‖ (N·s).
    pub linear_impulse: Estimate,
    /// ‖∫T dt‖ (N·m·s).
    pub(crate) angular_impulse: Estimate,
    /// Duration (s).
    pub(crate) duration: Estimate,
}

impl WrenchEventStatistics {
    /// The five estimates in [`WrenchIndicators::NAMES`] order.
    pub fn estimates(&self) -> [Estimate; 5] {
        [
            self.max_force,
            self.max_torque,
            self.linear_impulse,
            self.angular_impulse,
            self.duration,
        ]
    }
}

/// A run left out of a contact's statistics: its event count differs from the expected.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct EventCountMismatch {
    /// Run id.
    pub run: String,
    /// Completed events of the contact in this run.
    pub events: usize,
}

/// The statistics of one contact over a set of runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactStatistics {
    /// Contact label, `body1–body2`.
    pub contact: String,
    /// Runs in the set.
    pub runs: usize,
    /// The event count most runs have (the smallest, on a tie).
    pub expected_events: usize,
    /// Runs with exactly `expected_events` events: those averaged.
    pub matched_runs: usize,
    /// Every other run, in run order, with its count.
    pub mismatched_runs: Vec<EventCountMismatch>,
    /// Event 1, 2, … `expected_events`.
    pub events: Vec<WrenchEventStatistics>,
}

/// The statistics of every contact found in `events`, over the runs `runs` (every run
/// of the set, in order: a run without any event of a contact counts as 0 events).
/// Contacts in order of first appearance.
pub fn wrench_statistics(runs: &[String], events: &[RecordedEvent]) -> Vec<ContactStatistics> {
    let mut contacts: Vec<&str> = Vec::new();
    for e in events {
        if !contacts.contains(&e.label.as_str()) {
            contacts.push(&e.label);
        }
    }
    contacts
        .into_iter()
        .map(|contact| contact_statistics(contact, runs, events))
        .collect()
}

fn contact_statistics(
    contact: &str,
    runs: &[String],
    events: &[RecordedEvent],
) -> ContactStatistics {
    // Each run's events of this contact, in event order.
    let per_run: Vec<Vec<WrenchIndicators>> = runs
        .iter()
        .map(|run| {
            let mut own: Vec<&RecordedEvent> = (events.iter())
                .filter(|e| e.label == contact && &e.run == run)
                .collect();
            own.sort_by_key(|e| e.number);
            own.into_iter().map(RecordedEvent::wrench).collect()
        })
        .collect();
    let expected = most_common(per_run.iter().map(Vec::len));
    let matched: Vec<&Vec<WrenchIndicators>> =
        per_run.iter().filter(|e| e.len() == expected).collect();
    let mismatched_runs = (runs.iter().zip(&per_run))
        .filter(|(_, e)| e.len() != expected)
        .map(|(run, e)| EventCountMismatch {
            run: run.clone(),
            events: e.len(),
        })
        .collect();
    let events = (0..expected)
        .map(|k| {
            let column = |f: fn(&WrenchIndicators) -> f64| {
                Estimate::of(&matched.iter().map(|run| f(&run[k])).collect::<Vec<_>>())
            };
            WrenchEventStatistics {
                event: k + 1,
                runs: matched.len(),
                max_force: column(|i| i.max_force),
                max_torque: column(|i| i.max_torque),
                linear_impulse: column(|i| i.linear_impulse),
                angular_impulse: column(|i| i.angular_impulse),
                duration: column(|i| i.duration),
            }
        })
        .collect();
    ContactStatistics {
        contact: contact.to_owned(),
        runs: runs.len(),
        expected_events: expected,
        matched_runs: matched.len(),
        mismatched_runs,
        events,
    }
}

/// The most frequent of `counts`; the smallest on a tie, 0 for none.
fn most_common(counts: impl Iterator<Item = usize>) -> usize {
    let mut tally: std::collections::BTreeMap<usize, usize> = Default::default();
    for count in counts {
        *tally.entry(count).or_default() += 1;
    }
    // BTreeMap iterates in increasing count; max_by_key keeps the last maximum, so
    // iterate in reverse to keep the smallest count among equals.
    (tally.into_iter().rev())
        .max_by_key(|&(_, runs)| runs)
        .map_or(0, |(count, _)| count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::indicators::ContactEvent;

    fn event(run: &str, number: usize, value: f64) -> RecordedEvent {
        let touch_down = number as f64;
        RecordedEvent {
            run: run.into(),
            label: "peg–block".into(),
            number,
            event: ContactEvent {
                lift_off: Some(touch_down + 1.0),
                max_force: value,
                max_torque: 2.0 * value,
                linear_impulse: nalgebra::Vector3::new(value, 0.0, 0.0),
                ..ContactEvent::starting(0, touch_down)
            },
        }
    }

    #[test]
    fn ties_go_to_the_smaller_count() {
        assert_eq!(most_common([3, 4, 4, 3].into_iter()), 3);
        assert_eq!(most_common([3, 4, 4].into_iter()), 4);
        assert_eq!(most_common(std::iter::empty()), 0);
    }

    #[test]
    fn a_run_with_an_extra_event_is_reported_not_averaged() {
        let runs: Vec<String> = ["a", "b", "c", "d"].map(String::from).to_vec();
        let mut events = Vec::new();
        for (run, first) in [("a", 1.0), ("b", 2.0), ("c", 3.0)] {
            events.extend([event(run, 0, first), event(run, 1, 10.0 * first)]);
        }
        // d splits its second contact in two: matched by order its fragment would sit
        // beside the others' whole second contacts.
        events.extend([event("d", 0, 100.0), event("d", 1, 5.0), event("d", 2, 5.0)]);
        let stats = wrench_statistics(&runs, &events);
        assert_eq!(stats.len(), 1);
        let s = &stats[0];
        assert_eq!((s.expected_events, s.matched_runs, s.runs), (2, 3, 4));
        assert_eq!(
            s.mismatched_runs,
            [EventCountMismatch {
                run: "d".into(),
                events: 3
            }]
        );
        assert_eq!(s.events[0].max_force.mean, 2.0);
        assert_eq!(s.events[1].max_torque.mean, 40.0);
        // s = 1 over 3 runs: standard error 1/√3.
        assert!((s.events[0].linear_impulse.standard_error - 1.0 / 3f64.sqrt()).abs() < 1e-15);
        assert!(s.events[0].duration.standard_error == 0.0);
    }
}
