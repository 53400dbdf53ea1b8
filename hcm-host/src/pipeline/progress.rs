//! How the pipeline tells its caller how far it is: the library never prints, the
//! caller shows what it likes (the CLI draws progress bars).

/// A stage of the pipeline that reports its steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Stage 1: steps are generated runs.
    Generate,
    /// Stage 2: steps are GA generations (one step for least squares).
    Identify,
    /// Stage 3: steps are training epochs.
    Train,
    /// Stage 3: steps are fine-tuning epochs of the int8 twin.
    Int8Twin,
    /// Stage 5: one step.
    Evaluate,
}

/// Receives the pipeline's progress. Every method defaults to doing nothing. Calls may
/// come from worker threads (generation runs in parallel), hence `Sync`.
pub trait Progress: Sync {
    /// `stage` starts, with `steps` steps expected.
    fn begin(&self, stage: Stage, steps: u64) {
        let _ = (stage, steps);
    }
    /// `done` of `steps` steps of the current stage are done (`steps` may change as the
    /// stage learns its length).
    fn advance(&self, done: u64, steps: u64) {
        let _ = (done, steps);
    }
    /// `stage` ended.
    fn end(&self, stage: Stage) {
        let _ = stage;
    }
}

/// Progress nobody watches.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Progress for Silent {}
