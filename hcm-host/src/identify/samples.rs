//! The (δ, δ̇, δ̇0, f_n) samples a law is fitted to, read from the motion and force
//! columns of a data file with the scenario's geometry.

use super::{contact_samples, IdentifyError};
use crate::dataset::{Dataset, ForceSample};
use crate::scenario::Model;

/// Every in-contact sample of contact `c` in every run (the in-contact rows of
/// [`contact_samples`]), and how many events they came from. A run without a completed
/// contact is an error naming it: a silent drop would bias the fit. Motion not recorded
/// at the force samples (camera frames) is reconstructed there first; data with motion
/// and force on every row are read as recorded.
pub fn force_samples(
    model: &Model,
    data: &Dataset,
    c: usize,
) -> Result<(Vec<ForceSample>, usize), IdentifyError> {
    let all = contact_samples(model, data, c)?;
    let samples = (0..all.run.len())
        .filter(|&i| all.in_contact[i])
        .map(|i| ForceSample {
            depth: all.depth[i],
            rate: all.rate[i],
            approach_speed: all.approach_speed[i],
            max_depth: all.max_depth[i],
            force: all.measured[i],
        })
        .collect();
    Ok((samples, all.events))
}
