//! Long work from Python: the stage runs on a thread of its own while the calling
//! thread, Python's lock released, waits for it and checks for Ctrl-C every tenth of a
//! second; the stage's progress (hcm-host's `Progress`) goes to an optional Python
//! callable `progress(stage, done, total)`.
//!
//! hcm-host's stages take no cancellation token: a stage stops where it next reports
//! progress, by unwinding from that report with the private payload [`Interrupted`]
//! (its outputs are written atomically, so nothing half-written stays behind). Ctrl-C
//! then raises `KeyboardInterrupt`, an exception in the callback that exception.

use crate::errors::hcm_error;
use hcm_host::progress::{Progress, Stage};
use pyo3::prelude::*;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Mutex, Once};
use std::time::Duration;

/// How often the waiting thread looks for Ctrl-C.
const SIGNAL_PERIOD: Duration = Duration::from_millis(100);

/// The payload a stage unwinds with when it is asked to stop.
struct Interrupted;

/// A stage's progress, forwarded to Python, and the request to stop.
struct Reporter {
    callback: Option<Py<PyAny>>,
    stage: Mutex<&'static str>,
    stop: AtomicBool,
    /// Why the stage was stopped (KeyboardInterrupt, or the callback's exception).
    reason: Mutex<Option<PyErr>>,
}

impl Reporter {
    fn stop_with(&self, error: PyErr) {
        let mut reason = self.reason.lock().unwrap_or_else(|e| e.into_inner());
        reason.get_or_insert(error);
        self.stop.store(true, Ordering::SeqCst);
    }

    /// Calls the callback; unwinds with [`Interrupted`] if the stage must stop.
    fn report(&self, done: u64, total: u64) {
        if let Some(callback) = &self.callback {
            let stage = *self.stage.lock().unwrap_or_else(|e| e.into_inner());
            let called = Python::attach(|py| callback.call1(py, (stage, done, total)).map(drop));
            if let Err(error) = called {
                self.stop_with(error);
            }
        }
        if self.stop.load(Ordering::SeqCst) {
            panic::panic_any(Interrupted);
        }
    }
}

impl Progress for Reporter {
    fn begin(&self, stage: Stage, steps: u64) {
        *self.stage.lock().unwrap_or_else(|e| e.into_inner()) = stage.label();
        self.report(0, steps);
    }

    fn advance(&self, done: u64, steps: u64) {
        self.report(done, steps);
    }
}

/// Keeps the default panic message for real panics, none for a stage asked to stop.
fn quiet_interruptions() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !info.payload().is::<Interrupted>() {
                default(info);
            }
        }));
    });
}

/// Runs `work` with Python's lock released, its progress to `callback`, stopping it
/// on Ctrl-C; hcm's errors become `HcmError`s with the command's messages.
pub fn run_stage<T: Send>(
    py: Python<'_>,
    callback: Option<Py<PyAny>>,
    work: impl FnOnce(&dyn Progress) -> anyhow::Result<T> + Send,
) -> PyResult<T> {
    quiet_interruptions();
    let reporter = Reporter {
        callback,
        stage: Mutex::new(""),
        stop: AtomicBool::new(false),
        reason: Mutex::new(None),
    };
    let outcome = std::thread::scope(|scope| {
        let (done, finished) = mpsc::channel::<()>();
        // Behind a lock: the wait below runs with Python's lock released, in a closure
        // that must be shareable.
        let finished = Mutex::new(finished);
        let reporter = &reporter;
        let worker = scope.spawn(move || {
            let result = panic::catch_unwind(AssertUnwindSafe(|| work(reporter)));
            let _ = done.send(());
            result
        });
        loop {
            let wait = || {
                let finished = finished.lock().unwrap_or_else(|e| e.into_inner());
                finished.recv_timeout(SIGNAL_PERIOD)
            };
            match py.detach(wait) {
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    if let Err(error) = py.check_signals() {
                        reporter.stop_with(error);
                    }
                }
                _ => break,
            }
        }
        py.detach(|| worker.join())
    });
    let reason = || {
        reporter
            .reason
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
    };
    match outcome {
        Ok(Ok(Ok(value))) => match reason() {
            // Ctrl-C after the stage's last report: it finished; the interrupt stands.
            Some(error) => Err(error),
            None => Ok(value),
        },
        Ok(Ok(Err(error))) => Err(hcm_error(error)),
        Ok(Err(payload)) | Err(payload) => match (payload.is::<Interrupted>(), reason()) {
            (true, Some(error)) => Err(error),
            _ => panic::resume_unwind(payload),
        },
    }
}
