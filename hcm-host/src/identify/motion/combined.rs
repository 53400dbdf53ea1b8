//! The force term of a fit from motion and force together (one objective):
//! the contact's wrench at every instant with a measured force, at the
//! recorded poses of the candidate's own geometry (a shifted table moves every
//! indentation, so the rows are rebuilt per candidate: no simulation, a pass over the
//! samples), against the measured one — each component over its RMS, as the
//! least-squares fit from force samples weighs them ([`RecordedContact::residuals`]).

use crate::dataset::Dataset;
use crate::identify::rigid::RecordedContact;
use crate::scenario::Model;

/// The force data of contact `contact`.
pub struct ForceData<'a> {
    /// The measured data (poses and force).
    pub data: &'a Dataset,
    /// The contact fitted.
    pub contact: usize,
}

impl ForceData<'_> {
    /// Mean over the force instants of the squared, RMS-weighted wrench residual of
    /// `candidate` (–); +∞ where its rows cannot be built.
    pub fn cost(&self, candidate: &Model) -> f64 {
        let Ok(recorded) = RecordedContact::with_rows(candidate, self.data, self.contact, true)
        else {
            return f64::INFINITY;
        };
        let mut out = vec![0.0; 6 * recorded.samples.len()];
        recorded.residuals(candidate, &mut out);
        let rows = recorded.samples.len().max(1) as f64;
        let cost = out.iter().map(|r| r * r).sum::<f64>() / rows;
        if cost.is_finite() {
            cost
        } else {
            f64::INFINITY
        }
    }
}
