//! How far a candidate's replays are from the training tosses: the mean position error
//! (% of the body's width) plus the mean rotation error (degrees) over the tosses, the
//! scores `hcm predict` prints (1 % of the width weighs as much as 1°: the published
//! figures are of that size in both). A candidate whose replay of any toss fails scores
//! +∞.

use crate::dataset::Dataset;
use crate::replay::{prepare, simulate_toss, PreparedToss};
use crate::replay::{TossError, TossScore, TossSetup};
use crate::scenario::Model;
use rayon::prelude::*;

/// The tosses a fit replays, each checked once: window, initial state and frame grid
/// come from the data (and the scenario's plane), never from the candidate, so every
/// candidate is judged on the same frames.
#[derive(Clone, Debug)]
pub struct MotionTarget<'a> {
    /// The thrown body and the fixed bodies it touches as the scenario has them.
    pub(crate) setup: TossSetup,
    /// The tosses.
    pub(crate) tosses: Vec<PreparedToss<'a>>,
}

impl<'a> MotionTarget<'a> {
    /// The tosses of `data` for `model`'s body and plane.
    pub fn new(model: &Model, data: &'a Dataset) -> Result<MotionTarget<'a>, TossError> {
        let setup = TossSetup::new(model)?;
        let tosses = (data.runs.iter())
            .map(|run| prepare(&setup, run))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(MotionTarget { setup, tosses })
    }
}

/// Every toss's scores under `candidate` (in parallel, in the tosses' order); `None`
/// if a replay fails.
pub fn toss_scores(target: &MotionTarget<'_>, candidate: &Model) -> Option<Vec<TossScore>> {
    let scores: Vec<Option<TossScore>> = (target.tosses.par_iter())
        .map(|toss| {
            let prediction = simulate_toss(candidate, &target.setup, toss).ok()?;
            toss.score(&target.setup, &prediction).ok()
        })
        .collect();
    scores.into_iter().collect()
}

/// Mean position error (%) + mean rotation error (°) of `candidate` over the target's
/// tosses, summed in the tosses' order; +∞ if a replay fails.
pub fn motion_fitness(target: &MotionTarget<'_>, candidate: &Model) -> f64 {
    let Some(scores) = toss_scores(target, candidate) else {
        return f64::INFINITY;
    };
    let n = scores.len().max(1) as f64;
    let position: f64 = scores.iter().map(|s| s.position_error).sum();
    let rotation: f64 = scores.iter().map(|s| s.rotation_error).sum();
    let total = (position + rotation) / n;
    if total.is_finite() {
        total
    } else {
        f64::INFINITY
    }
}
