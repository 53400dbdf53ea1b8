//! Mean and standard deviation of the indicators over runs.

use super::{Indicators, RecordedEvent};
use serde::Serialize;

/// Mean and sample standard deviation of one quantity over runs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Statistic {
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation (n − 1); 0 for one run.
    pub std: f64,
}

impl Statistic {
    /// Of `values` (their unit); the mean is NaN for none, the std 0 for fewer than two.
    pub fn of(values: &[f64]) -> Statistic {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = if values.len() > 1 {
            values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)
        } else {
            0.0
        };
        Statistic {
            mean,
            std: var.sqrt(),
        }
    }
}

/// The statistics of the k-th event of one contact over all runs that have it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EventSummary {
    /// Contact label (`ball–ground`).
    pub contact: String,
    /// Event number within the contact (0 = first touch-down).
    pub event: usize,
    /// Number of runs with this event.
    pub runs: usize,
    /// Maximum force (N).
    pub max_force: Statistic,
    /// Impulse (N·s).
    pub impulse: Statistic,
    /// Energy loss (N·m).
    pub energy_loss: Statistic,
    /// Duration (s).
    pub duration: Statistic,
}

impl EventSummary {
    /// The means as indicators.
    pub fn mean(&self) -> Indicators {
        Indicators {
            max_force: self.max_force.mean,
            impulse: self.impulse.mean,
            energy_loss: self.energy_loss.mean,
            duration: self.duration.mean,
        }
    }
}

/// Groups events by (contact, event number) in order of first appearance and
/// summarises each group.
pub fn summarize(events: &[RecordedEvent]) -> Vec<EventSummary> {
    let mut keys: Vec<(String, usize)> = Vec::new();
    for e in events {
        let key = (e.label.clone(), e.number);
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .map(|(contact, event)| {
            let group: Vec<Indicators> = events
                .iter()
                .filter(|e| e.label == contact && e.number == event)
                .map(RecordedEvent::line)
                .collect();
            let column =
                |f: fn(&Indicators) -> f64| Statistic::of(&group.iter().map(f).collect::<Vec<_>>());
            EventSummary {
                runs: group.len(),
                max_force: column(|i| i.max_force),
                impulse: column(|i| i.impulse),
                energy_loss: column(|i| i.energy_loss),
                duration: column(|i| i.duration),
                contact,
                event,
            }
        })
        .collect()
}
