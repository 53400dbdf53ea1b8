//! Progress bars on standard error (hidden when it is not a terminal): one bar per stage
//! of the library's [`Progress`].

use super::progress_bar;
use hcm_host::progress::{Progress, Stage};
use indicatif::ProgressBar;
use std::sync::{Mutex, MutexGuard};

/// One progress bar per stage, named by `label`; with `status`, a stage's status
/// message replaces its name once it reports one.
pub struct Bars {
    bar: Mutex<Option<ProgressBar>>,
    label: fn(Stage) -> &'static str,
    status: bool,
}

impl Default for Bars {
    /// Bars named by [`Stage::label`], without status messages.
    fn default() -> Self {
        Bars {
            bar: Mutex::new(None),
            label: Stage::label,
            status: false,
        }
    }
}

impl Bars {
    /// Bars named by `label`, without status messages.
    pub fn named(label: fn(Stage) -> &'static str) -> Self {
        Bars {
            label,
            ..Bars::default()
        }
    }

    /// Bars named by `label` that show the stages' status messages.
    pub fn with_status(label: fn(Stage) -> &'static str) -> Self {
        Bars {
            label,
            status: true,
            ..Bars::default()
        }
    }

    fn bar(&self) -> MutexGuard<'_, Option<ProgressBar>> {
        // A panic while drawing leaves the bar usable.
        self.bar
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

impl Progress for Bars {
    fn begin(&self, stage: Stage, steps: u64) {
        *self.bar() = Some(progress_bar(steps, (self.label)(stage)));
    }

    fn advance(&self, done: u64, steps: u64) {
        if let Some(bar) = self.bar().as_ref() {
            bar.set_length(steps);
            bar.set_position(done);
        }
    }

    fn status(&self, message: &str) {
        if let (true, Some(bar)) = (self.status, self.bar().as_ref()) {
            bar.set_message(message.to_owned());
        }
    }

    fn end(&self, _: Stage) {
        if let Some(bar) = self.bar().take() {
            bar.finish_and_clear();
        }
    }
}
