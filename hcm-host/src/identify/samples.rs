//! The (δ, δ̇, δ̇0, f_n) samples a law is fitted to, read from the motion and force
//! columns of a data file with the scenario's geometry.

use super::IdentifyError;
use crate::dataset::complete;
use crate::dataset::Dataset;
use crate::indicators::{contact_history, event_spans};
use crate::scenario::Model;
use hcm_core::effect::ContactMemory;
use hcm_core::law::Indentation;

/// One in-contact sample: the state a normal law reads and the force it should give.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceSample {
    /// Indentation δ (m).
    pub depth: f64,
    /// Indentation rate δ̇ (m/s).
    pub rate: f64,
    /// Approach speed δ̇0 of the sample's impact (m/s).
    pub approach_speed: f64,
    /// Deepest indentation δ_max (m) of the sample's impact so far.
    pub max_depth: f64,
    /// Measured normal force f_n (N).
    pub force: f64,
}

impl ForceSample {
    /// The sample's state as the contact model reads it: (δ, δ̇, δ̇0) and δ_max.
    pub fn state(&self) -> (Indentation<f64>, ContactMemory<f64>) {
        (
            Indentation {
                depth: self.depth,
                rate: self.rate,
                approach_speed: self.approach_speed,
            },
            ContactMemory {
                max_depth: self.max_depth,
            },
        )
    }
}

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
