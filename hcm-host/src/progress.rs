//! How a long stage tells its caller how far it is: the library never prints, the
//! caller shows what it likes (the CLI draws progress bars). One trait for every
//! stage and every example.

/// A stage of a reproduction that reports its steps: the paper's five (the ball, the
/// flat shot, the peg-in-hole) and those of a fit from motion (the cube tosses).
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
    /// A fit from motion's genetic algorithm; steps are generations.
    MotionGenetic(Fold),
    /// A fit from motion's Nelder–Mead polish; steps are fitness evaluations.
    MotionPolish(Fold),
    /// Tosses predicted; steps are tosses.
    Predict(Fold),
    /// The motion diagnosis; steps are its candidates' fits.
    Diagnose,
    /// The final faces' ensembles; steps are tosses (each scatter's, then the forecast's).
    Faces,
    /// The held-out tosses forecast by the named chance; steps are tosses (ensembles,
    /// then replays).
    Forecast,
    /// A power study of the diagnosis; steps are data sets made and diagnosed.
    Power,
}

/// Which fold of a two-fold split a stage works on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fold {
    /// Fitted on the training part (even toss numbers).
    First,
    /// Fitted on the held-out part (odd toss numbers), the training part predicted.
    Second,
}

impl Stage {
    /// The stage's name as a progress display shows it.
    pub fn label(self) -> &'static str {
        match self {
            Stage::Generate => "1/5 generate",
            Stage::Identify => "2/5 identify",
            Stage::Train => "3/5 train",
            Stage::Int8Twin => "3/5 int8 twin",
            Stage::Evaluate => "5/5 evaluate",
            Stage::MotionGenetic(Fold::First) => "fit: GA",
            Stage::MotionPolish(Fold::First) => "fit: polish",
            Stage::Predict(Fold::First) => "predict",
            Stage::MotionGenetic(Fold::Second) => "second fold (fit on odd): GA",
            Stage::MotionPolish(Fold::Second) => "second fold: polish",
            Stage::Predict(Fold::Second) => "second fold: predict",
            Stage::Diagnose => "diagnose",
            Stage::Faces => "final faces",
            Stage::Forecast => "forecast by the named chance",
            Stage::Power => "power study",
        }
    }
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
    /// A short status of the current stage (e.g. the validation error so far), for a
    /// display to show beside its bar.
    fn status(&self, message: &str) {
        let _ = message;
    }
    /// `stage` ended.
    fn end(&self, stage: Stage) {
        let _ = stage;
    }
}

/// Runs `work` as `stage` of `steps` steps: [`Progress::begin`] before it and
/// [`Progress::end`] after it, whatever it returns (an error included).
pub fn in_stage<T>(
    progress: &dyn Progress,
    stage: Stage,
    steps: u64,
    work: impl FnOnce() -> T,
) -> T {
    progress.begin(stage, steps);
    let result = work();
    progress.end(stage);
    result
}

/// Progress nobody watches.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Progress for Silent {}
