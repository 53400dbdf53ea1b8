//! The (δ, δ̇, δ̇0, f_n) samples a law is fitted to, read from the motion and force
//! columns of a data file with the scenario's geometry.

use super::IdentifyError;
use crate::dataset::complete;
use crate::dataset::{Dataset, ForceSample};
use crate::indicators::{contact_history, event_spans};
use crate::scenario::Model;

/// Every in-contact sample of contact `c` in every run, and how many runs and
/// events they came from. A run without a completed contact is an error naming it:
/// a silent drop would bias the fit. Motion not recorded at the force samples (camera
/// frames) is reconstructed there first ([`complete`]); data with motion and force on
/// every row are read as recorded.
pub fn force_samples(
    model: &Model,
    data: &Dataset,
    c: usize,
) -> Result<(Vec<ForceSample>, usize), IdentifyError> {
    if data.runs.is_empty() {
        return Err(IdentifyError::NoData);
    }
    let completed = complete(model, data)?;
    let mut samples = Vec::new();
    let mut events = 0;
    for run in &completed.data.runs {
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
            let mut max_depth = 0.0_f64;
            samples.extend(span.inside.clone().map(|i| {
                max_depth = max_depth.max(history.depth[i]);
                ForceSample {
                    depth: history.depth[i],
                    rate: history.rate[i],
                    approach_speed,
                    max_depth,
                    force: history.force[i],
                }
            }));
        }
    }
    Ok((samples, events))
}
