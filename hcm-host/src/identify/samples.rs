//! The (δ, δ̇, δ̇0, f_n) samples a law is fitted to, read from the motion and force
//! columns of a data file with the scenario's geometry.

use super::IdentifyError;
use crate::dataset::Dataset;
use crate::indicators::{contact_history, event_spans};
use crate::scenario::Model;

/// One in-contact sample: the state a normal law reads and the force it should give.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceSample {
    /// Indentation δ (m).
    pub depth: f64,
    /// Indentation rate δ̇ (m/s).
    pub rate: f64,
    /// Approach speed δ̇0 of the sample's impact (m/s).
    pub approach_speed: f64,
    /// Measured normal force f_n (N).
    pub force: f64,
}

/// Every in-contact sample of contact `c` in every run, and how many runs and
/// events they came from. A run without a completed contact is an error naming it:
/// a silent drop would bias the fit.
pub fn force_samples(
    model: &Model,
    data: &Dataset,
    c: usize,
) -> Result<(Vec<ForceSample>, usize), IdentifyError> {
    if data.runs.is_empty() {
        return Err(IdentifyError::NoData);
    }
    let mut samples = Vec::new();
    let mut events = 0;
    for run in &data.runs {
        let history = contact_history(model, run, c)?;
        let spans = event_spans(&history);
        if spans.is_empty() {
            let (first, last) = (
                history.time.first().copied().unwrap_or(f64::NAN),
                history.time.last().copied().unwrap_or(f64::NAN),
            );
            return Err(IdentifyError::NoContact {
                run: run.id.clone(),
                from: first,
                to: last,
            });
        }
        for span in spans {
            events += 1;
            let approach_speed = span.approach_speed();
            samples.extend(span.inside.clone().map(|i| ForceSample {
                depth: history.depth[i],
                rate: history.rate[i],
                approach_speed,
                force: history.force[i],
            }));
        }
    }
    Ok((samples, events))
}
