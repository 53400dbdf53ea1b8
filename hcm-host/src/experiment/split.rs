//! S1/S2: the training and validation sets (paper Section 2 and 5).
//!
//! A run goes to S2 when its condition is one of `experiment.holdout_conditions`, or,
//! without any, when it is drawn into the random `holdout_fraction` of all runs. The draw
//! is selection sampling (Knuth's Algorithm S): run by run in order, each is taken with
//! probability (still needed)/(still to come), which takes exactly the count wanted,
//! uniformly, and holds nothing but two counters — so runs streamed to disk
//! (`hcm generate`) and a dataset in memory ([`split`]) are split alike.

use super::ExperimentError;
use crate::dataset::Dataset;
use crate::scenario::Scenario;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The two sets.
#[derive(Clone, Debug, PartialEq)]
pub struct Split {
    /// Training set S1.
    pub training: Dataset,
    /// Validation set S2.
    pub validation: Dataset,
}

/// The condition a run belongs to: the part of its id before the last `/` ("" if none).
pub fn condition_of(run_id: &str) -> &str {
    run_id
        .rsplit_once('/')
        .map_or("", |(condition, _)| condition)
}

/// Decides, run by run in the order of the experiment, which runs form S2.
pub struct Holdout<'a> {
    /// S2 = the runs of these conditions; if none, a random draw.
    conditions: &'a [String],
    rng: ChaCha8Rng,
    /// Runs still to draw into S2.
    needed: u64,
    /// Runs still to come.
    remaining: u64,
}

/// Runs drawn into S2 at random out of `runs`: the `fraction`, rounded, but at least one
/// and, from two runs on, at most all but one.
fn holdout_count(runs: usize, fraction: f64) -> usize {
    ((runs as f64 * fraction).round() as usize).clamp(1.min(runs), runs.saturating_sub(1).max(1))
}

impl<'a> Holdout<'a> {
    /// The split of `scenario`'s experiment of `total_runs` runs (all conditions), drawn
    /// with `seed`.
    pub fn new(scenario: &'a Scenario, total_runs: usize, seed: u64) -> Self {
        let e = &scenario.experiment;
        Holdout {
            conditions: &e.holdout_conditions,
            rng: ChaCha8Rng::seed_from_u64(seed ^ 0x5EED_5EED),
            needed: holdout_count(total_runs, e.holdout_fraction) as u64,
            remaining: total_runs as u64,
        }
    }

    /// Whether the next run, `run_id`, goes to S2.
    pub fn takes(&mut self, run_id: &str) -> bool {
        if !self.conditions.is_empty() {
            return self.conditions.iter().any(|c| c == condition_of(run_id));
        }
        if self.remaining == 0 {
            return false;
        }
        let taken = self.rng.random_range(0..self.remaining) < self.needed;
        self.remaining -= 1;
        self.needed -= u64::from(taken);
        taken
    }
}

/// Splits a dataset (the runs of an experiment in order) into S1 and S2 (see [`Holdout`]).
pub fn split(scenario: &Scenario, dataset: Dataset, seed: u64) -> Split {
    let mut holdout = Holdout::new(scenario, dataset.runs.len(), seed);
    let (mut training, mut validation) = (Dataset::default(), Dataset::default());
    for run in dataset.runs {
        if holdout.takes(&run.id) {
            validation.runs.push(run)
        } else {
            training.runs.push(run)
        }
    }
    Split {
        training,
        validation,
    }
}

/// Runs in S1 and S2 for `runs_per_condition` runs of each condition of `scenario`.
pub fn split_sizes(scenario: &Scenario, runs_per_condition: usize) -> (usize, usize) {
    let e = &scenario.experiment;
    let conditions = e.conditions.len().max(1);
    let total = runs_per_condition.saturating_mul(conditions);
    if e.holdout_conditions.is_empty() {
        let held = holdout_count(total, e.holdout_fraction);
        return (total - held, held);
    }
    let held = (e.conditions.iter())
        .filter(|c| e.holdout_conditions.contains(&c.name))
        .count();
    let per = |conditions: usize| runs_per_condition.saturating_mul(conditions);
    (per(conditions - held), per(held))
}

/// Refuses, before any work, a run count whose split would leave S1 or S2 empty, naming
/// the smallest `--runs` that works.
pub fn check_split(scenario: &Scenario, runs_per_condition: usize) -> Result<(), ExperimentError> {
    let e = &scenario.experiment;
    let conditions = e.conditions.len().max(1);
    let (training, validation) = split_sizes(scenario, runs_per_condition);
    if training > 0 && validation > 0 {
        return Ok(());
    }
    if !e.holdout_conditions.is_empty() {
        return Err(ExperimentError::AllHeldOut);
    }
    Err(ExperimentError::TooFewRuns {
        runs: runs_per_condition,
        minimum: 2usize.div_ceil(conditions),
        conditions,
        holdout_percent: 100.0 * e.holdout_fraction,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::Run;
    use std::path::Path;

    fn ball() -> Scenario {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/bouncing_ball.toml");
        Scenario::load(&path, &[]).unwrap()
    }

    fn runs(n: usize) -> Dataset {
        let runs = (0..n)
            .map(|k| Run {
                id: format!("{k:04}"),
                bodies: Vec::new(),
            })
            .collect();
        Dataset { runs }
    }

    #[test]
    fn the_random_split_takes_exactly_its_share_and_repeats_per_seed() {
        let ball = ball();
        for (n, held) in [(2, 1), (5, 1), (10, 1), (1000, 100), (1001, 100)] {
            let sets = split(&ball, runs(n), 7);
            assert_eq!(sets.validation.runs.len(), held, "{n} runs");
            assert_eq!(sets.training.runs.len(), n - held);
            assert_eq!(split_sizes(&ball, n), (n - held, held));
            assert_eq!(split(&ball, runs(n), 7), sets);
        }
        let ids = |s: Split| {
            s.validation
                .runs
                .into_iter()
                .map(|r| r.id)
                .collect::<Vec<_>>()
        };
        assert_ne!(
            ids(split(&ball, runs(1000), 7)),
            ids(split(&ball, runs(1000), 8))
        );
    }

    #[test]
    fn every_run_is_as_likely_to_be_held_out() {
        // 20 runs, 2 held out, over 4000 seeds: each run 400 times expected (σ ≈ 19).
        let ball = ball();
        let mut counts = [0usize; 20];
        for seed in 0..4000 {
            for run in split(&ball, runs(20), seed).validation.runs {
                counts[run.id.parse::<usize>().unwrap()] += 1;
            }
        }
        assert!(
            counts.iter().all(|&c| (320..480).contains(&c)),
            "{counts:?}"
        );
    }

    #[test]
    fn a_split_that_would_leave_a_set_empty_is_refused_with_the_minimum() {
        let ball = ball();
        assert!(check_split(&ball, 2).is_ok());
        let error = check_split(&ball, 1).unwrap_err().to_string();
        assert!(
            error.contains("--runs 1") && error.contains("--runs 2"),
            "{error}"
        );
    }
}
