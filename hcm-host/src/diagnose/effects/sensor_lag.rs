//! The force sensor lags the force: it reads the force at t − τ (a delay, s), or y with
//! T·ẏ + y = f (a first-order low-pass filter, time constant T in s). At first order a
//! filter is a lag too; on a line of force the shapes of their columns tell them apart,
//! from a wrench only the delay is judged.

use super::{first, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// τ or T ∈ [0, 20·Δt] (s).
#[derive(Debug)]
pub struct SensorLag {
    /// A low-pass filter rather than a pure delay.
    filter: bool,
}

/// The sensor reads the force at t − τ.
pub static DELAY: SensorLag = SensorLag { filter: false };
/// The sensor reads y, T·ẏ + y = f.
pub static FILTER: SensorLag = SensorLag { filter: true };

impl Effect for SensorLag {
    fn name(&self) -> &'static str {
        self.column().map_or("", Candidate::name)
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::LineForce || (evidence == Evidence::Wrench && !self.filter)
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let name = if self.filter {
            "time_constant"
        } else {
            "delay"
        };
        vec![Bound::linear(name, 0.0, 20.0 * s.interval.max(1e-7))]
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        let experiment = &mut model.scenario.experiment;
        match self.filter {
            true => experiment.sensor_filter = first(values),
            false => experiment.sensor_delay = first(values),
        }
    }
    fn column(&self) -> Option<Candidate> {
        Some(match self.filter {
            true => Candidate::SensorFilter,
            false => Candidate::SensorDelay,
        })
    }
}
