//! The force sensor reads F + b: a bias in every sample, in flight too (N).

use super::{Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// b ∈ [−F̂/10, F̂/10]³ (N, world components).
#[derive(Debug)]
pub struct ForceOffset;

impl Effect for ForceOffset {
    fn name(&self) -> &'static str {
        "force_offset"
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::Poses
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let force = s.contact.peak_force.max(f64::MIN_POSITIVE);
        (["x", "y", "z"].iter())
            .map(|a| Bound::linear(format!("offset_{a}"), -0.1 * force, 0.1 * force))
            .collect()
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![0.0; 3]
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        let b = &mut model.scenario.experiment.force_offset;
        for (k, v) in b.iter_mut().enumerate() {
            *v = values.get(k).copied().unwrap_or(0.0);
        }
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::ForceOffset)
    }
}
