//! The force sensor reads y, T·ẏ + y = f: a first-order low-pass filter (s), judged on a
//! line of force (at first order a lag, told from [`super::sensor_delay`] by its shape).

use super::{first, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// T ∈ [0, 20·Δt] (s).
#[derive(Debug)]
pub struct SensorFilter;

impl Effect for SensorFilter {
    fn name(&self) -> &'static str {
        "sensor_filter"
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::LineForce
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        vec![Bound::linear(
            "time_constant",
            0.0,
            20.0 * s.interval.max(1e-7),
        )]
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        model.scenario.experiment.sensor_filter = first(values);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::SensorFilter)
    }
}
