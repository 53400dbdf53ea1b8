//! The force sensor reads the force at t − τ (s).

use super::{first, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// τ ∈ [0, 20·Δt] (s).
#[derive(Debug)]
pub struct SensorDelay;

impl Effect for SensorDelay {
    fn name(&self) -> &'static str {
        "sensor_delay"
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::Poses
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        vec![Bound::linear("delay", 0.0, 20.0 * s.interval.max(1e-7))]
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        model.scenario.experiment.sensor_delay = first(values);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::SensorDelay)
    }
}
