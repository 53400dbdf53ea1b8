//! The tracker's lengths are s times the true ones (–): a change of how the data are
//! read, not of the model.

use super::{Effect, Family, Scales, Site};
use crate::dataset::{Dataset, Evidence};
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// s ∈ [0.9, 1.1] (–).
#[derive(Debug)]
pub struct LengthScale;

impl Effect for LengthScale {
    fn name(&self) -> &'static str {
        "length_scale"
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound::linear("scale", 0.9, 1.1)]
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![1.0]
    }
    fn per_contact(&self) -> bool {
        false
    }
    fn apply(&self, _model: &mut Model, _site: Site, _values: &[f64]) {}
    /// Every position and velocity divided by s (about the world origin).
    fn read(&self, data: &Dataset, values: &[f64]) -> Option<Dataset> {
        let scale = values.first().copied().unwrap_or(1.0);
        let mut out = data.clone();
        for run in &mut out.runs {
            for body in &mut run.bodies {
                for sample in &mut body.samples {
                    sample.position = sample.position.map(|x| x / scale);
                    sample.velocity = sample.velocity.map(|x| x / scale);
                }
            }
        }
        Some(out)
    }
}
