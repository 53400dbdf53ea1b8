//! The paper's contact indicators (maximum force, impulse, energy loss, duration),
//! the Eq 20 error between two of them, and their statistics over runs.
//!
//! Definitions (docs/reconstruction.md): over one contact event from the
//! touch-down to the lift-off δ = 0 crossing, the maximum normal force, the normal
//! impulse ∫f_n dt, the relative-motion energy loss ½·m_e·(δ̇_in² − δ̇_out²), and the
//! duration.

mod event;
mod from_data;
mod from_poses;
mod summary;
mod wrench;
mod wrench_summary;

pub use event::{events_of_runs, ContactEvent, RecordedEvent};
pub use from_data::{
    contact_history, event_spans, from_run, ContactHistory, EventSpan, IndicatorError,
};
pub use from_poses::pair_events_from_run;
pub use summary::{summarize, EventSummary, Statistic};
pub use wrench::WrenchIndicators;
pub use wrench_summary::{
    wrench_statistics, ContactStatistics, Estimate, EventCountMismatch, WrenchEventStatistics,
};

use serde::Serialize;

/// The four indicators of one contact event.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Indicators {
    /// Maximum normal contact force (N).
    pub max_force: f64,
    /// Normal contact impulse (N·s).
    pub impulse: f64,
    /// Contact energy loss (J = N·m).
    pub energy_loss: f64,
    /// Contact duration (s).
    pub duration: f64,
}

impl Indicators {
    /// Names of the indicators with their units, in [`Indicators::values`] order.
    pub const NAMES: [(&'static str, &'static str); 4] = [
        ("max_force", "N"),
        ("impulse", "N·s"),
        ("energy_loss", "N·m"),
        ("duration", "s"),
    ];

    /// The four values in a fixed order.
    pub fn values(&self) -> [f64; 4] {
        [
            self.max_force,
            self.impulse,
            self.energy_loss,
            self.duration,
        ]
    }

    /// Eq 20 error of each indicator of `self` against the reference `reference`:
    /// |(γ1 − γ2)/γ1| with γ1 the reference.
    pub fn relative_error(&self, reference: &Indicators) -> [f64; 4] {
        let (mine, theirs) = (self.values(), reference.values());
        std::array::from_fn(|i| eq20_error(theirs[i], mine[i]))
    }
}

/// The paper's error, Eq 20: |(γ1 − γ2)/γ1| (dimensionless; ×100 for %).
pub(crate) fn eq20_error(reference: f64, other: f64) -> f64 {
    ((reference - other) / reference).abs()
}
