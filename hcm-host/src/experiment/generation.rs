//! The runs of an experiment, made a chunk at a time: each chunk's runs are simulated in
//! parallel (rayon), then handed on in order. Memory holds one chunk, whatever the number
//! of runs; the runs do not depend on the chunk size or the thread count, since run `i`
//! draws from its own stream (seed, i).

use super::{conditions, noisy_model, noisy_run, run_id, run_rng, ExperimentError};
use crate::dataset::Run;
use crate::progress::{in_stage, Progress, Stage};
use crate::scenario::{Model, Scenario};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// `runs_per_condition` noisy runs of every condition of a scenario, numbered condition by
/// condition: run `i` is run `i % runs_per_condition` of condition `i / runs_per_condition`.
pub struct Generation {
    conditions: Vec<(String, Model)>,
    runs_per_condition: usize,
    total: usize,
    seed: u64,
    /// Runs simulated together before they are handed on: memory holds this many runs.
    /// Enough that every thread has several, so the pause at the end of a chunk costs
    /// little.
    pub(crate) chunk: usize,
}

impl Generation {
    /// The experiment of `scenario` (its conditions resolved), seeded with `seed`.
    pub fn new(
        scenario: &Scenario,
        runs_per_condition: usize,
        seed: u64,
    ) -> Result<Self, ExperimentError> {
        Generation::of_conditions(conditions(scenario)?, runs_per_condition, seed)
    }

    /// The experiment of `conditions` (each a name, "" for a lone one, and its model),
    /// seeded with `seed`: what [`Self::new`] makes of a scenario's conditions, for
    /// models changed after their resolution (a power study's hidden effect).
    pub fn of_conditions(
        conditions: Vec<(String, Model)>,
        runs_per_condition: usize,
        seed: u64,
    ) -> Result<Self, ExperimentError> {
        if runs_per_condition == 0 {
            return Err(ExperimentError::NoRuns);
        }
        let total = runs_per_condition.checked_mul(conditions.len()).ok_or(
            ExperimentError::TooManyRuns {
                runs: runs_per_condition,
                conditions: conditions.len(),
            },
        )?;
        Ok(Generation {
            conditions,
            runs_per_condition,
            total,
            seed,
            chunk: 256.max(8 * rayon::current_num_threads()),
        })
    }

    /// Runs in all conditions.
    pub fn total_runs(&self) -> usize {
        self.total
    }

    /// Runs of each condition.
    pub fn runs_per_condition(&self) -> usize {
        self.runs_per_condition
    }

    /// Experimental conditions (1 without any named).
    pub fn conditions(&self) -> usize {
        self.conditions.len()
    }

    /// Run `index` (of [`Self::total_runs`]), simulated.
    pub fn run(&self, index: usize) -> Result<Run, ExperimentError> {
        let (model, id) = self.condition_of(index);
        let mut rng = run_rng(self.seed, index as u64);
        let run = noisy_run(model, &mut rng).map_err(|source| ExperimentError::Simulation {
            run: id.clone(),
            source,
        })?;
        Ok(Run { id, ..run })
    }

    /// The model run `index` was simulated with: its condition's, with the run's own
    /// noisy contact parameters (Eq 18) — the same draws [`Self::run`] makes. Without
    /// the output noise, so simulating it gives the run's noise-free data.
    pub fn noisy_model(&self, index: usize) -> Result<Model, ExperimentError> {
        let (model, id) = self.condition_of(index);
        let mut rng = run_rng(self.seed, index as u64);
        noisy_model(model, &mut rng)
            .map_err(|source| ExperimentError::Simulation { run: id, source })
    }

    /// The id run `index` has.
    pub(crate) fn run_id(&self, index: usize) -> String {
        self.condition_of(index).1
    }

    /// The model of run `index`'s condition and the run's id.
    fn condition_of(&self, index: usize) -> (&Model, String) {
        let (name, model) = &self.conditions[index / self.runs_per_condition];
        let k = index % self.runs_per_condition;
        (model, run_id(name, k, self.runs_per_condition))
    }

    /// Makes every run and hands it to `each` with its index, in order, reporting
    /// [`Stage::Generate`] to `progress`, one step per simulated run (from worker
    /// threads). Stops at the first error, in run order: a failed simulation, or
    /// `each`'s.
    pub(crate) fn for_each<E: From<ExperimentError>>(
        &self,
        progress: &dyn Progress,
        each: impl FnMut(usize, Run) -> Result<(), E>,
    ) -> Result<(), E> {
        self.for_each_in(0..self.total, progress, each)
    }

    /// [`Self::for_each`] for the runs `indices` only (a shard's).
    pub(crate) fn for_each_in<E: From<ExperimentError>>(
        &self,
        indices: std::ops::Range<usize>,
        progress: &dyn Progress,
        mut each: impl FnMut(usize, Run) -> Result<(), E>,
    ) -> Result<(), E> {
        let chunk = self.chunk.max(1);
        let steps = indices.len() as u64;
        in_stage(progress, Stage::Generate, steps, || {
            // Runs finish on worker threads in any order: count them here.
            let done = AtomicU64::new(0);
            for start in indices.clone().step_by(chunk) {
                let end = indices.end.min(start + chunk);
                let runs: Vec<Result<Run, ExperimentError>> = (start..end)
                    .into_par_iter()
                    .map(|index| {
                        let run = self.run(index);
                        progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps);
                        run
                    })
                    .collect();
                for (index, run) in (start..end).zip(runs) {
                    each(index, run?)?;
                }
            }
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn the_runs_do_not_depend_on_the_chunk_size() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/bouncing_ball.toml");
        let ball = Scenario::load(&path, &[]).unwrap();
        let runs = |chunk: usize| {
            let mut generation = Generation::new(&ball, 5, 9).unwrap();
            generation.chunk = chunk;
            let mut runs = Vec::new();
            generation
                .for_each(
                    &crate::progress::Silent,
                    |index, run| -> Result<(), ExperimentError> {
                        assert_eq!(index, runs.len(), "in order");
                        runs.push(run);
                        Ok(())
                    },
                )
                .unwrap();
            runs
        };
        let whole = runs(256);
        assert_eq!(whole.len(), 5);
        assert_eq!(runs(1), whole);
        assert_eq!(runs(2), whole);
        assert_ne!(whole[0], whole[1], "each run its own noise");
    }

    #[test]
    fn run_counts_that_cannot_be_counted_are_refused() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/flat_shot.toml");
        let flat = Scenario::load(&path, &[]).unwrap();
        let error = Generation::new(&flat, usize::MAX, 1).err().unwrap();
        assert!(error.to_string().contains("--runs"), "{error}");
        assert!(matches!(
            Generation::new(&flat, 0, 1),
            Err(ExperimentError::NoRuns)
        ));
    }
}
