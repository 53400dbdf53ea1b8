//! What event location and sampling read from a stepper: the step just taken and the
//! solution anywhere inside it.

use super::OdeState;
use crate::Real;

/// A stepper's last accepted step [previous_time, time] and its continuous
/// extension. [`Dopri5`](super::Dopri5) and [`Rodas4`](super::Rodas4) both provide
/// it, so [`locate_crossing`](super::locate_crossing) and a recorder work with either.
pub trait DenseOutput<T: Real, S: OdeState<T>> {
    /// Start time (s) of the last accepted step.
    fn previous_time(&self) -> T;
    /// State at [`previous_time`](DenseOutput::previous_time).
    fn previous_state(&self) -> &S;
    /// End time (s) of the last accepted step: the current time.
    fn time(&self) -> T;
    /// State at [`time`](DenseOutput::time).
    fn state(&self) -> &S;
    /// The continuous extension at `time` (s), clamped to the step, written into
    /// `out`; exactly the stored states at the ends.
    fn dense_output(&self, time: T, out: &mut S);
}

impl<T: Real, S: OdeState<T>> DenseOutput<T, S> for super::Dopri5<T, S> {
    fn previous_time(&self) -> T {
        super::Dopri5::previous_time(self)
    }

    fn previous_state(&self) -> &S {
        super::Dopri5::previous_state(self)
    }

    fn time(&self) -> T {
        super::Dopri5::time(self)
    }

    fn state(&self) -> &S {
        super::Dopri5::state(self)
    }

    fn dense_output(&self, time: T, out: &mut S) {
        super::Dopri5::dense_output(self, time, out);
    }
}
