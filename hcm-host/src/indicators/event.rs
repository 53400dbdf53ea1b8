//! One contact event read back from a run's data, whatever the indicators it carries:
//! the 1D indicators along the line of centres ([`super::Indicators`], from
//! [`super::from_run`]) or the 3D wrench indicators ([`super::WrenchIndicators`], from
//! [`super::pair_events_from_run`]).

/// One contact event found in a run's data, with its indicators `I`.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordedEvent<I> {
    /// Run id.
    pub run: String,
    /// Contact label, `body1–body2`.
    pub contact: String,
    /// Event number within this contact and run (0 = first).
    pub event: usize,
    /// Interpolated touch-down time (s).
    pub touch_down: f64,
    /// Interpolated lift-off time (s).
    pub lift_off: f64,
    /// The indicators.
    pub indicators: I,
}
