//! Stage 1: the noise-added experiment (PM1) and its split into S1 and S2.

use super::{PipelineError, Progress, Stage};
use crate::experiment::{generate, split, Split};
use crate::scenario::Scenario;
use std::sync::atomic::{AtomicU64, Ordering};

/// `runs` noisy runs of every condition of `scenario` (Eq 18–19), split into S1
/// (training) and S2 (validation), both drawn with `seed`.
pub fn experiment(
    scenario: &Scenario,
    runs: usize,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Split, PipelineError> {
    let steps = (runs * scenario.experiment.conditions.len().max(1)) as u64;
    progress.begin(Stage::Generate, steps);
    // Runs finish on worker threads in any order: count them here.
    let done = AtomicU64::new(0);
    let data = generate(scenario, runs, seed, || {
        progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps)
    })?;
    progress.end(Stage::Generate);
    Ok(split(scenario, data, seed))
}
