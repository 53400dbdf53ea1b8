//! One contact event read back from a run's data, whatever the indicators it carries:
//! the 1D indicators along the line of centres ([`super::Indicators`], from
//! [`super::from_run`]) or the 3D wrench indicators ([`super::WrenchIndicators`], from
//! [`super::pair_events_from_run`]).

/// One contact event found in a run's data, with its indicators `I`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
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

/// Every run's events found by `find` (the 1D [`super::from_run`] or the 3D
/// [`super::pair_events_from_run`]), in run order, and the ids of the runs without a
/// completed contact.
pub fn events_of_runs<I, E>(
    runs: &[crate::dataset::Run],
    mut find: impl FnMut(&crate::dataset::Run) -> Result<Vec<RecordedEvent<I>>, E>,
) -> Result<(Vec<RecordedEvent<I>>, Vec<String>), E> {
    let (mut events, mut without_contact) = (Vec::new(), Vec::new());
    for run in runs {
        let found = find(run)?;
        if found.is_empty() {
            without_contact.push(run.id.clone());
        }
        events.extend(found);
    }
    Ok((events, without_contact))
}
