//! S1/S2: the training and validation sets (paper Section 2 and 5).

use crate::dataset::Dataset;
use crate::scenario::Scenario;
use rand::seq::SliceRandom;
use rand::SeedableRng;
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

/// Splits by the scenario's holdout conditions (S2 = their runs) or, without any,
/// at random: S2 = `holdout_fraction` of the runs (at least one), drawn with `seed`.
pub fn split(scenario: &Scenario, dataset: Dataset, seed: u64) -> Split {
    let e = &scenario.experiment;
    let in_validation: Vec<bool> = if e.holdout_conditions.is_empty() {
        let n = dataset.runs.len();
        let holdout = ((n as f64 * e.holdout_fraction).round() as usize)
            .clamp(1.min(n), n.saturating_sub(1).max(1));
        let mut order: Vec<usize> = (0..n).collect();
        order.shuffle(&mut ChaCha8Rng::seed_from_u64(seed ^ 0x5EED_5EED));
        let mut chosen = vec![false; n];
        order.iter().take(holdout).for_each(|&i| chosen[i] = true);
        chosen
    } else {
        dataset
            .runs
            .iter()
            .map(|r| {
                e.holdout_conditions
                    .iter()
                    .any(|c| c == condition_of(&r.id))
            })
            .collect()
    };
    let (mut training, mut validation) = (Dataset::default(), Dataset::default());
    for (run, held_out) in dataset.runs.into_iter().zip(in_validation) {
        if held_out {
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
