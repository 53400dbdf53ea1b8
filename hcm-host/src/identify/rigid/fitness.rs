//! How far a candidate's replay is from the measured events: per event, the relative
//! errors of the peak force and torque, of the linear and angular impulse (the motion
//! change each contact causes: Table 15's indicators), and of when the event starts
//! after the first (the motion between contacts), squared and averaged.

use super::target::{EventTarget, WrenchTarget};
use crate::indicators::WrenchIndicators;
use crate::scenario::Model;
use crate::simulate::simulate;

/// The error counted for each indicator of an event the candidate does not make.
const MISSING: f64 = 1.0;

/// The completed events of contact `c` when `model` is simulated: touch-down time (s)
/// and indicators; `None` if the simulation fails.
pub fn replay_events(model: &Model, c: usize) -> Option<Vec<(f64, WrenchIndicators)>> {
    let simulation = simulate(model).ok()?;
    Some(
        simulation
            .events
            .iter()
            .filter(|e| e.contact == c)
            .filter_map(|e| Some((e.touch_down, e.indicators()?)))
            .collect(),
    )
}

/// Mean squared relative error of `candidate` (a model started like `target.model`)
/// against the target's events; +∞ if its simulation fails.
pub fn event_fitness(target: &WrenchTarget, candidate: &Model) -> f64 {
    let Some(events) = replay_events(candidate, target.contact) else {
        return f64::INFINITY;
    };
    let first = events.first().map_or(0.0, |e| e.0);
    let mut sum = 0.0;
    for (k, wanted) in target.events.iter().enumerate() {
        sum += match events.get(k) {
            Some((touch_down, got)) => event_errors(wanted, got, touch_down - first)
                .iter()
                .map(|e| e * e)
                .sum::<f64>(),
            None => 5.0 * MISSING * MISSING,
        };
    }
    sum / (5 * target.events.len().max(1)) as f64
}

/// The five relative errors of one event: max force, max torque, linear impulse,
/// angular impulse, and the delay after the first event (relative to the event's
/// measured duration: a shift by one whole contact counts as 100 %).
pub fn event_errors(wanted: &EventTarget, got: &WrenchIndicators, delay: f64) -> [f64; 5] {
    let relative = |got: f64, wanted: f64| (got - wanted) / wanted.abs().max(f64::MIN_POSITIVE);
    let s = &wanted.statistics;
    [
        relative(got.max_force, s.max_force.mean),
        relative(got.max_torque, s.max_torque.mean),
        relative(got.linear_impulse, s.linear_impulse.mean),
        relative(got.angular_impulse, s.angular_impulse.mean),
        (delay - wanted.delay) / s.duration.mean.max(f64::MIN_POSITIVE),
    ]
}
