//! How much memory a simulation's record may take, estimated before anything runs, so
//! that a scenario or a `--runs` asking for more than the machine has is refused with
//! the figure and the key or option that lowers it — never an allocation failure
//! after minutes of work.

use crate::dataset::Sample;
use crate::scenario::Model;

/// Memory assumed available where the system does not say (B): 4 GiB.
const FALLBACK_BUDGET: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;

/// The most one run of `model` records (B): every recorded body (every moving body
/// when the scenario names none) sampled at the finer of the two record periods over
/// the whole run, one [`Sample`] each.
pub fn run_bytes(model: &Model) -> f64 {
    let record = &model.scenario.record;
    let period = record
        .contact_sample_period
        .min(record.flight_sample_period);
    let samples = (model.scenario.simulation.end_time / period).ceil() + 2.0;
    let bodies = match record.bodies.len() {
        0 => model.bodies.iter().filter(|b| !b.fixed).count(),
        n => n,
    };
    samples * bodies.max(1) as f64 * std::mem::size_of::<Sample>() as f64
}

/// The memory `run`'s samples take (B).
pub fn record_bytes(run: &crate::dataset::Run) -> f64 {
    let samples: usize = run.bodies.iter().map(|b| b.samples.len()).sum();
    (samples * std::mem::size_of::<Sample>()) as f64
}

/// The memory hcm may fill (B): the system's available memory (`MemAvailable` of
/// `/proc/meminfo`), else 4 GiB.
pub fn memory_budget() -> f64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| {
            let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
            let kilobytes: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kilobytes * 1024.0)
        })
        .filter(|b| *b > 0.0)
        .unwrap_or(FALLBACK_BUDGET)
}

/// `bytes` (B) for people.
pub fn shown_bytes(bytes: f64) -> String {
    crate::output::bytes(bytes.min(u64::MAX as f64) as u64)
}
