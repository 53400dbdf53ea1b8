//! Noise-added experiments (PM1, paper Section 4): many runs of a scenario with
//! noise on the contact parameters (Eq 18: the law's and, in 3D, the friction's) and on
//! the sampled outputs (Eq 19: force, torque), split into a training set S1 and a
//! validation set S2. A 3D run's recorded state just before its first contact
//! ([`pre_contact_states`]) is where a later stage replays it from.
//!
//! Every run draws from its own random stream, derived from the seed and the run's
//! index, so the data are bit-identical for a seed whatever the number of threads.
//! [`Generation`] makes the runs a chunk at a time, in parallel, and hands them on in
//! order: memory holds one chunk, however many runs are asked for, and
//! [`ExperimentWriter`] streams them to OUT, S1 and S2.

mod generation;
mod members;
mod noise;
mod pre_contact;
mod shard;
mod split;
mod write;

pub use generation::Generation;
pub use members::{member_model, simulate_members};
pub use noise::{noisy_model, noisy_run, read_by_sensor, sensor_is_exact};
pub use pre_contact::{
    pre_contact_states, replay_model, state_before, PreContact, PreContactError,
};
pub use shard::Shard;
pub use split::{check_split, condition_of, split, split_sizes, Holdout, Split};
pub use write::{write_shard, ExperimentWriter, Written};

