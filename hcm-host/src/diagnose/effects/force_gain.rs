//! The force sensor reads g × the wrench (–).

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// g ∈ [0.5, 2] (–).
#[derive(Debug)]
pub struct ForceGain;

impl Effect for ForceGain {
    fn name(&self) -> &'static str {
        "force_gain"
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Wrench
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound::linear("gain", 0.5, 2.0)]
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![1.0]
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        model.scenario.experiment.force_gain = first(values);
    }
}
