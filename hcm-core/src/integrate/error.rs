//! Why an integration stopped.

use core::fmt;

/// Why [`Dopri5::step`](super::Dopri5::step) could not take its step.
///
/// Times and steps are reported in s as `f64` whatever the float type, so that f32
/// and f64 runs share one error type. The stepper is left at the last accepted point
/// (its [`time`](super::Dopri5::time) and [`state`](super::Dopri5::state) are still
/// valid), so a caller can report where the run stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum IntegrationError {
    /// The run used up [`Settings::max_steps`](super::Settings::max_steps), counting
    /// accepted and rejected attempts.
    TooManySteps {
        /// Time (s) of the last accepted point.
        time: f64,
        /// Attempts (accepted + rejected) taken since the stepper was created.
        steps: u64,
    },
    /// Meeting the tolerance needed a step shorter than
    /// [`Settings::min_step`](super::Settings::min_step), or shorter than the float
    /// resolution of the time (t + h == t).
    StepTooSmall {
        /// Time (s) of the last accepted point.
        time: f64,
        /// The step (s) that would have been needed next.
        step: f64,
    },
    /// The state or its derivative became NaN or infinite, and shrinking the step
    /// down to [`Settings::min_step`](super::Settings::min_step) did not help (or the
    /// derivative at the current point itself is not finite).
    NonFinite {
        /// Time (s) of the last accepted point.
        time: f64,
    },
    /// A [`Settings`](super::Settings) field is outside its domain: tolerances must be
    /// finite, ≥ 0 and not both zero; `min_step` finite and > 0; `max_step` > 0.
    InvalidSettings {
        /// Name of the field, as spelled in `Settings`.
        setting: &'static str,
    },
}

impl fmt::Display for IntegrationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IntegrationError::TooManySteps { time, steps } => write!(
                f,
                "integration stopped at t = {time} s: {steps} step attempts used up \
                 max_steps; raise max_steps, loosen the tolerance, or check for a stiff \
                 or chattering contact"
            ),
            IntegrationError::StepTooSmall { time, step } => write!(
                f,
                "integration stopped at t = {time} s: the tolerance needs a step of \
                 {step} s, below min_step; the system is stiff or diverging there — \
                 loosen the tolerance or check the law parameters (stiffness, damping)"
            ),
            IntegrationError::NonFinite { time } => write!(
                f,
                "integration stopped at t = {time} s: the state or its derivative became \
                 NaN or infinite even at the smallest step; check the law parameters \
                 (validate them) and the initial state"
            ),
            IntegrationError::InvalidSettings { setting } => write!(
                f,
                "integrator setting `{setting}` is out of its domain (tolerances finite, \
                 >= 0 and not both 0; min_step finite and > 0; max_step > 0)"
            ),
        }
    }
}

impl core::error::Error for IntegrationError {}