use crate::dataset::{DataError, Dataset};
use crate::output::{NoSpace, OutputError};
use crate::progress::Progress;
use crate::scenario::{Model, Scenario, ScenarioError};
use crate::simulate::SimulationError;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Why an experiment could not be generated.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    /// A condition's overrides do not make a valid scenario.
    #[error("condition `{condition}`: {source}")]
    Condition {
        /// The condition's name.
        condition: String,
        /// What is wrong with the scenario its overrides make.
        source: ScenarioError,
    },
    /// A run's simulation failed.
    #[error("run `{run}`: {source}")]
    Simulation {
        /// The run's id.
        run: String,
        /// Why its simulation failed.
        source: SimulationError,
    },
    /// Nothing to generate.
    #[error("--runs must be at least 1")]
    NoRuns,
    /// More runs than can be counted.
    #[error("--runs {runs}: {runs} runs of each of {conditions} conditions are more than can be counted")]
    TooManyRuns {
        /// Runs asked for per condition (`--runs`).
        runs: usize,
        /// Conditions of the scenario.
        conditions: usize,
    },
    /// The split would leave S1 or S2 empty.
    #[error(
        "--runs {runs}: the split into S1 (training) and S2 (validation) needs at least one \
         run in each; with {conditions} condition(s) and a random {holdout_percent} % of the \
         runs held out for S2 (experiment.holdout_fraction), that takes --runs {minimum} \
         or more"
    )]
    TooFewRuns {
        /// Runs asked for per condition (`--runs`).
        runs: usize,
        /// The fewest runs per condition that leave S1 and S2 one run each.
        minimum: usize,
        /// Conditions of the scenario.
        conditions: usize,
        /// Share of the runs held out for S2 (%): `experiment.holdout_fraction` × 100.
        holdout_percent: f64,
    },
    /// Every condition is held out: S1 would be empty.
    #[error(
        "experiment.holdout_conditions names every condition, so S1 (training) would be \
         empty; leave at least one condition out of it"
    )]
    AllHeldOut,
    /// The runs would not fit in memory.
    #[error(
        "--runs {runs}: {total} runs of about {} each would take {}, more than the {} of \
         memory available; ask for at most {most} runs per condition",
        crate::simulate::shown_bytes(*per_run),
        crate::simulate::shown_bytes(*per_run * *total as f64),
        crate::simulate::shown_bytes(*budget)
    )]
    TooManyForMemory {
        /// Runs asked for per condition (`--runs`).
        runs: usize,
        /// Runs over every condition.
        total: usize,
        /// Memory one run's record takes, margin included (bytes).
        per_run: f64,
        /// Memory available to the runs (bytes).
        budget: f64,
        /// The most runs per condition that fit in the budget.
        most: u64,
    },
    /// The output would not fit on the disk.
    #[error(
        "{space} ({runs} runs of about {} each, written twice: OUT, then S1 and S2); \
         ask for fewer --runs or write elsewhere",
        crate::output::bytes(*per_run)
    )]
    TooLarge {
        /// Runs over every condition.
        runs: u64,
        /// Estimated size of one run's output (bytes).
        per_run: u64,
        /// Where the output was to go, and the space needed and free there.
        space: NoSpace,
    },
    /// An output could not be written, or a shard read.
    #[error(transparent)]
    Write(#[from] DataError),
    /// Shard files that do not make the experiment (`--merge`).
    #[error("--merge: {0}")]
    Merge(String),
    /// An output could not be created or moved into place.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// The conditions of an experiment: (name, model). A scenario without conditions
/// has one, named "".
pub fn conditions(scenario: &Scenario) -> Result<Vec<(String, Model)>, ExperimentError> {
    let specs = &scenario.experiment.conditions;
    if specs.is_empty() {
        let model = scenario
            .model()
            .map_err(|source| ExperimentError::Condition {
                condition: String::new(),
                source,
            })?;
        return Ok(vec![(String::new(), model)]);
    }
    specs
        .iter()
        .map(|c| {
            let fail = |source| ExperimentError::Condition {
                condition: c.name.clone(),
                source,
            };
            let model = scenario.with(&c.set).map_err(fail)?.model().map_err(fail)?;
            Ok((c.name.clone(), model))
        })
        .collect()
}

/// Run id of run `k` of `condition` (`0007`, or `v0.95/007` with conditions).
fn run_id(condition: &str, k: usize, runs: usize) -> String {
    let width = (runs.max(2) - 1).to_string().len();
    if condition.is_empty() {
        format!("{k:0width$}")
    } else {
        format!("{condition}/{k:0width$}")
    }
}

/// A random stream for run `index` of an experiment seeded with `seed`: SplitMix64
/// of the pair, so neighbouring runs get unrelated streams.
fn run_rng(seed: u64, index: u64) -> ChaCha8Rng {
    let mut z = seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ChaCha8Rng::seed_from_u64(z ^ (z >> 31))
}

/// How much more than its first run a run may take, on the safe side (–).
const RUN_SIZE_MARGIN: f64 = 2.0;

/// Refuses an experiment whose runs, all held in memory, would not fit there: the first
/// run of each condition simulated as a pilot, its record's size
/// ([`crate::simulate::footprint::record_bytes`]) with a margin of [`RUN_SIZE_MARGIN`]
/// (the runs differ by their noise only), times the runs.
fn fits_in_memory(generation: &Generation, runs: usize) -> Result<(), ExperimentError> {
    use crate::simulate::{memory_budget, record_bytes};
    let mut per_run: f64 = 0.0;
    for condition in 0..generation.conditions() {
        let pilot = generation.run(condition * generation.runs_per_condition())?;
        per_run = per_run.max(RUN_SIZE_MARGIN * record_bytes(&pilot));
    }
    let (total, budget) = (generation.total_runs(), memory_budget());
    if per_run * total as f64 <= budget {
        return Ok(());
    }
    let conditions = generation.conditions().max(1) as f64;
    Err(ExperimentError::TooManyForMemory {
        runs,
        total,
        per_run,
        budget,
        most: (budget / per_run / conditions).floor() as u64,
    })
}

/// Generates `runs_per_condition` noisy runs of every condition of `scenario`, in
/// memory, reporting [`Stage::Generate`](crate::progress::Stage::Generate) to
/// `progress` (a step per finished run).
pub fn generate(
    scenario: &Scenario,
    runs_per_condition: usize,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Dataset, ExperimentError> {
    generated(
        Generation::new(scenario, runs_per_condition, seed)?,
        progress,
    )
}

/// The runs of `generation` in memory (refused if they would not fit there), reporting
/// [`Stage::Generate`](crate::progress::Stage::Generate) to `progress`.
pub fn generated(
    generation: Generation,
    progress: &dyn Progress,
) -> Result<Dataset, ExperimentError> {
    let runs_per_condition = generation.runs_per_condition();
    fits_in_memory(&generation, runs_per_condition)?;
    let mut runs = Vec::with_capacity(generation.total_runs());
    generation.for_each(progress, |_, run| -> Result<(), ExperimentError> {
        runs.push(run);
        Ok(())
    })?;
    Ok(Dataset { runs })
}

/// The experiment of `scenario` in memory: `runs_per_condition` noisy runs of every
/// condition (Eq 18–19), split into S1 (training) and S2 (validation), both drawn
/// with `seed` — the runs and the split `hcm generate` streams to its files.
pub fn generate_split(
    scenario: &Scenario,
    runs_per_condition: usize,
    seed: u64,
    progress: &dyn Progress,
) -> Result<Split, ExperimentError> {
    let data = generate(scenario, runs_per_condition, seed, progress)?;
    Ok(split(scenario, data, seed))
}
