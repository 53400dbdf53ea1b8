//! The step-length rules both steppers share ([`Dopri5`](super::Dopri5) and
//! [`Rodas4`](super::Rodas4)): the cap on a step, the next attempt's interval with its
//! stretch to `until`, and the error for a step too small to take.

use super::dopri5::Settings;
use super::vector::is_finite;
use super::IntegrationError;
use crate::Real;

/// Longest step (s): min(settings.max_step, `limit`), floored at min_step; a NaN
/// `limit` is ignored.
pub(super) fn step_cap<T: Real>(settings: &Settings<T>, limit: T) -> T {
    let mut cap = settings.max_step;
    if !is_finite(cap) {
        cap = T::MAX;
    }
    if limit < cap {
        cap = limit;
    }
    if cap < settings.min_step {
        cap = settings.min_step;
    }
    cap
}

/// The next attempt's length h (s) and end time (s) from `time` (s): the wanted step
/// min(`next_step`, `cap`), stretched to end exactly at `until` when that is within
/// 1 % of a step (or closer than min_step); the error for a step too small to take.
/// `non_finite`: whether the last rejection was a NaN/∞ (decides the error's kind).
pub(super) fn next_interval<T: Real>(
    settings: &Settings<T>,
    time: T,
    next_step: T,
    (cap, until): (T, T),
    non_finite: bool,
) -> Result<(T, T), IntegrationError> {
    let wanted = if next_step < cap { next_step } else { cap };
    let remaining = until - time;
    let (h, end) = if remaining <= wanted * T::of(1.01) && remaining <= cap {
        (remaining, until)
    } else if wanted < settings.min_step {
        return Err(too_small(time, wanted, non_finite));
    } else {
        (wanted, time + wanted)
    };
    if end.is_nan() || end <= time || h.is_nan() || h <= T::zero() {
        return Err(too_small(time, h, non_finite));
    }
    Ok((h, end))
}

/// The error for a step `h` (s) from `time` (s) that cannot be taken.
fn too_small<T: Real>(time: T, h: T, non_finite: bool) -> IntegrationError {
    let time = time.to_f64();
    if non_finite {
        IntegrationError::NonFinite { time }
    } else {
        IntegrationError::StepTooSmall {
            time,
            step: h.to_f64(),
        }
    }
}
